// λ, the artist's knob, and the Phong exponent n it means; the chain's levels and the lobes they
// hold. The one place for both mappings (derivations and measurements: docs/phong-lobe.md and
// docs/chain-schedule.md).
//
// λ has the paper's meaning at one fixed size, so a material shows the same lobe under any
// environment and face size: solid-angle matching (McGuire et al. 2013) against a reference cube
// of face size 128, whose level-λ texels cover on average Ω = 4π / (6·(128/2^λ)²), set equal to
// the normalized lobe's solid angle 2π/(n+1):
//     n(λ) = 3·128²·4^−λ − 1,        λ(n) = log2(128·√3) − ½·log2(n + 1),
// with λ = 0 a true mirror (n = ∞) rather than n = 49151, and n clamped at 0 (a uniform
// hemisphere) beyond λ = log2(128√3) ≈ 7.79.
//
// The chain does not hold n(λ) at level λ: a level holds the lobe it can show between its texel
// centres (bilinear reads), σ ≈ 3.6 of its texels, n_k = M_k²/32 for a face of M_k ≥ 16 texels,
// and n = 1 (the diffuse kernel, irradiance/π) at the last level it reads, the first of 8 to 15
// texels. Smaller levels are never read. The renderer turns a material's n into a fractional
// chain level (`chainLevelForExponent`) until the lobe stack (scene/lobes.h) holds it, then reads
// the stack's exact lobes.
#pragma once

#include <limits>

namespace mipgloss {

inline constexpr int kLambdaReferenceSize = 128;
inline constexpr double kMirrorExponent = std::numeric_limits<double>::infinity();

// n(λ): ∞ for λ <= 0 (mirror), then 3·128²·4^−λ − 1 clamped at 0. NaN gives NaN.
double lambdaToExponent(double lambda);
// λ(n): 0 for n = ∞, clamped at 0 for n >= n(0+) and at λ(0) for n <= 0. NaN gives NaN.
double exponentToLambda(double exponent);
// λ as files of version 1 meant it: n = 3·N²·4^−λ − 1 against the base face size N they were
// saved with (clamped at 0). Used only to convert those files.
double legacyLambdaToExponent(double lambda, int baseSize);

// Validation for λ from the panel, a file or the command line.
inline constexpr double kMaxLambda = 8.0;  // n(λ) = 0 from 7.79 on
bool isValidLambda(double lambda);          // finite and in [0, kMaxLambda]
bool isValidExponent(double exponent);      // finite and >= 0, or +∞ (the mirror)

// The chain's schedule for a base of face size N (levels follow OpenGL's floor rule).
// Exponent held by level k: ∞ at 0 (the imported cube, the mirror), M²/32 for faces of M >= 16
// texels, 1 at the last read level; NaN for levels beyond it (never read).
double levelExponent(int baseSize, int level);
// The deepest level the renderer reads: the first with a face of 8–15 texels (0 when N < 16).
int lastReadLevel(int baseSize);
// The fractional chain level whose trilinear read is the renderer's stand-in for lobe n while
// λ moves. Between levels k and k+1 the GPU blends two lobes with weight t; t is chosen so the
// blend has the lobe's mean cosine (its band-1 factor (n+1)/(n+2), docs/phong-lobe.md):
//     t = (Λ(n_k) − Λ(n)) / (Λ(n_k) − Λ(n_k+1)),   Λ(n) = (n+1)/(n+2), Λ(∞) = 1,
// so the blend is as wide as the lobe on average (not the same shape: 10–58 % off it at half levels,
// mipgloss bench; the lobe stack removes that). 0 for the mirror, lastReadLevel for n <= 1.
double chainLevelForExponent(double exponent, int baseSize);
// The level whose faces hold lobe n(λ) at σ ≈ 3.6 texels if the schedule's regular part (faces
// M with n = M²/32) went on without end: log2(N / √(32 (n(λ) + 1))) = λ + log2(N/128) − ½·log2(96).
// A straight line in λ, so a shader can evaluate it per fragment (the grazing option's per-fragment
// λ, shading_plan.glsl): the renderer passes regularScheduleLevel(0, N) as the offset and the shader
// adds λ and clamps to the read levels. At level k's own lobe it reads k − ½·log2(1 + 32/M²).
double regularScheduleLevel(double lambda, int baseSize);
// Its inverse: the lobe the renderer means when it reads the chain at `lod` (∞ at 0, 1 at
// lastReadLevel and beyond). Λ(n) = (n+1)/(n+2) is inverted as n = (2Λ − 1)/(1 − Λ).
double exponentForChainLevel(double lod, int baseSize);

}  // namespace mipgloss
