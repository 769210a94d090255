#include "mipgloss/ui/renderer.h"

#include "mipgloss/ibl/colour.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/scene/layered.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/scene/lookup_plan.h"
#include "mipgloss/assets/textures.h"

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
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

namespace mipgloss::ui {

namespace {

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

// A chain level (GL_TEXTURE_MIN_LOD) as a sampler key: levels within 1/1024 share a sampler.
int levelKey(float level) { return static_cast<int>(std::lround(level * 1024.0f)); }

}  // namespace

struct Renderer::Impl {
    QOpenGLFunctions_4_1_Core* gl = nullptr;
    std::shared_ptr<const TextureCache> textureCache;  // the caller's (setTextures); null: maps drawn as missing
    std::unique_ptr<QOpenGLShaderProgram> objectProgram, backgroundProgram, toneProgram, aovProgram, outlineProgram;
    // object.frag and aov.frag built with MATERIAL_MAPS: the layered materials with texture maps
    // (MaterialMaps::inUse), drawn after the others (material_maps.glsl says why apart).
    std::unique_ptr<QOpenGLShaderProgram> objectMapsProgram, aovMapsProgram;
    GLuint emptyVao = 0;

    GLuint environmentTexture = 0;
    // The mirror: level 0 with its own box mips. The chain's deeper levels hold wide lobes
    // (phong.h), so a minified mirror read through the chain would turn glossy; through this it
    // gets mipmapping's usual footprint filtering instead.
    GLuint mirrorTexture = 0;
    GLuint irradianceTexture = 0;
    int environmentLevels = 0;
    int environmentFaceSize = 0;
    const CubeMap* uploadedIrradiance = nullptr;
    std::shared_ptr<const PreparedEnvironment> environment;  // keeps what is uploaded alive

    // Texture units besides 0 (the chain) and 1 (the irradiance map).
    static constexpr GLuint kStackUnit = 2, kSplitSumUnit = 3, kCoatChainUnit = 4, kDiffuseChainUnit = 6;
    // A material's texture maps (material_maps.glsl): base colour, metallic, roughness, normal,
    // occlusion, emissive.
    static constexpr GLuint kFirstMapUnit = 8;
    static constexpr int kMapCount = 6;

    // Texture maps on the GPU, one per decoded image and colour space (sRGB for base colour and
    // emission, linear for the rest), mip-mapped and anisotropically filtered; the decoded image
    // is kept alive here while its texture is (TextureCache hands out the same pointer).
    struct GpuTexture {
        std::shared_ptr<const TextureImage> image;
        GLuint texture = 0;
    };
    std::map<std::pair<std::string, bool>, GpuTexture> mapTextures;
    float maxAnisotropy = -1.0f;  // queried once: 0 when the GL has no anisotropic filtering
    GLuint splitSumTexture = 0;      // the split-sum table (specular.h), once a layered material is drawn
    GLuint whiteTexture = 0;         // 1×1 white: what a map unit holds when the material has no such map

    std::map<int, GLuint> samplers;  // level key -> sampler with GL_TEXTURE_MIN_LOD = that level

    // The lobe stack (lobes.h): its entries on the GPU, packed in one 2D atlas (lobeStackAtlas),
    // and the table the shaders find them by (lobe_stack.glsl).
    std::map<int, std::shared_ptr<const LobeStackEntry>> stackEntries;  // index -> entry
    GLuint stackTexture = 0;
    std::array<glm::vec4, kStackSlots> stackTable{};  // block x, y, face size, 1 when present
    std::array<float, kStackSlots> stackExponents{};
    std::array<float, kStackSlots> stackScales{};  // what an entry's stored texels are multiplied by
    int stackBaseSize = 0;  // the base face size the entries were made from
    std::optional<std::array<int, 4>> outputRect;  // setOutputRect: x, y, width, height
    bool transparentBackground = false;
    int highlighted = -1;  // setHighlightedObject
    std::unordered_map<const Mesh*, GpuMesh> meshes;

    // Targets: multisampled HDR colour + depth, resolved into a single-sample HDR texture.
    GLuint msFbo = 0, msColour = 0, msDepth = 0;
    GLuint resolveFbo = 0, resolveTexture = 0;
    int targetWidth = 0, targetHeight = 0, targetSamples = -1;

    RenderCounters counters;

