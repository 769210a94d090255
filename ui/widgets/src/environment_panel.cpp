#include "mipgloss/ui/environment_panel.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/scene_document.h"
#include "edit_sessions.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>

#include <cmath>

namespace mipgloss::ui {

namespace {
const int kFaceSizes[] = {64, 128, 256, 512, 1024};
}

QString environmentDisplayName(const std::string& source) {
    if (source == kBuiltinEnvironment) return QStringLiteral("courtyard");
    return QFileInfo(QString::fromStdString(source)).fileName();
}

// Not "%1²": QString::arg reads the superscript two as a digit of the placeholder.
QString squaredSize(int size) { return QString::number(size) + QStringLiteral("²"); }

EnvironmentPanel::EnvironmentPanel(SceneDocument* document, EnvironmentManager* environments, QWidget* parent)
    : QWidget(parent), document_(document), environments_(environments) {
    setObjectName(QStringLiteral("environmentPanel"));
    sessions_ = new EditSessions(this);
    auto* form = new QFormLayout(this);

    source_ = new QLabel(this);
    source_->setObjectName(QStringLiteral("envSourceLabel"));
    source_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    auto* open = new QPushButton(tr("Open…"), this);
    open->setObjectName(QStringLiteral("openEnvironmentButton"));
    connect(open, &QPushButton::clicked, this, &EnvironmentPanel::openRequested);
    auto* sourceRow = new QHBoxLayout;
    sourceRow->addWidget(source_, 1);
    sourceRow->addWidget(open);
    form->addRow(tr("Source"), sourceRow);
    info_ = new QLabel(this);
    info_->setObjectName(QStringLiteral("envInfoLabel"));
    info_->setWordWrap(true);
    form->addRow(QString(), info_);

    builder_ = new QComboBox(this);
    builder_->setObjectName(QStringLiteral("builderCombo"));
    for (const Builder b : kAllBuilders) builder_->addItem(QString::fromLatin1(builderName(b)));
    builder_->setToolTip(tr("How the environment's blurred levels are made, once per environment "
                            "(docs/builders.md): phong, the default, holds an exact Phong lobe at every "
                            "level, filtered across the cube's faces; box is the paper's 2×2 average "
                            "per face (fast, blocky, lobes that differ by face); paper is the paper's "
                            "own construction with borders; reference is the slow exact filter. "
                            "View → Compare shows two side by side."));
    connect(builder_, &QComboBox::currentTextChanged, this, [this](const QString& name) {
        Builder builder;
        if (parseBuilder(name.toStdString(), builder))
            editEnvironment([&](EnvironmentSettings& s) { s.builder = builder; });
    });
    form->addRow(tr("Mip builder"), builder_);

    faceSize_ = new QComboBox(this);
    faceSize_->setObjectName(QStringLiteral("faceSizeCombo"));
    for (int size : kFaceSizes) faceSize_->addItem(squaredSize(size), size);
    connect(faceSize_, &QComboBox::currentIndexChanged, this, [this](int) {
        const int size = faceSize_->currentData().toInt();
        editEnvironment([size](EnvironmentSettings& s) { s.faceSize = size; });
    });
    faceSize_->setToolTip(tr("The cube's face size in texels: larger keeps more detail for mirrors and "
                             "sharp gloss, and costs four times the memory and build time per step. "
                             "A material's λ means the same blur at any size."));
    form->addRow(tr("Face size"), faceSize_);

    handedness_ = new QComboBox(this);
    handedness_->setObjectName(QStringLiteral("handednessCombo"));
    handedness_->addItem(tr("right-handed (GL)"), static_cast<int>(Handedness::Right));
    handedness_->addItem(tr("left-handed (Irrlicht)"), static_cast<int>(Handedness::Left));
    handedness_->setToolTip(tr("How six face images are oriented (docs/conventions.md, Handedness)"));
    connect(handedness_, &QComboBox::currentIndexChanged, this, [this](int) {
        const auto h = static_cast<Handedness>(handedness_->currentData().toInt());
        editEnvironment([h](EnvironmentSettings& s) { s.handedness = h; });
    });
    form->addRow(tr("Face images"), handedness_);

    rotation_ = new QSlider(Qt::Horizontal, this);
    rotation_->setObjectName(QStringLiteral("envRotationSlider"));
    rotation_->setRange(-180, 180);
    rotation_->setToolTip(tr("Turns the environment about the vertical axis; never rebuilds. In the "
                             "view: Ctrl + left drag, or Shift + right drag"));
    sessions_->track(rotation_);
    connect(rotation_, &QSlider::valueChanged, this, [this](int degrees) {
        editDisplay([degrees](DisplaySettings& d) { d.environmentRotationDegrees = static_cast<float>(degrees); },
                    rotation_);
    });
    rotationDegrees_ = new QDoubleSpinBox(this);
    rotationDegrees_->setObjectName(QStringLiteral("envRotationSpin"));
    rotationDegrees_->setRange(-180.0, 180.0);
    rotationDegrees_->setDecimals(1);
    rotationDegrees_->setWrapping(true);
    rotationDegrees_->setSuffix(QStringLiteral("°"));
    rotationDegrees_->setKeyboardTracking(false);
    rotationDegrees_->setToolTip(rotation_->toolTip());
    sessions_->track(rotationDegrees_);
    connect(rotationDegrees_, &QDoubleSpinBox::valueChanged, this, [this](double degrees) {
        editDisplay([degrees](DisplaySettings& d) { d.environmentRotationDegrees = static_cast<float>(degrees); },
                    rotationDegrees_);
    });
    auto* rotationRow = new QHBoxLayout;
    rotationRow->addWidget(rotation_, 1);
    rotationRow->addWidget(rotationDegrees_);
    form->addRow(tr("Rotation"), rotationRow);

    showBackground_ = new QCheckBox(tr("Show"), this);
    showBackground_->setObjectName(QStringLiteral("showBackgroundCheck"));
    showBackground_->setToolTip(tr("Show the environment behind the objects (sharp, or blurred at its "
                                   "own λ). Hidden, it still lights the scene, and an exported PNG is "
                                   "transparent around the objects."));
    connect(showBackground_, &QCheckBox::toggled, this,
            [this](bool on) { editDisplay([on](DisplaySettings& d) { d.showBackground = on; }); });
    backgroundBlur_ = new QDoubleSpinBox(this);
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
    sessions_->track(backgroundBlur_);
    connect(backgroundBlur_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        editDisplay([v](DisplaySettings& d) { d.backgroundLambda = static_cast<float>(v); }, backgroundBlur_);
    });
    backdrop_ = new QPushButton(this);
    backdrop_->setObjectName(QStringLiteral("backdropButton"));
    backdrop_->setToolTip(tr("The colour behind the objects while the background is hidden, as the screen "
                             "shows it, whatever the exposure and tone map (white for product shots)"));
    connect(backdrop_, &QPushButton::clicked, this, [this] {
        if (!backdropDialog_) {
            backdropDialog_ = new QColorDialog(this);
            backdropDialog_->setObjectName(QStringLiteral("backdropDialog"));
            backdropDialog_->setWindowTitle(tr("Backdrop colour"));
            connect(backdropDialog_, &QColorDialog::colorSelected, this, [this](const QColor& c) {
                const Rgb colour(static_cast<float>(c.redF()), static_cast<float>(c.greenF()), static_cast<float>(c.blueF()));
                editDisplay([colour](DisplaySettings& d) { d.backdrop = colour; });
            });
        }
        const Rgb& now = document_->scene().display.backdrop;
        backdropDialog_->setCurrentColor(QColor::fromRgbF(now.r, now.g, now.b));
        backdropDialog_->open();
    });
    auto* backgroundRow = new QHBoxLayout;
    backgroundRow->addWidget(showBackground_);
    backgroundRow->addWidget(backgroundBlur_, 1);
    backgroundRow->addWidget(backdrop_);
    form->addRow(tr("Background"), backgroundRow);

