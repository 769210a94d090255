// Hostile mesh files (issue 11): what scripts/fuzz-meshes.sh found crashing or hanging OpenMesh's
// readers, kept under tests/assets/meshes/hostile/, and the validators of core/scene/src/
// mesh_validate.h on hand-made headers with the expected message worked out from the bytes.
#include "mipgloss/scene/mesh.h"
#include "mesh_validate.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

std::span<const unsigned char> asBytes(const std::string& s) {
    return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

// The MeshError `parse` throws on `bytes` named `file`; fails the test when it throws none.
template <typename Parse>
std::string refusal(Parse parse, const std::string& bytes, const std::string& file) {
    try {
        parse(asBytes(bytes), file);
    } catch (const MeshError& e) {
        EXPECT_EQ(e.file(), fs::path(file));
        return e.reason();
    }
    ADD_FAILURE() << file << " was read, expected a MeshError";
    return {};
}

std::string plyRefusal(const std::string& bytes) { return refusal(meshfile::parsePly, bytes, "t.ply"); }
std::string offRefusal(const std::string& bytes) { return refusal(meshfile::parseOff, bytes, "t.off"); }

#define EXPECT_CONTAINS(text, part) EXPECT_NE((text).find(part), std::string::npos) << "'" << (part) << "' not in: " << (text)

template <typename T>
void put(std::string& bytes, T value, bool bigEndian) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (bigEndian) std::reverse(raw, raw + sizeof(T));
    bytes.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

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

TEST(OmValidation, CountsMustFitTheFile) {
    std::string om = "OMTB";
    for (std::uint32_t c : {1000u, 1u, 3u}) put(om, c, false);
    om += std::string(64, '\0');
    const std::string reason = refusal(meshfile::checkOm, om, "t.om");
    EXPECT_CONTAINS(reason, "the header announces 1000 vertices, 1 face and 3 edges, more than 80 bytes can hold");
}

TEST(MeshValidation, DistinctCornersKeepTheirFirstOrder) {
    const std::vector<std::uint32_t> corners{5, 3, 5, 2, 3, 9};
    EXPECT_EQ(meshfile::distinctInOrder(corners), (std::vector<std::uint32_t>{5, 3, 2, 9}));
    EXPECT_TRUE(meshfile::distinctInOrder({}).empty());
}

TEST(MeshValidation, ObjFaceOfManyRepeatedCornersIsZeroAreaNotSlow) {
    // 60000 corners over 2 vertices: counted as one zero-area face, by sorting (comparing each
    // corner with those before it took 1.8e9 steps).
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf";
    for (int i = 0; i < 60000; ++i) obj += i % 2 ? " 1" : " 2";
    obj += "\n";
    const meshfile::Declared declared = meshfile::checkObj(asBytes(obj), "t.obj");
    EXPECT_EQ(declared.faces, 2u);
    EXPECT_EQ(declared.zeroAreaFaces, 1u);
}
