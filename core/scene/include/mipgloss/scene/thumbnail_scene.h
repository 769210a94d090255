// What a material thumbnail shows, GL-free: a sphere with the material in front of the
// environment, the camera that frames it, and what it needs of the chain. The pictures are drawn
// by the renderer (ui/render thumbnail.h) for the library dock and `mipgloss library thumbnails`.
#pragma once

#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/chain_needs.h"
#include "mipgloss/scene/scene.h"

namespace mipgloss {

// One unit sphere at the origin wearing `material`, the background shown (blurred at λ = 2 so a
// mirror's reflection reads against it), the scene's display defaults otherwise; `settings` is
// the environment it is shown under.
Scene thumbnailScene(const Material& material, const EnvironmentSettings& settings = {});
// The camera that frames thumbnailScene square, looking slightly down.
OrbitCamera thumbnailCamera();
// What thumbnailScene needs of the chain whatever the material (every level a λ can reach), so
// one prepared environment serves every thumbnail.
ChainNeeds thumbnailNeeds(int baseFaceSize);

}  // namespace mipgloss
