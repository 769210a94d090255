#version 410 core
// One environment lookup per layer and fragment (Ashikhmin & Ghosh 2002, §4), at the lobe the
// material means, as the shading plan says (shading_plan.glsl): plan, read, sum. Where the lobe
// stack holds a lobe (lobe_stack.glsl, core/scene/lobes.h) the lookup reads the exact lobe,
// widened by the pixel's footprint, for any λ, per object or per fragment. Where it does not yet
// (an entry still being made, a lobe sharper than the stack's top) it reads the chain: the bound
// sampler's GL_TEXTURE_MIN_LOD is the chain level standing in for the lobe (phong.h,
// chainLevelForExponent), trilinear.
//
// Built three times: the single lobe; LAYERED (the glTF material); LAYERED with MATERIAL_MAPS (with
// texture maps). Each kind of material has a program of its own, because a shader runs every
// branch it holds for each fragment on a CPU rasterizer (llvmpipe: masked SIMD): the maps' reads
// made every other object six times slower there, and the GGX lookups the single lobe 1.75×.
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

#ifdef LAYERED
// Lookup k of `count` of a GGX layer (layered.glsl, ggxLookup) in the frame (t, b, N): its light
// direction in the environment's frame, the lobe it reads (its share of the GGX lobe, widened by
// readGgx's footprint share `footprint`, lobe_stack.glsl widenedExponent), the stack's nearest
// entry to that lobe (2^¼ apart in n: within 9 % of it, which a lookup's share does not resolve)
// and its weights G2/G1·(1 − (1 − v·h)⁵) and G2/G1·(1 − v·h)⁵ (0 below the horizon).
struct LayerLookup {
    vec3 light;
    float shown;
    int entry;
    float weightA, weightB;
};

LayerLookup layerLookup(LayerRead r, vec3 v, vec3 t, vec3 b, float footprint, int k, int count) {
    GgxLookup g = ggxLookup(r.alpha, v, k, count);
    float n = lookupExponent(g.pdf, count);
    LayerLookup q;
    q.shown = widenedExponent(n, footprint);
    vec3 l = keptAboveHorizon(g.light, q.shown);
    q.light = normalize(l.x * t + l.y * b + l.z * r.normal);
    q.entry = stackNearestIndex(q.shown);
    q.weightA = max(g.weight, 0.0) * (1.0 - g.fresnelEdge);
    q.weightB = max(g.weight, 0.0) * g.fresnelEdge;
    return q;
}

// A held lookup's value (below): the stack's entry nearest its lobe (clamped to the layer's), of the
// remainder when the layer reads it, else of the whole environment less the lights in that lobe.
vec3 heldRead(LayerRead r, vec3 light, int entry, int subtracted) {
    int j = clamp(entry, r.entries.x, r.entries.y);
    // One read, of one table or the other (a select: both tables are uniforms).
    vec4 e = r.remainder ? uRemainderEntry[j] : vec4(uStackEntry[j].xyz, uStackScale[j]);
    return atlasRead(e.xyz, e.w, light) - lightsThrough(light, uStackExponent[j], subtracted);
}

// A held lobe n blended between the layer's two entries either side of it (lobe_stack.glsl,
// stackBlendOf: the blend keeps n's mean cosine), each read as heldRead reads it. The mean lobe
// reads so: its exponent moves smoothly over the sphere, and one entry (2^¼ apart in n + 1) drew a
// ring where the nearest changed.
vec3 heldBlend(LayerRead r, vec3 light, float n, int subtracted) {
    int j = clamp(stackSharperIndex(n), r.entries.x, r.entries.y);
    int wider = min(j + 1, r.entries.y);
    float w = stackBlendWeight(n, j, wider);
    return mix(heldRead(r, light, j, subtracted), heldRead(r, light, wider, subtracted), w);
}

// The chain level holding lobe n (phong.h, regularScheduleLevel): 0 for the mirror.
float chainLevelOf(float n) { return isinf(n) ? 0.0 : clamp(exponentLambda(n) + uLevelOffset, 0.0, uLastLevel); }

