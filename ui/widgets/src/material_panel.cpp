#include "mipgloss/ui/material_panel.h"

#include "mipgloss/assets/textures.h"

#include "mipgloss/ibl/colour.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/ui/scene_document.h"
#include "edit_sessions.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QToolTip>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

namespace mipgloss::ui {

QColor colorFromLinear(const Rgb& linear) {
    auto encode = [](float c) {
        return std::clamp(linearToSrgb(std::clamp(static_cast<double>(c), 0.0, 1.0)), 0.0, 1.0);
    };
    return QColor::fromRgbF(static_cast<float>(encode(linear.r)),
                            static_cast<float>(encode(linear.g)),
                            static_cast<float>(encode(linear.b)));
}

Rgb linearFromColor(const QColor& color) {
    const QColor rgb = color.toRgb();
    return Rgb(static_cast<float>(srgbToLinear(rgb.redF())),
               static_cast<float>(srgbToLinear(rgb.greenF())),
               static_cast<float>(srgbToLinear(rgb.blueF())));
}

namespace {

// The exponent box's top: the largest finite n, 3·128² − 1, the limit of n(λ) as λ → 0. It stands
// for the mirror (λ = 0, n = ∞; exponentToLambda gives 0 from here on) and reads "mirror".
const double kExponentBoxTop = 3.0 * kLambdaReferenceSize * kLambdaReferenceSize - 1.0;

// The exponent box: its maximum stands for the mirror and reads "mirror"; typing "mirror" (or
// "inf", "∞") asks for it.
class ExponentSpinBox : public QDoubleSpinBox {
public:
    using QDoubleSpinBox::QDoubleSpinBox;

protected:
    QString textFromValue(double value) const override {
        if (value >= maximum() - 0.5 * std::pow(10.0, -decimals())) return mirrorText();
        return QDoubleSpinBox::textFromValue(value);
    }
    double valueFromText(const QString& text) const override {
        if (isMirrorWord(text.trimmed(), true)) return maximum();
        return QDoubleSpinBox::valueFromText(text);
    }
    QValidator::State validate(QString& text, int& pos) const override {
        const QString t = text.trimmed();
        if (!t.isEmpty() && isMirrorWord(t, false))
            return isMirrorWord(t, true) ? QValidator::Acceptable : QValidator::Intermediate;
        return QDoubleSpinBox::validate(text, pos);
    }

private:
    static QString mirrorText() { return QStringLiteral("mirror"); }
    // `complete`: the whole word; otherwise a prefix of one while typing.
    static bool isMirrorWord(const QString& text, bool complete) {
        const QString lower = text.toLower();
        for (const QString& word : {mirrorText(), QStringLiteral("inf"), QStringLiteral("∞")})
            if (complete ? lower == word : word.startsWith(lower)) return true;
        return false;
    }
};

QDoubleSpinBox* makeSpin(QWidget* parent, const QString& name, double lo, double hi, int decimals,
                         double step) {
    auto* spin = new QDoubleSpinBox(parent);
    spin->setObjectName(name);
    spin->setRange(lo, hi);
    spin->setDecimals(decimals);
    spin->setSingleStep(step);
    spin->setKeyboardTracking(false);
    spin->setAccelerated(true);
    return spin;
}

// "Linear RGB r, g, b (sRGB #rrggbb)", after `lead` when there is one: a colour button's tooltip.
QString colourTip(const QString& lead, const Rgb& linear) {
    const QString values = MaterialPanel::tr("Linear RGB %1, %2, %3 (sRGB %4)")
                               .arg(linear.r, 0, 'f', 3)
                               .arg(linear.g, 0, 'f', 3)
                               .arg(linear.b, 0, 'f', 3)
                               .arg(colorFromLinear(linear).name());
    return lead.isEmpty() ? values : lead + QStringLiteral(" ") + values;
}

QIcon swatch(const QColor& color) {
    QPixmap pixmap(32, 16);
    pixmap.fill(color);
    return QIcon(pixmap);
}

}  // namespace

MaterialPanel::MaterialPanel(SceneDocument* document, QWidget* parent)
    : QWidget(parent), document_(document) {
    setObjectName(QStringLiteral("materialPanel"));
    auto* outer = new QVBoxLayout(this);

    hint_ = new QLabel(tr("Select an object in the scene list, or click one in the view, to edit "
                          "its material."),
                       this);
    hint_->setObjectName(QStringLiteral("hintLabel"));
    hint_->setWordWrap(true);
    outer->addWidget(hint_);

    editor_ = new QWidget(this);
    editor_->setObjectName(QStringLiteral("editor"));
    auto* editorLayout = new QVBoxLayout(editor_);
    editorLayout->setContentsMargins(0, 0, 0, 0);
    outer->addWidget(editor_);
    outer->addStretch(1);

    // Object.
    auto* objectBox = new QGroupBox(tr("Object"), editor_);
    auto* objectForm = new QFormLayout(objectBox);
    name_ = new QLineEdit(objectBox);
    name_->setObjectName(QStringLiteral("nameEdit"));
    objectForm->addRow(tr("Name"), name_);
    editorLayout->addWidget(objectBox);

    // Material: which one the object uses, its name, who shares it, and its parameters.
    auto* materialBox = new QGroupBox(tr("Material"), editor_);
    auto* form = new QFormLayout(materialBox);
    materialChooser_ = new QComboBox(materialBox);
    materialChooser_->setObjectName(QStringLiteral("materialCombo"));
    materialChooser_->setToolTip(tr("The scene's materials: choose one to use it for this object"));
    form->addRow(tr("Uses"), materialChooser_);
    materialName_ = new QLineEdit(materialBox);
    materialName_->setObjectName(QStringLiteral("materialNameEdit"));
    materialName_->setToolTip(tr("The material's name, unique in the scene"));
    form->addRow(tr("Material name"), materialName_);
    users_ = new QLabel(materialBox);
    users_->setObjectName(QStringLiteral("usersLabel"));
    makeUnique_ = new QPushButton(tr("Make unique"), materialBox);
    makeUnique_->setObjectName(QStringLiteral("makeUniqueButton"));
    makeUnique_->setToolTip(tr("Give this object a copy of the material of its own, so editing it "
                               "leaves the other objects as they are"));
    auto* usersRow = new QHBoxLayout;
    usersRow->addWidget(users_, 1);
    usersRow->addWidget(makeUnique_);
    form->addRow(QString(), usersRow);

    // What kind of material: layered (colour, metal, roughness) or the paper's single lobe.
    kind_ = new QComboBox(materialBox);
    kind_->setObjectName(QStringLiteral("kindCombo"));
    kind_->addItem(tr("Layered: colour, metal, roughness"), true);
    kind_->addItem(tr("Single lobe (the paper's)"), false);
    kind_->setToolTip(tr("Layered: a coloured matte base under a glossy reflection that grows toward the "
                         "silhouette, with an optional clear coat, set as in glTF and Substance. Single lobe: "
                         "one reflection of a chosen blur and tint, as in Ashikhmin & Ghosh's Figure 1."));
    form->addRow(tr("Kind"), kind_);
    buildLayeredEditor(materialBox);
    form->addRow(layered_);
    singleLobe_ = new QWidget(materialBox);
    singleLobe_->setObjectName(QStringLiteral("singleLobeEditor"));
    auto* single = new QFormLayout(singleLobe_);
    single->setContentsMargins(0, 0, 0, 0);
    form->addRow(singleLobe_);

    lambdaSlider_ = new QSlider(Qt::Horizontal, materialBox);
    lambdaSlider_->setObjectName(QStringLiteral("lambdaSlider"));
    lambdaSlider_->setSingleStep(1);
    lambdaSlider_->setPageStep(kSliderStepsPerLambda / 2);
    lambdaSlider_->setTickInterval(kSliderStepsPerLambda);
    lambdaSlider_->setTickPosition(QSlider::TicksBelow);
    lambdaSlider_->setRange(0, static_cast<int>(std::lround(kMaxLambda * kSliderStepsPerLambda)));
    lambdaSpin_ = makeSpin(materialBox, QStringLiteral("lambdaSpin"), 0.0, kMaxLambda, 2,
                           1.0 / kSliderStepsPerLambda);
    auto* lambdaRow = new QHBoxLayout;
    lambdaRow->addWidget(lambdaSlider_, 1);
    lambdaRow->addWidget(lambdaSpin_);
    single->addRow(tr("Blur λ"), lambdaRow);
    lambdaSlider_->setToolTip(
        tr("Blur λ: the Phong lobe n = 3·128²·4^−λ − 1, the same under any environment and face "
           "size. 0 is a mirror; each +1 makes the lobe twice as wide (n about 4× smaller); from "
           "%1 on n = 0, a uniform hemisphere.")
            .arg(exponentToLambda(0.0), 0, 'f', 2));
    lambdaSpin_->setToolTip(lambdaSlider_->toolTip());

    exponentSpin_ = new ExponentSpinBox(materialBox);
    exponentSpin_->setObjectName(QStringLiteral("exponentSpin"));
    exponentSpin_->setDecimals(2);
    exponentSpin_->setKeyboardTracking(false);
    exponentSpin_->setSingleStep(1.0);
    exponentSpin_->setRange(0.0, kExponentBoxTop);
    exponentSpin_->setToolTip(
        tr("Phong exponent n of the blur, λ = log2(128·√3) − ½·log2(n + 1); the same lobe under "
           "any environment. \"mirror\" (or \"inf\", ∞) is λ 0; n = 0 is a uniform hemisphere."));
    single->addRow(tr("Phong exponent n"), exponentSpin_);

    mode_ = new QComboBox(materialBox);
    mode_->setObjectName(QStringLiteral("modeCombo"));
    mode_->addItem(tr("reflection vector (glossy)"), static_cast<int>(LookupMode::Reflect));
    mode_->addItem(tr("surface normal (diffuse)"), static_cast<int>(LookupMode::Normal));
    single->addRow(tr("Look up by"), mode_);

    irradiance_ = new QCheckBox(tr("Use irradiance map"), materialBox);
    irradiance_->setObjectName(QStringLiteral("irradianceCheck"));
    irradiance_->setToolTip(tr("Normal mode: the exact cosine-weighted irradiance instead of the "
                               "chain at λ"));
    single->addRow(QString(), irradiance_);

    grazing_ = new QCheckBox(tr("Sharper at grazing angles"), materialBox);
    grazing_->setObjectName(QStringLiteral("grazingCheck"));
    single->addRow(QString(), grazing_);

    tint_ = new QPushButton(tr("Choose…"), materialBox);
    tint_->setObjectName(QStringLiteral("tintButton"));
    single->addRow(tr("Tint"), tint_);
    editorLayout->addWidget(materialBox);

    // Placement.
    auto* placementBox = new QGroupBox(tr("Placement"), editor_);
    auto* placement = new QFormLayout(placementBox);
    const char* axes[3] = {"X", "Y", "Z"};
    auto* translationRow = new QHBoxLayout;
    auto* rotationRow = new QHBoxLayout;
    for (int a = 0; a < 3; ++a) {
        translation_[a] = makeSpin(placementBox, QStringLiteral("translate") + axes[a], -1e6, 1e6,
                                   3, 0.1);
        rotation_[a] = makeSpin(placementBox, QStringLiteral("rotate") + axes[a], -360.0, 360.0, 1,
                                5.0);
        rotation_[a]->setSuffix(QStringLiteral("°"));
        translationRow->addWidget(translation_[a]);
        rotationRow->addWidget(rotation_[a]);
    }
    placement->addRow(tr("Position"), translationRow);
    placement->addRow(tr("Rotation"), rotationRow);
    scale_ = makeSpin(placementBox, QStringLiteral("scaleSpin"), 1e-5, 1e5, 5, 0.1);
    placement->addRow(tr("Scale"), scale_);
    editorLayout->addWidget(placementBox);

    // Edits -> document. Each widget's interaction is one undo step (edit_sessions.h).
    sessions_ = new EditSessions(this);
    for (QWidget* w : std::initializer_list<QWidget*>{lambdaSlider_, lambdaSpin_, exponentSpin_, scale_})
        sessions_->track(w);
    for (int a = 0; a < 3; ++a) {
        sessions_->track(translation_[a]);
        sessions_->track(rotation_[a]);
    }
    connect(name_, &QLineEdit::editingFinished, this, [this] {
        const QString text = name_->text().trimmed();
        if (document_->isValidIndex(document_->selected()) && !text.isEmpty())
            document_->setName(document_->selected(), text);
        else
            refresh();
    });
    connect(materialChooser_, &QComboBox::activated, this, [this](int item) {
        const auto id = static_cast<MaterialId>(materialChooser_->itemData(item).toUInt());
        document_->assignMaterial(document_->selected(), id);
        refreshMaterial();  // an id no longer in the scene changes nothing: show what is
    });
    connect(materialName_, &QLineEdit::editingFinished, this, &MaterialPanel::renameMaterial);
    connect(makeUnique_, &QPushButton::clicked, this,
            [this] { document_->makeMaterialUnique(document_->selected()); });
    connect(lambdaSlider_, &QSlider::valueChanged, this, [this](int v) {
        setLambda(v / static_cast<double>(kSliderStepsPerLambda), lambdaSlider_);
    });
    connect(lambdaSpin_, &QDoubleSpinBox::valueChanged, this,
            [this](double lambda) { setLambda(lambda, lambdaSpin_); });
    connect(exponentSpin_, &QDoubleSpinBox::valueChanged, this, [this](double n) {
        // The top is the mirror, λ = 0 exactly (the formula there gives 0 up to rounding).
        setLambda(n >= kExponentBoxTop ? 0.0 : exponentToLambda(n), exponentSpin_);
    });
    connect(mode_, &QComboBox::currentIndexChanged, this, [this](int) {
        const auto mode = static_cast<LookupMode>(mode_->currentData().toInt());
        editMaterial([mode](Material& m) { m.mode = mode; });
    });
    connect(irradiance_, &QCheckBox::toggled, this,
            [this](bool on) { editMaterial([on](Material& m) { m.useIrradiance = on; }); });
    connect(grazing_, &QCheckBox::toggled, this,
            [this](bool on) { editMaterial([on](Material& m) { m.sharperAtGrazing = on; }); });
    connect(tint_, &QPushButton::clicked, this, &MaterialPanel::chooseTint);
    connect(kind_, &QComboBox::activated, this, [this](int item) {
        const bool on = kind_->itemData(item).toBool();
        editMaterial([on](Material& m) { m.layered = on; });
        refreshMaterial();
    });
    connectLayeredEditor();
    for (int a = 0; a < 3; ++a) {
        // Each box edits only its own component of the document's value, so the others' rounding
        // (the boxes show 1 to 5 decimals) never leaks into the transform.
        QDoubleSpinBox* move = translation_[a];
        QDoubleSpinBox* turn = rotation_[a];
        connect(move, &QDoubleSpinBox::valueChanged, this, [this, a, move](double v) {
            editTransform([a, v](Transform& t) { t.translation[a] = static_cast<float>(v); }, move);
        });
        connect(turn, &QDoubleSpinBox::valueChanged, this, [this, a, turn](double v) {
            editTransform([a, v](Transform& t) { t.rotationDegrees[a] = static_cast<float>(v); }, turn);
        });
    }
    connect(scale_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        editTransform([v](Transform& t) { t.scale = static_cast<float>(v); }, scale_);
    });

