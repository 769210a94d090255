#include "mipgloss/ibl/ggx_fitted_lobes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace mipgloss {
namespace {

// [roughness row][N·v column][lobe][q1, q2, η, weightA, weightB], written by
// scripts/fit-ggx-lobes.py (its provenance and the fit's objective at every node:
// docs/material-truth.md, "Fitted lobes").
constexpr double kNodes[kFittedRoughnessNodes][kFittedCosNodes][kFittedLobeCount][kFittedLobeValues] = {
#include "ggx_fitted_lobes_table.inc"
};

// Where (roughness, N·v) falls on the grid: row and column coordinates in node units, clamped.
struct GridPoint {
    int row, column;
    double rowWeight, columnWeight;  // of row + 1, column + 1
};
GridPoint gridPoint(double roughness, double cosView) {
    const double theta = std::acos(std::clamp(cosView, 0.0, 1.0));
    const double x = 1.0 - std::sqrt(std::max(0.0, 1.0 - theta / (0.5 * std::numbers::pi)));
    const double c = std::clamp(x, 0.0, 1.0) * (kFittedCosNodes - 1);
    const double r = std::clamp((roughness - kFittedLeastRoughness) / kFittedRoughnessStep, 0.0,
                                static_cast<double>(kFittedRoughnessNodes - 1));
    GridPoint g;
    g.column = std::min(static_cast<int>(c), kFittedCosNodes - 2);
    g.row = std::min(static_cast<int>(r), kFittedRoughnessNodes - 2);
    g.columnWeight = c - g.column;
    g.rowWeight = r - g.row;
    return g;
}

}  // namespace

bool readsFittedLobes(double roughness, int lookups) {
    constexpr double kMost = kFittedLeastRoughness + kFittedRoughnessStep * (kFittedRoughnessNodes - 1);
    // Below the grid's first row (r 0.1) its lobes are read at the layer's α: in α's units GGX's
    // lobe keeps its shape as α → 0 (D(h) depends on tan θ_h / α; only the horizon, α·N·v apart
    // from R at most, moves away), and r 0.1's lobes at r 0.05 are within 1.0–1.3 % of the truth on
    // three maps, where eight visible normals were 8–24 % (docs/material-truth.md, "The
    // near-mirror's tail").
    return lookups == kFittedLobeCount && roughness > 0.0 && roughness <= kMost + 1e-9;
}

std::array<FittedLobe, kFittedLobeCount> fittedLobes(double roughness, double cosView) {
    const GridPoint g = gridPoint(roughness, cosView);
    const double alpha = roughness * roughness;
    const double mu = std::clamp(cosView, kLeastCosView, 1.0), s = std::sqrt(1.0 - mu * mu);
    const glm::dvec3 reflected(-s, 0.0, mu), towardNormal(mu, 0.0, s), across(0.0, 1.0, 0.0);
    std::array<FittedLobe, kFittedLobeCount> out;
    for (int k = 0; k < kFittedLobeCount; ++k) {
        double value[kFittedLobeValues];
        for (int i = 0; i < kFittedLobeValues; ++i) {
            auto at = [&](int row, int column) { return kNodes[row][column][k][i]; };
            const double low = std::lerp(at(g.row, g.column), at(g.row, g.column + 1), g.columnWeight);
            const double high = std::lerp(at(g.row + 1, g.column), at(g.row + 1, g.column + 1), g.columnWeight);
            value[i] = std::lerp(low, high, g.rowWeight);
        }
        FittedLobe& lobe = out[static_cast<std::size_t>(k)];
        lobe.direction = glm::normalize(reflected + alpha * (value[0] * towardNormal + value[1] * across));
        lobe.exponent = alpha > 0.0 ? std::max(std::exp(-value[2]) / (alpha * alpha) - 2.0, 0.0)
                                    : std::numeric_limits<double>::infinity();
        lobe.weightA = value[3];
        lobe.weightB = value[4];
    }
    return out;
}

ExponentRange fittedLobeExponentRange(double roughness) {
    ExponentRange range{0.0, std::numeric_limits<double>::infinity()};
    for (int column = 0; column < kFittedCosNodes; ++column) {
        const double x = static_cast<double>(column) / (kFittedCosNodes - 1);
        const double theta = (1.0 - (1.0 - x) * (1.0 - x)) * 0.5 * std::numbers::pi;
        for (const FittedLobe& lobe : fittedLobes(roughness, std::cos(theta))) {
            if (!(lobe.weightA + lobe.weightB > 0.0)) continue;
            range.sharpest = std::max(range.sharpest, lobe.exponent);
            range.widest = std::min(range.widest, lobe.exponent);
        }
    }
    if (std::isinf(range.widest)) range.widest = range.sharpest;
    return range;
}

double fittedLobeSharpestHeadOn(double roughness) {
    double sharpest = 0.0;
    for (const FittedLobe& lobe : fittedLobes(roughness, 1.0))
        if (lobe.weightA + lobe.weightB > 0.0) sharpest = std::max(sharpest, lobe.exponent);
    return sharpest;
}

std::vector<float> fittedLobeLayers() {
    constexpr std::size_t texels = kFittedCosNodes * kFittedRoughnessNodes;
    std::vector<float> out(texels * 4 * 2 * kFittedLobeCount, 0.0f);
    for (int k = 0; k < kFittedLobeCount; ++k)
        for (int row = 0; row < kFittedRoughnessNodes; ++row)
            for (int column = 0; column < kFittedCosNodes; ++column) {
                const double* v = kNodes[row][column][k];
                const std::size_t texel = static_cast<std::size_t>(row * kFittedCosNodes + column);
                float* shape = &out[(static_cast<std::size_t>(2 * k) * texels + texel) * 4];
                float* weights = &out[(static_cast<std::size_t>(2 * k + 1) * texels + texel) * 4];
                shape[0] = static_cast<float>(v[0]);
                shape[1] = static_cast<float>(v[1]);
                shape[2] = static_cast<float>(v[2]);
                weights[0] = static_cast<float>(v[3]);
                weights[1] = static_cast<float>(v[4]);
            }
    return out;
}

}  // namespace mipgloss
