#include "mipgloss/scene/mesh.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/IO/reader/OFFReader.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <unistd.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <streambuf>
#include <string_view>
#include <utility>

// Generated at build time from resources/meshes/teapot.obj (core/cmake/embed_file.cmake).
namespace mipgloss::embedded {
extern const unsigned char default_teapot_obj[];
extern const std::size_t default_teapot_obj_size;
}  // namespace mipgloss::embedded

namespace fs = std::filesystem;

namespace mipgloss {

bool Mesh::isValid() const {
    if (normals.size() != positions.size() || indices.size() % 3 != 0) return false;
    for (std::uint32_t i : indices)
        if (i >= positions.size()) return false;
    auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    for (const glm::vec3& p : positions)
        if (!finite(p)) return false;
    for (const glm::vec3& n : normals)
        if (!finite(n) || std::abs(glm::length(n) - 1.0f) > 1e-4f) return false;
    return true;
}

namespace {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;
using OpenMesh::FaceHandle;
using OpenMesh::VertexHandle;

constexpr std::array<const char*, 5> kExtensions = {".obj", ".off", ".ply", ".stl", ".om"};

// A face is zero-area when its height is below this fraction of its longest edge: collinear at
// float precision (a float coordinate holds ~7 digits). Its normal would be noise, its weight nil.
constexpr double kDegenerateHeight = 1e-7;

std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string extensionList() {
    std::string list;
    for (const char* e : kExtensions) list += (list.empty() ? "" : ", ") + std::string(e);
    return list;
}

// "1 face", "3 faces", "1 vertex", "2 vertices".
std::string count(std::size_t n, std::string_view one, std::string_view many) {
    return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}
std::string faces(std::size_t n) { return count(n, "face", "faces"); }
std::string vertices(std::size_t n) { return count(n, "vertex", "vertices"); }
std::string atLine(std::size_t line) { return "line " + std::to_string(line) + ": "; }

// ---------------------------------------------------------------------------------------------
// Input plumbing: a read-only, seekable stream over bytes already in memory (the OBJ reader reads
// twice, so it seeks back), which also notes whether a reader tried to read past the end: for
// the binary formats that is how a truncated file shows itself.

class MemoryStreamBuf : public std::streambuf {
public:
    explicit MemoryStreamBuf(std::span<const unsigned char> bytes) {
        // The get area is never written through: no putback buffer, no output.
        char* begin = const_cast<char*>(reinterpret_cast<const char*>(bytes.data()));
        setg(begin, begin, begin + bytes.size());
    }
    bool readPastEnd() const { return readPastEnd_; }

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        readPastEnd_ = true;
        return traits_type::eof();
    }
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override {
        if (!(which & std::ios_base::in)) return pos_type(off_type(-1));
        const off_type size = egptr() - eback();
        const off_type base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? gptr() - eback() : size;
        const off_type target = base + off;
        if (target < 0 || target > size) return pos_type(off_type(-1));
        setg(eback(), eback() + target, egptr());
        return pos_type(target);
    }
    pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
        return seekoff(off_type(pos), std::ios_base::beg, which);
    }

private:
    bool readPastEnd_ = false;
};

// OpenMesh's readers keep state in singletons and report through the global omerr()/omlog()
// streams, so reads are serialised. While one runs, its messages are collected here (for the
// error text) instead of reaching the console.
std::mutex& openMeshMutex() {
    static std::mutex m;
    return m;
}

class CapturedOpenMeshMessages {
public:
    CapturedOpenMeshMessages() {
        for (Route& r : routes_) {
            r.wasConnected = r.stream.disconnect(r.console);
            r.stream.connect(text_);
        }
    }
    ~CapturedOpenMeshMessages() {
        for (Route& r : routes_) {
            r.stream.disconnect(text_);
            if (r.wasConnected) r.stream.connect(r.console);
        }
    }
    CapturedOpenMeshMessages(const CapturedOpenMeshMessages&) = delete;
    CapturedOpenMeshMessages& operator=(const CapturedOpenMeshMessages&) = delete;