    // The sampler reading the chain from `level` on (GL_TEXTURE_MIN_LOD = level).
    GLuint sampler(float level) {
        const int key = levelKey(level);
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

    // Whether the stack on the GPU was made from the current environment.
    bool stackCurrent() const {
        return !stackEntries.empty() && environment && environment->filter &&
               stackEntries.begin()->second->filter == environment->filter;
    }
    // Whether shaders should look lobe n up in the stack (they then check, per fragment, that the
    // entries the footprint-widened lobe blends are there, and read the chain where not).
    bool stackServes(double exponent) const { return stackCurrent() && stackBlend(exponent, stackBaseSize).has_value(); }
    // Whether the stack holds lobe n itself: both entries it blends (the settled picture's test).
    bool stackHolds(double exponent) const {
        if (!stackCurrent()) return false;
        const auto blend = stackBlend(exponent, stackBaseSize);
        return blend && stackEntries.count(blend->sharper) && (blend->widerWeight == 0.0 || stackEntries.count(blend->wider));
    }
    // The stack's table and atlas for `program` (object, AOV and background programs).
    void bindStack(QOpenGLShaderProgram& program) {
        const bool current = stackCurrent();
        std::array<glm::vec4, kStackSlots> table = stackTable;
        if (!current)
            for (glm::vec4& e : table) e.w = 0.0f;
        gl->glUniform4fv(program.uniformLocation("uStackEntry"), kStackSlots, glm::value_ptr(table[0]));
        gl->glUniform1fv(program.uniformLocation("uStackExponent"), kStackSlots, stackExponents.data());
        gl->glUniform1fv(program.uniformLocation("uStackScale"), kStackSlots, stackScales.data());
        gl->glUniform1i(program.uniformLocation("uStackTop"), stackTop(std::max(stackBaseSize, 1)));
        gl->glActiveTexture(GL_TEXTURE0 + kStackUnit);
        gl->glBindTexture(GL_TEXTURE_2D, stackTexture);
        gl->glBindSampler(kStackUnit, 0);
        gl->glActiveTexture(GL_TEXTURE0);
    }

    // Binds the chain (or, for a mirror, the mirror texture) to `unit` with the sampler holding
    // the plan's MIN_LOD; unit 0 stays active.
    void bindChain(const ObjectLookup& plan, GLuint unit) {
        gl->glActiveTexture(GL_TEXTURE0 + unit);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, plan.mirror ? mirrorTexture : environmentTexture);
        gl->glBindSampler(unit, sampler(plan.minLevel));
        gl->glActiveTexture(GL_TEXTURE0);
    }

    // The split-sum table (specular.h) as an RG32F texture on unit 3, made the first time a layered
    // material is drawn (building the table takes about 0.2 s, which no single-lobe scene pays).
    void bindSplitSum() {
        if (splitSumTexture == 0) {
            const SplitSumTable& table = SplitSumTable::shared();
            gl->glGenTextures(1, &splitSumTexture);
            gl->glBindTexture(GL_TEXTURE_2D, splitSumTexture);
            gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
            gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, SplitSumTable::kCosSteps, SplitSumTable::kLambdaSteps, 0,
                             GL_RG, GL_FLOAT, table.nodes().data());
            gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        }
        gl->glActiveTexture(GL_TEXTURE0 + kSplitSumUnit);
        gl->glBindTexture(GL_TEXTURE_2D, splitSumTexture);
        gl->glBindSampler(kSplitSumUnit, 0);
        gl->glActiveTexture(GL_TEXTURE0);
    }

    // Where a program takes a layered material's values, resolved once per drawObjects call (a
    // name lookup per uniform per object would sit in the draw loop).
    struct LayeredUniforms {
        explicit LayeredUniforms(QOpenGLShaderProgram& p)
            : f0(p.uniformLocation("uF0")),
              diffuseColour(p.uniformLocation("uDiffuseColour")),
              specularLambda(p.uniformLocation("uSpecularLambda")),
              coat(p.uniformLocation("uCoat")),
              coatLambda(p.uniformLocation("uCoatLambda")),
              coatExponent(p.uniformLocation("uCoatExponent")),
              useCoatStack(p.uniformLocation("uUseCoatStack")),
              useDiffuseStack(p.uniformLocation("uUseDiffuseStack")),
              diffuseIrradiance(p.uniformLocation("uDiffuseIrradiance")) {}
        int f0, diffuseColour, specularLambda, coat, coatLambda, coatExponent, useCoatStack, useDiffuseStack,
            diffuseIrradiance;
    };

    // The uniforms a single-lobe material shares with a layered one's specular layer.
    struct LobeUniforms {
        int useStack, exponent;
    };

    // What drawing one object read: the stack's exact lobes (the settled picture), or the chain
    // standing in for a lobe while its entries are made.
    struct ObjectRead {
        bool settled = false;
        bool fromChain = false;
    };

