// glTF features as the specification draws them, through `mipgloss render` (issue 33): alpha BLEND
// composed farthest first over the backdrop, doubleSided false, a file's camera with its roll, the
// backdrop laid under the tone-mapped picture. Each scene is emissive quads under a black
// environment (a black metal reflects nothing of it), drawn with --tonemap linear at exposure 0,
// so every expected pixel is the specification's arithmetic on the emitted radiance, stated below.
#include "cli_support.h"
#include "gltf_writer.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <QImage>

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace mipgloss {
namespace {

namespace fs = std::filesystem;

using test::CliResult;
using test::q;
using test::runCli;

// A quad of half-height `half` at depth z, facing +Z (counter-clockwise seen from +Z) unless
// `facingAway`; x from x0 to x1.
Mesh quad(float x0, float x1, float half, float z, bool facingAway = false) {
    Mesh m;
    m.name = "quad";
    for (const glm::vec2 p : {glm::vec2(x0, -half), glm::vec2(x1, -half), glm::vec2(x1, half), glm::vec2(x0, half)}) {
        m.positions.emplace_back(p, z);
        m.normals.emplace_back(0.0f, 0.0f, facingAway ? -1.0f : 1.0f);
    }
    m.indices = facingAway ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2} : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
    return m;
}

// A material that shows only its emission: a black metal (F0 = 0, no diffuse) of roughness 1
// under a black environment, emitting `emissive` with coverage `alpha` (BLEND when below 1).
tinygltf::Material emitter(const std::string& name, glm::vec3 emissive, double alpha = 1.0, bool doubleSided = true) {
    tinygltf::Material m = test::pbrMaterial(name, {0, 0, 0, alpha}, 1.0, 1.0);
    m.emissiveFactor = {emissive.x, emissive.y, emissive.z};
    if (alpha < 1.0) m.alphaMode = "BLEND";
    m.doubleSided = doubleSided;
    return m;
}

// A perspective camera at (0, 0, 3) looking down −Z, turned by `rotation` about its node.
void addCamera(test::GltfWriter& w, const std::string& name, const glm::quat& rotation = glm::quat(1, 0, 0, 0)) {
    w.addCamera(name, 0.6, {0.0, 0.0, 3.0}, {rotation.x, rotation.y, rotation.z, rotation.w});
}

// An 8 × 4 lat-long of one radiance: zeros (nothing to reflect) or ones (a white furnace).
fs::path uniformEnvironment(const fs::path& folder, float radiance) {
    const fs::path file = folder / (radiance > 0.0f ? "white.exr" : "black.exr");
    auto out = OIIO::ImageOutput::create(file.string());
    const OIIO::ImageSpec spec(8, 4, 3, OIIO::TypeDesc::FLOAT);
    const std::vector<float> texels(8 * 4 * 3, radiance);
    EXPECT_TRUE(out && out->open(file.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, texels.data()) &&
                out->close());
    return file;
}
fs::path blackEnvironment(const fs::path& folder) { return uniformEnvironment(folder, 0.0f); }

float srgbEncode(float c) { return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

struct Rendered {
    CliResult result;
    QImage image;
};

Rendered render(const fs::path& gltf, const fs::path& environment, const std::string& camera, const std::string& backdrop,
                const fs::path& out, const std::string& toneMap = "linear") {
    Rendered r;
    r.result = runCli({"render", "--mesh", q(gltf), "--camera", QString::fromStdString(camera), "--env", q(environment),
                       "--background", QString::fromStdString(backdrop), "--tonemap", QString::fromStdString(toneMap),
                       "--size", "96x96", "--out", q(out)});
    r.image = QImage(q(out));
    return r;
}

// The pixel's encoded channels against the expected linear colour, within 2 of 255 (8 bits).
void expectPixel(const QImage& image, int x, int y, glm::vec3 linear, const std::string& what) {
    const QColor c = image.pixelColor(x, y);
    const float got[3] = {static_cast<float>(c.red()), static_cast<float>(c.green()), static_cast<float>(c.blue())};
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(got[i], 255.0f * srgbEncode(linear[i]), 2.0f)
            << what << ", channel " << i << " at (" << x << ", " << y << ")";
}

// Two half-transparent quads, red in front of green, over a blue backdrop: glTF's BLEND is
// "over", so the centre is 0.5·red + 0.5·(0.5·green + 0.5·blue) = (0.5, 0.25, 0.25); drawn in the
// wrong order it would be (0.25, 0.5, 0.25), drawn opaque (1, 0, 0).
TEST(GltfConformance, BlendedQuadsComposeFarthestFirstOverTheBackdrop) {
    test::TempDir dir;
    test::GltfWriter w;
    // The nearer quad first in the file: the order drawn must come from the depth, not the file.
    w.addToScene(w.addNode(w.addMesh(quad(-0.5f, 0.5f, 0.5f, 0.5f), w.addMaterial(emitter("Red", {1, 0, 0}, 0.5)))));
    w.addToScene(w.addNode(w.addMesh(quad(-0.5f, 0.5f, 0.5f, 0.0f), w.addMaterial(emitter("Green", {0, 1, 0}, 0.5)))));
    addCamera(w, "front");
    w.writeGltf(dir / "blend.gltf");
    const Rendered r = render(dir / "blend.gltf", blackEnvironment(dir.path()), "front", "0,0,1", dir / "blend.png");
    ASSERT_EQ(r.result.exitCode, 0) << r.result.err;
    EXPECT_EQ(r.result.err.find("warning"), std::string::npos) << "blending is drawn, not warned about: " << r.result.err;
    expectPixel(r.image, 48, 48, {0.5f, 0.25f, 0.25f}, "red over green over blue");
    expectPixel(r.image, 2, 2, {0.0f, 0.0f, 1.0f}, "the backdrop beside the quads");
}

// doubleSided false (glTF's default) draws only the side the winding calls front: a quad facing
// away from the camera shows the backdrop; the same quad double-sided shows its emission.
TEST(GltfConformance, ASingleSidedQuadSeenFromBehindIsNotDrawn) {
    test::TempDir dir;
    const fs::path environment = blackEnvironment(dir.path());
    for (const bool doubleSided : {false, true}) {
        test::GltfWriter w;
        w.addToScene(w.addNode(w.addMesh(quad(-0.5f, 0.5f, 0.5f, 0.0f, true), w.addMaterial(emitter("Back", {1, 1, 1}, 1.0, doubleSided)))));
        addCamera(w, "front");
        const std::string name = doubleSided ? "double" : "single";
        w.writeGltf(dir / (name + ".gltf"));
        const Rendered r = render(dir / (name + ".gltf"), environment, "front", "0,0,1", dir / (name + ".png"));
        ASSERT_EQ(r.result.exitCode, 0) << r.result.err;
        expectPixel(r.image, 48, 48, doubleSided ? glm::vec3(1.0f) : glm::vec3(0, 0, 1), name + "-sided quad's back");
    }
}

// The file's camera with its full orientation: rolled 90° to its left (its node turned +90° about
// +Z, so its up is world −X), the red left half (x < 0) of a quad shows at the top of the picture
// and the green right half at the bottom; not rolled, left and right. A camera the file lacks is
// refused naming the file and listing the cameras it has.
TEST(GltfConformance, TheFilesCameraIsLookedThroughWithItsRoll) {
    test::TempDir dir;
    test::GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(quad(-0.5f, 0.0f, 0.5f, 0.0f), w.addMaterial(emitter("Left", {1, 0, 0})))));
    w.addToScene(w.addNode(w.addMesh(quad(0.0f, 0.5f, 0.5f, 0.0f), w.addMaterial(emitter("Right", {0, 1, 0})))));
    addCamera(w, "level");
    addCamera(w, "rolled", glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1)));
    w.writeGltf(dir / "halves.gltf");
    const fs::path environment = blackEnvironment(dir.path());

    const Rendered level = render(dir / "halves.gltf", environment, "level", "0,0,0", dir / "level.png");
    ASSERT_EQ(level.result.exitCode, 0) << level.result.err;
    expectPixel(level.image, 36, 48, {1, 0, 0}, "level: the left half at the left");
    expectPixel(level.image, 60, 48, {0, 1, 0}, "level: the right half at the right");

    const Rendered rolled = render(dir / "halves.gltf", environment, "1", "0,0,0", dir / "rolled.png");
    ASSERT_EQ(rolled.result.exitCode, 0) << rolled.result.err;
    expectPixel(rolled.image, 48, 36, {1, 0, 0}, "rolled (camera 1): the left half at the top");
    expectPixel(rolled.image, 48, 60, {0, 1, 0}, "rolled: the right half at the bottom");

    const Rendered missing = render(dir / "halves.gltf", environment, "orbit", "0,0,0", dir / "missing.png");
    EXPECT_EQ(missing.result.exitCode, 1);
    EXPECT_NE(missing.result.err.find("halves.gltf"), std::string::npos) << missing.result.err;
    EXPECT_NE(missing.result.err.find("\"orbit\""), std::string::npos) << missing.result.err;
    EXPECT_NE(missing.result.err.find("1 \"rolled\""), std::string::npos) << missing.result.err;
}

