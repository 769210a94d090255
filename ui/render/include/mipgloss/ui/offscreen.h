// The same Renderer without a window: an OpenGL 4.1 core context on a QOffscreenSurface and a
// framebuffer object. Needs a QGuiApplication and (with Qt 6.4 on Linux) an X display.
#pragma once

#include "mipgloss/scene/camera.h"
#include "mipgloss/ui/renderer.h"

#include <QImage>

#include <memory>
#include <string>

namespace mipgloss::ui {

class OffscreenRenderer {
public:
    OffscreenRenderer();
    ~OffscreenRenderer();

    // Creates the context; false with `error` when no 4.1 core context can be made.
    bool initialize(std::string* error);

    // Renders `scene` (uploading `environment` if it is not the one drawn last) and returns the
    // tone-mapped sRGB picture.
    QImage render(const Scene& scene, const OrbitCamera& camera,
                  const std::shared_ptr<const PreparedEnvironment>& environment, int width, int height);

    // The lobe stack's entries later renders read lobes from (Renderer::setLobes).
    void setLobes(const std::vector<std::shared_ptr<const LobeStackEntry>>& lobes);
    // The object later renders outline (Renderer::setHighlightedObject); -1 by default.
    void setHighlightedObject(int index);
    // The decoded images later renders' texture maps read (Renderer::setTextures); null by default.
    void setTextures(std::shared_ptr<const TextureCache> textures);

    // The per-pixel account of the same view (Renderer::renderAov).
    AovImage renderAov(const Scene& scene, const OrbitCamera& camera,
                       const std::shared_ptr<const PreparedEnvironment>& environment, int width, int height);

    // The linear HDR colour of the last render (RGBA, bottom row first); see Renderer::readHdr.
    std::vector<glm::vec4> lastHdr(int& width, int& height);

    const RenderCounters& counters() const;
    std::string glDescription() const;
    // What this context can draw (Renderer::maxRenderSize); zeros before initialize().
    RenderSizeLimits maxRenderSize() const;
    // Blocks until the GPU has finished (for timing).
    void finish();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mipgloss::ui
