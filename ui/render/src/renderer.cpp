// The renderer's frame (renderer.h): initialise, environment and lobe uploads, and render(), which
// composes the object pass (object_pass.cpp), the background, the outline (outline_pass.cpp) and
// the tone pass over the GPU resources (gpu_resources.cpp).
#include "renderer_impl.h"

#include "shaders.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/lobes.h"

#include <QOpenGLContext>
#include <QOpenGLVersionFunctionsFactory>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace mipgloss::ui {

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

const RenderCounters& Renderer::counters() const { return impl_->counters; }
bool Renderer::isInitialized() const { return impl_->gl != nullptr; }
bool Renderer::hasEnvironment() const { return impl_->environmentTexture != 0 && impl_->environment; }

bool Renderer::initialize(std::string* error) {
    QOpenGLContext* context = QOpenGLContext::currentContext();
    if (!context) {
        if (error) *error = "no current OpenGL context";
        return false;
    }
    const QSurfaceFormat format = context->format();
    if (format.version() < qMakePair(4, 1)) {
        if (error)
            *error = "OpenGL 4.1 core is needed, the context has " +
                     std::to_string(format.majorVersion()) + "." + std::to_string(format.minorVersion());
        return false;
    }
    impl_->gl = QOpenGLVersionFunctionsFactory::get<QOpenGLFunctions_4_1_Core>(context);
    if (!impl_->gl || !impl_->gl->initializeOpenGLFunctions()) {
        impl_->gl = nullptr;
        if (error) *error = "cannot resolve the OpenGL 4.1 core functions";
        return false;
    }
    const QString objectVert = QStringLiteral("object.vert"), fullscreenVert = QStringLiteral("fullscreen.vert");
    impl_->objectProgram = buildProgram(objectVert, QStringLiteral("object.frag"), error);
    impl_->backgroundProgram = buildProgram(fullscreenVert, QStringLiteral("background.frag"), error);
    impl_->toneProgram = buildProgram(fullscreenVert, QStringLiteral("tonemap.frag"), error);
    impl_->aovProgram = buildProgram(objectVert, QStringLiteral("aov.frag"), error);
    impl_->outlineProgram = buildProgram(QStringLiteral("outline.vert"), QStringLiteral("outline.frag"), error);
    impl_->objectLayeredProgram = buildProgram(objectVert, QStringLiteral("object.frag"), error, "#define LAYERED\n");
    impl_->aovLayeredProgram = buildProgram(objectVert, QStringLiteral("aov.frag"), error, "#define LAYERED\n");
    impl_->objectMapsProgram =
        buildProgram(objectVert, QStringLiteral("object.frag"), error, "#define LAYERED\n#define MATERIAL_MAPS\n");
    impl_->aovMapsProgram = buildProgram(objectVert, QStringLiteral("aov.frag"), error, "#define LAYERED\n#define MATERIAL_MAPS\n");
    if (!impl_->objectProgram || !impl_->backgroundProgram || !impl_->toneProgram || !impl_->aovProgram ||
        !impl_->outlineProgram || !impl_->objectMapsProgram || !impl_->aovMapsProgram || !impl_->objectLayeredProgram ||
        !impl_->aovLayeredProgram) {
        impl_->gl = nullptr;
        return false;
    }
    auto* gl = impl_->gl;
    gl->glGenVertexArrays(1, &impl_->emptyVao);
    // Filtering across cube faces (the paper's seams, §5) is the GPU's job from here on.
    gl->glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    gl->glGenTextures(1, &impl_->environmentTexture);
    gl->glGenTextures(1, &impl_->mirrorTexture);
    gl->glGenTextures(1, &impl_->irradianceTexture);
    for (int j = 0; j < kStackSlots; ++j)
        impl_->stackExponents[static_cast<std::size_t>(j)] = j == 0 ? 3.0e38f : static_cast<float>(stackExponent(j));
    // The atlas: read at its base level only, bilinear; each face's border holds what lies beyond
    // its edge, so no read leaves its face's block.
    gl->glGenTextures(1, &impl_->stackTexture);
    gl->glBindTexture(GL_TEXTURE_2D, impl_->stackTexture);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB9_E5, 1, 1, 0, GL_RGB, GL_FLOAT, nullptr);
    return true;
}

