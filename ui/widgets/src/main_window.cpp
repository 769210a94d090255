#include "mipgloss/ui/main_window.h"

#include "mipgloss/assets/asset.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/scene/mesh.h"
#include "mipgloss/ui/atomic_file.h"
#include "mipgloss/ui/autosave.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/environment_panel.h"
#include "mipgloss/ui/library_dock.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/material_panel.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_file.h"
#include "mipgloss/ui/scene_list_delegate.h"
#include "mipgloss/ui/scene_list_model.h"
#include "mipgloss/ui/view_dialogs.h"
#include "mipgloss/ui/view_toolbar.h"
#include "mipgloss/ui/viewport.h"
#include "mipgloss/io/image_file.h"
#include "mipgloss/ui/recent_files.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QLocale>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QOpenGLContext>
#include <QProgressBar>
#include <QScrollArea>
#include <QScrollBar>
#include <QScreen>
#include <QSettings>
#include <QPushButton>
#include <QStatusBar>
#include <QStyle>
#include <QTimer>
#include <QToolButton>
#include <QUndoStack>
#include <QUrl>
#include <QVBoxLayout>

#include <cmath>
#include <iostream>

namespace mipgloss::ui {

namespace {

enum class DropKind { None, Scene, Library, Mesh, Environment };

// Image formats the environment import reads (OpenImageIO); a directory is a six-face set.
const QStringList kEnvironmentSuffixes = {"exr", "hdr", "png", "jpg", "jpeg", "tif", "tiff", "pfm"};

DropKind classify(const QString& path) {
    const QFileInfo info(path);
    if (info.isDir()) return DropKind::Environment;
    const QString suffix = info.suffix().toLower();
    // Scenes are saved as .mipgloss; .json is what older versions saved. A .mglib is a material
    // library: its materials are imported into the user's library (File → Import library).
    if (suffix == QLatin1String("mipgloss") || suffix == QLatin1String("json")) return DropKind::Scene;
    if (suffix == QLatin1String("mglib")) return DropKind::Library;
    for (const char* ext : importExtensions())
        if (QLatin1String(ext + 1) == suffix) return DropKind::Mesh;  // ext is ".obj"
    if (kEnvironmentSuffixes.contains(suffix)) return DropKind::Environment;
    return DropKind::None;
}

QString withSuffix(QString path, const QString& suffix) {
    if (!path.isEmpty() && QFileInfo(path).suffix().isEmpty()) path += QLatin1Char('.') + suffix;
    return path;
}

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent), autosave_(std::make_unique<Autosave>()) {
    setObjectName(QStringLiteral("mainWindow"));
    document_ = new SceneDocument(this);
    document_->resetScene(makeFigure1Scene());
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

    connect(document_, &SceneDocument::environmentChanged, this, &MainWindow::refreshStatus);
    connect(document_, &SceneDocument::changed, this, &MainWindow::updateModified);
    connect(environments_, &EnvironmentManager::environmentReady, this, &MainWindow::refreshStatus);
    connect(environments_, &EnvironmentManager::failed, this, &MainWindow::onEnvironmentFailed);
    connect(importer_, &MeshImporter::finished, this, &MainWindow::finishImport);
    connect(viewport_, &Viewport::objectClicked, document_, &SceneDocument::setSelected);
    connect(viewport_, &Viewport::glFailed, this, [this](const QString& message) {
        showMessage(tr("OpenGL: %1").arg(message), true);
    });

    autosaveTimer_ = new QTimer(this);
    autosaveTimer_->setInterval(kDefaultAutosaveIntervalMs);
    connect(autosaveTimer_, &QTimer::timeout, this, &MainWindow::autosaveNow);
    autosaveTimer_->start();

    markSaved();
    refreshTitle();
    refreshStatus();
    restoreLayout();
    const QStringList gone = RecentFiles::prune();
    if (!gone.isEmpty())
        showMessage(tr("No longer found, removed from Open Recent: %1").arg(gone.join(QStringLiteral(", "))),
                    false);
}

MainWindow::~MainWindow() {
    // Unsaved work the user never chose to drop keeps its autosave (offered at the next start).
    if (!isWindowModified()) autosave_->discard();
    // GL resources first (the viewport makes its context current), then the worker, then the
    // panels and the model that read the document, and the document last.
    // ~Viewport frees its GL resources itself; the context's aboutToBeDestroyed, emitted later
    // from ~QOpenGLWidget, must not call back into the half-destroyed viewport.
    if (QOpenGLContext* context = viewport_->context()) context->disconnect(viewport_);
    delete viewport_;
    viewport_ = nullptr;
    delete environments_;
    environments_ = nullptr;
    qDeleteAll(findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly));
    delete sceneModel_;
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
    banner_ = new QWidget(centre);
    banner_->setObjectName(QStringLiteral("messageBanner"));
    banner_->setAutoFillBackground(true);
    QPalette bannerPalette = banner_->palette();
    bannerPalette.setColor(QPalette::Window, QColor(0xf8, 0xd7, 0xda));
    bannerPalette.setColor(QPalette::WindowText, QColor(0x58, 0x15, 0x1c));
    banner_->setPalette(bannerPalette);
    auto* bannerLayout = new QHBoxLayout(banner_);
    bannerLayout->setContentsMargins(8, 4, 4, 4);
    bannerText_ = new QLabel(banner_);
    bannerText_->setObjectName(QStringLiteral("messageText"));
    bannerText_->setWordWrap(true);
    bannerText_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    auto* dismiss = new QToolButton(banner_);
    dismiss->setObjectName(QStringLiteral("dismissMessage"));
    dismiss->setText(QStringLiteral("✕"));
    dismiss->setToolTip(tr("Dismiss"));
    dismiss->setAutoRaise(true);
    connect(dismiss, &QToolButton::clicked, banner_, &QWidget::hide);
    bannerLayout->addWidget(bannerText_, 1);
    bannerLayout->addWidget(dismiss, 0, Qt::AlignTop);
    banner_->hide();
    centreLayout->addWidget(banner_);
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
    for (QAction*& recent : recentFileActions_) {
        recent = make(QString(), "recentFileAction");
        recent->setVisible(false);
        connect(recent, &QAction::triggered, this,
                [this, recent] { openRecentFile(recent->data().toString()); });
    }
    clearRecentAction_ = make(tr("&Clear list"), "clearRecentAction");
    connect(clearRecentAction_, &QAction::triggered, this, [this] {
        RecentFiles::clear();
        updateRecentFileActions();
    });
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
    // Delete removes only while the scene list has the focus (createSceneDock), never while typing
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
    sceneDock->setWidget(createSceneDock());
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
    connect(libraryDock_, &LibraryDock::messageShown, this,
            [this](const QString& message, bool error) { showMessage(message, error); });
    addDockWidget(Qt::RightDockWidgetArea, libraryDock_);
    tabifyDockWidget(materialDock, libraryDock_);
    materialDock->raise();
    // A new user (no library file yet) starts with the starter materials.
    if (!library_->open(defaultLibraryPath(), starterLibrary()))
        showMessage(tr("Your material library could not be read, so it is left as it is: %1")
                        .arg(library_->lastError()),
                    true);