    exposure_ = new QDoubleSpinBox(this);
    exposure_->setObjectName(QStringLiteral("exposureSpin"));
    exposure_->setRange(-static_cast<double>(kMaxExposureEv), static_cast<double>(kMaxExposureEv));
    exposure_->setSingleStep(0.5);
    exposure_->setDecimals(1);
    exposure_->setSuffix(QStringLiteral(" EV"));
    exposure_->setKeyboardTracking(false);
    exposure_->setToolTip(tr("Brightness of the picture in stops: +1 doubles it. The environment's light "
                             "is not changed, only how it is shown (and exported as PNG; an EXR is "
                             "written before exposure)."));
    sessions_->track(exposure_);
    connect(exposure_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        editDisplay([v](DisplaySettings& d) { d.exposureEv = static_cast<float>(v); }, exposure_);
    });
    form->addRow(tr("Exposure"), exposure_);

    toneMap_ = new QComboBox(this);
    toneMap_->setObjectName(QStringLiteral("toneMapCombo"));
    toneMap_->setToolTip(tr("How light brighter than the screen's white is shown: linear clips it, "
                            "Reinhard and ACES (film-like) roll it off smoothly, PBR Neutral (Khronos, the "
                            "glTF Sample Viewer's) keeps base colours as authored, AgX (Blender's) "
                            "desaturates highlights as film does"));
    for (ToneMap map : kAllToneMaps)
        toneMap_->addItem(QString::fromLatin1(toneMapName(map)), static_cast<int>(map));
    connect(toneMap_, &QComboBox::currentIndexChanged, this, [this](int) {
        const auto map = static_cast<ToneMap>(toneMap_->currentData().toInt());
        editDisplay([map](DisplaySettings& d) { d.toneMap = map; });
    });
    form->addRow(tr("Tone map"), toneMap_);

    samples_ = new QComboBox(this);
    samples_->setObjectName(QStringLiteral("samplesCombo"));
    samples_->setToolTip(tr("Smooths the objects' edges (multisampling). Skipped while you drag or the "
                            "turntable turns, so the view stays quick."));
    for (int n : {1, 2, 4, 8}) samples_->addItem(n == 1 ? tr("off") : QStringLiteral("%1×").arg(n), n);
    connect(samples_, &QComboBox::currentIndexChanged, this, [this](int) {
        const int n = samples_->currentData().toInt();
        editDisplay([n](DisplaySettings& d) { d.samples = n; });
    });
    form->addRow(tr("Multisampling"), samples_);

    // Multiple scattering (ggx_sampling.h, Scattering): the glTF BRDF as the specification writes
    // it loses the light that bounces between a rough surface's microfacets; kept, rough metals
    // are as bright as a path tracer draws them.
    keepBouncedLight_ = new QCheckBox(tr("Keep light bounced between microfacets"), this);
    keepBouncedLight_->setObjectName(QStringLiteral("keepBouncedLightCheck"));
    keepBouncedLight_->setToolTip(tr("Rough metals lose up to a third of their light under glTF's own "
                                     "BRDF, which counts one bounce; on, that light is kept (multiple "
                                     "scattering, as Blender's Multiscatter GGX and Filament do). Off "
                                     "shows the glTF specification's material exactly."));
    connect(keepBouncedLight_, &QCheckBox::toggled, this, [this](bool on) {
        editDisplay([on](DisplaySettings& d) { d.scattering = on ? Scattering::Compensated : Scattering::Single; });
    });
    form->addRow(tr("Materials"), keepBouncedLight_);

    connect(document_, &SceneDocument::environmentChanged, this, &EnvironmentPanel::refresh);
    connect(document_, &SceneDocument::displayChanged, this, &EnvironmentPanel::refresh);
    connect(environments_, &EnvironmentManager::environmentReady, this, &EnvironmentPanel::refresh);
    refresh();
}

