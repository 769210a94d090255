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

// What the rule did, with the energy (the sum of all values, channels added) each part changed.
struct SanitiseCounts {
    std::size_t nan = 0, inf = 0, negative = 0, huge = 0;
    double energy = 0.0;         // the sanitised pixels' sum
    double infAdded = 0.0;       // what +Inf became
    double negativeMoved = 0.0;  // the negatives' magnitude taken from their row neighbours
    double negativeAdded = 0.0;  // the part no neighbour could give: added by the clamp
    double hugeRemoved = 0.0;    // what lowering values above kMaxRadiance took away
    SanitiseCounts& operator+=(const SanitiseCounts& other);
};

// The one sanitising rule for every pixel mipgloss reads (images, face files, cube EXR files),
// row by row (`px` is whole rows of `width`), so a strip can be sanitised alone (docs/conventions.md):
// - NaN -> 0;
// - finite values above kMaxRadiance -> kMaxRadiance;
// - a run of +Inf -> the mean of the finite values bordering it in its row (0 if none);
// - a negative value -> 0, its magnitude taken from the nearest positive values in its row, half
//   from each side, so the row keeps its energy; −Inf -> 0.
// Throws std::invalid_argument if `px` is not whole rows.
SanitiseCounts sanitiseRows(std::span<Rgb> px, int width);

}  // namespace mipgloss::io_detail
