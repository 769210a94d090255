// Lat-long -> cube: what the pieces of the conversion share, internal to them. latlong.cpp has
// the method (its top comment) and the dispatch; latlong_bright.cpp the bright split and the
// excess splat; latlong_scatter.cpp the scatter, whole and strip by strip; latlong_gather.cpp
// the gather (docs/latlong-conversion.md).
#pragma once

#include "latlong.h"

#include "mipgloss/ibl/parallel.h"
#include "mipgloss/io/latlong.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

namespace mipgloss::latlong_detail {

constexpr double kPi = std::numbers::pi;

inline float peakOf(const Rgb& p) { return std::max({p.x, p.y, p.z}); }

inline std::size_t pixelIndex(int i, int j, int width) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i);
}

// Range k of `count` items cut into `parts` contiguous ranges.
inline int partBegin(int count, int parts, int k) {
    return static_cast<int>(static_cast<long long>(count) * k / parts);
}

// Where the calling thread reports, as a fraction of the caller's [p0, p1].
struct ProgressSpan {
    const Progress& progress;
    float p0, p1;
    void report(double fraction) const {
        reportProgress(progress, "import", p0 + (p1 - p0) * static_cast<float>(std::clamp(fraction, 0.0, 1.0)));
    }
    ProgressSpan sub(double a, double b) const {
        return {progress, p0 + (p1 - p0) * static_cast<float>(a), p0 + (p1 - p0) * static_cast<float>(b)};
    }
};

// Runs body(k) for k in [0, count) in `groups` consecutive groups, each in parallel, reporting
// after each group from the calling thread (which is where Cancelled may be thrown).
inline void forGroups(int count, int groups, const std::function<void(int)>& body, const ProgressSpan& progress) {
    groups = std::max(1, std::min(groups, count));
    for (int g = 0; g < groups; ++g) {
        parallelFor(partBegin(count, groups, g), partBegin(count, groups, g + 1), body);
        progress.report(static_cast<double>(g + 1) / groups);
    }
}

// ---- Bright pixels (latlong_bright.cpp) ------------------------------------------------------

struct ExcessPixel {
    int i, j;
    Rgb excess;
};

struct BrightSplit {
    Rgb limit{std::numeric_limits<float>::infinity()};  // the quadratures read min(L, limit)
    std::vector<ExcessPixel> excess;                    // in image order (rows, then columns)
};

float thresholdOfMean(const glm::dvec3& mean);
std::size_t brightCap(std::size_t pixels);
float raisedToCap(float threshold, std::vector<float> peaks, std::size_t cap);
std::vector<Rgb> poleValues(const Rgb* row, int width, const Rgb& limit);
BrightSplit splitBright(const LatLongView& img);
void splatExcess(const std::vector<ExcessPixel>& pixels, int width, int height, CubeMap& cube,
                 const ProgressSpan& progress);

// ---- The interpolated image ------------------------------------------------------------------

// atan2 in single precision from a minimax polynomial for atan on [0, 1] (odd, degree 15; its
// error is 4e-8 rad, fitted by iteratively reweighted least squares), about five times faster
// than the library's atan2f: 2e-7 rad is 5e-4 of a pixel on a 16k-wide image.
// (Hot paths below are marked always_inline: GCC at -O2 otherwise leaves them as calls.)
[[gnu::always_inline]] inline float fastAtan2(float y, float x) {
    const float ax = std::fabs(x), ay = std::fabs(y);
    const float hi = std::max(ax, ay), lo = std::min(ax, ay);
    if (hi == 0.0f) return 0.0f;
    const float a = lo / hi, s = a * a;
    const float r = a * (0.999999335698f + s * (-0.333298610341f + s * (0.199465672870f + s * (-0.139086342310f +
                    s * (0.096422035470f + s * (-0.055912357854f + s * (0.021862952738f + s * -0.004054560347f)))))));
    const float octant = ay > ax ? static_cast<float>(0.5 * kPi) - r : r;
    const float half = x < 0.0f ? static_cast<float>(kPi) - octant : octant;
    return y < 0.0f ? -half : half;
}