    // The viewport gets most of the window: the column as wide as the material panel wants.
    const int column = std::clamp(std::max(materialPanel_->sizeHint().width(), environmentPanel_->sizeHint().width()) +
                                      QApplication::style()->pixelMetric(QStyle::PM_ScrollBarExtent) + 8,
                                  260, 440);
    resizeDocks({materialDock}, {column}, Qt::Horizontal);
    resizeDocks({sceneDock, materialDock}, {160, 600}, Qt::Vertical);
}

QWidget* MainWindow::createSceneDock() {
    auto* panel = new QWidget(this);
    auto* layout = new QVBoxLayout(panel);
    sceneModel_ = new SceneListModel(document_, this);
    sceneList_ = new QListView(panel);
    sceneList_->setObjectName(QStringLiteral("sceneList"));
    sceneList_->setModel(sceneModel_);
    sceneList_->setItemDelegate(new SceneListDelegate(sceneList_));
    sceneList_->setSelectionMode(QAbstractItemView::SingleSelection);
    sceneList_->setContextMenuPolicy(Qt::ActionsContextMenu);
    // Library materials dropped onto a row (SceneListModel::dropMimeData).
    sceneList_->setDragDropMode(QAbstractItemView::DropOnly);
    sceneList_->setDefaultDropAction(Qt::CopyAction);
    sceneList_->setDropIndicatorShown(true);
    layout->addWidget(sceneList_, 1);

    // Selection, both ways. The model moves rows rather than resetting, and the document hands a
    // removed object's selection on before removing it, so the list's selection never changes
    // behind the document's back; each direction sets the other only when it differs, so the
    // round trip ends there.
    connect(sceneList_->selectionModel(), &QItemSelectionModel::selectionChanged, this, [this] {
        const QModelIndexList rows = sceneList_->selectionModel()->selectedRows();
        document_->setSelected(rows.isEmpty() ? -1 : rows.first().row());
    });
    connect(document_, &SceneDocument::selectionChanged, this, &MainWindow::showSelectionInList);

    sceneList_->addActions({duplicateAction_, removeAction_, frameAllAction_});
    auto* buttons = new QHBoxLayout;
    for (QAction* action : {duplicateAction_, removeAction_, frameAllAction_}) {
        auto* button = new QToolButton(panel);
        button->setDefaultAction(action);
        buttons->addWidget(button);
    }
    buttons->addStretch(1);
    layout->addLayout(buttons);
    showSelectionInList(document_->selected());
    return panel;
}

