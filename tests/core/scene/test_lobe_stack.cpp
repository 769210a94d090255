// The lobe stack (lobes.h, docs/lobe-stack.md): its grid, the band-1 blend of neighbours, the
// footprint's widening, which entries a scene asks for, the atlas, and how close a blend of exact
// neighbours comes to the exact lobe between them on held-out maps.
#include "sphere_scene.h"
#include "test_support.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace mipgloss {
namespace {

Material glossy(float lambda, bool grazing = false) {
    Material m;
    m.lambda = lambda;
    m.sharperAtGrazing = grazing;
    return m;
}

// Spheres wearing `materials`, the background hidden (it would add its own lobe).
Scene sceneOf(const std::vector<Material>& materials) {
    Scene scene = test::spheresWearing(materials);
    scene.display.showBackground = false;
    return scene;
}

TEST(LobeStack, NeighboursAreTwoToTheQuarterApartInExponent) {
    // n(λ) + 1 = 3·128²·4^−λ, λ = j/8: (n_j + 1)/(n_{j+1} + 1) = 4^(1/8) = 2^¼ exactly, wherever n
    // is not clamped at 0 (from λ = 7.79, entry 63).
    for (int j = 1; j + 1 < kStackLast; ++j)
        EXPECT_NEAR((stackExponent(j) + 1.0) / (stackExponent(j + 1) + 1.0), std::pow(2.0, 0.25), 1e-12) << j;
    EXPECT_EQ(stackExponent(kStackLast), 0.0) << "the last entry is the uniform hemisphere";
    EXPECT_GT(stackExponent(kStackLast - 1), 0.0);
}

TEST(LobeStack, TopIsTheSharpestLobeItsCubeHoldsAndReachesTheIssuesRange) {
    for (int n : {16, 64, 256, 512}) {
        const int top = stackTop(n);
        EXPECT_TRUE(stackEntryHoldsLobe(stackExponent(top), n)) << n;
        if (top > 1) {
            EXPECT_FALSE(stackEntryHoldsLobe(stackExponent(top - 1), n)) << n;
        }
    }
    // Issue 24 asks for n up to 4096 at base 256: the stack's top there is n = 7305 (face 484).
    EXPECT_GE(stackExponent(stackTop(256)), 4096.0);
    EXPECT_TRUE(stackBlend(4096.0, 256).has_value());
}

TEST(LobeStack, BlendKeepsTheLobesMeanCosineBetweenItsNeighbours) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> logN(0.0, std::log(7000.0));
    for (int i = 0; i < 2000; ++i) {
        const double n = std::exp(logN(rng)) - 1.0;
        const auto b = stackBlend(n, 256);
        ASSERT_TRUE(b.has_value()) << n;
        EXPECT_GE(stackExponent(b->sharper), n);
        EXPECT_LE(stackExponent(b->wider), n);
        EXPECT_EQ(b->wider, b->sharper + 1);
        // Λ = (n+1)/(n+2): (1 − w)·Λ_sharper + w·Λ_wider = Λ(n).
        auto meanCos = [](double e) { return (e + 1.0) / (e + 2.0); };
        const double blended = (1.0 - b->widerWeight) * meanCos(stackExponent(b->sharper)) +
                               b->widerWeight * meanCos(stackExponent(b->wider));
        EXPECT_NEAR(blended, meanCos(n), 1e-12) << n;
    }
    // On an entry: that entry alone.
    const auto on = stackBlend(stackExponent(30), 256);
    ASSERT_TRUE(on);
    EXPECT_EQ(on->sharper, 30);
    EXPECT_EQ(on->widerWeight, 0.0);
    // Not the stack's: sharper than its top, the mirror, NaN, negative.
    EXPECT_FALSE(stackBlend(stackExponent(stackTop(256)) * 1.01, 256));
    EXPECT_FALSE(stackBlend(kMirrorExponent, 256));
    EXPECT_FALSE(stackBlend(std::nan(""), 256));
    EXPECT_FALSE(stackBlend(-1.0, 256));
    // n = 0 and between 0 and the last positive entry.
    EXPECT_EQ(stackBlend(0.0, 256)->sharper, kStackLast);
    EXPECT_EQ(stackBlend(0.01, 256)->wider, kStackLast);
}

