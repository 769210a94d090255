// The OFF reader (core/assets/src/formats/off.cpp) on hand-made files.
#include "format_test_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::test;

namespace {

std::string offRefusal(const std::string& bytes) { return refusal(meshfile::parseOff, bytes, "t.off"); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// OFF, OM and the shared pieces

TEST(OffValidation, CountsFacesAndIndicesAreChecked) {
    EXPECT_CONTAINS(offRefusal("OFF\n1000000 1 0\n0 0 0\n"),
                    "the header announces 1000000 vertices and 1 face (at least 6000008 bytes)");
    EXPECT_CONTAINS(offRefusal("OFF\n-3 1 0\n"), "line 2: cannot read the OFF vertex count '-3'");
    EXPECT_CONTAINS(offRefusal("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n"),
                    "line 6: face 0 has '4000000000' vertices (3 to 65536 expected");
    EXPECT_CONTAINS(offRefusal("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"),
                    "line 6: face 0 refers to vertex 5, but the file has 3 vertices");
    EXPECT_CONTAINS(offRefusal("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1    \n"), "line 6: face 0 has 2 of its 3 vertex numbers");
    EXPECT_CONTAINS(offRefusal("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2"),
                    "the file ends inside its last face, with no line end (truncated file)");
    EXPECT_CONTAINS(offRefusal("4OFF\n"), "4OFF (homogeneous coordinates) is not supported");
    // Binary (OpenMesh's little-endian layout): one triangle whose last index is 7.
    std::string binary = "OFF BINARY\n";
    for (std::int32_t c : {3, 1, 0}) put(binary, c, false);
    binary += std::string(36, '\0');
    for (std::int32_t v : {3, 0, 1, 7}) put(binary, v, false);
    EXPECT_CONTAINS(offRefusal(binary), "byte offset " + std::to_string(binary.size() - 4) +
                                            ": face 0 refers to vertex 7, but the file has 3 vertices");
    binary.resize(binary.size() - 4);
    put(binary, std::int32_t{-1}, false);
    binary.replace(11, 4, std::string("\xff\xff\xff\x7f", 4));
    EXPECT_CONTAINS(offRefusal(binary), "the header announces 2147483647 vertices and 1 faces");
}

TEST(OffValidation, CommentsAndCountsOnTheMagicLineAreRead) {
    const meshfile::Polygons p = meshfile::parseOff(
        asBytes("# a comment\nOFF 3 1 0 # counts here\n\n0 0 0\n1 0 0 # x\n0 1 0\n3 0 1 2 255 0 0\n"), "t.off");
    EXPECT_EQ(p.positions.size(), 3u);
    EXPECT_EQ(p.corners, (std::vector<std::uint32_t>{0, 1, 2}));
}
