// The desktop window's bugs of issue 20, each driven as a user meets it (QTest): a selected
// library thumbnail keeps its colours, library names are shown whole, a later success takes an
// error banner down, the status bar says when an environment is loaded or failed, long errors are
// cut short beside the environment status, which is itself shown whole, and Ctrl+Z in a number
// field undoes the document.
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/library_dock.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/material_panel.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/thumbnail_cache.h"

#include "test_support.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QApplication>
#include <QDoubleSpinBox>
#include <QHelpEvent>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QProgressBar>
#include <QSignalSpy>
#include <QSortFilterProxyModel>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTest>
#include <QToolTip>
#include <QUndoStack>

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
using mipgloss::test::smallEnvironment;
using mipgloss::test::waitUntil;

namespace {

constexpr int kEnvironmentTimeoutMs = 120000;  // llvmpipe and a shared CPU are slow

bool environmentSettled(MainWindow& w) {
    return waitUntil([&] { return w.environments()->current() && !w.environments()->busy() && !w.importing(); },
                     kEnvironmentTimeoutMs);
}

bool environmentLoaded(MainWindow& w, const fs::path& file) {
    return waitUntil(
        [&] {
            const auto current = w.environments()->current();
            return current && fs::path(current->settings.source) == file && !w.environments()->busy();
        },
        kEnvironmentTimeoutMs);
}

// What the status bar's message area shows now: Qt's temporary message, else the window's own
// message label when it has one.
QString shownStatus(MainWindow& w) {
    const QString temporary = w.statusBar()->currentMessage();
    if (!temporary.isEmpty()) return temporary;
    const auto* label = w.statusBar()->findChild<QLabel*>(QStringLiteral("statusMessage"));
    return label && label->isVisible() ? label->text() : QString();
}

QWidget* banner(MainWindow& w) { return w.findChild<QWidget*>(QStringLiteral("messageBanner")); }

void writeFile(const fs::path& path, const std::string& bytes) { test::writeBytes(path, bytes); }

QString qstr(const fs::path& path) { return QString::fromStdString(path.string()); }

LibraryMaterial orange(const std::string& name) {
    LibraryMaterial e;
    e.name = name;
    e.material.lambda = 2.0f;
    e.material.tint = {1.0f, 0.45f, 0.08f};
    return e;
}

// Mean |difference| of the channels of two same-sized regions, in grey levels.
double meanDifference(const QImage& a, const QRect& ra, const QImage& b, const QRect& rb) {
    const QImage x = a.copy(ra).convertToFormat(QImage::Format_RGB32);
    const QImage y = b.copy(rb).convertToFormat(QImage::Format_RGB32);
    if (x.size() != y.size() || x.isNull()) return -1.0;
    double sum = 0.0;
    for (int j = 0; j < x.height(); ++j)
        for (int i = 0; i < x.width(); ++i) {
            const QRgb p = x.pixel(i, j), q = y.pixel(i, j);
            sum += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) + std::abs(qBlue(p) - qBlue(q));
        }
    return sum / (3.0 * x.width() * x.height());
}

// The middle of a cell's thumbnail: a square of 60 % of the thumbnail's side, centred where the
// thumbnail is (the top of the cell, centred across it), away from any frame drawn around it.
QRect thumbnailMiddle(const QRect& cell) {
    const int side = ThumbnailCache::kThumbnailSize * 6 / 10;
    const QPoint centre(cell.center().x(), cell.top() + 4 + ThumbnailCache::kThumbnailSize / 2);
    return QRect(centre.x() - side / 2, centre.y() - side / 2, side, side);
}

// The number of separate bands of text ("ink": far from the view's background) in the rows of
// `image` from `top` to `bottom` (inclusive), between `left` and `right`.
int textBands(const QImage& image, int left, int right, int top, int bottom, QColor background) {
    int bands = 0;
    bool inBand = false;
    for (int y = std::max(top, 0); y <= std::min(bottom, image.height() - 1); ++y) {
        bool ink = false;
        for (int x = std::max(left, 0); x <= std::min(right, image.width() - 1) && !ink; ++x) {
            const QColor c = image.pixelColor(x, y);
            ink = std::abs(c.red() - background.red()) + std::abs(c.green() - background.green()) +
                      std::abs(c.blue() - background.blue()) >
                  150;
        }
        if (ink && !inBand) ++bands;
        inBand = ink;
    }
    return bands;
}