    // Document -> widgets.
    connect(document_, &SceneDocument::selectionChanged, this, &MaterialPanel::refresh);
    connect(document_, &SceneDocument::objectsChanged, this, &MaterialPanel::refresh);
    connect(document_, &SceneDocument::materialsChanged, this, &MaterialPanel::refreshMaterials);
    connect(document_, &SceneDocument::materialChanged, this, [this](int index) {
        // Another object taking or leaving the selected one's material changes who shares it.
        if (index == document_->selected())
            refreshMaterial();
        else
            refreshUsers();
    });
    connect(document_, &SceneDocument::transformChanged, this, [this](int index) {
        if (index == document_->selected()) refreshTransform();
    });
    connect(document_, &SceneDocument::objectChanged, this, [this](int index) {
        if (index == document_->selected()) refresh();
    });
    refresh();
}

void MaterialPanel::refresh() {
    const bool valid = document_->isValidIndex(document_->selected());
    editor_->setEnabled(valid);
    hint_->setVisible(!valid);
    {
        const QSignalBlocker block(name_);
        name_->setText(valid ? QString::fromStdString(document_->object(document_->selected()).name)
                             : QString());
    }
    refreshMaterials();
    refreshTransform();
}

void MaterialPanel::refreshMaterials() {
    {
        const QSignalBlocker block(materialChooser_);
        materialChooser_->clear();
        for (const NamedMaterial& m : document_->scene().materials)
            materialChooser_->addItem(QString::fromStdString(m.name), QVariant::fromValue(m.id));
    }
    refreshMaterial();
}

