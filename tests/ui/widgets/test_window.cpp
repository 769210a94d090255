// The real window under X (Xvfb + Mesa llvmpipe in CI): selection through the scene list, λ edits
// through the material panel redrawing without rebuilding or re-uploading the chain, imports and
// their placement, bad files that leave the scene (and the undo stack) as they were, Edit → Undo
// and Redo, and library materials dropped on the scene list. Saving: test_saving.cpp.
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/library_dock.h"
#include "mipgloss/ui/thumbnail_cache.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/material_mime.h"
#include "mipgloss/ui/material_panel.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_list_model.h"
#include "mipgloss/ui/viewport.h"

#include "test_support.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QAction>
#include <QColorDialog>
#include <QPushButton>
#include <QDir>
#include <QDropEvent>
#include <QMimeData>
#include <QToolButton>
#include <QUrl>
#include <QDoubleSpinBox>
#include <QFile>
#include <QImage>
#include <QListView>
#include <QMenu>
#include <QMenuBar>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QUndoStack>
#include <QTemporaryDir>
#include <QTest>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

using namespace mipgloss;
using namespace mipgloss::ui;
namespace fs = std::filesystem;
using mipgloss::test::typeInto;
using mipgloss::test::openWindow;
using mipgloss::test::waitUntil;

namespace {

constexpr int kEnvironmentTimeoutMs = 120000;  // llvmpipe and a shared CPU are slow
constexpr int kFrameTimeoutMs = 60000;

// Waits for the environment to be ready and idle, then for a frame drawn after that.
::testing::AssertionResult settledFrame(MainWindow& w) {
    if (!waitUntil([&] { return w.environments()->current() && !w.environments()->busy() && !w.importing(); },
                   kEnvironmentTimeoutMs))
        return ::testing::AssertionFailure() << "environment not ready within " << kEnvironmentTimeoutMs << " ms";
    QSignalSpy frames(w.viewport(), &Viewport::frameDrawn);
    w.viewport()->update();
    if (!waitUntil([&] { return frames.count() > 0; }, kFrameTimeoutMs))
        return ::testing::AssertionFailure() << "no frame within " << kFrameTimeoutMs << " ms";
    if (!w.viewport()->glError().isEmpty())
        return ::testing::AssertionFailure() << "GL: " << w.viewport()->glError().toStdString();
    return ::testing::AssertionSuccess();
}

std::string outputPath(const std::string& name) {
    const fs::path dir = MIPGLOSS_TEST_OUTPUT_DIR;
    std::error_code ec;
    fs::create_directories(dir, ec);
    return (dir / name).string();
}

// The screen square holding the central part (70 %) of an object's bounding sphere.
QRect objectRegion(MainWindow& w, int index, const QSize& image) {
    const SceneObject& o = w.document()->object(index);
    const OrbitCamera& camera = w.viewport()->camera();
    const float aspect = static_cast<float>(image.width()) / static_cast<float>(image.height());
    const glm::mat4 vp = camera.projection(aspect, sceneBounds(w.document()->scene())) * camera.view();
    const glm::vec4 clip = vp * glm::vec4(o.worldCentre(), 1.0f);
    const float x = (0.5f * clip.x / clip.w + 0.5f) * static_cast<float>(image.width());
    const float y = (0.5f - 0.5f * clip.y / clip.w) * static_cast<float>(image.height());
    const float distance = glm::length(o.worldCentre() - camera.position());
    const float r = 0.7f * o.worldRadius() / (distance * std::tan(glm::radians(0.5f * camera.fovYDegrees))) *
                    0.5f * static_cast<float>(image.height());
    return QRect(static_cast<int>(x - r), static_cast<int>(y - r), static_cast<int>(2 * r),
                 static_cast<int>(2 * r))
        .intersected(QRect(QPoint(0, 0), image));
}

struct RegionDiff {
    double meanAbs = 0.0;         // mean |ΔRGB| per channel, 0..255
    double changedFraction = 0.0;  // pixels with some channel off by more than 8
};

RegionDiff compare(const QImage& a, const QImage& b, const QRect& region) {
    RegionDiff d;
    if (region.isEmpty()) return d;
    const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
    double sum = 0.0;
    long changed = 0, count = 0;
    for (int row = region.top(); row <= region.bottom(); ++row)
        for (int col = region.left(); col <= region.right(); ++col) {
            const QRgb p = x.pixel(col, row), q = y.pixel(col, row);
            const int dr = std::abs(qRed(p) - qRed(q)), dg = std::abs(qGreen(p) - qGreen(q)),
                      db = std::abs(qBlue(p) - qBlue(q));
            sum += dr + dg + db;
            changed += std::max({dr, dg, db}) > 8 ? 1 : 0;
            ++count;
        }
    d.meanAbs = sum / (3.0 * static_cast<double>(count));
    d.changedFraction = static_cast<double>(changed) / static_cast<double>(count);
    return d;
}

// |after − before| × 4, with the compared square outlined in red.
QImage diffImage(const QImage& a, const QImage& b, const QRect& region) {
    const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
    QImage out(x.size(), QImage::Format_RGB32);
    for (int row = 0; row < out.height(); ++row)
        for (int col = 0; col < out.width(); ++col) {
            const QRgb p = x.pixel(col, row), q = y.pixel(col, row);
            auto d = [](int u, int v) { return std::min(255, 4 * std::abs(u - v)); };
            out.setPixel(col, row, qRgb(d(qRed(p), qRed(q)), d(qGreen(p), qGreen(q)), d(qBlue(p), qBlue(q))));
        }
    for (int col = region.left(); col <= region.right(); ++col)
        for (int row : {region.top(), region.bottom()}) out.setPixel(col, row, qRgb(255, 0, 0));
    for (int row = region.top(); row <= region.bottom(); ++row)
        for (int col : {region.left(), region.right()}) out.setPixel(col, row, qRgb(255, 0, 0));
    return out;
}

void writeFile(const QString& path, const QByteArray& bytes) {
    QFile f(path);
    ASSERT_TRUE(f.open(QIODevice::WriteOnly | QIODevice::Truncate)) << path.toStdString();
    f.write(bytes);
}

// An OBJ sphere of the given radius centred at `centre`.
QByteArray sphereObj(float radius, glm::vec3 centre, int rings = 8, int segments = 16) {
    const Mesh m = makeSphere(rings, segments);
    QByteArray out;
    for (const glm::vec3& p : m.positions) {
        const glm::vec3 q = centre + radius * p;
        out += QByteArray("v ") + QByteArray::number(q.x, 'g', 9) + ' ' + QByteArray::number(q.y, 'g', 9) +
               ' ' + QByteArray::number(q.z, 'g', 9) + '\n';
    }
    for (std::size_t i = 0; i < m.indices.size(); i += 3)
        out += "f " + QByteArray::number(m.indices[i] + 1) + ' ' + QByteArray::number(m.indices[i + 1] + 1) +
               ' ' + QByteArray::number(m.indices[i + 2] + 1) + '\n';
    return out;
}

}  // namespace