    // The first message, trimmed, or "" when OpenMesh said nothing.
    std::string firstLine() const {
        std::istringstream in(text_.str());
        std::string line;
        while (std::getline(in, line)) {
            const auto b = line.find_first_not_of(" \t\r");
            if (b == std::string::npos) continue;
            return line.substr(b, line.find_last_not_of(" \t\r") + 1 - b);
        }
        return {};
    }

private:
    struct Route {
        OpenMesh::mostream& stream;
        std::ostream& console;  // where OpenMesh connects it by default
        bool wasConnected;
    };

    std::ostringstream text_;
    std::array<Route, 3> routes_{Route{::omerr(), std::cerr, false}, Route{::omlog(), std::clog, false},
                                 Route{::omout(), std::cout, false}};
};

// OpenMesh's ImporterT drops a face it dislikes with a console message and goes on; this one
// counts each case so the loader can say what was wrong. It also triangulates polygons itself (a
// fan, each triangle added on its own), and where the half-edge structure cannot take a triangle
// (an edge shared by three faces, a vertex joining two fans) gives that triangle its own copies
// of the vertices and remembers the originals, so the output mesh stays welded as in the file.
class CheckingImporter final : public OpenMesh::IO::ImporterT<OMesh> {
public:
    explicit CheckingImporter(OMesh& mesh) : ImporterT<OMesh>(mesh), target_(mesh) {}

    using ImporterT<OMesh>::add_face;
    FaceHandle add_face(const VHandles& face) override {
        ++facesSeen;
        if (face.size() < 3) {
            ++shortFaces;
            return FaceHandle();
        }
        for (VertexHandle vh : face)
            if (!target_.is_valid_handle(vh)) {
                ++badIndexFaces;
                return FaceHandle();
            }
        distinct_.clear();
        for (VertexHandle vh : face)
            if (std::find(distinct_.begin(), distinct_.end(), vh) == distinct_.end()) distinct_.push_back(vh);
        if (distinct_.size() < 3) {
            ++repeatedVertexFaces;
            return FaceHandle();
        }
        FaceHandle last;
        for (std::size_t i = 1; i + 1 < distinct_.size(); ++i) {
            last = target_.add_face(distinct_[0], distinct_[i], distinct_[i + 1]);
            if (!last.is_valid()) last = addSeparately({distinct_[0], distinct_[i], distinct_[i + 1]});
        }
        return last;
    }

    std::size_t facesSeen = 0;                // faces the reader handed over
    std::size_t shortFaces = 0;               // fewer than 3 vertices
    std::size_t badIndexFaces = 0;            // a vertex index the file does not have
    std::size_t repeatedVertexFaces = 0;      // fewer than 3 distinct vertices: zero area
    std::vector<std::pair<int, int>> copies;  // (copy, original) vertex indices

private:
    FaceHandle addSeparately(const std::array<VertexHandle, 3>& tri) {
        std::array<VertexHandle, 3> own;
        for (std::size_t k = 0; k < 3; ++k) {
            const OMesh::Point p = target_.point(tri[k]);  // a copy: add_vertex may reallocate
            own[k] = target_.add_vertex(p);
            copies.emplace_back(own[k].idx(), tri[k].idx());
        }
        return target_.add_face(own[0], own[1], own[2]);
    }

    OMesh& target_;
    std::vector<VertexHandle> distinct_;
};

// ---------------------------------------------------------------------------------------------
// Format checks OpenMesh does not make. Each returns what the file claims (counts), or throws.

struct Declared {
    std::optional<std::size_t> vertices;
    std::optional<std::size_t> faces;
    std::size_t zeroAreaFaces = 0;  // faces the reader drops before the importer sees them
};

