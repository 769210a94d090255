// MaterialPanel without OpenGL: λ, slider and Phong exponent kept in step through real key input,
// one λ range and one λ <-> n mapping whatever the environment's face size, enabling rules, a
// slider drag as one undo step, renaming, assigning and splitting shared materials, and the
// sRGB <-> linear conversion.
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/ui/material_panel.h"
#include "mipgloss/ui/scene_document.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSlider>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTest>
#include <QUndoStack>

#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

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
        Material m;
        m.lambda = 2.0f;
        s.addObject(o, m);
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
    // [0, kMaxLambda] whatever the environment (the chain's level count no longer limits λ).
    EXPECT_EQ(slider->maximum(), 8 * MaterialPanel::kSliderStepsPerLambda);
    EXPECT_DOUBLE_EQ(spin->maximum(), kMaxLambda);

    typeInto(spin, QStringLiteral("3.5"));
    EXPECT_FLOAT_EQ(doc.materialOf(0).lambda, 3.5f);
    EXPECT_EQ(slider->value(), 70);
    // n(3.5) = 3·128²·4^−3.5 − 1 = 383.
    EXPECT_NEAR(exponent->value(), 3.0 * 128 * 128 * std::pow(4.0, -3.5) - 1.0, 0.006);
    EXPECT_NEAR(exponent->value(), 383.0, 0.006);
    EXPECT_FLOAT_EQ(doc.materialOf(1).lambda, 2.0f) << "only the selected object changes";

    slider->setValue(30);  // what a drag does
    EXPECT_FLOAT_EQ(doc.materialOf(0).lambda, 1.5f);
    EXPECT_DOUBLE_EQ(spin->value(), 1.5);

    // The top of the range, beyond n = 0: λ 8 is allowed and shows n = 0.
    slider->setValue(slider->maximum());
    EXPECT_FLOAT_EQ(doc.materialOf(0).lambda, 8.0f);
    EXPECT_EQ(exponent->value(), 0.0);

    // Out of range input cannot get through: the spin box stops at kMaxLambda.
    typeInto(spin, QStringLiteral("99"));
    EXPECT_LE(doc.materialOf(0).lambda, 8.0f);
    EXPECT_TRUE(isValidLambda(doc.materialOf(0).lambda));
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
    const double expected = exponentToLambda(100.0);
    EXPECT_NEAR(doc.materialOf(1).lambda, expected, 1e-5);
    EXPECT_NEAR(spin->value(), expected, 0.005);
    // The document's λ gives back the typed exponent (not one rounded through the λ box).
    EXPECT_NEAR(exponent->value(), 100.0, 0.01);

    // Digits beyond the largest finite exponent are refused as they are typed.
    typeInto(exponent, QStringLiteral("1000000"));
    EXPECT_LE(exponent->value(), exponent->maximum());
    // λ = 0 is the mirror, n = ∞, shown as "mirror"; the box's top (3·128² − 1, the limit as
    // λ → 0) means it too, and "mirror" and "inf" can be typed.
    typeInto(exponent, QStringLiteral("49151"));
    EXPECT_EQ(doc.materialOf(1).lambda, 0.0f);
    EXPECT_EQ(exponent->text(), QStringLiteral("mirror"));
    typeInto(spin, QStringLiteral("2"));
    EXPECT_NE(exponent->text(), QStringLiteral("mirror"));
    typeInto(exponent, QStringLiteral("mirror"));
    EXPECT_EQ(doc.materialOf(1).lambda, 0.0f);
    EXPECT_EQ(exponent->text(), QStringLiteral("mirror"));
    typeInto(spin, QStringLiteral("2"));
    typeInto(exponent, QStringLiteral("inf"));  // QTest types Latin-1 only, so not "∞"
    EXPECT_EQ(doc.materialOf(1).lambda, 0.0f);
    typeInto(spin, QStringLiteral("0"));
    EXPECT_EQ(exponent->text(), QStringLiteral("mirror"));

    // The sharpest λ > 0 is not shown as a mirror.
    Material sharp = doc.materialOf(1);
    sharp.lambda = 1e-6f;
    doc.setMaterial(1, sharp);
    EXPECT_NE(exponent->text(), QStringLiteral("mirror"));

    // n = 0 (a uniform hemisphere) is λ(0) = log2(128·√3) ≈ 7.79, inside the range.
    typeInto(exponent, QStringLiteral("0"));
    EXPECT_NEAR(doc.materialOf(1).lambda, std::log2(128.0 * std::sqrt(3.0)), 1e-5);
    EXPECT_EQ(exponent->value(), 0.0);
}

