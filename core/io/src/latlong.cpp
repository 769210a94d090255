#include "latlong.h"

#include "mipgloss/ibl/parallel.h"
#include "mipgloss/io/latlong.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss {

namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Lat-long -> cube at the cost of about one pass (docs/latlong-conversion.md).
//
// A texel is the solid-angle weighted mean of the bilinearly interpolated image over its
// footprint. Two quadratures compute it, and the one that costs less for the two sizes is used
// (gathers()):
//  - Scatter (the image has more pixels than the cube has texels, up to about as many): every
//    pixel is cut into ku × kv strata, spaced at most half the narrowest texel (a corner texel,
//    (2/N)/3 rad) as before, and each stratum, interpolated at its centre, is added with its exact
//    solid angle Δφ·(cos θ0 − cos θ1) to the texel that holds its direction. One pass over the
//    image in row order; ku = kv = 1 once pixels are under half the narrowest texel.
//  - Gather (the cube is finer than the image): a texel is the mean of an Sx × Sy grid of
//    bilinear reads on its face plane, each weighted by the solid-angle density
//    dΩ/(dx dy) = (1 + x² + y²)^(−3/2) at its point, the grid spaced at most half a pixel in u
//    and in v and never coarser than 2 × 2.
// Bright pixels (suns) are split off first and their excess added with exact bookkeeping
// (splitBright, splatExcess).
//
// Determinism: every parallel loop runs over a fixed partition (row blocks, bands, face rows)
// that does not depend on the thread count, and partial sums are combined in a fixed order.
// Scatter and splat write straight into the cube: the image is cut into bands of rows, each
// spanning more θ than any texel, so a texel meets at most two neighbouring bands; the even
// bands run in parallel, then the odd ones, and every texel's sum is made in the same order.

float peakOf(const Rgb& p) { return std::max({p.x, p.y, p.z}); }

std::size_t pixelIndex(int i, int j, int width) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i);
}

// Range k of `count` items cut into `parts` contiguous ranges.
int partBegin(int count, int parts, int k) {
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
void forGroups(int count, int groups, const std::function<void(int)>& body, const ProgressSpan& progress) {
    groups = std::max(1, std::min(groups, count));
    for (int g = 0; g < groups; ++g) {
        parallelFor(partBegin(count, groups, g), partBegin(count, groups, g + 1), body);
        progress.report(static_cast<double>(g + 1) / groups);
    }
}

// ---- Bright pixels ---------------------------------------------------------------------------
//
// The few pixels far above the image's mean (a sun) carry much of its energy, and a quadrature
// moves a percent or two of one stratum's worth of it. So the image is split into min(L, T),
// converted by quadrature, and the sparse excess max(L − T, 0), whose energy is added exactly
// (splatExcess). T is 16 × the brightest channel's solid-angle weighted mean, raised if need be
// so that at most 2 % of pixels exceed it. No copy of the image is made: the quadratures clamp
// each tap they read.

struct ExcessPixel {
    int i, j;
    Rgb excess;
};

struct BrightSplit {
    Rgb limit{std::numeric_limits<float>::infinity()};  // the quadratures read min(L, limit)
    std::vector<ExcessPixel> excess;                    // in image order (rows, then columns)
};

// T from the image's weighted mean: 16 × its brightest channel (the stream's lower bounds T_k
// use the same rule on partial sums).
float thresholdOfMean(const glm::dvec3& mean) { return static_cast<float>(16.0 * std::max({mean.x, mean.y, mean.z})); }

// How many of `pixels` may exceed T: 2 % of them; 0 where no cap applies.
std::size_t brightCap(std::size_t pixels) {
    const std::size_t cap = pixels / 50;
    return cap < pixels ? cap : 0;
}

// T raised to the cap-th largest peak when at least cap of `peaks` (every peak above T) are.
float raisedToCap(float threshold, std::vector<float> peaks, std::size_t cap) {
    if (cap == 0 || peaks.size() < cap) return threshold;
    // The cap-th largest of all peaks is the (count − cap)-th smallest of those above.
    const auto nth = peaks.begin() + static_cast<std::ptrdiff_t>(peaks.size() - cap);
    std::nth_element(peaks.begin(), nth, peaks.end());
    return std::max(threshold, *nth);
}

// A pole's value: the mean of the row next to it clamped to `limit`, the same in every column.
std::vector<Rgb> poleValues(const Rgb* row, int width, const Rgb& limit) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < width; ++i) sum += glm::dvec3(glm::min(row[i], limit));
    return std::vector<Rgb>(static_cast<std::size_t>(width), Rgb(sum / static_cast<double>(width)));
}

BrightSplit splitBright(const LatLongView& img) {
    const int w = img.width, h = img.height;
    const int blocks = std::min(h, 64);
    auto rowsOf = [&](int k) { return std::pair{partBegin(h, blocks, k), partBegin(h, blocks, k + 1)}; };

    // The solid-angle weighted mean, summed per block and the blocks in order.
    std::vector<glm::dvec3> sums(static_cast<std::size_t>(blocks), glm::dvec3(0.0));
    std::vector<double> weights(static_cast<std::size_t>(blocks), 0.0);
    parallelFor(0, blocks, [&](int k) {
        const auto [j0, j1] = rowsOf(k);
        for (int j = j0; j < j1; ++j) {
            const double rw = std::cos(kPi * j / h) - std::cos(kPi * (j + 1) / h);
            glm::dvec3 row(0.0);
            for (int i = 0; i < w; ++i) row += glm::dvec3(img.pixels[pixelIndex(i, j, w)]);
            sums[static_cast<std::size_t>(k)] += rw * row;
            weights[static_cast<std::size_t>(k)] += rw * w;
        }
    });
    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    for (int k = 0; k < blocks; ++k) {
        sum += sums[static_cast<std::size_t>(k)];
        wsum += weights[static_cast<std::size_t>(k)];
    }
    float threshold = thresholdOfMean(sum / wsum);

    // Raised to the cap-th largest peak when more than cap pixels exceed it. Only the pixels above
    // 16 × the mean are collected for the selection, which is usually none.
    if (const std::size_t cap = brightCap(img.pixels.size()); cap > 0) {
        std::vector<std::vector<float>> above(static_cast<std::size_t>(blocks));
        parallelFor(0, blocks, [&](int k) {
            const auto [j0, j1] = rowsOf(k);
            for (std::size_t p = pixelIndex(0, j0, w); p < pixelIndex(0, j1, w); ++p)
                if (peakOf(img.pixels[p]) > threshold) above[static_cast<std::size_t>(k)].push_back(peakOf(img.pixels[p]));
        });
        std::vector<float> peaks;
        for (const auto& part : above) peaks.insert(peaks.end(), part.begin(), part.end());
        threshold = raisedToCap(threshold, std::move(peaks), cap);
    }
    BrightSplit out;
    if (!(threshold > 0.0f)) return out;
    out.limit = Rgb(threshold);
    std::vector<std::vector<ExcessPixel>> parts(static_cast<std::size_t>(blocks));
    parallelFor(0, blocks, [&](int k) {
        const auto [j0, j1] = rowsOf(k);
        for (int j = j0; j < j1; ++j)
            for (int i = 0; i < w; ++i) {
                const Rgb& p = img.pixels[pixelIndex(i, j, w)];
                if (peakOf(p) > threshold)
                    parts[static_cast<std::size_t>(k)].push_back({i, j, glm::max(p - out.limit, Rgb(0.0f))});
            }
    });
    for (const auto& part : parts) out.excess.insert(out.excess.end(), part.begin(), part.end());
    return out;
}

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

