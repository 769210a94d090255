// The conversion mipgloss used before latLongToCube (latlong_quadrature.h): the code as it was in
// core/io/src/latlong.cpp, less its progress reports, kept on the tests' side as their reference.
#include "latlong_quadrature.h"

#include "mipgloss/ibl/parallel.h"
#include "mipgloss/io/import.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace mipgloss {

namespace {
namespace quadrature {

using Image = DecodedImage;
constexpr double kPi = std::numbers::pi;

// Each cube texel is the solid-angle weighted mean of the lat-long image over its footprint on
// the sphere. The integral is a quadrature: every lat-long pixel is cut into ku × kv strata, the
// image is interpolated bilinearly (wrapping in u) at each stratum's centre, and the stratum
// carries its exact solid angle, Δφ·(cos θ0 − cos θ1). Each stratum belongs to the texel whose
// footprint holds its direction, so the conversion neither aliases (a texel averages every
// stratum it covers) nor leaves holes, and its weighted mean is the image's own. The strata are
// spaced at most half the angular width of the smallest cube texel (a corner texel: (2/N)/3 rad)
// so every texel receives several; a texel that still gets none takes a bilinear sample at its
// centre. Bright pixels are handled apart (BrightSplit below).
//
// The loop gathers rather than scatters: each face row is one task, and a texel visits the
// strata inside a conservative (θ, φ) box around its footprint, so no two tasks write the same
// texel and the result does not depend on the thread count.

struct LatLongSampler {
    int width, height;
    // The image with a row above and below holding the pole values (each the mean of the row
    // next to it), so bilinear interpolation in the first and last half rows runs to the pole's
    // single value instead of clamping, which would smear row 0's variation in φ over the pole.
    std::vector<Rgb> padded;
    int ku, kv;  // strata per pixel in u and v
    int nu, nv;  // total strata across the width and down the height
    struct Column { float cosPhi, sinPhi; int i0, i1; float fx; };
    struct Row { float cosTheta, sinTheta; int p0, p1; float fy; double weight; };
    std::vector<Column> cols;
    std::vector<Row> rows;

    LatLongSampler(const Image& img, int faceSize) : width(img.width), height(img.height) {
        const std::size_t w = static_cast<std::size_t>(width);
        padded.resize(w * static_cast<std::size_t>(height + 2));
        std::copy(img.px.begin(), img.px.end(), padded.begin() + static_cast<std::ptrdiff_t>(w));
        glm::dvec3 top(0.0), bottom(0.0);
        for (int i = 0; i < width; ++i) {
            top += glm::dvec3(img.at(i, 0));
            bottom += glm::dvec3(img.at(i, height - 1));
        }
        std::fill_n(padded.begin(), w, Rgb(top / static_cast<double>(width)));
        std::fill_n(padded.end() - static_cast<std::ptrdiff_t>(w), w, Rgb(bottom / static_cast<double>(width)));

        const double texel = (2.0 / faceSize) / 3.0;  // smallest texel's angular width
        ku = std::max(1, static_cast<int>(std::ceil(2.0 * (2.0 * kPi / width) / texel)));
        kv = std::max(1, static_cast<int>(std::ceil(2.0 * (kPi / height) / texel)));
        nu = width * ku;
        nv = height * kv;
        cols.resize(static_cast<std::size_t>(nu));
        for (int a = 0; a < nu; ++a) {
            const double u = (a + 0.5) / nu;
            const double phi = 2.0 * kPi * (u - 0.5);
            cols[static_cast<std::size_t>(a)] = column(u);
            cols[static_cast<std::size_t>(a)].cosPhi = static_cast<float>(std::cos(phi));
            cols[static_cast<std::size_t>(a)].sinPhi = static_cast<float>(std::sin(phi));
        }
        rows.resize(static_cast<std::size_t>(nv));
        for (int b = 0; b < nv; ++b) {
            const double v = (b + 0.5) / nv;
            Row& r = rows[static_cast<std::size_t>(b)];
            r = row(v);
            r.cosTheta = static_cast<float>(std::cos(kPi * v));
            r.sinTheta = static_cast<float>(std::sin(kPi * v));
            r.weight = std::cos(kPi * b / nv) - std::cos(kPi * (b + 1) / nv);
        }
    }

