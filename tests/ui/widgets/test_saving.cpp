// Saving as users expect, through the window (main_window.h): the title's modified mark follows
// the saved scene, New, Open and closing ask before dropping changes (Save, Discard, Cancel; once
// through a real QMessageBox), the Open Recent menu, autosave and its restore after a crash offered
// by the window, and exported images written atomically. The session's own rules (what an autosave
// holds, recent files' order and limit) are tested without a window in
// tests/ui/documents/test_scene_file_session.cpp. Everything under QStandardPaths test mode, so the
// user's own folders are never touched.
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/ui/autosave.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/recent_files.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_file.h"
#include "mipgloss/ui/viewport.h"

#include "session_test_support.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QMessageBox>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QUndoStack>

#include <memory>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::asFile;
using mipgloss::test::readAll;
using mipgloss::test::useTestFolders;
using mipgloss::test::waitUntil;
using mipgloss::test::writeTriangle;

namespace {

// A window whose questions are answered by the test and counted.
struct Window {
    std::unique_ptr<MainWindow> w = std::make_unique<MainWindow>();
    MainWindow::SaveChoice answer = MainWindow::SaveChoice::Cancel;
    QString saveAs;  // what the save dialog returns
    int asked = 0;
    std::vector<QString> askedNames;

    Window() {
        w->prompts().saveChanges = [this](const QString& name) {
            ++asked;
            askedNames.push_back(name);
            return answer;
        };
        w->prompts().saveFileName = [this](const QString&) { return saveAs; };
        w->prompts().restoreAutosave = [](const QString&) {
            ADD_FAILURE() << "no autosave restore was expected";
            return false;
        };
    }
    SceneDocument& doc() { return *w->document(); }
    void edit(float lambda = 1.25f) {
        Material m = doc().materialOf(0);
        m.lambda = lambda;
        doc().setMaterial(0, m);
    }
};

std::vector<std::string> names(const Scene& scene) {
    std::vector<std::string> out;
    for (const SceneObject& o : scene.objects) out.push_back(o.name);
    return out;
}

// Clicks `button` on the first QMessageBox named `name` that shows up (polled, since exec() blocks
// the caller in a nested event loop); *found tells whether it came.
void answerMessageBox(const QString& name, QMessageBox::StandardButton button, bool* found) {
    auto* timer = new QTimer;
    timer->setInterval(20);
    QObject::connect(timer, &QTimer::timeout, [timer, name, button, found] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box || box->objectName() != name) return;
        *found = true;
        timer->stop();
        timer->deleteLater();
        QTest::mouseClick(box->button(button), Qt::LeftButton);
    });
    timer->start();
    QTimer::singleShot(10000, timer, [timer] { timer->deleteLater(); });  // never left running
}

}  // namespace

TEST(Saving, ModifiedMarkFollowsTheSavedScene) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    Window win;
    MainWindow& w = *win.w;
    EXPECT_EQ(w.windowTitle(), QStringLiteral("Untitled[*] — mipgloss"));
    EXPECT_FALSE(w.isWindowModified());

    win.edit();
    EXPECT_TRUE(w.isWindowModified());
    // Save of a scene never saved is Save As: the dialog's file.
    win.saveAs = dir.filePath(QStringLiteral("gold"));
    ASSERT_TRUE(w.save()) << w.lastMessage().toStdString();
    EXPECT_EQ(w.sceneFile(), dir.filePath(QStringLiteral("gold.mipgloss")));
    EXPECT_FALSE(w.isWindowModified());
    EXPECT_EQ(w.windowTitle(), QStringLiteral("gold.mipgloss[*] — mipgloss"));
    // The file holds the scene and the view it was saved with (the camera is not an edit).
    Scene withView = w.document()->scene();
    withView.camera = w.viewport()->camera();
    EXPECT_EQ(asFile(loadScene(w.sceneFile().toStdString())), asFile(withView));

    // Edit, undo back to the saved state, redo, save with Ctrl+S's action (no dialog now).
    win.edit(6.0f);
    EXPECT_TRUE(w.isWindowModified());
    win.doc().undoStack()->undo();
    EXPECT_FALSE(w.isWindowModified()) << "undone to what was saved";
    win.doc().undoStack()->undo();
    EXPECT_TRUE(w.isWindowModified()) << "undone past what was saved";
    win.doc().undoStack()->redo();
    win.doc().undoStack()->redo();
    EXPECT_TRUE(w.isWindowModified());
    win.saveAs = dir.filePath(QStringLiteral("never.json"));
    auto* save = w.findChild<QAction*>(QStringLiteral("saveAction"));
    ASSERT_NE(save, nullptr);
    EXPECT_TRUE(save->shortcuts().contains(QKeySequence(QKeySequence::Save)));
    save->trigger();
    EXPECT_FALSE(w.isWindowModified());
    EXPECT_FALSE(QFileInfo::exists(win.saveAs)) << "a scene with a file saves to it";
    const Scene reloaded = loadScene(w.sceneFile().toStdString());
    EXPECT_FLOAT_EQ(reloaded.materialOf(reloaded.objects[0]).lambda, 6.0f);
    EXPECT_EQ(win.asked, 0);

    // An edit and its exact opposite: the same scene, not modified.
    Transform t = win.doc().object(2).transform;
    const Transform original = t;
    t.scale = 3.0f;
    win.doc().setTransform(2, t);
    win.doc().setTransform(2, original);
    EXPECT_FALSE(w.isWindowModified());
}

