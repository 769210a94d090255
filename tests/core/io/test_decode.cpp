// The decode by strips (core/io/src/decode.cpp): every layout of file (scanline, tiled, grey,
// half) decodes to exactly its values across strip boundaries; the sanitising rule holds across
// strips; a header asking for absurd memory is refused before anything is allocated; progress
// and cancelling run during the decode.
#include "mipgloss/io/import.h"
#include "mipgloss/io/texture.h"
#include "sanitise.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

using namespace mipgloss;
using mipgloss::io_detail::SanitiseCounts;
using mipgloss::io_detail::sanitiseRows;
namespace fs = std::filesystem;
using test::TempDir;

namespace {

// A value unique to each pixel and channel, exactly representable in half (multiples of 1/64
// below 32).
float sample(int x, int y, int c) { return static_cast<float>((x * 7 + y * 13 + c * 5) % 2000) / 64.0f; }

void writeExr(const fs::path& file, int w, int h, int channels, OIIO::TypeDesc type, int tile = 0) {
    std::vector<float> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(channels));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                px[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) *
                       static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)] = sample(x, y, c);
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(w, h, channels, type);
    if (tile > 0) spec.tile_width = spec.tile_height = tile;
    spec.attribute("compression", "zip");
    ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    ASSERT_TRUE(out->close()) << out->geterror();
}

// Every pixel equals what was written (grey replicated to RGB), or the first mismatch.
void expectExact(const DecodedImage& img, int w, int h, int channels) {
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float want = sample(x, y, channels >= 3 ? c : 0);
                ASSERT_EQ(img.at(x, y)[c], want) << "pixel " << x << "," << y << " channel " << c;
            }
}

}  // namespace

TEST(DecodeStrips, ScanlineFilesTallerThanAStripDecodeExactly) {
    TempDir dir;
    // 600 rows: two whole strips of 256 and a partial one.
    writeExr(dir / "float.exr", 37, 600, 3, OIIO::TypeDesc::FLOAT);
    expectExact(decodeImage(dir / "float.exr"), 37, 600, 3);
    writeExr(dir / "half.exr", 37, 600, 3, OIIO::TypeDesc::HALF);
    expectExact(decodeImage(dir / "half.exr"), 37, 600, 3);
}

TEST(DecodeStrips, TiledFilesDecodeExactlyByRowsOfTiles) {
    TempDir dir;
    // 32-pixel tiles: the width and height are not multiples, so edge tiles are partial.
    writeExr(dir / "tiled.exr", 100, 600, 3, OIIO::TypeDesc::HALF, 32);
    {
        auto in = OIIO::ImageInput::open((dir / "tiled.exr").string());
        ASSERT_TRUE(in);
        ASSERT_EQ(in->spec().tile_width, 32) << "the file must really be tiled for this test";
    }
    expectExact(decodeImage(dir / "tiled.exr"), 100, 600, 3);
}

TEST(DecodeStrips, GreyAndGreyAlphaAreReplicatedInEveryStrip) {
    TempDir dir;
    writeExr(dir / "grey.exr", 20, 600, 1, OIIO::TypeDesc::FLOAT);
    expectExact(decodeImage(dir / "grey.exr"), 20, 600, 1);
    writeExr(dir / "grey_alpha.exr", 20, 600, 2, OIIO::TypeDesc::HALF);
    expectExact(decodeImage(dir / "grey_alpha.exr"), 20, 600, 2);
}

