// The mesh value type and its geometry: the test spheres, area-weighted normals, bounds and the
// validity invariants (mipgloss/scene/mesh.h). Reading mesh files is tests/core/assets.
#include "mipgloss/scene/mesh.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <glm/mat2x2.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
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

// Tangents (computeTangents: MikkTSpace, the reference implementation, with glTF's sign).
namespace {

// A quad in z = 0 facing +Z over x in [x0, x1], y in [−1, 1], with u = uOf(x) and glTF's v
// running down the image, v = (1 − y)/2; vertices 0..3 at (x0, 1), (x1, 1), (x1, −1), (x0, −1).
void addQuad(Mesh& mesh, float x0, float x1, float (*uOf)(float)) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (const glm::vec2 xy : {glm::vec2(x0, 1), glm::vec2(x1, 1), glm::vec2(x1, -1), glm::vec2(x0, -1)}) {
        mesh.positions.emplace_back(xy, 0.0f);
        mesh.normals.emplace_back(0, 0, 1);
        mesh.uvs.emplace_back(uOf(xy.x), (1.0f - xy.y) / 2.0f);
    }
    mesh.indices.insert(mesh.indices.end(), {base + 3, base + 2, base + 1, base + 3, base + 1, base});
}

// The bitangent the shader builds (material_maps.glsl; glTF): cross(N, T)·w.
glm::vec3 bitangentOf(const Mesh& mesh, std::uint32_t v) {
    return glm::cross(mesh.normals[v], glm::vec3(mesh.tangents[v])) * mesh.tangents[v].w;
}

}  // namespace

// glTF: the normal map's +X is the tangent (u increasing), its +Y up the image (v decreasing).
TEST(MeshTangents, FollowUAndPointTheBitangentUpTheImage) {
    Mesh quad;
    addQuad(quad, -1.0f, 1.0f, [](float x) { return (x + 1.0f) / 2.0f; });
    computeTangents(quad);
    ASSERT_TRUE(quad.isValid());
    ASSERT_EQ(quad.tangents.size(), 4u);
    for (std::uint32_t v = 0; v < 4; ++v) {
        expectNear(glm::vec3(quad.tangents[v]), {1, 0, 0}, 1e-5f, "tangent " + std::to_string(v));
        EXPECT_EQ(quad.tangents[v].w, 1.0f);
        expectNear(bitangentOf(quad, v), {0, 1, 0}, 1e-5f, "bitangent " + std::to_string(v));
    }
}

// The frame follows the UVs the normal map reads: on UV set 1 (here u along −y, v along −x), and
// through KHR_texture_transform's matrix (a quarter turn and a mirror of u): each time the tangent
// is the direction in which the sampled u grows and the bitangent the one in which the sampled v
// falls (up the image), from the quad's linear mapping: ∂p/∂u' and −∂p/∂v'.
TEST(MeshTangents, FollowTheUvSetAndTheTransformTheNormalMapReads) {
    Mesh quad;
    addQuad(quad, -1.0f, 1.0f, [](float x) { return (x + 1.0f) / 2.0f; });
    for (const glm::vec3& p : quad.positions) quad.uvs1.emplace_back((1.0f - p.y) / 2.0f, (1.0f - p.x) / 2.0f);
    // uv = A·p + b on this quad: set 0 has A = [[½, 0], [0, −½]], set 1 [[0, −½], [−½, 0]].
    const glm::mat2 set0(0.5f, 0.0f, 0.0f, -0.5f), set1(0.0f, -0.5f, -0.5f, 0.0f);  // columns
    const float c = 0.0f, s = 1.0f;  // a quarter turn
    const glm::mat3 turnAndMirror = glm::mat3(-1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f) *
                                    glm::mat3(c, -s, 0.0f, s, c, 0.0f, 0.0f, 0.0f, 1.0f);
    struct Case {
        const char* name;
        int set;
        glm::mat3 transform;
        glm::mat2 uvOfPosition;
    };
    for (const Case& k : {Case{"set 1", 1, glm::mat3(1.0f), set1},
                          Case{"set 0 turned and mirrored", 0, turnAndMirror, glm::mat2(turnAndMirror) * set0},
                          Case{"set 1 turned and mirrored", 1, turnAndMirror, glm::mat2(turnAndMirror) * set1}}) {
        Mesh m = quad;
        computeTangents(m, k.set, k.transform);
        ASSERT_TRUE(m.isValid()) << k.name;
        const glm::mat2 positionOfUv = glm::inverse(k.uvOfPosition);  // columns ∂p/∂u', ∂p/∂v'
        const glm::vec3 tangent(glm::normalize(positionOfUv[0]), 0.0f), up(glm::normalize(-positionOfUv[1]), 0.0f);
        for (std::uint32_t v = 0; v < m.vertexCount(); ++v) {
            expectNear(glm::vec3(m.tangents[v]), tangent, 1e-5f, std::string(k.name) + ": tangent " + std::to_string(v));
            expectNear(bitangentOf(m, v), up, 1e-5f, std::string(k.name) + ": bitangent " + std::to_string(v));
        }
    }
}

