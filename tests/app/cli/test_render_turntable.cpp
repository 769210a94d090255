// `mipgloss render`, run as a user would (a child process under the test's X display): turntables,
// spins, comparisons, a scene's saved camera, a 4K EXR, and what render refuses before it draws.
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/io/import.h"
#include "mipgloss/assets/mesh_files.h"
#include "render_cli_support.h"
#include "render_support.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <QImage>
#include <QProcess>
#include <QTemporaryDir>

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

// Turntables, spins and side-by-side comparisons (render's --spin, --turntable, --compare-*), and
// the sizes and names render refuses before it draws. Small pictures (160x120): CI is 2 cores.
namespace mipgloss {
namespace {

namespace fs = std::filesystem;

using test::CliResult;
using test::FloatImage;
using test::objectRect;
using test::q;
using test::readFloatImage;
using test::runRender;

// How two pictures of the same size differ, over columns [x0, x1) (8-bit channel steps).
struct PictureDiff {
    int maxChannel = 0;     // the largest channel difference
    double mean = 0.0;      // mean channel difference
    int pixelsOver = 0;     // pixels with a channel differing by more than the threshold
};

PictureDiff compare(const QImage& a, const QImage& b, int threshold = 8, int x0 = 0, int x1 = -1) {
    PictureDiff d;
    if (x1 < 0) x1 = a.width();
    long long sum = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = x0; x < x1; ++x) {
            const QRgb p = a.pixel(x, y), r = b.pixel(x, y);
            const int m = std::max({std::abs(qRed(p) - qRed(r)), std::abs(qGreen(p) - qGreen(r)),
                                    std::abs(qBlue(p) - qBlue(r))});
            sum += std::abs(qRed(p) - qRed(r)) + std::abs(qGreen(p) - qGreen(r)) + std::abs(qBlue(p) - qBlue(r));
            d.maxChannel = std::max(d.maxChannel, m);
            d.pixelsOver += m > threshold ? 1 : 0;
        }
    d.mean = static_cast<double>(sum) / (3.0 * a.height() * std::max(x1 - x0, 1));
    return d;
}

std::string describe(const PictureDiff& d) {
    std::ostringstream out;
    out << "max " << d.maxChannel << ", mean " << d.mean << ", " << d.pixelsOver << " pixels over";
    return out.str();
}

// Both pictures and their difference (×8) into the test output folder, for a failing comparison.
void keep(const std::string& name, const QImage& a, const QImage& b) {
    QImage diff(a.size(), QImage::Format_RGB32);
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const QRgb p = a.pixel(x, y), r = b.pixel(x, y);
            diff.setPixel(x, y, qRgb(std::min(255, 8 * std::abs(qRed(p) - qRed(r))),
                                     std::min(255, 8 * std::abs(qGreen(p) - qGreen(r))),
                                     std::min(255, 8 * std::abs(qBlue(p) - qBlue(r)))));
        }
    a.save(q(test::outputDir() / (name + "_a.png")));
    b.save(q(test::outputDir() / (name + "_b.png")));
    diff.save(q(test::outputDir() / (name + "_diff.png")));
}

// A teapot (a mirror) and a glossy sphere off the axis under the built-in environment turned by
// 30°, seen through a saved camera (so every render of it, whatever its objects' placement, is
// seen from the same place). `turn`: the objects really turned by that many degrees about the
// vertical axis through the camera's target, as on a turntable.
const glm::vec3 kTarget(0.5f, 0.3f, 0.0f);

