// Material thumbnails: a sphere with the material, in front of the environment (what it shows is
// core's, thumbnail_scene.h), rendered by the same Renderer as the viewport (offscreen.h). Used by the library dock and by
// `mipgloss library thumbnails`.
#pragma once

#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/thumbnail_scene.h"

#include <QImage>

#include <memory>

namespace mipgloss::ui {

class OffscreenRenderer;

// Renders `material`'s thumbnail (thumbnailScene and thumbnailCamera, mipgloss/scene/
// thumbnail_scene.h), `size` × `size` pixels, under `environment`.
QImage renderThumbnail(OffscreenRenderer& renderer, const Material& material,
                       const std::shared_ptr<const PreparedEnvironment>& environment, int size);

}  // namespace mipgloss::ui
