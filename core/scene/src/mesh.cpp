#include "mipgloss/scene/mesh.h"

#include "mesh_validate.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

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
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <streambuf>
#include <string_view>
#include <utility>

// Generated at build time from resources/meshes/teapot.obj (core/cmake/embed_file.cmake).
namespace mipgloss::embedded {
extern const unsigned char default_teapot_obj[];
extern const std::size_t default_teapot_obj_size;
}  // namespace mipgloss::embedded

namespace fs = std::filesystem;

namespace mipgloss {

bool Mesh::isValid() const {
    if (normals.size() != positions.size() || indices.size() % 3 != 0) return false;
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

using meshfile::Declared;
using meshfile::faces;
using meshfile::vertices;
using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;
using OpenMesh::FaceHandle;
using OpenMesh::VertexHandle;

constexpr std::array<const char*, 5> kExtensions = {".obj", ".off", ".ply", ".stl", ".om"};

// A face is zero-area when its height is below this fraction of its longest edge: collinear at
// float precision (a float coordinate holds ~7 digits). Its normal would be noise, its weight nil.
constexpr double kDegenerateHeight = 1e-7;

std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string extensionList() {
    std::string list;
    for (const char* e : kExtensions) list += (list.empty() ? "" : ", ") + std::string(e);
    return list;
}


// ---------------------------------------------------------------------------------------------
// Input plumbing: a read-only, seekable stream over bytes already in memory (the OBJ reader reads
// twice, so it seeks back), which also notes whether a reader tried to read past the end: for
// the binary formats that is how a truncated file shows itself.

class MemoryStreamBuf : public std::streambuf {
public:
    explicit MemoryStreamBuf(std::span<const unsigned char> bytes) {
        // The get area is never written through: no putback buffer, no output.
        char* begin = const_cast<char*>(reinterpret_cast<const char*>(bytes.data()));
        setg(begin, begin, begin + bytes.size());
    }
    bool readPastEnd() const { return readPastEnd_; }

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        readPastEnd_ = true;
        return traits_type::eof();
    }
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override {
        if (!(which & std::ios_base::in)) return pos_type(off_type(-1));
        const off_type size = egptr() - eback();
        const off_type base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? gptr() - eback() : size;
        const off_type target = base + off;
        if (target < 0 || target > size) return pos_type(off_type(-1));
        setg(eback(), eback() + target, egptr());
        return pos_type(target);
    }
    pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
        return seekoff(off_type(pos), std::ios_base::beg, which);
    }

private:
    bool readPastEnd_ = false;
};

// OpenMesh's readers keep state in singletons and report through the global omerr()/omlog()
// streams, so reads are serialised. While one runs, its messages are collected here (for the
// error text) instead of reaching the console.
std::mutex& openMeshMutex() {
    static std::mutex m;
    return m;
}

class CapturedOpenMeshMessages {
public:
    CapturedOpenMeshMessages() {
        for (Route& r : routes_) {
            r.wasConnected = r.stream.disconnect(r.console);
            r.stream.connect(text_);
        }
    }
    ~CapturedOpenMeshMessages() {
        for (Route& r : routes_) {
            r.stream.disconnect(text_);
            if (r.wasConnected) r.stream.connect(r.console);
        }
    }
    CapturedOpenMeshMessages(const CapturedOpenMeshMessages&) = delete;
    CapturedOpenMeshMessages& operator=(const CapturedOpenMeshMessages&) = delete;

    // The first message, trimmed, or "" when OpenMesh said nothing.
    std::string firstLine() const {
        std::istringstream in(text_.str());
        std::string line;
        while (std::getline(in, line)) {
            const auto b = line.find_first_not_of(" \t\r");
            if (b == std::string::npos) continue;
            return line.substr(b, line.find_last_not_of(" \t\r") + 1 - b);
        }
        return {};
    }

private:
    struct Route {
        OpenMesh::mostream& stream;
        std::ostream& console;  // where OpenMesh connects it by default
        bool wasConnected;
    };

    std::ostringstream text_;
    std::array<Route, 3> routes_{Route{::omerr(), std::cerr, false}, Route{::omlog(), std::clog, false},
                                 Route{::omout(), std::cout, false}};
};

// OpenMesh's ImporterT drops a face it dislikes with a console message and goes on; this one
// counts each case so the loader can say what was wrong. It also triangulates polygons itself (a
// fan, each triangle added on its own), and where the half-edge structure cannot take a triangle
// (an edge shared by three faces, a vertex joining two fans) gives that triangle its own copies
// of the vertices and remembers the originals, so the output mesh stays welded as in the file.
class CheckingImporter final : public OpenMesh::IO::ImporterT<OMesh> {
public:
    explicit CheckingImporter(OMesh& mesh) : ImporterT<OMesh>(mesh), target_(mesh) {}