fs::path outputPath(const std::string& name) {
    const fs::path dir = MIPGLOSS_TEST_OUTPUT_DIR;
    std::error_code ec;
    fs::create_directories(dir, ec);
    return dir / name;
}

}  // namespace

// Bug: a selected thumbnail was tinted by the selection colour (QIcon's Selected mode), so an
// orange material looked olive. Its pixels are the unselected ones; the selection is a frame and
// background around it.
TEST(WindowBugs, SelectedThumbnailKeepsItsColours) {
    LibraryDocument doc(nullptr);
    doc.add(orange("orange"));
    doc.add(orange("orange 2"));  // the same parameters: the same picture
    SceneDocument scene;
    EnvironmentManager environments;
    environments.request(smallEnvironment(), ChainNeeds{});
    ASSERT_TRUE(environments.waitUntilIdle());
    LibraryDock dock(&doc, &scene, &environments);
    dock.resize(320, 400);
    dock.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&dock));
    ThumbnailCache& cache = *dock.thumbnails();
    ASSERT_TRUE(waitUntil([&] { return cache.isCurrent(doc.entry(0).material) && !cache.busy(); }, 60000));

    QListView* view = dock.view();
    const QModelIndex first = dock.filterModel()->index(0, 0), second = dock.filterModel()->index(1, 0);
    const QImage unselected = view->viewport()->grab().toImage();
    view->setCurrentIndex(first);
    ASSERT_TRUE(view->selectionModel()->isSelected(first));
    QCoreApplication::processEvents();
    const QImage selected = view->viewport()->grab().toImage();
    selected.save(qstr(outputPath("window_bugs_selected_thumbnail.png")));

    const QRect a = thumbnailMiddle(view->visualRect(first)), b = thumbnailMiddle(view->visualRect(second));
    const QColor middle = selected.pixelColor(a.center());
    std::printf("selected thumbnail's middle %d,%d,%d; unselected %d,%d,%d\n", middle.red(), middle.green(),
                middle.blue(), unselected.pixelColor(a.center()).red(), unselected.pixelColor(a.center()).green(),
                unselected.pixelColor(a.center()).blue());
    // The same thumbnail selected and not, and beside an unselected twin: only rounding apart.
    EXPECT_LT(meanDifference(selected, a, unselected, a), 1.0) << "the selected thumbnail is tinted";
    EXPECT_LT(meanDifference(selected, a, selected, b), 1.0) << "the selected thumbnail is tinted";
    // The selection still shows around it.
    const QRect cell = view->visualRect(first);
    EXPECT_GT(meanDifference(selected, cell, unselected, cell), 3.0) << "the selection is not shown";
}

