#include "lobe_filter.h"

#include "mipgloss/ibl/colour.h"
#include "mipgloss/ibl/parallel.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mipgloss::detail {

namespace {

glm::vec3 toLocal(const glm::vec3& r, Face f) {
    const FaceFrame& fr = faceFrame(f);
    return {glm::dot(r, fr.u), glm::dot(r, fr.v), glm::dot(r, fr.axis)};
}

float angleBetween(const glm::vec3& a, const glm::vec3& b) {
    // atan2 form: accurate for tiny and large angles alike.
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

int nodeGroupFor(int size) {
    if (size % 4 == 0) return 4;
    if (size % 2 == 0) return 2;
    return 1;
}

// Per-thread scratch for the node walk: visit stamps avoid clearing between output texels.
struct WalkScratch {
    std::vector<std::uint32_t> stamp;
    std::uint32_t current = 0;
    std::vector<int> queue;
    const NodeGrid* grid = nullptr;

    void begin(const NodeGrid& g) {
        const std::size_t n = 6u * static_cast<std::size_t>(g.nodes) * static_cast<std::size_t>(g.nodes);
        if (grid != &g || stamp.size() != n) {
            stamp.assign(n, 0);
            current = 0;
            grid = &g;
        }
        if (++current == 0) {  // wrapped: forget every old stamp
            std::fill(stamp.begin(), stamp.end(), 0);
            current = 1;
        }
        queue.clear();
    }
};

WalkScratch& threadScratch() {
    thread_local WalkScratch scratch;
    return scratch;
}

// Calls visit(face, nodeX, nodeY) for every node whose bounding cone meets the cap of half-angle
// α (given as cos α, sin α) around unit direction r.
template <class Visit>
void forEachNodeInCap(const NodeGrid& g, const glm::vec3& r, float cosA, float sinA, Visit&& visit) {
    WalkScratch& s = threadScratch();
    s.begin(g);
    const int n = g.nodes;
    const int perFace = n * n;
    auto push = [&](Face f, int x, int y) {
        const int id = static_cast<int>(f) * perFace + y * n + x;
        if (s.stamp[static_cast<std::size_t>(id)] == s.current) return;
        s.stamp[static_cast<std::size_t>(id)] = s.current;
        s.queue.push_back(id);
    };
    const TexelRef start = texelOf(directionToFace(r), n);
    push(start.face, start.x, start.y);
    for (std::size_t head = 0; head < s.queue.size(); ++head) {
        const int id = s.queue[head];
        const Face f = static_cast<Face>(id / perFace);
        const int local = id % perFace;
        const int x = local % n, y = local / n;
        // Accept when angle(r, axis) <= α + β, i.e. r·axis >= cos(α + β).
        const float cb = g.cosRadius[static_cast<std::size_t>(local)];
        const float sb = g.sinRadius[static_cast<std::size_t>(local)];
        const float threshold = cosA * cb - sinA * sb;
        if (glm::dot(r, g.axis[static_cast<std::size_t>(id)]) < threshold && head != 0) continue;
        visit(f, x, y);
        const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k) {
            const TexelRef nb = resolveTexel(f, x + dx[k], y + dy[k], n);
            push(nb.face, nb.x, nb.y);
        }
    }
}

// Weights w(x) = (1 - x)^n for x = 1 - R·ω in [0, xmax), tabulated for linear interpolation.
// With 4096 intervals over the support, n·Δx = ln(1/cutoff)/4096, so the interpolation's relative
// error ((n·Δx)²/8) stays below 1e-6.
class WeightTable {
public:
    WeightTable(double exponent, double xmax) : xmax_(static_cast<float>(xmax)) {
        std::vector<float> values(kIntervals + 3);
        for (int i = 0; i <= kIntervals + 1; ++i) {
            const double x = std::min(1.0, xmax * i / kIntervals);
            values[static_cast<std::size_t>(i)] =
                exponent == 0.0 ? 1.0f : static_cast<float>(std::exp(exponent * std::log1p(-x)));
        }
        values[kIntervals + 2] = values[kIntervals + 1];
        // Each interval as (value at its start, step to the next): one 8-byte load per tap.
        pairs_.resize(2 * (kIntervals + 2));
        for (std::size_t i = 0; i < kIntervals + 2; ++i) {
            pairs_[2 * i] = values[i];
            pairs_[2 * i + 1] = values[i + 1] - values[i];
        }
        scale_ = static_cast<float>(kIntervals / xmax);
    }
    float xmax() const { return xmax_; }
    float scale() const { return scale_; }
    // Interval i's (start value, step): pairs()[2i], pairs()[2i + 1].
    const float* pairs() const { return pairs_.data(); }
    // w(x), and 0 from xmax on (the cut). The index is clamped first, so it stays inside the
    // table whatever x is (the vector path computes every lane before masking).
    float cut(float x) const {
        const float f = std::min(x, xmax_) * scale_;
        const int i = static_cast<int>(f);
        const float w = pairs_[2 * static_cast<std::size_t>(i)] +
                        (f - static_cast<float>(i)) * pairs_[2 * static_cast<std::size_t>(i) + 1];
        return x < xmax_ ? w : 0.0f;
    }

private:
    static constexpr int kIntervals = 4096;
    std::vector<float> pairs_;
    float xmax_;
    float scale_ = 0.0f;
};


// Output texels are processed in tiles of kTile×kTile: the node walk runs once per tile with the
// cap widened by the tile's own angular radius, and each texel then tests the collected nodes'
// cones against its own cap (one dot product each) before touching their texels.
constexpr int kTile = 8;

// What a tile pass sums: at the base, energy and solid angle sit at one point, so one weight serves
// both (Combined). On a coarser level they sit at different points: the energy pass reads
// `denominators` made by a geometry pass over face +X only. The solid-angle sum Σ w(R·g)·Ω is the
// same at the matching texel of every face, because the cube's symmetries map face +X's output
// texels onto every face's and the source grid (identical in each face's frame, and symmetric
// under the square's own symmetries) onto itself.
enum class Pass { Combined, Energy, Geometry };

// A source's texels regrouped node by node (a node's group² texels contiguous, in row order) with
// every coordinate and colour channel in its own array: the tap loop over one node (sumNode) then
// loads four taps of a channel at once. Geometry is shared by the six faces (face-local frame);
// energy and its directions are per face.
struct NodeTaps {
    int taps = 0;  // texels per node, group²
    std::array<std::vector<float>, 4> geo;                  // x, y, z, Ω
    std::array<std::array<std::vector<float>, 6>, 3> dir;   // energy direction x, y, z per face (coarse sources)
    std::array<std::array<std::vector<float>, 6>, 3> energy;  // r, g, b per face
};

NodeTaps packNodeTaps(const LobeSource& src) {
    const NodeGrid& g = src.grid;
    const int group = g.group, size = src.size;
    NodeTaps p;
    p.taps = group * group;
    const std::size_t n = static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
    // Packed position of texel (x, y): its node's slot, then its place in the node.
    auto packed = [&](int x, int y) {
        const int node = (y / group) * g.nodes + x / group;
        return static_cast<std::size_t>(node) * static_cast<std::size_t>(p.taps) +
               static_cast<std::size_t>((y % group) * group + x % group);
    };
    for (auto& v : p.geo) v.resize(n);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const std::size_t k = static_cast<std::size_t>(y) * size + static_cast<std::size_t>(x), q = packed(x, y);
            for (int c = 0; c < 3; ++c) p.geo[static_cast<std::size_t>(c)][q] = src.geoDir[k][c];
            p.geo[3][q] = src.omega[k];
        }
    const bool separate = !src.energyDir[0].empty();
    parallelFor(0, 6, [&](int fi) {
        const std::size_t f = static_cast<std::size_t>(fi);
        for (int c = 0; c < 3; ++c) {
            p.energy[static_cast<std::size_t>(c)][f].resize(n);
            if (separate) p.dir[static_cast<std::size_t>(c)][f].resize(n);
        }
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const std::size_t k = static_cast<std::size_t>(y) * size + static_cast<std::size_t>(x), q = packed(x, y);
                for (int c = 0; c < 3; ++c) {
                    p.energy[static_cast<std::size_t>(c)][f][q] = src.energy[f][k][c];
                    if (separate) p.dir[static_cast<std::size_t>(c)][f][q] = src.energyDir[f][k][c];
                }
            }
    });
    return p;
}