// ---- Scatter ---------------------------------------------------------------------------------

struct Strata {
    int ku, kv;  // per pixel, across and down
};

// Strata spaced at most half the narrowest texel (a corner texel, (2/N)/3 rad) in θ and in φ
// at the equator, so every texel receives several and a texel's boundary is resolved to a sixth
// of its width at a face centre.
Strata strataFor(int width, int height, int n) {
    const double texel = (2.0 / n) / 3.0;
    return {std::max(1, static_cast<int>(std::ceil(2.0 * (2.0 * kPi / width) / texel))),
            std::max(1, static_cast<int>(std::ceil(2.0 * (kPi / height) / texel)))};
}

// Image rows per band. A texel's θ-extent is at most its angular diameter, at most that of a face
// centre texel, whose diagonal is ≈ 2√2/N rad (the 1×1 face's, 1.91 rad, is below 3.2/1). A band
// spanning 3.2/N rad of θ is wider, so no texel meets two bands that are not neighbours.
int bandRows(int height, int n) {
    const double rows = std::ceil((3.2 / n) / (kPi / height));
    return std::clamp(static_cast<int>(rows), 1, height);
}

// Runs band(j0, j1) for every band of `rowsPerBand` image rows of [lo, hi): the even bands in
// parallel, then the odd ones (see the note at the top), in `groups` groups per phase, reporting
// after each from the calling thread.
void forBandsInTwoPhases(int lo, int hi, int rowsPerBand, const std::function<void(int j0, int j1)>& band,
                         const ProgressSpan& progress, int groups = 10) {
    const int bands = (hi - lo + rowsPerBand - 1) / rowsPerBand;
    for (int parity = 0; parity < 2; ++parity) {
        const int count = (bands - parity + 1) / 2;
        if (count <= 0) continue;
        forGroups(count, groups, [&](int k) {
            const int b = 2 * k + parity;
            band(lo + b * rowsPerBand, std::min(hi, lo + (b + 1) * rowsPerBand));
        }, progress.sub(0.5 * parity, 0.5 * (parity + 1)));
    }
}



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

// ---- Gather ----------------------------------------------------------------------------------

// Reads per axis: at least 2, so that a texel is a mean over its footprint even where it is far
// smaller than a pixel (one read at the centre missed a dark one-pixel line on city.exr by 99 %).
constexpr int kMinReadsPerAxis = 2, kMaxReadsPerAxis = 64;

// Reads per axis for the texel centred at face-plane point (x, y), spacing them at most half a
// pixel in u and in v. From the Jacobian of (φ, θ) along the face's u and v directions: with
// D = axis + x·u + y·v, ρ² = Dx² + Dz², dφ = (Dx dDz − Dz dDx)/ρ² and
// dθ = (Dy dρ − ρ dDy)/|D|², dρ = (Dx dDx + Dz dDz)/ρ. Near a pole a texel spans many pixel
// columns and gets up to kMaxReadsPerAxis; `coarse` says that the texel is wider than
// kMaxReadsPerAxis/2 pixels by arc length (sin θ·dφ and dθ), which the reads would undersample.
struct Reads {
    int x, y;
    bool coarse;
};
Reads readsPerAxis(const FaceFrame& fr, double x, double y, double texel, int width, int height) {
    const glm::dvec3 d = glm::dvec3(fr.axis) + x * glm::dvec3(fr.u) + y * glm::dvec3(fr.v);
    const double rho2 = d.x * d.x + d.z * d.z;
    if (rho2 < 1e-12) return {kMaxReadsPerAxis, kMaxReadsPerAxis, false};  // a pole at the centre
    const double rho = std::sqrt(rho2), len2 = rho2 + d.y * d.y;
    bool coarse = false;
    auto reads = [&](const glm::dvec3& e) {
        const double dphi = std::fabs((d.x * e.z - d.z * e.x) / rho2) * width / (2.0 * kPi);
        const double dtheta = std::fabs((d.y * (d.x * e.x + d.z * e.z) / rho - rho * e.y) / len2) * height / kPi;
        const double arc = texel * std::max(dphi * rho / std::sqrt(len2), dtheta);  // sin θ = ρ/|D|
        coarse = coarse || 2.0 * arc > kMaxReadsPerAxis;
        const double pixels = texel * std::max(dphi, dtheta);
        return std::clamp(static_cast<int>(std::ceil(2.0 * pixels - 1e-9)), kMinReadsPerAxis, kMaxReadsPerAxis);
    };
    const int sx = reads(glm::dvec3(fr.u)), sy = reads(glm::dvec3(fr.v));
    return {sx, sy, coarse};
}

// Total reads of a gather at face size n (the cost model's count), from every `stride`-th
// texel; infinite when some texel is too coarse for the reads (Reads::coarse).
double gatherReads(int width, int height, int n) {
    const double texel = 2.0 / n;
    const int stride = std::max(1, n / 64);
    double total = 0.0;
    // The four side faces are the same up to a turn about y; +Y and −Y mirror each other.
    for (Face f : {Face::PX, Face::PY}) {
        const double faces = f == Face::PX ? 4.0 : 2.0;
        for (int y = stride / 2; y < n; y += stride)
            for (int x = stride / 2; x < n; x += stride) {
                const Reads s = readsPerAxis(faceFrame(f), (x + 0.5) * texel - 1.0, (y + 0.5) * texel - 1.0,
                                             texel, width, height);
                if (s.coarse) return std::numeric_limits<double>::infinity();
                total += faces * stride * stride * s.x * s.y;
            }
    }
    return total;
}

void gather(const Source& src, CubeMap& cube, const ProgressSpan& progress) {
    const int n = cube.size();
    const double texel = 2.0 / n;
    forGroups(cubeRows(n), 20, [&](int row) {
        const auto [f, y] = faceRowOf(row, n);
        const FaceFrame& fr = faceFrame(f);
        for (int x = 0; x < n; ++x) {
            const double x0 = x * texel - 1.0, y0 = y * texel - 1.0;
            const Reads s = readsPerAxis(fr, x0 + 0.5 * texel, y0 + 0.5 * texel, texel, src.width, src.height);
            Rgb sum(0.0f);
            float wsum = 0.0f;
            for (int b = 0; b < s.y; ++b) {
                const float py = static_cast<float>(y0 + (b + 0.5) * texel / s.y);
                for (int a = 0; a < s.x; ++a) {
                    const float px = static_cast<float>(x0 + (a + 0.5) * texel / s.x);
                    const float r2 = 1.0f + px * px + py * py;
                    const float w = 1.0f / (r2 * std::sqrt(r2));  // dΩ / (dx dy)
                    sum += w * src.sample(fr.axis + px * fr.u + py * fr.v);
                    wsum += w;
                }
            }
            cube.at(f, x, y) = sum / wsum;
        }
    }, progress);
}

// A gather read costs about this many scatter strata: 41–49 ns against 6–7 ns of CPU time,
// measured on city.exr at N = 64, 256 and 512 on the 2-core development machine
// (docs/latlong-conversion.md).
constexpr double kReadCostInStrata = 7.0;

// ---- Excess splat ----------------------------------------------------------------------------

