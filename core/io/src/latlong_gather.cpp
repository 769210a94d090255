// Lat-long -> cube by the gather (the cube finer than the image): each texel the weighted mean
// of a grid of bilinear reads on its face plane, and the count of those reads for the cost
// model (gatherReads). The method: latlong.cpp's top comment and docs/latlong-conversion.md.
#include "latlong_internal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mipgloss::latlong_detail {

// ---- Gather ----------------------------------------------------------------------------------

namespace {

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

}  // namespace

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

}  // namespace mipgloss::latlong_detail