// The image read bilinearly (wrapping in u), each tap clamped to the bright limit, with a row
// above and below holding the pole values (each the mean of the clamped row next to it), so
// interpolation in the first and last half rows runs to the pole's single value instead of
// clamping, which would smear row 0's variation in φ over the pole.
class Source {
public:
    struct Column { int i0, i1; float fx; };
    struct Row { int p0, p1; float fy; };  // rows of the padded image: 0 and H + 1 are the poles

    Source(const LatLongView& img, Rgb limit)
        : width(img.width), height(img.height), px_(img.pixels.data()), limit_(limit),
          top_(poleValues(px_, width, limit)), bottom_(poleValues(px_ + pixelIndex(0, height - 1, width), width, limit)) {}

    const int width, height;

    const Rgb* row(int p) const {
        if (p == 0) return top_.data();
        if (p == height + 1) return bottom_.data();
        return px_ + pixelIndex(0, p - 1, width);
    }
    [[gnu::always_inline]] Rgb tap(const Rgb* r, int i) const { return glm::min(r[i], limit_); }

    // Bilinear weights at u (wrapping) and at v (pole rows at v = 0 and 1).
    static Column columnAt(double u, int width) {
        const double x = u * width - 0.5;
        const double fl = std::floor(x);
        const int i0 = (static_cast<int>(fl) % width + width) % width;
        return {i0, (i0 + 1) % width, static_cast<float>(x - fl)};
    }
    static Row rowAtV(double v, int height) {
        const double y = std::clamp(v * height - 0.5, -0.5, height - 0.5);  // row 0's centre at 0
        if (y < 0.0) return {0, 1, static_cast<float>(2.0 * (y + 0.5))};    // top pole to row 0
        if (y > height - 1)                                                  // last row to bottom pole
            return {height, height + 1, static_cast<float>(2.0 * (y - (height - 1)))};
        const double fl = std::floor(y);
        const int p0 = static_cast<int>(fl) + 1;
        return {p0, std::min(p0 + 1, height), static_cast<float>(y - fl)};
    }

    [[gnu::always_inline]] Rgb value(const Column& c, const Rgb* r0, const Rgb* r1, float fy) const {
        const Rgb a = tap(r0, c.i0), b = tap(r0, c.i1), d = tap(r1, c.i0), e = tap(r1, c.i1);
        return (a * (1.0f - c.fx) + b * c.fx) * (1.0f - fy) + (d * (1.0f - c.fx) + e * c.fx) * fy;
    }

    // Bilinear read along a direction (need not be unit length). Single precision: a few
    // thousandths of a pixel on a 16k image. θ through atan2, which keeps its digits near the poles.
    [[gnu::always_inline]] Rgb sample(const glm::vec3& d) const {
        constexpr float kInvTwoPi = static_cast<float>(0.5 / kPi), kInvPi = static_cast<float>(1.0 / kPi);
        const float u = 0.5f + fastAtan2(d.z, d.x) * kInvTwoPi;
        const float v = fastAtan2(std::sqrt(d.x * d.x + d.z * d.z), d.y) * kInvPi;
        // Column: x = u·W − ½ in [−½, W − ½]; truncating x + 1 is floor(x) + 1.
        const float x = u * static_cast<float>(width) - 0.5f;
        const int xi = static_cast<int>(x + 1.0f) - 1;
        const Column c{xi < 0 ? width - 1 : xi, xi + 1 >= width ? 0 : xi + 1, x - static_cast<float>(xi)};
        // Row: y = v·H − ½ in [−½, H − ½], the pole rows beyond the first and last centres.
        const float y = v * static_cast<float>(height) - 0.5f;
        if (y < 0.0f) return value(c, row(0), row(1), std::min(1.0f, 2.0f * (y + 0.5f)));
        if (y >= static_cast<float>(height - 1))
            return value(c, row(height), row(height + 1), std::min(1.0f, 2.0f * (y - static_cast<float>(height - 1))));
        const int yi = static_cast<int>(y);
        return value(c, row(yi + 1), row(yi + 2), y - static_cast<float>(yi));
    }

private:
    const Rgb* px_;
    Rgb limit_;
    std::vector<Rgb> top_, bottom_;
};

