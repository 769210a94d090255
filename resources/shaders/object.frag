#version 410 core
// One environment lookup per fragment (Ashikhmin & Ghosh 2002, §4). While a material's λ moves,
// the lookup reads the chain: the bound sampler's GL_TEXTURE_MIN_LOD is the chain level standing
// in for the material's lobe (phong.h, chainLevelForExponent), so texture() samples at
// max(that level, footprint LOD) with trilinear filtering. Once λ rests, the lookup reads the
// material's own lobe cube (lobes.h), which holds the exact lobe. A layered material (layered.h)
// makes three such lookups, each from its own chain sampler or lobe cube, and sums them weighted
// by layered.glsl.
in vec3 vWorldPosition;
in vec3 vNormal;

uniform samplerCube uEnvironment;  // unit 0: the chain
uniform samplerCube uIrradiance;   // unit 1: E/π, used by normal mode when asked
uniform samplerCube uLobe;         // unit 2: the material's lobe cube, when uUseLobe
uniform vec3 uCameraPosition;
uniform mat3 uEnvironmentRotation;  // world direction -> environment direction
uniform vec3 uTint;
uniform int uLookup;       // LOOKUP_REFLECT, LOOKUP_NORMAL or LOOKUP_IRRADIANCE (lookup_plan.h)
uniform bool uUseLobe;
uniform bool uSharperAtGrazing;
uniform float uLambda;       // only for uSharperAtGrazing (the sampler then has MIN_LOD 0)
uniform float uLevelOffset;  // chain level of λ: λ + uLevelOffset (phong.h), for the grazing option
uniform float uLastLevel;    // the chain's last read level
// Layered: the specular layer reads uEnvironment / uLobe (units 0, 2) like the single lobe.
uniform bool uLayered;
uniform samplerCube uCoatChain;     // unit 4: the chain at the coat's level (or the mirror)
uniform samplerCube uCoatLobe;      // unit 5
uniform samplerCube uDiffuseChain;  // unit 6: the chain at the n = 1 level
uniform samplerCube uDiffuseLobe;   // unit 7
uniform bool uUseCoatLobe;
uniform bool uUseDiffuseLobe;
uniform bool uDiffuseIrradiance;    // the base from the irradiance map (unit 1)

#include "layered.glsl"

vec3 readLayer(samplerCube chain, samplerCube lobe, bool useLobe, vec3 direction) {
    return useLobe ? texture(lobe, direction).rgb : texture(chain, direction).rgb;
}

layout(location = 0) out vec4 fragColour;

void main() {
    vec3 n = normalize(vNormal);
    vec3 v = normalize(uCameraPosition - vWorldPosition);
    // Open meshes (the teapot's lid gap) show their inside: light it with the inward normal.
    if (!gl_FrontFacing) n = -n;
    if (uLayered) {
        vec3 r = uEnvironmentRotation * reflect(-v, n);
        vec3 normal = uEnvironmentRotation * n;
        vec3 wDiffuse, wSpecular, wCoat;
        layerWeights(clamp(dot(n, v), 0.0, 1.0), wDiffuse, wSpecular, wCoat);
        vec3 diffuse = uDiffuseIrradiance ? texture(uIrradiance, normal).rgb
                                          : readLayer(uDiffuseChain, uDiffuseLobe, uUseDiffuseLobe, normal);
        vec3 specular = readLayer(uEnvironment, uLobe, uUseLobe, r);
        vec3 coat = uCoat > 0.0 ? readLayer(uCoatChain, uCoatLobe, uUseCoatLobe, r) : vec3(0.0);
        fragColour = vec4(wDiffuse * diffuse + wSpecular * specular + wCoat * coat, 1.0);
        return;
    }
    vec3 direction = uEnvironmentRotation * (uLookup == LOOKUP_REFLECT ? reflect(-v, n) : n);

    vec3 colour;
    if (uLookup == LOOKUP_IRRADIANCE) {
        colour = texture(uIrradiance, direction).rgb;
    } else if (uSharperAtGrazing) {
        // λ falls to 0 as the view grazes the surface, with Schlick's (1 - cos θ)^5 weight: the
        // paper's §6 wish that glossy reflections sharpen at grazing angles. The footprint LOD
        // of the hardware is kept, so far objects still get mipmapping's blur.
        float cosTheta = clamp(dot(n, v), 0.0, 1.0);
        float lambda = uLambda * (1.0 - pow(1.0 - cosTheta, 5.0));
        float level = lambda > 0.0 ? clamp(lambda + uLevelOffset, 0.0, uLastLevel) : 0.0;
        float footprint = textureQueryLod(uEnvironment, direction).y;
        colour = textureLod(uEnvironment, direction, max(level, footprint)).rgb;
    } else if (uUseLobe) {
        colour = texture(uLobe, direction).rgb;
    } else {
        colour = texture(uEnvironment, direction).rgb;
    }
    fragColour = vec4(uTint * colour, 1.0);
}