// Text lines with numbers, for the OBJ and ASCII STL checks.
class LineScanner {
public:
    explicit LineScanner(std::span<const unsigned char> bytes)
        : p_(reinterpret_cast<const char*>(bytes.data())), end_(p_ + bytes.size()) {}
    bool done() const { return p_ >= end_; }
    std::size_t lineNumber() const { return line_; }
    // The next line without its terminator.
    std::string_view next() {
        const char* b = p_;
        const char* e = static_cast<const char*>(std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_)));
        if (!e) e = end_;
        p_ = e < end_ ? e + 1 : end_;
        ++line_;
        return {b, static_cast<std::size_t>(e - b)};
    }

private:
    const char* p_;
    const char* end_;
    std::size_t line_ = 0;
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

// Three readable coordinates at the front of `rest`; `finite` says whether all three are.
bool parseXyz(std::string_view rest, bool& finite) {
    finite = true;
    for (int k = 0; k < 3; ++k) {
        const auto value = parseFloat(nextToken(rest));
        if (!value) return false;
        finite = finite && std::isfinite(*value);
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

// OBJ: OpenMesh reads vertices with operator>> (which rejects "nan", "inf" and overflowing
// numbers, and then skips the line, shifting every later index), drops faces with a bad index or
// fewer than three distinct vertices without a word, and skips unreadable index tokens. So the
// file is checked here first, with line numbers for the messages.
Declared checkObj(std::span<const unsigned char> bytes, const std::string& file) {
    if (const auto at = firstBinaryByte(bytes))
        throw MeshError(file, "not an OBJ file: binary data (" + binaryByteText(bytes, *at) + ")");
    LineScanner lines(bytes);
    std::size_t vertexCount = 0, faceCount = 0, zeroArea = 0, nonFinite = 0, firstNonFiniteLine = 0;
    long long maxIndex = 0;
    std::size_t maxIndexLine = 0;
    std::vector<long long> distinct;
    while (!lines.done()) {
        std::string_view rest = lines.next();
        const std::string_view key = nextToken(rest);
        if (key == "v") {
            bool finite = true;
            if (!parseXyz(rest, finite))
                throw MeshError(file, atLine(lines.lineNumber()) +
                                          "a vertex without three readable coordinates (truncated or corrupt file)");
            if (!finite && nonFinite++ == 0) firstNonFiniteLine = lines.lineNumber();
            ++vertexCount;
        } else if (key == "f") {
            ++faceCount;
            distinct.clear();
            std::size_t corners = 0;
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
                if (std::find(distinct.begin(), distinct.end(), value) == distinct.end()) distinct.push_back(value);
                ++corners;
            }
            // A face line cut short is how a truncated file usually ends.
            if (corners < 3)
                throw MeshError(file, atLine(lines.lineNumber()) + "a face with only " + vertices(corners) +
                                          " (truncated or corrupt file)");
            if (distinct.size() < 3) ++zeroArea;
        }
    }
    if (nonFinite > 0)
        throw MeshError(file, vertices(nonFinite) + " with non-finite (NaN or infinite) coordinates, first at line " +
                                  std::to_string(firstNonFiniteLine));
    if (maxIndex > static_cast<long long>(vertexCount))
        throw MeshError(file, atLine(maxIndexLine) + "a face refers to vertex " + std::to_string(maxIndex) +
                                  ", but the file has only " + vertices(vertexCount) +
                                  " (truncated or corrupt file)");
    return {vertexCount, faceCount, zeroArea};
}

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

// ASCII STL: OpenMesh reads the three lines after each "outer loop" as vertices whatever they
// hold (a cut-off facet becomes a triangle at the origin), and reads "nan" as 0.
Declared checkAsciiStl(std::span<const unsigned char> bytes, const std::string& file) {
    LineScanner lines(bytes);
    std::size_t facets = 0, nonFinite = 0, firstNonFiniteLine = 0;
    bool ended = false;  // an "endsolid" after the last facet: the file is whole
    while (!lines.done()) {
        const std::string_view line = lines.next();
        if (line.find("endsolid") != std::string_view::npos || line.find("ENDSOLID") != std::string_view::npos) {
            ended = true;
            continue;
        }
        if (line.find("outer") == std::string_view::npos && line.find("OUTER") == std::string_view::npos) continue;
        ended = false;
        ++facets;
        const std::size_t facetLine = lines.lineNumber();
        for (int k = 0; k < 3; ++k) {
            std::string_view rest = lines.done() ? std::string_view{} : lines.next();
            const std::string_view key = nextToken(rest);
            bool finite = true;
            if ((key != "vertex" && key != "VERTEX") || !parseXyz(rest, finite))
                throw MeshError(
                    file, atLine(facetLine) + "a facet without three readable vertices (truncated or corrupt file)");
            if (!finite && nonFinite++ == 0) firstNonFiniteLine = lines.lineNumber();
        }
    }
    if (!ended) throw MeshError(file, "truncated or corrupt file: the ASCII STL does not end with 'endsolid'");
    if (nonFinite > 0)
        throw MeshError(file, vertices(nonFinite) + " with non-finite (NaN or infinite) coordinates, first at line " +
                                  std::to_string(firstNonFiniteLine));
    return {std::nullopt, facets, 0};
}

// STL comes as text or binary with nothing but the size to tell them apart (binary headers may
// start with "solid" too): binary is 84 bytes plus 50 per triangle, the count at offset 80.
Declared checkStl(std::span<const unsigned char> bytes, const std::string& file, bool& binary,
                  std::vector<std::string>& warnings) {
    const std::uint64_t triangles = bytes.size() >= 84 ? readLe32(bytes, 80) : 0;
    const std::uint64_t binarySize = 84 + 50 * triangles;
    binary = bytes.size() >= 84 && bytes.size() == binarySize;
    if (!binary && startsWithWord(bytes, "solid") && !firstBinaryByte(bytes)) return checkAsciiStl(bytes, file);
    if (bytes.size() < 84)
        throw MeshError(file, "not an STL file: too short for binary STL (" + std::to_string(bytes.size()) +
                                  " bytes) and not ASCII STL (no 'solid')");
    if (bytes.size() < binarySize)
        throw MeshError(file, "truncated or corrupt binary STL: the header announces " + std::to_string(triangles) +
                                  " triangles (" + std::to_string(binarySize) + " bytes), the file has " +
                                  std::to_string(bytes.size()) + " bytes");
    if (bytes.size() > binarySize)
        warnings.push_back(file + ": " + std::to_string(bytes.size() - binarySize) +
                           " bytes after the last triangle ignored");
    binary = true;
    // Non-finite coordinates checked here: OpenMesh merges corners in an ordered map, which NaN breaks.
    std::size_t nonFinite = 0;
    for (std::uint64_t t = 0; t < triangles; ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            bool finite = true;
            for (std::size_t c = 0; c < 3; ++c) {
                const std::uint32_t raw =
                    readLe32(bytes, static_cast<std::size_t>(84 + 50 * t + 12 * (k + 1) + 4 * c));
                float value;
                std::memcpy(&value, &raw, sizeof value);
                finite = finite && std::isfinite(value);
            }
            if (!finite) ++nonFinite;
        }
    if (nonFinite > 0)
        throw MeshError(file,
                        vertices(nonFinite) + " (triangle corners) with non-finite (NaN or infinite) coordinates");
    return {std::nullopt, static_cast<std::size_t>(triangles), 0};
}

// PLY: the header names the counts; OpenMesh reads on past the end of a short file.
Declared checkPly(std::span<const unsigned char> bytes, const std::string& file, bool& binary) {
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()),
                                std::min<std::size_t>(bytes.size(), 1 << 16));
    if (!(text.starts_with("ply\n") || text.starts_with("ply\r\n")))
        throw MeshError(file, "not a PLY file (it does not start with 'ply')");
    const std::size_t end = text.find("end_header");
    if (end == std::string_view::npos)
        throw MeshError(file, "not a readable PLY file: the header has no 'end_header' (truncated or corrupt file)");
    Declared declared;
    binary = false;
    std::span<const unsigned char> header = bytes.first(end);
    LineScanner lines(header);
    while (!lines.done()) {
        std::string_view rest = lines.next();
        const std::string_view key = nextToken(rest);
        if (key == "format") {
            binary = nextToken(rest) != "ascii";
        } else if (key == "element") {
            const std::string_view name = nextToken(rest);
            const std::string_view n = nextToken(rest);
            std::size_t value = 0;
            const auto [ptr, ec] = std::from_chars(n.data(), n.data() + n.size(), value);
            if (ec != std::errc() || ptr != n.data() + n.size())
                throw MeshError(
                    file, atLine(lines.lineNumber()) + "cannot read the PLY element count '" + std::string(n) + "'");
            if (name == "vertex") declared.vertices = value;
            if (name == "face") declared.faces = value;
        }
    }
    return declared;
}

