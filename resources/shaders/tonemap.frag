#version 410 core
// Linear HDR -> display: exposure, a tone map, then the exact sRGB encoding (IEC 61966-2-1).
uniform sampler2D uHdr;
uniform float uExposure;  // 2^EV
uniform int uToneMap;     // TONE_MAP_LINEAR (clipped), _REINHARD, _ACES (Narkowicz 2015 fit),
                          // _PBR_NEUTRAL (Khronos), _AGX (Sobotka; Wrensch's fit); scene.h
// 1: the target's alpha is the coverage (Renderer::setTransparentBackground). The resolved colour
// is then premultiplied by it (cleared to 0, edges averaged with it), so it is divided out before
// the tone map, which is not linear, and the alpha written beside the colour (straight alpha).
// 2: the same coverage, the picture then laid over uBackdrop (sRGB-encoded, as the screen shows
// it) in linear light, so the backdrop is the colour asked for whatever the exposure or tone map.
uniform int uAlpha;
uniform vec3 uBackdrop;

layout(location = 0) out vec4 fragColour;

// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral): below the knee (0.76) only the
// 0.04 black offset moves a colour, so base colours show as authored; above it the peak is
// compressed toward 1 and the colour desaturated in proportion.
vec3 pbrNeutral(vec3 color) {
    const float startCompression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(color.r, min(color.g, color.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    float peak = max(color.r, max(color.g, color.b));
    if (peak < startCompression) return color;
    const float d = 1.0 - startCompression;
    float newPeak = 1.0 - d * d / (peak + d - startCompression);
    color *= newPeak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(color, vec3(newPeak), g);
}

// AgX (Troy Sobotka's, Blender 4's default view) as Benjamin Wrensch's minimal fit writes it: the
// inset matrix, log2 exposure over [−12.47, 4.03] EV, the base contrast's sigmoid as a degree-6
// polynomial, the outset matrix; its output is display-referred (gamma 2.2), so it is decoded to
// linear for the sRGB encoding below.
vec3 agx(vec3 val) {
    const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                            0.0784335999999992, 0.878468636469772, 0.0784336,
                            0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                             -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                             -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
    const float minEv = -12.47393, maxEv = 4.026069;
    val = inset * val;
    val = clamp(log2(max(val, vec3(1e-10))), minEv, maxEv);
    val = (val - minEv) / (maxEv - minEv);
    vec3 x2 = val * val, x4 = x2 * x2;
    val = 15.5 * x4 * x2 - 40.14 * x4 * val + 31.96 * x4 - 6.868 * x2 * val + 0.4298 * x2 + 0.1191 * val - 0.00232;
    val = outset * val;
    return pow(clamp(val, 0.0, 1.0), vec3(2.2));
}

vec3 toneMap(vec3 x) {
    if (uToneMap == TONE_MAP_PBR_NEUTRAL) return clamp(pbrNeutral(x), 0.0, 1.0);
    if (uToneMap == TONE_MAP_AGX) return agx(x);
    if (uToneMap == TONE_MAP_REINHARD) return x / (1.0 + x);
    if (uToneMap == TONE_MAP_ACES) return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    return clamp(x, 0.0, 1.0);
}

vec3 srgbEncode(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

vec3 srgbDecode(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

void main() {
    vec4 texel = texelFetch(uHdr, ivec2(gl_FragCoord.xy), 0);
    float alpha = uAlpha != 0 ? clamp(texel.a, 0.0, 1.0) : 1.0;
    vec3 hdr = alpha > 0.0 ? texel.rgb / alpha : vec3(0.0);
    vec3 display = toneMap(max(hdr, 0.0) * uExposure);
    if (uAlpha == 2) {
        fragColour = vec4(srgbEncode(mix(srgbDecode(uBackdrop), display, alpha)), 1.0);
        return;
    }
    fragColour = vec4(srgbEncode(display), alpha);
}
