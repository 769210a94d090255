// Issue 24, item 6: the import, every chain level, the irradiance map and every stack entry keep a
// one-pixel sun of 1e9 (its energy within 1 %), and a map scaled by 1e-30 is the map at its own
// scale times 1e-30. Through the whole import: a float EXR written from a held-out HDRI.
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"
#include "radiance_range.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace mipgloss {
namespace {

constexpr int kFace = 128;

PreparedEnvironment prepared(const std::filesystem::path& file) {
    EnvironmentSettings settings;
    settings.source = file.string();
    settings.faceSize = kFace;
    return prepareEnvironment(settings, ChainNeeds{16, true});
}

// Each cube of the environment with its name: base, every chain level the renderer reads (through
// lastReadLevel; the deeper ones, faces of 4, 2 and 1 texels, hold a lobe at six to 96 points, whose
// mean is not the sphere's: a point sun moves it by 1.1 % at the 1×1 level whatever its radiance),
// the irradiance map and the lobe stack's entries nearest n = 8 … 4096 (n = 1024 is the issue's).
std::vector<std::pair<std::string, CubeMap>> cubesOf(const PreparedEnvironment& env) {
    std::vector<std::pair<std::string, CubeMap>> cubes{{"base", *env.base}};
    for (int k = 0; k <= lastReadLevel(env.base->size()); ++k)
        cubes.emplace_back("level " + std::to_string(k), env.chain->levels[static_cast<std::size_t>(k)]);
    cubes.emplace_back("irradiance", *env.irradiance);
    for (double n : {8.0, 64.0, 1024.0, 4096.0}) {
        // The lobe stack's entry nearest to n.
        const LobeStackEntry lobe = makeStackEntry(env, static_cast<int>(std::lround(exponentToLambda(n) * kStackStepsPerLevel)));
        cubes.emplace_back("stack entry n " + std::to_string(static_cast<int>(lobe.exponent)), *lobe.cube);
    }
    return cubes;
}

TEST(RadianceRange, SunOf1e9KeepsItsEnergyInEveryLevelAndStackEntry) {
    MIPGLOSS_REQUIRE_ASSET(test::rangeMapAsset());
    test::TempDir dir;
    constexpr float kSun = 1e9f;
    test::writeRangeMap(dir / "map.exr", 1.0, 0.0f);
    const double omega = test::writeRangeMap(dir / "sun.exr", 1.0, kSun);
    const PreparedEnvironment map = prepared(dir / "map.exr"), sun = prepared(dir / "sun.exr");
    // Each cube's mean radiance over the sphere: the map's, plus the sun's energy over 4π
    // (a normalized lobe, the irradiance map's E/π included, keeps the mean: Λ₀ = 1).
    const double sunMean = kSun * omega / (4.0 * std::numbers::pi);
    const auto mapCubes = cubesOf(map), sunCubes = cubesOf(sun);
    ASSERT_EQ(mapCubes.size(), sunCubes.size());
    std::printf("[ range ] the sun's mean %.4g, the map's %.4g\n", sunMean, mapCubes[0].second.weightedMean().g);
    for (std::size_t i = 0; i < sunCubes.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double want = mapCubes[i].second.weightedMean()[c] + sunMean;
            const double got = sunCubes[i].second.weightedMean()[c];
            if (c == 1) std::printf("[ range ] %-14s %+.4f %%\n", sunCubes[i].first.c_str(), 100.0 * (got / want - 1.0));
            EXPECT_NEAR(got / want, 1.0, 0.01) << sunCubes[i].first << " channel " << c;
        }
}

TEST(RadianceRange, MapScaledBy1em30IsTheMapTimes1em30InEveryCube) {
    MIPGLOSS_REQUIRE_ASSET(test::rangeMapAsset());
    test::TempDir dir;
    test::writeRangeMap(dir / "map.exr", 1.0, 0.0f);
    test::writeRangeMap(dir / "tiny.exr", 1e-30, 0.0f);
    const auto a = cubesOf(prepared(dir / "map.exr")), b = cubesOf(prepared(dir / "tiny.exr"));
    ASSERT_EQ(a.size(), b.size());
    // Texel by texel: float keeps 1e-30 × radiance to its 24 bits (the smallest normal float is
    // 1.2e-38), so every filter gives the same numbers scaled, up to rounding: within 1e-4 of the
    // texel, or of 1e-3 of the cube's mean for texels far below it.
    for (std::size_t i = 0; i < a.size(); ++i) {
        const CubeMap& x = a[i].second;
        const CubeMap& y = b[i].second;
        const double floor = 1e-3 * x.weightedMean().g;
        double worst = 0.0;
        for (Face f : kAllFaces)
            for (int t = 0; t < x.size(); ++t)
                for (int s = 0; s < x.size(); ++s)
                    for (int c = 0; c < 3; ++c) {
                        const double want = x.at(f, s, t)[c];
                        worst = std::max(worst, std::abs(static_cast<double>(y.at(f, s, t)[c]) * 1e30 - want) / (want + floor));
                    }
        std::printf("[ range ] %-14s worst relative difference %.3g\n", a[i].first.c_str(), worst);
        EXPECT_LE(worst, 1e-4) << a[i].first;
    }
}

}  // namespace
}  // namespace mipgloss
