// Mesh files refused (mesh_files.h): every cut, bad token, non-finite vertex, empty, random,
// truncated or unknown file is a MeshError naming the file and the reason.
#include "mesh_file_support.h"
#include "mipgloss/assets/mesh_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

using test::binaryPly;
using test::binaryStl;
using test::OMesh;
using test::readText;
using test::teapotAsset;
using test::TempDir;
using test::toOpenMesh;
using test::writeBytes;

// Loading `file` must fail with a MeshError naming it and containing `reason`.
void expectMeshError(const fs::path& file, const std::string& reason) {
    try {
        const Mesh mesh = loadMesh(file);
        ADD_FAILURE() << file << " loaded (" << mesh.triangleCount() << " triangles), expected an error with '"
                      << reason << "'";
    } catch (const MeshError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find(reason), std::string::npos) << "expected '" << reason << "' in: " << what;
        EXPECT_EQ(e.file(), file);
        std::printf("  %s\n", what.c_str());
    }
}

// The same for `file` written with `bytes` first.
void expectMeshError(const fs::path& file, const std::string& bytes, const std::string& reason) {
    writeBytes(file, bytes);
    expectMeshError(file, reason);
}

// A copy of the teapot OBJ text with each line passed through `edit` (return false to drop it).
template <typename Edit>
std::string editedTeapot(Edit edit) {
    std::istringstream in(readText(teapotAsset()));
    std::string out, line;
    while (std::getline(in, line))
        if (edit(line)) out += line + "\n";
    return out;
}

}  // namespace

TEST(MeshImportErrors, ObjCutInAFaceLineNamesTheLine) {
    MIPGLOSS_REQUIRE_ASSET(teapotAsset());
    TempDir dir;
    std::string text = readText(teapotAsset());
    // Cut half-way through the file, just after the first index of a face line.
    const std::size_t face = text.find("\nf ", text.size() / 2);
    ASSERT_NE(face, std::string::npos);
    const std::size_t cut = text.find(' ', face + 3);
    expectMeshError(dir / "cut.obj", text.substr(0, cut), "a face with only 1 vertex (truncated or corrupt file)");
    // And after the second.
    expectMeshError(dir / "cut2.obj", text.substr(0, text.find(' ', cut + 1)),
                    "a face with only 2 vertices (truncated or corrupt file)");
}

TEST(MeshImportErrors, ObjFacesReferToMissingVertices) {
    MIPGLOSS_REQUIRE_ASSET(teapotAsset());
    TempDir dir;
    // The last 57 of the 8257 vertex lines lost, as when a file's vertex block is cut short.
    std::size_t seen = 0;
    writeBytes(dir / "missing.obj",
               editedTeapot([&](const std::string& line) { return !line.starts_with("v ") || ++seen <= 8257 - 57; }));
    expectMeshError(dir / "missing.obj", "but the file has only 8200 vertices (truncated or corrupt file)");
}

TEST(MeshImportErrors, ObjVertexWithoutThreeCoordinatesNamesTheLine) {
    TempDir dir;
    expectMeshError(dir / "short.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 0.25 0.5",
                    "line 5: a vertex without three readable coordinates");
}