void MaterialPanel::refreshMaterial() {
    const int index = document_->selected();
    const bool valid = document_->isValidIndex(index);
    const NamedMaterial* named = valid ? document_->namedMaterialOf(index) : nullptr;
    {
        const QSignalBlocker b1(materialChooser_), b2(materialName_);
        materialChooser_->setCurrentIndex(
            named ? materialChooser_->findData(QVariant::fromValue(named->id)) : -1);
        materialName_->setText(named ? QString::fromStdString(named->name) : QString());
    }
    refreshUsers();
    materialName_->setEnabled(named != nullptr);

    const Material m = valid ? document_->materialOf(index) : Material{};
    // The document holds only valid λ (scene_document.h); the clamp is for display alone.
    const double lambda = std::clamp(static_cast<double>(m.lambda), 0.0, kMaxLambda);
    const QSignalBlocker b1(lambdaSlider_), b2(lambdaSpin_), b3(exponentSpin_), b4(mode_),
        b5(irradiance_), b6(grazing_);
    lambdaSlider_->setValue(static_cast<int>(std::lround(lambda * kSliderStepsPerLambda)));
    lambdaSpin_->setValue(lambda);
    // "mirror" only for λ = 0 itself: the sharpest λ > 0 shows just below the box's top.
    const double shownStep = std::pow(10.0, -exponentSpin_->decimals());
    exponentSpin_->setValue(lambda > 0.0 ? std::min(lambdaToExponent(lambda), kExponentBoxTop - shownStep)
                                         : kExponentBoxTop);
    mode_->setCurrentIndex(mode_->findData(static_cast<int>(m.mode)));
    irradiance_->setChecked(m.useIrradiance);
    irradiance_->setEnabled(m.mode == LookupMode::Normal);
    grazing_->setChecked(m.sharperAtGrazing);
    {
        const QSignalBlocker block(kind_);
        kind_->setCurrentIndex(kind_->findData(m.layered));
    }
    layered_->setVisible(m.layered);
    singleLobe_->setVisible(!m.layered);
    refreshLayers(m);
    const QColor color = colorFromLinear(m.tint);
    tint_->setIcon(swatch(color));
    tint_->setToolTip(colourTip(QString(), m.tint));
}