// Σ over one node's taps of w(x)·(E, Ω) with x = ½|r − ω|², w cut at xmax. (½|r − ω|² is 1 − r·ω
// for unit vectors, without the cancellation of computing 1 − r·ω directly.) Float sums over at
// most 16 taps; the caller adds them up in double.
struct NodeSum {
    float r = 0.0f, g = 0.0f, b = 0.0f, w = 0.0f;
};

template <bool kEnergy, bool kSolidAngle>
NodeSum sumNode(const glm::vec3& rf, const float* dx, const float* dy, const float* dz, const float* er,
                const float* eg, const float* eb, const float* om, int taps, const WeightTable& table) {
    int t = 0;
    NodeSum s;
#if defined(__SSE2__)
    // Four taps at a time (SSE2, every x86-64). Each lane computes what `table.cut` computes, op
    // for op; only the order of the float sums differs from the scalar loop.
    if (taps % 4 == 0) {
        const __m128 rx = _mm_set1_ps(rf.x), ry = _mm_set1_ps(rf.y), rz = _mm_set1_ps(rf.z);
        const __m128 half = _mm_set1_ps(0.5f), xmax = _mm_set1_ps(table.xmax()), scale = _mm_set1_ps(table.scale());
        const float* pairs = table.pairs();
        __m128 ar = _mm_setzero_ps(), ag = _mm_setzero_ps(), ab = _mm_setzero_ps(), aw = _mm_setzero_ps();
        for (; t < taps; t += 4) {
            const __m128 d0 = _mm_sub_ps(rx, _mm_loadu_ps(dx + t));
            const __m128 d1 = _mm_sub_ps(ry, _mm_loadu_ps(dy + t));
            const __m128 d2 = _mm_sub_ps(rz, _mm_loadu_ps(dz + t));
            const __m128 x = _mm_mul_ps(
                half, _mm_add_ps(_mm_add_ps(_mm_mul_ps(d0, d0), _mm_mul_ps(d1, d1)), _mm_mul_ps(d2, d2)));
            const __m128 f = _mm_mul_ps(_mm_min_ps(x, xmax), scale);
            const __m128i i = _mm_cvttps_epi32(f);
            alignas(16) std::int32_t idx[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(idx), i);
            // Gather the four (start, step) pairs: (a0 s0), (a1 s1) -> (a0 a1 s0 s1), and so on.
            const __m128 p0 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(pairs + 2 * idx[0])));
            const __m128 p1 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(pairs + 2 * idx[1])));
            const __m128 p2 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(pairs + 2 * idx[2])));
            const __m128 p3 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(pairs + 2 * idx[3])));
            const __m128 lo = _mm_unpacklo_ps(p0, p1), hi = _mm_unpacklo_ps(p2, p3);
            const __m128 start = _mm_movelh_ps(lo, hi), step = _mm_movehl_ps(hi, lo);
            __m128 w = _mm_add_ps(start, _mm_mul_ps(_mm_sub_ps(f, _mm_cvtepi32_ps(i)), step));
            w = _mm_and_ps(w, _mm_cmplt_ps(x, xmax));
            if constexpr (kEnergy) {
                ar = _mm_add_ps(ar, _mm_mul_ps(w, _mm_loadu_ps(er + t)));
                ag = _mm_add_ps(ag, _mm_mul_ps(w, _mm_loadu_ps(eg + t)));
                ab = _mm_add_ps(ab, _mm_mul_ps(w, _mm_loadu_ps(eb + t)));
            }
            if constexpr (kSolidAngle) aw = _mm_add_ps(aw, _mm_mul_ps(w, _mm_loadu_ps(om + t)));
        }
        auto total = [](__m128 v) {
            alignas(16) float lane[4];
            _mm_store_ps(lane, v);
            return (lane[0] + lane[1]) + (lane[2] + lane[3]);
        };
        if constexpr (kEnergy) s = {total(ar), total(ag), total(ab), 0.0f};
        if constexpr (kSolidAngle) s.w = total(aw);
    }
