// Cube comparisons shared by the lat-long tests and benchmarks.
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <algorithm>
#include <cmath>

namespace mipgloss::test {

// Largest per-texel difference relative to max(|b|, 1 % of b's mean), over channels.
inline double maxRelDiff(const CubeMap& a, const CubeMap& b) {
    const glm::dvec3 m = b.weightedMean();
    const double floor = 0.01 * std::max({m.x, m.y, m.z});
    double worst = 0.0;
    for (Face f : kAllFaces)
        for (int y = 0; y < a.size(); ++y)
            for (int x = 0; x < a.size(); ++x)
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::fabs(static_cast<double>(a.at(f, x, y)[c] - b.at(f, x, y)[c])) /
                                                std::max(static_cast<double>(b.at(f, x, y)[c]), floor));
    return worst;
}

}  // namespace mipgloss::test
