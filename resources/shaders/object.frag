#version 410 core
// One environment lookup per fragment (Ashikhmin & Ghosh 2002, §4), at the lobe the material
// means. Where the lobe stack holds it (lobe_stack.glsl, core/scene/lobes.h) the lookup reads the
// exact lobe, widened by the pixel's footprint, for any λ, per object or per fragment. Where it
// does not yet (an entry still being made, a lobe sharper than the stack's top) it reads the
// chain: the bound sampler's GL_TEXTURE_MIN_LOD is the chain level standing in for the lobe
// (phong.h, chainLevelForExponent), trilinear. A layered material (layered.h) makes three such
// lookups and sums them weighted by layered.glsl.
in vec3 vWorldPosition;
in vec3 vNormal;

uniform samplerCube uEnvironment;  // unit 0: the chain
uniform samplerCube uIrradiance;   // unit 1: E/π, used by normal mode when asked
uniform vec3 uCameraPosition;
uniform mat3 uEnvironmentRotation;  // world direction -> environment direction
uniform vec3 uTint;
uniform int uLookup;       // LOOKUP_REFLECT, LOOKUP_NORMAL or LOOKUP_IRRADIANCE (lookup_plan.h)
uniform bool uUseStack;    // read the lobe stack where it holds the lobe (else the chain)
uniform float uExponent;   // the lobe the material means (+inf for a mirror)
uniform bool uSharperAtGrazing;
uniform float uLambda;       // only for uSharperAtGrazing (the sampler then has MIN_LOD 0)
uniform float uLevelOffset;  // chain level of λ: λ + uLevelOffset (phong.h), for the grazing option
uniform float uLastLevel;    // the chain's last read level
// Layered: the specular layer reads uEnvironment (unit 0) like the single lobe.
uniform bool uLayered;
uniform samplerCube uCoatChain;     // unit 4: the chain at the coat's level (or the mirror)
uniform samplerCube uDiffuseChain;  // unit 6: the chain at the n = 1 level
uniform bool uUseCoatStack;
uniform bool uUseDiffuseStack;
uniform bool uDiffuseIrradiance;    // the base from the irradiance map (unit 1)
uniform float uCoatExponent;

#include "layered.glsl"
#ifdef MATERIAL_MAPS
#include "material_maps.glsl"
#endif
#include "cube_lod.glsl"
#include "lobe_stack.glsl"

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

#ifdef MATERIAL_MAPS
// Lobe n chosen per fragment (a roughness map): the stack's exact lobe where it holds it, else the
// chain at n's own level, never sharper than the footprint's (the grazing option's rule below).
vec3 readLobePerFragment(float n, vec3 d, vec3 dx, vec3 dy) {
    bool complete;
    float shown = footprintLimitedExponent(n, dx, dy, complete);
    if (uUseStack && stackHolds(shown)) return stackRead(d, shown);
    float lambda = exponentLambda(n);
    float level = lambda > 0.0 ? clamp(lambda + uLevelOffset, 0.0, uLastLevel) : 0.0;
    float footprint = cubeLevelOfDetail(d, float(textureSize(uEnvironment, 0).x));
    return textureLod(uEnvironment, d, max(level, footprint)).rgb;
}
#endif

layout(location = 0) out vec4 fragColour;

