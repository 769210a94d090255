// `mipgloss render`, run as a user would (a child process under the test's X display).
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

namespace mipgloss {
namespace {

using test::CliResult;
using test::FloatImage;
using test::objectRect;
using test::readFloatImage;
using test::runRender;

// A copy of an OBJ with every vertex scaled so the largest extent is `size`.
void writeScaledObj(const std::filesystem::path& from, const std::filesystem::path& to, float size) {
    std::ifstream in(from);
    std::vector<std::string> lines;
    std::string line;
    glm::vec3 lo(1e30f), hi(-1e30f);
    while (std::getline(in, line)) {
        lines.push_back(line);
        if (line.rfind("v ", 0) == 0) {
            std::istringstream s(line.substr(2));
            glm::vec3 p;
            s >> p.x >> p.y >> p.z;
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    }
    const glm::vec3 extent = hi - lo;
    const float k = size / std::max({extent.x, extent.y, extent.z});
    std::ofstream out(to);
    for (const std::string& l : lines) {
        if (l.rfind("v ", 0) == 0) {
            std::istringstream s(l.substr(2));
            glm::vec3 p;
            s >> p.x >> p.y >> p.z;
            out << "v " << p.x * k << ' ' << p.y * k << ' ' << p.z * k << '\n';
        } else {
            out << l << '\n';
        }
    }
}

TEST(RenderCommand, DefaultSceneIsFigure1) {
    QTemporaryDir dir;
    const QString out = dir.filePath("default.png");
    const CliResult run = runRender({"--out", out});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const QImage image(out);
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(image.size(), QSize(1024, 384));
    EXPECT_NE(run.err.find("4 objects (4 drawn"), std::string::npos) << run.err;
}

TEST(RenderCommand, EnvironmentAloneDrawsJustTheEnvironment) {
    QTemporaryDir dir;
    const QString out = dir.filePath("env.png");
    const CliResult run = runRender({"--env", QString::fromStdString(test::asset("env/sunset.exr").string()), "--size",
                            "320x200", "--out", out});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.err.find("0 objects"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("filtered through level 0"), std::string::npos)
        << "nothing reaches past level 0: no lobe filtering\n" << run.err;
    const QImage image(out);
    ASSERT_EQ(image.size(), QSize(320, 200));
    // A real sky: not one flat colour.
    EXPECT_TRUE(objectRect(image).isValid());
}

TEST(RenderCommand, MeshesAreFramedWhateverTheirScale) {
    QTemporaryDir dir;
    std::vector<QRect> rects;
    for (const float size : {0.2f, 120.0f}) {
        const std::filesystem::path obj = std::filesystem::path(dir.path().toStdString()) /
                                          ("bunny_" + std::to_string(static_cast<int>(size * 10)) + ".obj");
        writeScaledObj(test::asset("meshes/bunny_npm_lowres.obj"), obj, size);
        const QString out = dir.filePath(QStringLiteral("bunny_%1.png").arg(size));
        const CliResult run = runRender({"--mesh", QString::fromStdString(obj.string()), "--no-background", "--size",
                                "400x300", "--samples", "0", "--out", out});
        ASSERT_EQ(run.exitCode, 0) << run.err;
        const QRect r = objectRect(QImage(out));
        ASSERT_TRUE(r.isValid());
        // Framed: the mesh spans most of the limiting dimension, and nothing is cut off.
        EXPECT_GT(std::max(r.width() / 400.0, r.height() / 300.0), 0.7) << "size " << size;
        EXPECT_GT(r.left(), 0);
        EXPECT_GT(r.top(), 0);
        EXPECT_LT(r.right(), 399);
        EXPECT_LT(r.bottom(), 299);
        rects.push_back(r);
    }
    // The same picture at both scales, to a pixel or two.
    EXPECT_LE(std::abs(rects[0].width() - rects[1].width()), 2);
    EXPECT_LE(std::abs(rects[0].height() - rects[1].height()), 2);
}

TEST(RenderCommand, BadInputIsAMessageNamingTheFileAndExitOne) {
    QTemporaryDir dir;
    const QString out = dir.filePath("x.png");
    const std::string truncated = (dir.path() + "/truncated.obj").toStdString();
    std::ofstream(truncated) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2";
    CliResult run = runRender({"--mesh", QString::fromStdString(truncated), "--out", out});
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_NE(run.err.find("truncated.obj"), std::string::npos) << run.err;

    const std::string notAnImage = (dir.path() + "/sky.exr").toStdString();
    std::ofstream(notAnImage) << "this is not an image";
    run = runRender({"--env", QString::fromStdString(notAnImage), "--out", out});
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_NE(run.err.find("sky.exr"), std::string::npos) << run.err;

    run = runRender({"--lambda", "nan", "--out", out});
    EXPECT_EQ(run.exitCode, 2) << "absurd λ is a usage error";
    run = runRender({});
    EXPECT_EQ(run.exitCode, 2) << "--out is required";
    EXPECT_FALSE(QFile::exists(out));
}

}  // namespace
}  // namespace mipgloss

namespace mipgloss {
namespace {

// "Renders anyone can check": the linear EXR and the AOV from the command line, read back with
// OpenImageIO and checked against the exact convolution at the directions the AOV names.
TEST(RenderCommand, LinearExrAndAovLetAnyoneCheckThePicture) {
    test::TempDir dir;
    const auto sphere = dir / "sphere.obj";
    writeMesh(makeSphere(64, 128), sphere);
    const auto out = dir / "sphere.exr", aov = dir / "sphere_aov.exr";
    const CliResult r = runRender({"--env", QString::fromStdString(test::asset("env/sunrise.exr").string()), "--env-size",
                                "64", "--mesh", QString::fromStdString(sphere.string()), "--exponent", "16", "--size",
                                "192x192", "--no-background", "--out", QString::fromStdString(out.string()), "--aov",
                                QString::fromStdString(aov.string())});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const FloatImage picture = readFloatImage(out), account = readFloatImage(aov);
    ASSERT_EQ(picture.width, 192);
    ASSERT_EQ(account.width, 192);
    ASSERT_FALSE(picture.values.empty());
    ASSERT_FALSE(account.values.empty());
    std::vector<std::string> names = account.channels;
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"dirX", "dirY", "dirZ", "exact", "exponent"}));

