#include "mipgloss/ui/main_window.h"

#include "mipgloss/assets/default_scene.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/environment_panel.h"
#include "mipgloss/ui/file_kinds.h"
#include "mipgloss/ui/library_dock.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/material_panel.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/view_dialogs.h"
#include "mipgloss/ui/view_toolbar.h"
#include "mipgloss/ui/viewport.h"

#include "environment_requests.h"
#include "field_undo_keys.h"
#include "image_export.h"
#include "recent_files_menu.h"
#include "scene_list_panel.h"
#include "status_indicators.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QListView>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QOpenGLContext>
#include <QPushButton>
#include <QScreen>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QStyle>
#include <QUndoStack>
#include <QUrl>
#include <QVBoxLayout>

#include <algorithm>

namespace mipgloss::ui {

namespace {

QString environmentImagesFilter() {
    return QObject::tr("Environment images (%1);;All files (*)").arg(dialogPatternsOf(FileKind::Environment));
}

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
    setObjectName(QStringLiteral("mainWindow"));
    document_ = new SceneDocument(this);
    document_->resetScene(makeFigure1Scene());
    session_ = new SceneFileSession(document_, this);
    session_->setSceneToSave([this] { return sceneWithView(); });
    environments_ = new EnvironmentManager(this);
    environments_->watch(document_);
    importer_ = new MeshImporter(document_, this);
    setDefaultPrompts();

    createCentre();
    createActions();
    createDocks();
    createMenus();
    createStatusBar();
    createViewToolBar();
    setAcceptDrops(true);

    environmentRequests_ = new EnvironmentRequests(document_, environments_, messages_, this);
    connect(importer_, &MeshImporter::finished, this, &MainWindow::finishImport);
    connect(viewport_, &Viewport::objectClicked, document_, &SceneDocument::setSelected);
    connect(viewport_, &Viewport::glFailed, this, [this](const QString& message) {
        messages_->showMessage(tr("OpenGL: %1").arg(message), true);
    });
    connectSession();

    restoreLayout();
    session_->pruneRecentFiles();
}

MainWindow::~MainWindow() {
    // The file session first (it watches the document; unsaved work keeps its autosave), then GL
    // resources (the viewport makes its context current), then the worker, then the panels and
    // the model that read the document, and the document last.
    delete session_;
    session_ = nullptr;
    // ~Viewport frees its GL resources itself; the context's aboutToBeDestroyed, emitted later
    // from ~QOpenGLWidget, must not call back into the half-destroyed viewport.
    if (QOpenGLContext* context = viewport_->context()) context->disconnect(viewport_);
    delete viewport_;
    viewport_ = nullptr;
    delete environments_;
    environments_ = nullptr;
    qDeleteAll(findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly));
    delete importer_;
    delete document_;
}

// ---------------------------------------------------------------------------------------------
// Construction

void MainWindow::createCentre() {
    // The message banner above the viewport.
    auto* centre = new QWidget(this);
    auto* centreLayout = new QVBoxLayout(centre);
    centreLayout->setContentsMargins(0, 0, 0, 0);
    centreLayout->setSpacing(0);
    messages_ = new MessageBar(statusBar(), centre);
    connect(messages_, &MessageBar::messageShown, this, &MainWindow::messageShown);
    centreLayout->addWidget(messages_);
    viewport_ = new Viewport(document_, environments_, centre);
    viewport_->setObjectName(QStringLiteral("viewport"));
    centreLayout->addWidget(viewport_, 1);
    setCentralWidget(centre);
}

