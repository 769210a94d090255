// Edits the selected object's material and placement through the SceneDocument.
//
// λ is shown three ways, kept in step: a slider (steps of 1/20 of a level), a spin box, and the
// equivalent Phong exponent n = lambdaToExponent(λ, N) (phong.h), N the environment's base face
// size from the document. The exponent is editable: typing n sets λ = exponentToLambda(n, N). The
// sharpest λ = 0 stands for n = 3N² − 1 (the base level's texel), shown as "mirror"; the
// exponent's range is [0, 3N² − 1], λ's is [0, last level of the chain], so no widget can produce
// a λ outside [0, kMaxLambda].
//
// The spin boxes commit on Enter, focus loss or arrow steps (no keyboard tracking): a half-typed
// number never reaches the document. Widgets are refreshed from the document with their signals
// blocked, so a refresh never writes back.
//
// Object names for tests: nameEdit, lambdaSlider, lambdaSpin, exponentSpin, modeCombo,
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

    // Steps per mip level on the slider.
    static constexpr int kSliderStepsPerLevel = 20;

    // The base face size the exponent refers to, and the last level λ can reach.
    int faceSize() const;
    int maxLevel() const;

private:
    void refresh();          // everything from the document
    void refreshRanges();    // λ and exponent ranges from the environment's face size
    void refreshMaterial();  // material widgets from the selected object
    void refreshTransform();
    void editMaterial(const std::function<void(Material&)>& edit);
    void editTransform(const std::function<void(Transform&)>& edit);
    void setLambda(double lambda);
    void chooseTint();

    SceneDocument* document_;
    QLabel* hint_ = nullptr;
    QWidget* editor_ = nullptr;
    QLineEdit* name_ = nullptr;
    QSlider* lambdaSlider_ = nullptr;
    QDoubleSpinBox* lambdaSpin_ = nullptr;
    QDoubleSpinBox* exponentSpin_ = nullptr;
    QComboBox* mode_ = nullptr;
    QCheckBox* irradiance_ = nullptr;
    QCheckBox* grazing_ = nullptr;
    QPushButton* tint_ = nullptr;
    QDoubleSpinBox* translation_[3] = {};
    QDoubleSpinBox* rotation_[3] = {};
    QDoubleSpinBox* scale_ = nullptr;
};

}  // namespace mipgloss::ui
