#include "mipgloss/ui/main_window.h"

#include "mipgloss/ibl/builders.h"
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
#include "mipgloss/ui/viewport.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QListView>
#include <QLocale>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QOpenGLContext>
#include <QProgressBar>
#include <QScrollArea>
#include <QScrollBar>
#include <QPushButton>
#include <QStatusBar>
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
    for (const char* ext : meshExtensions())
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
    resize(1280, 800);
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

    newAction_ = make(tr("&New scene (Figure 1)"), "newAction");
    newAction_->setShortcuts(QKeySequence::New);
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

    frameAllAction_ = make(tr("&Frame all"), "frameAllAction");
    frameAllAction_->setShortcut(QKeySequence(Qt::Key_F));
    connect(frameAllAction_, &QAction::triggered, this, &MainWindow::frameAll);
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
    area->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    // As wide as the panel wants, so nothing is cut off sideways.
    area->setMinimumWidth(panel->minimumSizeHint().width() + area->verticalScrollBar()->sizeHint().width());
    return area;
}
}  // namespace

void MainWindow::createDocks() {
    auto* sceneDock = new QDockWidget(tr("Scene"), this);
    sceneDock->setObjectName(QStringLiteral("sceneDock"));
    sceneDock->setWidget(createSceneDock());
    addDockWidget(Qt::LeftDockWidgetArea, sceneDock);

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

    // The viewport gets most of the width.
    resizeDocks({sceneDock, materialDock}, {200, 360}, Qt::Horizontal);
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
    view->addAction(frameAllAction_);
    view->addAction(showCountersAction_);
    view->addSeparator();
    for (QDockWidget* dock : findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly))
        view->addAction(dock->toggleViewAction());
}

void MainWindow::createStatusBar() {
    envStatus_ = new QLabel(this);
    envStatus_->setObjectName(QStringLiteral("envStatusLabel"));
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
    autosaveTimer_->stop();
    forgetAutosave();
    event->accept();
}

bool MainWindow::newScene() {
    if (!maybeSave()) return false;
    document_->resetScene(makeFigure1Scene());
    sceneFile_.clear();
    markSaved();
    forgetAutosave();
    refreshTitle();
    viewport_->frameAll();
    showMessage(tr("New scene: Figure 1"), false);
    return true;
}

bool MainWindow::openScene(const QString& path) { return maybeSave() && loadSceneFile(path); }

bool MainWindow::loadSceneFile(const QString& path) {
    try {
        SceneFileReport report;
        Scene scene = loadScene(path.toStdString(), &report);
        document_->resetScene(std::move(scene));
        matchesFile(path);
        viewport_->frameAll();
        for (const std::string& w : report.warnings) std::cerr << "mipgloss: " << w << '\n';
        if (report.warnings.empty())
            showMessage(tr("Opened %1").arg(QFileInfo(path).fileName()), false);
        else
            showMessage(tr("Opened %1 with warnings:\n%2")
                            .arg(QFileInfo(path).fileName(),
                                 QString::fromStdString(report.warnings.front())),
                        false);
        return true;
    } catch (const SceneFileError& e) {
        showMessage(QString::fromStdString(e.what()), true);
    } catch (const std::exception& e) {
        showMessage(path + QStringLiteral(": ") + QString::fromStdString(e.what()), true);
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
        mipgloss::ui::saveScene(document_->scene(), path.toStdString());
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
        document_->resetScene(std::move(scene));
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
    envStatus_->setText(text);
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
        statusBar()->showMessage(message.section(QLatin1Char('\n'), 0, 0), 30000);
        if (log) std::cerr << "mipgloss: " << message.toStdString() << '\n';
    } else {
        statusBar()->showMessage(message, 8000);
    }
    emit messageShown(message, error);
}

// ---------------------------------------------------------------------------------------------
// Actions

