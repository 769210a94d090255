// `mipgloss render`, run as a user would (a child process under the test's X display).
#include "render_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <QImage>
#include <QProcess>
#include <QTemporaryDir>

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
