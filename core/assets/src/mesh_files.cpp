#include "mipgloss/assets/mesh_files.h"

#include "formats/mesh_formats.h"
#include "formats/reading.h"
#include "mipgloss/io/atomic_write.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>

#include <unistd.h>

namespace fs = std::filesystem;

namespace mipgloss {

namespace {

using meshfile::faces;
using meshfile::lowerExtension;
using meshfile::vertices;
using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;
using OpenMesh::VertexHandle;

constexpr std::array<const char*, 5> kExtensions = {".obj", ".off", ".ply", ".stl", ".om"};

std::string extensionList() {
    std::string list;
    for (const char* e : kExtensions) list += (list.empty() ? "" : ", ") + std::string(e);
    return list;
}


// OpenMesh's writers keep state in singletons (its IOManager), so writes are serialised.
std::mutex& openMeshMutex() {
    static std::mutex m;
    return m;
}

bool isZeroArea(const std::array<float, 3>& a, const std::array<float, 3>& b, const std::array<float, 3>& c) {
    return isZeroAreaTriangle({a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {c[0], c[1], c[2]});
}

constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();

meshfile::Polygons readPolygons(std::span<const unsigned char> bytes, const std::string& file,
                                const std::string& ext) {
    if (ext == ".obj") return meshfile::parseObj(bytes, file);
    if (ext == ".stl") return meshfile::parseStl(bytes, file);
    if (ext == ".ply") return meshfile::parsePly(bytes, file);
    if (ext == ".off") return meshfile::parseOff(bytes, file);
    return meshfile::parseOm(bytes, file);
}

Mesh readMesh(std::span<const unsigned char> bytes, const std::string& file, const std::string& ext,
              MeshReport* report) {
    if (std::find(kExtensions.begin(), kExtensions.end(), ext) == kExtensions.end())
        throw MeshError(file, "unsupported mesh format '" + ext + "' (expected " + extensionList() + ")");
    if (bytes.empty()) throw MeshError(file, "file is empty (0 bytes)");

    meshfile::Polygons polygons = readPolygons(bytes, file, ext);
    std::vector<std::string> warnings = std::move(polygons.warnings);
    const std::size_t fileVertices = polygons.positions.size();
    const auto& points = polygons.positions;
    std::size_t nonFinite = 0;
    for (const auto& p : points)
        if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) ++nonFinite;
    if (nonFinite > 0) throw MeshError(file, vertices(nonFinite) + " with non-finite (NaN or infinite) coordinates");

    // Each face as a fan over its distinct corners, in file vertex numbers; a face of fewer than
    // three distinct corners, or a fan triangle of zero area, is dropped and counted.
    Mesh mesh;
    mesh.name = fs::path(file).stem().string();
    mesh.indices.reserve(3 * polygons.faceCount());
    std::size_t zeroArea = 0;
    for (std::size_t f = 0; f < polygons.faceCount(); ++f) {
        const std::span<const std::uint32_t> face(polygons.corners.data() + polygons.faceStarts[f],
                                                  polygons.faceStarts[f + 1] - polygons.faceStarts[f]);
        const std::vector<std::uint32_t> loop = meshfile::distinctInOrder(face);
        if (loop.size() < 3) {
            ++zeroArea;
            continue;
        }
        for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
            const std::array<std::uint32_t, 3> tri{loop[0], loop[i], loop[i + 1]};
            if (isZeroArea(points[tri[0]], points[tri[1]], points[tri[2]])) {
                ++zeroArea;
                continue;
            }
            mesh.indices.insert(mesh.indices.end(), tri.begin(), tri.end());
        }
    }
    if (mesh.indices.empty()) {
        if (zeroArea > 0) throw MeshError(file, "all " + faces(zeroArea) + " have zero area");
        if (fileVertices == 0) throw MeshError(file, "no vertices and no faces: not a mesh file");
        throw MeshError(file, "no faces, only " + vertices(fileVertices) + " (a point cloud?)");
    }

    // Keep the vertices faces use, in file order.
    std::vector<std::uint32_t> remap(fileVertices, kUnused);
    for (std::uint32_t i : mesh.indices) remap[i] = 0;
    mesh.positions.reserve(fileVertices);
    for (std::size_t v = 0; v < fileVertices; ++v) {
        if (remap[v] == kUnused) continue;
        remap[v] = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.emplace_back(points[v][0], points[v][1], points[v][2]);
    }
    for (std::uint32_t& i : mesh.indices) i = remap[i];
    const std::size_t unused = fileVertices - mesh.positions.size();

