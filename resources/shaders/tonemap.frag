#version 410 core
// Linear HDR -> display: exposure, a tone map, then the exact sRGB encoding (IEC 61966-2-1).
uniform sampler2D uHdr;
uniform float uExposure;  // 2^EV
uniform int uToneMap;     // TONE_MAP_LINEAR (clipped), _REINHARD, _ACES (Narkowicz 2015 fit)
// 1: the target's alpha is the coverage (Renderer::setTransparentBackground). The resolved colour
// is then premultiplied by it (cleared to 0, edges averaged with it), so it is divided out before
// the tone map, which is not linear, and the alpha written beside the colour (straight alpha).
// 2: the same coverage, the picture then laid over uBackdrop (sRGB-encoded, as the screen shows
// it) in linear light, so the backdrop is the colour asked for whatever the exposure or tone map.
uniform int uAlpha;
uniform vec3 uBackdrop;

layout(location = 0) out vec4 fragColour;

vec3 toneMap(vec3 x) {
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
