// The layered material as glTF 2.0 defines it (core/ibl/gltf_brdf.h; docs/material-truth.md): its
// GGX layers read by lookups drawn from GGX's visible normals (core/ibl/ggx_sampling.h, the C++
// half of this file), their energy from the exact albedo table uploaded as uGgxAlbedo, and the
// weights each layer's value is multiplied by. Included by shading_plan.glsl.
uniform sampler2D uGgxAlbedo;  // TEXTURE_UNIT_SPLIT_SUM, RGB = (A, B, Bd) at the table's nodes
uniform sampler2D uGgxLobeMean;  // TEXTURE_UNIT_LOBE_MEAN: the same nodes' mean light direction, RG = (x, z) (ggx_sampling.h, meanLobe)
uniform vec3 uF0;              // mix(dielectric F0, baseColor, metallic) (layered.h, specularF0)
uniform float uF90;            // mix(specularWeight, 1, metallic) (specularF90)
uniform vec3 uDiffuseF0;       // the F0 of what the diffuse loses (diffuseFresnelF0)
uniform vec3 uDiffuseColour;   // baseColor · (1 − metallic)
uniform float uSpecularRoughness;
uniform float uCoat;           // 0: no coat
uniform float uCoatRoughness;
uniform int uSpecularLookups;  // lookups per fragment of each GGX layer (lobes.h, ggxLayerLookups)
uniform int uCoatLookups;
uniform float uSpecularMeanShare;  // how much of each layer reads its mean lobe (ggx_sampling.h, meanLobeShare)
uniform float uCoatMeanShare;
uniform bool uCompensated;     // multiple scattering (ggx_sampling.h, Scattering::Compensated)
uniform ivec2 uSpecularEntries;  // the stack entries each layer's lookups read, first and last
uniform ivec2 uCoatEntries;      // (lobes.h, ggxEntries; all made when uUseStack/uUseCoatStack)
// The same entries made from the smooth remainder (lobes.h, remainderEntries; bright_lights.h,
// withoutBrightLights), in the stack's atlas: x, y, face size, scale (lobe_stack.glsl, atlasRead).
// When a held layer's are all there (uSpecularRemainder, uCoatRemainder) its lookups read them
// and subtract no light; else they read the whole environment and subtract the lights from each.
uniform vec4 uRemainderEntry[STACK_SLOTS];
uniform bool uSpecularRemainder;
uniform bool uCoatRemainder;
// Whether the stack holds each layer's lookups (lobes.h, ggxLookupsHeld: its sharpest head-on):
// its lookups then read the atlas alone (object.frag, readGgx), a sharper one its first entry.
uniform bool uSpecularHeld;
uniform bool uCoatHeld;
// Whether a held layer's lookups are the eight lobes fitted to its GGX lobe (ggx_fitted_lobes.h,
// readsFittedLobes), read from the fitted nodes: layer 2k (q1, q2, η), layer 2k + 1 (weightA, weightB).
uniform bool uSpecularFitted;
uniform bool uCoatFitted;
uniform sampler2DArray uGgxFittedLobes;  // TEXTURE_UNIT_FITTED_LOBES
// The environment's bright texels as points of energy (bright_lights.h), in its frame: shaded with
// the exact BRDF, and taken out of every lookup (each lookup's lobe would have blurred them).
uniform vec4 uLightDirection[MAX_BRIGHT_LIGHTS];  // xyz: unit direction, w: its angular radius
uniform vec3 uLightEnergy[MAX_BRIGHT_LIGHTS];
uniform int uLightCount;
uniform float uLightsMinAlpha;  // the least α whose lobe shades the lights apart (object_pass.cpp)

const float HALF_PI = 1.57079632679;
const float PI = 3.14159265359;

