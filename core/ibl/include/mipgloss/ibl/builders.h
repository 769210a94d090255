// Mip-chain builders, selectable by enum (and by name in files and on the command line). Every
// builder takes a base cube (level 0, the mirror) and returns a full chain down to 1×1 with
// seamless (or, for `paper`, its own) borders filled. Level k holds the lobe the schedule in
// phong.h declares (levelExponent): σ ≈ 3.6 of its texels, n = 1 at the last read level, box
// steps below it (never read).
//
//   phong      the default: level k is the normalized Phong convolution of the sphere at n_k,
//              filtered across faces with exact solid angles, from the energy pyramid level whose
//              texels are about half the lobe's σ (never coarser than 32², so a lobe wider than
//              the pyramid's texels by far keeps 6 000+ source points); each pyramid texel keeps
//              its energy at its energy-weighted direction, so a sun stays where it is.
//              O(N²) for the chain (docs/chain-schedule.md counts the taps and measures the error
//              of each shortcut).
//   box        per-face 2×2 box filter: what glGenerateMipmap does. Read through seamless
//              filtering it shows no step at cube edges (SeamPicture measures it); its defect is
//              its lobe, far from the Phong lobe the schedule declares (docs/builders.md).
//   paper      Ashikhmin & Ghosh 2002, §3: each face enlarged by its four unfolded neighbours,
//              corners filled with a copy of a face image (we use the opposite face), repeatedly
//              box-filtered, the centre cut out with a one-texel border that sampling uses.
//   reference  the exact discrete normalized Phong convolution of the base at every read level,
//              in double precision with the lobe cut at 1e-10 of its peak. Slow; tests and bench.
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/progress.h"

#include <array>
#include <memory>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace mipgloss {

class PhongFilter;

enum class Builder { Phong, Box, Paper, Reference };
inline constexpr Builder kDefaultBuilder = Builder::Phong;
// Every builder, the default first.
inline constexpr std::array<Builder, 4> kAllBuilders{Builder::Phong, Builder::Box, Builder::Paper,
                                                     Builder::Reference};
const char* builderName(Builder builder);  // "phong", "box", "paper", "reference"
bool parseBuilder(std::string_view text, Builder& out);

struct BuildOptions {
    // Levels above this index are filled by a cheap box filter from the level before instead of
    // the builder's own filter ("skip what the scene doesn't need"); -1 builds every read level.
    // Levels beyond lastReadLevel (phong.h) are box steps whatever this says.
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
// `filter`, when given, is this base's PhongFilter (kept for the lobe stack): its pyramid is reused.
MipChain buildPhongChain(const CubeMap& base, const BuildOptions& options = {}, const PhongFilter* filter = nullptr);
MipChain buildReferenceChain(const CubeMap& base, const BuildOptions& options = {});

// One box step: each face of `level` resampled to `size` by area-proportional weights (2×2
// averaging when halving), borders filled. The box builder's step, and the cube EXR file's levels
// below a chain that stops early.
CubeMap boxDownsample(const CubeMap& level, int size);

// The default builder's machinery, kept for lobes made after the chain: each entry of the lobe
// stack (scene/lobes.h) comes from the same energy pyramid. Built once per base
// (about a third of the base's size in memory); filter() may run on any thread.
// The default builder's shortcuts (docs/chain-schedule.md). The defaults are the product's;
// `mipgloss bench --shortcuts` builds with each one changed to measure what it costs.
struct PhongShortcuts {
    // The source: the coarsest energy-pyramid level whose face has at least √(sourceFactor·n)
    // texels (√8·√n: texels of 1.57/M rad ≈ 0.55σ), and never one below minSourceSize.
    double sourceFactor = 8.0;
    int minSourceSize = 32;
    // The lobe cut: (R·ω)^n below this fraction of its peak is left out. For the schedule's
    // Gaussian-like lobes the tail beyond it holds about as much of the energy; the weights are
    // normalized over what is kept, so a constant stays exact. 1e-4 rather than 1e-3: beside a
    // sun 10⁴× brighter than the sky the lost tail shows (sunrise at 512, level 1: read error
    // 0.29 % at 1e-4 against 0.83 % at 1e-3, for 15 % more time; `mipgloss bench --shortcuts`).
    double cutoff = 1e-4;
    // Faces from this size on are filtered at half size and brought up by cubic B-spline
    // interpolation (σ = 1.8 texels at half size is far above its Nyquist rate); 0: never.
    int upsampleFromSize = 256;
};

class PhongFilter {
public:
    explicit PhongFilter(const CubeMap& base, const PhongShortcuts& shortcuts = {});
    ~PhongFilter();
    PhongFilter(const PhongFilter&) = delete;
    PhongFilter& operator=(const PhongFilter&) = delete;

    int baseSize() const;
    // The normalized Phong convolution of the base at `exponent` (>= 0, finite), at the texel
    // centres of a face of `size`, borders filled.
    CubeMap filter(double exponent, int size) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The face size of a lobe stack entry: large enough that the lobe is σ ≈ 3.6 texels wide, so bilinear
// reads between its centres stay within about 1 % (docs/chain-schedule.md), i.e. ceil(√(32 n)),
// at least 16 (smooth enough that even the widest lobes show no texel structure; 32 below n = 1,
// whose kernel is nearly a step at the horizon) and at most min(2N, 1024) for a base of size N: lobes sharper than that are held
// more coarsely, and the stack stops below them (stackTop).
int stackEntryFaceSize(double exponent, int baseSize);
// True when stackEntryFaceSize holds the lobe at full width (√(32 n) fits under the cap).
bool stackEntryHoldsLobe(double exponent, int baseSize);

// Exact discrete normalized Phong convolution of `base` with exponent n, sampled at the texel
// centres of a face of size `outSize` (double precision, lobe cut at `cutoff` of its peak).
CubeMap referenceConvolution(const CubeMap& base, double exponent, int outSize,
                             double cutoff = 1e-10);

// The same sum at any directions (need not be normalized): the truth a picture is compared with.
std::vector<Rgb> referenceLobeAt(const CubeMap& base, double exponent, const std::vector<glm::vec3>& directions,
                                 double cutoff = 1e-10);

}  // namespace mipgloss