TEST(LobeStack, FootprintAddsItsSecondMomentToTheLobes) {
    EXPECT_DOUBLE_EQ(footprintExponent(100.0, 0.0, 0.0), 100.0);
    // 1/(n'+2) = 1/(n+2) + (dx² + dy²)/24.
    const double n = footprintExponent(1000.0, 0.05, 0.02);
    EXPECT_NEAR(1.0 / (n + 2.0), 1.0 / 1002.0 + (0.05 * 0.05 + 0.02 * 0.02) / 24.0, 1e-15);
    // A mirror seen through a footprint is the footprint's lobe; never below 0.
    EXPECT_NEAR(footprintExponent(kMirrorExponent, 0.1, 0.0), 24.0 / 0.01 - 2.0, 1e-9);
    EXPECT_EQ(footprintExponent(0.0, 10.0, 10.0), 0.0);
    // Second moments add under convolution: a Phong lobe (n = 400) averaged over a square of side
    // w = 0.08 rad around the pole (numerically: 0.5 mrad steps, the square sampled at 5×5 points,
    // whose second moment is (1 − 1/25)·w²/12 per axis) has mean 1 − cos θ equal to the formula's
    // 1/(n'+2) for that moment within 1 % (the rest is of higher order in θ: measured 0.5 %).
    const double lobeN = 400.0, w = 0.08;
    double sumW = 0.0, sumOneMinusCos = 0.0;
    const double step = 0.0005;
    for (double x = -0.4; x <= 0.4; x += step)
        for (double y = -0.4; y <= 0.4; y += step) {
            // Lobe about the pole, convolved with the box: the box-averaged lobe at (x, y) is the
            // lobe at (x − a, y − b) averaged over a, b in [−w/2, w/2]: sample 5×5 offsets.
            double value = 0.0;
            for (int a = 0; a < 5; ++a)
                for (int b = 0; b < 5; ++b) {
                    const double ox = x - w * ((a + 0.5) / 5.0 - 0.5), oy = y - w * ((b + 0.5) / 5.0 - 0.5);
                    const double cosT = 1.0 / std::sqrt(1.0 + ox * ox + oy * oy);
                    value += std::pow(cosT, lobeN);
                }
            const double cosT = 1.0 / std::sqrt(1.0 + x * x + y * y);
            const double jacobian = cosT * cosT * cosT;  // solid angle of a plane element at (x, y)
            sumW += value * jacobian;
            sumOneMinusCos += value * jacobian * (1.0 - cosT);
        }
    const double sampledW = w * std::sqrt(1.0 - 1.0 / 25.0);
    const double measured = sumOneMinusCos / sumW, formula = 1.0 / (footprintExponent(lobeN, sampledW, sampledW) + 2.0);
    EXPECT_NEAR(measured / formula, 1.0, 0.01) << measured << " vs " << formula;
}

// Entries first … last.
std::vector<int> range(int first, int last) {
    std::vector<int> out;
    for (int j = first; j <= last; ++j) out.push_back(j);
    return out;
}

