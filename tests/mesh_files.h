// Mesh files written byte by byte for the mesh tests and the import benchmark: binary PLY and OBJ
// text of a Mesh, independent of the importer under test.
#pragma once

#include "mipgloss/scene/mesh.h"

#include <cstdint>
#include <cstdio>
#include <string>

namespace mipgloss::test {

template <typename T>
void append(std::string& bytes, const T& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// Little-endian binary PLY: float positions, one uchar-counted int list per triangle.
inline std::string binaryPly(const Mesh& mesh) {
    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(mesh.vertexCount()) +
                        "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                        std::to_string(mesh.triangleCount()) +
                        "\nproperty list uchar int vertex_indices\nend_header\n";
    bytes.reserve(bytes.size() + 12 * mesh.vertexCount() + 13 * mesh.triangleCount());
    for (const glm::vec3& p : mesh.positions) bytes.append(reinterpret_cast<const char*>(&p), 12);
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        bytes.push_back(3);
        for (std::size_t k = 0; k < 3; ++k) append(bytes, static_cast<std::int32_t>(mesh.indices[t + k]));
    }
    return bytes;
}

// OBJ text: v lines (7 significant digits) and 1-based f lines.
inline std::string objText(const Mesh& mesh) {
    std::string text;
    text.reserve(40 * mesh.vertexCount() + 24 * mesh.triangleCount());
    char line[128];
    for (const glm::vec3& p : mesh.positions) {
        const int n = std::snprintf(line, sizeof line, "v %.7g %.7g %.7g\n", static_cast<double>(p.x),
                                    static_cast<double>(p.y), static_cast<double>(p.z));
        text.append(line, static_cast<std::size_t>(n));
    }
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const int n = std::snprintf(line, sizeof line, "f %u %u %u\n", mesh.indices[t] + 1, mesh.indices[t + 1] + 1,
                                    mesh.indices[t + 2] + 1);
        text.append(line, static_cast<std::size_t>(n));
    }
    return text;
}

}  // namespace mipgloss::test
