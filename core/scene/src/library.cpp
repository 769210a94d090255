#include "mipgloss/scene/library.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <set>

namespace mipgloss {

namespace {

// One UTF-8 sequence at the front of `text`: its code point and length in bytes, or nothing when
// the bytes are not valid UTF-8 (a stray continuation byte, a truncated or overlong sequence, a
// surrogate, beyond U+10FFFF).
struct CodePoint {
    char32_t value;
    std::size_t bytes;
};

std::optional<CodePoint> decodeUtf8(std::string_view text) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    const unsigned char lead = byte(0);
    if (lead < 0x80) return CodePoint{lead, 1};
    std::size_t length = 0;
    char32_t value = 0;
    if ((lead & 0xE0) == 0xC0) {
        length = 2;
        value = lead & 0x1Fu;
    } else if ((lead & 0xF0) == 0xE0) {
        length = 3;
        value = lead & 0x0Fu;
    } else if ((lead & 0xF8) == 0xF0) {
        length = 4;
        value = lead & 0x07u;
    } else {
        return std::nullopt;
    }
    if (text.size() < length) return std::nullopt;
    for (std::size_t i = 1; i < length; ++i) {
        if ((byte(i) & 0xC0) != 0x80) return std::nullopt;
        value = (value << 6) | (byte(i) & 0x3Fu);
    }
    constexpr std::array<char32_t, 5> kSmallest{0, 0, 0x80, 0x800, 0x10000};
    if (value < kSmallest[length] || value > 0x10FFFF || (value >= 0xD800 && value <= 0xDFFF))
        return std::nullopt;
    return CodePoint{value, length};
}

// C0 and C1 controls, DEL, and the Unicode line and paragraph separators: characters that break a
// name across lines or do not show.
bool isControl(char32_t c) {
    return c < 0x20 || (c >= 0x7F && c <= 0x9F) || c == 0x2028 || c == 0x2029;
}

// Unicode's space separators (category Zs) and the zero-width space: what a name of "only white
// space" may be made of once controls are refused.
bool isSpace(char32_t c) {
    return c == 0x20 || c == 0xA0 || c == 0x1680 || (c >= 0x2000 && c <= 0x200B) || c == 0x202F ||
           c == 0x205F || c == 0x3000 || c == 0xFEFF;
}

bool isFileSafe(char32_t c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == ' ' ||
           c == '.' || c == '_' || c == '-';
}

constexpr std::size_t kMaxFileNameBytes = 100;
constexpr const char* kEmptyFileName = "material";

char asciiLower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

std::string asciiLower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](char c) { return asciiLower(c); });
    return text;
}

// Windows refuses these as a file's name before its first dot ("CON", "con.png", "COM1.x"),
// whatever the case.
bool isWindowsDeviceName(std::string_view stem) {
    const std::string lower = asciiLower(std::string(stem));
    if (lower == "con" || lower == "prn" || lower == "aux" || lower == "nul") return true;
    return lower.size() == 4 && (lower.starts_with("com") || lower.starts_with("lpt")) &&
           lower[3] >= '0' && lower[3] <= '9';
}

// Windows drops trailing dots and spaces from file names, so "a." and "a" would be one file.
void dropTrailingDotsAndSpaces(std::string& name) {
    while (!name.empty() && (name.back() == '.' || name.back() == ' ')) name.pop_back();
}

// Cuts `name` to `bytes` (file-safe names are ASCII, so any cut is between characters) and keeps
// it a valid file-safe name.
std::string cutTo(std::string name, std::size_t bytes) {
    if (name.size() > bytes) name.resize(bytes);
    dropTrailingDotsAndSpaces(name);
    return name.empty() ? std::string(kEmptyFileName) : name;
}

}  // namespace

std::string materialNameProblem(std::string_view name) {
    if (name.empty()) return "a material name cannot be empty";
    if (name.size() > kMaxMaterialNameBytes)
        return "a material name is at most " + std::to_string(kMaxMaterialNameBytes) +
               " bytes long; this one has " + std::to_string(name.size());
    bool onlySpace = true;
    for (std::size_t i = 0; i < name.size();) {
        const std::optional<CodePoint> c = decodeUtf8(name.substr(i));
        if (!c) return "a material name must be valid UTF-8 (byte " + std::to_string(i) + " is not)";
        if (isControl(c->value))
            return "a material name cannot contain control characters such as tabs or line breaks";
        onlySpace = onlySpace && isSpace(c->value);
        i += c->bytes;
    }
    if (onlySpace) return "a material name cannot be only white space";
    return {};
}

int MaterialLibrary::indexOf(std::string_view name) const {
    for (std::size_t i = 0; i < entries.size(); ++i)
        if (entries[i].name == name) return static_cast<int>(i);
    return -1;
}

const LibraryMaterial* MaterialLibrary::find(std::string_view name) const {
    const int i = indexOf(name);
    return i < 0 ? nullptr : &entries[static_cast<std::size_t>(i)];
}

