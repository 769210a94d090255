// The schedule's promise on the committed real HDRIs (tests/assets/env, CC0): every read level
// k >= 1 of the default chain, read between texel centres as the GPU reads it (sampleChain at
// level k), within 2 % of the exact lobe levelExponent(N, k) there (readError). sunrise and
// sunset have a sun. The box chain, at the same levels, is the old schedule's problem: it is not
// the scheduled lobe. Directions per level as in tests/core/ibl/test_between_centres.cpp (1500
// for n >= 64, 600 for 8 < n < 64, 300 for n <= 8: wide lobes make the truth dear, and their
// smooth result is sampled finely enough by fewer).
//
// Measured read error, all maps and levels: 0.19–1.13 % (worst: studio and sunrise at n = 1);
// sunrise at 256 0.37–1.13 %. Box at the same levels 25–427 %, at least 73× the default's.
// Required: <= 2 %, and box > 3× the default.
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/import.h"
#include "core/between_centres_support.h"
#include "test_support.h"

#include <cmath>
#include <string>
#include <vector>

using namespace mipgloss;

namespace {

void expectReadsBetweenCentres(const std::string& map, int size) {
    const auto path = test::asset("env/" + map + ".exr");
    MIPGLOSS_REQUIRE_ASSET(path);
    ImportOptions o;
    o.faceSize = size;
    const CubeMap base = loadEnvironment(path, o).cube;
    test::expectReadsBetweenCentres(base, map);
}

}  // namespace

TEST(RealHdriBetweenCentres, EveryMapAtBase128ReadsWithinTwoPercentOfItsLobes) {
    for (const char* map : {"city", "courtyard", "forest", "interior", "night", "studio", "sunrise", "sunset"})
        expectReadsBetweenCentres(map, 128);
}

TEST(RealHdriBetweenCentres, SunAtBase256ReadsWithinTwoPercentOfItsLobes) { expectReadsBetweenCentres("sunrise", 256); }