// OFF: "OFF" (or COFF, NOFF, STOFF, ...) then the vertex, face and edge counts.
Declared checkOff(std::span<const unsigned char> bytes, const std::string& file, bool& binary) {
    LineScanner lines(bytes.first(std::min<std::size_t>(bytes.size(), 1 << 16)));
    std::string_view rest;
    while (!lines.done()) {
        rest = lines.next();
        std::string_view probe = rest;
        const std::string_view first = nextToken(probe);
        if (!first.empty() && first[0] != '#') break;
    }
    const std::string_view magic = nextToken(rest);
    if (!magic.ends_with("OFF")) throw MeshError(file, "not an OFF file (it does not start with 'OFF')");
    std::string_view afterMagic = rest;
    binary = nextToken(afterMagic) == "BINARY";
    Declared declared;
    // Dimension-prefixed variants (nOFF, 4OFF) put more before the counts; leave those to OpenMesh.
    if (binary || magic.starts_with("n") || magic.find('4') != std::string_view::npos) return declared;
    std::array<std::size_t, 2> counts{};
    for (std::size_t k = 0; k < counts.size();) {
        std::string_view token = nextToken(rest);
        if (token.empty() || token[0] == '#') {
            if (lines.done()) return declared;
            rest = lines.next();
            continue;
        }
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), counts[k]);
        if (ec != std::errc() || ptr != token.data() + token.size())
            throw MeshError(file, atLine(lines.lineNumber()) + "cannot read the OFF vertex and face counts");
        ++k;
    }
    declared.vertices = counts[0];
    declared.faces = counts[1];
    return declared;
}

