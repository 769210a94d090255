// Shared by the render tests: an offscreen renderer per test binary, picture output on failure,
// and the CPU side of the paper's lookup (the same direction, the same level, on the core's chain).
#pragma once

#include "mipgloss/ibl/colour.h"
#include "mipgloss/scene/camera.h"
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/offscreen.h"

#include <QCoreApplication>
#include <QImage>
#include <QString>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mipgloss::test {

inline std::filesystem::path outputDir() {
    std::filesystem::path dir = MIPGLOSS_TEST_OUTPUT_DIR;
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::unique_ptr<ui::OffscreenRenderer>& sharedRendererSlot() {
    static std::unique_ptr<ui::OffscreenRenderer> renderer;
    return renderer;
}

// One context for the whole binary (llvmpipe contexts are cheap, but shader compiles are not).
// Released while the application still exists: its GL teardown needs the platform.
inline ui::OffscreenRenderer* sharedRenderer(std::string* error = nullptr) {
    std::unique_ptr<ui::OffscreenRenderer>& renderer = sharedRendererSlot();
    static std::string failure;
    static bool tried = false;
    if (!tried) {
        tried = true;
        auto r = std::make_unique<ui::OffscreenRenderer>();
        if (r->initialize(&failure)) renderer = std::move(r);
        qAddPostRoutine([] { sharedRendererSlot().reset(); });
    }
    if (error) *error = failure;
    return renderer.get();
}

// One unit sphere at the origin with `material`, no background, no multisampling (each pixel is
// one fragment at its centre): what the per-pixel checks compare. The mesh (256×128 quads) is
// made once and shared, so the renderer uploads it once per binary.
inline Scene sphereScene(const Material& material) {
    static const auto sphere = std::make_shared<const Mesh>(makeSphere(128, 256));
    Scene scene;
    SceneObject object;
    object.name = "sphere";
    object.mesh = sphere;
    scene.addObject(object, material);
    scene.display.showBackground = false;
    scene.display.samples = 0;
    return scene;
}

// Linear HDR pixels (bottom row first) -> an 8-bit picture for humans: clipped, sRGB-encoded.
inline QImage hdrToImage(const std::vector<glm::vec4>& hdr, int width, int height, float scale = 1.0f) {
    QImage image(width, height, QImage::Format_RGB32);
    auto encode = [](float c) {
        return static_cast<int>(std::lround(linearToSrgb(std::clamp(static_cast<double>(c), 0.0, 1.0)) * 255.0));
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec4& p = hdr[static_cast<std::size_t>(y * width + x)];
            image.setPixel(x, height - 1 - y, qRgb(encode(p.r * scale), encode(p.g * scale), encode(p.b * scale)));
        }
    return image;
}

// The camera ray through a pixel centre (x from the left, y from the bottom).
struct Ray {
    glm::vec3 origin, direction;
};
inline Ray pixelRay(const glm::mat4& inverseViewProjection, int x, int y, int width, int height) {
    const float nx = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f;
    const float ny = 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height) - 1.0f;
    const glm::vec4 a = inverseViewProjection * glm::vec4(nx, ny, -1.0f, 1.0f);
    const glm::vec4 b = inverseViewProjection * glm::vec4(nx, ny, 1.0f, 1.0f);
    const glm::vec3 o = glm::vec3(a) / a.w;
    return {o, glm::normalize(glm::vec3(b) / b.w - o)};
}

// Nearest hit of a ray with the unit sphere at the origin.
inline std::optional<glm::vec3> hitUnitSphere(const Ray& ray) {
    const float b = glm::dot(ray.origin, ray.direction);
    const float c = glm::dot(ray.origin, ray.origin) - 1.0f;
    const float disc = b * b - c;
    if (disc <= 0.0f) return std::nullopt;
    const float t = -b - std::sqrt(disc);
    if (t <= 0.0f) return std::nullopt;
    return ray.origin + t * ray.direction;
}

// The GL cube-map footprint LOD (OpenGL 4.5 §8.14.1, with §8.13's face coordinates) of a lookup
// direction field, from its finite differences to the next pixel in x and y.
inline float footprintLod(const glm::vec3& d, const glm::vec3& dx, const glm::vec3& dy, int faceSize) {
    const FaceCoord c = directionToFace(d);
    // Face coordinates of v on d's face plane, as GL differentiates them.
    auto onFace = [&](const glm::vec3& v) { return faceCoordOnPlane(c.face, v); };
    const glm::vec2 st = onFace(d);
    const glm::vec2 ddx = (onFace(dx) - st) * static_cast<float>(faceSize);
    const glm::vec2 ddy = (onFace(dy) - st) * static_cast<float>(faceSize);
    const float rho = std::max(glm::length(ddx), glm::length(ddy));
    return std::log2(std::max(rho, 1e-30f));
}


// The exact lobe of each pixel's own exponent at its direction. Exponents are many (each pixel's
// footprint widens its lobe by its own amount), so the truth is computed at exponents 2^(1/32)
// apart in n + 1 around them and interpolated in 1/(n + 2) (the blend the stack itself makes 2^¼
// apart is within 0.6 %; this one, 8× finer, within 0.6 %/64 = 0.01 %).
inline std::vector<Rgb> exactLobesAt(const CubeMap& base, const std::vector<double>& exponents, const std::vector<glm::vec3>& dirs) {
    constexpr double kCellsPerOctave = 32.0;
    auto cellOf = [&](double n) { return static_cast<int>(std::floor(std::log2(n + 1.0) * kCellsPerOctave)); };
    auto exponentAt = [&](int cell) { return std::exp2(cell / kCellsPerOctave) - 1.0; };
    std::map<int, std::vector<std::size_t>> cells;
    for (std::size_t i = 0; i < exponents.size(); ++i) cells[cellOf(exponents[i])].push_back(i);
    std::vector<Rgb> truth(dirs.size());
    for (const auto& [cell, members] : cells) {
        std::vector<glm::vec3> d;
        for (std::size_t i : members) d.push_back(dirs[i]);
        const double n0 = exponentAt(cell), n1 = exponentAt(cell + 1);
        const std::vector<Rgb> a = referenceLobeAt(base, n0, d), b = referenceLobeAt(base, n1, d);
        for (std::size_t k = 0; k < members.size(); ++k) {
            const double n = exponents[members[k]];
            const double t = (1.0 / (n + 2.0) - 1.0 / (n0 + 2.0)) / (1.0 / (n1 + 2.0) - 1.0 / (n0 + 2.0));
            truth[members[k]] = a[k] + static_cast<float>(t) * (b[k] - a[k]);
        }
    }
    return truth;
}

// A picture as `mipgloss render` draws it, settled (every lobe in use from its own cube, made first),
// and its AOV, from a fixed orbit (yaw 30°, pitch 20°) framing the scene.
struct SettledRender {
    std::vector<glm::vec4> hdr;
    ui::AovImage aov;
};

inline SettledRender renderSettled(ui::OffscreenRenderer& renderer, const Scene& scene,
                                   const std::shared_ptr<const PreparedEnvironment>& env, int size) {
    renderer.setLobes(makeStackEntries(*env, scene));
    OrbitCamera camera;
    camera.yawDegrees = 30.0f;
    camera.pitchDegrees = 20.0f;
    camera.frame(sceneBounds(scene), 1.0f);
    SettledRender out;
    renderer.render(scene, camera, env, size, size);
    int w = 0, h = 0;
    out.hdr = renderer.lastHdr(w, h);
    out.aov = renderer.renderAov(scene, camera, env, size, size);
    return out;
}

}  // namespace mipgloss::test
