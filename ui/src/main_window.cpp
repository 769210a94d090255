#include "mipgloss/ui/main_window.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/mesh.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/material_panel.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_file.h"
#include "mipgloss/ui/scene_list_model.h"
#include "mipgloss/ui/viewport.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QFutureWatcher>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QListView>
#include <QLocale>
#include <QMenuBar>
#include <QMimeData>
#include <QOpenGLContext>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QStatusBar>
#include <QToolButton>
#include <QUrl>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>

#include <algorithm>
#include <functional>
#include <iostream>
#include <memory>

namespace mipgloss::ui {

struct MainWindow::ImportResult {
    QString path;
    std::shared_ptr<const Mesh> mesh;
    QString error;
    std::vector<std::string> warnings;
};

namespace {

enum class DropKind { None, Scene, Mesh, Environment };

// Image formats the environment import reads (OpenImageIO); a directory is a six-face set.
const QStringList kEnvironmentSuffixes = {"exr", "hdr", "png", "jpg", "jpeg", "tif", "tiff", "pfm"};
const int kFaceSizes[] = {64, 128, 256, 512, 1024};

// "128²". (Not "%1²": QString::arg reads the superscript two as a digit of the placeholder.)
QString squared(int size) { return QString::number(size) + QStringLiteral("²"); }

DropKind classify(const QString& path) {
    const QFileInfo info(path);
    if (info.isDir()) return DropKind::Environment;
    const QString suffix = info.suffix().toLower();
    if (suffix == QLatin1String("json")) return DropKind::Scene;
    for (const char* ext : meshExtensions())
        if (QLatin1String(ext + 1) == suffix) return DropKind::Mesh;  // ext is ".obj"
    if (kEnvironmentSuffixes.contains(suffix)) return DropKind::Environment;
    return DropKind::None;
}

QString environmentName(const std::string& source) {
    if (source == kBuiltinEnvironment) return QStringLiteral("courtyard");
    return QFileInfo(QString::fromStdString(source)).fileName();
}

MainWindow::ImportResult loadOne(const QString& path) {
    MainWindow::ImportResult result;
    result.path = path;
    try {
        MeshReport report;
        Mesh mesh = loadMesh(path.toStdString(), &report);
        if (mesh.name.empty()) mesh.name = QFileInfo(path).completeBaseName().toStdString();
        result.mesh = std::make_shared<const Mesh>(std::move(mesh));
        result.warnings = std::move(report.warnings);
    } catch (const MeshError& e) {
        result.error = QString::fromStdString(e.what());
    } catch (const std::exception& e) {  // e.g. out of memory on a huge file
        result.error = path + QStringLiteral(": ") + QString::fromStdString(e.what());
    }
    return result;
}

// The placement rule of main_window.h: scale to the median radius when wildly different, put to
// the right of the visible scene.
Transform placeBeside(const Scene& scene, const Mesh& mesh) {
    std::vector<float> radii;
    for (const SceneObject& o : scene.objects)
        if (o.visible && o.mesh) radii.push_back(o.worldRadius());
    Transform t;
    const float r = mesh.bounds.radius();
    float typical = 0.0f;
    if (!radii.empty()) {
        std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
        typical = radii[radii.size() / 2];
    }
    if (typical > 0.0f && r > 0.0f && (r > 4.0f * typical || r < 0.25f * typical))
        t.scale = typical / r;
    const float placedRadius = r * t.scale;
    glm::vec3 centre(0.0f);
    if (!radii.empty()) {
        const Bounds b = sceneBounds(scene);
        const float gap = 0.2f * (typical > 0.0f ? typical : placedRadius);
        centre = glm::vec3(b.max.x + gap + placedRadius, b.centre().y, b.centre().z);
    }
    t.translation = centre - t.scale * mesh.bounds.centre();
    return t;
}

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
    setObjectName(QStringLiteral("mainWindow"));
    document_ = new SceneDocument(this);
    document_->resetScene(makeFigure1Scene());
    environments_ = new EnvironmentManager(this);
    environments_->watch(document_);

