// The look-dev window (issue 20) as a user meets it: a laptop-sized screen, the view the largest
// part; the camera's keys wherever the focus is; zoom toward the cursor; the camera saved with the
// scene; meshes opened as a new scene; turning the environment by hand; the turntable; the split
// comparison; exporting at any size, PNG with alpha and linear EXR; the shortcuts window.
#include "mipgloss/scene/view_gestures.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/view_dialogs.h"
#include "mipgloss/ui/view_toolbar.h"
#include "mipgloss/ui/viewport.h"
#include "mesh_files.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QListView>
#include <QSignalSpy>
#include <QSpinBox>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <QWheelEvent>

#include <glm/geometric.hpp>

#include <cmath>
#include <memory>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::openWindow;
using mipgloss::test::waitUntil;

namespace {

constexpr int kEnvironmentTimeoutMs = 120000;  // llvmpipe and a shared CPU are slow
constexpr int kFrameTimeoutMs = 60000;

bool environmentIdle(MainWindow& w) {
    const bool main = w.environments()->current() && w.environments()->current()->complete() &&
                      !w.environments()->busy() && !w.importing();
    EnvironmentManager* compared = w.viewport()->comparisonEnvironments();
    return main && (!compared || (compared->current() && compared->current()->complete() && !compared->busy()));
}

// Waits until every environment is built and settled, then for a frame drawn after that.
::testing::AssertionResult settledFrame(MainWindow& w) {
    if (!waitUntil([&] { return environmentIdle(w); }, kEnvironmentTimeoutMs))
        return ::testing::AssertionFailure() << "environment not ready within " << kEnvironmentTimeoutMs << " ms";
    // Stack entries come kSettleMs after the last change: wait that out, then until idle again.
    QTest::qWait(400);
    if (!waitUntil([&] { return environmentIdle(w); }, kEnvironmentTimeoutMs))
        return ::testing::AssertionFailure() << "lobes not ready";
    QSignalSpy frames(w.viewport(), &Viewport::frameDrawn);
    w.viewport()->update();
    if (!waitUntil([&] { return frames.count() > 0; }, kFrameTimeoutMs))
        return ::testing::AssertionFailure() << "no frame within " << kFrameTimeoutMs << " ms";
    return ::testing::AssertionSuccess();
}

void writeFile(const QString& path, const std::string& bytes) {
    QFile f(path);
    ASSERT_TRUE(f.open(QIODevice::WriteOnly));
    f.write(bytes.data(), static_cast<qint64>(bytes.size()));
}

// Mean |ΔRGB| (0..255 per channel) over `region` of two images of one size.
double meanDifference(const QImage& a, const QImage& b, const QRect& region) {
    const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
    double sum = 0.0;
    long count = 0;
    for (int row = region.top(); row <= region.bottom(); ++row)
        for (int col = region.left(); col <= region.right(); ++col) {
            const QRgb p = x.pixel(col, row), q = y.pixel(col, row);
            sum += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) + std::abs(qBlue(p) - qBlue(q));
            ++count;
        }
    return count ? sum / (3.0 * static_cast<double>(count)) : 0.0;
}

}  // namespace

TEST(LookDevWindow, FitsALaptopScreenWithTheViewTakingMostOfIt) {
    // 1280×800 less a title bar and a panel: what a laptop's window manager leaves.
    for (const QSize size : {QSize(1280, 720), QSize(1280, 760), QSize(1600, 1000)}) {
        auto w = openWindow(size);
        w->document()->setSelected(1);  // the material panel at its tallest
        QCoreApplication::processEvents();
        ASSERT_TRUE(waitUntil([&] { return w->size() == size; }, 5000)) << "the window refused " << size.width()
                                                                        << "x" << size.height();
        const QRect window(QPoint(0, 0), w->size());
        const QRect status(w->statusBar()->mapTo(w.get(), QPoint(0, 0)), w->statusBar()->size());
        EXPECT_TRUE(window.contains(status)) << "the status bar is off the window";
        EXPECT_TRUE(w->statusBar()->isVisible());
        const QSize view = w->viewport()->size();
        const double share = static_cast<double>(view.width() * view.height()) /
                             static_cast<double>(size.width() * size.height());
        std::printf("[ LookDevWindow ] %dx%d: view %dx%d, %.0f %% of the window\n", size.width(), size.height(),
                    view.width(), view.height(), 100.0 * share);
        EXPECT_GE(share, 0.5);
        // Every dock is inside the window, nothing cut off below.
        for (QDockWidget* dock : w->findChildren<QDockWidget*>()) {
            // A tab behind another is "visible" but parked off the window: only what shows counts.
            if (!dock->isVisible() || dock->visibleRegion().isEmpty()) continue;
            const QRect where(dock->mapTo(w.get(), QPoint(0, 0)), dock->size());
            EXPECT_TRUE(window.contains(where)) << dock->objectName().toStdString() << " at " << where.x() << ","
                                                << where.y() << " " << where.width() << "x" << where.height();
        }
        const QSize least = w->minimumSizeHint().expandedTo(w->minimumSize());
        EXPECT_LE(least.height(), 720);
        EXPECT_LE(least.width(), 1280);
    }
}

