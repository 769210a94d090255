#include "gltf_json_check.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace mipgloss::gltfjson {

namespace {

// Keys whose value is an index into one of the file's arrays (glTF 2.0's glTFid).
bool isIndexKey(std::string_view key) {
    for (const char* k : {"scene", "mesh", "camera", "skin", "skeleton", "bufferView", "buffer", "material", "indices",
                          "source", "sampler", "index", "input", "output", "node"})
        if (key == k) return true;
    return false;
}
// Arrays of indices (inside an element: at the top level "nodes" is the array of nodes itself).
bool isIndexArray(std::string_view key) { return key == "children" || key == "nodes" || key == "joints"; }
// Sizes and offsets: whole numbers >= 0.
bool isSizeKey(std::string_view key) {
    for (const char* k : {"byteOffset", "byteLength", "byteStride", "count", "texCoord"})
        if (key == k) return true;
    return false;
}
// Vectors of numbers (or, for "scale", a normal map's number).
bool isNumberArray(std::string_view key) {
    for (const char* k : {"matrix", "translation", "rotation", "scale", "baseColorFactor", "emissiveFactor",
                          "specularColorFactor", "weights", "offset", "min", "max"})
        if (key == k) return true;
    return false;
}

// Members whose value is a string (glTF 2.0's schema), a number, or true/false.
bool isStringKey(std::string_view key) {
    for (const char* k : {"name", "uri", "mimeType", "generator", "version", "minVersion", "copyright", "alphaMode",
                          "interpolation", "path", "type"})
        if (key == k) return true;
    return false;
}
bool isNumberKey(std::string_view key) {
    for (const char* k : {"metallicFactor", "roughnessFactor", "alphaCutoff", "strength", "yfov", "znear", "zfar",
                          "aspectRatio", "xmag", "ymag", "emissiveStrength", "ior", "specularFactor", "clearcoatFactor",
                          "clearcoatRoughnessFactor"})
        if (key == k) return true;
    return false;
}
bool isBooleanKey(std::string_view key) { return key == "normalized" || key == "doubleSided"; }

// The enumerations glTF 2.0 gives as whole numbers, by member and the array its object is in
// ("" when none lists them): the values allowed.
const std::vector<double>* enumerationOf(std::string_view member, std::string_view array) {
    static const std::vector<double> modes{0, 1, 2, 3, 4, 5, 6}, targets{34962, 34963},
        componentTypes{5120, 5121, 5122, 5123, 5125, 5126}, magFilters{9728, 9729},
        minFilters{9728, 9729, 9984, 9985, 9986, 9987}, wraps{33071, 33648, 10497};
    if (member == "mode" && array == "primitives") return &modes;
    if (member == "target" && array == "bufferViews") return &targets;
    if (member == "componentType") return &componentTypes;
    if (member == "magFilter") return &magFilters;
    if (member == "minFilter") return &minFilters;
    if (member == "wrapS" || member == "wrapT") return &wraps;
    return nullptr;
}

// The enumerations glTF 2.0 gives as strings, likewise (an image's mimeType: the core's two and
// the two its texture extensions add).
const std::vector<std::string_view>* wordsOf(std::string_view member, std::string_view array) {
    static const std::vector<std::string_view> alphaModes{"OPAQUE", "MASK", "BLEND"},
        accessorTypes{"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"},
        cameraTypes{"perspective", "orthographic"}, mimeTypes{"image/jpeg", "image/png", "image/webp", "image/ktx2"};
    if (member == "alphaMode" && array == "materials") return &alphaModes;
    if (member == "type" && array == "accessors") return &accessorTypes;
    if (member == "type" && array == "cameras") return &cameraTypes;
    if (member == "mimeType" && array == "images") return &mimeTypes;
    return nullptr;
}

// "a, b, c": an enumeration's values for a message.
template <class Values, class Show>
std::string joined(const Values& values, Show show) {
    std::string out;
    for (const auto& v : values) out += (out.empty() ? "" : ", ") + show(v);
    return out;
}

// Whether uri[i] starts a %XX escape (RFC 3986: '%' and two hexadecimal digits).
bool escapeAt(std::string_view uri, std::size_t i) {
    auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
    return uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) && hex(uri[i + 2]);
}

constexpr double kLargestIndex = 2147483647.0;        // glTF's indices are int32 in every reader we know
constexpr double kLargestSize = 9007199254740992.0;   // 2^53: JSON's exact integers