TEST(LobeStack, InUseAreEachLobesNeighboursAndTheWiderOnesItsFootprintReaches) {
    static_assert(kFootprintReach == 4, "the expectations below count four wider entries");
    Scene scene = sceneOf({glossy(0.0f), glossy(3.0f), glossy(3.3f), glossy(9.0f)});
    // λ 3 is entry 24 itself (its wider neighbour 25 and four more come too); λ 3.3 lies between
    // 26 and 27 (and 28 … 31); the mirror and an invalid λ ask for nothing.
    EXPECT_EQ(lobesInUse(scene, 256), range(24, 31));
    scene.objects[1].visible = false;
    EXPECT_EQ(lobesInUse(scene, 256), range(26, 31));
    scene.display.showBackground = true;
    scene.display.backgroundLambda = 2.0f;
    std::vector<int> withBackground = range(16, 21);
    for (int j : range(26, 31)) withBackground.push_back(j);
    EXPECT_EQ(lobesInUse(scene, 256), withBackground);
    scene.environment.builder = Builder::Box;
    EXPECT_TRUE(lobesInUse(scene, 256).empty()) << "other builders are shown as they are";
    // The grazing option: from the stack's top to λ 2's entries and the four past them; at base
    // 512 not the entries of faces over 512 (stackTop 3 has 1024).
    EXPECT_EQ(lobesInUse(sceneOf({glossy(2.0f, true)}), 256), range(stackTop(256), 21));
    const std::vector<int> grazing512 = lobesInUse(sceneOf({glossy(2.0f, true)}), 512);
    ASSERT_FALSE(grazing512.empty());
    EXPECT_GT(grazing512.front(), stackTop(512));
    EXPECT_EQ(grazing512.front(), firstEntryMadeAhead(512));
    EXPECT_LE(stackEntryFaceSize(stackExponent(grazing512.front()), 512), kGrazingLargestFace);
    EXPECT_GT(stackEntryFaceSize(stackExponent(grazing512.front() - 1), 512), kGrazingLargestFace);
    // The end of the stack: n = 0 asks for the last entry only.
    EXPECT_EQ(lobesInUse(sceneOf({glossy(7.9f)}), 256), range(kStackLast, kStackLast));
    // Near: the rest of the stack (faces up to 512), nearest first, none repeated or in use.
    const std::vector<int> inUse = lobesInUse(sceneOf({glossy(4.0f)}), 256);
    ASSERT_EQ(inUse, range(32, 37));
    const std::vector<int> near = lobesNear(inUse, 256);
    ASSERT_EQ(near.size(), static_cast<std::size_t>(kStackLast - stackTop(256) + 1 - 6));
    EXPECT_TRUE(near[0] == 31 || near[0] == 38);
    for (std::size_t i = 1; i < near.size(); ++i) {
        auto distance = [](int j) { return j < 32 ? 32 - j : j - 37; };
        EXPECT_LE(distance(near[i - 1]), distance(near[i]));
        EXPECT_TRUE(near[i] < 32 || near[i] > 37) << near[i];
    }
    const std::vector<int> within = lobesNear(inUse, 256, 8);
    for (int j : within) EXPECT_TRUE(j >= 24 && j <= 45) << j;
    // At base 512 no entry of a face over 512 is made ahead.
    for (int j : lobesNear(lobesInUse(sceneOf({glossy(4.0f)}), 512), 512))
        EXPECT_LE(stackEntryFaceSize(stackExponent(j), 512), kGrazingLargestFace);
}

TEST(LobeStack, EntryIsTheExactConvolutionAtItsCentres) {
    EnvironmentSettings settings;
    settings.faceSize = 32;
    const PreparedEnvironment env = prepareEnvironment(settings, ChainNeeds{0, false});
    ASSERT_TRUE(env.filter);
    // Below n = 1 the faces are at least 32 (the kernel is nearly a step at the horizon).
    EXPECT_EQ(stackEntryFaceSize(stackExponent(62), 32), 32);
    EXPECT_EQ(stackEntryFaceSize(stackExponent(56), 32), 16);
    for (int index : {40, 56, 62, stackTop(32)}) {
        SCOPED_TRACE("entry " + std::to_string(index));
        const LobeStackEntry lobe = makeStackEntry(env, index);
        EXPECT_EQ(lobe.index, index);
        EXPECT_EQ(lobe.exponent, stackExponent(index));
        ASSERT_TRUE(lobe.cube);
        EXPECT_EQ(lobe.cube->size(), stackEntryFaceSize(lobe.exponent, 32));
        EXPECT_EQ(lobe.filter, env.filter);
        // What differs from the exact sum is the lobe cut and float weights (the stack entries'
        // bound before the stack: 0.5 % relative RMS, 0.1 % in the mean).
        const LevelError e = compareCubes(*lobe.cube, referenceConvolution(*env.base, lobe.exponent, lobe.cube->size()));
        EXPECT_LE(e.relRms, 0.005);
        EXPECT_LE(std::fabs(e.meanRelDiff), 0.001);
    }
    PreparedEnvironment none;
    EXPECT_THROW(makeStackEntry(none, 20), std::logic_error);
    EXPECT_THROW(makeStackEntry(env, 0), std::out_of_range) << "entry 0 would be the mirror";
    EXPECT_THROW(makeStackEntry(env, kStackLast + 1), std::out_of_range);
}