    using ImporterT<OMesh>::add_face;
    FaceHandle add_face(const VHandles& face) override {
        ++facesSeen;
        if (face.size() < 3) {
            ++shortFaces;
            return FaceHandle();
        }
        for (VertexHandle vh : face)
            if (!target_.is_valid_handle(vh)) {
                ++badIndexFaces;
                return FaceHandle();
            }
        corners_.clear();
        for (VertexHandle vh : face) corners_.push_back(static_cast<std::uint32_t>(vh.idx()));
        const std::vector<std::uint32_t> distinct = meshfile::distinctInOrder(corners_);
        if (distinct.size() < 3) {
            ++repeatedVertexFaces;
            return FaceHandle();
        }
        distinct_.clear();
        for (std::uint32_t v : distinct) distinct_.emplace_back(static_cast<int>(v));
        FaceHandle last;
        for (std::size_t i = 1; i + 1 < distinct_.size(); ++i) {
            last = target_.add_face(distinct_[0], distinct_[i], distinct_[i + 1]);
            if (!last.is_valid()) last = addSeparately({distinct_[0], distinct_[i], distinct_[i + 1]});
        }
        return last;
    }

    std::size_t facesSeen = 0;                // faces the reader handed over
    std::size_t shortFaces = 0;               // fewer than 3 vertices
    std::size_t badIndexFaces = 0;            // a vertex index the file does not have
    std::size_t repeatedVertexFaces = 0;      // fewer than 3 distinct vertices: zero area
    std::vector<std::pair<int, int>> copies;  // (copy, original) vertex indices

private:
    FaceHandle addSeparately(const std::array<VertexHandle, 3>& tri) {
        std::array<VertexHandle, 3> own;
        for (std::size_t k = 0; k < 3; ++k) {
            const OMesh::Point p = target_.point(tri[k]);  // a copy: add_vertex may reallocate
            own[k] = target_.add_vertex(p);
            copies.emplace_back(own[k].idx(), tri[k].idx());
        }
        return target_.add_face(own[0], own[1], own[2]);
    }

    OMesh& target_;
    std::vector<std::uint32_t> corners_;
    std::vector<VertexHandle> distinct_;
};


std::string formatName(const std::string& ext) {
    std::string name = ext.substr(1);
    for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return name;
}

bool isZeroArea(const OMesh::Point& a, const OMesh::Point& b, const OMesh::Point& c) {
    const glm::dvec3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]), pc(c[0], c[1], c[2]);
    const glm::dvec3 e0 = pb - pa, e1 = pc - pa, e2 = pc - pb;
    const glm::dvec3 n = glm::cross(e0, e1);
    const double longest2 = std::max({glm::dot(e0, e0), glm::dot(e1, e1), glm::dot(e2, e2)});
    // height = |n| / longest <= k * longest
    return glm::dot(n, n) <= kDegenerateHeight * kDegenerateHeight * longest2 * longest2;
}

constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();