TEST(MeshImportErrors, ObjUnreadableOrOutOfRangeFaceIndexNamesTheToken) {
    TempDir dir;
    expectMeshError(dir / "token.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x3\n",
                    "line 4: cannot read the face index 'x3'");
    expectMeshError(dir / "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                    "line 4: cannot read the face index '0'");
    expectMeshError(dir / "before.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "points before the first vertex");
}

TEST(MeshImportErrors, NanVerticesAreCountedWithTheFirstLine) {
    MIPGLOSS_REQUIRE_ASSET(teapotAsset());
    TempDir dir;
    std::size_t n = 0;
    writeBytes(dir / "nan.obj", editedTeapot([&](std::string& line) {
                   if (line.starts_with("v ") && (++n == 100 || n == 200)) line = "v 0.5 nan 0.25";
                   return true;
               }));
    expectMeshError(dir / "nan.obj", "2 vertices with non-finite (NaN or infinite) coordinates, first at line 102");

    // Binary formats hold NaN as bits.
    Mesh sphere = makeSphere(4, 6);
    sphere.positions[3].z = std::numeric_limits<float>::quiet_NaN();
    expectMeshError(dir / "nan.ply", binaryPly(sphere), "1 vertex with non-finite (NaN or infinite) coordinates");
    expectMeshError(dir / "nan.stl", binaryStl(sphere, glm::vec3(0.0f)),
                    "with non-finite (NaN or infinite) coordinates");
}

TEST(MeshImportErrors, InfiniteVerticesAreCountedWithTheFirstLine) {
    TempDir dir;
    expectMeshError(dir / "inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nv 0 0 1e39\nf 1 2 3\nf 1 3 4\n",
                    "2 vertices with non-finite (NaN or infinite) coordinates, first at line 2");
    Mesh sphere = makeSphere(4, 6);
    sphere.positions[5].x = -std::numeric_limits<float>::infinity();
    expectMeshError(dir / "inf.ply", binaryPly(sphere), "1 vertex with non-finite (NaN or infinite) coordinates");
    expectMeshError(dir / "inf.stl",
                    "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                    "vertex 0 -inf 0\nendloop\nendfacet\nendsolid x\n",
                    "1 vertex with non-finite (NaN or infinite) coordinates, first at line 6");
}

TEST(MeshImportErrors, OnlyZeroAreaFacesIsRefused) {
    TempDir dir;
    expectMeshError(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 0 0\nf 1 2 3\nf 2 4 3\nf 1 1 2\n",
                    "all 3 faces have zero area");
}

TEST(MeshImportErrors, NoFacesIsRefusedWithTheVertexCount) {
    TempDir dir;
    expectMeshError(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces, only 3 vertices");
    expectMeshError(dir / "notes.obj", "# just a comment\nthis is not a mesh\n", "no vertices and no faces");
    expectMeshError(dir / "points.ply",
                    "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n0 0 0\n1 1 1\n",
                    "no faces, only 2 vertices");
}

TEST(MeshImportErrors, EmptyFileOfEveryFormatIsCalledEmpty) {
    TempDir dir;
    for (const char* name : {"empty.obj", "empty.stl", "empty.ply", "empty.off", "empty.om"})
        expectMeshError(dir / name, "", "file is empty (0 bytes)");
}

TEST(MeshImportErrors, RandomBytesAreNotTheFormatTheirNameSays) {
    TempDir dir;
    std::mt19937 rng(7);
    std::string noise(4096, '\0');
    for (char& c : noise) c = static_cast<char>(rng() & 0xff);
    const std::pair<const char*, const char*> cases[] = {
        {"noise.obj", "not an OBJ file: binary data"},
        {"noise.stl", "truncated or corrupt binary STL: the header announces"},
        {"noise.ply", "not a PLY file"},
        {"noise.off", "not an OFF file"},
        {"noise.om", "not an OpenMesh .om file"},
    };
    for (const auto& [name, reason] : cases) expectMeshError(dir / name, noise, reason);
    expectMeshError(dir / "tiny.stl", noise.substr(0, 40), "not an STL file: too short for binary STL (40 bytes)");
}

TEST(MeshImportErrors, TruncatedBinaryFilesNameWhatTheHeaderAnnounced) {
    TempDir dir;
    const Mesh sphere = makeSphere(8, 16);
    const std::string stl = binaryStl(sphere, glm::vec3(0.0f));
    expectMeshError(dir / "cut.stl", stl.substr(0, stl.size() - 20),
                    "truncated or corrupt binary STL: the header announces 224 triangles (11284 bytes)");
    const std::string ply = binaryPly(sphere);
    expectMeshError(dir / "cut.ply", ply.substr(0, ply.size() * 2 / 3), "truncated");
    const OMesh om = toOpenMesh(sphere);
    ASSERT_TRUE(OpenMesh::IO::write_mesh(om, (dir / "whole.om").string()));
    const std::string omBytes = readText(dir / "whole.om");
    expectMeshError(dir / "cut.om", omBytes.substr(0, omBytes.size() / 2), "truncated");
}

TEST(MeshImportErrors, TruncatedTextFilesAreRefused) {
    TempDir dir;
    const OMesh om = toOpenMesh(makeSphere(8, 16));
    for (const char* name : {"whole.off", "whole.ply", "whole.stl"}) {
        SCOPED_TRACE(name);
        ASSERT_TRUE(OpenMesh::IO::write_mesh(om, (dir / name).string()));
        ASSERT_EQ(loadMesh(dir / name).triangleCount(), 224u);
        const std::string text = readText(dir / name);
        // Cut in the vertices, in the faces, and just before the end.
        for (std::size_t size : {text.size() / 5, text.size() * 2 / 3, text.size() - 3}) {
            const fs::path cut = dir / ("cut_" + std::to_string(size) + fs::path(name).extension().string());
            expectMeshError(cut, text.substr(0, size), "truncated or corrupt file");
        }
    }
}

TEST(MeshImportErrors, UnknownExtensionMissingFileAndFolder) {
    TempDir dir;
    expectMeshError(dir / "model.xyz", "v 0 0 0\n",
                    "unsupported mesh format '.xyz' (expected .obj, .off, .ply, .stl, .om)");
    expectMeshError(dir / "nowhere.obj", "file not found");
    fs::create_directories(dir / "folder.obj");
    expectMeshError(dir / "folder.obj", "is a directory");
    try {
        const std::string bytes = "v 0 0 0\n";
        loadMeshFromMemory(
            std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()),
            "memory.fbx");
        ADD_FAILURE() << "loaded an .fbx";
    } catch (const MeshError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "memory.fbx: unsupported mesh format '.fbx' (expected .obj, .off, .ply, .stl, .om)");
        EXPECT_EQ(e.reason(), "unsupported mesh format '.fbx' (expected .obj, .off, .ply, .stl, .om)");
    }
}

// ---------------------------------------------------------------------------------------------
// Size: more vertices than 16-bit indices reach (the timing of a million triangles is the
// MeshImport benchmark in tests/bench)
