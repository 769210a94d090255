// Lat-long (equirectangular) image -> cube, filtered (the method is described in latlong.cpp and
// docs/latlong-conversion.md; the orientation convention and the public entry points are
// mipgloss/io/latlong.h). Internal to the io library.
#pragma once

#include "decode.h"

namespace mipgloss::io_detail {

// Converts at face size `faceSize`, reporting progress from p0 to p1. Borders are left for the
// caller's makeSeamless.
CubeMap latLongToCube(const Image& img, int faceSize, const Progress& progress, float p0, float p1);

}  // namespace mipgloss::io_detail