    // Centre: the message banner above the viewport.
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

    auto* sceneDock = new QDockWidget(tr("Scene"), this);
    sceneDock->setObjectName(QStringLiteral("sceneDock"));
    sceneDock->setWidget(buildSceneDock());
    addDockWidget(Qt::LeftDockWidgetArea, sceneDock);

    auto* materialDock = new QDockWidget(tr("Material"), this);
    materialDock->setObjectName(QStringLiteral("materialDock"));
    materialPanel_ = new MaterialPanel(document_, materialDock);
    materialDock->setWidget(materialPanel_);
    addDockWidget(Qt::RightDockWidgetArea, materialDock);

    auto* environmentDock = new QDockWidget(tr("Environment"), this);
    environmentDock->setObjectName(QStringLiteral("environmentDock"));
    environmentDock->setWidget(buildEnvironmentDock());
    addDockWidget(Qt::RightDockWidgetArea, environmentDock);

    // The viewport gets most of the width.
    resizeDocks({sceneDock, materialDock}, {200, 360}, Qt::Horizontal);

    buildMenus();
    buildStatusBar();
    setAcceptDrops(true);

    connect(document_, &SceneDocument::environmentChanged, this, [this] {
        refreshEnvironmentWidgets();
        refreshStatus();
    });
    connect(document_, &SceneDocument::displayChanged, this,
            &MainWindow::refreshEnvironmentWidgets);
    connect(environments_, &EnvironmentManager::environmentReady, this, [this] {
        refreshEnvironmentWidgets();
        refreshStatus();
    });
    connect(environments_, &EnvironmentManager::failed, this, &MainWindow::onEnvironmentFailed);
    connect(viewport_, &Viewport::objectClicked, document_, &SceneDocument::setSelected);
    connect(viewport_, &Viewport::glFailed, this, [this](const QString& message) {
        showMessage(tr("OpenGL: %1").arg(message), true);
    });

    refreshEnvironmentWidgets();
    refreshStatus();
    refreshTitle();
    resize(1280, 800);
}

MainWindow::~MainWindow() {
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
    delete document_;
}

// ---------------------------------------------------------------------------------------------
// Construction

void MainWindow::buildMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("&New scene (Figure 1)"), QKeySequence::New, this, &MainWindow::newScene);
    file->addAction(tr("&Open scene…"), QKeySequence::Open, this, &MainWindow::openSceneDialog);
    file->addAction(tr("Save scene &as…"), QKeySequence::SaveAs, this,
                    &MainWindow::saveSceneDialog);
    file->addSeparator();
    file->addAction(tr("Open &environment…"), QKeySequence(tr("Ctrl+E")), this,
                    &MainWindow::openEnvironmentDialog);
    file->addAction(tr("Open environment &folder…"), this, [this] {
        const QString dir = QFileDialog::getExistingDirectory(
            this, tr("Folder with six face images"), lastDirectory_);
        if (!dir.isEmpty()) openEnvironment(dir);
    });
    file->addAction(tr("&Import mesh…"), QKeySequence(tr("Ctrl+I")), this,
                    &MainWindow::importMeshDialog);
    file->addAction(tr("E&xport image…"), this, &MainWindow::exportImageDialog);
    file->addSeparator();
    file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    edit->addAction(tr("&Duplicate"), QKeySequence(tr("Ctrl+D")), this,
                    &MainWindow::duplicateSelected);

    QMenu* view = menuBar()->addMenu(tr("&View"));
    view->addAction(tr("&Frame all"), QKeySequence(Qt::Key_F), this, &MainWindow::frameAll);
    QAction* counters = view->addAction(tr("Show &counters overlay"));
    counters->setObjectName(QStringLiteral("showCountersAction"));
    counters->setCheckable(true);
    connect(counters, &QAction::toggled, viewport_, &Viewport::setShowCounters);
    view->addSeparator();
    for (QDockWidget* dock : findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly))
        view->addAction(dock->toggleViewAction());
}

