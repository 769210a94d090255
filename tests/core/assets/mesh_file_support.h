// What the mesh file tests share (test_mesh_files.cpp, test_mesh_file_errors.cpp): the teapot
// asset, OpenMesh's copy of a mesh for its writers, binary STL written byte by byte.
#pragma once

#include "mesh_files.h"
#include "test_support.h"

#include "mipgloss/scene/mesh.h"

// OpenMesh's writers make the files of the other formats (its include path is the system one; the
// library comes with mipgloss_core, which links it).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace mipgloss::test {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

inline std::filesystem::path teapotAsset() { return asset("meshes/teapot_newell_seg16.obj"); }

// The mesh as OpenMesh holds it, for its writers.
inline OMesh toOpenMesh(const Mesh& mesh) {
    OMesh om;
    std::vector<OMesh::VertexHandle> vh;
    vh.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) vh.push_back(om.add_vertex(OMesh::Point(p.x, p.y, p.z)));
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
        om.add_face(vh[mesh.indices[t]], vh[mesh.indices[t + 1]], vh[mesh.indices[t + 2]]);
    return om;
}

// Binary STL with the given per-facet normal (STL readers must not trust it).
inline std::string binaryStl(const Mesh& mesh, const glm::vec3& facetNormal) {
    std::string bytes(80, ' ');
    append(bytes, static_cast<std::uint32_t>(mesh.triangleCount()));
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        for (float c : {facetNormal.x, facetNormal.y, facetNormal.z}) append(bytes, c);
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) append(bytes, mesh.positions[mesh.indices[t + k]][c]);
        append(bytes, std::uint16_t{0});
    }
    return bytes;
}

}  // namespace mipgloss::test
