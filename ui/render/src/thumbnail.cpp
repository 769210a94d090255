#include "mipgloss/ui/thumbnail.h"

#include "mipgloss/ui/offscreen.h"

namespace mipgloss::ui {

QImage renderThumbnail(OffscreenRenderer& renderer, const Material& material,
                       const std::shared_ptr<const PreparedEnvironment>& environment, int size) {
    const Scene scene = thumbnailScene(material, environment ? environment->settings : EnvironmentSettings{});
    return renderer.render(scene, thumbnailCamera(), environment, size, size);
}

}  // namespace mipgloss::ui
