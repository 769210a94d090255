// Triangle meshes: a GL-free value type and import of OBJ, OFF, PLY, STL and OM files (our own
// readers, core/scene/src/formats/mesh_formats.h; OpenMesh writes them).
//
// Import always recomputes vertex normals from the faces (area-weighted, computeVertexNormals):
// STL carries none, OBJ/PLY normals are often missing or inconsistent, and one rule for every
// format keeps the lookups (reflection vector, normal) comparable across files.
//
// Validation (MeshError names the file and the problem; nothing is half-loaded):
//   - unreadable, truncated or non-mesh file, or a file with no faces -> error; a face that
//     refers to a vertex the file lacks, or has fewer than 3 vertices, counts as truncated;
//   - a non-finite (NaN/Inf) vertex coordinate -> error (it would poison the bounds and framing);
//   - zero-area (degenerate) faces are dropped and counted in the report; if none remain -> error.
//     Zero area: fewer than 3 distinct vertices, or a height below 1e-7 of the longest edge;
//   - vertices no face uses are dropped (they would distort the bounds).
// Polygons are triangulated as fans. Non-manifold faces (an edge shared by three faces, a pinched
// vertex) are kept, on the file's own vertices. Vertices keep their file order.
// Loads may run on any thread at once; writes are serialised (OpenMesh's writers share state).
#pragma once

#include "mipgloss/io/file_error.h"
#include "mipgloss/scene/bounds.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss {

class MeshError : public FileError {
public:
    using FileError::FileError;
};

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
    Bounds bounds;

    std::size_t triangleCount() const { return indices.size() / 3; }
    std::size_t vertexCount() const { return positions.size(); }
    bool isValid() const;
};

struct MeshReport {
    std::size_t degenerateFacesDropped = 0;
    std::size_t unusedVerticesDropped = 0;
    std::vector<std::string> warnings;  // one line each, naming the file
};

// Loads a mesh file; the format comes from the extension (.obj .off .ply .stl .om, any case).
Mesh loadMesh(const std::filesystem::path& path, MeshReport* report = nullptr);

// Same from bytes in memory; `nameForMessages` supplies the extension and the name in errors.
Mesh loadMeshFromMemory(std::span<const unsigned char> bytes, const std::string& nameForMessages,
                        MeshReport* report = nullptr);

// Writes a mesh (format from the extension; PLY, STL and OFF binary), atomically (the old file or
// the whole new one, mipgloss/io/atomic_write.h). Faces OpenMesh cannot hold (non-manifold ones)
// are left out. Throws MeshError.
void writeMesh(const Mesh& mesh, const std::filesystem::path& path);

// Extensions loadMesh accepts, lower case with the dot (".obj", ...).
std::span<const char* const> meshExtensions();

// The embedded Utah teapot of the default scene (resources/meshes/teapot.obj, see NOTICE.md).
Mesh defaultTeapot();

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
// Per-vertex tangents from the UVs (needs uvs): each triangle's tangent and bitangent from its
// UV gradients, summed by corner angle, Gram–Schmidt against the normal, w the handedness
// (MikkTSpace's rules per vertex, without its splitting of vertices at mirrored UV seams).
// A vertex whose UVs are degenerate gets any unit tangent perpendicular to its normal.
void computeTangents(Mesh& mesh);

}  // namespace mipgloss