TEST(DecodeStrips, EachRuleIsRowLocalAndKeepsTheRowsEnergy) {
    TempDir dir;
    // +Inf in the first strip beside 3 and 1; the largest finite value (42) in the last strip no
    // longer matters; a negative of −2 in row 300 between ones; NaN.
    const int w = 8, h = 600;
    std::vector<float> px(static_cast<std::size_t>(w * h * 3), 1.0f);
    px[0] = std::numeric_limits<float>::infinity();
    px[3] = 3.0f;  // pixel (1, 0), red
    px[static_cast<std::size_t>((w * (h - 1) + 3) * 3 + 1)] = 42.0f;
    px[5] = std::numeric_limits<float>::quiet_NaN();
    px[static_cast<std::size_t>((w * 300 + 4) * 3)] = -2.0f;  // pixel (4, 300), red
    auto out = OIIO::ImageOutput::create((dir / "inf.exr").string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open((dir / "inf.exr").string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
    ASSERT_TRUE(out->close());
    ImportReport report;
    const DecodedImage img = decodeImage(dir / "inf.exr", &report);
    EXPECT_EQ(img.at(0, 0).x, 3.0f) << "+Inf at the row's start: its one finite neighbour";
    EXPECT_EQ(img.at(1, 0).z, 0.0f);    // NaN -> 0
    // −2 -> 0, and 2 taken from the row's seven ones (all within 16 pixels), in proportion: 5/7 each.
    EXPECT_EQ(img.at(4, 300).x, 0.0f);
    for (int x : {0, 1, 2, 3, 5, 6, 7}) EXPECT_NEAR(img.at(x, 300).x, 5.0f / 7.0f, 1e-6f) << x;
    double row = 0.0;
    for (int x = 0; x < w; ++x) row += img.at(x, 300).x;
    EXPECT_NEAR(row, 8.0 - 1.0 - 2.0, 1e-5) << "the row's signed sum, kept (float rounding)";
    EXPECT_EQ(report.infCount, 1u);
    EXPECT_EQ(report.nanCount, 1u);
    EXPECT_EQ(report.negativeCount, 1u);
    ASSERT_EQ(report.warnings.size(), 1u);
    // Energy: 4800·3 − 1 values of 1 (less the NaN), the 3, the 42, the +Inf's 3 and the −2 moved.
    EXPECT_NE(report.warnings[0].find("adding 0.02 %"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("taking their 0.01 %"), std::string::npos) << report.warnings[0];
}

// A sun in a sky row with the large negative lobes DWAB's ringing leaves beside it (blue −300,
// red −50, four pixels): the sun pays for them, the sky beyond the ringing's neighbourhood keeps
// its colour exactly, and the row its signed sum. The first rule took the debt from the nearest
// values outward, half each side: 600 of blue drained the sky's 1.0 per pixel across the whole
// row (a lime band).
TEST(DecodeStrips, RingingBesideASunIsPaidByTheSunNotTheSky) {
    const int w = 512;
    const Rgb sky(0.3f, 0.5f, 1.0f);
    std::vector<Rgb> row(w, sky);
    row[256] = Rgb(5000.0f);
    for (int x : {254, 255, 257, 258}) row[static_cast<std::size_t>(x)] = Rgb(-50.0f, 0.5f, -300.0f);
    double signedSum = 0.0;
    for (const Rgb& p : row) signedSum += static_cast<double>(p.x) + p.y + p.z;
    const SanitiseCounts n = sanitiseRows(row, w);
    EXPECT_EQ(n.negative, 8u);
    EXPECT_EQ(n.negativeAdded, 0.0);
    double sum = 0.0;
    for (int x = 0; x < w; ++x) {
        const Rgb& p = row[static_cast<std::size_t>(x)];
        sum += static_cast<double>(p.x) + p.y + p.z;
        ASSERT_TRUE(p.x >= 0.0f && p.y >= 0.0f && p.z >= 0.0f) << x;
        if (std::abs(x - 256) > 2 + 16) {
            EXPECT_EQ(p, sky) << "the sky at " << x << " untouched";
        }
    }
    EXPECT_NEAR(sum / signedSum, 1.0, 1e-6) << "the row's signed sum kept (float rounding)";
    // Within the neighbourhood the sky pays in proportion to its value: at most (1200 / 5000) of it.
    EXPECT_GT(row[270].z, 0.7f * sky.z);
    EXPECT_NEAR(row[256].z, 5000.0f - 1200.0f, 20.0f) << "the sun pays nearly all";
}

// A JPEG texture cut short decodes without an error from OpenImageIO (libjpeg fills the rest with
// grey): it is refused, from a file and from memory, naming it; the whole file still decodes.
TEST(DecodeLimits, TruncatedJpegTextureIsRefusedNotDrawnGrey) {
    TempDir dir;
    const int w = 128, h = 128;
    std::vector<unsigned char> px(static_cast<std::size_t>(w * h * 3));
    for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<unsigned char>((i * 2654435761u) >> 24);
    const fs::path whole = dir / "noise.jpg";
    auto out = OIIO::ImageOutput::create(whole.string());
    ASSERT_TRUE(out && out->open(whole.string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8)) &&
                out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close());
    std::ifstream in(whole, std::ios::binary);
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 4000u);
    EXPECT_EQ(decodeTexture(whole).width, w);
    EXPECT_EQ(decodeTextureFromMemory(bytes, "whole", "image/jpeg").width, w);
    const std::vector<unsigned char> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
    const fs::path half = dir / "half.jpg";
    std::ofstream(half, std::ios::binary).write(reinterpret_cast<const char*>(cut.data()), static_cast<std::streamsize>(cut.size()));
    for (int fromMemory : {0, 1}) {
        try {
            if (fromMemory) decodeTextureFromMemory(cut, "model.glb#image 2", "image/jpeg");
            else decodeTexture(half);
            ADD_FAILURE() << "a truncated JPEG decoded, from " << (fromMemory ? "memory" : "a file");
        } catch (const TextureError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("a truncated JPEG"), std::string::npos) << what;
            EXPECT_NE(what.find(fromMemory ? "model.glb#image 2" : half.string()), std::string::npos) << what;
        }
    }
}

