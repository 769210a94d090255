#include "mipgloss/ibl/irradiance.h"

#include "lobe_filter.h"

#include <algorithm>

namespace mipgloss {

namespace {
// Source texels (32² faces, 2.8° at the face centre) are far below
// the cosine lobe's width (σ ≈ 0.7 rad): the point approximation of the pyramid costs < 1e-4.
constexpr int kMaxSourceSize = 32;
constexpr double kIrradianceCutoff = 1e-7;
}  // namespace

CubeMap computeIrradiance(const CubeMap& base, int outSize) {
    detail::LobeSource src = detail::baseSource(base);
    while (src.size > kMaxSourceSize && src.size % 2 == 0) src = detail::coarsenSource(src);
    // D₁(t) = t/π is the normalized Phong lobe with n = 1, so E(N)/π is that convolution.
    return detail::convolve(src, 1.0, std::min(outSize, base.size()), kIrradianceCutoff);
}

}  // namespace mipgloss