TEST(LookDevWindow, DocksNarrowAndTheLayoutIsRemembered) {
    QByteArray saved;
    int narrowed = 0;
    {
        auto w = openWindow(QSize(1280, 760));
        QDockWidget* material = w->findChild<QDockWidget*>(QStringLiteral("materialDock"));
        ASSERT_TRUE(material);
        const int before = material->width();
        w->resizeDocks({material}, {220}, Qt::Horizontal);
        QCoreApplication::processEvents();
        narrowed = material->width();
        EXPECT_LT(narrowed, before);
        EXPECT_LE(narrowed, 260) << "the dock cannot be narrowed";
        ASSERT_TRUE(w->close());
    }
    auto w = openWindow(QSize(1280, 760));
    QCoreApplication::processEvents();
    QDockWidget* material = w->findChild<QDockWidget*>(QStringLiteral("materialDock"));
    // The layout came back (the window's size is the test's own, so the dock's width is compared).
    EXPECT_NEAR(material->width(), narrowed, 12);
}

TEST(LookDevWindow, CameraKeysWorkWhereverTheFocusIs) {
    auto w = openWindow();
    QListView* list = w->sceneList();
    // Without a window manager (Xvfb alone) nothing activates the window: Qt is told.
    QApplication::setActiveWindow(w.get());
    list->setFocus();
    ASSERT_TRUE(waitUntil([&] { return list->hasFocus(); }, 2000));
    w->viewport()->camera().yawDegrees = 77.0f;
    w->viewport()->camera().fovYDegrees = 55.0f;
    QTest::keyClick(list, Qt::Key_Home);
    EXPECT_EQ(w->viewport()->camera().yawDegrees, OrbitCamera{}.yawDegrees);
    EXPECT_EQ(w->viewport()->camera().fovYDegrees, OrbitCamera{}.fovYDegrees);
    EXPECT_TRUE(list->hasFocus()) << "Home took the focus";

    // F frames the selection: the camera aims at the selected teapot and comes closer.
    w->document()->setSelected(3);
    const float allDistance = w->viewport()->camera().distance;
    QTest::keyClick(list, Qt::Key_F);
    const Bounds teapot = *objectBounds(w->document()->object(3));
    EXPECT_LT(glm::distance(w->viewport()->camera().target, teapot.centre()), 1e-4f);
    EXPECT_LT(w->viewport()->camera().distance, 0.6f * allDistance);
    EXPECT_EQ(w->document()->selected(), 3) << "framing changed the selection";
    // A frames everything again.
    QTest::keyClick(list, Qt::Key_A);
    EXPECT_NEAR(w->viewport()->camera().distance, allDistance, 1e-3f * allDistance);
}

