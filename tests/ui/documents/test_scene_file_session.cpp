// The scene-file session without a window (scene_file_session.h): save then reopen, the modified
// flag and its signal, the title, recent files (order, limit, files gone), autosave (what it writes,
// when it is removed) and restoring a leftover, all with real files in temporary folders, under
// QStandardPaths test mode (tests/ui/main.cpp), so the user's own folders are never touched.
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/assets/mesh_files.h"
#include "mipgloss/ui/recent_files.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_file.h"
#include "mipgloss/ui/scene_file_session.h"

#include "session_test_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include <memory>
#include <optional>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::asFile;
using mipgloss::test::readAll;
using mipgloss::test::useTestFolders;
using mipgloss::test::writeTriangle;

namespace {

// A document holding Figure 1 and its session, as a window makes them.
struct Session {
    std::unique_ptr<SceneDocument> document = std::make_unique<SceneDocument>();
    std::unique_ptr<SceneFileSession> session;

    Session() {
        document->resetScene(makeFigure1Scene());
        session = std::make_unique<SceneFileSession>(document.get());
    }
    ~Session() { session.reset(); }  // before the document it watches
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    void editLambda(float lambda) {
        Material m = document->materialOf(0);
        m.lambda = lambda;
        document->setMaterial(0, m);
    }
};

}  // namespace

TEST(SceneFileSession, ANewSessionIsUntitledAndUnmodified) {
    useTestFolders();
    Session s;
    EXPECT_TRUE(s.session->file().isEmpty());
    EXPECT_FALSE(s.session->isModified());
    EXPECT_EQ(s.session->displayName(), QStringLiteral("Untitled"));
    EXPECT_EQ(s.session->windowTitle(), QStringLiteral("Untitled[*] — mipgloss"));
    EXPECT_EQ(s.session->autosaveInterval(), SceneFileSession::kDefaultAutosaveIntervalMs);
    EXPECT_EQ(QFileInfo(s.session->saveAsSuggestion()).fileName(), QStringLiteral("untitled.mipgloss"));
}

TEST(SceneFileSession, SavedThenReopenedIsTheSameScene) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString path = dir.filePath(QStringLiteral("gold.mipgloss"));
    QByteArray saved;
    {
        Session s;
        s.editLambda(1.25f);
        s.document->setName(1, QStringLiteral("renamed"));
        ASSERT_TRUE(s.session->isModified());
        QSignalSpy titles(s.session.get(), &SceneFileSession::titleChanged);
        QSignalSpy messages(s.session.get(), &SceneFileSession::messageShown);
        ASSERT_TRUE(s.session->saveTo(path));
        EXPECT_EQ(s.session->file(), QFileInfo(path).absoluteFilePath());
        EXPECT_FALSE(s.session->isModified());
        ASSERT_EQ(titles.count(), 1);
        EXPECT_EQ(titles.front().front().toString(), QStringLiteral("gold.mipgloss[*] — mipgloss"));
        ASSERT_EQ(messages.count(), 1);
        EXPECT_EQ(messages.front().at(0).toString(), QStringLiteral("Saved gold.mipgloss"));
        EXPECT_FALSE(messages.front().at(1).toBool());
        EXPECT_EQ(s.session->lastDirectory(), QFileInfo(path).absolutePath());
        EXPECT_EQ(s.session->saveAsSuggestion(), s.session->file());
        saved = asFile(s.document->scene());
    }

    Session t;
    QSignalSpy replaced(t.session.get(), &SceneFileSession::sceneReplaced);
    QSignalSpy opened(t.session.get(), &SceneFileSession::openReported);
    ASSERT_TRUE(t.session->open(path));
    EXPECT_EQ(asFile(t.document->scene()), saved);
    EXPECT_FLOAT_EQ(t.document->materialOf(0).lambda, 1.25f);
    EXPECT_EQ(t.document->object(1).name, "renamed");
    EXPECT_EQ(t.document->undoStack()->count(), 0) << "an opened scene has no history";
    EXPECT_FALSE(t.session->isModified());
    EXPECT_EQ(t.session->file(), QFileInfo(path).absoluteFilePath());
    EXPECT_EQ(replaced.count(), 1);
    ASSERT_EQ(opened.count(), 1);
    EXPECT_EQ(opened.front().at(0).toString(), QStringLiteral("Opened gold.mipgloss"));
    EXPECT_FALSE(opened.front().at(1).toBool());
}