void MainWindow::createActions() {
    auto make = [this](const QString& text, const char* name) {
        auto* action = new QAction(text, this);
        action->setObjectName(QLatin1String(name));
        return action;
    };

    newEmptyAction_ = make(tr("&New scene"), "newEmptyAction");
    newEmptyAction_->setShortcuts(QKeySequence::New);
    newEmptyAction_->setStatusTip(tr("A scene with no objects, under the environment in use"));
    connect(newEmptyAction_, &QAction::triggered, this, &MainWindow::newEmptyScene);
    newAction_ = make(tr("New &Figure 1 scene"), "newAction");
    newAction_->setStatusTip(tr("The paper's Figure 1: four teapots, mirror to diffuse, under the courtyard"));
    connect(newAction_, &QAction::triggered, this, &MainWindow::newScene);
    openAction_ = make(tr("&Open scene…"), "openAction");
    openAction_->setShortcuts(QKeySequence::Open);
    connect(openAction_, &QAction::triggered, this, &MainWindow::openSceneDialog);
    saveAction_ = make(tr("&Save scene"), "saveAction");
    saveAction_->setShortcuts(QKeySequence::Save);
    connect(saveAction_, &QAction::triggered, this, &MainWindow::save);
    saveAsAction_ = make(tr("Save scene &as…"), "saveAsAction");
    saveAsAction_->setShortcuts(QKeySequence::SaveAs);
    connect(saveAsAction_, &QAction::triggered, this, &MainWindow::saveAs);
    openEnvironmentAction_ = make(tr("Open &environment…"), "openEnvironmentAction");
    openEnvironmentAction_->setShortcut(QKeySequence(tr("Ctrl+E")));
    connect(openEnvironmentAction_, &QAction::triggered, this, &MainWindow::openEnvironmentDialog);
    openEnvironmentFolderAction_ = make(tr("Open environment &folder…"), "openEnvironmentFolderAction");
    connect(openEnvironmentFolderAction_, &QAction::triggered, this, &MainWindow::openEnvironmentFolderDialog);
    importMeshAction_ = make(tr("&Import mesh…"), "importMeshAction");
    importMeshAction_->setShortcut(QKeySequence(tr("Ctrl+I")));
    connect(importMeshAction_, &QAction::triggered, this, &MainWindow::importMeshDialog);
    exportImageAction_ = make(tr("E&xport image…"), "exportImageAction");
    connect(exportImageAction_, &QAction::triggered, this, &MainWindow::exportImageDialog);
    quitAction_ = make(tr("&Quit"), "quitAction");
    quitAction_->setShortcuts(QKeySequence::Quit);
    connect(quitAction_, &QAction::triggered, this, &QWidget::close);

    // The stack keeps their text ("Undo Change λ of Gold") and enabled state.
    undoAction_ = document_->undoStack()->createUndoAction(this);
    undoAction_->setObjectName(QStringLiteral("undoAction"));
    undoAction_->setShortcuts(QKeySequence::Undo);
    redoAction_ = document_->undoStack()->createRedoAction(this);
    redoAction_->setObjectName(QStringLiteral("redoAction"));
    redoAction_->setShortcuts(QKeySequence::Redo);
    duplicateAction_ = make(tr("&Duplicate"), "duplicateAction");
    duplicateAction_->setShortcut(QKeySequence(tr("Ctrl+D")));
    connect(duplicateAction_, &QAction::triggered, this, &MainWindow::duplicateSelected);
    removeAction_ = make(tr("&Remove"), "removeAction");
    // Delete removes only while the scene list has the focus (SceneListPanel), never while typing
    // in a spin box.
    removeAction_->setShortcut(QKeySequence::Delete);
    removeAction_->setShortcutContext(Qt::WidgetWithChildrenShortcut);
    connect(removeAction_, &QAction::triggered, this, &MainWindow::removeSelected);

    // Window-wide (not only while the view has the focus, which a click in it would take by
    // selecting or deselecting); a text field keeps its letters (it accepts the shortcut override).
    frameSelectedAction_ = make(tr("Frame &selected"), "frameSelectedAction");
    frameSelectedAction_->setShortcut(QKeySequence(Qt::Key_F));
    frameSelectedAction_->setToolTip(tr("Frame the selected object (all objects when none is selected) (F)"));
    connect(frameSelectedAction_, &QAction::triggered, this, &MainWindow::frameSelected);
    frameAllAction_ = make(tr("&Frame all"), "frameAllAction");
    frameAllAction_->setShortcut(QKeySequence(Qt::Key_A));
    frameAllAction_->setToolTip(tr("Frame every object (A)"));
    connect(frameAllAction_, &QAction::triggered, this, &MainWindow::frameAll);
    resetViewAction_ = make(tr("&Reset view"), "resetViewAction");
    resetViewAction_->setShortcut(QKeySequence(Qt::Key_Home));
    resetViewAction_->setToolTip(tr("The default view angle and field of view, framing every object (Home)"));
    connect(resetViewAction_, &QAction::triggered, this, &MainWindow::resetView);
    turntableAction_ = make(tr("&Turntable"), "turntableAction");
    turntableAction_->setCheckable(true);
    turntableAction_->setShortcut(QKeySequence(Qt::Key_T));
    turntableAction_->setToolTip(tr("Turn the objects or the environment continuously (T)"));
    connect(turntableAction_, &QAction::toggled, viewport_, &Viewport::setTurntableRunning);
    shortcutsAction_ = make(tr("&Keyboard and mouse shortcuts"), "shortcutsAction");
    shortcutsAction_->setShortcut(QKeySequence::HelpContents);
    connect(shortcutsAction_, &QAction::triggered, this, &MainWindow::showShortcuts);
    showCountersAction_ = make(tr("Show &counters overlay"), "showCountersAction");
    showCountersAction_->setCheckable(true);
    connect(showCountersAction_, &QAction::toggled, viewport_, &Viewport::setShowCounters);
}

