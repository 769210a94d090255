#include "mipgloss/assets/default_scene.h"
#include "mipgloss/assets/mesh_files.h"
#include "mesh_file_support.h"
#include "test_support.h"

#include <unistd.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

using test::append;
using test::binaryPly;
using test::objText;

using test::OMesh;
using test::binaryStl;
using test::teapotAsset;
using test::toOpenMesh;

using test::TempDir;

using test::readText;
using test::writeBytes;

fs::path resourceTeapot() { return test::assetDir().parent_path().parent_path() / "resources/meshes/teapot.obj"; }

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance, const std::string& what) {
    EXPECT_LE(glm::length(a - b), tolerance)
        << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Real assets

TEST(MeshImport, LoadsRealAssetsWithTheirCounts) {
    struct Case {
        const char* file;
        std::size_t vertices, triangles;
    };
    // Counts from tests/assets/SOURCES.md.
    for (const Case& c :
         {Case{"meshes/teapot_newell_seg16.obj", 8257, 16256}, Case{"meshes/suzanne_pmndrs.obj", 7503, 14842},
          Case{"meshes/bunny_npm_lowres.obj", 1839, 3674}}) {
        SCOPED_TRACE(c.file);
        MIPGLOSS_REQUIRE_ASSET(test::asset(c.file));
        MeshReport report;
        const Mesh mesh = loadMesh(test::asset(c.file), &report);
        EXPECT_EQ(mesh.triangleCount(), c.triangles);
        EXPECT_EQ(mesh.vertexCount(), c.vertices);
        EXPECT_EQ(report.degenerateFacesDropped, 0u);
        EXPECT_EQ(report.unusedVerticesDropped, 0u);
        for (const std::string& w : report.warnings) std::printf("  warning: %s\n", w.c_str());
        EXPECT_TRUE(mesh.isValid());
        EXPECT_EQ(mesh.name, fs::path(c.file).stem().string());
        EXPECT_GT(mesh.bounds.radius(), 0.1f);
    }
}

TEST(MeshImport, TeapotBoundsAreYUp) {
    MIPGLOSS_REQUIRE_ASSET(teapotAsset());
    const Mesh mesh = loadMesh(teapotAsset());
    // Spout to handle along x, lid knob on +y, round in z.
    const glm::vec3 size = mesh.bounds.max - mesh.bounds.min;
    EXPECT_GT(size.x, size.y);
    EXPECT_NEAR(size.z, 2.0f * mesh.bounds.max.z, 1e-3f);
    EXPECT_NEAR(mesh.bounds.radius(), 0.5f * glm::length(size), 1e-6f);
}

TEST(MeshNormals, PointOutwardOnWatertightBunny) {
    const fs::path file = test::asset("meshes/bunny_npm_lowres.obj");
    MIPGLOSS_REQUIRE_ASSET(file);
    const Mesh mesh = loadMesh(file);
    ASSERT_TRUE(mesh.isValid());
    const glm::vec3 centre = mesh.bounds.centre();
    std::size_t outward = 0;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        if (glm::dot(mesh.normals[v], mesh.positions[v] - centre) > 0.0f) ++outward;
    const double fraction = static_cast<double>(outward) / static_cast<double>(mesh.vertexCount());
    std::printf("  bunny: %.1f%% of normals point away from the centre\n", 100.0 * fraction);
    EXPECT_GT(fraction, 0.85);
    // The divergence theorem: a closed outward-oriented surface encloses a positive volume.
    double volume = 0.0;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
        volume += glm::dot(glm::dvec3(mesh.positions[mesh.indices[t]]),
                           glm::cross(glm::dvec3(mesh.positions[mesh.indices[t + 1]]),
                                      glm::dvec3(mesh.positions[mesh.indices[t + 2]]))) /
                  6.0;
    EXPECT_GT(volume, 0.0);
}

TEST(MeshTeapot, DefaultEqualsTheResourceFile) {
    ASSERT_TRUE(fs::exists(resourceTeapot())) << resourceTeapot();
    const Mesh embedded = defaultTeapot();
    const Mesh file = loadMesh(resourceTeapot());
    EXPECT_EQ(embedded.name, "teapot");
    EXPECT_EQ(embedded.triangleCount(), 16256u);
    EXPECT_TRUE(embedded.isValid());
    EXPECT_EQ(embedded.indices, file.indices);
    EXPECT_EQ(embedded.positions, file.positions);
    EXPECT_EQ(embedded.normals, file.normals);
}

TEST(DefaultScene, IsFigure1OnOneEmbeddedTeapot) {
    const Scene scene = makeFigure1Scene();
    ASSERT_EQ(scene.objects.size(), 4u);
    for (const SceneObject& object : scene.objects) {
        EXPECT_EQ(object.mesh, scene.objects[0].mesh) << "one teapot, shared";
        EXPECT_EQ(object.meshSource, "builtin:teapot");
    }
    EXPECT_EQ(scene.objects[0].mesh->triangleCount(), defaultTeapot().triangleCount());
}

TEST(MeshImport, ExtensionsAreListedAndCaseInsensitive) {
    std::vector<std::string> listed(meshExtensions().begin(), meshExtensions().end());
    EXPECT_EQ(listed, (std::vector<std::string>{".obj", ".off", ".ply", ".stl", ".om"}));
    MIPGLOSS_REQUIRE_ASSET(teapotAsset());
    const std::string text = readText(teapotAsset());
    const std::span<const unsigned char> bytes(reinterpret_cast<const unsigned char*>(text.data()), text.size());
    const Mesh upper = loadMeshFromMemory(bytes, "TEAPOT.OBJ");
    EXPECT_EQ(upper.name, "TEAPOT");
    EXPECT_EQ(upper.triangleCount(), 16256u);
    EXPECT_EQ(upper.positions, loadMesh(teapotAsset()).positions);
}

// ---------------------------------------------------------------------------------------------
// Every format

TEST(MeshImport, ReadsEveryFormatAlike) {
    // The bunny: closed and manifold, so OpenMesh's writers take it whole (the teapot has three
    // triangles at pinched vertices that its half-edge structure refuses).
    const fs::path bunny = test::asset("meshes/bunny_npm_lowres.obj");
    MIPGLOSS_REQUIRE_ASSET(bunny);
    TempDir dir;
    const Mesh reference = loadMesh(bunny);
    const OMesh om = toOpenMesh(reference);
    using OpenMesh::IO::Options;
    struct Case {
        const char* name;
        Options::Flag flags;
    };
    for (const Case& c : {Case{"bunny.obj", Options::Default}, Case{"bunny.off", Options::Default},
                          Case{"bunny_binary.off", Options::Binary}, Case{"bunny.ply", Options::Default},
                          Case{"bunny_binary.ply", Options::Binary}, Case{"bunny.stl", Options::Default},
                          Case{"bunny_binary.stl", Options::Binary}, Case{"bunny.om", Options::Binary}}) {
        SCOPED_TRACE(c.name);
        const fs::path file = dir / c.name;
        ASSERT_TRUE(OpenMesh::IO::write_mesh(om, file.string(), Options(c.flags), 9)) << file;
        MeshReport report;
        const Mesh mesh = loadMesh(file, &report);
        EXPECT_TRUE(mesh.isValid());
        EXPECT_EQ(mesh.triangleCount(), reference.triangleCount());
        EXPECT_EQ(mesh.vertexCount(), reference.vertexCount());
        EXPECT_EQ(report.degenerateFacesDropped, 0u);
        EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
        // Same triangles over the same points (the order may differ: STL welds by position).
        double area = 0.0, referenceArea = 0.0;
        for (const Mesh* m : {&mesh, &reference})
            for (std::size_t t = 0; t < m->indices.size(); t += 3)
                (m == &mesh ? area : referenceArea) +=
                    0.5 * glm::length(
                              glm::cross(glm::dvec3(m->positions[m->indices[t + 1]] - m->positions[m->indices[t]]),
                                         glm::dvec3(m->positions[m->indices[t + 2]] - m->positions[m->indices[t]])));
        EXPECT_NEAR(area, referenceArea, 1e-6 * referenceArea);
        expectNear(mesh.bounds.min, reference.bounds.min, 1e-6f, "bounds.min");
        expectNear(mesh.bounds.max, reference.bounds.max, 1e-6f, "bounds.max");
        EXPECT_EQ(mesh.name, file.stem().string());
    }
}

TEST(MeshImport, TriangulatesPolygons) {
    TempDir dir;
    // A unit cube of six quads, as OBJ and as OFF.
    const std::string positions = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";
    const char* quads[] = {"1 4 3 2", "5 6 7 8", "1 2 6 5", "2 3 7 6", "3 4 8 7", "4 1 5 8"};
    std::string obj, off = "OFF\n8 6 0\n" + positions;
    std::istringstream lines(positions);
    for (std::string line; std::getline(lines, line);) obj += "v " + line + "\n";
    for (const char* q : quads) {
        obj += std::string("f ") + q + "\n";
        std::istringstream idx(q);
        off += "4";
        for (int i; idx >> i;) off += " " + std::to_string(i - 1);
        off += "\n";
    }
    writeBytes(dir / "cube.obj", obj);
    writeBytes(dir / "cube.off", off);
    for (const char* name : {"cube.obj", "cube.off"}) {
        SCOPED_TRACE(name);
        const Mesh cube = loadMesh(dir / name);
        EXPECT_EQ(cube.triangleCount(), 12u);
        EXPECT_EQ(cube.vertexCount(), 8u);
        ASSERT_TRUE(cube.isValid());
        // Each corner's normal is the normalised sum of its three outward face normals.
        for (std::size_t v = 0; v < cube.vertexCount(); ++v) {
            const glm::vec3 out = glm::normalize(cube.positions[v] - glm::vec3(0.5f));
            EXPECT_GT(glm::dot(cube.normals[v], out), 0.9f) << "vertex " << v;
        }
    }
}

TEST(MeshImport, KeepsNonManifoldTrianglesWelded) {
    TempDir dir;
    // Three triangles on the edge 1-2 (a fin), and a fourth touching only at vertex 1 (a pinch).
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv -1 0 0\nv -1 0 -1\n"
        "f 1 2 3\nf 2 1 4\nf 1 2 5\nf 1 6 7\n";
    writeBytes(dir / "fin.obj", obj);
    MeshReport report;
    const Mesh mesh = loadMesh(dir / "fin.obj", &report);
    EXPECT_EQ(mesh.triangleCount(), 4u);
    EXPECT_EQ(mesh.vertexCount(), 7u) << "copies OpenMesh needs for its half-edges map back to the file's vertices";
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 6}));
    EXPECT_TRUE(mesh.isValid());
    EXPECT_TRUE(report.warnings.empty()) << "nothing was dropped";
}