void Renderer::destroy() {
    Impl& d = *impl_;
    if (!d.gl) return;
    for (auto& [mesh, g] : d.meshes) d.releaseMesh(g);
    d.meshes.clear();
    for (auto& [key, t] : d.mapTextures) d.gl->glDeleteTextures(1, &t.texture);
    d.mapTextures.clear();
    d.gl->glDeleteTextures(1, &d.whiteTexture);
    d.whiteTexture = 0;
    for (auto& [key, s] : d.samplers) d.gl->glDeleteSamplers(1, &s);
    for (auto& [key, s] : d.mapSamplers) d.gl->glDeleteSamplers(1, &s);
    d.samplers.clear();
    d.stackEntries.clear();
    d.gl->glDeleteTextures(1, &d.stackTexture);
    d.stackTexture = 0;
    d.releaseTargets();
    d.gl->glDeleteTextures(1, &d.environmentTexture);
    d.gl->glDeleteTextures(1, &d.mirrorTexture);
    d.gl->glDeleteTextures(1, &d.irradianceTexture);
    d.gl->glDeleteTextures(1, &d.splitSumTexture);
    d.splitSumTexture = 0;
    d.gl->glDeleteTextures(1, &d.lobeMeanTexture);
    d.lobeMeanTexture = 0;
    d.gl->glDeleteTextures(1, &d.fittedLobesTexture);
    d.fittedLobesTexture = 0;
    d.gl->glDeleteVertexArrays(1, &d.emptyVao);
    d.objectProgram.reset();
    d.backgroundProgram.reset();
    d.toneProgram.reset();
    d.aovProgram.reset();
    d.objectMapsProgram.reset();
    d.aovMapsProgram.reset();
    d.objectLayeredProgram.reset();
    d.aovLayeredProgram.reset();
    d.objectTapsProgram.reset();
    d.objectMapsTapsProgram.reset();
    d.tapsProgramFailed[0] = d.tapsProgramFailed[1] = false;
    d.outlineProgram.reset();
    d.environment.reset();
    d.gl = nullptr;
}

void Renderer::setEnvironment(const std::shared_ptr<const PreparedEnvironment>& environment) {
    Impl& d = *impl_;
    if (!d.gl || !environment || !environment->base || d.environment == environment) return;
    const CubeMap& base = *environment->base;
    const std::shared_ptr<const PreparedEnvironment>& before = d.environment;
    // Only the levels the renderer reads (phong.h): smaller ones cannot hold a lobe under
    // bilinear reads, and GL_TEXTURE_MAX_LEVEL keeps the GPU from reaching past the last.
    const int last = std::min(lastReadLevel(base.size()), fullChainLevelCount(base.size()) - 1);
    const bool newBase = !before || before->base != environment->base;
    if (newBase) {
        // Once per import, whether its early environment or the complete one comes first.
        d.uploadCube(d.mirrorTexture, {&base});
        d.gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.mirrorTexture);
        d.gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, 1000);
        d.gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        d.gl->glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
        d.uploadCube(d.environmentTexture, {&base});
        d.environmentFaceSize = base.size();
        // The old import's irradiance map is not this one's: until its own arrives, objects that
        // ask for it read the chain by the normal.
        d.uploadedIrradiance = nullptr;
        ++d.counters.baseUploads;
    }
    if (environment->chain) {
        // Level 0 of every builder's chain holds the base's texels (builders.h), already there.
        if (newBase || before->chain != environment->chain) {
            std::vector<const CubeMap*> levels;
            const int chainLast = std::min(last, environment->chain->levelCount() - 1);
            for (int k = 1; k <= chainLast; ++k) levels.push_back(&environment->chain->levels[static_cast<std::size_t>(k)]);
            if (!levels.empty()) d.uploadCube(d.environmentTexture, levels, 1);
            d.environmentLevels = chainLast + 1;
            ++d.counters.chainUploads;
        }
    } else if (newBase || before->chain) {
        // No chain yet: GL's 2×2 box mips of the base stand in for it (the `box` builder).
        d.gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.environmentTexture);
        d.gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, last);
        d.gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER,
                              last > 0 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        if (last > 0) d.gl->glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
        d.environmentLevels = last + 1;
    }
    if (environment->irradiance && environment->irradiance.get() != d.uploadedIrradiance) {
        d.uploadCube(d.irradianceTexture, {environment->irradiance.get()});
        d.uploadedIrradiance = environment->irradiance.get();
        ++d.counters.irradianceUploads;
    }
    d.environment = environment;
}

