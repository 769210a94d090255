#include "mipgloss/scene/aov_exactness.h"

#include <cmath>
#include <cstddef>

namespace mipgloss {

std::vector<float> withoutMixedPixels(int width, int height, const std::vector<float>& exponent,
                                      const std::vector<float>& exact) {
    std::vector<float> result = exact;
    auto at = [&](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x); };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = at(x, y);
            if (exact[i] == 0.0f) continue;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    const bool inside = nx >= 0 && ny >= 0 && nx < width && ny < height;
                    const float e = inside ? exponent[at(nx, ny)] : 0.0f;
                    if (!(std::abs(e - exponent[i]) <= 0.05f * exponent[i])) result[i] = 0.0f;
                }
        }
    return result;
}

}  // namespace mipgloss