void MainWindow::createMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(newEmptyAction_);
    file->addAction(newAction_);
    file->addAction(openAction_);
    recentMenu_ = file->addMenu(tr("Open &recent"));
    recentMenu_->setObjectName(QStringLiteral("recentMenu"));
    for (QAction* recent : recentFileActions_) recentMenu_->addAction(recent);
    recentMenu_->addSeparator();
    recentMenu_->addAction(clearRecentAction_);
    connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::updateRecentFileActions);
    updateRecentFileActions();
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
        const QString path = QFileDialog::getOpenFileName(
            this, tr("Compare with environment"), lastDirectory_,
            tr("Environment images (*.exr *.hdr *.png *.jpg *.jpeg *.tif *.tiff *.pfm);;All files (*)"));
        if (!path.isEmpty()) viewToolBar_->compareEnvironment(path);
    });
    // The comparison's environment is read by its own manager: its failures are shown too.
    connect(viewport_, &Viewport::comparisonFailed, this,
            [this](const QString& message) { showMessage(tr("Comparison: %1").arg(message), true); });
    // A texture map that cannot be read is drawn without: said, not an error (nothing is lost).
    connect(viewport_, &Viewport::textureWarnings, this,
            [this](const QStringList& warnings) { showMessageOf(MessageKind::Other, warnings.join(QLatin1Char('\n')), false); });
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
    // The message on the left takes the room the permanent widgets leave (they get theirs first);
    // the environment's status is whole when there is room and cut short (…) when not, so it
    // never sets the window's least width.
    statusMessage_ = makeElidedLabel(this, QStringLiteral("statusMessage"));
    statusMessage_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    statusBar()->addWidget(statusMessage_, 1);
    statusMessageTimer_ = new QTimer(this);
    statusMessageTimer_->setSingleShot(true);
    connect(statusMessageTimer_, &QTimer::timeout, this, [this] { setElidedText(statusMessage_, QString()); });
    envStatus_ = makeElidedLabel(this, QStringLiteral("envStatusLabel"));
    progress_ = new QProgressBar(this);
    progress_->setObjectName(QStringLiteral("envProgress"));
    progress_->setRange(0, 100);
    progress_->setMaximumWidth(220);
    progress_->setTextVisible(true);
    progress_->hide();
    statusBar()->addPermanentWidget(progress_);
    statusBar()->addPermanentWidget(envStatus_);
    connect(environments_, &EnvironmentManager::busyChanged, this, [this](bool busy) {
        progress_->setVisible(busy || importing());
        if (busy) {
            progress_->setRange(0, 100);
            progress_->setValue(0);
        }
    });
    connect(environments_, &EnvironmentManager::progress, this,
            [this](const QString& stage, double fraction) {
                progress_->setRange(0, 100);
                progress_->setFormat(stage + QStringLiteral(" %p%"));
                progress_->setValue(static_cast<int>(std::lround(100.0 * fraction)));
            });
    connect(importer_, &MeshImporter::backgroundStarted, this, [this](int files) {
        // One file: a busy indicator (a file is read whole, with no progress of its own); several:
        // the fraction of files read.
        progress_->setRange(0, files > 1 ? 100 : 0);
        progress_->setValue(0);
        progress_->setFormat(tr("importing"));
        progress_->show();
        showMessage(tr("Importing %n mesh(es)…", nullptr, files), false);
    });
    connect(importer_, &MeshImporter::progress, this, [this](const QString& stage, double fraction) {
        if (progress_->maximum() == 0) return;
        progress_->setFormat(stage + QStringLiteral(" %p%"));
        progress_->setValue(static_cast<int>(std::lround(100.0 * fraction)));
    });
    // The library dock's messages are about library files (showMessageOf's rule); the window's
    // own connection (createDocks) has shown them by the time this one runs.
    Q_ASSERT(libraryDock_);
    connect(libraryDock_, &LibraryDock::messageShown, this,
            [this](const QString&, bool error) { noteOutcome(MessageKind::Library, error); });
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
// Files: modified state, saving, recent files, autosave

QString MainWindow::displayName() const {
    return sceneFile_.isEmpty() ? tr("Untitled") : QFileInfo(sceneFile_).fileName();
}

void MainWindow::refreshTitle() {
    setWindowTitle(QStringLiteral("%1[*] — mipgloss").arg(displayName()));
}

void MainWindow::markSaved() {
    savedScene_ = document_->scene();
    updateModified();
}

