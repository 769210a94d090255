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
    return r;
}

LayerRead ggxRead(vec3 r, vec3 dx, vec3 dy, vec3 normal, vec3 view, float roughness, bool useStack, ivec2 entries,
                  bool held, bool remainder, int lookups, float meanShare, bool fitted) {
    LayerRead g = layerRead(READ_GGX, r, dx, dy, 0.0, useStack);
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
    layerWeightsOf(p.cosView, p.f0, p.f90, p.diffuseF0, p.diffuseColour, roughness, p.wDiffuse, p.wSpecular, p.wSpecularEdge, p.wCoat,
                   p.wCoatEdge, p.coatWeight, p.compensation);
    p.specular = ggxRead(r, rdx, rdy, normal, view, roughness, uUseStack, uSpecularEntries, uSpecularHeld, uSpecularRemainder, uSpecularLookups,
                         uSpecularMeanShare, uSpecularFitted);
    p.diffuse = uDiffuseIrradiance ? layerRead(READ_IRRADIANCE, normal, ndx, ndy, 1.0, false)
                                   : layerRead(READ_LOBE, normal, ndx, ndy, 1.0, uUseDiffuseStack);
    p.coat = uCoat > 0.0 ? ggxRead(r, rdx, rdy, normal, view, uCoatRoughness, uUseCoatStack, uCoatEntries, uCoatHeld, uCoatRemainder,
                                         uCoatLookups, uCoatMeanShare, uCoatFitted) : noRead();
    return p;
#endif
}
