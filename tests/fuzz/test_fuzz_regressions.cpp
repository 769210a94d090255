// Every committed fuzz input, replayed through the fuzz targets' own entries (entries.h) in the
// normal suite: the seed corpora (tests/fuzz/corpus/<target>/, valid and damaged files that must
// stay within the contract) and each input that once broke it (tests/fuzz/regressions/<target>/,
// one file per fixed crash, hang or broken contract).
#include "entries.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> files;
    if (!fs::is_directory(dir)) return files;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file() && e.path().filename() != "README.md") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::uint8_t> readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzInputs : public ::testing::TestWithParam<const char*> {};

// The seed corpus is required (an empty one would make this test pass on nothing); the
// regressions folder holds files only once a crash has been found and fixed.
TEST_P(FuzzInputs, EveryCommittedInputIsRefusedByNameOrLoadsValid) {
    const std::string target = GetParam();
    const mipgloss::fuzz::Entry entry = mipgloss::fuzz::entryNamed(target);
    ASSERT_NE(entry, nullptr) << target;
    const fs::path root = MIPGLOSS_FUZZ_DIR;
    const std::vector<fs::path> corpus = filesIn(root / "corpus" / target);
    ASSERT_GE(corpus.size(), 3u) << "seed corpus missing: " << (root / "corpus" / target);
    std::vector<fs::path> all = corpus;
    const std::vector<fs::path> crashes = filesIn(root / "regressions" / target);
    all.insert(all.end(), crashes.begin(), crashes.end());
    for (const fs::path& file : all) {
        const std::vector<std::uint8_t> bytes = readBytes(file);
        std::string problem;
        EXPECT_NO_THROW(problem = entry(bytes)) << file;
        EXPECT_EQ(problem, "") << file;
    }
}

#ifdef MIPGLOSS_FUZZ_HAVE_UI
const auto kTargets = ::testing::Values("environment_import", "mesh_import", "gltf_import", "mtl_import", "scene_file",
                                      "library_file");
#else
const auto kTargets = ::testing::Values("environment_import", "mesh_import", "gltf_import", "mtl_import");
#endif

std::string targetName(const ::testing::TestParamInfo<const char*>& target) { return target.param; }

INSTANTIATE_TEST_SUITE_P(Targets, FuzzInputs, kTargets, targetName);

}  // namespace
