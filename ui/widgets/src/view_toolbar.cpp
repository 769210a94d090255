#include "mipgloss/ui/view_toolbar.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ui/environment_panel.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/viewport.h"

#include <QAction>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QStackedWidget>

#include <cmath>

namespace mipgloss::ui {

namespace {
// The comparison kinds, in the combo's order.
constexpr Comparison::Kind kKinds[] = {Comparison::Kind::Off, Comparison::Kind::Builder,
                                       Comparison::Kind::Environment, Comparison::Kind::Material};
}  // namespace

ViewToolBar::ViewToolBar(Viewport* viewport, SceneDocument* document, LibraryDocument* library,
                         const QList<QAction*>& frameActions, QAction* turntable, QWidget* parent)
    : QToolBar(tr("View"), parent), viewport_(viewport), document_(document), library_(library) {
    setObjectName(QStringLiteral("viewToolBar"));
    setMovable(false);
    addActions(frameActions);
    addSeparator();

    fov_ = new QSpinBox(this);
    fov_->setObjectName(QStringLiteral("fovSpin"));
    fov_->setRange(static_cast<int>(Viewport::kMinFov), static_cast<int>(Viewport::kMaxFov));
    fov_->setPrefix(tr("FOV "));
    fov_->setSuffix(QStringLiteral("°"));
    fov_->setToolTip(tr("Field of view, vertical, in degrees: small is a long lens (flat, little "
                        "perspective), large a wide one. Saved with the scene."));
    connect(fov_, &QSpinBox::valueChanged, viewport_, [this](int degrees) {
        viewport_->setFieldOfView(static_cast<float>(degrees));
    });
    addWidget(fov_);
    addSeparator();

    addAction(turntable);
    spin_ = new QComboBox(this);
    spin_->setObjectName(QStringLiteral("turntableSpinCombo"));
    spin_->addItem(tr("object"), static_cast<int>(TurntableSpin::Object));
    spin_->addItem(tr("environment"), static_cast<int>(TurntableSpin::Environment));
    spin_->setToolTip(tr("What the turntable turns: the objects (the background stays put) or the "
                         "environment around them"));
    connect(spin_, &QComboBox::currentIndexChanged, viewport_, [this](int) {
        viewport_->setTurntableSpin(static_cast<TurntableSpin>(spin_->currentData().toInt()));
    });
    addWidget(spin_);
    speed_ = new QDoubleSpinBox(this);
    speed_->setObjectName(QStringLiteral("turntableSpeedSpin"));
    speed_->setRange(-360.0, 360.0);
    speed_->setDecimals(0);
    speed_->setSingleStep(10.0);
    speed_->setSuffix(tr(" °/s"));
    speed_->setValue(static_cast<double>(viewport_->turntableSpeed()));
    speed_->setToolTip(tr("Turntable speed in degrees per second (negative turns the other way; 30 is "
                          "one turn in 12 s)"));
    connect(speed_, &QDoubleSpinBox::valueChanged, viewport_,
            [this](double v) { viewport_->setTurntableSpeed(static_cast<float>(v)); });
    addWidget(speed_);
    addSeparator();

    auto* compareLabel = new QLabel(tr(" Compare "), this);
    addWidget(compareLabel);
    compareKind_ = new QComboBox(this);
    compareKind_->setObjectName(QStringLiteral("compareCombo"));
    compareKind_->addItem(tr("off"));
    compareKind_->addItem(tr("builder"));
    compareKind_->addItem(tr("environment"));
    compareKind_->addItem(tr("material"));
    compareKind_->setToolTip(tr("Split the view: left the scene as it is, right the same camera with "
                                "another mip builder, another environment, or another material on "
                                "the selected object. Drag the divider to move it."));
    addWidget(compareKind_);
    compareChoice_ = new QStackedWidget(this);
    compareChoice_->addWidget(new QWidget(compareChoice_));  // off: nothing to choose
    compareBuilder_ = new QComboBox(compareChoice_);
    compareBuilder_->setObjectName(QStringLiteral("compareBuilderCombo"));
    for (const Builder b : kAllBuilders) compareBuilder_->addItem(QString::fromLatin1(builderName(b)));
    compareBuilder_->setCurrentText(QString::fromLatin1(builderName(Builder::Box)));
    compareBuilder_->setToolTip(tr("The right half's mip builder (box is the paper's own chain)"));
    compareChoice_->addWidget(compareBuilder_);
    compareEnvironment_ = new QPushButton(tr("Choose…"), compareChoice_);
    compareEnvironment_->setObjectName(QStringLiteral("compareEnvironmentButton"));
    compareEnvironment_->setToolTip(tr("The right half's environment"));
    connect(compareEnvironment_, &QPushButton::clicked, this, &ViewToolBar::chooseComparedEnvironment);
    compareChoice_->addWidget(compareEnvironment_);
    compareMaterial_ = new QComboBox(compareChoice_);
    compareMaterial_->setObjectName(QStringLiteral("compareMaterialCombo"));
    compareMaterial_->setToolTip(tr("The library material the selected object wears in the right half"));
    compareMaterial_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
    compareChoice_->addWidget(compareMaterial_);
    compareChoice_->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Fixed);
    compareChoice_->setMaximumWidth(240);  // a choice, not a stretch across the toolbar
    addWidget(compareChoice_);
    fillMaterials();