    // The GL texture of map `ref` (sRGB or linear), uploaded the first time; 0 when its image is
    // not decoded (yet, or refused: TextureCache::problem).
    GLuint mapTexture(const TextureRef& ref, bool srgb) {
        if (ref.empty()) return 0;
        const auto key = std::make_pair(ref.key(), srgb);  // the image, whatever channel a map reads
        const std::shared_ptr<const TextureImage> decoded = textureCache ? textureCache->find(ref) : nullptr;
        auto it = mapTextures.find(key);
        if (it != mapTextures.end() && it->second.image == decoded) return it->second.texture;
        if (it != mapTextures.end()) {
            gl->glDeleteTextures(1, &it->second.texture);
            mapTextures.erase(it);
        }
        if (!decoded || decoded->width <= 0 || decoded->height <= 0) return 0;
        GpuTexture g;
        g.image = decoded;
        gl->glGenTextures(1, &g.texture);
        gl->glBindTexture(GL_TEXTURE_2D, g.texture);
        gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl->glTexImage2D(GL_TEXTURE_2D, 0, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, decoded->width, decoded->height, 0, GL_RGBA,
                         GL_UNSIGNED_BYTE, decoded->rgba.data());
        gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->glGenerateMipmap(GL_TEXTURE_2D);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        if (maxAnisotropy < 0.0f) {
            // GL_TEXTURE_MAX_ANISOTROPY (core in 4.6, EXT_texture_filter_anisotropic before).
            GLfloat most = 0.0f;
            gl->glGetFloatv(0x84FF /* GL_MAX_TEXTURE_MAX_ANISOTROPY */, &most);
            maxAnisotropy = gl->glGetError() == GL_NO_ERROR ? std::min(most, 16.0f) : 0.0f;
        }
        if (maxAnisotropy > 1.0f) gl->glTexParameterf(GL_TEXTURE_2D, 0x84FE /* GL_TEXTURE_MAX_ANISOTROPY */, maxAnisotropy);
        ++counters.textureUploads;
        counters.textureBytes += decoded->bytes() * 4 / 3;
        return mapTextures[key] = g, g.texture;
    }

    // Frees the map textures no material of `scene` reads any more.
    void collectMapTextures(const Scene& scene) {
        std::set<std::string> used;
        for (const TextureRef& t : texturesOf(scene)) used.insert(t.key());
        for (auto it = mapTextures.begin(); it != mapTextures.end();) {
            if (!used.count(it->first.first)) {
                counters.textureBytes -= std::min(counters.textureBytes, it->second.image->bytes() * 4 / 3);
                gl->glDeleteTextures(1, &it->second.texture);
                it = mapTextures.erase(it);
            } else {
                ++it;
            }
        }
    }

    // Where a program takes a material's maps (material_maps.glsl), resolved once per drawObjects call.
    struct MapUniforms {
        explicit MapUniforms(QOpenGLShaderProgram& p)
            : metallicChannel(p.uniformLocation("uMetallicChannel")),
              roughnessChannel(p.uniformLocation("uRoughnessChannel")),
              baseColor(p.uniformLocation("uBaseColor")),
              baseAlpha(p.uniformLocation("uBaseAlpha")),
              metallic(p.uniformLocation("uMetallic")),
              roughness(p.uniformLocation("uRoughness")),
              specular(p.uniformLocation("uSpecular")),
              normalScale(p.uniformLocation("uNormalScale")),
              occlusionStrength(p.uniformLocation("uOcclusionStrength")),
              emissive(p.uniformLocation("uEmissive")),
              alphaMode(p.uniformLocation("uAlphaMode")),
              alphaCutoff(p.uniformLocation("uAlphaCutoff")) {
            const char* use[kMapCount] = {"uUseBaseColorMap", "uUseMetallicMap", "uUseRoughnessMap",
                                          "uUseNormalMap", "uUseOcclusionMap", "uUseEmissiveMap"};
            const char* sampler[kMapCount] = {"uBaseColorMap", "uMetallicMap", "uRoughnessMap",
                                              "uNormalMap", "uOcclusionMap", "uEmissiveMap"};
            for (int i = 0; i < kMapCount; ++i) {
                uses[i] = p.uniformLocation(use[i]);
                samplers[i] = p.uniformLocation(sampler[i]);
            }
        }
        int metallicChannel, roughnessChannel, baseColor, baseAlpha, metallic, roughness, specular,
            normalScale, occlusionStrength, emissive, alphaMode, alphaCutoff;
        int uses[kMapCount], samplers[kMapCount];
    };