void MainWindow::matchesFile(const QString& path) {
    sceneFile_ = QFileInfo(path).absoluteFilePath();
    lastDirectory_ = QFileInfo(path).absolutePath();
    markSaved();
    forgetAutosave();
    RecentFiles::add(sceneFile_);
    updateRecentFileActions();
    refreshTitle();
}

void MainWindow::updateModified() {
    const bool modified = !savedScene_ || document_->scene() != *savedScene_;
    // Back at the saved state (undone to it): the autosave holds nothing worth restoring.
    if (!modified && isWindowModified()) forgetAutosave();
    setWindowModified(modified);
}

void MainWindow::forgetAutosave() {
    autosave_->discard();
    lastAutosaved_.reset();
}

bool MainWindow::maybeSave() {
    if (!isWindowModified()) return true;
    switch (prompts_.saveChanges(displayName())) {
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
    autosaveTimer_->stop();
    forgetAutosave();
    event->accept();
}

bool MainWindow::newScene() {
    if (!maybeSave()) return false;
    showNewScene(makeFigure1Scene());
    sceneFile_.clear();
    markSaved();
    forgetAutosave();
    refreshTitle();
    showMessage(tr("New scene: Figure 1"), false);
    return true;
}

bool MainWindow::newEmptyScene() {
    if (!maybeSave()) return false;
    Scene scene;
    scene.environment = document_->scene().environment;
    scene.display = document_->scene().display;
    showNewScene(std::move(scene));
    sceneFile_.clear();
    markSaved();
    forgetAutosave();
    refreshTitle();
    showMessage(tr("New scene: import meshes (File → Import mesh, or drop them on the window)"), false);
    return true;
}

void MainWindow::showNewScene(Scene scene) {
    const std::optional<OrbitCamera> camera = scene.camera;
    document_->resetScene(std::move(scene));
    if (camera)
        viewport_->setCamera(*camera);
    else
        viewport_->resetView();
}

Scene MainWindow::sceneWithView() const {
    Scene scene = document_->scene();
    scene.camera = viewport_->camera();
    return scene;
}

bool MainWindow::openScene(const QString& path) { return maybeSave() && loadSceneFile(path); }

bool MainWindow::loadSceneFile(const QString& path) {
    try {
        SceneFileReport report;
        Scene scene = loadScene(path.toStdString(), &report);
        showNewScene(std::move(scene));
        matchesFile(path);
        for (const std::string& w : report.warnings) std::cerr << "mipgloss: " << w << '\n';
        if (report.warnings.empty())
            showMessageOf(MessageKind::Scene, tr("Opened %1").arg(QFileInfo(path).fileName()), false);
        else
            showMessageOf(MessageKind::Scene,
                          tr("Opened %1 with warnings:\n%2")
                              .arg(QFileInfo(path).fileName(), QString::fromStdString(report.warnings.front())),
                          false);
        return true;
    } catch (const SceneFileError& e) {
        showMessageOf(MessageKind::Scene, QString::fromStdString(e.what()), true);
    } catch (const std::exception& e) {
        showMessageOf(MessageKind::Scene, path + QStringLiteral(": ") + QString::fromStdString(e.what()), true);
    }
    return false;
}

bool MainWindow::openRecentFile(const QString& path) {
    if (!QFileInfo::exists(path)) {
        RecentFiles::remove(path);
        updateRecentFileActions();
        showMessage(tr("%1: no longer exists; removed from Open Recent").arg(path), true);
        return false;
    }
    return openScene(path);
}

bool MainWindow::save() { return sceneFile_.isEmpty() ? saveAs() : saveScene(sceneFile_); }

bool MainWindow::saveAs() {
    const QString suggestion =
        sceneFile_.isEmpty() ? QFileInfo(lastDirectory_, tr("untitled.mipgloss")).filePath() : sceneFile_;
    const QString path = withSuffix(prompts_.saveFileName(suggestion), QStringLiteral("mipgloss"));
    if (path.isEmpty()) return false;
    return saveScene(path);
}

bool MainWindow::saveScene(const QString& path) {
    try {
        mipgloss::ui::saveScene(sceneWithView(), path.toStdString());
    } catch (const SceneFileError& e) {
        showMessage(QString::fromStdString(e.what()), true);
        return false;
    }
    matchesFile(path);
    showMessage(tr("Saved %1").arg(QFileInfo(path).fileName()), false);
    return true;
}

void MainWindow::updateRecentFileActions() {
    const QStringList files = RecentFiles::files();
    for (std::size_t i = 0; i < recentFileActions_.size(); ++i) {
        QAction* action = recentFileActions_[i];
        const bool used = static_cast<qsizetype>(i) < files.size();
        action->setVisible(used);
        if (!used) continue;
        const QString& file = files.at(static_cast<qsizetype>(i));
        action->setText(tr("&%1 %2").arg(i + 1).arg(QFileInfo(file).fileName()));
        action->setToolTip(file);
        action->setStatusTip(file);
        action->setData(file);
    }
    clearRecentAction_->setEnabled(!files.isEmpty());
    if (recentMenu_) recentMenu_->setEnabled(!files.isEmpty());
}

int MainWindow::autosaveInterval() const { return autosaveTimer_->interval(); }

void MainWindow::setAutosaveInterval(int milliseconds) { autosaveTimer_->setInterval(milliseconds); }

bool MainWindow::autosaveNow() {
    if (!isWindowModified()) return false;
    if (lastAutosaved_ && *lastAutosaved_ == document_->scene()) return false;
    try {
        autosave_->write(document_->scene(), sceneFile_);
    } catch (const FileError& e) {
        // Once per reason, not every minute.
        const QString message = tr("Autosave failed: %1").arg(QString::fromStdString(e.what()));
        if (message != lastAutosaveError_) showMessage(message, true);
        lastAutosaveError_ = message;
        return false;
    }
    lastAutosaved_ = document_->scene();
    lastAutosaveError_.clear();
    return true;
}

bool MainWindow::offerAutosaveRestore() {
    const std::vector<Autosave::Leftover> leftovers = Autosave::leftovers();
    if (leftovers.empty()) return false;
    const Autosave::Leftover& newest = leftovers.front();
    const QString work = newest.sceneFile.isEmpty() ? tr("a scene that was never saved")
                                                    : QFileInfo(newest.sceneFile).fileName();
    const QString question = tr("mipgloss did not close properly last time. Restore the changes to %1 "
                                "autosaved %2?")
                                 .arg(work, QLocale().toString(newest.written, QLocale::ShortFormat));
    if (!prompts_.restoreAutosave(question)) {
        Autosave::remove(newest);
        return false;
    }
    if (!maybeSave()) return false;
    try {
        SceneFileReport report;
        Scene scene = loadScene(newest.file.toStdString(), &report);
        for (const std::string& w : report.warnings) std::cerr << "mipgloss: " << w << '\n';
        showNewScene(std::move(scene));
    } catch (const SceneFileError& e) {
        // Kept: the user may still rescue it by hand, and the message says where it is.
        showMessage(tr("Could not restore the autosave: %1").arg(QString::fromStdString(e.what())), true);
        return false;
    }
    Autosave::remove(newest);
    sceneFile_ = newest.sceneFile;
    savedScene_.reset();  // what is on disk is unknown: modified until saved
    forgetAutosave();
    updateModified();
    refreshTitle();
    viewport_->frameAll();
    showMessage(tr("Restored the autosaved changes to %1").arg(displayName()), false);
    return true;
}

// ---------------------------------------------------------------------------------------------
// Refreshing widgets from the document and the environment

void MainWindow::refreshStatus() {
    const auto current = environments_->current();
    const EnvironmentSettings& s = current ? current->settings : document_->scene().environment;
    QString text = QStringLiteral("%1 · %2 · %3")
                       .arg(environmentDisplayName(s.source))
                       .arg(squaredSize(current && current->base ? current->base->size() : s.faceSize))
                       .arg(QString::fromLatin1(builderName(s.builder)));
    if (!current) text += tr(" (loading)");
    else if (!current->complete()) text += tr(" (building the chain)");
    setElidedText(envStatus_, text);

    // The environment openEnvironment asked for: loaded (drawn, perhaps before its chain), or the
    // document no longer asks for it (undone, another scene opened; a failure is
    // onEnvironmentFailed's). Either way the status bar stops saying it is being opened.
    if (openingEnvironment_.empty()) return;
    const QString name = QFileInfo(QString::fromStdString(openingEnvironment_)).fileName();
    if (current && current->settings.source == openingEnvironment_) {
        openingEnvironment_.clear();
        showMessageOf(MessageKind::Environment, tr("Loaded %1").arg(name), false);
    } else if (document_->scene().environment.source != openingEnvironment_) {
        openingEnvironment_.clear();
        if (statusMessage_->toolTip() == tr("Opening environment %1…").arg(name)) showStatusMessage(QString(), 0);
    }
}

void MainWindow::showSelectionInList(int index) {
    QItemSelectionModel* selection = sceneList_->selectionModel();
    if (document_->isValidIndex(index))
        selection->setCurrentIndex(sceneModel_->index(index), QItemSelectionModel::ClearAndSelect);
    else
        selection->clear();
}

void MainWindow::showMessage(const QString& message, bool error, bool log) {
    lastMessage_ = message;
    lastMessageIsError_ = error;
    if (error) {
        bannerText_->setText(message);
        banner_->show();
        bannerKind_ = MessageKind::Other;  // showMessageOf names the kind
        showStatusMessage(message, 30000);
        if (log) std::cerr << "mipgloss: " << message.toStdString() << '\n';
    } else {
        showStatusMessage(message, 8000);
    }
    emit messageShown(message, error);
}

// ---------------------------------------------------------------------------------------------
// Actions

bool MainWindow::openEnvironment(const QString& path) {
    const QFileInfo info(path);
    if (!info.exists()) {
        showMessageOf(MessageKind::Environment, tr("%1: no such file or folder").arg(path), true);
        return false;
    }
    lastDirectory_ = info.absolutePath();
    EnvironmentSettings settings = document_->scene().environment;
    settings.source = info.absoluteFilePath().toStdString();
    settings.layout = EnvLayout::Auto;
    environments_->forgetFailure();  // an explicit open reads the file again, fixed or not
    openingEnvironment_ = settings.source;
    showMessage(tr("Opening environment %1…").arg(info.fileName()), false);
    statusMessageTimer_->stop();  // said until it is loaded or fails (refreshStatus, onEnvironmentFailed)
    document_->setEnvironment(settings);
    refreshStatus();  // the file drawn already: loaded at once
    return true;
}

void MainWindow::onEnvironmentFailed(const QString& message) {
    openingEnvironment_.clear();
    showMessageOf(MessageKind::Environment, message, true, /*log=*/false);  // the manager logs its failures
    // Keep drawing what was there, and make the document say so again; the step that asked for
    // the file is withdrawn rather than answered by a step of its own (scene_document.h).
    EnvironmentSettings fallback;  // nothing drawn yet: the embedded default
    if (const auto current = environments_->current()) fallback = current->settings;
    document_->withdrawFailedEnvironment(environments_->lastFailure(), fallback);
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
    progress_->setVisible(importing() || environments_->busy());
    progress_->setRange(0, 100);
    if (openingMeshes_ && !added.isEmpty()) {
        // openMeshes: the imported objects are a new, untitled scene (the import's undo step
        // holds the objects they replaced).
        openingMeshes_ = false;
        sceneFile_.clear();
        refreshTitle();
    }
    openingMeshes_ = false;
    if (!added.isEmpty()) viewport_->frameAll();
    if (!errors.isEmpty())
        showMessageOf(MessageKind::Meshes, (errors + importer_->warnings()).join(QLatin1Char('\n')), true);
    else if (!added.isEmpty())
        showMessageOf(MessageKind::Meshes,
                      (QStringList{tr("Imported %1").arg(added.join(QStringLiteral(", ")))} + importer_->warnings())
                          .join(QLatin1Char('\n')),
                      false);
    emit importFinished(static_cast<int>(added.size()));
}

bool MainWindow::exportImage(const QString& path, QSize size) {
    const qreal ratio = viewport_->devicePixelRatio();
    if (size == QSize())  // the view's own pixels
        size = QSize(static_cast<int>(std::lround(viewport_->width() * ratio)),
                     static_cast<int>(std::lround(viewport_->height() * ratio)));
    QByteArray format = QFileInfo(path).suffix().toUpper().toLatin1();
    if (format.isEmpty()) format = "PNG";
    const bool exr = format == "EXR";
    try {
        // Before anything is drawn: a folder that cannot take the file.
        const QFileInfo folder(QFileInfo(path).absolutePath());
        if (!folder.isDir()) throw FileError(path.toStdString(), "its folder does not exist");
        if (!folder.isWritable()) throw FileError(path.toStdString(), "its folder is not writable");
        QString why;
        std::vector<float> hdr;
        const QImage image = viewport_->renderImage(size.width(), size.height(), /*transparent=*/true,
                                                    exr ? &hdr : nullptr, &why);
        if (image.isNull()) throw FileError(path.toStdString(), why.toStdString());
        if (exr) {
            writeFloatChannels(path.toStdString(), image.width(), image.height(), {"R", "G", "B", "A"}, hdr);
        } else {
            // Straight alpha (the tone pass un-premultiplies); opaque where the background shows.
            const QImage out = document_->scene().display.showBackground
                                   ? image.convertToFormat(QImage::Format_RGB888)
                                   : image.convertToFormat(QImage::Format_RGBA8888);
            writeFileAtomically(path.toStdString(),
                                [&](QIODevice& device) { return out.save(&device, format.constData()); });
        }
        lastDirectory_ = QFileInfo(path).absolutePath();
        showMessage(tr("Exported %1 (%2×%3%4)")
                        .arg(QFileInfo(path).fileName())
                        .arg(image.width())
                        .arg(image.height())
                        .arg(exr ? tr(", linear float") : QString()),
                    false);
        return true;
    } catch (const FileError& e) {
        showMessage(QString::fromStdString(e.what()), true);
    } catch (const std::exception& e) {
        showMessage(path + QStringLiteral(": ") + QString::fromStdString(e.what()), true);
    }
    return false;
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
    QStringList meshPatterns;
    for (const char* ext : importExtensions()) meshPatterns << QStringLiteral("*%1").arg(QLatin1String(ext));
    const QStringList paths = QFileDialog::getOpenFileNames(
        this, tr("Open a scene, or meshes as a new scene"), lastDirectory_,
        tr("Scenes, meshes and assets (*.mipgloss *.json %1);;mipgloss scenes (*.mipgloss *.json);;Meshes and assets (%1)")
            .arg(meshPatterns.join(QLatin1Char(' '))));
    if (paths.isEmpty()) return;
    QStringList meshes;
    for (const QString& path : paths)
        if (classify(path) == DropKind::Mesh) meshes << path;
    if (meshes.isEmpty())
        loadSceneFile(paths.front());
    else
        openMeshes(meshes, /*askFirst=*/false);  // asked above, before the file dialog
}

void MainWindow::openEnvironmentDialog() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open environment (a lat-long, cross or strip image, or one face of six)"),
        lastDirectory_,
        tr("Environment images (*.exr *.hdr *.png *.jpg *.jpeg *.tif *.tiff *.pfm);;All files (*)"));
    if (!path.isEmpty()) openEnvironment(path);
}