// n = 1024 typed gives λ = exponentToLambda(1024) and shows 1024 back, under a 128² and a 512²
// environment alike: the panel's mapping does not depend on the face size.
TEST(MaterialPanel, ExponentIsIndependentOfTheFaceSize) {
    ShownPanel shown(0);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    auto* exponent = child<QDoubleSpinBox>(panel, "exponentSpin");
    auto* spin = child<QDoubleSpinBox>(panel, "lambdaSpin");
    auto* slider = child<QSlider>(panel, "lambdaSlider");
    ASSERT_TRUE(exponent && spin && slider);

    typeInto(exponent, QStringLiteral("1024"));
    // λ(1024) = log2(128·√3) − ½·log2(1025).
    const double expected = std::log2(128.0 * std::sqrt(3.0)) - 0.5 * std::log2(1025.0);
    EXPECT_NEAR(exponentToLambda(1024.0), expected, 1e-12);
    EXPECT_NEAR(doc.materialOf(0).lambda, expected, 1e-6);
    EXPECT_NEAR(exponent->value(), 1024.0, 0.005);
    const float lambda = doc.materialOf(0).lambda;
    const QString shownText = exponent->text();

    for (int faceSize : {512, 128, 64, 512}) {
        EnvironmentSettings e = doc.scene().environment;
        e.faceSize = faceSize;
        doc.setEnvironment(e);
        EXPECT_EQ(doc.materialOf(0).lambda, lambda) << faceSize;
        EXPECT_EQ(exponent->text(), shownText) << faceSize;
        EXPECT_NEAR(exponent->value(), 1024.0, 0.005) << faceSize;
        EXPECT_EQ(slider->maximum(), 8 * MaterialPanel::kSliderStepsPerLambda) << faceSize;
        EXPECT_DOUBLE_EQ(spin->maximum(), kMaxLambda) << faceSize;
    }
    // Typing it again under 512² gives the same λ.
    typeInto(spin, QStringLiteral("1"));
    typeInto(exponent, QStringLiteral("1024"));
    EXPECT_EQ(doc.materialOf(0).lambda, lambda);
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
    EXPECT_EQ(doc.materialOf(0).mode, LookupMode::Normal);
    EXPECT_TRUE(irradiance->isEnabled());
    clickIndicator(irradiance);
    EXPECT_TRUE(doc.materialOf(0).useIrradiance);
    clickIndicator(grazing);
    EXPECT_TRUE(doc.materialOf(0).sharperAtGrazing);
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

namespace {

// The centre of a slider's handle, where a user grabs it.
QPoint handleCentre(QSlider* slider) {
    QStyleOptionSlider opt;
    opt.initFrom(slider);
    opt.orientation = slider->orientation();
    opt.minimum = slider->minimum();
    opt.maximum = slider->maximum();
    opt.tickPosition = slider->tickPosition();
    opt.tickInterval = slider->tickInterval();
    opt.singleStep = slider->singleStep();
    opt.pageStep = slider->pageStep();
    opt.sliderPosition = slider->sliderPosition();
    opt.sliderValue = slider->value();
    opt.upsideDown = slider->invertedAppearance();
    return slider->style()->subControlRect(QStyle::CC_Slider, &opt, QStyle::SC_SliderHandle, slider).center();
}

// A drag of the handle by `dx` pixels in `steps` mouse moves.
void drag(QSlider* slider, int dx, int steps) {
    const QPoint start = handleCentre(slider);
    QTest::mousePress(slider, Qt::LeftButton, {}, start);
    for (int i = 1; i <= steps; ++i) QTest::mouseMove(slider, start + QPoint(dx * i / steps, 0));
    QTest::mouseRelease(slider, Qt::LeftButton, {}, start + QPoint(dx, 0));
}

void typeIntoLine(QLineEdit* edit, const QString& text) {
    edit->setFocus();
    edit->selectAll();
    QTest::keyClicks(edit, text);
    QTest::keyClick(edit, Qt::Key_Return);
}

}  // namespace

TEST(MaterialPanel, SliderDragIsOneUndoStep) {
    ShownPanel shown(0);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    auto* slider = child<QSlider>(shown.panel, "lambdaSlider");
    ASSERT_NE(slider, nullptr);
    ASSERT_EQ(doc.undoStack()->count(), 0);
    const float start = doc.materialOf(0).lambda;

    std::vector<float> seen;
    QObject::connect(&doc, &SceneDocument::materialChanged, &doc,
                     [&](int index) { if (index == 0) seen.push_back(doc.materialOf(0).lambda); });
    drag(slider, slider->width() / 4, 12);
    ASSERT_GE(seen.size(), 3u) << "the drag must pass through several values";
    const float dragged = doc.materialOf(0).lambda;
    EXPECT_GT(dragged, start + 0.5f);
    EXPECT_EQ(doc.undoStack()->count(), 1) << seen.size() << " values, one step";
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Change λ of left"));

    // A second drag is a second step.
    drag(slider, -slider->width() / 8, 6);
    EXPECT_LT(doc.materialOf(0).lambda, dragged);
    EXPECT_EQ(doc.undoStack()->count(), 2);
    doc.undoStack()->undo();
    EXPECT_EQ(doc.materialOf(0).lambda, dragged);
    doc.undoStack()->undo();
    EXPECT_EQ(doc.materialOf(0).lambda, start);
    EXPECT_EQ(slider->value(), static_cast<int>(std::lround(start * MaterialPanel::kSliderStepsPerLambda)));
}

TEST(MaterialPanel, RenamesAssignsAndMakesMaterialsUnique) {
    ShownPanel shown(0);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    auto* combo = child<QComboBox>(panel, "materialCombo");
    auto* name = child<QLineEdit>(panel, "materialNameEdit");
    auto* users = child<QLabel>(panel, "usersLabel");
    auto* unique = child<QPushButton>(panel, "makeUniqueButton");
    ASSERT_TRUE(combo && name && users && unique);
    EXPECT_EQ(combo->count(), 2);
    EXPECT_EQ(combo->currentText(), QStringLiteral("left"));
    EXPECT_EQ(name->text(), QStringLiteral("left"));
    EXPECT_FALSE(users->isVisible()) << "not shared";
    EXPECT_FALSE(unique->isEnabled());

    // Both objects on one material: the panel says so.
    doc.assignMaterial(1, doc.object(0).material);
    EXPECT_TRUE(users->isVisible());
    EXPECT_EQ(users->text(), QStringLiteral("used by 2 objects"));
    EXPECT_TRUE(unique->isEnabled());

    // Rename: both objects' material is renamed; a name another material has is refused.
    typeIntoLine(name, QStringLiteral("Gold"));
    EXPECT_EQ(doc.namedMaterialOf(0)->name, "Gold");
    EXPECT_EQ(doc.namedMaterialOf(1)->name, "Gold");
    EXPECT_EQ(combo->currentText(), QStringLiteral("Gold"));
    typeIntoLine(name, QStringLiteral("right"));
    EXPECT_EQ(doc.namedMaterialOf(0)->name, "Gold");
    EXPECT_EQ(name->text(), QStringLiteral("Gold"));

    // Assign: choosing "right" in the combo gives object 0 that material.
    const MaterialId gold = doc.object(0).material;
    const int rightItem = combo->findText(QStringLiteral("right"));
    ASSERT_GE(rightItem, 0);
    QTest::keyClick(combo, rightItem > combo->currentIndex() ? Qt::Key_Down : Qt::Key_Up);
    ASSERT_EQ(combo->currentIndex(), rightItem);
    EXPECT_EQ(doc.namedMaterialOf(0)->name, "right");
    EXPECT_EQ(doc.object(1).material, gold);
    EXPECT_FALSE(users->isVisible());
    doc.undoStack()->undo();
    EXPECT_EQ(doc.object(0).material, gold);
    EXPECT_EQ(combo->currentText(), QStringLiteral("Gold"));

    // Make unique: object 0 gets "Gold 2", the same parameters, and editing it leaves object 1.
    QTest::mouseClick(unique, Qt::LeftButton);
    const NamedMaterial* own = doc.namedMaterialOf(0);
    ASSERT_NE(own, nullptr);
    EXPECT_EQ(own->name, "Gold 2");
    EXPECT_NE(own->id, gold);
    EXPECT_EQ(own->material, doc.materialOf(1));
    EXPECT_EQ(doc.object(1).material, gold);
    EXPECT_FALSE(users->isVisible());
    EXPECT_EQ(combo->count(), 3);
    auto* spin = child<QDoubleSpinBox>(panel, "lambdaSpin");
    typeInto(spin, QStringLiteral("6"));
    EXPECT_FLOAT_EQ(doc.materialOf(0).lambda, 6.0f);
    EXPECT_FLOAT_EQ(doc.materialOf(1).lambda, 2.0f);
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    EXPECT_EQ(doc.object(0).material, gold);
    EXPECT_EQ(combo->count(), 2);
    EXPECT_TRUE(users->isVisible());
}

// Steps made in one spin box while it keeps the focus are one undo step; the next box, or the same
// box visited again, starts another.
TEST(MaterialPanel, StepsInOneBoxWhileFocusedAreOneUndoStep) {
    ShownPanel shown(1);
    ASSERT_TRUE(shown.exposed());
    shown.panel.activateWindow();
    if (!QTest::qWaitForWindowActive(&shown.panel)) GTEST_SKIP() << "the panel cannot be activated here";
    SceneDocument& doc = shown.doc;
    auto* x = child<QDoubleSpinBox>(shown.panel, "translateX");
    auto* y = child<QDoubleSpinBox>(shown.panel, "translateY");
    ASSERT_TRUE(x && y);
    const Transform start = doc.object(1).transform;
    typeInto(x, QStringLiteral("1"));
    QTest::keyClick(x, Qt::Key_Up);
    QTest::keyClick(x, Qt::Key_Up);
    typeInto(x, QStringLiteral("4"));
    EXPECT_FLOAT_EQ(doc.object(1).transform.translation.x, 4.0f);
    EXPECT_EQ(doc.undoStack()->count(), 1);
    typeInto(y, QStringLiteral("2"));  // another box: another step
    EXPECT_EQ(doc.undoStack()->count(), 2);
    typeInto(x, QStringLiteral("5"));  // back to the first: a new visit, a new step
    EXPECT_EQ(doc.undoStack()->count(), 3);
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    EXPECT_FLOAT_EQ(doc.object(1).transform.translation.x, 4.0f);
    EXPECT_EQ(doc.object(1).transform.translation.y, start.translation.y);
    doc.undoStack()->undo();
    EXPECT_EQ(doc.object(1).transform, start);
    EXPECT_DOUBLE_EQ(x->value(), static_cast<double>(start.translation.x));
}

// The layered editor: "Kind" switches and shows only that kind's editor; roughness, λ and n stay in
// step both ways; every value edit is one undo step; the document never holds an out-of-range value.
TEST(MaterialPanel, LayeredEditorSpeaksRoughnessMetalAndCoatKeptInStep) {
    ShownPanel shown(0);
    ASSERT_TRUE(shown.exposed());
    SceneDocument& doc = shown.doc;
    MaterialPanel& panel = shown.panel;
    auto* kind = child<QComboBox>(panel, "kindCombo");
    auto* layeredEditor = child<QWidget>(panel, "layeredEditor");
    auto* singleEditor = child<QWidget>(panel, "singleLobeEditor");
    auto* roughness = child<QDoubleSpinBox>(panel, "roughnessSpin");
    auto* roughnessSlider = child<QSlider>(panel, "roughnessSlider");
    auto* lambda = child<QDoubleSpinBox>(panel, "roughnessLambdaSpin");
    auto* exponent = child<QDoubleSpinBox>(panel, "roughnessExponentSpin");
    auto* metallic = child<QDoubleSpinBox>(panel, "metallicSpin");
    auto* coat = child<QDoubleSpinBox>(panel, "coatSpin");
    ASSERT_TRUE(kind && layeredEditor && singleEditor && roughness && roughnessSlider && lambda && exponent &&
                metallic && coat);
    EXPECT_FALSE(layeredEditor->isVisible());
    EXPECT_TRUE(singleEditor->isVisible());

    kind->setCurrentIndex(kind->findData(true));
    emit kind->activated(kind->currentIndex());
    ASSERT_TRUE(doc.materialOf(0).layered);
    EXPECT_TRUE(layeredEditor->isVisible());
    EXPECT_FALSE(singleEditor->isVisible());
    EXPECT_FALSE(doc.materialOf(1).layered) << "only the selected object's material";

    typeInto(roughness, QStringLiteral("0.3"));
    EXPECT_FLOAT_EQ(doc.materialOf(0).layers.roughness, 0.3f);
    EXPECT_EQ(roughnessSlider->value(), 30);
    EXPECT_NEAR(exponent->value(), roughnessToExponent(0.3), 0.006);
    EXPECT_NEAR(lambda->value(), exponentToLambda(roughnessToExponent(0.3)), 0.006);

    typeInto(lambda, QStringLiteral("3"));  // λ 3: n = 767
    EXPECT_NEAR(doc.materialOf(0).layers.roughness, exponentToRoughness(lambdaToExponent(3.0)), 1e-6);
    EXPECT_NEAR(exponent->value(), 767.0, 0.01);
    typeInto(exponent, QStringLiteral("mirror"));
    EXPECT_EQ(doc.materialOf(0).layers.roughness, 0.0f);
    EXPECT_EQ(lambda->value(), 0.0);

    const int steps = doc.undoStack()->count();
    typeInto(metallic, QStringLiteral("1"));
    typeInto(coat, QStringLiteral("0.75"));
    EXPECT_EQ(doc.materialOf(0).layers.metallic, 1.0f);
    EXPECT_EQ(doc.materialOf(0).layers.coat, 0.75f);
    EXPECT_EQ(doc.undoStack()->count(), steps + 2);
    typeInto(coat, QStringLiteral("7"));  // the box stops at 1
    EXPECT_LE(doc.materialOf(0).layers.coat, 1.0f);
    EXPECT_TRUE(isValidMaterial(doc.materialOf(0)));
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    EXPECT_EQ(doc.materialOf(0).layers.metallic, 0.0f);
    EXPECT_EQ(metallic->value(), 0.0);
    // KHR_materials_specular's weight: one undo step, shown again from the document.
    auto* specularWeight = child<QDoubleSpinBox>(panel, "specularWeightSpin");
    ASSERT_TRUE(specularWeight && child<QPushButton>(panel, "specularColorButton"));
    EXPECT_EQ(specularWeight->value(), 1.0);
    typeInto(specularWeight, QStringLiteral("0.25"));
    EXPECT_FLOAT_EQ(doc.materialOf(0).layers.specularWeight, 0.25f);
    doc.undoStack()->undo();
    EXPECT_EQ(doc.materialOf(0).layers.specularWeight, 1.0f);
    EXPECT_EQ(specularWeight->value(), 1.0);
    // For a human to look at: the panel as it shows a layered material.
    std::filesystem::create_directories(MIPGLOSS_TEST_OUTPUT_DIR);
    panel.grab().save(QStringLiteral(MIPGLOSS_TEST_OUTPUT_DIR "/material_panel_layered.png"));
}
