#include "mipgloss/ui/renderer.h"

#include "mipgloss/ibl/phong.h"

#include <QFile>
#include <QOpenGLContext>
#include <QOpenGLFunctions_4_1_Core>
#include <QOpenGLShaderProgram>
#include <QOpenGLVersionFunctionsFactory>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace mipgloss::ui {

namespace {

// Largest finite half float: HDR values above it (a sanitised +Inf) would become Inf in RGB16F.
constexpr float kHalfMax = 65504.0f;

struct GpuMesh {
    std::weak_ptr<const Mesh> source;
    GLuint vao = 0, vbo = 0, ibo = 0;
    GLsizei indexCount = 0;
};

// World direction -> environment direction: turning the environment by θ about +Y is looking up
// the direction turned by -θ.
glm::mat3 environmentRotation(float degrees) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(-degrees), glm::vec3(0, 1, 0)));
}

// λ as a sampler key: materials within 1/1024 of a level share a sampler.
int lambdaKey(float lambda) { return static_cast<int>(std::lround(lambda * 1024.0f)); }

}  // namespace

struct Renderer::Impl {
    QOpenGLFunctions_4_1_Core* gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> objectProgram, backgroundProgram, toneProgram;
    GLuint emptyVao = 0;

    GLuint environmentTexture = 0;
    GLuint irradianceTexture = 0;
    int environmentLevels = 0;
    int environmentFaceSize = 0;
    const CubeMap* uploadedIrradiance = nullptr;
    std::shared_ptr<const PreparedEnvironment> environment;  // keeps what is uploaded alive

    std::map<int, GLuint> samplers;  // λ key -> sampler with GL_TEXTURE_MIN_LOD = λ
    std::unordered_map<const Mesh*, GpuMesh> meshes;

    // Targets: multisampled HDR colour + depth, resolved into a single-sample HDR texture.
    GLuint msFbo = 0, msColour = 0, msDepth = 0;
    GLuint resolveFbo = 0, resolveTexture = 0;
    int targetWidth = 0, targetHeight = 0, targetSamples = -1;

    RenderCounters counters;

    GLuint sampler(float lambda) {
        const int key = lambdaKey(lambda);
        auto it = samplers.find(key);
        if (it != samplers.end()) return it->second;
        GLuint s = 0;
        gl->glGenSamplers(1, &s);
        gl->glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
        gl->glSamplerParameterf(s, GL_TEXTURE_MIN_LOD, static_cast<float>(key) / 1024.0f);
        gl->glSamplerParameterf(s, GL_TEXTURE_MAX_LOD, 1000.0f);
        ++counters.samplersCreated;
        samplers.emplace(key, s);
        return s;
    }

