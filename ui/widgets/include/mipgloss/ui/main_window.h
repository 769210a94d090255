// The desktop window: the viewport in the middle, docks for the scene list, the material and the
// environment (environment_panel.h), menus, drag and drop, and a status bar with the environment
// and its progress. Built the way Qt's application example is: the actions are members made in
// createActions(), menus are made from them in createMenus(), docks in createDocks().
//
// Editing. Every scene edit is one step on the document's undo stack (scene_document.h); Edit →
// Undo and Redo (the platform's shortcuts) name it: "Undo Change λ of Gold".
//
// Files. File → New, Open, Open Recent, Save (Ctrl+S; a scene never saved asks for a file, as Save
// As does), Save As, Quit. The scene's file, title, modified mark, recent files and autosave are
// the session's (scene_file_session.h); the window asks the questions: New, Open, Quit and closing
// the window ask first when the scene is modified (Save, Discard or Cancel), and an autosave a
// crashed session left is offered by offerAutosaveRestore() (the application calls it at start).
// What is opened, dropped or given on the command line is told apart by fileKindOf (file_kinds.h).
//
// Errors a user can cause (a broken mesh, environment or scene file) never change the scene: a
// failed mesh adds nothing, a failed environment leaves the old one drawn (and the document's
// environment settings are put back to it, without an undo step: the step that asked for the file
// is withdrawn, SceneDocument::withdrawFailedEnvironment), a failed scene file leaves the open
// scene. Each is shown by the message bar (message_bar.h: a dismissable banner above the viewport
// and the status line), kept in lastMessage() and logged to stderr. Every file the window writes
// (scenes, autosaves, exported images) is written atomically (atomic_file.h).
//
// Imported meshes: mesh_importer.h (loading off the UI thread, the placement rule); one import is
// one undo step, and the view frames all afterwards.
#pragma once

#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/mesh_importer.h"
#include "mipgloss/ui/message_bar.h"
#include "mipgloss/ui/scene_file_session.h"

#include <QMainWindow>
#include <QSize>
#include <QString>
#include <QStringList>

#include <cstdint>
#include <functional>

class QAction;
class QMenu;
class QListView;
class QWidget;

namespace mipgloss::ui {

class SceneDocument;
class LibraryDocument;
class LibraryDock;
class EnvironmentManager;
class EnvironmentRequests;
class EnvironmentPanel;
class Viewport;
class MaterialPanel;
class ViewToolBar;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    static constexpr std::int64_t kBackgroundImportBytes = MeshImporter::kBackgroundImportBytes;
    static constexpr float kImportedLambda = MeshImporter::kImportedLambda;
    static constexpr int kDefaultAutosaveIntervalMs = SceneFileSession::kDefaultAutosaveIntervalMs;
    // saveState's version (restoreLayout): a layout saved by a build with other docks is ignored.
    static constexpr int kLayoutVersion = 2;

    SceneDocument* document() const { return document_; }
    // The user's material library (library_document.h), opened from defaultLibraryPath(), and its
    // dock. Library edits share the document's undo stack but never mark the scene modified.
    LibraryDocument* library() const { return library_; }
    LibraryDock* libraryDock() const { return libraryDock_; }
    EnvironmentManager* environments() const { return environments_; }
    Viewport* viewport() const { return viewport_; }
    MaterialPanel* materialPanel() const { return materialPanel_; }
    EnvironmentPanel* environmentPanel() const { return environmentPanel_; }
    QListView* sceneList() const { return sceneList_; }
    ViewToolBar* viewToolBar() const { return viewToolBar_; }
    MeshImporter* importer() const { return importer_; }
    // The scene's file, modified state, recent files and autosave.
    SceneFileSession* session() const { return session_; }
    // The banner above the viewport and the status line.
    MessageBar* messages() const { return messages_; }

    // The last message shown (error or information) and whether it was an error.
    const QString& lastMessage() const { return messages_->lastMessage(); }
    bool lastMessageIsError() const { return messages_->lastMessageIsError(); }
    // The scene file the document was last opened from or saved to; empty for a new scene.
    const QString& sceneFile() const { return session_->file(); }
    // True while a background mesh import runs.
    bool importing() const { return importer_->busy(); }

    // The questions the window asks the user. The defaults are dialogs (QMessageBox with the
    // object name "saveChangesBox" or "restoreAutosaveBox", QFileDialog); tests may replace them.
    enum class SaveChoice { Save, Discard, Cancel };
    struct Prompts {
        // Unsaved changes to the scene called `name` are about to be dropped.
        std::function<SaveChoice(const QString& name)> saveChanges;
        // The file to save to (Save As, or Save of a scene never saved); empty cancels.
        std::function<QString(const QString& suggestion)> saveFileName;
        // An autosave a crashed session left: restore it (true) or discard it (false)?
        std::function<bool(const QString& question)> restoreAutosave;
    };
    Prompts& prompts() { return prompts_; }

    int autosaveInterval() const { return session_->autosaveInterval(); }
    void setAutosaveInterval(int milliseconds) { session_->setAutosaveInterval(milliseconds); }
    // This session's autosave (its file exists while modified work is autosaved).
    const Autosave& autosave() const { return session_->autosave(); }

public slots:
    // New (Figure 1), Open, Save, Save As and opening a recent file. New and Open ask first when
    // the scene is modified (false: cancelled, or the file could not be read).
    bool newScene();
    // A scene with no objects, under the environment and display settings in use (an artist's
    // HDRI stays loaded). File → New (Ctrl+N); newScene() is File → New Figure 1 scene.
    bool newEmptyScene();
    bool openScene(const QString& path);
    bool openRecentFile(const QString& path);  // a file gone from disk leaves Open Recent
    bool save();
    bool saveAs();
    // Writes the scene to `path` and makes it the scene's file; asks nothing.
    bool saveScene(const QString& path);
    // Offers the newest autosave a crashed session left behind (Prompts::restoreAutosave); true
    // when one was restored.
    bool offerAutosaveRestore();
    // Writes the autosave now if the scene is modified and changed since the last one (the
    // session's timer calls it); false when there was nothing to write or the write failed.
    bool autosaveNow() { return session_->autosaveNow(); }