TEST(SceneFileSession, SaveWritesTheSceneToSave) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    Session s;
    // The window's view camera, added to what is written but never to the document.
    OrbitCamera camera;
    camera.distance = 7.5f;
    camera.yawDegrees = 30.0f;
    s.session->setSceneToSave([&] {
        Scene scene = s.document->scene();
        scene.camera = camera;
        return scene;
    });
    const QString path = dir.filePath(QStringLiteral("view.mipgloss"));
    ASSERT_TRUE(s.session->saveTo(path));
    const Scene written = loadScene(path.toStdString());
    ASSERT_TRUE(written.camera.has_value());
    EXPECT_FLOAT_EQ(written.camera->distance, 7.5f);
    EXPECT_FLOAT_EQ(written.camera->yawDegrees, 30.0f);
    EXPECT_FALSE(s.document->scene().camera.has_value());
    EXPECT_FALSE(s.session->isModified()) << "the camera is not an edit";
}

TEST(SceneFileSession, ModifiedFollowsTheSavedSceneAndSignalsOnlyChanges) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    Session s;
    QSignalSpy modified(s.session.get(), &SceneFileSession::modifiedChanged);
    s.editLambda(1.25f);
    s.editLambda(2.5f);
    ASSERT_EQ(modified.count(), 1) << "set once, not per edit";
    EXPECT_TRUE(modified.back().front().toBool());
    ASSERT_TRUE(s.session->saveTo(dir.filePath(QStringLiteral("a.mipgloss"))));
    ASSERT_EQ(modified.count(), 2);
    EXPECT_FALSE(modified.back().front().toBool());

    // Edit, undo back to the saved state, undo past it, redo to it.
    s.editLambda(6.0f);
    EXPECT_TRUE(s.session->isModified());
    s.document->undoStack()->undo();
    EXPECT_FALSE(s.session->isModified()) << "undone to what was saved";
    s.document->undoStack()->undo();
    EXPECT_TRUE(s.session->isModified()) << "undone past what was saved";
    s.document->undoStack()->redo();
    EXPECT_FALSE(s.session->isModified());
    EXPECT_EQ(modified.count(), 6);

    // An edit and its exact opposite: the same scene, not modified.
    Transform t = s.document->object(2).transform;
    const Transform original = t;
    t.scale = 3.0f;
    s.document->setTransform(2, t);
    s.document->setTransform(2, original);
    EXPECT_FALSE(s.session->isModified());

    // Meshes opened as a new scene: untitled, as modified as it was; Save As suggests a new file
    // in the folder last saved in.
    s.editLambda(3.0f);
    s.session->detachFromFile();
    EXPECT_TRUE(s.session->file().isEmpty());
    EXPECT_EQ(s.session->windowTitle(), QStringLiteral("Untitled[*] — mipgloss"));
    EXPECT_TRUE(s.session->isModified());
    EXPECT_EQ(s.session->saveAsSuggestion(), QDir(dir.path()).absoluteFilePath(QStringLiteral("untitled.mipgloss")));

    // New: untitled, nothing to save, no history.
    QSignalSpy replaced(s.session.get(), &SceneFileSession::sceneReplaced);
    s.session->startNew(makeFigure1Scene());
    EXPECT_FALSE(s.session->isModified());
    EXPECT_EQ(replaced.count(), 1);
    EXPECT_EQ(s.document->undoStack()->count(), 0);
}