void MainWindow::openEnvironmentFolderDialog() {
    const QString dir =
        QFileDialog::getExistingDirectory(this, tr("Folder with six face images"), lastDirectory_);
    if (!dir.isEmpty()) openEnvironment(dir);
}

void MainWindow::importMeshDialog() {
    QStringList patterns;
    for (const char* ext : importExtensions()) patterns << QStringLiteral("*%1").arg(QLatin1String(ext));
    const QStringList paths = QFileDialog::getOpenFileNames(
        this, tr("Import meshes"), lastDirectory_,
        tr("Meshes and assets (%1);;All files (*)").arg(patterns.join(QLatin1Char(' '))));
    importMeshes(paths);
}

void MainWindow::exportImageDialog() {
    const qreal ratio = viewport_->devicePixelRatio();
    const QSize viewSize(static_cast<int>(std::lround(viewport_->width() * ratio)),
                         static_cast<int>(std::lround(viewport_->height() * ratio)));
    ExportImageDialog options(viewSize, viewport_->maxRenderSize(), this);
    if (options.exec() != QDialog::Accepted) return;
    const bool exr = options.format() == ExportImageDialog::Format::Exr;
    const QString suffix = exr ? QStringLiteral("exr") : QStringLiteral("png");
    const QString path = withSuffix(
        QFileDialog::getSaveFileName(this, tr("Export image"), lastDirectory_,
                                     exr ? tr("OpenEXR images (*.exr)") : tr("PNG images (*.png)")),
        suffix);
    if (!path.isEmpty()) exportImage(path, options.imageSize());
}