// Samplers' wrap modes, read where the UVs leave [0, 1]: a quad whose u runs from −1 to 2 emits a
// 2 × 1 texture (red texel, green texel; nearest magnification). At u = −0.75, −0.25 and 1.75
// repeat reads red, green, green; clamp-to-edge red, red, green; mirrored repeat green, red, red.
// The same quad reading UV set 1 (= set 0) through KHR_texture_transform's offset (0.5, 0) under
// repeat shows repeat's colours swapped.
TEST(GltfConformance, WrapModesUvSetsAndTextureTransformsReadTheTexelsTheSpecificationSays) {
    test::TempDir dir;
    const fs::path environment = blackEnvironment(dir.path());
    const test::TestImage redGreen = test::makeImage(2, 1, 3, [](int x, int) -> std::vector<std::uint8_t> {
        return x == 0 ? std::vector<std::uint8_t>{255, 0, 0} : std::vector<std::uint8_t>{0, 255, 0};
    });
    Mesh strip = quad(-0.5f, 0.5f, 0.5f, 0.0f);
    for (std::size_t i = 0; i < strip.vertexCount(); ++i)
        strip.uvs.emplace_back(strip.positions[i].x < 0.0f ? -1.0f : 2.0f, strip.positions[i].y > 0.0f ? 0.0f : 1.0f);
    strip.uvs1 = strip.uvs;
    const int columns[] = {26, 35, 70};  // u = −0.75, −0.25, 1.75: x = (u + 1)/3 − 0.5, column 48 + 48·x/0.928
    const glm::vec3 red(1, 0, 0), green(0, 1, 0);
    struct Case {
        const char* name;
        int wrap;
        bool shifted;  // UV set 1 through KHR_texture_transform's offset (0.5, 0)
        glm::vec3 expected[3];
    };
    const Case cases[] = {{"repeat", TINYGLTF_TEXTURE_WRAP_REPEAT, false, {red, green, green}},
                          {"clamp", TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE, false, {red, red, green}},
                          {"mirror", TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT, false, {green, red, red}},
                          {"shifted", TINYGLTF_TEXTURE_WRAP_REPEAT, true, {green, red, red}}};
    for (const Case& c : cases) {
        test::GltfWriter w;
        const int texture = w.addTexture(w.addImage(test::encodePng(redGreen)));
        tinygltf::Sampler sampler;
        sampler.wrapS = sampler.wrapT = c.wrap;
        sampler.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
        w.model().samplers = {sampler};
        w.model().textures[static_cast<std::size_t>(texture)].sampler = 0;
        tinygltf::Material m = emitter("Strip", {1, 1, 1});
        m.emissiveTexture.index = texture;
        if (c.shifted) {
            m.emissiveTexture.texCoord = 1;
            m.emissiveTexture.extensions["KHR_texture_transform"] = tinygltf::Value(tinygltf::Value::Object{
                {"offset", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(0.5), tinygltf::Value(0.0)})}});
            w.model().extensionsUsed = {"KHR_texture_transform"};
        }
        w.addToScene(w.addNode(w.addMesh(strip, w.addMaterial(m))));
        addCamera(w, "front");
        const fs::path file = dir / (std::string(c.name) + ".gltf");
        w.writeGltf(file);
        const Rendered r = render(file, environment, "front", "0,0,0", dir / (std::string(c.name) + ".png"));
        ASSERT_EQ(r.result.exitCode, 0) << r.result.err;
        for (int i = 0; i < 3; ++i) expectPixel(r.image, columns[i], 48, c.expected[i], c.name);
    }
}