QWidget* MainWindow::buildSceneDock() {
    auto* panel = new QWidget(this);
    auto* layout = new QVBoxLayout(panel);
    sceneModel_ = new SceneListModel(document_, this);
    sceneList_ = new QListView(panel);
    sceneList_->setObjectName(QStringLiteral("sceneList"));
    sceneList_->setModel(sceneModel_);
    sceneList_->setSelectionMode(QAbstractItemView::SingleSelection);
    sceneList_->setContextMenuPolicy(Qt::ActionsContextMenu);
    layout->addWidget(sceneList_, 1);

    // Selection, both ways. The model resets on objectsChanged (connected first, in the model),
    // and then the list's selection is put back from the document.
    connect(sceneList_->selectionModel(), &QItemSelectionModel::selectionChanged, this, [this] {
        if (syncingSelection_) return;
        const QModelIndexList rows = sceneList_->selectionModel()->selectedRows();
        document_->setSelected(rows.isEmpty() ? -1 : rows.first().row());
    });
    connect(document_, &SceneDocument::selectionChanged, this, &MainWindow::syncListSelection);
    connect(document_, &SceneDocument::objectsChanged, this, &MainWindow::syncListSelection);

    auto* duplicate = new QAction(tr("Duplicate"), sceneList_);
    duplicate->setObjectName(QStringLiteral("duplicateAction"));
    connect(duplicate, &QAction::triggered, this, &MainWindow::duplicateSelected);
    auto* remove = new QAction(tr("Remove"), sceneList_);
    remove->setObjectName(QStringLiteral("removeAction"));
    // Delete removes only while the list has focus, never while typing in a spin box.
    remove->setShortcut(QKeySequence::Delete);
    remove->setShortcutContext(Qt::WidgetWithChildrenShortcut);
    connect(remove, &QAction::triggered, this, &MainWindow::removeSelected);
    auto* frame = new QAction(tr("Frame all"), sceneList_);
    connect(frame, &QAction::triggered, this, &MainWindow::frameAll);
    sceneList_->addActions({duplicate, remove, frame});

    auto* buttons = new QHBoxLayout;
    for (QAction* action : {duplicate, remove, frame}) {
        auto* button = new QToolButton(panel);
        button->setDefaultAction(action);
        buttons->addWidget(button);
    }
    buttons->addStretch(1);
    layout->addLayout(buttons);
    syncListSelection();
    return panel;
}