void EnvironmentPanel::editEnvironment(const std::function<void(EnvironmentSettings&)>& edit,
                                       const QObject* from) {
    EnvironmentSettings s = document_->scene().environment;
    edit(s);
    document_->setEnvironment(s, from ? sessions_->key(from) : 0);
}

void EnvironmentPanel::showBackdropSwatch(const Rgb& colour) {
    const QColor c = QColor::fromRgbF(colour.r, colour.g, colour.b);
    backdrop_->setText(tr("Backdrop"));
    backdrop_->setStyleSheet(QStringLiteral("QPushButton { background-color: %1; color: %2; }")
                                 .arg(c.name(), c.lightnessF() > 0.5 ? QStringLiteral("black") : QStringLiteral("white")));
}

void EnvironmentPanel::editDisplay(const std::function<void(DisplaySettings&)>& edit, const QObject* from) {
    DisplaySettings d = document_->scene().display;
    edit(d);
    document_->setDisplay(d, from ? sessions_->key(from) : 0);
}

void EnvironmentPanel::refresh() {
    const EnvironmentSettings& s = document_->scene().environment;
    const DisplaySettings& d = document_->scene().display;
    source_->setText(environmentDisplayName(s.source));
    source_->setToolTip(QString::fromStdString(s.source));

    const QSignalBlocker b1(builder_), b2(faceSize_), b3(handedness_), b4(rotation_),
        b5(showBackground_), b6(backgroundBlur_), b7(exposure_), b8(toneMap_), b9(samples_),
        b10(rotationDegrees_), b11(keepBouncedLight_);
    builder_->setCurrentText(QString::fromLatin1(builderName(s.builder)));
    int sizeIndex = faceSize_->findData(s.faceSize);
    if (sizeIndex < 0) {  // a size from a scene file or the command line
        faceSize_->addItem(squaredSize(s.faceSize), s.faceSize);
        sizeIndex = faceSize_->count() - 1;
    }
    faceSize_->setCurrentIndex(sizeIndex);
    handedness_->setCurrentIndex(handedness_->findData(static_cast<int>(s.handedness)));
    rotation_->setValue(static_cast<int>(std::lround(d.environmentRotationDegrees)));
    rotationDegrees_->setValue(static_cast<double>(d.environmentRotationDegrees));
    showBackground_->setChecked(d.showBackground);
    backgroundBlur_->setValue(d.backgroundLambda);
    backgroundBlur_->setEnabled(d.showBackground);
    showBackdropSwatch(d.backdrop);
    exposure_->setValue(d.exposureEv);
    toneMap_->setCurrentIndex(toneMap_->findData(static_cast<int>(d.toneMap)));
    int samplesIndex = samples_->findData(d.samples);
    if (samplesIndex < 0) {
        samples_->addItem(QStringLiteral("%1×").arg(d.samples), d.samples);
        samplesIndex = samples_->count() - 1;
    }
    samples_->setCurrentIndex(samplesIndex);
    keepBouncedLight_->setChecked(d.scattering == Scattering::Compensated);

    const auto current = environments_->current();
    if (current && !current->complete()) {
        // An early environment (environment_manager.h): drawn from its base while the chain is built.
        info_->setText(tr("%1 · %2 · import %3 s; building the %4 chain (glossy objects show box "
                          "mips of the base until it is done)")
                           .arg(environmentDisplayName(current->settings.source))
                           .arg(squaredSize(current->base ? current->base->size() : 0))
                           .arg(current->importSeconds, 0, 'f', 2)
                           .arg(QString::fromLatin1(builderName(current->settings.builder))));
    } else if (current) {
        info_->setText(tr("%1 · %2 · %3 · import %4 s, build %5 s, filtered through level %6 of %7%8")
                           .arg(environmentDisplayName(current->settings.source))
                           .arg(squaredSize(current->base ? current->base->size() : 0))
                           .arg(QString::fromLatin1(builderName(current->settings.builder)))
                           .arg(current->importSeconds, 0, 'f', 2)
                           .arg(current->buildSeconds, 0, 'f', 2)
                           .arg(current->lastFilteredLevel)
                           .arg(current->levelCount() - 1)
                           .arg(current->irradiance ? tr(", irradiance map") : QString()));
    } else {
        info_->setText(tr("loading…"));
    }
}

}  // namespace mipgloss::ui