// OM: "OM", the mesh kind, the version, then little-endian vertex, face and edge counts.
Declared checkOm(std::span<const unsigned char> bytes, const std::string& file) {
    if (bytes.size() < 16 || bytes[0] != 'O' || bytes[1] != 'M')
        throw MeshError(file, "not an OpenMesh .om file (no 'OM' signature)");
    return {readLe32(bytes, 4), readLe32(bytes, 8), 0};
}

// OpenMesh's OFF reader takes the layout (binary, colours, normals) from its last
// can_u_read(filename) call, which reading from a stream never makes: so make it, on a file that
// holds the header line alone. Called under openMeshMutex().
bool primeOffReader(std::span<const unsigned char> bytes) {
    const auto* text = reinterpret_cast<const char*>(bytes.data());
    const std::size_t length = std::min<std::size_t>(bytes.size(), 1024);
    const std::string_view header(text, std::find(text, text + length, '\n') - text);
    std::error_code ec;
    const fs::path folder = fs::temp_directory_path(ec);
    if (ec) return false;
    const fs::path probe = folder / ("mipgloss_off_header_" + std::to_string(::getpid()) + ".off");
    {
        std::ofstream out(probe, std::ios::binary);
        out << header << '\n';
        if (!out) return false;
    }
    const bool known = OpenMesh::IO::OFFReader().can_u_read(probe.string());
    fs::remove(probe, ec);
    return known;
}

std::string formatName(const std::string& ext) {
    std::string name = ext.substr(1);
    for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return name;
}