// A, B and Bd at roughness r and N·v, read bilinearly between the table's nodes as
// GgxAlbedoTable::at reads them: s from x = 1 − √(1 − θ/(π/2)), θ = acos(N·v); t from r.
vec2 ggxTableCoordinates(float roughness, float cosView) {
    float theta = acos(clamp(cosView, 0.0, 1.0));
    float x = 1.0 - sqrt(max(0.0, 1.0 - theta / HALF_PI));
    float y = clamp(roughness, 0.0, 1.0);
    return vec2((x * float(GGX_COS_STEPS - 1) + 0.5) / float(GGX_COS_STEPS),
                (y * float(GGX_ROUGHNESS_STEPS - 1) + 0.5) / float(GGX_ROUGHNESS_STEPS));
}

vec3 ggxAlbedo(float roughness, float cosView) {
    return texture(uGgxAlbedo, ggxTableCoordinates(roughness, cosView)).rgb;
}

// The one Phong lobe with the GGX lobe's first moment at roughness r and N·v (ggx_sampling.h,
// meanLobe): xyz its direction in the frame N = z, v = (sin θ, 0, cos θ); w its exponent,
// 1/(n + 2) = 1 − |m|.
vec4 ggxMeanLobe(float roughness, float cosView) {
    vec2 m = texture(uGgxLobeMean, ggxTableCoordinates(roughness, cosView)).rg;
    float len = length(m);
    if (!(len > 0.0)) return vec4(0.0, 0.0, 1.0, 0.0);
    float n = len < 1.0 ? max(1.0 / (1.0 - len) - 2.0, 0.0) : 1.0e30;
    return vec4(m.x / len, 0.0, m.y / len, n);
}

// What each layer's value is multiplied by at N·v = cosView (gltf_brdf.h), and c·Fc, what the coat
// takes from the base:
//   coat       c·Fc(N·v)·A_c and c·Fc(N·v)·B_c, likewise     Fc = 0.04 + 0.96 (1 − N·v)⁵
//   specular   (1 − c·Fc)·F0·A  on the lookups' A-weighted mean, (1 − c·Fc)·F90·B on their B-weighted one
//   diffuse    (1 − c·Fc)·c_diff·(1 − Fd0 − (F90 − Fd0)·Bd)  on E(N)/π   (F90 = 1: (1 − Fd0)(1 − Bd))
// and `compensation`, what multiple scattering multiplies the specular layer by, lookups and lights:
// 1 + F0·(1 − A − B)/(A + B) when uCompensated, else 1 (ggx_sampling.h, scatteringCompensation).
void layerWeightsOf(float cosView, vec3 f0, float f90, vec3 diffuseF0, vec3 diffuseColour, float roughness,
                    out vec3 diffuse, out vec3 specular, out vec3 specularEdge, out vec3 coat, out vec3 coatEdge,
                    out float coatWeight, out vec3 compensation) {
    vec3 e = ggxAlbedo(roughness, cosView);
    float m = 1.0 - clamp(cosView, 0.0, 1.0);
    coatWeight = uCoat > 0.0 ? uCoat * (COAT_F0 + (1.0 - COAT_F0) * m * m * m * m * m) : 0.0;
    vec3 c = uCoat > 0.0 ? ggxAlbedo(uCoatRoughness, cosView) : vec3(0.0);
    float base = 1.0 - coatWeight;
    coat = vec3(coatWeight * c.x);
    coatEdge = vec3(coatWeight * c.y);
    float albedo = e.x + e.y;
    compensation = uCompensated && albedo > 0.0 ? vec3(1.0) + f0 * ((1.0 - albedo) / albedo) : vec3(1.0);
    specular = compensation * base * f0 * e.x;
    specularEdge = compensation * base * f90 * e.y;
    diffuse = base * diffuseColour * (vec3(1.0) - diffuseF0 - (vec3(f90) - diffuseF0) * e.z);
}

// Lookup k of K at α for the view `v` in the frame N = z (ggx_sampling.h, ggxLookup: Heitz 2018's
// visible normals at (u1, u2) = ((k + ½)/K, radical inverse of k)): the light direction, its
// weight G2/G1 (0 below the horizon), its pdf and (1 − v·h)⁵.
struct GgxLookup {
    vec3 light;
    float weight, pdf, fresnelEdge;
};

float smithMasking(float alpha, float c) {
    float a2 = alpha * alpha;
    return c > 0.0 ? 2.0 * c / (c + sqrt(a2 + (1.0 - a2) * c * c)) : 0.0;
}

