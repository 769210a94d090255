// OBJ assets (asset.h): an OBJ's faces split by material into parts with UVs and authored normals,
// and its MTL libraries read into layered materials with texture maps. A reader of its own, not
// parseObj's (obj.cpp), because a part needs what parseObj skips: texture coordinates, normals,
// materials and smoothing groups, and vertices split wherever those differ.
#include "mipgloss/assets/asset.h"

#include "formats/mesh_formats.h"
#include "formats/reading.h"
#include "mipgloss/ibl/specular.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace mipgloss {
namespace {

using meshfile::atLine;
using meshfile::isBlank;
using meshfile::nextToken;
using meshfile::parseFloat;
using meshfile::shown;

// A line of a file, for refusals and warnings that name it.
struct Where {
    const fs::path& file;
    std::size_t line = 0;

    [[noreturn]] void fail(const std::string& what) const { throw AssetError(file, atLine(line) + what); }
    std::string warning(const std::string& what) const { return file.string() + ": " + atLine(line) + what; }
};

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
    while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
    return s;
}

// The end of a statement's words: the line's end or a comment.
bool endOfWords(std::string_view token) { return token.empty() || token[0] == '#'; }

// Binary bytes are refused naming the line they are on, as every other refusal does.
void requireText(std::span<const unsigned char> bytes, const fs::path& file, std::string_view format) {
    const auto at = meshfile::firstBinaryByte(bytes);
    if (!at) return;
    const auto before = bytes.first(*at);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    Where{file, line}.fail("binary data (" + meshfile::binaryByteText(bytes, *at) + "): not an " +
                           std::string(format) + " text file");
}

// A finite number from the next word of `rest`.
float readNumber(std::string_view& rest, const Where& where, std::string_view what) {
    const std::string_view token = nextToken(rest);
    const auto value = parseFloat(token);
    if (!value) where.fail("cannot read the " + std::string(what) + " value '" + shown(token) + "'");
    if (!std::isfinite(*value)) where.fail(std::string(what) + " " + shown(token) + " is not a finite number");
    return *value;
}

// ---------------------------------------------------------------------------------------------
// MTL

struct MtlLibrary {
    std::vector<AssetMaterial> materials;
    std::vector<std::string> warnings;
};

// A material while its statements are read. Ns and Pr both set the roughness, and d and Tr both
// the alpha, so the values wait for the material's end, where the one that wins is chosen.
struct MtlMaterial {
    AssetMaterial out;
    std::optional<float> ns, pr;
    std::optional<float> d, tr;
    bool emissiveColour = false;  // a Ke line
};

// "Kd r g b" (or "Kd r", grey, as the MTL specification allows), each component finite.
Rgb readColour(std::string_view rest, const Where& where, std::string_view what) {
    const float r = readNumber(rest, where, what);
    std::string_view probe = rest;
    if (endOfWords(nextToken(probe))) return Rgb(r);
    const float g = readNumber(rest, where, what);
    const float b = readNumber(rest, where, what);
    return {r, g, b};
}

// The texture statements' options (the MTL specification's "Options for texture map statements"),
// each with how many words follow it. -o, -s and -t take one to three numbers.
struct TextureOption {
    std::string_view name;
    int minWords, maxWords;
    bool numbers;
};
constexpr std::array<TextureOption, 13> kTextureOptions{{
    {"-blendu", 1, 1, false}, {"-blendv", 1, 1, false}, {"-cc", 1, 1, false},
    {"-clamp", 1, 1, false},  {"-type", 1, 1, false},   {"-imfchan", 1, 1, false},
    {"-bm", 1, 1, true},      {"-boost", 1, 1, true},   {"-texres", 1, 1, true},
    {"-mm", 2, 2, true},      {"-o", 1, 3, true},       {"-s", 1, 3, true},
    {"-t", 1, 3, true},
}};

struct TextureStatement {
    TextureRef texture;
    std::optional<float> bumpScale;  // -bm
};

