// The OFF reader, text and OpenMesh's binary (formats/mesh_formats.h).
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

namespace {

// ---------------------------------------------------------------------------------------------
// OFF (Geomview, www.geomview.org/docs/html/OFF.html): "[ST][C][N][4][n]OFF", for nOFF the
// dimension, then "vertices faces edges", one vertex a line (coordinates first, then what the
// prefixes add), one face a line ("n i1 ... in", then an optional colour); '#' starts a comment.
// Binary ("OFF BINARY"): as OpenMesh writes it (what writeMesh writes), little-endian int32
// counts, float32 coordinates (+ normal, + texture coordinates), int32 "n i1 ... in" per face.

struct OffMagic {
    bool texture = false, colour = false, normal = false, binary = false;
    std::size_t dimension = 3;
};

// Lines of an OFF text with words, comments cut off.
class OffLines {
public:
    explicit OffLines(std::span<const unsigned char> bytes) : lines_(bytes) {}
    std::optional<std::string_view> next() {
        while (!lines_.done()) {
            std::string_view line = lines_.next();
            line = line.substr(0, line.find('#'));
            std::string_view probe = line;
            if (!nextToken(probe).empty()) return line;
        }
        return std::nullopt;
    }
    std::size_t lineNumber() const { return lines_.lineNumber(); }
    std::size_t offset() const { return lines_.offset(); }
    bool lastLineEnded() const { return lines_.lastLineEnded(); }

private:
    LineScanner lines_;
};

}  // namespace