TEST(MainWindow, LambdaEditRedrawsWithoutRebuildingOrUploading) {
    auto w = openWindow();
    EXPECT_EQ(w->windowTitle(), QStringLiteral("Untitled[*] — mipgloss"));
    ASSERT_TRUE(settledFrame(*w));
    ASSERT_EQ(w->document()->objectCount(), 4);

    // Select object 1 with a click on its row.
    QListView* list = w->sceneList();
    ASSERT_NE(list, nullptr);
    const QRect row = list->visualRect(list->model()->index(1, 0));
    ASSERT_FALSE(row.isEmpty());
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, row.center());
    ASSERT_EQ(w->document()->selected(), 1);

    auto* lambdaSpin = w->materialPanel()->findChild<QDoubleSpinBox*>(QStringLiteral("lambdaSpin"));
    auto* exponentSpin = w->materialPanel()->findChild<QDoubleSpinBox*>(QStringLiteral("exponentSpin"));
    ASSERT_TRUE(lambdaSpin && exponentSpin);
    ASSERT_TRUE(lambdaSpin->isEnabled());
    EXPECT_DOUBLE_EQ(lambdaSpin->value(), 3.5);

    // Close up on the selected teapot, so the check sees its reflection in detail.
    {
        const SceneObject& o = w->document()->object(1);
        const glm::vec3 r(o.worldRadius());
        const float aspect = static_cast<float>(w->viewport()->width()) /
                             static_cast<float>(std::max(w->viewport()->height(), 1));
        w->viewport()->camera().frame(Bounds{o.worldCentre() - r, o.worldCentre() + r}, aspect, 1.05f);
        ASSERT_TRUE(settledFrame(*w));
    }
    const QImage before = w->viewport()->grabFramebuffer();
    const std::uint64_t buildsBefore = w->environments()->counters().chainBuilds;
    const std::uint64_t uploadsBefore = w->viewport()->counters().chainUploads;
    const std::uint64_t settledBefore = w->viewport()->counters().objectsSettled;
    EXPECT_GE(uploadsBefore, 1u);

    QSignalSpy frames(w->viewport(), &Viewport::frameDrawn);
    typeInto(lambdaSpin, QStringLiteral("0.5"));
    EXPECT_FLOAT_EQ(w->document()->materialOf(1).lambda, 0.5f);
    ASSERT_TRUE(waitUntil([&] { return frames.count() > 0; }, kFrameTimeoutMs)) << "no frame after the edit";
    // Nothing is built or uploaded for the chain. λ 0.5 (n = 24575) is sharper than the lobe
    // stack's sharpest entry at this face size (lobes.h, stackTop): the chain shows it.
    ASSERT_TRUE(w->environments()->waitUntilIdle());
    ASSERT_TRUE(settledFrame(*w));
    EXPECT_EQ(w->viewport()->counters().objectsSettled, settledBefore - 1) << "λ 0.5 from the chain";
    const QImage after = w->viewport()->grabFramebuffer();

    ASSERT_EQ(before.size(), after.size());
    const QRect selected = objectRegion(*w, 1, after.size());
    // Outside the selected object's square (the background, the neighbours' edges) nothing changes.
    const RegionDiff inSelected = compare(before, after, selected);
    const RegionDiff inTopBand = compare(before, after, QRect(0, 0, after.width(), std::max(selected.top(), 1)));
    std::printf("λ 3.5 -> 0.5: object 1 region %dx%d mean |Δ| %.2f, %.1f%% changed; above it mean |Δ| %.3f\n",
                selected.width(), selected.height(), inSelected.meanAbs, 100.0 * inSelected.changedFraction,
                inTopBand.meanAbs);
    const bool ok = inSelected.meanAbs > 2.0 && inSelected.changedFraction > 0.05 &&
                    inTopBand.meanAbs < 0.1 * inSelected.meanAbs;
    EXPECT_TRUE(ok) << "the picture must change where the selected object is, and only there";
    if (!ok || HasFailure()) {
        before.save(QString::fromStdString(outputPath("window_lambda_before.png")));
        after.save(QString::fromStdString(outputPath("window_lambda_after.png")));
        diffImage(before, after, selected).save(QString::fromStdString(outputPath("window_lambda_diff.png")));
    }
    EXPECT_EQ(w->environments()->counters().chainBuilds, buildsBefore);
    EXPECT_EQ(w->viewport()->counters().chainUploads, uploadsBefore);

    // Any λ with no waiting (issue 24): λ 4 rests, its entries are made, then (quietly) those
    // within a level of them; λ at quarter steps there is read from the stack's exact lobes on the
    // very first frame after the edit: nothing is made for it, the object counts as settled.
    typeInto(lambdaSpin, QStringLiteral("4"));
    ASSERT_TRUE(w->environments()->waitUntilIdle());
    ASSERT_TRUE(settledFrame(*w));
    EXPECT_EQ(w->viewport()->counters().objectsSettled, settledBefore) << "λ 4 from the stack";
    ASSERT_TRUE(waitUntil([&] { return !w->environments()->makingLobes(); }, kEnvironmentTimeoutMs));
    for (const char* lambda : {"4.25", "4.5", "4.75", "3.75", "3.5"}) {
        const std::uint64_t lobes = w->environments()->counters().lobeBuilds;
        QSignalSpy quarterFrames(w->viewport(), &Viewport::frameDrawn);
        typeInto(lambdaSpin, QString::fromLatin1(lambda));
        ASSERT_TRUE(waitUntil([&] { return quarterFrames.count() > 0; }, kFrameTimeoutMs)) << lambda;
        EXPECT_EQ(w->environments()->counters().lobeBuilds, lobes) << "λ " << lambda << ": nothing made";
        EXPECT_EQ(w->viewport()->counters().objectsSettled, settledBefore) << "λ " << lambda << " read from the stack at once";
    }

    // Typing an exponent sets λ through the one mapping (phong.h), whatever the face size.
    typeInto(exponentSpin, QStringLiteral("250"));
    EXPECT_NEAR(w->document()->materialOf(1).lambda, exponentToLambda(250.0), 1e-5);
    EXPECT_NEAR(lambdaSpin->value(), exponentToLambda(250.0), 0.005);
    EXPECT_NEAR(exponentSpin->value(), 250.0, 0.01);
    EXPECT_EQ(w->environments()->counters().chainBuilds, buildsBefore);

    // The selection is two-way: selecting in the document moves the list.
    w->document()->setSelected(2);
    ASSERT_FALSE(list->selectionModel()->selectedRows().isEmpty());
    EXPECT_EQ(list->selectionModel()->selectedRows().first().row(), 2);
    EXPECT_DOUBLE_EQ(lambdaSpin->value(), 5.0);
}

