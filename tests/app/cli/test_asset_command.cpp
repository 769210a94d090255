// Assets from the command line, as a user runs them (issue 21's "must show"): `mipgloss render
// --mesh ASSET` draws a glTF and an OBJ with MTL textured, and the same assets with their images
// gone untextured with a warning naming the file; `--aov` exponents vary over an object with a
// roughness map; `library import-gltf` lands the materials under their names; a hostile glTF is
// refused naming the file and the element, exit status 1, never a crash. Assets written here
// (tests/tools/gltf_writer.h), none tuned to.
#include "gltf_writer.h"
#include "cli_support.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <QImage>
#include <QProcess>
#include <QStringList>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace mipgloss {
namespace {

namespace fs = std::filesystem;

using test::CliResult;
using test::q;
using test::runCli;

test::TestImage checker() {
    return test::makeImage(64, 64, 3, [](int x, int y) -> std::vector<std::uint8_t> {
        return ((x / 16) + (y / 16)) % 2 ? std::vector<std::uint8_t>{200, 30, 30} : std::vector<std::uint8_t>{20, 160, 170};
    });
}

// Pixels that are clearly the checker's red, and its teal (the tone-mapped PNG).
std::pair<int, int> checkerPixels(const fs::path& png) {
    const QImage image(q(png));
    int red = 0, teal = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const QColor c = image.pixelColor(x, y);
            red += c.red() > 2 * c.green() && c.red() > 2 * c.blue() ? 1 : 0;
            teal += c.green() > 2 * c.red() && c.blue() > 2 * c.red() ? 1 : 0;
        }
    return {red, teal};
}

QStringList renderArgs(const fs::path& mesh, const fs::path& out) {
    return {"render", "--mesh", q(mesh), "--env", q(test::asset("env/forest.exr")), "--env-size", "64", "--size",
            "160x160", "--no-background", "--out", q(out)};
}

