#version 410 core
// One environment lookup per layer and fragment (Ashikhmin & Ghosh 2002, §4), at the lobe the
// material means, as the shading plan says (shading_plan.glsl): plan, read, sum. Where the lobe
// stack holds a lobe (lobe_stack.glsl, core/scene/lobes.h) the lookup reads the exact lobe,
// widened by the pixel's footprint, for any λ, per object or per fragment. Where it does not yet
// (an entry still being made, a lobe sharper than the stack's top) it reads the chain: the bound
// sampler's GL_TEXTURE_MIN_LOD is the chain level standing in for the lobe (phong.h,
// chainLevelForExponent), trilinear.
//
// Built twice: without and with MATERIAL_MAPS (the layered materials with texture maps, drawn by
// a program of their own, because a shader runs every branch it holds for each fragment on a CPU
// rasterizer (llvmpipe: masked SIMD) and the maps' reads made every other object six times slower
// there).
#include "shading_plan.glsl"

// Lobe n at direction d (unit; dx, dy its change to the next pixels): the stack's exact lobe
// widened by the footprint when it holds it, else the chain with the same derivatives (explicit,
// as this branch is not uniform across fragments).
vec3 readLobe(samplerCube chain, bool useStack, float n, vec3 d, vec3 dx, vec3 dy) {
    if (useStack) {
        bool complete;
        float shown = footprintLimitedExponent(n, dx, dy, complete);
        if (stackHolds(shown)) return stackRead(d, shown);
    }
    return textureGrad(chain, d, dx, dy).rgb;
}

// A lobe chosen per fragment (READ_LEVEL): the stack's exact lobe where it may and does hold it,
// else the chain at λ's level, never sharper than the footprint's level as the specification
// defines it (cube_lod.glsl: llvmpipe's textureQueryLod is levels off for cube maps and read a
// blurry level at the sphere's centre).
vec3 readLevel(LayerRead r) {
    bool complete;
    float shown = footprintLimitedExponent(r.exponent, r.dx, r.dy, complete);
    if (r.useStack && stackHolds(shown)) return stackRead(r.direction, shown);
    float level = r.lambda > 0.0 ? clamp(r.lambda + uLevelOffset, 0.0, uLastLevel) : 0.0;
    float footprint = cubeLevelOfDetail(r.direction, float(textureSize(uEnvironment, 0).x));
    return textureLod(uEnvironment, r.direction, max(level, footprint)).rgb;
}

// One layer's value; `chain` is the layer's (its sampler holds the level standing in for its lobe).
// Branches, not ?: (a select evaluates both sides, and the per-fragment read is the dearer).
vec3 readLayer(samplerCube chain, LayerRead r) {
    if (r.kind == READ_NONE) return vec3(0.0);
    if (r.kind == READ_IRRADIANCE) return texture(uIrradiance, r.direction).rgb;
    if (r.kind == READ_LEVEL) return readLevel(r);
    return readLobe(chain, r.useStack, r.exponent, r.direction, r.dx, r.dy);
}

layout(location = 0) out vec4 fragColour;

void main() {
    FragmentPlan p = planFragment();
    vec3 diffuse = readLayer(uDiffuseChain, p.diffuse);
    vec3 specular = readLayer(uEnvironment, p.specular);
    vec3 coat = readLayer(uCoatChain, p.coat);
    if (p.cut) discard;
    fragColour = vec4(p.occlusion * (p.wDiffuse * diffuse + p.wSpecular * specular + p.wCoat * coat) + p.emissive, 1.0);
}
