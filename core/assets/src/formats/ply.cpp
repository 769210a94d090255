// The PLY reader, ASCII and binary in either byte order (formats/mesh_formats.h).
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

}  // namespace mipgloss::meshfile