// The words of one option, from the front of `rest`: at most maxWords, and for a numeric option
// only words that read as numbers (so "-o 1 2 tex.png" leaves the path alone).
std::vector<std::string_view> optionWords(std::string_view& rest, const TextureOption& option, const Where& where) {
    std::vector<std::string_view> words;
    while (static_cast<int>(words.size()) < option.maxWords) {
        std::string_view probe = rest;
        const std::string_view word = nextToken(probe);
        const auto number = option.numbers ? parseFloat(word) : std::nullopt;
        if (word.empty() || (option.numbers && !number)) break;
        if (number && !std::isfinite(*number))
            where.fail("the " + std::string(option.name) + " value " + shown(word) + " is not a finite number");
        words.push_back(word);
        rest = probe;
    }
    if (static_cast<int>(words.size()) < option.minWords)
        where.fail("the texture option " + std::string(option.name) + " needs " + std::to_string(option.minWords) +
                   (option.numbers ? " number" : " word") + (option.minWords > 1 ? "s" : ""));
    return words;
}

int imfchanChannel(std::string_view word, const Where& where) {
    if (word == "r") return 0;
    if (word == "g") return 1;
    if (word == "b") return 2;
    // Matte, luminance and depth are single-channel images: their one channel is the first.
    if (word == "m" || word == "l" || word == "z") return 0;
    where.fail("-imfchan " + shown(word) + " is not one of r, g, b, m, l, z");
}

// "map_Kd [options] path": the options, then the rest of the line is the path (it may hold spaces),
// with Windows separators turned and resolved against the library's folder.
TextureStatement readTexture(std::string_view rest, const Where& where, std::string_view key, const fs::path& folder) {
    TextureStatement out;
    for (;;) {
        std::string_view probe = rest;
        const std::string_view word = nextToken(probe);
        const auto option = std::find_if(kTextureOptions.begin(), kTextureOptions.end(),
                                         [&](const TextureOption& o) { return o.name == word; });
        // Anything else starts the path, a file name beginning with '-' included.
        if (option == kTextureOptions.end()) break;
        rest = probe;
        const std::vector<std::string_view> words = optionWords(rest, *option, where);
        if (option->name == "-bm") out.bumpScale = std::clamp(*parseFloat(words[0]), -kMaxNormalScale, kMaxNormalScale);
        if (option->name == "-imfchan") out.texture.channel = imfchanChannel(words[0], where);
    }
    std::string path(trimmed(rest));
    if (path.empty()) where.fail(std::string(key) + " without a file");
    std::replace(path.begin(), path.end(), '\\', '/');
    const fs::path named(path);
    out.texture.file = (named.is_absolute() ? named : folder / named).lexically_normal().string();
    return out;
}

// What the file names once a material's statements are all read (MtlMaterial).
AssetMaterial finished(MtlMaterial m) {
    Layers& layers = m.out.material.layers;
    MaterialMaps& maps = layers.maps;
    // Pr is the roughness itself; Ns is a Phong exponent for renderers without one.
    if (m.pr)
        layers.roughness = *m.pr;
    else if (m.ns)
        layers.roughness = std::clamp(static_cast<float>(exponentToRoughness(*m.ns)), 0.0f, 1.0f);
    // d is the opacity; Tr (1 − d) is the older spelling, and some exporters write it inverted,
    // so where both are there d is the one to trust.
    if (m.d)
        maps.baseAlpha = *m.d;
    else if (m.tr)
        maps.baseAlpha = 1.0f - *m.tr;
    if (maps.baseAlpha < 1.0f) maps.alphaMode = AlphaMode::Blend;
    // The emissive map multiplies the emissive colour: without a Ke line it would multiply 0.
    if (!maps.emissive.empty() && !m.emissiveColour) maps.emissiveFactor = Rgb(1.0f);
    return std::move(m.out);
}