    void uploadCube(GLuint texture, const std::vector<const CubeMap*>& levels) {
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
        gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        std::vector<float> face;
        for (std::size_t level = 0; level < levels.size(); ++level) {
            const CubeMap& cube = *levels[level];
            const int n = cube.size();
            face.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * 3);
            for (Face f : kAllFaces) {
                // Interior texels only; our row 0 is t = 0, which is GL's first row.
                std::size_t i = 0;
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        const Rgb& c = cube.at(f, x, y);
                        face[i++] = std::min(c.r, kHalfMax);
                        face[i++] = std::min(c.g, kHalfMax);
                        face[i++] = std::min(c.b, kHalfMax);
                    }
                gl->glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f),
                                 static_cast<GLint>(level), GL_RGB16F, n, n, 0, GL_RGB, GL_FLOAT,
                                 face.data());
            }
        }
        const GLint last = static_cast<GLint>(levels.size()) - 1;
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, last);
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER,
                            last > 0 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
    }

    GpuMesh& gpuMesh(const std::shared_ptr<const Mesh>& mesh) {
        auto it = meshes.find(mesh.get());
        if (it != meshes.end() && !it->second.source.expired()) return it->second;
        if (it != meshes.end()) releaseMesh(it->second);
        GpuMesh g;
        g.source = mesh;
        std::vector<float> interleaved;
        interleaved.reserve(mesh->positions.size() * 6);
        for (std::size_t i = 0; i < mesh->positions.size(); ++i) {
            const glm::vec3& p = mesh->positions[i];
            const glm::vec3& n = mesh->normals[i];
            interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
        }
        gl->glGenVertexArrays(1, &g.vao);
        gl->glBindVertexArray(g.vao);
        gl->glGenBuffers(1, &g.vbo);
        gl->glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
        gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                         interleaved.data(), GL_STATIC_DRAW);
        gl->glGenBuffers(1, &g.ibo);
        gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo);
        gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                         static_cast<GLsizeiptr>(mesh->indices.size() * sizeof(std::uint32_t)),
                         mesh->indices.data(), GL_STATIC_DRAW);
        const GLsizei stride = 6 * sizeof(float);
        gl->glEnableVertexAttribArray(0);
        gl->glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
        gl->glEnableVertexAttribArray(1);
        gl->glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<const void*>(3 * sizeof(float)));
        gl->glBindVertexArray(0);
        g.indexCount = static_cast<GLsizei>(mesh->indices.size());
        ++counters.meshUploads;
        return meshes[mesh.get()] = g;
    }

    void releaseMesh(GpuMesh& g) {
        gl->glDeleteVertexArrays(1, &g.vao);
        gl->glDeleteBuffers(1, &g.vbo);
        gl->glDeleteBuffers(1, &g.ibo);
        g = GpuMesh{};
    }

    // Frees the GPU copies of meshes no scene object holds any more.
    void collectMeshes() {
        for (auto it = meshes.begin(); it != meshes.end();) {
            if (it->second.source.expired()) {
                releaseMesh(it->second);
                it = meshes.erase(it);
            } else {
                ++it;
            }
        }
    }

    void releaseTargets() {
        if (msFbo) gl->glDeleteFramebuffers(1, &msFbo);
        if (resolveFbo) gl->glDeleteFramebuffers(1, &resolveFbo);
        if (msColour) gl->glDeleteRenderbuffers(1, &msColour);
        if (msDepth) gl->glDeleteRenderbuffers(1, &msDepth);
        if (resolveTexture) gl->glDeleteTextures(1, &resolveTexture);
        msFbo = resolveFbo = msColour = msDepth = resolveTexture = 0;
        targetWidth = targetHeight = 0;
        targetSamples = -1;
    }

    void ensureTargets(int width, int height, int samples) {
        GLint maxSamples = 0;
        gl->glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
        samples = std::clamp(samples, 0, static_cast<int>(maxSamples));
        if (samples == 1) samples = 0;
        if (width == targetWidth && height == targetHeight && samples == targetSamples) return;
        releaseTargets();
        gl->glGenRenderbuffers(1, &msColour);
        gl->glBindRenderbuffer(GL_RENDERBUFFER, msColour);
        gl->glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA16F, width, height);
        gl->glGenRenderbuffers(1, &msDepth);
        gl->glBindRenderbuffer(GL_RENDERBUFFER, msDepth);
        gl->glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width,
                                             height);
        gl->glGenFramebuffers(1, &msFbo);
        gl->glBindFramebuffer(GL_FRAMEBUFFER, msFbo);
        gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msColour);
        gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msDepth);

        gl->glGenTextures(1, &resolveTexture);
        gl->glBindTexture(GL_TEXTURE_2D, resolveTexture);
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl->glGenFramebuffers(1, &resolveFbo);
        gl->glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo);
        gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                   resolveTexture, 0);
        targetWidth = width;
        targetHeight = height;
        targetSamples = samples;
    }
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

const RenderCounters& Renderer::counters() const { return impl_->counters; }
bool Renderer::isInitialized() const { return impl_->gl != nullptr; }
bool Renderer::hasEnvironment() const { return impl_->environmentTexture != 0 && impl_->environment; }