    // The truth: the same import, the exact normalized Phong convolution at the AOV's directions.
    ImportOptions options;
    options.faceSize = 64;
    const CubeMap base = loadEnvironment(test::asset("env/sunrise.exr"), options).cube;
    std::vector<glm::vec3> directions;
    std::vector<double> exponents;
    std::vector<Rgb> shown;
    int object = 0;
    for (int y = 0; y < account.height; ++y)
        for (int x = 0; x < account.width; ++x) {
            const float exponent = account.at(x, y, "exponent");
            if (exponent == 0.0f) continue;
            ++object;
            // The lobe the pixel shows: n = 16 widened by its footprint (lobe_stack.glsl), never sharper.
            EXPECT_LE(exponent, 16.0f * (1.0f + 1e-5f)) << x << "," << y;
            EXPECT_GT(exponent, 0.0f) << x << "," << y;
            const glm::vec3 d(account.at(x, y, "dirX"), account.at(x, y, "dirY"), account.at(x, y, "dirZ"));
            EXPECT_NEAR(glm::length(d), 1.0f, 1e-4f);
            if (account.at(x, y, "exact") != 1.0f) continue;
            directions.push_back(d);
            exponents.push_back(exponent);
            shown.push_back(Rgb(picture.at(x, y, "R"), picture.at(x, y, "G"), picture.at(x, y, "B")));
        }
    ASSERT_GT(object, 192 * 192 / 8);
    EXPECT_GE(static_cast<double>(directions.size()) / object, 0.8) << "issue 24: at least 80 % of the object marked exact";
    const double error = relativeRms(shown, test::exactLobesAt(base, exponents, directions));
    std::printf("[ RenderCommand ] exponent 16 at face 64: %zu of %d object pixels exact, relative RMS %.2f %%\n",
                directions.size(), object, 100.0 * error);
    // Bound 2 %, the issue's.
    EXPECT_LE(error, 0.02);
}

