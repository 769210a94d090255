// The reads-between-texel-centres check the ibl (analytic fields) and io (real HDRIs) tests share:
// every read level of the default chain, read as the GPU reads it at uniform directions, against
// the exact lobe there (docs/chain-schedule.md).
#pragma once

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mipgloss::test {

// Directions per level: the exact reference costs a sum over the lobe's support per direction,
// the whole hemisphere for n <= 8, whose smooth fields 300 directions already sample densely.
inline int readDirectionCount(double n) { return n >= 64.0 ? 1500 : n > 8.0 ? 600 : 300; }

// The default chain reads within 2 % of the declared lobe at every read level k >= 1 of `base`,
// and the box chain (the paper's, at the same levels) reads more than 3× worse.
inline void expectReadsBetweenCentres(const CubeMap& base, const std::string& label) {
    const int size = base.size();
    const MipChain phong = buildPhongChain(base);
    const MipChain box = buildBoxChain(base);
    ASSERT_GE(lastReadLevel(size), 1) << label;
    for (int k = 1; k <= lastReadLevel(size); ++k) {
        SCOPED_TRACE(label + " base " + std::to_string(size) + " level " + std::to_string(k));
        const double n = levelExponent(size, k);
        const auto dirs = uniformDirections(readDirectionCount(n));
        const std::vector<Rgb> truth = referenceLobeAt(base, n, dirs);
        const double err = relativeRms(readChain(phong, k, dirs), truth);
        const double boxErr = relativeRms(readChain(box, k, dirs), truth);
        EXPECT_LE(err, 0.02);
        // The old schedule's problem is real: the box chain at the same level is no Phong lobe.
        EXPECT_GT(boxErr, 3.0 * err);
    }
}

}  // namespace mipgloss::test
