// Mesh files checked byte by byte before OpenMesh sees them, and the PLY, OFF and OM readers (see
// mesh_validate.h for why).
#include "mesh_validate.h"

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
#include <unordered_map>
#include <string_view>
#include <utility>

namespace mipgloss::meshfile {

namespace {

// "1 face", "3 faces", "1 vertex", "2 vertices".
std::string count(std::size_t n, std::string_view one, std::string_view many) {
    return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

// Text lines, for the OBJ, ASCII STL and OFF checks and the PLY header.
class LineScanner {
public:
    explicit LineScanner(std::span<const unsigned char> bytes)
        : begin_(reinterpret_cast<const char*>(bytes.data())), p_(begin_), end_(begin_ + bytes.size()) {}
    bool done() const { return p_ >= end_; }
    std::size_t lineNumber() const { return line_; }
    // Bytes read so far (the lines returned and their terminators).
    std::size_t offset() const { return static_cast<std::size_t>(p_ - begin_); }
    // Whether the last line returned ended with a line end (not with the end of the file).
    bool lastLineEnded() const { return lastLineEnded_; }
    // The next line without its terminator.
    std::string_view next() {
        const char* b = p_;
        const char* e = static_cast<const char*>(std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_)));
        lastLineEnded_ = e != nullptr;
        if (!e) e = end_;
        p_ = e < end_ ? e + 1 : end_;
        ++line_;
        return {b, static_cast<std::size_t>(e - b)};
    }

private:
    const char* begin_;
    const char* p_;
    const char* end_;
    std::size_t line_ = 0;
    bool lastLineEnded_ = true;
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view nextToken(std::string_view& s) {
    std::size_t b = 0;
    while (b < s.size() && isBlank(s[b])) ++b;
    std::size_t e = b;
    while (e < s.size() && !isBlank(s[e])) ++e;
    std::string_view token = s.substr(b, e - b);
    s.remove_prefix(e);
    return token;
}

// A decimal number as the text formats write it ("+1.5e3", "nan", "inf" included), rounded to
// float as the file's reader would: 1e39 becomes infinite, 1e-50 zero.
std::optional<float> parseFloat(std::string_view token) {
    if (!token.empty() && token[0] == '+') token.remove_prefix(1);
    if (token.empty()) return std::nullopt;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ptr != token.data() + token.size()) return std::nullopt;
    // Beyond double's range from_chars leaves `value` alone; strtod says which way (HUGE_VAL or 0).
    if (ec == std::errc::result_out_of_range)
        value = std::strtod(std::string(token).c_str(), nullptr);
    else if (ec != std::errc())
        return std::nullopt;
    return static_cast<float>(value);
}

// Three readable coordinates at the front of `rest` into `xyz`; `finite` says whether all three are.
bool parseXyz(std::string_view rest, bool& finite, std::array<float, 3>& xyz) {
    finite = true;
    for (float& c : xyz) {
        const auto value = parseFloat(nextToken(rest));
        if (!value) return false;
        c = *value;
        finite = finite && std::isfinite(c);
    }
    return true;
}

// The offset of the first byte that no text file holds (NUL and other control codes), if any.
std::optional<std::size_t> firstBinaryByte(std::span<const unsigned char> bytes) {
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        const unsigned char c = bytes[i];
        if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\v' && c != '\f') || c == 0x7f) return i;
    }
    return std::nullopt;
}

std::string binaryByteText(std::span<const unsigned char> bytes, std::size_t at) {
    char text[64];
    std::snprintf(text, sizeof text, "byte 0x%02x at offset %zu", static_cast<unsigned>(bytes[at]), at);
    return text;
}

}  // namespace

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