bool same(const TexelRef& a, const TexelRef& b) { return a.x == b.x && a.y == b.y && a.face == b.face; }

// texelOf(c, n) with floor done as a truncation, which is the same for the non-negative s·n and
// t·n that directionToFace gives (s, t in [0, 1]), and saves two library calls.
TexelRef texelFrom(const FaceCoord& c, int n) {
    const float m = static_cast<float>(n);
    return {c.face, std::min(static_cast<int>(c.s * m), n - 1), std::min(static_cast<int>(c.t * m), n - 1)};
}

// One excess pixel's energy, cut into cells and added to the texels under it (splatExcess has the
// method). Cell corners and centres lie on a lattice of half a cell, whose face coordinates are
// computed once per pixel.
class PixelSplat {
public:
    PixelSplat(CubeMap& cube, const std::vector<double>& cornerArea, int cu, int cv, double pixelPhi, double pixelTheta)
        : cube_(cube), n_(cube.size()), area_(cornerArea), cu_(cu), cv_(cv), gu_(2 * cu), gv_(2 * cv),
          pixelPhi_(pixelPhi), pixelTheta_(pixelTheta) {
        phi_.resize(static_cast<std::size_t>(gu_) + 1);
        theta_.resize(static_cast<std::size_t>(gv_) + 1);
        coords_.resize(phi_.size() * theta_.size());
    }

    void splat(const ExcessPixel& p) {
        p0_ = pixelPhi_ * p.i - kPi;
        t0_ = pixelTheta_ * p.j;
        dp_ = pixelPhi_ / gu_;
        dt_ = pixelTheta_ / gv_;
        excess_ = glm::dvec3(p.excess);
        havePhi_.assign(phi_.size(), 0);
        haveTheta_.assign(theta_.size(), 0);
        haveCoord_.assign(coords_.size(), 0);
        for (int b = 0; b < cv_; ++b)
            for (int a = 0; a < cu_; ++a) cell(2 * a, 2 * a + 2, 2 * b, 2 * b + 2, kCubeEdgeSplits);
        flush();
    }

private:
    // (cos, sin) of the lattice's azimuths and polar angles, and its points' face coordinates.
    const glm::dvec2& phi(int a) { return trig(phi_, havePhi_, a, p0_, dp_); }
    const glm::dvec2& theta(int b) { return trig(theta_, haveTheta_, b, t0_, dt_); }
    static const glm::dvec2& trig(std::vector<glm::dvec2>& table, std::vector<char>& have, int k, double origin, double step) {
        if (!have[static_cast<std::size_t>(k)]) {
            table[static_cast<std::size_t>(k)] = {std::cos(origin + k * step), std::sin(origin + k * step)};
            have[static_cast<std::size_t>(k)] = 1;
        }
        return table[static_cast<std::size_t>(k)];
    }
    const FaceCoord& coord(int a, int b) {
        const std::size_t k = static_cast<std::size_t>(b) * phi_.size() + static_cast<std::size_t>(a);
        if (!haveCoord_[k]) {
            const glm::dvec2 p = phi(a), t = theta(b);
            coords_[k] = directionToFace(glm::vec3(glm::dvec3(t.y * p.x, t.x, t.y * p.y)));
            haveCoord_[k] = 1;
        }
        return coords_[k];
    }

    void add(const TexelRef& t, double omega) {
        if (!same(t, run_)) {
            flush();
            run_ = t;
        }
        energy_ += omega * excess_;
    }
    void flush() {
        if (run_.x >= 0) {
            const std::size_t c = static_cast<std::size_t>(n_) + 1;
            auto a = [&](int i, int j) { return area_[static_cast<std::size_t>(j) * c + static_cast<std::size_t>(i)]; };
            const int x = run_.x, y = run_.y;
            cube_.at(run_.face, x, y) += Rgb(energy_ / (a(x, y) - a(x, y + 1) - a(x + 1, y) + a(x + 1, y + 1)));
        }
        run_ = {Face::PX, -1, -1};
        energy_ = glm::dvec3(0.0);
    }

    // Face coordinates at lattice position (a, b), cached on the lattice itself.
    FaceCoord coordAt(double a, double b) {
        if (a == std::floor(a) && b == std::floor(b)) return coord(static_cast<int>(a), static_cast<int>(b));
        return directionToFace(glm::vec3(sphericalDirection(t0_ + b * dt_, p0_ + a * dp_)));
    }
    TexelRef texelAt(double a, double b) { return texelFrom(coordAt(a, b), n_); }
    double solidAngle(double a0, double a1, double b0, double b1) {
        auto cosTheta = [&](double b) { return b == std::floor(b) ? theta(static_cast<int>(b)).x : std::cos(t0_ + b * dt_); };
        return dp_ * (a1 - a0) * (cosTheta(b0) - cosTheta(b1));
    }

    // The cell between lattice positions a0..a1 (azimuth) and b0..b1 (polar angle), which may
    // be halved `splits` more times.
    void cell(double a0, double a1, double b0, double b1, int splits) {
        const double am = 0.5 * (a0 + a1), bm = 0.5 * (b0 + b1);
        const TexelRef c = texelAt(am, bm);
        const double omega = solidAngle(a0, a1, b0, b1);
        if (same(texelAt(a0, b0), c) && same(texelAt(a1, b0), c) && same(texelAt(a0, b1), c) && same(texelAt(a1, b1), c)) {
            add(c, omega);
        } else if (!straddling(a0, a1, b0, b1, omega)) {
            if (splits > 0)
                quarters(a0, a1, b0, b1, splits);
            else
                add(c, omega);
        }
    }
    void quarters(double a0, double a1, double b0, double b1, int splits) {
        const double am = 0.5 * (a0 + a1), bm = 0.5 * (b0 + b1);
        cell(a0, am, b0, bm, splits - 1);
        cell(am, a1, b0, bm, splits - 1);
        cell(a0, am, bm, b1, splits - 1);
        cell(am, a1, bm, b1, splits - 1);
    }

