// The shading plan every object fragment goes through, whatever its material (Filament's main.fs
// shape: plan, then its consumers): object.frag reads and sums it, aov.frag classifies and writes
// it. A single-lobe material is one lookup (Ashikhmin & Ghosh 2002, §4) with its direction,
// footprint and lobe, weighted by its tint. A layered material is the glTF 2.0 BRDF (layered.h,
// docs/material-truth.md): the diffuse base (one lookup by the normal), the specular layer and the
// clear coat (each K lookups drawn from GGX's visible normals, layered.glsl), summed with the
// weights of layered.glsl. Texture maps (MATERIAL_MAPS, material_maps.glsl) give the shading
// normal, the weights and, with a roughness map, each fragment its own GGX lobe.
in vec3 vWorldPosition;
in vec3 vNormal;

uniform samplerCube uEnvironment;  // TEXTURE_UNIT_CHAIN: the chain (or the mirror), specular layer and single lobe
uniform samplerCube uIrradiance;   // TEXTURE_UNIT_IRRADIANCE: E/π
uniform vec3 uCameraPosition;
uniform mat3 uEnvironmentRotation;  // world direction -> environment direction
uniform vec3 uTint;
uniform int uLookup;       // LOOKUP_REFLECT, LOOKUP_NORMAL or LOOKUP_IRRADIANCE (lookup_plan.h)
uniform bool uUseStack;    // read the lobe stack where it holds the lobe (else the chain)
uniform float uExponent;   // the lobe the material means (+inf for a mirror)
uniform bool uSharperAtGrazing;
uniform float uLambda;       // only for uSharperAtGrazing (the sampler then has MIN_LOD 0)
uniform float uLevelOffset;  // chain level of λ: λ + uLevelOffset (phong.h), for per-fragment lobes
uniform float uLastLevel;    // the chain's last read level
uniform samplerCube uCoatChain;     // TEXTURE_UNIT_COAT_CHAIN: the chain at the coat's level (or the mirror)
uniform samplerCube uDiffuseChain;  // TEXTURE_UNIT_DIFFUSE_CHAIN: the chain at the n = 1 level
uniform bool uUseCoatStack;
uniform bool uUseDiffuseStack;
uniform bool uDiffuseIrradiance;    // the base from the irradiance map

#ifdef LAYERED
#include "layered.glsl"
#endif
#ifdef MATERIAL_MAPS
#include "material_maps.glsl"
#endif
#include "cube_lod.glsl"
#include "lobe_stack.glsl"

// How a layer is read.
const int READ_NONE = 0;        // the material has no such layer
const int READ_LOBE = 1;        // lobe n: the stack's, widened by the footprint, where it holds it, else the
                                // layer's chain through its sampler (MIN_LOD: the level standing in for n)
const int READ_IRRADIANCE = 2;  // the irradiance map
const int READ_LEVEL = 3;       // a lobe chosen per fragment: the stack's where `useStack` and it holds it,
                                // else the chain at λ's own level, never sharper than the footprint's
const int READ_GGX = 4;         // a GGX layer: K lookups about R (object.frag, readGgx; layered.glsl)

struct LayerRead {
    int kind;
    vec3 direction, dx, dy;  // unit, in the environment's frame; its change to the next pixels
    float exponent;          // n (+inf: the mirror)
    float lambda;            // READ_LEVEL: the λ whose chain level stands in for n
    bool useStack;
    bool grazingMirror;      // READ_LEVEL at the grazing option's λ = 0: the chain's base, not a lobe
    vec3 normal, view;       // READ_GGX: N and v in the environment's frame
    float alpha;             // READ_GGX: roughness²
    ivec2 entries;           // READ_GGX: the stack entries its lookups read (lobes.h, ggxEntries)
    bool held;               // READ_GGX: the stack holds its lookups (lobes.h, ggxLookupsHeld; object_pass.cpp
                             // sets it only where the stack is read)
    bool remainder;          // READ_GGX, held: and the remainder's entries, without the bright lights
    int lookups;             // READ_GGX: how many (lobes.h, ggxLayerLookups)
    float meanShare;         // READ_GGX: how much reads the mean lobe instead (ggx_sampling.h, meanLobeShare)
    bool fitted;             // READ_GGX: its lookups are the fitted lobes (ggx_fitted_lobes.h), held or not
    float footprint;         // READ_GGX: the variance every lookup's lobe is widened by (lobe_stack.glsl,
                             // widenedExponent): the footprint's share at this tap (FootprintTaps)
};

