// Issue 24, item 6: the picture does not depend on the environment's absolute scale. A held-out
// HDRI (tests/radiance_range.h) with a one-pixel sun of 1e9 keeps the sun's energy in the picture
// (mirror, glossy n = 1024 from its stack entry, diffuse from the irradiance map) within 1 %, and
// the map scaled by 1e-30 renders, after an exposure of log2(1e30), as the map at its own scale.
// Before float storage the uploads and picture targets were half floats: the sun clamped at 65504
// and a map at 1e-30 was black.
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/environment.h"
#include "radiance_range.h"
#include "render_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <glm/matrix.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <tuple>

namespace mipgloss {
namespace {

constexpr int kFace = 128, kPixels = 160;

struct MapCase {
    double scale;
    float sun;
    bool keepMap;
    bool operator<(const MapCase& o) const {
        return std::tie(scale, sun, keepMap) < std::tie(o.scale, o.sun, o.keepMap);
    }
};

std::shared_ptr<const PreparedEnvironment> environment(const MapCase& c) {
    static std::map<MapCase, std::shared_ptr<const PreparedEnvironment>> cache;
    auto& env = cache[c];
    if (!env) {
        const auto file = test::outputDir() / "radiance_range_map.exr";
        test::writeRangeMap(file, c.scale, c.sun, c.keepMap);
        EnvironmentSettings settings;
        settings.source = file.string();
        settings.faceSize = kFace;
        env = std::make_shared<const PreparedEnvironment>(prepareEnvironment(settings, ChainNeeds{16, true}));
    }
    return env;
}

Material materialFor(const char* name) {
    Material m;
    if (std::string(name) == "mirror") m.lambda = 0.0f;
    else if (std::string(name) == "n 1024") m.lambda = static_cast<float>(exponentToLambda(1024.0));
    else if (std::string(name) == "n 64") m.lambda = static_cast<float>(exponentToLambda(64.0));
    else {
        m.mode = LookupMode::Normal;
        m.useIrradiance = true;
    }
    return m;
}

// The settled picture's linear pixels and whether each is on the sphere.
struct Picture {
    std::vector<glm::vec4> hdr;
    std::vector<bool> onSphere;
    glm::mat4 inverse;
};

Picture render(const char* material, const MapCase& map) {
    ui::OffscreenRenderer* renderer = test::sharedRenderer();
    const Scene scene = test::sphereScene(materialFor(material));
    Picture p;
    p.hdr = test::renderSettled(*renderer, scene, environment(map), kPixels).hdr;
    OrbitCamera camera;
    camera.yawDegrees = 30.0f;
    camera.pitchDegrees = 20.0f;
    camera.frame(sceneBounds(scene), 1.0f);
    p.inverse = glm::inverse(camera.projection(1.0f, sceneBounds(scene)) * camera.view());
    p.onSphere.resize(p.hdr.size());
    for (int y = 0; y < kPixels; ++y)
        for (int x = 0; x < kPixels; ++x)
            p.onSphere[static_cast<std::size_t>(y * kPixels + x)] =
                test::hitUnitSphere(test::pixelRay(p.inverse, x, y, kPixels, kPixels)).has_value();
    return p;
}

glm::dvec3 sumOnSphere(const Picture& p) {
    glm::dvec3 s(0.0);
    for (std::size_t i = 0; i < p.hdr.size(); ++i)
        if (p.onSphere[i]) s += glm::dvec3(p.hdr[i]);
    return s;
}

TEST(RadianceRange, SunOf1e9KeepsItsEnergyInThePicture) {
    std::string error;
    ASSERT_NE(test::sharedRenderer(&error), nullptr) << error;
    MIPGLOSS_REQUIRE_ASSET(test::rangeMapAsset());
    // The sun alone (a black map): what it adds to the picture. The reference is the same sun at
    // 1e3, where every value the GPU stores is well inside half's range, times 1e6: rendering is
    // linear in the environment, so the two agree unless a value was clamped or underflowed.
    const MapCase big{1.0, 1e9f, false}, small{1.0, 1e3f, false};
    for (const char* material : {"mirror", "n 1024", "diffuse"}) {
        const glm::dvec3 a = sumOnSphere(render(material, big)), b = sumOnSphere(render(material, small)) * 1e6;
        std::printf("[ range ] %-8s sun 1e9 / (1e6 × sun 1e3) over the sphere: %.5f\n", material, a.g / b.g);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c] / b[c], 1.0, 0.01) << material << " channel " << c;
    }
    // The diffuse sphere against the sun's energy computed analytically: E/π at a normal N is
    // Φ·max(0, N·s)/π for a point sun of energy Φ = L·Ω (its lat-long pixel's exact solid angle)
    // in direction s (the imported base's energy centroid).
    const auto env = environment(big);
    glm::dvec3 centroid(0.0);
    double total = 0.0;
    const CubeMap& base = *env->base;
    for (Face f : kAllFaces)
        for (int y = 0; y < base.size(); ++y)
            for (int x = 0; x < base.size(); ++x) {
                const double e = base.at(f, x, y).g * texelSolidAngle(x, y, base.size());
                centroid += e * glm::dvec3(texelDirection(f, x, y, base.size()));
                total += e;
            }
    const double phi = 1e9 * test::sunSolidAngle(1024, 512);
    EXPECT_NEAR(total / phi, 1.0, 1e-3) << "the import keeps the sun's energy";
    const glm::vec3 s = glm::vec3(glm::normalize(centroid));
    const Picture diffuse = render("diffuse", big);
    double want = 0.0, got = 0.0;
    for (int y = 0; y < kPixels; ++y)
        for (int x = 0; x < kPixels; ++x) {
            const auto hit = test::hitUnitSphere(test::pixelRay(diffuse.inverse, x, y, kPixels, kPixels));
            if (!hit) continue;
            want += phi * std::max(0.0f, glm::dot(glm::normalize(*hit), s)) / std::numbers::pi;
            got += diffuse.hdr[static_cast<std::size_t>(y * kPixels + x)].g;
        }
    std::printf("[ range ] diffuse  sun 1e9 over the sphere against Φ·max(0, N·s)/π: %.5f\n", got / want);
    EXPECT_NEAR(got / want, 1.0, 0.01);
}

