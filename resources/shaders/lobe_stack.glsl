// The lobe stack (core/scene/lobes.h, docs/lobe-stack.md): exact Phong lobes at λ = j/8, packed in
// one 2D atlas, each face with its one-texel border, read at their base level only. Any lobe n
// (per object or per fragment) is the blend of its two neighbours with the weight that keeps its
// mean cosine (stackBlend in lobes.h); a fragment whose footprint is wider than its lobe reads
// the wider lobe the footprint makes (footprintExponent). Included by shading_plan.glsl and
// background.frag.
uniform sampler2D uStack;                   // TEXTURE_UNIT_STACK: the atlas (RGB9_E5), linear, no mips
uniform vec4 uStackEntry[STACK_SLOTS];      // per entry: block origin x, y (texels), face size, 1 when present
uniform float uStackExponent[STACK_SLOTS];  // per entry: its exponent
uniform float uStackScale[STACK_SLOTS];     // per entry: what its stored texels are multiplied by
uniform int uStackTop;                      // the sharpest entry (lobes.h, stackTop)

// Face and (s, t) of a direction, by the major axis as the OpenGL specification's cube map table
// gives them (§8.13; core/ibl/cubemap.h, directionToFace, follows the same table).
vec2 cubeFaceCoord(vec3 d, out int face) {
    vec3 a = abs(d);
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        ma = a.x; face = d.x >= 0.0 ? 0 : 1; sc = d.x >= 0.0 ? -d.z : d.z; tc = -d.y;
    } else if (a.y >= a.z) {
        ma = a.y; face = d.y >= 0.0 ? 2 : 3; sc = d.x; tc = d.y >= 0.0 ? d.z : -d.z;
    } else {
        ma = a.z; face = d.z >= 0.0 ? 4 : 5; sc = d.z >= 0.0 ? d.x : -d.x; tc = -d.y;
    }
    return 0.5 * (vec2(sc, tc) / ma + 1.0);
}

// The atlas block `entry` (x, y, face size) at direction d, times `scale`: bilinear between its
// face's texel centres, across the face edge through the border (which holds the lobe on the
// face's extended plane).
vec3 atlasRead(vec3 entry, float scale, vec3 d) {
    int face;
    vec2 st = cubeFaceCoord(d, face);
    float stride = entry.z + 2.0;
    vec2 texel = entry.xy + vec2(float(face % 3), float(face / 3)) * stride + 1.0 + st * entry.z;
    return textureLod(uStack, texel / vec2(textureSize(uStack, 0)), 0.0).rgb * scale;
}

// Entry j at direction d.
vec3 stackEntryAt(int j, vec3 d) { return atlasRead(uStackEntry[j].xyz, uStackScale[j], d); }

// λ ↔ n, the one place in GLSL (phong.h, exponentToLambda and lambdaToExponent):
// λ(n) = max(0, log2(128·√3) − ½·log2(n + 1)), 0 for the mirror; n(λ) = 3·128²·4^−λ − 1 clamped at 0.
float exponentLambda(float n) { return isinf(n) ? 0.0 : max(0.0, 0.5 * log2(LAMBDA_EXPONENT_SCALE / (n + 1.0))); }
float grazingExponent(float lambda) { return max(LAMBDA_EXPONENT_SCALE * exp2(-2.0 * lambda) - 1.0, 0.0); }

// Whether lobe n is one the stack can hold (finite, not sharper than its top entry).
bool stackRange(float n) { return n >= 0.0 && !isinf(n) && n <= uStackExponent[uStackTop]; }

// The entry on n's sharper side (stackBlend in lobes.h): the last from the top whose lobe is at
// least as sharp. n must be in stackRange.
int stackSharperIndex(float n) {
    int j = clamp(int(floor(exponentLambda(n) * float(STACK_STEPS_PER_LEVEL))), uStackTop, STACK_LAST);
    if (j > uStackTop && uStackExponent[j] < n) --j;
    if (j < STACK_LAST && uStackExponent[j + 1] >= n) ++j;
    return j;
}

