// The mesh value type and its geometry: the test spheres, area-weighted normals, bounds and the
// validity invariants (mipgloss/scene/mesh.h). Reading mesh files is tests/core/assets.
#include "mipgloss/scene/mesh.h"
#include "test_support.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

using namespace mipgloss;

namespace {

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance, const std::string& what) {
    EXPECT_LE(glm::length(a - b), tolerance)
        << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

}  // namespace

TEST(MeshSphere, IsValidWithExactNormals) {
    const Mesh sphere = makeSphere(16, 32);
    ASSERT_TRUE(sphere.isValid());
    EXPECT_EQ(sphere.triangleCount(), 2u * 32u * 15u);
    EXPECT_EQ(sphere.vertexCount(), 2u + 32u * 15u);
    for (std::size_t v = 0; v < sphere.vertexCount(); ++v) {
        EXPECT_NEAR(glm::length(sphere.positions[v]), 1.0f, 1e-6f) << "vertex " << v;
        expectNear(sphere.normals[v], sphere.positions[v], 1e-5f,
                   "normal vs position of vertex " + std::to_string(v));
    }
    expectNear(sphere.bounds.min, glm::vec3(-1.0f), 1e-6f, "bounds.min");
    expectNear(sphere.bounds.max, glm::vec3(1.0f), 1e-6f, "bounds.max");
    EXPECT_NEAR(sphere.bounds.radius(), std::sqrt(3.0f), 1e-6f);
    EXPECT_EQ(makeSphere().triangleCount(), 2u * 128u * 63u);
}

TEST(MeshNormals, FromFacesMatchTheSphereAndFaceOutward) {
    Mesh sphere = makeSphere(32, 64);
    const std::vector<glm::vec3> exact = sphere.normals;
    computeVertexNormals(sphere);
    ASSERT_TRUE(sphere.isValid());
    float worst = 1.0f;
    for (std::size_t v = 0; v < exact.size(); ++v) worst = std::min(worst, glm::dot(sphere.normals[v], exact[v]));
    std::printf("  smallest cos(face-derived, exact) = %.6f\n", static_cast<double>(worst));
    EXPECT_GT(worst, 0.999f);
}

TEST(MeshNormals, AreAreaWeighted) {
    // A vertex at the origin shared by a triangle in the xy plane (normal +z, area 2) and one in
    // the yz plane (normal +x, area 1/2): its normal is (1/2, 0, 2) normalised.
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 1, 0}, {0, 0, 1}};
    mesh.indices = {0, 1, 2, 0, 3, 4};
    computeVertexNormals(mesh);
    expectNear(mesh.normals[0], glm::normalize(glm::vec3(0.5f, 0.0f, 2.0f)), 1e-6f, "shared vertex");
    expectNear(mesh.normals[1], glm::vec3(0, 0, 1), 1e-6f, "vertex of the big triangle only");
    expectNear(mesh.normals[4], glm::vec3(1, 0, 0), 1e-6f, "vertex of the small triangle only");
}

TEST(MeshNormals, ZeroAreaNeighbourhoodGetsUp) {
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    mesh.indices = {0, 1, 2};
    computeVertexNormals(mesh);
    for (const glm::vec3& n : mesh.normals) expectNear(n, glm::vec3(0, 1, 0), 0.0f, "normal");
    EXPECT_TRUE(mesh.isValid());
}

TEST(MeshBounds, ComputeBoundsAndValidity) {
    Mesh mesh;
    mesh.positions = {{-1, 2, 3}, {4, -5, 6}, {0, 0, -7}};
    mesh.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
    mesh.indices = {0, 1, 2};
    computeBounds(mesh);
    expectNear(mesh.bounds.min, glm::vec3(-1, -5, -7), 0.0f, "min");
    expectNear(mesh.bounds.max, glm::vec3(4, 2, 6), 0.0f, "max");
    expectNear(mesh.bounds.centre(), glm::vec3(1.5f, -1.5f, -0.5f), 0.0f, "centre");
    EXPECT_FLOAT_EQ(mesh.bounds.radius(), 0.5f * std::sqrt(25.0f + 49.0f + 169.0f));
    EXPECT_TRUE(mesh.isValid());

    Mesh bad = mesh;
    bad.indices.back() = 3;
    EXPECT_FALSE(bad.isValid()) << "index out of range";
    bad = mesh;
    bad.normals[1] = {0, 2, 0};
    EXPECT_FALSE(bad.isValid()) << "normal not unit";
    bad = mesh;
    bad.positions[2].x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(bad.isValid()) << "NaN position";
    bad = mesh;
    bad.indices.pop_back();
    EXPECT_FALSE(bad.isValid()) << "indices not a multiple of 3";
    bad = mesh;
    bad.normals.pop_back();
    EXPECT_FALSE(bad.isValid()) << "fewer normals than positions";
}
