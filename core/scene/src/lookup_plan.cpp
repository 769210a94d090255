#include "mipgloss/scene/lookup_plan.h"

#include "mipgloss/ibl/bright_lights.h"
#include "mipgloss/ibl/ggx_fitted_lobes.h"
#include "mipgloss/ibl/ggx_sampling.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/scene/layered.h"
#include "mipgloss/scene/lobes.h"

#include <sstream>

namespace mipgloss {

ObjectLookup planLookup(const Material& material, bool irradianceReady, int chainFaceSize) {
    ObjectLookup plan;
    plan.lambda = isValidLambda(material.lambda) ? material.lambda : 0.0f;
    plan.exponent = lambdaToExponent(plan.lambda);
    plan.lookup = material.mode == LookupMode::Reflect ? ShaderLookup::Reflect : ShaderLookup::Normal;
    if (plan.lookup == ShaderLookup::Normal && material.useIrradiance && irradianceReady)
        plan.lookup = ShaderLookup::Irradiance;
    const bool chainOrLobe = plan.lookup != ShaderLookup::Irradiance;
    plan.sharperAtGrazing = material.sharperAtGrazing && chainOrLobe;
    plan.mirror = plan.lambda <= 0.0f && chainOrLobe;
    plan.readsLobeStack = chainOrLobe && plan.lambda > 0.0f;
    plan.minLevel = material.sharperAtGrazing || plan.mirror
                        ? 0.0f
                        : static_cast<float>(chainLevelForExponent(plan.exponent, chainFaceSize));
    return plan;
}

ObjectLookup planBackground(float lambda, int chainFaceSize) {
    Material seen;
    seen.lambda = lambda;
    seen.mode = LookupMode::Reflect;
    return planLookup(seen, false, chainFaceSize);
}

LayeredLookup planLayered(const Material& material, bool irradianceReady, int chainFaceSize) {
    auto single = [&](double lambda, LookupMode mode, bool useIrradiance) {
        Material m;
        m.lambda = static_cast<float>(lambda);
        m.mode = mode;
        m.useIrradiance = useIrradiance;
        return planLookup(m, irradianceReady, chainFaceSize);
    };
    // A GGX layer of any roughness above 0 reads its lobes per fragment (object.frag, readGgx),
    // from the stack where it holds them and else from the chain at each lobe's level: never the
    // mirror texture, whose levels are GL's 2 × 2 box mips, though a near-mirror's λ is 0. Read
    // there, a near-mirror's tail lobes saw a sun 0.1 rad off R as a box of two texels, not as
    // its lobe does (sunrise, r 0.05: 6.0 where the truth is 9.2; docs/material-truth.md, "The
    // near-mirror's tail"). Only r = 0, one lookup along R, is the mirror.
    auto ggx = [&](double roughness, double lambda) {
        ObjectLookup p = single(lambda, LookupMode::Reflect, false);
        if (roughness > 0.0) {
            p.mirror = false;
            p.readsLobeStack = true;
            p.minLevel = 0.0f;
        }
        return p;
    };
    const Layers& l = material.layers;
    LayeredLookup plan;
    plan.diffuse = single(diffuseLambda(), LookupMode::Normal, material.useIrradiance);
    plan.specular = ggx(l.roughness, specularLambda(l));
    plan.hasCoat = hasCoat(l);
    if (plan.hasCoat) plan.coat = ggx(l.coatRoughness, coatLambda(l));
    return plan;
}

bool drawsFootprintTaps(const Material& material) {
    if (!material.layered) return false;
    const Layers& l = material.layers;
    return l.roughness < kFootprintTapsRoughness || (l.coat > 0.0f && l.coatRoughness < kFootprintTapsRoughness) ||
           !l.maps.roughness.empty();
}

std::string shaderDefines() {
    std::string text;
    auto define = [&](const char* name, int value) {
        text += "#define " + std::string(name) + " " + std::to_string(value) + "\n";
    };
    define("LOOKUP_REFLECT", static_cast<int>(ShaderLookup::Reflect));
    define("LOOKUP_NORMAL", static_cast<int>(ShaderLookup::Normal));
    define("LOOKUP_IRRADIANCE", static_cast<int>(ShaderLookup::Irradiance));
    define("TONE_MAP_LINEAR", static_cast<int>(ToneMap::Linear));
    define("TONE_MAP_REINHARD", static_cast<int>(ToneMap::Reinhard));
    define("TONE_MAP_ACES", static_cast<int>(ToneMap::Aces));
    define("TONE_MAP_PBR_NEUTRAL", static_cast<int>(ToneMap::PbrNeutral));
    define("TONE_MAP_AGX", static_cast<int>(ToneMap::Agx));
    // The GGX albedo table (ggx_sampling.h, layered.glsl) and the lookups' lobes.
    define("GGX_ROUGHNESS_STEPS", GgxAlbedoTable::kRoughnessSteps);
    define("MAX_FOOTPRINT_TAPS_DRAWN", kMaxFootprintTaps);
    define("GGX_COS_STEPS", GgxAlbedoTable::kCosSteps);
    auto defineFloat = [&](const char* name, double value) {
        std::ostringstream number;
        number.precision(9);
        number << std::showpoint << value;
        text += "#define " + std::string(name) + " " + number.str() + "\n";
    };
    defineFloat("MAX_LAMBDA", kMaxLambda);
    defineFloat("COAT_F0", kDielectricF0);
    define("MAX_BRIGHT_LIGHTS", kMaxBrightLights);
    defineFloat("SAMPLE_SPREAD", kSampleSpread);
    // The fitted lobes' grid (ggx_fitted_lobes.h).
    define("FITTED_COS_NODES", kFittedCosNodes);
    define("FITTED_ROUGHNESS_NODES", kFittedRoughnessNodes);
    defineFloat("FITTED_LEAST_ROUGHNESS", kFittedLeastRoughness);
    defineFloat("FITTED_ROUGHNESS_STEP", kFittedRoughnessStep);
    // The lobe stack (lobes.h, lobe_stack.glsl) and λ ↔ n (phong.h): n(λ) = 3·128²·4^−λ − 1.
    define("STACK_SLOTS", kStackSlots);
    define("STACK_STEPS_PER_LEVEL", kStackStepsPerLevel);
    define("STACK_LAST", kStackLast);
    define("STACK_FOOTPRINT_REACH", kFootprintReach);
    defineFloat("LAMBDA_EXPONENT_SCALE", 3.0 * kLambdaReferenceSize * kLambdaReferenceSize);
    // Texture maps (material_maps.glsl): the alpha modes (scene.h).
    define("ALPHA_OPAQUE", static_cast<int>(AlphaMode::Opaque));
    define("ALPHA_MASK", static_cast<int>(AlphaMode::Mask));
    define("ALPHA_BLEND", static_cast<int>(AlphaMode::Blend));
    return text;
}

}  // namespace mipgloss