// The background's blur is a material's λ: [0, kMaxLambda] under any face size, and what is typed
// reaches the document unchanged.
TEST(MainWindow, BackgroundBlurUsesTheOneLambdaRange) {
    auto w = openWindow();
    auto* blur = w->findChild<QDoubleSpinBox*>(QStringLiteral("backgroundBlurSpin"));
    ASSERT_NE(blur, nullptr);
    SceneDocument* doc = w->document();
    for (int faceSize : {64, 512, 128}) {
        EnvironmentSettings e = doc->scene().environment;
        e.faceSize = faceSize;
        doc->setEnvironment(e);
        EXPECT_EQ(blur->minimum(), 0.0) << faceSize;
        EXPECT_EQ(blur->maximum(), kMaxLambda) << faceSize;
    }
    ASSERT_TRUE(blur->isEnabled());
    typeInto(blur, QStringLiteral("7.5"));  // beyond a 64² or 128² chain's old last level
    EXPECT_FLOAT_EQ(doc->scene().display.backgroundLambda, 7.5f);
    typeInto(blur, QStringLiteral("99"));
    EXPECT_TRUE(isValidLambda(doc->scene().display.backgroundLambda));
    EXPECT_LE(doc->scene().display.backgroundLambda, 8.0f);
}

// The backdrop's swatch opens a colour dialog; the colour chosen is the document's backdrop, one
// undo step named for it, and the swatch shows it.
TEST(MainWindow, BackdropColourIsChosenInADialogAndIsOneUndoStep) {
    auto w = openWindow();
    SceneDocument* doc = w->document();
    auto* button = w->findChild<QPushButton*>(QStringLiteral("backdropButton"));
    ASSERT_NE(button, nullptr);
    button->click();
    auto* dialog = w->findChild<QColorDialog*>(QStringLiteral("backdropDialog"));
    ASSERT_NE(dialog, nullptr);
    EXPECT_TRUE(dialog->isVisible());
    const Rgb before = doc->scene().display.backdrop;
    dialog->setCurrentColor(QColor(255, 255, 255));
    dialog->accept();
    EXPECT_EQ(doc->scene().display.backdrop, Rgb(1.0f));
    EXPECT_EQ(doc->undoStack()->undoText(), QStringLiteral("Change backdrop colour"));
    EXPECT_TRUE(button->styleSheet().contains(QStringLiteral("#ffffff")));
    doc->undoStack()->undo();
    EXPECT_EQ(doc->scene().display.backdrop, before);
}