void Renderer::render(const Scene& scene, const OrbitCamera& camera, int width, int height,
                      unsigned targetFbo) {
    Impl& d = *impl_;
    if (!d.gl || width <= 0 || height <= 0) return;
    auto* gl = d.gl;
    d.collectMeshes();
    d.collectMapTextures(scene);
    d.ensureTargets(width, height, scene.display.samples);

    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const glm::mat4 view = camera.view();
    const glm::mat4 projection = camera.projection(aspect, sceneBounds(scene));
    const glm::mat4 viewProjection = projection * view;
    const glm::mat3 envRotation = environmentRotation(scene.display.environmentRotationDegrees);
    const Frustum frustum = Frustum::fromViewProjection(viewProjection);

    gl->glBindFramebuffer(GL_FRAMEBUFFER, d.msFbo);
    gl->glViewport(0, 0, width, height);
    // Without the background the target's alpha is the objects' coverage: the tone pass lays
    // the picture over the backdrop (or hands the coverage on, for a transparent export).
    const bool hidden = !scene.display.showBackground;
    const bool transparent = d.transparentBackground && hidden;
    if (hidden)
        gl->glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    else
        gl->glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    gl->glStencilMask(0xFF);
    gl->glClearStencil(0);
    gl->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthFunc(GL_LESS);
    gl->glDepthMask(GL_TRUE);
    gl->glDisable(GL_CULL_FACE);  // imported meshes are often open or inconsistently wound
    gl->glEnable(GL_MULTISAMPLE);

    d.counters.objectsDrawn = d.counters.objectsCulled = d.counters.drawCalls = 0;
    d.counters.objectsSettled = d.counters.objectsFromChain = 0;
    const bool haveEnvironment = hasEnvironment();
    if (haveEnvironment) {
        gl->glActiveTexture(GL_TEXTURE0 + unitIndex(TextureUnit::Irradiance));
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.irradianceTexture);
        gl->glBindSampler(unitIndex(TextureUnit::Irradiance), 0);
        gl->glActiveTexture(GL_TEXTURE0);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.environmentTexture);

        d.drawAllObjects(false, Impl::ObjectSet::Covering, scene, camera.position(), viewProjection, envRotation, frustum);

        if (scene.display.showBackground) {
            // Drawn last at the far plane, so covered pixels are never shaded.
            const glm::mat4 rotationOnly = projection * glm::mat4(glm::mat3(view));
            QOpenGLShaderProgram& bg = *d.backgroundProgram;
            bg.bind();
            gl->glUniformMatrix4fv(bg.uniformLocation("uInverseViewProjection"), 1, GL_FALSE,
                                   glm::value_ptr(glm::inverse(rotationOnly)));
            gl->glUniformMatrix3fv(bg.uniformLocation("uEnvironmentRotation"), 1, GL_FALSE,
                                   glm::value_ptr(envRotation));
            const ObjectLookup plan = planBackground(scene.display.backgroundLambda, d.environmentFaceSize);
            gl->glUniform1f(bg.uniformLocation("uLod"), plan.minLevel);
            gl->glUniform1i(bg.uniformLocation("uUseStack"), plan.readsLobeStack && d.stackServes(plan.exponent) ? 1 : 0);
            gl->glUniform1f(bg.uniformLocation("uExponent"), static_cast<float>(plan.exponent));
            d.bindStack(bg);
            gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.environmentTexture);
            gl->glBindSampler(unitIndex(TextureUnit::Chain), d.sampler(0.0f));
            gl->glDepthFunc(GL_LEQUAL);
            gl->glDepthMask(GL_FALSE);
            gl->glBindVertexArray(d.emptyVao);
            gl->glDrawArrays(GL_TRIANGLES, 0, 3);
            ++d.counters.drawCalls;
            gl->glDepthMask(GL_TRUE);
            gl->glDepthFunc(GL_LESS);
        }
        // Blended materials over everything else (glTF's BLEND): colour by their alpha; the
        // target's alpha (the coverage the tone pass reads) by alpha over what it had. Depth
        // tested, not written, so each shows what lies behind it.
        gl->glEnable(GL_BLEND);
        gl->glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        gl->glDepthMask(GL_FALSE);
        d.drawAllObjects(false, Impl::ObjectSet::Blended, scene, camera.position(), viewProjection, envRotation, frustum);
        gl->glDepthMask(GL_TRUE);
        gl->glDisable(GL_BLEND);
        gl->glDisable(GL_CULL_FACE);
        gl->glBindSampler(unitIndex(TextureUnit::Chain), 0);
    }
    d.drawOutline(scene, viewProjection, width, height);

    // Resolve the multisampled HDR target, then tone-map into the caller's framebuffer.
    gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, d.msFbo);
    gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, d.resolveFbo);
    gl->glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);

    gl->glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    gl->glViewport(0, 0, width, height);
    gl->glDisable(GL_DEPTH_TEST);
    QOpenGLShaderProgram& tone = *d.toneProgram;
    tone.bind();
    tone.setUniformValue("uExposure", std::exp2(scene.display.exposureEv));
    tone.setUniformValue("uToneMap", static_cast<int>(scene.display.toneMap));
    tone.setUniformValue("uAlpha", transparent ? 1 : hidden ? 2 : 0);
    const Rgb backdrop = glm::clamp(scene.display.backdrop, 0.0f, 1.0f);
    tone.setUniformValue("uBackdrop", backdrop.r, backdrop.g, backdrop.b);
    if (d.outputRect) {
        gl->glEnable(GL_SCISSOR_TEST);
        gl->glScissor((*d.outputRect)[0], (*d.outputRect)[1], (*d.outputRect)[2], (*d.outputRect)[3]);
    }
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_2D, d.resolveTexture);
    gl->glBindVertexArray(d.emptyVao);
    gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    gl->glBindVertexArray(0);
    gl->glDisable(GL_SCISSOR_TEST);
    tone.release();
    ++d.counters.frames;
}

