#include "mipgloss/scene/mesh.h"

#include "formats/mesh_formats.h"
#include "formats/reading.h"
#include "mipgloss/io/atomic_write.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

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

// Generated at build time from resources/meshes/teapot.obj (core/cmake/embed_file.cmake).
namespace mipgloss::embedded {
extern const unsigned char default_teapot_obj[];
extern const std::size_t default_teapot_obj_size;
}  // namespace mipgloss::embedded

namespace fs = std::filesystem;

namespace mipgloss {

bool Mesh::isValid() const {
    if (normals.size() != positions.size() || indices.size() % 3 != 0) return false;
    if (!uvs.empty() && uvs.size() != positions.size()) return false;
    if (!tangents.empty() && tangents.size() != positions.size()) return false;
    for (const glm::vec2& t : uvs)
        if (!std::isfinite(t.x) || !std::isfinite(t.y)) return false;
    for (std::uint32_t i : indices)
        if (i >= positions.size()) return false;
    auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    for (const glm::vec3& p : positions)
        if (!finite(p)) return false;
    for (const glm::vec3& n : normals)
        if (!finite(n) || std::abs(glm::length(n) - 1.0f) > 1e-4f) return false;
    return true;
}

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

Mesh defaultTeapot() {
    return loadMeshFromMemory({embedded::default_teapot_obj, embedded::default_teapot_obj_size}, "teapot.obj");
}

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

Mesh makeSphere(int rings, int segments) {
    rings = std::max(rings, 2);
    segments = std::max(segments, 3);
    Mesh mesh;
    mesh.name = "sphere";
    // y-up: a vertex at each pole, rings - 1 circles of `segments` vertices between.
    auto direction = [](double theta, double phi) {
        return glm::vec3(
            glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    };
    mesh.positions.emplace_back(0.0f, 1.0f, 0.0f);
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s)
            mesh.positions.push_back(direction(std::numbers::pi * r / rings, 2.0 * std::numbers::pi * s / segments));
    mesh.positions.emplace_back(0.0f, -1.0f, 0.0f);
    const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    auto at = [&](int r, int s) { return static_cast<std::uint32_t>(1 + (r - 1) * segments + s % segments); };
    // Counter-clockwise seen from outside.
    for (int s = 0; s < segments; ++s) mesh.indices.insert(mesh.indices.end(), {0u, at(1, s + 1), at(1, s)});
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s)
            mesh.indices.insert(mesh.indices.end(),
                                {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r + 1, s)});
    for (int s = 0; s < segments; ++s)
        mesh.indices.insert(mesh.indices.end(), {south, at(rings - 1, s), at(rings - 1, s + 1)});
    mesh.normals.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) mesh.normals.push_back(glm::normalize(p));
    computeBounds(mesh);
    return mesh;
}

bool isZeroAreaTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    // A float coordinate holds ~7 digits: a height below 1e-7 of the longest edge is collinear.
    constexpr double kDegenerateHeight = 1e-7;
    const glm::dvec3 pa(a), pb(b), pc(c);
    const glm::dvec3 e0 = pb - pa, e1 = pc - pa, e2 = pc - pb;
    const glm::dvec3 n = glm::cross(e0, e1);
    const double longest2 = std::max({glm::dot(e0, e0), glm::dot(e1, e1), glm::dot(e2, e2)});
    // height = |n| / longest <= k * longest
    return glm::dot(n, n) <= kDegenerateHeight * kDegenerateHeight * longest2 * longest2;
}

