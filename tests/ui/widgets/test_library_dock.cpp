// The material library in the window: LibraryDocument (undoable edits written at once, a file it
// cannot read left alone), LibraryModel (QAbstractItemModelTester, names, tooltips, drags),
// material drags (material_mime.h), ThumbnailCache (drawn under the current environment, only
// for visible rows, never twice for the same parameters), LibraryDock (apply by double-click,
// add from the selected object, search) and drops on the viewport.
#include "gltf_writer.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/library_dock.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/library_model.h"
#include "mipgloss/ui/material_mime.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/thumbnail.h"
#include "mipgloss/ui/thumbnail_cache.h"
#include "mipgloss/ui/viewport.h"
#include "render_support.h"
#include "scene_test_support.h"
#include "test_support.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QAbstractItemModelTester>
#include <QAction>
#include <QDropEvent>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QMimeData>
#include <QSignalSpy>
#include <QSortFilterProxyModel>
#include <QTest>
#include <QUndoStack>
#include <QUrl>

#include <glm/matrix.hpp>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::smallEnvironment;
using mipgloss::test::sphereObject;
namespace fs = std::filesystem;

namespace {

LibraryMaterial entry(const std::string& name, float lambda, LookupMode mode = LookupMode::Reflect,
                      Rgb tint = Rgb(1.0f)) {
    LibraryMaterial e;
    e.name = name;
    e.material.lambda = lambda;
    e.material.mode = mode;
    e.material.tint = tint;
    return e;
}

// Gathers what QAbstractItemModelTester reports ("qt.modeltest" warnings) while alive, so a
// broken model fails the test rather than only printing.
class ModelTesterReports {
public:
    ModelTesterReports() {
        reports().clear();
        previous_ = qInstallMessageHandler(&ModelTesterReports::handle);
    }
    ~ModelTesterReports() { qInstallMessageHandler(previous_); }
    ModelTesterReports(const ModelTesterReports&) = delete;
    ModelTesterReports& operator=(const ModelTesterReports&) = delete;
    static QStringList& reports() {
        static QStringList r;
        return r;
    }

private:
    static void handle(QtMsgType type, const QMessageLogContext& context, const QString& text) {
        if (type != QtDebugMsg && context.category && QByteArray(context.category) == "qt.modeltest")
            reports() << text;
    }
    QtMessageHandler previous_ = nullptr;
};

// The model's names, row by row, against the document's.
void expectRowsMatch(const LibraryModel& model, const LibraryDocument& doc) {
    ASSERT_EQ(model.rowCount(), doc.count());
    for (int row = 0; row < doc.count(); ++row)
        EXPECT_EQ(model.data(model.index(row)).toString().toStdString(), doc.entry(row).name) << "row " << row;
}

// A drag over `widget` to `at` and a drop there, as Qt delivers them: enter, move, drop.
struct DropOutcome {
    bool entered = false, moved = false, dropped = false;
};
DropOutcome dragAndDrop(QWidget& widget, QPointF at, const QMimeData* mime) {
    DropOutcome out;
    QDragEnterEvent enter(at.toPoint(), Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(&widget, &enter);
    out.entered = enter.isAccepted();
    if (!out.entered) return out;
    QDragMoveEvent move(at.toPoint(), Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(&widget, &move);
    out.moved = move.isAccepted();
    QDropEvent drop(at, Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(&widget, &drop);
    out.dropped = drop.isAccepted();
    return out;
}

// Mean |difference| of two pictures' channels, in grey levels.
double meanDifference(const QImage& a, const QImage& b) {
    const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
    if (x.size() != y.size() || x.isNull()) return -1.0;
    double sum = 0.0;
    for (int j = 0; j < x.height(); ++j)
        for (int i = 0; i < x.width(); ++i) {
            const QRgb p = x.pixel(i, j), q = y.pixel(i, j);
            sum += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) + std::abs(qBlue(p) - qBlue(q));
        }
    return sum / (3.0 * x.width() * x.height());
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// LibraryDocument

TEST(LibraryDocument, EveryEditUndoesToTheLibraryBeforeItAndRedoesToTheOneAfter) {
    QUndoStack stack;
    LibraryDocument doc(&stack);
    doc.add(entry("Gold", 3.0f, LookupMode::Reflect, Rgb(1.0f, 0.8f, 0.3f)));
    doc.add(entry("Chalk", 7.0f, LookupMode::Normal));
    doc.add(entry("Chrome", 0.0f));
    Material brushed;
    brushed.lambda = 4.5f;
    const std::vector<std::pair<std::string, std::function<void()>>> edits = {
        {"add", [&] { doc.add(entry("Glass", 1.0f)); }},
        {"add a taken name", [&] { EXPECT_EQ(doc.entry(doc.add(entry("Gold", 2.0f))).name, "Gold 2"); }},
        {"remove", [&] { doc.remove(1); }},
        {"rename", [&] { EXPECT_TRUE(doc.rename(0, QStringLiteral("Old gold"))); }},
        {"duplicate", [&] { EXPECT_EQ(doc.duplicate(0), 1); }},
        {"parameters", [&] { EXPECT_TRUE(doc.setMaterial(2, brushed)); }},
        {"move down", [&] { doc.move(0, 2); }},
        {"move up", [&] { doc.move(2, 0); }},
    };
    for (const auto& [what, edit] : edits) {
        const MaterialLibrary before = doc.library();
        const int steps = stack.count();
        edit();
        const MaterialLibrary after = doc.library();
        EXPECT_NE(after, before) << what;
        EXPECT_EQ(stack.count(), steps + 1) << what << ": one undo step";
        stack.undo();
        EXPECT_EQ(doc.library(), before) << what << ": undo";
        stack.redo();
        EXPECT_EQ(doc.library(), after) << what << ": redo";
    }
    // Parameter edits of one entry merge: a slider dragged over it is one step.
    const int steps = stack.count();
    const MaterialLibrary before = doc.library();
    for (float lambda : {2.0f, 2.5f, 3.5f}) {
        Material m = doc.entry(0).material;
        m.lambda = lambda;
        doc.setMaterial(0, m);
    }
    EXPECT_EQ(stack.count(), steps + 1);
    stack.undo();
    EXPECT_EQ(doc.library(), before);
}

TEST(LibraryDocument, RefusesInvalidNamesAndParameters) {
    LibraryDocument doc(nullptr);
    EXPECT_EQ(doc.add(entry("   ", 1.0f)), -1);
    EXPECT_EQ(doc.add(entry("Tab\tname", 1.0f)), -1);
    EXPECT_EQ(doc.add(entry("Too blurry", 9.0f)), -1) << "λ above kMaxLambda";
    EXPECT_EQ(doc.add(entry("Negative", 1.0f, LookupMode::Reflect, Rgb(-1.0f, 0.0f, 0.0f))), -1);
    EXPECT_EQ(doc.count(), 0);
    ASSERT_EQ(doc.add(entry("  Gold ", 3.0f)), 0);
    EXPECT_EQ(doc.entry(0).name, "Gold") << "ends trimmed";
    ASSERT_EQ(doc.add(entry("Silver", 3.0f)), 1);
    EXPECT_FALSE(doc.rename(1, QStringLiteral("Gold"))) << "taken";
    EXPECT_FALSE(doc.rename(1, QStringLiteral("")));
    EXPECT_TRUE(doc.rename(1, QStringLiteral("Silver"))) << "its own name: nothing to do";
    EXPECT_EQ(doc.undoStack()->count(), 2) << "refusals and no-ops push nothing";
    Material bad;
    bad.lambda = std::nanf("");
    EXPECT_FALSE(doc.setMaterial(0, bad));
    EXPECT_EQ(doc.entry(0).material.lambda, 3.0f);
}

TEST(LibraryDocument, EveryEditIsOnDiskAtOnce) {
    test::TempDir dir;
    const fs::path file = dir / "lib" / "library.json";
    QUndoStack stack;
    LibraryDocument doc(&stack);
    EXPECT_TRUE(doc.open(file)) << "a missing file is an empty library";
    EXPECT_FALSE(doc.isDetached());
    EXPECT_FALSE(fs::exists(file)) << "created by the first edit, not by opening";
    QSignalSpy saved(&doc, &LibraryDocument::saved);
    const std::vector<std::pair<std::string, std::function<void()>>> edits = {
        {"add", [&] { doc.add(entry("Gold", 3.0f)); }},
        {"add", [&] { doc.add(entry("Chalk", 7.0f, LookupMode::Normal)); }},
        {"rename", [&] { doc.rename(0, QStringLiteral("Brass")); }},
        {"duplicate", [&] { doc.duplicate(1); }},
        {"parameters", [&] { doc.setMaterial(0, entry("", 5.0f).material); }},
        {"move", [&] { doc.move(0, 2); }},
        {"remove", [&] { doc.remove(1); }},
        {"undo", [&] { stack.undo(); }},
        {"undo", [&] { stack.undo(); }},
        {"redo", [&] { stack.redo(); }},
    };
    for (const auto& [what, edit] : edits) {
        const int savesBefore = static_cast<int>(saved.count());
        edit();
        ASSERT_TRUE(fs::exists(file)) << what;
        EXPECT_EQ(loadLibrary(file), doc.library()) << what;
        EXPECT_EQ(saved.count(), savesBefore + 1) << what;
    }
    // Opened again, the file is the library.
    LibraryDocument again(nullptr);
    EXPECT_TRUE(again.open(file));
    EXPECT_EQ(again.library(), doc.library());
}

// A new user's library (no file yet) opens as the starter materials, in memory; the first edit
// writes them with it. A file that exists, even empty, is the user's and is never replaced.
TEST(LibraryDocument, AMissingFileStartsFromTheStarterLibraryWrittenByTheFirstEdit) {
    test::TempDir dir;
    const fs::path file = dir / "library.json";
    QUndoStack stack;
    LibraryDocument doc(&stack);
    ASSERT_TRUE(doc.open(file, starterLibrary()));
    EXPECT_EQ(doc.library(), starterLibrary());
    EXPECT_FALSE(fs::exists(file));
    doc.add(entry("Mine", 2.0f));
    ASSERT_TRUE(fs::exists(file));
    MaterialLibrary expected = starterLibrary();
    expected.entries.push_back(entry("Mine", 2.0f));
    EXPECT_EQ(loadLibrary(file), expected);

    const fs::path empty = dir / "empty.json";
    saveLibrary(MaterialLibrary{}, empty);
    ASSERT_TRUE(doc.open(empty, starterLibrary()));
    EXPECT_EQ(doc.count(), 0) << "the user's own empty library stays empty";
}

TEST(LibraryDocument, AnUnreadableFileIsRefusedAndItsBytesNeverChange) {
    test::TempDir dir;
    const fs::path file = dir / "library.json";
    const std::string corrupt = "{\"format\": \"mipgloss-library\", \"version\": 1, \"materials\": [{\"name\": \"Go";
    test::writeBytes(file, corrupt);
    QUndoStack stack;
    LibraryDocument doc(&stack);
    QSignalSpy failures(&doc, &LibraryDocument::saveFailed);
    EXPECT_FALSE(doc.open(file));
    EXPECT_TRUE(doc.isDetached());
    EXPECT_EQ(doc.count(), 0) << "an empty library in memory";
    EXPECT_TRUE(doc.lastError().contains(QStringLiteral("library.json"))) << doc.lastError().toStdString();

    // Edits, undo and redo work in memory and never touch the file.
    doc.add(entry("Gold", 3.0f));
    doc.add(entry("Chalk", 7.0f));
    doc.rename(0, QStringLiteral("Brass"));
    doc.duplicate(1);
    doc.remove(0);
    stack.undo();
    stack.redo();
    EXPECT_EQ(doc.count(), 2);
    EXPECT_EQ(test::readText(file), corrupt);
    EXPECT_EQ(failures.count(), 0) << "not writing is not a failure";

    // The user's choice: keep the library in another file; the unreadable one still untouched.
    const fs::path other = dir / "kept.json";
    ASSERT_TRUE(doc.saveAs(other));
    EXPECT_FALSE(doc.isDetached());
    EXPECT_EQ(doc.file(), other);
    EXPECT_EQ(loadLibrary(other), doc.library());
    doc.add(entry("Glass", 1.0f));
    EXPECT_EQ(loadLibrary(other), doc.library()) << "attached to the new file";
    EXPECT_EQ(test::readText(file), corrupt);

    // Or, explicitly, replace the unreadable file.
    LibraryDocument second(nullptr);
    EXPECT_FALSE(second.open(file));
    second.add(entry("Chrome", 0.0f));
    EXPECT_EQ(test::readText(file), corrupt);
    ASSERT_TRUE(second.replaceUnreadableFile());
    EXPECT_FALSE(second.isDetached());
    EXPECT_EQ(loadLibrary(file), second.library());
}

TEST(LibraryDocument, AFailedSaveIsReportedAndTheLibraryKept) {
    test::TempDir dir;
    const fs::path file = dir / "folder" / "library.json";
    LibraryDocument doc(nullptr);
    ASSERT_TRUE(doc.open(file));
    // The library's folder becomes a plain file: no write can succeed.
    test::writeBytes(dir / "folder", "not a folder");
    QSignalSpy failures(&doc, &LibraryDocument::saveFailed);
    ASSERT_EQ(doc.add(entry("Gold", 3.0f)), 0);
    ASSERT_EQ(failures.count(), 1);
    EXPECT_TRUE(failures.at(0).at(0).toString().contains(QStringLiteral("library.json")))
        << failures.at(0).at(0).toString().toStdString();
    EXPECT_EQ(doc.count(), 1) << "the edit is kept in memory";
    EXPECT_EQ(doc.entry(0).name, "Gold");
}

TEST(LibraryDocument, ImportMergesWithFreeNamesAsOneUndoStepAndExportWritesTheLibrary) {
    test::TempDir dir;
    MaterialLibrary shared;
    shared.entries = {entry("Gold", 3.0f), entry("Chalk", 7.0f, LookupMode::Normal), entry("Glass", 1.0f)};
    saveLibrary(shared, dir / "shared.json");

    QUndoStack stack;
    LibraryDocument doc(&stack);
    doc.add(entry("Gold", 2.0f));   // same name, other parameters: imported as "Gold 2"
    doc.add(entry("Glass", 1.0f));  // the same entry: skipped
    const MaterialLibrary before = doc.library();
    EXPECT_EQ(doc.importFrom(dir / "shared.json"), 2);
    ASSERT_EQ(doc.count(), 4);
    EXPECT_EQ(doc.entry(2).name, "Gold 2");
    EXPECT_EQ(doc.entry(2).material.lambda, 3.0f);
    EXPECT_EQ(doc.entry(3).name, "Chalk");
    EXPECT_EQ(doc.importFrom(dir / "shared.json"), 1) << "Gold 2 is not Gold: once more";
    stack.undo();
    stack.undo();
    EXPECT_EQ(doc.library(), before) << "each import is one step";

    test::writeBytes(dir / "broken.json", "[1, 2");
    EXPECT_EQ(doc.importFrom(dir / "broken.json"), -1);
    EXPECT_TRUE(doc.lastError().contains(QStringLiteral("broken.json")));
    EXPECT_EQ(doc.library(), before);

    ASSERT_TRUE(doc.exportTo(dir / "out" / "export.json"));
    EXPECT_EQ(loadLibrary(dir / "out" / "export.json"), doc.library());
    EXPECT_TRUE(doc.file().empty()) << "exporting does not change the document's file";
}

TEST(LibraryDocument, OpeningAnotherLibraryRetiresTheOldOnesCommands) {
    test::TempDir dir;
    MaterialLibrary other;
    other.entries = {entry("A", 1.0f), entry("B", 2.0f)};
    saveLibrary(other, dir / "other.json");
    const std::string bytes = test::readText(dir / "other.json");
    QUndoStack stack;
    LibraryDocument doc(&stack);
    doc.add(entry("Gold", 3.0f));
    doc.add(entry("Chalk", 7.0f));
    ASSERT_TRUE(doc.open(dir / "other.json"));
    stack.undo();  // the "add Chalk" of the old library: must not remove a row of this one
    EXPECT_EQ(doc.library(), other);
    EXPECT_EQ(test::readText(dir / "other.json"), bytes);
}

// ---------------------------------------------------------------------------------------------
// LibraryModel and drags

TEST(LibraryModel, PassesTheModelTesterThroughEditsAndUndo) {
    ModelTesterReports reports;
    test::TempDir dir;
    QUndoStack stack;
    LibraryDocument doc(&stack);
    LibraryModel model(&doc);
    QAbstractItemModelTester tester(&model, QAbstractItemModelTester::FailureReportingMode::Warning);
    QSignalSpy resets(&model, &QAbstractItemModel::modelReset);
    QSignalSpy inserted(&model, &QAbstractItemModel::rowsInserted);
    QSignalSpy moved(&model, &QAbstractItemModel::rowsMoved);

    doc.add(entry("Gold", 3.0f));
    doc.add(entry("Chalk", 7.0f));
    doc.add(entry("Chrome", 0.0f));
    expectRowsMatch(model, doc);
    EXPECT_TRUE(model.setData(model.index(1), QStringLiteral("Plaster")));
    EXPECT_FALSE(model.setData(model.index(1), QStringLiteral("Gold"))) << "taken";
    EXPECT_FALSE(model.setData(model.index(1), QStringLiteral(" ")));
    doc.duplicate(0);
    doc.move(0, 3);
    doc.move(3, 1);
    doc.remove(2);
    expectRowsMatch(model, doc);
    while (stack.canUndo()) stack.undo();
    expectRowsMatch(model, doc);
    EXPECT_EQ(model.rowCount(), 0);
    while (stack.canRedo()) stack.redo();
    expectRowsMatch(model, doc);
    EXPECT_EQ(resets.count(), 0) << "edits update rows; only open() resets";
    EXPECT_GT(inserted.count(), 0);
    EXPECT_GT(moved.count(), 0);
    saveLibrary(MaterialLibrary{{entry("X", 1.0f)}}, dir / "x.json");
    doc.open(dir / "x.json");
    EXPECT_EQ(resets.count(), 1);
    expectRowsMatch(model, doc);
    EXPECT_TRUE(ModelTesterReports::reports().isEmpty()) << ModelTesterReports::reports().join('\n').toStdString();
}

TEST(LibraryModel, TooltipNamesLambdaExponentModeAndTint) {
    LibraryDocument doc(nullptr);
    doc.add(entry("Gold", 3.0f, LookupMode::Reflect, Rgb(1.0f, 0.8f, 0.3f)));
    LibraryMaterial chalk = entry("Chalk", 7.0f, LookupMode::Normal);
    chalk.material.useIrradiance = true;
    doc.add(chalk);
    doc.add(entry("Chrome", 0.0f));
    LibraryModel model(&doc);
    // n(3) = 3·128²·4⁻³ − 1 = 767 (phong.h).
    EXPECT_EQ(model.data(model.index(0), Qt::ToolTipRole).toString(),
              QStringLiteral("λ 3.00 · n 767 · reflect · tint 1.000, 0.800, 0.300"));
    EXPECT_EQ(model.data(model.index(1), Qt::ToolTipRole).toString(),
              QStringLiteral("λ 7.00 · n 2.00 · normal (irradiance) · tint 1.000, 1.000, 1.000"));
    EXPECT_EQ(model.data(model.index(2), Qt::ToolTipRole).toString(),
              QStringLiteral("λ 0.00 · n ∞ · reflect · tint 1.000, 1.000, 1.000"));
    EXPECT_FALSE(model.data(model.index(0), Qt::DecorationRole).value<QPixmap>().isNull()) << "a placeholder";
}

TEST(MaterialMime, AnEntryRoundTripsAndAnythingElseIsNothing) {
    LibraryMaterial gold = entry("Gold “24k”", 3.25f, LookupMode::Normal, Rgb(1.0f, 0.8f, 0.3f));
    gold.material.useIrradiance = true;
    gold.material.sharperAtGrazing = true;
    std::unique_ptr<QMimeData> mime(materialMimeData(gold));
    ASSERT_TRUE(mime->hasFormat(QString::fromLatin1(kMaterialMimeType)));
    const std::optional<LibraryMaterial> back = materialFromMimeData(mime.get());
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, gold);

    QMimeData garbage;
    garbage.setData(QString::fromLatin1(kMaterialMimeType), "{\"format\": \"mipgloss-library\"");
    EXPECT_FALSE(materialFromMimeData(&garbage).has_value());
    QMimeData text;
    text.setText(QStringLiteral("Gold"));
    EXPECT_FALSE(materialFromMimeData(&text).has_value());
    EXPECT_FALSE(materialFromMimeData(nullptr).has_value());

    // Through the model, as a drag starts.
    LibraryDocument doc(nullptr);
    doc.add(gold);
    LibraryModel model(&doc);
    EXPECT_TRUE(model.flags(model.index(0)) & Qt::ItemIsDragEnabled);
    std::unique_ptr<QMimeData> dragged(model.mimeData({model.index(0)}));
    ASSERT_TRUE(dragged);
    EXPECT_EQ(materialFromMimeData(dragged.get()), gold);
}

// ---------------------------------------------------------------------------------------------
// Thumbnails

TEST(ThumbnailCache, DrawsUnderTheCurrentEnvironmentAndNeverTwiceForTheSameParameters) {
    LibraryDocument doc(nullptr);
    doc.add(entry("Chrome", 0.0f));
    doc.add(entry("Gold", 3.0f, LookupMode::Reflect, Rgb(1.0f, 0.8f, 0.3f)));
    doc.add(entry("Chalk", 7.0f, LookupMode::Normal));
    EnvironmentManager environments;
    ThumbnailCache cache(&doc, &environments);
    EXPECT_EQ(cache.counters().renders, 0u) << "nothing without an environment";
    environments.request(smallEnvironment(), ChainNeeds{});  // only level 0 filtered for the scene
    ASSERT_TRUE(environments.waitUntilIdle());
    ASSERT_TRUE(test::waitUntil([&] { return !cache.busy(); }, 60000));
    ASSERT_TRUE(cache.error().isEmpty()) << cache.error().toStdString();
    EXPECT_EQ(cache.counters().environmentBuilds, 1u);
    EXPECT_EQ(cache.counters().renders, 3u);
    ASSERT_TRUE(cache.environment());
    EXPECT_EQ(cache.environment()->lastFilteredLevel, thumbnailNeeds(32).lastFilteredLevel)
        << "its own chain reaches every λ, whatever the scene's needs";
    EXPECT_TRUE(cache.environment()->irradiance);
    const QImage chromeBefore = cache.thumbnail(doc.entry(0).material).toImage();
    chromeBefore.save(QString::fromStdString((test::outputDir() / "thumbnail_courtyard.png").string()));

    // The scene's chain growing deeper builds nothing for the thumbnails and redraws nothing.
    environments.request(smallEnvironment(), ChainNeeds{4, true});
    ASSERT_TRUE(environments.waitUntilIdle());
    QTest::qWait(50);
    EXPECT_EQ(cache.counters().environmentBuilds, 1u);
    EXPECT_EQ(cache.counters().renders, 3u);

    // A rename or a duplicate keeps the parameters: no new drawing.
    doc.rename(0, QStringLiteral("Mirror"));
    doc.duplicate(1);
    QTest::qWait(50);
    EXPECT_EQ(cache.counters().renders, 3u);
    EXPECT_TRUE(cache.isCurrent(doc.entry(2).material));
    // New parameters: exactly one.
    Material brass = doc.entry(1).material;
    brass.lambda = 4.0f;
    doc.setMaterial(1, brass);
    ASSERT_TRUE(test::waitUntil([&] { return !cache.busy(); }, 60000));
    EXPECT_EQ(cache.counters().renders, 4u);

    // Another environment: every entry drawn again (all are visible here), and the pictures change.
    const fs::path sunset = test::asset("env/sunset.exr");
    MIPGLOSS_REQUIRE_ASSET(sunset);
    environments.request(smallEnvironment(sunset.string()), ChainNeeds{});
    ASSERT_TRUE(environments.waitUntilIdle());
    ASSERT_TRUE(test::waitUntil([&] { return cache.counters().environmentBuilds == 2 && !cache.busy(); }, 60000));
    EXPECT_EQ(cache.counters().renders, 8u) << "4 entries, 4 distinct parameter sets";
    const QImage chromeAfter = cache.thumbnail(doc.entry(0).material).toImage();
    chromeAfter.save(QString::fromStdString((test::outputDir() / "thumbnail_sunset.png").string()));
    const double difference = meanDifference(chromeBefore, chromeAfter);
    std::printf("chrome thumbnail, courtyard vs sunset: mean |difference| %.1f grey levels\n", difference);
    // A mirror shows the environment itself: a courtyard by day and a sunset differ everywhere;
    // 10 grey levels is far above anything but another picture.
    EXPECT_GT(difference, 10.0);
}

TEST(LibraryDock, DrawsThumbnailsOnlyForTheRowsInView) {
    LibraryDocument doc(nullptr);
    for (int i = 0; i < 120; ++i) doc.add(entry("Material " + std::to_string(i), 0.05f * static_cast<float>(i)));
    SceneDocument scene;
    EnvironmentManager environments;
    environments.request(smallEnvironment(), ChainNeeds{});
    ASSERT_TRUE(environments.waitUntilIdle());
    LibraryDock dock(&doc, &scene, &environments);
    dock.resize(300, 360);
    dock.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&dock));
    ThumbnailCache& cache = *dock.thumbnails();
    ASSERT_TRUE(test::waitUntil([&] { return cache.environment() && !cache.busy(); }, 60000));
    const std::uint64_t first = cache.counters().renders;
    dock.grab().save(QString::fromStdString((test::outputDir() / "library_dock.png").string()));
    // Rows whose cells meet the view's viewport, counted here independently of the dock.
    auto rowsInView = [&] {
        int n = 0;
        const QRect area = dock.view()->viewport()->rect();
        for (int r = 0; r < dock.filterModel()->rowCount(); ++r)
            if (dock.view()->visualRect(dock.filterModel()->index(r, 0)).intersects(area)) ++n;
        return n;
    };
    const int inView = rowsInView();
    std::printf("rows in view %d of %d; thumbnails drawn %llu\n", inView, doc.count(),
                static_cast<unsigned long long>(first));
    EXPECT_GT(first, 0u);
    EXPECT_EQ(first, static_cast<std::uint64_t>(inView));
    EXPECT_LT(first, 120u);
    EXPECT_TRUE(cache.isCurrent(doc.entry(0).material));
    EXPECT_FALSE(cache.isCurrent(doc.entry(119).material));

    // Scrolling to the end draws the rows that come into view, and no others.
    dock.view()->scrollToBottom();
    ASSERT_TRUE(test::waitUntil([&] { return !cache.busy(); }, 60000));
    EXPECT_TRUE(cache.isCurrent(doc.entry(119).material));
    EXPECT_LE(cache.counters().renders, first + static_cast<std::uint64_t>(rowsInView()));
    EXPECT_LT(cache.counters().renders, 120u);
}

// ---------------------------------------------------------------------------------------------
// The dock's actions

TEST(LibraryDock, DoubleClickAppliesToTheSelectedObjectAndAddUsesItsMaterialName) {
    SceneDocument scene;
    Material plain;
    plain.lambda = 2.0f;
    scene.addObject(sphereObject("ball", 0.0f), plain);  // selected; its material is named "ball"
    LibraryDocument doc(nullptr);
    doc.add(entry("Chrome", 0.0f));
    doc.add(entry("Gold", 3.0f, LookupMode::Reflect, Rgb(1.0f, 0.8f, 0.3f)));
    EnvironmentManager environments;
    LibraryDock dock(&doc, &scene, &environments);
    dock.resize(320, 400);
    dock.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&dock));
    QListView* list = dock.findChild<QListView*>(QStringLiteral("libraryList"));
    ASSERT_TRUE(list);

    const QModelIndex gold = dock.filterModel()->index(1, 0);
    const QPoint centre = list->visualRect(gold).center();
    // A real double-click: press, release, double-click, release (QTest's mouseDClick alone sends
    // only the third, which an item view takes for a press when no press came before it).
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, centre);
    QTest::mouseDClick(list->viewport(), Qt::LeftButton, {}, centre);
    QTest::mouseRelease(list->viewport(), Qt::LeftButton, {}, centre);
    EXPECT_EQ(scene.materialOf(0), doc.entry(1).material);
    ASSERT_TRUE(scene.namedMaterialOf(0));
    EXPECT_EQ(scene.namedMaterialOf(0)->libraryEntry, "Gold");

    // Add from the selected object: its material, under its material's name.
    QAction* add = dock.findChild<QAction*>(QStringLiteral("libraryAddAction"));
    ASSERT_TRUE(add);
    ASSERT_TRUE(add->isEnabled());
    add->trigger();
    ASSERT_EQ(doc.count(), 3);
    EXPECT_EQ(doc.entry(2).name, "Gold 2") << "the object's material is named Gold now: made unique";
    EXPECT_EQ(doc.entry(2).material, scene.materialOf(0));
    EXPECT_EQ(dock.currentRow(), 2) << "the new entry is selected";

    // Nothing selected: Apply and Add are off.
    scene.setSelected(-1);
    EXPECT_FALSE(add->isEnabled());
    EXPECT_FALSE(dock.findChild<QAction*>(QStringLiteral("libraryApplyAction"))->isEnabled());
    EXPECT_FALSE(dock.applyRow(0));
}

