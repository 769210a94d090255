// Texture caches are their callers' (textures.h): two caches share nothing, and a glTF's embedded
// images decode from what the asset's own parse kept (Asset::images), never from a second parse
// of the file (gltfio's loader / resource loader split).
#include "gltf_writer.h"
#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/textures.h"
#include "mipgloss/io/texture.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::test;
namespace fs = std::filesystem;

namespace {

// A 2 × 2 image of one colour.
TestImage plain(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    return makeImage(2, 2, 3, [=](int, int) -> std::vector<std::uint8_t> { return {r, g, b}; });
}

// A .glb holding one textured quad whose base colour map is an embedded PNG of (r, g, b).
fs::path writeTexturedGlb(const fs::path& file, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    GltfWriter w;
    const int texture = w.addTexture(w.addImage(encodePng(plain(r, g, b))));
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("Plain", {1, 1, 1, 1}, 0, 0.5, texture)))));
    w.writeGlb(file);
    return file;
}

}  // namespace

TEST(TextureCache, TwoCachesAreIndependent) {
    TempDir dir;
    const fs::path file = dir.path() / "red.png";
    writePng(plain(200, 0, 0), file);
    const TextureRef ref{file.string(), -1, 0};
    TextureCache document, command;
    EXPECT_TRUE(document.load({ref}).empty());
    ASSERT_NE(document.find(ref), nullptr);
    EXPECT_EQ(document.images(), 1u);
    EXPECT_EQ(command.find(ref), nullptr) << "a map loaded in one cache is not in another";
    EXPECT_EQ(command.images(), 0u);
    EXPECT_EQ(command.bytes(), 0u);

    // A refusal stays in its cache too.
    const TextureRef missing{(dir.path() / "missing.png").string(), -1, 0};
    EXPECT_EQ(command.load({missing}).size(), 1u);
    EXPECT_NE(command.problem(missing), "");
    EXPECT_EQ(document.problem(missing), "");
}

TEST(TextureCache, GltfImagesComeFromTheAssetsFirstParse) {
    TempDir dir;
    const fs::path file = writeTexturedGlb(dir.path() / "plain.glb", 10, 200, 30);
    const Asset asset = loadAsset(file);
    ASSERT_EQ(asset.materials.size(), 1u);
    const TextureRef ref = asset.materials[0].material.layers.maps.baseColor;
    ASSERT_EQ(ref.image, 0);
    ASSERT_EQ(asset.images.count(ref.key()), 1u) << "the embedded image is kept by the read";

    // The file is gone: only what the asset kept can give the image.
    fs::remove(file);
    TextureCache cache;
    const std::vector<std::string> warnings = cache.load({ref}, asset.images);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    const auto image = cache.find(ref);
    ASSERT_NE(image, nullptr);
    ASSERT_EQ(image->width, 2);
    ASSERT_EQ(image->height, 2);
    EXPECT_EQ(image->rgba[0], 10);
    EXPECT_EQ(image->rgba[1], 200);
    EXPECT_EQ(image->rgba[2], 30);
    EXPECT_EQ(image->rgba[3], 255);

    // Without the kept images the file is read again, and its absence is the map's problem.
    TextureCache again;
    ASSERT_EQ(again.load({ref}).size(), 1u);
    EXPECT_EQ(again.find(ref), nullptr);
    EXPECT_NE(again.problem(ref).find(file.string()), std::string::npos) << again.problem(ref);
}

TEST(TextureCache, EveryImageOfAGltfFileFromOneLoad) {
    // Two maps of one file, neither kept: both decode in one load (the file parsed once for both).
    TempDir dir;
    GltfWriter w;
    const int red = w.addTexture(w.addImage(encodePng(plain(255, 0, 0))));
    const int blue = w.addTexture(w.addImage(encodePng(plain(0, 0, 255))));
    tinygltf::Material m = pbrMaterial("Two", {1, 1, 1, 1}, 0, 0.5, red);
    m.occlusionTexture.index = blue;
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
    const fs::path file = dir.path() / "two.glb";
    w.writeGlb(file);
    const TextureRef first{file.string(), 0, 0}, second{file.string(), 1, 0}, absent{file.string(), 5, 0};
    TextureCache cache;
    const std::vector<std::string> warnings = cache.load({first, second, absent});
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("image 5 is not in the file (it has 2)"), std::string::npos) << warnings[0];
    ASSERT_NE(cache.find(first), nullptr);
    ASSERT_NE(cache.find(second), nullptr);
    EXPECT_EQ(cache.find(first)->rgba[0], 255);
    EXPECT_EQ(cache.find(second)->rgba[2], 255);
}