    // Bilinear interpolation weights at u (wrapping) and v (padded rows; pole rows at v = 0, 1).
    Column column(double u) const {
        const double x = u * width - 0.5;
        const double fl = std::floor(x);
        const int i0 = (static_cast<int>(fl) % width + width) % width;
        return {0.0f, 0.0f, i0, (i0 + 1) % width, static_cast<float>(x - fl)};
    }
    Row row(double v) const {
        const double y = std::clamp(v * height - 0.5, -0.5, height - 0.5);  // row 0's centre at 0
        Row r{};
        if (y < 0.0) {  // between the top pole (y = -1/2) and row 0
            r.p0 = 0;
            r.p1 = 1;
            r.fy = static_cast<float>(2.0 * (y + 0.5));
        } else if (y > height - 1) {  // between the last row and the bottom pole
            r.p0 = height;
            r.p1 = height + 1;
            r.fy = static_cast<float>(2.0 * (y - (height - 1)));
        } else {
            const double fl = std::floor(y);
            r.p0 = static_cast<int>(fl) + 1;
            r.p1 = std::min(r.p0 + 1, height);
            r.fy = static_cast<float>(y - fl);
        }
        return r;
    }

    const Rgb& at(int i, int p) const {
        return padded[static_cast<std::size_t>(p) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)];
    }
    Rgb value(const Column& c, const Row& r) const {
        const Rgb a = at(c.i0, r.p0), b = at(c.i1, r.p0);
        const Rgb d = at(c.i0, r.p1), e = at(c.i1, r.p1);
        return (a * (1.0f - c.fx) + b * c.fx) * (1.0f - r.fy) + (d * (1.0f - c.fx) + e * c.fx) * r.fy;
    }

