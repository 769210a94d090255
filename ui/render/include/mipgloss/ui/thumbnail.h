// Material thumbnails: a sphere with the material, in front of the environment (what it shows is
// core's, thumbnail_scene.h), rendered by the same Renderer as the viewport (offscreen.h). Used by the library dock and by
// `mipgloss library thumbnails`.
#pragma once

#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/thumbnail_scene.h"

#include <QImage>

#include <memory>

namespace mipgloss {
class TextureCache;  // mipgloss/assets/textures.h
}

namespace mipgloss::ui {

class OffscreenRenderer;

// Renders `material`'s thumbnail (thumbnailScene and thumbnailCamera, mipgloss/scene/
// thumbnail_scene.h), `size` × `size` pixels, under `environment`. Its texture maps are decoded
// into `textures` (the caller's: one per thumbnail cache or command; null draws them missing),
// which the renderer then reads.
QImage renderThumbnail(OffscreenRenderer& renderer, const std::shared_ptr<TextureCache>& textures,
                       const Material& material, const std::shared_ptr<const PreparedEnvironment>& environment,
                       int size);

}  // namespace mipgloss::ui
