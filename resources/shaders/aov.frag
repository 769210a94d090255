#version 410 core
// The renders anyone can check (mipgloss render --aov): per pixel, the direction the environment
// is read at (after the environment's rotation, i.e. in the frame of the baked faces), the Phong
// exponent of the lobe the pixel shows, and whether the pixel is meant to equal that lobe at that
// direction. The lookup mirrors object.frag. A layered material adds, per layer, the direction it
// read, its lobe and the weight object.frag multiplies that lobe by (layered.glsl), so the picture
// at an exact pixel is Σ weight ⊙ lobe(direction); the single-lobe fields then describe its
// specular layer.
in vec3 vWorldPosition;
in vec3 vNormal;

uniform samplerCube uEnvironment;
uniform samplerCube uIrradiance;
uniform vec3 uCameraPosition;
uniform mat3 uEnvironmentRotation;
uniform int uLookup;
uniform bool uUseStack;
uniform bool uSharperAtGrazing;
uniform float uLambda;
uniform float uExponent;       // the lobe the material means (+inf for a mirror)
uniform bool uLayered;
uniform samplerCube uCoatChain;
uniform bool uUseCoatStack;
uniform bool uUseDiffuseStack;
uniform bool uDiffuseIrradiance;
uniform float uCoatExponent;

#include "layered.glsl"
#ifdef MATERIAL_MAPS
#include "material_maps.glsl"
#endif
#include "cube_lod.glsl"
#include "lobe_stack.glsl"

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

void main() {
    vec3 n = normalize(vNormal);
    vec3 v = normalize(uCameraPosition - vWorldPosition);
    if (!gl_FrontFacing) n = -n;
    float cosView = clamp(dot(n, v), 0.0, 1.0);
    vec3 r = normalize(uEnvironmentRotation * reflect(-v, n));
    vec3 normal = normalize(uEnvironmentRotation * n);
    vec3 rdx = dFdx(r), rdy = dFdy(r), ndx = dFdx(normal), ndy = dFdy(normal);
    aovDiffuseDirection = vec4(0.0);
    aovDiffuseWeight = vec4(0.0, 0.0, 0.0, cosView);
    aovSpecularWeight = vec4(0.0);
    aovCoatDirection = vec4(0.0);
    aovCoatWeight = vec4(0.0);
#ifdef MATERIAL_MAPS
    {
        // object.frag's mapped branch: the mapped normal's directions, each fragment's own
        // specular lobe from the roughness map, the weights from the mapped base colour and
        // metallic, times the occlusion. Emission is not a lobe: an emitting pixel is not exact.
        MaterialSample s = sampleMaterial(n);
        vec3 mn = s.normal;
        float mCos = clamp(dot(mn, v), 0.0, 1.0);
        vec3 mr = normalize(uEnvironmentRotation * reflect(-v, mn));
        vec3 mnormal = normalize(uEnvironmentRotation * mn);
        vec3 mrdx = dFdx(mr), mrdy = dFdy(mr), mndx = dFdx(mnormal), mndy = dFdy(mnormal);
        float exponent = uUseRoughnessMap ? roughnessExponent(s.roughness) : uExponent;
        vec3 wDiffuse, wSpecular, wCoat;
        layerWeightsOf(mCos, mix(vec3(uSpecular), s.baseColor, s.metallic), s.baseColor * (1.0 - s.metallic),
                       uUseRoughnessMap ? exponentLambda(exponent) : uSpecularLambda, wDiffuse, wSpecular, wCoat);
        float specularShown, diffuseShown = 1.0, coatShown = uCoatExponent;
        bool exact = lobeRead(uUseStack, exponent, mr, mrdx, mrdy, uEnvironment, specularShown);
        if (uDiffuseIrradiance)
            exact = exact && baseOnly(uIrradiance, mnormal);
        else
            exact = lobeRead(uUseDiffuseStack, 1.0, mnormal, mndx, mndy, uEnvironment, diffuseShown) && exact;
        if (uCoat > 0.0)
            exact = lobeRead(uUseCoatStack, uCoatExponent, mr, mrdx, mrdy, uCoatChain, coatShown) && exact;
        exact = exact && all(equal(s.emissive, vec3(0.0)));
        if (s.cut) discard;
        aovDirection = vec4(mr, specularShown);
        aovExact = vec4(exact ? 1.0 : 0.0, 0.0, 0.0, 1.0);
        aovDiffuseDirection = vec4(mnormal, diffuseShown);
        aovDiffuseWeight = vec4(s.occlusion * wDiffuse, mCos);
        aovSpecularWeight = vec4(s.occlusion * wSpecular, 0.0);
        if (uCoat > 0.0) {
            aovCoatDirection = vec4(mr, coatShown);
            aovCoatWeight = vec4(s.occlusion * wCoat, 0.0);
        }
    }
#else
    if (uLayered) {
        vec3 wDiffuse, wSpecular, wCoat;
        layerWeights(cosView, wDiffuse, wSpecular, wCoat);
        float specularShown, diffuseShown = 1.0, coatShown = uCoatExponent;
        bool exact = lobeRead(uUseStack, uExponent, r, rdx, rdy, uEnvironment, specularShown);
        if (uDiffuseIrradiance)
            exact = exact && baseOnly(uIrradiance, normal);
        else
            exact = lobeRead(uUseDiffuseStack, 1.0, normal, ndx, ndy, uEnvironment, diffuseShown) && exact;
        if (uCoat > 0.0)
            exact = lobeRead(uUseCoatStack, uCoatExponent, r, rdx, rdy, uCoatChain, coatShown) && exact;
        aovDirection = vec4(r, specularShown);
        aovExact = vec4(exact ? 1.0 : 0.0, 0.0, 0.0, 1.0);
        aovDiffuseDirection = vec4(normal, diffuseShown);
        aovDiffuseWeight = vec4(wDiffuse, cosView);
        aovSpecularWeight = vec4(wSpecular, 0.0);
        if (uCoat > 0.0) {
            aovCoatDirection = vec4(r, coatShown);
            aovCoatWeight = vec4(wCoat, 0.0);
        }
        return;
    }
    bool reflectLookup = uLookup == LOOKUP_REFLECT;
    vec3 direction = reflectLookup ? r : normal;
    vec3 ddx = reflectLookup ? rdx : ndx, ddy = reflectLookup ? rdy : ndy;
    float exponent = uLookup == LOOKUP_IRRADIANCE ? 1.0 : uExponent;
    bool exact = false;
    if (uLookup == LOOKUP_IRRADIANCE) {
        exact = baseOnly(uIrradiance, direction);
    } else if (uSharperAtGrazing) {
        // The fragment's own λ (object.frag): exact where the stack holds it.
        float lambda = uLambda * (1.0 - pow(1.0 - cosView, 5.0));
        if (lambda > 0.0) {
            float shown;
            exact = lobeRead(uUseStack, grazingExponent(lambda), direction, ddx, ddy, uEnvironment, shown);
            exponent = shown;
        } else {
            exponent = intBitsToFloat(0x7f800000);  // +inf: the mirror, read through the chain
        }
    } else {
        float shown;
        exact = lobeRead(uUseStack, exponent, direction, ddx, ddy, uEnvironment, shown);
        exponent = shown;
    }
    aovDirection = vec4(direction, exponent);
    aovExact = vec4(exact ? 1.0 : 0.0, 0.0, 0.0, 1.0);
#endif
}
