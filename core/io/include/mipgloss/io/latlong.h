// The lat-long (equirectangular) orientation convention, in one place: the one Blender and
// three.js use, converted to y up (docs/conventions.md, "Lat-long"):
//     u = 0.5 + atan2(z, x) / (2π)      (u across the width; the image centre looks along +X)
//     v = acos(y) / π                    (v = 0 is the top row, the zenith +Y)
// Checked on the shared HDRIs: the sun of sunset.exr lands at (0.81, 0.06, 0.59) and that of
// sunrise.exr at (0.80, 0.14, 0.58), both above the horizon.
//
// Lat-long -> cube is filtered: each texel is the solid-angle weighted mean of the bilinearly
// interpolated image over the texel's footprint, so a cube coarser than the image does not alias
// and a finer one is smooth. Near the poles the interpolation runs to the pole's single value (the
// mean of the first or last row) rather than clamping, so pole texels carry no azimuthal streaks.
// The few pixels far above the mean (suns) have their excess splatted with exact solid-angle
// bookkeeping, so their energy stays where they are. The conversion costs about one pass over the
// source pixels when it shrinks and a few reads per texel when it grows (the method and its
// figures: docs/latlong-conversion.md). The cube's weighted mean matches the image's within
// 0.15 % on all eight shared HDRIs at face sizes 64 and 256 (LatLongConversion tests).
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/progress.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

namespace mipgloss {

// Unit direction for the polar angle θ (from +Y) and azimuth φ (from +X towards +Z).
inline glm::dvec3 sphericalDirection(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

// Image coordinates (u, v in [0, 1]) -> unit direction.
inline glm::dvec3 latLongDirection(double u, double v) {
    return sphericalDirection(std::numbers::pi * v, 2.0 * std::numbers::pi * (u - 0.5));
}

// Direction (non-zero) -> image coordinates (u in (0, 1], v in [0, 1]).
inline glm::dvec2 latLongCoord(const glm::dvec3& dir) {
    const double len = std::sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
    return {0.5 + std::atan2(dir.z, dir.x) / (2.0 * std::numbers::pi),
            std::acos(std::clamp(dir.y / len, -1.0, 1.0)) / std::numbers::pi};
}

// A lat-long image in memory: width × height linear RGB pixels, row 0 at the top (v = 0), every
// value finite and non-negative (what import's sanitising guarantees).
struct LatLongView {
    int width = 0;
    int height = 0;
    std::span<const Rgb> pixels;  // width × height, row-major
};

// Lat-long -> cube with faces of `faceSize`, borders filled (makeSeamless). The result does not
// depend on the number of threads. Reports stage "import" from 0 to 1 on the calling thread and
// throws Cancelled when `progress` says stop. Throws std::invalid_argument when the sizes disagree.
CubeMap latLongToCube(const LatLongView& image, int faceSize, const Progress& progress = {});

// Which quadrature latLongToCube uses for these sizes: Scatter (every pixel cut into strata, each
// added to the texel that holds it; chosen when the image has many more pixels than the cube has
// texels) or Gather (a few reads per texel; chosen when the cube is about as fine or finer).
// docs/latlong-conversion.md gives the cost model.
enum class LatLongMethod { Scatter, Gather };
LatLongMethod latLongMethod(int width, int height, int faceSize);


}  // namespace mipgloss