TEST(DecodeLimits, HeaderClaimingAMillionSquaredPixelsIsRefusedBeforeAllocating) {
    TempDir dir;
    // A Radiance header for 1e6 × 1e6 pixels (12 TB of float RGB) and a few bytes of data. Were the
    // pixels allocated first, the process would die; the refusal names the file and the need.
    const fs::path file = dir / "huge.hdr";
    std::ofstream(file, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1000000 +X 1000000\n"
                                          << std::string(64, '\x80');
    try {
        decodeImage(file);
        FAIL() << "a 1e6 x 1e6 header was decoded";
    } catch (const EnvError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find("1000000x1000000"), std::string::npos) << what;
        EXPECT_NE(what.find("TiB"), std::string::npos) << what;
    }
    // The same through the environment import, which the window and bake use.
    EXPECT_THROW(loadEnvironment(file), EnvError);
}

TEST(DecodeLimits, TruncatedLargeExrIsRefusedNamingTheFile) {
    TempDir dir;
    writeExr(dir / "big.exr", 512, 256, 3, OIIO::TypeDesc::HALF);
    std::ifstream in(dir / "big.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 4000u);
    const fs::path cut = dir / "cut.exr";
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    try {
        decodeImage(cut);
        FAIL() << "a file cut in half was decoded";
    } catch (const EnvError& e) {
        EXPECT_NE(std::string(e.what()).find(cut.string()), std::string::npos) << e.what();
    }
}

TEST(DecodeProgress, ReportsAfterEveryStripAndCancelsMidDecode) {
    TempDir dir;
    writeExr(dir / "tall.exr", 16, 2560, 3, OIIO::TypeDesc::HALF);  // ten strips
    std::vector<float> seen;
    decodeImage(dir / "tall.exr", nullptr, [&](const std::string& stage, float f) {
        EXPECT_EQ(stage, "import");
        seen.push_back(f);
        return true;
    });
    ASSERT_EQ(seen.size(), 10u);
    for (std::size_t i = 0; i < seen.size(); ++i)
        EXPECT_FLOAT_EQ(seen[i], static_cast<float>(i + 1) / 10.0f);
    int calls = 0;
    EXPECT_THROW(decodeImage(dir / "tall.exr", nullptr, [&](const std::string&, float) { return ++calls < 4; }),
                 Cancelled);
    EXPECT_EQ(calls, 4) << "the decode stops at the first report that says so, not at the end";
}

TEST(DecodeLimits, ExrAttributeClaimingMoreThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
    TempDir dir;
    // A valid small EXR, then one more header attribute whose size claims 1.8 GB: OpenEXR 3.1 would
    // allocate that before finding the file too short (13 s and 1.8 GB, found by the fuzzer).
    writeExr(dir / "ok.exr", 4, 2, 3, OIIO::TypeDesc::HALF);
    std::ifstream in(dir / "ok.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 8u);
    const std::string attribute = std::string("comments") + '\0' + "string" + '\0' + std::string("\x00\x00\x00\x6c", 4);
    bytes.insert(8, attribute);  // first in the header
    const fs::path file = dir / "bomb.exr";
    std::ofstream(file, std::ios::binary) << bytes;
    try {
        decodeImage(file);
        FAIL() << "the attribute was read";
    } catch (const EnvError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find("'comments' (string) claims 1811939328 bytes"), std::string::npos) << what;
    }
    // The same bytes from memory (the embedded and fuzzed path).
    const std::vector<unsigned char> memory(bytes.begin(), bytes.end());
    EXPECT_THROW(loadEnvironmentFromMemory(memory, "bomb.exr"), EnvError);
    // And the untouched file still decodes: the check reads a real header through.
    EXPECT_EQ(decodeImage(dir / "ok.exr").width, 4);
}

TEST(DecodeStrips, ValuesNearFloatMaxAreLoweredSoAveragesStayFinite) {
    TempDir dir;
    // Finite values near 3.4e38 (a fuzzed float TIFF had them): any average over them overflowed.
    const int w = 16, h = 8;
    std::vector<float> px(static_cast<std::size_t>(w * h * 3), 3.0e38f);
    px[0] = 2.0f;
    px[1] = std::numeric_limits<float>::infinity();
    auto out = OIIO::ImageOutput::create((dir / "huge.exr").string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open((dir / "huge.exr").string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
    ASSERT_TRUE(out->close());
    ImportReport report;
    const DecodedImage img = decodeImage(dir / "huge.exr", &report);
    EXPECT_EQ(img.at(0, 0).x, 2.0f);
    EXPECT_EQ(img.at(0, 0).y, kMaxRadiance) << "+Inf takes its row neighbours' mean: both at the ceiling";
    EXPECT_EQ(img.at(5, 5).z, kMaxRadiance);
    EXPECT_EQ(report.hugeCount, static_cast<std::size_t>(w * h * 3 - 2));
    EXPECT_EQ(report.infCount, 1u);
    const ImportedEnvironment env = loadEnvironment(dir / "huge.exr");
    for (Face f : kAllFaces)
        for (int y = 0; y < env.cube.size(); ++y)
            for (int x = 0; x < env.cube.size(); ++x)
                for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(env.cube.at(f, x, y)[c]));
}
