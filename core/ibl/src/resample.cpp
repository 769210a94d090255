#include "mipgloss/ibl/resample.h"

#include "mipgloss/ibl/parallel.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace mipgloss {

CubeMap resampleCube(const CubeMap& cube, int size) {
    const int n = cube.size();
    if (size == n) return cube;
    CubeMap out(size);
    if (size > n) {
        // Growing: bilinear through the borders, so samples near an edge see the neighbour.
        CubeMap src = cube;
        src.makeSeamless();
        parallelFor(0, cubeRows(size), [&](int row) {
            const auto [f, y] = faceRowOf(row, size);
            const float inv = 1.0f / static_cast<float>(size);
            for (int x = 0; x < size; ++x)
                out.at(f, x, y) = src.sample(f, (static_cast<float>(x) + 0.5f) * inv,
                                             (static_cast<float>(y) + 0.5f) * inv);
        });
    } else {
        // Shrinking: each output texel is the exact solid-angle weighted mean of the source
        // texels under its footprint, partial texels weighted by the solid angle of the overlap.
        const double scale = static_cast<double>(n) / size;
        auto plane = [&](double texels) { return 2.0 * texels / n - 1.0; };
        parallelFor(0, cubeRows(size), [&](int row) {
            const auto [f, y] = faceRowOf(row, size);
            const double y0 = y * scale, y1 = (y + 1) * scale;
            for (int x = 0; x < size; ++x) {
                const double x0 = x * scale, x1 = (x + 1) * scale;
                glm::dvec3 sum(0.0);
                double wsum = 0.0;
                const int syEnd = std::min(n, static_cast<int>(std::ceil(y1 - 1e-9)));
                const int sxEnd = std::min(n, static_cast<int>(std::ceil(x1 - 1e-9)));
                for (int sy = static_cast<int>(std::floor(y0)); sy < syEnd; ++sy) {
                    const double oy0 = std::max(y0, static_cast<double>(sy));
                    const double oy1 = std::min(y1, static_cast<double>(sy + 1));
                    if (oy1 <= oy0) continue;
                    for (int sx = static_cast<int>(std::floor(x0)); sx < sxEnd; ++sx) {
                        const double ox0 = std::max(x0, static_cast<double>(sx));
                        const double ox1 = std::min(x1, static_cast<double>(sx + 1));
                        if (ox1 <= ox0) continue;
                        const double w = faceRectSolidAngle(plane(ox0), plane(oy0), plane(ox1), plane(oy1));
                        sum += w * glm::dvec3(cube.at(f, sx, sy));
                        wsum += w;
                    }
                }
                out.at(f, x, y) = Rgb(sum / wsum);
            }
        });
    }
    out.makeSeamless();
    return out;
}

}  // namespace mipgloss
