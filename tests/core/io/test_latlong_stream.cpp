// The lat-long scatter fed strip by strip as a file is decoded (io_detail::LatLongStream,
// core/io/src/latlong.h; the method: latlong_scatter.cpp, "Scatter, strip by strip", and
// docs/big-environments.md). Each strip is clamped to a lower bound T_k of the bright threshold T
// known when it arrives, and the difference min(L, T) − min(L, T_k) of the pixels above T_k is
// scattered once T is known; strips with too many such pixels, or +Inf, and the first and last
// are kept whole for the end. The claim checked here: the result is the cube of the whole image
// with T known from the start, up to rounding. The reference is the same stream given the whole
// image as one strip, which defers it whole, so T is exact before anything is scattered (the
// non-streamed algorithm), and the cases are built so that every path is taken (stats()).
#include "latlong.h"

#include "cube_compare.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/io/import.h"
#include "mipgloss/io/latlong.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

using namespace mipgloss;
using io_detail::LatLongStream;

namespace {

constexpr int kW = 2048, kH = 1024;  // four strips of kLatLongStripRows

std::size_t index(int i, int j) { return static_cast<std::size_t>(j) * kW + static_cast<std::size_t>(i); }

// A smooth sky with a bright patch in the second strip (2000 pixels at 12: above that strip's
// clamp T_1 ≈ 8 but below T ≈ 16, so they are candidates whose difference is not 0, and few
// enough, under 1/64 of the strip, that the strip is not deferred) and a 2 × 2 sun of 10⁴ in the
// third (above T: excess).
std::vector<Rgb> sky() {
    std::vector<Rgb> px(static_cast<std::size_t>(kW) * kH);
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            const glm::dvec3 d = latLongDirection((i + 0.5) / kW, (j + 0.5) / kH);
            px[index(i, j)] = Rgb(static_cast<float>(1.0 + 0.3 * d.y + 0.2 * d.x), static_cast<float>(1.0 + 0.1 * d.z), 1.0f);
        }
    for (int j = 300; j < 320; ++j)
        for (int i = 900; i < 1000; ++i) px[index(i, j)] = Rgb(12.0f, 11.0f, 10.0f);
    for (int j = 700; j < 702; ++j)
        for (int i = 1500; i < 1502; ++i) px[index(i, j)] = Rgb(1e4f, 8e3f, 5e3f);
    return px;
}

// The sky with every pixel of rows [j0, j1) at `value`.
std::vector<Rgb> skyWithRows(int j0, int j1, float value) {
    std::vector<Rgb> px = sky();
    std::fill(px.begin() + static_cast<std::ptrdiff_t>(index(0, j0)), px.begin() + static_cast<std::ptrdiff_t>(index(0, j1)),
              Rgb(value));
    return px;
}

struct Converted {
    CubeMap cube;
    LatLongStream::Stats stats;
};
// The stream given `px` in strips of `rows` rows.
Converted streamed(const std::vector<Rgb>& px, int n, int rows) {
    LatLongStream stream(kW, kH, n);
    for (int y0 = 0; y0 < kH; y0 += rows) {
        const int y1 = std::min(kH, y0 + rows);
        const std::span<const Rgb> strip(px.data() + index(0, y0), static_cast<std::size_t>(y1 - y0) * kW);
        stream.addStrip(y0, y1, strip);
    }
    Converted out{stream.finish({}, 0.0f, 1.0f), stream.stats()};
    std::printf("[stream] strips of %d rows: %d strips, %d kept whole to the end, %d clamped late, %zu candidates "
                "(%zu corrected), %zu excess\n", rows, out.stats.strips, out.stats.deferred, out.stats.promoted,
                out.stats.candidates, out.stats.corrected, out.stats.excess);
    return out;
}

void expectSameUpToRounding(const CubeMap& got, const CubeMap& want, const char* what) {
    const double rms = compareCubes(got, want).relRms, worst = test::maxRelDiff(got, want);
    std::printf("[stream] %s: rel RMS %.2e, largest texel %.2e\n", what, rms, worst);
    EXPECT_LE(rms, 1e-6) << what;
    EXPECT_LE(worst, 1e-5) << what;
}

}  // namespace

TEST(LatLongStream, StripsClampedBeforeTheThresholdIsKnownGiveTheWholeImagesCube) {
    const std::vector<Rgb> px = sky();
    // N 64: one stratum per pixel; N 256: 3 × 3 interpolated strata per pixel.
    for (int n : {64, 256}) {
        ASSERT_TRUE(io_detail::latLongStreams(kW, kH, n));
        const Converted whole = streamed(px, n, kH), strips = streamed(px, n, io_detail::kLatLongStripRows);
        EXPECT_EQ(whole.stats.strips, 1);
        EXPECT_EQ(whole.stats.deferred, 1);
        EXPECT_EQ(strips.stats.strips, 4);
        EXPECT_EQ(strips.stats.deferred, 1) << "the last, no other";
        EXPECT_EQ(strips.stats.promoted, 0);
        EXPECT_GE(strips.stats.corrected, 2000u) << "the patch's pixels are corrected";
        EXPECT_EQ(strips.stats.excess, 4u);
        EXPECT_EQ(whole.stats.excess, 4u);
        expectSameUpToRounding(strips.cube, whole.cube, n == 64 ? "N 64, strips vs whole" : "N 256, strips vs whole");
    }
}