    connect(compareKind_, &QComboBox::currentIndexChanged, this, [this](int index) {
        compareChoice_->setCurrentIndex(index);
        applyComparison();
    });
    connect(compareBuilder_, &QComboBox::currentIndexChanged, this, &ViewToolBar::applyComparison);
    connect(compareMaterial_, &QComboBox::currentIndexChanged, this, &ViewToolBar::applyComparison);
    for (auto signal : {&LibraryDocument::reset, &LibraryDocument::fileChanged})
        connect(library_, signal, this, &ViewToolBar::fillMaterials);
    connect(library_, &LibraryDocument::entryInserted, this, &ViewToolBar::fillMaterials);
    connect(library_, &LibraryDocument::entryRemoved, this, &ViewToolBar::fillMaterials);
    connect(library_, &LibraryDocument::entryChanged, this, &ViewToolBar::fillMaterials);

    connect(viewport_, &Viewport::cameraChanged, this, &ViewToolBar::refreshFromCamera);
    refreshFromCamera();
}

void ViewToolBar::refreshFromCamera() {
    const QSignalBlocker block(fov_);
    fov_->setValue(static_cast<int>(std::lround(viewport_->camera().fovYDegrees)));
}

void ViewToolBar::fillMaterials() {
    const QString current = compareMaterial_->currentText();
    {
        const QSignalBlocker block(compareMaterial_);
        compareMaterial_->clear();
        for (int row = 0; row < library_->count(); ++row)
            compareMaterial_->addItem(QString::fromStdString(library_->entry(row).name));
        const int keep = compareMaterial_->findText(current);
        compareMaterial_->setCurrentIndex(keep >= 0 ? keep : 0);
    }
    if (compareKind_->currentIndex() == 3) applyComparison();
}

void ViewToolBar::compareEnvironment(const QString& source) {
    comparedEnvironment_ = source;
    compareEnvironment_->setText(environmentDisplayName(source.toStdString()));
    compareEnvironment_->setToolTip(source);
    if (compareKind_->currentIndex() != 2) compareKind_->setCurrentIndex(2);  // applies it
    else applyComparison();
}

void ViewToolBar::applyComparison() {
    Comparison c;
    c.kind = kKinds[std::clamp(compareKind_->currentIndex(), 0, 3)];
    switch (c.kind) {
        case Comparison::Kind::Off: break;
        case Comparison::Kind::Builder:
            if (!parseBuilder(compareBuilder_->currentText().toStdString(), c.builder)) c.kind = Comparison::Kind::Off;
            break;
        case Comparison::Kind::Environment:
            // Nothing chosen yet: ask, and compare once there is something.
            if (comparedEnvironment_.isEmpty()) {
                c.kind = Comparison::Kind::Off;
                emit chooseComparedEnvironment();
                if (!comparedEnvironment_.isEmpty()) return;  // compareEnvironment() applied it
                const QSignalBlocker block(compareKind_);     // cancelled: back to off
                compareKind_->setCurrentIndex(0);
                compareChoice_->setCurrentIndex(0);
                break;
            }
            c.environment = comparedEnvironment_.toStdString();
            break;
        case Comparison::Kind::Material: {
            const int row = compareMaterial_->currentIndex();
            if (row < 0 || row >= library_->count()) {
                c.kind = Comparison::Kind::Off;
                break;
            }
            c.material = library_->entry(row).material;
            c.materialName = QString::fromStdString(library_->entry(row).name);
            break;
        }
    }
    viewport_->setComparison(c);
}

}  // namespace mipgloss::ui