// The map a texture statement sets, or none.
TextureRef* textureNamed(std::string_view key, MaterialMaps& maps) {
    if (key == "map_Kd") return &maps.baseColor;
    if (key == "map_Pr") return &maps.roughness;
    if (key == "map_Pm") return &maps.metallic;
    if (key == "map_Ke") return &maps.emissive;
    // Exporters (Blender's among them) write the tangent-space normal map as a bump map.
    if (key == "bump" || key == "map_Bump" || key == "map_bump" || key == "norm") return &maps.normal;
    return nullptr;
}

// The warning for a texture statement whose map the metallic–roughness model has no place for.
std::optional<std::string> unreadMap(std::string_view key) {
    if (key == "map_Ns") return "map_Ns (a shininess map) is not read; use map_Pr";
    if (key == "map_Ks") return "map_Ks (a specular colour map) is not read: metallic-roughness has no specular colour";
    if (key == "map_d") return "map_d (an alpha map) is not read; the alpha of map_Kd is";
    return std::nullopt;
}

// One statement of the current material.
void readMtlStatement(std::string_view key, std::string_view rest, const Where& where, const fs::path& folder,
                      MtlMaterial& m, std::vector<std::string>& warnings) {
    Layers& layers = m.out.material.layers;
    if (key == "Kd") {
        layers.baseColor = glm::clamp(readColour(rest, where, key), 0.0f, 1.0f);
    } else if (key == "Ke") {
        layers.maps.emissiveFactor = glm::clamp(readColour(rest, where, key), 0.0f, kMaxEmissive);
        m.emissiveColour = true;
    } else if (key == "Ns") {
        const float n = readNumber(rest, where, key);
        if (n < 0.0f) where.fail("Ns is negative (a Phong exponent is at least 0)");
        m.ns = n;
    } else if (key == "Pr") {
        m.pr = std::clamp(readNumber(rest, where, key), 0.0f, 1.0f);
    } else if (key == "Pm") {
        layers.metallic = std::clamp(readNumber(rest, where, key), 0.0f, 1.0f);
    } else if (key == "d") {
        // "-halo" makes the dissolve depend on the view; the opacity after it is all we draw.
        std::string_view probe = rest;
        if (nextToken(probe) == "-halo") rest = probe;
        m.d = std::clamp(readNumber(rest, where, key), 0.0f, 1.0f);
    } else if (key == "Tr") {
        m.tr = std::clamp(readNumber(rest, where, key), 0.0f, 1.0f);
    } else if (const auto warning = unreadMap(key)) {
        warnings.push_back(where.warning(*warning));
    } else if (TextureRef* target = textureNamed(key, layers.maps)) {
        TextureStatement statement = readTexture(rest, where, key, folder);
        *target = std::move(statement.texture);
        if (target == &layers.maps.normal && statement.bumpScale) layers.maps.normalScale = *statement.bumpScale;
    }
    // Ks, the Phong specular colour, has no place in the metallic–roughness model: F0 of the
    // dielectric stays 0.04, a metal's is its Kd. It and every other key are skipped unread.
}

MtlLibrary parseMtlWithWarnings(std::span<const unsigned char> bytes, const fs::path& file, const fs::path& folder) {
    requireText(bytes, file, "MTL");
    MtlLibrary library;
    UniqueNames names;
    std::optional<MtlMaterial> current;
    auto finish = [&] {
        if (current) library.materials.push_back(finished(std::move(*current)));
        current.reset();
    };
    meshfile::LineScanner lines(bytes);
    while (!lines.done()) {
        std::string_view rest = lines.next();
        const std::string_view key = nextToken(rest);
        const Where where{file, lines.lineNumber()};
        if (key == "newmtl") {
            finish();
            current.emplace();
            current->out.name = names.take(std::string(trimmed(rest)));
            current->out.material.layered = true;
        } else if (current && !endOfWords(key)) {
            // Statements before the first newmtl describe no material: skipped.
            readMtlStatement(key, rest, where, folder, *current, library.warnings);
        }
    }
    finish();
    return library;
}