Polygons parseOff(std::span<const unsigned char> bytes, const std::string& file) {
    OffLines lines(bytes);
    auto first = lines.next();
    std::string_view rest = first ? *first : std::string_view{};
    std::string_view magic = nextToken(rest);
    OffMagic kind;
    auto consume = [&](std::string_view prefix) {
        if (!magic.starts_with(prefix)) return false;
        magic.remove_prefix(prefix.size());
        return true;
    };
    kind.texture = consume("ST");
    kind.colour = consume("C");
    kind.normal = consume("N");
    const bool homogeneous = consume("4");
    const bool dimensioned = consume("n");
    if (magic != "OFF") throw MeshError(file, "not an OFF file (it does not start with 'OFF')");
    if (homogeneous) throw MeshError(file, atLine(lines.lineNumber()) + "4OFF (homogeneous coordinates) is not supported");
    std::string_view probe = rest;
    if (nextToken(probe) == "BINARY") {
        kind.binary = true;
        rest = probe;
        if (!nextToken(probe).empty()) throw MeshError(file, atLine(lines.lineNumber()) + "words after 'BINARY'");
    }
    Polygons out;
    if (kind.binary) {
        if (kind.colour || dimensioned)
            throw MeshError(file, "binary OFF with colours or a dimension (C, n) is not supported");
        // Binary data start after the header line.
        ByteReader in(bytes, lines.offset(), false);
        std::array<std::uint64_t, 3> counts{};
        for (auto& c : counts) {
            const auto raw = in.next(4);
            if (!raw) throw MeshError(file, atOffset(in.offset()) + "the file ends in the counts (truncated file)");
            c = *raw;
        }
        const std::uint64_t perVertex = 4 * (3 + (kind.normal ? 3 : 0) + (kind.texture ? 2 : 0));
        if (counts[0] > 0x7fffffff || counts[1] > 0x7fffffff ||
            mulAdd(counts[0], perVertex, 16 * counts[1]) > in.left())
            throw MeshError(file, "truncated or corrupt file: the header announces " +
                                      std::to_string(static_cast<std::int32_t>(counts[0])) + " vertices and " +
                                      std::to_string(static_cast<std::int32_t>(counts[1])) + " faces, " +
                                      std::to_string(in.left()) + " bytes follow");
        out.positions.reserve(static_cast<std::size_t>(counts[0]));
        out.faceStarts.reserve(static_cast<std::size_t>(counts[1]) + 1);
        for (std::uint64_t v = 0; v < counts[0]; ++v) {
            std::array<float, 3> p{};
            for (float& c : p) {
                const auto bits = static_cast<std::uint32_t>(*in.next(4));  // the size check above holds them
                std::memcpy(&c, &bits, sizeof c);
            }
            in.skip(static_cast<std::size_t>(perVertex - 12));
            out.positions.push_back(p);
        }
        for (std::uint64_t f = 0; f < counts[1]; ++f) {
            const std::size_t at = in.offset();
            const auto n = in.next(4);
            if (!n) throw MeshError(file, atOffset(at) + "the file ends in face " + std::to_string(f) + " (truncated file)");
            if (*n < 3 || *n > kMaxFaceCorners || 4 * *n > in.left())
                throw MeshError(file, atOffset(at) + "face " + std::to_string(f) + " has " +
                                          std::to_string(static_cast<std::int32_t>(*n)) +
                                          " vertices (3 to " + std::to_string(kMaxFaceCorners) +
                                          " and within the file expected; truncated or corrupt file)");
            for (std::uint64_t j = 0; j < *n; ++j) {
                const std::size_t indexAt = in.offset();
                const auto index = static_cast<std::uint32_t>(*in.next(4));
                if (index >= counts[0])
                    throw MeshError(file, atOffset(indexAt) + "face " + std::to_string(f) + " refers to vertex " +
                                              std::to_string(static_cast<std::int32_t>(index)) + ", but the file has " +
                                              vertices(counts[0]) + " (corrupt file)");
                out.corners.push_back(index);
            }
            out.faceStarts.push_back(out.corners.size());
        }
        if (in.left() > 0)
            out.warnings.push_back(file + ": " + std::to_string(in.left()) + " bytes after the last face ignored");
        return out;
    }

    // Text. The dimension of nOFF, then the counts, may follow on the magic's line or the next.
    auto nextWord = [&]() -> std::string_view {
        std::string_view word = nextToken(rest);
        while (word.empty()) {
            const auto line = lines.next();
            if (!line) return {};
            rest = *line;
            word = nextToken(rest);
        }
        return word;
    };
    if (dimensioned) {
        const std::string_view d = nextWord();
        if (d != "3")
            throw MeshError(file, atLine(lines.lineNumber()) + "nOFF of dimension '" + shown(d) +
                                      "' (only 3 is supported)");
    }
    std::array<std::uint64_t, 3> counts{};
    for (std::size_t k = 0; k < 2; ++k) {
        const std::string_view word = nextWord();
        const auto value = parseCount(word);
        if (!value)
            throw MeshError(file, atLine(lines.lineNumber()) + "cannot read the OFF " +
                                      (k == 0 ? "vertex" : "face") + " count '" + shown(word) +
                                      "' (a whole number up to " + std::to_string(kMaxElements) + ")");
        counts[k] = *value;
    }
    // The edge count is optional and unused; nothing else may share its line.
    const std::string_view edges = nextToken(rest);
    if (!edges.empty() && !parseCount(edges))
        throw MeshError(file, atLine(lines.lineNumber()) + "cannot read the OFF edge count '" + shown(edges) + "'");
    // The fewest bytes that hold them: "0 0 0\n" a vertex, "3 0 0 0\n" a face.
    const std::uint64_t left = bytes.size() - lines.offset();
    if (mulAdd(counts[0], 6, 8 * counts[1]) > left + 1)
        throw MeshError(file, "truncated or corrupt file: the header announces " + vertices(counts[0]) + " and " +
                                  faces(counts[1]) + " (at least " + std::to_string(mulAdd(counts[0], 6, 8 * counts[1])) +
                                  " bytes), the file has " + std::to_string(left) + " bytes after the counts");
    out.positions.reserve(static_cast<std::size_t>(counts[0]));
    out.faceStarts.reserve(static_cast<std::size_t>(counts[1]) + 1);
    auto ended = [&](const char* what, std::uint64_t i, std::uint64_t n) {
        throw MeshError(file, "truncated or corrupt file: it ends after " + std::to_string(i) + " of " +
                                  std::to_string(n) + " " + what);
    };
    for (std::uint64_t v = 0; v < counts[0]; ++v) {
        const auto line = lines.next();
        if (!line) ended("vertices", v, counts[0]);
        rest = *line;
        std::array<float, 3> p{};
        for (float& c : p) {
            const std::string_view word = nextToken(rest);
            const auto value = parseFloat(word);
            if (!value)
                throw MeshError(file, atLine(lines.lineNumber()) + "vertex " + std::to_string(v) +
                                          " has no three readable coordinates (truncated or corrupt file)");
            c = *value;
        }
        out.positions.push_back(p);
    }
    for (std::uint64_t f = 0; f < counts[1]; ++f) {
        const auto line = lines.next();
        if (!line) ended("faces", f, counts[1]);
        rest = *line;
        const std::string_view word = nextToken(rest);
        const auto n = parseInteger(word);
        if (!n || *n < 3 || *n > static_cast<long long>(kMaxFaceCorners))
            throw MeshError(file, atLine(lines.lineNumber()) + "face " + std::to_string(f) + " has '" +
                                      shown(word) + "' vertices (3 to " + std::to_string(kMaxFaceCorners) +
                                      " expected; truncated or corrupt file)");
        for (long long j = 0; j < *n; ++j) {
            const std::string_view indexWord = nextToken(rest);
            const auto index = parseInteger(indexWord);
            if (!index)
                throw MeshError(file, atLine(lines.lineNumber()) + "face " + std::to_string(f) + " has " +
                                          std::to_string(j) + " of its " + std::to_string(*n) +
                                          " vertex numbers (truncated or corrupt file)");
            if (*index < 0 || static_cast<std::uint64_t>(*index) >= counts[0])
                throw MeshError(file, atLine(lines.lineNumber()) + "face " + std::to_string(f) + " refers to vertex " +
                                          shown(indexWord) + ", but the file has " + vertices(counts[0]) +
                                          " (vertices count from 0; corrupt file)");
            out.corners.push_back(static_cast<std::uint32_t>(*index));
        }
        out.faceStarts.push_back(out.corners.size());
    }
    // A text file cut inside its last number still reads: only the missing line end tells.
    if (counts[1] > 0 && !lines.lastLineEnded() && nextToken(rest).empty())
        throw MeshError(file, atLine(lines.lineNumber()) +
                                  "the file ends inside its last face, with no line end (truncated file)");
    if (lines.next())
        out.warnings.push_back(file + ": " + atLine(lines.lineNumber()) + "lines after the last face ignored");
    return out;
}

}  // namespace mipgloss::meshfile
