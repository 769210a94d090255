#include "mipgloss/ui/thumbnail.h"

#include "mipgloss/assets/textures.h"

#include "mipgloss/ui/offscreen.h"

namespace mipgloss::ui {

QImage renderThumbnail(OffscreenRenderer& renderer, const std::shared_ptr<TextureCache>& textures,
                       const Material& material, const std::shared_ptr<const PreparedEnvironment>& environment,
                       int size) {
    const Scene scene = thumbnailScene(material, environment ? environment->settings : EnvironmentSettings{});
    // A textured material's maps, decoded once for every thumbnail the caller's cache serves
    // (textures.h); one that cannot be read leaves its map out, as in the view.
    if (textures) textures->load(texturesOf(scene));
    renderer.setTextures(textures);
    return renderer.render(scene, thumbnailCamera(), environment, size, size);
}

}  // namespace mipgloss::ui