// ---------------------------------------------------------------------------------------------
// Drag and drop: scenes open, meshes import, an image or a folder becomes the environment.

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    if (!event->mimeData()->hasUrls()) return;
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile() && classify(url.toLocalFile()) != DropKind::None) {
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
    QString scene, environment;
    QStringList libraries, meshes, unknown;
    for (const QString& path : paths) {
        switch (classify(path)) {
            case DropKind::Scene: if (scene.isEmpty()) scene = path; break;
            case DropKind::Library: libraries << path; break;
            case DropKind::Mesh: meshes << path; break;
            case DropKind::Environment: environment = path; break;
            case DropKind::None: unknown << path; break;
        }
    }
    // A scene replaces everything, so it goes first; meshes and an environment then add to it.
    if (!scene.isEmpty()) openScene(scene);
    if (!meshes.isEmpty()) {
        if (meshesOpen && scene.isEmpty())
            openMeshes(meshes);
        else
            importMeshes(meshes);
    }
    if (!environment.isEmpty()) openEnvironment(environment);
    for (const QString& library : libraries) libraryDock_->importLibrary(library);
    if (!unknown.isEmpty())
        showMessage(tr("Not a scene, mesh or environment (or not found): %1")
                        .arg(unknown.join(QStringLiteral(", "))),
                    true);
}