QWidget* MainWindow::buildEnvironmentDock() {
    auto* panel = new QWidget(this);
    auto* form = new QFormLayout(panel);

    envSource_ = new QLabel(panel);
    envSource_->setObjectName(QStringLiteral("envSourceLabel"));
    envSource_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    auto* open = new QPushButton(tr("Open…"), panel);
    connect(open, &QPushButton::clicked, this, &MainWindow::openEnvironmentDialog);
    auto* sourceRow = new QHBoxLayout;
    sourceRow->addWidget(envSource_, 1);
    sourceRow->addWidget(open);
    form->addRow(tr("Source"), sourceRow);
    envInfo_ = new QLabel(panel);
    envInfo_->setObjectName(QStringLiteral("envInfoLabel"));
    envInfo_->setWordWrap(true);
    form->addRow(QString(), envInfo_);

    auto editEnvironment = [this](const std::function<void(EnvironmentSettings&)>& edit) {
        EnvironmentSettings s = document_->scene().environment;
        edit(s);
        document_->setEnvironment(s);
    };
    auto editDisplay = [this](const std::function<void(DisplaySettings&)>& edit) {
        DisplaySettings d = document_->scene().display;
        edit(d);
        document_->setDisplay(d);
    };

    builder_ = new QComboBox(panel);
    builder_->setObjectName(QStringLiteral("builderCombo"));
    for (const Builder b : kAllBuilders) builder_->addItem(QString::fromLatin1(builderName(b)));
    connect(builder_, &QComboBox::currentTextChanged, this, [editEnvironment](const QString& name) {
        Builder builder;
        if (parseBuilder(name.toStdString(), builder))
            editEnvironment([&](EnvironmentSettings& s) { s.builder = builder; });
    });
    form->addRow(tr("Mip builder"), builder_);

    faceSize_ = new QComboBox(panel);
    faceSize_->setObjectName(QStringLiteral("faceSizeCombo"));
    for (int size : kFaceSizes) faceSize_->addItem(squared(size), size);
    connect(faceSize_, &QComboBox::currentIndexChanged, this, [this, editEnvironment](int) {
        const int size = faceSize_->currentData().toInt();
        editEnvironment([size](EnvironmentSettings& s) { s.faceSize = size; });
    });
    form->addRow(tr("Face size"), faceSize_);

    handedness_ = new QComboBox(panel);
    handedness_->setObjectName(QStringLiteral("handednessCombo"));
    handedness_->addItem(tr("right-handed (GL)"), static_cast<int>(Handedness::Right));
    handedness_->addItem(tr("left-handed (Irrlicht)"), static_cast<int>(Handedness::Left));
    handedness_->setToolTip(tr("How six face images are oriented (docs/conventions.md, Handedness)"));
    connect(handedness_, &QComboBox::currentIndexChanged, this, [this, editEnvironment](int) {
        const auto h = static_cast<Handedness>(handedness_->currentData().toInt());
        editEnvironment([h](EnvironmentSettings& s) { s.handedness = h; });
    });
    form->addRow(tr("Face images"), handedness_);

    rotation_ = new QSlider(Qt::Horizontal, panel);
    rotation_->setObjectName(QStringLiteral("envRotationSlider"));
    rotation_->setRange(-180, 180);
    rotation_->setToolTip(tr("Turns the environment about +Y (degrees); never rebuilds"));
    connect(rotation_, &QSlider::valueChanged, this, [editEnvironment](int degrees) {
        editEnvironment([degrees](EnvironmentSettings& s) {
            s.rotationDegrees = static_cast<float>(degrees);
        });
    });
    form->addRow(tr("Rotation"), rotation_);

    showBackground_ = new QCheckBox(tr("Show"), panel);
    showBackground_->setObjectName(QStringLiteral("showBackgroundCheck"));
    connect(showBackground_, &QCheckBox::toggled, this, [editDisplay](bool on) {
        editDisplay([on](DisplaySettings& d) { d.showBackground = on; });
    });
    backgroundBlur_ = new QDoubleSpinBox(panel);
    backgroundBlur_->setObjectName(QStringLiteral("backgroundBlurSpin"));
    backgroundBlur_->setPrefix(QStringLiteral("blur λ "));
    backgroundBlur_->setDecimals(2);
    backgroundBlur_->setSingleStep(0.25);
    // The same λ as a material's (phong.h): one meaning under any environment and face size.
    backgroundBlur_->setRange(0.0, kMaxLambda);
    backgroundBlur_->setToolTip(
        tr("The background's blur λ, as a material's: the Phong lobe n = 3·128²·4^−λ − 1, the same "
           "under any environment and face size; 0 is sharp, each +1 makes the lobe twice as "
           "wide"));
    backgroundBlur_->setKeyboardTracking(false);
    connect(backgroundBlur_, &QDoubleSpinBox::valueChanged, this, [editDisplay](double v) {
        editDisplay([v](DisplaySettings& d) { d.backgroundLambda = static_cast<float>(v); });
    });
    auto* backgroundRow = new QHBoxLayout;
    backgroundRow->addWidget(showBackground_);
    backgroundRow->addWidget(backgroundBlur_, 1);
    form->addRow(tr("Background"), backgroundRow);

    exposure_ = new QDoubleSpinBox(panel);
    exposure_->setObjectName(QStringLiteral("exposureSpin"));
    exposure_->setRange(-20.0, 20.0);
    exposure_->setSingleStep(0.5);
    exposure_->setDecimals(1);
    exposure_->setSuffix(QStringLiteral(" EV"));
    exposure_->setKeyboardTracking(false);
    connect(exposure_, &QDoubleSpinBox::valueChanged, this, [editDisplay](double v) {
        editDisplay([v](DisplaySettings& d) { d.exposureEv = static_cast<float>(v); });
    });
    form->addRow(tr("Exposure"), exposure_);

    toneMap_ = new QComboBox(panel);
    toneMap_->setObjectName(QStringLiteral("toneMapCombo"));
    for (ToneMap map : {ToneMap::Linear, ToneMap::Reinhard, ToneMap::Aces})
        toneMap_->addItem(QString::fromLatin1(toneMapName(map)), static_cast<int>(map));
    connect(toneMap_, &QComboBox::currentIndexChanged, this, [this, editDisplay](int) {
        const auto map = static_cast<ToneMap>(toneMap_->currentData().toInt());
        editDisplay([map](DisplaySettings& d) { d.toneMap = map; });
    });
    form->addRow(tr("Tone map"), toneMap_);

    samples_ = new QComboBox(panel);
    samples_->setObjectName(QStringLiteral("samplesCombo"));
    for (int n : {1, 2, 4, 8}) samples_->addItem(n == 1 ? tr("off") : QStringLiteral("%1×").arg(n), n);
    connect(samples_, &QComboBox::currentIndexChanged, this, [this, editDisplay](int) {
        const int n = samples_->currentData().toInt();
        editDisplay([n](DisplaySettings& d) { d.samples = n; });
    });
    form->addRow(tr("Multisampling"), samples_);
    return panel;
}

