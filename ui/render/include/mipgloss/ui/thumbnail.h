// Material thumbnails: a sphere with the material, in front of the environment, rendered by the
// same Renderer as the viewport (offscreen.h). Used by the library dock and by
// `mipgloss library thumbnails`.
#pragma once

#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/scene.h"

#include <QImage>

#include <memory>

namespace mipgloss::ui {

class OffscreenRenderer;

// One unit sphere at the origin wearing `material`, the background shown (blurred at λ = 2 so a
// mirror's reflection reads against it), the scene's display defaults otherwise; `settings` is
// the environment it is shown under.
Scene thumbnailScene(const Material& material, const EnvironmentSettings& settings = {});
// The camera that frames thumbnailScene square, looking slightly down.
OrbitCamera thumbnailCamera();
// What thumbnailScene needs of the chain whatever the material (every level a λ can reach), so
// one prepared environment serves every thumbnail.
ChainNeeds thumbnailNeeds(int baseFaceSize);

// Renders `material`'s thumbnail, `size` × `size` pixels, under `environment`.
QImage renderThumbnail(OffscreenRenderer& renderer, const Material& material,
                       const std::shared_ptr<const PreparedEnvironment>& environment, int size);

}  // namespace mipgloss::ui
