// A material library: named materials an artist keeps across scenes (the library dock, the
// `mipgloss library` commands, `render --library`). A plain value; library_file.h (ui) reads and
// writes it as JSON. Names are unique within a library, compared exactly (case-sensitive, as
// typed); an entry's parameters are a scene Material (scene.h), the same λ meaning (phong.h).
#pragma once

#include "mipgloss/scene/scene.h"

#include <string>
#include <string_view>
#include <vector>

namespace mipgloss {

struct LibraryMaterial {
    std::string name;
    Material material;

    bool operator==(const LibraryMaterial&) const = default;
};

// Why a name cannot be a material's name, or "" when it can: not empty, not only white space, no
// control characters (tabs, new lines), at most kMaxMaterialNameBytes bytes of valid UTF-8.
inline constexpr std::size_t kMaxMaterialNameBytes = 200;
std::string materialNameProblem(std::string_view name);

struct MaterialLibrary {
    std::vector<LibraryMaterial> entries;  // in the user's order

    int indexOf(std::string_view name) const;  // -1 when absent
    const LibraryMaterial* find(std::string_view name) const;
    LibraryMaterial* find(std::string_view name);
    bool contains(std::string_view name) const { return indexOf(name) >= 0; }

    // A free name: `base` or "base 2", "base 3"... (uniqueName in scene.h).
    std::string uniqueName(const std::string& base) const;

    bool operator==(const MaterialLibrary&) const = default;
};

// A file name for `name` (without extension) that every common file system accepts: each
// character outside [A-Za-z0-9 ._-] (every non-ASCII one, and each byte that is not UTF-8) becomes
// one '_', leading dots and trailing dots and spaces are dropped, Windows device names (CON, NUL,
// COM1..., also before a dot: "con.x") get a '_' after them, empty becomes "material", at most 100
// bytes.
std::string fileSafeName(std::string_view name);

// The materials a new user's library starts with (mipgloss-gui on first start, when the user has no
// library file yet): a dozen layered materials people make, from chrome, gold and copper to
// plastic, rubber, clay, ceramic, car paint, satin and varnished wood, with measured-looking values
// (linear base colours; metals' from their F0), and the paper's own mirror and diffuse.
MaterialLibrary starterLibrary();
// fileSafeName for every entry, made unique case-insensitively ("a", "A" -> "a", "A-2") so no two
// entries share a file, in the library's order.
std::vector<std::string> thumbnailFileNames(const MaterialLibrary& library);

}  // namespace mipgloss