GgxLookup ggxLookup(float alpha, vec3 v, int k, int count) {
    float u1 = (float(k) + 0.5) / float(count);
    float u2 = float(bitfieldReverse(uint(k))) * 2.3283064365386963e-10;
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u1), phi = 2.0 * PI * u2;
    float p1 = r * cos(phi);
    float s = 0.5 * (1.0 + vh.z);
    float p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * r * sin(phi);
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    vec3 h = normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
    float vDotH = clamp(dot(v, h), 0.0, 1.0);
    GgxLookup g;
    g.light = 2.0 * vDotH * h - v;
    float m = 1.0 - vDotH;
    g.fresnelEdge = m * m * m * m * m;
    float a2 = alpha * alpha;
    float g1 = smithMasking(alpha, v.z);
    float cl = g.light.z, cv = v.z;
    // G2/G1 = 4·V·(N·l)(N·v)/G1, V Appendix B's height-correlated visibility.
    float visibilityDenominator = cl * sqrt(cv * cv * (1.0 - a2) + a2) + cv * sqrt(cl * cl * (1.0 - a2) + a2);
    g.weight = cl > 0.0 && g1 > 0.0 ? 2.0 * cl * cv / (visibilityDenominator * g1) : 0.0;
    float d = h.z * h.z * (a2 - 1.0) + 1.0;
    g.pdf = alpha > 0.0 ? g1 * a2 / (PI * d * d) / (4.0 * cv) : intBitsToFloat(0x7f800000);
    return g;
}

// Where (roughness, N·v) is on the fitted lobes' grid (ggx_fitted_lobes.h, gridPoint): the
// texture coordinates of its bilinear read, x = 1 − √(1 − θ/(π/2)) across, roughness down.
vec2 fittedLobeCoordinates(float roughness, float cosView) {
    float theta = acos(clamp(cosView, 0.0, 1.0));
    float x = 1.0 - sqrt(max(0.0, 1.0 - theta / HALF_PI));
    float row = clamp((roughness - FITTED_LEAST_ROUGHNESS) / FITTED_ROUGHNESS_STEP, 0.0, float(FITTED_ROUGHNESS_NODES - 1));
    return vec2((x * float(FITTED_COS_NODES - 1) + 0.5) / float(FITTED_COS_NODES), (row + 0.5) / float(FITTED_ROUGHNESS_NODES));
}

// Fitted lobe k at the grid point `at` for α and the view v = (sin θ, 0, cos θ) (ggx_fitted_lobes.h,
// fittedLobes): its direction in the frame N = z, normalize(R + α(q1·e1 + q2·e2)) with
// e1 = (cos θ, 0, sin θ), e2 = y; its exponent e^(−η)/α² − 2; its weights (F0 part, edge part).
struct FittedLobe {
    vec3 direction;
    float exponent;
    vec2 weights;
};

FittedLobe fittedLobe(vec2 at, float alpha, vec3 v, int k) {
    vec4 shape = texture(uGgxFittedLobes, vec3(at, float(2 * k)));
    FittedLobe f;
    f.weights = texture(uGgxFittedLobes, vec3(at, float(2 * k + 1))).xy;
    f.direction = normalize(vec3(-v.x, 0.0, v.z) + alpha * (shape.x * vec3(v.z, 0.0, v.x) + vec3(0.0, shape.y, 0.0)));
    f.exponent = max(exp(-shape.z) / (alpha * alpha) - 2.0, 0.0);
    return f;
}

// The lobe lookup k reads: 2π·K·pdf/kSampleSpread − 1 (ggx_sampling.h, lookupExponent).
float lookupExponent(float pdf, int count) {
    return isinf(pdf) ? pdf : max(0.0, 2.0 * PI * float(count) * pdf / SAMPLE_SPREAD - 1.0);
}