// ---------------------------------------------------------------------------------------------
// OBJ

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// Smoothing keys: a face's group (s N, N >= 1), the file's faces before any "s" line (kSmoothAll:
// one group, as loadMesh smooths a file that says nothing), or a face of its own (s off, s 0:
// −1 − the face's number), so an "off" face shares no computed normal.
constexpr std::int64_t kSmoothAll = 0;
constexpr std::int64_t kSmoothOff = -1;  // the reader's state; each face's key is its own

struct Corner {
    std::size_t position = kNone, uv = kNone, normal = kNone;  // 0-based, kNone: not given
};

// What makes two corners one vertex of a part: the same position, UV and authored normal, and
// without an authored normal, the same smoothing key (the computed normal is shared within it).
struct VertexKey {
    std::size_t position, uv, normal;
    std::int64_t smoothing;
    bool operator==(const VertexKey&) const = default;
};

struct VertexKeyHash {
    std::size_t operator()(const VertexKey& k) const {
        std::size_t h = std::hash<std::size_t>{}(k.position);
        for (std::size_t v : {k.uv, k.normal, static_cast<std::size_t>(k.smoothing)})
            h ^= std::hash<std::size_t>{}(v) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
        return h;
    }
};

// A part while the faces are read. Its normals hold the authored unit normal, or 0 where the
// vertex's normal is to be computed from its faces.
struct PartBuilder {
    std::string name;
    int material = -1;
    Mesh mesh;
    bool anyUv = false;
    std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> vertices;
};

// The file's vertex data as read so far, with the parts the faces go to.
struct ObjReader {
    ObjReader(const fs::path& f, const std::vector<AssetMaterial>& m, const std::unordered_map<std::string, int>& named)
        : file(f), materials(m), materialNamed(named) {}

    const fs::path& file;
    const std::vector<AssetMaterial>& materials;
    const std::unordered_map<std::string, int>& materialNamed;  // as the libraries name them
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uvs;      // v down already
    std::vector<glm::vec3> normals;  // unit, or 0: zero length in the file (computed instead)
    std::vector<PartBuilder> parts;
    UniqueNames partNames;  // a material's name, or the file's stem, which may be one too
    std::unordered_map<int, std::size_t> partOfMaterial;
    int material = -1;
    std::int64_t smoothing = kSmoothAll;  // a group, kSmoothAll or kSmoothOff
    std::size_t faceCount = 0;
    std::size_t zeroArea = 0;
    std::set<std::string> unknownMaterials;
    std::vector<std::string> warnings;
    std::vector<Corner> corners;  // the face being read
};

std::array<float, 3> readXyz(std::string_view rest, const Where& where, std::string_view what) {
    std::array<float, 3> xyz{};
    bool finite = true;
    if (!meshfile::parseXyz(rest, finite, xyz))
        where.fail(std::string(what) + " without three readable coordinates (truncated or corrupt file)");
    if (!finite) where.fail(std::string(what) + " with non-finite (NaN or infinite) coordinates");
    return xyz;
}

void readPosition(ObjReader& r, std::string_view rest, const Where& where) {
    const auto p = readXyz(rest, where, "a vertex");  // a w after them is ignored
    r.positions.emplace_back(p[0], p[1], p[2]);
}

void readNormal(ObjReader& r, std::string_view rest, const Where& where) {
    const auto n = readXyz(rest, where, "a normal");
    const glm::dvec3 d(n[0], n[1], n[2]);
    const double length = glm::length(d);
    r.normals.push_back(length > 0.0 && std::isfinite(length) ? glm::vec3(d / length) : glm::vec3(0.0f));
}

// "vt u [v [w]]", v 0 when missing; stored v down (glTF's convention, Mesh::uvs).
void readUv(ObjReader& r, std::string_view rest, const Where& where) {
    const float u = readNumber(rest, where, "texture coordinate");
    std::string_view probe = rest;
    const float v = endOfWords(nextToken(probe)) ? 0.0f : readNumber(rest, where, "texture coordinate");
    r.uvs.emplace_back(u, 1.0f - v);
}

