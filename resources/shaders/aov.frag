#version 410 core
// The renders anyone can check (mipgloss render --aov): per pixel, the direction the environment
// is read at (after the environment's rotation, i.e. in the frame of the baked faces), the Phong
// exponent of the lobe the pixel shows, and whether the pixel is meant to equal that lobe at that
// direction. The same shading plan as object.frag (shading_plan.glsl): plan, classify, write. A
// layered material adds, per layer, the direction it read, its lobe and the weight object.frag
// multiplies that lobe by (layered.glsl), so the picture at an exact pixel is
// Σ weight ⊙ lobe(direction); the single-lobe fields then describe its specular layer. A GGX layer
// (every layered material's specular and coat) reads K lookups: its weight is the layer's albedo,
// its direction R, and its pixels are never marked exact (the truth they are measured against is
// the glTF BRDF's integral, material_truth.h).
#include "shading_plan.glsl"

layout(location = 0) out vec4 aovDirection;  // xyz: unit direction, w: exponent
layout(location = 1) out vec4 aovExact;      // x: 1 exact, 0 not
layout(location = 2) out vec4 aovDiffuseDirection;  // layered: xyz the normal read, w: 1
layout(location = 3) out vec4 aovDiffuseWeight;     // rgb: its weight, w: N·v (every object)
layout(location = 4) out vec4 aovSpecularWeight;    // rgb: the specular layer's weight
layout(location = 5) out vec4 aovCoatDirection;     // xyz, w: the coat's exponent
layout(location = 6) out vec4 aovCoatWeight;        // rgb: the coat's weight

// Whether texture(cube, direction) here reads the base level alone (cube_lod.glsl: the level the
// GPU computes, not textureQueryLod, which on llvmpipe is levels off for cube maps).
bool baseOnly(samplerCube cube, vec3 direction) {
    return readsBaseLevelOnly(direction, float(textureSize(cube, 0).x));
}

// What one lobe lookup shows, as object.frag's readLobe makes it: the exponent, and whether the
// value is that lobe at that direction. Stack reads are exact (base level, the exact lobe widened
// by the footprint, which is the exponent reported) unless the footprint would widen the lobe past
// what the stack holds for it; a mirror read is exact where the GPU reads the mirror's base
// level; the chain standing in for a glossy lobe never is.
bool lobeRead(bool useStack, float n, vec3 d, vec3 dx, vec3 dy, samplerCube chain, out float shown) {
    bool complete;
    float widened = footprintLimitedExponent(n, dx, dy, complete);
    bool fromStack = useStack && stackHolds(widened);
    bool mirrorBase = isinf(n) && baseOnly(chain, d);
    shown = fromStack ? widened : n;
    return (fromStack && complete) || mirrorBase;
}

// What one layer's read (object.frag, readLayer) shows: its lobe (1 for the irradiance map) and
// whether it is exact. The grazing option's λ = 0 reads the chain's base standing in for the
// mirror: not exact.
bool classifyLayer(samplerCube chain, LayerRead r, out float shown) {
    shown = r.exponent;
    if (r.kind == READ_GGX) {
        // K lookups (object.frag, readGgx): no one lobe, so never exact; the exponent reported is
        // the Phong lobe with GGX's peak, n = 2/α² − 2 (Walter et al. 2007), kept above 0 (0 means
        // no object here).
        shown = max(2.0 / max(r.alpha * r.alpha, 1e-12) - 2.0, 1e-3);
        return false;
    }
    if (r.kind == READ_IRRADIANCE) return baseOnly(uIrradiance, r.direction);
    if (r.grazingMirror) return false;
    return lobeRead(r.useStack, r.exponent, r.direction, r.dx, r.dy, chain, shown);
}

void main() {
    FragmentPlan p = planFragment();
#ifdef LAYERED
    // The layers at the pixel's centre (object.frag shades the mean of its taps, placeTaps).
    planLayersAt(p, 0.0);
#endif
    float specularShown, diffuseShown, coatShown;
    bool exact = classifyLayer(uEnvironment, p.specular, specularShown);
    bool diffuse = p.diffuse.kind != READ_NONE, coat = p.coat.kind != READ_NONE;
    if (diffuse) exact = classifyLayer(uEnvironment, p.diffuse, diffuseShown) && exact;
    if (coat) exact = classifyLayer(uCoatChain, p.coat, coatShown) && exact;
    exact = exact && all(equal(p.emissive, vec3(0.0)));  // emission is not a lobe
    if (p.cut) discard;
    aovDirection = vec4(p.specular.direction, specularShown);
    aovExact = vec4(exact ? 1.0 : 0.0, 0.0, 0.0, 1.0);
    aovDiffuseDirection = diffuse ? vec4(p.diffuse.direction, diffuseShown) : vec4(0.0);
    aovDiffuseWeight = vec4(p.occlusion * p.wDiffuse, p.cosView);
    aovSpecularWeight = p.layered ? vec4(p.occlusion * (p.wSpecular + p.wSpecularEdge), 0.0) : vec4(0.0);
    aovCoatDirection = coat ? vec4(p.coat.direction, coatShown) : vec4(0.0);
    aovCoatWeight = coat ? vec4(p.occlusion * (p.wCoat + p.wCoatEdge), 0.0) : vec4(0.0);
}