// A mirrored UV layout (u = |x|, the left half a mirror image of the right): each half's tangent
// follows its own u, the bitangent stays up the image on both, and the seam's shared vertices are
// split, one per tangent, as MikkTSpace's users split them.
TEST(MeshTangents, MirroredSeamSplitsItsVerticesAndKeepsEachSidesFrame) {
    Mesh mirrored;
    addQuad(mirrored, 0.0f, 1.0f, [](float x) { return x; });
    addQuad(mirrored, -1.0f, 0.0f, [](float x) { return -x; });
    // The halves share the seam's two vertices (x = 0: same position, normal and UV): weld them.
    mirrored.indices = {3, 2, 1, 3, 1, 0, 7, 3, 0, 7, 0, 4};
    const std::size_t before = mirrored.vertexCount();
    computeTangents(mirrored);
    ASSERT_TRUE(mirrored.isValid());
    EXPECT_EQ(mirrored.vertexCount(), before + 2) << "the seam's two vertices, once per side";
    for (std::size_t c = 0; c < mirrored.indices.size(); ++c) {
        const std::uint32_t v = mirrored.indices[c];
        const bool left = c >= 6;
        expectNear(glm::vec3(mirrored.tangents[v]), {left ? -1.0f : 1.0f, 0, 0}, 1e-5f, "corner " + std::to_string(c));
        EXPECT_EQ(mirrored.tangents[v].w, left ? -1.0f : 1.0f) << "corner " << c;
        expectNear(bitangentOf(mirrored, v), {0, 1, 0}, 1e-5f, "bitangent at corner " + std::to_string(c));
    }
}

// The UV sphere (u around +Y, v from the top): away from the poles each tangent is unit, on the
// sphere's tangent plane along ∂p/∂u, and the bitangent points toward the top (v decreasing),
// each within the angle between neighbouring facets (a flat facet's UV gradient is not the smooth
// sphere's: 3.6° at most here, the facets 7.5° apart).
TEST(MeshTangents, OnTheUvSphereFollowLongitudeAndPointToTheTop) {
    const int rings = 24, segments = 48;
    const Mesh sphere = makeUvSphere(rings, segments);
    ASSERT_TRUE(sphere.isValid());
    ASSERT_EQ(sphere.tangents.size(), sphere.vertexCount());
    const float facet = static_cast<float>(std::cos(2.0 * std::numbers::pi / segments));
    int checked = 0;
    for (std::uint32_t v = 0; v < sphere.vertexCount(); ++v) {
        const glm::vec3 p = sphere.positions[v];
        if (std::abs(p.y) > std::cos(2.0 * std::numbers::pi / rings)) continue;  // the two rings at each pole
        const glm::vec3 t(sphere.tangents[v]);
        const glm::vec3 alongU = glm::normalize(glm::vec3(-p.z, 0.0f, p.x));  // ∂p/∂φ, φ from +X toward +Z
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(t, alongU), facet) << "vertex " << v;
        const glm::vec3 towardTop = glm::normalize(glm::vec3(0, 1, 0) - p * p.y);
        EXPECT_GT(glm::dot(bitangentOf(sphere, v), towardTop), facet) << "vertex " << v;
        ++checked;
    }
    EXPECT_GT(checked, rings * segments / 2);
}