    // A cell across texel edges, its corners on one face. Across a cell no wider than the
    // narrowest texel the face coordinates (S, T) = N·(s, t) are an affine function of the cell's
    // own (α, β) ∈ [0, 1]² (fitted to its four corners), so the part of the cell in texel (i, j)
    // is the polygon where i ≤ S < i + 1 and j ≤ T < j + 1: the unit square clipped by up to four
    // lines. Its share of the cell is its area weighted by dΩ = sin θ dθ dφ. False when the
    // corners lie on different faces (a cube edge) or the cell meets more than 9 texels.
    bool straddling(double a0, double a1, double b0, double b1, double omega) {
        const std::array<FaceCoord, 4> c{coordAt(a0, b0), coordAt(a1, b0), coordAt(a0, b1), coordAt(a1, b1)};
        for (const FaceCoord& k : c)
            if (k.face != c[0].face) return false;
        const double m = n_;
        // S(α, β) = s0 + sa·α + sb·β, and T likewise, fitted to the four corners (least squares).
        auto fit = [&](auto get) {
            const double v00 = get(c[0]) * m, v10 = get(c[1]) * m, v01 = get(c[2]) * m, v11 = get(c[3]) * m;
            const double da = 0.5 * ((v10 - v00) + (v11 - v01)), db = 0.5 * ((v01 - v00) + (v11 - v10));
            return glm::dvec3(0.25 * (v00 + v10 + v01 + v11) - 0.5 * (da + db), da, db);
        };
        const glm::dvec3 fs = fit([](const FaceCoord& k) { return static_cast<double>(k.s); });
        const glm::dvec3 ft = fit([](const FaceCoord& k) { return static_cast<double>(k.t); });
        auto range = [&](const glm::dvec3& f) {
            const double lo = f.x + std::min(0.0, f.y) + std::min(0.0, f.z), hi = f.x + std::max(0.0, f.y) + std::max(0.0, f.z);
            return glm::ivec2(std::clamp(static_cast<int>(std::floor(lo)), 0, n_ - 1), std::clamp(static_cast<int>(std::floor(hi)), 0, n_ - 1));
        };
        const glm::ivec2 is = range(fs), it = range(ft);
        if ((is.y - is.x + 1) * (it.y - it.x + 1) > 9) return false;
        // dΩ = sin θ dθ dφ, with sin θ linear in β across the cell: a polygon's weight is its area
        // in (α, β) times sin θ at its centroid.
        const double sinA = std::sin(t0_ + b0 * dt_), sinB = std::sin(t0_ + b1 * dt_);
        std::array<std::pair<TexelRef, double>, 9> parts;
        std::size_t count = 0;
        double total = 0.0;
        for (int j = it.x; j <= it.y; ++j)
            for (int i = is.x; i <= is.y; ++i) {
                Polygon poly{{{{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}}, 4};
                // The face's own edges (0 and N) are not cuts.
                if (i > 0) poly = clip(poly, fs, static_cast<double>(i), 1.0);
                if (i < n_ - 1) poly = clip(poly, fs, static_cast<double>(i + 1), -1.0);
                if (j > 0) poly = clip(poly, ft, static_cast<double>(j), 1.0);
                if (j < n_ - 1) poly = clip(poly, ft, static_cast<double>(j + 1), -1.0);
                double area = 0.0, beta = 0.0;  // 2 × area and 6 × area × centroid β (shoelace)
                for (std::size_t k = 0; k < poly.count; ++k) {
                    const glm::dvec2 &u = poly.v[k], &v = poly.v[(k + 1) % poly.count];
                    const double cross = u.x * v.y - v.x * u.y;
                    area += cross;
                    beta += (u.y + v.y) * cross;
                }
                if (!(std::fabs(area) > 0.0)) continue;
                const double weight = std::fabs(0.5 * area) * (sinA + (sinB - sinA) * beta / (3.0 * area));
                parts[count++] = {TexelRef{c[0].face, i, j}, weight};
                total += weight;
            }
        if (!(total > 0.0)) return false;
        for (std::size_t k = 0; k < count; ++k) add(parts[k].first, omega * parts[k].second / total);
        return true;
    }

    // A convex polygon in (α, β), at most 8 vertices (a square cut by four lines).
    struct Polygon {
        std::array<glm::dvec2, 8> v;
        std::size_t count;
    };
    // The part of `poly` where sign·(f·(1, α, β) − k) ≥ 0 (Sutherland–Hodgman, one plane).
    static Polygon clip(const Polygon& poly, const glm::dvec3& f, double k, double sign) {
        Polygon out{{}, 0};
        auto d = [&](const glm::dvec2& q) { return sign * (f.x + f.y * q.x + f.z * q.y - k); };
        for (std::size_t i = 0; i < poly.count; ++i) {
            const glm::dvec2 &p = poly.v[i], &q = poly.v[(i + 1) % poly.count];
            const double dp = d(p), dq = d(q);
            if (dp >= 0.0 && out.count < 8) out.v[out.count++] = p;
            if ((dp >= 0.0) != (dq >= 0.0) && out.count < 8) out.v[out.count++] = p + (dp / (dp - dq)) * (q - p);
        }
        return out;
    }

    static constexpr int kCubeEdgeSplits = 4;  // halvings of a cell across a cube edge
    CubeMap& cube_;
    int n_;
    const std::vector<double>& area_;
    int cu_, cv_, gu_, gv_;
    double pixelPhi_, pixelTheta_;
    double p0_ = 0.0, t0_ = 0.0, dp_ = 0.0, dt_ = 0.0;
    glm::dvec3 excess_{0.0};
    std::vector<glm::dvec2> phi_, theta_;
    std::vector<FaceCoord> coords_;
    std::vector<char> havePhi_, haveTheta_, haveCoord_;
    TexelRef run_{Face::PX, -1, -1};
    glm::dvec3 energy_{0.0};
};

// The excess of the bright pixels (BrightSplit), added to the cube with exact bookkeeping. Each
// excess pixel is cut into cells no wider than the narrowest texel, (2/N)/3. A cell whose four
// corners and centre lie in one texel goes to it whole, with its exact solid angle
// Δφ·(cos θ0 − cos θ1); a cell across texel edges is shared between the texels it meets by the
// areas of its pieces (PixelSplat::straddling), and one across a cube edge is halved up to four
// times, the smallest pieces going to the texel at their centre. The pieces' solid angles sum
// to the pixel's, so the excess energy is kept exactly, and a one-pixel sun is shared between
// texels to within about 0.1 % of its energy. (The uniform sub-strata of 1/4 of the narrowest
// texel used before shared it only to a third of a pixel at N = 64: 18 % of the sun's texel on
// sunrise.exr.)
void splatExcess(const std::vector<ExcessPixel>& pixels, int width, int height, CubeMap& cube,
                 const ProgressSpan& progress) {
    if (pixels.empty()) {
        progress.report(1.0);
        return;
    }
    const int n = cube.size();
    // Texel solid angles from the signed areas A(x, y) at the (n + 1)² texel corners
    // (texelSolidAngle's own arithmetic, so Ω is the same to the last bit).
    const double inv = 2.0 / n;
    const std::size_t corners = static_cast<std::size_t>(n) + 1;
    std::vector<double> area(corners * corners);
    parallelFor(0, n + 1, [&](int j) {
        for (int i = 0; i <= n; ++i) {
            const double x = i * inv - 1.0, y = j * inv - 1.0;
            area[static_cast<std::size_t>(j) * corners + static_cast<std::size_t>(i)] =
                std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
        }
    });
    const double narrow = (2.0 / n) / 3.0;
    const double pixelPhi = 2.0 * kPi / width, pixelTheta = kPi / height;
    const int cu = std::max(1, static_cast<int>(std::ceil(pixelPhi / narrow)));
    const int cv = std::max(1, static_cast<int>(std::ceil(pixelTheta / narrow)));
    forBandsInTwoPhases(0, height, bandRows(height, n), [&](int j0, int j1) {
        auto byRow = [](const ExcessPixel& p, int j) { return p.j < j; };
        const auto first = std::lower_bound(pixels.begin(), pixels.end(), j0, byRow);
        const auto last = std::lower_bound(first, pixels.end(), j1, byRow);
        PixelSplat splat(cube, area, cu, cv, pixelPhi, pixelTheta);
        for (auto p = first; p != last; ++p) splat.splat(*p);
    }, progress);
}

// ---- Scatter, strip by strip ------------------------------------------------------------------
//
// The scatter reads the image once in row order, so it runs as the strips are decoded (the
// decoder hands each strip over while it reads the next: import.cpp). What stands in the way is
// the bright split: T comes from the whole image's weighted mean, and every tap is clamped to it.
// Strip k is therefore clamped to a lower bound of T known when it arrives,
//     T_k = 16 × (the weighted sums of the finite rows so far) / (the whole image's weight),
// which cannot exceed T: the sums only grow (non-negative terms, rounding is monotone) and the cap
// only raises T. The pixels of the strip above T_k are kept (candidates), and once T is known the
// difference D = min(L, T) − min(L, T_k) of each is scattered through the same strata (the
// quadrature is linear in the pixel values), so the cube is the quadrature of min(L, T) exactly as
// if T had been known from the start; only rounding differs. Nothing is subtracted, so a sun far
// above T_k costs no precision. A strip with more than 1/64 of its pixels above T_k (near the top
// pole the sums are still small), a strip holding +Inf (replaced by the image's largest finite
// value only at the end) and the last strip are deferred: kept whole. A deferred finite strip is
// looked at again after every later one and clamped as soon as few enough of its pixels exceed
// the grown bound; what is still deferred at the end is scattered with T. The pole values (the
// means of the first and last rows clamped to T) and the two rows that read them wait for the end.
// What is held besides the cube: the deferred strips, two rows at each end of the other strips,
// the candidates (at most 1/64 of those strips) and per-row sums.
//
// Determinism: the strips are fixed by the caller (import: the decoder's strips of 256 rows;
// latLongToCube: the same), the steps run one after another, each over bands in two phases, the
// deferred rows at the end in row order and the candidates in image order after them. Nothing
// depends on the number of threads.
class ScatterStream {
public:
    ScatterStream(int width, int height, int n)
        : width_(width), height_(height), n_(n), st_(strataFor(width, height, n)), nv_(height * st_.kv),
          one_(st_.ku == 1 && st_.kv == 1), columns_(width, st_.ku, n), rowsPerBand_(bandRows(height, n)), cube_(n),
          weight_(6 * static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0.0f),
          rowSum_(static_cast<std::size_t>(height), glm::dvec3(0.0)), rowWeight_(static_cast<std::size_t>(height)),
          rowPeak_(static_cast<std::size_t>(height), std::numeric_limits<float>::infinity()),
          limit_(static_cast<std::size_t>(height), std::numeric_limits<float>::infinity()),
          row_(static_cast<std::size_t>(height), nullptr), kept_(static_cast<std::size_t>(height)),
          done_(static_cast<std::size_t>(height), 0), deferred_(static_cast<std::size_t>(height), 0) {
        for (int j = 0; j < height; ++j) {
            rowWeight_[static_cast<std::size_t>(j)] = std::cos(kPi * j / height) - std::cos(kPi * (j + 1) / height);
            weightSum_ += rowWeight_[static_cast<std::size_t>(j)] * width;
        }
    }