TEST(LookDevWindow, FieldOfViewFromTheToolbarAndTheWheelZoomsTowardTheCursor) {
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    QSpinBox* fov = w->viewToolBar()->fieldOfView();
    fov->setValue(60);
    EXPECT_EQ(w->viewport()->camera().fovYDegrees, 60.0f);
    fov->setValue(500);  // the spin box stops at the range
    EXPECT_EQ(w->viewport()->camera().fovYDegrees, Viewport::kMaxFov);
    fov->setValue(30);

    // The wheel over the rightmost teapot: the target moves toward it, the teapot stays put.
    Viewport* view = w->viewport();
    const SceneObject& teapot = w->document()->object(3);
    const OrbitCamera before = view->camera();
    const float aspect = static_cast<float>(view->width()) / static_cast<float>(view->height());
    auto pixelOf = [&](const OrbitCamera& c, const glm::vec3& p) {
        const glm::vec4 clip = c.projection(aspect, sceneBounds(w->document()->scene())) * c.view() * glm::vec4(p, 1.0f);
        return QPointF((0.5 * clip.x / clip.w + 0.5) * view->width(), (0.5 - 0.5 * clip.y / clip.w) * view->height());
    };
    const QPointF at = pixelOf(before, teapot.worldCentre());
    QWheelEvent wheel(at, view->mapToGlobal(at), QPoint(), QPoint(0, 240), Qt::NoButton, Qt::NoModifier,
                      Qt::NoScrollPhase, false);
    QCoreApplication::sendEvent(view, &wheel);
    const OrbitCamera after = view->camera();
    EXPECT_NEAR(after.distance, before.distance * 0.85f * 0.85f, 1e-3f * before.distance);
    EXPECT_LT(glm::distance(after.target, teapot.worldCentre()), glm::distance(before.target, teapot.worldCentre()));
    // The point zoomed at (on the teapot's picking sphere, under the cursor) stays under it.
    const Ray ray = pixelRay(before, w->document()->scene(), view->width(), view->height(),
                             static_cast<int>(at.x()), static_cast<int>(at.y()));
    const glm::vec3 pivot = *zoomPivot(w->document()->scene(), before, ray);
    const QPointF moved = pixelOf(after, pivot), was = pixelOf(before, pivot);
    EXPECT_NEAR(moved.x(), was.x(), 1.0);
    EXPECT_NEAR(moved.y(), was.y(), 1.0);
}

TEST(LookDevWindow, TheCameraSurvivesSaveAndOpen) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    auto w = openWindow();
    OrbitCamera camera;
    camera.target = {0.25f, 0.5f, -0.75f};
    camera.distance = 7.5f;
    camera.yawDegrees = 40.0f;
    camera.pitchDegrees = 25.0f;
    camera.fovYDegrees = 50.0f;
    w->viewport()->setCamera(camera);
    const QString file = dir.filePath(QStringLiteral("view.mipgloss"));
    ASSERT_TRUE(w->saveScene(file)) << w->lastMessage().toStdString();
    EXPECT_FALSE(w->isWindowModified());
    ASSERT_TRUE(w->newScene());
    EXPECT_NE(w->viewport()->camera(), camera);
    ASSERT_TRUE(w->openScene(file)) << w->lastMessage().toStdString();
    EXPECT_EQ(w->viewport()->camera(), camera);
    EXPECT_EQ(w->viewToolBar()->fieldOfView()->value(), 50);
    EXPECT_FALSE(w->isWindowModified());
}

TEST(LookDevWindow, MeshesOpenedAsASceneReplaceTheDemoAndAreFramed) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    auto w = openWindow();
    SceneDocument* doc = w->document();
    ASSERT_EQ(doc->objectCount(), 4);
    // A scan 120 units across, far from the origin: alone, unscaled and framed.
    const QString scan = dir.filePath(QStringLiteral("scan.obj"));
    Mesh sphere = makeSphere(8, 16);
    for (glm::vec3& p : sphere.positions) p = glm::vec3(500.0f, 40.0f, -300.0f) + 60.0f * p;
    writeFile(scan, test::objText(sphere));
    QSignalSpy finished(w.get(), &MainWindow::importFinished);
    w->openFiles({scan}, /*meshesOpen=*/true);
    ASSERT_TRUE(waitUntil([&] { return !finished.isEmpty(); }, 60000));
    ASSERT_EQ(doc->objectCount(), 1);
    EXPECT_EQ(doc->object(0).transform.scale, 1.0f);
    EXPECT_LT(glm::distance(w->viewport()->camera().target, doc->object(0).worldCentre()), 1.0f);
    EXPECT_TRUE(w->sceneFile().isEmpty());
    // One undo step brings the teapots back.
    doc->undoStack()->undo();
    EXPECT_EQ(doc->objectCount(), 4);

    // A file that cannot be read changes nothing.
    const QString broken = dir.filePath(QStringLiteral("broken.obj"));
    writeFile(broken, "v 0 0 0\nf 1 2 3\n");
    finished.clear();
    w->openFiles({broken}, true);
    ASSERT_TRUE(waitUntil([&] { return !finished.isEmpty(); }, 60000));
    EXPECT_EQ(doc->objectCount(), 4);
    EXPECT_TRUE(w->lastMessageIsError());

    // New scene is empty and keeps the environment in use.
    EnvironmentSettings env = doc->scene().environment;
    env.builder = Builder::Box;
    doc->setEnvironment(env);
    ASSERT_TRUE(w->newEmptyScene());
    EXPECT_EQ(doc->objectCount(), 0);
    EXPECT_EQ(doc->scene().environment.builder, Builder::Box);
}

