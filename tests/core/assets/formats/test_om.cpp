// The OM reader (core/assets/src/formats/om.cpp): against what OpenMesh itself writes and reads, and
// on damaged files (OpenMesh's own OMReader freed twice or crashed on the fuzzer's).
// OpenMesh's colour vectors (VectorT<unsigned char, 3>) are default-constructed uninitialised, so
// GCC warns where these tests request colours, inside the standard library's headers.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "format_test_support.h"
#include "test_support.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::test;
namespace fs = std::filesystem;

TEST(OmValidation, CountsMustFitTheFile) {
    std::string om = "OMTB";
    for (std::uint32_t c : {1000u, 1u, 3u}) put(om, c, false);
    om += std::string(64, '\0');
    const std::string reason = refusal(meshfile::checkOm, om, "t.om");
    EXPECT_CONTAINS(reason, "the header announces 1000 vertices, 1 face and 3 edges, more than 80 bytes can hold");
}


// ---------------------------------------------------------------------------------------------
// OM, read by parseOm (OpenMesh's OMReader freed twice or crashed on the fuzzer's damaged files)

namespace {

using OmTriMesh = OpenMesh::TriMesh_ArrayKernelT<>;
using OmPolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

std::string omRefusal(const std::string& bytes) { return refusal(meshfile::parseOm, bytes, "t.om"); }

// One triangle as OpenMesh 9 writes it (version 2.2, 84 bytes): the header (3 vertices, 1 face,
// 3 edges), positions at 16 (data from 18), halfedge topology at 54 (data from 56: per halfedge
// next, to-vertex, face as int8), vertex topology at 74, face topology at 79 (its halfedge at
// 81), the end marker at 82.
std::string omTriangle() {
    const unsigned char bytes[] = {
        'O', 'M', 'T', 0x42, 3, 0, 0, 0, 1, 0, 0, 0, 3, 0, 0, 0,  //
        0x00, 0x16, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x80, 0x3f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
        0, 0, 0x80, 0x3f, 0, 0, 0, 0,  // positions (0 0 0) (1 0 0) (0 1 0)
        0xf8, 0x16, 2, 1, 0, 5, 0, 0xff, 4, 2, 0, 1, 1, 0xff, 0, 0, 0, 3, 2, 0xff,  // halfedges
        0xe0, 0x06, 5, 1, 3,  // vertices
        0xe8, 0x06, 4,        // faces
        0x1c, 0x00};          // end
    return std::string(reinterpret_cast<const char*>(bytes), sizeof bytes);
}

void putByte(std::string& bytes, std::size_t at, unsigned value) { bytes[at] = static_cast<char>(value); }
void putU16(std::string& bytes, std::size_t at, unsigned value) {
    bytes[at] = static_cast<char>(value & 0xff);
    bytes[at + 1] = static_cast<char>(value >> 8);
}

// The mesh as OpenMesh's reader sees `bytes`: positions, and each face's corners round its loop
// from the face's halfedge (the order parseOm promises).
template <typename OmMesh>
meshfile::Polygons readWithOpenMesh(const std::string& bytes) {
    OmPolyMesh mesh;
    std::istringstream in(bytes);
    OpenMesh::IO::Options options;
    EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, in, ".om", options));
    meshfile::Polygons out;
    for (const auto vh : mesh.vertices()) {
        const auto p = mesh.point(vh);
        out.positions.push_back({p[0], p[1], p[2]});
    }
    for (const auto fh : mesh.faces()) {
        const auto first = mesh.halfedge_handle(fh);
        auto he = first;
        do {
            out.corners.push_back(static_cast<std::uint32_t>(mesh.to_vertex_handle(he).idx()));
            he = mesh.next_halfedge_handle(he);
        } while (he != first);
        out.faceStarts.push_back(out.corners.size());
    }
    return out;
}

template <typename OmMesh>
std::string writtenByOpenMesh(const OmMesh& mesh, OpenMesh::IO::Options options = {}) {
    std::ostringstream out;
    EXPECT_TRUE(OpenMesh::IO::write_mesh(mesh, out, ".om", options));
    return out.str();
}

OmPolyMesh asPolyMesh(const Mesh& m) {
    OmPolyMesh out;
    std::vector<OmPolyMesh::VertexHandle> vh;
    for (const glm::vec3& p : m.positions) vh.push_back(out.add_vertex({p.x, p.y, p.z}));
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3)
        out.add_face(vh[m.indices[i]], vh[m.indices[i + 1]], vh[m.indices[i + 2]]);
    return out;
}

