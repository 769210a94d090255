// What the mesh file readers share (internal to mipgloss_assets, core/assets/src/formats/): text
// lines and words with their line numbers, numbers as the text formats write them, little- and
// big-endian binary values, and the wording of counts and places in messages.
#pragma once

#include "mipgloss/assets/mesh_files.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <span>
#include <string>

namespace mipgloss::meshfile {

// A path's extension in lower case with its dot (".obj"): how every reader picks a format.
inline std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// "1 face", "3 faces", "1 vertex", "2 vertices".
inline std::string count(std::size_t n, std::string_view one, std::string_view many) {
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

inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

inline std::string_view nextToken(std::string_view& s) {
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
inline std::optional<float> parseFloat(std::string_view token) {
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
inline bool parseXyz(std::string_view rest, bool& finite, std::array<float, 3>& xyz) {
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
inline std::optional<std::size_t> firstBinaryByte(std::span<const unsigned char> bytes) {
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        const unsigned char c = bytes[i];
        if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\v' && c != '\f') || c == 0x7f) return i;
    }
    return std::nullopt;
}

inline std::string binaryByteText(std::span<const unsigned char> bytes, std::size_t at) {
    char text[64];
    std::snprintf(text, sizeof text, "byte 0x%02x at offset %zu", static_cast<unsigned>(bytes[at]), at);
    return text;
}

inline std::uint32_t readLe32(std::span<const unsigned char> bytes, std::size_t at) {
    return static_cast<std::uint32_t>(bytes[at]) | static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
           static_cast<std::uint32_t>(bytes[at + 2]) << 16 | static_cast<std::uint32_t>(bytes[at + 3]) << 24;
}

inline bool startsWithWord(std::span<const unsigned char> bytes, std::string_view word) {
    std::size_t i = 0;
    while (i < bytes.size() && (isBlank(static_cast<char>(bytes[i])) || bytes[i] == '\n')) ++i;
    if (bytes.size() - i < word.size()) return false;
    for (std::size_t k = 0; k < word.size(); ++k)
        if (std::tolower(bytes[i + k]) != word[k]) return false;
    return true;
}

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
inline std::string shown(std::string_view word) {
    std::string out(word.substr(0, 40));
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return word.size() > 40 ? out + "..." : out;
}

inline std::optional<long long> parseInteger(std::string_view token) {
    if (!token.empty() && token[0] == '+') token.remove_prefix(1);
    long long value = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
    return value;
}

// An element count as a header states it: decimal digits only, at most kMaxElements.
inline std::optional<std::uint64_t> parseCount(std::string_view token) {
    std::uint64_t value = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() || value > kMaxElements)
        return std::nullopt;
    return value;
}

inline std::string atOffset(std::size_t offset) { return "byte offset " + std::to_string(offset) + ": "; }

// a * b + c, saturating (header counts times record sizes, compared with the file size).
inline std::uint64_t mulAdd(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
    if (b != 0 && a > (max - c) / b) return max;
    return a * b + c;
}

}  // namespace mipgloss::meshfile
