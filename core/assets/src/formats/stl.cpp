// The STL reader, ASCII and binary (formats/mesh_formats.h).
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
#include <unordered_map>
#include <vector>

namespace mipgloss::meshfile {

namespace {

// STL stores each triangle's corners as coordinates; corners at the same position are one vertex
// (welded by exact value, -0 and +0 alike), numbered in the order they first appear, so the mesh
// is connected and its normals smooth where the surface is.
class StlWelder {
public:
    explicit StlWelder(Polygons& out) : out_(out) {}
    void reserve(std::size_t triangles) {
        out_.corners.reserve(3 * triangles);
        out_.faceStarts.reserve(triangles + 1);
        index_.reserve(triangles);  // a closed triangle mesh has about half as many vertices
    }
    void corner(const std::array<float, 3>& p) {
        Key key{};
        for (std::size_t c = 0; c < 3; ++c) {
            const float v = p[c] + 0.0f;  // -0 becomes +0
            std::memcpy(&key[c], &v, sizeof v);
        }
        const auto [it, added] = index_.try_emplace(key, static_cast<std::uint32_t>(out_.positions.size()));
        if (added) out_.positions.push_back(p);
        out_.corners.push_back(it->second);
        if (out_.corners.size() % 3 == 0) out_.faceStarts.push_back(out_.corners.size());
    }

private:
    using Key = std::array<std::uint32_t, 3>;
    struct Hash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = 0x9e3779b97f4a7c15ull;
            for (std::uint32_t v : k) h = (h ^ v) * 0xff51afd7ed558ccdull;
            return static_cast<std::size_t>(h ^ (h >> 32));
        }
    };
    Polygons& out_;
    std::unordered_map<Key, std::uint32_t, Hash> index_;
};

// ASCII STL: three "vertex" lines after each "outer loop"; a facet cut short, or a file without
// its "endsolid", is a truncated file.
Polygons parseAsciiStl(std::span<const unsigned char> bytes, const std::string& file) {
    LineScanner lines(bytes);
    Polygons out;
    StlWelder weld(out);
    std::size_t nonFinite = 0, firstNonFiniteLine = 0;
    bool ended = false;  // an "endsolid" after the last facet: the file is whole
    while (!lines.done()) {
        const std::string_view line = lines.next();
        if (line.find("endsolid") != std::string_view::npos || line.find("ENDSOLID") != std::string_view::npos) {
            ended = true;
            continue;
        }
        if (line.find("outer") == std::string_view::npos && line.find("OUTER") == std::string_view::npos) continue;
        ended = false;
        const std::size_t facetLine = lines.lineNumber();
        for (int k = 0; k < 3; ++k) {
            std::string_view rest = lines.done() ? std::string_view{} : lines.next();
            const std::string_view key = nextToken(rest);
            std::array<float, 3> p{};
            bool finite = true;
            if ((key != "vertex" && key != "VERTEX") || !parseXyz(rest, finite, p))
                throw MeshError(
                    file, atLine(facetLine) + "a facet without three readable vertices (truncated or corrupt file)");
            if (!finite && nonFinite++ == 0) firstNonFiniteLine = lines.lineNumber();
            weld.corner(p);
        }
    }
    if (!ended) throw MeshError(file, "truncated or corrupt file: the ASCII STL does not end with 'endsolid'");
    if (nonFinite > 0)
        throw MeshError(file, vertices(nonFinite) + " with non-finite (NaN or infinite) coordinates, first at line " +
                                  std::to_string(firstNonFiniteLine));
    return out;
}

}  // namespace

// STL comes as text or binary with nothing but the size to tell them apart (binary headers may
// start with "solid" too): binary is 84 bytes plus 50 per triangle, the count at offset 80.
Polygons parseStl(std::span<const unsigned char> bytes, const std::string& file) {
    const std::uint64_t triangles = bytes.size() >= 84 ? readLe32(bytes, 80) : 0;
    const std::uint64_t binarySize = 84 + 50 * triangles;
    const bool binary = bytes.size() >= 84 && bytes.size() == binarySize;
    if (!binary && startsWithWord(bytes, "solid") && !firstBinaryByte(bytes)) return parseAsciiStl(bytes, file);
    if (bytes.size() < 84)
        throw MeshError(file, "not an STL file: too short for binary STL (" + std::to_string(bytes.size()) +
                                  " bytes) and not ASCII STL (no 'solid')");
    if (bytes.size() < binarySize)
        throw MeshError(file, "truncated or corrupt binary STL: the header announces " + std::to_string(triangles) +
                                  " triangles (" + std::to_string(binarySize) + " bytes), the file has " +
                                  std::to_string(bytes.size()) + " bytes");
    Polygons out;
    if (bytes.size() > binarySize)
        out.warnings.push_back(file + ": " + std::to_string(bytes.size() - binarySize) +
                               " bytes after the last triangle ignored");
    StlWelder weld(out);
    weld.reserve(static_cast<std::size_t>(triangles));
    std::size_t nonFinite = 0;
    for (std::uint64_t t = 0; t < triangles; ++t)
        for (std::size_t k = 0; k < 3; ++k) {  // after the facet normal (12 bytes), three corners
            std::array<float, 3> p{};
            for (std::size_t c = 0; c < 3; ++c) {
                const std::uint32_t raw =
                    readLe32(bytes, static_cast<std::size_t>(84 + 50 * t + 12 * (k + 1) + 4 * c));
                std::memcpy(&p[c], &raw, sizeof raw);
            }
            if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) ++nonFinite;
            weld.corner(p);
        }
    if (nonFinite > 0)
        throw MeshError(file,
                        vertices(nonFinite) + " (triangle corners) with non-finite (NaN or infinite) coordinates");
    return out;
}

}  // namespace mipgloss::meshfile