#endif
    for (; t < taps; ++t) {
        const float d0 = rf.x - dx[t], d1 = rf.y - dy[t], d2 = rf.z - dz[t];
        const float w = table.cut(0.5f * (d0 * d0 + d1 * d1 + d2 * d2));
        if constexpr (kEnergy) {
            s.r += w * er[t];
            s.g += w * eg[t];
            s.b += w * eb[t];
        }
        if constexpr (kSolidAngle) s.w += w * om[t];
    }
    return s;
}

template <Pass kPass>
void convolveTile(const LobeSource& src, const NodeTaps& taps, const WeightTable& table, float alpha, FaceGrid& out,
                  int tile, std::vector<double>& denominators) {
    const int m = out.size;
    const int b = out.border;
    const int extent = out.extent();
    const int tilesPerSide = (extent + kTile - 1) / kTile;
    const Face fo = static_cast<Face>(tile / (tilesPerSide * tilesPerSide));
    const int local = tile % (tilesPerSide * tilesPerSide);
    const int x0 = (local % tilesPerSide) * kTile - b, y0 = (local / tilesPerSide) * kTile - b;
    const int x1 = std::min(m + b, x0 + kTile), y1 = std::min(m + b, y0 + kTile);
    const float invM = 1.0f / static_cast<float>(m);
    const glm::vec3 centre = faceToDirection(fo, 0.5f * static_cast<float>(x0 + x1) * invM,
                                             0.5f * static_cast<float>(y0 + y1) * invM);
    float tileRadius = 0.0f;
    for (int cy : {y0, y1})
        for (int cx : {x0, x1})
            tileRadius = std::max(tileRadius, angleBetween(centre, faceToDirection(fo, static_cast<float>(cx) * invM,
                                                                                 static_cast<float>(cy) * invM)));
    const float wide = std::min(alpha + tileRadius + 1e-4f, 3.1415926f);
    thread_local std::vector<int> nodes;
    nodes.clear();
    const NodeGrid& grid = src.grid;
    const int perFace = grid.nodes * grid.nodes;
    forEachNodeInCap(grid, centre, std::cos(wide), std::sin(wide), [&](Face f, int nx, int ny) {
        nodes.push_back(static_cast<int>(f) * perFace + ny * grid.nodes + nx);
    });
    const float cosA = std::cos(alpha), sinA = std::sin(alpha);
    const int size = src.size;
    const int n = taps.taps;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            const glm::vec3 r = faceToDirection(fo, (static_cast<float>(x) + 0.5f) * invM,
                                                (static_cast<float>(y) + 0.5f) * invM);
            std::array<glm::vec3, 6> rl;
            for (Face f : kAllFaces) rl[static_cast<std::size_t>(f)] = toLocal(r, f);
            glm::dvec3 acc(0.0);
            double wsum = 0.0;
            for (const int id : nodes) {
                const int nodeLocal = id % perFace;
                const float threshold = cosA * grid.cosRadius[static_cast<std::size_t>(nodeLocal)] -
                                        sinA * grid.sinRadius[static_cast<std::size_t>(nodeLocal)];
                if (glm::dot(r, grid.axis[static_cast<std::size_t>(id)]) < threshold) continue;
                const std::size_t fi = static_cast<std::size_t>(id / perFace);
                const std::size_t off = static_cast<std::size_t>(nodeLocal) * static_cast<std::size_t>(n);
                // The energy pass weighs by the energy's own directions, the others by the texels'.
                auto dir = [&](std::size_t c) {
                    return (kPass == Pass::Energy ? taps.dir[c][fi].data() : taps.geo[c].data()) + off;
                };
                auto energy = [&](std::size_t c) { return taps.energy[c][fi].data() + off; };
                const NodeSum s = sumNode<kPass != Pass::Geometry, kPass != Pass::Energy>(
                    rl[fi], dir(0), dir(1), dir(2), energy(0), energy(1), energy(2), taps.geo[3].data() + off, n, table);
                acc += glm::dvec3(s.r, s.g, s.b);
                wsum += static_cast<double>(s.w);
            }
            const std::size_t texel = out.index(x, y);
            if constexpr (kPass == Pass::Geometry) {
                denominators[texel] = wsum;
                continue;
            }
            if constexpr (kPass == Pass::Energy) wsum = denominators[texel];
            Rgb value;
            if (wsum > 0.0) {
                value = Rgb(acc / wsum);
            } else {
                // The lobe is narrower than the source texels around r: its limit is the texel holding r.
                const TexelRef t = texelOf(directionToFace(r), size);
                const std::size_t k = static_cast<std::size_t>(t.y) * size + static_cast<std::size_t>(t.x);
                value = src.energy[static_cast<std::size_t>(t.face)][k] / src.omega[k];
            }
            out.at(fo, x, y) = value;
        }
    }
}

