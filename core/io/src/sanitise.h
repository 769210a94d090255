// The decoded image type and the one sanitising rule for every pixel mipgloss reads, apart from
// the decoder (decode.h) so that the conversions built on them (latlong*.cpp) need no OpenImageIO
// header. Internal to the io library; implemented in decode.cpp.
#pragma once

#include "mipgloss/io/import.h"

#include <cstddef>
#include <span>

namespace mipgloss::io_detail {

// A decoded image: linear float RGB, row 0 at the top (import.h).
using Image = DecodedImage;

struct SanitiseCounts {
    std::size_t nan = 0, inf = 0, negative = 0, huge = 0;
};

// The one sanitising rule for every pixel mipgloss reads (images, face files, cube EXR files):
// NaN -> 0, negative (including -Inf) -> 0, finite values above kMaxRadiance -> kMaxRadiance,
// +Inf -> the largest value left among `px`.
SanitiseCounts sanitise(std::span<Rgb> px);

// The rule in two steps, for data that arrives in pieces: sanitiseFinite fixes NaN and negatives,
// counts +Inf (leaving it) and raises `maxFinite` to the piece's largest finite value;
// replaceInfinities then sets every +Inf to the final `maxFinite`.
SanitiseCounts sanitiseFinite(std::span<Rgb> px, float& maxFinite);
void replaceInfinities(std::span<Rgb> px, float maxFinite);

}  // namespace mipgloss::io_detail
