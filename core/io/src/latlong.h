// Lat-long (equirectangular) image -> cube, filtered (the quadrature is described in latlong.cpp;
// the orientation convention is mipgloss/io/latlong.h). Internal to the io library.
#pragma once

#include "decode.h"

namespace mipgloss::io_detail {

// Converts at face size `faceSize`, reporting progress from p0 to p1.
CubeMap latLongToCube(const Image& img, int faceSize, const Progress& progress, float p0, float p1);

}  // namespace mipgloss::io_detail
