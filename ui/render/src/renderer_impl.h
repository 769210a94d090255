// The renderer's state (renderer.h), shared by its passes: the GPU resources (gpu_resources.cpp),
// the object pass (object_pass.cpp), the outline (outline_pass.cpp) and the AOV (aov_pass.cpp); the
// frame that composes them is renderer.cpp.
#pragma once

#include "mipgloss/ui/renderer.h"

#include "mipgloss/scene/lookup_plan.h"
#include "mipgloss/assets/textures.h"
#include "texture_units.h"

#include <QOpenGLFunctions_4_1_Core>
#include <QOpenGLShaderProgram>

#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <array>
#include <map>
#include <optional>
#include <unordered_map>

namespace mipgloss::ui {

struct GpuMesh {
    std::weak_ptr<const Mesh> source;
    GLuint vao = 0, vbo = 0, ibo = 0;
    GLsizei indexCount = 0;
    bool uvs1 = false, colours = false;  // TEXCOORD_1 and COLOR_0 in the buffer (locations 4, 5)
};

// World direction -> environment direction: turning the environment by θ about +Y is looking up
// the direction turned by -θ.
inline glm::mat3 environmentRotation(float degrees) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(-degrees), glm::vec3(0, 1, 0)));
}

struct Renderer::Impl {
    QOpenGLFunctions_4_1_Core* gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> objectProgram, backgroundProgram, toneProgram, aovProgram, outlineProgram;
    // object.frag and aov.frag built with MATERIAL_MAPS: the layered materials with texture maps
    // (MaterialMaps::inUse), drawn after the others (object.frag says why apart).
    std::unique_ptr<QOpenGLShaderProgram> objectMapsProgram, aovMapsProgram;
    std::unique_ptr<QOpenGLShaderProgram> objectLayeredProgram, aovLayeredProgram;
    // Built on first use (tapsProgram): none, until an object needs taps.
    std::unique_ptr<QOpenGLShaderProgram> objectTapsProgram, objectMapsTapsProgram;
    bool tapsProgramFailed[2] = {false, false};
    QOpenGLShaderProgram* tapsProgram(bool maps);
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

    // Texture maps on the GPU, one per decoded image and colour space (sRGB for base colour and
    // emission, linear for the rest), mip-mapped and anisotropically filtered; the decoded image
    // is kept alive here while its texture is (TextureCache hands out the same pointer).
    struct GpuTexture {
        std::shared_ptr<const TextureImage> image;
        GLuint texture = 0;
    };
    std::map<std::pair<std::string, bool>, GpuTexture> mapTextures;
    std::shared_ptr<const TextureCache> textures;  // setTextures: the decoded images maps read
    float maxAnisotropy = -1.0f;  // queried once: 0 when the GL has no anisotropic filtering
    GLuint splitSumTexture = 0;      // the split-sum table (specular.h), once a layered material is drawn
    GLuint lobeMeanTexture = 0;      // its lobes' mean directions (ggx_sampling.h, meanLobe), likewise
    GLuint fittedLobesTexture = 0;   // the fitted lobes' nodes (ggx_fitted_lobes.h), a 2D array, likewise
    GLuint whiteTexture = 0;         // 1×1 white: what a map unit holds when the material has no such map

    std::map<int, GLuint> samplers;  // level key -> sampler with GL_TEXTURE_MIN_LOD = that level

    // The lobe stack (lobes.h): its entries on the GPU, packed in one 2D atlas (lobeStackAtlas),
    // and the table the shaders find them by (lobe_stack.glsl).
    std::map<int, std::shared_ptr<const LobeStackEntry>> stackEntries;  // index -> entry
    GLuint stackTexture = 0;
    std::array<glm::vec4, kStackSlots> stackTable{};  // block x, y, face size, 1 when present
    std::array<float, kStackSlots> stackExponents{};
    std::array<float, kStackSlots> stackScales{};  // what an entry's stored texels are multiplied by
    // The remainder entries (lobes.h, LobeStackEntry::remainder) in the same atlas: per index,
    // block x, y, face size and what its texels are multiplied by (0 when absent).
    std::array<glm::vec4, kStackSlots> remainderTable{};
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

    // Whether the stack on the GPU was made from the current environment.
    bool stackCurrent() const {
        return !stackEntries.empty() && environment && environment->filter &&
               stackEntries.begin()->second->filter == environment->filter;
    }
    // Whether shaders should look lobe n up in the stack (they then check, per fragment, that the
    // entries the footprint-widened lobe blends are there, and read the chain where not).
    bool stackServes(double exponent) const { return stackCurrent() && stackBlend(exponent, stackBaseSize).has_value(); }
    // Whether the remainder entries j0 … j1 are all on the GPU, from the current environment.
    bool remainderHolds(int first, int last) const {
        if (!stackCurrent() || first > last) return false;
        for (int j = first; j <= last; ++j)
            if (!stackEntries.count(stackKey(j, true))) return false;
        return true;
    }
    // Whether the stack holds lobe n itself: both entries it blends (the settled picture's test).
    bool stackHolds(double exponent) const {
        if (!stackCurrent()) return false;
        const auto blend = stackBlend(exponent, stackBaseSize);
        return blend && stackEntries.count(blend->sharper) && (blend->widerWeight == 0.0 || stackEntries.count(blend->wider));
    }

    // Where a program takes a layered material's values, its maps' and a single lobe's (object_pass.cpp),
    // and what drawing one object read.
    struct LayeredUniforms;
    struct MapUniforms;
    struct LobeUniforms;
    struct ObjectRead;

