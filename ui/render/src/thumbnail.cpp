#include "mipgloss/ui/thumbnail.h"

#include "mipgloss/scene/textures.h"

#include "mipgloss/ui/offscreen.h"

namespace mipgloss::ui {

QImage renderThumbnail(OffscreenRenderer& renderer, const Material& material,
                       const std::shared_ptr<const PreparedEnvironment>& environment, int size) {
    const Scene scene = thumbnailScene(material, environment ? environment->settings : EnvironmentSettings{});
    // A textured material's maps, decoded once for every thumbnail and view that shows them
    // (textures.h); one that cannot be read leaves its map out, as in the view.
    sharedTextureCache().load(texturesOf(scene));
    return renderer.render(scene, thumbnailCamera(), environment, size, size);
}

}  // namespace mipgloss::ui