namespace {
// A panel in a vertical scroll area, so a tall panel (a layered material's editor) scrolls inside its
// dock instead of making the window taller than a laptop's screen.
QScrollArea* scrollable(QWidget* panel, QWidget* parent) {
    auto* area = new QScrollArea(parent);
    area->setObjectName(panel->objectName() + QStringLiteral("Scroll"));
    area->setWidget(panel);
    area->setWidgetResizable(true);
    area->setFrameShape(QFrame::NoFrame);
    // Narrowable: a dock narrower than the panel scrolls sideways rather than holding the view
    // to a fixed width; it opens as wide as the panel wants (createDocks).
    area->setHorizontalScrollBarPolicy(Qt::ScrollBarAsNeeded);
    area->setMinimumWidth(160);
    return area;
}
}  // namespace

void MainWindow::createDocks() {
    // One column on the right, as in Blender and Toolbag: the scene list above, the material, its
    // library and the environment as tabs below, so the view keeps the rest of the window.
    auto* sceneDock = new QDockWidget(tr("Scene"), this);
    sceneDock->setObjectName(QStringLiteral("sceneDock"));
    auto* scenePanel = new SceneListPanel(document_, {duplicateAction_, removeAction_, frameAllAction_}, sceneDock);
    sceneList_ = scenePanel->list();
    sceneDock->setWidget(scenePanel);
    addDockWidget(Qt::RightDockWidgetArea, sceneDock);

    auto* materialDock = new QDockWidget(tr("Material"), this);
    materialDock->setObjectName(QStringLiteral("materialDock"));
    materialPanel_ = new MaterialPanel(document_, materialDock);
    materialDock->setWidget(scrollable(materialPanel_, materialDock));
    addDockWidget(Qt::RightDockWidgetArea, materialDock);

    auto* environmentDock = new QDockWidget(tr("Environment"), this);
    environmentDock->setObjectName(QStringLiteral("environmentDock"));
    environmentPanel_ = new EnvironmentPanel(document_, environments_, environmentDock);
    connect(environmentPanel_, &EnvironmentPanel::openRequested, this, &MainWindow::openEnvironmentDialog);
    environmentDock->setWidget(scrollable(environmentPanel_, environmentDock));
    addDockWidget(Qt::RightDockWidgetArea, environmentDock);
    splitDockWidget(sceneDock, materialDock, Qt::Vertical);
    tabifyDockWidget(materialDock, environmentDock);

    // The library: beside the material panel, tabbed, so a material and its library are one click
    // apart. A library that cannot be read is refused (its file left alone) and the dock says so.
    library_ = new LibraryDocument(document_->undoStack(), this);
    libraryDock_ = new LibraryDock(library_, document_, environments_, this);
    // Its messages are about library files (message_bar.h: Kind).
    connect(libraryDock_, &LibraryDock::messageShown, this, [this](const QString& message, bool error) {
        messages_->showMessageOf(MessageBar::Kind::Library, message, error);
    });
    addDockWidget(Qt::RightDockWidgetArea, libraryDock_);
    tabifyDockWidget(materialDock, libraryDock_);
    materialDock->raise();
    // A new user (no library file yet) starts with the starter materials.
    if (!library_->open(defaultLibraryPath(), starterLibrary()))
        messages_->showMessage(tr("Your material library could not be read, so it is left as it is: %1")
                        .arg(library_->lastError()),
                    true);

    // The viewport gets most of the window: the column as wide as the material panel wants.
    const int column = std::clamp(std::max(materialPanel_->sizeHint().width(), environmentPanel_->sizeHint().width()) +
                                      QApplication::style()->pixelMetric(QStyle::PM_ScrollBarExtent) + 8,
                                  260, 440);
    resizeDocks({materialDock}, {column}, Qt::Horizontal);
    resizeDocks({sceneDock, materialDock}, {160, 600}, Qt::Vertical);
}