    // A layered material's maps: binds each decoded one to its unit (white where none) and sets
    // the factors. Returns whether the roughness map is read (each fragment its own lobe).
    bool bindMaps(const MapUniforms& u, const Layers& l) {
        const MaterialMaps& m = l.maps;
        if (!m.inUse()) return false;
        if (whiteTexture == 0) {
            const std::uint8_t white[4] = {255, 255, 255, 255};
            gl->glGenTextures(1, &whiteTexture);
            gl->glBindTexture(GL_TEXTURE_2D, whiteTexture);
            gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
            gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        const TextureRef* refs[kMapCount] = {&m.baseColor, &m.metallic, &m.roughness, &m.normal, &m.occlusion, &m.emissive};
        const bool srgb[kMapCount] = {true, false, false, false, false, true};
        bool used[kMapCount];
        GLuint textures[kMapCount];
        // Uploads first (each binds its texture to the active unit), then the units.
        gl->glActiveTexture(GL_TEXTURE0 + kFirstMapUnit + kMapCount);
        for (int i = 0; i < kMapCount; ++i) textures[i] = mapTexture(*refs[i], srgb[i]);
        for (int i = 0; i < kMapCount; ++i) {
            const GLuint texture = textures[i];
            used[i] = texture != 0;
            const GLuint unit = kFirstMapUnit + static_cast<GLuint>(i);
            gl->glActiveTexture(GL_TEXTURE0 + unit);
            gl->glBindTexture(GL_TEXTURE_2D, used[i] ? texture : whiteTexture);
            gl->glBindSampler(unit, 0);
            gl->glUniform1i(u.samplers[i], static_cast<GLint>(unit));
            gl->glUniform1i(u.uses[i], used[i] ? 1 : 0);
        }
        gl->glActiveTexture(GL_TEXTURE0);
        gl->glUniform1i(u.metallicChannel, m.metallic.channel);
        gl->glUniform1i(u.roughnessChannel, m.roughness.channel);
        gl->glUniform3fv(u.baseColor, 1, glm::value_ptr(l.baseColor));
        gl->glUniform1f(u.baseAlpha, m.baseAlpha);
        gl->glUniform1f(u.metallic, l.metallic);
        gl->glUniform1f(u.roughness, l.roughness);
        gl->glUniform1f(u.specular, l.specular);
        gl->glUniform1f(u.normalScale, m.normalScale);
        gl->glUniform1f(u.occlusionStrength, m.occlusionStrength);
        gl->glUniform3fv(u.emissive, 1, glm::value_ptr(m.emissiveFactor));
        gl->glUniform1i(u.alphaMode, static_cast<int>(m.alphaMode));
        gl->glUniform1f(u.alphaCutoff, m.alphaCutoff);
        return used[2];
    }

    // Sets a layered material's uniforms and binds its three lookups.
    ObjectRead bindLayered(const LayeredUniforms& u, const LobeUniforms& lobeUniforms, const MapUniforms& mapUniforms,
                           const Material& m, bool irradianceReady) {
        bindSplitSum();
        LayeredLookup plan = planLayered(m, irradianceReady, environmentFaceSize);
        const bool roughnessMapped = bindMaps(mapUniforms, m.layers);
        if (roughnessMapped && !plan.specular.mirror) {
            // Each fragment picks its own lobe (object.frag, readLobePerFragment): the stack where
            // it holds it, else the chain at that lobe's level, which needs the chain from level 0.
            plan.specular.minLevel = 0.0f;
        }
        const bool diffuseIrradiance = plan.diffuse.lookup == ShaderLookup::Irradiance;
        const bool specular = plan.specular.readsLobeStack &&
                              (roughnessMapped ? stackCurrent() : stackServes(plan.specular.exponent));
        const bool coat = plan.hasCoat && plan.coat.readsLobeStack && stackServes(plan.coat.exponent);
        const bool diffuse = !diffuseIrradiance && plan.diffuse.readsLobeStack && stackServes(plan.diffuse.exponent);
        auto set1i = [&](int location, bool v) { gl->glUniform1i(location, v ? 1 : 0); };
        auto set1f = [&](int location, double v) { gl->glUniform1f(location, static_cast<float>(v)); };
        gl->glUniform3fv(u.f0, 1, glm::value_ptr(specularF0(m.layers)));
        gl->glUniform3fv(u.diffuseColour, 1, glm::value_ptr(diffuseColour(m.layers)));
        set1f(u.specularLambda, plan.specular.lambda);
        set1f(u.coat, plan.hasCoat ? m.layers.coat : 0.0f);
        set1f(u.coatLambda, plan.coat.lambda);
        set1i(lobeUniforms.useStack, specular);
        set1f(lobeUniforms.exponent, plan.specular.exponent);
        set1i(u.useCoatStack, coat);
        set1f(u.coatExponent, plan.coat.exponent);
        set1i(u.useDiffuseStack, diffuse);
        set1i(u.diffuseIrradiance, diffuseIrradiance);
        bindChain(plan.specular, 0);
        if (plan.hasCoat) bindChain(plan.coat, kCoatChainUnit);
        if (!diffuseIrradiance) bindChain(plan.diffuse, kDiffuseChainUnit);
        auto held = [&](const ObjectLookup& layer) { return layer.mirror || stackHolds(layer.exponent); };
        ObjectRead read;
        read.settled = (roughnessMapped ? specular : held(plan.specular)) && (!plan.hasCoat || held(plan.coat)) &&
                       (diffuseIrradiance || held(plan.diffuse));
        read.fromChain = !read.settled;
        return read;
    }

    // Draws the visible objects with `program` (object.frag, or aov.frag when `aov`), each from
    // the lobe stack where it holds its lobes, else from the chain at the level standing in for it.
    void drawObjects(QOpenGLShaderProgram& program, const Scene& scene, const glm::vec3& eye,
                     const glm::mat4& viewProjection, const glm::mat3& envRotation, const Frustum& frustum,
                     bool aov, bool mapped) {
        program.bind();
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
        const LobeUniforms lobeUniforms{program.uniformLocation("uUseStack"), program.uniformLocation("uExponent")};
        bindStack(program);
        const int locLayered = program.uniformLocation("uLayered");
        const LayeredUniforms layeredUniforms(program);
        const MapUniforms mapUniforms(program);
        // Level of λ in the regular part of the schedule, for the grazing option's per-fragment λ:
        // log2(N / √(32 n(λ))) = λ + log2(N/128) − ½·log2(96) (phong.h).
        gl->glUniform1f(program.uniformLocation("uLevelOffset"),
                        static_cast<float>(std::log2(std::max(environmentFaceSize, 1) / 128.0) - 0.5 * std::log2(96.0)));
        gl->glUniform1f(program.uniformLocation("uLastLevel"), static_cast<float>(std::max(environmentLevels - 1, 0)));
        const bool irradianceReady = uploadedIrradiance != nullptr;

        for (const SceneObject& object : scene.objects) {
            if (!object.visible || !object.mesh || object.mesh->indices.empty()) continue;
            if (drawsMaps(scene.materialOf(object)) != mapped) continue;  // the other program's
            if (!frustum.intersectsSphere(object.worldCentre(), object.worldRadius())) {
                if (!aov) ++counters.objectsCulled;
                continue;
            }
            const GpuMesh& mesh = gpuMesh(object.mesh);
            const Material& m = scene.materialOf(object);
            const glm::mat4 model = object.transform.matrix();
            const glm::mat3 rotation =
                glm::mat3(model) / std::max(std::abs(object.transform.scale), 1e-30f);
            gl->glUniformMatrix4fv(locModel, 1, GL_FALSE, glm::value_ptr(model));
            gl->glUniformMatrix3fv(locNormal, 1, GL_FALSE, glm::value_ptr(rotation));
            gl->glUniform1i(locLayered, m.layered ? 1 : 0);
            ObjectRead read;
            if (m.layered) {
                read = bindLayered(layeredUniforms, lobeUniforms, mapUniforms, m, irradianceReady);
            } else {
                const ObjectLookup plan = planLookup(m, irradianceReady, environmentFaceSize);
                const bool stack = plan.readsLobeStack && (plan.sharperAtGrazing ? stackCurrent() : stackServes(plan.exponent));
                gl->glUniform3fv(locTint, 1, glm::value_ptr(m.tint));
                gl->glUniform1i(locLookup, static_cast<int>(plan.lookup));
                gl->glUniform1i(locGrazing, plan.sharperAtGrazing ? 1 : 0);
                gl->glUniform1f(locLambda, plan.lambda);
                gl->glUniform1i(lobeUniforms.useStack, stack ? 1 : 0);
                gl->glUniform1f(lobeUniforms.exponent, static_cast<float>(plan.exponent));
                // The paper's one statement per object: the sampler holding MIN_LOD, here the chain
                // level standing in for the material's lobe where the stack does not hold it; a
                // mirror reads the mirror texture.
                bindChain(plan, 0);
                read.settled = plan.readsLobeStack && !plan.sharperAtGrazing && stackHolds(plan.exponent);
                read.fromChain = !read.settled && plan.readsChainForLobe();
            }
            gl->glBindVertexArray(mesh.vao);
            gl->glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
            if (aov) continue;
            ++counters.objectsDrawn;
            ++counters.drawCalls;
            if (read.settled) ++counters.objectsSettled;
            else if (read.fromChain) ++counters.objectsFromChain;
        }
    }

    static bool drawsMaps(const Material& m) { return m.layered && m.layers.maps.inUse(); }

    // The objects, in two programs: those without maps, then those with (drawObjects's `mapped`).
    void drawAllObjects(bool aov, const Scene& scene, const glm::vec3& eye, const glm::mat4& viewProjection,
                        const glm::mat3& envRotation, const Frustum& frustum) {
        drawObjects(aov ? *aovProgram : *objectProgram, scene, eye, viewProjection, envRotation, frustum, aov, false);
        if (std::any_of(scene.objects.begin(), scene.objects.end(),
                        [&](const SceneObject& o) { return o.visible && o.mesh && drawsMaps(scene.materialOf(o)); }))
            drawObjects(aov ? *aovMapsProgram : *objectMapsProgram, scene, eye, viewProjection, envRotation, frustum,
                        aov, true);
    }

    // Sends `levels` as the texture's levels firstLevel, firstLevel + 1, … (those below stay) and
    // makes the last of them its GL_TEXTURE_MAX_LEVEL. 32-bit float, as the core holds them: half
    // floats clamp at 65504 (a mirror kept 0.1 % of a one-pixel sun of 1e9, an n = 1024 sphere 7 %)
    // and lose everything below 6e-8 (a map at 1e-30 was black), so the picture depended on the
    // environment's absolute scale. Float costs twice the memory and no measurable frame time on
    // llvmpipe (docs/radiance-range.md, issue 24).
    void uploadCube(GLuint texture, const std::vector<const CubeMap*>& levels, int firstLevel = 0) {
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
        gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        std::vector<float> face;
        for (std::size_t k = 0; k < levels.size(); ++k) {
            const CubeMap& cube = *levels[k];
            const std::size_t level = static_cast<std::size_t>(firstLevel) + k;
            const int n = cube.size();
            face.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * 3);
            for (Face f : kAllFaces) {
                // Interior texels only; our row 0 is t = 0, which is GL's first row.
                std::size_t i = 0;
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        const Rgb& c = cube.at(f, x, y);
                        face[i++] = c.r;
                        face[i++] = c.g;
                        face[i++] = c.b;
                    }
                gl->glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f),
                                 static_cast<GLint>(level), GL_RGB32F, n, n, 0, GL_RGB, GL_FLOAT,
                                 face.data());
            }
        }
        const GLint last = firstLevel + static_cast<GLint>(levels.size()) - 1;
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, last);
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER,
                            last > 0 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
    }

    // The highlighted object's outline (setHighlightedObject), after everything else so nothing
    // covers it: its silhouette marked in the stencil, then the object pushed outward along its
    // normals drawn where the stencil is not marked. Depth is neither tested nor written, so the
    // whole silhouette shows, also where another object hides it.
    void drawOutline(const Scene& scene, const glm::mat4& viewProjection, int width, int height) {
        if (highlighted < 0 || highlighted >= static_cast<int>(scene.objects.size())) return;
        const SceneObject& object = scene.objects[static_cast<std::size_t>(highlighted)];
        if (!object.visible || !object.mesh || object.mesh->indices.empty()) return;
        const GpuMesh& mesh = gpuMesh(object.mesh);
        QOpenGLShaderProgram& program = *outlineProgram;
        program.bind();
        const glm::mat4 model = object.transform.matrix();
        const glm::mat3 rotation = glm::mat3(model) / std::max(std::abs(object.transform.scale), 1e-30f);
        gl->glUniformMatrix4fv(program.uniformLocation("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
        gl->glUniformMatrix4fv(program.uniformLocation("uModel"), 1, GL_FALSE, glm::value_ptr(model));
        gl->glUniformMatrix3fv(program.uniformLocation("uNormalMatrix"), 1, GL_FALSE, glm::value_ptr(rotation));
        gl->glUniform2f(program.uniformLocation("uViewportSize"), static_cast<float>(width), static_cast<float>(height));
        // An orange that reads on sky and ground alike, bright enough to survive the tone map.
        gl->glUniform3f(program.uniformLocation("uColour"), 4.0f, 1.1f, 0.05f);
        gl->glDisable(GL_DEPTH_TEST);
        gl->glDepthMask(GL_FALSE);
        gl->glEnable(GL_STENCIL_TEST);
        gl->glBindVertexArray(mesh.vao);
        // 1: the silhouette, stencil only.
        gl->glStencilFunc(GL_ALWAYS, 1, 0xFF);
        gl->glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        gl->glUniform1f(program.uniformLocation("uWidthPixels"), 0.0f);
        gl->glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
        // 2: the band around it.
        gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        gl->glStencilFunc(GL_NOTEQUAL, 1, 0xFF);
        gl->glStencilMask(0x00);
        gl->glUniform1f(program.uniformLocation("uWidthPixels"), kOutlineWidthPixels);
        gl->glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
        counters.drawCalls += 2;
        gl->glStencilMask(0xFF);
        gl->glDisable(GL_STENCIL_TEST);
        gl->glDepthMask(GL_TRUE);
        gl->glEnable(GL_DEPTH_TEST);
        gl->glBindVertexArray(0);
        program.release();
    }

    GpuMesh& gpuMesh(const std::shared_ptr<const Mesh>& mesh) {
        auto it = meshes.find(mesh.get());
        if (it != meshes.end() && !it->second.source.expired()) return it->second;
        if (it != meshes.end()) releaseMesh(it->second);
        GpuMesh g;
        g.source = mesh;
        // Position and normal, then the asset's UV and tangent where it has them.
        const bool uvs = mesh->uvs.size() == mesh->positions.size();
        const bool tangents = mesh->tangents.size() == mesh->positions.size();
        const std::size_t floats = 6 + (uvs ? 2 : 0) + (tangents ? 4 : 0);
        std::vector<float> interleaved;
        interleaved.reserve(mesh->positions.size() * floats);
        for (std::size_t i = 0; i < mesh->positions.size(); ++i) {
            const glm::vec3& p = mesh->positions[i];
            const glm::vec3& n = mesh->normals[i];
            interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
            if (uvs) interleaved.insert(interleaved.end(), {mesh->uvs[i].x, mesh->uvs[i].y});
            if (tangents) {
                const glm::vec4& t = mesh->tangents[i];
                interleaved.insert(interleaved.end(), {t.x, t.y, t.z, t.w});
            }
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
        const auto stride = static_cast<GLsizei>(floats * sizeof(float));
        gl->glEnableVertexAttribArray(0);
        gl->glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
        gl->glEnableVertexAttribArray(1);
        gl->glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<const void*>(3 * sizeof(float)));
        std::size_t offset = 6;
        if (uvs) {
            gl->glEnableVertexAttribArray(2);
            gl->glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset * sizeof(float)));
            offset += 2;
        }
        if (tangents) {
            gl->glEnableVertexAttribArray(3);
            gl->glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset * sizeof(float)));
        }
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
        // The linear picture in 32-bit float, like the cubes it reads (uploadCube): scene-referred
        // at any scale until the tone pass applies the exposure.
        gl->glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA32F, width, height);
        gl->glGenRenderbuffers(1, &msDepth);
        gl->glBindRenderbuffer(GL_RENDERBUFFER, msDepth);
        gl->glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width,
                                             height);
        gl->glGenFramebuffers(1, &msFbo);
        gl->glBindFramebuffer(GL_FRAMEBUFFER, msFbo);
        gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msColour);
        // Depth and a stencil (the selection outline's mask).
        gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, msDepth);

        gl->glGenTextures(1, &resolveTexture);
        gl->glBindTexture(GL_TEXTURE_2D, resolveTexture);
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
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
// A shader's source with the C++ enums' GLSL names (lookup_plan.h, shaderDefines) after its
// #version line; empty when the resource is missing.
QByteArray shaderSource(const char* path, const char* extraDefines = "") {
    QFile file(QString::fromUtf8(path));
    if (!file.open(QIODevice::ReadOnly)) return {};
    QByteArray source = file.readAll();
    // #include "layered.glsl", "cube_lod.glsl", "lobe_stack.glsl" (GLSL has no includes): the file's text in its
    // place, then #line so the compiler's line numbers stay those of the including file.
    for (const char* name : {"layered.glsl", "material_maps.glsl", "cube_lod.glsl", "lobe_stack.glsl"}) {
        const QByteArray include = QByteArray("#include \"") + name + "\"\n";
        if (const qsizetype at = source.indexOf(include); at >= 0) {
            QFile shared(QStringLiteral(":/mipgloss/shaders/") + QLatin1String(name));
            if (!shared.open(QIODevice::ReadOnly)) return {};
            const int lineAfter = static_cast<int>(source.left(at).count('\n')) + 2;
            source.replace(at, include.size(), shared.readAll() + "#line " + QByteArray::number(lineAfter) + "\n");
        }
    }
    const qsizetype versionEnd = source.indexOf('\n') + 1;
    // #line keeps the compiler's line numbers those of the file.
    source.insert(versionEnd, QByteArray::fromStdString(shaderDefines() + extraDefines + "#line 2\n"));
    return source;
}