void MaterialPanel::refreshUsers() {
    const int index = document_->selected();
    const NamedMaterial* named = document_->isValidIndex(index) ? document_->namedMaterialOf(index) : nullptr;
    const int users = named ? document_->scene().usersOf(named->id) : 0;
    users_->setText(users > 1 ? tr("used by %n objects", nullptr, users) : QString());
    users_->setVisible(users > 1);
    makeUnique_->setEnabled(users > 1);
}

void MaterialPanel::refreshTransform() {
    const bool valid = document_->isValidIndex(document_->selected());
    const SceneObject* object = valid ? &document_->object(document_->selected()) : nullptr;
    const Transform t = object ? object->transform : Transform{};
    // Arrow steps of about a twentieth of the object's size, so a 0.2-unit scan and a 120-unit one
    // both move sensibly.
    const float radius = object ? object->worldRadius() : 1.0f;
    const double step =
        radius > 0.0f ? std::pow(10.0, std::floor(std::log10(0.1 * radius))) : 0.1;
    for (int a = 0; a < 3; ++a) {
        const QSignalBlocker b1(translation_[a]), b2(rotation_[a]);
        translation_[a]->setValue(t.translation[a]);
        translation_[a]->setSingleStep(step);
        rotation_[a]->setValue(t.rotationDegrees[a]);
    }
    const QSignalBlocker b(scale_);
    scale_->setValue(t.scale);
}

