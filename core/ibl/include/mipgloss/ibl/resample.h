// Cube -> cube at another face size, keeping the solid-angle weighted mean.
#pragma once

#include "mipgloss/ibl/cubemap.h"

namespace mipgloss {

// Resamples a cube to another face size. Shrinking: each texel is the exact solid-angle weighted
// mean of the source texels under its footprint (partial texels weighted by the solid angle of
// the overlap), so the weighted mean is kept. Growing: bilinear through CubeMap::sample, so
// samples near an edge see the neighbouring face. The same size returns a copy.
CubeMap resampleCube(const CubeMap& cube, int size);

}  // namespace mipgloss