namespace {

std::uint32_t readLe32(std::span<const unsigned char> bytes, std::size_t at) {
    return static_cast<std::uint32_t>(bytes[at]) | static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
           static_cast<std::uint32_t>(bytes[at + 2]) << 16 | static_cast<std::uint32_t>(bytes[at + 3]) << 24;
}

bool startsWithWord(std::span<const unsigned char> bytes, std::string_view word) {
    std::size_t i = 0;
    while (i < bytes.size() && (isBlank(static_cast<char>(bytes[i])) || bytes[i] == '\n')) ++i;
    if (bytes.size() - i < word.size()) return false;
    for (std::size_t k = 0; k < word.size(); ++k)
        if (std::tolower(bytes[i + k]) != word[k]) return false;
    return true;
}

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

namespace {

// ---------------------------------------------------------------------------------------------
// Shared by the PLY and OFF readers.

// Numbers read from the file, little- or big-endian.
class ByteReader {
public:
    ByteReader(std::span<const unsigned char> bytes, std::size_t at, bool bigEndian)
        : bytes_(bytes), at_(at), bigEndian_(bigEndian) {}
    std::size_t offset() const { return at_; }
    std::size_t left() const { return bytes_.size() - at_; }
    // The next `size` bytes as an unsigned integer of that size, or nothing at the end of the file.
    std::optional<std::uint64_t> next(std::size_t size) {
        if (left() < size) return std::nullopt;
        std::uint64_t value = 0;
        for (std::size_t k = 0; k < size; ++k) {
            const std::size_t byte = bigEndian_ ? k : size - 1 - k;
            value = value << 8 | bytes_[at_ + byte];
        }
        at_ += size;
        return value;
    }
    void skip(std::size_t size) { at_ += std::min(size, left()); }

private:
    std::span<const unsigned char> bytes_;
    std::size_t at_;
    bool bigEndian_;
};

// Whitespace-separated words of a text body, counting lines for the messages.
class WordReader {
public:
    WordReader(std::span<const unsigned char> bytes, std::size_t at, std::size_t line)
        : p_(reinterpret_cast<const char*>(bytes.data()) + std::min(at, bytes.size())),
          end_(reinterpret_cast<const char*>(bytes.data()) + bytes.size()),
          line_(line) {}
    // The next word, "" at the end of the file.
    std::string_view next() {
        while (p_ < end_ && isSpace(*p_)) line_ += *p_++ == '\n' ? 1 : 0;
        const char* b = p_;
        while (p_ < end_ && !isSpace(*p_)) ++p_;
        return {b, static_cast<std::size_t>(p_ - b)};
    }
    std::size_t line() const { return line_; }
    std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }
    // Whether the file ends right after the last word read, with no line end: cut inside it.
    bool cutAfterLastWord() const { return p_ == end_ && !isSpace(p_[-1]); }
    // Bytes other than white space after the last word read.
    std::size_t wordBytesLeft() const {
        std::size_t n = 0;
        for (const char* q = p_; q < end_; ++q) n += isSpace(*q) ? 0 : 1;
        return n;
    }

private:
    static bool isSpace(char c) { return c == '\n' || isBlank(c); }
    const char* p_;
    const char* end_;
    std::size_t line_;
};

// A word of the file for a message: at most 40 bytes, anything unprintable shown as '?'.
std::string shown(std::string_view word) {
    std::string out(word.substr(0, 40));
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return word.size() > 40 ? out + "..." : out;
}

std::optional<long long> parseInteger(std::string_view token) {
    if (!token.empty() && token[0] == '+') token.remove_prefix(1);
    long long value = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
    return value;
}

// An element count as a header states it: decimal digits only, at most kMaxElements.
std::optional<std::uint64_t> parseCount(std::string_view token) {
    std::uint64_t value = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() || value > kMaxElements)
        return std::nullopt;
    return value;
}

std::string atOffset(std::size_t offset) { return "byte offset " + std::to_string(offset) + ": "; }

// a * b + c, saturating (header counts times record sizes, compared with the file size).
std::uint64_t mulAdd(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
    if (b != 0 && a > (max - c) / b) return max;
    return a * b + c;
}

// ---------------------------------------------------------------------------------------------
// PLY (Turk's format, paulbourke.net/dataformats/ply): "ply", "format ascii|binary_little_endian|
// binary_big_endian 1.0", then "element NAME COUNT" each followed by its "property TYPE NAME" and
// "property list COUNT_TYPE TYPE NAME" lines, "comment"/"obj_info" lines anywhere, "end_header";
// then the elements' values in header order, as text or packed binary.