bool MainWindow::openEnvironment(const QString& path) {
    const QFileInfo info(path);
    if (!info.exists()) {
        showMessage(tr("%1: no such file or folder").arg(path), true);
        return false;
    }
    lastDirectory_ = info.absolutePath();
    EnvironmentSettings settings = document_->scene().environment;
    settings.source = info.absoluteFilePath().toStdString();
    settings.layout = EnvLayout::Auto;
    environments_->forgetFailure();  // an explicit open reads the file again, fixed or not
    document_->setEnvironment(settings);
    showMessage(tr("Opening environment %1…").arg(info.fileName()), false);
    return true;
}

void MainWindow::onEnvironmentFailed(const QString& message) {
    showMessage(message, true, /*log=*/false);  // the manager logs its failures
    // Keep drawing what was there, and make the document say so again; the step that asked for
    // the file is withdrawn rather than answered by a step of its own (scene_document.h).
    EnvironmentSettings fallback;  // nothing drawn yet: the embedded default
    if (const auto current = environments_->current()) fallback = current->settings;
    document_->withdrawFailedEnvironment(environments_->lastFailure(), fallback);
}

void MainWindow::importMeshes(const QStringList& paths) { importer_->import(paths); }

void MainWindow::finishImport(const QStringList& added, const QStringList& errors) {
    progress_->setVisible(importing() || environments_->busy());
    progress_->setRange(0, 100);
    if (!added.isEmpty()) viewport_->frameAll();
    if (!errors.isEmpty())
        showMessage(errors.join(QLatin1Char('\n')), true);
    else if (!added.isEmpty())
        showMessage(tr("Imported %1").arg(added.join(QStringLiteral(", "))), false);
    emit importFinished(static_cast<int>(added.size()));
}

bool MainWindow::exportImage(const QString& path) {
    const QImage image = viewport_->grabFramebuffer();
    QByteArray format = QFileInfo(path).suffix().toUpper().toLatin1();
    if (format.isEmpty()) format = "PNG";
    try {
        if (image.isNull()) throw FileError(path.toStdString(), "the view could not be grabbed");
        writeFileAtomically(path.toStdString(),
                            [&](QIODevice& device) { return image.save(&device, format.constData()); });
    } catch (const FileError& e) {
        showMessage(QString::fromStdString(e.what()), true);
        return false;
    }
    lastDirectory_ = QFileInfo(path).absolutePath();
    showMessage(tr("Exported %1 (%2×%3)").arg(QFileInfo(path).fileName()).arg(image.width()).arg(image.height()),
                false);
    return true;
}

void MainWindow::frameAll() { viewport_->frameAll(); }

void MainWindow::removeSelected() { document_->removeObject(document_->selected()); }

void MainWindow::duplicateSelected() {
    if (document_->duplicateObject(document_->selected()) >= 0) viewport_->frameAll();
}

// ---------------------------------------------------------------------------------------------
// Dialogs

void MainWindow::openSceneDialog() {
    // Asked before the file dialog, as every other application does.
    if (!maybeSave()) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Open scene"), lastDirectory_,
                                                      tr("mipgloss scenes (*.mipgloss *.json)"));
    if (!path.isEmpty()) loadSceneFile(path);
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
    for (const char* ext : meshExtensions()) patterns << QStringLiteral("*%1").arg(QLatin1String(ext));
    const QStringList paths = QFileDialog::getOpenFileNames(
        this, tr("Import meshes"), lastDirectory_,
        tr("Meshes (%1);;All files (*)").arg(patterns.join(QLatin1Char(' '))));
    importMeshes(paths);
}

void MainWindow::exportImageDialog() {
    const QString path = withSuffix(
        QFileDialog::getSaveFileName(this, tr("Export image"), lastDirectory_, tr("PNG images (*.png)")),
        QStringLiteral("png"));
    if (!path.isEmpty()) exportImage(path);
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

void MainWindow::openFiles(const QStringList& paths) {
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
    if (!meshes.isEmpty()) importMeshes(meshes);
    if (!environment.isEmpty()) openEnvironment(environment);
    for (const QString& library : libraries) libraryDock_->importLibrary(library);
    if (!unknown.isEmpty())
        showMessage(tr("Not a scene, mesh or environment (or not found): %1")
                        .arg(unknown.join(QStringLiteral(", "))),
                    true);
}

}  // namespace mipgloss::ui