// Cubic B-spline weights (1−t)³/6, (3t³−6t²+4)/6, (−3t³+3t²+3t+1)/6, t³/6 for the two phases of
// a 2× upsampling: output texel centres fall at t = 0.75 (even outputs) and t = 0.25 (odd ones)
// between grid texels i and i + 1. All positive: no ringing from the evaluation itself.
constexpr std::array<std::array<float, 4>, 2> kCubicBSpline{{
    {1.0f / 384.0f, 121.0f / 384.0f, 235.0f / 384.0f, 27.0f / 384.0f},  // t = 0.75
    {27.0f / 384.0f, 235.0f / 384.0f, 121.0f / 384.0f, 1.0f / 384.0f},  // t = 0.25
}};

// Interpolating cubic B-spline coefficients along one line (stride apart): solves
// (c[i-1] + 4 c[i] + c[i+1]) / 6 = v[i] by the Thomas algorithm, the line's ends taken as
// c = 0 beyond them. The error that assumption makes decays by 2 − √3 ≈ 0.27 per texel inward,
// so a border of 6 texels leaves under 4e-4 of it on the face (Unser 1999, "Splines: a perfect
// fit for signal and image processing").
void bsplineCoefficients(Rgb* v, int count, std::ptrdiff_t stride, std::vector<float>& scratch) {
    scratch.resize(static_cast<std::size_t>(count));
    // Forward sweep with the constant diagonals 1/6, 4/6, 1/6 (in units of 1/6: 1, 4, 1).
    float cp = 1.0f / 4.0f;
    scratch[0] = cp;
    v[0] = v[0] * (6.0f / 4.0f);
    for (int i = 1; i < count; ++i) {
        const float m = 4.0f - cp;
        cp = 1.0f / m;
        scratch[static_cast<std::size_t>(i)] = cp;
        v[i * stride] = (6.0f * v[i * stride] - v[(i - 1) * stride]) / m;
    }
    for (int i = count - 2; i >= 0; --i) v[i * stride] -= scratch[static_cast<std::size_t>(i)] * v[(i + 1) * stride];
}

}  // namespace