fs::path writeTurntableScene(const fs::path& file, float turn = 0.0f) {
    struct Placed {
        const char* mesh;
        const char* material;
        glm::vec3 at;
        float yaw, scale;
    };
    const Placed objects[] = {{"builtin:teapot", "chrome", {0.0f, 0.0f, 0.0f}, 20.0f, 1.0f},
                              {"builtin:sphere", "satin", {1.6f, 0.4f, -0.5f}, 0.0f, 0.45f}};
    const float c = std::cos(glm::radians(turn)), s = std::sin(glm::radians(turn));
    std::ostringstream json;
    json.precision(9);
    json << R"({"format": "mipgloss-scene", "version": 6,
      "environment": {"source": "builtin:courtyard", "faceSize": 64},
      "display": {"environmentRotationDegrees": 30, "backgroundLambda": 1},
      "materials": [{"name": "chrome", "lambda": 0, "tint": [1, 0.85, 0.6]}, {"name": "satin", "lambda": 3}],
      "objects": [)";
    for (std::size_t i = 0; i < std::size(objects); ++i) {
        const Placed& o = objects[i];
        // Ry(turn) about the target: the position turns, and so does the object (its own yaw).
        const glm::vec3 d = o.at - kTarget;
        const glm::vec3 at = kTarget + glm::vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
        json << (i ? ", " : "") << R"({"mesh": ")" << o.mesh << R"(", "material": ")" << o.material
             << R"(", "transform": {"translation": [)" << at.x << ", " << at.y << ", " << at.z
             << R"(], "rotationDegrees": [0, )" << o.yaw + turn << "," << R"( 0], "scale": )" << o.scale << "}}";
    }
    json << R"(],
      "camera": {"target": [)" << kTarget.x << ", " << kTarget.y << ", " << kTarget.z
         << R"(], "distance": 5.5, "yawDegrees": 25, "pitchDegrees": 15, "fovYDegrees": 35}})";
    std::ofstream(file) << json.str();
    return file;
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

QStringList small(const fs::path& scene) { return {q(scene), "--size", "160x120", "--quiet"}; }

// A scene saved with a camera is drawn through it (twice as far: the objects half as wide), one
// without is framed, and --yaw frames again.
TEST(RenderCommand, ASceneIsDrawnThroughItsSavedCamera) {
    test::TempDir dir;
    const fs::path scene = writeTurntableScene(dir / "scene.mipgloss");
    std::string text = test::readText(scene);
    const std::string saved = "\"distance\": 5.5";
    const std::size_t at = text.find(saved);
    ASSERT_NE(at, std::string::npos);
    std::ofstream(dir / "far.mipgloss") << std::string(text).replace(at, saved.size(), "\"distance\": 11");
    std::ofstream(dir / "framed.mipgloss") << text.substr(0, text.find(",\n      \"camera\"")) + "}";
    auto widthOf = [&](const std::string& name, const QStringList& extra = {}) {
        const fs::path out = dir / (name + ".png");
        const CliResult r = runRender(small(dir / (name + ".mipgloss")) + extra +
                                   QStringList{"--no-background", "--samples", "0", "--out", q(out)});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return objectRect(QImage(q(out))).width();
    };
    const int near = widthOf("scene"), far = widthOf("far"), framed = widthOf("framed");
    EXPECT_NEAR(static_cast<double>(far) / near, 0.5, 0.08) << near << " and " << far << " pixels wide";
    EXPECT_GT(std::abs(framed - near), 4) << "framed, not the saved view";
    EXPECT_NE(widthOf("far", {"--yaw", "25"}), far) << "--yaw frames again";
}

// N frames of a whole turn: exactly N files, all different, the first the plain render, the last
// one step before it (--spin -45 and --spin 315 alike): a seamless loop.
TEST(RenderCommand, TurntableWritesEveryFrameOfASeamlessTurn) {
    test::TempDir dir;
    const fs::path scene = writeTurntableScene(dir / "scene.mipgloss");
    const fs::path frames = dir / "frames";
    const CliResult turn = runRender(small(scene) + QStringList{"--turntable", "8", "--out", q(frames / "frame_%03d.png")});
    ASSERT_EQ(turn.exitCode, 0) << turn.err;
    EXPECT_EQ(turn.err.find("frame 1/8"), std::string::npos) << "--quiet: no progress\n" << turn.err;
    const std::vector<std::string> names = filesIn(frames);
    ASSERT_EQ(names.size(), 8u);
    std::vector<QImage> images;
    for (int i = 0; i < 8; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%03d.png", i);
        EXPECT_EQ(names[static_cast<std::size_t>(i)], name);
        images.emplace_back(q(frames / name));
        ASSERT_EQ(images.back().size(), QSize(160, 120)) << name;
    }
    for (std::size_t i = 0; i < images.size(); ++i)
        for (std::size_t j = i + 1; j < images.size(); ++j)
            EXPECT_GT(compare(images[i], images[j]).pixelsOver, 100) << "frames " << i << " and " << j;

    // Measured on llvmpipe: identical (the same camera and rotation to the last bit). Bound: no
    // channel off by more than 1 step.
    auto expectSame = [&](const QImage& frame, const QStringList& extra, const std::string& what) {
        const fs::path out = dir / "single.png";
        const CliResult r = runRender(small(scene) + extra + QStringList{"--out", q(out)});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const QImage single(q(out));
        const PictureDiff d = compare(frame, single);
        EXPECT_LE(d.maxChannel, 1) << what << ": " << describe(d);
        if (d.maxChannel > 1) keep("turntable_" + what, frame, single);
    };
    expectSame(images[0], {}, "frame0_plain");
    expectSame(images[7], {"--spin", "-45"}, "frame7_spin-45");
    expectSame(images[7], {"--spin", "315"}, "frame7_spin315");
    expectSame(images[2], {"--spin", "90"}, "frame2_spin90");
}

// The end-to-end proof of the sign: turning the view by θ (object spin) is the scene whose objects
// really stand turned by θ about the target's vertical axis, seen through the same saved camera,
// background and objects alike; the opposite sign is clearly not.
TEST(RenderCommand, ObjectSpinIsTheSceneWithItsObjectsReallyTurned) {
    test::TempDir dir;
    const fs::path scene = writeTurntableScene(dir / "scene.mipgloss");
    for (const float theta : {60.0f, -130.0f}) {
        const std::string tag = std::to_string(static_cast<int>(theta));
        const fs::path turnedScene = writeTurntableScene(dir / ("turned" + tag + ".mipgloss"), theta);
        const fs::path spun = dir / ("spun" + tag + ".png"), real = dir / ("real" + tag + ".png"),
                       wrong = dir / ("wrong" + tag + ".png");
        ASSERT_EQ(runRender(small(scene) + QStringList{"--spin", QString::number(theta), "--out", q(spun)}).exitCode, 0);
        ASSERT_EQ(runRender(small(turnedScene) + QStringList{"--out", q(real)}).exitCode, 0);
        ASSERT_EQ(runRender(small(scene) + QStringList{"--spin", QString::number(-theta), "--out", q(wrong)}).exitCode, 0);
        const QImage a(q(spun)), b(q(real)), c(q(wrong));
        const PictureDiff same = compare(a, b), opposite = compare(c, b);
        std::printf("[ RenderCommand ] spin %g vs objects turned %g: %s; the opposite sign: max %d, %d pixels over\n",
                    theta, theta, describe(same).c_str(), opposite.maxChannel,
                    opposite.pixelsOver);
        // Measured on llvmpipe: max 2 and 3 steps, mean 0.0003, no pixel over 8 (the geometry's
        // rounding differs, nothing else); the opposite sign 7 355 and 7 564 pixels over. Bounds: at most 0.5 % of the pixels (96) over 8 steps, mean under
        // 0.1 step, and the opposite sign at least 1 % over.
        EXPECT_LE(same.pixelsOver, 96) << "θ " << theta << ": " << describe(same);
        EXPECT_LT(same.mean, 0.1) << "θ " << theta << ": " << describe(same);
        EXPECT_GT(opposite.pixelsOver, 192) << "θ " << theta << ": " << describe(opposite);
        if (same.pixelsOver > 96 || same.mean >= 0.1) keep("spin_vs_turned" + tag, a, b);
    }
}

// Environment spin: the objects stay where they are (the same silhouettes against a plain
// background), their reflections turn.
TEST(RenderCommand, EnvironmentSpinKeepsTheSilhouettesAndTurnsTheReflections) {
    test::TempDir dir;
    const fs::path scene = writeTurntableScene(dir / "scene.mipgloss");
    const fs::path plain = dir / "plain.png", spun = dir / "spun.png";
    const QStringList flat{"--no-background", "--samples", "0"};
    ASSERT_EQ(runRender(small(scene) + flat + QStringList{"--out", q(plain)}).exitCode, 0);
    const CliResult r = runRender(small(scene) + flat +
                               QStringList{"--spin", "90", "--turntable-spin", "environment", "--out", q(spun)});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const QImage a(q(plain)), b(q(spun));
    const QRgb background = a.pixel(0, 0);
    ASSERT_EQ(b.pixel(0, 0), background);
    int object = 0, silhouetteDiffers = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const bool inA = a.pixel(x, y) != background, inB = b.pixel(x, y) != background;
            object += inA ? 1 : 0;
            silhouetteDiffers += inA != inB ? 1 : 0;
        }
    EXPECT_GT(object, 160 * 120 / 20);
    EXPECT_EQ(silhouetteDiffers, 0);
    const PictureDiff reflections = compare(a, b);
    EXPECT_GT(reflections.pixelsOver, object / 4) << describe(reflections);
    if (silhouetteDiffers != 0) keep("environment_spin", a, b);
}

// --compare-builder and --compare-env: the left half is the plain render, bit for bit (measured
// identical on llvmpipe: the same GL state draws it); the right half is the render with the other
// environment (again bit for bit), the PNG's divider in its first column aside.
TEST(RenderCommand, ComparisonsKeepTheLeftHalfAndShowTheOtherEnvironmentOnTheRight) {
    test::TempDir dir;
    const fs::path scene = writeTurntableScene(dir / "scene.mipgloss");
    const QString sunset = q(test::asset("env/sunset.exr"));
    struct Case {
        QStringList compareFlags, sameAsFlags;
        const char* name;
    };
    for (const Case& c : {Case{{"--compare-builder", "box"}, {"--builder", "box"}, "builder"},
                          Case{{"--compare-env", sunset}, {"--env", sunset}, "env"}}) {
        for (const char* ext : {".png", ".exr"}) {
            const fs::path plain = dir / (std::string("plain") + ext), other = dir / (std::string("other") + ext),
                           both = dir / (std::string(c.name) + ext);
            ASSERT_EQ(runRender(small(scene) + QStringList{"--out", q(plain)}).exitCode, 0);
            ASSERT_EQ(runRender(small(scene) + c.sameAsFlags + QStringList{"--out", q(other)}).exitCode, 0);
            const CliResult r = runRender(small(scene) + c.compareFlags + QStringList{"--out", q(both)});
            ASSERT_EQ(r.exitCode, 0) << r.err;
            if (std::string(ext) == ".png") {
                const QImage left(q(plain)), right(q(other)), picture(q(both));
                ASSERT_EQ(picture.size(), QSize(160, 120));
                EXPECT_EQ(compare(picture, left, 0, 0, 80).maxChannel, 0) << c.name;
                EXPECT_EQ(compare(picture, right, 0, 81, 160).maxChannel, 0) << c.name;
                // Measured: 602 (box) and 9 417 (sunset) of the 9 480 right-half pixels over 8 steps.
                const PictureDiff changed = compare(picture, left, 8, 81, 160);
                std::printf("[ RenderCommand ] --compare-%s: right half against the plain render: %s\n", c.name,
                            describe(changed).c_str());
                EXPECT_GT(changed.pixelsOver, 300) << c.name << ": the right half changed";
                for (int y = 0; y < 120; ++y) EXPECT_EQ(picture.pixel(80, y), qRgb(255, 255, 255)) << "divider, row " << y;
                if (compare(picture, left, 0, 0, 80).maxChannel != 0) keep(std::string("compare_") + c.name, picture, left);
            } else {
                const FloatImage left = readFloatImage(plain), right = readFloatImage(other),
                                 picture = readFloatImage(both);
                ASSERT_EQ(picture.width, 160);
                ASSERT_EQ(picture.channels, (std::vector<std::string>{"R", "G", "B"}));
                int leftDiffers = 0, rightDiffers = 0, changed = 0;
                for (int y = 0; y < 120; ++y)
                    for (int x = 0; x < 160; ++x)
                        for (const char* ch : {"R", "G", "B"}) {
                            const float v = picture.at(x, y, ch);
                            if (x < 80) leftDiffers += v != left.at(x, y, ch) ? 1 : 0;
                            else {
                                rightDiffers += v != right.at(x, y, ch) ? 1 : 0;  // no divider: pure data
                                changed += std::abs(v - left.at(x, y, ch)) > 0.01f * (1.0f + std::abs(v)) ? 1 : 0;
                            }
                        }
                EXPECT_EQ(leftDiffers, 0) << c.name;
                EXPECT_EQ(rightDiffers, 0) << c.name;
                EXPECT_GT(changed, 80 * 120 / 10) << c.name;
            }
        }
    }
}

// A 4k linear picture: 3840x2160 float RGB, read back with OpenImageIO.
TEST(RenderCommand, FourKLinearExrIsWrittenWholeAsFloatRgb) {
    test::TempDir dir;
    const fs::path out = dir / "4k.exr";
    const auto start = std::chrono::steady_clock::now();
    const CliResult r = runRender({"--size", "3840x2160", "--quiet", "--out", q(out)});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::printf("[ RenderCommand ] Figure 1 at 3840x2160 to a linear EXR: %.2f s, the whole command\n", seconds);
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 3840);
    EXPECT_EQ(spec.height, 2160);
    EXPECT_EQ(spec.nchannels, 3);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
    std::vector<float> row(3840 * 3);
    ASSERT_TRUE(in->read_scanline(1080, 0, OIIO::TypeDesc::FLOAT, row.data()));
    EXPECT_GT(*std::max_element(row.begin(), row.end()), 0.0f);
}