bool isZeroArea(const OMesh::Point& a, const OMesh::Point& b, const OMesh::Point& c) {
    const glm::dvec3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]), pc(c[0], c[1], c[2]);
    const glm::dvec3 e0 = pb - pa, e1 = pc - pa, e2 = pc - pb;
    const glm::dvec3 n = glm::cross(e0, e1);
    const double longest2 = std::max({glm::dot(e0, e0), glm::dot(e1, e1), glm::dot(e2, e2)});
    // height = |n| / longest <= k * longest
    return glm::dot(n, n) <= kDegenerateHeight * kDegenerateHeight * longest2 * longest2;
}

constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();

Mesh readMesh(std::span<const unsigned char> bytes, const std::string& file, const std::string& ext,
              MeshReport* report) {
    if (std::find(kExtensions.begin(), kExtensions.end(), ext) == kExtensions.end())
        throw MeshError(file, "unsupported mesh format '" + ext + "' (expected " + extensionList() + ")");
    if (bytes.empty()) throw MeshError(file, "file is empty (0 bytes)");
    const std::string format = formatName(ext);

    std::vector<std::string> warnings;
    Declared declared;
    bool binary = false;
    if (ext == ".obj")
        declared = checkObj(bytes, file);
    else if (ext == ".stl")
        declared = checkStl(bytes, file, binary, warnings);
    else if (ext == ".ply")
        declared = checkPly(bytes, file, binary);
    else if (ext == ".off")
        declared = checkOff(bytes, file, binary);
    else if (ext == ".om") {
        declared = checkOm(bytes, file);
        binary = true;
    }

    OMesh om;
    CheckingImporter importer(om);
    OpenMesh::IO::Options options;
    if (ext == ".stl" && binary) options += OpenMesh::IO::Options::Binary;
    bool ok = false, pastEnd = false, streamFailed = false;
    std::string said;
    {
        std::lock_guard lock(openMeshMutex());
        CapturedOpenMeshMessages messages;
        MemoryStreamBuf buffer(bytes);
        std::istream in(&buffer);
        if (ext == ".off" && !primeOffReader(bytes))
            throw MeshError(file, "not a readable OFF file (unsupported header, or no temporary folder to read it)");
        ok = OpenMesh::IO::IOManager().read(in, ext, importer, options);
        pastEnd = buffer.readPastEnd();
        streamFailed = in.fail();
        said = messages.firstLine();
    }
    const std::string detail = said.empty() ? "" : " (OpenMesh: " + said + ")";
    // Binary readers never look past the data they expect; text readers fail at the end of a
    // short file.
    if (pastEnd && (binary || !ok))
        throw MeshError(file, "truncated or corrupt file: it ends before the data its header announces" + detail);
    if (!ok) throw MeshError(file, "not a readable " + format + " file" + detail);
    // The text readers of OFF and PLY read numbers with operator>>, which fails at the end of a
    // short file or on a word; they go on with zeros.
    if (!binary && streamFailed && (ext == ".off" || ext == ".ply"))
        throw MeshError(file, "truncated or corrupt file: it ends early or holds unreadable numbers");
    if (importer.shortFaces > 0)
        throw MeshError(file, faces(importer.shortFaces) + " with fewer than 3 vertices (truncated or corrupt file)");
    if (importer.badIndexFaces > 0)
        throw MeshError(file, faces(importer.badIndexFaces) + (importer.badIndexFaces == 1 ? " refers" : " refer") +
                                  " to vertices the file does not have (truncated or corrupt file)");

    const std::size_t vertexCount = om.n_vertices();
    const std::size_t fileVertices = vertexCount - importer.copies.size();
    if (declared.vertices && *declared.vertices != fileVertices)
        throw MeshError(file, "truncated or corrupt file: " + vertices(*declared.vertices) + " expected, " +
                                  std::to_string(fileVertices) + " could be read" + detail);
    std::size_t zeroArea = importer.repeatedVertexFaces + declared.zeroAreaFaces;
    if (declared.faces && ext == ".stl") {
        zeroArea += *declared.faces - std::min(*declared.faces, importer.facesSeen);  // merged corners
    } else if (declared.faces && ext != ".om" && importer.facesSeen + declared.zeroAreaFaces != *declared.faces) {
        throw MeshError(file, "truncated or corrupt file: " + faces(*declared.faces) + " expected, " +
                                  std::to_string(importer.facesSeen + declared.zeroAreaFaces) + " could be read" +
                                  detail);
    }

    // Copies made for non-manifold triangles map back to the file's vertex.
    std::vector<std::uint32_t> original(vertexCount);
    for (std::size_t v = 0; v < vertexCount; ++v) original[v] = static_cast<std::uint32_t>(v);
    for (const auto& [copy, source] : importer.copies)
        original[static_cast<std::size_t>(copy)] = static_cast<std::uint32_t>(source);

    const OMesh::Point* points = om.points();
    std::size_t nonFinite = 0;
    for (std::size_t v = 0; v < vertexCount; ++v)
        if (original[v] == v &&
            !(std::isfinite(points[v][0]) && std::isfinite(points[v][1]) && std::isfinite(points[v][2])))
            ++nonFinite;
    if (nonFinite > 0) throw MeshError(file, vertices(nonFinite) + " with non-finite (NaN or infinite) coordinates");

    // Triangles in file vertex numbers; faces OpenMesh holds as polygons (OM files) become fans.
    Mesh mesh;
    mesh.name = fs::path(file).stem().string();
    mesh.indices.reserve(3 * om.n_faces());
    std::vector<std::uint32_t> loop;
    for (const auto fh : om.faces()) {
        loop.clear();
        const auto first = om.halfedge_handle(fh);
        auto he = first;
        do {
            loop.push_back(original[static_cast<std::size_t>(om.to_vertex_handle(he).idx())]);
            he = om.next_halfedge_handle(he);
        } while (he != first && loop.size() <= vertexCount);
        for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
            const std::array<std::uint32_t, 3> tri{loop[0], loop[i], loop[i + 1]};
            if (isZeroArea(points[tri[0]], points[tri[1]], points[tri[2]])) {
                ++zeroArea;
                continue;
            }
            mesh.indices.insert(mesh.indices.end(), tri.begin(), tri.end());
        }
    }
    if (mesh.indices.empty()) {
        if (zeroArea > 0) throw MeshError(file, "all " + faces(zeroArea) + " have zero area");
        if (fileVertices == 0) throw MeshError(file, "no vertices and no faces: not a mesh file");
        throw MeshError(file, "no faces, only " + vertices(fileVertices) + " (a point cloud?)");
    }

    // Keep the vertices faces use, in file order.
    std::vector<std::uint32_t> remap(vertexCount, kUnused);
    for (std::uint32_t i : mesh.indices) remap[i] = 0;
    mesh.positions.reserve(fileVertices);
    for (std::size_t v = 0; v < vertexCount; ++v) {
        if (remap[v] == kUnused) continue;
        remap[v] = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.emplace_back(points[v][0], points[v][1], points[v][2]);
    }
    for (std::uint32_t& i : mesh.indices) i = remap[i];
    const std::size_t unused = fileVertices - mesh.positions.size();

    computeVertexNormals(mesh);
    computeBounds(mesh);

    if (zeroArea > 0) warnings.push_back(file + ": dropped " + faces(zeroArea) + " with zero area");
    if (unused > 0) warnings.push_back(file + ": dropped " + vertices(unused) + " no face uses");
    if (report) {
        report->degenerateFacesDropped = zeroArea;
        report->unusedVerticesDropped = unused;
        report->warnings = std::move(warnings);
    }
    return mesh;
}

}  // namespace