TEST(SceneFileSession, FilesThatCannotBeReadOrWrittenAreMessagesAndChangeNothing) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString good = dir.filePath(QStringLiteral("good.mipgloss"));
    Session s;
    ASSERT_TRUE(s.session->saveTo(good));
    s.editLambda(4.0f);
    const Scene edited = s.document->scene();

    const QString broken = dir.filePath(QStringLiteral("broken.json"));
    test::writeBytes(broken.toStdString(), "{ not a scene");
    QSignalSpy opened(s.session.get(), &SceneFileSession::openReported);
    EXPECT_FALSE(s.session->open(broken));
    ASSERT_EQ(opened.count(), 1);
    EXPECT_TRUE(opened.front().at(1).toBool());
    EXPECT_TRUE(opened.front().at(0).toString().contains(QStringLiteral("broken.json")))
        << opened.front().at(0).toString().toStdString();
    EXPECT_EQ(s.document->scene(), edited);
    EXPECT_EQ(s.session->file(), QFileInfo(good).absoluteFilePath());
    EXPECT_TRUE(s.session->isModified());

    // A folder that cannot be made (a file stands where it would be).
    const QString blocked = dir.filePath(QStringLiteral("good.mipgloss/inside.mipgloss"));
    QSignalSpy messages(s.session.get(), &SceneFileSession::messageShown);
    EXPECT_FALSE(s.session->saveTo(blocked));
    ASSERT_EQ(messages.count(), 1);
    EXPECT_TRUE(messages.front().at(1).toBool());
    EXPECT_TRUE(messages.front().at(0).toString().contains(QStringLiteral("inside.mipgloss")))
        << messages.front().at(0).toString().toStdString();
    EXPECT_EQ(s.session->file(), QFileInfo(good).absoluteFilePath());
    EXPECT_TRUE(s.session->isModified());
    EXPECT_FALSE(RecentFiles::files().contains(QFileInfo(blocked).absoluteFilePath()));
}

TEST(RecentFiles, KeepOrderAndLimitAndDropMissingFiles) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    std::vector<QString> files;
    for (int i = 0; i < 10; ++i) {
        files.push_back(dir.filePath(QStringLiteral("scene%1.json").arg(i)));
        saveScene(makeFigure1Scene(), files.back().toStdString());
    }
    RecentFiles::add(files[0]);
    RecentFiles::add(files[1]);
    RecentFiles::add(files[2]);
    RecentFiles::add(files[0]);  // again: first, and once
    EXPECT_EQ(RecentFiles::files(), (QStringList{files[0], files[2], files[1]}));
    for (const QString& f : files) RecentFiles::add(f);
    ASSERT_EQ(RecentFiles::files().size(), kMaxRecentFiles);
    EXPECT_EQ(RecentFiles::files().front(), files[9]);
    EXPECT_EQ(RecentFiles::files().back(), files[2]);

    QFile::remove(files[5]);
    EXPECT_EQ(RecentFiles::prune(), QStringList{files[5]});
    EXPECT_FALSE(RecentFiles::files().contains(files[5]));
    EXPECT_EQ(RecentFiles::files().size(), kMaxRecentFiles - 1);
    RecentFiles::clear();
}

TEST(SceneFileSession, OpeningAndSavingPutAFileFirstInRecentFiles) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    std::vector<QString> files;
    for (int i = 0; i < 3; ++i) {
        files.push_back(dir.filePath(QStringLiteral("scene%1.mipgloss").arg(i)));
        saveScene(makeFigure1Scene(), files.back().toStdString());
    }
    Session s;
    QSignalSpy changed(s.session.get(), &SceneFileSession::recentFilesChanged);
    ASSERT_TRUE(s.session->open(files[0]));
    ASSERT_TRUE(s.session->open(files[1]));
    const QString saved = dir.filePath(QStringLiteral("saved.mipgloss"));
    ASSERT_TRUE(s.session->saveTo(saved));
    ASSERT_TRUE(s.session->open(files[0]));
    EXPECT_EQ(s.session->recentFiles(), (QStringList{files[0], saved, files[1]}));
    EXPECT_EQ(changed.count(), 4);

    // A file gone since: dropped, with an error naming it; one still there stays.
    QFile::remove(files[1]);
    QSignalSpy messages(s.session.get(), &SceneFileSession::messageShown);
    EXPECT_TRUE(s.session->recentFileExists(saved));
    EXPECT_FALSE(s.session->recentFileExists(files[1]));
    EXPECT_EQ(s.session->recentFiles(), (QStringList{files[0], saved}));
    ASSERT_EQ(messages.count(), 1);
    EXPECT_TRUE(messages.front().at(1).toBool());
    EXPECT_TRUE(messages.front().at(0).toString().contains(QStringLiteral("scene1.mipgloss")));

    // At start: every entry gone is dropped, in one message that is not an error.
    QFile::remove(saved);
    s.session->pruneRecentFiles();
    EXPECT_EQ(s.session->recentFiles(), QStringList{files[0]});
    ASSERT_EQ(messages.count(), 2);
    EXPECT_FALSE(messages.back().at(1).toBool());
    EXPECT_TRUE(messages.back().at(0).toString().contains(QStringLiteral("saved.mipgloss")));
    s.session->pruneRecentFiles();
    EXPECT_EQ(messages.count(), 2) << "nothing gone, nothing said";

    s.session->clearRecentFiles();
    EXPECT_TRUE(s.session->recentFiles().isEmpty());
}