    // Rows [y0, y1), the next in order, sanitised except for +Inf (hasInfinity says whether
    // there is any). `rows` need only live for the call: what is needed later is copied.
    void addStrip(int y0, int y1, std::span<const Rgb> rows, bool hasInfinity) {
        if (y0 != next_ || y1 <= y0 || y1 > height_ || rows.size() != static_cast<std::size_t>(y1 - y0) * width_)
            throw std::invalid_argument("lat-long strip rows " + std::to_string(y0) + ".." + std::to_string(y1) +
                                        " out of order or of the wrong size");
        next_ = y1;
        for (int j = y0; j < y1; ++j) row_[static_cast<std::size_t>(j)] = rows.data() + static_cast<std::size_t>(j - y0) * width_;
        if (!hasInfinity) {
            sumRows(y0, y1);
            for (int j = y0; j < y1; ++j) partial_ += rowWeight_[static_cast<std::size_t>(j)] * rowSum_[static_cast<std::size_t>(j)];
            clamp_ = thresholdOfMean(partial_ / weightSum_);
        }
        strips_.push_back({y0, y1, true, hasInfinity, std::numeric_limits<float>::infinity(), {}});
        ++stats_.strips;
        // The last strip waits for the end whatever it holds: nothing is decoded after it.
        if (hasInfinity || y1 == height_) {
            ++stats_.deferred;
            for (int j = y0; j < y1; ++j) {
                deferred_[static_cast<std::size_t>(j)] = 1;
                keep(j);
            }
        } else {
            clampOrDefer(strips_.back(), false);
        }
        // A strip deferred earlier is looked at again with the clamp as it is now (near the top
        // pole the first strips' sums are small, so they wait for a few more).
        for (Strip& s : strips_)
            if (s.deferred && !s.infinity && s.y1 <= y0) clampOrDefer(s, true);
        scatterReady();
        for (int j = 0; j < y1; ++j)
            if (kept_[static_cast<std::size_t>(j)].empty()) row_[static_cast<std::size_t>(j)] = nullptr;
    }

    // After the last strip: T, the deferred rows, the candidates' differences, the normalising
    // and the excess. +Inf in the deferred strips becomes `maxFinite`.
    CubeMap finish(float maxFinite, const ProgressSpan& progress) {
        if (next_ != height_) throw std::invalid_argument("lat-long image incomplete: " + std::to_string(next_) + " of " +
                                                          std::to_string(height_) + " rows");
        for (const Strip& s : strips_) {
            if (!s.infinity) continue;
            for (int j = s.y0; j < s.y1; ++j) io_detail::replaceInfinities(kept_[static_cast<std::size_t>(j)], maxFinite);
            sumRows(s.y0, s.y1);
        }
        const float threshold = finalThreshold();
        const float limit = threshold > 0.0f ? threshold : std::numeric_limits<float>::infinity();
        for (const Strip& s : strips_)
            if (s.deferred)
                for (int j = s.y0; j < s.y1; ++j) limit_[static_cast<std::size_t>(j)] = limit;
        // The poles: the first and last rows clamped to T (the rows themselves may be clamped
        // lower; their candidates' differences are corrected like any other).
        poleTop_ = poleValues(row_.front(), width_, Rgb(limit));
        poleBottom_ = poleValues(row_.back(), width_, Rgb(limit));
        progress.report(0.1);
        // The rows not scattered yet, in runs, in row order.
        for (int j = 0; j < height_;) {
            if (done_[static_cast<std::size_t>(j)]) {
                ++j;
                continue;
            }
            int end = j;
            while (end < height_ && !done_[static_cast<std::size_t>(end)]) ++end;
            scatterRows(j, end, progress.sub(0.1 + 0.7 * j / height_, 0.1 + 0.7 * end / height_), 10);
            j = end;
        }
        correctCandidates(limit);
        normalise();
        progress.report(0.85);
        if (threshold > 0.0f) {
            const std::vector<ExcessPixel> excess = excessPixels(threshold);
            stats_.excess = excess.size();
            splatExcess(excess, width_, height_, cube_, progress.sub(0.85, 1.0));
        }
        progress.report(1.0);
        return std::move(cube_);
    }

    const io_detail::LatLongStream::Stats& stats() const { return stats_; }

private:
    struct Candidate {
        int i, j;
        Rgb value;
    };
    struct Strip {
        int y0, y1;
        bool deferred, infinity;
        float limit;                       // T_k (immediate strips)
        std::vector<Candidate> candidates;  // immediate strips: pixels above T_k, in image order
    };