Mesh loadMesh(const fs::path& path, MeshReport* report) {
    const std::string file = path.string();
    std::error_code ec;
    if (!fs::exists(path, ec)) throw MeshError(path, "file not found");
    if (fs::is_directory(path, ec)) throw MeshError(path, "is a directory, expected a mesh file");
    const std::string ext = lowerExtension(path);
    if (std::find(kExtensions.begin(), kExtensions.end(), ext) == kExtensions.end())
        throw MeshError(
            path, "unsupported mesh format '" + path.extension().string() + "' (expected " + extensionList() + ")");
    const auto size = fs::file_size(path, ec);
    if (ec) throw MeshError(path, "cannot read the file: " + ec.message());
    if (size == 0) throw MeshError(path, "file is empty (0 bytes)");
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
        throw MeshError(path, "cannot read the file");
    return readMesh(bytes, file, ext, report);
}

Mesh loadMeshFromMemory(std::span<const unsigned char> bytes, const std::string& nameForMessages,
                        MeshReport* report) {
    return readMesh(bytes, nameForMessages, lowerExtension(nameForMessages), report);
}

std::span<const char* const> meshExtensions() { return kExtensions; }

Mesh defaultTeapot() {
    return loadMeshFromMemory({embedded::default_teapot_obj, embedded::default_teapot_obj_size}, "teapot.obj");
}