TEST(SceneFileSession, AutosaveWritesModifiedWorkWithAbsolutePathsOnItsTimer) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString triangle = writeTriangle(dir);
    const QString sceneFile = dir.filePath(QStringLiteral("shot.mipgloss"));
    Session s;
    EXPECT_FALSE(s.session->autosaveNow()) << "nothing modified";
    EXPECT_FALSE(QFileInfo::exists(s.session->autosave().file()));

    // A scene with a mesh file beside it, saved, then edited.
    Scene scene = s.document->scene();
    SceneObject object = scene.objects.front();
    object.name = "triangle";
    object.mesh = std::make_shared<const Mesh>(loadMesh(triangle.toStdString()));
    object.meshSource = QFileInfo(triangle).absoluteFilePath().toStdString();
    s.document->addObject(object);
    ASSERT_TRUE(s.session->saveTo(sceneFile));
    s.document->setName(4, QStringLiteral("edited"));
    ASSERT_TRUE(s.session->isModified());

    s.session->setAutosaveInterval(30);
    EXPECT_EQ(s.session->autosaveInterval(), 30);
    ASSERT_TRUE(QTest::qWaitFor([&] { return QFileInfo::exists(s.session->autosave().file()); }, 10000))
        << "no autosave in " << Autosave::folder().toStdString();
    EXPECT_TRUE(s.session->autosave().file().startsWith(Autosave::folder()));
    EXPECT_TRUE(Autosave::leftovers().empty()) << "a live session's autosave is no leftover";

    // A scene file whose meshes are absolute paths, which loads as the same scene, and knows the
    // file the work belongs to.
    const QJsonObject root = QJsonDocument::fromJson(readAll(s.session->autosave().file())).object();
    const QJsonArray objects = root.value(QStringLiteral("objects")).toArray();
    ASSERT_EQ(objects.size(), 5);
    EXPECT_EQ(objects.at(4).toObject().value(QStringLiteral("mesh")).toString(), QFileInfo(triangle).absoluteFilePath());
    EXPECT_EQ(objects.at(0).toObject().value(QStringLiteral("mesh")).toString(), QStringLiteral("builtin:teapot"));
    EXPECT_EQ(root.value(QStringLiteral("autosave")).toObject().value(QStringLiteral("sceneFile")).toString(),
              QFileInfo(sceneFile).absoluteFilePath());
    EXPECT_EQ(asFile(loadScene(s.session->autosave().file().toStdString())), asFile(s.document->scene()));

    // Later edits are written on the next tick; no change, nothing written.
    s.document->setName(4, QStringLiteral("later"));
    auto autosavedName = [&] { return loadScene(s.session->autosave().file().toStdString()).objects[4].name; };
    ASSERT_TRUE(QTest::qWaitFor([&] { return autosavedName() == "later"; }, 10000));
    s.session->setAutosaveInterval(SceneFileSession::kDefaultAutosaveIntervalMs);
    EXPECT_FALSE(s.session->autosaveNow()) << "nothing new to write";

    // Undoing back to the saved scene leaves nothing to restore.
    s.document->undoStack()->undo();
    s.document->undoStack()->undo();
    EXPECT_FALSE(s.session->isModified());
    EXPECT_FALSE(QFileInfo::exists(s.session->autosave().file()));
}