void MainWindow::buildStatusBar() {
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
}

// ---------------------------------------------------------------------------------------------
// Refreshing widgets from the document and the environment

void MainWindow::refreshEnvironmentWidgets() {
    const EnvironmentSettings& s = document_->scene().environment;
    const DisplaySettings& d = document_->scene().display;
    envSource_->setText(environmentName(s.source));
    envSource_->setToolTip(QString::fromStdString(s.source));

    const QSignalBlocker b1(builder_), b2(faceSize_), b3(handedness_), b4(rotation_),
        b5(showBackground_), b6(backgroundBlur_), b7(exposure_), b8(toneMap_), b9(samples_);
    builder_->setCurrentText(QString::fromLatin1(builderName(s.builder)));
    int sizeIndex = faceSize_->findData(s.faceSize);
    if (sizeIndex < 0) {  // a size from a scene file or the command line
        faceSize_->addItem(squared(s.faceSize), s.faceSize);
        sizeIndex = faceSize_->count() - 1;
    }
    faceSize_->setCurrentIndex(sizeIndex);
    handedness_->setCurrentIndex(handedness_->findData(static_cast<int>(s.handedness)));
    rotation_->setValue(static_cast<int>(std::lround(s.rotationDegrees)));
    showBackground_->setChecked(d.showBackground);
    backgroundBlur_->setValue(d.backgroundLambda);
    backgroundBlur_->setEnabled(d.showBackground);
    exposure_->setValue(d.exposureEv);
    toneMap_->setCurrentIndex(toneMap_->findData(static_cast<int>(d.toneMap)));
    int samplesIndex = samples_->findData(d.samples);
    if (samplesIndex < 0) {
        samples_->addItem(QStringLiteral("%1×").arg(d.samples), d.samples);
        samplesIndex = samples_->count() - 1;
    }
    samples_->setCurrentIndex(samplesIndex);

    if (const auto current = environments_->current()) {
        envInfo_->setText(tr("%1 · %2 · %3 · import %4 s, build %5 s, filtered through level %6 "
                             "of %7%8")
                              .arg(environmentName(current->settings.source))
                              .arg(squared(current->base ? current->base->size() : 0))
                              .arg(QString::fromLatin1(builderName(current->settings.builder)))
                              .arg(current->importSeconds, 0, 'f', 2)
                              .arg(current->buildSeconds, 0, 'f', 2)
                              .arg(current->lastFilteredLevel)
                              .arg(current->levelCount() - 1)
                              .arg(current->irradiance ? tr(", irradiance map") : QString()));
    } else {
        envInfo_->setText(tr("loading…"));
    }
}

