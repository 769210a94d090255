// MaterialPanel without OpenGL: λ, slider and Phong exponent kept in step through real key input,
// ranges from the environment's face size, enabling rules, and the sRGB <-> linear conversion.
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ui/material_panel.h"
#include "mipgloss/ui/scene_document.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QSlider>
#include <QTest>

#include <cmath>
#include <memory>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::typeInto;

namespace {

Scene twoSpheres() {
    const auto mesh = std::make_shared<const Mesh>(makeSphere(8, 16));
    Scene s;
    for (float x : {0.0f, 3.0f}) {
        SceneObject o;
        o.name = x == 0.0f ? "left" : "right";
        o.mesh = mesh;
        o.meshSource = "builtin:sphere";
        o.transform.translation.x = x;
        o.material.lambda = 2.0f;
        s.objects.push_back(o);
    }
    s.environment.faceSize = 128;
    return s;
}

template <class W>
W* child(QWidget& panel, const char* name) {
    W* w = panel.findChild<W*>(QLatin1String(name));
    EXPECT_NE(w, nullptr) << "no widget named " << name;
    return w;
}

// Two spheres in a document, one selected, and a shown panel editing them.
struct ShownPanel {
    SceneDocument doc;
    MaterialPanel panel{&doc};
    explicit ShownPanel(int selected) {
        doc.resetScene(twoSpheres());
        doc.setSelected(selected);
        panel.show();
    }
    bool exposed() { return QTest::qWaitForWindowExposed(&panel); }
};

// A click on a check box's indicator (its centre may lie past the end of the text, where a click
// does nothing).
void clickIndicator(QCheckBox* box) {
    QTest::mouseClick(box, Qt::LeftButton, {}, QPoint(6, box->height() / 2));
}

}  // namespace

TEST(MaterialPanel, DisabledWithHintWhenNothingSelected) {
    ShownPanel shown(-1);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    auto* editor = child<QWidget>(panel, "editor");
    auto* hint = child<QLabel>(panel, "hintLabel");
    ASSERT_TRUE(editor && hint);
    EXPECT_FALSE(editor->isEnabled());
    EXPECT_TRUE(hint->isVisible());
    doc.setSelected(1);
    EXPECT_TRUE(editor->isEnabled());
    EXPECT_FALSE(hint->isVisible());
    EXPECT_EQ(child<QLineEdit>(panel, "nameEdit")->text(), QStringLiteral("right"));
    doc.removeObject(1);  // selection passes to "left"
    EXPECT_EQ(child<QLineEdit>(panel, "nameEdit")->text(), QStringLiteral("left"));
    doc.resetScene(Scene{});
    EXPECT_FALSE(editor->isEnabled());
}

TEST(MaterialPanel, LambdaSpinSliderAndExponentStayInStep) {
    ShownPanel shown(0);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    auto* spin = child<QDoubleSpinBox>(panel, "lambdaSpin");
    auto* slider = child<QSlider>(panel, "lambdaSlider");
    auto* exponent = child<QDoubleSpinBox>(panel, "exponentSpin");
    ASSERT_TRUE(spin && slider && exponent);
    EXPECT_EQ(slider->maximum(), 7 * MaterialPanel::kSliderStepsPerLevel);  // 128² -> levels 0..7
    EXPECT_DOUBLE_EQ(exponent->maximum(), 3.0 * 128 * 128 - 1.0);

    typeInto(spin, QStringLiteral("3.5"));
    EXPECT_FLOAT_EQ(doc.object(0).material.lambda, 3.5f);
    EXPECT_EQ(slider->value(), 70);
    EXPECT_NEAR(exponent->value(), lambdaToExponent(3.5, 128), 0.006);
    EXPECT_FLOAT_EQ(doc.object(1).material.lambda, 2.0f) << "only the selected object changes";

    slider->setValue(30);  // what a drag does
    EXPECT_FLOAT_EQ(doc.object(0).material.lambda, 1.5f);
    EXPECT_DOUBLE_EQ(spin->value(), 1.5);

    // Out of range input cannot get through: the spin box clamps to the last level.
    typeInto(spin, QStringLiteral("99"));
    EXPECT_LE(doc.object(0).material.lambda, 7.0f);
}