// COLOR_0 multiplies the base colour: a white dielectric in a white furnace with red vertex colours
// shows red (its diffuse), grey specular alike in every channel; without them it is grey.
TEST(GltfConformance, VertexColoursMultiplyTheBaseColour) {
    test::TempDir dir;
    const fs::path environment = uniformEnvironment(dir.path(), 1.0f);
    for (const bool coloured : {true, false}) {
        test::GltfWriter w;
        Mesh q = quad(-0.5f, 0.5f, 0.5f, 0.0f);
        if (coloured) q.colours.assign(q.vertexCount(), glm::vec4(1, 0, 0, 1));
        w.addToScene(w.addNode(w.addMesh(q, w.addMaterial(test::pbrMaterial("White", {1, 1, 1, 1}, 0.0, 1.0)))));
        addCamera(w, "front");
        const std::string name = coloured ? "coloured" : "plain";
        w.writeGltf(dir / (name + ".gltf"));
        const Rendered r = render(dir / (name + ".gltf"), environment, "front", "0,0,0", dir / (name + ".png"));
        ASSERT_EQ(r.result.exitCode, 0) << r.result.err;
        const QColor c = r.image.pixelColor(48, 48);
        std::printf("[ GltfConformance ] %s quad in a white furnace: %d %d %d\n", name.c_str(), c.red(), c.green(), c.blue());
        EXPECT_LE(std::abs(c.green() - c.blue()), 2) << name;
        if (coloured) EXPECT_GT(c.red() - c.green(), 100) << "the red vertex colour";
        else EXPECT_LE(std::abs(c.red() - c.green()), 2) << "no vertex colour: grey";
    }
}

