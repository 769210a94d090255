// The glTF fuzz target's structure-aware mutations (gltf_mutator.h) do what they say, and the
// glTF entry keeps its contract (refused naming the file, or a valid asset) on a thousand and more
// of them made from the committed seeds: a short in-process run of what fuzz_gltf_import runs
// for minutes, in every build.
#include "entries.h"
#include "gltf_mutator.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

using namespace mipgloss::fuzz;
namespace fs = std::filesystem;

namespace {

const std::string kGltf =
    R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":3,"name":"n"}],"images":[{"uri":"a.png"}]})";

std::vector<std::uint8_t> readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(GltfMutator, IndexWrapMovesAnIndexPastTheIntegersItMayHold) {
    std::set<std::string> seen;
    for (unsigned seed = 1; seed < 200; ++seed) {
        std::minstd_rand rng(seed * 2654435761u);  // small seeds spread (minstd's first draws follow the seed)
        const std::string out = mutateGltfJson(kGltf, GltfMutation::IndexWrap, rng, 4096);
        ASSERT_NE(out, kGltf);
        // The one index changed is a node's mesh (3) or a scene's node (0), never "2.0".
        const bool mesh = out.find("\"mesh\":3,") == std::string::npos, node = out.find("\"nodes\":[0]") == std::string::npos;
        ASSERT_TRUE(mesh != node) << out;
        seen.insert(out);
    }
    for (const char* wrapped : {R"("mesh":4294967299)", R"("mesh":2147483651)", R"("mesh":-4)", R"("mesh":8589934595)",
                                R"("nodes":[4294967296])", R"("nodes":[-1])"}) {
        bool found = false;
        for (const std::string& s : seen) found = found || s.find(wrapped) != std::string::npos;
        EXPECT_TRUE(found) << wrapped;
    }
}

TEST(GltfMutator, DeepNestingGoesPastTheCheckersDepthWithinMaxSize) {
    std::size_t deepest = 0;
    for (unsigned seed = 1; seed < 100; ++seed) {
        std::minstd_rand rng(seed * 2654435761u);  // small seeds spread (minstd's first draws follow the seed)
        const std::string out = mutateGltfJson(kGltf, GltfMutation::DeepNesting, rng, 16384);
        EXPECT_LE(out.size(), 16384u);
        std::size_t depth = 0, most = 0;
        bool inString = false;
        for (char c : out) {
            if (c == '"') inString = !inString;
            if (inString) continue;
            if (c == '[' || c == '{') most = std::max(most, ++depth);
            if (c == ']' || c == '}') --depth;
        }
        deepest = std::max(deepest, most);
    }
    EXPECT_GT(deepest, 1000u) << "nesting far past the 64 levels the JSON check allows";
}

TEST(GltfMutator, AGlbKeepsItsContainerLengthsAndBinaryChunk) {
    const std::vector<std::uint8_t> glb = readBytes(fs::path(MIPGLOSS_FUZZ_DIR) / "corpus/gltf_import/quad-textured.glb");
    ASSERT_GT(glb.size(), 28u);
    std::uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, glb.data() + 12, 4);
    const std::vector<std::uint8_t> bin(glb.begin() + 20 + jsonLength, glb.end());
    int mutated = 0;
    for (unsigned seed = 1; seed < 100; ++seed) {
        std::minstd_rand rng(seed * 2654435761u);  // small seeds spread (minstd's first draws follow the seed)
        const std::vector<std::uint8_t> out = mutateGltf(glb, rng, 65536);
        if (out.empty()) continue;
        ++mutated;
        std::uint32_t total = 0, chunk = 0;
        std::memcpy(&total, out.data() + 8, 4);
        std::memcpy(&chunk, out.data() + 12, 4);
        EXPECT_EQ(total, out.size());
        EXPECT_EQ(chunk % 4, 0u);
        ASSERT_EQ(20 + chunk + bin.size(), out.size());
        EXPECT_TRUE(std::equal(bin.begin(), bin.end(), out.end() - static_cast<std::ptrdiff_t>(bin.size())));
    }
    EXPECT_GT(mutated, 90);
}

// 1 600 mutations (400 per seed, every kind) through the glTF entry: each refused with an
// AssetError naming fuzz.glb or loaded valid (entries.h's contract).
TEST(GltfMutator, TheGltfEntryKeepsItsContractOnMutatedSeeds) {
    const mipgloss::fuzz::Entry entry = entryNamed("gltf_import");
    ASSERT_NE(entry, nullptr);
    int cases = 0;
    for (const auto& e : fs::directory_iterator(fs::path(MIPGLOSS_FUZZ_DIR) / "corpus/gltf_import")) {
        const std::vector<std::uint8_t> seed = readBytes(e.path());
        for (unsigned s = 1; s <= 400; ++s) {
            std::minstd_rand rng(s * 2654435761u);
            std::vector<std::uint8_t> input = mutateGltf(seed, rng, 16384);
            // A second mutation on half of them: damage that needs two steps (a wrapped index in a
            // duplicated node).
            if (!input.empty() && s % 2 == 0) {
                std::vector<std::uint8_t> twice = mutateGltf(input, rng, 16384);
                if (!twice.empty()) input = std::move(twice);
            }
            if (input.empty()) continue;
            ++cases;
            const std::string problem = entry(input);
            ASSERT_TRUE(problem.empty()) << e.path().filename() << " mutation " << s << ": " << problem << "\n"
                                         << std::string(input.begin(), input.begin() + std::min<std::size_t>(input.size(), 600));
        }
    }
    EXPECT_GT(cases, 1200);
}
