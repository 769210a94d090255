// Colour conventions, in one place (docs/conventions.md, "Colour"): everything inside mipgloss is
// linear Rec. 709 RGB. sRGB-encoded values (8- and 16-bit images, the tint swatch in the material
// panel) are decoded on the way in and encoded on the way out with the exact IEC 61966-2-1
// transfer functions below; luminance is Rec. 709's.
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <cmath>

namespace mipgloss {

// The sRGB EOTF: encoded value in [0, 1] -> linear.
inline double srgbToLinear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// Its inverse: linear value in [0, 1] -> encoded.
inline double linearToSrgb(double linear) {
    return linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// Luminance of a linear Rec. 709 colour.
inline double luminance(const Rgb& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The largest finite IEEE half float: what a half-float file, texture or render target can hold.
// Every writer and upload that stores half clamps to it (cube EXR, DDS, the renderer's uploads).
inline constexpr float kHalfMax = 65504.0f;

}  // namespace mipgloss