TEST(LookDevWindow, CtrlDragTurnsTheEnvironmentInOneUndoStep) {
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    Viewport* view = w->viewport();
    const OrbitCamera camera = view->camera();
    const int steps = w->document()->undoStack()->count();
    const QPoint start(view->width() / 2, view->height() / 2);
    QTest::mousePress(view, Qt::LeftButton, Qt::ControlModifier, start);
    for (int i = 1; i <= 5; ++i) {
        QMouseEvent move(QEvent::MouseMove, QPointF(start + QPoint(10 * i, 0)), view->mapToGlobal(QPointF(start + QPoint(10 * i, 0))),
                         Qt::NoButton, Qt::LeftButton, Qt::ControlModifier);
        QCoreApplication::sendEvent(view, &move);
    }
    QTest::mouseRelease(view, Qt::LeftButton, Qt::ControlModifier, start + QPoint(50, 0));
    EXPECT_NEAR(w->document()->scene().display.environmentRotationDegrees, 50.0f * Viewport::kEnvironmentDegreesPerPixel,
                1e-3f);
    EXPECT_EQ(w->document()->undoStack()->count(), steps + 1);
    EXPECT_EQ(view->camera(), camera) << "the camera moved with the environment";
    // Its angle, in degrees, in the Environment panel.
    auto* degrees = w->findChild<QDoubleSpinBox*>(QStringLiteral("envRotationSpin"));
    ASSERT_TRUE(degrees);
    EXPECT_NEAR(degrees->value(), 50.0 * static_cast<double>(Viewport::kEnvironmentDegreesPerPixel), 0.05);
    w->document()->undoStack()->undo();
    EXPECT_EQ(w->document()->scene().display.environmentRotationDegrees, 0.0f);
}

TEST(LookDevWindow, TheTurntableTurnsTheViewWithoutEditingTheScene) {
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    const Scene before = w->document()->scene();
    const QImage still = w->viewport()->grabFramebuffer();
    QAction* turntable = w->findChild<QAction*>(QStringLiteral("turntableAction"));
    ASSERT_TRUE(turntable);
    w->viewToolBar()->turntableSpeed()->setValue(90.0);
    QSignalSpy frames(w->viewport(), &Viewport::frameDrawn);
    turntable->setChecked(true);
    ASSERT_TRUE(waitUntil([&] { return frames.count() >= 3; }, 30000));
    turntable->setChecked(false);
    const float angle = w->viewport()->turntableDegrees();
    EXPECT_GT(std::abs(angle), 1.0f);
    EXPECT_EQ(w->document()->scene(), before);
    EXPECT_FALSE(w->isWindowModified());
    // The objects turned: the shown camera orbits by the opposite angle, the environment with it.
    const TurnedView shown = w->viewport()->shownView();
    EXPECT_NEAR(std::remainder(shown.camera.yawDegrees - w->viewport()->camera().yawDegrees + angle, 360.0f), 0.0f, 1e-3f);
    EXPECT_NEAR(std::remainder(shown.environmentRotationDegrees + angle, 360.0f), 0.0f, 1e-3f);
    const QImage turned = w->viewport()->grabFramebuffer();
    EXPECT_GT(meanDifference(still, turned, QRect(QPoint(0, 0), still.size())), 0.5);
    // Home puts it back.
    w->resetView();
    EXPECT_EQ(w->viewport()->turntableDegrees(), 0.0f);
}

