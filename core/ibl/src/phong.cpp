#include "mipgloss/ibl/phong.h"

#include "mipgloss/ibl/cubemap.h"

#include <algorithm>
#include <cmath>

namespace mipgloss {

namespace {
double solidAngleExponent(double lambda, int size) {
    const double n = static_cast<double>(size);
    return std::max(0.0, 3.0 * n * n * std::exp2(-2.0 * lambda) - 1.0);
}
}  // namespace

double lambdaToExponent(double lambda) {
    if (std::isnan(lambda)) return lambda;
    if (lambda <= 0.0) return kMirrorExponent;
    return solidAngleExponent(lambda, kLambdaReferenceSize);
}

double exponentToLambda(double exponent) {
    if (std::isnan(exponent)) return exponent;
    if (std::isinf(exponent) && exponent > 0.0) return 0.0;
    const double n = std::max(0.0, exponent);
    const double lambda = std::log2(kLambdaReferenceSize * std::sqrt(3.0)) - 0.5 * std::log2(n + 1.0);
    return std::max(0.0, lambda);
}

double legacyLambdaToExponent(double lambda, int baseSize) {
    if (std::isnan(lambda)) return lambda;
    if (lambda <= 0.0) return kMirrorExponent;
    return solidAngleExponent(lambda, std::max(baseSize, 1));
}

bool isValidLambda(double lambda) { return std::isfinite(lambda) && lambda >= 0.0 && lambda <= kMaxLambda; }

bool isValidExponent(double exponent) {
    return exponent >= 0.0 && (std::isfinite(exponent) || exponent == kMirrorExponent);
}

int lastReadLevel(int baseSize) {
    if (baseSize < 16) return 0;
    int k = 0;
    while (levelSize(baseSize, k) >= 16) ++k;
    return k;  // the first level with a face of 8..15 texels
}

double levelExponent(int baseSize, int level) {
    if (level <= 0) return kMirrorExponent;
    const int last = lastReadLevel(baseSize);
    if (level > last) return std::numeric_limits<double>::quiet_NaN();
    if (level == last) return 1.0;
    const double m = static_cast<double>(levelSize(baseSize, level));
    return m * m / 32.0;
}

namespace {
// The lobe's mean cosine, its band-1 factor: the quantity a two-level blend matches (phong.h).
double meanCosine(double n) { return std::isinf(n) ? 1.0 : (n + 1.0) / (n + 2.0); }
}  // namespace

double chainLevelForExponent(double exponent, int baseSize) {
    const int last = lastReadLevel(baseSize);
    if (last == 0 || std::isnan(exponent) || exponent >= kMirrorExponent) return 0.0;
    if (exponent <= 1.0) return static_cast<double>(last);
    const double target = meanCosine(exponent);
    for (int k = 0; k < last; ++k) {
        const double hi = meanCosine(levelExponent(baseSize, k)), lo = meanCosine(levelExponent(baseSize, k + 1));
        if (target >= lo) return k + (hi - target) / (hi - lo);
    }
    return static_cast<double>(last);
}

double regularScheduleLevel(double lambda, int baseSize) {
    return lambda + std::log2(std::max(baseSize, 1) / 128.0) - 0.5 * std::log2(96.0);
}

double exponentForChainLevel(double lod, int baseSize) {
    const int last = lastReadLevel(baseSize);
    if (std::isnan(lod)) return lod;
    if (lod <= 0.0 || last == 0) return kMirrorExponent;
    if (lod >= last) return 1.0;
    const int k = static_cast<int>(std::floor(lod));
    const double hi = meanCosine(levelExponent(baseSize, k)), lo = meanCosine(levelExponent(baseSize, k + 1));
    const double target = hi - (lod - k) * (hi - lo);
    return (2.0 * target - 1.0) / (1.0 - target);
}

}  // namespace mipgloss