enum class PlyType : unsigned char { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> plyType(std::string_view name) {
    static constexpr std::pair<std::string_view, PlyType> kNames[] = {
        {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (const auto& [n, t] : kNames)
        if (n == name) return t;
    return std::nullopt;
}

std::size_t plySize(PlyType t) {
    switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
    }
    return 8;
}

bool isInteger(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

// A binary value as a double (every PLY type fits one exactly but float64 itself).
double plyBinaryValue(PlyType t, std::uint64_t raw) {
    switch (t) {
    case PlyType::Int8: return static_cast<std::int8_t>(static_cast<std::uint8_t>(raw));
    case PlyType::Int16: return static_cast<std::int16_t>(static_cast<std::uint16_t>(raw));
    case PlyType::Int32: return static_cast<std::int32_t>(static_cast<std::uint32_t>(raw));
    case PlyType::UInt8:
    case PlyType::UInt16:
    case PlyType::UInt32: return static_cast<double>(raw);
    case PlyType::Float32: {
        const auto bits = static_cast<std::uint32_t>(raw);
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
    }
    case PlyType::Float64: {
        double d;
        std::memcpy(&d, &raw, sizeof d);
        return d;
    }
    }
    return 0.0;
}

// The range of an integer type, for text values.
bool fitsPlyInteger(PlyType t, long long v) {
    switch (t) {
    case PlyType::Int8: return v >= -128 && v <= 127;
    case PlyType::UInt8: return v >= 0 && v <= 255;
    case PlyType::Int16: return v >= -32768 && v <= 32767;
    case PlyType::UInt16: return v >= 0 && v <= 65535;
    case PlyType::Int32: return v >= INT32_MIN && v <= INT32_MAX;
    case PlyType::UInt32: return v >= 0 && v <= 0xffffffffLL;
    default: return true;
    }
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;
    std::optional<PlyType> listCount;  // a list: its count's type
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::size_t line = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    bool binary = false;
    bool bigEndian = false;
    std::vector<PlyElement> elements;
    std::size_t bodyOffset = 0;  // the first byte after the "end_header" line
    std::size_t bodyLine = 0;    // its line number (text bodies)
};

// A header longer than this is not a mesh header (a real one is a few hundred bytes).
constexpr std::size_t kMaxPlyHeaderBytes = 1 << 20;

PlyHeader readPlyHeader(std::span<const unsigned char> bytes, const std::string& file) {
    const std::span<const unsigned char> head = bytes.first(std::min(bytes.size(), kMaxPlyHeaderBytes));
    LineScanner lines(head);
    auto trimmed = [](std::string_view line) {
        while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        return line;
    };
    if (lines.done() || trimmed(lines.next()) != "ply")
        throw MeshError(file, "not a PLY file (it does not start with 'ply')");
    PlyHeader header;
    bool haveFormat = false;
    auto fail = [&](const std::string& what) { throw MeshError(file, atLine(lines.lineNumber()) + what); };
    while (true) {
        if (lines.done())
            throw MeshError(file, "not a readable PLY file: the header has no 'end_header' line" +
                                      std::string(bytes.size() > kMaxPlyHeaderBytes ? " in its first 1 MiB" : "") +
                                      " (truncated or corrupt file)");
        std::string_view rest = trimmed(lines.next());
        const std::string_view key = nextToken(rest);
        if (key == "comment" || key == "obj_info" || key.empty()) continue;
        if (key == "end_header") {
            if (!nextToken(rest).empty()) fail("words after 'end_header'");
            if (!haveFormat) fail("the header has no 'format' line");
            // The body starts after this line's end.
            header.bodyOffset = lines.offset();
            header.bodyLine = lines.lineNumber() + 1;
            break;
        }
        if (key == "format") {
            if (haveFormat) fail("a second 'format' line");
            if (!header.elements.empty()) fail("'format' after the first element");
            const std::string_view kind = nextToken(rest), version = nextToken(rest);
            if (kind == "ascii") {
            } else if (kind == "binary_little_endian") {
                header.binary = true;
            } else if (kind == "binary_big_endian") {
                header.binary = header.bigEndian = true;
            } else {
                fail("unknown PLY format '" + shown(kind) +
                     "' (expected ascii, binary_little_endian or binary_big_endian)");
            }
            if (version.empty()) fail("the format line has no version (1.0)");
            if (version != "1.0" && version != "1") fail("unknown PLY version '" + shown(version) + "'");
            if (!nextToken(rest).empty()) fail("words after the format");
            haveFormat = true;
        } else if (key == "element") {
            PlyElement element;
            element.name = nextToken(rest);
            const std::string_view n = nextToken(rest);
            const auto count = parseCount(n);
            if (element.name.empty() || !count)
                fail("cannot read the element count '" + shown(n) + "' (a whole number up to " +
                     std::to_string(kMaxElements) + ")");
            if (!nextToken(rest).empty()) fail("words after the element count");
            for (const PlyElement& e : header.elements)
                if (e.name == element.name) fail("a second element '" + element.name + "'");
            element.count = *count;
            element.line = lines.lineNumber();
            header.elements.push_back(std::move(element));
        } else if (key == "property") {
            if (header.elements.empty()) fail("a property before any element");
            PlyProperty property;
            std::string_view typeName = nextToken(rest);
            if (typeName == "list") {
                const std::string_view countName = nextToken(rest);
                property.listCount = plyType(countName);
                if (!property.listCount || !isInteger(*property.listCount))
                    fail("a list count of type '" + shown(countName) + "' (expected an integer type)");
                typeName = nextToken(rest);
            }
            const auto type = plyType(typeName);
            if (!type)
                fail("unknown property type '" + shown(typeName) +
                     "' (expected char, uchar, short, ushort, int, uint, float, double or int8 ... float64)");
            property.type = *type;
            property.name = nextToken(rest);
            if (property.name.empty()) fail("a property without a name");
            if (!nextToken(rest).empty()) fail("words after the property name");
            PlyElement& element = header.elements.back();
            for (const PlyProperty& p : element.properties)
                if (p.name == property.name) fail("a second property '" + property.name + "' in '" + element.name + "'");
            element.properties.push_back(std::move(property));
        } else {
            fail("unknown header line '" + shown(key) + "'");
        }
    }
    return header;
}

// What the mesh needs from the header, found once.
struct PlyLayout {
    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    std::array<std::size_t, 3> xyz{};   // property numbers of x, y, z in the vertex element
    std::size_t indices = 0;            // property number of vertex_indices in the face element
};

PlyLayout plyLayout(const PlyHeader& header, const std::string& file) {
    PlyLayout layout;
    for (const PlyElement& e : header.elements) {
        if (e.count > 0 && e.properties.empty())
            throw MeshError(file, atLine(e.line) + "element '" + e.name + "' has " + std::to_string(e.count) +
                                      " entries but no properties");
        if (e.name == "vertex") layout.vertex = &e;
        if (e.name == "face") layout.face = &e;
    }
    if (!layout.vertex) throw MeshError(file, "not a mesh: the PLY header has no 'vertex' element");
    const char* axes[] = {"x", "y", "z"};
    for (std::size_t k = 0; k < 3; ++k) {
        const auto& ps = layout.vertex->properties;
        const auto it = std::find_if(ps.begin(), ps.end(), [&](const PlyProperty& p) { return p.name == axes[k]; });
        if (it == ps.end() || it->listCount)
            throw MeshError(file, atLine(layout.vertex->line) + "the vertices have no number property '" +
                                      axes[k] + "'");
        layout.xyz[k] = static_cast<std::size_t>(it - ps.begin());
    }
    if (layout.face) {
        const auto& ps = layout.face->properties;
        const auto it = std::find_if(ps.begin(), ps.end(), [](const PlyProperty& p) {
            return p.name == "vertex_indices" || p.name == "vertex_index";
        });
        if (it == ps.end() || !it->listCount || !isInteger(it->type))
            throw MeshError(file, atLine(layout.face->line) +
                                      "the faces have no integer list 'vertex_indices' (or 'vertex_index')");
        layout.indices = static_cast<std::size_t>(it - ps.begin());
    }
    return layout;
}

// The fewest bytes the body can take: every scalar and list count written, face lists with 3
// entries (fewer is refused), other lists empty. Text: each value a digit and a separator.
std::uint64_t plyMinimumBody(const PlyHeader& header, const PlyLayout& layout) {
    std::uint64_t total = 0;
    for (const PlyElement& e : header.elements) {
        std::uint64_t record = 0;
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const PlyProperty& p = e.properties[k];
            const std::uint64_t entries = &e == layout.face && k == layout.indices ? 3 : 0;
            record += header.binary ? (p.listCount ? plySize(*p.listCount) : 0) + (p.listCount ? entries : 1) * plySize(p.type)
                                    : 2 * (1 + entries);
        }
        total = mulAdd(e.count, record, total);
    }
    return total;
}

class PlyBodyReader {
public:
    PlyBodyReader(std::span<const unsigned char> bytes, const PlyHeader& header, const std::string& file)
        : header_(header), file_(file), binary_(bytes, header.bodyOffset, header.bigEndian),
          text_(bytes, header.bodyOffset, header.bodyLine) {}