void MainWindow::refreshStatus() {
    const auto current = environments_->current();
    const EnvironmentSettings& s = current ? current->settings : document_->scene().environment;
    QString text = QStringLiteral("%1 · %2 · %3")
                       .arg(environmentName(s.source))
                       .arg(squared(current && current->base ? current->base->size() : s.faceSize))
                       .arg(QString::fromLatin1(builderName(s.builder)));
    if (!current) text += tr(" (loading)");
    envStatus_->setText(text);
}

void MainWindow::refreshTitle() {
    const QString name = sceneFile_.isEmpty() ? tr("Figure 1") : QFileInfo(sceneFile_).fileName();
    setWindowTitle(QStringLiteral("mipgloss — %1").arg(name));
}

void MainWindow::syncListSelection() {
    syncingSelection_ = true;
    QItemSelectionModel* selection = sceneList_->selectionModel();
    const int row = document_->selected();
    if (document_->isValidIndex(row))
        selection->setCurrentIndex(sceneModel_->index(row), QItemSelectionModel::ClearAndSelect);
    else
        selection->clearSelection();
    syncingSelection_ = false;
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

void MainWindow::newScene() {
    document_->resetScene(makeFigure1Scene());
    sceneFile_.clear();
    refreshTitle();
    viewport_->frameAll();
    showMessage(tr("New scene: Figure 1"), false);
}

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
    // Keep drawing what was there, and make the document say so again, unless the document has
    // moved on to another environment meanwhile (a newer request is then on its way).
    EnvironmentSettings settings = document_->scene().environment;
    if (settings.source != environments_->lastFailure().source) return;
    if (const auto current = environments_->current()) {
        settings.source = current->settings.source;
        settings.layout = current->settings.layout;
        settings.handedness = current->settings.handedness;
        settings.faceSize = current->settings.faceSize;
        settings.builder = current->settings.builder;
    } else {
        settings = EnvironmentSettings{};  // nothing drawn yet: the embedded default
    }
    document_->setEnvironment(settings);
}

void MainWindow::importMeshes(const QStringList& paths) {
    if (paths.isEmpty()) return;
    std::int64_t bytes = 0;
    for (const QString& path : paths) bytes += QFileInfo(path).size();
    auto loadAll = [paths] {
        std::vector<ImportResult> results;
        for (const QString& path : paths) results.push_back(loadOne(path));
        return results;
    };
    if (bytes <= kBackgroundImportBytes) {
        finishImport(loadAll());
        return;
    }
    ++importsRunning_;
    progress_->setRange(0, 0);  // busy indicator: OpenMesh reports no progress
    progress_->setFormat(tr("importing"));
    progress_->show();
    showMessage(tr("Importing %n mesh(es)…", nullptr, static_cast<int>(paths.size())), false);
    auto* watcher = new QFutureWatcher<std::vector<ImportResult>>(this);
    connect(watcher, &QFutureWatcher<std::vector<ImportResult>>::finished, this, [this, watcher] {
        --importsRunning_;
        progress_->setVisible(importing() || environments_->busy());
        progress_->setRange(0, 100);
        finishImport(watcher->result());
        watcher->deleteLater();
    });
    watcher->setFuture(QtConcurrent::run(loadAll));
}