    // Clamps strip s to the present lower bound of T (clamp_), keeping its pixels above it as
    // candidates, unless more than 1/64 of them are: then it is deferred (kept whole) or stays so.
    void clampOrDefer(Strip& s, bool wasDeferred) {
        if (countAbove(s.y0, s.y1, clamp_) > static_cast<std::size_t>(s.y1 - s.y0) * width_ / 64) {
            if (!wasDeferred) {
                ++stats_.deferred;
                for (int j = s.y0; j < s.y1; ++j) {
                    deferred_[static_cast<std::size_t>(j)] = 1;
                    keep(j);
                }
            }
            return;
        }
        if (wasDeferred) {
            --stats_.deferred;
            ++stats_.promoted;
        }
        s.deferred = false;
        s.limit = clamp_;
        s.candidates = above(s.y0, s.y1, clamp_);
        stats_.candidates += s.candidates.size();
        for (int j = s.y0; j < s.y1; ++j) {
            limit_[static_cast<std::size_t>(j)] = clamp_;
            deferred_[static_cast<std::size_t>(j)] = 0;
        }
    }

    // Scatters every row not done whose strata read only rows clamped already (j − 1 .. j + 1;
    // rows 0 and height − 1, which read a pole, wait for the end), in runs, in row order; then
    // keeps of the clamped strips only the two rows at each end, which rows left may read.
    void scatterReady() {
        static const Progress silent;  // in the background: only the caller's thread reports
        for (int j = 1; j < next_ - 1;) {
            if (done_[static_cast<std::size_t>(j)] || !ready(j)) {
                ++j;
                continue;
            }
            int end = j;
            while (end < next_ - 1 && !done_[static_cast<std::size_t>(end)] && ready(end)) ++end;
            scatterRows(j, end, {silent, 0.0f, 1.0f}, 1);
            j = end;
        }
        for (const Strip& s : strips_) {
            if (s.deferred) continue;
            for (int j = s.y0 + 2; j < s.y1 - 2; ++j) {
                auto& k = kept_[static_cast<std::size_t>(j)];
                if (!k.empty() && done_[static_cast<std::size_t>(j - 1)] && done_[static_cast<std::size_t>(j)] &&
                    done_[static_cast<std::size_t>(j + 1)]) {
                    std::vector<Rgb>().swap(k);
                    row_[static_cast<std::size_t>(j)] = nullptr;
                }
            }
            for (int j : {s.y0, s.y0 + 1, s.y1 - 2, s.y1 - 1})
                if (j >= s.y0 && j < s.y1 && row_[static_cast<std::size_t>(j)]) keep(j);
        }
    }

    bool ready(int j) const {
        for (int r = j - 1; r <= j + 1; ++r)
            if (r < 0 || r >= next_ || deferred_[static_cast<std::size_t>(r)] || !row_[static_cast<std::size_t>(r)])
                return false;
        return true;
    }
    void keep(int j) {
        auto& k = kept_[static_cast<std::size_t>(j)];
        if (k.empty()) k.assign(row_[static_cast<std::size_t>(j)], row_[static_cast<std::size_t>(j)] + width_);
        row_[static_cast<std::size_t>(j)] = k.data();
    }

    // Each row's sum, and its brightest channel (rowPeak_), which lets countAbove and above skip
    // the rows with nothing above the bound: on a sky with one sun, almost every row.
    void sumRows(int y0, int y1) {
        parallelFor(y0, y1, [&](int j) {
            const Rgb* r = row_[static_cast<std::size_t>(j)];
            glm::dvec3 sum(0.0);
            float peak = 0.0f;
            for (int i = 0; i < width_; ++i) {
                sum += glm::dvec3(r[i]);
                peak = std::max(peak, peakOf(r[i]));
            }
            rowSum_[static_cast<std::size_t>(j)] = sum;
            rowPeak_[static_cast<std::size_t>(j)] = peak;
        });
    }
    bool anyAbove(int y0, int y1, float limit) const {
        for (int j = y0; j < y1; ++j)
            if (!(rowPeak_[static_cast<std::size_t>(j)] <= limit)) return true;
        return false;
    }

    // How many pixels of rows [y0, y1) have their brightest channel above `limit` (branch-free).
    std::size_t countAbove(int y0, int y1, float limit) const {
        if (!anyAbove(y0, y1, limit)) return 0;
        std::vector<std::size_t> counts(static_cast<std::size_t>(y1 - y0), 0);
        parallelFor(y0, y1, [&](int j) {
            if (rowPeak_[static_cast<std::size_t>(j)] <= limit) return;
            const Rgb* r = row_[static_cast<std::size_t>(j)];
            std::size_t n = 0;
            for (int i = 0; i < width_; ++i) n += peakOf(r[i]) > limit ? 1u : 0u;
            counts[static_cast<std::size_t>(j - y0)] = n;
        });
        std::size_t total = 0;
        for (std::size_t n : counts) total += n;
        return total;
    }

    // The pixels of rows [y0, y1) whose brightest channel exceeds `limit`, in image order.
    std::vector<Candidate> above(int y0, int y1, float limit) const {
        if (!anyAbove(y0, y1, limit)) return {};
        std::vector<std::vector<Candidate>> parts(static_cast<std::size_t>(y1 - y0));
        parallelFor(y0, y1, [&](int j) {
            if (rowPeak_[static_cast<std::size_t>(j)] <= limit) return;
            const Rgb* r = row_[static_cast<std::size_t>(j)];
            auto& part = parts[static_cast<std::size_t>(j - y0)];
            for (int i = 0; i < width_; ++i)
                if (peakOf(r[i]) > limit) part.push_back({i, j, r[i]});
        });
        std::vector<Candidate> out;
        for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
        return out;
    }