void MainWindow::createMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(newEmptyAction_);
    file->addAction(newAction_);
    file->addAction(openAction_);
    auto* recent = new RecentFilesMenu(session_, file);
    connect(recent, &RecentFilesMenu::fileChosen, this, &MainWindow::openRecentFile);
    file->addMenu(recent);
    file->addAction(saveAction_);
    file->addAction(saveAsAction_);
    file->addSeparator();
    file->addAction(openEnvironmentAction_);
    file->addAction(openEnvironmentFolderAction_);
    file->addAction(importMeshAction_);
    file->addAction(exportImageAction_);
    file->addSeparator();
    file->addAction(libraryDock_->importLibraryAction());
    file->addAction(libraryDock_->exportLibraryAction());
    file->addSeparator();
    file->addAction(quitAction_);

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    edit->addAction(undoAction_);
    edit->addAction(redoAction_);
    edit->addSeparator();
    edit->addAction(duplicateAction_);
    edit->addAction(removeAction_);

    QMenu* view = menuBar()->addMenu(tr("&View"));
    view->addAction(frameSelectedAction_);
    view->addAction(frameAllAction_);
    view->addAction(resetViewAction_);
    // The glTF files' own cameras (SceneDocument::fileCameraViews), listed as the menu opens so
    // it follows imports, undo and opened scenes.
    QMenu* lookThrough = view->addMenu(tr("&Look through"));
    lookThrough->setObjectName(QStringLiteral("lookThroughMenu"));
    lookThrough->setToolTip(tr("Look through a camera the imported files hold"));
    lookThrough->setToolTipsVisible(true);
    connect(lookThrough, &QMenu::aboutToShow, this, [this, lookThrough] { fillLookThroughMenu(lookThrough); });
    view->addSeparator();
    view->addAction(turntableAction_);
    view->addAction(showCountersAction_);
    view->addSeparator();
    for (QDockWidget* dock : findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly))
        view->addAction(dock->toggleViewAction());

    QMenu* help = menuBar()->addMenu(tr("&Help"));
    help->addAction(shortcutsAction_);
    QAction* about = help->addAction(tr("&About mipgloss"));
    about->setObjectName(QStringLiteral("aboutAction"));
    connect(about, &QAction::triggered, this, [this] {
        QMessageBox::about(this, tr("About mipgloss"),
                           tr("<b>mipgloss %1</b><p>Blurry, glossy and diffuse reflections from one "
                              "cube-map mip chain, after Ashikhmin &amp; Ghosh, <i>Simple Blurry "
                              "Reflections with Environment Maps</i> (2002).</p>")
                               .arg(QCoreApplication::applicationVersion()));
    });
}