    // GPU resources (gpu_resources.cpp).
    // The sampler reading the chain from `level` on (GL_TEXTURE_MIN_LOD = level).
    GLuint sampler(float level);
    std::map<int, GLuint> mapSamplers;  // wrap and filter key -> sampler (mapSampler)
    GLuint mapSampler(const TextureSampling& sampling);
    // The split-sum table (specular.h) as an RG32F texture on TextureUnit::SplitSum, made the first
    // time a layered material is drawn (building the table takes about 0.2 s, which no single-lobe scene pays).
    void bindSplitSum();
    // The GL texture of map `ref` (sRGB or linear), uploaded the first time; 0 when its image is
    // not decoded (yet, or refused: TextureCache::problem).
    GLuint mapTexture(const TextureRef& ref, bool srgb);
    // Frees the map textures no material of `scene` reads any more.
    void collectMapTextures(const Scene& scene);
    // Sends `levels` as the texture's levels firstLevel, firstLevel + 1, … (those below stay) and
    // makes the last of them its GL_TEXTURE_MAX_LEVEL. 32-bit float, as the core holds them: half
    // floats clamp at 65504 (a mirror kept 0.1 % of a one-pixel sun of 1e9, an n = 1024 sphere 7 %)
    // and lose everything below 6e-8 (a map at 1e-30 was black), so the picture depended on the
    // environment's absolute scale. Float costs twice the memory and no measurable frame time on
    // llvmpipe (docs/radiance-range.md, issue 24).
    void uploadCube(GLuint texture, const std::vector<const CubeMap*>& levels, int firstLevel = 0);
    GpuMesh& gpuMesh(const std::shared_ptr<const Mesh>& mesh);
    void releaseMesh(GpuMesh& g);
    // Frees the GPU copies of meshes no scene object holds any more.
    void collectMeshes();
    void releaseTargets();
    void ensureTargets(int width, int height, int samples);

    // The object pass (object_pass.cpp).
    // The stack's table and atlas for `program` (object, AOV and background programs).
    void bindStack(QOpenGLShaderProgram& program);
    // Binds the chain (or, for a mirror, the mirror texture) to `unit` with the sampler holding
    // the plan's MIN_LOD; unit 0 stays active.
    void bindChain(const ObjectLookup& plan, GLuint unit);
    // A layered material's maps: binds each decoded one to its unit (white where none) and sets
    // the factors. Returns whether the roughness map is read (each fragment its own lobe).
    bool bindMaps(const MapUniforms& u, const Layers& l);
    // Sets a layered material's uniforms and binds its three lookups; `lookups` is the display's K
    // and `lightsShaded` whether it shades the bright lights (each layer's lookups: ggxLayerLookups).
    ObjectRead bindLayered(const LayeredUniforms& u, const LobeUniforms& lobeUniforms, const MapUniforms& mapUniforms,
                           const Material& m, bool irradianceReady, int lookups, bool lightsShaded);
    // Draws the visible objects with `program` (object.frag, or aov.frag when `aov`), each from
    // the lobe stack where it holds its lobes, else from the chain at the level standing in for it.
    // Whether an object's layered material is drawn with the maps' program: it has maps, or its
    // mesh has vertex colours (COLOR_0 multiplies the base colour there).
    static bool drawsMaps(const SceneObject& o, const Material& m) {
        return m.layered && (m.layers.maps.inUse() || (o.mesh && !o.mesh->colours.empty()));
    }
    // Which program draws an object: the single lobe, the glTF material, or it with maps; each
    // layered one with or without taps along the pixel's footprint (lookup_plan.h,
    // drawsFootprintTaps).
    enum class ObjectProgram { Single, Layered, LayeredMaps, LayeredTaps, LayeredMapsTaps };
    static ObjectProgram programOf(const Scene& scene, const SceneObject& o) {
        const Material& m = scene.materialOf(o);
        if (!m.layered) return ObjectProgram::Single;
        const bool taps = scene.display.footprintTaps && drawsFootprintTaps(m);
        if (drawsMaps(o, m)) return taps ? ObjectProgram::LayeredMapsTaps : ObjectProgram::LayeredMaps;
        return taps ? ObjectProgram::LayeredTaps : ObjectProgram::Layered;
    }
    static bool isBlended(const Material& m) { return m.layered && m.layers.maps.alphaMode == AlphaMode::Blend; }
    // Draws scene.objects[i] for each i of `objects`, in that order, with `program`.
    void drawObjects(QOpenGLShaderProgram& program, const Scene& scene, const std::vector<int>& objects,
                     const glm::vec3& eye, const glm::mat4& viewProjection, const glm::mat3& envRotation,
                     const Frustum& frustum, bool aov);

    // Which objects drawAllObjects draws: those that cover what is behind them (opaque and
    // masked), those blended over it (glTF's BLEND: after the background, farthest first, depth
    // not written), or every one as if opaque (the AOV: what the nearest surface is).
    enum class ObjectSet { Covering, Blended, All };
    void drawAllObjects(bool aov, ObjectSet set, const Scene& scene, const glm::vec3& eye,
                        const glm::mat4& viewProjection, const glm::mat3& envRotation, const Frustum& frustum);

    // The outline pass (outline_pass.cpp).
    // The highlighted object's outline (setHighlightedObject), after everything else so nothing
    // covers it: its silhouette marked in the stencil, then the object pushed outward along its
    // normals drawn where the stencil is not marked. Depth is neither tested nor written, so the
    // whole silhouette shows, also where another object hides it.
    void drawOutline(const Scene& scene, const glm::mat4& viewProjection, int width, int height);
};

}  // namespace mipgloss::ui