struct FragmentPlan {
    bool layered;
    float cosView;  // N·v with the shading normal
    LayerRead diffuse, specular, coat;
    vec3 wDiffuse, wSpecular, wCoat;  // what each layer's value is multiplied by (a GGX layer's
                                      // A-weighted lookups)
    vec3 wSpecularEdge, wCoatEdge;    // a GGX layer's B-weighted lookups (layered.glsl)
    vec3 f0, diffuseColour;           // the glTF material at this fragment (with maps, mapped)
    float f90;                        // its Fresnel at grazing (KHR_materials_specular; else 1)
    vec3 diffuseF0;                   // the F0 of what its diffuse loses (layered.h)
    float coatWeight;                 // c·Fc(N·v): what the coat takes from the base
    vec3 compensation;                // multiple scattering's factor on the specular (layered.glsl)
    float occlusion;                  // multiplies the sum (1 without maps)
    vec3 emissive;                    // added to it (0 without maps)
    bool cut;                         // alpha below the mask's cutoff: no fragment
    float alpha;                      // the coverage blended materials draw with (else 1)
    // A layered fragment before planLayersAt places it in its pixel: N, v (the environment's
    // frame), their change per pixel along the footprint's long axis, the roughness at this
    // fragment, and the taps it is shaded at.
    vec3 normal, view, normalAlong, viewAlong;
    vec3 rdx, rdy, ndx, ndy;
    float roughness;
    int taps;
    float tapHalfWidth;  // taps at tapHalfWidth·(2(i + ½)/taps − 1) pixels along the axis
    float tapShare;      // the footprint's share left to each tap's lobes (LayerRead.footprint)
};

LayerRead layerRead(int kind, vec3 d, vec3 dx, vec3 dy, float n, bool useStack) {
    LayerRead r;
    r.kind = kind;
    r.direction = d;
    r.dx = dx;
    r.dy = dy;
    r.exponent = n;
    r.lambda = 0.0;
    r.useStack = useStack;
    r.grazingMirror = false;
    r.normal = vec3(0.0);
    r.view = vec3(0.0);
    r.alpha = 0.0;
    r.entries = ivec2(0);
    r.held = false;
    r.remainder = false;
    r.lookups = 1;
    r.meanShare = 0.0;
    r.fitted = false;
    r.footprint = 0.0;
    return r;
}

LayerRead ggxRead(vec3 r, vec3 dx, vec3 dy, float footprint, vec3 normal, vec3 view, float roughness, bool useStack,
                  ivec2 entries, bool held, bool remainder, int lookups, float meanShare, bool fitted) {
    LayerRead g = layerRead(READ_GGX, r, dx, dy, 0.0, useStack);
    g.footprint = footprint;
    g.entries = entries;
    g.held = held;
    g.remainder = remainder;
    g.lookups = lookups;
    g.meanShare = meanShare;
    g.fitted = fitted;
    g.normal = normal;
    g.view = view;
    g.alpha = roughness * roughness;
    return g;
}

LayerRead noRead() { return layerRead(READ_NONE, vec3(0.0), vec3(0.0), vec3(0.0), 0.0, false); }

// The grazing option: λ falls to 0 as the view grazes the surface, with Schlick's (1 − cos θ)^5
// weight, the paper's §6 wish that glossy reflections sharpen at grazing angles. Each fragment
// reads its own lobe n(λ) from the stack; where the stack does not hold it (near the mirror), the
// chain at its level, with the footprint's level kept; λ = 0 reads the chain's base.
LayerRead grazingRead(vec3 d, vec3 dx, vec3 dy, float cosView) {
    float lambda = uLambda * (1.0 - pow(1.0 - cosView, 5.0));
    bool glossy = lambda > 0.0;
    LayerRead r = layerRead(READ_LEVEL, d, dx, dy, glossy ? grazingExponent(lambda) : intBitsToFloat(0x7f800000),
                            uUseStack && glossy);
    r.lambda = lambda;
    r.grazingMirror = !glossy;
    return r;
}

