// The OM reader, OpenMesh's own binary format (formats/mesh_formats.h).
#include "formats/mesh_formats.h"
#include "formats/reading.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <string>
#include <vector>

namespace mipgloss::meshfile {

// OM (OpenMesh's own): "OM", the mesh kind, the version, then little-endian vertex, face and
// edge counts; chunks follow. OpenMesh reserves what the counts say and reads each chunk for
// that many entities, so the counts must fit the file: a position is 3 floats, and every face
// and edge takes at least a byte of some chunk.
void checkOm(std::span<const unsigned char> bytes, const std::string& file) {
    if (bytes.size() < 16 || bytes[0] != 'O' || bytes[1] != 'M')
        throw MeshError(file, "not an OpenMesh .om file (no 'OM' signature)");
    const std::uint64_t vertexCount = readLe32(bytes, 4), faceCount = readLe32(bytes, 8),
                        edgeCount = readLe32(bytes, 12);
    const std::uint64_t size = bytes.size();
    if (12 * vertexCount > size || faceCount > size || edgeCount > size)
        throw MeshError(file, "truncated or corrupt file: the header announces " + vertices(vertexCount) + ", " +
                                  faces(faceCount) + " and " + std::to_string(edgeCount) + " edges, more than " +
                                  std::to_string(size) + " bytes can hold");
}


// ---------------------------------------------------------------------------------------------
// OM, read here (OpenMesh's OMReader reserves and loops on whatever the header and the chunks
// say, trusts every index, and frees twice on some damaged files). The layout, from OpenMesh's
// OMFormat.hh and what OpenMesh 9's writer writes (version 2.2):
//   header: "OM", the mesh kind ('T', 'Q' or 'P'), the version byte (major << 5 | minor), then
//           uint32 vertex, face and edge counts (little-endian);
//   chunks: a uint16 chunk header (bit 0 reserved, 1 named, 2-4 entity, 5-8 type, 9 signed,
//           10 float, 11-13 dimension - 1, 14-15 the size code), its name when named (a length
//           byte and the bytes), then the data: one value per entity (per vertex, face, edge,
//           halfedge, or one for the mesh);
//   the end: a chunk whose entity is the sentinel (7).
// From version 2.0 the faces are halfedges: per edge two (next, to-vertex, face) triples,
// per face one of its halfedges, per vertex one outgoing halfedge, as signed integers of the
// chunk's size code; a face's corners are the to-vertices round its next-loop.
namespace {

enum : unsigned {
    kOmVertex = 0, kOmMesh = 1, kOmFace = 2, kOmEdge = 4, kOmHalfedge = 6, kOmSentinel = 7,
    kOmPosition = 0, kOmNormal = 1, kOmTexcoord = 2, kOmStatus = 3, kOmColour = 4, kOmCustom = 6, kOmTopology = 7,
};

constexpr std::uint8_t omVersion(unsigned major, unsigned minor) {
    return static_cast<std::uint8_t>((major & 7u) << 5 | (minor & 31u));
}
std::string omVersionText(std::uint8_t v) { return std::to_string(v >> 5) + "." + std::to_string(v & 31u); }

struct OmChunk {
    std::size_t at = 0;  // the chunk header's offset
    bool named = false;
    unsigned entity = 0, type = 0, isFloat = 0, dim = 0, bits = 0;
};

const char* omEntityName(unsigned e) {
    switch (e) {
    case kOmVertex: return "vertex";
    case kOmMesh: return "mesh";
    case kOmFace: return "face";
    case kOmEdge: return "edge";
    case kOmHalfedge: return "halfedge";
    default: return "unknown";
    }
}

// "a vertex", "an edge", ... for the messages.
std::string aEntity(unsigned e) { return std::string(e == kOmEdge ? "an " : "a ") + omEntityName(e); }

// Topology as the file holds it, every value range-checked when read.
struct OmTopology {
    std::vector<std::int64_t> next, to, face;  // per halfedge
    std::vector<std::int64_t> faceHalfedge;    // per face
    std::size_t halfedgeAt = 0, faceAt = 0;     // data offsets, for the messages
    std::size_t intSize = 0, faceIntSize = 0;
    bool haveHalfedges = false, haveFaces = false, haveVertices = false;
};

}  // namespace

Polygons parseOm(std::span<const unsigned char> bytes, const std::string& file) {
    checkOm(bytes, file);  // the signature, and counts no file of this size can hold
    const char kind = static_cast<char>(bytes[2]);
    if (kind != 'T' && kind != 'Q' && kind != 'P')
        throw MeshError(file, atOffset(2) + "unknown OM mesh kind '" + shown(std::string_view(&kind, 1)) +
                                  "' (expected T, Q or P; corrupt file)");
    const std::uint8_t version = bytes[3];
    // 2.0 brought the halfedge topology read here, 2.2 (OpenMesh 9) the type names of custom
    // properties; before 2.0 faces were vertex lists, after 2.2 is not yet written.
    if (version < omVersion(2, 0) || version > omVersion(2, 2))
        throw MeshError(file, atOffset(3) + "OM version " + omVersionText(version) +
                                  " is not supported (this reads 2.0 to 2.2, what OpenMesh 7 to 9 write; re-save "
                                  "the file with OpenMesh 9, or as OBJ or PLY)");
    const std::uint64_t vertexCount = readLe32(bytes, 4), faceCount = readLe32(bytes, 8),
                        edgeCount = readLe32(bytes, 12), halfedgeCount = 2 * edgeCount;
    auto entityCount = [&](unsigned entity) -> std::uint64_t {
        switch (entity) {
        case kOmVertex: return vertexCount;
        case kOmFace: return faceCount;
        case kOmEdge: return edgeCount;
        case kOmHalfedge: return halfedgeCount;
        default: return 1;  // the mesh
        }
    };

    ByteReader in(bytes, 16, false);
    auto fail = [&](std::size_t at, const std::string& what) { throw MeshError(file, atOffset(at) + what); };
    // A named chunk's name, or a custom property's type name: a length byte, then the bytes.
    auto skipName = [&](const char* what) {
        const std::size_t at = in.offset();
        const auto length = in.next(1);
        if (!length || *length > in.left())
            fail(at, std::string("the file ends inside a ") + what + " (truncated or corrupt file)");
        in.skip(static_cast<std::size_t>(*length));
    };
    // `count` values of `size` bytes must follow; returns where they start.
    auto need = [&](const OmChunk& c, std::uint64_t count, std::uint64_t size) {
        const std::uint64_t total = mulAdd(count, size, 0);
        if (total > in.left())
            fail(c.at, aEntity(c.entity) + " chunk of " + std::to_string(count) + " x " +
                           std::to_string(size) + " bytes, but " + std::to_string(in.left()) +
                           " bytes follow (truncated or corrupt file)");
        return in.offset();
    };
    // A signed integer of 1, 2, 4 or 8 bytes (the topology's size code), read as OpenMesh does.
    auto signedValue = [&](std::size_t size) -> std::int64_t {
        const std::uint64_t raw = *in.next(size);  // `need` checked the bytes are there
        switch (size) {
        case 1: return static_cast<std::int8_t>(raw);
        case 2: return static_cast<std::int16_t>(raw);
        case 4: return static_cast<std::int32_t>(raw);
        default: return static_cast<std::int64_t>(raw);
        }
    };
    // `count` indices, each in [low, high): where one is not, the file is refused at its offset.
    auto readIndices = [&](const OmChunk& c, std::vector<std::int64_t>& out, std::uint64_t count, std::int64_t low,
                           std::uint64_t high, const char* what) {
        const std::size_t size = std::size_t{1} << c.bits;
        need(c, count, size);
        out.reserve(static_cast<std::size_t>(count));
        for (std::uint64_t i = 0; i < count; ++i) {
            const std::size_t at = in.offset();
            const std::int64_t v = signedValue(size);
            if (v < low || (v >= 0 && static_cast<std::uint64_t>(v) >= high))
                fail(at, std::string(what) + " " + std::to_string(v) + " out of range (" + std::to_string(low) +
                             " to " + std::to_string(static_cast<std::int64_t>(high) - 1) + "; corrupt file)");
            out.push_back(v);
        }
    };

    Polygons out;
    OmTopology topo;
    bool havePositions = false, ended = false;
    while (!ended) {
        if (in.left() == 0) fail(in.offset(), "the file ends without the OM end marker (truncated file)");
        OmChunk c;
        c.at = in.offset();
        const auto raw = in.next(2);
        if (!raw) fail(c.at, "the file ends inside a chunk header (truncated file)");
        const auto h = static_cast<unsigned>(*raw);
        c.named = (h >> 1) & 1u;
        c.entity = (h >> 2) & 7u;
        c.type = (h >> 5) & 15u;
        c.isFloat = (h >> 10) & 1u;
        c.dim = ((h >> 11) & 7u) + 1;
        c.bits = (h >> 14) & 3u;
        if (h & 1u) fail(c.at, "a chunk header with its reserved bit set (corrupt file)");
        if (c.entity == kOmSentinel) {
            ended = true;
            break;
        }
        if (c.entity != kOmVertex && c.entity != kOmMesh && c.entity != kOmFace && c.entity != kOmEdge &&
            c.entity != kOmHalfedge)
            fail(c.at, "a chunk of unknown entity " + std::to_string(c.entity) + " (corrupt file)");
        if (c.named) skipName("property name");
        const std::uint64_t count = entityCount(c.entity);
        const std::string where = aEntity(c.entity) + " ";
        switch (c.type) {
        case kOmCustom: {
            // A custom property: (from 2.2) its type name, a uint32 byte count, the bytes. Skipped.
            if (version > omVersion(2, 1)) skipName("property type name");
            const std::size_t at = in.offset();
            const auto size = in.next(4);
            if (!size || *size > in.left())
                fail(at, "a custom property of " + (size ? std::to_string(*size) : std::string("?")) + " bytes, but " +
                             std::to_string(in.left()) + " bytes follow (truncated or corrupt file)");
            in.skip(static_cast<std::size_t>(*size));
            break;
        }
        case kOmPosition: {
            if (c.entity != kOmVertex) fail(c.at, "positions for " + where + "chunk (corrupt file)");
            if (havePositions) fail(c.at, "a second position chunk (corrupt file)");
            if (!c.isFloat || c.dim != 3 || c.bits > 1)
                fail(c.at, "positions of " + std::to_string(c.dim) + " " + (c.isFloat ? "floating-point" : "integer") +
                               " values (3 floats or doubles expected; corrupt file)");
            const std::size_t scalar = c.bits == 0 ? 4 : 8;
            need(c, vertexCount, 3 * scalar);
            out.positions.reserve(static_cast<std::size_t>(vertexCount));
            for (std::uint64_t v = 0; v < vertexCount; ++v) {
                std::array<float, 3> p{};
                for (float& x : p) {
                    const std::uint64_t bitsOf = *in.next(scalar);
                    if (scalar == 4) {
                        const auto b32 = static_cast<std::uint32_t>(bitsOf);
                        std::memcpy(&x, &b32, sizeof x);
                    } else {
                        double d;
                        std::memcpy(&d, &bitsOf, sizeof d);
                        x = static_cast<float>(d);
                    }
                }
                out.positions.push_back(p);
            }
            havePositions = true;
            break;
        }
        case kOmTopology: {
            const std::size_t size = std::size_t{1} << c.bits;
            if (c.entity == kOmHalfedge) {
                if (topo.haveHalfedges) fail(c.at, "a second halfedge topology chunk (corrupt file)");
                need(c, halfedgeCount, 3 * size);
                topo.halfedgeAt = in.offset();
                topo.intSize = size;
                topo.next.reserve(static_cast<std::size_t>(halfedgeCount));
                topo.to.reserve(static_cast<std::size_t>(halfedgeCount));
                topo.face.reserve(static_cast<std::size_t>(halfedgeCount));
                for (std::uint64_t he = 0; he < halfedgeCount; ++he) {
                    std::array<std::int64_t, 3> v{};
                    std::array<std::size_t, 3> at{};
                    for (std::size_t k = 0; k < 3; ++k) {
                        at[k] = in.offset();
                        v[k] = signedValue(size);
                    }
                    auto check = [&](std::size_t k, std::int64_t low, std::uint64_t high, const char* what) {
                        if (v[k] < low || (v[k] >= 0 && static_cast<std::uint64_t>(v[k]) >= high))
                            fail(at[k], "halfedge " + std::to_string(he) + " has " + what + " " + std::to_string(v[k]) +
                                            ", but the file has " + std::to_string(high) + " (corrupt file)");
                    };
                    check(0, 0, halfedgeCount, "next halfedge");
                    check(1, 0, vertexCount, "vertex");
                    check(2, -1, faceCount, "face");
                    topo.next.push_back(v[0]);
                    topo.to.push_back(v[1]);
                    topo.face.push_back(v[2]);
                }
                topo.haveHalfedges = true;
            } else if (c.entity == kOmFace) {
                if (topo.haveFaces) fail(c.at, "a second face topology chunk (corrupt file)");
                topo.faceAt = in.offset();
                topo.faceIntSize = size;
                readIndices(c, topo.faceHalfedge, faceCount, 0, halfedgeCount, "a face's halfedge");
                topo.haveFaces = true;
            } else if (c.entity == kOmVertex) {
                if (topo.haveVertices) fail(c.at, "a second vertex topology chunk (corrupt file)");
                std::vector<std::int64_t> outgoing;  // unused: a vertex's halfedge follows from the faces
                readIndices(c, outgoing, vertexCount, -1, halfedgeCount, "a vertex's halfedge");
                topo.haveVertices = true;
            } else {
                fail(c.at, "topology for " + where + "chunk (corrupt file)");
            }
            break;
        }
        case kOmNormal:
        case kOmTexcoord:
        case kOmColour:
        case kOmStatus: {
            // Not used here: skipped by their size. A status is OpenMesh's 32-bit flag word
            // whatever the header says; the others are `dim` scalars of the size code's size.
            if (c.isFloat && c.bits > 2) fail(c.at, "a floating-point size code of 3 (corrupt file)");
            const std::uint64_t size = c.type == kOmStatus ? 4
                                       : c.isFloat         ? c.dim * (std::uint64_t{4} << c.bits)
                                                           : c.dim * (std::uint64_t{1} << c.bits);
            need(c, count, size);
            in.skip(static_cast<std::size_t>(count * size));
            break;
        }
        default:
            fail(c.at, where + "chunk of unknown type " + std::to_string(c.type) + " (corrupt file)");
        }
    }
    if (in.left() > 0)
        out.warnings.push_back(file + ": " + std::to_string(in.left()) + " bytes after the OM end marker ignored");

    if (vertexCount > 0 && !havePositions)
        throw MeshError(file, "the file announces " + vertices(vertexCount) + " but has no positions (corrupt file)");
    if (faceCount > 0 && (!topo.haveHalfedges || !topo.haveFaces))
        throw MeshError(file, "the file announces " + faces(faceCount) + " but has no " +
                                  (topo.haveHalfedges ? "face" : "halfedge") + " topology (corrupt file)");

    // Each face's corners round its loop. A halfedge belongs to one face, so every loop must come
    // back to its start through halfedges of that face only, none visited before: the walks
    // together cost at most one step per halfedge.
    std::vector<bool> visited(topo.next.size(), false);
    for (std::uint64_t f = 0; f < faceCount; ++f) {
        const auto start = static_cast<std::size_t>(topo.faceHalfedge[f]);
        const std::size_t faceAt = topo.faceAt + f * topo.faceIntSize;
        std::size_t he = start;
        std::size_t corners = 0;
        do {
            const std::size_t heAt = topo.halfedgeAt + he * 3 * topo.intSize;
            if (topo.face[he] != static_cast<std::int64_t>(f))
                fail(heAt, "halfedge " + std::to_string(he) + " on face " + std::to_string(f) +
                               "'s loop belongs to face " + std::to_string(topo.face[he]) + " (corrupt file)");
            if (visited[he] || ++corners > kMaxFaceCorners)
                fail(faceAt, "face " + std::to_string(f) + "'s halfedges do not close into a loop (corrupt file)");
            visited[he] = true;
            out.corners.push_back(static_cast<std::uint32_t>(topo.to[he]));
            he = static_cast<std::size_t>(topo.next[he]);
        } while (he != start);
        if (corners < 3)
            fail(faceAt, "face " + std::to_string(f) + " has " + vertices(corners) + " (a face needs 3 or more; corrupt file)");
        out.faceStarts.push_back(out.corners.size());
    }
    return out;
}

}  // namespace mipgloss::meshfile