void main() {
    vec3 n = normalize(vNormal);
    vec3 v = normalize(uCameraPosition - vWorldPosition);
    // Open meshes (the teapot's lid gap) show their inside: light it with the inward normal.
    if (!gl_FrontFacing) n = -n;
#ifdef MATERIAL_MAPS
    // A layered material with texture maps: this program (object.frag built with MATERIAL_MAPS)
    // draws only those. A program of its own, because a shader runs every branch it holds for
    // each fragment on a CPU rasterizer (llvmpipe: masked SIMD) and the maps' reads made every
    // other object six times slower there.
    {
        // Texture maps (material_maps.glsl): the mapped normal gives both lookup directions, the
        // mapped roughness each fragment's own specular lobe, base colour and metallic its weights.
        MaterialSample s = sampleMaterial(n);
        vec3 mn = s.normal;
        vec3 mr = normalize(uEnvironmentRotation * reflect(-v, mn));
        vec3 mnormal = normalize(uEnvironmentRotation * mn);
        vec3 mrdx = dFdx(mr), mrdy = dFdy(mr), mndx = dFdx(mnormal), mndy = dFdy(mnormal);
        float exponent = uUseRoughnessMap ? roughnessExponent(s.roughness) : uExponent;
        vec3 f0 = mix(vec3(uSpecular), s.baseColor, s.metallic);
        vec3 wDiffuse, wSpecular, wCoat;
        layerWeightsOf(clamp(dot(mn, v), 0.0, 1.0), f0, s.baseColor * (1.0 - s.metallic),
                       uUseRoughnessMap ? exponentLambda(exponent) : uSpecularLambda, wDiffuse, wSpecular, wCoat);
        vec3 diffuse = uDiffuseIrradiance ? texture(uIrradiance, mnormal).rgb
                                          : readLobe(uDiffuseChain, uUseDiffuseStack, 1.0, mnormal, mndx, mndy);
        // Branches, not ?: (a select evaluates both sides, and the per-fragment read is the dearer).
        vec3 specular;
        if (uUseRoughnessMap)
            specular = readLobePerFragment(exponent, mr, mrdx, mrdy);
        else
            specular = readLobe(uEnvironment, uUseStack, uExponent, mr, mrdx, mrdy);
        vec3 coat = uCoat > 0.0 ? readLobe(uCoatChain, uUseCoatStack, uCoatExponent, mr, mrdx, mrdy) : vec3(0.0);
        if (s.cut) discard;
        fragColour = vec4(s.occlusion * (wDiffuse * diffuse + wSpecular * specular + wCoat * coat) + s.emissive, 1.0);
    }
#else
    // Both lookup directions and their footprints, in uniform control flow.
    vec3 r = normalize(uEnvironmentRotation * reflect(-v, n));
    vec3 normal = normalize(uEnvironmentRotation * n);
    vec3 rdx = dFdx(r), rdy = dFdy(r), ndx = dFdx(normal), ndy = dFdy(normal);
    if (uLayered) {
        vec3 wDiffuse, wSpecular, wCoat;
        layerWeights(clamp(dot(n, v), 0.0, 1.0), wDiffuse, wSpecular, wCoat);
        vec3 diffuse = uDiffuseIrradiance ? texture(uIrradiance, normal).rgb
                                          : readLobe(uDiffuseChain, uUseDiffuseStack, 1.0, normal, ndx, ndy);
        vec3 specular = readLobe(uEnvironment, uUseStack, uExponent, r, rdx, rdy);
        vec3 coat = uCoat > 0.0 ? readLobe(uCoatChain, uUseCoatStack, uCoatExponent, r, rdx, rdy) : vec3(0.0);
        fragColour = vec4(wDiffuse * diffuse + wSpecular * specular + wCoat * coat, 1.0);
        return;
    }
    bool reflectLookup = uLookup == LOOKUP_REFLECT;
    vec3 direction = reflectLookup ? r : normal;
    vec3 ddx = reflectLookup ? rdx : ndx, ddy = reflectLookup ? rdy : ndy;

    vec3 colour;
    if (uLookup == LOOKUP_IRRADIANCE) {
        colour = texture(uIrradiance, direction).rgb;
    } else if (uSharperAtGrazing) {
        // λ falls to 0 as the view grazes the surface, with Schlick's (1 - cos θ)^5 weight: the
        // paper's §6 wish that glossy reflections sharpen at grazing angles. Each fragment reads
        // its own lobe from the stack; where the stack does not hold it (near the mirror), the
        // chain at its level, with the footprint's level kept.
        float cosTheta = clamp(dot(n, v), 0.0, 1.0);
        float lambda = uLambda * (1.0 - pow(1.0 - cosTheta, 5.0));
        bool complete;
        float shown = footprintLimitedExponent(grazingExponent(lambda), ddx, ddy, complete);
        float level = lambda > 0.0 ? clamp(lambda + uLevelOffset, 0.0, uLastLevel) : 0.0;
        // The footprint's level as the specification defines it (cube_lod.glsl): llvmpipe's
        // textureQueryLod is levels off for cube maps and read a blurry level at the sphere's centre.
        float footprint = cubeLevelOfDetail(direction, float(textureSize(uEnvironment, 0).x));
        if (uUseStack && lambda > 0.0 && stackHolds(shown))
            colour = stackRead(direction, shown);
        else
            colour = textureLod(uEnvironment, direction, max(level, footprint)).rgb;
    } else {
        colour = readLobe(uEnvironment, uUseStack, uExponent, direction, ddx, ddy);
    }
    fragColour = vec4(uTint * colour, 1.0);
#endif
}