void computeVertexNormals(Mesh& mesh) {
    // The cross product of two edges is the face normal scaled by twice the area: summing them
    // weights each face by its area.
    std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
        const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
        sum[a] += n;
        sum[b] += n;
        sum[c] += n;
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t v = 0; v < sum.size(); ++v) {
        const double length = glm::length(sum[v]);
        mesh.normals[v] =
            length > 0.0 && std::isfinite(length) ? glm::vec3(sum[v] / length) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void fillMissingNormals(Mesh& mesh) {
    const auto zero = [](const glm::vec3& n) { return n == glm::vec3(0.0f); };
    if (mesh.normals.size() == mesh.positions.size() && std::none_of(mesh.normals.begin(), mesh.normals.end(), zero))
        return;
    std::vector<glm::vec3> authored = std::move(mesh.normals);
    computeVertexNormals(mesh);
    for (std::size_t v = 0; v < authored.size() && v < mesh.normals.size(); ++v)
        if (!zero(authored[v])) mesh.normals[v] = authored[v];
}

Mesh makeUvSphere(int rings, int segments) {
    rings = std::max(rings, 2);
    segments = std::max(segments, 3);
    Mesh mesh;
    mesh.name = "sphere";
    for (int r = 0; r <= rings; ++r) {
        const double theta = std::numbers::pi * r / rings;
        for (int s = 0; s <= segments; ++s) {
            const double phi = 2.0 * std::numbers::pi * s / segments;
            const glm::vec3 p(glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
            mesh.positions.push_back(p);
            mesh.normals.push_back(r == 0 ? glm::vec3(0, 1, 0) : r == rings ? glm::vec3(0, -1, 0) : glm::normalize(p));
            mesh.uvs.emplace_back(static_cast<float>(s) / static_cast<float>(segments),
                                  static_cast<float>(r) / static_cast<float>(rings));
        }
    }
    auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
    // Counter-clockwise seen from outside (as makeSphere); no triangles of zero area at the poles.
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            if (r > 0) mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1)});
            if (r + 1 < rings) mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r + 1, s + 1), at(r + 1, s)});
        }
    computeBounds(mesh);
    computeTangents(mesh);
    return mesh;
}

void computeTangents(Mesh& mesh) {
    const std::size_t n = mesh.positions.size();
    if (mesh.uvs.size() != n || mesh.normals.size() != n) {
        mesh.tangents.clear();
        return;
    }
    // Per triangle: T, B with dp1 = du1·T + dv1·B, dp2 = du2·T + dv2·B (Lengyel), each corner's
    // share weighted by its angle, as MikkTSpace weights them.
    std::vector<glm::dvec3> tangent(n, glm::dvec3(0.0)), bitangent(n, glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t v[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        const glm::dvec3 p0(mesh.positions[v[0]]), p1(mesh.positions[v[1]]), p2(mesh.positions[v[2]]);
        const glm::dvec2 t0(mesh.uvs[v[0]]), t1(mesh.uvs[v[1]]), t2(mesh.uvs[v[2]]);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
        const glm::dvec2 d1 = t1 - t0, d2 = t2 - t0;
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20) || !std::isfinite(det)) continue;
        const glm::dvec3 ft = (e1 * d2.y - e2 * d1.y) / det;
        const glm::dvec3 fb = (e2 * d1.x - e1 * d2.x) / det;
        const glm::dvec3 ps[3] = {p0, p1, p2};
        for (int c = 0; c < 3; ++c) {
            const glm::dvec3 a = ps[(c + 1) % 3] - ps[c], b = ps[(c + 2) % 3] - ps[c];
            const double la = glm::length(a), lb = glm::length(b);
            if (!(la > 0.0 && lb > 0.0)) continue;
            const double angle = std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
            tangent[v[c]] += angle * ft;
            bitangent[v[c]] += angle * fb;
        }
    }
    mesh.tangents.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 normal(mesh.normals[i]);
        glm::dvec3 tan = tangent[i] - normal * glm::dot(normal, tangent[i]);
        double length = glm::length(tan);
        if (!(length > 1e-12) || !std::isfinite(length)) {
            // Any direction perpendicular to the normal.
            tan = glm::cross(std::abs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), normal);
            length = glm::length(tan);
        }
        tan /= length;
        const double handedness = glm::dot(glm::cross(normal, tan), bitangent[i]) < 0.0 ? -1.0 : 1.0;
        mesh.tangents[i] = glm::vec4(glm::vec3(tan), static_cast<float>(handedness));
    }
}

void computeBounds(Mesh& mesh) {
    if (mesh.positions.empty()) {
        mesh.bounds = {};
        return;
    }
    Bounds b{mesh.positions[0], mesh.positions[0]};
    for (const glm::vec3& p : mesh.positions) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    mesh.bounds = b;
}

}  // namespace mipgloss