void MainWindow::createViewToolBar() {
    viewToolBar_ = new ViewToolBar(viewport_, document_, library_,
                                   {frameSelectedAction_, frameAllAction_, resetViewAction_}, turntableAction_, this);
    addToolBar(Qt::TopToolBarArea, viewToolBar_);
    connect(viewToolBar_, &ViewToolBar::chooseComparedEnvironment, this, [this] {
        const QString path = QFileDialog::getOpenFileName(this, tr("Compare with environment"),
                                                          session_->lastDirectory(), environmentImagesFilter());
        if (!path.isEmpty()) viewToolBar_->compareEnvironment(path);
    });
    // The comparison's environment is read by its own manager: its failures are shown too.
    connect(viewport_, &Viewport::comparisonFailed, this,
            [this](const QString& message) { messages_->showMessage(tr("Comparison: %1").arg(message), true); });
    // A texture map that cannot be read is drawn without: said, not an error (nothing is lost).
    connect(viewport_, &Viewport::textureWarnings, this,
            [this](const QStringList& warnings) { messages_->showMessage(warnings.join(QLatin1Char('\n')), false); });
}

void MainWindow::restoreLayout() {
    const std::unique_ptr<QSettings> settings = userSettings();
    const QByteArray geometry = settings->value(QStringLiteral("window/geometry")).toByteArray();
    const QByteArray state = settings->value(QStringLiteral("window/state")).toByteArray();
    if (!geometry.isEmpty() && restoreGeometry(geometry)) {
        if (!state.isEmpty()) restoreState(state, kLayoutVersion);
        return;
    }
    // First start: most of the screen, maximised where the window manager does that.
    if (const QScreen* screen = this->screen()) {
        const QRect available = screen->availableGeometry();
        resize(std::min(available.width(), 1600), std::min(available.height(), 1000));
    } else {
        resize(1280, 800);
    }
    setWindowState(windowState() | Qt::WindowMaximized);
}

void MainWindow::saveLayout() const {
    const std::unique_ptr<QSettings> settings = userSettings();
    settings->setValue(QStringLiteral("window/geometry"), saveGeometry());
    settings->setValue(QStringLiteral("window/state"), saveState(kLayoutVersion));
}

void MainWindow::createStatusBar() {
    // The message line (createCentre: MessageBar) takes the room these leave.
    new StatusIndicators(statusBar(), document_, environments_, importer_, this);
    connect(importer_, &MeshImporter::backgroundStarted, this, [this](int files) {
        messages_->showMessage(tr("Importing %n mesh(es)…", nullptr, files), false);
    });
    sendFieldUndoKeysToDocument();
}

void MainWindow::setDefaultPrompts() {
    prompts_.saveChanges = [this](const QString& name) {
        QMessageBox box(QMessageBox::Warning, tr("mipgloss"), tr("Save the changes to %1?").arg(name),
                        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, this);
        box.setObjectName(QStringLiteral("saveChangesBox"));
        box.setInformativeText(tr("Changes you do not save are lost."));
        box.setDefaultButton(QMessageBox::Save);
        switch (box.exec()) {
            case QMessageBox::Save: return SaveChoice::Save;
            case QMessageBox::Discard: return SaveChoice::Discard;
            default: return SaveChoice::Cancel;
        }
    };
    prompts_.saveFileName = [this](const QString& suggestion) {
        return QFileDialog::getSaveFileName(this, tr("Save scene as"), suggestion,
                                            tr("mipgloss scenes (*.mipgloss)"));
    };
    prompts_.restoreAutosave = [this](const QString& question) {
        QMessageBox box(QMessageBox::Question, tr("mipgloss"), question, QMessageBox::NoButton, this);
        box.setObjectName(QStringLiteral("restoreAutosaveBox"));
        QPushButton* restore = box.addButton(tr("Restore"), QMessageBox::AcceptRole);
        box.addButton(QMessageBox::Discard);
        box.setDefaultButton(restore);
        box.exec();
        return box.clickedButton() == restore;
    };
}

