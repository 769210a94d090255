// λ (mip level, GL_TEXTURE_MIN_LOD) <-> Phong exponent n: the one place this mapping lives.
//
// Derivation (solid-angle matching, McGuire et al. 2013). Level λ of a chain with base face
// size N has faces of size M = N / 2^λ, so one of its 6·M² texels covers on average
//     Ω_texel = 4π / (6 M²) = 2π / (3 N² 4^-λ).
// The normalized Phong lobe D_n(R·ω) = (n+1)/(2π) · max(0, R·ω)^n has peak (n+1)/(2π), so the
// solid angle it "covers" (its integral over its peak) is
//     Ω_lobe = 2π / (n + 1).
// Setting Ω_lobe = Ω_texel: n + 1 = 3 N² 4^-λ, i.e.
//     λ = log2(N √3) − ½ log2(n + 1),        n = 3 N² 4^-λ − 1.
// The lobe's angular standard deviation is then about 1/√n ≈ 0.37 of a level-λ texel: a level's
// texel centres sample its lobe below Nyquist, which is why accuracy is measured at texel centres.
// Beyond λ = log2(N√3) the formula gives n < 0; the exponent is clamped at 0 (a uniform
// hemisphere), the blurriest lobe the model has.
#pragma once

namespace mipgloss {

// n(λ) for a chain of base face size N. λ may be fractional; the result is >= 0.
double lambdaToExponent(double lambda, int baseSize);

// λ(n) for a chain of base face size N; n >= 0 (negative n is treated as 0). Not clamped to the
// chain: callers that need a level index clamp with `clampLambda`.
double exponentToLambda(double exponent, int baseSize);

// λ clamped to [0, levelCount-1]; NaN becomes 0.
double clampLambda(double lambda, int levelCount);

}  // namespace mipgloss
