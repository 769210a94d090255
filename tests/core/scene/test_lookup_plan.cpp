// planLookup: what the renderer binds for one object (lookup_plan.h), and the shaders' names for
// the C++ enums.
#include "mipgloss/scene/lookup_plan.h"

#include "mipgloss/ibl/phong.h"

#include <gtest/gtest.h>

#include <limits>

using namespace mipgloss;

namespace {

constexpr int kFace = 256;

Material material(float lambda, LookupMode mode = LookupMode::Reflect) {
    Material m;
    m.lambda = lambda;
    m.mode = mode;
    return m;
}

// The taps along a pixel's footprint are drawn for a layered material whose GGX layer (the
// specular, or a coat there is) is under roughness 0.5, or whose roughness comes from a map;
// never for the single lobe; and the shader's cap is the plan's.
TEST(LookupPlan, PolishedLayersAndRoughnessMapsAreDrawnWithFootprintTaps) {
    Material single;
    EXPECT_FALSE(drawsFootprintTaps(single));
    Material rough;
    rough.layered = true;
    rough.layers.roughness = kFootprintTapsRoughness;
    EXPECT_FALSE(drawsFootprintTaps(rough));
    Material polished = rough;
    polished.layers.roughness = 0.3f;
    EXPECT_TRUE(drawsFootprintTaps(polished));
    Material coated = rough;
    coated.layers.coat = 1.0f;
    coated.layers.coatRoughness = 0.1f;
    EXPECT_TRUE(drawsFootprintTaps(coated));
    coated.layers.coat = 0.0f;  // no coat: its roughness means nothing
    EXPECT_FALSE(drawsFootprintTaps(coated));
    Material mapped = rough;
    mapped.layers.maps.roughness.file = "roughness.png";
    EXPECT_TRUE(drawsFootprintTaps(mapped));
    EXPECT_NE(shaderDefines().find("#define MAX_FOOTPRINT_TAPS_DRAWN " + std::to_string(kMaxFootprintTaps) + "\n"),
              std::string::npos);
}

}  // namespace

TEST(LookupPlan, MirrorReadsTheMirrorTextureAtLevelZeroWithNoStackEntry) {
    const ObjectLookup plan = planLookup(material(0.0f), true, kFace);
    EXPECT_EQ(plan.lookup, ShaderLookup::Reflect);
    EXPECT_TRUE(plan.mirror);
    EXPECT_FALSE(plan.readsLobeStack);
    EXPECT_FALSE(plan.readsChainForLobe());
    EXPECT_EQ(plan.minLevel, 0.0f);
    EXPECT_EQ(plan.exponent, lambdaToExponent(0.0));
}

TEST(LookupPlan, GlossyReadsItsStackEntryAndTheChainLevelOfItsExponentMeanwhile) {
    for (const LookupMode mode : {LookupMode::Reflect, LookupMode::Normal}) {
        const ObjectLookup plan = planLookup(material(3.5f, mode), false, kFace);
        EXPECT_EQ(plan.lookup, mode == LookupMode::Reflect ? ShaderLookup::Reflect : ShaderLookup::Normal);
        EXPECT_FALSE(plan.mirror);
        EXPECT_TRUE(plan.readsLobeStack);
        EXPECT_TRUE(plan.readsChainForLobe());
        EXPECT_EQ(plan.exponent, lambdaToExponent(3.5));
        EXPECT_FLOAT_EQ(plan.minLevel, static_cast<float>(chainLevelForExponent(lambdaToExponent(3.5), kFace)));
        EXPECT_GT(plan.minLevel, 0.0f);
    }
}