#ifdef LAYERED
// The taps a layered fragment is shaded at (docs/material-truth.md, "The footprint's long axis").
// A pixel shows the mean of its material over its area (a path tracer's box filter; bench truth
// --truth-at area). Over the pixel R sweeps the parallelogram of its derivatives dx, dy, whose
// variances along its axes are λ±/12, λ± the eigenvalues of [dx·dx dx·dy; dx·dy dy·dy]. Where the
// parallelogram is round, each lobe widened by it is that mean (the lobe convolved with the
// footprint); at a sphere's rim it is a sliver (R sweeps 0.25 rad across a 384² sphere's rim pixel
// one way, 0.01 the other), and no widened lobe is the box filter of a reflection that moves
// several lobe widths along one axis. So the fragment is shaded at `taps` positions spaced evenly
// along the long axis, as many as the sliver holds round footprints and no more than keep R at
// most α (the sharpest GGX layer's) apart beyond the short axis's sweep, at most
// MAX_FOOTPRINT_TAPS and only in the taps' program (lookup_plan.h, drawsFootprintTaps); and each
// lobe is widened by the disc as large as what each tap keeps of the parallelogram (λ−
// across, λ− + (λ+ − λ−)/taps² along): with one tap √(λ+λ−)/12 = |dx × dy|/12 (the same where
// the footprint is round; "The footprint at the rim": the mean of its axes' variances read a
// soft box the rim pixel's reflection never meets). N and v move with the taps, so the weights,
// the horizon and the lights' highlights are the pixel's mean too.
#ifdef FOOTPRINT_TAPS
const int MAX_FOOTPRINT_TAPS = MAX_FOOTPRINT_TAPS_DRAWN;  // lookup_plan.h, kMaxFootprintTaps
#else
const int MAX_FOOTPRINT_TAPS = 1;
#endif

void placeTaps(inout FragmentPlan p, float alpha, vec3 vdx, vec3 vdy) {
    float a = dot(p.rdx, p.rdx), b = dot(p.rdx, p.rdy), c = dot(p.rdy, p.rdy);
    float mid = 0.5 * (a + c), spread = sqrt(0.25 * (a - c) * (a - c) + b * b);
    float longAxis = mid + spread, shortAxis = max(mid - spread, 0.0);
    // The long axis on the screen: λ+'s eigenvector, from the better-conditioned row.
    vec2 axis = a >= c ? vec2(longAxis - c, b) : vec2(b, longAxis - a);
    float axisLength = length(axis);
    axis = axisLength > 0.0 ? axis / axisLength : vec2(1.0, 0.0);
    // As many taps as the sliver holds round footprints (a round one needs none), and no more
    // than α's spacing asks.
    float excess = sqrt(max(longAxis - shortAxis, 0.0));
    float rounds = floor(sqrt(longAxis / max(shortAxis, 1e-20 * longAxis)) + 0.5);
    p.taps = alpha > 0.0 ? int(clamp(min(ceil(excess / alpha), rounds), 1.0, float(MAX_FOOTPRINT_TAPS))) : 1;
    p.normalAlong = axis.x * p.ndx + axis.y * p.ndy;
    p.viewAlong = axis.x * vdx + axis.y * vdy;
    // Evenly spaced taps over ±h pixels have the variance of the box of half-width h less
    // h²/(3·taps²), which each tap keeps; h² = (1 − λ−/λ+)/4 leaves each tap λ− + (λ+ − λ−)/taps²
    // along the axis and λ− across it, and its lobes are widened by the disc of that area (the
    // geometric mean: with one tap |dx × dy|/12, and λ−/12 as the taps grow).
    p.tapHalfWidth = p.taps > 1 ? 0.5 * sqrt(max(1.0 - shortAxis / longAxis, 0.0)) : 0.0;
    float along = shortAxis + (longAxis - shortAxis) / float(p.taps * p.taps);
    p.tapShare = sqrt(along * shortAxis) / 12.0;
}
#endif