TEST(MainWindow, ImportedMeshesArePlacedBesideAndSizedToTheScene) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    auto w = openWindow();
    SceneDocument* doc = w->document();
    const float teapotRadius = doc->object(0).worldRadius();
    // A 120-unit scan far from the origin and a 0.1-unit one: both end up teapot-sized, beside.
    const QString big = dir.filePath(QStringLiteral("big_scan.obj"));
    const QString tiny = dir.filePath(QStringLiteral("tiny.obj"));
    writeFile(big, sphereObj(120.0f, {500.0f, 40.0f, -300.0f}));
    writeFile(tiny, sphereObj(0.1f, {0.0f, 0.0f, 0.0f}));

    QSignalSpy finished(w.get(), &MainWindow::importFinished);
    float previousMaxX = sceneBounds(doc->scene()).max.x;
    for (const QString& path : {big, tiny}) {
        w->importMeshes({path});
        ASSERT_TRUE(waitUntil([&] { return !finished.isEmpty(); }, 60000));
        EXPECT_EQ(finished.takeFirst().at(0).toInt(), 1);
        const int index = doc->objectCount() - 1;
        const SceneObject& o = doc->object(index);
        EXPECT_EQ(doc->selected(), index);
        EXPECT_EQ(QString::fromStdString(o.name), QFileInfo(path).completeBaseName());
        EXPECT_EQ(w->document()->scene().materialOf(o).lambda, MainWindow::kImportedLambda);
        EXPECT_EQ(w->document()->scene().materialOf(o).mode, LookupMode::Reflect);
        EXPECT_NEAR(o.worldRadius(), teapotRadius, 0.01f * teapotRadius) << path.toStdString();
        EXPECT_GT(o.worldCentre().x - o.worldRadius(), previousMaxX) << "must not overlap the scene";
        EXPECT_NEAR(o.worldCentre().y, sceneBounds(doc->scene()).centre().y, 0.5f * teapotRadius);
        previousMaxX = sceneBounds(doc->scene()).max.x;
        EXPECT_FALSE(w->lastMessageIsError()) << w->lastMessage().toStdString();
    }
    EXPECT_EQ(doc->objectCount(), 6);
    ASSERT_TRUE(settledFrame(*w));

    // A mesh of a similar size keeps its own scale.
    const QString similar = dir.filePath(QStringLiteral("similar.obj"));
    writeFile(similar, sphereObj(0.5f * teapotRadius, {0.0f, 0.0f, 0.0f}));
    w->importMeshes({similar});
    ASSERT_TRUE(waitUntil([&] { return !finished.isEmpty(); }, 60000));
    EXPECT_EQ(doc->object(doc->objectCount() - 1).transform.scale, 1.0f);
}

TEST(MainWindow, LargeMeshImportsInTheBackground) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString path = dir.filePath(QStringLiteral("dense.obj"));
    const QByteArray obj = sphereObj(1.0f, {0.0f, 0.0f, 0.0f}, 200, 400);
    ASSERT_GT(obj.size(), MainWindow::kBackgroundImportBytes);
    writeFile(path, obj);
    auto w = openWindow();
    QSignalSpy finished(w.get(), &MainWindow::importFinished);
    const int before = w->document()->objectCount();
    w->importMeshes({path});
    EXPECT_TRUE(w->importing()) << "a large file must not block the UI thread";
    EXPECT_EQ(w->document()->objectCount(), before);
    ASSERT_TRUE(waitUntil([&] { return !finished.isEmpty(); }, 120000));
    EXPECT_FALSE(w->importing());
    EXPECT_EQ(w->document()->objectCount(), before + 1);
    EXPECT_EQ(w->document()->object(before).mesh->triangleCount(), makeSphere(200, 400).triangleCount());
}