TEST(LookDevWindow, CompareBuilderKeepsTheLeftAndChangesTheRight) {
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    const QImage plain = w->viewport()->grabFramebuffer();
    QComboBox* builder = w->viewToolBar()->compareBuilder();
    builder->setCurrentText(QStringLiteral("box"));
    w->viewToolBar()->compareKind()->setCurrentIndex(1);  // builder
    ASSERT_EQ(w->viewport()->comparison().kind, Comparison::Kind::Builder);
    EXPECT_EQ(w->viewport()->comparison().builder, Builder::Box);
    EXPECT_EQ(w->viewport()->rightLabel().left(3), QStringLiteral("box"));
    ASSERT_TRUE(settledFrame(*w));
    // The right half builds its chain from the left's imported cube: the file is not read again.
    ASSERT_TRUE(w->viewport()->comparisonEnvironments());
    EXPECT_EQ(w->viewport()->comparisonEnvironments()->counters().imports, 0u);
    EXPECT_EQ(w->viewport()->comparisonEnvironments()->counters().chainBuilds, 1u);
    const QImage split = w->viewport()->grabFramebuffer();
    ASSERT_EQ(split.size(), plain.size());
    const int x = static_cast<int>(std::lround(w->viewport()->dividerFraction() * static_cast<float>(split.width())));
    // Left of the divider (less the labels' strip at the top and a column for the line): as it was.
    const QRect left(0, 40, x - 2, split.height() - 40);
    const QRect right(x + 2, 40, split.width() - x - 2, split.height() - 40);
    const double leftDiff = meanDifference(plain, split, left), rightDiff = meanDifference(plain, split, right);
    std::printf("[ LookDevWindow ] compare phong | box: left %.3f, right %.3f mean |dRGB|\n", leftDiff, rightDiff);
    EXPECT_LT(leftDiff, 0.05);
    EXPECT_GT(rightDiff, 0.3);
    // The divider moves; off puts the view back.
    w->viewport()->setDividerFraction(0.25f);
    EXPECT_FLOAT_EQ(w->viewport()->dividerFraction(), 0.25f);
    w->viewToolBar()->compareKind()->setCurrentIndex(0);
    EXPECT_EQ(w->viewport()->comparisonEnvironments(), nullptr);
    ASSERT_TRUE(settledFrame(*w));
    EXPECT_LT(meanDifference(plain, w->viewport()->grabFramebuffer(), QRect(QPoint(0, 0), plain.size())), 0.05);
}

TEST(LookDevWindow, CompareMaterialShowsTheSelectedObjectWearingAnother) {
    auto w = openWindow();
    w->document()->setSelected(0);  // the mirror teapot
    ASSERT_TRUE(settledFrame(*w));
    QComboBox* material = w->viewToolBar()->compareMaterial();
    ASSERT_GT(material->count(), 0);
    material->setCurrentIndex(material->findText(QStringLiteral("clay")) >= 0 ? material->findText(QStringLiteral("clay")) : 0);
    w->viewport()->setDividerFraction(0.05f);  // the right part holds every teapot
    w->viewToolBar()->compareKind()->setCurrentIndex(3);
    ASSERT_EQ(w->viewport()->comparison().kind, Comparison::Kind::Material);
    ASSERT_TRUE(settledFrame(*w));
    EnvironmentManager* compared = w->viewport()->comparisonEnvironments();
    ASSERT_TRUE(compared);
    // The shadow scene: only the selected object's material differs, and it is the chosen one.
    EXPECT_EQ(w->viewport()->rightLabel(), material->currentText());
    // The same environment: neither read nor built again, only the new material's lobes.
    EXPECT_EQ(compared->counters().imports, 0u);
    EXPECT_EQ(compared->counters().chainBuilds, 0u);
    EXPECT_EQ(compared->current().get(), w->environments()->current().get());
    EXPECT_FALSE(w->isWindowModified());
}