// One index of a corner: 1-based or negative (counting back from the last of `count` read so far).
std::size_t resolveIndex(std::string_view text, std::size_t count, std::string_view what, const Where& where) {
    const auto value = meshfile::parseInteger(text);
    if (!value || *value == 0) where.fail("cannot read the face index '" + shown(text) + "' (corrupt file)");
    const long long n = static_cast<long long>(count);
    const long long index = *value < 0 ? *value + n : *value - 1;
    if (index < 0)
        where.fail("the face index " + shown(text) + " points before the first " + std::string(what) +
                   " (corrupt file)");
    if (index >= n)
        where.fail("a face refers to " + std::string(what) + " " + shown(text) + ", but only " + std::to_string(count) +
                   " come before it (truncated or corrupt file)");
    return static_cast<std::size_t>(index);
}

// "v", "v/vt", "v//vn", "v/vt/vn" (an empty vt or vn: not given).
Corner readCorner(const ObjReader& r, std::string_view token, const Where& where) {
    std::array<std::string_view, 3> fields;
    std::size_t count = 0;
    for (std::string_view rest = token;; ++count) {
        if (count == fields.size()) where.fail("cannot read the face corner '" + shown(token) + "' (corrupt file)");
        const std::size_t slash = rest.find('/');
        fields[count] = rest.substr(0, slash);
        if (slash == std::string_view::npos) break;
        rest.remove_prefix(slash + 1);
    }
    Corner c;
    c.position = resolveIndex(fields[0], r.positions.size(), "vertex", where);
    if (!fields[1].empty()) c.uv = resolveIndex(fields[1], r.uvs.size(), "texture coordinate", where);
    if (!fields[2].empty()) c.normal = resolveIndex(fields[2], r.normals.size(), "normal", where);
    return c;
}

// The part the current material's faces go to, made at its first face.
PartBuilder& currentPart(ObjReader& r) {
    const auto [it, added] = r.partOfMaterial.try_emplace(r.material, r.parts.size());
    if (added) {
        PartBuilder part;
        const std::string stem = r.file.stem().string();
        const std::string base = r.material >= 0 ? r.materials[static_cast<std::size_t>(r.material)].name
                                                 : (stem.empty() ? "Mesh" : stem);
        part.name = r.partNames.take(base);
        part.material = r.material;
        r.parts.push_back(std::move(part));
    }
    return r.parts[it->second];
}

std::uint32_t vertexOf(ObjReader& r, PartBuilder& part, const Corner& c, std::int64_t smoothing, const Where& where) {
    const bool authored = c.normal != kNone && r.normals[c.normal] != glm::vec3(0.0f);
    const VertexKey key{c.position, c.uv, authored ? c.normal : kNone, authored ? kSmoothAll : smoothing};
    const auto found = part.vertices.find(key);
    if (found != part.vertices.end()) return found->second;
    if (part.mesh.positions.size() > meshfile::kMaxElements) where.fail("a part with more than 2^32 vertices");
    const auto index = static_cast<std::uint32_t>(part.mesh.positions.size());
    part.vertices.emplace(key, index);
    part.mesh.positions.push_back(r.positions[c.position]);
    part.mesh.uvs.push_back(c.uv != kNone ? r.uvs[c.uv] : glm::vec2(0.0f));
    part.mesh.normals.push_back(authored ? r.normals[c.normal] : glm::vec3(0.0f));
    part.anyUv = part.anyUv || c.uv != kNone;
    return index;
}