    // Where the next value is, for messages.
    std::string where() const {
        return header_.binary ? atOffset(binary_.offset()) : atLine(text_.line());
    }
    std::size_t left() const { return header_.binary ? binary_.left() : text_.left(); }

    // Where the last value read starts (its byte offset, or its line).
    std::string lastWhere() const { return header_.binary ? atOffset(lastOffset_) : atLine(lastLine_); }

    double number(PlyType type, const PlyElement& e, std::uint64_t entry) {
        if (header_.binary) {
            lastOffset_ = binary_.offset();
            const auto raw = binary_.next(plySize(type));
            if (!raw) ended(e, entry);
            return plyBinaryValue(type, *raw);
        }
        const std::string_view word = text_.next();
        lastLine_ = text_.line();
        if (word.empty()) ended(e, entry);
        if (isInteger(type)) {
            const auto value = parseInteger(word);
            if (!value || !fitsPlyInteger(type, *value))
                throw MeshError(file_, lastWhere() + "'" + shown(word) + "' is not a " + typeName(type) + " (" +
                                           e.name + " " + std::to_string(entry) + "; corrupt file)");
            return static_cast<double>(*value);
        }
        const auto value = parseFloat(word);
        if (!value)
            throw MeshError(file_, lastWhere() + "'" + shown(word) + "' is not a number (" + e.name + " " +
                                       std::to_string(entry) + "; corrupt file)");
        return static_cast<double>(*value);
    }
    void skip(PlyType type, const PlyElement& e, std::uint64_t entry) {
        if (header_.binary) {
            if (binary_.left() < plySize(type)) ended(e, entry);
            binary_.skip(plySize(type));
        } else {
            number(type, e, entry);
        }
    }
    [[noreturn]] void ended(const PlyElement& e, std::uint64_t entry) const {
        throw MeshError(file_, where() + "the file ends in " + e.name + " " + std::to_string(entry) + " of " +
                                   std::to_string(e.count) + " (truncated or corrupt file)");
    }
    WordReader& text() { return text_; }
    ByteReader& binary() { return binary_; }

private:
    static std::string typeName(PlyType t) {
        switch (t) {
        case PlyType::Int8: return "char";
        case PlyType::UInt8: return "uchar";
        case PlyType::Int16: return "short";
        case PlyType::UInt16: return "ushort";
        case PlyType::Int32: return "int";
        case PlyType::UInt32: return "uint";
        default: return "number";
        }
    }