TEST(LibraryDock, SearchFiltersByNameIgnoringCaseAndActionsWorkOnTheShownEntry) {
    SceneDocument scene;
    LibraryDocument doc(nullptr);
    doc.add(entry("Gold", 3.0f));
    doc.add(entry("Chalk", 7.0f));
    doc.add(entry("Rose gold", 2.0f));
    EnvironmentManager environments;
    LibraryDock dock(&doc, &scene, &environments);
    QLineEdit* search = dock.findChild<QLineEdit*>(QStringLiteral("librarySearch"));
    ASSERT_TRUE(search);
    QTest::keyClicks(search, QStringLiteral("GOLD"));
    ASSERT_EQ(dock.filterModel()->rowCount(), 2);
    EXPECT_EQ(dock.filterModel()->index(1, 0).data().toString(), QStringLiteral("Rose gold"));
    dock.view()->setCurrentIndex(dock.filterModel()->index(1, 0));
    EXPECT_EQ(dock.currentRow(), 2) << "the library row behind the filtered one";
    dock.findChild<QAction*>(QStringLiteral("libraryDuplicateAction"))->trigger();
    ASSERT_EQ(doc.count(), 4);
    EXPECT_EQ(doc.entry(3).name, "Rose gold 2");
    EXPECT_EQ(dock.currentRow(), 3);
    dock.findChild<QAction*>(QStringLiteral("libraryDeleteAction"))->trigger();
    EXPECT_EQ(doc.count(), 3);
    EXPECT_FALSE(doc.library().contains("Rose gold 2"));
}