struct Frame {
    bool object = false;
    std::string key;     // the member key this container is the value of (an array's, for its elements)
    int depth = 0;       // 1: the top-level object
    bool skip = false;   // extras, or an extension not read: its nesting only
    bool attributes = false;  // its members are accessor indices (a primitive's attributes, a morph target)
    std::size_t count = 0;    // elements (array) or members (object) so far
    std::string member;       // object: the current member's key
};

enum class Kind { Number, String, Literal, Object, Array };

struct Syntax {
    std::string text;
};

class Scanner {
public:
    Scanner(std::string_view json, const std::set<std::string>& read, std::set<std::string>* imageUris)
        : s_(json), read_(read), imageUris_(imageUris) {}

    Problem run() {
        try {
            scan();
        } catch (const Syntax& why) {
            return {why.text, true};
        } catch (const std::string& why) {
            return {why, false};
        }
        return {};
    }

private:
    [[noreturn]] void syntax(const std::string& what) const {
        std::size_t line = 1, column = 1;
        for (std::size_t k = 0; k < i_ && k < s_.size(); ++k) {
            if (s_[k] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        throw Syntax{"its JSON is not valid: " + what + " at line " + std::to_string(line) + ", column " +
                     std::to_string(column)};
    }
    [[noreturn]] void refuse(const std::string& what) const { throw path() + " " + what; }

    // The JSON path of the value being read: nodes[3].mesh.
    std::string path() const {
        std::string out;
        for (const Frame& f : stack_) {
            if (f.object) {
                if (!out.empty()) out += '.';
                out += f.member;
            } else {
                out += '[' + std::to_string(f.count) + ']';
            }
        }
        return out.empty() ? std::string("the top level") : out;
    }

    void whitespace() {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
    }

    std::string string() {  // at the opening quote; returns the decoded text (non-ASCII escapes as '?')
        ++i_;
        std::string out;
        while (true) {
            if (i_ >= s_.size()) syntax("a string is not closed");
            const char c = s_[i_++];
            if (c == '"') return out;
            if (static_cast<unsigned char>(c) < 0x20) syntax("a control character inside a string");
            if (c != '\\') {
                out += c;
                continue;
            }
            if (i_ >= s_.size()) syntax("a string is not closed");
            const char e = s_[i_++];
            switch (e) {
                case '"': case '\\': case '/': out += e; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': {
                    if (i_ + 4 > s_.size()) syntax("a \\u escape is cut short");
                    unsigned code = 0;
                    for (int k = 0; k < 4; ++k) {
                        const char h = s_[i_++];
                        code <<= 4;
                        if (h >= '0' && h <= '9') code |= static_cast<unsigned>(h - '0');
                        else if (h >= 'a' && h <= 'f') code |= static_cast<unsigned>(h - 'a' + 10);
                        else if (h >= 'A' && h <= 'F') code |= static_cast<unsigned>(h - 'A' + 10);
                        else syntax("a \\u escape that is not hexadecimal");
                    }
                    out += code < 0x80 ? static_cast<char>(code) : '?';
                    break;
                }
                default: syntax(std::string("an unknown escape \\") + e);
            }
        }
    }

    // The number at i_, its text checked against JSON's grammar by strtod's reading all of it.
    double number() {
        const std::size_t start = i_;
        while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '-' || s_[i_] == '+' ||
                                  s_[i_] == '.' || s_[i_] == 'e' || s_[i_] == 'E'))
            ++i_;
        const std::string text(s_.substr(start, i_ - start));
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || text[0] == '+' || end != text.c_str() + text.size()) {
            i_ = start;
            syntax("a number that is not one (\"" + text.substr(0, 24) + "\")");
        }
        return value;
    }

    // The rule for a value about to be read, from the member or array holding it.
    void check(Kind kind, double value, std::string_view text = {}) {
        if (stack_.empty()) return;  // the top level: value() has seen it is an object
        const Frame& parent = stack_.back();
        if (parent.skip) return;
        auto whole = [&](double largest, const char* what) {
            const std::string rule = std::string(what) + " is a whole number from 0 to " +
                                     (largest == kLargestIndex ? "2147483647" : "2^53");
            if (kind != Kind::Number) refuse("is not a number: " + rule);
            if (!(std::isfinite(value) && value >= 0.0 && value <= largest && value == std::floor(value))) {
                std::string shown = std::to_string(value);
                if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e18)
                    shown = std::to_string(static_cast<long long>(value));
                refuse("is " + shown + ": " + rule);
            }
        };
        if (parent.object) {
            if (parent.attributes || isIndexKey(parent.member)) whole(kLargestIndex, "an index");
            else if (isSizeKey(parent.member)) {
                whole(kLargestSize, "a size or offset");
                // glTF's schema: a buffer, a buffer view and an accessor hold at least one byte
                // or element (a BIN chunk with a 0-byte buffer threw out of tinygltf unnamed).
                if ((parent.member == "byteLength" || parent.member == "count") && value < 1.0)
                    refuse("is 0: a " + std::string(parent.member == "count" ? "count" : "byteLength") + " is at least 1");
            }
            else if (isNumberArray(parent.member) && kind != Kind::Array && kind != Kind::Number)
                refuse("must be numbers");
            else if (const std::vector<double>* allowed = enumerationOf(parent.member, parent.key)) {
                // A value outside glTF's list (a wrapped target, a mode of 3.0e9) is not a hint to
                // ignore: tinygltf would read it, or its default, without a word.
                if (kind != Kind::Number || std::find(allowed->begin(), allowed->end(), value) == allowed->end())
                    refuse(std::string(kind == Kind::Number ? "is not one of glTF's values (" : "is not a number (glTF's values: ") +
                           joined(*allowed, [](double v) { return std::to_string(static_cast<int>(v)); }) + ")");
            } else if (isStringKey(parent.member) && kind != Kind::String)
                refuse("is not a string");
            else if (const std::vector<std::string_view>* words = wordsOf(parent.member, parent.key);
                     words && std::find(words->begin(), words->end(), text) == words->end())
                refuse("is \"" + std::string(text.substr(0, 40)) + "\", not one of glTF's values (" +
                       joined(*words, [](std::string_view w) { return std::string(w); }) + ")");
            else if (isNumberKey(parent.member) && kind != Kind::Number)
                refuse("is not a number");
            else if (isBooleanKey(parent.member) && kind != Kind::Literal)
                refuse("is not true or false");
        } else if (parent.depth >= 3 && isIndexArray(parent.key)) {
            whole(kLargestIndex, "an index");
        } else if (isNumberArray(parent.key) && kind != Kind::Number) {
            refuse("is not a number (the vector must hold numbers only)");
        }
    }

    // A buffer's or image's URI (not a data: URI): its %-escapes decoded (RFC 3986), a NUL in it
    // refused (it would cut the path short), and a buffer's refused when absolute or leaving the
    // asset's folder, since only the asset's own folder is read (docs/assets.md, "Paths"). An
    // image's such URI is the reader's warning (the map left out), not a refusal.
    void checkUri(const std::string& text) {
        if (stack_.size() != 3 || !stack_.back().object || stack_.back().member != "uri") return;
        const std::string& array = stack_.back().key;
        if (array != "buffers" && array != "images") return;
        if (text.rfind("data:", 0) == 0) return;
        for (std::size_t i = 0; i < text.size(); ++i)
            if (text[i] == '%' && !escapeAt(text, i))
                refuse("holds a '%' that is not an escape (RFC 3986: '%' and two hexadecimal digits; a file name's '%' is written %25)");
        const std::string decoded = decodeUri(text);
        if (decoded.find('\0') != std::string::npos) refuse("holds an encoded NUL (%00): not a file name");
        if (array == "images" && imageUris_) {
            imageUris_->insert(decoded);
            imageUris_->insert(text);  // as tinygltf may join it, undecoded
        }
        if (array == "buffers" && leavesFolder(decoded))
            refuse("\"" + text.substr(0, 120) + "\" lies outside the asset's folder; mipgloss reads only files in it or below it");
    }

    void open(bool object) {
        Frame f;
        f.object = object;
        if (!stack_.empty()) {
            const Frame& parent = stack_.back();
            f.key = parent.object ? parent.member : parent.key;
            f.skip = parent.skip || (parent.object && parent.member == "extras") ||
                     (parent.object && parent.key == "extensions" && !read_.count(parent.member));
            f.attributes = !f.skip && object &&
                           ((parent.object && parent.member == "attributes") || (!parent.object && parent.key == "targets"));
        }
        f.depth = static_cast<int>(stack_.size()) + 1;
        if (f.depth > kMaxGltfJsonDepth)
            throw "its JSON nests deeper than " + std::to_string(kMaxGltfJsonDepth) + " levels (at " + path() +
                ", byte " + std::to_string(i_) + "); glTF needs a handful";
        stack_.push_back(std::move(f));
    }

    // One value at i_ (after whitespace); a container is opened and left on the stack.
    void value() {
        whitespace();
        if (i_ >= s_.size()) syntax("the text ends where a value should be");
        const char c = s_[i_];
        if (stack_.empty() && c != '{') syntax("the file is not a JSON object");
        if (c == '{' || c == '[') {
            // A sparse accessor's "indices" is an object of its own (the reader refuses sparse
            // accessors by name later); a primitive's is an index like any other.
            if (!(c == '{' && !stack_.empty() && stack_.back().object && stack_.back().member == "indices" &&
                  stack_.back().key == "sparse"))
                check(c == '{' ? Kind::Object : Kind::Array, 0.0);
            ++i_;
            open(c == '{');
            return;
        }
        // A refusal names the value by its JSON path (path()), not its byte: no position to keep.
        if (c == '"') {
            const std::string text = string();
            check(Kind::String, 0.0, text);
            checkUri(text);
            return;
        }
        if (c == '-' || std::isdigit(static_cast<unsigned char>(c))) {
            check(Kind::Number, number());
            return;
        }
        for (const std::string_view word : {"true", "false", "null"})
            if (s_.substr(i_, word.size()) == word) {
                check(Kind::Literal, 0.0);
                i_ += word.size();
                return;
            }
        syntax(std::string("unexpected '") + (std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c) : std::string("?")) +
               "'");
    }

    void scan() {
        value();
        if (stack_.empty()) syntax("the file is not a JSON object");
        while (!stack_.empty()) {
            whitespace();
            if (i_ >= s_.size()) syntax("the text ends inside " + path());
            Frame& top = stack_.back();
            const char c = s_[i_], close = top.object ? '}' : ']';
            if (c == close) {
                ++i_;
                stack_.pop_back();
                if (!stack_.empty()) ++stack_.back().count;  // the container was its parent's value
                continue;
            }
            if (top.count > 0) {
                if (c != ',') syntax(std::string("expected ',' or '") + close + "'");
                ++i_;
                whitespace();
            }
            if (top.object) {
                if (i_ >= s_.size() || s_[i_] != '"') syntax("expected a member's name in quotes");
                top.member = string();
                whitespace();
                if (i_ >= s_.size() || s_[i_] != ':') syntax("expected ':' after \"" + top.member + "\"");
                ++i_;
            }
            const std::size_t depth = stack_.size();
            value();  // `top` may be gone: a container value pushes a frame
            if (stack_.size() == depth) ++stack_.back().count;  // a scalar, done
        }
        // A GLB's JSON chunk is padded to 4 bytes (with spaces, or NULs by some writers).
        while (i_ < s_.size() && (s_[i_] == '\0' || s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
        if (i_ < s_.size()) syntax("text after the JSON object");
    }

    std::string_view s_;
    const std::set<std::string>& read_;
    std::set<std::string>* imageUris_;
    std::size_t i_ = 0;
    std::vector<Frame> stack_;
};

}  // namespace

std::string decodeUri(std::string_view uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (escapeAt(uri, i)) {
            out += static_cast<char>(std::stoi(std::string(uri.substr(i + 1, 2)), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

bool leavesFolder(std::string_view path) {
    if (path.empty()) return false;
    if (path[0] == '/' || path[0] == '\\') return true;
    if (path.size() >= 2 && std::isalpha(static_cast<unsigned char>(path[0])) && path[1] == ':') return true;  // C:
    int depth = 0;
    std::size_t start = 0;
    while (start <= path.size()) {
        std::size_t end = path.find_first_of("/\\", start);
        if (end == std::string_view::npos) end = path.size();
        const std::string_view part = path.substr(start, end - start);
        if (part == "..") {
            if (--depth < 0) return true;
        } else if (!part.empty() && part != ".") {
            ++depth;
        }
        start = end + 1;
    }
    return false;
}

Problem problem(std::string_view json, const std::set<std::string>& readExtensions, std::set<std::string>* imageUris) {
    return Scanner(json, readExtensions, imageUris).run();
}

}  // namespace mipgloss::gltfjson