// What render refuses before it draws: exit status non-zero, the problem named, no file written.
TEST(RenderCommand, BadSizesPatternsCountsAndFoldersAreRefusedWritingNothing) {
    test::TempDir dir;
    const fs::path scene = writeTurntableScene(dir / "scene.mipgloss");
    std::ofstream(dir / "not-a-folder") << "a file";
    const std::string d = dir.path().string();
    struct Refusal {
        QStringList args;
        std::vector<std::string> named;  // each in the message
    };
    std::vector<Refusal> refusals = {
        {{"--size", "0x120", "--out", q(dir / "a.png")}, {"--size", "0x120", "width 0"}},
        {{"--size", "160x-5", "--out", q(dir / "a.png")}, {"--size", "160x-5", "height -5"}},
        {{"--size", "100000x120", "--out", q(dir / "a.png")}, {"--size", "100000", "GL_MAX_"}},
        {{"--size", "160x100000", "--out", q(dir / "a.exr")}, {"--size", "100000", "GL_MAX_"}},
        {{"--size", "99999999999x1", "--out", q(dir / "a.png")}, {"--size", "99999999999x1"}},
        {{"--size", "big", "--out", q(dir / "a.png")}, {"--size", "big"}},
        {{"--turntable", "4", "--out", q(dir / "frame.png")}, {"--turntable", "frame.png", "integer conversion"}},
        {{"--turntable", "4", "--out", q(dir / "frame_%s.png")}, {"'%s'", "integer conversion"}},
        {{"--turntable", "4", "--out", q(dir / "f_%d_%03d.png")}, {"more than one", "'%03d'"}},
        {{"--turntable", "4", "--out", q(dir / "%d" / "f.png")}, {"folder", "'%d'"}},
        {{"--turntable", "4", "--out", q(dir / "f_%d.xyz")}, {"--out", ".xyz"}},
        {{"--turntable", "0", "--out", q(dir / "f_%d.png")}, {"--turntable", "'0'", "1 to 3600"}},
        {{"--turntable", "3601", "--out", q(dir / "f_%d.png")}, {"--turntable", "'3601'"}},
        {{"--turntable", "-2", "--out", q(dir / "f_%d.png")}, {"--turntable", "'-2'"}},
        {{"--turntable", "2.5", "--out", q(dir / "f_%d.png")}, {"--turntable", "'2.5'"}},
        {{"--turntable-spin", "camera", "--out", q(dir / "a.png")}, {"--turntable-spin", "camera"}},
        {{"--turntable", "4", "--out", q(dir / "not-a-folder" / "f_%d.png")}, {"not-a-folder", "not a folder"}},
        {{"--out", q(dir / "not-a-folder" / "sub" / "a.png")}, {"not-a-folder", "not a folder"}},
        {{"--turntable", "2", "--out", "/proc/mipgloss_%d.png"}, {"/proc", "cannot write"}},
        {{"--compare-builder", "box", "--turntable", "2", "--out", q(dir / "f_%d.png")},
         {"--compare-builder", "--turntable"}},
        {{"--compare-env", q(dir / "sky.exr"), "--aov", q(dir / "aov.exr"), "--out", q(dir / "a.exr")},
         {"--compare-env", "--aov"}},
        {{"--compare-builder", "sideways", "--out", q(dir / "a.png")}, {"--compare-builder", "sideways"}},
        {{"--compare-env", q(dir / "missing.exr"), "--out", q(dir / "a.png")}, {"missing.exr"}},
    };
    // One sample beyond this OpenGL's GL_MAX_SAMPLES (llvmpipe's 4 or 8, a GPU's 32): refused with
    // the limit named; where the limit is at or beyond --samples' own 16, 17 is refused by the flag.
    std::string glError;
    ui::OffscreenRenderer* renderer = test::sharedRenderer(&glError);
    ASSERT_NE(renderer, nullptr) << glError;
    const int maxSamples = renderer->maxRenderSize().maxSamples;
    ASSERT_GT(maxSamples, 0);
    const int beyond = std::min(maxSamples, 16) + 1;
    const std::string samplesFlag = "--samples " + std::to_string(beyond);
    refusals.push_back({{"--samples", QString::number(beyond), "--out", q(dir / "a.png")},
                        beyond <= 16 ? std::vector<std::string>{samplesFlag, "GL_MAX_SAMPLES"}
                                     : std::vector<std::string>{"--samples needs a number from 0", "'17'"}});
    for (const Refusal& refusal : refusals) {
        const CliResult r = runRender(small(scene) + refusal.args);
        const std::string what = refusal.args.join(' ').toStdString();
        EXPECT_NE(r.exitCode, 0) << what;
        for (const std::string& word : refusal.named) EXPECT_NE(r.err.find(word), std::string::npos) << what << ": " << r.err;
        EXPECT_EQ(filesIn(dir.path()), (std::vector<std::string>{"not-a-folder", "scene.mipgloss"})) << what;
    }
}

}  // namespace
}  // namespace mipgloss