TEST(MainWindow, BadFilesLeaveTheSceneAsItWas) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    // A truncated OBJ: the bunny cut in the middle of a face line.
    const fs::path bunny = test::asset("meshes/bunny_npm_lowres.obj");
    MIPGLOSS_REQUIRE_ASSET(bunny);
    QByteArray whole;
    {
        QFile f(QString::fromStdString(bunny.string()));
        ASSERT_TRUE(f.open(QIODevice::ReadOnly));
        whole = f.readAll();
    }
    const qsizetype lastFace = whole.lastIndexOf("\nf ");
    ASSERT_GT(lastFace, 0);
    const qsizetype cut = whole.indexOf(' ', lastFace + 3);  // after the face's first index
    const QString truncated = dir.filePath(QStringLiteral("truncated_bunny.obj"));
    writeFile(truncated, whole.left(cut + 1));
    const QString nanObj = dir.filePath(QStringLiteral("nan_vertices.obj"));
    writeFile(nanObj, "v 0 0 0\nv nan 1 0\nv 0 1 0\nv 1 1 1\nf 1 2 3\nf 1 3 4\n");
    const QString noFaces = dir.filePath(QStringLiteral("no_faces.obj"));
    writeFile(noFaces, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const QString textExr = dir.filePath(QStringLiteral("sky.exr"));
    writeFile(textExr, "this is not an image\n");
    const QString wide = dir.filePath(QStringLiteral("three_by_two.png"));
    {
        QImage image(3, 2, QImage::Format_RGB32);
        image.fill(Qt::gray);
        ASSERT_TRUE(image.save(wide));
    }
    const QString badScene = dir.filePath(QStringLiteral("bad_scene.json"));
    writeFile(badScene, R"({"format": "mipgloss-scene", "version": 1, "objects": [{"mesh": "gone.obj"}]})");
    const QString badLambda = dir.filePath(QStringLiteral("bad_lambda.json"));
    writeFile(badLambda, R"({"format": "mipgloss-scene", "version": 2, "objects": [
        {"name": "fine", "mesh": "builtin:sphere", "material": {"lambda": 2}},
        {"name": "absurd", "mesh": "builtin:sphere", "material": {"lambda": -1}}]})");

    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    SceneDocument* doc = w->document();
    const int objects = doc->objectCount();
    const EnvironmentSettings environment = doc->scene().environment;
    const auto prepared = w->environments()->current();
    const QString title = w->windowTitle();

    auto expectUnchanged = [&](const QString& file) {
        SCOPED_TRACE(file.toStdString());
        EXPECT_TRUE(w->lastMessageIsError());
        EXPECT_TRUE(w->lastMessage().contains(QFileInfo(file).fileName())) << w->lastMessage().toStdString();
        EXPECT_EQ(doc->objectCount(), objects);
        EXPECT_EQ(doc->scene().environment, environment);
        EXPECT_EQ(w->environments()->current(), prepared);
        EXPECT_EQ(w->windowTitle(), title);
        EXPECT_TRUE(settledFrame(*w)) << "the window must still draw";
        const auto* banner = w->findChild<QWidget*>(QStringLiteral("messageBanner"));
        ASSERT_NE(banner, nullptr);
        EXPECT_TRUE(banner->isVisible());
    };

    for (const QString& mesh : {truncated, nanObj, noFaces}) {
        w->importMeshes({mesh});
        expectUnchanged(mesh);
    }
    // A batch with a good and a bad file adds the good one and reports the bad one.
    w->importMeshes({QString::fromStdString(bunny.string()), noFaces});
    EXPECT_EQ(doc->objectCount(), objects + 1);
    EXPECT_TRUE(w->lastMessage().contains(QStringLiteral("no_faces.obj")));
    doc->removeObject(objects);

    for (const QString& env : {textExr, wide}) {
        const std::uint64_t failures = w->environments()->counters().failures;
        const int steps = doc->undoStack()->count();
        const QString undoText = doc->undoStack()->undoText();
        EXPECT_TRUE(w->openEnvironment(env));  // it exists; reading it fails on the worker
        ASSERT_TRUE(waitUntil([&] { return w->environments()->counters().failures > failures; },
                              kEnvironmentTimeoutMs))
            << env.toStdString();
        expectUnchanged(env);
        // The open is withdrawn: no step asks for the file again, none answers the failure.
        EXPECT_EQ(doc->undoStack()->count(), steps);
        EXPECT_EQ(doc->undoStack()->undoText(), undoText);
        EXPECT_FALSE(doc->undoStack()->canRedo());
    }
    EXPECT_FALSE(w->openEnvironment(dir.filePath(QStringLiteral("absent.hdr"))));
    expectUnchanged(dir.filePath(QStringLiteral("absent.hdr")));

    const std::vector<std::string> namesBefore = [&] {
        std::vector<std::string> names;
        for (const SceneObject& o : doc->scene().objects) names.push_back(o.name);
        return names;
    }();
    EXPECT_FALSE(w->openScene(badScene));
    expectUnchanged(badScene);
    EXPECT_TRUE(w->lastMessage().contains(QStringLiteral("gone.obj")));
    for (int i = 0; i < doc->objectCount(); ++i) EXPECT_EQ(doc->object(i).name, namesBefore[static_cast<std::size_t>(i)]);
    // An absurd λ is an error naming the file and the field, and the scene stays as it was.
    EXPECT_FALSE(w->openScene(badLambda));
    expectUnchanged(badLambda);
    EXPECT_TRUE(w->lastMessage().contains(QStringLiteral("objects[1].material.lambda")))
        << w->lastMessage().toStdString();
    for (int i = 0; i < doc->objectCount(); ++i) EXPECT_EQ(doc->object(i).name, namesBefore[static_cast<std::size_t>(i)]);
}