// "f c1 c2 c3 ...": a fan of triangles into the current material's part.
void readFace(ObjReader& r, std::string_view rest, const Where& where) {
    r.corners.clear();
    for (std::string_view token = nextToken(rest); !endOfWords(token); token = nextToken(rest)) {
        if (r.corners.size() == meshfile::kMaxFaceCorners)
            where.fail("a face with more than " + std::to_string(meshfile::kMaxFaceCorners) + " vertices (corrupt file)");
        r.corners.push_back(readCorner(r, token, where));
    }
    // A face line cut short is how a truncated file usually ends.
    if (r.corners.size() < 3)
        where.fail("a face with only " + meshfile::vertices(r.corners.size()) + " (truncated or corrupt file)");
    const std::int64_t smoothing = r.smoothing == kSmoothOff ? -1 - static_cast<std::int64_t>(r.faceCount) : r.smoothing;
    ++r.faceCount;
    PartBuilder& part = currentPart(r);
    for (std::size_t i = 1; i + 1 < r.corners.size(); ++i) {
        const std::array<Corner, 3> tri{r.corners[0], r.corners[i], r.corners[i + 1]};
        if (isZeroAreaTriangle(r.positions[tri[0].position], r.positions[tri[1].position], r.positions[tri[2].position])) {
            ++r.zeroArea;
            continue;
        }
        for (const Corner& c : tri) part.mesh.indices.push_back(vertexOf(r, part, c, smoothing, where));
    }
}

// "usemtl NAME": the material of the faces that follow; an empty name is the default material.
void selectMaterial(ObjReader& r, std::string_view rest, const Where& where) {
    const std::string name(trimmed(rest));
    const auto found = r.materialNamed.find(name);
    r.material = found != r.materialNamed.end() ? found->second : -1;
    if (found == r.materialNamed.end() && !name.empty() && r.unknownMaterials.insert(name).second)
        r.warnings.push_back(where.warning("usemtl " + shown(name) +
                                           ": no such material in the libraries read; drawn with the default material"));
}

// "s N", "s off", "s 0": the smoothing group of the faces that follow (off: each face its own).
void selectSmoothing(ObjReader& r, std::string_view rest, const Where& where) {
    const std::string_view token = nextToken(rest);
    if (token == "off") {
        r.smoothing = kSmoothOff;
        return;
    }
    const auto group = meshfile::parseInteger(token);
    if (!group || *group < 0) where.fail("cannot read the smoothing group '" + shown(token) + "'");
    r.smoothing = *group == 0 ? kSmoothOff : *group;
}

// The libraries the mtllib lines name, in order, each once. Read before the faces, so a usemtl
// may come before the mtllib that defines its material.
std::vector<std::string> libraryNames(std::span<const unsigned char> bytes) {
    std::vector<std::string> names;
    std::unordered_set<std::string_view> seen;
    meshfile::LineScanner lines(bytes);
    while (!lines.done()) {
        std::string_view rest = lines.next();
        if (nextToken(rest) != "mtllib") continue;
        for (std::string_view name = nextToken(rest); !endOfWords(name); name = nextToken(rest))
            if (seen.insert(name).second) names.emplace_back(name);
    }
    return names;
}

// The materials of the libraries `mtlFiles` holds, named uniquely across them, and the warnings
// of reading them (a library missing, a map not read).
void readLibraries(std::span<const unsigned char> bytes, const fs::path& file, std::span<const NamedBytes> mtlFiles,
                   Asset& asset, std::unordered_map<std::string, int>& materialNamed) {
    UniqueNames names;
    for (const std::string& name : libraryNames(bytes)) {
        const auto found = std::find_if(mtlFiles.begin(), mtlFiles.end(),
                                        [&](const NamedBytes& f) { return f.name == name; });
        if (found == mtlFiles.end()) {
            asset.warnings.push_back(file.string() + ": material library " + shown(name) +
                                     " not found; its materials are drawn with the default material");
            continue;
        }
        // Texture paths are relative to the library, which the name places relative to the OBJ.
        const fs::path mtlFile = (file.parent_path() / name).lexically_normal();
        MtlLibrary library;
        try {
            library = parseMtlWithWarnings(found->bytes, mtlFile, mtlFile.parent_path());
        } catch (const FileError& e) {
            // Named as the OBJ asked for it (an `mtllib tex.png` refused the whole OBJ naming only
            // the PNG): the OBJ still draws, with the default material where it would have used it.
            asset.warnings.push_back(file.string() + ": material library " + shown(name) + " is not readable (" +
                                     e.what() + "); its materials are drawn with the default material");
            continue;
        }
        asset.warnings.insert(asset.warnings.end(), library.warnings.begin(), library.warnings.end());
        for (AssetMaterial& m : library.materials) {
            // usemtl names the material as its library does; the first of a name is the one.
            materialNamed.try_emplace(m.name, static_cast<int>(asset.materials.size()));
            m.name = names.take(m.name);
            asset.materials.push_back(std::move(m));
        }
    }
}

