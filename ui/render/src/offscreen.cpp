#include "mipgloss/ui/offscreen.h"

#include "mipgloss/ui/gl_format.h"

#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QOpenGLFunctions>

namespace mipgloss::ui {

struct OffscreenRenderer::Impl {
    QOffscreenSurface surface;
    QOpenGLContext context;
    std::unique_ptr<QOpenGLFramebufferObject> fbo;
    Renderer renderer;
    bool ready = false;

    ~Impl() {
        if (ready && context.makeCurrent(&surface)) {
            fbo.reset();
            renderer.destroy();
            context.doneCurrent();
        }
    }
};

OffscreenRenderer::OffscreenRenderer() : impl_(std::make_unique<Impl>()) {}
OffscreenRenderer::~OffscreenRenderer() = default;

bool OffscreenRenderer::initialize(std::string* error) {
    Impl& d = *impl_;
    const QSurfaceFormat format = surfaceFormat();
    d.surface.setFormat(format);
    d.surface.create();
    d.context.setFormat(format);
    if (!d.surface.isValid() || !d.context.create() || !d.context.makeCurrent(&d.surface)) {
        if (error) *error = "cannot create an OpenGL 4.1 core context (is there an X display?)";
        return false;
    }
    if (!d.renderer.initialize(error)) return false;
    d.ready = true;
    return true;
}

QImage OffscreenRenderer::render(const Scene& scene, const OrbitCamera& camera,
                                 const std::shared_ptr<const PreparedEnvironment>& environment,
                                 int width, int height) {
    Impl& d = *impl_;
    if (!d.ready || !d.context.makeCurrent(&d.surface)) return {};
    if (!d.fbo || d.fbo->width() != width || d.fbo->height() != height) {
        QOpenGLFramebufferObjectFormat format;
        format.setInternalTextureFormat(GL_RGBA8);
        d.fbo = std::make_unique<QOpenGLFramebufferObject>(width, height, format);
    }
    d.renderer.setEnvironment(environment);
    d.renderer.render(scene, camera, width, height, d.fbo->handle());
    return d.fbo->toImage(true).convertToFormat(QImage::Format_RGB32);
}

void OffscreenRenderer::setHighlightedObject(int index) { impl_->renderer.setHighlightedObject(index); }

void OffscreenRenderer::setTextures(std::shared_ptr<const TextureCache> textures) {
    impl_->renderer.setTextures(std::move(textures));
}

void OffscreenRenderer::setLobes(const std::vector<std::shared_ptr<const LobeStackEntry>>& lobes) {
    if (!impl_->ready || !impl_->context.makeCurrent(&impl_->surface)) return;
    impl_->renderer.setLobes(lobes);
}

AovImage OffscreenRenderer::renderAov(const Scene& scene, const OrbitCamera& camera,
                                      const std::shared_ptr<const PreparedEnvironment>& environment, int width,
                                      int height) {
    Impl& d = *impl_;
    if (!d.ready || !d.context.makeCurrent(&d.surface)) return {};
    d.renderer.setEnvironment(environment);
    return d.renderer.renderAov(scene, camera, width, height);
}

std::vector<glm::vec4> OffscreenRenderer::lastHdr(int& width, int& height) {
    if (!impl_->ready || !impl_->context.makeCurrent(&impl_->surface)) {
        width = height = 0;
        return {};
    }
    return impl_->renderer.readHdr(width, height);
}

const RenderCounters& OffscreenRenderer::counters() const { return impl_->renderer.counters(); }

std::string OffscreenRenderer::glDescription() const {
    if (!impl_->ready || !impl_->context.makeCurrent(&impl_->surface)) return "no OpenGL";
    return impl_->renderer.glDescription();
}

RenderSizeLimits OffscreenRenderer::maxRenderSize() const {
    if (!impl_->ready || !impl_->context.makeCurrent(&impl_->surface)) return {};
    return impl_->renderer.maxRenderSize();
}

void OffscreenRenderer::finish() {
    if (impl_->ready && impl_->context.makeCurrent(&impl_->surface)) impl_->context.functions()->glFinish();
}

}  // namespace mipgloss::ui