TEST(MeshImport, RecomputesStlNormals) {
    TempDir dir;
    const Mesh sphere = makeSphere(12, 24);
    // Facet normals pointing the same wrong way for every triangle, and some not even unit.
    writeBytes(dir / "garbage_normals.stl", binaryStl(sphere, glm::vec3(0.0f, 0.0f, -7.0f)));
    const Mesh mesh = loadMesh(dir / "garbage_normals.stl");
    ASSERT_TRUE(mesh.isValid());
    EXPECT_EQ(mesh.triangleCount(), sphere.triangleCount());
    EXPECT_EQ(mesh.vertexCount(), sphere.vertexCount()) << "STL corners are welded by position";
    float worst = 1.0f;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        worst = std::min(worst, glm::dot(mesh.normals[v], glm::normalize(mesh.positions[v])));
    EXPECT_GT(worst, 0.99f);
}

TEST(MeshImport, BinaryStlMayStartWithSolid) {
    // Many exporters write "solid ..." into the binary header; the size says binary.
    TempDir dir;
    const Mesh sphere = makeSphere(6, 12);
    std::string stl = binaryStl(sphere, glm::vec3(0.0f));
    stl.replace(0, 14, "solid exported");
    writeBytes(dir / "solid_header.stl", stl);
    const Mesh mesh = loadMesh(dir / "solid_header.stl");
    EXPECT_EQ(mesh.triangleCount(), sphere.triangleCount());
    EXPECT_EQ(mesh.vertexCount(), sphere.vertexCount());
}

