// Mesh files: OBJ, OFF, PLY, STL and OM files read into a Mesh (mipgloss/scene/mesh.h) by our own
// readers (core/assets/src/formats/mesh_formats.h); OpenMesh writes them.
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
#include "mipgloss/scene/mesh.h"

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace mipgloss {

class MeshError : public FileError {
public:
    using FileError::FileError;
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

}  // namespace mipgloss
