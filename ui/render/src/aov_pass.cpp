// The AOV pass (Renderer::renderAov): the view drawn once more with aov.frag into seven float
// targets, read back into an AovImage.
#include "renderer_impl.h"

#include "mipgloss/scene/aov_exactness.h"
#include "mipgloss/scene/bounds.h"

#include <glm/geometric.hpp>

namespace mipgloss::ui {

AovImage Renderer::renderAov(const Scene& scene, const OrbitCamera& camera, int width, int height) {
    Impl& d = *impl_;
    AovImage aov;
    if (!d.gl || width <= 0 || height <= 0 || !hasEnvironment()) return aov;
    auto* gl = d.gl;
    d.collectMeshes();
    d.collectMapTextures(scene);
    // A single-sample float target of aov.frag's seven colours and depth, made for this call.
    constexpr int kTargets = 7;
    GLuint fbo = 0, colour[kTargets] = {}, depth = 0;
    gl->glGenFramebuffers(1, &fbo);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->glGenTextures(kTargets, colour);
    for (int i = 0; i < kTargets; ++i) {
        gl->glBindTexture(GL_TEXTURE_2D, colour[i]);
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), GL_TEXTURE_2D,
                                   colour[i], 0);
    }
    gl->glGenRenderbuffers(1, &depth);
    gl->glBindRenderbuffer(GL_RENDERBUFFER, depth);
    gl->glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    GLenum buffers[kTargets];
    for (int i = 0; i < kTargets; ++i) buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    gl->glDrawBuffers(kTargets, buffers);
    gl->glViewport(0, 0, width, height);
    gl->glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthFunc(GL_LESS);
    gl->glDepthMask(GL_TRUE);
    gl->glDisable(GL_CULL_FACE);

    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const glm::mat4 viewProjection = camera.projection(aspect, sceneBounds(scene)) * camera.view();
    gl->glActiveTexture(GL_TEXTURE0 + unitIndex(TextureUnit::Irradiance));
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.irradianceTexture);
    gl->glBindSampler(unitIndex(TextureUnit::Irradiance), 0);
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.environmentTexture);
    d.drawAllObjects(true, Renderer::Impl::ObjectSet::All, scene, camera.position(), viewProjection,
                     environmentRotation(scene.display.environmentRotationDegrees),
                     Frustum::fromViewProjection(viewProjection));
    gl->glBindSampler(unitIndex(TextureUnit::Chain), 0);

    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<std::vector<glm::vec4>> targets(kTargets, std::vector<glm::vec4>(count));
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    for (int i = 0; i < kTargets; ++i) {
        gl->glReadBuffer(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
        gl->glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, targets[static_cast<std::size_t>(i)].data());
    }
    const std::vector<glm::vec4>& first = targets[0];
    const std::vector<glm::vec4>& second = targets[1];
    gl->glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->glDeleteFramebuffers(1, &fbo);
    gl->glDeleteTextures(kTargets, colour);
    gl->glDeleteRenderbuffers(1, &depth);

    aov.width = width;
    aov.height = height;
    aov.direction.resize(count);
    aov.exponent.resize(count);
    aov.exact.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        aov.direction[i] = glm::vec3(first[i]);
        aov.exponent[i] = first[i].w;
        aov.exact[i] = second[i].x;
    }
    aov.cosView.resize(count);
    for (std::size_t i = 0; i < count; ++i) aov.cosView[i] = targets[3][i].w;
    for (const SceneObject& object : scene.objects)
        aov.layered = aov.layered || (object.visible && object.mesh && scene.materialOf(object).layered);
    if (aov.layered) {
        auto fill = [&](AovImage::Layer& layer, const std::vector<glm::vec4>& directions,
                        const std::vector<glm::vec4>* exponents, const std::vector<glm::vec4>& weights) {
            layer.direction.resize(count);
            layer.exponent.resize(count);
            layer.weight.resize(count);
            for (std::size_t i = 0; i < count; ++i) {
                layer.direction[i] = glm::vec3(directions[i]);
                layer.exponent[i] = exponents ? (*exponents)[i].w : 0.0f;
                layer.weight[i] = glm::vec3(weights[i]);
            }
        };
        fill(aov.diffuse, targets[2], &targets[2], targets[3]);
        fill(aov.specular, targets[0], nullptr, targets[4]);
        fill(aov.coat, targets[5], &targets[5], targets[6]);
        // The specular layer's lobe where the pixel is layered (its weight is set), else 0.
        for (std::size_t i = 0; i < count; ++i)
            if (aov.diffuse.exponent[i] != 0.0f) aov.specular.exponent[i] = first[i].w;
    }
    // Pixels mixing lobes (multisampling, the background) are not exact (aov_exactness.h).
    aov.exact = withoutMixedPixels(width, height, aov.exponent, aov.exact);
    return aov;
}

// Central differences, one-sided at the object's edge, none where neither neighbour is on it
// (a rasterizer's dFdx/dFdy come from the same neighbours).
PixelGeometry aovPixelGeometry(const AovImage& aov, std::size_t i) {
    const auto normalAt = [&](std::size_t k) { return glm::normalize(glm::dvec3(aov.diffuse.direction[k])); };
    const auto viewAt = [&](std::size_t k) {
        const glm::dvec3 n = normalAt(k), r = glm::normalize(glm::dvec3(aov.direction[k]));
        return glm::normalize(2.0 * glm::dot(n, r) * n - r);
    };
    const int w = aov.width, h = aov.height;
    const int x = static_cast<int>(i % static_cast<std::size_t>(w)), y = static_cast<int>(i / static_cast<std::size_t>(w));
    const auto on = [&](int px, int py) {
        return px >= 0 && py >= 0 && px < w && py < h &&
               aov.exponent[static_cast<std::size_t>(py) * static_cast<std::size_t>(w) + static_cast<std::size_t>(px)] != 0.0f;
    };
    const auto index = [&](int px, int py) { return static_cast<std::size_t>(py) * static_cast<std::size_t>(w) + static_cast<std::size_t>(px); };
    PixelGeometry g;
    g.n = normalAt(i);
    g.v = viewAt(i);
    const auto change = [&](int ax, int ay, glm::dvec3& dn, glm::dvec3& dv) {
        const bool ahead = on(x + ax, y + ay), behind = on(x - ax, y - ay);
        if (ahead && behind) {
            dn = 0.5 * (normalAt(index(x + ax, y + ay)) - normalAt(index(x - ax, y - ay)));
            dv = 0.5 * (viewAt(index(x + ax, y + ay)) - viewAt(index(x - ax, y - ay)));
        } else if (ahead) {
            dn = normalAt(index(x + ax, y + ay)) - g.n;
            dv = viewAt(index(x + ax, y + ay)) - g.v;
        } else if (behind) {
            dn = g.n - normalAt(index(x - ax, y - ay));
            dv = g.v - viewAt(index(x - ax, y - ay));
        }
    };
    change(1, 0, g.dndx, g.dvdx);
    change(0, 1, g.dndy, g.dvdy);
    return g;
}

}  // namespace mipgloss::ui