TEST(LookupPlan, IrradianceIsReadByTheNormalOnlyOnceItsMapIsReady) {
    Material m = material(6.0f, LookupMode::Normal);
    m.useIrradiance = true;
    const ObjectLookup ready = planLookup(m, true, kFace);
    EXPECT_EQ(ready.lookup, ShaderLookup::Irradiance);
    EXPECT_FALSE(ready.readsLobeStack);
    EXPECT_FALSE(ready.mirror);
    EXPECT_FALSE(ready.readsChainForLobe());
    // Until it is, the chain at λ stands in, as for any glossy normal lookup.
    const ObjectLookup waiting = planLookup(m, false, kFace);
    EXPECT_EQ(waiting.lookup, ShaderLookup::Normal);
    EXPECT_TRUE(waiting.readsLobeStack);
    // The irradiance map never applies to a reflection.
    m.mode = LookupMode::Reflect;
    EXPECT_EQ(planLookup(m, true, kFace).lookup, ShaderLookup::Reflect);
}

TEST(LookupPlan, SharperAtGrazingReadsEachFragmentsLobeFromTheStackOrItsOwnChainLevel) {
    Material m = material(4.0f);
    m.sharperAtGrazing = true;
    const ObjectLookup plan = planLookup(m, true, kFace);
    EXPECT_TRUE(plan.sharperAtGrazing);
    EXPECT_TRUE(plan.readsLobeStack) << "the lobe stack holds every fragment's own lobe";
    EXPECT_EQ(plan.minLevel, 0.0f);
    EXPECT_EQ(plan.lambda, 4.0f);
    // Not for the irradiance map, which has no levels to pick.
    m.mode = LookupMode::Normal;
    m.useIrradiance = true;
    EXPECT_FALSE(planLookup(m, true, kFace).sharperAtGrazing);
}

TEST(LookupPlan, AnInvalidLambdaIsDrawnAsAMirror) {
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), -1.0f, 1e9f}) {
        const ObjectLookup plan = planLookup(material(bad), true, kFace);
        EXPECT_EQ(plan.lambda, 0.0f) << bad;
        EXPECT_TRUE(plan.mirror) << bad;
        EXPECT_FALSE(plan.readsLobeStack) << bad;
    }
}

TEST(LookupPlan, TheBackgroundIsPlannedAsAReflectMaterialOfItsBlur) {
    for (const float lambda : {0.0f, 0.5f, 3.5f, 7.9f}) {
        const ObjectLookup background = planBackground(lambda, kFace);
        const ObjectLookup object = planLookup(material(lambda), true, kFace);
        EXPECT_EQ(background.lookup, ShaderLookup::Reflect) << lambda;
        EXPECT_EQ(background.mirror, lambda == 0.0f) << lambda;
        EXPECT_EQ(background.readsLobeStack, lambda > 0.0f) << lambda;
        EXPECT_EQ(background.minLevel, object.minLevel) << lambda;
        EXPECT_FLOAT_EQ(background.minLevel,
                        lambda > 0.0f ? static_cast<float>(chainLevelForExponent(lambdaToExponent(lambda), kFace)) : 0.0f);
    }
    const ObjectLookup nan = planBackground(std::numeric_limits<float>::quiet_NaN(), kFace);
    EXPECT_EQ(nan.minLevel, 0.0f);
    EXPECT_FALSE(nan.readsLobeStack);
}

TEST(LookupPlan, ShaderDefinesNameEveryEnumValueTheShadersCompare) {
    const std::string defines = shaderDefines();
    EXPECT_NE(defines.find("#define LOOKUP_REFLECT 0\n"), std::string::npos);
    EXPECT_NE(defines.find("#define LOOKUP_NORMAL 1\n"), std::string::npos);
    EXPECT_NE(defines.find("#define LOOKUP_IRRADIANCE 2\n"), std::string::npos);
    EXPECT_NE(defines.find("#define TONE_MAP_LINEAR " + std::to_string(static_cast<int>(ToneMap::Linear)) + "\n"),
              std::string::npos);
    EXPECT_NE(defines.find("#define TONE_MAP_REINHARD " + std::to_string(static_cast<int>(ToneMap::Reinhard)) + "\n"),
              std::string::npos);
    EXPECT_NE(defines.find("#define TONE_MAP_ACES " + std::to_string(static_cast<int>(ToneMap::Aces)) + "\n"),
              std::string::npos);
}
