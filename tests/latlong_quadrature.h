// The lat-long conversion mipgloss used before, a gathered stratified quadrature (each texel
// visits the strata in a conservative (θ, φ) box around it): the same definition of a texel as
// latLongToCube (mipgloss/io/latlong.h), 10–1000× slower. Only the tests and the benchmark use it,
// as the reference they compare latLongToCube with.
#pragma once

#include "mipgloss/io/latlong.h"

namespace mipgloss {

CubeMap latLongToCubeQuadrature(const LatLongView& image, int faceSize);

}  // namespace mipgloss
