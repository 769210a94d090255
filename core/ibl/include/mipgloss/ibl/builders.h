// Mip-chain builders, selectable by name. Every builder takes a base cube (level 0) and returns a
// full chain down to 1×1 with seamless (or, for `paper`, its own) borders filled.
//
//   box        per-face 2×2 box filter: what glGenerateMipmap does; the baseline that seams.
//   paper      Ashikhmin & Ghosh 2002, §3: each face enlarged by its four unfolded neighbours,
//              corners filled with a copy of a face image (we use the opposite face), repeatedly
//              box-filtered, the centre cut out with a one-texel border that sampling uses.
//   phong      the default: level k is the normalized Phong-lobe convolution of the sphere at
//              n = lambdaToExponent(k, N), filtered across faces with exact solid angles. Levels
//              1..3 filter the base itself; deeper levels filter an energy-preserving pyramid level
//              three steps finer that keeps each texel's energy at its energy-weighted direction
//              (so a sun stays where it is). O(N²) per level, O(N² log N) in all.
//   reference  the exact discrete normalized Phong convolution of the base at every level, in
//              double precision with the lobe cut at 1e-10 of its peak. Slow; for tests and bench.
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace mipgloss {

inline constexpr std::string_view kDefaultBuilder = "phong";

// Names of all builders, the default first.
std::vector<std::string> builderNames();
bool isBuilderName(std::string_view name);

struct BuildOptions {
    // Levels above this index are filled by a cheap box filter from the level before instead of
    // the builder's own filter ("skip what the scene doesn't need"); -1 builds every level.
    int lastFilteredLevel = -1;
    // Called with the fraction done, from the calling thread; return false to cancel.
    std::function<bool(float)> progress;
};

// Thrown when BuildOptions::progress asks to stop.
struct BuildCancelled {};

// Builds the chain. `base` must be non-empty with finite, non-negative texels (import ensures it).
// Throws std::invalid_argument for an unknown name.
MipChain buildChain(const CubeMap& base, std::string_view method, const BuildOptions& options = {});

// The individual builders.
MipChain buildBoxChain(const CubeMap& base, const BuildOptions& options = {});
MipChain buildPaperChain(const CubeMap& base, const BuildOptions& options = {});
MipChain buildPhongChain(const CubeMap& base, const BuildOptions& options = {});
MipChain buildReferenceChain(const CubeMap& base, const BuildOptions& options = {});

// Exact discrete normalized Phong convolution of `base` with exponent n, sampled at the texel
// centres of a face of size `outSize` (double precision, lobe cut at `cutoff` of its peak).
CubeMap referenceConvolution(const CubeMap& base, double exponent, int outSize,
                             double cutoff = 1e-10);

}  // namespace mipgloss