TEST(RadianceRange, MapAt1em30RendersAsTheMapAtItsOwnScaleAfterExposure) {
    std::string error;
    ASSERT_NE(test::sharedRenderer(&error), nullptr) << error;
    MIPGLOSS_REQUIRE_ASSET(test::rangeMapAsset());
    const MapCase own{1.0, 0.0f, true}, tiny{1e-30, 0.0f, true};
    // The linear picture (what readHdr and `render --out x.exr` return): scene-referred, so the
    // tiny map's is 1e-30 times the map's. Relative RMS over the sphere's pixels within 2 %.
    for (const char* material : {"mirror", "n 64", "n 1024", "diffuse"}) {
        const Picture a = render(material, own), b = render(material, tiny);
        double num = 0.0, den = 0.0;
        for (std::size_t i = 0; i < a.hdr.size(); ++i) {
            if (!a.onSphere[i]) continue;
            const glm::dvec3 d = glm::dvec3(b.hdr[i]) * 1e30 - glm::dvec3(a.hdr[i]);
            num += glm::dot(d, d);
            den += glm::dot(glm::dvec3(a.hdr[i]), glm::dvec3(a.hdr[i]));
        }
        const double rel = std::sqrt(num / den);
        std::printf("[ range ] %-8s map at 1e-30 × 1e30 vs the map: relative RMS %.3g %%\n", material, 100.0 * rel);
        EXPECT_LT(rel, 0.02) << material;
    }
    // The displayed picture, background and multisampling included: exposure +log2(1e30) on the
    // tiny map against exposure 0 on the map, 8-bit sRGB, within one level at every pixel.
    Scene scene = test::sphereScene(materialFor("n 64"));
    scene.display.showBackground = true;
    scene.display.samples = 4;
    ui::OffscreenRenderer* renderer = test::sharedRenderer();
    OrbitCamera camera;
    camera.yawDegrees = 30.0f;
    camera.pitchDegrees = 20.0f;
    camera.frame(sceneBounds(scene), 1.0f);
    renderer->setLobes(makeStackEntries(*environment(own), scene));
    const QImage a = renderer->render(scene, camera, environment(own), kPixels, kPixels);
    renderer->setLobes(makeStackEntries(*environment(tiny), scene));
    scene.display.exposureEv = static_cast<float>(std::log2(1e30));
    const QImage b = renderer->render(scene, camera, environment(tiny), kPixels, kPixels);
    int worst = 0;
    for (int y = 0; y < kPixels; ++y)
        for (int x = 0; x < kPixels; ++x) {
            const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
            worst = std::max({worst, std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)), std::abs(qBlue(p) - qBlue(q))});
        }
    if (worst > 1) {
        a.save(QString::fromStdString((test::outputDir() / "radiance_range_own.png").string()));
        b.save(QString::fromStdString((test::outputDir() / "radiance_range_tiny.png").string()));
    }
    std::printf("[ range ] displayed picture, tiny map at +%.2f EV vs the map: worst 8-bit difference %d\n",
                scene.display.exposureEv, worst);
    EXPECT_LE(worst, 1);
}

}  // namespace
}  // namespace mipgloss
