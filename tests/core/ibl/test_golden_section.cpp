// goldenSectionMinimum (metrics.h), the search the exponent fits use: on functions whose minimum
// is known, the bracket's midpoint lands within the tolerance, in the number of steps the
// shrinking by φ = (√5 − 1)/2 predicts.
#include "mipgloss/ibl/metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mipgloss {
namespace {

TEST(GoldenSection, FindsAParabolasVertexWithinTheTolerance) {
    const double found = goldenSectionMinimum([](double x) { return (x - 1.3) * (x - 1.3); }, -4.0, 6.0, 1e-6);
    EXPECT_NEAR(found, 1.3, 1e-6);
}

TEST(GoldenSection, FindsAnAsymmetricMinimumNearTheBracketsEdge) {
    // |x − 0.05| + 0.1·x² has its minimum at 0.05 (the kink), just inside [0, 10].
    const double found =
        goldenSectionMinimum([](double x) { return std::abs(x - 0.05) + 0.1 * x * x; }, 0.0, 10.0, 1e-5);
    EXPECT_NEAR(found, 0.05, 1e-5);
}

TEST(GoldenSection, StopsAfterMaxStepsWithTheBracketShrunkByPhiPerStep) {
    // Evaluations: two to start, one per step. After k steps the bracket is (b − a)·φ^k wide.
    int evaluations = 0;
    const double found = goldenSectionMinimum(
        [&](double x) {
            ++evaluations;
            return (x - 2.0) * (x - 2.0);
        },
        0.0, 10.0, 0.0, 18);
    EXPECT_EQ(evaluations, 2 + 18);
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    EXPECT_NEAR(found, 2.0, 0.5 * 10.0 * std::pow(phi, 18) + 1e-12);
}

}  // namespace
}  // namespace mipgloss