// A lookup's value where the stack may not hold it: its entry where the stack holds it, else the
// chain at the level that holds the lobe the footprint shows (phong.h, regularScheduleLevel): a
// near-mirror lookup reads the base, not a blurred level the hardware's footprint would pick (a
// level's lobe is 3.6 of its texels wide); less the lights in that lobe, shaded exactly instead.
vec3 chainRead(LayerRead r, vec3 light, float shown, int entry, int apart) {
    vec3 value;
    if (r.useStack && entry >= r.entries.x) {
        int j = min(entry, r.entries.y);
        shown = uStackExponent[j];
        value = stackEntryAt(j, light);
    } else {
        value = textureLod(uEnvironment, light, chainLevelOf(shown)).rgb;
    }
    return value - lightsThrough(light, shown, apart);
}

// A fitted lobe's value where the stack may not hold it (a near-mirror layer's): as chainRead, but
// a lobe sharper than the stack's range yet wider than the base's bilinear tent (at face 256 the
// stack's sharpest is n ≈ 7300, 1.5 texels; a near-mirror's fitted lobes reach 3·10⁵) is four
// bilinear taps of the base spread ±s along two axes across it, s² = 1/(n + 2) − τ²/6 (the lobe's
// variance per axis less the tent's, τ = 2/N a texel), not one read as sharp as a texel: on the
// CPU with exact lobes, forest metal r 0.05 at 384² 14.7 % as points, 4.3 % with the taps, 1.3 %
// exact (docs/material-truth.md, "The near-mirror's tail"). One loop's body: no branch to pay
// twice on a CPU rasterizer, only its reads.
vec3 fittedChainRead(LayerRead r, vec3 light, float shown, int apart) {
    int entry = stackNearestIndex(shown);
    if (r.useStack && entry >= r.entries.x) {
        int j = min(entry, r.entries.y);
        return stackEntryAt(j, light) - lightsThrough(light, uStackExponent[j], apart);
    }
    float level = chainLevelOf(shown);
    float texel = 2.0 / float(textureSize(uEnvironment, 0).x);
    float spread = level > 0.0 || isinf(shown) ? 0.0 : sqrt(max(1.0 / (shown + 2.0) - texel * texel / 6.0, 0.0));
    vec3 e1 = normalize(cross(light, abs(light.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    vec3 e2 = cross(light, e1);
    vec3 a = spread * (e1 + e2), b = spread * (e1 - e2);
    vec3 value = 0.25 * (textureLod(uEnvironment, light + a, level).rgb + textureLod(uEnvironment, light - a, level).rgb +
                         textureLod(uEnvironment, light + b, level).rgb + textureLod(uEnvironment, light - b, level).rgb);
    return value - lightsThrough(light, shown, apart);
}

// A GGX layer (READ_GGX, layered.glsl): K lookups at GGX's visible normals, each the stack's exact
// lobe as wide as its share of the GGX lobe (widened by the footprint of R), read from its light
// raised until the lobe's half-maximum is above the horizon (keptAboveHorizon), their means weighted
// by G2/G1·(1 − (1 − v·h)⁵) and by G2/G1·(1 − v·h)⁵, which the plan's weights (the table's A and B)
// multiply; plus the bright lights through the exact BRDF of Fresnel `f0`, `f90`, times `layer`
// (what the coat leaves, or takes; and multiple scattering's factor on the specular). One lookup
// along R for the mirror.
//
// Two loops, of which a draw runs one (the other counts to 0): a CPU rasterizer runs both sides
// of every branch for every fragment (llvmpipe: masked SIMD), but no loop that no fragment enters.
//   held    (the stack holds the layer's lookups head-on: lobes.h, ggxLookupsHeld) one atlas read
//           per lookup, a sharper one (toward grazing) of the range's first entry; of the
//           remainder's entry (bright_lights.h: no lights in it) when read, else of the whole
//           environment's less what the lights put in that lobe;
//   else    per lookup the stack's entry where it holds it, else the chain at the level holding
//           the lobe, less the lights' share: an entry still being made, a lobe sharper than the
//           stack's first (near-mirror layers), a roughness map's fragments.
vec3 readGgx(LayerRead r, vec3 weight, vec3 edgeWeight, vec3 f0, float f90, vec3 layer) {
    float cosView = clamp(dot(r.normal, r.view), 1e-4, 1.0);
    vec3 t = r.view - cosView * r.normal;
    float tl = length(t);
    t = tl > 1e-6 ? t / tl : normalize(cross(r.normal, abs(r.normal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    vec3 b = cross(r.normal, t);
    vec3 v = vec3(sqrt(max(0.0, 1.0 - cosView * cosView)), 0.0, cosView);
    // A rough layer reads its mean lobe (ggx_sampling.h, meanLobeShare) instead of, or blended
    // with, its K lookups: no loop runs that the layer does not read.
    int count = r.meanShare >= 1.0 ? 0 : (r.alpha > 0.0 ? max(r.lookups, 1) : 1);
    vec3 sumA = vec3(0.0), sumB = vec3(0.0);
    float weightA = 0.0, weightB = 0.0;
    // The lights are points: shaded apart only where the lobe is wider than a few base texels
    // (uLightsMinAlpha, object_pass.cpp); a sharper lobe reads them in the environment.
    bool split = r.alpha >= uLightsMinAlpha;
    bool subtract = split && !r.remainder;
    // The lights each loop goes through: none where it would discard them (lightsThrough).
    int apart = split ? uLightCount : 0, subtracted = subtract ? uLightCount : 0;
    // The footprint widens every lookup's lobe the same way (lobe_stack.glsl, widenedExponent), by
    // what the fragment's taps along the footprint's long axis leave of it (shading_plan.glsl,
    // placeTaps): with one tap the disc as large as the pixel's parallelogram of directions.
    float footprint = r.footprint;
    // Layers read their fitted lobes (ggx_fitted_lobes.h) where they have them, else the visible
    // normals: held, each from the atlas; else each as chainRead reads a lookup (a near-mirror's
    // sharp lobes from the chain's base, its tail's from the stack). The visible normals' chain
    // loop starts where the others end.
    int fittedCount = r.held && r.fitted ? count : 0;
    int fittedChain = !r.held && r.fitted ? count : 0;
    int held = r.held && !r.fitted ? count : 0;
    int chainFrom = r.held || r.fitted ? count : 0;
    vec2 fittedAt = fittedLobeCoordinates(sqrt(r.alpha), cosView);
    for (int k = 0; k < fittedChain; ++k) {
        FittedLobe f = fittedLobe(fittedAt, r.alpha, v, k);
        vec3 light = normalize(f.direction.x * t + f.direction.y * b + f.direction.z * r.normal);
        vec3 value = fittedChainRead(r, light, widenedExponent(f.exponent, footprint), apart);
        sumA += f.weights.x * value;
        sumB += f.weights.y * value;
        weightA += f.weights.x;
        weightB += f.weights.y;
    }
    for (int k = 0; k < fittedCount; ++k) {
        FittedLobe f = fittedLobe(fittedAt, r.alpha, v, k);
        vec3 light = normalize(f.direction.x * t + f.direction.y * b + f.direction.z * r.normal);
        vec3 value = heldRead(r, light, stackNearestIndex(widenedExponent(f.exponent, footprint)), subtracted);
        sumA += f.weights.x * value;
        sumB += f.weights.y * value;
        weightA += f.weights.x;
        weightB += f.weights.y;
    }
    for (int k = 0; k < held; ++k) {
        LayerLookup q = layerLookup(r, v, t, b, footprint, k, count);
        vec3 value = heldRead(r, q.light, q.entry, subtracted);
        sumA += q.weightA * value;
        sumB += q.weightB * value;
        weightA += q.weightA;
        weightB += q.weightB;
    }
    for (int k = chainFrom; k < count; ++k) {
        LayerLookup q = layerLookup(r, v, t, b, footprint, k, count);
        vec3 value = chainRead(r, q.light, q.shown, q.entry, apart);
        sumA += q.weightA * value;
        sumB += q.weightB * value;
        weightA += q.weightA;
        weightB += q.weightB;
    }
    vec3 meanA = weightA > 0.0 ? sumA / weightA : vec3(0.0), meanB = weightB > 0.0 ? sumB / weightB : vec3(0.0);
    // The mean lobe: one read, from the stack as the lookups read it, not kept above the horizon
    // (its direction is the clamped lobe's mean already).
    int meanReads = r.meanShare > 0.0 ? 1 : 0;
    for (int k = 0; k < meanReads; ++k) {
        vec4 m = ggxMeanLobe(sqrt(r.alpha), cosView);
        float shown = widenedExponent(m.w, footprint);
        vec3 light = normalize(m.x * t + m.z * r.normal);
        vec3 value = r.held ? heldBlend(r, light, shown, subtracted) : chainRead(r, light, shown, stackNearestIndex(shown), apart);
        meanA = mix(meanA, value, r.meanShare);
        meanB = mix(meanB, value, r.meanShare);
    }
    vec3 lookups = weight * meanA + edgeWeight * meanB;
    return lookups + layer * lightsSpecular(r.normal, t, b, r.view, r.alpha, f0, f90, apart);
}

// The diffuse base: its read less the bright lights' Lambert share, weighted, plus the lights
// through glTF's diffuse exactly.
vec3 readDiffuse(FragmentPlan p) {
    vec3 value = readLayer(uDiffuseChain, p.diffuse);
    vec3 exact, lambert;
    lightsDiffuse(p.specular.normal, p.specular.view, p.diffuseF0, p.f90, exact, lambert);
    return p.wDiffuse * (value - lambert) + (1.0 - p.coatWeight) * p.diffuseColour * exact;
}

// The diffuse, specular and coat of a layered fragment placed `offset` pixels along its footprint's
// long axis (shading_plan.glsl, planLayersAt, which replaces p's layers and weights and keeps the
// rest: no copy of the plan, which llvmpipe pays for).
vec3 layeredAt(inout FragmentPlan p, float offset) {
    planLayersAt(p, offset);
    vec3 diffuse = readDiffuse(p);
    vec3 specular = readGgx(p.specular, p.wSpecular, p.wSpecularEdge, p.f0, p.f90, (1.0 - p.coatWeight) * p.compensation);
    vec3 coat = vec3(0.0);
    // The coat lobe has no Fresnel of its own (KHR_materials_clearcoat: its Fresnel is the mix's).
    if (p.coat.kind == READ_GGX) coat = readGgx(p.coat, p.wCoat, p.wCoatEdge, vec3(1.0), 1.0, vec3(p.coatWeight));
    return diffuse + specular + coat;
}

#endif

layout(location = 0) out vec4 fragColour;

void main() {
    FragmentPlan p = planFragment();
#ifdef LAYERED
    // The pixel's mean over its taps along the footprint's long axis (placeTaps): the first tap
    // outside any loop, so a fragment with one (all but those where R sweeps a sliver several
    // lobes long) pays nothing for the others' (a CPU rasterizer runs no loop no fragment enters).
    vec3 sum = layeredAt(p, tapOffset(p, 0));
#ifdef FOOTPRINT_TAPS
    // Only in the taps' program (lookup_plan.h, drawsFootprintTaps): the loop's code alone, entered
    // by no fragment, made llvmpipe's layered frame a third slower.
    for (int i = 1; i < p.taps; ++i) sum += layeredAt(p, tapOffset(p, i));
#endif
    if (p.cut) discard;
    // A blended material's alpha is its coverage (glTF): the renderer blends it over what is
    // behind (object_pass.cpp).
    fragColour = vec4(p.occlusion * sum / float(p.taps) + p.emissive, p.alpha);
#else
    vec3 value = p.wSpecular * readLayer(uEnvironment, p.specular);
    fragColour = vec4(value, 1.0);
#endif
}