// Bug: names were cut to about 8 characters (the first entry's one line of text set every
// cell's size). A name takes up to two lines and is shown whole; one longer than that is cut
// short in the middle; the tooltip names every entry whole.
TEST(WindowBugs, LibraryNamesAreShownWhole) {
    const QString longName = QStringLiteral("satin fabric from the studio's second shoot, warm key light, take 12");
    LibraryDocument doc(nullptr);
    doc.add(orange("chrome"));  // a short first name: the cells must not take their size from it
    doc.add(orange("brushed aluminium"));
    doc.add(orange("white satin plastic wrap"));
    doc.add(orange(longName.toStdString()));
    SceneDocument scene;
    EnvironmentManager environments;
    LibraryDock dock(&doc, &scene, &environments);
    dock.resize(520, 400);
    dock.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&dock));
    QListView* view = dock.view();
    const QFontMetrics metrics = view->fontMetrics();
    const QImage picture = view->viewport()->grab().toImage();
    picture.save(qstr(outputPath("window_bugs_library_names.png")));
    const QColor background = view->viewport()->palette().color(QPalette::Base);

    for (int row : {1, 2, 3}) {
        const QString name = dock.filterModel()->index(row, 0).data().toString();
        SCOPED_TRACE(name.toStdString());
        const QRect cell = view->visualRect(dock.filterModel()->index(row, 0));
        ASSERT_TRUE(view->viewport()->rect().contains(cell));
        EXPECT_GE(cell.height(), ThumbnailCache::kThumbnailSize + 2 * metrics.lineSpacing())
            << "the cell has no room for two lines";
        // The lines of text drawn below the thumbnail: one for a name that fits the cell's width
        // with room to spare, two for one wider than the cell.
        const int below = cell.top() + ThumbnailCache::kThumbnailSize + 6;
        const int cellBottom = cell.top() + std::max(cell.height(), view->gridSize().height()) - 1;
        const int bands = textBands(picture, cell.left(), cell.right(), below, cellBottom, background);
        const int advance = metrics.horizontalAdvance(name);
        if (advance > cell.width()) EXPECT_EQ(bands, 2);
        else if (advance < cell.width() - 16) EXPECT_EQ(bands, 1);
        else EXPECT_TRUE(bands == 1 || bands == 2) << bands;

        // What is drawn: the whole name, or for the longest its start and end around an ellipsis.
        const QStringList lines = LibraryDock::nameLines(name, view->font(), cell.width() - 8);
        EXPECT_LE(lines.size(), 2);
        if (row < 3) {
            EXPECT_EQ(lines.join(QLatin1Char(' ')), name);
        } else {
            ASSERT_EQ(lines.size(), 2);
            EXPECT_TRUE(name.startsWith(lines[0])) << lines[0].toStdString();
            EXPECT_TRUE(lines[1].contains(QChar(0x2026))) << lines[1].toStdString();
            EXPECT_TRUE(name.endsWith(lines[1].section(QChar(0x2026), 1))) << lines[1].toStdString();
        }

        // The tooltip names the entry whole, above what the model says of its material.
        const QPoint at = cell.center();
        QHelpEvent help(QEvent::ToolTip, at, view->viewport()->mapToGlobal(at));
        QApplication::sendEvent(view->viewport(), &help);
        EXPECT_TRUE(QToolTip::text().startsWith(name + QLatin1Char('\n'))) << QToolTip::text().toStdString();
        EXPECT_TRUE(QToolTip::text().contains(QStringLiteral("λ 2.00"))) << QToolTip::text().toStdString();
        QToolTip::hideText();
    }
}