Mesh readMesh(std::span<const unsigned char> bytes, const std::string& file, const std::string& ext,
              MeshReport* report) {
    if (std::find(kExtensions.begin(), kExtensions.end(), ext) == kExtensions.end())
        throw MeshError(file, "unsupported mesh format '" + ext + "' (expected " + extensionList() + ")");
    if (bytes.empty()) throw MeshError(file, "file is empty (0 bytes)");
    const std::string format = formatName(ext);

    std::vector<std::string> warnings;
    Declared declared;
    bool binary = false;
    // PLY, OFF and OM are read by meshfile (mesh_validate.h says why), OBJ and STL by OpenMesh
    // once checked.
    std::optional<meshfile::Polygons> polygons;
    if (ext == ".obj")
        declared = meshfile::checkObj(bytes, file);
    else if (ext == ".stl")
        declared = meshfile::checkStl(bytes, file, binary, warnings);
    else {
        polygons = ext == ".ply"   ? meshfile::parsePly(bytes, file)
                   : ext == ".off" ? meshfile::parseOff(bytes, file)
                                   : meshfile::parseOm(bytes, file);
        declared = {polygons->positions.size(), polygons->faceCount(), 0};
        warnings = std::move(polygons->warnings);
        binary = true;  // read whole: no stream for OpenMesh to fail on
    }

    OMesh om;
    CheckingImporter importer(om);
    OpenMesh::IO::Options options;
    if (ext == ".stl" && binary) options += OpenMesh::IO::Options::Binary;
    bool ok = false, pastEnd = false;
    std::string said;
    {
        std::lock_guard lock(openMeshMutex());
        CapturedOpenMeshMessages messages;
        if (polygons) {
            importer.reserve(static_cast<unsigned>(polygons->positions.size()), 0,
                             static_cast<unsigned>(polygons->faceCount()));
            for (const auto& p : polygons->positions) importer.add_vertex(OMesh::Point(p[0], p[1], p[2]));
            CheckingImporter::VHandles face;
            for (std::size_t f = 0; f < polygons->faceCount(); ++f) {
                face.clear();
                for (std::size_t c = polygons->faceStarts[f]; c < polygons->faceStarts[f + 1]; ++c)
                    face.emplace_back(static_cast<int>(polygons->corners[c]));
                importer.add_face(face);
            }
            ok = true;
        } else {
            MemoryStreamBuf buffer(bytes);
            std::istream in(&buffer);
            ok = OpenMesh::IO::IOManager().read(in, ext, importer, options);
            pastEnd = buffer.readPastEnd();
        }
        said = messages.firstLine();
    }
    const std::string detail = said.empty() ? "" : " (OpenMesh: " + said + ")";
    // Binary readers never look past the data they expect; text readers fail at the end of a
    // short file.
    if (pastEnd && (binary || !ok))
        throw MeshError(file, "truncated or corrupt file: it ends before the data its header announces" + detail);
    if (!ok) throw MeshError(file, "not a readable " + format + " file" + detail);
    if (importer.shortFaces > 0)
        throw MeshError(file, faces(importer.shortFaces) + " with fewer than 3 vertices (truncated or corrupt file)");
    if (importer.badIndexFaces > 0)
        throw MeshError(file, faces(importer.badIndexFaces) + (importer.badIndexFaces == 1 ? " refers" : " refer") +
                                  " to vertices the file does not have (truncated or corrupt file)");

    const std::size_t vertexCount = om.n_vertices();
    const std::size_t fileVertices = vertexCount - importer.copies.size();
    if (declared.vertices && *declared.vertices != fileVertices)
        throw MeshError(file, "truncated or corrupt file: " + vertices(*declared.vertices) + " expected, " +
                                  std::to_string(fileVertices) + " could be read" + detail);
    std::size_t zeroArea = importer.repeatedVertexFaces + declared.zeroAreaFaces;
    if (declared.faces && ext == ".stl") {
        zeroArea += *declared.faces - std::min(*declared.faces, importer.facesSeen);  // merged corners
    } else if (declared.faces && importer.facesSeen + declared.zeroAreaFaces != *declared.faces) {
        throw MeshError(file, "truncated or corrupt file: " + faces(*declared.faces) + " expected, " +
                                  std::to_string(importer.facesSeen + declared.zeroAreaFaces) + " could be read" +
                                  detail);
    }

    // Copies made for non-manifold triangles map back to the file's vertex.
    std::vector<std::uint32_t> original(vertexCount);
    for (std::size_t v = 0; v < vertexCount; ++v) original[v] = static_cast<std::uint32_t>(v);
    for (const auto& [copy, source] : importer.copies)
        original[static_cast<std::size_t>(copy)] = static_cast<std::uint32_t>(source);

    const OMesh::Point* points = om.points();
    std::size_t nonFinite = 0;
    for (std::size_t v = 0; v < vertexCount; ++v)
        if (original[v] == v &&
            !(std::isfinite(points[v][0]) && std::isfinite(points[v][1]) && std::isfinite(points[v][2])))
            ++nonFinite;
    if (nonFinite > 0) throw MeshError(file, vertices(nonFinite) + " with non-finite (NaN or infinite) coordinates");

    // Triangles in file vertex numbers (the importer adds triangles only; a polygon would become a fan).
    Mesh mesh;
    mesh.name = fs::path(file).stem().string();
    mesh.indices.reserve(3 * om.n_faces());
    std::vector<std::uint32_t> loop;
    for (const auto fh : om.faces()) {
        loop.clear();
        const auto first = om.halfedge_handle(fh);
        auto he = first;
        do {
            loop.push_back(original[static_cast<std::size_t>(om.to_vertex_handle(he).idx())]);
            he = om.next_halfedge_handle(he);
        } while (he != first && loop.size() <= vertexCount);
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
    std::vector<std::uint32_t> remap(vertexCount, kUnused);
    for (std::uint32_t i : mesh.indices) remap[i] = 0;
    mesh.positions.reserve(fileVertices);
    for (std::size_t v = 0; v < vertexCount; ++v) {
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
    if (!fs::exists(path, ec)) throw MeshError(path, "file not found");
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
    std::lock_guard<std::mutex> lock(openMeshMutex());
    if (!OpenMesh::IO::write_mesh(out, path.string(), options))
        throw MeshError(path, "could not be written");
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