TEST(LibraryDock, AnUnreadableLibraryShowsItsProblemNamingTheFile) {
    test::TempDir dir;
    test::writeBytes(dir / "library.json", "not json");
    SceneDocument scene;
    LibraryDocument doc(nullptr);
    EnvironmentManager environments;
    LibraryDock dock(&doc, &scene, &environments);
    dock.show();
    QWidget* problem = dock.findChild<QWidget*>(QStringLiteral("libraryProblem"));
    QLabel* text = dock.findChild<QLabel*>(QStringLiteral("libraryProblemText"));
    ASSERT_TRUE(problem && text);
    EXPECT_FALSE(problem->isVisible());
    doc.open(dir / "library.json");
    EXPECT_TRUE(problem->isVisible());
    EXPECT_TRUE(text->text().contains(QStringLiteral("library.json"))) << text->text().toStdString();
    ASSERT_TRUE(doc.saveAs(dir / "elsewhere.json"));
    EXPECT_FALSE(problem->isVisible());
    EXPECT_EQ(test::readText(dir / "library.json"), "not json");
}

// ---------------------------------------------------------------------------------------------
// Dropping on the viewport

TEST(Viewport, DroppedMaterialGoesToTheObjectUnderTheCursor) {
    SceneDocument scene;
    scene.addObject(sphereObject("left", -2.0f), Material{});
    scene.addObject(sphereObject("right", 2.0f), Material{});
    EnvironmentManager environments;
    Viewport viewport(&scene, &environments);
    viewport.resize(480, 320);
    viewport.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&viewport));
    viewport.frameAll();
    const Material leftBefore = scene.materialOf(0);

    // Where the right sphere's centre is on screen, through the viewport's own camera.
    const float aspect = static_cast<float>(viewport.width()) / static_cast<float>(viewport.height());
    const glm::vec4 clip = viewport.camera().projection(aspect, sceneBounds(scene.scene())) *
                           viewport.camera().view() * glm::vec4(2.0f, 0.0f, 0.0f, 1.0f);
    const QPointF onRight((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(viewport.width()),
                          (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(viewport.height()));
    const LibraryMaterial gold = entry("Gold", 3.0f, LookupMode::Reflect, Rgb(1.0f, 0.8f, 0.3f));
    std::unique_ptr<QMimeData> mime(materialMimeData(gold));

    const DropOutcome missed = dragAndDrop(viewport, QPointF(4.0, 4.0), mime.get());
    EXPECT_TRUE(missed.entered) << "a material is welcome anywhere in the view";
    EXPECT_FALSE(missed.moved) << "but over empty space the cursor says no";
    EXPECT_FALSE(missed.dropped);
    EXPECT_EQ(scene.materialOf(1), Material{});

    const DropOutcome hit = dragAndDrop(viewport, onRight, mime.get());
    EXPECT_TRUE(hit.moved);
    EXPECT_TRUE(hit.dropped);
    EXPECT_EQ(scene.materialOf(1), gold.material);
    EXPECT_EQ(scene.namedMaterialOf(1)->libraryEntry, "Gold");
    EXPECT_EQ(scene.materialOf(0), leftBefore) << "the other object keeps its material";
    EXPECT_EQ(scene.selected(), 1);

    // Files are not the viewport's: it lets them pass to the window, which opens them.
    QMimeData files;
    files.setUrls({QUrl::fromLocalFile(QStringLiteral("/tmp/scene.json"))});
    EXPECT_FALSE(dragAndDrop(viewport, onRight, &files).entered);
}

// "Import Library…" takes an asset too: its materials, named as in the file, textured, one undo
// step; the same asset again adds nothing (equal entries are skipped).
TEST(LibraryDocument, ImportingAGltfAddsItsNamedTexturedMaterialsAsOneStep) {
    test::TempDir dir;
    test::GltfWriter w;
    const test::TestImage grey = test::makeImage(4, 4, 3, [](int, int) { return std::vector<std::uint8_t>{90, 90, 90}; });
    const int base = w.addTexture(w.addImage(test::encodePng(grey)));
    const int a = w.addMaterial(test::pbrMaterial("Painted steel", {1, 1, 1, 1}, 1.0, 0.4, base));
    const int b = w.addMaterial(test::pbrMaterial("Rubber", {0.05f, 0.05f, 0.05f, 1}, 0.0, 0.8));
    w.addToScene(w.addNode(w.addMesh(test::texturedQuad(), a)));
    w.addToScene(w.addNode(w.addMesh(test::texturedQuad(), b), {3.0, 0.0, 0.0}));
    w.writeGlb(dir / "tool.glb");

    QUndoStack stack;
    LibraryDocument doc(&stack);
    EXPECT_EQ(doc.importFrom(dir / "tool.glb"), 2) << doc.lastError().toStdString();
    ASSERT_EQ(doc.count(), 2);
    EXPECT_EQ(doc.entry(0).name, "Painted steel");
    EXPECT_EQ(doc.entry(0).material.layers.maps.baseColor.image, 0);
    EXPECT_EQ(doc.entry(0).material.layers.maps.baseColor.file, (dir / "tool.glb").string());
    EXPECT_EQ(doc.entry(1).name, "Rubber");
    EXPECT_EQ(doc.importFrom(dir / "tool.glb"), 0);
    stack.undo();
    EXPECT_EQ(doc.count(), 0);
    test::writeBytes(dir / "broken.glb", "glTF");
    EXPECT_EQ(doc.importFrom(dir / "broken.glb"), -1);
    EXPECT_TRUE(doc.lastError().contains(QStringLiteral("broken.glb"))) << doc.lastError().toStdString();
}
