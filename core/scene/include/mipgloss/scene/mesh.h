// Triangle meshes: a GL-free value type and the geometry on it (normals, tangents, bounds, the
// test spheres). Reading and writing mesh files is the assets room's (mipgloss/assets/mesh_files.h).
#pragma once

#include "mipgloss/scene/bounds.h"

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mipgloss {

// Indexed triangles with one unit normal per vertex. Invariants (checked by `isValid`):
// positions.size() == normals.size(), indices.size() % 3 == 0, every index < positions.size(),
// every coordinate finite, normals unit length.
struct Mesh {
    std::string name;  // for the scene list: the file stem, or a given name
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<std::uint32_t> indices;
    // Assets only (asset.h), each empty or one per vertex: texture coordinates (glTF's TEXCOORD_0,
    // v down as glTF has it) and tangents (xyz unit, w = ±1 the bitangent's sign, glTF's TANGENT).
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> tangents;
    // glTF's TEXCOORD_1 (a second UV set a texture may name) and COLOR_0 (linear RGBA, multiplying
    // the base colour and its alpha), each empty or one per vertex.
    std::vector<glm::vec2> uvs1;
    std::vector<glm::vec4> colours;
    Bounds bounds;

    std::size_t triangleCount() const { return indices.size() / 3; }
    std::size_t vertexCount() const { return positions.size(); }
    bool isValid() const;
};

// A UV sphere of radius 1 at the origin with exact normals (tests, the sphere render checks).
Mesh makeSphere(int rings = 64, int segments = 128);
// The same sphere with texture coordinates (u = φ/2π around +Y from +X toward +Z, v = θ/π from the
// top, glTF's v down) and tangents: its seam and poles have a vertex per UV, so a texture wraps
// once around it (textured thumbnails).
Mesh makeUvSphere(int rings = 48, int segments = 96);

// The one rule for a zero-area (degenerate) triangle, every reader's: its height below 1e-7 of
// its longest edge, collinear at float precision (its normal would be noise, its weight nil).
bool isZeroAreaTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// Area-weighted vertex normals from the faces; zero-area neighbourhoods get (0, 1, 0).
void computeVertexNormals(Mesh& mesh);
// Authored normals kept, computed ones (computeVertexNormals) where there are none or a vertex's
// is zero: what the asset readers do with a file's normals (asset.h).
void fillMissingNormals(Mesh& mesh);
// Recomputes `bounds` from the positions.
void computeBounds(Mesh& mesh);
// Per-vertex tangents from the UVs (needs uvs and normals), MikkTSpace's: the reference
// implementation (third_party/mikktspace, zlib licence), which glTF names for a file without
// TANGENT and bakers bake normal maps against; the sign is glTF's (the bitangent up the image).
// A vertex whose corners get different tangents (a mirrored UV seam) is split into one vertex per
// tangent (duplicateVertex), so the vertex count may grow and indices change. A vertex no triangle
// uses gets any unit tangent perpendicular to its normal. `uvSet` is the UV set the normal map
// reads (0: uvs, 1: uvs1): glTF computes absent tangents from "the texture coordinates associated
// with the normal texture". `uvTransform` (KHR_texture_transform's, TextureSampling::uvTransform)
// maps those UVs to where the map is sampled; the frame follows it, so a rotated or mirrored normal
// map still tilts the way its texels say.
void computeTangents(Mesh& mesh, int uvSet = 0, const glm::mat3& uvTransform = glm::mat3(1.0f));
// Appends a copy of vertex `vertex` (every per-vertex array the mesh has) and returns its index.
std::uint32_t duplicateVertex(Mesh& mesh, std::uint32_t vertex);

}  // namespace mipgloss