// A 3 x 2 grid of quads with a pentagon beside it: polygons of 4 and 5 corners.
OmPolyMesh quadsAndPentagon() {
    OmPolyMesh m;
    std::vector<OmPolyMesh::VertexHandle> v;
    for (int y = 0; y <= 2; ++y)
        for (int x = 0; x <= 3; ++x) v.push_back(m.add_vertex({float(x), float(y), 0.25f * float(x * y)}));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            m.add_face(std::vector<OmPolyMesh::VertexHandle>{v[std::size_t(y * 4 + x)], v[std::size_t(y * 4 + x + 1)],
                                                           v[std::size_t(y * 4 + x + 5)], v[std::size_t(y * 4 + x + 4)]});
    const auto a = m.add_vertex({4.5f, 0.0f, 0.0f}), b = m.add_vertex({5.0f, 1.0f, 0.0f}),
               c = m.add_vertex({4.5f, 2.0f, 0.0f});
    m.add_face(std::vector<OmPolyMesh::VertexHandle>{v[3], a, b, c, v[11]});
    return m;
}

void expectSameAsOpenMesh(const std::string& bytes, const std::string& what) {
    SCOPED_TRACE(what);
    const meshfile::Polygons ours = meshfile::parseOm(asBytes(bytes), what + ".om");
    const meshfile::Polygons theirs = readWithOpenMesh<OmPolyMesh>(bytes);
    EXPECT_GT(ours.faceCount(), 0u);
    EXPECT_EQ(ours.positions, theirs.positions);
    EXPECT_EQ(ours.faceStarts, theirs.faceStarts);
    EXPECT_EQ(ours.corners, theirs.corners);
    EXPECT_TRUE(ours.warnings.empty());
}

}  // namespace

TEST(OmValidation, ReadsWhatOpenMeshWritesAsOpenMeshReadsIt) {
    expectSameAsOpenMesh(omTriangle(), "triangle");
    // A triangle mesh ('T'), with every optional chunk OpenMesh writes for one: vertex and face
    // normals and colours, texture coordinates, status, and custom properties of a vertex, a
    // face, an edge, a halfedge and the mesh (the last a string), all skipped by their sizes.
    OmTriMesh tet;
    const auto a = tet.add_vertex({0, 0, 0}), b = tet.add_vertex({1, 0, 0}), c = tet.add_vertex({0, 1, 0}),
               d = tet.add_vertex({0, 0, 1});
    tet.add_face(a, c, b);
    tet.add_face(a, b, d);
    tet.add_face(a, d, c);
    tet.add_face(b, c, d);
    expectSameAsOpenMesh(writtenByOpenMesh(tet), "tetrahedron");
    tet.request_vertex_normals();
    tet.request_face_normals();
    tet.request_vertex_colors();
    tet.request_face_colors();
    tet.request_vertex_texcoords2D();
    tet.request_vertex_status();
    tet.request_face_status();
    tet.request_edge_status();
    tet.update_normals();
    for (const auto vh : tet.vertices()) tet.set_color(vh, {1, 2, 3});
    for (const auto fh : tet.faces()) tet.set_color(fh, {4, 5, 6});
    OpenMesh::VPropHandleT<float> vp;
    OpenMesh::FPropHandleT<std::int32_t> fp;
    OpenMesh::EPropHandleT<double> ep;
    OpenMesh::HPropHandleT<std::int16_t> hp;
    OpenMesh::MPropHandleT<std::string> mp;
    tet.add_property(vp, "v:weight");
    tet.add_property(fp, "f:id");
    tet.add_property(ep, "e:length");
    tet.add_property(hp, "h:flag");
    tet.add_property(mp, "m:note");
    tet.property(vp).set_persistent(true);
    tet.property(fp).set_persistent(true);
    tet.property(ep).set_persistent(true);
    tet.property(hp).set_persistent(true);
    tet.mproperty(mp).set_persistent(true);
    tet.property(mp) = "a note of some length";
    OpenMesh::IO::Options all = OpenMesh::IO::Options::VertexNormal;
    all += OpenMesh::IO::Options::FaceNormal;
    all += OpenMesh::IO::Options::VertexColor;
    all += OpenMesh::IO::Options::FaceColor;
    all += OpenMesh::IO::Options::VertexTexCoord;
    all += OpenMesh::IO::Options::Status;
    const std::string full = writtenByOpenMesh(tet, all);
    EXPECT_GT(full.size(), 300u);  // the optional chunks are there
    expectSameAsOpenMesh(full, "tetrahedron with every chunk");
    // Polygons ('P'): quads and a pentagon, each face's corners in OpenMesh's order.
    expectSameAsOpenMesh(writtenByOpenMesh(quadsAndPentagon()), "quads");
    // Real meshes: thousands of vertices, so 16- and 32-bit topology indices.
    for (const char* name : {"meshes/teapot_newell_seg16.obj", "meshes/bunny_npm_lowres.obj"}) {
        const fs::path file = test::asset(name);
        MIPGLOSS_REQUIRE_ASSET(file);
        expectSameAsOpenMesh(writtenByOpenMesh(asPolyMesh(loadMesh(file))), name);
    }
    // Through loadMesh: the quads become two triangles each, the pentagon three.
    const std::string quads = writtenByOpenMesh(quadsAndPentagon());
    EXPECT_EQ(loadMeshFromMemory(asBytes(quads), "quads.om").triangleCount(), 6u * 2u + 3u);
}