void MaterialPanel::editMaterial(const std::function<void(Material&)>& edit, const QObject* from) {
    const int index = document_->selected();
    if (!document_->isValidIndex(index)) return;
    Material m = document_->materialOf(index);
    edit(m);
    document_->setMaterial(index, m, from ? sessions_->key(from) : 0);
}

void MaterialPanel::editTransform(const std::function<void(Transform&)>& edit, const QObject* from) {
    const int index = document_->selected();
    if (!document_->isValidIndex(index)) return;
    Transform t = document_->object(index).transform;
    edit(t);
    document_->setTransform(index, t, sessions_->key(from));
}

void MaterialPanel::setLambda(double lambda, const QObject* from) {
    // The widgets' ranges keep λ in [0, kMaxLambda]; never send the document anything else.
    if (!isValidLambda(lambda)) {
        refreshMaterial();
        return;
    }
    editMaterial([lambda](Material& m) { m.lambda = static_cast<float>(lambda); }, from);
    // A value the document already had (e.g. the same λ reached from a rounded exponent) emits
    // nothing: show the document's λ anyway.
    refreshMaterial();
}

void MaterialPanel::renameMaterial() {
    const int index = document_->selected();
    const NamedMaterial* named = document_->isValidIndex(index) ? document_->namedMaterialOf(index) : nullptr;
    if (!named) return;
    const QString text = materialName_->text().trimmed();
    if (text == QString::fromStdString(named->name)) return;
    if (!document_->setMaterialName(index, text)) {
        const std::string problem = materialNameProblem(text.toStdString());
        QToolTip::showText(materialName_->mapToGlobal(QPoint(0, materialName_->height())),
                           problem.empty() ? tr("Another material is named \"%1\"").arg(text)
                                           : QString::fromStdString(problem),
                           materialName_);
    }
    // Refused or made: show the document's name.
    const QSignalBlocker block(materialName_);
    materialName_->setText(QString::fromStdString(document_->namedMaterialOf(index)->name));
}

namespace {
constexpr int kUnitSliderSteps = 100;  // a [0, 1] slider's steps
}  // namespace

