// `mipgloss library add` and `library thumbnails`' flags (library_options.h), parsed without
// opening the library: defaults, each flag, the exact words for bad values and conflicts.
#include "library_options.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"

#include "usage_error.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mipgloss::app {
namespace {

LibraryAddOptions addWith(std::vector<std::string> args) { return parseLibraryAddOptions(Args(std::move(args))); }

TEST(LibraryAddOptions, ANameAloneAddsTheDefaultMaterial) {
    const LibraryAddOptions o = addWith({"lib.mglib", "--name", "plain"});
    EXPECT_EQ(o.file, std::filesystem::path("lib.mglib"));
    EXPECT_EQ(o.name, "plain");
    const Material defaults;
    EXPECT_EQ(o.material.lambda, defaults.lambda);
    EXPECT_EQ(o.material.mode, defaults.mode);
    EXPECT_FALSE(o.material.layered || o.material.useIrradiance || o.material.sharperAtGrazing);
}

TEST(LibraryAddOptions, EachFlagSetsTheMaterial) {
    const LibraryAddOptions o = addWith({"lib.mglib", "--name", "x", "--lambda", "2", "--mode", "normal", "--tint",
                                         "1,0.5,0.25", "--irradiance", "--grazing"});
    EXPECT_EQ(o.material.lambda, 2.0f);
    EXPECT_EQ(o.material.mode, LookupMode::Normal);
    EXPECT_EQ(o.material.tint.g, 0.5f);
    EXPECT_TRUE(o.material.useIrradiance && o.material.sharperAtGrazing);
}

TEST(LibraryAddOptions, ALayerFlagMakesItLayeredWithLambdaAsTheSpecularRoughness) {
    const LibraryAddOptions o = addWith({"lib.mglib", "--name", "x", "--coat", "0.5", "--lambda", "3"});
    EXPECT_TRUE(o.material.layered);
    EXPECT_EQ(o.material.layers.coat, 0.5f);
    EXPECT_NEAR(o.material.layers.roughness, exponentToRoughness(lambdaToExponent(3.0)), 1e-6);
    EXPECT_EQ(o.material.lambda, 0.0f);
}

TEST(LibraryAddOptions, SpecularWeightAndColourAreKhrMaterialsSpecularsFactors) {
    const LibraryAddOptions o =
        addWith({"lib.mglib", "--name", "x", "--specular-weight", "0.25", "--specular-color", "1,0.5,12"});
    EXPECT_TRUE(o.material.layered);
    EXPECT_EQ(o.material.layers.specularWeight, 0.25f);
    EXPECT_EQ(o.material.layers.specularColor, Rgb(1.0f, 0.5f, 12.0f));
    EXPECT_EQ(usageError([] { addWith({"lib.mglib", "--name", "x", "--specular-weight", "1.5"}); }).find("--specular-weight"),
              0u);
    EXPECT_EQ(usageError([] { addWith({"lib.mglib", "--name", "x", "--specular-color", "1,1,20000"}); }),
              "--specular-color needs three numbers from 0 to 10000 (it multiplies F0, which is then at most 1), got "
              "1.000000,1.000000,20000.000000");
}

TEST(LibraryAddOptions, BadValuesAndConflictsAreRefusedInTheirExactWords) {
    EXPECT_EQ(usageError([] { addWith({}); }), "library add needs LIB.mglib");
    EXPECT_EQ(usageError([] { addWith({"--name", "x"}); }), "library add needs LIB.mglib first, got '--name'");
    EXPECT_EQ(usageError([] { addWith({"lib.mglib"}); }), "library add needs --name NAME");
    EXPECT_EQ(usageError([] { addWith({"lib.mglib", "--name", "x", "--lambda", "1", "--exponent", "3"}); }),
              "--exponent: λ is already set by --lambda; give --lambda or --exponent once");
    EXPECT_EQ(usageError([] { addWith({"lib.mglib", "--name", "x", "--roughness", "0.3", "--lambda", "1"}); }),
              "--lambda and --roughness both set the specular lobe; give one");
    EXPECT_EQ(usageError([] { addWith({"lib.mglib", "--name", "x", "--mode", "sideways"}); }),
              "--mode is reflect or normal, got 'sideways'");
    EXPECT_EQ(usageError([] { addWith({"lib.mglib", "--name", "x", "--bogus"}); }),
              "library add: unknown argument '--bogus'");
    EXPECT_NE(usageError([] { addWith({"lib.mglib", "--name", "   "}); }).find("--name '   ': "), std::string::npos);
}

TEST(LibraryThumbnailOptions, DefaultsAndEachFlag) {
    const LibraryThumbnailOptions plain = parseLibraryThumbnailOptions(Args({"lib.mglib", "--out", "thumbs"}));
    EXPECT_EQ(plain.outDir, std::filesystem::path("thumbs"));
    EXPECT_EQ(plain.size, 256);
    EXPECT_EQ(plain.environment.source, EnvironmentSettings{}.source);
    const LibraryThumbnailOptions o = parseLibraryThumbnailOptions(
        Args({"lib.mglib", "--out", "t", "--env", "sky.exr", "--size", "64", "--env-size", "32"}));
    EXPECT_EQ(o.environment.source, "sky.exr");
    EXPECT_EQ(o.size, 64);
    EXPECT_EQ(o.environment.faceSize, 32);
    EXPECT_EQ(usageError([] { parseLibraryThumbnailOptions(Args({"lib.mglib"})); }),
              "library thumbnails needs --out DIR");
}

}  // namespace
}  // namespace mipgloss::app
