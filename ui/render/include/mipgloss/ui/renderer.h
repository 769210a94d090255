// The OpenGL renderer shared by the viewport widget and offscreen rendering. It holds GL state
// only (textures, samplers, buffers, programs) and draws a mipgloss::Scene it is handed.
//
// The paper's method (Ashikhmin & Ghosh 2002, §4): the environment is one cube texture holding the
// chain's read levels (GL_TEXTURE_MAX_LEVEL = lastReadLevel), trilinear filtering,
// GL_TEXTURE_CUBE_MAP_SEAMLESS on. A material's λ means one Phong lobe n(λ) (phong.h). Where the
// lobe stack holds that lobe (setLobes; lobes.h, lobe_stack.glsl) every fragment reads it exactly,
// widened by its own footprint, at any λ, the moment λ changes. Where the stack does not hold it
// yet, the object reads the chain at the level standing in for that lobe, held as a sampler
// object's GL_TEXTURE_MIN_LOD, so the GPU picks max(level, footprint LOD). Samplers are shared by
// materials with the same level; changing λ picks a sampler, nothing is rebuilt.
//
// Frame: objects and background into a multisampled RGBA32F target (linear HDR at any scale,
// docs/radiance-range.md), resolved, then one pass applies exposure, the tone map and the sRGB
// encoding into the caller's framebuffer.
// Requires an OpenGL 4.1 core context (current during every call).
#pragma once

#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/scene/material_truth.h"
#include "mipgloss/scene/scene.h"

#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mipgloss {
class TextureCache;  // mipgloss/assets/textures.h
}

namespace mipgloss::ui {

struct RenderCounters {
    std::uint64_t frames = 0;
    std::uint64_t baseUploads = 0;        // imported base cubes sent (mirror texture and level 0)
    std::uint64_t chainUploads = 0;       // chains sent to the GPU (their levels below the base)
    std::uint64_t irradianceUploads = 0;
    std::uint64_t meshUploads = 0;
    std::uint64_t samplersCreated = 0;
    std::uint64_t objectsDrawn = 0;       // in the last frame
    std::uint64_t objectsCulled = 0;      // in the last frame (outside the view frustum)
    std::uint64_t drawCalls = 0;          // in the last frame
    std::uint64_t lobeUploads = 0;        // lobe stack entries sent to the GPU (a new set sends all again)
    std::uint64_t lobesResident = 0;      // lobe stack entries on the GPU now
    std::uint64_t stackBytes = 0;         // the lobe stack's atlas on the GPU (RGB9_E5, 4 bytes a texel)
    std::uint64_t objectsSettled = 0;     // in the last frame: every lobe read from the lobe stack
    std::uint64_t objectsFromChain = 0;   // in the last frame: blurred, read from the chain
    std::uint64_t textureUploads = 0;     // texture maps sent to the GPU (each image and colour space once)
    std::uint64_t textureBytes = 0;       // texture maps on the GPU now, mip levels included (RGBA8)
};

// The largest picture this OpenGL can draw, and what limits it: each axis is the smallest of
// GL_MAX_TEXTURE_SIZE (the HDR targets are textures), GL_MAX_RENDERBUFFER_SIZE (the multisampled
// ones) and GL_MAX_VIEWPORT_DIMS; `widthLimit` and `heightLimit` name the one that binds. The
// multisampled target takes at most maxSamples samples (GL_MAX_SAMPLES). A size beyond these is
// refused before anything is drawn (`mipgloss render --size`), never left to GL to fail.
struct RenderSizeLimits {
    int maxWidth = 0, maxHeight = 0;
    const char* widthLimit = "";
    const char* heightLimit = "";
    int maxSamples = 0;
};

// The per-pixel account of a render (mipgloss render --aov), bottom row first.
struct AovImage {
    int width = 0, height = 0;
    std::vector<glm::vec3> direction;  // unit direction the environment is read at (baked frame)
    std::vector<float> exponent;       // the lobe shown; 0 where no object, +inf for a mirror
    std::vector<float> exact;          // 1 where the pixel is meant to equal that lobe there
    // Per pixel, every object: N·v (the view's cosine with the shading normal).
    std::vector<float> cosView;
    // A layered material's layers (layered.h): the direction each read (the fields above are its
    // specular layer), its lobe (diffuse: 1) and its weight; 0 elsewhere and for a layer the
    // material lacks. At an exact pixel the picture is Σ weight ⊙ lobe(direction).
    struct Layer {
        std::vector<glm::vec3> direction;
        std::vector<float> exponent;
        std::vector<glm::vec3> weight;
    };
    Layer diffuse, specular, coat;
    bool layered = false;  // some object drawn has a layered material
};

// Pixel i's normal and view (N: the diffuse layer's direction, v = 2(N·R)N − R from the specular's
// R) and their change to the next pixels right and down, from its neighbours on the object: what
// its truth over its area moves across (material_truth.h, materialTruthOverPixel). A layered
// material's AOV.
PixelGeometry aovPixelGeometry(const AovImage& aov, std::size_t i);

class Renderer {
public:
    Renderer();
    ~Renderer();  // call destroy() first, with the context current
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Compiles the shaders; false with `error` set when the context cannot run them.
    bool initialize(std::string* error);
    void destroy();
    bool isInitialized() const;

