// A glossy layer's closed forms: roughness ↔ Phong exponent, Schlick's Fresnel, and the split-sum
// table that folds Fresnel and the horizon out of a Phong lobe (derivations and measured errors:
// docs/layered-materials.md).
//
// The layer the tables describe reflects, toward the viewer v, the environment through the
// normalized Phong lobe about the reflection vector r (the lobe the chain and the stack entries hold,
// phong.h), with Schlick's Fresnel at the half vector and nothing from below the surface:
//     S(v) = ∫ L(ω) · F(ω·h) · [N·ω > 0] · (n+1)/(2π) · max(0, r·ω)^n dω,   h = (ω + v)/|ω + v|,
//     F(c) = F0 + (1 − F0)·(1 − c)^5 = F0·(1 − (1 − c)^5) + (1 − c)^5.
// The split sum reads the lobe from the chain (a lookup) and multiplies it by the layer's albedo
// in a white environment, which is linear in F0:
//     S(v) ≈ lobe_n(r) · (F0·A(n, N·v) + B(n, N·v)),
//     A = ∫ (1 − (1 − ω·h)^5) [N·ω > 0] lobe_n(ω) dω,   B = ∫ (1 − ω·h)^5 [N·ω > 0] lobe_n(ω) dω.
// Exact in a uniform environment; elsewhere the error is what docs/layered-materials.md measures.
#pragma once

#include <array>
#include <span>
#include <vector>

namespace mipgloss {

// Roughness (glTF's perceptual roughness, α = r²) ↔ the Phong exponent of the reflected lobe:
//     n(r) = kRoughnessFit · (r^−4 − 1),   r(n) = (kRoughnessFit / (n + kRoughnessFit))^(1/4),
// fitted against GGX's reflected-direction distribution at normal incidence (total variation,
// docs/layered-materials.md). r = 0 is the mirror (n = ∞), r = 1 the uniform hemisphere (n = 0).
inline constexpr double kRoughnessFit = 0.37;
double roughnessToExponent(double roughness);  // clamps r to [0, 1]; NaN gives NaN
double exponentToRoughness(double exponent);   // ∞ → 0, n <= 0 → 1; NaN gives NaN

// F0 of common dielectrics (glTF's default, a clear coat's).
inline constexpr double kDielectricF0 = 0.04;

double schlickFresnel(double f0, double cosine);

struct SplitSum {
    double a = 0.0;  // the F0 term
    double b = 0.0;  // the constant term
    double albedo(double f0) const { return f0 * a + b; }
};

// A and B for lobe n (∞: the mirror) seen at N·v = cosView, integrated on a `samples` ×
// `samples` grid (stratified in the lobe's own measure, so every sample weighs the same). The
// reference the table is built from and checked against.
SplitSum splitSumIntegral(double exponent, double cosView, int samples = 256);

// A(λ, N·v) and B(λ, N·v) on a grid of kLambdaSteps × kCosSteps nodes, read bilinearly: uniform
// in λ over [0, kMaxLambda], and uniform in x = 1 − √(1 − θ/(π/2)), θ = acos(N·v). The horizon
// cuts a wide lobe as a smooth function of θ (of N·v it has a square-root corner at N·v = 1), and
// a narrow one within Δθ ≈ 1/√n of grazing (0.005 rad at λ = 0+): x is linear in θ head-on and
// crowds the nodes toward grazing (the last step is 0.0004 rad). Built once per process on first
// use (64² samples a node, about 0.1 s).
class SplitSumTable {
public:
    static constexpr int kLambdaSteps = 33;
    static constexpr int kCosSteps = 65;

    static const SplitSumTable& shared();

    // Bilinear read; λ and N·v are clamped to the grid.
    SplitSum at(double lambda, double cosView) const;
    // The nodes as (A, B) pairs, x fastest: what the renderer uploads as an RG texture whose s is
    // x = columnOfCosView(N·v) and t is λ / kMaxLambda.
    std::span<const float> nodes() const { return nodes_; }

    explicit SplitSumTable(int samples);

    // x of N·v, in [0, 1] (0 head-on), and N·v of a node column.
    static double columnOfCosView(double cosView);
    static double cosViewOfColumn(int column);

private:
    std::vector<float> nodes_;
};

}  // namespace mipgloss