TEST(SceneFileSession, SavingNewAndACleanEndRemoveTheAutosave) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    Session s;
    s.editLambda(2.0f);
    ASSERT_TRUE(s.session->autosaveNow());
    ASSERT_TRUE(QFileInfo::exists(s.session->autosave().file()));
    ASSERT_TRUE(s.session->saveTo(dir.filePath(QStringLiteral("s.mipgloss"))));
    EXPECT_FALSE(QFileInfo::exists(s.session->autosave().file())) << "saved";

    s.editLambda(3.0f);
    ASSERT_TRUE(s.session->autosaveNow());
    s.session->startNew(makeFigure1Scene());
    EXPECT_FALSE(QFileInfo::exists(s.session->autosave().file())) << "New";

    s.editLambda(4.0f);
    ASSERT_TRUE(s.session->autosaveNow());
    s.session->endCleanly();
    EXPECT_FALSE(QFileInfo::exists(s.session->autosave().file())) << "a clean end";
    EXPECT_TRUE(s.session->isModified()) << "dropped knowingly, still modified";
    EXPECT_TRUE(Autosave::leftovers().empty());
}

TEST(SceneFileSession, ACrashLeavesTheAutosaveAndRestoreBringsItBack) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString sceneFile = dir.filePath(QStringLiteral("shot.json"));
    QByteArray autosaved;
    {
        Session s;
        ASSERT_TRUE(s.session->saveTo(sceneFile));
        s.document->setName(0, QStringLiteral("unsaved"));
        ASSERT_TRUE(s.session->autosaveNow());
        autosaved = asFile(s.document->scene());
        // The session ends modified, without endCleanly: as in a crash, the autosave stays.
    }
    const std::optional<Autosave::Leftover> leftover = SceneFileSession::newestLeftover();
    ASSERT_TRUE(leftover.has_value());
    EXPECT_EQ(leftover->sceneFile, QFileInfo(sceneFile).absoluteFilePath());
    const QString question = SceneFileSession::restoreQuestion(*leftover);
    EXPECT_TRUE(question.contains(QStringLiteral("shot.json"))) << question.toStdString();

    Session next;
    QSignalSpy replaced(next.session.get(), &SceneFileSession::sceneReplaced);
    QSignalSpy messages(next.session.get(), &SceneFileSession::messageShown);
    ASSERT_TRUE(next.session->restore(*leftover));
    EXPECT_EQ(asFile(next.document->scene()), autosaved);
    EXPECT_EQ(next.document->object(0).name, "unsaved");
    EXPECT_TRUE(next.session->isModified()) << "restored work is not saved work";
    EXPECT_EQ(next.session->file(), QFileInfo(sceneFile).absoluteFilePath());
    EXPECT_EQ(next.session->windowTitle(), QStringLiteral("shot.json[*] — mipgloss"));
    EXPECT_EQ(replaced.count(), 1);
    ASSERT_EQ(messages.count(), 1);
    EXPECT_FALSE(messages.front().at(1).toBool());
    EXPECT_FALSE(QFileInfo::exists(leftover->file));
    EXPECT_FALSE(SceneFileSession::newestLeftover().has_value()) << "restored: no longer offered";
    next.session->endCleanly();
}

TEST(SceneFileSession, AnUnmodifiedSessionLeavesNoAutosaveAndABrokenOneIsKept) {
    useTestFolders();
    {
        Session s;
        s.editLambda(2.0f);
        ASSERT_TRUE(s.session->autosaveNow());
        s.document->undoStack()->undo();  // back to what it started with: nothing to keep
    }
    EXPECT_FALSE(SceneFileSession::newestLeftover().has_value());

    // A leftover that cannot be read is kept, for the user to rescue by hand, with a message.
    QDir().mkpath(Autosave::folder());
    const QString broken = QDir(Autosave::folder()).filePath(QStringLiteral("broken.json"));
    test::writeBytes(broken.toStdString(), "{ not a scene");
    const std::optional<Autosave::Leftover> leftover = SceneFileSession::newestLeftover();
    ASSERT_TRUE(leftover.has_value());
    EXPECT_TRUE(SceneFileSession::restoreQuestion(*leftover).contains(QStringLiteral("a scene that was never saved")));
    Session s;
    const Scene before = s.document->scene();
    QSignalSpy messages(s.session.get(), &SceneFileSession::messageShown);
    EXPECT_FALSE(s.session->restore(*leftover));
    ASSERT_EQ(messages.count(), 1);
    EXPECT_TRUE(messages.front().at(1).toBool());
    EXPECT_EQ(s.document->scene(), before);
    EXPECT_FALSE(s.session->isModified());
    EXPECT_TRUE(QFileInfo::exists(broken));
    Autosave::remove(*leftover);
}
