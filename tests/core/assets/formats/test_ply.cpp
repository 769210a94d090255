// The PLY reader (core/assets/src/formats/ply.cpp) on hand-made files, each expected message worked
// out from the bytes.
#include "format_test_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::test;

namespace {

std::string plyRefusal(const std::string& bytes) { return refusal(meshfile::parsePly, bytes, "t.ply"); }

// A tetrahedron as binary PLY in either byte order: float x y z, uchar-counted int lists.
std::string tetrahedronPly(bool bigEndian) {
    std::string bytes = std::string("ply\nformat ") + (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
    const float points[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& p : points)
        for (float c : p) put(bytes, c, bigEndian);
    const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& f : faces) {
        bytes.push_back(3);
        for (int i : f) put(bytes, i, bigEndian);
    }
    return bytes;
}

const std::string kAsciiHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

}  // namespace

// ---------------------------------------------------------------------------------------------
// PLY headers, by hand

TEST(PlyValidation, CountsAreComparedWithTheFileSizeBeforeAnythingIsReserved) {
    // 4294967295 vertices of 12 bytes and 1 face of 1 + 3 * 4 bytes need 51539607553 bytes.
    const std::string reason = plyRefusal(
        "ply\nformat binary_little_endian 1.0\nelement vertex 4294967295\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" +
        std::string(64, '\0'));
    EXPECT_CONTAINS(reason, "the header announces 4294967295 vertices and 1 face (at least 51539607553 bytes)");
    EXPECT_CONTAINS(reason, "the file has 64 bytes after the header");
}

TEST(PlyValidation, CountsBeyondThirtyTwoBitsOrNegativeAreRefusedWithTheLine) {
    for (const char* count : {"4294967296", "-1", "1e9", "12abc"}) {
        const std::string reason = plyRefusal("ply\nformat ascii 1.0\nelement vertex " + std::string(count) + "\n");
        EXPECT_CONTAINS(reason, "line 3: cannot read the element count '" + std::string(count) + "'");
    }
}

TEST(PlyValidation, HeaderStructureIsStrict) {
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\nend_header\n"),
                    "line 3: a property before any element");
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n"),
                    "line 4: unknown property type 'float128'");
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\n"),
                    "line 4: a list count of type 'float' (expected an integer type)");
    EXPECT_CONTAINS(plyRefusal("ply\nformat binary 1.0\n"), "line 2: unknown PLY format 'binary'");
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\nelement vertex 1\nelement vertex 1\n"),
                    "line 4: a second element 'vertex'");
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n"),
                    "line 5: a second property 'x' in 'vertex'");
    // OpenMesh looped for ever here: "end_header" only inside a comment, then the end of the file.
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\ncomment end_header\nelement vertex 1\n"),
                    "the header has no 'end_header' line");
    EXPECT_CONTAINS(plyRefusal("ply\nelement vertex 1\nend_header\n"), "line 3: the header has no 'format' line");
    EXPECT_CONTAINS(plyRefusal("PLY?\n"), "not a PLY file");
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nend_header\n"
                               "0 0\n1 1\n"),
                    "line 3: the vertices have no number property 'z'");
    EXPECT_CONTAINS(plyRefusal("ply\nformat ascii 1.0\nelement vertex 9\nend_header\n"),
                    "line 3: element 'vertex' has 9 entries but no properties");
}

TEST(PlyValidation, FaceListSizesAreBounded) {
    // A uint count of 70000 corners, more than kMaxFaceCorners (65536) and more than the file holds.
    std::string big = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
    const std::size_t faceAt = big.size() + 36;
    big += std::string(36, '\0');
    put(big, std::uint32_t{70000}, false);
    big += std::string(12, '\0');
    EXPECT_CONTAINS(plyRefusal(big), "byte offset " + std::to_string(faceAt) + ": face 0 has a list of 70000 values");
    // Two corners: no face.
    EXPECT_CONTAINS(plyRefusal(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n2 0 1    \n"),
                    "line 13: face 0 has 2 vertices (a face needs 3 or more");
    // A negative count in text (OpenMesh read it as 4294967295 and looped).
    EXPECT_CONTAINS(plyRefusal(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n"), "line 13: '-1' is not a uchar");
}

TEST(PlyValidation, IndicesOutOfRangeNameTheFaceAndWhere) {
    EXPECT_CONTAINS(plyRefusal(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                    "line 13: face 0 refers to vertex 3, but the file has 3 vertices (vertices count from 0");
    std::string bytes = tetrahedronPly(false);
    // Face 2's second index (after 4 vertices of 12 bytes and two faces of 13).
    const std::size_t at = bytes.size() - 4 * 13 + 2 * 13 + 1 + 4;
    bytes.replace(at, 4, std::string("\xff\xff\xff\xff", 4));
    EXPECT_CONTAINS(plyRefusal(bytes), "byte offset " + std::to_string(at) + ": face 2 refers to vertex -1");
}

TEST(PlyValidation, TruncatedBodiesAreRefusedWhereTheyEnd) {
    // The last face announces 4 corners and holds 3: the file ends 12 bytes into it.
    std::string bytes = tetrahedronPly(false);
    bytes[bytes.size() - 13] = 4;
    EXPECT_CONTAINS(plyRefusal(bytes), "byte offset " + std::to_string(bytes.size()) +
                                           ": the file ends in face 3 of 4 (truncated or corrupt file)");
    // Text cut inside the last number reads "3 0 1 2" from "3 0 1 23": only the missing line end tells.
    EXPECT_CONTAINS(plyRefusal(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2"),
                    "the file ends inside its last value, with no line end (truncated file)");
    EXPECT_CONTAINS(plyRefusal(kAsciiHeader + "0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n"), "line 12: 'zero' is not a number");
}

TEST(PlyValidation, BothByteOrdersReadAlike) {
    const meshfile::Polygons little = meshfile::parsePly(asBytes(tetrahedronPly(false)), "le.ply");
    const meshfile::Polygons big = meshfile::parsePly(asBytes(tetrahedronPly(true)), "be.ply");
    EXPECT_EQ(little.positions, big.positions);
    EXPECT_EQ(little.corners, big.corners);
    EXPECT_EQ(big.corners, (std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
    EXPECT_EQ(big.positions[3], (std::array<float, 3>{0.0f, 0.0f, 1.0f}));
    EXPECT_EQ(loadMeshFromMemory(asBytes(tetrahedronPly(true)), "be.ply").triangleCount(), 4u);
}

TEST(PlyValidation, OtherElementsAndListsAreSkippedWithinTheirBytes) {
    // A material element with a list before the faces, as real exporters write.
    const std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nproperty uchar red\nelement material 1\nproperty list uchar float k\n"
                             "element face 1\nproperty list uchar int vertex_indices\nproperty int flags\nend_header\n"
                             "0 0 0 9\n1 0 0 9\n0 1 0 9\n2 0.5 0.25\n3 0 1 2 7\n";
    const meshfile::Polygons p = meshfile::parsePly(asBytes(text), "t.ply");
    EXPECT_EQ(p.faceCount(), 1u);
    EXPECT_EQ(p.corners, (std::vector<std::uint32_t>{0, 1, 2}));
}