NodeGrid makeNodeGrid(int size) {
    NodeGrid g;
    g.size = size;
    g.group = nodeGroupFor(size);
    g.nodes = size / g.group;
    const int n = g.nodes;
    const float inv = 1.0f / static_cast<float>(n);
    g.axis.resize(6u * static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    g.cosRadius.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    g.sinRadius.resize(g.cosRadius.size());
    for (Face f : kAllFaces)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                g.axis[static_cast<std::size_t>(static_cast<int>(f) * n * n + y * n + x)] =
                    texelDirection(f, x, y, n);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            // The farthest point of a node from its axis is a corner (the cap around the axis
            // meets the face plane in a convex region); a small margin covers rounding.
            const glm::vec3 a = texelDirection(Face::PX, x, y, n);
            float radius = 0.0f;
            for (int cy = 0; cy <= 1; ++cy)
                for (int cx = 0; cx <= 1; ++cx)
                    radius = std::max(radius, angleBetween(a, faceToDirection(Face::PX, static_cast<float>(x + cx) * inv,
                                                                             static_cast<float>(y + cy) * inv)));
            radius += 1e-4f;
            g.cosRadius[static_cast<std::size_t>(y * n + x)] = std::cos(radius);
            g.sinRadius[static_cast<std::size_t>(y * n + x)] = std::sin(radius);
        }
    }
    return g;
}

