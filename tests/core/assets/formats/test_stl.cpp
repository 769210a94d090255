// The STL reader (core/assets/src/formats/stl.cpp): text and binary told apart by the size, and
// corners at one position welded into one vertex.
#include "format_test_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::test;

namespace {

using Triangle = std::array<std::array<float, 3>, 3>;

std::string binaryStl(const std::vector<Triangle>& triangles) {
    std::string bytes(80, ' ');
    put(bytes, static_cast<std::uint32_t>(triangles.size()), false);
    for (const Triangle& t : triangles) {
        for (int k = 0; k < 3; ++k) put(bytes, 0.0f, false);  // the facet normal, unused
        for (const auto& corner : t)
            for (float c : corner) put(bytes, c, false);
        bytes.append(2, '\0');  // attribute byte count
    }
    return bytes;
}

std::string asciiStl(const std::vector<Triangle>& triangles) {
    std::string text = "solid square\n";
    for (const Triangle& t : triangles) {
        text += "facet normal 0 0 1\n outer loop\n";
        for (const auto& c : t)
            text += "  vertex " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
        text += " endloop\nendfacet\n";
    }
    return text + "endsolid square\n";
}

// A unit square as two triangles sharing the diagonal; one corner written as -0.
const std::vector<Triangle> kSquare = {Triangle{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}},
                                       Triangle{{{-0.0f, 0, 0}, {1, 1, 0}, {0, 1, 0}}}};

}  // namespace

TEST(StlReader, CornersAtOnePositionAreOneVertexInBothForms) {
    for (const std::string& bytes : {binaryStl(kSquare), asciiStl(kSquare)}) {
        const meshfile::Polygons p = meshfile::parseStl(asBytes(bytes), "square.stl");
        EXPECT_EQ(p.positions.size(), 4u);  // six corners, four places (-0 is 0)
        ASSERT_EQ(p.faceCount(), 2u);
        EXPECT_EQ(p.corners, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));  // in first-seen order
        const Mesh mesh = loadMeshFromMemory(asBytes(bytes), "square.stl");
        EXPECT_EQ(mesh.vertexCount(), 4u);
        EXPECT_EQ(mesh.triangleCount(), 2u);
    }
}

TEST(StlReader, ATriangleWhoseCornersWeldIntoFewerThanThreeIsDroppedAsZeroArea) {
    const std::vector<Triangle> triangles = {kSquare[0], Triangle{{{0, 0, 0}, {0, 0, 0}, {1, 1, 0}}}};
    MeshReport report;
    const Mesh mesh = loadMeshFromMemory(asBytes(binaryStl(triangles)), "t.stl", &report);
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(report.degenerateFacesDropped, 1u);
}

TEST(StlReader, BinaryCutShortIsRefusedWithTheSizesAndTextWithoutItsEnd) {
    std::string bytes = binaryStl(kSquare);
    bytes.resize(bytes.size() - 10);
    EXPECT_CONTAINS(refusal(meshfile::parseStl, bytes, "t.stl"),
                    "the header announces 2 triangles (184 bytes), the file has 174 bytes");
    std::string text = asciiStl(kSquare);
    text.resize(text.find("endsolid"));
    EXPECT_CONTAINS(refusal(meshfile::parseStl, text, "t.stl"), "does not end with 'endsolid'");
}
