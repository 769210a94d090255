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

namespace {

// A w × h image of `channels` 8-bit channels, noise (every box average differs from its neighbours').
TestImage noise(int w, int h, int channels) {
    return makeImage(w, h, channels, [=](int x, int y) {
        std::vector<std::uint8_t> texel;
        for (int c = 0; c < channels; ++c)
            texel.push_back(static_cast<std::uint8_t>(((x * 73856093u) ^ (y * 19349663u) ^ (c * 83492791u)) >> 7));
        return texel;
    });
}

}  // namespace

// An image larger than maxSize is halved as its rows are read, in bands, never held whole
// (texture.h): the result is the whole image decoded and then halved, byte for byte, for odd
// sizes (the last row and column of each level counted once) and every channel count, from a file
// and from memory, with the downsizing warning naming both sizes.
TEST(TextureDecode, HalvingWhileReadingEqualsHalvingTheWholeImage) {
    TempDir dir;
    for (int channels : {1, 2, 3, 4})
        for (const auto& [w, h] : {std::pair{203, 77}, std::pair{64, 129}, std::pair{1, 33}}) {
            const TestImage image = noise(w, h, channels);
            const fs::path file = dir / ("noise" + std::to_string(channels) + ".png");
            writePng(image, file);
            TextureImage whole = decodeTexture(file, 1 << 14);
            ASSERT_EQ(whole.width, w);
            ASSERT_TRUE(whole.warnings.empty());
            for (int side : {100, 30, 13, 2, 1}) {
                TextureImage expected = whole;
                downsizeTexture(expected, side);
                for (const TextureImage& got : {decodeTexture(file, side), decodeTextureFromMemory(encodePng(image), "noise.png", "image/png", side)}) {
                    const std::string where = std::to_string(w) + " x " + std::to_string(h) + ", " +
                                              std::to_string(channels) + " channels, side " + std::to_string(side);
                    ASSERT_EQ(got.width, expected.width) << where;
                    ASSERT_EQ(got.height, expected.height) << where;
                    EXPECT_EQ(got.fileWidth, w);
                    EXPECT_EQ(got.fileHeight, h);
                    EXPECT_TRUE(got.rgba == expected.rgba) << where;
                    const bool downsized = got.width != w || got.height != h;
                    ASSERT_EQ(got.warnings.size(), downsized ? 1u : 0u) << where;
                    if (downsized) {
                        EXPECT_NE(got.warnings[0].find(std::to_string(w) + " x " + std::to_string(h) + " downsized to " +
                                                       std::to_string(got.width) + " x " + std::to_string(got.height)),
                                  std::string::npos) << got.warnings[0];
                    }
                }
            }
        }
}

// The header gives an image's size before a pixel is decoded; a header past the pixel limit is
// refused naming the file.
TEST(TextureDecode, SizeFromTheHeaderAlone) {
    TempDir dir;
    const fs::path file = dir / "wide.png";
    writePng(noise(300, 7, 3), file);
    const TextureSize size = textureSize(file);
    EXPECT_EQ(size.width, 300);
    EXPECT_EQ(size.height, 7);
    EXPECT_EQ(fittedTextureSize(size, 100).width, 75);
    EXPECT_EQ(fittedTextureSize(size, 100).height, 2);
    const TextureSize fromMemory = textureSizeFromMemory(encodePng(noise(5, 9, 1)), "small.png", "image/png");
    EXPECT_EQ(fromMemory.width, 5);
    EXPECT_EQ(fromMemory.height, 9);
    try {
        textureSize(dir / "absent.png");
        ADD_FAILURE() << "a missing file has no size";
    } catch (const TextureError& e) {
        EXPECT_NE(std::string(e.what()).find("absent.png"), std::string::npos) << e.what();
    }
}

// The budget is planned from the headers: three 256² images (256 KiB of RGBA each) under a
// 200 KiB budget are each decoded at the size the plan gives (the largest halved in turn until the
// total fits), equal to the whole image halved, each with one warning naming both sizes and the
// budget; what the cache holds is within the budget.
TEST(TextureCache, TheBudgetIsPlannedFromTheHeadersBeforeDecoding) {
    TempDir dir;
    std::vector<TextureRef> refs;
    std::vector<fs::path> files;
    for (int i = 0; i < 3; ++i) {
        files.push_back(dir / ("big" + std::to_string(i) + ".png"));
        writePng(noise(256, 256 - i, 3), files.back());
        TextureRef ref;
        ref.file = files.back().string();
        refs.push_back(ref);
    }
    const std::size_t budget = 200 << 10;
    TextureCache cache(4096, budget);
    const std::vector<std::string> warnings = cache.load(refs);
    EXPECT_LE(cache.bytes(), budget);
    EXPECT_GT(cache.bytes(), budget / 4) << "halved no further than the budget needs";
    ASSERT_EQ(warnings.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        const std::shared_ptr<const TextureImage> got = cache.find(refs[i]);
        ASSERT_TRUE(got);
        TextureImage expected = decodeTexture(files[i], 1 << 14);
        downsizeTexture(expected, std::max(got->width, got->height));
        EXPECT_EQ(got->width, expected.width);
        EXPECT_TRUE(got->rgba == expected.rgba) << files[i];
        const std::string& w = warnings[i];
        EXPECT_NE(w.find(files[i].string()), std::string::npos) << w;
        EXPECT_NE(w.find("256 x " + std::to_string(256 - i) + " downsized to " + std::to_string(got->width)), std::string::npos) << w;
        EXPECT_NE(w.find("MiB budget"), std::string::npos) << w;
    }
}
