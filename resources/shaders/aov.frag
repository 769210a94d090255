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
uniform samplerCube uLobe;
uniform vec3 uCameraPosition;
uniform mat3 uEnvironmentRotation;
uniform int uLookup;
uniform bool uUseLobe;
uniform bool uLobeExact;       // the lobe cube holds the lobe at full width
uniform bool uSharperAtGrazing;
uniform float uExponent;       // the lobe the material means (+inf for a mirror)
uniform bool uLayered;
uniform samplerCube uCoatChain;
uniform samplerCube uCoatLobe;
uniform samplerCube uDiffuseLobe;
uniform bool uUseCoatLobe;
uniform bool uUseDiffuseLobe;
uniform bool uCoatLobeExact;
uniform bool uDiffuseLobeExact;
uniform bool uDiffuseIrradiance;
uniform float uCoatExponent;

#include "layered.glsl"
#include "cube_lod.glsl"

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

// A lobe read exactly: from a cube that holds it at full width, at its base level.
bool exactRead(bool useLobe, bool lobeExact, samplerCube lobe, bool mirror, samplerCube chain, vec3 direction) {
    if (useLobe) return lobeExact && baseOnly(lobe, direction);
    return mirror && baseOnly(chain, direction);
}

void main() {
    vec3 n = normalize(vNormal);
    vec3 v = normalize(uCameraPosition - vWorldPosition);
    if (!gl_FrontFacing) n = -n;
    float cosView = clamp(dot(n, v), 0.0, 1.0);
    aovDiffuseDirection = vec4(0.0);
    aovDiffuseWeight = vec4(0.0, 0.0, 0.0, cosView);
    aovSpecularWeight = vec4(0.0);
    aovCoatDirection = vec4(0.0);
    aovCoatWeight = vec4(0.0);
    if (uLayered) {
        vec3 r = normalize(uEnvironmentRotation * reflect(-v, n));
        vec3 normal = normalize(uEnvironmentRotation * n);
        vec3 wDiffuse, wSpecular, wCoat;
        layerWeights(cosView, wDiffuse, wSpecular, wCoat);
        bool exact = exactRead(uUseLobe, uLobeExact, uLobe, isinf(uExponent), uEnvironment, r);
        if (uDiffuseIrradiance)
            exact = exact && baseOnly(uIrradiance, normal);
        else
            exact = exact && uUseDiffuseLobe && uDiffuseLobeExact && baseOnly(uDiffuseLobe, normal);
        if (uCoat > 0.0)
            exact = exact && exactRead(uUseCoatLobe, uCoatLobeExact, uCoatLobe, isinf(uCoatExponent), uCoatChain, r);
        aovDirection = vec4(r, uExponent);
        aovExact = vec4(exact ? 1.0 : 0.0, 0.0, 0.0, 1.0);
        aovDiffuseDirection = vec4(normal, 1.0);
        aovDiffuseWeight = vec4(wDiffuse, cosView);
        aovSpecularWeight = vec4(wSpecular, 0.0);
        if (uCoat > 0.0) {
            aovCoatDirection = vec4(r, uCoatExponent);
            aovCoatWeight = vec4(wCoat, 0.0);
        }
        return;
    }
    vec3 direction = normalize(uEnvironmentRotation * (uLookup == LOOKUP_REFLECT ? reflect(-v, n) : n));
    float exponent = uLookup == LOOKUP_IRRADIANCE ? 1.0 : uExponent;
    // Exact where the value is one lobe read at one direction with no footprint widening it:
    // from the lobe cube (or the irradiance map, or the mirror level) with the GPU reading its
    // base level (footprint LOD <= 0), never through the grazing option's per-fragment blend.
    bool exact = false;
    if (uLookup == LOOKUP_IRRADIANCE) {
        exact = baseOnly(uIrradiance, direction);
    } else if (!uSharperAtGrazing) {
        if (uUseLobe)
            exact = uLobeExact && baseOnly(uLobe, direction);
        else if (isinf(exponent))
            exact = baseOnly(uEnvironment, direction);
    }
    aovDirection = vec4(direction, exponent);
    aovExact = vec4(exact ? 1.0 : 0.0, 0.0, 0.0, 1.0);
}