TEST(Saving, CancelKeepsTheWindowAndTheScene) {
    useTestFolders();
    Window win;
    MainWindow& w = *win.w;
    w.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
    win.edit();
    const Scene edited = win.doc().scene();
    win.answer = MainWindow::SaveChoice::Cancel;

    EXPECT_FALSE(w.close());
    EXPECT_TRUE(w.isVisible());
    EXPECT_FALSE(w.newScene());
    QTemporaryDir dir;
    const QString other = dir.filePath(QStringLiteral("other.json"));
    saveScene(makeFigure1Scene(), other.toStdString());
    EXPECT_FALSE(w.openScene(other));
    EXPECT_EQ(win.asked, 3);
    EXPECT_EQ(win.askedNames.front(), QStringLiteral("Untitled"));
    EXPECT_EQ(win.doc().scene(), edited);
    EXPECT_TRUE(w.isWindowModified());
    EXPECT_TRUE(w.sceneFile().isEmpty());

    // Save, but the file dialog is cancelled: nothing is dropped either.
    win.answer = MainWindow::SaveChoice::Save;
    win.saveAs.clear();
    EXPECT_FALSE(w.newScene());
    EXPECT_EQ(win.doc().scene(), edited);
    w.setWindowModified(false);  // let the window go without asking
}

TEST(Saving, DiscardDropsTheChangesAndSaveWritesThem) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    Window win;
    MainWindow& w = *win.w;
    const std::vector<std::string> figure1 = names(win.doc().scene());
    win.doc().setName(0, QStringLiteral("renamed"));
    win.answer = MainWindow::SaveChoice::Discard;
    ASSERT_TRUE(w.newScene());
    EXPECT_EQ(names(win.doc().scene()), figure1);
    EXPECT_FALSE(w.isWindowModified());
    EXPECT_EQ(win.doc().undoStack()->count(), 0);

    // Save writes the scene before it is dropped.
    win.doc().setName(0, QStringLiteral("kept"));
    win.answer = MainWindow::SaveChoice::Save;
    win.saveAs = dir.filePath(QStringLiteral("kept.json"));
    ASSERT_TRUE(w.newScene());
    EXPECT_EQ(loadScene(win.saveAs.toStdString()).objects[0].name, "kept");
    EXPECT_EQ(names(win.doc().scene()), figure1);
    EXPECT_TRUE(w.sceneFile().isEmpty());

    // Open over changes: Discard, and the file opens unmodified.
    win.doc().setName(1, QStringLiteral("dropped"));
    win.answer = MainWindow::SaveChoice::Discard;
    ASSERT_TRUE(w.openScene(win.saveAs));
    EXPECT_EQ(win.doc().object(0).name, "kept");
    EXPECT_NE(win.doc().object(1).name, "dropped");
    EXPECT_FALSE(w.isWindowModified());
    EXPECT_EQ(win.asked, 3);

    // Unmodified: nothing is asked.
    EXPECT_TRUE(w.newScene());
    EXPECT_EQ(win.asked, 3);
    win.doc().setName(0, QStringLiteral("x"));
    EXPECT_TRUE(w.close());
    EXPECT_EQ(win.asked, 4);
}