TEST(OmValidation, CountsAndChunkSizesAreComparedWithTheBytesThatFollow) {
    // 6 vertices of 12 bytes need 72 bytes; 66 follow the position chunk's header.
    std::string bytes = omTriangle();
    putByte(bytes, 4, 6);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 16: a vertex chunk of 6 x 12 bytes, but 66 bytes follow");
    // A custom property claiming 1000 bytes where 14 follow.
    bytes = omTriangle();
    const std::string custom = std::string("\xc2\x00\x01p\x05" "float", 10) + std::string("\xe8\x03\x00\x00", 4) +
                               std::string(12, '\0');
    bytes.insert(82, custom);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 92: a custom property of 1000 bytes, but 14 bytes follow");
    // A face normal chunk (1 x 12 bytes) with 4 bytes and the end marker after it.
    bytes = omTriangle();
    bytes.insert(82, std::string("\x28\x16\0\0\0\0", 6));
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 82: a face chunk of 1 x 12 bytes, but 6 bytes follow");
    // A name longer than the rest of the file.
    bytes = omTriangle();
    bytes.insert(82, std::string("\xc2\x00\xff", 3));
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 84: the file ends inside a property name");
    // The header's counts beyond the file (checkOm, before any chunk).
    bytes = omTriangle();
    putU16(bytes, 8, 0xffff);
    EXPECT_CONTAINS(omRefusal(bytes), "the header announces 3 vertices, 65535 faces and 3 edges, more than 84 bytes");
}

TEST(OmValidation, UnknownHeaderBitsKindsAndVersionsAreRefused) {
    std::string bytes = omTriangle();
    putU16(bytes, 74, 0x06ec);  // entity 3
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 74: a chunk of unknown entity 3");
    bytes = omTriangle();
    putU16(bytes, 74, 0x06a0);  // vertex, type 5
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 74: a vertex chunk of unknown type 5");
    bytes = omTriangle();
    putU16(bytes, 74, 0x06e1);  // the reserved bit
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 74: a chunk header with its reserved bit set");
    bytes = omTriangle();
    putU16(bytes, 16, 0x0e00);  // positions of 2 floats
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 16: positions of 2 floating-point values");
    bytes = omTriangle();
    putByte(bytes, 2, 'X');
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 2: unknown OM mesh kind 'X'");
    bytes = omTriangle();
    putByte(bytes, 3, 0x43);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 3: OM version 2.3 is not supported");
    putByte(bytes, 3, 0x20);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 3: OM version 1.0 is not supported");
}

TEST(OmValidation, TopologyIsRangeCheckedAndEveryLoopWalkedToItsEnd) {
    std::string bytes = omTriangle();
    putByte(bytes, 57, 9);  // halfedge 0's to-vertex
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 57: halfedge 0 has vertex 9, but the file has 3");
    bytes = omTriangle();
    putByte(bytes, 81, 6);  // the face's halfedge: there are 6 (0 to 5)
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 81: a face's halfedge 6 out of range (0 to 5");
    bytes = omTriangle();
    putByte(bytes, 76, 0xfe);  // vertex 0's halfedge -2 (-1 is "isolated")
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 76: a vertex's halfedge -2 out of range (-1 to 5");
    // Halfedge 2's next made itself: 4 -> 0 -> 2 -> 2 never comes back to 4.
    bytes = omTriangle();
    putByte(bytes, 62, 2);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 81: face 0's halfedges do not close into a loop");
    // Halfedge 0's next made halfedge 1, on the boundary (face -1).
    bytes = omTriangle();
    putByte(bytes, 56, 1);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 59: halfedge 1 on face 0's loop belongs to face -1");
    // A loop of two halfedges: 4 -> 0 -> 4.
    bytes = omTriangle();
    putByte(bytes, 56, 4);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 81: face 0 has 2 vertices (a face needs 3 or more");
}

TEST(OmValidation, TruncatedFilesAreRefusedWhereTheyEnd) {
    std::string bytes = omTriangle();
    bytes.resize(70);  // inside the halfedges
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 54: a halfedge chunk of 6 x 3 bytes, but 14 bytes follow");
    bytes = omTriangle();
    bytes.resize(82);  // no end marker
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 82: the file ends without the OM end marker (truncated file)");
    bytes.resize(83);
    putByte(bytes, 82, 0x1c);
    EXPECT_CONTAINS(omRefusal(bytes), "byte offset 82: the file ends inside a chunk header");
    // Faces announced, no topology for them.
    bytes = omTriangle();
    bytes.resize(54);
    bytes += std::string("\x1c\x00", 2);
    EXPECT_CONTAINS(omRefusal(bytes), "the file announces 1 face but has no halfedge topology");
}
