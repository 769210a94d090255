// The OBJ reader (formats/mesh_formats.h).
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

// OBJ: positions ("v") and faces ("f", each corner's vertex index before any '/'; negative
// indices count back from the last vertex read). Everything else (texture coordinates, normals,
// groups, materials) is skipped. Every line is checked, with line numbers for the messages.
Polygons parseObj(std::span<const unsigned char> bytes, const std::string& file) {
    if (const auto at = firstBinaryByte(bytes))
        throw MeshError(file, "not an OBJ file: binary data (" + binaryByteText(bytes, *at) + ")");
    LineScanner lines(bytes);
    Polygons out;
    std::size_t nonFinite = 0, firstNonFiniteLine = 0;
    long long maxIndex = 0;
    std::size_t maxIndexLine = 0;
    std::vector<std::uint32_t>& corners = out.corners;
    while (!lines.done()) {
        std::string_view rest = lines.next();
        const std::string_view key = nextToken(rest);
        if (key == "v") {
            std::array<float, 3> p{};
            bool finite = true;
            if (!parseXyz(rest, finite, p))
                throw MeshError(file, atLine(lines.lineNumber()) +
                                          "a vertex without three readable coordinates (truncated or corrupt file)");
            if (!finite && nonFinite++ == 0) firstNonFiniteLine = lines.lineNumber();
            out.positions.push_back(p);
        } else if (key == "f") {
            const std::size_t vertexCount = out.positions.size();
            const std::size_t faceStart = corners.size();
            for (std::string_view token = nextToken(rest); !token.empty() && token[0] != '#';
                 token = nextToken(rest)) {
                const std::string_view index = token.substr(0, token.find('/'));
                long long value = 0;
                const auto [ptr, ec] = std::from_chars(index.data(), index.data() + index.size(), value);
                if (ec != std::errc() || ptr != index.data() + index.size() || value == 0)
                    throw MeshError(file, atLine(lines.lineNumber()) + "cannot read the face index '" +
                                              std::string(token) + "' (corrupt file)");
                if (value < 0) value += static_cast<long long>(vertexCount) + 1;  // counts back from here
                if (value < 1)
                    throw MeshError(file, atLine(lines.lineNumber()) + "the face index " + std::string(token) +
                                              " points before the first vertex (corrupt file)");
                if (value > maxIndex) {
                    maxIndex = value;
                    maxIndexLine = lines.lineNumber();
                }
                if (corners.size() - faceStart == kMaxFaceCorners)
                    throw MeshError(file, atLine(lines.lineNumber()) + "a face with more than " +
                                              std::to_string(kMaxFaceCorners) + " vertices (corrupt file)");
                // Beyond 32 bits it is out of range anyway (the check below says so). Stored from 0.
                corners.push_back(static_cast<std::uint32_t>(std::min<long long>(value, 0xffffffffLL) - 1));
            }
            // A face line cut short is how a truncated file usually ends.
            if (corners.size() - faceStart < 3)
                throw MeshError(file, atLine(lines.lineNumber()) + "a face with only " +
                                          vertices(corners.size() - faceStart) + " (truncated or corrupt file)");
            out.faceStarts.push_back(corners.size());
        }
    }
    if (nonFinite > 0)
        throw MeshError(file, vertices(nonFinite) + " with non-finite (NaN or infinite) coordinates, first at line " +
                                  std::to_string(firstNonFiniteLine));
    if (maxIndex > static_cast<long long>(out.positions.size()))
        throw MeshError(file, atLine(maxIndexLine) + "a face refers to vertex " + std::to_string(maxIndex) +
                                  ", but the file has only " + vertices(out.positions.size()) +
                                  " (truncated or corrupt file)");
    return out;
}

}  // namespace mipgloss::meshfile