// The entry nearest lobe n, in λ (entries 2^¼ apart in n): not clamped to the stack's range.
int stackNearestIndex(float n) { return int(round(exponentLambda(n) * float(STACK_STEPS_PER_LEVEL))); }

// The wider neighbour's weight in the blend of entries `sharper` and `wider` that keeps lobe n's
// mean cosine (lobes.h, stackBlend): linear in 1/(n + 2), the lobe's mean of 1 − cos θ.
float stackBlendWeight(float n, int sharper, int wider) {
    float u = 1.0 / (n + 2.0), u0 = 1.0 / (uStackExponent[sharper] + 2.0), u1 = 1.0 / (uStackExponent[wider] + 2.0);
    return u1 > u0 ? clamp((u - u0) / (u1 - u0), 0.0, 1.0) : 0.0;
}

// n's neighbours and the wider one's weight; false when the stack does not hold both (n sharper
// than its top entry, or an entry not yet made).
bool stackBlendOf(float n, out int sharper, out float weight) {
    sharper = 0;
    weight = 0.0;
    if (!stackRange(n)) return false;
    int j = stackSharperIndex(n);
    int wider = min(j + 1, STACK_LAST);
    weight = stackBlendWeight(n, j, wider);
    // Float rounding at an entry: a weight within 1e-4 of 0 or 1 reads that entry alone, so a
    // lobe on an entry never needs the neighbour the C++ side did not ask for.
    if (weight > 0.9999) {
        j = wider;
        weight = 0.0;
    }
    if (weight < 1e-4) weight = 0.0;
    sharper = j;
    return uStackEntry[j].w > 0.5 && (weight == 0.0 || uStackEntry[min(j + 1, STACK_LAST)].w > 0.5);
}

bool stackHolds(float n) {
    int j;
    float w;
    return stackBlendOf(n, j, w);
}

vec3 stackRead(vec3 d, float n) {
    int j;
    float w;
    stackBlendOf(n, j, w);
    vec3 sharp = stackEntryAt(j, d);
    return w > 0.0 ? mix(sharp, stackEntryAt(min(j + 1, STACK_LAST), d), w) : sharp;
}

// Lobe n widened by a footprint's share w = (|dx|² + |dy|²)/24 (lobes.h, footprintExponent):
// 1/(n' + 2) = 1/(n + 2) + w. A caller reading many lobes through one footprint computes w once.
float widenedExponent(float n, float w) {
    float u = (isinf(n) ? 0.0 : 1.0 / (n + 2.0)) + w;
    return u > 0.0 ? max(1.0 / u - 2.0, 0.0) : n;
}

// The lobe a pixel shows when its unit lookup direction changes by dx, dy to the next pixels
// (lobes.h, footprintExponent): 1/(n' + 2) = 1/(n + 2) + (|dx|² + |dy|²)/24.
float footprintExponent(float n, vec3 dx, vec3 dy) {
    return widenedExponent(n, (dot(dx, dx) + dot(dy, dy)) / 24.0);
}

// Lobe n (held by the stack) widened by the footprint, but never past the widest entry the scene
// asks the stack for on n's behalf (lobes.h, kFootprintReach entries past n's wider neighbour):
// so the picture does not depend on which other entries happen to be made. `complete` is false
// where the footprint would widen it further (the pixel then shows a lobe sharper than its
// footprint, and the AOV does not call it exact).
float footprintLimitedExponent(float n, vec3 dx, vec3 dy, out bool complete) {
    float shown = footprintExponent(n, dx, dy);
    complete = true;
    if (!stackRange(n)) return shown;
    float widest = uStackExponent[min(stackSharperIndex(n) + 1 + STACK_FOOTPRINT_REACH, STACK_LAST)];
    if (shown < widest) {
        complete = shown >= widest * 0.999;
        shown = widest;
    }
    return shown;
}