// Where lookup lobe n about `light` (frame N = z) reads from: raised toward N until the lobe's
// half-maximum cone is above the horizon, its azimuth kept (ggx_sampling.h, keptAboveHorizon).
vec3 keptAboveHorizon(vec3 light, float n) {
    float lowest = isinf(n) ? -1.0 : sqrt(max(0.0, 1.0 - exp2(-2.0 / max(n, 1e-6))));
    float across = length(light.xy);
    vec3 raised = across > 0.0 ? vec3(light.xy * (sqrt(1.0 - lowest * lowest) / across), lowest) : vec3(0.0, 0.0, 1.0);
    return light.z >= lowest ? light : raised;
}

// What the first `count` bright lights add to lookup lobe n at direction d: each light a disc of
// radius ρ_j, so the lobe convolved with it, a normalized Phong lobe (phong.h) widened as the
// footprint widens one (lobes.h, footprintExponent): 1/(n' + 2) = 1/(n + 2) + ρ²/4;
// Σ E_j·(n' + 1)/(2π)·max(0, d·l_j)^n'. The caller passes 0 lights where it would discard the sum:
// a CPU rasterizer runs both sides of a branch for every fragment, but not a loop nobody enters.
vec3 lightsThrough(vec3 d, float n, int count) {
    vec3 sum = vec3(0.0);
    float u = isinf(n) ? 0.0 : 1.0 / (n + 2.0);
    for (int j = 0; j < count; ++j) {
        float c = dot(d, uLightDirection[j].xyz);
        float radius = uLightDirection[j].w;
        float w = u + 0.25 * radius * radius;
        if (c <= 0.0 || w <= 0.0) continue;
        float widened = max(1.0 / w - 2.0, 0.0);
        sum += uLightEnergy[j] * ((widened + 1.0) / (2.0 * PI) * pow(c, widened));
    }
    return sum;
}

// GGX's D averaged over a light's disc (bright_lights.h, discAveragedGgx: the derivation and the
// tests): P22's mean over the disc in slope space, the point-to-parallel-disc form factor.
float discDistribution(float alpha, float cosHalf, float radius) {
    float c = max(cosHalf, 1e-3), c2 = c * c;
    float slope2 = max(1.0 - c2, 0.0) / c2;
    float halfAngle = 0.5 * radius;
    float r = max(min(halfAngle, 0.5 * c) / (c * sqrt(c)), 1e-6);
    float a2 = alpha * alpha;
    float a = a2 + slope2 - r * r;
    float b = 4.0 * a2 * r * r;
    float q = sqrt(a * a + b);
    // 1 − a/q without its cancellation when a > 0.
    float inside = 0.5 * (a > 0.0 ? b / (q * (q + a)) : 1.0 - a / q);
    return inside / (PI * r * r * c2 * c2);
}

// GGX's D averaged over a light's disc as the ellipse its half vectors make (bright_lights.h,
// lightAveragedGgx: the derivation and the tests): the disc of its area where the ellipse is
// round, lost in the lobe or far from the peak, else P22 over the ellipse as an equal-area octagon in slope space, by
// Lambert's formula for the form factor from the point α above it. A loop that no fragment away
// from grazing enters (a CPU rasterizer runs both sides of a branch, not a loop nobody enters).
// (t, bt): any tangent frame of n, the slope plane's axes.
float lightDistribution(float alpha, vec3 n, vec3 t, vec3 bt, vec3 v, vec3 l, vec3 h, float radius) {
    float cosHalf = dot(n, h), viewDotHalf = max(dot(v, h), 1e-3);
    float disc = discDistribution(alpha, max(cosHalf, 0.0), radius * inversesqrt(viewDotHalf));
    float a = 0.52695 * radius;  // ½ρ·√(π/2√2): the octagon of the ellipse's area
    float b = a / viewDotHalf;
    float c2 = max(cosHalf * cosHalf, 1e-6);
    float longRadius = b / c2;
    // |slope of h|² = (1 − cos²)/cos²; beyond longRadius + 2α, the tail.
    float reach = longRadius + 2.0 * alpha;
    bool elliptic = viewDotHalf < 0.77 && cosHalf > 1e-3 && longRadius >= 0.5 * alpha && (1.0 - c2) <= reach * reach * c2;
    // Vertices 0…8 (the 8th is the 0th again), an edge from each to the one before: 9 or 0
    // passes, so no fragment away from grazing enters the loop.
    int vertices = elliptic ? 9 : 0;
    vec3 inPlane = normalize(l - v), across = normalize(cross(h, l - v));
    float flux = 0.0;
    vec3 previous = vec3(0.0);
    for (int k = 0; k < vertices; ++k) {
        float phi = 0.78539816 * float(k);
        vec3 d = normalize(h + a * cos(phi) * inPlane + b * sin(phi) * across);
        vec2 s = vec2(dot(d, t), dot(d, bt)) / max(dot(d, n), 1e-3);
        vec3 w = normalize(vec3(s, -alpha));
        vec3 c = cross(previous, w);
        float sine = length(c);
        if (k > 0 && sine > 0.0) flux += atan(sine, dot(previous, w)) * (c.z / sine);
        previous = w;
    }
    float formFactor = abs(flux) / (2.0 * PI);
    return elliptic ? formFactor / (cosHalf * 2.82842712 * a * b) : disc;
}