std::unique_ptr<QOpenGLShaderProgram> buildProgram(const char* vertexPath, const char* fragmentPath,
                                                   std::string* error, const char* extraDefines = "") {
    auto program = std::make_unique<QOpenGLShaderProgram>();
    if (!program->addCacheableShaderFromSourceCode(QOpenGLShader::Vertex, shaderSource(vertexPath, extraDefines)) ||
        !program->addCacheableShaderFromSourceCode(QOpenGLShader::Fragment, shaderSource(fragmentPath, extraDefines)) ||
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
    impl_->aovProgram = buildProgram(":/mipgloss/shaders/object.vert", ":/mipgloss/shaders/aov.frag", error);
    impl_->outlineProgram = buildProgram(":/mipgloss/shaders/outline.vert", ":/mipgloss/shaders/outline.frag", error);
    impl_->objectMapsProgram = buildProgram(":/mipgloss/shaders/object.vert", ":/mipgloss/shaders/object.frag", error,
                                            "#define MATERIAL_MAPS\n");
    impl_->aovMapsProgram = buildProgram(":/mipgloss/shaders/object.vert", ":/mipgloss/shaders/aov.frag", error,
                                         "#define MATERIAL_MAPS\n");
    if (!impl_->objectProgram || !impl_->backgroundProgram || !impl_->toneProgram || !impl_->aovProgram ||
        !impl_->outlineProgram || !impl_->objectMapsProgram || !impl_->aovMapsProgram) {
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
    for (QOpenGLShaderProgram* program : {impl_->objectProgram.get(), impl_->aovProgram.get(),
                                          impl_->objectMapsProgram.get(), impl_->aovMapsProgram.get()}) {
        program->bind();
        program->setUniformValue("uEnvironment", 0);
        program->setUniformValue("uIrradiance", 1);
        program->setUniformValue("uStack", 2);
        program->setUniformValue("uSplitSum", 3);
        program->setUniformValue("uCoatChain", 4);
        program->setUniformValue("uDiffuseChain", 6);
    }
    impl_->backgroundProgram->bind();
    impl_->backgroundProgram->setUniformValue("uEnvironment", 0);
    impl_->backgroundProgram->setUniformValue("uStack", 2);
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
    for (auto& [key, t] : d.mapTextures) d.gl->glDeleteTextures(1, &t.texture);
    d.mapTextures.clear();
    d.gl->glDeleteTextures(1, &d.whiteTexture);
    d.whiteTexture = 0;
    for (auto& [key, s] : d.samplers) d.gl->glDeleteSamplers(1, &s);
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
    d.gl->glDeleteVertexArrays(1, &d.emptyVao);
    d.objectProgram.reset();
    d.backgroundProgram.reset();
    d.toneProgram.reset();
    d.aovProgram.reset();
    d.objectMapsProgram.reset();
    d.aovMapsProgram.reset();
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
    const float grey = 0.18f;  // without a background: a mid grey, linear
    const bool transparent = d.transparentBackground && !scene.display.showBackground;
    if (transparent)
        gl->glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    else
        gl->glClearColor(grey, grey, grey, 1.0f);
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
        gl->glActiveTexture(GL_TEXTURE1);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.irradianceTexture);
        gl->glBindSampler(1, 0);
        gl->glActiveTexture(GL_TEXTURE0);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.environmentTexture);

        d.drawAllObjects(false, scene, camera.position(), viewProjection, envRotation, frustum);

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
    tone.setUniformValue("uAlpha", transparent ? 1 : 0);
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

void Renderer::setTextures(std::shared_ptr<const TextureCache> textures) { impl_->textureCache = std::move(textures); }

void Renderer::setLobes(const std::vector<std::shared_ptr<const LobeStackEntry>>& lobes) {
    Impl& d = *impl_;
    if (!d.gl) return;
    std::map<int, std::shared_ptr<const LobeStackEntry>> wanted;
    for (const auto& lobe : lobes)
        if (lobe && lobe->cube && lobe->index >= 1 && lobe->index <= kStackLast) wanted[lobe->index] = lobe;
    if (wanted == d.stackEntries) return;
    d.stackEntries = wanted;
    d.stackTable.fill(glm::vec4(0.0f));
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
    std::vector<std::pair<int, int>> sizes;
    for (const auto& [index, lobe] : wanted) sizes.emplace_back(index, lobe->cube->size());
    GLint maxSize = 0;
    d.gl->glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const LobeStackAtlas atlas = lobeStackAtlas(sizes, std::min(4096, static_cast<int>(maxSize)));
    std::vector<float> texels(static_cast<std::size_t>(atlas.width) * static_cast<std::size_t>(atlas.height) * 3, 0.0f);
    std::size_t i = 0;
    d.stackScales.fill(1.0f);
    for (const auto& [index, lobe] : wanted) {
        const AtlasPlacement& at = atlas.placed[i++];
        const CubeMap& cube = *lobe->cube;
        const int stride = cube.size() + 2;
        float largest = 0.0f;
        for (Face f : kAllFaces)
            for (const Rgb& c : cube.faceStorage(f)) largest = std::max({largest, c.r, c.g, c.b});
        // 2^k with largest·2^k in [32704, 65408): exact, and within float's range for any entry
        // (the import keeps radiance in [0, 1e20], and a map at 1e-30 still has 2^99 of room).
        const float scale = largest > 0.0f ? std::exp2(std::floor(std::log2(65408.0f / largest))) : 1.0f;
        d.stackScales[static_cast<std::size_t>(index)] = 1.0f / scale;
        for (Face f : kAllFaces) {
            const std::vector<Rgb>& face = cube.faceStorage(f);  // (size + 2)² with the border, row 0 first
            const int fx = at.x + (static_cast<int>(f) % 3) * stride, fy = at.y + (static_cast<int>(f) / 3) * stride;
            for (int y = 0; y < stride; ++y)
                for (int x = 0; x < stride; ++x) {
                    const Rgb& c = face[static_cast<std::size_t>(y) * static_cast<std::size_t>(stride) + static_cast<std::size_t>(x)];
                    float* t = &texels[(static_cast<std::size_t>(fy + y) * static_cast<std::size_t>(atlas.width) +
                                        static_cast<std::size_t>(fx + x)) * 3];
                    t[0] = c.r * scale;
                    t[1] = c.g * scale;
                    t[2] = c.b * scale;
                }
        }
        d.stackTable[static_cast<std::size_t>(index)] =
            glm::vec4(static_cast<float>(at.x), static_cast<float>(at.y), static_cast<float>(cube.size()), 1.0f);
        ++d.counters.lobeUploads;
    }
    d.gl->glBindTexture(GL_TEXTURE_2D, d.stackTexture);
    d.gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    d.gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB9_E5, atlas.width, atlas.height, 0, GL_RGB, GL_FLOAT, texels.data());
    d.counters.stackBytes = static_cast<std::uint64_t>(atlas.width) * static_cast<std::uint64_t>(atlas.height) * 4;
}

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
    gl->glActiveTexture(GL_TEXTURE1);
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.irradianceTexture);
    gl->glBindSampler(1, 0);
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, d.environmentTexture);
    d.drawAllObjects(true, scene, camera.position(), viewProjection,
                     environmentRotation(scene.display.environmentRotationDegrees),
                     Frustum::fromViewProjection(viewProjection));
    gl->glBindSampler(0, 0);

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
    // A pixel beside the background or another lobe is not one lobe at one direction in the
    // picture (multisampling mixes them): not exact. Neighbours on one surface differ a little
    // (each pixel's footprint widens its lobe by its own amount, lobe_stack.glsl): within 5 %,
    // a mix of them is within 0.05 % of the lobe between (the stack's own blend of lobes 19 %
    // apart is within 0.6 %), so they count as the same lobe.
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x);
            if (aov.exact[i] == 0.0f) continue;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    const bool inside = nx >= 0 && ny >= 0 && nx < width && ny < height;
                    const float e = inside ? first[static_cast<std::size_t>(ny) * width + static_cast<std::size_t>(nx)].w : 0.0f;
                    if (!(std::abs(e - first[i].w) <= 0.05f * first[i].w)) aov.exact[i] = 0.0f;
                }
        }
    return aov;
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