TEST(MeshImport, FromMemoryMatchesFile) {
    TempDir dir;
    const Mesh sphere = makeSphere(8, 16);
    const std::string ply = binaryPly(sphere);
    writeBytes(dir / "ball.ply", ply);
    const Mesh fromFile = loadMesh(dir / "ball.ply");
    const Mesh fromMemory = loadMeshFromMemory(
        std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(ply.data()), ply.size()), "ball.ply");
    EXPECT_EQ(fromMemory.name, "ball");
    EXPECT_EQ(fromMemory.indices, fromFile.indices);
    EXPECT_EQ(fromMemory.positions, fromFile.positions);
    EXPECT_EQ(fromMemory.positions, sphere.positions);
    EXPECT_EQ(fromMemory.indices, sphere.indices);
}

// ---------------------------------------------------------------------------------------------
// Validation: what is dropped and reported

TEST(MeshImport, DropsAndCountsZeroAreaFaces) {
    MIPGLOSS_REQUIRE_ASSET(teapotAsset());
    TempDir dir;
    // Three zero-area faces: a repeated index, two corners at the same place, three collinear points.
    const std::string text = readText(teapotAsset()) +
                             "v 0 0 0\nv 0 0 0\nv 1 0 0\nv 0.5 0 0\n"
                             "f 1 1 2\nf -4 -3 -2\nf -4 -2 -1\n";
    writeBytes(dir / "teapot_degenerate.obj", text);
    MeshReport report;
    const Mesh mesh = loadMesh(dir / "teapot_degenerate.obj", &report);
    EXPECT_EQ(mesh.triangleCount(), 16256u);
    EXPECT_EQ(report.degenerateFacesDropped, 3u);
    EXPECT_EQ(report.unusedVerticesDropped, 4u) << "the degenerate faces' own vertices are left unused";
    EXPECT_EQ(mesh.vertexCount(), 8257u);
    ASSERT_FALSE(report.warnings.empty());
    bool named = false;
    for (const std::string& w : report.warnings) {
        std::printf("  warning: %s\n", w.c_str());
        named = named ||
                (w.find("teapot_degenerate.obj") != std::string::npos && w.find("zero area") != std::string::npos);
    }
    EXPECT_TRUE(named);
}