TEST(MaterialPanel, TypingAnExponentSetsLambda) {
    ShownPanel shown(1);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    auto* exponent = child<QDoubleSpinBox>(panel, "exponentSpin");
    auto* spin = child<QDoubleSpinBox>(panel, "lambdaSpin");
    ASSERT_TRUE(exponent && spin);

    typeInto(exponent, QStringLiteral("100"));
    const double expected = exponentToLambda(100.0, 128);
    EXPECT_NEAR(doc.object(1).material.lambda, expected, 1e-5);
    EXPECT_NEAR(spin->value(), expected, 0.005);
    // The document's λ gives back the typed exponent (not one rounded through the λ box).
    EXPECT_NEAR(exponent->value(), 100.0, 0.01);

    // Digits beyond the largest exponent are refused as they are typed.
    typeInto(exponent, QStringLiteral("1000000"));
    EXPECT_LE(exponent->value(), exponent->maximum());
    // The largest exponent, 3N² − 1, is the base level: λ = 0, shown as "mirror"; "mirror" can be
    // typed too.
    typeInto(exponent, QStringLiteral("49151"));
    EXPECT_EQ(doc.object(1).material.lambda, 0.0f);
    EXPECT_EQ(exponent->text(), QStringLiteral("mirror"));
    typeInto(spin, QStringLiteral("2"));
    typeInto(exponent, QStringLiteral("mirror"));
    EXPECT_EQ(doc.object(1).material.lambda, 0.0f);

    // n = 0 (a uniform hemisphere) lies beyond the chain: λ stops at the last level.
    typeInto(exponent, QStringLiteral("0"));
    EXPECT_FLOAT_EQ(doc.object(1).material.lambda, 7.0f);
}

TEST(MaterialPanel, RangesFollowTheFaceSize) {
    SceneDocument doc;
    doc.resetScene(twoSpheres());
    doc.setSelected(0);
    MaterialPanel panel(&doc);
    EnvironmentSettings e = doc.scene().environment;
    e.faceSize = 64;
    doc.setEnvironment(e);
    EXPECT_EQ(panel.maxLevel(), 6);
    EXPECT_EQ(child<QSlider>(panel, "lambdaSlider")->maximum(), 6 * MaterialPanel::kSliderStepsPerLevel);
    EXPECT_DOUBLE_EQ(child<QDoubleSpinBox>(panel, "exponentSpin")->maximum(), 3.0 * 64 * 64 - 1.0);
    EXPECT_NEAR(child<QDoubleSpinBox>(panel, "exponentSpin")->value(), lambdaToExponent(2.0, 64), 0.006);
}

TEST(MaterialPanel, IrradianceOnlyInNormalMode) {
    ShownPanel shown(0);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    auto* mode = child<QComboBox>(panel, "modeCombo");
    auto* irradiance = child<QCheckBox>(panel, "irradianceCheck");
    auto* grazing = child<QCheckBox>(panel, "grazingCheck");
    ASSERT_TRUE(mode && irradiance && grazing);
    EXPECT_FALSE(irradiance->isEnabled());
    mode->setCurrentIndex(mode->findData(static_cast<int>(LookupMode::Normal)));
    EXPECT_EQ(doc.object(0).material.mode, LookupMode::Normal);
    EXPECT_TRUE(irradiance->isEnabled());
    clickIndicator(irradiance);
    EXPECT_TRUE(doc.object(0).material.useIrradiance);
    clickIndicator(grazing);
    EXPECT_TRUE(doc.object(0).material.sharperAtGrazing);
    doc.setSelected(1);
    EXPECT_FALSE(irradiance->isChecked());
    EXPECT_FALSE(irradiance->isEnabled());
}

TEST(MaterialPanel, TransformBoxesEditOneComponentEach) {
    ShownPanel shown(1);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    Transform t = doc.object(1).transform;
    t.translation = {3.0f, 0.123456f, -0.5f};
    t.scale = 0.0123456f;
    doc.setTransform(1, t);
    typeInto(child<QDoubleSpinBox>(panel, "rotateY"), QStringLiteral("45"));
    const Transform& now = doc.object(1).transform;
    EXPECT_FLOAT_EQ(now.rotationDegrees.y, 45.0f);
    // The other components keep their exact values, not the boxes' rounded ones.
    EXPECT_EQ(now.translation, t.translation);
    EXPECT_EQ(now.scale, t.scale);
    typeInto(child<QDoubleSpinBox>(panel, "translateX"), QStringLiteral("-2"));
    EXPECT_FLOAT_EQ(doc.object(1).transform.translation.x, -2.0f);
}

TEST(ColourConversion, SwatchRoundTripsThroughLinear) {
    // Every 8-bit colour survives QColor -> linear -> QColor.
    for (int v = 0; v < 256; ++v) {
        const QColor c(v, 255 - v, (v * 7) % 256);
        const QColor back = colorFromLinear(linearFromColor(c));
        EXPECT_EQ(back.red(), c.red()) << v;
        EXPECT_EQ(back.green(), c.green()) << v;
        EXPECT_EQ(back.blue(), c.blue()) << v;
    }
    // Linear mid-grey 0.5 is sRGB 188, not 128.
    EXPECT_EQ(colorFromLinear(Rgb(0.5f)).red(), 188);
}