void MainWindow::finishImport(const std::vector<ImportResult>& results) {
    QStringList errors, added;
    for (const ImportResult& r : results) {
        for (const std::string& w : r.warnings) std::cerr << "mipgloss: " << w << '\n';
        if (!r.mesh) {
            errors << r.error;
            continue;
        }
        SceneObject object;
        object.name = QFileInfo(r.path).completeBaseName().toStdString();
        object.meshSource = QFileInfo(r.path).absoluteFilePath().toStdString();
        object.mesh = r.mesh;
        Material material;
        material.lambda = kImportedLambda;
        material.mode = LookupMode::Reflect;
        object.transform = placeBeside(document_->scene(), *r.mesh);
        document_->addObject(std::move(object), material);
        added << tr("%1 (%2 triangles)")
                     .arg(QFileInfo(r.path).fileName())
                     .arg(QLocale().toString(static_cast<qlonglong>(r.mesh->triangleCount())));
        lastDirectory_ = QFileInfo(r.path).absolutePath();
    }
    if (!added.isEmpty()) viewport_->frameAll();
    if (!errors.isEmpty())
        showMessage(errors.join(QLatin1Char('\n')), true);
    else if (!added.isEmpty())
        showMessage(tr("Imported %1").arg(added.join(QStringLiteral(", "))), false);
    emit importFinished(static_cast<int>(added.size()));
}

bool MainWindow::openScene(const QString& path) {
    try {
        SceneFileReport report;
        Scene scene = loadScene(path.toStdString(), &report);
        document_->resetScene(std::move(scene));
        sceneFile_ = QFileInfo(path).absoluteFilePath();
        lastDirectory_ = QFileInfo(path).absolutePath();
        refreshTitle();
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

bool MainWindow::saveScene(const QString& path) {
    try {
        mipgloss::ui::saveScene(document_->scene(), path.toStdString());
        sceneFile_ = QFileInfo(path).absoluteFilePath();
        lastDirectory_ = QFileInfo(path).absolutePath();
        refreshTitle();
        showMessage(tr("Saved %1").arg(QFileInfo(path).fileName()), false);
        return true;
    } catch (const SceneFileError& e) {
        showMessage(QString::fromStdString(e.what()), true);
    }
    return false;
}

bool MainWindow::exportImage(const QString& path) {
    const QImage image = viewport_->grabFramebuffer();
    if (image.isNull() || !image.save(path)) {
        showMessage(tr("%1: could not write the image").arg(path), true);
        return false;
    }
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
    const QString path = QFileDialog::getOpenFileName(this, tr("Open scene"), lastDirectory_,
                                                      tr("mipgloss scenes (*.json)"));
    if (!path.isEmpty()) openScene(path);
}

void MainWindow::saveSceneDialog() {
    QString path = QFileDialog::getSaveFileName(this, tr("Save scene as"),
                                                sceneFile_.isEmpty() ? lastDirectory_ : sceneFile_,
                                                tr("mipgloss scenes (*.json)"));
    if (path.isEmpty()) return;
    if (QFileInfo(path).suffix().isEmpty()) path += QStringLiteral(".json");
    saveScene(path);
}

void MainWindow::openEnvironmentDialog() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open environment (a lat-long, cross or strip image, or one face of six)"),
        lastDirectory_,
        tr("Environment images (*.exr *.hdr *.png *.jpg *.jpeg *.tif *.tiff *.pfm);;All files (*)"));
    if (!path.isEmpty()) openEnvironment(path);
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
    QString path = QFileDialog::getSaveFileName(this, tr("Export image"), lastDirectory_,
                                                tr("PNG images (*.png)"));
    if (path.isEmpty()) return;
    if (QFileInfo(path).suffix().isEmpty()) path += QStringLiteral(".png");
    exportImage(path);
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
    QStringList meshes, unknown;
    for (const QString& path : paths) {
        switch (classify(path)) {
            case DropKind::Scene: if (scene.isEmpty()) scene = path; break;
            case DropKind::Mesh: meshes << path; break;
            case DropKind::Environment: environment = path; break;
            case DropKind::None: unknown << path; break;
        }
    }
    // A scene replaces everything, so it goes first; meshes and an environment then add to it.
    if (!scene.isEmpty()) openScene(scene);
    if (!meshes.isEmpty()) importMeshes(meshes);
    if (!environment.isEmpty()) openEnvironment(environment);
    if (!unknown.isEmpty())
        showMessage(tr("Not a scene, mesh or environment (or not found): %1")
                        .arg(unknown.join(QStringLiteral(", "))),
                    true);
}

}  // namespace mipgloss::ui