// glTF's textures are straight alpha (the specification; OpenImageIO associates alpha on decode
// unless told not to): a texel of colour (200, 100, 50) and alpha 64 decodes as (200, 100, 50, 64),
// not as (50, 25, 13, 64), from a file and from bytes embedded in a .glb alike.
TEST(TextureCache, ColourIsKeptWhereAlphaIsBelowOne) {
    TempDir dir;
    const TestImage translucent =
        makeImage(2, 2, 4, [](int, int) -> std::vector<std::uint8_t> { return {200, 100, 50, 64}; });
    const fs::path png = dir.path() / "translucent.png";
    writePng(translucent, png);
    GltfWriter w;
    const int texture = w.addTexture(w.addImage(encodePng(translucent)));
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("Leaf", {1, 1, 1, 1}, 0, 0.5, texture)))));
    const fs::path glb = dir.path() / "leaf.glb";
    w.writeGlb(glb);
    const Asset asset = loadAsset(glb);
    const TextureRef embedded = asset.materials.at(0).material.layers.maps.baseColor;
    const TextureRef external{png.string(), -1, 0};

    TextureCache cache;
    EXPECT_TRUE(cache.load({embedded, external}, asset.images).empty());
    for (const TextureRef& ref : {embedded, external}) {
        const auto image = cache.find(ref);
        ASSERT_NE(image, nullptr) << ref.key();
        ASSERT_EQ(image->rgba.size(), 16u);
        for (int texel = 0; texel < 4; ++texel) {
            EXPECT_EQ(image->rgba[texel * 4 + 0], 200) << ref.key() << " texel " << texel;
            EXPECT_EQ(image->rgba[texel * 4 + 1], 100) << ref.key();
            EXPECT_EQ(image->rgba[texel * 4 + 2], 50) << ref.key();
            EXPECT_EQ(image->rgba[texel * 4 + 3], 64) << ref.key();
        }
    }
}

// Grey and grey + alpha images become RGBA with the grey in every colour channel, read in place
// (decodeTexture reads straight into the RGBA buffer and expands each pixel there).
TEST(TextureDecode, GreyAndGreyAlphaExpandToRgbaInPlace) {
    for (int channels : {1, 2, 3}) {
        const TestImage image = makeImage(3, 2, channels, [&](int x, int y) {
            std::vector<std::uint8_t> texel{static_cast<std::uint8_t>(40 * x + 100 * y + 1)};
            if (channels >= 2) texel.push_back(static_cast<std::uint8_t>(200 - x));
            if (channels == 3) texel.push_back(7);
            return texel;
        });
        const TextureImage decoded = decodeTextureFromMemory(encodePng(image), "grey.png", "image/png");
        ASSERT_EQ(decoded.width, 3);
        EXPECT_EQ(decoded.channels, channels);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) {
                const std::uint8_t* q = &decoded.rgba[static_cast<std::size_t>(y * 3 + x) * 4];
                const auto v = static_cast<std::uint8_t>(40 * x + 100 * y + 1);
                EXPECT_EQ(q[0], v) << channels << " channels at " << x << "," << y;
                EXPECT_EQ(q[1], channels == 3 ? static_cast<std::uint8_t>(200 - x) : v);
                EXPECT_EQ(q[2], channels == 3 ? 7 : v);
                EXPECT_EQ(q[3], channels == 2 ? static_cast<std::uint8_t>(200 - x) : 255);
            }
    }
}