// ---- Scatter (latlong_scatter.cpp) -----------------------------------------------------------

struct Strata {
    int ku, kv;  // per pixel, across and down
};

Strata strataFor(int width, int height, int n);
int bandRows(int height, int n);
void forBandsInTwoPhases(int lo, int hi, int rowsPerBand, const std::function<void(int j0, int j1)>& band,
                         const ProgressSpan& progress, int groups = 10);

// The texel that holds each stratum, from tables instead of a directionToFace per stratum. A
// stratum row (θ) and column (φ) give the direction (sin θ cos φ, cos θ, sin θ sin φ); with
// ĥ = (cos φ, 0, sin φ) and the face frames (faceFrame: a point (s, t) looks along
// axis + (2s − 1)·u + (2t − 1)·v):
//   - on a side face (axis, u horizontal, v = −y), s = ½(1 + (u·ĥ)/(axis·ĥ)) depends on φ alone
//     and t = ½(1 + v_y·cot θ/(axis·ĥ));
//   - on ±Y, s = ½(1 + |tan θ|·(u·ĥ)) and t = ½(1 + |tan θ|·(v·ĥ)).
// The face is directionToFace's: the same products sin θ·|cos φ|, sin θ·|sin φ| and |cos θ| are
// compared, ties to x, then y. The columns are stored as parallel arrays and a whole stratum row
// is looked up in one branch-free loop (texelsOfRow), which the compiler vectorises: both faces'
// indices are computed and one is selected, so the per-stratum cost is a few vector operations
// instead of a branchy call (the 8k → 512² scatter: 4 strata per pixel, 134 M lookups).
struct StrataColumns {
    std::vector<Source::Column> taps;  // bilinear taps of the stratum's centre
    std::vector<int> pixel;            // the image column the stratum lies in
    std::vector<float> major;          // |cos φ| or |sin φ|: sin θ times it is the side face's |ma|
    std::vector<float> polarTies;      // 1 where x wins ties with y (the polar test is >), else 0 (≥)
    std::vector<int> side;             // texel index of the side face's column: (face·n)·n + x
    std::vector<float> sideT;          // v_y/(axis·ĥ) on the side face
    std::array<std::vector<float>, 2> polarS, polarT;  // u·ĥ and v·ĥ on +Y and −Y

    StrataColumns(int width, int ku, int n) {
        const int nu = width * ku;
        const std::size_t size = static_cast<std::size_t>(nu);
        taps.resize(size);
        pixel.resize(size);
        major.resize(size);
        polarTies.resize(size);
        side.resize(size);
        sideT.resize(size);
        for (int k = 0; k < 2; ++k) {
            polarS[static_cast<std::size_t>(k)].resize(size);
            polarT[static_cast<std::size_t>(k)].resize(size);
        }
        for (int a = 0; a < nu; ++a) {
            const std::size_t i = static_cast<std::size_t>(a);
            const double u = (a + 0.5) / nu, phi = 2.0 * kPi * (u - 0.5);
            taps[i] = Source::columnAt(u, width);
            pixel[i] = a / ku;
            const float cosPhi = static_cast<float>(std::cos(phi)), sinPhi = static_cast<float>(std::sin(phi));
            const bool sideIsX = std::fabs(cosPhi) >= std::fabs(sinPhi);  // x wins ties with z
            major[i] = sideIsX ? std::fabs(cosPhi) : std::fabs(sinPhi);
            polarTies[i] = sideIsX ? 1.0f : 0.0f;  // x wins ties with y; y wins them with z
            const Face f = sideIsX ? (cosPhi >= 0.0f ? Face::PX : Face::NX) : (sinPhi >= 0.0f ? Face::PZ : Face::NZ);
            const glm::dvec3 h(cosPhi, 0.0, sinPhi);
            const FaceFrame& fr = faceFrame(f);
            const double across = glm::dot(glm::dvec3(fr.axis), h);
            const double s = 0.5 * (1.0 + glm::dot(glm::dvec3(fr.u), h) / across);
            side[i] = (static_cast<int>(f) * n) * n + std::clamp(static_cast<int>(s * n), 0, n - 1);
            sideT[i] = static_cast<float>(fr.v.y / across);
            for (int k = 0; k < 2; ++k) {
                const FaceFrame& p = faceFrame(k == 0 ? Face::PY : Face::NY);
                polarS[static_cast<std::size_t>(k)][i] = static_cast<float>(glm::dot(glm::dvec3(p.u), h));
                polarT[static_cast<std::size_t>(k)][i] = static_cast<float>(glm::dot(glm::dvec3(p.v), h));
            }
        }
    }