// ---------------------------------------------------------------------------------------------
// Files: what the session says, and the questions it needs answered (scene_file_session.h)

void MainWindow::connectSession() {
    setWindowTitle(session_->windowTitle());
    connect(session_, &SceneFileSession::titleChanged, this, &QWidget::setWindowTitle);
    connect(session_, &SceneFileSession::modifiedChanged, this, &QWidget::setWindowModified);
    connect(session_, &SceneFileSession::sceneReplaced, this, &MainWindow::showSceneCamera);
    connect(session_, &SceneFileSession::openReported, this, [this](const QString& message, bool error) {
        messages_->showMessageOf(MessageBar::Kind::Scene, message, error);
    });
    connect(session_, &SceneFileSession::messageShown, this,
            [this](const QString& message, bool error) { messages_->showMessage(message, error); });
}

bool MainWindow::maybeSave() {
    if (!session_->isModified()) return true;
    switch (prompts_.saveChanges(session_->displayName())) {
        case SaveChoice::Save: return save();
        case SaveChoice::Discard: return true;
        case SaveChoice::Cancel: break;
    }
    return false;
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (!maybeSave()) {
        event->ignore();
        return;
    }
    // A clean exit: the work is saved or knowingly dropped.
    saveLayout();
    session_->endCleanly();
    event->accept();
}

bool MainWindow::newScene() {
    if (!maybeSave()) return false;
    session_->startNew(makeFigure1Scene());
    messages_->showMessage(tr("New scene: Figure 1"), false);
    return true;
}

bool MainWindow::newEmptyScene() {
    if (!maybeSave()) return false;
    Scene scene;
    scene.environment = document_->scene().environment;
    scene.display = document_->scene().display;
    session_->startNew(std::move(scene));
    messages_->showMessage(tr("New scene: import meshes (File → Import mesh, or drop them on the window)"), false);
    return true;
}

void MainWindow::showSceneCamera() {
    if (const std::optional<OrbitCamera>& camera = document_->scene().camera)
        viewport_->setCamera(*camera);
    else
        viewport_->resetView();
}

Scene MainWindow::sceneWithView() const {
    Scene scene = document_->scene();
    scene.camera = viewport_->camera();
    return scene;
}

bool MainWindow::openScene(const QString& path) { return maybeSave() && session_->open(path); }

bool MainWindow::openRecentFile(const QString& path) { return session_->recentFileExists(path) && openScene(path); }

bool MainWindow::save() { return session_->file().isEmpty() ? saveAs() : saveScene(session_->file()); }

bool MainWindow::saveAs() {
    const QString path =
        withSuffix(prompts_.saveFileName(session_->saveAsSuggestion()), QString::fromLatin1(kSceneSuffix));
    if (path.isEmpty()) return false;
    return saveScene(path);
}

bool MainWindow::saveScene(const QString& path) { return session_->saveTo(path); }

bool MainWindow::offerAutosaveRestore() {
    const std::optional<Autosave::Leftover> newest = SceneFileSession::newestLeftover();
    if (!newest) return false;
    if (!prompts_.restoreAutosave(SceneFileSession::restoreQuestion(*newest))) {
        Autosave::remove(*newest);
        return false;
    }
    if (!maybeSave() || !session_->restore(*newest)) return false;
    viewport_->frameAll();
    return true;
}

// ---------------------------------------------------------------------------------------------
// Actions

bool MainWindow::openEnvironment(const QString& path) {
    if (!environmentRequests_->open(path)) return false;
    session_->noteDirectoryOf(path);
    return true;
}

void MainWindow::importMeshes(const QStringList& paths) { importer_->import(paths); }

bool MainWindow::openMeshes(const QStringList& paths, bool askFirst) {
    if (paths.isEmpty() || (askFirst && !maybeSave())) return false;
    // The objects go in finishImport, in the import's own undo step, and only if a mesh was read:
    // a file that fails leaves the scene as it was.
    openingMeshes_ = true;
    importer_->import(paths, MeshImporter::Placement::ReplaceObjects);
    return true;
}