    const PlyHeader& header_;
    const std::string& file_;
    ByteReader binary_;
    WordReader text_;
    std::size_t lastOffset_ = 0, lastLine_ = 0;
};

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

Polygons parsePly(std::span<const unsigned char> bytes, const std::string& file) {
    const PlyHeader header = readPlyHeader(bytes, file);
    const PlyLayout layout = plyLayout(header, file);
    // No count is trusted before the bytes that must hold it are there.
    const std::uint64_t body = bytes.size() - header.bodyOffset;
    const std::uint64_t needed = plyMinimumBody(header, layout);
    if (needed > body + (header.binary ? 0 : 1))
        throw MeshError(file, "truncated or corrupt file: the header announces " + vertices(layout.vertex->count) +
                                  (layout.face ? " and " + faces(layout.face->count) : std::string()) +
                                  " (at least " + std::to_string(needed) + " bytes), the file has " +
                                  std::to_string(body) + " bytes after the header");
    const std::uint64_t vertexCount = layout.vertex->count;

    Polygons out;
    out.positions.reserve(static_cast<std::size_t>(vertexCount));
    if (layout.face) out.faceStarts.reserve(static_cast<std::size_t>(layout.face->count) + 1);
    PlyBodyReader in(bytes, header, file);
    std::vector<std::uint32_t> face;
    for (const PlyElement& e : header.elements) {
        const bool isVertex = &e == layout.vertex, isFace = &e == layout.face;
        for (std::uint64_t entry = 0; entry < e.count; ++entry) {
            std::array<float, 3> p{};
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                const PlyProperty& property = e.properties[k];
                if (!property.listCount) {
                    const bool axis = isVertex && std::find(layout.xyz.begin(), layout.xyz.end(), k) != layout.xyz.end();
                    if (!axis) {
                        in.skip(property.type, e, entry);
                        continue;
                    }
                    const double value = in.number(property.type, e, entry);
                    p[static_cast<std::size_t>(std::find(layout.xyz.begin(), layout.xyz.end(), k) - layout.xyz.begin())] =
                        static_cast<float>(value);
                    continue;
                }
                const double length = in.number(*property.listCount, e, entry);
                const bool indices = isFace && k == layout.indices;
                // A list no longer than the bytes left could hold (text: a digit and a space each).
                const double room = static_cast<double>(in.left()) /
                                    static_cast<double>(header.binary ? plySize(property.type) : 2);
                const bool tooLong = indices && length > static_cast<double>(kMaxFaceCorners);
                if (length < 0 || length > room + 1 || tooLong)
                    throw MeshError(file, in.lastWhere() + e.name + " " + std::to_string(entry) + " has a list of " +
                                              std::to_string(static_cast<long long>(length)) + " values (" +
                                              (length < 0   ? std::string("negative")
                                               : tooLong    ? "a face has at most " + std::to_string(kMaxFaceCorners)
                                                            : std::string("more than the rest of the file holds")) +
                                              "; corrupt file)");
                const auto n = static_cast<std::size_t>(length);
                if (!indices) {
                    for (std::size_t j = 0; j < n; ++j) in.skip(property.type, e, entry);
                    continue;
                }
                if (n < 3)
                    throw MeshError(file, in.lastWhere() + "face " + std::to_string(entry) + " has " + vertices(n) +
                                              " (a face needs 3 or more; truncated or corrupt file)");
                face.clear();
                for (std::size_t j = 0; j < n; ++j) {
                    const double index = in.number(property.type, e, entry);
                    if (index < 0 || index >= static_cast<double>(vertexCount))
                        throw MeshError(file, in.lastWhere() + "face " + std::to_string(entry) + " refers to vertex " +
                                                  std::to_string(static_cast<long long>(index)) +
                                                  ", but the file has " + vertices(vertexCount) +
                                                  " (vertices count from 0; corrupt file)");
                    face.push_back(static_cast<std::uint32_t>(index));
                }
            }
            if (isVertex) out.positions.push_back(p);
            if (isFace) {
                out.corners.insert(out.corners.end(), face.begin(), face.end());
                out.faceStarts.push_back(out.corners.size());
            }
        }
    }
    if (header.binary) {
        if (in.binary().left() > 0)
            out.warnings.push_back(file + ": " + std::to_string(in.binary().left()) +
                                   " bytes after the last element ignored");
    } else {
        // A text file cut inside its last number still reads: only the missing line end tells.
        if (in.text().cutAfterLastWord())
            throw MeshError(file, in.where() +
                                      "the file ends inside its last value, with no line end (truncated file)");
        if (const std::size_t extra = in.text().wordBytesLeft(); extra > 0)
            out.warnings.push_back(file + ": " + std::to_string(extra) + " bytes after the last element ignored");
    }
    return out;
}

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

std::vector<std::uint32_t> distinctInOrder(std::span<const std::uint32_t> values) {
    // (value, position) sorted: the first of each run is that value's first appearance.
    std::vector<std::pair<std::uint32_t, std::size_t>> sorted(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) sorted[i] = {values[i], i};
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::size_t> firsts;
    for (std::size_t i = 0; i < sorted.size(); ++i)
        if (i == 0 || sorted[i].first != sorted[i - 1].first) firsts.push_back(sorted[i].second);
    std::sort(firsts.begin(), firsts.end());
    std::vector<std::uint32_t> out;
    out.reserve(firsts.size());
    for (std::size_t i : firsts) out.push_back(values[i]);
    return out;
}

std::string faces(std::size_t n) { return count(n, "face", "faces"); }
std::string vertices(std::size_t n) { return count(n, "vertex", "vertices"); }
std::string atLine(std::size_t line) { return "line " + std::to_string(line) + ": "; }

}  // namespace mipgloss::meshfile