TEST(LobeStack, AtlasHoldsEveryFaceOnceInsideItsBounds) {
    std::vector<std::pair<int, int>> sizes;
    for (int j = 11; j <= kStackLast; ++j) sizes.emplace_back(j, stackEntryFaceSize(stackExponent(j), 256));
    const LobeStackAtlas atlas = lobeStackAtlas(sizes, 2048);
    ASSERT_EQ(atlas.placed.size(), sizes.size());
    struct Rect { int x0, y0, x1, y1; };
    std::vector<Rect> rects;
    double used = 0.0;
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        const AtlasPlacement& p = atlas.placed[i];
        EXPECT_EQ(p.index, sizes[i].first);
        EXPECT_EQ(p.size, sizes[i].second);
        const Rect r{p.x, p.y, p.x + 3 * (p.size + 2), p.y + 2 * (p.size + 2)};
        EXPECT_GE(r.x0, 0);
        EXPECT_GE(r.y0, 0);
        EXPECT_LE(r.x1, atlas.width);
        EXPECT_LE(r.y1, atlas.height);
        for (const Rect& o : rects)
            EXPECT_TRUE(r.x1 <= o.x0 || o.x1 <= r.x0 || r.y1 <= o.y0 || o.y1 <= r.y0) << "entry " << p.index << " overlaps";
        rects.push_back(r);
        used += static_cast<double>(r.x1 - r.x0) * (r.y1 - r.y0);
    }
    EXPECT_LE(atlas.width, 2048);
    // Shelf packing, largest first: printed, not a bound.
    std::printf("atlas %d x %d, %.0f %% used, %.1f MB as RGB9_E5\n", atlas.width, atlas.height,
                100.0 * used / (static_cast<double>(atlas.width) * atlas.height), atlas.megabytes(4));
}

// The blend of two exact neighbours against the exact lobe between them, on held-out maps (one
// with a sun through a window, one without), at λ a half, a quarter and three quarters of the way
// between entries, n from about 4 to 4000: this isolates the blend from the cubes' bilinear reads
// (which the render tests measure). Directions: 400 uniform.
TEST(LobeStack, BlendOfExactNeighboursIsWithinOnePercentOfTheLobeBetween) {
    const auto dirs = uniformDirections(400, 3);
    double worst = 0.0;
    for (const char* map : {"env/interior.exr", "env/courtyard.exr"}) {
        ImportOptions options;
        options.faceSize = 48;
        const CubeMap base = loadEnvironment(test::asset(map), options).cube;
        for (int j : {14, 22, 30, 38, 46, 54}) {
            for (double frac : {0.25, 0.5, 0.75}) {
                const double n = lambdaToExponent((j + frac) / kStackStepsPerLevel);
                const auto b = stackBlend(n, 1024);
                ASSERT_TRUE(b);
                const auto sharp = referenceLobeAt(base, stackExponent(b->sharper), dirs, 1e-8);
                const auto wide = referenceLobeAt(base, stackExponent(b->wider), dirs, 1e-8);
                const auto truth = referenceLobeAt(base, n, dirs, 1e-8);
                std::vector<Rgb> blend(dirs.size());
                for (std::size_t i = 0; i < dirs.size(); ++i)
                    blend[i] = sharp[i] + static_cast<float>(b->widerWeight) * (wide[i] - sharp[i]);
                const double err = relativeRms(blend, truth);
                worst = std::max(worst, err);
                // Measured worst 0.52 % (interior, n = 248, half way); issue 24 aims at 1 %.
                EXPECT_LE(err, 0.01) << map << " n " << n;
            }
        }
    }
    std::printf("worst blend error %.3f %%\n", 100.0 * worst);
}

}  // namespace
}  // namespace mipgloss