LobeSource baseSource(const CubeMap& base) {
    LobeSource s;
    const int m = base.size();
    s.size = m;
    s.grid = makeNodeGrid(m);
    const std::size_t n = static_cast<std::size_t>(m) * static_cast<std::size_t>(m);
    s.geoDir.resize(n);
    s.omega.resize(n);
    s.geoMoment.resize(n);
    parallelFor(0, m, [&](int y) {
        for (int x = 0; x < m; ++x) {
            const std::size_t k = static_cast<std::size_t>(y) * m + static_cast<std::size_t>(x);
            s.geoDir[k] = toLocal(texelDirection(Face::PX, x, y, m), Face::PX);
            s.omega[k] = static_cast<float>(texelSolidAngle(x, y, m));
            s.geoMoment[k] = s.omega[k] * s.geoDir[k];
        }
    });
    parallelFor(0, 6, [&](int fi) {
        const Face f = static_cast<Face>(fi);
        auto& e = s.energy[static_cast<std::size_t>(fi)];
        e.resize(n);
        for (int y = 0; y < m; ++y)
            for (int x = 0; x < m; ++x) {
                const std::size_t k = static_cast<std::size_t>(y) * m + static_cast<std::size_t>(x);
                e[k] = base.at(f, x, y) * s.omega[k];
            }
    });
    return s;
}

namespace {
// In double: an energy moment of a map scaled by 1e-30 is about 1e-34, whose square underflows
// float to 0 (the texel then fell back to its geometric centre: 15 % off at level 1, issue 24).
glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& fallback) {
    const glm::dvec3 d(v);
    const double len = glm::length(d);
    return len > 0.0 && std::isfinite(len) ? glm::vec3(d / len) : fallback;
}
}  // namespace

LobeSource coarsenSource(const LobeSource& fine) {
    assert(fine.size % 2 == 0);
    LobeSource s;
    const int m = fine.size / 2;
    s.size = m;
    s.grid = makeNodeGrid(m);
    const std::size_t n = static_cast<std::size_t>(m) * static_cast<std::size_t>(m);
    s.geoDir.resize(n);
    s.omega.resize(n);
    s.geoMoment.resize(n);
    auto fineIndex = [&](int x, int y) {
        return static_cast<std::size_t>(y) * fine.size + static_cast<std::size_t>(x);
    };
    for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x) {
            const std::size_t k = static_cast<std::size_t>(y) * m + static_cast<std::size_t>(x);
            glm::vec3 moment(0.0f);
            float omega = 0.0f;
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 2; ++i) {
                    const std::size_t c = fineIndex(2 * x + i, 2 * y + j);
                    moment += fine.geoMoment[c];
                    omega += fine.omega[c];
                }
            s.geoMoment[k] = moment;
            s.omega[k] = omega;
            s.geoDir[k] = glm::normalize(moment);
        }
    parallelFor(0, 6, [&](int face) {
        const std::size_t fi = static_cast<std::size_t>(face);
        auto& e = s.energy[fi];
        auto& ed = s.energyDir[fi];
        auto& em = s.energyMoment[fi];
        e.resize(n);
        ed.resize(n);
        em.resize(n);
        const bool fineIsBase = fine.energyMoment[fi].empty();
        for (int y = 0; y < m; ++y)
            for (int x = 0; x < m; ++x) {
                const std::size_t k = static_cast<std::size_t>(y) * m + static_cast<std::size_t>(x);
                Rgb energy(0.0f);
                glm::vec3 moment(0.0f);
                for (int j = 0; j < 2; ++j)
                    for (int i = 0; i < 2; ++i) {
                        const std::size_t c = fineIndex(2 * x + i, 2 * y + j);
                        energy += fine.energy[fi][c];
                        moment += fineIsBase ? static_cast<float>(luminance(fine.energy[fi][c])) * fine.geoDir[c]
                                             : fine.energyMoment[fi][c];
                    }
                e[k] = energy;
                em[k] = moment;
                ed[k] = normalizedOr(moment, s.geoDir[k]);
            }
    });
    return s;
}