void MainWindow::finishImport(const QStringList& added, const QStringList& errors) {
    if (openingMeshes_ && !added.isEmpty()) {
        // openMeshes: the imported objects are a new, untitled scene (the import's undo step
        // holds the objects they replaced).
        openingMeshes_ = false;
        session_->detachFromFile();
    }
    openingMeshes_ = false;
    if (!added.isEmpty()) viewport_->frameAll();
    if (!errors.isEmpty())
        messages_->showMessageOf(MessageBar::Kind::Meshes, (errors + importer_->warnings()).join(QLatin1Char('\n')),
                                 true);
    else if (!added.isEmpty())
        messages_->showMessageOf(MessageBar::Kind::Meshes,
                      (QStringList{tr("Imported %1").arg(added.join(QStringLiteral(", ")))} + importer_->warnings())
                          .join(QLatin1Char('\n')),
                      false);
    emit importFinished(static_cast<int>(added.size()));
}

bool MainWindow::exportImage(const QString& path, QSize size) {
    if (size == QSize()) size = devicePixelSize(*viewport_);  // the view's own pixels
    try {
        const ExportedImage image = exportViewImage(*viewport_, path, size, document_->scene().display.showBackground);
        session_->noteDirectoryOf(path);
        messages_->showMessage(tr("Exported %1 (%2×%3%4)")
                                   .arg(QFileInfo(path).fileName())
                                   .arg(image.size.width())
                                   .arg(image.size.height())
                                   .arg(image.linear ? tr(", linear float") : QString()),
                               false);
        return true;
    } catch (const FileError& e) {
        messages_->showMessage(QString::fromStdString(e.what()), true);
    } catch (const std::exception& e) {
        messages_->showMessage(path + QStringLiteral(": ") + QString::fromStdString(e.what()), true);
    }
    return false;
}

void MainWindow::fillLookThroughMenu(QMenu* menu) {
    menu->clear();
    const std::vector<SceneDocument::CameraView> views = document_->fileCameraViews();
    if (views.empty()) {
        QAction* none = menu->addAction(tr("No cameras in the scene's files"));
        none->setEnabled(false);
        return;
    }
    for (const SceneDocument::CameraView& v : views) {
        QAction* action = menu->addAction(v.label);
        const OrbitCamera camera = v.view;
        connect(action, &QAction::triggered, this, [this, camera, label = v.label] {
            viewport_->setCamera(camera);
            messages_->showMessage(tr("Looking through %1").arg(label), false);
        });
    }
}

void MainWindow::frameAll() { viewport_->frameAll(); }

void MainWindow::frameSelected() { viewport_->frameSelected(); }

void MainWindow::resetView() { viewport_->resetView(); }

void MainWindow::showShortcuts() {
    QList<QAction*> actions;
    for (QAction* a : findChildren<QAction*>()) actions.append(a);
    // In menu order: the menus' own lists, then whatever else has keys.
    QList<QAction*> ordered;
    for (QAction* menu : menuBar()->actions())
        if (menu->menu())
            for (QAction* a : menu->menu()->actions()) {
                if (a->menu())
                    for (QAction* sub : a->menu()->actions()) ordered.append(sub);
                else
                    ordered.append(a);
            }
    for (QAction* a : actions)
        if (!ordered.contains(a)) ordered.append(a);
    ShortcutsDialog dialog(ordered, this);
    dialog.exec();
}

void MainWindow::removeSelected() { document_->removeObject(document_->selected()); }

void MainWindow::duplicateSelected() {
    if (document_->duplicateObject(document_->selected()) >= 0) viewport_->frameAll();
}

// ---------------------------------------------------------------------------------------------
// Dialogs