LibraryMaterial* MaterialLibrary::find(std::string_view name) {
    const int i = indexOf(name);
    return i < 0 ? nullptr : &entries[static_cast<std::size_t>(i)];
}

std::string MaterialLibrary::uniqueName(const std::string& base) const {
    return mipgloss::uniqueName(base, [this](const std::string& name) { return contains(name); });
}

std::string fileSafeName(std::string_view name) {
    std::string out;
    for (std::size_t i = 0; i < name.size();) {
        // A character outside the safe set becomes one '_' however many bytes it takes; a byte
        // that is not valid UTF-8 becomes one '_' of its own.
        const std::optional<CodePoint> c = decodeUtf8(name.substr(i));
        const std::size_t bytes = c ? c->bytes : 1;
        out += (c && isFileSafe(c->value)) ? static_cast<char>(c->value) : '_';
        i += bytes;
    }
    // A leading dot hides the file on Unix, and "." and ".." are folders.
    const std::size_t firstNotDot = out.find_first_not_of('.');
    out.erase(0, firstNotDot == std::string::npos ? out.size() : firstNotDot);
    out = cutTo(std::move(out), kMaxFileNameBytes);
    const std::size_t stemEnd = std::min(out.find('.'), out.size());
    if (isWindowsDeviceName(std::string_view(out).substr(0, stemEnd))) {
        out.insert(stemEnd, "_");
        out = cutTo(std::move(out), kMaxFileNameBytes);
    }
    return out;
}

std::vector<std::string> thumbnailFileNames(const MaterialLibrary& library) {
    std::vector<std::string> names;
    names.reserve(library.entries.size());
    // Compared in lower case: Windows and macOS file systems do not tell "A" from "a".
    std::set<std::string> taken;
    for (const LibraryMaterial& entry : library.entries) {
        const std::string base = fileSafeName(entry.name);
        std::string name = base;
        for (int n = 2; taken.contains(asciiLower(name)); ++n) {
            const std::string suffix = "-" + std::to_string(n);
            name = cutTo(base, kMaxFileNameBytes - suffix.size()) + suffix;
        }
        taken.insert(asciiLower(name));
        names.push_back(std::move(name));
    }
    return names;
}

MaterialLibrary starterLibrary() {
    MaterialLibrary library;
    auto layered = [&](const char* name, Rgb base, float metallic, float roughness, float coat = 0.0f,
                       float coatRoughness = 0.05f, float specular = 0.04f) {
        Material m;
        m.layered = true;
        m.layers = {base, metallic, roughness, specular, coat, coatRoughness, MaterialMaps{}};
        library.entries.push_back({name, m});
    };
    // Metals: the base colour is F0 (linear sRGB of measured reflectance, as glTF's samples use).
    layered("Chrome", Rgb(0.550f, 0.556f, 0.554f), 1.0f, 0.05f);
    layered("Gold", Rgb(1.000f, 0.766f, 0.336f), 1.0f, 0.25f);
    layered("Copper", Rgb(0.955f, 0.638f, 0.538f), 1.0f, 0.3f);
    layered("Brushed aluminium", Rgb(0.913f, 0.922f, 0.924f), 1.0f, 0.45f);
    // Dielectrics: a coloured matte base under a colourless reflection of F0 0.04 (rubber 0.03).
    layered("Red plastic", Rgb(0.60f, 0.04f, 0.03f), 0.0f, 0.25f);
    layered("White satin plastic", Rgb(0.80f, 0.80f, 0.78f), 0.0f, 0.45f);
    layered("Black rubber", Rgb(0.03f, 0.03f, 0.03f), 0.0f, 0.75f, 0.0f, 0.05f, 0.03f);
    layered("Clay", Rgb(0.45f, 0.28f, 0.20f), 0.0f, 0.9f);
    layered("Satin fabric", Rgb(0.50f, 0.10f, 0.30f), 0.0f, 0.6f);
    // Coated: a clear varnish over the base.
    layered("Glazed ceramic", Rgb(0.85f, 0.84f, 0.80f), 0.0f, 0.4f, 1.0f, 0.03f);
    layered("Blue car paint", Rgb(0.05f, 0.10f, 0.45f), 0.4f, 0.45f, 1.0f, 0.03f);
    layered("Varnished wood", Rgb(0.30f, 0.15f, 0.06f), 0.0f, 0.6f, 0.8f, 0.08f);
    // The paper's single lobes (Figure 1): a mirror and its diffuse (the normal at λ 7).
    Material mirror;
    library.entries.push_back({"Mirror (single lobe)", mirror});
    Material diffuse;
    diffuse.lambda = 7.0f;
    diffuse.mode = LookupMode::Normal;
    library.entries.push_back({"Diffuse (single lobe)", diffuse});
    return library;
}

}  // namespace mipgloss
