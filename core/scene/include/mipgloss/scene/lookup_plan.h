// How the GPU reads the environment for one object, decided here without OpenGL so it is tested
// headless; the renderer (ui/render/src/object_pass.cpp) only binds what planLookup returns. And the
// GLSL names of the values the shaders take from C++ (the lookup, the tone map), written once:
// shaderDefines() is put after each shader's #version line.
#pragma once

#include "mipgloss/scene/scene.h"

#include <string>

namespace mipgloss {

// What the shaders look the environment up by (object.frag, aov.frag: uLookup).
enum class ShaderLookup : int {
    Reflect = 0,     // the reflection vector, into the chain or the lobe stack
    Normal = 1,      // the normal, into the chain or the lobe stack
    Irradiance = 2,  // the normal, into the irradiance map (E/π)
};

struct ObjectLookup {
    ShaderLookup lookup = ShaderLookup::Reflect;
    float lambda = 0.0f;            // the material's λ; 0 (a mirror) when it is not a valid λ
    double exponent = 1.0;          // its Phong exponent n(λ) (phong.h)
    bool sharperAtGrazing = false;  // λ per fragment from the view angle (object.frag)
    bool readsLobeStack = false;     // read the lobe stack where it holds the lobe (lobes.h)
    bool mirror = false;            // read the mirror texture (λ = 0)
    // The sampler's GL_TEXTURE_MIN_LOD on the chain: the chain level standing in for the lobe
    // (phong.h, chainLevelForExponent); 0 for a mirror and for the per-fragment λ, whose shader
    // picks its own level.
    float minLevel = 0.0f;

    // Whether the chain stands in for the lobe where the stack does not hold it (a glossy lookup).
    bool readsChainForLobe() const { return lookup != ShaderLookup::Irradiance && lambda > 0.0f; }
};

// `irradianceReady`: the environment's irradiance map is on the GPU; `chainFaceSize`: the chain's
// base face size.
ObjectLookup planLookup(const Material& material, bool irradianceReady, int chainFaceSize);

// The background (background.frag): the environment seen along the view ray, blurred by the
// display's λ exactly as a reflect material of that λ is, so the plan is that material's (its lobe
// cube once ready, the chain level standing in meanwhile; an invalid λ is sharp).
ObjectLookup planBackground(float lambda, int chainFaceSize);

// A layered material's three lookups (layered.h), each planned as the single lobe it reads: the
// diffuse base by the normal at n = 1 (or the irradiance map once ready, when it asks), the
// specular layer and the coat by R at their own λ. `coat` is meaningful only when hasCoat.
struct LayeredLookup {
    ObjectLookup diffuse, specular, coat;
    bool hasCoat = false;
};
LayeredLookup planLayered(const Material& material, bool irradianceReady, int chainFaceSize);

// Whether a layered material is drawn with taps along each pixel's footprint (shading_plan.glsl,
// placeTaps; docs/material-truth.md, "The footprint's long axis"): a GGX layer sharper than
// kFootprintTapsRoughness, or a roughness map (its fragments may be). A rougher layer's lobe
// (α ≥ 0.25) is wider than R's sweep across a pixel but at a silhouette's last pixels, and the
// taps' program costs llvmpipe about a third more per frame even where no fragment takes a second
// tap, so such materials are drawn without them.
inline constexpr float kFootprintTapsRoughness = 0.5f;
inline constexpr int kMaxFootprintTaps = 4;
bool drawsFootprintTaps(const Material& material);

// "#define LOOKUP_REFLECT 0" ... and "#define TONE_MAP_LINEAR 0" ..., one line each; and the
// split-sum table's shape and the coat's F0 for layered.glsl (specular.h).
std::string shaderDefines();

}  // namespace mipgloss
