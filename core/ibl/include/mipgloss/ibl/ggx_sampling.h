// How the renderer reads a GGX layer from the one environment (docs/material-truth.md): K
// lookups per layer and fragment, each the exact Phong lobe (the lobe stack) at a light direction
// drawn from GGX's distribution of visible normals, as wide as that direction's share of the
// lobe (filtered importance sampling, Křivánek & Colbert 2008), and the layer's albedo from a
// table so a uniform environment returns exactly the BRDF's. The C++ half of layered.glsl: the
// sample pattern, the lobe each lookup reads (for the stack entries a scene needs) and the table.
//
// In the frame N = z, v = (sin θ, 0, cos θ), sample k of K is the visible normal h_k of
// Heitz 2018 ("Sampling the GGX distribution of visible normals") at (u1, u2) = ((k + ½)/K,
// radical inverse of k), its light l_k = reflect(−v, h_k), with
//     pdf(l) = G1(v)·D(h) / (4 N·v),      weight_k = G2(v, l) / G1(v)  (= f·cos/pdf for F = 1),
// and the lookup's lobe n_k from its share Ω_k = 1/(K·pdf(l_k)) of the sphere: a normalized Phong
// lobe covers 2π/(n + 1) (phong.h), so n_k = 2π·K·pdf(l_k)/kSampleSpread − 1. Fresnel splits the
// sum as the split sum does: F = F0·(1 − (1 − v·h)⁵) + (1 − v·h)⁵, so the layer is
//     F0 ⊙ A(μ, r)·Σ a_k L_k / Σ a_k  +  B(μ, r)·Σ b_k L_k / Σ b_k,
//     a_k = weight_k·(1 − (1 − v·h_k)⁵),  b_k = weight_k·(1 − v·h_k)⁵,
// with A and B the exact single-scattering albedos of the BRDF (GgxAlbedoTable): each layer's
// lookups set the shape, the table its energy.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <span>
#include <string>
#include <vector>

namespace mipgloss {

// The lookups per GGX layer and fragment the renderer makes by default (the bench measures the
// others: `mipgloss bench truth`).
inline constexpr int kGgxLookups = 8;
// How much wider than its share of the sphere each lookup's lobe is (see above): lobes overlap
// their neighbours, so K of them sum to a smooth lobe. Chosen on the `city` map only.
inline constexpr double kSampleSpread = 2.0;

// The smallest N·v the samplers, the tables and the fitted lobes use: the view on the horizon has
// no visible normals; 1e-4 is 0.006° above it.
inline constexpr double kLeastCosView = 1e-4;

// Sample k of `count`: (u1, u2) = ((k + ½)/count, radical inverse base 2 of k).
glm::dvec2 ggxSequence(int k, int count);

struct GgxLookup {
    glm::dvec3 light{0.0, 0.0, 1.0};  // unit, in the frame N = z (zero weight below the horizon)
    double weight = 0.0;              // G2/G1
    double pdf = 0.0;                 // of the light direction (per steradian)
    double fresnelEdge = 0.0;         // (1 − v·h)⁵
};
// Sample `u` of the visible normals at α for the view `view` (unit, frame N = z, view.z > 0).
GgxLookup ggxLookup(double alpha, const glm::dvec3& view, const glm::dvec2& u);
// The lobe a lookup reads: 2π·count·pdf/kSampleSpread − 1, at least 0; ∞ for α = 0.
double lookupExponent(double pdf, int count, double spread = kSampleSpread);
// Where a lookup's lobe reads from (frame N = z): its light, raised toward N until the lobe's
// half-maximum cone (cos^n θ = ½, sin θ½ = √(1 − 2^(−2/n))) is above the horizon. The truth
// integrates over the upper hemisphere only; a lobe about a light near the horizon would average
// in what lies below it (a forest's dark ground under a rough metal: 6–12 % too dark), so it
// reads from the lowest direction whose lobe mostly sees the sky, its azimuth kept. A lobe of
// n = 0 (half-maximum at 90°) reads about N: the clamped cosine about N is the upper hemisphere.
// Measured in docs/material-truth.md ("The horizon").
glm::dvec3 keptAboveHorizon(const glm::dvec3& light, double exponent);

// The sharpest and widest lobe any fragment's lookups read at α (N·v over its range).
struct ExponentRange {
    double sharpest = 0.0, widest = 0.0;
};
ExponentRange lookupExponentRange(double alpha, int count, double spread = kSampleSpread);

// The single-scattering albedos of the glTF specular lobe (F·D·V·cos over the hemisphere) split
// by F0, and the diffuse lobe's Fresnel loss, on a grid of roughness × N·v (N·v columns as
// SplitSumTable's, crowded toward grazing), read bilinearly:
//     A(μ, r) = ∫ (1 − (1 − v·h)⁵) D V cos dω,   B(μ, r) = ∫ (1 − v·h)⁵ D V cos dω,
//     Bd(μ)   = (1/π) ∫ (1 − v·h)⁵ cos dω        (the glTF diffuse is (1 − F0)(1 − Bd) of Lambert's
//                                                 in a uniform environment; no roughness in it).
// Built once per process (VNDF quadrature of 64² stratified samples a node, about 0.1 s).
class GgxAlbedoTable {
public:
    static constexpr int kRoughnessSteps = 33;
    static constexpr int kCosSteps = 65;
    static const GgxAlbedoTable& shared();
    explicit GgxAlbedoTable(int samples);

