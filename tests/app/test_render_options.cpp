// `mipgloss render`'s flags (render_options.h), parsed without OpenGL or files: defaults, each
// flag, the exact words for bad values, and the flags that do not go together.
#include "render_options.h"

#include "mipgloss/ibl/phong.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mipgloss::app {
namespace {

RenderOptions parse(std::vector<std::string> args) { return parseRenderOptions(Args(std::move(args))); }

// The message of the UsageError parsing `args` throws ("" when it throws none).
std::string refusal(std::vector<std::string> args) {
    try {
        parse(std::move(args));
    } catch (const UsageError& e) {
        return e.what();
    }
    return "";
}

TEST(RenderOptions, OnlyOutGivenLeavesEverythingToTheScene) {
    const RenderOptions o = parse({"--out", "a.png"});
    EXPECT_EQ(o.out, std::filesystem::path("a.png"));
    EXPECT_EQ(o.firstOut(), std::filesystem::path("a.png"));
    EXPECT_FALSE(o.scene || o.environment || o.aov || o.library || o.libraryMaterial);
    EXPECT_TRUE(o.meshes.empty());
    EXPECT_FALSE(o.lambda || o.mode || o.exposure || o.backgroundLambda || o.yaw || o.pitch || o.spin);
    EXPECT_FALSE(o.toneMap || o.envSize || o.samples || o.turntable || o.builder || o.compare());
    EXPECT_FALSE(o.layers.any());
    EXPECT_EQ(o.spinKind, TurntableSpin::Object);
    EXPECT_FALSE(o.noBackground || o.quiet || o.noSettle || o.noStack);
    EXPECT_EQ(o.width, 0) << "0: the scene's default size, chosen by runRender";
    EXPECT_EQ(o.height, 0);
}

TEST(RenderOptions, EachFlagSetsItsField) {
    const RenderOptions o = parse({"scene.mipgloss", "--env", "sky.exr", "--mesh", "a.obj", "--mesh", "b.glb",
                                   "--out", "o.exr", "--aov", "aov.exr", "--library", "l.mglib", "--material", "gold",
                                   "--lambda", "2.5", "--mode", "normal", "--exposure", "-1.5", "--background-lambda",
                                   "4", "--yaw", "30", "--pitch", "-20", "--env-size", "64", "--samples", "4",
                                   "--builder", "box", "--tonemap", "aces", "--size", "320x200", "--spin", "45",
                                   "--no-background", "--quiet", "--no-settle", "--metallic", "1",
                                   "--scattering", "compensated"});
    EXPECT_EQ(o.scene, std::filesystem::path("scene.mipgloss"));
    EXPECT_EQ(o.environment, std::filesystem::path("sky.exr"));
    EXPECT_EQ(o.meshes, (std::vector<std::filesystem::path>{"a.obj", "b.glb"}));
    EXPECT_EQ(o.aov, std::filesystem::path("aov.exr"));
    EXPECT_EQ(o.library, std::filesystem::path("l.mglib"));
    EXPECT_EQ(o.libraryMaterial, "gold");
    EXPECT_EQ(o.lambda, 2.5f);
    EXPECT_EQ(o.lambdaFlag, "--lambda");
    EXPECT_EQ(o.mode, LookupMode::Normal);
    EXPECT_EQ(o.exposure, -1.5f);
    EXPECT_EQ(o.backgroundLambda, 4.0f);
    EXPECT_EQ(o.yaw, 30.0f);
    EXPECT_EQ(o.pitch, -20.0f);
    EXPECT_EQ(o.envSize, 64);
    EXPECT_EQ(o.samples, 4);
    EXPECT_EQ(o.builder, Builder::Box);
    EXPECT_EQ(o.toneMap, ToneMap::Aces);
    EXPECT_EQ(o.width, 320);
    EXPECT_EQ(o.height, 200);
    EXPECT_EQ(o.spin, 45.0f);
    EXPECT_TRUE(o.noBackground && o.quiet && o.noSettle && !o.noStack);
    EXPECT_EQ(o.layers.metallic, 1.0f);
    EXPECT_EQ(o.scattering, Scattering::Compensated);
}

TEST(RenderOptions, ExponentIsReadAsTheLambdaOfThatLobe) {
    const RenderOptions o = parse({"--exponent", "100", "--out", "a.png"});
    ASSERT_TRUE(o.lambda);
    EXPECT_NEAR(*o.lambda, exponentToLambda(100.0), 1e-5);
    EXPECT_EQ(o.lambdaFlag, "--exponent");
    EXPECT_EQ(parse({"--exponent", "mirror", "--out", "a.png"}).lambda, 0.0f);
}

TEST(RenderOptions, TurntableParsesOutAsAFramePattern) {
    const RenderOptions o = parse({"--turntable", "12", "--turntable-spin", "environment", "--out", "f_%03d.png"});
    EXPECT_EQ(o.turntable, 12);
    EXPECT_EQ(o.spinKind, TurntableSpin::Environment);
    EXPECT_EQ(o.frames.format(7), "f_007.png");
    EXPECT_EQ(o.firstOut(), std::filesystem::path("f_000.png"));
}

TEST(RenderOptions, CompareFlagsMakeAComparison) {
    EXPECT_TRUE(parse({"--compare-builder", "paper", "--out", "a.png"}).compare());
    EXPECT_EQ(parse({"--compare-builder", "paper", "--out", "a.png"}).compareBuilder, Builder::Paper);
    EXPECT_EQ(parse({"--compare-env", "b.exr", "--out", "a.png"}).compareEnv, std::filesystem::path("b.exr"));
}

TEST(RenderOptions, BadValuesAreRefusedInTheirExactWords) {
    EXPECT_EQ(refusal({}), "render needs --out IMAGE");
    EXPECT_EQ(refusal({"--out"}), "--out needs a value");
    EXPECT_EQ(refusal({"--frobnicate", "--out", "a.png"}), "unknown option '--frobnicate'");
    EXPECT_EQ(refusal({"a.mipgloss", "b.mipgloss", "--out", "a.png"}), "more than one scene given");
    EXPECT_EQ(refusal({"--builder", "sideways", "--out", "a.png"}),
              "--builder is phong, box, paper or reference, got 'sideways'");
    EXPECT_EQ(refusal({"--compare-builder", "sideways", "--out", "a.png"}),
              "--compare-builder is phong, box, paper or reference, got 'sideways'");
    EXPECT_EQ(refusal({"--tonemap", "filmic", "--out", "a.png"}),
              "--tonemap is linear, reinhard, aces, pbr-neutral or agx, got 'filmic'");
    EXPECT_EQ(refusal({"--scattering", "double", "--out", "a.png"}),
              "--scattering is single or compensated, got 'double'");
    EXPECT_EQ(refusal({"--background", "2,0,0", "--out", "a.png"}),
              "--background takes a colour as the screen shows it, each of R,G,B in [0, 1]");
    EXPECT_EQ(refusal({"--camera", "camera0", "--out", "a.png"}),
              "--camera NAME|INDEX looks through a camera of a --mesh glTF file");
    EXPECT_EQ(refusal({"--mesh", "a.gltf", "--camera", "0", "--yaw", "10", "--out", "a.png"}),
              "--camera and --yaw/--pitch do not go together (whose view?)");
    EXPECT_EQ(refusal({"--mode", "refract", "--out", "a.png"}), "--mode is reflect or normal, got 'refract'");
    EXPECT_EQ(refusal({"--turntable-spin", "camera", "--out", "a.png"}),
              "--turntable-spin is object or environment, got 'camera'");
    EXPECT_EQ(refusal({"--turntable", "0", "--out", "f_%d.png"}),
              "--turntable needs a whole number from 1 to 3600, got '0'");
    EXPECT_EQ(refusal({"--turntable", "2.5", "--out", "f_%d.png"}),
              "--turntable needs a whole number from 1 to 3600, got '2.5'");
    EXPECT_EQ(refusal({"--size", "0x120", "--out", "a.png"}), "--size 0x120: the width 0 must be at least 1");
    EXPECT_NE(refusal({"--lambda", "9", "--out", "a.png"}).find("--lambda needs a number from 0"), std::string::npos);
    EXPECT_NE(refusal({"--samples", "17", "--out", "a.png"}).find("--samples needs a number from 0"), std::string::npos);
    EXPECT_NE(refusal({"--turntable", "4", "--out", "frame.png"}).find("--out frame.png with --turntable: "),
              std::string::npos);
}

TEST(RenderOptions, FlagsThatDoNotGoTogetherAreRefused) {
    EXPECT_EQ(refusal({"--library", "l.mglib", "--out", "a.png"}), "--library LIB.mglib and --material NAME go together");
    EXPECT_EQ(refusal({"--material", "gold", "--out", "a.png"}), "--library LIB.mglib and --material NAME go together");
    EXPECT_EQ(refusal({"--compare-builder", "box", "--turntable", "2", "--out", "f_%d.png"}),
              "--compare-builder and --turntable do not go together (one picture or a turn)");
    EXPECT_EQ(refusal({"--compare-env", "b.exr", "--aov", "v.exr", "--out", "a.exr"}),
              "--compare-env and --aov do not go together (the AOV of which half?)");
    EXPECT_EQ(refusal({"--turntable", "2", "--aov", "v.exr", "--out", "f_%d.exr"}),
              "--turntable and --aov do not go together");
    EXPECT_EQ(refusal({"--no-settle", "--no-stack", "--out", "a.png"}),
              "--no-settle and --no-stack do not go together (the stack ahead, or none?)");
}

}  // namespace
}  // namespace mipgloss::app
