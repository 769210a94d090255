// Hostile mesh files (issue 11): what scripts/fuzz-meshes.sh found crashing or hanging OpenMesh's
// readers, kept under tests/assets/meshes/hostile/, each refused naming the file and where; and
// what the readers share (formats/reading.h). Each format's own tests are in formats/.
#include "mipgloss/assets/mesh_files.h"
#include "formats/mesh_formats.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// The fuzzer's finds: each crashed (SIGSEGV) or hung `mipgloss render --mesh` before; each must
// now be refused with its name and the reason, with the line or byte offset.

TEST(MeshHostile, EveryFuzzedFileIsRefusedNamingItAndWhere) {
    const fs::path dir = test::asset("meshes/hostile");
    MIPGLOSS_REQUIRE_ASSET(dir);
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const fs::path file = entry.path();
        if (file.extension() == ".md") continue;
        ++files;
        try {
            const Mesh mesh = loadMesh(file);
            ADD_FAILURE() << file << " loaded (" << mesh.triangleCount() << " triangles)";
        } catch (const MeshError& e) {
            EXPECT_EQ(e.file(), file);
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
            std::printf("  %s: %s\n", file.filename().c_str(), e.reason().c_str());
        }
    }
    EXPECT_GT(files, 0u);
}

TEST(MeshValidation, DistinctCornersKeepTheirFirstOrder) {
    const std::vector<std::uint32_t> corners{5, 3, 5, 2, 3, 9};
    EXPECT_EQ(meshfile::distinctInOrder(corners), (std::vector<std::uint32_t>{5, 3, 2, 9}));
    EXPECT_TRUE(meshfile::distinctInOrder({}).empty());
}