void MaterialPanel::buildLayeredEditor(QWidget* parent) {
    layered_ = new QWidget(parent);
    layered_->setObjectName(QStringLiteral("layeredEditor"));
    auto* form = new QFormLayout(layered_);
    form->setContentsMargins(0, 0, 0, 0);
    // A [0, 1] value as a slider and a box side by side.
    auto unitRow = [&](const QString& name, QSlider*& slider, QDoubleSpinBox*& spin, const QString& tip) {
        slider = new QSlider(Qt::Horizontal, layered_);
        slider->setObjectName(name + QStringLiteral("Slider"));
        slider->setRange(0, kUnitSliderSteps);
        slider->setPageStep(kUnitSliderSteps / 10);
        spin = makeSpin(layered_, name + QStringLiteral("Spin"), 0.0, 1.0, 3, 0.01);
        slider->setToolTip(tip);
        spin->setToolTip(tip);
        auto* row = new QHBoxLayout;
        row->addWidget(slider, 1);
        row->addWidget(spin);
        return row;
    };

    baseColor_ = new QPushButton(tr("Choose…"), layered_);
    baseColor_->setObjectName(QStringLiteral("baseColorButton"));
    form->addRow(tr("Base colour"), baseColor_);

    form->addRow(tr("Metallic"),
                 unitRow(QStringLiteral("metallic"), metallicSlider_, metallic_,
                         tr("0 for plastic, paint, wood, stone, skin; 1 for bare metal. A metal has no matte "
                            "layer: its reflection takes the base colour.")));

    form->addRow(tr("Roughness"),
                 unitRow(QStringLiteral("roughness"), roughnessSlider_, roughness_,
                         tr("How blurred the reflection is: 0 a mirror, 0.2 polished, 0.5 satin, 1 fully "
                            "matte. λ and n beside it are the same setting in mipgloss's own terms.")));
    roughnessLambda_ = makeSpin(layered_, QStringLiteral("roughnessLambdaSpin"), 0.0, exponentToLambda(0.0), 2, 0.05);
    roughnessLambda_->setToolTip(tr("The reflection's blur as λ, the scale single-lobe materials use: each +1 "
                                    "makes it twice as wide"));
    roughnessExponent_ = new ExponentSpinBox(layered_);
    roughnessExponent_->setObjectName(QStringLiteral("roughnessExponentSpin"));
    roughnessExponent_->setDecimals(2);
    roughnessExponent_->setKeyboardTracking(false);
    roughnessExponent_->setRange(0.0, kExponentBoxTop);
    roughnessExponent_->setToolTip(tr("The reflection's blur as a Phong exponent: larger is sharper; \"mirror\" "
                                      "is roughness 0"));
    // Labels rather than prefixes: the exponent box reads "mirror" typed on its own.
    auto* lobeRow = new QHBoxLayout;
    lobeRow->addWidget(new QLabel(QStringLiteral("λ"), layered_));
    lobeRow->addWidget(roughnessLambda_, 1);
    lobeRow->addWidget(new QLabel(QStringLiteral("n"), layered_));
    lobeRow->addWidget(roughnessExponent_, 1);
    form->addRow(QString(), lobeRow);

    specular_ = makeSpin(layered_, QStringLiteral("specularSpin"), 0.0, 1.0, 3, 0.005);
    specular_->setToolTip(tr("How much a non-metal reflects seen head-on: 0.04 suits most plastic, paint, glass "
                             "and skin, water is 0.02, gems up to about 0.08. Every reflection still grows "
                             "toward the silhouette."));
    form->addRow(tr("Specular"), specular_);
    specularColor_ = new QPushButton(tr("Choose…"), layered_);
    specularColor_->setObjectName(QStringLiteral("specularColorButton"));
    specularWeight_ = makeSpin(layered_, QStringLiteral("specularWeightSpin"), 0.0, 1.0, 3, 0.01);
    specularWeight_->setPrefix(tr("weight "));
    specularWeight_->setToolTip(tr("How strongly a non-metal reflects at every angle, its edges included: 1 as "
                                   "glTF's plain material, 0 a purely matte surface (the light it no longer "
                                   "reflects goes to its colour). Metals are untouched."));
    auto* specularRow = new QHBoxLayout;
    specularRow->addWidget(specularColor_);
    specularRow->addWidget(specularWeight_, 1);
    form->addRow(tr("Specular tint"), specularRow);

    form->addRow(tr("Clear coat"),
                 unitRow(QStringLiteral("coat"), coatSlider_, coat_,
                         tr("A clear varnish over everything, as on car paint, lacquered wood or a glazed "
                            "pot: 0 none, 1 a full coat.")));
    coatRoughness_ = makeSpin(layered_, QStringLiteral("coatRoughnessSpin"), 0.0, 1.0, 3, 0.01);
    coatRoughness_->setToolTip(tr("How blurred the varnish's own reflection is; usually close to 0."));
    form->addRow(tr("Coat roughness"), coatRoughness_);

    layeredIrradiance_ = new QCheckBox(tr("Matte base from the irradiance map"), layered_);
    layeredIrradiance_->setObjectName(QStringLiteral("layeredIrradianceCheck"));
    layeredIrradiance_->setToolTip(tr("Light the matte base with the exact irradiance map instead of the "
                                      "chain's widest lobe (they differ slightly; the map costs a build)"));
    form->addRow(QString(), layeredIrradiance_);

    textureMaps_ = new QLabel(layered_);
    textureMaps_->setObjectName(QStringLiteral("textureMapsLabel"));
    // One map a line, no word wrap: a wrapped label in this scrolled form was given one line's height.
    textureMaps_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    form->addRow(tr("Textures"), textureMaps_);
}

