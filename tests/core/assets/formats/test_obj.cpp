// The OBJ reader (core/assets/src/formats/obj.cpp) on hand-made files.
#include "format_test_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::test;

TEST(MeshValidation, ObjFaceOfManyRepeatedCornersIsZeroAreaNotSlow) {
    // 60000 corners over 2 vertices: counted as one zero-area face, by sorting (comparing each
    // corner with those before it took 1.8e9 steps).
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf";
    for (int i = 0; i < 60000; ++i) obj += i % 2 ? " 1" : " 2";
    obj += "\n";
    EXPECT_EQ(meshfile::parseObj(asBytes(obj), "t.obj").faceCount(), 2u);
    MeshReport report;
    const Mesh mesh = loadMeshFromMemory(asBytes(obj), "t.obj", &report);
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(report.degenerateFacesDropped, 1u);
}

TEST(ObjReader, CornersAreTheVertexIndexBeforeAnySlashAndNegativeIndicesCountBack) {
    const std::string obj =
        "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
        "g part\nusemtl red\nf 1/1/1 2/1/1 3//1 4\nv 2 0 0\nf -1 -4 -3\n";
    const meshfile::Polygons p = meshfile::parseObj(asBytes(obj), "t.obj");
    EXPECT_EQ(p.positions.size(), 5u);
    ASSERT_EQ(p.faceCount(), 2u);
    EXPECT_EQ(p.corners, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 1, 2}));
    EXPECT_EQ(p.positions[4], (std::array<float, 3>{2.0f, 0.0f, 0.0f}));
    // The quad becomes a fan of two triangles, the second face one more: three in all.
    EXPECT_EQ(loadMeshFromMemory(asBytes(obj), "t.obj").triangleCount(), 3u);
}