namespace mipgloss {
namespace {

Material layered(float roughness, bool mapped = false) {
    Material m;
    m.layered = true;
    m.layers.roughness = roughness;
    if (mapped) m.layers.maps.roughness.file = "roughness.png";
    return m;
}

TEST(RemainderStack, LayersReadItOnlyWhereEveryLightIsNarrowerThanTheirLobe) {
    const int base = 256;
    const std::vector<PointLight> sun{{glm::vec3(0, 1, 0), Rgb(100.0f), 0.01f}};
    const std::vector<PointLight> softBox{{glm::vec3(0, 1, 0), Rgb(100.0f), 0.4f}};
    // r 0.6: α 0.36, its lookups held (head-on the sharpest is inside the stack).
    ASSERT_TRUE(ggxLookupsHeld(0.6, kGgxLookups, base));
    EXPECT_TRUE(ggxReadsRemainder(0.6, kGgxLookups, base, false, 0.01));
    EXPECT_TRUE(ggxReadsRemainder(0.6, kGgxLookups, base, false, 0.36)) << "ρ = α";
    EXPECT_FALSE(ggxReadsRemainder(0.6, kGgxLookups, base, false, 0.37)) << "a light wider than the lobe";
    // A near-mirror layer is not held (its sharpest lookups read the chain) and reads the lights
    // in the environment (α = 0.0025 < 4/256); a roughness map may be any roughness.
    EXPECT_FALSE(ggxLookupsHeld(0.05, kGgxLookups, base));
    EXPECT_FALSE(ggxReadsRemainder(0.05, kGgxLookups, base, false, 0.0));
    EXPECT_FALSE(ggxLookupsHeld(0.6, kGgxLookups, base, true));
    EXPECT_FALSE(ggxReadsRemainder(0.6, kGgxLookups, base, true, 0.0));

    Scene scene = sceneOf({layered(0.6f), layered(0.05f), layered(0.8f, true)});
    EXPECT_EQ(remainderEntries(scene, base, sun), remainderEntriesOf(0.6, kGgxLookups, base)) << "the rough layer's entries alone";
    // Those are the layer's entries from the one holding its sharpest lookup head-on: the sharper
    // ones its grazing lookups would read are made for the whole environment only.
    const std::vector<int> all = ggxEntries(0.6, kGgxLookups, base), rest = remainderEntriesOf(0.6, kGgxLookups, base);
    ASSERT_FALSE(rest.empty());
    EXPECT_EQ(rest.front(), ggxHeadOnEntry(0.6, kGgxLookups, base));
    EXPECT_EQ(rest.back(), all.back());
    EXPECT_GT(rest.front(), all.front()) << "grazing lookups are sharper than head-on ones";
    EXPECT_TRUE(remainderEntriesOf(0.05, kGgxLookups, base).empty());
    EXPECT_TRUE(remainderEntries(scene, base, softBox).empty());
    EXPECT_TRUE(remainderEntries(scene, base, {}).empty()) << "no lights: the whole stack is the remainder";
    EXPECT_NEAR(remainderReach(scene, base), 0.36, 1e-6);
    EXPECT_NEAR(chainNeeds(scene, base).remainderReach, 0.36, 1e-6);
    scene.display.brightLights = false;
    EXPECT_TRUE(remainderEntries(scene, base, sun).empty()) << "lights not shaded apart";
    EXPECT_EQ(remainderReach(scene, base), 0.0);
}

TEST(GgxLayerLookups, APolishedLayerWhoseLightsAreApartReadsTheMostLookupsTheStackHolds) {
    // r 0.125 and 0.15 at face 128 (α 0.016, 0.023 ≥ 2/128): the stack does not hold eight of
    // their lookups (each an eighth of the lobe, sharper than its first entry), so they read the
    // most of 4, 2, 1 it holds: each of those is read from an entry, not the chain's base.
    for (const auto& [roughness, base] : {std::pair{0.125, 128}, {0.15, 128}, {0.1, 256}}) {
        SCOPED_TRACE(testing::Message() << "r " << roughness << " at face " << base);
        ASSERT_FALSE(ggxLookupsHeld(roughness, kGgxLookups, base));
        ASSERT_GE(roughness * roughness, lightsApartMinAlpha(base));
        const int fewer = ggxLayerLookups(roughness, kGgxLookups, base, false, true);
        EXPECT_LT(fewer, kGgxLookups);
        EXPECT_EQ(kGgxLookups % fewer, 0) << "K halved";
        EXPECT_TRUE(ggxLookupsHeld(roughness, fewer, base));
        EXPECT_FALSE(ggxLookupsHeld(roughness, 2 * fewer, base)) << "the most it holds";
        // What the scene makes follows: the entries of those lookups, none sharper.
        Material polished = layered(static_cast<float>(roughness));
        polished.useIrradiance = true;  // no diffuse lobe among the entries
        const Scene scene = sceneOf({polished});
        EXPECT_EQ(lobesInUse(scene, base), ggxEntries(roughness, fewer, base));
        // Without the lights apart there is nothing to subtract: K as the display says.
        EXPECT_EQ(ggxLayerLookups(roughness, kGgxLookups, base, false, false), kGgxLookups);
        EXPECT_EQ(ggxLayerLookups(roughness, kGgxLookups, base, true, true), kGgxLookups) << "a roughness map: any lobe";
    }
    // Held layers read K; near-mirrors (α < 2/N: the lights in the environment) too.
    EXPECT_EQ(ggxLayerLookups(0.6, kGgxLookups, 128, false, true), kGgxLookups);
    EXPECT_EQ(ggxLayerLookups(0.2, 16, 256, false, true), 16);
    ASSERT_LT(0.05 * 0.05, lightsApartMinAlpha(256));
    EXPECT_EQ(ggxLayerLookups(0.05, kGgxLookups, 256, false, true), kGgxLookups);
    EXPECT_EQ(ggxLayerLookups(0.15, 1, 128, false, true), 1);
}

TEST(RemainderStack, EntryIsTheWholeEntryLessTheLightsExcessThroughTheSameLobe) {
    const auto path = test::asset("env/sunrise.exr");
    MIPGLOSS_REQUIRE_ASSET(path);
    EnvironmentSettings settings;
    settings.source = path.string();
    settings.faceSize = 32;
    const PreparedEnvironment none = prepareEnvironment(settings, ChainNeeds{0, false});
    ASSERT_FALSE(none.lights.empty());
    EXPECT_FALSE(none.remainderFilter) << "no layer asked for it";
    EXPECT_THROW(makeStackEntry(none, 40, true), std::logic_error);
    const PreparedEnvironment env = prepareEnvironment(settings, ChainNeeds{0, false, 1.0});
    ASSERT_TRUE(env.remainderFilter);
    EXPECT_TRUE(env.satisfies(settings, ChainNeeds{0, false, 1.0}));
    EXPECT_FALSE(none.satisfies(settings, ChainNeeds{0, false, 1.0})) << "the remainder is built when asked";
    EXPECT_FALSE(none.wantsRemainder(widestLight(none.lights) * 0.5)) << "lights wider than every layer: not built";
    // The filter is linear: whole − remainder = the filter of what the lights took out, texel for
    // texel (float sums: within 1e-4 of the whole entry's largest value).
    CubeMap excess = *env.base;
    const CubeMap remainder = withoutBrightLights(*env.base);
    for (Face f : kAllFaces)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) excess.at(f, x, y) -= remainder.at(f, x, y);
    excess.makeSeamless();
    const PhongFilter excessFilter(excess);
    for (int index : {24, 40, 56}) {
        SCOPED_TRACE("entry " + std::to_string(index));
        const LobeStackEntry whole = makeStackEntry(env, index), rest = makeStackEntry(env, index, true);
        EXPECT_TRUE(rest.remainder);
        EXPECT_EQ(stackKey(rest), index + kRemainderKeyOffset);
        EXPECT_EQ(rest.filter, env.filter) << "known by its environment's filter, like every entry";
        const CubeMap lights = excessFilter.filter(whole.exponent, whole.cube->size());
        float largest = 0.0f;
        for (Face f : kAllFaces)
            for (int y = 0; y < whole.cube->size(); ++y)
                for (int x = 0; x < whole.cube->size(); ++x) largest = std::max(largest, whole.cube->at(f, x, y).g);
        for (Face f : kAllFaces)
            for (int y = 0; y < whole.cube->size(); ++y)
                for (int x = 0; x < whole.cube->size(); ++x)
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(whole.cube->at(f, x, y)[c] - rest.cube->at(f, x, y)[c], lights.at(f, x, y)[c], 1e-4f * largest);
    }
}

}  // namespace
}  // namespace mipgloss