    // Sets the document's environment source to `path` (a file, a face of a six-face set or a
    // directory; environment_requests.h); the EnvironmentManager imports it. False (with a
    // message) if it does not exist; a file that exists but cannot be read fails later through
    // EnvironmentManager::failed.
    bool openEnvironment(const QString& path);
    // Meshes added beside the scene (File → Import mesh, drops).
    void importMeshes(const QStringList& paths);
    // Meshes opened as the scene (File → Open, the command line): asks first when the scene is
    // modified, then, once a mesh is read, the scene's objects are replaced by them, framed, under
    // the environment in use, as a new untitled scene; one undo step brings the old objects back.
    // False when cancelled. A file that cannot be read leaves the scene as it was. `askFirst`
    // false: the caller has asked already.
    bool openMeshes(const QStringList& paths, bool askFirst = true);
    // Writes what the view shows at `size` (empty: the view's own size), through the renderer, not
    // the window: a .exr file holds the linear, scene-referred picture (float RGBA, before exposure
    // and tone mapping), other formats the tone-mapped one; both carry the objects' coverage as
    // alpha when the background is hidden. A size beyond OpenGL's limits, an unwritable folder or a
    // failed render: false with a message naming the file and the problem; nothing is written.
    bool exportImage(const QString& path, QSize size = QSize());
    // What dropping files does, also for command-line arguments, by fileKindOf: a scene opens
    // (the first given, before the rest), mesh files import (added beside the scene; with
    // `meshesOpen` they are opened as the scene instead, as the command line does: openMeshes), an
    // image or a folder becomes the environment (the last one given), a library's materials go
    // into the user's library; anything else is named in an error.
    void openFiles(const QStringList& paths, bool meshesOpen = false);
    void frameAll();
    void frameSelected();  // all when nothing is selected
    void resetView();      // the default view angle and field of view, framing all
    void showShortcuts();  // Help → Keyboard and mouse shortcuts
    void removeSelected();
    void duplicateSelected();

signals:
    void messageShown(const QString& message, bool error);
    // After importMeshes: how many objects were added (failures have their own messages).
    void importFinished(int added);

protected:
    void closeEvent(QCloseEvent* event) override;
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void createCentre();
    void createActions();
    void createDocks();
    void createMenus();
    void createStatusBar();
    void createViewToolBar();
    // The window's geometry and its docks' layout, kept in the user's settings (closeEvent) and
    // restored when the window is made; with none saved the window opens maximised.
    void restoreLayout();
    void saveLayout() const;
    // The document's scene with the view's camera: what Save writes.
    Scene sceneWithView() const;
    // The document has a new scene (SceneFileSession::sceneReplaced): the view shows its saved
    // camera, or frames it.
    void showSceneCamera();
    void fillLookThroughMenu(QMenu* menu);  // View → Look through, each time it opens

    // Files: the session's signals shown; the questions asked.
    void connectSession();
    bool maybeSave();
    void setDefaultPrompts();

    // Undo and Redo keys in the Material and Environment panels' fields undo the document
    // (field_undo_keys.h).
    void sendFieldUndoKeysToDocument();
    void finishImport(const QStringList& added, const QStringList& errors);

    void openSceneDialog();
    void openEnvironmentDialog();
    void openEnvironmentFolderDialog();
    void importMeshDialog();
    void exportImageDialog();

    SceneDocument* document_ = nullptr;
    EnvironmentManager* environments_ = nullptr;
    MeshImporter* importer_ = nullptr;
    Viewport* viewport_ = nullptr;
    MaterialPanel* materialPanel_ = nullptr;
    EnvironmentPanel* environmentPanel_ = nullptr;
    QListView* sceneList_ = nullptr;

    SceneFileSession* session_ = nullptr;
    MessageBar* messages_ = nullptr;
    EnvironmentRequests* environmentRequests_ = nullptr;

    // Actions (createActions), in menu order.
    LibraryDocument* library_ = nullptr;
    LibraryDock* libraryDock_ = nullptr;
    QAction* newAction_ = nullptr;
    QAction* openAction_ = nullptr;
    QAction* saveAction_ = nullptr;
    QAction* saveAsAction_ = nullptr;
    QAction* openEnvironmentAction_ = nullptr;
    QAction* openEnvironmentFolderAction_ = nullptr;
    QAction* importMeshAction_ = nullptr;
    QAction* exportImageAction_ = nullptr;
    QAction* quitAction_ = nullptr;
    QAction* undoAction_ = nullptr;
    QAction* redoAction_ = nullptr;
    QAction* duplicateAction_ = nullptr;
    QAction* removeAction_ = nullptr;
    QAction* frameAllAction_ = nullptr;
    QAction* frameSelectedAction_ = nullptr;
    QAction* resetViewAction_ = nullptr;
    QAction* turntableAction_ = nullptr;
    QAction* showCountersAction_ = nullptr;
    QAction* newEmptyAction_ = nullptr;
    QAction* shortcutsAction_ = nullptr;
    ViewToolBar* viewToolBar_ = nullptr;
    // openMeshes is under way: its import's objects make a new, untitled scene.
    bool openingMeshes_ = false;

    Prompts prompts_;
};

}  // namespace mipgloss::ui
