#include "mipgloss/scene/framing.h"

namespace mipgloss {

OrbitCamera framingCamera(const Scene& scene, float aspect) {
    OrbitCamera camera;
    camera.frame(sceneBounds(scene), aspect);
    return camera;
}

}  // namespace mipgloss