// A light's (N·l)⁺ averaged over its disc, which the horizon may cut (bright_lights.h,
// horizonCosine).
float horizonCosine(float cosLight, float radius) {
    if (cosLight >= radius) return cosLight;
    if (cosLight <= -radius) return 0.0;
    float u = cosLight / radius, w = sqrt(max(0.0, 1.0 - u * u));
    return radius * (u * (0.5 + (u * w + asin(u)) / PI) + (2.0 / (3.0 * PI)) * w * w * w);
}

// The first `count` lights through the glTF specular lobe exactly (gltf_brdf.h): Σ F(v·h)·D·V·(N·l)·E_j,
// D GGX's averaged over the light's disc (lightDistribution), V and F at its centre. (t, bt): the
// layer's tangent frame of `normal` (object.frag, readGgx), the slope plane's axes. 0 lights
// where the layer reads them in the environment (lightsThrough: no loop nobody enters).
vec3 lightsSpecular(vec3 normal, vec3 t, vec3 bt, vec3 view, float alpha, vec3 f0, float f90, int count) {
    vec3 sum = vec3(0.0);
    float cv = dot(normal, view);
    if (cv <= 0.0) return sum;
    float a2 = alpha * alpha;
    for (int j = 0; j < count; ++j) {
        vec3 l = uLightDirection[j].xyz;
        float radius = uLightDirection[j].w;
        float cl = horizonCosine(dot(normal, l), radius);
        if (cl <= 0.0) continue;
        vec3 h = normalize(l + view);
        float distribution = lightDistribution(alpha, normal, t, bt, view, l, h, radius);
        float visibility = 0.5 / (cl * sqrt(cv * cv * (1.0 - a2) + a2) + cv * sqrt(cl * cl * (1.0 - a2) + a2));
        float m = 1.0 - clamp(dot(view, h), 0.0, 1.0);
        vec3 fresnel = f0 + (vec3(f90) - f0) * (m * m * m * m * m);
        sum += fresnel * (distribution * visibility * cl) * uLightEnergy[j];
    }
    return sum;
}

// The lights through the glTF diffuse exactly, and through the model's (1 − F0)(1 − Bd)·E/π, whose
// difference corrects the diffuse read: Σ (1 − F(v·h))·(N·l)/π·E_j and Σ (N·l)/π·E_j.
void lightsDiffuse(vec3 normal, vec3 view, vec3 f0, float f90, out vec3 exact, out vec3 lambert) {
    exact = vec3(0.0);
    lambert = vec3(0.0);
    for (int j = 0; j < uLightCount; ++j) {
        vec3 l = uLightDirection[j].xyz;
        float cl = horizonCosine(dot(normal, l), uLightDirection[j].w);
        if (cl <= 0.0) continue;
        vec3 h = normalize(l + view);
        float m = 1.0 - clamp(dot(view, h), 0.0, 1.0);
        vec3 fresnel = f0 + (vec3(f90) - f0) * (m * m * m * m * m);
        exact += (vec3(1.0) - fresnel) * (cl / PI) * uLightEnergy[j];
        lambert += (cl / PI) * uLightEnergy[j];
    }
}
