// `mipgloss render`, run as a user would (a child process under the test's X display).
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/mesh.h"
#include "render_support.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <QImage>
#include <QProcess>
#include <QTemporaryDir>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace mipgloss {
namespace {

struct CliResult {
    int exitCode = -1;
    std::string err;
};

CliResult runCli(const QStringList& args) {
    QProcess process;
    process.start(QStringLiteral(MIPGLOSS_CLI), QStringList{"render"} + args);
    process.waitForFinished(120000);
    return {process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -1,
            process.readAllStandardError().toStdString()};
}

// The bounding box of pixels that differ from the top-left corner's (the flat background).
QRect objectRect(const QImage& image) {
    const QRgb background = image.pixel(0, 0);
    QRect r;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (image.pixel(x, y) != background) r |= QRect(x, y, 1, 1);
    return r;
}

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
    const CliResult run = runCli({"--out", out});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const QImage image(out);
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(image.size(), QSize(1024, 384));
    EXPECT_NE(run.err.find("4 objects (4 drawn"), std::string::npos) << run.err;
}

TEST(RenderCommand, EnvironmentAloneDrawsJustTheEnvironment) {
    QTemporaryDir dir;
    const QString out = dir.filePath("env.png");
    const CliResult run = runCli({"--env", QString::fromStdString(test::asset("env/sunset.exr").string()), "--size",
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
        const CliResult run = runCli({"--mesh", QString::fromStdString(obj.string()), "--no-background", "--size",
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
    CliResult run = runCli({"--mesh", QString::fromStdString(truncated), "--out", out});
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_NE(run.err.find("truncated.obj"), std::string::npos) << run.err;

    const std::string notAnImage = (dir.path() + "/sky.exr").toStdString();
    std::ofstream(notAnImage) << "this is not an image";
    run = runCli({"--env", QString::fromStdString(notAnImage), "--out", out});
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_NE(run.err.find("sky.exr"), std::string::npos) << run.err;

    run = runCli({"--lambda", "nan", "--out", out});
    EXPECT_EQ(run.exitCode, 2) << "absurd λ is a usage error";
    run = runCli({});
    EXPECT_EQ(run.exitCode, 2) << "--out is required";
    EXPECT_FALSE(QFile::exists(out));
}

}  // namespace
}  // namespace mipgloss

namespace mipgloss {
namespace {

// One float image read back with its channel names (top row first).
struct FloatImage {
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::vector<float> values;
    float at(int x, int y, const std::string& channel) const {
        const auto c = std::find(channels.begin(), channels.end(), channel) - channels.begin();
        return values[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                          channels.size() + static_cast<std::size_t>(c)];
    }
};

FloatImage readFloatImage(const std::filesystem::path& file) {
    FloatImage image;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) return image;
    const OIIO::ImageSpec& spec = in->spec();
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.channelnames;
    image.values.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                        static_cast<std::size_t>(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.values.data())) image.values.clear();
    return image;
}

// "Renders anyone can check": the linear EXR and the AOV from the command line, read back with
// OpenImageIO and checked against the exact convolution at the directions the AOV names.
TEST(RenderCommand, LinearExrAndAovLetAnyoneCheckThePicture) {
    test::TempDir dir;
    const auto sphere = dir / "sphere.obj";
    writeMesh(makeSphere(64, 128), sphere);
    const auto out = dir / "sphere.exr", aov = dir / "sphere_aov.exr";
    const CliResult r = runCli({"--env", QString::fromStdString(test::asset("env/sunrise.exr").string()), "--env-size",
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
    std::vector<Rgb> shown;
    int object = 0;
    for (int y = 0; y < account.height; ++y)
        for (int x = 0; x < account.width; ++x) {
            const float exponent = account.at(x, y, "exponent");
            if (exponent == 0.0f) continue;
            ++object;
            EXPECT_NEAR(exponent, 16.0f, 1e-3f) << x << "," << y;
            const glm::vec3 d(account.at(x, y, "dirX"), account.at(x, y, "dirY"), account.at(x, y, "dirZ"));
            EXPECT_NEAR(glm::length(d), 1.0f, 1e-4f);
            if (account.at(x, y, "exact") != 1.0f) continue;
            directions.push_back(d);
            shown.push_back(Rgb(picture.at(x, y, "R"), picture.at(x, y, "G"), picture.at(x, y, "B")));
        }
    ASSERT_GT(object, 192 * 192 / 8);
    EXPECT_GE(static_cast<double>(directions.size()) / object, 0.5) << "at least half the object marked exact";
    const double error = relativeRms(shown, referenceLobeAt(base, 16.0, directions));
    std::printf("[ RenderCommand ] exponent 16 at face 64: %zu of %d object pixels exact, relative RMS %.2f %%\n",
                directions.size(), object, 100.0 * error);
    // Measured 0.84 % (12 364 of 13 432 pixels exact) on llvmpipe; bound 2 %, the issue's.
    EXPECT_LE(error, 0.02);
}

TEST(RenderCommand, AbsurdExponentOrLambdaIsAUsageErrorNamingTheFlag) {
    for (const QStringList& args : {QStringList{"--exponent", "-1"}, QStringList{"--exponent", "nan"},
                                    QStringList{"--lambda", "1e9"}, QStringList{"--lambda", "-0.5"}}) {
        const CliResult r = runCli(args + QStringList{"--out", "never.png"});
        EXPECT_EQ(r.exitCode, 2) << args.join(' ').toStdString() << ": " << r.err;
        EXPECT_NE(r.err.find(args.front().toStdString()), std::string::npos) << r.err;
    }
}

}  // namespace
}  // namespace mipgloss
