// Lat-long -> cube: the bright split (splitBright: the threshold T, and the excess of the pixels
// above it) and the excess splat (splatExcess: that excess added to the cube with exact
// bookkeeping). The method: latlong.cpp's top comment and docs/latlong-conversion.md.
#include "latlong_internal.h"

#include "mipgloss/ibl/parallel.h"

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace mipgloss::latlong_detail {

// ---- Bright pixels ---------------------------------------------------------------------------
//
// The few pixels far above the image's mean (a sun) carry much of its energy, and a quadrature
// moves a percent or two of one stratum's worth of it. So the image is split into min(L, T),
// converted by quadrature, and the sparse excess max(L − T, 0), whose energy is added exactly
// (splatExcess). T is 16 × the brightest channel's solid-angle weighted mean, raised if need be
// so that at most 2 % of pixels exceed it. No copy of the image is made: the quadratures clamp
// each tap they read.

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

// ---- Excess splat ----------------------------------------------------------------------------

namespace {

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

}  // namespace

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

}  // namespace mipgloss::latlong_detail
