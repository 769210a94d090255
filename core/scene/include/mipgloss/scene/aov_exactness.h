// The AOV's rule for pixels that mix lobes (mipgloss render --aov; the renderer's renderAov): a
// pixel is one lobe at one direction only where its neighbours show that lobe too. GL-free, so it
// is tested without a display.
#pragma once
#include <vector>

namespace mipgloss {

// `exact` with every pixel cleared (0) whose 3 × 3 neighbourhood leaves the picture, touches the
// background (exponent 0) or shows another lobe: exponents more than 5 % apart. An infinite
// exponent (a mirror) is never within 5 % of anything, itself included (∞ − ∞ is NaN).
// Both are width × height, row 0 first.
//
// Why 5 %: a pixel beside the background or another lobe is not one lobe at one direction in the
// picture (multisampling mixes them). Neighbours on one surface differ a little (each pixel's
// footprint widens its lobe by its own amount, lobe_stack.glsl): within 5 %, a mix of them is
// within 0.05 % of the lobe between (the stack's own blend of lobes 19 % apart is within 0.6 %),
// so they count as the same lobe.
std::vector<float> withoutMixedPixels(int width, int height, const std::vector<float>& exponent,
                                      const std::vector<float>& exact);

}  // namespace mipgloss