void MaterialPanel::connectLayeredEditor() {
    for (QWidget* w : std::initializer_list<QWidget*>{metallicSlider_, metallic_, roughnessSlider_, roughness_,
                                                      roughnessLambda_, roughnessExponent_, specular_, specularWeight_,
                                                      coatSlider_, coat_, coatRoughness_})
        sessions_->track(w);
    auto unit = [this](QSlider* slider, QDoubleSpinBox* spin, float Layers::*field) {
        connect(slider, &QSlider::valueChanged, this, [this, slider, field](int v) {
            const float value = static_cast<float>(v) / kUnitSliderSteps;
            editLayers([field, value](Layers& l) { l.*field = value; }, slider);
        });
        connect(spin, &QDoubleSpinBox::valueChanged, this, [this, spin, field](double v) {
            editLayers([field, v](Layers& l) { l.*field = static_cast<float>(v); }, spin);
        });
    };
    unit(metallicSlider_, metallic_, &Layers::metallic);
    unit(roughnessSlider_, roughness_, &Layers::roughness);
    unit(coatSlider_, coat_, &Layers::coat);
    connect(specular_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        editLayers([v](Layers& l) { l.specular = static_cast<float>(v); }, specular_);
    });
    connect(specularWeight_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        editLayers([v](Layers& l) { l.specularWeight = static_cast<float>(v); }, specularWeight_);
    });
    connect(coatRoughness_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        editLayers([v](Layers& l) { l.coatRoughness = static_cast<float>(v); }, coatRoughness_);
    });
    connect(roughnessLambda_, &QDoubleSpinBox::valueChanged, this, [this](double lambda) {
        const auto r = static_cast<float>(exponentToRoughness(lambdaToExponent(lambda)));
        editLayers([r](Layers& l) { l.roughness = r; }, roughnessLambda_);
    });
    connect(roughnessExponent_, &QDoubleSpinBox::valueChanged, this, [this](double n) {
        const auto r = n >= kExponentBoxTop ? 0.0f : static_cast<float>(exponentToRoughness(n));
        editLayers([r](Layers& l) { l.roughness = r; }, roughnessExponent_);
    });
    connect(baseColor_, &QPushButton::clicked, this, &MaterialPanel::chooseBaseColor);
    connect(specularColor_, &QPushButton::clicked, this, &MaterialPanel::chooseSpecularColor);
    connect(layeredIrradiance_, &QCheckBox::toggled, this,
            [this](bool on) { editMaterial([on](Material& m) { m.useIrradiance = on; }); });
}

void MaterialPanel::editLayers(const std::function<void(Layers&)>& edit, const QObject* from) {
    editMaterial([&edit](Material& m) { edit(m.layers); }, from);
    refreshMaterial();  // the other views of the same value (slider, box, λ, n)
}