    // Bilinear sample at a direction (the fallback for a texel without strata).
    Rgb sample(const glm::vec3& dir) const {
        const glm::dvec2 uv = latLongCoord(glm::dvec3(dir));
        const double u = uv.x, v = uv.y;
        return value(column(u), row(v));
    }
};

void convertTexel(const LatLongSampler& ll, CubeMap& cube, Face f, int x, int y) {
    const int n = cube.size();
    const float inv = 1.0f / static_cast<float>(n);
    // Sample the texel's boundary: extremes of θ and φ over the footprint lie on it unless a
    // pole is inside, which is tested separately.
    constexpr int kPerEdge = 4;
    std::array<glm::vec3, 4 * kPerEdge> boundary;
    for (int i = 0; i < kPerEdge; ++i) {
        const float a = static_cast<float>(i) / kPerEdge;
        const float x0 = static_cast<float>(x), y0 = static_cast<float>(y);
        boundary[static_cast<std::size_t>(i)] = faceToDirection(f, (x0 + a) * inv, y0 * inv);
        boundary[static_cast<std::size_t>(kPerEdge + i)] = faceToDirection(f, (x0 + 1) * inv, (y0 + a) * inv);
        boundary[static_cast<std::size_t>(2 * kPerEdge + i)] = faceToDirection(f, (x0 + 1 - a) * inv, (y0 + 1) * inv);
        boundary[static_cast<std::size_t>(3 * kPerEdge + i)] = faceToDirection(f, x0 * inv, (y0 + 1 - a) * inv);
    }
    const glm::vec3 centre = texelDirection(f, x, y, n);
    const double phiC = std::atan2(static_cast<double>(centre.z), static_cast<double>(centre.x));
    // Azimuths relative to the centre's, compared through a pseudo-angle (monotonic in the angle
    // over (-π, π]) so that only the two extremes need an atan2.
    const double uc = std::cos(phiC), us = std::sin(phiC);
    auto pseudo = [](double sn, double cs) {
        const double d = std::fabs(sn) + std::fabs(cs);
        return d > 0.0 ? std::copysign(1.0 - cs / d, sn) : 0.0;
    };
    // θ from the points of least and greatest y, through atan2 (acos loses digits near the poles);
    // the segment length from the chord (a dot product near 1 loses them too).
    glm::dvec3 top(0.0, -2.0, 0.0), bottom(0.0, 2.0, 0.0);
    double maxChord = 0.0;
    double pMin = 0.0, pMax = 0.0;
    glm::dvec2 atMin(1.0, 0.0), atMax(1.0, 0.0);  // (cos, sin) of the extreme relative azimuths
    for (std::size_t i = 0; i < boundary.size(); ++i) {
        const glm::dvec3 d(boundary[i]);
        if (d.y > top.y) top = d;
        if (d.y < bottom.y) bottom = d;
        const double cs = d.x * uc + d.z * us, sn = d.z * uc - d.x * us;
        const double p = pseudo(sn, cs);
        if (p < pMin) {
            pMin = p;
            atMin = {cs, sn};
        }
        if (p > pMax) {
            pMax = p;
            atMax = {cs, sn};
        }
        maxChord = std::max(maxChord, glm::length(d - glm::dvec3(boundary[(i + 1) % boundary.size()])));
    }
    auto polar = [](const glm::dvec3& d) { return std::atan2(std::hypot(d.x, d.z), d.y); };
    double thetaMin = polar(top);
    double thetaMax = polar(bottom);
    const double dMin = pMin < 0.0 ? std::atan2(atMin.y, atMin.x) : 0.0;
    const double dMax = pMax > 0.0 ? std::atan2(atMax.y, atMax.x) : 0.0;
    const double seg = 2.0 * std::asin(std::min(1.0, 0.5 * maxChord));
    // Between two boundary samples the boundary strays at most seg/2 in angle, so θ at most seg/2
    // and φ at most (seg/2)/sin θ.
    const double margin = 0.5 * seg + 1e-5;
    thetaMin -= margin;
    thetaMax += margin;
    // A pole inside or on the texel: θ reaches 0 (or π) and φ takes every value.
    auto holds = [&](const glm::vec3& pole) {
        const FaceCoord c = directionToFace(pole);
        const float eps = 1e-4f * inv;
        return c.face == f && c.s >= static_cast<float>(x) * inv - eps &&
               c.s <= static_cast<float>(x + 1) * inv + eps && c.t >= static_cast<float>(y) * inv - eps &&
               c.t <= static_cast<float>(y + 1) * inv + eps;
    };
    if (holds({0.0f, 1.0f, 0.0f})) thetaMin = 0.0;
    if (holds({0.0f, -1.0f, 0.0f})) thetaMax = kPi;
    bool fullPhi = thetaMin <= 0.0 || thetaMax >= kPi;
    double phiLo = 0.0, phiHi = 0.0;
    if (!fullPhi) {
        const double sinMin = std::min(std::sin(thetaMin), std::sin(thetaMax));
        const double phiMargin = margin / sinMin;
        phiLo = phiC + dMin - phiMargin;
        phiHi = phiC + dMax + phiMargin;
        fullPhi = phiHi - phiLo >= kPi;
    }
    int aLo = 0, aHi = ll.nu - 1;
    if (!fullPhi) {
        aLo = static_cast<int>(std::floor((phiLo / (2.0 * kPi) + 0.5) * ll.nu - 0.5));
        aHi = static_cast<int>(std::ceil((phiHi / (2.0 * kPi) + 0.5) * ll.nu - 0.5));
        if (aHi - aLo + 1 >= ll.nu) {
            aLo = 0;
            aHi = ll.nu - 1;
        }
    }
    const int bLo = std::max(0, static_cast<int>(std::floor(std::max(thetaMin, 0.0) / kPi * ll.nv - 0.5)));
    const int bHi = std::min(ll.nv - 1, static_cast<int>(std::ceil(std::min(thetaMax, kPi) / kPi * ll.nv - 0.5)));

    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    for (int b = bLo; b <= bHi; ++b) {
        const LatLongSampler::Row& r = ll.rows[static_cast<std::size_t>(b)];
        for (int a = aLo; a <= aHi; ++a) {
            const int ai = a < 0 ? a + ll.nu : (a >= ll.nu ? a - ll.nu : a);
            const LatLongSampler::Column& c = ll.cols[static_cast<std::size_t>(ai)];
            const glm::vec3 dir(r.sinTheta * c.cosPhi, r.cosTheta, r.sinTheta * c.sinPhi);
            // texelOf: each direction belongs to exactly one texel.
            const TexelRef t = texelOf(directionToFace(dir), n);
            if (t.face != f || t.x != x || t.y != y) continue;
            sum += r.weight * glm::dvec3(ll.value(c, r));
            wsum += r.weight;
        }
    }
    cube.at(f, x, y) = wsum > 0.0 ? Rgb(sum / wsum) : ll.sample(centre);
}

// The few pixels far above the image's mean (a sun) carry much of its energy, and the ratio
// Σw·L/Σw above scales each texel's strata by Ω_texel/Σw, which is 1 only up to how the strata
// tile the texel: a percent or two for one stratum's worth of sun. So the image is split into
// min(L, T), converted as above, and the sparse excess max(L - T, 0), whose energy is splatted
// exactly: each excess pixel is cut into sub-strata far smaller than a texel, each carrying its
// exact solid angle times the excess, and a texel adds (its energy)/Ω_texel. Σ Ω·value is then
// the image's own weighted sum for the excess, and constants and smooth images are unaffected.
struct BrightSplit {
    Image clamped;
    struct Pixel { int i, j; Rgb excess; };
    std::vector<Pixel> excess;
};

BrightSplit splitBright(const Image& img) {
    BrightSplit out{img, {}};
    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    std::vector<float> peaks(img.px.size());
    for (int j = 0; j < img.height; ++j) {
        const double w = std::cos(kPi * j / img.height) - std::cos(kPi * (j + 1) / img.height);
        for (int i = 0; i < img.width; ++i) {
            const Rgb& p = img.at(i, j);
            sum += w * glm::dvec3(p);
            wsum += w;
            peaks[static_cast<std::size_t>(j) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(i)] =
                std::max({p.x, p.y, p.z});
        }
    }
    const glm::dvec3 mean = sum / wsum;
    // 16× the brightest channel's mean, raised if need be so that at most 2 % of pixels exceed it.
    float threshold = static_cast<float>(16.0 * std::max({mean.x, mean.y, mean.z}));
    const std::size_t cap = img.px.size() / 50;
    if (cap > 0 && cap < peaks.size()) {
        std::nth_element(peaks.begin(), peaks.end() - static_cast<std::ptrdiff_t>(cap), peaks.end());
        threshold = std::max(threshold, *(peaks.end() - static_cast<std::ptrdiff_t>(cap)));
    }
    if (!(threshold > 0.0f)) return out;
    for (int j = 0; j < img.height; ++j)
        for (int i = 0; i < img.width; ++i) {
            Rgb& p = out.clamped.px[static_cast<std::size_t>(j) * static_cast<std::size_t>(img.width) +
                                    static_cast<std::size_t>(i)];
            if (std::max({p.x, p.y, p.z}) <= threshold) continue;
            out.excess.push_back({i, j, glm::max(p - Rgb(threshold), Rgb(0.0f))});
            p = glm::min(p, Rgb(threshold));
        }
    return out;
}

// Adds the excess pixels' energy to the texels under them (see BrightSplit).
void splatExcess(const std::vector<BrightSplit::Pixel>& pixels, int width, int height, CubeMap& cube) {
    if (pixels.empty()) return;
    const int n = cube.size();
    // Sub-strata at most 1/4 of the narrowest texel's width, (2/N)/3.
    const double texel = (2.0 / n) / 3.0;
    const int su = std::max(1, static_cast<int>(std::ceil(4.0 * (2.0 * kPi / width) / texel)));
    const int sv = std::max(1, static_cast<int>(std::ceil(4.0 * (kPi / height) / texel)));
    using Energy = std::vector<std::pair<std::uint64_t, glm::dvec3>>;
    const int chunks = std::min(static_cast<int>(pixels.size()), 64);
    std::vector<Energy> parts(static_cast<std::size_t>(chunks));
    parallelFor(0, chunks, [&](int c) {
        std::map<std::uint64_t, glm::dvec3> acc;
        // Neighbouring sub-strata mostly share a texel: sum runs before touching the map.
        std::uint64_t runKey = std::numeric_limits<std::uint64_t>::max();
        glm::dvec3 run(0.0);
        const std::size_t begin = pixels.size() * static_cast<std::size_t>(c) / static_cast<std::size_t>(chunks);
        const std::size_t end = pixels.size() * static_cast<std::size_t>(c + 1) / static_cast<std::size_t>(chunks);
        for (std::size_t k = begin; k < end; ++k) {
            const BrightSplit::Pixel& p = pixels[k];
            const double dphi = 2.0 * kPi / (static_cast<double>(width) * su);
            for (int b = 0; b < sv; ++b) {
                const double t0 = kPi * (p.j + static_cast<double>(b) / sv) / height;
                const double t1 = kPi * (p.j + static_cast<double>(b + 1) / sv) / height;
                const double w = dphi * (std::cos(t0) - std::cos(t1));
                const double theta = 0.5 * (t0 + t1);
                for (int a = 0; a < su; ++a) {
                    const double phi = 2.0 * kPi * ((p.i + (a + 0.5) / su) / width - 0.5);
                    const glm::vec3 dir(sphericalDirection(theta, phi));
                    const TexelRef t = texelOf(directionToFace(dir), n);
                    const int tx = t.x, ty = t.y;
                    const std::uint64_t key = (static_cast<std::uint64_t>(t.face) * static_cast<std::uint64_t>(n) +
                                               static_cast<std::uint64_t>(ty)) * static_cast<std::uint64_t>(n) +
                                              static_cast<std::uint64_t>(tx);
                    if (key != runKey) {
                        if (runKey != std::numeric_limits<std::uint64_t>::max()) acc[runKey] += run;
                        runKey = key;
                        run = glm::dvec3(0.0);
                    }
                    run += w * glm::dvec3(p.excess);
                }
            }
        }
        if (runKey != std::numeric_limits<std::uint64_t>::max()) acc[runKey] += run;
        parts[static_cast<std::size_t>(c)].assign(acc.begin(), acc.end());
    });
    const std::uint64_t un = static_cast<std::uint64_t>(n);
    for (const Energy& part : parts)
        for (const auto& [key, energy] : part) {
            const int x = static_cast<int>(key % un), y = static_cast<int>((key / un) % un);
            const Face f = kAllFaces[static_cast<std::size_t>(key / (un * un))];
            cube.at(f, x, y) += Rgb(energy / texelSolidAngle(x, y, n));
        }
}


CubeMap latLongToCube(const Image& img, int faceSize) {
    const BrightSplit split = splitBright(img);
    const LatLongSampler ll(split.clamped, faceSize);
    CubeMap cube(faceSize);
    parallelFor(0, 6 * faceSize, [&](int row) {
        const Face f = kAllFaces[static_cast<std::size_t>(row / faceSize)];
        const int y = row % faceSize;
        for (int x = 0; x < faceSize; ++x) convertTexel(ll, cube, f, x, y);
    });
    splatExcess(split.excess, img.width, img.height, cube);
    return cube;
}

}  // namespace quadrature
}  // namespace

CubeMap latLongToCubeQuadrature(const LatLongView& image, int faceSize) {
    if (image.width < 1 || image.height < 1 || faceSize < 1 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
        throw std::invalid_argument("latLongToCubeQuadrature: the image's sizes disagree");
    const DecodedImage img{image.width, image.height, {image.pixels.begin(), image.pixels.end()}};
    CubeMap cube = quadrature::latLongToCube(img, faceSize);
    cube.makeSeamless();
    return cube;
}

}  // namespace mipgloss
