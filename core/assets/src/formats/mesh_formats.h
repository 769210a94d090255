// The mesh file readers (internal to mipgloss_assets): pure functions over the bytes, one per
// format and each in its own file here (obj.cpp, stl.cpp, ply.cpp, off.cpp, om.cpp; what they
// share in reading.h), each returning the file's polygons or throwing MeshError with the file name and the line
// or byte offset. The loader (mesh.cpp) turns polygons into a Mesh; nothing else reads the files.
//
// They are ours, not OpenMesh's, because OpenMesh's readers are not written for hostile input:
// its PLY header parser loops forever at the end of a file whose header never ends, indexes the
// element list before any element exists (a "property" line first: a crash), and its PLY and OFF
// body readers reserve whatever counts the header claims and, once a number fails to parse, go on
// "reading" zeros for as many elements and list entries as claimed (4e9 of them: a hang that ends
// in std::bad_alloc); its OBJ reader skips a vertex it cannot read (shifting every later index)
// and drops faces without a word; its ASCII STL reader reads a cut-off facet as a triangle at the
// origin; its OMReader trusts every topology index (a damaged file ended in a double free); and
// all of them report through OpenMesh's global message streams, whose rerouting leaks (its
// mostream::disconnect erases a target without deleting it). So:
//   - OBJ (parseObj): positions and faces, every line checked;
//   - STL (parseStl), ASCII or binary: triangles, corners at one position welded into one vertex;
//   - PLY and OFF (parsePly, parseOff): reading them here is the smaller and the stricter program
//     (a binary face's list size says where the next face starts, so checking the indices means
//     decoding every value);
//   - OM (parseOm): the halfedge topology range-checked and each face's loop walked; the chunks we
//     do not use (normals, colours, texture coordinates, status, custom properties) skipped by
//     their sizes, each checked against the bytes that follow.
// Every check costs time linear in the file size, and no count is trusted before it is compared
// with the bytes that must hold it, so no file costs more memory than a small multiple of its size.
#pragma once

#include "mipgloss/assets/mesh_files.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mipgloss::meshfile {

// The most corners one face may have (OBJ, OFF, PLY): a polygon is triangulated as a fan and its
// repeated corners found by sorting, so this bounds nothing but sense; a larger list is a
// corrupt count.
inline constexpr std::size_t kMaxFaceCorners = 1u << 16;
// The most vertices or faces a file may declare: indices are 32-bit (Mesh::indices).
inline constexpr std::uint64_t kMaxElements = 0xffffffffu;

// A mesh as a file holds it: positions, and faces as runs of vertex indices, every index below
// positions.size() and every face at least 3 corners (the parsers guarantee both).
struct Polygons {
    std::vector<std::array<float, 3>> positions;
    std::vector<std::size_t> faceStarts{0};  // face f is corners[faceStarts[f], faceStarts[f + 1])
    std::vector<std::uint32_t> corners;
    std::vector<std::string> warnings;  // one line each, naming the file

    std::size_t faceCount() const { return faceStarts.size() - 1; }
};

// OBJ: "v" positions and "f" faces (negative indices count back), everything else skipped.
Polygons parseObj(std::span<const unsigned char> bytes, const std::string& file);
// STL, ASCII or binary (told apart by the size): triangles over welded corners.
Polygons parseStl(std::span<const unsigned char> bytes, const std::string& file);
// OM: the signature, and the header's counts against the file size (parseOm's first step).
void checkOm(std::span<const unsigned char> bytes, const std::string& file);

// PLY, ASCII or binary (either byte order), read whole.
Polygons parsePly(std::span<const unsigned char> bytes, const std::string& file);
// OFF ("OFF", "COFF", "NOFF", "STOFF", ... in text; OpenMesh's little-endian "OFF BINARY"), read whole.
Polygons parseOff(std::span<const unsigned char> bytes, const std::string& file);
// OM (OpenMesh's own binary format, versions 2.0 to 2.2: OpenMesh 7 to 9), read whole: positions
// and the faces' halfedge loops; every other chunk skipped by its checked size.
Polygons parseOm(std::span<const unsigned char> bytes, const std::string& file);

// The distinct values of `values` in the order they first appear (by sorting: a face of n corners
// costs n log n, where comparing each corner with the ones before would cost n^2).
std::vector<std::uint32_t> distinctInOrder(std::span<const std::uint32_t> values);

// "1 face", "3 faces", "1 vertex", "2 vertices", "line 7: ".
std::string faces(std::size_t n);
std::string vertices(std::size_t n);
std::string atLine(std::size_t line);

}  // namespace mipgloss::meshfile