void Renderer::setOutputRect(int x, int y, int width, int height) {
    impl_->outputRect = std::array<int, 4>{x, y, std::max(width, 0), std::max(height, 0)};
}

void Renderer::clearOutputRect() { impl_->outputRect.reset(); }

void Renderer::setTransparentBackground(bool transparent) { impl_->transparentBackground = transparent; }

void Renderer::setHighlightedObject(int index) { impl_->highlighted = index; }

void Renderer::setTextures(std::shared_ptr<const TextureCache> textures) { impl_->textures = std::move(textures); }

void Renderer::setLobes(const std::vector<std::shared_ptr<const LobeStackEntry>>& lobes) {
    Impl& d = *impl_;
    if (!d.gl) return;
    std::map<int, std::shared_ptr<const LobeStackEntry>> wanted;  // by stackKey: both kinds
    for (const auto& lobe : lobes)
        if (lobe && lobe->cube && lobe->index >= 1 && lobe->index <= kStackLast) wanted[stackKey(*lobe)] = lobe;
    if (wanted == d.stackEntries) return;
    d.stackEntries = wanted;
    d.stackTable.fill(glm::vec4(0.0f));
    d.remainderTable.fill(glm::vec4(0.0f));
    d.counters.lobesResident = wanted.size();
    d.counters.stackBytes = 0;
    if (wanted.empty()) return;
    d.stackBaseSize = wanted.begin()->second->filter ? wanted.begin()->second->filter->baseSize() : 0;
    // The atlas is packed again for every new set of entries and sent whole: the set changes when
    // λ leaves the range made (a few times a drag), and sending 40 MB costs tens of milliseconds.
    // Stored as GL_RGB9_E5 (a shared exponent, 9-bit mantissas: 4 bytes a texel, a third of
    // RGB32F; each texel's largest channel within 2^-10, the others within 2^-10 of it), each entry
    // scaled by a power of two that brings its largest value just under the format's 65408 and
    // scaled back in the shader (uStackScale), so no environment's absolute scale matters
    // (docs/lobe-stack.md).
    std::vector<std::pair<int, const CubeMap*>> cubes;
    for (const auto& [key, lobe] : wanted) cubes.emplace_back(key, lobe->cube.get());
    GLint maxSize = 0;
    d.gl->glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const PackedLobeStack packed = packLobeStack(cubes, std::min(4096, static_cast<int>(maxSize)));
    const LobeStackAtlas& atlas = packed.atlas;
    d.stackScales.fill(1.0f);
    for (std::size_t e = 0; e < cubes.size(); ++e) {
        const AtlasPlacement& at = atlas.placed[e];
        const auto index = static_cast<std::size_t>(stackKeyIndex(at.index));
        if (isRemainderKey(at.index)) {
            d.remainderTable[index] = glm::vec4(static_cast<float>(at.x), static_cast<float>(at.y), static_cast<float>(at.size), packed.scales[e]);
        } else {
            d.stackScales[index] = packed.scales[e];
            d.stackTable[index] = glm::vec4(static_cast<float>(at.x), static_cast<float>(at.y), static_cast<float>(at.size), 1.0f);
        }
        ++d.counters.lobeUploads;
    }
    d.gl->glBindTexture(GL_TEXTURE_2D, d.stackTexture);
    d.gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    d.gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB9_E5, atlas.width, atlas.height, 0, GL_RGB, GL_FLOAT, packed.texels.data());
    d.counters.stackBytes = static_cast<std::uint64_t>(atlas.width) * static_cast<std::uint64_t>(atlas.height) * 4;
}


