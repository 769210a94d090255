// Issue 24, item 6 ("any radiance"): a held-out HDRI at any absolute scale, with or without a
// one-pixel sun, written as a float EXR so that it goes through the whole import (decode,
// sanitising, lat-long conversion), and the sun's energy computed analytically. Shared by the core
// tests (chain levels, stack entries) and the render tests (the picture).
#pragma once

#include "mipgloss/io/image_file.h"
#include "mipgloss/io/import.h"
#include "test_support.h"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

namespace mipgloss::test {

// The map: tests/assets/env/city.exr (1024×512), tuned by no other accuracy test.
inline std::filesystem::path rangeMapAsset() { return asset("env/city.exr"); }

// The sun's pixel, above the horizon, away from the poles and the seam.
inline constexpr int kSunX = 300, kSunY = 150;

// The exact solid angle of the sun's pixel in a W×H lat-long: (2π/W)(cos θ0 − cos θ1).
inline double sunSolidAngle(int width, int height) {
    const double pi = std::numbers::pi;
    const double theta0 = pi * kSunY / height, theta1 = pi * (kSunY + 1) / height;
    return 2.0 * pi / width * (std::cos(theta0) - std::cos(theta1));
}

// The map times `scale` (`keepMap` false: black), with pixel (kSunX, kSunY) set to `sun` when sun > 0,
// written to `file` as 32-bit float. Returns the pixel's solid angle.
inline double writeRangeMap(const std::filesystem::path& file, double scale, float sun, bool keepMap = true) {
    const DecodedImage map = decodeImage(rangeMapAsset());
    std::vector<float> values;
    values.reserve(map.px.size() * 3);
    for (const Rgb& p : map.px)
        for (int c = 0; c < 3; ++c) values.push_back(keepMap ? static_cast<float>(p[c] * scale) : 0.0f);
    if (sun > 0.0f)
        for (int c = 0; c < 3; ++c)
            values[(static_cast<std::size_t>(kSunY) * static_cast<std::size_t>(map.width) + kSunX) * 3 + c] = sun;
    writeFloatChannels(file, map.width, map.height, {"R", "G", "B"}, values);
    return sunSolidAngle(map.width, map.height);
}

}  // namespace mipgloss::test
