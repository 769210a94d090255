// A layered material's texture maps (core/scene/scene.h, MaterialMaps; docs/assets.md), read at
// the fragment's UV. Included by shading_plan.glsl, after layered.glsl, when object.frag and aov.frag
// are built with MATERIAL_MAPS: the programs that draw the materials with maps (MaterialMaps::inUse).
in vec2 vUv;
in vec4 vTangent;  // world xyz, w: the bitangent's sign
in vec2 vUv1;      // TEXCOORD_1
in vec4 vColour;   // COLOR_0: multiplies the base colour and its alpha

// From unit TEXTURE_UNIT_FIRST_MAP on, in this order (texture_units.h).
uniform sampler2D uBaseColorMap;  // sRGB, so reads are linear
uniform sampler2D uMetallicMap;
uniform sampler2D uRoughnessMap;
uniform sampler2D uNormalMap;
uniform sampler2D uOcclusionMap;
uniform sampler2D uEmissiveMap;   // sRGB
uniform bool uUseBaseColorMap, uUseMetallicMap, uUseRoughnessMap, uUseNormalMap, uUseOcclusionMap, uUseEmissiveMap;
uniform int uMetallicChannel, uRoughnessChannel;
uniform vec3 uBaseColor;
uniform float uBaseAlpha, uMetallic, uRoughness;
// The dielectric's Fresnel (layered.h, dielectricFresnel: f0, f90, diffuseF0), mixed per fragment
// with the mapped metal's.
uniform vec3 uDielectricF0;
uniform float uDielectricF90, uDiffuseDielectricF0;
uniform float uNormalScale, uOcclusionStrength;
uniform vec3 uEmissive;
// Each map's UV set (0 or 1) and KHR_texture_transform, in MapSlot order (scene.h, TextureSampling).
uniform int uMapTexCoord[6];
uniform mat3 uMapTransform[6];
uniform int uAlphaMode;  // ALPHA_OPAQUE, ALPHA_MASK, ALPHA_BLEND (its alpha the coverage it is blended with)
uniform float uAlphaCutoff;

struct MaterialSample {
    vec3 baseColor;
    float alpha;
    float metallic;
    float roughness;
    vec3 normal;     // world, unit: the mapped normal
    float occlusion;
    vec3 emissive;
    bool cut;        // alpha below the mask's cutoff
};

float channelOf(vec4 texel, int channel) { return texel[clamp(channel, 0, 3)]; }

// Where map `slot` is read: its UV set through its transform.
vec2 mapUv(int slot) { return (uMapTransform[slot] * vec3(uMapTexCoord[slot] == 1 ? vUv1 : vUv, 1.0)).xy; }

// The maps at this fragment; `n` is the interpolated world normal (already facing the viewer).
MaterialSample sampleMaterial(vec3 n) {
    MaterialSample s;
    vec4 base = (uUseBaseColorMap ? texture(uBaseColorMap, mapUv(0)) : vec4(1.0)) * clamp(vColour, 0.0, 1.0);
    s.baseColor = clamp(uBaseColor * base.rgb, 0.0, 1.0);
    s.alpha = uBaseAlpha * base.a;
    s.metallic = clamp(uMetallic * (uUseMetallicMap ? channelOf(texture(uMetallicMap, mapUv(1)), uMetallicChannel) : 1.0), 0.0, 1.0);
    s.roughness = clamp(uRoughness * (uUseRoughnessMap ? channelOf(texture(uRoughnessMap, mapUv(2)), uRoughnessChannel) : 1.0), 0.0, 1.0);
    s.normal = n;
    if (uUseNormalMap) {
        vec3 t = vTangent.xyz - n * dot(n, vTangent.xyz);
        float tl = length(t);
        if (tl > 1e-6) {
            t /= tl;
            vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
            vec3 m = texture(uNormalMap, mapUv(3)).xyz * 2.0 - 1.0;
            m.xy *= uNormalScale;
            vec3 mapped = t * m.x + b * m.y + n * m.z;
            float ml = length(mapped);
            if (ml > 1e-6) s.normal = mapped / ml;
        }
    }
    s.occlusion = uUseOcclusionMap ? 1.0 + uOcclusionStrength * (texture(uOcclusionMap, mapUv(4)).r - 1.0) : 1.0;
    s.emissive = uEmissive * (uUseEmissiveMap ? texture(uEmissiveMap, mapUv(5)).rgb : vec3(1.0));
    s.cut = uAlphaMode == ALPHA_MASK && s.alpha < uAlphaCutoff;
    return s;
}