double supportCosine(double exponent, double cutoff) {
    if (exponent <= 0.0) return 0.0;
    return std::exp(std::log(cutoff) / exponent);
}

FaceGrid convolveGrid(const LobeSource& src, double exponent, int size, int border, double cutoff) {
    const double cmin = supportCosine(exponent, cutoff);
    // 1 - cmin without cancellation for huge exponents.
    const double xmax = exponent <= 0.0 ? 1.0 : -std::expm1(std::log(cutoff) / exponent);
    const WeightTable table(exponent, xmax);
    const float alpha = static_cast<float>(std::acos(cmin));
    FaceGrid out(size, border);
    const bool separate = !src.energyDir[0].empty();
    const int tilesPerSide = (out.extent() + kTile - 1) / kTile;
    const int tilesPerFace = tilesPerSide * tilesPerSide;
    std::vector<double> denominators(static_cast<std::size_t>(out.extent()) * static_cast<std::size_t>(out.extent()));
    const NodeTaps taps = packNodeTaps(src);
    if (separate)  // face +X's tiles come first: the geometry pass covers exactly them
        parallelFor(0, tilesPerFace, [&](int tile) {
            convolveTile<Pass::Geometry>(src, taps, table, alpha, out, tile, denominators);
        });
    parallelFor(0, 6 * tilesPerFace, [&](int tile) {
        if (separate)
            convolveTile<Pass::Energy>(src, taps, table, alpha, out, tile, denominators);
        else
            convolveTile<Pass::Combined>(src, taps, table, alpha, out, tile, denominators);
    });
    return out;
}

CubeMap convolve(const LobeSource& src, double exponent, int outSize, double cutoff) {
    const FaceGrid grid = convolveGrid(src, exponent, outSize, 0, cutoff);
    CubeMap out(outSize);
    for (Face f : kAllFaces)
        for (int y = 0; y < outSize; ++y)
            for (int x = 0; x < outSize; ++x) out.at(f, x, y) = grid.at(f, x, y);
    out.makeSeamless();
    return out;
}

CubeMap convolveUpsampled(const LobeSource& src, double exponent, int outSize, double cutoff) {
    assert(outSize % 2 == 0);
    const int m = outSize / 2;
    // The border values are the filter evaluated on the face's plane extended past its edges, so
    // the grid is smooth across them (no kink where the faces meet); six texels of it keep the
    // spline's end conditions away from the face (bsplineCoefficients).
    constexpr int kBorder = 6;
    FaceGrid grid = convolveGrid(src, exponent, m, kBorder, cutoff);
    const int e = grid.extent();
    parallelFor(0, 6, [&](int fi) {
        std::vector<float> scratch;
        Rgb* v = grid.values[static_cast<std::size_t>(fi)].data();
        for (int y = 0; y < e; ++y) bsplineCoefficients(v + static_cast<std::ptrdiff_t>(y) * e, e, 1, scratch);
        for (int x = 0; x < e; ++x) bsplineCoefficients(v + x, e, e, scratch);
    });
    CubeMap out(outSize);
    parallelFor(0, cubeRows(outSize), [&](int row) {
        const auto [f, y] = faceRowOf(row, outSize);
        // Output centre (y + 0.5)/outSize on the face is grid coordinate y/2 - 0.25.
        const int gy = (y - (y % 2 == 0 ? 2 : 1)) / 2;  // the grid texel before it
        const auto& wy = kCubicBSpline[static_cast<std::size_t>(y % 2)];
        for (int x = 0; x < outSize; ++x) {
            const int gx = (x - (x % 2 == 0 ? 2 : 1)) / 2;
            const auto& wx = kCubicBSpline[static_cast<std::size_t>(x % 2)];
            Rgb v(0.0f);
            for (int j = 0; j < 4; ++j) {
                Rgb rowSum(0.0f);
                for (int i = 0; i < 4; ++i) rowSum += wx[static_cast<std::size_t>(i)] * grid.at(f, gx - 1 + i, gy - 1 + j);
                v += wy[static_cast<std::size_t>(j)] * rowSum;
            }
            // An interpolating spline may overshoot beside a sharp peak; radiance is never negative.
            out.at(f, x, y) = glm::max(v, Rgb(0.0f));
        }
    });
    out.makeSeamless();
    return out;
}