// ---------------------------------------------------------------------------------------------
// The banner and the status bar

void MainWindow::showMessageOf(MessageKind kind, const QString& message, bool error, bool log) {
    showMessage(message, error, log);
    noteOutcome(kind, error);
}

void MainWindow::noteOutcome(MessageKind kind, bool error) {
    if (error)
        bannerKind_ = kind;
    else if (kind != MessageKind::Other && bannerKind_ == kind)
        banner_->hide();  // what failed has been done since (main_window.h: MessageKind)
}

void MainWindow::showStatusMessage(const QString& message, int timeoutMs) {
    // One line: an error's first (the banner has the rest), a message's lines joined.
    const QString line = message.contains(QLatin1Char('\n')) && lastMessageIsError_
                             ? message.section(QLatin1Char('\n'), 0, 0)
                             : QString(message).replace(QLatin1Char('\n'), QLatin1Char(' '));
    setElidedText(statusMessage_, line);
    statusMessage_->setToolTip(message);
    if (timeoutMs > 0 && !message.isEmpty())
        statusMessageTimer_->start(timeoutMs);
    else
        statusMessageTimer_->stop();
}

namespace {

// QLabel cuts a long text off at its edge (or, in a layout, makes its least width the whole
// text's). This one shows its text cut short (…) to the width it has, keeps the whole text in its
// tooltip, asks for the whole text's width and gets by with none.
class ElidedLabel : public QLabel {
public:
    using QLabel::QLabel;

