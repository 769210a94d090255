// Mip-chain builders, selectable by enum (and by name in files and on the command line). Every builder takes a base cube (level 0) and returns a
// full chain down to 1×1 with seamless (or, for `paper`, its own) borders filled.
//
//   box        per-face 2×2 box filter: what glGenerateMipmap does. Read through seamless
//              filtering it shows no step at cube edges (SeamPicture measures it); its defect is
//              its lobe, far from the Phong lobe its λ declares (docs/builders.md).
//   paper      Ashikhmin & Ghosh 2002, §3: each face enlarged by its four unfolded neighbours,
//              corners filled with a copy of a face image (we use the opposite face), repeatedly
//              box-filtered, the centre cut out with a one-texel border that sampling uses.
//   phong      the default: level k is the normalized Phong-lobe convolution of the sphere at
//              n = lambdaToExponent(k, N), filtered across faces with exact solid angles. Levels
//              1..3 filter the base itself; deeper levels filter an energy-preserving pyramid level
//              three steps finer that keeps each texel's energy at its energy-weighted direction
//              (so a sun stays where it is). O(N²) per level; the levels shrink 4× each, so
//              O(N²) for the chain (docs/builders.md counts the taps).
//   reference  the exact discrete normalized Phong convolution of the base at every level, in
//              double precision with the lobe cut at 1e-10 of its peak. Slow; for tests and bench.
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/progress.h"

#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace mipgloss {

enum class Builder { Phong, Box, Paper, Reference };
inline constexpr Builder kDefaultBuilder = Builder::Phong;
// Every builder, the default first.
inline constexpr std::array<Builder, 4> kAllBuilders{Builder::Phong, Builder::Box, Builder::Paper,
                                                     Builder::Reference};
const char* builderName(Builder builder);  // "phong", "box", "paper", "reference"
bool parseBuilder(std::string_view text, Builder& out);

struct BuildOptions {
    // Levels above this index are filled by a cheap box filter from the level before instead of
    // the builder's own filter ("skip what the scene doesn't need"); -1 builds every level.
    int lastFilteredLevel = -1;
    // Stage "build"; returning false stops the build with Cancelled (progress.h).
    Progress progress;
};

// Builds the chain. `base` must be non-empty with finite, non-negative texels (import ensures it).
// Throws Cancelled when options.progress asks to stop.
MipChain buildChain(const CubeMap& base, Builder builder, const BuildOptions& options = {});

// The individual builders.
MipChain buildBoxChain(const CubeMap& base, const BuildOptions& options = {});
MipChain buildPaperChain(const CubeMap& base, const BuildOptions& options = {});
MipChain buildPhongChain(const CubeMap& base, const BuildOptions& options = {});
MipChain buildReferenceChain(const CubeMap& base, const BuildOptions& options = {});

// One box step: each face of `level` resampled to `size` by area-proportional weights (2×2
// averaging when halving), borders filled. The box builder's step, and the cube EXR file's levels
// below a chain that stops early.
CubeMap boxDownsample(const CubeMap& level, int size);

// Exact discrete normalized Phong convolution of `base` with exponent n, sampled at the texel
// centres of a face of size `outSize` (double precision, lobe cut at `cutoff` of its peak).
CubeMap referenceConvolution(const CubeMap& base, double exponent, int outSize,
                             double cutoff = 1e-10);

}  // namespace mipgloss