    std::size_t size() const { return taps.size(); }

    // A stratum row's constants for texelIndex: sin θ, |cos θ|, capped cot θ and |tan θ|, and
    // the pole's face.
    struct RowGeometry {
        float sn, polar, cot, tanAbs;
        std::size_t k;  // 0: +Y (cos θ > 0), 1: −Y
        int polarBase;
    };
    static RowGeometry rowGeometry(float sn, float ct, int n) {
        const std::size_t k = ct > 0.0f ? 0 : 1;
        return {sn, std::fabs(ct), std::clamp(ct / sn, -2.0f, 2.0f), std::min(sn / std::fabs(ct), 2.0f), k,
                (2 + static_cast<int>(k)) * n * n};  // faces 2 and 3 are +Y and −Y
    }

    // Index (face·n + y)·n + x of the texel holding stratum a of a row. A texel index q·n is
    // clamped to [0, n − 1] in float before it is truncated, which is floor for q·n ≥ 0, as
    // clamp(int(q·n)) was. |tan θ| is only used where the pole's face wins
    // (|cos θ| ≥ sin θ·|ma| ≥ sin θ/√2, so |tan θ| ≤ √2) and cot θ only where a side face wins
    // (|cot θ| < 1): both are capped at 2, which keeps the unused lane finite. Branch-free, so
    // that texelsOfRow vectorises; the same arithmetic serves single strata (texelOf).
    [[gnu::always_inline]] static int texelIndex(const RowGeometry& g, float ps, float pt, float mj, float ties, float st,
                                                 int sd, int n) {
        const float m = static_cast<float>(n), top = static_cast<float>(n - 1);
        const float sideMa = g.sn * mj;
        // polar > sideMa where x wins ties, polar ≥ sideMa elsewhere (bitwise: no branch).
        const bool polarWins = (g.polar > sideMa) | ((ties == 0.0f) & (g.polar == sideMa));
        const float px = std::min(std::max(0.5f * (1.0f + g.tanAbs * ps) * m, 0.0f), top);
        const float py = std::min(std::max(0.5f * (1.0f + g.tanAbs * pt) * m, 0.0f), top);
        const float sy = std::min(std::max(0.5f * (1.0f + st * g.cot) * m, 0.0f), top);
        const int polarIndex = g.polarBase + static_cast<int>(py) * n + static_cast<int>(px);
        const int sideIndex = sd + static_cast<int>(sy) * n;
        return polarWins ? polarIndex : sideIndex;
    }

    // The texels of every stratum of the row (sin θ, cos θ), into `out` (size() entries).
    void texelsOfRow(float sn, float ct, int n, int* out) const {
        const RowGeometry g = rowGeometry(sn, ct, n);
        const float* ps = polarS[g.k].data();
        const float* pt = polarT[g.k].data();
        const float* mj = major.data();
        const float* ties = polarTies.data();
        const float* st = sideT.data();
        const int* sd = side.data();
        const std::size_t count = size();
#pragma omp simd
        for (std::size_t a = 0; a < count; ++a) out[a] = texelIndex(g, ps[a], pt[a], mj[a], ties[a], st[a], sd[a], n);
    }
    int texelOf(std::size_t a, float sn, float ct, int n) const {
        const RowGeometry g = rowGeometry(sn, ct, n);
        return texelIndex(g, polarS[g.k][a], polarT[g.k][a], major[a], polarTies[a], sideT[a], side[a], n);
    }
};