    struct Albedo {
        double a = 0.0, b = 0.0, diffuseEdge = 0.0;
        // The specular lobe's mean light direction for F = 1, ∫ l·D V cos dω / ∫ D V cos dω, in the
        // frame N = z, v = (sin θ, 0, cos θ): not unit; its length is the lobe's mean cosine about
        // its direction (meanLobe).
        double meanX = 0.0, meanZ = 1.0;
        double specular(double f0) const { return f0 * a + b; }
    };
    Albedo at(double roughness, double cosView) const;
    // The nodes as (A, B, Bd) triples, N·v column fastest: an RGB texture with s from
    // SplitSumTable::columnOfCosView and t = roughness.
    std::span<const float> nodes() const { return nodes_; }
    // The mean light directions (meanX, meanZ) at the same nodes: an RG texture read as nodes().
    std::span<const float> meanNodes() const { return meanNodes_; }

private:
    std::vector<float> nodes_, meanNodes_;
};

// The one Phong lobe with the GGX lobe's first moment (the mean resultant of its light directions,
// Albedo::meanX/meanZ): its direction that mean's, its exponent the one whose mean cosine is its
// length, 1/(n + 2) = 1 − |m| (phong.h: a normalized Phong lobe's mean of 1 − cos θ). A linear
// environment is read exactly by it; a rough layer's whole lobe is nearly a Phong lobe (at α = 1
// GGX's D is uniform over half vectors) and read by it better than by K lookups: measured on the
// CPU model with exact lobes (docs/material-truth.md, "The roughest layers: one lobe"), white metal
// r 1 on seven maps 0.45–1.4 % against K = 8's 3.3–9.8 %; at r 0.6–0.8 it is worse on some.
struct MeanLobe {
    glm::dvec3 direction{0.0, 0.0, 1.0};  // unit, frame N = z, v = (sin θ, 0, cos θ)
    double exponent = 0.0;
};
MeanLobe meanLobe(const GgxAlbedoTable::Albedo& albedo);
// How much of a GGX layer of `roughness` reads its mean lobe instead of its K lookups: 0 up to
// r = 0.8, 1 from 0.9, linear between (both read there, so a slider moves the picture smoothly).
// The range is where the CPU model measured the mean lobe better on every one of seven maps (0.9)
// and worse on half of them (0.8).
inline constexpr double kMeanLobeFrom = 0.8, kMeanLobeAll = 0.9;
double meanLobeShare(double roughness);
// The sharpest and widest mean lobe of a layer of `roughness` over N·v (the table's columns).
ExponentRange meanLobeExponentRange(double roughness);

// Multiple scattering (Fdez-Agüera 2019, "A Multiple-Scattering Microfacet Model for Real-Time
// Image-based Lighting", JCGT 8(1)): single-scattering GGX loses the light that bounces between
// microfacets, 1 − E of it for a white metal (E = A + B, 9 % at r 0.5 head-on, 60 % at r 1 toward
// grazing); compensated, the specular lobe is scaled by 1 + F0·(1 − E)/E, so a white metal keeps
// all its energy and a coloured one gains the F0-tinted share a path tracer's bounces give. Off
// (Single) is the glTF specification's BRDF, the default; the truth follows the same switch
// (material_truth.h).
enum class Scattering { Single, Compensated };
inline constexpr std::array<Scattering, 2> kAllScatterings = {Scattering::Single, Scattering::Compensated};
const char* scatteringName(Scattering scattering);  // "single", "compensated"
bool parseScattering(const std::string& text, Scattering& out);
// What the compensation multiplies a specular lobe of Fresnel F0 by, per channel, for the lobe's
// albedos `e` at its roughness and N·v: 1 + F0·(1 − E)/E compensated, 1 single.
glm::dvec3 scatteringCompensation(const glm::dvec3& f0, const GgxAlbedoTable::Albedo& e, Scattering scattering);

// The same integrals by VNDF quadrature on a samples × samples grid (what the table is built from).
GgxAlbedoTable::Albedo ggxAlbedoIntegral(double roughness, double cosView, int samples);

}  // namespace mipgloss
