// The camera that shows a whole scene: used by offscreen renders, the command line and the tests,
// and by the window's "frame all".
#pragma once

#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/scene.h"

namespace mipgloss {

// Frames every visible object of the scene for an image of this aspect (width / height).
OrbitCamera framingCamera(const Scene& scene, float aspect);

}  // namespace mipgloss