void readObjLines(ObjReader& r, std::span<const unsigned char> bytes) {
    meshfile::LineScanner lines(bytes);
    while (!lines.done()) {
        std::string_view rest = lines.next();
        const std::string_view key = nextToken(rest);
        const Where where{r.file, lines.lineNumber()};
        if (key == "v") readPosition(r, rest, where);
        else if (key == "vt") readUv(r, rest, where);
        else if (key == "vn") readNormal(r, rest, where);
        else if (key == "f") readFace(r, rest, where);
        else if (key == "usemtl") selectMaterial(r, rest, where);
        else if (key == "s") selectSmoothing(r, rest, where);
        // o and g do not split parts (materials do); mtllib was read first; the rest is skipped.
    }
}

// The part's mesh: computed normals where the file gave none (area-weighted over the faces that
// share the vertex), UVs only when a corner had them, bounds, and tangents for a normal map.
Mesh finishedMesh(PartBuilder& part, bool normalMap) {
    Mesh mesh = std::move(part.mesh);
    mesh.name = part.name;
    fillMissingNormals(mesh);
    if (!part.anyUv) mesh.uvs.clear();
    computeBounds(mesh);
    if (normalMap && !mesh.uvs.empty()) computeTangents(mesh);
    return mesh;
}

}  // namespace

std::vector<AssetMaterial> parseMtl(std::span<const unsigned char> bytes, const fs::path& file,
                                    const fs::path& folder) {
    return parseMtlWithWarnings(bytes, file, folder).materials;
}

Asset loadObjAssetFromMemory(std::span<const unsigned char> bytes, const fs::path& file,
                             std::span<const NamedBytes> mtlFiles) {
    requireText(bytes, file, "OBJ");
    Asset asset;
    std::unordered_map<std::string, int> materialNamed;
    readLibraries(bytes, file, mtlFiles, asset, materialNamed);

    ObjReader r(file, asset.materials, materialNamed);
    readObjLines(r, bytes);
    if (r.faceCount == 0)
        throw AssetError(file, "no faces (" + meshfile::vertices(r.positions.size()) + " and not one face)");
    // Every face gave a triangle or a zero-area count: no triangle anywhere means all were zero-area.
    if (std::all_of(r.parts.begin(), r.parts.end(), [](const PartBuilder& p) { return p.mesh.indices.empty(); }))
        throw AssetError(file, "all " + meshfile::faces(r.zeroArea) + " have zero area: nothing to draw");
    asset.warnings.insert(asset.warnings.end(), r.warnings.begin(), r.warnings.end());
    if (r.zeroArea > 0)
        asset.warnings.push_back(file.string() + ": " +
                                 meshfile::count(r.zeroArea, "degenerate face", "degenerate faces") +
                                 " dropped (zero area)");

    for (PartBuilder& part : r.parts) {
        if (part.mesh.indices.empty()) continue;  // every face of it had zero area
        const bool normalMap =
            part.material >= 0 && !asset.materials[static_cast<std::size_t>(part.material)].material.layers.maps.normal.empty();
        asset.parts.push_back({part.name, std::make_shared<const Mesh>(finishedMesh(part, normalMap)), part.material});
    }
    return asset;
}

}  // namespace mipgloss
