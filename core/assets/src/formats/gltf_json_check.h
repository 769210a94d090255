// The glTF JSON read once, before tinygltf parses it (issue 34): tinygltf 2.7 recurses once per
// level of nesting (a file nesting 30 000 arrays in its extras overflows the stack) and reads
// every index as a plain int (4294967296 becomes 0, −4 a huge offset). This scan is iterative,
// keeps nothing but the path it is at, and refuses, naming the element by its JSON path:
//   - text that is not JSON (where, in words, not the parser's internals);
//   - nesting deeper than kMaxGltfJsonDepth;
//   - an index (a node's mesh, a primitive's attribute or material, a textureInfo's index, a
//     scene's nodes, ...) that is not a whole number from 0 to 2³¹ − 1;
//   - a size or offset (byteOffset, byteLength, byteStride, count, texCoord) that is not a whole
//     number from 0 to 2⁵³;
//   - a vector (matrix, translation, rotation, scale, the colour factors, offsets, min, max,
//     weights) holding anything but numbers;
//   - a buffer's or image's URI holding an encoded NUL, and a buffer's URI that is absolute or
//     leaves the asset's folder (only the asset's folder is read; an image's such URI is a
//     warning in the reader, its map left out).
// Extras, and extensions the reader does not read, are the author's own: only their nesting is
// checked. What the values mean against each other (an index within its array, the asset
// version) is checked on the parsed model (gltf.cpp).
#pragma once

#include <set>
#include <string>
#include <string_view>

namespace mipgloss::gltfjson {

inline constexpr int kMaxGltfJsonDepth = 64;

// What is wrong, in words: `text` names the JSON path ("nodes[3].mesh is 4294967296: ...") or,
// for text that is not JSON (`notJson`), where ("at line 3, column 7"). Empty text: nothing.
struct Problem {
    std::string text;
    bool notJson = false;
    bool empty() const { return text.empty(); }
};
// `readExtensions` are the extension names whose contents are checked like the core's. With
// `imageUris`, the images' URIs (not data: ones) are added to it, as written and %-decoded.
Problem problem(std::string_view json, const std::set<std::string>& readExtensions,
                std::set<std::string>* imageUris = nullptr);

// A URI's %XX escapes decoded (RFC 3986); a '%' not followed by two hex digits stays as it is.
std::string decodeUri(std::string_view uri);
// True when the relative path `path` (decoded) is absolute (/, \, C:) or climbs out of its
// folder with "..".
bool leavesFolder(std::string_view path);

}  // namespace mipgloss::gltfjson