    // T: 16 × the brightest channel's weighted mean, raised to the cap-th largest peak when more
    // than cap = 2 % of the pixels exceed it. Every pixel above 16 × the mean is a candidate or
    // in a deferred strip, since 16 × the mean is at least every T_k.
    float finalThreshold() const {
        glm::dvec3 sum(0.0);
        for (int j = 0; j < height_; ++j) sum += rowWeight_[static_cast<std::size_t>(j)] * rowSum_[static_cast<std::size_t>(j)];
        const float threshold = thresholdOfMean(sum / weightSum_);
        const std::size_t cap = brightCap(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
        if (cap == 0) return threshold;
        std::vector<float> peaks;
        forEachBright(threshold, [&](int, int, const Rgb& p) { peaks.push_back(peakOf(p)); });
        return raisedToCap(threshold, std::move(peaks), cap);
    }
    // Calls f(i, j, value) for every pixel whose peak exceeds `threshold` (at least every T_k), in
    // image order.
    template <class F> void forEachBright(float threshold, F f) const {
        for (const Strip& s : strips_) {
            if (s.deferred) {
                for (int j = s.y0; j < s.y1; ++j) {
                    const Rgb* r = kept_[static_cast<std::size_t>(j)].data();
                    for (int i = 0; i < width_; ++i)
                        if (peakOf(r[i]) > threshold) f(i, j, r[i]);
                }
            } else {
                for (const Candidate& c : s.candidates)
                    if (peakOf(c.value) > threshold) f(c.i, c.j, c.value);
            }
        }
    }
    std::vector<ExcessPixel> excessPixels(float threshold) const {
        std::vector<ExcessPixel> out;
        forEachBright(threshold, [&](int i, int j, const Rgb& p) { out.push_back({i, j, glm::max(p - Rgb(threshold), Rgb(0.0f))}); });
        return out;
    }

    // Padded row p (0: the top pole, height + 1: the bottom pole) and its clamp.
    const Rgb* padded(int p) const {
        if (p == 0) return poleTop_.data();
        if (p == height_ + 1) return poleBottom_.data();
        return row_[static_cast<std::size_t>(p - 1)];
    }
    float paddedLimit(int p) const {
        return p == 0 || p == height_ + 1 ? std::numeric_limits<float>::infinity() : limit_[static_cast<std::size_t>(p - 1)];
    }

    Rgb& texel(int index) {
        return cube_.at(kAllFaces[static_cast<std::size_t>(index / (n_ * n_))], index % n_, (index / n_) % n_);
    }
    struct StratumRow {
        double v, w;  // centre (v) and solid angle per unit Δφ
        float sn, ct;
    };
    // Stratum row b: its centre, and its strata's solid angle per unit Δφ, cos θ0 − cos θ1. Every
    // stratum row has ku strata per pixel (fewer towards the poles was measured and not kept:
    // docs/latlong-conversion.md, "Not done here").
    StratumRow stratumRow(int b) const {
        const double v = (b + 0.5) / nv_;
        return {v, std::cos(kPi * b / nv_) - std::cos(kPi * (b + 1) / nv_), static_cast<float>(std::sin(kPi * v)),
                static_cast<float>(std::cos(kPi * v))};
    }

    // Every stratum of image rows [j0, j1) added with its solid angle to the texel that holds it:
    // bands in two phases, `groups` groups per phase (1 in the background).
    void scatterRows(int j0, int j1, const ProgressSpan& progress, int groups) {
        forBandsInTwoPhases(j0, j1, rowsPerBand_, [&](int b0, int b1) { band(b0, b1); }, progress, groups);
        for (int j = j0; j < j1; ++j) done_[static_cast<std::size_t>(j)] = 1;
    }
    // The strata of image rows [j0, j1), a stratum row at a time, or two at a time when there are
    // several per image row (kv ≥ 2): the two rows' texels (texelsOfRow, vectorised) agree for
    // almost every column (a texel spans several stratum rows), so their values, each weighted
    // by its row's solid angle, are summed in one pass of runs wherever they agree, and added
    // one by one where they do not. Stratum values go into a padded four-float array (the
    // image rows interpolated to the stratum row's θ once, vectorised, then read across at each
    // stratum's u), so a run costs one vector add per stratum before the cube is touched.
    void band(int j0, int j1) {
        const std::size_t count = columns_.size(), w3 = 3 * static_cast<std::size_t>(width_);
        Scratch scratch{std::vector<float>(one_ ? 0 : w3), std::vector<float>(one_ ? 0 : w3), {},
                        std::vector<int>(count), std::vector<int>(count), std::vector<Lanes>(count)};
        for (int b = j0 * st_.kv; b < j1 * st_.kv;) {
            if (!one_ && b + 1 < j1 * st_.kv) {
                stratumRows(b, b + 1, scratch);
                b += 2;
            } else {
                stratumRows(b, -1, scratch);
                b += 1;
            }
        }
    }

    using Lanes = float __attribute__((vector_size(16)));
    struct Scratch {
        std::vector<float> line0, line1;  // the interpolated rows, weighted (3 floats a pixel)
        std::vector<float> both;          // their sum
        std::vector<int> texels0, texels1;
        std::vector<Lanes> values;
    };

    // Stratum row b's values into `line`, each times its row's weight w (not one_).
    void weightedLine(const StratumRow& sr, float* line) const {
        const Source::Row r = Source::rowAtV(sr.v, height_);
        const float* r0 = &padded(r.p0)->x;
        const float* r1 = &padded(r.p1)->x;
        const float l0 = paddedLimit(r.p0), l1 = paddedLimit(r.p1);
        const float w = static_cast<float>(sr.w), fy = r.fy * w, gy = (1.0f - r.fy) * w;
        const std::size_t w3 = 3 * static_cast<std::size_t>(width_);
#pragma omp simd
        for (std::size_t k = 0; k < w3; ++k) line[k] = std::min(r0[k], l0) * gy + std::min(r1[k], l1) * fy;
    }
    static Lanes at(const float* line, const Source::Column& c) {
        const float* p = line + 3 * static_cast<std::size_t>(c.i0);
        const float* q = line + 3 * static_cast<std::size_t>(c.i1);
        const float gx = 1.0f - c.fx;
        return Lanes{p[0] * gx + q[0] * c.fx, p[1] * gx + q[1] * c.fx, p[2] * gx + q[2] * c.fx, 0.0f};
    }

    // Stratum row b0, with b1 (≥ 0) beside it.
    void stratumRows(int b0, int b1, Scratch& s) {
        const std::size_t count = columns_.size();
        const StratumRow sr0 = stratumRow(b0), sr1 = stratumRow(b1 >= 0 ? b1 : b0);
        const double w = b1 >= 0 ? sr0.w + sr1.w : sr0.w;  // a column of strata where both agree
        columns_.texelsOfRow(sr0.sn, sr0.ct, n_, s.texels0.data());
        if (b1 >= 0) columns_.texelsOfRow(sr1.sn, sr1.ct, n_, s.texels1.data());
        const int* t0 = s.texels0.data();
        const int* t1 = b1 >= 0 ? s.texels1.data() : t0;
        const Source::Column* taps = columns_.taps.data();
        if (one_) {  // ku = kv = 1: stratum a is pixel a, weighted here
            const float* px = &row_[static_cast<std::size_t>(b0)]->x;
            const float limit = limit_[static_cast<std::size_t>(b0)], wf = static_cast<float>(sr0.w);
            for (std::size_t a = 0; a < count; ++a)
                s.values[a] = Lanes{std::min(px[3 * a], limit) * wf, std::min(px[3 * a + 1], limit) * wf,
                                    std::min(px[3 * a + 2], limit) * wf, 0.0f};
        } else {
            weightedLine(sr0, s.line0.data());
            if (b1 >= 0) {
                weightedLine(sr1, s.line1.data());
                float* l0 = s.line0.data();
                const float* l1 = s.line1.data();
                const std::size_t w3 = 3 * static_cast<std::size_t>(width_);
                // line0 + line1, the sum where the two rows agree; line1 keeps row b1's own.
                std::vector<float>& both = s.both;
                both.resize(w3);
                float* sum = both.data();
#pragma omp simd
                for (std::size_t k = 0; k < w3; ++k) sum[k] = l0[k] + l1[k];
                for (std::size_t a = 0; a < count; ++a) s.values[a] = at(sum, taps[a]);
            } else {
                for (std::size_t a = 0; a < count; ++a) s.values[a] = at(s.line0.data(), taps[a]);
            }
        }
        // Neighbouring strata mostly share a texel: values are summed in runs before the cube is
        // touched. Three runs stay open: columns where both rows' strata share a texel, and each
        // row's own where they do not (near a pole the two rows' texels differ often, and one
        // flush per stratum there put the pole texels' single-precision sums 3e-5 off).
        struct Run {
            int texel = -1;
            Lanes sum{};
            std::size_t count = 0;
        };
        auto flush = [&](Run& r, double weight) {
            if (r.count == 0) return;
            texel(r.texel) += Rgb(glm::dvec3(r.sum[0], r.sum[1], r.sum[2]));
            weight_[static_cast<std::size_t>(r.texel)] += static_cast<float>(weight * static_cast<double>(r.count));
            r.count = 0;
        };
        auto add = [&](Run& r, int t, Lanes v, double weight) {
            if (t != r.texel) {
                flush(r, weight);
                r.texel = t;
                r.sum = v;
            } else {
                r.sum += v;
            }
            ++r.count;
        };
        Run both, only0, only1;
        for (std::size_t a = 0; a < count; ++a) {
            if (t0[a] == t1[a]) {
                add(both, t0[a], s.values[a], w);
            } else {
                add(only0, t0[a], at(s.line0.data(), taps[a]), sr0.w);
                add(only1, t1[a], at(s.line1.data(), taps[a]), sr1.w);
            }
        }
        flush(both, w);
        flush(only0, sr0.w);
        flush(only1, sr1.w);
    }

    // Each candidate's D = min(L, T) − min(L, T_k), added through every stratum whose
    // interpolation reads its pixel, with that stratum's weight for it. In image order, on the
    // calling thread: they are few (at most 1/64 of the strips they came from).
    void correctCandidates(float limit) {
        const int nu = static_cast<int>(columns_.size());
        for (const Strip& s : strips_) {
            if (s.deferred) continue;
            for (const Candidate& c : s.candidates) {
                const Rgb d = glm::min(c.value, Rgb(limit)) - glm::min(c.value, Rgb(s.limit));
                if (d == Rgb(0.0f)) continue;
                ++stats_.corrected;
                const int p = c.j + 1;  // padded row
                // Stratum rows whose interpolation rows include p, and columns whose taps include i.
                const int b0 = std::max(0, (c.j - 1) * st_.kv), b1 = std::min(nv_, (c.j + 2) * st_.kv);
                for (int b = b0; b < b1; ++b) {
                    const StratumRow sr = stratumRow(b);
                    float wy = 0.0f;
                    if (one_) {
                        wy = b == c.j ? 1.0f : 0.0f;
                    } else {
                        const Source::Row r = Source::rowAtV(sr.v, height_);
                        wy = (r.p0 == p ? 1.0f - r.fy : 0.0f) + (r.p1 == p ? r.fy : 0.0f);
                    }
                    if (wy == 0.0f) continue;
                    for (int a = (c.i - 1) * st_.ku; a < (c.i + 2) * st_.ku; ++a) {
                        const std::size_t col = static_cast<std::size_t>(((a % nu) + nu) % nu);
                        float wx = 0.0f;
                        if (one_) {
                            wx = columns_.pixel[col] == c.i ? 1.0f : 0.0f;
                        } else {
                            const Source::Column& t = columns_.taps[col];
                            wx = (t.i0 == c.i ? 1.0f - t.fx : 0.0f) + (t.i1 == c.i ? t.fx : 0.0f);
                        }
                        if (wx == 0.0f) continue;
                        texel(columns_.texelOf(col, sr.sn, sr.ct, n_)) += Rgb(sr.w * glm::dvec3(d * (wx * wy)));
                    }
                }
            }
        }
    }

    // Sums to means; a texel that got no stratum (none does at this spacing, strataFor) stays 0.
    void normalise() {
        parallelFor(0, cubeRows(n_), [&](int r) {
            const auto [f, y] = faceRowOf(r, n_);
            for (int x = 0; x < n_; ++x) {
                const float wt = weight_[(static_cast<std::size_t>(f) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(y)) *
                                             static_cast<std::size_t>(n_) + static_cast<std::size_t>(x)];
                Rgb& t = cube_.at(f, x, y);
                t = wt > 0.0f ? t / wt : Rgb(0.0f);
            }
        });
    }

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

// Gather when its reads cost less than the scatter's strata (kReadCostInStrata). Both are
// well within the previous conversion's error against the exact texel means
// (docs/latlong-conversion.md); gather is the more accurate of the two where both apply.
bool gathers(int width, int height, int n) {
    const Strata st = strataFor(width, height, n);
    const double strata = static_cast<double>(width) * st.ku * static_cast<double>(height) * st.kv;
    return kReadCostInStrata * gatherReads(width, height, n) < strata;
}

void checkSizes(int width, int height, std::size_t pixels, int faceSize) {
    if (width < 1 || height < 1 || faceSize < 1 || pixels != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw std::invalid_argument("latLongToCube: " + std::to_string(width) + " × " + std::to_string(height) +
                                    " image with " + std::to_string(pixels) + " pixels, face size " +
                                    std::to_string(faceSize));
}

CubeMap convert(const LatLongView& img, int faceSize, const ProgressSpan& progress) {
    checkSizes(img.width, img.height, img.pixels.size(), faceSize);
    if (!gathers(img.width, img.height, faceSize)) {
        // The scatter takes the image in the decoder's strips, so that a decoded file and an image
        // in memory give the same cube to the bit.
        ScatterStream stream(img.width, img.height, faceSize);
        const std::size_t w = static_cast<std::size_t>(img.width);
        for (int y0 = 0; y0 < img.height; y0 += io_detail::kLatLongStripRows) {
            const int y1 = std::min(img.height, y0 + io_detail::kLatLongStripRows);
            stream.addStrip(y0, y1, img.pixels.subspan(static_cast<std::size_t>(y0) * w, static_cast<std::size_t>(y1 - y0) * w),
                            false);
            progress.report(0.5 * y1 / img.height);
        }
        return stream.finish(0.0f, progress.sub(0.5, 1.0));
    }
    const BrightSplit split = splitBright(img);
    progress.report(0.05);
    const Source src(img, split.limit);
    CubeMap cube(faceSize);
    gather(src, cube, progress.sub(0.05, 0.9));
    splatExcess(split.excess, img.width, img.height, cube, progress.sub(0.9, 1.0));
    return cube;
}

}  // namespace

LatLongMethod latLongMethod(int width, int height, int faceSize) {
    return gathers(width, height, faceSize) ? LatLongMethod::Gather : LatLongMethod::Scatter;
}

CubeMap latLongToCube(const LatLongView& image, int faceSize, const Progress& progress) {
    CubeMap cube = convert(image, faceSize, {progress, 0.0f, 1.0f});
    cube.makeSeamless();
    return cube;
}

namespace io_detail {

CubeMap latLongToCube(const Image& img, int faceSize, const Progress& progress, float p0, float p1) {
    return convert({img.width, img.height, img.px}, faceSize, {progress, p0, p1});
}

bool latLongStreams(int width, int height, int faceSize) {
    return width >= 1 && height >= 1 && faceSize >= 1 && !gathers(width, height, faceSize);
}

struct LatLongStream::Impl {
    ScatterStream stream;
};

LatLongStream::LatLongStream(int width, int height, int faceSize) {
    checkSizes(width, height, static_cast<std::size_t>(width) * static_cast<std::size_t>(height), faceSize);
    impl_ = std::make_unique<Impl>(Impl{ScatterStream(width, height, faceSize)});
}
LatLongStream::~LatLongStream() = default;

void LatLongStream::addStrip(int y0, int y1, std::span<const Rgb> rows, bool hasInfinity) {
    impl_->stream.addStrip(y0, y1, rows, hasInfinity);
}

CubeMap LatLongStream::finish(float maxFinite, const Progress& progress, float p0, float p1) {
    return impl_->stream.finish(maxFinite, {progress, p0, p1});
}

const LatLongStream::Stats& LatLongStream::stats() const { return impl_->stream.stats(); }

}  // namespace io_detail

}  // namespace mipgloss