TEST(MainWindow, SaveAndOpenSceneRoundTrip) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    auto w = openWindow();
    Material m = w->document()->materialOf(2);
    m.lambda = 1.25f;
    m.sharperAtGrazing = true;
    w->document()->setMaterial(2, m);
    const QString file = dir.filePath(QStringLiteral("mine.json"));
    ASSERT_TRUE(w->saveScene(file)) << w->lastMessage().toStdString();
    EXPECT_EQ(w->windowTitle(), QStringLiteral("mine.json[*] — mipgloss"));
    w->newScene();
    EXPECT_EQ(w->windowTitle(), QStringLiteral("Untitled[*] — mipgloss"));
    EXPECT_NE(w->document()->materialOf(2), m);
    ASSERT_TRUE(w->openScene(file)) << w->lastMessage().toStdString();
    EXPECT_EQ(w->document()->materialOf(2), m);
    EXPECT_EQ(w->windowTitle(), QStringLiteral("mine.json[*] — mipgloss"));
    EXPECT_FALSE(w->isWindowModified());
    ASSERT_TRUE(settledFrame(*w));
    const QString png = dir.filePath(QStringLiteral("shot.png"));
    ASSERT_TRUE(w->exportImage(png));
    const QImage shot(png);
    EXPECT_EQ(shot.size(), w->viewport()->grabFramebuffer().size());
}

TEST(MainWindow, DroppedFilesOpenByKind) {
    const fs::path bunny = test::asset("meshes/bunny_npm_lowres.obj");
    const fs::path sky = test::asset("env/sunset.exr");
    MIPGLOSS_REQUIRE_ASSET(bunny);
    MIPGLOSS_REQUIRE_ASSET(sky);
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    const int objects = w->document()->objectCount();

    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(QString::fromStdString(bunny.string())),
                  QUrl::fromLocalFile(QString::fromStdString(sky.string()))});
    QDragEnterEvent enter(QPoint(300, 300), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(w.get(), &enter);
    EXPECT_TRUE(enter.isAccepted());
    QDropEvent drop(QPointF(300, 300), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(w.get(), &drop);

    EXPECT_EQ(w->document()->objectCount(), objects + 1);
    EXPECT_EQ(w->document()->object(objects).name, "bunny_npm_lowres");
    EXPECT_EQ(fs::path(w->document()->scene().environment.source), sky);
    ASSERT_TRUE(settledFrame(*w));
    EXPECT_EQ(fs::path(w->environments()->current()->settings.source), sky);
    EXPECT_FALSE(w->lastMessageIsError()) << w->lastMessage().toStdString();

    // A file of no known kind is refused at the door.
    QMimeData other;
    other.setUrls({QUrl::fromLocalFile(QStringLiteral("/tmp/notes.txt"))});
    QDragEnterEvent refused(QPoint(300, 300), Qt::CopyAction, &other, Qt::LeftButton, Qt::NoModifier);
    refused.setAccepted(false);
    QApplication::sendEvent(w.get(), &refused);
    EXPECT_FALSE(refused.isAccepted());
}

TEST(MainWindow, SceneListButtonsAndDeleteKey) {
    auto w = openWindow();
    SceneDocument* doc = w->document();
    QListView* list = w->sceneList();
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualRect(list->model()->index(0, 0)).center());
    ASSERT_EQ(doc->selected(), 0);

    QToolButton* duplicate = nullptr;
    for (QToolButton* b : w->findChildren<QToolButton*>())
        if (b->defaultAction() && b->defaultAction()->objectName() == QLatin1String("duplicateAction")) duplicate = b;
    ASSERT_NE(duplicate, nullptr);
    QTest::mouseClick(duplicate, Qt::LeftButton);
    EXPECT_EQ(doc->objectCount(), 5);
    EXPECT_EQ(doc->selected(), 1);
    EXPECT_EQ(doc->object(1).mesh.get(), doc->object(0).mesh.get());
    EXPECT_EQ(list->selectionModel()->selectedRows().first().row(), 1);

    // Delete removes the selected object while the list has the focus (a window shortcut).
    w->activateWindow();
    if (!QTest::qWaitForWindowActive(w.get())) GTEST_SKIP() << "the window cannot be activated here";
    list->setFocus();
    QTest::keyClick(list, Qt::Key_Delete);
    EXPECT_EQ(doc->objectCount(), 4);
    EXPECT_EQ(doc->object(1).name, "glossy (λ 3.5)");
    EXPECT_EQ(doc->selected(), 1);
    // ... but never while a number is typed in the material panel.
    auto* spin = w->materialPanel()->findChild<QDoubleSpinBox*>(QStringLiteral("lambdaSpin"));
    spin->setFocus();
    QTest::keyClick(spin, Qt::Key_Delete);
    EXPECT_EQ(doc->objectCount(), 4);
}