void writeText(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

TEST(AssetCommand, GltfAndObjWithMtlAreDrawnTexturedAndWithoutTheirImagesWithAWarning) {
    MIPGLOSS_REQUIRE_ASSET(test::asset("env/forest.exr"));
    test::TempDir dir;
    // glTF: the checker as an external image beside it.
    test::writePng(checker(), dir / "checker.png");
    test::GltfWriter w;
    const int base = w.addTexture(w.addImage({}, "checker.png"));
    w.addToScene(w.addNode(w.addMesh(test::texturedSphere(), w.addMaterial(test::pbrMaterial("Checker", {1, 1, 1, 1}, 0.0, 0.5, base)))));
    w.writeGltf(dir / "ball.gltf");
    // OBJ + MTL: a quad facing the camera, the same checker.
    writeText(dir / "tile.mtl", "newmtl Tile\nKd 1 1 1\nPr 0.5\nmap_Kd checker.png\n");
    writeText(dir / "tile.obj", "mtllib tile.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                "vn 0 0 1\nusemtl Tile\nf 1/1/1 2/2/1 3/3/1 4/4/1\n");
    for (const char* asset : {"ball.gltf", "tile.obj"}) {
        const fs::path out = dir / (std::string(asset) + ".png");
        const CliResult r = runCli(renderArgs(dir / asset, out));
        ASSERT_EQ(r.exitCode, 0) << asset << "\n" << r.err;
        const auto [red, teal] = checkerPixels(out);
        std::printf("[ AssetCommand ] %s textured: %d red and %d teal pixels\n", asset, red, teal);
        EXPECT_GT(red, 500) << asset;
        EXPECT_GT(teal, 500) << asset;
    }
    // The image gone: both drawn untextured (the factor's white), a warning naming the file.
    fs::remove(dir / "checker.png");
    for (const char* asset : {"ball.gltf", "tile.obj"}) {
        const fs::path out = dir / (std::string(asset) + "_missing.png");
        const CliResult r = runCli(renderArgs(dir / asset, out));
        ASSERT_EQ(r.exitCode, 0) << asset << "\n" << r.err;
        EXPECT_NE(r.err.find((dir / "checker.png").string()), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("file not found"), std::string::npos) << r.err;
        const auto [red, teal] = checkerPixels(out);
        EXPECT_LT(red, 20) << asset;
        EXPECT_LT(teal, 20) << asset;
    }
}

TEST(AssetCommand, AovExponentsVaryOverAnObjectWithARoughnessMap) {
    MIPGLOSS_REQUIRE_ASSET(test::asset("env/forest.exr"));
    test::TempDir dir;
    // Roughness 0.16 at the top (v = 0) to 0.90 at the bottom: both in view from any side.
    const test::TestImage ramp = test::makeImage(4, 64, 3, [](int, int y) -> std::vector<std::uint8_t> {
        return {0, static_cast<std::uint8_t>(40 + 3 * y), 0};
    });
    test::GltfWriter w;
    const int mr = w.addTexture(w.addImage(test::encodePng(ramp)));
    w.addToScene(w.addNode(w.addMesh(test::texturedSphere(), w.addMaterial(test::pbrMaterial("Ramp", {0.5f, 0.5f, 0.5f, 1}, 1.0, 1.0, -1, mr)))));
    w.writeGlb(dir / "ramp.glb");
    const fs::path out = dir / "ramp.exr", aov = dir / "ramp_aov.exr";
    QStringList args = renderArgs(dir / "ramp.glb", out);
    args << "--aov" << q(aov);
    const CliResult r = runCli(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto in = OIIO::ImageInput::open(aov.string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec spec = in->spec();
    const int e = spec.channelindex("exponent"), x = spec.channelindex("exact");
    ASSERT_GE(e, 0);
    std::vector<float> values(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, values.data()));
    float lowest = 1e30f, highest = 0.0f;
    int object = 0, exact = 0;
    for (std::size_t p = 0; p < values.size(); p += static_cast<std::size_t>(spec.nchannels)) {
        const float n = values[p + static_cast<std::size_t>(e)];
        if (n == 0.0f) continue;
        ++object;
        exact += values[p + static_cast<std::size_t>(x)] == 1.0f ? 1 : 0;
        lowest = std::min(lowest, n);
        highest = std::max(highest, n);
    }
    std::printf("[ AssetCommand ] roughness map: %d object pixels, exponents %.2f to %.1f, %d marked exact\n", object,
                lowest, highest, exact);
    ASSERT_GT(object, 160 * 160 / 4);
    // The AOV reports each GGX lobe as n = 2/α² − 2, α = r² (aov.frag): the pixels nearest the poles
    // show r ≈ 0.25 and ≈ 0.85, n ≈ 510 and 1.8. A layered pixel is K lookups, never one lobe: none
    // is marked exact (docs/material-truth.md).
    EXPECT_GT(highest / lowest, 100.0f);
    EXPECT_EQ(exact, 0);
}

TEST(AssetCommand, ImportGltfLandsTheMaterialsInALibraryByName) {
    test::TempDir dir;
    test::GltfWriter w;
    const int base = w.addTexture(w.addImage(test::encodePng(checker())));
    const int a = w.addMaterial(test::pbrMaterial("Weathered brass", {0.9f, 0.7f, 0.3f, 1}, 1.0, 0.35, base));
    const int b = w.addMaterial(test::pbrMaterial("Rubber grip", {0.05f, 0.05f, 0.05f, 1}, 0.0, 0.8));
    w.addToScene(w.addNode(w.addMesh(test::texturedSphere(8, 16), a)));
    w.addToScene(w.addNode(w.addMesh(test::texturedQuad(), b)));
    w.writeGlb(dir / "tool.glb");
    const fs::path lib = dir / "lib.mglib";
    CliResult r = runCli({"library", "import-gltf", q(lib), q(dir / "tool.glb")});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runCli({"library", "import-gltf", q(lib), q(dir / "tool.glb")});  // again: " 2" names
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runCli({"library", "list", q(lib)});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> names;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) names.push_back(line.substr(0, line.find('\t')));
    EXPECT_EQ(names, (std::vector<std::string>{"Weathered brass", "Rubber grip", "Weathered brass 2", "Rubber grip 2"}));
    EXPECT_NE(r.out.find("base-color-map " + (dir / "tool.glb").string() + "#image 0"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("metallic 1\troughness 0.35"), std::string::npos) << r.out;
}

// A material whose map names an image file that is not there is imported (the library keeps the
// reference: it draws once the file is back), with a warning naming the asset, the material and
// the file, rather than nothing until the library is opened.
TEST(AssetCommand, ImportGltfSaysWhichMaterialsReadAnImageThatIsNotThere) {
    test::TempDir dir;
    test::GltfWriter w;
    const int base = w.addTexture(w.addImage(test::encodePng(checker()), "gone.png"));
    w.addToScene(w.addNode(w.addMesh(test::texturedQuad(), w.addMaterial(test::pbrMaterial("Painted", {1, 1, 1, 1}, 0.0, 0.5, base)))));
    w.writeGltf(dir / "painted.gltf");
    fs::remove(dir / "gone.png");
    const CliResult r = runCli({"library", "import-gltf", q(dir / "lib.mglib"), q(dir / "painted.gltf")});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find((dir / "painted.gltf").string() + ": material \"Painted\" reads " + (dir / "gone.png").string() +
                         ", which is not there"),
              std::string::npos) << r.err;
    EXPECT_NE(r.out.find("added \"Painted\", textured"), std::string::npos) << r.out;
}

TEST(AssetCommand, HostileGltfIsRefusedNamingTheFileAndTheElement) {
    test::TempDir dir;
    test::GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(test::texturedQuad(), -1)));
    std::string json = w.gltf();
    struct Case {
        const char* file;
        std::string text;
        const char* names;
    };
    // Accessor 0 (POSITION) claims 4000 elements in a buffer view of 48 bytes.
    std::string past = json;
    past.replace(past.find("\"count\": 4"), 10, "\"count\": 4000");
    const std::vector<Case> cases{
        {"past.gltf", past, "accessor 0"},
        {"cut.gltf", json.substr(0, json.size() / 2), "not a readable glTF"},
        {"empty.glb", "", "empty"},
        {"garbage.glb", "glTF\x02\0\0\0\xff\xff\xff\xff", "not a readable GLB"},
    };
    for (const Case& c : cases) {
        writeText(dir / c.file, c.text);
        const CliResult r = runCli({"render", "--mesh", q(dir / c.file), "--out", q(dir / "x.png"), "--size", "64x64"});
        EXPECT_EQ(r.exitCode, 1) << c.file << "\n" << r.err;  // refused, not a crash (-1)
        EXPECT_NE(r.err.find((dir / c.file).string()), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(c.names), std::string::npos) << c.file << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir / "x.png"));
    }
}

}  // namespace
}  // namespace mipgloss
