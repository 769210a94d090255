// Error and seam metrics, all on texel centres with exact solid-angle weights.
#pragma once

#include "mipgloss/ibl/colour.h"
#include "mipgloss/ibl/cubemap.h"

#include <functional>
#include <vector>

namespace mipgloss {

struct LevelError {
    double relRms = 0.0;          // sqrt(Σ Ω |a-b|²) / sqrt(Σ Ω |b|²) over RGB
    double relRmsBorder = 0.0;    // the same over texels on face borders
    double relRmsInterior = 0.0;  // the same over the other texels (0 when a face has none)
    double meanRelDiff = 0.0;     // (mean(a) - mean(b)) / mean(b), solid-angle weighted, luminance
    bool hasInterior = false;
};

// Compares `test` with the truth `reference` (same size).
LevelError compareCubes(const CubeMap& test, const CubeMap& reference);

// Every texel on a face edge of a size-m cube (m >= 2), four edges per face: calls
// fn(face, edge texel x, y, the texel across the edge, the inward neighbour's x, y). The one
// walk over edge pairs that seam measures share.
template <class Fn>
void forEachEdgePair(int m, Fn&& fn) {
    for (Face f : kAllFaces)
        for (int i = 0; i < m; ++i) {
            const int ex[4] = {0, m - 1, i, i}, ey[4] = {i, i, 0, m - 1};
            const int ox[4] = {-1, m, i, i}, oy[4] = {i, i, -1, m};
            const int ix[4] = {1, m - 2, i, i}, iy[4] = {i, i, 1, m - 2};
            for (int k = 0; k < 4; ++k) fn(f, ex[k], ey[k], resolveTexel(f, ox[k], oy[k], m), ix[k], iy[k]);
        }
}

// Jumps across cube edges against jumps just inside the faces, as luminance gradients (difference
// over the angle between the two texel centres): for every texel on a face edge, the pair formed
// with the texel across the edge, and the pair formed with its inward neighbour.
struct SeamStats {
    double edgeGradient = 0.0;
    double insideGradient = 0.0;
    double ratio = 0.0;  // edge / inside; 0 when the face is smaller than 2×2
};
SeamStats seamStats(const CubeMap& level);

// ---- What the picture sees: reads between texel centres (docs/chain-schedule.md) ----

// `count` directions uniformly distributed on the sphere, from a fixed seed (repeatable).
std::vector<glm::vec3> uniformDirections(int count, unsigned seed = 1);

// The chain read as the GPU reads it: seamless bilinear within a level, linear between
// floor(lod) and the next level (lod clamped to the chain).
Rgb sampleChain(const MipChain& chain, const glm::vec3& direction, double lod);

// sampleChain at every direction.
std::vector<Rgb> readChain(const MipChain& chain, double lod, const std::vector<glm::vec3>& directions);

// Relative RMS over RGB: sqrt(Σ|a−b|²) / sqrt(Σ|b|²) (directions drawn uniformly carry equal
// weight). `test` and `truth` have the same length.
double relativeRms(const std::vector<Rgb>& test, const std::vector<Rgb>& truth);

// The chain read at `lod` at `directions` against the exact normalized Phong convolution of
// `base` at `exponent` there (referenceLobeAt): relative RMS.
double readError(const MipChain& chain, double lod, const CubeMap& base, double exponent,
                 const std::vector<glm::vec3>& directions);

// The x in [a, b] where `cost` (unimodal there) is least: golden-section search (Kiefer 1953), the
// bracket shrunk by φ = (√5 − 1)/2 per step, one new evaluation a step, until it is at most
// `tolerance` wide or after `maxSteps` steps; the bracket's midpoint.
double goldenSectionMinimum(const std::function<double(double)>& cost, double a, double b, double tolerance,
                            int maxSteps = 1000);

// Exponent n whose exact Phong convolution of `base`, sampled at the texel centres of a face of
// `level.size()`, best matches `level` in relative RMS (golden-section search on log n within
// [guess/16, guess·16]).
double fitExponent(const CubeMap& level, const CubeMap& base, double guess);

}  // namespace mipgloss