    computeVertexNormals(mesh);
    computeBounds(mesh);

    if (zeroArea > 0) warnings.push_back(file + ": dropped " + faces(zeroArea) + " with zero area");
    if (unused > 0) warnings.push_back(file + ": dropped " + vertices(unused) + " no face uses");
    if (report) {
        report->degenerateFacesDropped = zeroArea;
        report->unusedVerticesDropped = unused;
        report->warnings = std::move(warnings);
    }
    return mesh;
}

// readMesh with what the libraries underneath may throw (std::bad_alloc first: the checks bound
// memory to a multiple of the file's size, not to what the machine has) made a MeshError naming
// the file, so every caller's one catch covers every file.
Mesh readMeshNamed(std::span<const unsigned char> bytes, const std::string& file, const std::string& ext,
                   MeshReport* report) {
    try {
        return readMesh(bytes, file, ext, report);
    } catch (const MeshError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw MeshError(file, "not enough memory to read it (" + std::to_string(bytes.size()) + " bytes)");
    } catch (const std::exception& e) {
        throw MeshError(file, std::string("cannot be read: ") + e.what());
    }
}

}  // namespace

Mesh loadMesh(const fs::path& path, MeshReport* report) {
    const std::string file = path.string();
    std::error_code ec;
    if (!fs::exists(path, ec)) throw MeshError(path, kFileNotFound);
    if (fs::is_directory(path, ec)) throw MeshError(path, "is a directory, expected a mesh file");
    const std::string ext = lowerExtension(path);
    if (std::find(kExtensions.begin(), kExtensions.end(), ext) == kExtensions.end())
        throw MeshError(
            path, "unsupported mesh format '" + path.extension().string() + "' (expected " + extensionList() + ")");
    const auto size = fs::file_size(path, ec);
    if (ec) throw MeshError(path, "cannot read the file: " + ec.message());
    if (size == 0) throw MeshError(path, "file is empty (0 bytes)");
    std::vector<unsigned char> bytes;
    try {
        bytes.resize(static_cast<std::size_t>(size));
    } catch (const std::exception&) {
        throw MeshError(path, "not enough memory to read it (" + std::to_string(size) + " bytes)");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
        throw MeshError(path, "cannot read the file");
    return readMeshNamed(bytes, file, ext, report);
}

Mesh loadMeshFromMemory(std::span<const unsigned char> bytes, const std::string& nameForMessages,
                        MeshReport* report) {
    return readMeshNamed(bytes, nameForMessages, lowerExtension(nameForMessages), report);
}

std::span<const char* const> meshExtensions() { return kExtensions; }

void writeMesh(const Mesh& mesh, const fs::path& path) {
    const std::string ext = lowerExtension(path);
    const auto& known = meshExtensions();
    if (std::find_if(known.begin(), known.end(), [&](const char* e) { return ext == e; }) == known.end())
        throw MeshError(path, "cannot write '" + ext + "' files (use " + extensionList() + ")");
    OMesh out;
    std::vector<VertexHandle> handles;
    handles.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) handles.push_back(out.add_vertex(OMesh::Point(p.x, p.y, p.z)));
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
        out.add_face(handles[mesh.indices[i]], handles[mesh.indices[i + 1]], handles[mesh.indices[i + 2]]);
    OpenMesh::IO::Options options;
    if (ext == ".ply" || ext == ".stl" || ext == ".off") options += OpenMesh::IO::Options::Binary;
    // OpenMesh writes into memory (it picks the writer by the extension), and the bytes reach the
    // file atomically like every file mipgloss writes (mipgloss/io/atomic_write.h).
    std::ostringstream bytes(std::ios::out | std::ios::binary);
    {
        std::lock_guard<std::mutex> lock(openMeshMutex());
        if (!OpenMesh::IO::write_mesh(out, bytes, "mesh" + ext, options))
            throw MeshError(path, "could not be written");
    }
    const std::string data = std::move(bytes).str();
    writeAtomically(path, [&](int fd) {
        for (std::size_t done = 0; done < data.size();) {
            const ::ssize_t n = ::write(fd, data.data() + done, data.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) throw MeshError(path, std::string("could not be written: ") + std::strerror(errno));
            done += static_cast<std::size_t>(n);
        }
    });
}

}  // namespace mipgloss