void MainWindow::openSceneDialog() {
    // Asked before the file dialog, as every other application does.
    if (!maybeSave()) return;
    const QStringList paths = QFileDialog::getOpenFileNames(
        this, tr("Open a scene, or meshes as a new scene"), session_->lastDirectory(),
        tr("Scenes, meshes and assets (%1 %2);;mipgloss scenes (%1);;Meshes and assets (%2)")
            .arg(dialogPatternsOf(FileKind::Scene), dialogPatternsOf(FileKind::Mesh)));
    if (paths.isEmpty()) return;
    QStringList meshes;
    for (const QString& path : paths)
        if (fileKindOf(path) == FileKind::Mesh) meshes << path;
    if (meshes.isEmpty())
        session_->open(paths.front());
    else
        openMeshes(meshes, /*askFirst=*/false);  // asked above, before the file dialog
}

void MainWindow::openEnvironmentDialog() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open environment (a lat-long, cross or strip image, or one face of six)"), session_->lastDirectory(),
        environmentImagesFilter());
    if (!path.isEmpty()) openEnvironment(path);
}

void MainWindow::openEnvironmentFolderDialog() {
    const QString dir =
        QFileDialog::getExistingDirectory(this, tr("Folder with six face images"), session_->lastDirectory());
    if (!dir.isEmpty()) openEnvironment(dir);
}

void MainWindow::importMeshDialog() {
    const QStringList paths =
        QFileDialog::getOpenFileNames(this, tr("Import meshes"), session_->lastDirectory(),
                                      tr("Meshes and assets (%1);;All files (*)").arg(dialogPatternsOf(FileKind::Mesh)));
    importMeshes(paths);
}

void MainWindow::exportImageDialog() {
    ExportImageDialog options(devicePixelSize(*viewport_), viewport_->maxRenderSize(), this);
    if (options.exec() != QDialog::Accepted) return;
    const bool exr = options.format() == ExportImageDialog::Format::Exr;
    const QString suffix = exr ? QStringLiteral("exr") : QStringLiteral("png");
    const QString path = withSuffix(
        QFileDialog::getSaveFileName(this, tr("Export image"), session_->lastDirectory(),
                                     exr ? tr("OpenEXR images (*.exr)") : tr("PNG images (*.png)")),
        suffix);
    if (!path.isEmpty()) exportImage(path, options.imageSize());
}

// ---------------------------------------------------------------------------------------------
// Drag and drop: scenes open, meshes import, an image or a folder becomes the environment.

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    if (!event->mimeData()->hasUrls()) return;
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile() && fileKindOf(url.toLocalFile()) != FileKind::Unknown) {
            event->acceptProposedAction();
            return;
        }
}

void MainWindow::dropEvent(QDropEvent* event) {
    QStringList paths;
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile()) paths << url.toLocalFile();
    event->acceptProposedAction();
    openFiles(paths);
}

void MainWindow::openFiles(const QStringList& paths, bool meshesOpen) {
    const FilesByKind files = sortByKind(paths);
    // A scene replaces everything, so it goes first; meshes and an environment then add to it.
    if (!files.scene.isEmpty()) openScene(files.scene);
    if (!files.meshes.isEmpty()) {
        if (meshesOpen && files.scene.isEmpty())
            openMeshes(files.meshes);
        else
            importMeshes(files.meshes);
    }
    if (!files.environment.isEmpty()) openEnvironment(files.environment);
    for (const QString& library : files.libraries) libraryDock_->importLibrary(library);
    if (!files.unknown.isEmpty())
        messages_->showMessage(
            tr("Not a scene, mesh or environment (or not found): %1").arg(files.unknown.join(QStringLiteral(", "))),
            true);
}

void MainWindow::sendFieldUndoKeysToDocument() {
    // On the application: the panels' fields come and go (a layered material's editor), and the
    // override goes to whichever has the focus.
    qApp->installEventFilter(new FieldUndoKeys(
        [this](const QWidget* field) {
            return (materialPanel_ && materialPanel_->isAncestorOf(field)) ||
                   (environmentPanel_ && environmentPanel_->isAncestorOf(field));
        },
        this));
}

}  // namespace mipgloss::ui
