// The CPU model of a held GGX layer's fitted lobes as object.frag's readGgx reads them
// (ggx_fitted_lobes.h), each lobe the exact normalized Phong lobe over the base faces
// (referenceLobeAt) instead of the lobe stack's entry: what the fit gives apart from the GPU.
// Shared by the lookups' tests (test_ggx_lookups.cpp) and mipgloss_replay_truth_dump.
#pragma once

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/ggx_fitted_lobes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mipgloss::test {

// readGgx's frame: t toward v in the tangent plane, b = N × t, and v in it, (sin θ, 0, cos θ).
struct LayerFrame {
    glm::dvec3 t, b, n;
    glm::dvec3 local;  // v in the frame N = z
};

inline LayerFrame layerFrameOf(const glm::dvec3& n, const glm::dvec3& v) {
    const double mu = std::clamp(glm::dot(n, v), 1e-4, 1.0);
    glm::dvec3 t = v - mu * n;
    const double tl = glm::length(t);
    t = tl > 1e-9 ? t / tl : glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    return {t, glm::cross(n, t), n, glm::dvec3(std::sqrt(1 - mu * mu), 0, mu)};
}

// The fitted lobes' weighted mean of `base` (green) at normal n, view v: what the albedo table's
// A + B multiplies.
inline double fittedLobesMean(const CubeMap& base, double roughness, const glm::dvec3& n, const glm::dvec3& v) {
    const LayerFrame f = layerFrameOf(n, v);
    double sum = 0.0, weights = 0.0;
    for (const FittedLobe& lobe : fittedLobes(roughness, glm::dot(n, v))) {
        const glm::dvec3 l = lobe.direction.x * f.t + lobe.direction.y * f.b + lobe.direction.z * f.n;
        const double w = lobe.weightA + lobe.weightB;
        sum += w * referenceLobeAt(base, lobe.exponent, {glm::vec3(l)}, 1e-6)[0].g;
        weights += w;
    }
    return weights > 0.0 ? sum / weights : 0.0;
}

}  // namespace mipgloss::test