namespace {

// Skip what the scene does not need, seen through the window's counters: no frames while idle,
// the irradiance map only once an object asks for it (and then no chain rebuild).
TEST(MainWindow, IdleDrawsNothingAndIrradianceComesOnlyWhenAsked) {
    auto w = openWindow();
    ASSERT_TRUE(settledFrame(*w));
    // The library's thumbnails (the starter materials) are drawn in the background too.
    ASSERT_TRUE(waitUntil([&] { return !w->libraryDock()->thumbnails()->busy(); }, kEnvironmentTimeoutMs));
    const quint64 framesBefore = w->viewport()->counters().frames;
    QTest::qWait(1500);  // events processed, nothing changed
    EXPECT_EQ(w->viewport()->counters().frames, framesBefore) << "frames drawn while idle";

    const EnvironmentCounters before = w->environments()->counters();
    EXPECT_EQ(before.irradianceBuilds, 0u) << "Figure 1 does not use the irradiance map";
    EXPECT_FALSE(w->environments()->current()->irradiance);
    Material m = w->document()->materialOf(3);
    ASSERT_EQ(m.mode, LookupMode::Normal);
    m.useIrradiance = true;
    w->document()->setMaterial(3, m);
    ASSERT_TRUE(settledFrame(*w));
    const EnvironmentCounters after = w->environments()->counters();
    EXPECT_EQ(after.irradianceBuilds, 1u);
    EXPECT_EQ(after.chainBuilds, before.chainBuilds) << "the chain is kept";
    EXPECT_EQ(w->viewport()->counters().irradianceUploads, 1u);
    EXPECT_EQ(w->viewport()->counters().chainUploads, 1u);
}

}  // namespace

TEST(MainWindow, EditMenuUndoesAndRedoesWithTheStandardShortcuts) {
    auto w = openWindow();
    SceneDocument* doc = w->document();
    auto* undo = w->findChild<QAction*>(QStringLiteral("undoAction"));
    auto* redo = w->findChild<QAction*>(QStringLiteral("redoAction"));
    ASSERT_TRUE(undo && redo);
    EXPECT_FALSE(undo->isEnabled());
    doc->setSelected(1);
    auto* lambdaSpin = w->materialPanel()->findChild<QDoubleSpinBox*>(QStringLiteral("lambdaSpin"));
    ASSERT_NE(lambdaSpin, nullptr);
    typeInto(lambdaSpin, QStringLiteral("0.5"));
    ASSERT_FLOAT_EQ(doc->materialOf(1).lambda, 0.5f);
    EXPECT_TRUE(undo->isEnabled());
    EXPECT_EQ(undo->text(), QStringLiteral("Undo Change λ of Polished"));
    EXPECT_TRUE(undo->shortcuts().contains(QKeySequence(QKeySequence::Undo)));

    w->activateWindow();
    if (!QTest::qWaitForWindowActive(w.get())) GTEST_SKIP() << "the window cannot be activated here";
    w->sceneList()->setFocus();  // not a text field, whose own undo would take the keys
    QTest::keySequence(w.get(), QKeySequence::Undo);
    EXPECT_FLOAT_EQ(doc->materialOf(1).lambda, 3.5f);
    EXPECT_DOUBLE_EQ(lambdaSpin->value(), 3.5);
    EXPECT_EQ(redo->text(), QStringLiteral("Redo Change λ of Polished"));
    QTest::keySequence(w.get(), QKeySequence::Redo);
    EXPECT_FLOAT_EQ(doc->materialOf(1).lambda, 0.5f);
}

// A library material dragged onto a row of the scene list is applied to that object.
TEST(MainWindow, LibraryMaterialDroppedOnASceneRowIsApplied) {
    auto w = openWindow();
    SceneDocument* doc = w->document();
    QListView* list = w->sceneList();
    LibraryMaterial velvet{"Velvet", Material{}};
    velvet.material.lambda = 6.5f;
    velvet.material.mode = LookupMode::Normal;
    std::unique_ptr<QMimeData> mime(materialMimeData(velvet));
    const QPoint target = list->visualRect(list->model()->index(2, 0)).center();
    ASSERT_FALSE(target.isNull());

    QDragEnterEvent enter(target, Qt::CopyAction, mime.get(), Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &enter);
    EXPECT_TRUE(enter.isAccepted());
    QDragMoveEvent move(target, Qt::CopyAction, mime.get(), Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &move);
    EXPECT_TRUE(move.isAccepted());
    QDropEvent drop(QPointF(target), Qt::CopyAction, mime.get(), Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &drop);

    EXPECT_EQ(doc->materialOf(2), velvet.material);
    EXPECT_EQ(doc->namedMaterialOf(2)->name, "Velvet");
    EXPECT_NE(doc->materialOf(1), velvet.material) << "only the row it was dropped on";
    EXPECT_EQ(doc->undoStack()->undoText(), QStringLiteral("Apply Velvet to glossy (λ 5)"));
    EXPECT_EQ(list->model()->index(2, 0).data(SceneListModel::MaterialNameRole).toString(), QStringLiteral("Velvet"));
    EXPECT_TRUE(w->isWindowModified());
    doc->undoStack()->undo();
    EXPECT_FALSE(w->isWindowModified());
}