// --no-stack: what the window shows before any lobe stack entry has arrived. The glossy sphere is
// read from the chain, so it differs from the settled picture, and no glossy pixel is marked exact
// (only the lobe stack, the mirror or the irradiance map can be). --no-settle: what the window shows
// while a slider moves, every entry made ahead: the settled picture (no entry besides those in use
// is read; the atlas holds them elsewhere, so bilinear weights round differently: within 0.1 %),
// its AOV the same.
TEST(RenderCommand, NoSettleIsTheSettledPictureAndNoStackTheChainsWithNoGlossyPixelExact) {
    test::TempDir dir;
    const auto sphere = dir / "sphere.obj";
    writeMesh(makeSphere(32, 64), sphere);
    const QString env = QString::fromStdString(test::asset("env/sunrise.exr").string());
    auto render = [&](const std::string& name, const char* flag) {
        const auto out = dir / (name + ".exr"), aov = dir / (name + "_aov.exr");
        QStringList args{"--env", env, "--env-size", "64", "--mesh", QString::fromStdString(sphere.string()),
                         "--exponent", "16", "--size", "192x192", "--no-background", "--out",
                         QString::fromStdString(out.string()), "--aov", QString::fromStdString(aov.string())};
        if (flag) args << flag;
        const CliResult r = runRender(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return std::pair(readFloatImage(out), readFloatImage(aov));
    };
    const auto [settled, settledAov] = render("settled", nullptr);
    const auto [instant, instantAov] = render("instant", "--no-settle");
    const auto [chain, chainAov] = render("chain", "--no-stack");
    ASSERT_EQ(chain.width, 192);
    ASSERT_EQ(instant.width, 192);
    int object = 0, exactSettled = 0, exactInstant = 0, exactChain = 0;
    double sumDifference = 0.0, sum = 0.0, instantDifference = 0.0;
    for (int y = 0; y < 192; ++y)
        for (int x = 0; x < 192; ++x) {
            if (chainAov.at(x, y, "exponent") == 0.0f) continue;
            ++object;
            EXPECT_NEAR(chainAov.at(x, y, "exponent"), 16.0f, 1e-3f);
            exactSettled += settledAov.at(x, y, "exact") == 1.0f ? 1 : 0;
            exactInstant += instantAov.at(x, y, "exact") == 1.0f ? 1 : 0;
            exactChain += chainAov.at(x, y, "exact") == 1.0f ? 1 : 0;
            for (const char* c : {"R", "G", "B"}) {
                sumDifference += std::abs(chain.at(x, y, c) - settled.at(x, y, c));
                instantDifference = std::max(instantDifference, std::abs(instant.at(x, y, c) - settled.at(x, y, c)) /
                                                                    std::max(std::abs(static_cast<double>(settled.at(x, y, c))), 1e-3));
                sum += std::abs(settled.at(x, y, c));
            }
        }
    ASSERT_GT(object, 192 * 192 / 8);
    std::printf("[ RenderCommand ] exponent 16: settled %d of %d exact, --no-settle %d (largest relative difference %.2g), "
                "--no-stack %d; mean |chain - settled| %.2f %% of the mean\n", exactSettled, object, exactInstant,
                instantDifference, exactChain, 100.0 * sumDifference / sum);
    EXPECT_GE(exactSettled, object * 8 / 10);
    EXPECT_EQ(exactInstant, exactSettled);
    EXPECT_LE(instantDifference, 1e-3) << "the entries made ahead changed the picture";
    EXPECT_EQ(exactChain, 0);
    EXPECT_GT(sumDifference / sum, 1e-3) << "the chain's picture is the stack's: were the entries made?";
    const CliResult both = runRender({"--no-settle", "--no-stack", "--out", "never.png"});
    EXPECT_EQ(both.exitCode, 2) << both.err;
    EXPECT_NE(both.err.find("--no-stack"), std::string::npos) << both.err;
}

TEST(RenderCommand, AbsurdExponentOrLambdaIsAUsageErrorNamingTheFlag) {
    for (const QStringList& args : {QStringList{"--exponent", "-1"}, QStringList{"--exponent", "nan"},
                                    QStringList{"--lambda", "1e9"}, QStringList{"--lambda", "-0.5"}}) {
        const CliResult r = runRender(args + QStringList{"--out", "never.png"});
        EXPECT_EQ(r.exitCode, 2) << args.join(' ').toStdString() << ": " << r.err;
        EXPECT_NE(r.err.find(args.front().toStdString()), std::string::npos) << r.err;
    }
}

}  // namespace
}  // namespace mipgloss