TEST(LookDevWindow, ExportsAnySizeAsPngWithAlphaAndLinearExr) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    const QString png = dir.filePath(QStringLiteral("big.png"));
    ASSERT_TRUE(w->exportImage(png, QSize(640, 240))) << w->lastMessage().toStdString();
    const QImage shot(png);
    EXPECT_EQ(shot.size(), QSize(640, 240));
    EXPECT_FALSE(shot.hasAlphaChannel()) << "the background is shown: opaque";

    // The background hidden: it still lights the teapots, and the PNG is transparent around them.
    DisplaySettings d = w->document()->scene().display;
    d.showBackground = false;
    w->document()->setDisplay(d);
    const QString cut = dir.filePath(QStringLiteral("cut.png"));
    ASSERT_TRUE(w->exportImage(cut, QSize(400, 150))) << w->lastMessage().toStdString();
    const QImage alpha = QImage(cut).convertToFormat(QImage::Format_RGBA8888);
    ASSERT_TRUE(alpha.hasAlphaChannel());
    EXPECT_EQ(qAlpha(alpha.pixel(0, 0)), 0) << "a corner is background";
    int opaque = 0;
    for (int x = 0; x < alpha.width(); ++x) opaque += qAlpha(alpha.pixel(x, alpha.height() / 2)) == 255 ? 1 : 0;
    // Four teapots, each about 20 px across this row at this size (88 measured here).
    EXPECT_GT(opaque, 4 * 12) << "the teapots are opaque";
    EXPECT_LT(opaque, alpha.width() / 2) << "the background is not";

    // Linear EXR: float RGBA, the teapots' pixels as the renderer holds them (not tone-mapped).
    const QString exr = dir.filePath(QStringLiteral("linear.exr"));
    ASSERT_TRUE(w->exportImage(exr, QSize(320, 120))) << w->lastMessage().toStdString();
    auto in = OIIO::ImageInput::open(exr.toStdString());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 320);
    EXPECT_EQ(spec.height, 120);
    EXPECT_EQ(spec.nchannels, 4);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
    std::vector<float> pixels(static_cast<std::size_t>(spec.width * spec.height * 4));
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()));
    EXPECT_EQ(pixels[3], 0.0f) << "the corner's alpha";

    // Bad sizes and folders: refused with a message, nothing written.
    for (const QSize bad : {QSize(0, 0), QSize(100000, 100), QSize(100, 100000)}) {
        const QString file = dir.filePath(QStringLiteral("bad.png"));
        EXPECT_FALSE(w->exportImage(file, bad));
        EXPECT_TRUE(w->lastMessageIsError());
        EXPECT_TRUE(w->lastMessage().contains(QStringLiteral("bad.png"))) << w->lastMessage().toStdString();
        EXPECT_FALSE(QFile::exists(file));
    }
    const QString nowhere = dir.filePath(QStringLiteral("missing/folder/x.png"));
    EXPECT_FALSE(w->exportImage(nowhere, QSize(64, 64)));
    EXPECT_TRUE(w->lastMessage().contains(QStringLiteral("folder"))) << w->lastMessage().toStdString();
    // And the window still draws.
    ASSERT_TRUE(settledFrame(*w));
}

TEST(LookDevWindow, TheShortcutsWindowListsTheViewKeysAndGestures) {
    auto w = openWindow();
    ShortcutsDialog dialog(w->findChildren<QAction*>(), w.get());
    auto has = [&](const QString& what, const QString& keys) {
        for (const auto& [a, k] : dialog.rows())
            if (a.contains(what) && k.contains(keys)) return true;
        return false;
    };
    EXPECT_TRUE(has(QStringLiteral("Frame selected"), QStringLiteral("F")));
    EXPECT_TRUE(has(QStringLiteral("Frame all"), QStringLiteral("A")));
    EXPECT_TRUE(has(QStringLiteral("Reset view"), QStringLiteral("Home")));
    EXPECT_TRUE(has(QStringLiteral("Turntable"), QStringLiteral("T")));
    EXPECT_TRUE(has(QStringLiteral("Undo"), QStringLiteral("Ctrl+Z")));
    EXPECT_TRUE(has(QStringLiteral("Turn the environment"), QStringLiteral("Ctrl")));
}

TEST(LookDevWindow, ABrokenComparedEnvironmentIsAMessageAndTheViewKeepsDrawing) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString broken = dir.filePath(QStringLiteral("broken.hdr"));
    writeFile(broken, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 64 +X 128\ntruncated");
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    const Scene before = w->document()->scene();
    QSignalSpy messages(w.get(), &MainWindow::messageShown);
    w->viewToolBar()->compareEnvironment(broken);
    ASSERT_EQ(w->viewport()->comparison().kind, Comparison::Kind::Environment);
    ASSERT_TRUE(waitUntil([&] { return w->lastMessageIsError() && w->lastMessage().contains(QStringLiteral("broken.hdr")); },
                          kEnvironmentTimeoutMs))
        << w->lastMessage().toStdString();
    EXPECT_TRUE(w->lastMessage().startsWith(QStringLiteral("Comparison: "))) << w->lastMessage().toStdString();
    EXPECT_EQ(w->document()->scene(), before) << "the scene's own environment changed";
    QSignalSpy frames(w->viewport(), &Viewport::frameDrawn);
    w->viewport()->update();
    EXPECT_TRUE(waitUntil([&] { return frames.count() > 0; }, kFrameTimeoutMs));
}