    // Uploads what of the environment is not on the GPU yet: a new base (to the mirror texture
    // and the chain texture's level 0), a new chain (its levels below the base: every builder's
    // level 0 is the base), a new irradiance map. A PreparedEnvironment never changes once made,
    // so its identity is its version. An early one (no chain yet) is drawn from its base with
    // GL's box mips standing in for the chain: the `box` builder's picture, whose lobes are
    // narrower than the schedule's, so glossy objects look sharper until the chain arrives;
    // its chain then sends only the levels below the base.
    void setEnvironment(const std::shared_ptr<const PreparedEnvironment>& environment);
    bool hasEnvironment() const;

    // The lobe stack's entries (lobes.h): replaces the previous set (the atlas is packed and sent
    // again when the set changes). Entries made from another environment than the current one
    // are not read.
    void setLobes(const std::vector<std::shared_ptr<const LobeStackEntry>>& lobes);
    // The decoded images the scene's texture maps read: the caller's (one per document or command),
    // shared because a worker may be filling it while frames are drawn. Null: every map is drawn as
    // missing (the material without it).
    void setTextures(std::shared_ptr<const TextureCache> textures);

    // Draws into framebuffer `targetFbo` (0 = default) of `width` × `height` pixels.
    void render(const Scene& scene, const OrbitCamera& camera, int width, int height,
                unsigned targetFbo);

    // Limits what render() writes into the target to the rectangle (x, y from the bottom left, in
    // pixels), leaving the rest of the target as it was: a split view draws its right half over
    // its left this way. The whole picture is still drawn (the rectangle only scissors the final
    // pass). clearOutputRect() writes the whole target again.
    void setOutputRect(int x, int y, int width, int height);
    void clearOutputRect();

    // With the background hidden, what is not an object is transparent: cleared to alpha 0 instead
    // of a mid grey, the tone pass un-premultiplies the resolved colour before the tone map and
    // writes the coverage as alpha (an image exported with an alpha channel). Off by default: the
    // window's view is opaque.
    void setTransparentBackground(bool transparent);

    // Outlines object `index` of the scene render() draws (-1: none): a band kOutlineWidthPixels
    // wide around its whole silhouette, drawn over whatever hides it, so a selected object is
    // found even behind another. The window's view sets it; pictures written to files never do.
    void setHighlightedObject(int index);
    static constexpr float kOutlineWidthPixels = 2.0f;

    // The same view's per-pixel directions, exponents and exactness (no multisampling; pixels
    // next to the background or to another lobe are never exact).
    AovImage renderAov(const Scene& scene, const OrbitCamera& camera, int width, int height);

    // The last frame's linear HDR colour (before exposure and tone mapping), bottom row first,
    // RGBA. For the render tests' CPU comparison.
    std::vector<glm::vec4> readHdr(int& width, int& height);

    const RenderCounters& counters() const;

    // The GL version and renderer strings, for logs.
    std::string glDescription() const;

    // What this context can draw (RenderSizeLimits); zeros before initialize().
    RenderSizeLimits maxRenderSize() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mipgloss::ui