// The real dialog, driven as a user would: Cancel keeps the window open, Discard closes it.
TEST(Saving, RealSaveChangesDialogIsAnswered) {
    useTestFolders();
    auto w = std::make_unique<MainWindow>();
    w->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(w.get()));
    w->document()->setName(0, QStringLiteral("unsaved"));
    const Scene edited = w->document()->scene();

    bool found = false;
    answerMessageBox(QStringLiteral("saveChangesBox"), QMessageBox::Cancel, &found);
    EXPECT_FALSE(w->close());
    ASSERT_TRUE(found) << "no Save/Discard/Cancel question came";
    EXPECT_TRUE(w->isVisible());
    EXPECT_EQ(w->document()->scene(), edited);

    found = false;
    answerMessageBox(QStringLiteral("saveChangesBox"), QMessageBox::Discard, &found);
    EXPECT_TRUE(w->close());
    EXPECT_TRUE(found);
    EXPECT_FALSE(w->isVisible());
}

TEST(Saving, RecentFilesKeepOrderAndDropMissingFiles) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    std::vector<QString> files;
    for (int i = 0; i < 10; ++i) {
        files.push_back(dir.filePath(QStringLiteral("scene%1.json").arg(i)));
        saveScene(makeFigure1Scene(), files.back().toStdString());
        RecentFiles::add(files.back());
    }

    // The window: saving and opening put a file first; the menu lists them; a file gone since is
    // removed with a message when chosen, and the scene stays.
    Window win;
    MainWindow& w = *win.w;
    ASSERT_TRUE(w.openScene(files[3]));
    EXPECT_EQ(RecentFiles::files().front(), files[3]);
    const QString saved = dir.filePath(QStringLiteral("saved.json"));
    ASSERT_TRUE(w.saveScene(saved));
    EXPECT_EQ(RecentFiles::files().front(), saved);
    std::vector<QAction*> shown;
    for (QAction* a : w.findChildren<QAction*>(QStringLiteral("recentFileAction")))
        if (a->isVisible()) shown.push_back(a);
    ASSERT_EQ(shown.size(), static_cast<std::size_t>(kMaxRecentFiles));
    EXPECT_EQ(shown.front()->data().toString(), saved);
    EXPECT_TRUE(shown.front()->text().contains(QStringLiteral("saved.json")));

    QFile::remove(files[4]);
    const std::vector<std::string> before = names(win.doc().scene());
    EXPECT_FALSE(w.openRecentFile(files[4]));
    EXPECT_TRUE(w.lastMessageIsError());
    EXPECT_TRUE(w.lastMessage().contains(QStringLiteral("scene4.json")));
    EXPECT_FALSE(RecentFiles::files().contains(files[4]));
    EXPECT_EQ(names(win.doc().scene()), before);
    EXPECT_EQ(w.sceneFile(), saved);

    // Choosing an entry opens it.
    for (QAction* a : w.findChildren<QAction*>(QStringLiteral("recentFileAction")))
        if (a->isVisible() && a->data().toString() == files[6]) a->trigger();
    EXPECT_EQ(w.sceneFile(), files[6]);
    RecentFiles::clear();
}

TEST(Saving, AutosaveWritesTheSceneAndACrashLeavesItForRestore) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString triangle = writeTriangle(dir);
    const QString sceneFile = dir.filePath(QStringLiteral("shot.json"));
    QByteArray autosaved;
    {
        Window win;
        MainWindow& w = *win.w;
        ASSERT_TRUE(w.saveScene(sceneFile));
        w.importMeshes({triangle});
        ASSERT_EQ(win.doc().objectCount(), 5);
        ASSERT_TRUE(w.isWindowModified());
        w.setAutosaveInterval(30);
        ASSERT_TRUE(waitUntil([&] { return QFileInfo::exists(w.autosave().file()); }, 10000))
            << "no autosave in " << Autosave::folder().toStdString();
        EXPECT_TRUE(Autosave::leftovers().empty()) << "a live session's autosave is no leftover";
        EXPECT_EQ(asFile(loadScene(w.autosave().file().toStdString())), asFile(win.doc().scene()));

        // Later edits are written on the next tick.
        win.doc().setName(4, QStringLiteral("later"));
        auto autosavedName = [&] { return loadScene(w.autosave().file().toStdString()).objects[4].name; };
        ASSERT_TRUE(waitUntil([&] { return autosavedName() == "later"; }, 10000));
        autosaved = asFile(win.doc().scene());
        w.setAutosaveInterval(MainWindow::kDefaultAutosaveIntervalMs);
        // The window goes without being closed, as in a crash: the modified work's autosave stays.
    }
    const std::vector<Autosave::Leftover> leftovers = Autosave::leftovers();
    ASSERT_EQ(leftovers.size(), 1u);
    EXPECT_EQ(leftovers.front().sceneFile, sceneFile);

    Window next;
    QString question;
    next.w->prompts().restoreAutosave = [&](const QString& q) {
        question = q;
        return true;
    };
    ASSERT_TRUE(next.w->offerAutosaveRestore()) << next.w->lastMessage().toStdString();
    EXPECT_TRUE(question.contains(QStringLiteral("shot.json"))) << question.toStdString();
    EXPECT_EQ(asFile(next.doc().scene()), autosaved);
    EXPECT_EQ(next.doc().object(4).name, "later");
    EXPECT_TRUE(next.w->isWindowModified()) << "restored work is not saved work";
    EXPECT_EQ(next.w->sceneFile(), sceneFile);
    EXPECT_EQ(next.w->windowTitle(), QStringLiteral("shot.json[*] — mipgloss"));
    EXPECT_TRUE(Autosave::leftovers().empty()) << "restored: no longer offered";
    EXPECT_FALSE(QFileInfo::exists(leftovers.front().file));
    next.w->setWindowModified(false);  // let it go without an autosave
}

