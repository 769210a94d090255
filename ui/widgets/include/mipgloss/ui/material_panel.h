// Edits the selected object's name, material and placement through the SceneDocument.
//
// Materials are named and may be shared (scene.h): the panel edits the material the selected
// object uses, so every object sharing it changes; a line says how many objects use it ("used by
// 3 objects", shown only when shared), and "Make unique" gives the selected object a copy of its
// own. The material combo lists the scene's materials and assigns the chosen one to the object;
// the material's name is edited beside it (a name another material has is refused, and the box
// shows the material's name again).
//
// λ is shown three ways, kept in step: a slider (steps of 1/20), a spin box, and the equivalent
// Phong exponent n = lambdaToExponent(λ) (phong.h). λ has one meaning whatever the environment:
// the same lobe under any environment and face size, each +1 a lobe twice as wide (n about 4×
// smaller); the panel never looks at the environment. All three cover λ in [0, kMaxLambda]. The
// exponent is editable: typing n sets λ = exponentToLambda(n). λ = 0 is a true mirror (n = ∞),
// shown as "mirror", and typing "mirror" (or "inf", "∞") asks for it; the largest finite n,
// 3·128² − 1 (the limit as λ → 0), is the box's top and means the mirror too. n = 0 (a uniform
// hemisphere) is λ ≈ 7.79, and every λ beyond it up to kMaxLambda shows n = 0. So no widget can
// produce a λ outside [0, kMaxLambda] or a NaN one.
//
// The spin boxes commit on Enter, focus loss or arrow steps (no keyboard tracking): a half-typed
// number never reaches the document. Widgets are refreshed from the document with their signals
// blocked, so a refresh never writes back. Every edit is one undo step per interaction
// (edit_sessions.h): a drag of the λ slider, or the steps made in one box while it has the focus.
//
// A material is layered (layered.h; the default for new materials made here is the paper's single
// lobe, as before) or single-lobe; "Kind" switches, and only that kind's editor is shown. The
// layered editor speaks in artists' words: base colour, metallic, roughness (with λ and the Phong
// exponent n beside it, all three editable and kept in step: roughnessToExponent), specular,
// clear coat and coat roughness, each a slider and a box over [0, 1] (so no widget can produce an
// out-of-range value), tooltips saying what each does.
//
// Object names for tests: nameEdit (the object's name), materialCombo, materialNameEdit, kindCombo,
// baseColorButton, metallicSpin, roughnessSpin, roughnessLambdaSpin, roughnessExponentSpin,
// specularSpin, coatSpin, coatRoughnessSpin, layeredIrradianceCheck (and each spin's slider:
// metallicSlider, roughnessSlider, coatSlider),
// usersLabel, makeUniqueButton, lambdaSlider, lambdaSpin, exponentSpin, modeCombo,
// irradianceCheck, grazingCheck, tintButton, translateX/Y/Z, rotateX/Y/Z, scaleSpin, editor,
// hintLabel.
#pragma once

#include "mipgloss/scene/scene.h"

#include <QColor>
#include <QWidget>

#include <functional>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSlider;

namespace mipgloss::ui {

class EditSessions;
class SceneDocument;

// QColor values are sRGB-encoded, materials hold linear RGB: the conversion is colour.h's exact
// sRGB transfer functions, the same the environment import decodes 8-bit images with.
// Linear RGB -> sRGB QColor (components clamped to [0, 1]) and back.
QColor colorFromLinear(const Rgb& linear);
Rgb linearFromColor(const QColor& color);

class MaterialPanel : public QWidget {
    Q_OBJECT
public:
    explicit MaterialPanel(SceneDocument* document, QWidget* parent = nullptr);

    // Slider steps per unit of λ; the slider spans [0, kMaxLambda].
    static constexpr int kSliderStepsPerLambda = 20;

private:
    void refresh();           // everything from the document
    void refreshMaterial();   // material widgets from the selected object
    void refreshMaterials();  // the material combo: the scene's materials
    void refreshUsers();      // how many objects share the selected object's material
    void refreshTransform();
    // `from`: the widget the edit comes from, whose interaction makes one undo step.
    void editMaterial(const std::function<void(Material&)>& edit, const QObject* from = nullptr);
    void editTransform(const std::function<void(Transform&)>& edit, const QObject* from);
    void setLambda(double lambda, const QObject* from);
    void renameMaterial();
    void chooseTint();
    void chooseBaseColor();
    void chooseSpecularColor();
    void buildLayeredEditor(QWidget* parent);
    void connectLayeredEditor();
    void refreshLayers(const Material& m);
    // Sets one layer value (a roughness from λ or n too) as one undo step per interaction of `from`.
    void editLayers(const std::function<void(Layers&)>& edit, const QObject* from);

    SceneDocument* document_;
    EditSessions* sessions_ = nullptr;
    QLabel* hint_ = nullptr;
    QWidget* editor_ = nullptr;
    QLineEdit* name_ = nullptr;
    QComboBox* materialChooser_ = nullptr;
    QLineEdit* materialName_ = nullptr;
    QLabel* users_ = nullptr;
    QPushButton* makeUnique_ = nullptr;
    QSlider* lambdaSlider_ = nullptr;
    QDoubleSpinBox* lambdaSpin_ = nullptr;
    QDoubleSpinBox* exponentSpin_ = nullptr;
    QComboBox* mode_ = nullptr;
    QCheckBox* irradiance_ = nullptr;
    QCheckBox* grazing_ = nullptr;
    QPushButton* tint_ = nullptr;
    QComboBox* kind_ = nullptr;
    QWidget* singleLobe_ = nullptr;
    QWidget* layered_ = nullptr;
    QPushButton* baseColor_ = nullptr;
    QSlider* metallicSlider_ = nullptr;
    QDoubleSpinBox* metallic_ = nullptr;
    QSlider* roughnessSlider_ = nullptr;
    QDoubleSpinBox* roughness_ = nullptr;
    QDoubleSpinBox* roughnessLambda_ = nullptr;
    QDoubleSpinBox* roughnessExponent_ = nullptr;
    QDoubleSpinBox* specular_ = nullptr;
    // KHR_materials_specular: the dielectric's reflection colour and strength (scene.h).
    QPushButton* specularColor_ = nullptr;
    QDoubleSpinBox* specularWeight_ = nullptr;
    QSlider* coatSlider_ = nullptr;
    QDoubleSpinBox* coat_ = nullptr;
    QDoubleSpinBox* coatRoughness_ = nullptr;
    QCheckBox* layeredIrradiance_ = nullptr;
    // Which parameters a texture map sets (an imported asset's material): hidden without maps.
    QLabel* textureMaps_ = nullptr;
    QDoubleSpinBox* translation_[3] = {};
    QDoubleSpinBox* rotation_[3] = {};
    QDoubleSpinBox* scale_ = nullptr;
};

}  // namespace mipgloss::ui