// The environment panel's edits are undo steps too; a drag of the rotation slider is one.
TEST(MainWindow, EnvironmentRotationDragIsOneUndoStep) {
    auto w = openWindow();
    SceneDocument* doc = w->document();
    auto* rotation = w->findChild<QSlider*>(QStringLiteral("envRotationSlider"));
    auto* exposure = w->findChild<QDoubleSpinBox*>(QStringLiteral("exposureSpin"));
    ASSERT_TRUE(rotation && exposure);
    const Scene before = doc->scene();
    rotation->setSliderDown(true);  // what pressing the handle does
    for (int degrees = 5; degrees <= 90; degrees += 5) rotation->setValue(degrees);
    rotation->setSliderDown(false);
    EXPECT_FLOAT_EQ(doc->scene().display.environmentRotationDegrees, 90.0f);
    EXPECT_EQ(doc->undoStack()->count(), 1);
    EXPECT_EQ(doc->undoStack()->undoText(), QStringLiteral("Rotate environment"));
    typeInto(exposure, QStringLiteral("1.5"));
    EXPECT_EQ(doc->undoStack()->count(), 2);
    EXPECT_EQ(doc->undoStack()->undoText(), QStringLiteral("Change exposure"));
    doc->undoStack()->undo();
    doc->undoStack()->undo();
    EXPECT_EQ(doc->scene(), before);
    EXPECT_EQ(rotation->value(), 0);
    EXPECT_DOUBLE_EQ(exposure->value(), 0.0);
    EXPECT_FALSE(w->isWindowModified());
}

// The library dock lives in the window: File has Import/Export library, applying an entry is a
// scene edit (it marks the scene modified and undoes), and a library edit is saved at once and
// undoable from the same Edit menu but never marks the scene modified.
TEST(MainWindow, LibraryDockAppliesEntriesAndItsEditsNeverMarkTheScene) {
    auto w = openWindow();
    test::TempDir dir;
    const fs::path file = dir.path() / "library.json";
    ASSERT_TRUE(w->library()->open(file));
    ASSERT_NE(w->libraryDock(), nullptr);
    EXPECT_EQ(w->libraryDock()->objectName(), QStringLiteral("libraryDock"));
    bool importInMenu = false;
    for (QAction* a : w->menuBar()->actions())
        if (a->menu() && a->menu()->actions().contains(w->libraryDock()->importLibraryAction())) importInMenu = true;
    EXPECT_TRUE(importInMenu) << "File → Import library";
    EXPECT_FALSE(w->isWindowModified());

    LibraryMaterial gold{"Gold", {}};
    gold.material.lambda = 2.5f;
    gold.material.tint = {1.0f, 0.8f, 0.3f};
    ASSERT_EQ(w->library()->add(gold), 0);
    EXPECT_FALSE(w->isWindowModified()) << "a library edit is saved already; the scene is unchanged";
    EXPECT_EQ(loadLibrary(file).entries.size(), 1u);

    SceneDocument* doc = w->document();
    doc->setSelected(2);
    const Material before = doc->materialOf(2);
    w->libraryDock()->setCurrentRow(0);
    w->libraryDock()->applyEntryAction()->trigger();
    EXPECT_EQ(doc->materialOf(2), gold.material);
    ASSERT_NE(doc->namedMaterialOf(2), nullptr);
    EXPECT_EQ(doc->namedMaterialOf(2)->libraryEntry, "Gold");
    EXPECT_TRUE(w->isWindowModified());

    doc->undoStack()->undo();  // the apply
    EXPECT_EQ(doc->materialOf(2), before);
    EXPECT_FALSE(w->isWindowModified()) << "undone back to the opened scene";
    doc->undoStack()->undo();  // the library add
    EXPECT_EQ(w->library()->library().entries.size(), 0u);
    EXPECT_EQ(loadLibrary(file).entries.size(), 0u) << "the undo is on disk too";
    EXPECT_FALSE(w->isWindowModified());
}

// A laptop screen (1280×800 less a panel and the title bar) holds the whole window: the docks
// scroll rather than push the window taller than the screen, whatever the material panel shows
// (a layered material's editor is the tallest).
TEST(MainWindow, FitsALaptopScreenWithALayeredMaterialSelected) {
    auto w = openWindow();
    Material paint;
    paint.layered = true;
    w->document()->setMaterial(0, paint);
    w->document()->setSelected(0);
    QCoreApplication::processEvents();
    const QSize least = w->minimumSizeHint().expandedTo(w->minimumSize());
    std::printf("[ MainWindow ] minimum size %dx%d\n", least.width(), least.height());
    EXPECT_LE(least.height(), 720);
    EXPECT_LE(least.width(), 1280);
}