TEST(LatLongStream, AStripWithManyPixelsAboveItsClampIsKeptWhole) {
    // Ten full rows at 50 in strip 1: its clamp is T_1 ≈ 16 × (0.5 + 0.011 × 50) ≈ 17, so 20480
    // pixels, more than 1/64 of the strip, exceed it.
    const std::vector<Rgb> px = skyWithRows(256, 266, 50.0f);
    const Converted got = streamed(px, 64, io_detail::kLatLongStripRows), want = streamed(px, 64, kH);
    EXPECT_EQ(got.stats.deferred, 2) << "the bright one (T ≈ 25 stays below 50) and the last";
    expectSameUpToRounding(got.cube, want.cube, "bright strip kept whole");
}

TEST(LatLongStream, AStripDeferredWhenItCameIsClampedOnceTheSumsHaveGrown) {
    // Ten full rows at 5 in the first strip, whose clamp is T_0 ≈ 16 × 0.15 × 1.3 ≈ 3: deferred
    // when it comes; after the second, T_1 ≈ 9 > 5 and it is clamped and scattered then.
    const std::vector<Rgb> px = skyWithRows(100, 110, 5.0f);
    const Converted got = streamed(px, 256, io_detail::kLatLongStripRows), want = streamed(px, 256, kH);
    EXPECT_EQ(got.stats.promoted, 1);
    EXPECT_EQ(got.stats.deferred, 1) << "the last";
    expectSameUpToRounding(got.cube, want.cube, "first strip clamped late");
}

TEST(LatLongStream, RefusesStripsOutOfOrderAndAnUnfinishedImage) {
    const std::vector<Rgb> px = sky();
    LatLongStream stream(kW, kH, 64);
    const std::span<const Rgb> strip(px.data(), static_cast<std::size_t>(256) * kW);
    EXPECT_THROW(stream.addStrip(256, 512, strip), std::invalid_argument);
    stream.addStrip(0, 256, strip);
    EXPECT_THROW(stream.finish({}, 0.0f, 1.0f), std::invalid_argument);
}

// The previewer and bake read a file this way: decoded strip by strip, each converted in the
// background while the next is read. The cube is the one the same image in memory gives, to the
// bit (the same strips), and cancelling mid-decode stops it cleanly.
namespace {
// The sky as a half-float zip OpenEXR, by scanlines or in tiles of `tile`.
void writeSky(const std::filesystem::path& file, int tile = 0) {
    const std::vector<Rgb> px = sky();
    OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::HALF);
    spec.attribute("compression", "zip");
    if (tile > 0) spec.tile_width = spec.tile_height = tile;
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out && out->open(file.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
    ASSERT_TRUE(out->close());
}
}  // namespace

TEST(LatLongStream, AStreamedFileGivesTheCubeOfTheImageInMemoryToTheBit) {
    const test::TempDir dir;
    const auto file = dir.path() / "sky.exr", tiled = dir.path() / "tiled.exr";
    writeSky(file);
    writeSky(tiled, 64);
    ImportOptions options;
    options.faceSize = 64;
    const ImportedEnvironment env = loadEnvironment(file, options);
    EXPECT_EQ(env.report.layout, EnvLayout::LatLong);
    const DecodedImage image = decodeImage(file);
    const CubeMap want = latLongToCube(LatLongView{image.width, image.height, image.px}, 64);
    ASSERT_EQ(env.cube.size(), 64);
    std::size_t differ = 0;
    for (Face f : kAllFaces)
        for (int y = -1; y <= 64; ++y)
            for (int x = -1; x <= 64; ++x) differ += env.cube.at(f, x, y) == want.at(f, x, y) ? 0 : 1;
    EXPECT_EQ(differ, 0u);
    // Tiles of 64 are read four rows of tiles at a time: the same strips.
    EXPECT_EQ(loadEnvironment(tiled, options).cube.weightedMean(), env.cube.weightedMean());

    // The bar rises through the decode, which carries the conversion, with no jump.
    std::vector<float> fractions;
    loadEnvironment(file, options, [&](const std::string&, float f) {
        fractions.push_back(f);
        return true;
    });
    ASSERT_GE(fractions.size(), 6u);
    for (std::size_t k = 1; k < fractions.size(); ++k) {
        EXPECT_GE(fractions[k], fractions[k - 1]) << "report " << k;
        EXPECT_LE(fractions[k] - fractions[k - 1], 0.25f) << "report " << k << ": from " << fractions[k - 1];
    }
    EXPECT_EQ(fractions.back(), 1.0f);

    int reports = 0;
    const Progress cancelAfterTwoStrips = [&](const std::string&, float) { return ++reports < 3; };
    EXPECT_THROW(loadEnvironment(file, options, cancelAfterTwoStrips), Cancelled);
    EXPECT_EQ(reports, 3);
    EXPECT_EQ(loadEnvironment(file, options).cube.weightedMean(), env.cube.weightedMean()) << "works again after a cancel";
}

TEST(LatLongStream, AFileCutShortMidStreamIsRefusedNamingItAndTheNextImportWorks) {
    const test::TempDir dir;
    const auto file = dir.path() / "sky.exr", cut = dir.path() / "cut.exr";
    writeSky(file);
    {
        std::ifstream in(file, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 3 / 5);  // in the third strip
    }
    ImportOptions options;
    options.faceSize = 64;
    try {
        loadEnvironment(cut, options);
        FAIL() << "a file cut short was imported";
    } catch (const EnvError& e) {
        EXPECT_NE(std::string(e.what()).find(cut.string()), std::string::npos) << e.what();
    }
    EXPECT_EQ(loadEnvironment(file, options).cube.size(), 64);
}