FragmentPlan planFragment() {
    vec3 n = normalize(vNormal);
    vec3 v = normalize(uCameraPosition - vWorldPosition);
    // Open meshes (the teapot's lid gap) show their inside: light it with the inward normal.
    if (!gl_FrontFacing) n = -n;
    FragmentPlan p;
    p.occlusion = 1.0;
    p.emissive = vec3(0.0);
    p.cut = false;
    p.alpha = 1.0;
#ifdef MATERIAL_MAPS
    // The mapped normal gives both lookup directions (material_maps.glsl).
    MaterialSample s = sampleMaterial(n);
    n = s.normal;
    p.occlusion = s.occlusion;
    p.emissive = s.emissive;
    p.cut = s.cut;
    if (uAlphaMode == ALPHA_BLEND) p.alpha = clamp(s.alpha, 0.0, 1.0);
#endif
    p.cosView = clamp(dot(n, v), 0.0, 1.0);
    // Both lookup directions and their footprints, in uniform control flow.
    vec3 r = normalize(uEnvironmentRotation * reflect(-v, n));
    vec3 normal = normalize(uEnvironmentRotation * n);
    vec3 rdx = dFdx(r), rdy = dFdy(r), ndx = dFdx(normal), ndy = dFdy(normal);
#ifndef LAYERED
    // The single-lobe program (object_pass.cpp: each material's own program, so neither pays for
    // the other's branches on a CPU rasterizer).
    p.layered = false;
    {
        bool reflectLookup = uLookup == LOOKUP_REFLECT;
        vec3 d = reflectLookup ? r : normal, ddx = reflectLookup ? rdx : ndx, ddy = reflectLookup ? rdy : ndy;
        if (uLookup == LOOKUP_IRRADIANCE)
            p.specular = layerRead(READ_IRRADIANCE, d, ddx, ddy, 1.0, false);
        else if (uSharperAtGrazing)
            p.specular = grazingRead(d, ddx, ddy, p.cosView);
        else
            p.specular = layerRead(READ_LOBE, d, ddx, ddy, uExponent, uUseStack);
        p.diffuse = noRead();
        p.coat = noRead();
        p.wDiffuse = vec3(0.0);
        p.wSpecular = uTint;
        p.wCoat = vec3(0.0);
        p.wSpecularEdge = vec3(0.0);
        p.wCoatEdge = vec3(0.0);
        p.f0 = vec3(0.0);
        p.f90 = 1.0;
        p.diffuseF0 = vec3(0.0);
        p.diffuseColour = vec3(0.0);
        p.coatWeight = 0.0;
        p.compensation = vec3(1.0);
        return p;
    }
#else
    p.layered = true;
    vec3 view = normalize(uEnvironmentRotation * v);
    float roughness = uSpecularRoughness;
#ifdef MATERIAL_MAPS
    // The mapped roughness: each fragment its own GGX lobe.
    if (uUseRoughnessMap) roughness = s.roughness;
    // The weights from the mapped base colour and metallic.
    p.f0 = mix(uDielectricF0, s.baseColor, s.metallic);
    p.f90 = mix(uDielectricF90, 1.0, s.metallic);
    p.diffuseF0 = mix(vec3(uDiffuseDielectricF0), s.baseColor, s.metallic);
    p.diffuseColour = s.baseColor * (1.0 - s.metallic);
#else
    p.f0 = uF0;
    p.f90 = uF90;
    p.diffuseF0 = uDiffuseF0;
    p.diffuseColour = uDiffuseColour;
#endif
    p.normal = normal;
    p.view = view;
    p.rdx = rdx;
    p.rdy = rdy;
    p.ndx = ndx;
    p.ndy = ndy;
    p.roughness = roughness;
    // The layers themselves are planned where the caller places the fragment (planLayersAt).
    p.diffuse = noRead();
    p.specular = noRead();
    p.coat = noRead();
    float sharpest = uCoat > 0.0 ? min(roughness, uCoatRoughness) : roughness;
    placeTaps(p, sharpest * sharpest, dFdx(view), dFdy(view));
    return p;
#endif
}

#ifdef LAYERED
// The layers of a layered fragment at `offset` pixels from its centre along the footprint's long
// axis (placeTaps): N and v moved there (to first order, as bench truth's pixel mean moves them),
// the weights at that N·v, each GGX layer's lookups widened by the share the taps leave.
void planLayersAt(inout FragmentPlan p, float offset) {
    vec3 normal = normalize(p.normal + offset * p.normalAlong);
    vec3 view = normalize(p.view + offset * p.viewAlong);
    // Below the surface only by the linearization at a rim, or an interpolated normal there.
    float below = 1e-4 - dot(normal, view);
    if (below > 0.0) view = normalize(view + below * normal);
    p.cosView = clamp(dot(normal, view), 0.0, 1.0);
    vec3 r = reflect(-view, normal);
    layerWeightsOf(p.cosView, p.f0, p.f90, p.diffuseF0, p.diffuseColour, p.roughness, p.wDiffuse, p.wSpecular, p.wSpecularEdge,
                   p.wCoat, p.wCoatEdge, p.coatWeight, p.compensation);
    p.specular = ggxRead(r, p.rdx, p.rdy, p.tapShare, normal, view, p.roughness, uUseStack, uSpecularEntries, uSpecularHeld,
                         uSpecularRemainder, uSpecularLookups, uSpecularMeanShare, uSpecularFitted);
    p.diffuse = uDiffuseIrradiance ? layerRead(READ_IRRADIANCE, normal, p.ndx, p.ndy, 1.0, false)
                                   : layerRead(READ_LOBE, normal, p.ndx, p.ndy, 1.0, uUseDiffuseStack);
    p.coat = uCoat > 0.0 ? ggxRead(r, p.rdx, p.rdy, p.tapShare, normal, view, uCoatRoughness, uUseCoatStack, uCoatEntries, uCoatHeld,
                                   uCoatRemainder, uCoatLookups, uCoatMeanShare, uCoatFitted)
                         : noRead();
}

// Where tap `i` of the fragment's `taps` lies along the long axis, in pixels from its centre.
float tapOffset(FragmentPlan p, int i) { return p.tapHalfWidth * (2.0 * (float(i) + 0.5) / float(p.taps) - 1.0); }
#endif