TEST(Saving, DeclinedRestoreDiscardsTheAutosaveAndCleanExitLeavesNone) {
    useTestFolders();
    QString file;
    {
        Window win;
        win.edit();
        ASSERT_TRUE(win.w->autosaveNow());
        file = win.w->autosave().file();
        ASSERT_TRUE(QFileInfo::exists(file));
        EXPECT_FALSE(win.w->autosaveNow()) << "nothing new to write";
    }
    ASSERT_EQ(Autosave::leftovers().size(), 1u);
    EXPECT_TRUE(Autosave::leftovers().front().sceneFile.isEmpty());
    {
        Window win;
        const Scene before = win.doc().scene();
        win.w->prompts().restoreAutosave = [](const QString&) { return false; };
        EXPECT_FALSE(win.w->offerAutosaveRestore());
        EXPECT_EQ(win.doc().scene(), before);
        EXPECT_FALSE(QFileInfo::exists(file));
        EXPECT_TRUE(Autosave::leftovers().empty());
        EXPECT_FALSE(win.w->offerAutosaveRestore()) << "nothing left to offer";
    }
    {
        // A clean exit (closed, changes discarded) removes this session's autosave.
        Window win;
        win.edit();
        ASSERT_TRUE(win.w->autosaveNow());
        ASSERT_TRUE(QFileInfo::exists(win.w->autosave().file()));
        win.answer = MainWindow::SaveChoice::Discard;
        EXPECT_TRUE(win.w->close());
        EXPECT_FALSE(QFileInfo::exists(win.w->autosave().file()));
    }
    {
        // Undoing back to the saved scene, or saving, leaves nothing to restore either.
        QTemporaryDir dir;
        Window win;
        win.edit();
        ASSERT_TRUE(win.w->autosaveNow());
        win.doc().undoStack()->undo();
        EXPECT_FALSE(QFileInfo::exists(win.w->autosave().file()));
        win.edit();
        ASSERT_TRUE(win.w->autosaveNow());
        ASSERT_TRUE(win.w->saveScene(dir.filePath(QStringLiteral("s.json"))));
        EXPECT_FALSE(QFileInfo::exists(win.w->autosave().file()));
    }
    EXPECT_TRUE(Autosave::leftovers().empty());
}

// exportImage goes through writeFileAtomically: a failed export leaves the old file as it was.
TEST(Saving, FailedExportLeavesTheOldImage) {
    useTestFolders();
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    Window win;
    MainWindow& w = *win.w;
    w.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
    ASSERT_TRUE(waitUntil([&] { return w.viewport()->isValid(); }, 60000));
    const QString bogus = dir.filePath(QStringLiteral("shot.notanimageformat"));
    {
        QFile f(bogus);
        ASSERT_TRUE(f.open(QIODevice::WriteOnly));
        f.write("the old bytes");
    }
    EXPECT_FALSE(w.exportImage(bogus));
    EXPECT_TRUE(w.lastMessageIsError());
    EXPECT_TRUE(w.lastMessage().contains(QStringLiteral("shot.notanimageformat")))
        << w.lastMessage().toStdString();
    EXPECT_EQ(readAll(bogus), QByteArray("the old bytes"));
    EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files), QStringList{QStringLiteral("shot.notanimageformat")})
        << "no temporary file left behind";
    const QString png = dir.filePath(QStringLiteral("shot.png"));
    ASSERT_TRUE(w.exportImage(png)) << w.lastMessage().toStdString();
    EXPECT_FALSE(QImage(png).isNull());
}