namespace {
std::unique_ptr<QOpenGLShaderProgram> buildProgram(const char* vertexPath, const char* fragmentPath,
                                                   std::string* error) {
    auto program = std::make_unique<QOpenGLShaderProgram>();
    if (!program->addCacheableShaderFromSourceFile(QOpenGLShader::Vertex, vertexPath) ||
        !program->addCacheableShaderFromSourceFile(QOpenGLShader::Fragment, fragmentPath) ||
        !program->link()) {
        if (error)
            *error = std::string("shader ") + fragmentPath + ": " + program->log().toStdString();
        return nullptr;
    }
    return program;
}
}  // namespace

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
    impl_->objectProgram = buildProgram(":/mipgloss/shaders/object.vert", ":/mipgloss/shaders/object.frag", error);
    impl_->backgroundProgram =
        buildProgram(":/mipgloss/shaders/fullscreen.vert", ":/mipgloss/shaders/background.frag", error);
    impl_->toneProgram = buildProgram(":/mipgloss/shaders/fullscreen.vert", ":/mipgloss/shaders/tonemap.frag", error);
    if (!impl_->objectProgram || !impl_->backgroundProgram || !impl_->toneProgram) {
        impl_->gl = nullptr;
        return false;
    }
    auto* gl = impl_->gl;
    gl->glGenVertexArrays(1, &impl_->emptyVao);
    // Filtering across cube faces (the paper's seams, §5) is the GPU's job from here on.
    gl->glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    gl->glGenTextures(1, &impl_->environmentTexture);
    gl->glGenTextures(1, &impl_->irradianceTexture);
    impl_->objectProgram->bind();
    impl_->objectProgram->setUniformValue("uEnvironment", 0);
    impl_->objectProgram->setUniformValue("uIrradiance", 1);
    impl_->backgroundProgram->bind();
    impl_->backgroundProgram->setUniformValue("uEnvironment", 0);
    impl_->toneProgram->bind();
    impl_->toneProgram->setUniformValue("uHdr", 0);
    impl_->toneProgram->release();
    return true;
}

void Renderer::destroy() {
    Impl& d = *impl_;
    if (!d.gl) return;
    for (auto& [mesh, g] : d.meshes) d.releaseMesh(g);
    d.meshes.clear();
    for (auto& [key, s] : d.samplers) d.gl->glDeleteSamplers(1, &s);
    d.samplers.clear();
    d.releaseTargets();
    d.gl->glDeleteTextures(1, &d.environmentTexture);
    d.gl->glDeleteTextures(1, &d.irradianceTexture);
    d.gl->glDeleteVertexArrays(1, &d.emptyVao);
    d.objectProgram.reset();
    d.backgroundProgram.reset();
    d.toneProgram.reset();
    d.environment.reset();
    d.gl = nullptr;
}

