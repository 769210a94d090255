// Files handed to the window (mipgloss-gui's command line, a file manager's "Open with", drops), told
// apart by extension (main_window.cpp, classify): a scene is .mipgloss or, from older versions,
// .json; a .mglib library's materials are imported into the user's library; anything else is named
// in an error message. Under QStandardPaths test mode, so the user's own library is never touched.
#include "mipgloss/ui/autosave.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/recent_files.h"
#include "mipgloss/ui/scene_document.h"

#include <gtest/gtest.h>

#include <QDir>
#include <QStandardPaths>
#include <QTemporaryDir>

#include <filesystem>

using namespace mipgloss;
using namespace mipgloss::ui;

namespace {

void useTestFolders() {
    QStandardPaths::setTestModeEnabled(true);
    QDir(Autosave::folder()).removeRecursively();
    RecentFiles::clear();
}

// A scene whose first material is λ = `lambda`, saved to `path` by a window of its own.
void saveSceneWithLambda(const QString& path, float lambda) {
    MainWindow writer;
    Material m = writer.document()->materialOf(0);
    m.lambda = lambda;
    writer.document()->setMaterial(0, m);
    ASSERT_TRUE(writer.saveScene(path)) << writer.lastMessage().toStdString();
}

}  // namespace

TEST(OpenFiles, AMipglossFileOpensAsTheScene) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString path = dir.filePath(QStringLiteral("gold.mipgloss"));
    saveSceneWithLambda(path, 1.25f);

    MainWindow w;
    w.openFiles({path});
    EXPECT_EQ(w.sceneFile(), path) << w.lastMessage().toStdString();
    EXPECT_FALSE(w.lastMessageIsError()) << w.lastMessage().toStdString();
    EXPECT_FLOAT_EQ(w.document()->materialOf(0).lambda, 1.25f);
}

TEST(OpenFiles, AJsonSceneOfAnOlderVersionStillOpens) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString path = dir.filePath(QStringLiteral("old.json"));
    saveSceneWithLambda(path, 2.5f);

    MainWindow w;
    w.openFiles({path});
    EXPECT_EQ(w.sceneFile(), path) << w.lastMessage().toStdString();
    EXPECT_FLOAT_EQ(w.document()->materialOf(0).lambda, 2.5f);
}

TEST(OpenFiles, AnMglibFileIsImportedIntoTheLibraryAndLeavesTheSceneAlone) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString path = dir.filePath(QStringLiteral("shared.mglib"));
    {
        LibraryDocument source(nullptr);
        ASSERT_TRUE(source.open(std::filesystem::path(dir.filePath(QStringLiteral("source.mglib")).toStdString())));
        LibraryMaterial gold;
        gold.name = "Opened gold";
        gold.material.lambda = 2.0f;
        ASSERT_GE(source.add(gold), 0) << source.lastError().toStdString();
        ASSERT_TRUE(source.exportTo(std::filesystem::path(path.toStdString())));
    }

    MainWindow w;
    const int before = w.library()->count();
    w.openFiles({path});
    EXPECT_FALSE(w.lastMessageIsError()) << w.lastMessage().toStdString();
    ASSERT_EQ(w.library()->count(), before + 1);
    EXPECT_EQ(w.library()->entry(before).material.lambda, 2.0f);
    EXPECT_TRUE(w.sceneFile().isEmpty());  // a library is not a scene
}

TEST(OpenFiles, AnUnknownFileIsNamedInAnError) {
    useTestFolders();
    MainWindow w;
    w.openFiles({QStringLiteral("/nonexistent/notes.txt")});
    EXPECT_TRUE(w.lastMessageIsError());
    EXPECT_TRUE(w.lastMessage().contains(QStringLiteral("notes.txt"))) << w.lastMessage().toStdString();
}