// Khronos PBR Neutral, from its definition (KhronosGroup/ToneMapping): a grey of 0.5 is below the
// knee (0.76), so only the black offset 0.04 moves it: 0.46; a grey of 2 loses the offset (1.96),
// then its peak is compressed to 1 − 0.24²/(1.96 + 0.24 − 0.76) = 0.96 (a grey stays grey). AgX:
// greys 0.05, 0.5, 2 and 16 come out rising, all below white, and 16 is not clipped to 1.
TEST(GltfConformance, PbrNeutralAndAgxToneMapsGreysAsTheirDefinitionsSay) {
    test::TempDir dir;
    const fs::path environment = blackEnvironment(dir.path());
    const float greys[] = {0.05f, 0.5f, 2.0f, 16.0f};
    test::GltfWriter w;
    for (int i = 0; i < 4; ++i) {
        const float x0 = -0.5f + 0.25f * static_cast<float>(i);
        w.addToScene(w.addNode(w.addMesh(quad(x0, x0 + 0.25f, 0.5f, 0.0f),
                                         w.addMaterial(emitter("Grey " + std::to_string(i), glm::vec3(greys[i]))))));
    }
    addCamera(w, "front");
    w.writeGltf(dir / "greys.gltf");
    const int columns[] = {29, 42, 54, 67};  // each strip's middle: x at 48 + 48·x/0.928 (the half-height in view)
    const Rendered neutral = render(dir / "greys.gltf", environment, "front", "0,0,0", dir / "neutral.png", "pbr-neutral");
    ASSERT_EQ(neutral.result.exitCode, 0) << neutral.result.err;
    expectPixel(neutral.image, columns[1], 48, glm::vec3(0.46f), "PBR Neutral of 0.5");
    expectPixel(neutral.image, columns[2], 48, glm::vec3(0.96f), "PBR Neutral of 2");
    const Rendered agx = render(dir / "greys.gltf", environment, "front", "0,0,0", dir / "agx.png", "agx");
    ASSERT_EQ(agx.result.exitCode, 0) << agx.result.err;
    int previous = -1;
    for (int i = 0; i < 4; ++i) {
        const QColor c = agx.image.pixelColor(columns[i], 48);
        EXPECT_GT(c.green(), previous) << "AgX of " << greys[i] << " rises";
        EXPECT_LE(std::abs(c.red() - c.green()) + std::abs(c.blue() - c.green()), 2) << "a grey stays grey";
        previous = c.green();
    }
    EXPECT_LT(previous, 255) << "AgX keeps 16 below white";
}

}  // namespace
}  // namespace mipgloss
