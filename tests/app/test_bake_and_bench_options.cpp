// `mipgloss bake` and `mipgloss bench`'s flags (bake_options.h, bench_options.h), parsed without
// reading an environment: defaults, each flag, the exact words for bad values and conflicts.
#include "bake_options.h"
#include "bench_options.h"

#include "usage_error.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mipgloss::app {
namespace {

BakeOptions bakeWith(std::vector<std::string> args) { return parseBakeOptions(Args(std::move(args))); }
BenchOptions benchWith(std::vector<std::string> args) { return parseBenchOptions(Args(std::move(args))); }

TEST(BakeOptions, OnlyOutGivenBakesTheDefaultEnvironmentAsTheRequestDefaults) {
    const BakeOptions o = bakeWith({"--out", "dir"});
    const BakeRequest defaults;
    EXPECT_EQ(o.request.outDir, std::filesystem::path("dir"));
    EXPECT_TRUE(o.request.environment.empty());
    EXPECT_EQ(o.request.builder, defaults.builder);
    EXPECT_EQ(o.request.format, BakeFormat::Exr);
    EXPECT_EQ(o.request.exr.compression, defaults.exr.compression);
    EXPECT_FALSE(o.request.exr.half);
    EXPECT_TRUE(o.request.parallelWrite);
    EXPECT_FALSE(o.request.irradiance || o.quiet || o.help);
}

TEST(BakeOptions, EachFlagSetsItsField) {
    const BakeOptions o = bakeWith({"sky.hdr", "--out", "dir", "--builder", "paper", "--size", "64", "--layout", "hcross",
                                    "--handedness", "left", "--irradiance", "--format", "dds", "--dds-type", "float",
                                    "--serial-write", "--quiet"});
    EXPECT_EQ(o.request.environment, std::filesystem::path("sky.hdr"));
    EXPECT_EQ(o.request.builder, Builder::Paper);
    EXPECT_EQ(o.request.import.faceSize, 64);
    EXPECT_EQ(o.request.import.layout, EnvLayout::HorizontalCross);
    EXPECT_EQ(o.request.import.handedness, Handedness::Left);
    EXPECT_TRUE(o.request.irradiance);
    EXPECT_EQ(o.request.format, BakeFormat::Dds);
    EXPECT_EQ(o.request.ddsType, DdsType::Float);
    EXPECT_FALSE(o.request.parallelWrite);
    EXPECT_TRUE(o.quiet);
    const BakeOptions exr = bakeWith({"--out", "dir", "--exr-compression", "zip:9", "--exr-type", "half"});
    EXPECT_EQ(exr.request.exr.compression, "zip:9");
    EXPECT_TRUE(exr.request.exr.half);
}

TEST(BakeOptions, HelpAnswersWhateverFollows) {
    EXPECT_TRUE(bakeWith({"--help", "--frobnicate"}).help);
}

TEST(BakeOptions, BadValuesAndConflictsAreRefusedInTheirExactWords) {
    EXPECT_EQ(usageError([] { bakeWith({}); }), "bake needs --out DIR");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--builder", "fast"}); }),
              "--builder is phong, box, paper or reference, got 'fast'");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--layout", "sphere"}); }),
              "--layout is auto, faces, hcross, vcross, hstrip, vstrip or latlong, got 'sphere'");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--handedness", "up"}); }), "--handedness is right or left, got 'up'");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--format", "png"}); }), "--format is exr or dds, got 'png'");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--exr-type", "double"}); }), "--exr-type is float or half, got 'double'");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--exr-compression", "lzma"}); }), "unknown OpenEXR compression 'lzma'");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--size", "0"}); }), "--size needs a whole number from 1 to 16384, got '0'");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--dds-type", "half"}); }), "--dds-type needs --format dds");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--format", "dds", "--exr-type", "half"}); }),
              "--exr-type needs --format exr");
    EXPECT_EQ(usageError([] { bakeWith({"a.hdr", "b.hdr", "--out", "d"}); }),
              "more than one environment given ('a.hdr', 'b.hdr')");
    EXPECT_EQ(usageError([] { bakeWith({"--out", "d", "--bogus"}); }), "unknown option '--bogus'");
}

TEST(BenchOptions, DefaultsAreThreeSizesAndTheThreeFastBuilders) {
    const BenchOptions o = benchWith({});
    EXPECT_EQ(o.sizes, (std::vector<int>{128, 256, 512}));
    EXPECT_EQ(o.builders, (std::vector<Builder>{Builder::Phong, Builder::Box, Builder::Paper}));
    EXPECT_EQ(o.repeat, 3);
    EXPECT_EQ(o.directions, 1500);
    EXPECT_TRUE(o.halfLevels && o.centres);
    EXPECT_FALSE(o.shortcuts || o.help);
    EXPECT_TRUE(o.environments.empty() && o.plot.empty());
}

TEST(BenchOptions, EachFlagSetsItsField) {
    const BenchOptions o = benchWith({"--env", "a.exr", "--env", "b.hdr", "--sizes", "16,,64", "--builders", "box,reference",
                                      "--repeat", "1", "--directions", "200", "--no-half", "--no-centre", "--shortcuts",
                                      "--plot", "p.svg"});
    EXPECT_EQ(o.environments, (std::vector<std::filesystem::path>{"a.exr", "b.hdr"}));
    EXPECT_EQ(o.sizes, (std::vector<int>{16, 64}));
    EXPECT_EQ(o.builders, (std::vector<Builder>{Builder::Box, Builder::Reference}));
    EXPECT_EQ(o.repeat, 1);
    EXPECT_EQ(o.directions, 200);
    EXPECT_FALSE(o.halfLevels || o.centres);
    EXPECT_TRUE(o.shortcuts);
    EXPECT_EQ(o.plot, std::filesystem::path("p.svg"));
}

TEST(BenchOptions, BadValuesAreRefusedInTheirExactWords) {
    EXPECT_EQ(usageError([] { benchWith({"--builders", "phong,fast"}); }),
              "--builders is phong, box, paper or reference, got 'fast'");
    EXPECT_EQ(usageError([] { benchWith({"--sizes", ","}); }), "--sizes needs at least one size");
    EXPECT_EQ(usageError([] { benchWith({"--builders", ""}); }), "--builders needs at least one builder");
    EXPECT_EQ(usageError([] { benchWith({"--sizes", "8"}); }),
              "--sizes: face 8 has no read level below the base (needs 16 or more)");
    EXPECT_EQ(usageError([] { benchWith({"--repeat", "x"}); }), "--repeat needs a whole number from 1 to 16384, got 'x'");
    EXPECT_EQ(usageError([] { benchWith({"--frobnicate"}); }), "unknown option '--frobnicate'");
}

}  // namespace
}  // namespace mipgloss::app
