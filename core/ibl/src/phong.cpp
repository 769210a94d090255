#include "mipgloss/ibl/phong.h"

#include <algorithm>
#include <cmath>

namespace mipgloss {

double lambdaToExponent(double lambda, int baseSize) {
    const double n = static_cast<double>(baseSize);
    return std::max(0.0, 3.0 * n * n * std::exp2(-2.0 * lambda) - 1.0);
}

double exponentToLambda(double exponent, int baseSize) {
    const double n = std::max(0.0, exponent);
    return std::log2(static_cast<double>(baseSize) * std::sqrt(3.0)) - 0.5 * std::log2(n + 1.0);
}

double clampLambda(double lambda, int levelCount) {
    if (std::isnan(lambda)) return 0.0;
    return std::clamp(lambda, 0.0, static_cast<double>(std::max(0, levelCount - 1)));
}

}  // namespace mipgloss