ExactLobe::ExactLobe(const CubeMap& base, double exponent, double cutoff)
    : base_(base), exponent_(exponent), grid_(makeNodeGrid(base.size())) {
    const int m = base.size();
    const std::size_t n = static_cast<std::size_t>(m) * static_cast<std::size_t>(m);
    dir_.resize(n);
    omega_.resize(n);
    for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x) {
            const std::size_t k = static_cast<std::size_t>(y) * m + static_cast<std::size_t>(x);
            const double sc = 2.0 * (x + 0.5) / m - 1.0, tc = 2.0 * (y + 0.5) / m - 1.0;
            dir_[k] = glm::normalize(glm::dvec3(sc, tc, 1.0));
            omega_[k] = texelSolidAngle(x, y, m);
        }
    const double cmin = supportCosine(exponent, cutoff);
    xmax_ = exponent <= 0.0 ? 1.0 : -std::expm1(std::log(cutoff) / exponent);
    // The walk only culls; a slightly wider cap costs a few taps and loses none.
    const double alpha = std::min(std::acos(cmin) * 1.0001 + 1e-6, 0.5 * 3.14159265358979);
    cosA_ = static_cast<float>(std::cos(alpha));
    sinA_ = static_cast<float>(std::sin(alpha));
}

Rgb ExactLobe::at(const glm::dvec3& direction) const {
    const int m = base_.size();
    const glm::dvec3 r = glm::normalize(direction);
    glm::dvec3 acc(0.0);
    double wsum = 0.0;
    forEachNodeInCap(grid_, glm::vec3(r), cosA_, sinA_, [&](Face f, int nx, int ny) {
        const FaceFrame& fr = faceFrame(f);
        const glm::dvec3 rl(glm::dot(r, glm::dvec3(fr.u)), glm::dot(r, glm::dvec3(fr.v)),
                            glm::dot(r, glm::dvec3(fr.axis)));
        for (int j = 0; j < grid_.group; ++j)
            for (int i = 0; i < grid_.group; ++i) {
                const int sx = nx * grid_.group + i, sy = ny * grid_.group + j;
                const std::size_t k = static_cast<std::size_t>(sy) * m + static_cast<std::size_t>(sx);
                const glm::dvec3 d = rl - dir_[k];
                const double xk = 0.5 * glm::dot(d, d);
                if (xk >= xmax_) continue;
                const double w = (exponent_ == 0.0 ? 1.0 : std::exp(exponent_ * std::log1p(-xk))) * omega_[k];
                acc += w * glm::dvec3(base_.at(f, sx, sy));
                wsum += w;
            }
    });
    if (wsum > 0.0) return Rgb(acc / wsum);
    const TexelRef t = texelOf(directionToFace(glm::vec3(r)), m);
    return base_.at(t.face, t.x, t.y);
}

CubeMap convolveExact(const CubeMap& base, double exponent, int outSize, double cutoff) {
    const ExactLobe lobe(base, exponent, cutoff);
    CubeMap out(outSize);
    parallelFor(0, cubeRows(outSize), [&](int row) {
        const auto [fo, y] = faceRowOf(row, outSize);
        const FaceFrame& fro = faceFrame(fo);
        for (int x = 0; x < outSize; ++x) {
            const double sc = 2.0 * (x + 0.5) / outSize - 1.0, tc = 2.0 * (y + 0.5) / outSize - 1.0;
            out.at(fo, x, y) = lobe.at(glm::dvec3(fro.axis) + sc * glm::dvec3(fro.u) + tc * glm::dvec3(fro.v));
        }
    });
    out.makeSeamless();
    return out;
}

}  // namespace mipgloss::detail
