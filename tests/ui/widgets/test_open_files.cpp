// Files handed to the window (mipgloss-gui's command line, a file manager's "Open with", drops), told
// apart by extension (file_kinds.h, fileKindOf): a scene is .mipgloss or, from older versions,
// .json; a .mglib library's materials are imported into the user's library; anything else is named
// in an error message. Under QStandardPaths test mode, so the user's own library is never touched.
#include "gltf_writer.h"
#include "mipgloss/ui/autosave.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/recent_files.h"
#include "mipgloss/ui/scene_document.h"

#include "session_test_support.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QLabel>
#include <QMimeData>
#include <QSignalSpy>
#include <QUndoStack>
#include <QUrl>
#include <QStandardPaths>
#include <QTemporaryDir>

#include <filesystem>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::useTestFolders;

namespace {

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

// A glTF dropped on the window (a file manager's drag): its parts come in as one import with
// their materials named as in the file and shared, the material panel says which parameters a
// texture map sets, and a missing image is a warning, not an error; undo takes it all back.
TEST(OpenFiles, ADroppedGltfBringsItsPartsAndNamedTexturedMaterials) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const std::filesystem::path folder = dir.path().toStdString();
    test::GltfWriter writer;
    const test::TestImage grey = test::makeImage(8, 8, 3, [](int, int) { return std::vector<std::uint8_t>{90, 90, 90}; });
    const int base = writer.addTexture(writer.addImage(test::encodePng(grey)));
    const int missing = writer.addTexture(writer.addImage({}, "gone.png"));
    const int textured = writer.addMaterial(test::pbrMaterial("Painted steel", {1, 1, 1, 1}, 1.0, 0.4, base, base));
    const int bumpy = writer.addMaterial(test::pbrMaterial("Bumpy", {1, 1, 1, 1}, 0.0, 0.5, -1, -1, missing));
    const int sphere = writer.addMesh(test::texturedSphere(8, 16), textured);
    writer.addToScene(writer.addNode(sphere));
    writer.addToScene(writer.addNode(sphere, {3.0, 0.0, 0.0}));  // the same material, shared
    writer.addToScene(writer.addNode(writer.addMesh(test::texturedQuad(), bumpy), {0.0, 3.0, 0.0}));
    writer.writeGlb(folder / "thing.glb");

    MainWindow w;
    SceneDocument* doc = w.document();
    const int before = doc->objectCount();
    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(QString::fromStdString((folder / "thing.glb").string()))});
    QSignalSpy finished(&w, &MainWindow::importFinished);
    QDragEnterEvent enter(QPoint(10, 10), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(&w, &enter);
    ASSERT_TRUE(enter.isAccepted());
    QDropEvent drop(QPointF(10, 10), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(&w, &drop);
    ASSERT_TRUE(test::waitUntil([&] { return !finished.isEmpty(); }, 60000));
    ASSERT_EQ(doc->objectCount(), before + 3) << w.lastMessage().toStdString();
    EXPECT_FALSE(w.lastMessageIsError()) << w.lastMessage().toStdString();
    EXPECT_TRUE(w.lastMessage().contains(QStringLiteral("gone.png"))) << w.lastMessage().toStdString();
    EXPECT_EQ(doc->namedMaterialOf(before)->name, "Painted steel");
    EXPECT_EQ(doc->object(before).material, doc->object(before + 1).material);
    EXPECT_EQ(doc->namedMaterialOf(before + 2)->name, "Bumpy");
    EXPECT_EQ(doc->object(before + 2).meshPart, 2);

    doc->setSelected(before);
    auto* label = w.findChild<QLabel*>(QStringLiteral("textureMapsLabel"));
    ASSERT_NE(label, nullptr);
    EXPECT_TRUE(label->text().contains(QStringLiteral("base colour"))) << label->text().toStdString();
    EXPECT_TRUE(label->text().contains(QStringLiteral("roughness"))) << label->text().toStdString();
    doc->setSelected(before + 2);
    EXPECT_TRUE(label->text().contains(QStringLiteral("normal (missing)"))) << label->text().toStdString();

    doc->undoStack()->undo();
    EXPECT_EQ(doc->objectCount(), before);
}