std::vector<glm::vec4> Renderer::readHdr(int& width, int& height) {
    Impl& d = *impl_;
    width = d.targetWidth;
    height = d.targetHeight;
    std::vector<glm::vec4> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    if (!d.gl || pixels.empty()) return pixels;
    d.gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, d.resolveFbo);
    d.gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    d.gl->glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, pixels.data());
    return pixels;
}

RenderSizeLimits Renderer::maxRenderSize() const {
    RenderSizeLimits limits;
    QOpenGLFunctions_4_1_Core* gl = impl_->gl;
    if (!gl) return limits;
    GLint texture = 0, renderbuffer = 0, samples = 0;
    GLint viewport[2] = {0, 0};
    gl->glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
    gl->glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
    gl->glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    gl->glGetIntegerv(GL_MAX_SAMPLES, &samples);
    auto smallest = [&](int& size, const char*& name, GLint viewportLimit) {
        size = texture;
        name = "GL_MAX_TEXTURE_SIZE";
        if (renderbuffer < size) size = renderbuffer, name = "GL_MAX_RENDERBUFFER_SIZE";
        if (viewportLimit < size) size = viewportLimit, name = "GL_MAX_VIEWPORT_DIMS";
    };
    smallest(limits.maxWidth, limits.widthLimit, viewport[0]);
    smallest(limits.maxHeight, limits.heightLimit, viewport[1]);
    limits.maxSamples = samples;
    return limits;
}

std::string Renderer::glDescription() const {
    if (!impl_->gl) return "no OpenGL";
    auto str = [&](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(impl_->gl->glGetString(name));
        return std::string(s ? s : "?");
    };
    return str(GL_VERSION) + " / " + str(GL_RENDERER);
}

}  // namespace mipgloss::ui