void writeMesh(const Mesh& mesh, const fs::path& path) {
    const std::string ext = lowerExtension(path);
    const auto& known = meshExtensions();
    if (std::find_if(known.begin(), known.end(), [&](const char* e) { return ext == e; }) == known.end())
        throw MeshError(path, "cannot write '" + ext + "' files (use " + extensionList() + ")");
    OMesh out;
    std::vector<VertexHandle> handles;
    handles.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) handles.push_back(out.add_vertex(OMesh::Point(p.x, p.y, p.z)));
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
        out.add_face(handles[mesh.indices[i]], handles[mesh.indices[i + 1]], handles[mesh.indices[i + 2]]);
    OpenMesh::IO::Options options;
    if (ext == ".ply" || ext == ".stl" || ext == ".off") options += OpenMesh::IO::Options::Binary;
    std::lock_guard<std::mutex> lock(openMeshMutex());
    if (!OpenMesh::IO::write_mesh(out, path.string(), options))
        throw MeshError(path, "could not be written");
}

Mesh makeSphere(int rings, int segments) {
    rings = std::max(rings, 2);
    segments = std::max(segments, 3);
    Mesh mesh;
    mesh.name = "sphere";
    // y-up: a vertex at each pole, rings - 1 circles of `segments` vertices between.
    auto direction = [](double theta, double phi) {
        return glm::vec3(
            glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    };
    mesh.positions.emplace_back(0.0f, 1.0f, 0.0f);
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s)
            mesh.positions.push_back(direction(std::numbers::pi * r / rings, 2.0 * std::numbers::pi * s / segments));
    mesh.positions.emplace_back(0.0f, -1.0f, 0.0f);
    const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    auto at = [&](int r, int s) { return static_cast<std::uint32_t>(1 + (r - 1) * segments + s % segments); };
    // Counter-clockwise seen from outside.
    for (int s = 0; s < segments; ++s) mesh.indices.insert(mesh.indices.end(), {0u, at(1, s + 1), at(1, s)});
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s)
            mesh.indices.insert(mesh.indices.end(),
                                {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r + 1, s)});
    for (int s = 0; s < segments; ++s)
        mesh.indices.insert(mesh.indices.end(), {south, at(rings - 1, s), at(rings - 1, s + 1)});
    mesh.normals.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) mesh.normals.push_back(glm::normalize(p));
    computeBounds(mesh);
    return mesh;
}

void computeVertexNormals(Mesh& mesh) {
    // The cross product of two edges is the face normal scaled by twice the area: summing them
    // weights each face by its area.
    std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
        const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
        sum[a] += n;
        sum[b] += n;
        sum[c] += n;
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t v = 0; v < sum.size(); ++v) {
        const double length = glm::length(sum[v]);
        mesh.normals[v] =
            length > 0.0 && std::isfinite(length) ? glm::vec3(sum[v] / length) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void computeBounds(Mesh& mesh) {
    if (mesh.positions.empty()) {
        mesh.bounds = {};
        return;
    }
    Bounds b{mesh.positions[0], mesh.positions[0]};
    for (const glm::vec3& p : mesh.positions) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    mesh.bounds = b;
}

}  // namespace mipgloss