void Renderer::setEnvironment(const std::shared_ptr<const PreparedEnvironment>& environment) {
    Impl& d = *impl_;
    if (!d.gl || !environment || !environment->chain || d.environment == environment) return;
    // The chain is uploaded only when it is a different chain (a new irradiance map alone
    // uploads just that).
    if (!d.environment || d.environment->chain != environment->chain) {
        std::vector<const CubeMap*> levels;
        for (const CubeMap& level : environment->chain->levels) levels.push_back(&level);
        d.uploadCube(d.environmentTexture, levels);
        d.environmentLevels = environment->chain->levelCount();
        d.environmentFaceSize = environment->chain->baseSize();
        ++d.counters.chainUploads;
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
    d.ensureTargets(width, height, scene.display.samples);

    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const glm::mat4 view = camera.view();
    const glm::mat4 projection = camera.projection(aspect, sceneBounds(scene));
    const glm::mat4 viewProjection = projection * view;
    const glm::mat3 envRotation = environmentRotation(scene.environment.rotationDegrees);
    const Frustum frustum = Frustum::fromViewProjection(viewProjection);

    gl->glBindFramebuffer(GL_FRAMEBUFFER, d.msFbo);
    gl->glViewport(0, 0, width, height);
    const float grey = 0.18f;  // without a background: a mid grey, linear
    gl->glClearColor(grey, grey, grey, 1.0f);
    gl->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthFunc(GL_LESS);
    gl->glDepthMask(GL_TRUE);
    gl->glDisable(GL_CULL_FACE);  // imported meshes are often open or inconsistently wound
    gl->glEnable(GL_MULTISAMPLE);

    d.counters.objectsDrawn = d.counters.objectsCulled = d.counters.drawCalls = 0;
    const bool haveEnvironment = hasEnvironment();
    if (haveEnvironment) {
        gl->glActiveTexture(GL_TEXTURE1);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.irradianceTexture);
        gl->glBindSampler(1, 0);
        gl->glActiveTexture(GL_TEXTURE0);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.environmentTexture);

        QOpenGLShaderProgram& program = *d.objectProgram;
        program.bind();
        const glm::vec3 eye = camera.position();
        gl->glUniformMatrix4fv(program.uniformLocation("uViewProjection"), 1, GL_FALSE,
                               glm::value_ptr(viewProjection));
        gl->glUniformMatrix3fv(program.uniformLocation("uEnvironmentRotation"), 1, GL_FALSE,
                               glm::value_ptr(envRotation));
        gl->glUniform3fv(program.uniformLocation("uCameraPosition"), 1, glm::value_ptr(eye));
        const int locModel = program.uniformLocation("uModel");
        const int locNormal = program.uniformLocation("uNormalMatrix");
        const int locTint = program.uniformLocation("uTint");
        const int locLookup = program.uniformLocation("uLookup");
        const int locGrazing = program.uniformLocation("uSharperAtGrazing");
        const int locLambda = program.uniformLocation("uLambda");
        const bool irradianceReady = d.uploadedIrradiance != nullptr;

        for (const SceneObject& object : scene.objects) {
            if (!object.visible || !object.mesh || object.mesh->indices.empty()) continue;
            if (!frustum.intersectsSphere(object.worldCentre(), object.worldRadius())) {
                ++d.counters.objectsCulled;
                continue;
            }
            const GpuMesh& mesh = d.gpuMesh(object.mesh);
            const Material& m = object.material;
            const float lambda = static_cast<float>(clampLambda(m.lambda, d.environmentLevels));
            int lookup = m.mode == LookupMode::Reflect ? 0 : 1;
            if (lookup == 1 && m.useIrradiance && irradianceReady) lookup = 2;
            const glm::mat4 model = object.transform.matrix();
            const glm::mat3 rotation =
                glm::mat3(model) / std::max(std::abs(object.transform.scale), 1e-30f);
            gl->glUniformMatrix4fv(locModel, 1, GL_FALSE, glm::value_ptr(model));
            gl->glUniformMatrix3fv(locNormal, 1, GL_FALSE, glm::value_ptr(rotation));
            gl->glUniform3fv(locTint, 1, glm::value_ptr(m.tint));
            gl->glUniform1i(locLookup, lookup);
            gl->glUniform1i(locGrazing, m.sharperAtGrazing && lookup != 2 ? 1 : 0);
            gl->glUniform1f(locLambda, lambda);
            // The paper's one statement per object: the sampler holding MIN_LOD = λ.
            gl->glBindSampler(0, d.sampler(m.sharperAtGrazing ? 0.0f : lambda));
            gl->glBindVertexArray(mesh.vao);
            gl->glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
            ++d.counters.objectsDrawn;
            ++d.counters.drawCalls;
        }

        if (scene.display.showBackground) {
            // Drawn last at the far plane, so covered pixels are never shaded.
            const glm::mat4 rotationOnly = projection * glm::mat4(glm::mat3(view));
            QOpenGLShaderProgram& bg = *d.backgroundProgram;
            bg.bind();
            gl->glUniformMatrix4fv(bg.uniformLocation("uInverseViewProjection"), 1, GL_FALSE,
                                   glm::value_ptr(glm::inverse(rotationOnly)));
            gl->glUniformMatrix3fv(bg.uniformLocation("uEnvironmentRotation"), 1, GL_FALSE,
                                   glm::value_ptr(envRotation));
            gl->glUniform1f(bg.uniformLocation("uLod"),
                            static_cast<float>(clampLambda(scene.display.backgroundLambda, d.environmentLevels)));
            gl->glBindSampler(0, d.sampler(0.0f));
            gl->glDepthFunc(GL_LEQUAL);
            gl->glDepthMask(GL_FALSE);
            gl->glBindVertexArray(d.emptyVao);
            gl->glDrawArrays(GL_TRIANGLES, 0, 3);
            ++d.counters.drawCalls;
            gl->glDepthMask(GL_TRUE);
            gl->glDepthFunc(GL_LESS);
        }
        gl->glBindSampler(0, 0);
    }

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
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_2D, d.resolveTexture);
    gl->glBindVertexArray(d.emptyVao);
    gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    gl->glBindVertexArray(0);
    tone.release();
    ++d.counters.frames;
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

std::string Renderer::glDescription() const {
    if (!impl_->gl) return "no OpenGL";
    auto str = [&](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(impl_->gl->glGetString(name));
        return std::string(s ? s : "?");
    };
    return str(GL_VERSION) + " / " + str(GL_RENDERER);
}

}  // namespace mipgloss::ui