// The scatter fed strip by strip (latlong_scatter.cpp, "Scatter, strip by strip", has the method
// and each member's comment). The private members are declared inline, as they were when
// defined in the class, so that GCC still inlines the hot ones (at, texel) in latlong_scatter.cpp.
class ScatterStream {
public:
    ScatterStream(int width, int height, int n);
    void addStrip(int y0, int y1, std::span<const Rgb> rows);
    CubeMap finish(const ProgressSpan& progress);

    const io_detail::LatLongStream::Stats& stats() const { return stats_; }

private:
    struct Candidate {
        int i, j;
        Rgb value;
    };
    struct Strip {
        int y0, y1;
        bool deferred;
        float limit;                       // T_k (immediate strips)
        std::vector<Candidate> candidates;  // immediate strips: pixels above T_k, in image order
    };

    inline void clampOrDefer(Strip& s, bool wasDeferred);
    inline void scatterReady();
    inline bool ready(int j) const;
    inline void keep(int j);
    inline void sumRows(int y0, int y1);
    inline bool anyAbove(int y0, int y1, float limit) const;
    inline std::size_t countAbove(int y0, int y1, float limit) const;
    inline std::vector<Candidate> above(int y0, int y1, float limit) const;
    inline float finalThreshold() const;
    template <class F> inline void forEachBright(float threshold, F f) const;
    inline std::vector<ExcessPixel> excessPixels(float threshold) const;
    inline const Rgb* padded(int p) const;
    inline float paddedLimit(int p) const;
    inline Rgb& texel(int index);

    struct StratumRow {
        double v, w;  // centre (v) and solid angle per unit Δφ
        float sn, ct;
    };
    inline StratumRow stratumRow(int b) const;
    inline void scatterRows(int j0, int j1, const ProgressSpan& progress, int groups);
    inline void band(int j0, int j1);

    using Lanes = float __attribute__((vector_size(16)));
    struct Scratch {
        std::vector<float> line0, line1;  // the interpolated rows, weighted (3 floats a pixel)
        std::vector<float> both;          // their sum
        std::vector<int> texels0, texels1;
        std::vector<Lanes> values;
    };
    inline void weightedLine(const StratumRow& sr, float* line) const;
    static inline Lanes at(const float* line, const Source::Column& c);
    inline void stratumRows(int b0, int b1, Scratch& s);
    inline void correctCandidates(float limit);
    inline void normalise();

    const int width_, height_, n_;
    const Strata st_;
    const int nv_;
    const bool one_;  // one stratum per pixel: its centre is the pixel's, its value the pixel's own
    const StrataColumns columns_;
    const int rowsPerBand_;
    CubeMap cube_;
    std::vector<float> weight_;
    std::vector<glm::dvec3> rowSum_;  // Σ over the row's pixels
    std::vector<double> rowWeight_;   // cos θ_j − cos θ_{j+1}
    std::vector<float> rowPeak_;      // the row's brightest channel (+Inf until sumRows)
    double weightSum_ = 0.0;          // Σ rowWeight·width, the image's weight
    glm::dvec3 partial_{0.0};         // Σ rowWeight·rowSum over the finite rows so far
    float clamp_ = 0.0f;              // 16 × partial_'s brightest channel / weightSum_: T's lower bound
    std::vector<float> limit_;        // each row's clamp: T_k, or T for deferred rows once known
    std::vector<const Rgb*> row_;     // the rows readable now
    std::vector<std::vector<Rgb>> kept_;
    std::vector<char> done_, deferred_;
    std::vector<Strip> strips_;
    std::vector<Rgb> poleTop_, poleBottom_;
    int next_ = 0;
    io_detail::LatLongStream::Stats stats_;
};

// ---- Gather (latlong_gather.cpp) -------------------------------------------------------------

double gatherReads(int width, int height, int n);
void gather(const Source& src, CubeMap& cube, const ProgressSpan& progress);

}  // namespace mipgloss::latlong_detail