void MaterialPanel::refreshLayers(const Material& m) {
    const Layers& l = m.layers;
    const QSignalBlocker b1(metallicSlider_), b2(metallic_), b3(roughnessSlider_), b4(roughness_),
        b5(roughnessLambda_), b6(roughnessExponent_), b7(specular_), b8(coatSlider_), b9(coat_), b10(coatRoughness_),
        b11(layeredIrradiance_), b12(specularWeight_);
    metallicSlider_->setValue(static_cast<int>(std::lround(l.metallic * kUnitSliderSteps)));
    metallic_->setValue(l.metallic);
    roughnessSlider_->setValue(static_cast<int>(std::lround(l.roughness * kUnitSliderSteps)));
    roughness_->setValue(l.roughness);
    const double n = roughnessToExponent(l.roughness);
    roughnessLambda_->setValue(exponentToLambda(n));
    const double shownStep = std::pow(10.0, -roughnessExponent_->decimals());
    roughnessExponent_->setValue(std::isinf(n) ? kExponentBoxTop : std::min(n, kExponentBoxTop - shownStep));
    specular_->setValue(l.specular);
    specularWeight_->setValue(l.specularWeight);
    coatSlider_->setValue(static_cast<int>(std::lround(l.coat * kUnitSliderSteps)));
    coat_->setValue(l.coat);
    coatRoughness_->setValue(l.coatRoughness);
    layeredIrradiance_->setChecked(m.useIrradiance);
    // The parameters a map sets: the value beside them is its factor (the map multiplies it).
    const MaterialMaps& maps = l.maps;
    const std::pair<QString, const TextureRef*> textures[] = {
        {tr("base colour"), &maps.baseColor}, {tr("metallic"), &maps.metallic},   {tr("roughness"), &maps.roughness},
        {tr("normal"), &maps.normal},         {tr("occlusion"), &maps.occlusion}, {tr("emissive"), &maps.emissive}};
    QStringList mapped, files;
    for (const auto& [what, ref] : textures)
        if (!ref->empty()) {
            const std::string problem = document_->textures()->problem(*ref);
            mapped << (problem.empty() ? what : tr("%1 (missing)").arg(what));
            files << QStringLiteral("%1: %2%3").arg(what, QString::fromStdString(ref->key()),
                                                     problem.empty() ? QString() : QStringLiteral(" — ") + QString::fromStdString(problem));
        }
    textureMaps_->setVisible(!mapped.isEmpty());
    if (auto* form = qobject_cast<QFormLayout*>(layered_->layout()))
        if (QWidget* label = form->labelForField(textureMaps_)) label->setVisible(!mapped.isEmpty());
    textureMaps_->setText(mapped.join(QLatin1Char('\n')));
    textureMaps_->setToolTip(tr("Texture maps set these; the values above multiply them.\n%1")
                                 .arg(files.join(QLatin1Char('\n'))));
    const QColor color = colorFromLinear(l.baseColor);
    baseColor_->setIcon(swatch(color));
    baseColor_->setToolTip(colourTip(
        tr("The surface's own colour: the matte layer of plastic, paint or wood, the reflection of a metal."),
        l.baseColor));
    // A colour above 1 (glTF allows it: F0 is clamped after the product) shows clipped in the
    // swatch; the tooltip gives the values.
    specularColor_->setIcon(swatch(colorFromLinear(glm::min(l.specularColor, Rgb(1.0f)))));
    specularColor_->setToolTip(colourTip(
        tr("Tints a non-metal's reflection seen head-on (its F0 times this colour, at most 1); toward the "
           "edges it turns white. White is glTF's plain material."),
        l.specularColor));
}

void MaterialPanel::chooseSpecularColor() {
    const int index = document_->selected();
    if (!document_->isValidIndex(index)) return;
    const QColor chosen =
        QColorDialog::getColor(colorFromLinear(glm::min(document_->materialOf(index).layers.specularColor, Rgb(1.0f))),
                               this, tr("Specular tint (shown in sRGB, stored linear)"));
    if (!chosen.isValid()) return;  // cancelled
    const Rgb colour = glm::clamp(linearFromColor(chosen), Rgb(0.0f), Rgb(1.0f));
    editMaterial([colour](Material& m) { m.layers.specularColor = colour; });
}

void MaterialPanel::chooseBaseColor() {
    const int index = document_->selected();
    if (!document_->isValidIndex(index)) return;
    const QColor chosen = QColorDialog::getColor(colorFromLinear(document_->materialOf(index).layers.baseColor),
                                                 this, tr("Base colour (shown in sRGB, stored linear)"));
    if (!chosen.isValid()) return;  // cancelled
    Rgb colour = glm::clamp(linearFromColor(chosen), Rgb(0.0f), Rgb(1.0f));
    editMaterial([colour](Material& m) { m.layers.baseColor = colour; });
}

void MaterialPanel::chooseTint() {
    const int index = document_->selected();
    if (!document_->isValidIndex(index)) return;
    const QColor chosen = QColorDialog::getColor(colorFromLinear(document_->materialOf(index).tint),
                                                 this, tr("Tint (shown in sRGB, stored linear)"));
    if (!chosen.isValid()) return;  // cancelled
    const Rgb tint = linearFromColor(chosen);
    editMaterial([tint](Material& m) { m.tint = tint; });
}

}  // namespace mipgloss::ui