// Bug: a failed import's banner stayed up after a later successful one. The rule: a success of
// the same kind of action (scene, environment, meshes, library) takes the banner down; another
// kind leaves it.
TEST(WindowBugs, ALaterSuccessOfTheSameKindTakesTheBannerDown) {
    test::TempDir dir;
    writeFile(dir / "no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    writeFile(dir / "tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    writeFile(dir / "bad_scene.json", "{ not a scene");
    writeFile(dir / "sky.exr", "this is not an image\n");
    const fs::path studio = test::asset("env/studio.exr");
    MIPGLOSS_REQUIRE_ASSET(studio);

    auto w = openWindow();
    ASSERT_TRUE(environmentSettled(*w));
    QWidget* shown = banner(*w);
    ASSERT_NE(shown, nullptr);
    ASSERT_TRUE(w->saveScene(qstr(dir / "good.mipgloss"))) << w->lastMessage().toStdString();
    ASSERT_TRUE(w->libraryDock()->exportLibrary(qstr(dir / "good.mglib")));
    EXPECT_FALSE(shown->isVisible());

    auto importAndWait = [&](const fs::path& mesh) {
        QSignalSpy finished(w.get(), &MainWindow::importFinished);
        w->importMeshes({qstr(mesh)});
        return waitUntil([&] { return !finished.isEmpty(); }, 60000);
    };

    // Meshes: a failure shows the banner, another kind's success leaves it, a mesh import takes it down.
    ASSERT_TRUE(importAndWait(dir / "no_faces.obj"));
    EXPECT_TRUE(shown->isVisible());
    ASSERT_TRUE(w->openScene(qstr(dir / "good.mipgloss")));
    EXPECT_TRUE(shown->isVisible()) << "a scene opened says nothing about the mesh that failed";
    ASSERT_TRUE(importAndWait(dir / "tetra.obj"));
    EXPECT_FALSE(w->lastMessageIsError()) << w->lastMessage().toStdString();
    EXPECT_FALSE(shown->isVisible()) << "the mesh import succeeded";

    // Scenes.
    EXPECT_FALSE(w->openScene(qstr(dir / "bad_scene.json")));
    EXPECT_TRUE(shown->isVisible());
    ASSERT_TRUE(w->openScene(qstr(dir / "good.mipgloss")));
    EXPECT_FALSE(shown->isVisible()) << "the scene opened";

    // Environments: the success is the environment loaded, not the request.
    const std::uint64_t failures = w->environments()->counters().failures;
    ASSERT_TRUE(w->openEnvironment(qstr(dir / "sky.exr")));
    ASSERT_TRUE(waitUntil([&] { return w->environments()->counters().failures > failures; }, kEnvironmentTimeoutMs));
    EXPECT_TRUE(shown->isVisible());
    ASSERT_TRUE(w->openEnvironment(qstr(studio)));
    ASSERT_TRUE(environmentLoaded(*w, studio));
    QCoreApplication::processEvents();
    EXPECT_FALSE(shown->isVisible()) << "the environment loaded";

    // Library imports.
    EXPECT_FALSE(w->libraryDock()->importLibrary(qstr(dir / "absent.mglib")));
    EXPECT_TRUE(shown->isVisible());
    EXPECT_TRUE(w->libraryDock()->importLibrary(qstr(dir / "good.mglib")));
    EXPECT_FALSE(shown->isVisible()) << "the library import succeeded";
}

// Bug: the status bar kept "Opening environment …" after the environment was loaded (and after
// it failed). It says "Loaded" once it is, and the error when it fails.
TEST(WindowBugs, StatusBarSaysWhenTheEnvironmentIsLoadedOrFailed) {
    test::TempDir dir;
    writeFile(dir / "sky.exr", "this is not an image\n");
    const fs::path studio = test::asset("env/studio.exr");
    MIPGLOSS_REQUIRE_ASSET(studio);
    auto w = openWindow();
    ASSERT_TRUE(environmentSettled(*w));

    ASSERT_TRUE(w->openEnvironment(qstr(studio)));
    EXPECT_TRUE(shownStatus(*w).startsWith(QStringLiteral("Opening environment studio.exr")))
        << shownStatus(*w).toStdString();
    ASSERT_TRUE(environmentLoaded(*w, studio));
    QCoreApplication::processEvents();
    EXPECT_FALSE(shownStatus(*w).contains(QStringLiteral("Opening"))) << shownStatus(*w).toStdString();
    EXPECT_TRUE(shownStatus(*w).contains(QStringLiteral("Loaded studio.exr"))) << shownStatus(*w).toStdString();

    const std::uint64_t failures = w->environments()->counters().failures;
    ASSERT_TRUE(w->openEnvironment(qstr(dir / "sky.exr")));
    EXPECT_TRUE(shownStatus(*w).startsWith(QStringLiteral("Opening environment sky.exr")));
    ASSERT_TRUE(waitUntil([&] { return w->environments()->counters().failures > failures; }, kEnvironmentTimeoutMs));
    ASSERT_TRUE(environmentSettled(*w));
    QCoreApplication::processEvents();
    EXPECT_FALSE(shownStatus(*w).contains(QStringLiteral("Opening"))) << shownStatus(*w).toStdString();
    EXPECT_TRUE(shownStatus(*w).contains(QStringLiteral("sky.exr"))) << "the error names the file";
}

// Bug: a long error ran into the environment status on the right. The message is cut short (…)
// to the room left beside it; the whole of it is in the banner and the tooltip.
TEST(WindowBugs, ALongErrorIsCutShortBesideTheEnvironmentStatus) {
    auto w = openWindow(QSize(1280, 800));
    ASSERT_TRUE(environmentSettled(*w));
    const QString path = QStringLiteral("/tmp/nowhere") + QStringLiteral("/a folder with a long name").repeated(12) +
                         QStringLiteral("/sky.exr");
    EXPECT_FALSE(w->openEnvironment(path));
    QCoreApplication::processEvents();
    const auto* envStatus = w->statusBar()->findChild<QLabel*>(QStringLiteral("envStatusLabel"));
    ASSERT_NE(envStatus, nullptr);
    const QString shown = shownStatus(*w);
    std::printf("shown: %s\n", shown.toStdString().c_str());
    EXPECT_TRUE(shown.contains(QChar(0x2026))) << "not cut short: " << shown.toStdString();
    EXPECT_LT(shown.size(), w->lastMessage().size());
    const auto* label = w->statusBar()->findChild<QLabel*>(QStringLiteral("statusMessage"));
    ASSERT_NE(label, nullptr) << "the status bar's message is its own label";
    EXPECT_LE(label->fontMetrics().horizontalAdvance(label->text()), label->contentsRect().width());
    EXPECT_LT(label->geometry().right(), envStatus->geometry().left()) << "the message overlaps the status";
    EXPECT_EQ(label->toolTip(), w->lastMessage());
    EXPECT_TRUE(banner(*w)->isVisible());
    w->grab().save(qstr(outputPath("window_bugs_long_error.png")));
}

// Bug: the environment status on the right of the status bar was clipped. At 1280 px it is shown
// whole, also with a long file name and a long message beside it; in a window narrower than the
// text it is cut short (…) with the whole text in its tooltip, inside the window.
TEST(WindowBugs, EnvironmentStatusIsShownWhole) {
    test::TempDir dir;
    const fs::path studio = test::asset("env/studio.exr");
    MIPGLOSS_REQUIRE_ASSET(studio);
    const fs::path longName =
        dir / "studio_softbox_key_light_with_a_rim_from_the_left_shot_by_a_photographer_who_names_files_4k.exr";
    fs::copy_file(studio, longName);
    auto w = openWindow(QSize(1280, 800));
    ASSERT_TRUE(environmentSettled(*w));
    ASSERT_TRUE(w->openEnvironment(qstr(longName)));
    ASSERT_TRUE(environmentLoaded(*w, longName));
    EXPECT_FALSE(w->openEnvironment(QStringLiteral("/tmp/nowhere/") + QStringLiteral("long ").repeated(80)));
    QCoreApplication::processEvents();
    auto* envStatus = w->statusBar()->findChild<QLabel*>(QStringLiteral("envStatusLabel"));
    ASSERT_NE(envStatus, nullptr);
    auto expectWhole = [&] {
        const QString whole = envStatus->toolTip().isEmpty() ? envStatus->text() : envStatus->toolTip();
        std::printf("envStatus '%s' (%d px of %d)\n", envStatus->text().toStdString().c_str(),
                    envStatus->fontMetrics().horizontalAdvance(envStatus->text()), envStatus->contentsRect().width());
        EXPECT_TRUE(whole.contains(QString::fromStdString(longName.stem().string())))
            << whole.toStdString();
        EXPECT_LE(envStatus->fontMetrics().horizontalAdvance(envStatus->text()), envStatus->contentsRect().width());
        EXPECT_GE(envStatus->contentsRect().height(), envStatus->fontMetrics().height());
        const QRect inWindow(envStatus->mapTo(w.get(), QPoint(0, 0)), envStatus->size());
        EXPECT_TRUE(w->rect().contains(inWindow)) << "the label runs past the window's edge";
    };
    ASSERT_EQ(w->width(), 1280);
    expectWhole();
    EXPECT_EQ(envStatus->text(), envStatus->toolTip().isEmpty() ? envStatus->text() : envStatus->toolTip())
        << "cut short at 1280 px";
    EXPECT_FALSE(envStatus->text().contains(QChar(0x2026)));
    // Narrower than the text: cut short, whole in the tooltip.
    w->resize(700, 800);
    QCoreApplication::processEvents();
    ASSERT_LT(w->width(), envStatus->sizeHint().width() + 100) << "the window cannot be made narrow enough here";
    expectWhole();
    EXPECT_TRUE(envStatus->text().contains(QChar(0x2026))) << envStatus->text().toStdString();
    w->grab().save(qstr(outputPath("window_bugs_env_status.png")));
}

// Bug: Ctrl+Z did nothing while a number field had the focus: the field's own text undo took the
// keys. In the panels' number fields the keys undo and redo the document (typing not yet entered
// is undone first, as text); the library's search field keeps its text undo.
TEST(WindowBugs, UndoKeysInANumberFieldUndoTheDocument) {
    auto w = openWindow();
    SceneDocument* doc = w->document();
    w->activateWindow();
    if (!QTest::qWaitForWindowActive(w.get())) GTEST_SKIP() << "the window cannot be activated here";
    doc->setSelected(1);
    auto* lambda = w->materialPanel()->findChild<QDoubleSpinBox*>(QStringLiteral("lambdaSpin"));
    ASSERT_NE(lambda, nullptr);
    const float before = doc->materialOf(1).lambda;
    typeInto(lambda, QStringLiteral("0.5"));
    ASSERT_FLOAT_EQ(doc->materialOf(1).lambda, 0.5f);
    ASSERT_EQ(QApplication::focusWidget(), lambda);

    QTest::keyClick(QApplication::focusWidget(), Qt::Key_Z, Qt::ControlModifier);
    EXPECT_FLOAT_EQ(doc->materialOf(1).lambda, before) << "Ctrl+Z in the λ field";
    EXPECT_DOUBLE_EQ(lambda->value(), static_cast<double>(before));
    QTest::keyClick(QApplication::focusWidget(), Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    EXPECT_FLOAT_EQ(doc->materialOf(1).lambda, 0.5f) << "Ctrl+Shift+Z in the λ field";

    // Typing not yet entered is undone as text first; the document is left alone.
    const int steps = doc->undoStack()->count();
    lambda->selectAll();
    QTest::keyClicks(lambda, QStringLiteral("1"));
    ASSERT_EQ(lambda->text(), QStringLiteral("1"));
    QTest::keyClick(QApplication::focusWidget(), Qt::Key_Z, Qt::ControlModifier);
    EXPECT_NE(lambda->text(), QStringLiteral("1"));
    EXPECT_FLOAT_EQ(doc->materialOf(1).lambda, 0.5f);
    EXPECT_EQ(doc->undoStack()->count(), steps);
    EXPECT_EQ(doc->undoStack()->index(), steps);

    // The environment panel's fields too.
    auto* exposure = w->findChild<QDoubleSpinBox*>(QStringLiteral("exposureSpin"));
    ASSERT_NE(exposure, nullptr);
    typeInto(exposure, QStringLiteral("1.5"));
    ASSERT_FLOAT_EQ(doc->scene().display.exposureEv, 1.5f);
    QTest::keyClick(QApplication::focusWidget(), Qt::Key_Z, Qt::ControlModifier);
    EXPECT_FLOAT_EQ(doc->scene().display.exposureEv, 0.0f) << "Ctrl+Z in the exposure field";

    // The library's search field keeps its own text undo.
    auto* search = w->findChild<QLineEdit*>(QStringLiteral("librarySearch"));
    ASSERT_NE(search, nullptr);
    const int index = doc->undoStack()->index();
    search->setFocus();
    QTest::keyClicks(search, QStringLiteral("gold"));
    QTest::keyClick(search, Qt::Key_Z, Qt::ControlModifier);
    EXPECT_NE(search->text(), QStringLiteral("gold"));
    EXPECT_EQ(doc->undoStack()->index(), index) << "the search field's Ctrl+Z undid the document";
}