TEST(MeshImport, DropsUnusedVerticesFromTheBounds) {
    MIPGLOSS_REQUIRE_ASSET(teapotAsset());
    TempDir dir;
    const Mesh reference = loadMesh(teapotAsset());
    writeBytes(dir / "stray.obj", readText(teapotAsset()) + "v 100 100 100\nv -50 0 0\n");
    MeshReport report;
    const Mesh mesh = loadMesh(dir / "stray.obj", &report);
    EXPECT_EQ(report.unusedVerticesDropped, 2u);
    EXPECT_EQ(mesh.vertexCount(), reference.vertexCount());
    EXPECT_EQ(mesh.bounds.min, reference.bounds.min);
    EXPECT_EQ(mesh.bounds.max, reference.bounds.max);
}

TEST(MeshImport, StlDegenerateTrianglesAreCounted) {
    TempDir dir;
    Mesh sphere = makeSphere(6, 8);
    // Two extra triangles: one with a repeated corner, one collinear.
    sphere.positions.insert(sphere.positions.end(), {{3, 0, 0}, {4, 0, 0}, {5, 0, 0}});
    const auto n = static_cast<std::uint32_t>(sphere.positions.size());
    sphere.indices.insert(sphere.indices.end(), {n - 3, n - 3, n - 2, n - 3, n - 2, n - 1});
    writeBytes(dir / "with_degenerate.stl", binaryStl(sphere, glm::vec3(0.0f)));
    MeshReport report;
    const Mesh mesh = loadMesh(dir / "with_degenerate.stl", &report);
    EXPECT_EQ(mesh.triangleCount(), sphere.triangleCount() - 2);
    EXPECT_EQ(report.degenerateFacesDropped, 2u);
    EXPECT_LE(mesh.bounds.max.x, 1.0f) << "the degenerate triangles' corners are dropped";
}

// ---------------------------------------------------------------------------------------------
// Validation: errors


TEST(MeshImport, LargeMeshKeepsEveryTriangleWithThirtyTwoBitIndices) {
    TempDir dir;
    const Mesh sphere = makeSphere(200, 400);  // 159,200 triangles over 79,602 vertices
    ASSERT_GT(sphere.vertexCount(), 65536u);
    writeBytes(dir / "large.ply", binaryPly(sphere));
    writeBytes(dir / "large.obj", objText(sphere));
    for (const char* name : {"large.ply", "large.obj"}) {
        SCOPED_TRACE(name);
        MeshReport report;
        const Mesh mesh = loadMesh(dir / name, &report);
        EXPECT_EQ(mesh.triangleCount(), sphere.triangleCount());
        EXPECT_EQ(mesh.vertexCount(), sphere.vertexCount());
        EXPECT_EQ(report.degenerateFacesDropped, 0u);
        EXPECT_EQ(report.unusedVerticesDropped, 0u);
        EXPECT_TRUE(mesh.isValid());
        EXPECT_GE(*std::max_element(mesh.indices.begin(), mesh.indices.end()), 65536u)
            << "indices above 16 bits survive";
        // Every vertex on the unit sphere: 1e-6 for PLY's floats, 1e-6 for OBJ's 7 significant digits.
        float worst = 0.0f;
        for (const glm::vec3& p : mesh.positions) worst = std::max(worst, std::abs(glm::length(p) - 1.0f));
        EXPECT_LT(worst, 1e-6f);
    }
}

namespace mipgloss {
namespace {

TEST(MeshExport, WrittenFilesLoadBackAlike) {
    const Mesh sphere = makeSphere(16, 32);
    const test::TempDir dir;
    for (const char* ext : {".ply", ".obj", ".stl", ".off", ".om"}) {
        const auto file = dir / (std::string("sphere") + ext);
        writeMesh(sphere, file);
        const Mesh back = loadMesh(file);
        EXPECT_EQ(back.triangleCount(), sphere.triangleCount()) << ext;
        EXPECT_NEAR(back.bounds.radius(), sphere.bounds.radius(), 1e-5f) << ext;
    }
    EXPECT_THROW(writeMesh(sphere, dir / "sphere.xyz"), MeshError);
    // Written atomically: a rewrite replaces the file whole and leaves no temporary beside it.
    writeMesh(makeSphere(4, 8), dir / "sphere.ply");
    EXPECT_EQ(loadMesh(dir / "sphere.ply").triangleCount(), makeSphere(4, 8).triangleCount());
    int files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 5);
}

}  // namespace
}  // namespace mipgloss
