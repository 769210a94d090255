// A window's scene-file session: which file the document's scene belongs to, whether it differs
// from what was last opened or saved, saving, the recent files, autosave and its restore. QtCore
// only, so it runs and is tested without a display: the questions (save the changes? which file?
// restore the autosave?) are the window's, which asks them and then tells the session what to do.
//
// Files. A scene is opened (open) or saved (saveTo) through scene_file.h, whose writes are atomic
// (atomic_file.h); either makes the file the scene's (file(), absolute), first in the recent files
// (recent_files.h) and the folder dialogs start in (lastDirectory()). The title is
// "<file name>[*] — mipgloss" ("Untitled" before the first save), with the platform's modified
// mark.
//
// Modified. The scene is modified when it differs (Scene::operator==) from the one last opened,
// saved or made new; so undoing back to the saved state clears the mark, and library edits, which
// share the undo stack, never set it.
//
// Autosave (autosave.h). While the scene is modified it is written every autosaveInterval() (a
// minute) to the user's data folder; saving, New, Open, undoing back to the saved scene and a
// clean exit (endCleanly) remove it, and unsaved work the user never chose to drop keeps it when
// the session ends. A file left by a session that did not end cleanly is offered for restoring
// (newestLeftover, restore): the restored scene keeps the file name it had (or none) and is
// modified, as what is on disk is unknown.
//
// Messages (what was opened, saved or restored, and what failed, naming the file and the reason)
// are signals for the window to show; warnings of a file that opened are logged to stderr.
#pragma once

#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/autosave.h"
#include "mipgloss/ui/scene_document.h"

#include <QObject>
#include <QString>
#include <QStringList>

#include <functional>
#include <memory>
#include <optional>

class QTimer;

namespace mipgloss::ui {

class SceneDocument;

class SceneFileSession : public QObject {
    Q_OBJECT
public:
    static constexpr int kDefaultAutosaveIntervalMs = 60 * 1000;

    // Watches `document`, whose scene now is the saved one: a new, untitled scene.
    explicit SceneFileSession(SceneDocument* document, QObject* parent = nullptr);
    ~SceneFileSession() override;  // unmodified: its autosave is removed; modified: kept

    // What Save writes: the document's scene unless set (the window adds its view's camera).
    void setSceneToSave(std::function<Scene()> sceneToSave);

    // The file the scene was last opened from or saved to (absolute); empty for a new scene.
    const QString& file() const { return file_; }
    QString displayName() const;  // the file's name, or "Untitled"
    QString windowTitle() const;  // "<displayName>[*] — mipgloss"
    bool isModified() const { return modified_; }
    // The folder the user last opened or saved in; file dialogs start there.
    const QString& lastDirectory() const { return lastDirectory_; }
    void noteDirectoryOf(const QString& path);
    // Save As's suggestion: the scene's file, or "untitled.mipgloss" in lastDirectory().
    QString saveAsSuggestion() const;

    // The document's scene becomes `scene`, new and untitled, with nothing to save (File → New).
    void startNew(Scene scene);
    // Reads `path` and makes its scene the document's (fresh, no undo history); false with a
    // message when it cannot be read, the document left as it was.
    bool open(const QString& path);
    // Writes the scene to save to `path` and makes it the scene's file; false with a message.
    bool saveTo(const QString& path);
    // The scene no longer belongs to its file (meshes opened as a new scene): untitled, and as
    // modified as it was.
    void detachFromFile();

    // File → Open Recent, newest first.
    QStringList recentFiles() const;
    void clearRecentFiles();
    // False when `path` no longer exists: its entry is dropped, with a message.
    bool recentFileExists(const QString& path);
    // Drops the entries whose files are gone, with a message naming them (at start).
    void pruneRecentFiles();

    int autosaveInterval() const;
    void setAutosaveInterval(int milliseconds);
    // This session's autosave (its file exists while modified work is autosaved).
    const Autosave& autosave() const { return *autosave_; }
    // Writes the autosave now if the scene is modified and changed since the last one (the timer
    // calls it); false when there was nothing to write or the write failed (said once per reason).
    bool autosaveNow();
    // The work is saved or knowingly dropped and the window goes: no autosave, none kept.
    void endCleanly();

    // The newest autosave a session that did not end cleanly left behind, if any.
    static std::optional<Autosave::Leftover> newestLeftover();
    // The question the window asks about it.
    static QString restoreQuestion(const Autosave::Leftover& leftover);
    // Makes the leftover's scene the document's (modified, under the file it belonged to) and
    // removes the leftover; false with a message when it cannot be read (it is kept then, for the
    // user to rescue by hand).
    bool restore(const Autosave::Leftover& leftover);

signals:
    void titleChanged(const QString& title);
    void modifiedChanged(bool modified);
    // The document holds a new scene from a file, a restored autosave or New: the view shows the
    // scene's saved camera, or frames it.
    void sceneReplaced();
    void recentFilesChanged();
    // The outcome of opening a scene file (a later success answers an earlier failure).
    void openReported(const QString& message, bool error);
    // Everything else the user is told: saving, autosave, recent files, restoring.
    void messageShown(const QString& message, bool error);

private:
    void replaceScene(Scene scene, FileCameras cameras = {});
    void setFile(const QString& file);
    void markSaved();                      // the document's scene is the saved one
    void matchesFile(const QString& path);  // opened or saved: its file, saved state, recent files
    void updateModified();
    void forgetAutosave();  // the work is safe or knowingly dropped: no autosave to keep

    SceneDocument* document_;
    std::function<Scene()> sceneToSave_;
    QString file_;
    QString lastDirectory_;
    // The scene as last opened, saved or made new; none for a restored autosave (whose saved
    // state is unknown, so it stays modified until saved).
    std::optional<Scene> savedScene_;
    bool modified_ = false;
    std::unique_ptr<Autosave> autosave_;
    QTimer* autosaveTimer_ = nullptr;
    std::optional<Scene> lastAutosaved_;
    QString lastAutosaveError_;
};

}  // namespace mipgloss::ui