    void setWholeText(const QString& text) {
        whole_ = text;
        setToolTip(text);
        updateGeometry();
        elide();
    }

    QSize sizeHint() const override {
        const QMargins m = contentsMargins();
        return {fontMetrics().horizontalAdvance(whole_) + m.left() + m.right() + 2 * margin(),
                QLabel::sizeHint().height()};
    }
    QSize minimumSizeHint() const override { return {0, QLabel::minimumSizeHint().height()}; }

protected:
    void resizeEvent(QResizeEvent* event) override {
        QLabel::resizeEvent(event);
        elide();
    }

private:
    void elide() {
        // elidedText cuts some texts that fit their horizontalAdvance (measured here with a glyph
        // from a fallback font, "²"): given exactly its sizeHint, the label shows the whole text.
        const int room = contentsRect().width() - 2 * margin();
        const QFontMetrics metrics = fontMetrics();
        setText(metrics.horizontalAdvance(whole_) <= room ? whole_ : metrics.elidedText(whole_, Qt::ElideRight, room));
    }

    QString whole_;
};

// The window's Undo and Redo keys in the panels' fields. A focused line edit or spin box takes
// Ctrl+Z and Ctrl+Shift+Z for its own text (it accepts the ShortcutOverride), so Edit → Undo never
// fired while one had the focus. In the Material and Environment panels a field's text history is
// only values the document already has (and undoes), so there the keys are the document's: the
// override is refused and the window's action fires. Typing not yet entered is undone as text
// first, as a user expects of a field being typed in. Fields elsewhere keep their text undo: the
// library's search text is in no document, and its Ctrl+Z should bring back what was typed.
class FieldUndoKeys : public QObject {
public:
    FieldUndoKeys(std::function<bool(const QWidget*)> inPanels, QObject* parent)
        : QObject(parent), inPanels_(std::move(inPanels)) {}

    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() != QEvent::ShortcutOverride) return false;
        const auto* key = static_cast<QKeyEvent*>(event);
        if (!key->matches(QKeySequence::Undo) && !key->matches(QKeySequence::Redo)) return false;
        const auto* field = qobject_cast<QWidget*>(watched);
        if (!field || !(qobject_cast<const QAbstractSpinBox*>(field) || qobject_cast<const QLineEdit*>(field)) ||
            !inPanels_(field) || beingTyped(field))
            return false;
        event->ignore();  // not the field's: the shortcut goes to the window's action
        return true;
    }

private:
    // True while a field shows text it has not handed on: a spin box whose text is not its
    // value's, a line edit edited since it was last set.
    static bool beingTyped(const QWidget* field) {
        if (const auto* spin = qobject_cast<const QDoubleSpinBox*>(field)) {
            const bool special = !spin->specialValueText().isEmpty() && spin->value() == spin->minimum();
            const QString shown =
                special ? spin->specialValueText() : spin->prefix() + spin->textFromValue(spin->value()) + spin->suffix();
            return spin->text() != shown;
        }
        if (const auto* edit = qobject_cast<const QLineEdit*>(field)) return edit->isModified();
        return false;
    }

    std::function<bool(const QWidget*)> inPanels_;
};

}  // namespace

QLabel* MainWindow::makeElidedLabel(QWidget* parent, const QString& objectName) {
    auto* label = new ElidedLabel(parent);
    label->setObjectName(objectName);
    label->setTextFormat(Qt::PlainText);
    return label;
}

void MainWindow::setElidedText(QLabel* label, const QString& text) { static_cast<ElidedLabel*>(label)->setWholeText(text); }

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
