#include "gltf_mutator.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string_view>

namespace mipgloss::fuzz {

namespace {

struct Span {
    std::size_t begin = 0, end = 0;  // [begin, end) in the text
};

bool isNumberStart(char c) { return c == '-' || (c >= '0' && c <= '9'); }

// The end of the string starting at `at` (its opening quote), past the closing quote.
std::size_t stringEnd(const std::string& s, std::size_t at) {
    std::size_t i = at + 1;
    while (i < s.size() && s[i] != '"') i += s[i] == '\\' ? 2 : 1;
    return std::min(i + 1, s.size());
}

// The end of the number or literal starting at `at` (strings: stringEnd; containers: tokenize's
// stack).
std::size_t scalarEnd(const std::string& s, std::size_t at) {
    std::size_t i = at;
    while (i < s.size() && std::string_view(",]} \t\r\n:").find(s[i]) == std::string_view::npos) ++i;
    return i;
}

struct Tokens {
    std::vector<Span> values;   // every value (after ':', '[' or ',', outside strings)
    std::vector<Span> numbers;  // the values that are numbers
    std::vector<Span> strings;  // the values that are strings
    std::vector<Span> indices;  // numbers that follow an index key, or lie in a "nodes"/"children"-like array
};

bool isIndexKey(std::string_view key) {
    static constexpr std::array<std::string_view, 22> keys{
        "mesh", "material", "source", "sampler", "bufferView", "buffer", "index", "indices", "scene", "camera",
        "skin", "node", "POSITION", "NORMAL", "TANGENT", "TEXCOORD_0", "TEXCOORD_1", "COLOR_0", "texCoord",
        "input", "output", "skeleton"};
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

bool isIndexArrayKey(std::string_view key) {
    return key == "nodes" || key == "children" || key == "joints" || key == "materials" || key == "scenes";
}

Tokens tokenize(const std::string& s) {
    Tokens t;
    std::string lastKey;
    std::vector<std::string> arrayKeys;  // the key of each open array ("" for none)
    bool expectValue = false;
    // Containers' ends found by a stack in the same pass (valueEnd per bracket was quadratic in
    // the nesting: 8 000 levels made each mutation 10^8 steps); one never closed ends at the text's end.
    std::vector<std::size_t> open;  // indices into t.values of the containers not yet closed
    for (std::size_t i = 0; i < s.size();) {
        const char c = s[i];
        if (c == '"') {
            const std::size_t end = stringEnd(s, i);
            std::size_t j = end;
            while (j < s.size() && (s[j] == ' ' || s[j] == '\n' || s[j] == '\r' || s[j] == '\t')) ++j;
            if (j < s.size() && s[j] == ':') {  // a key (a value is never followed by ':')
                lastKey = end >= i + 2 ? s.substr(i + 1, end - i - 2) : std::string();
            } else {
                t.values.push_back({i, end});
                t.strings.push_back({i, end});
            }
            expectValue = false;
            i = end;
            continue;
        }
        if (c == ':' || c == ',') {
            expectValue = true;
            ++i;
            continue;
        }
        if (c == '[' || c == '{') {
            open.push_back(t.values.size());
            t.values.push_back({i, s.size()});
            if (c == '[') arrayKeys.push_back(expectValue ? lastKey : std::string());
            expectValue = c == '[';
            ++i;
            continue;
        }
        if (c == ']' || c == '}') {
            if (!open.empty()) {
                t.values[open.back()].end = i + 1;
                open.pop_back();
            }
            if (c == ']' && !arrayKeys.empty()) arrayKeys.pop_back();
            expectValue = false;
            ++i;
            continue;
        }
        if (isNumberStart(c) || c == 't' || c == 'f' || c == 'n') {
            const std::size_t end = scalarEnd(s, i);
            t.values.push_back({i, end});
            if (isNumberStart(c)) {
                t.numbers.push_back({i, end});
                const bool inIndexArray = !arrayKeys.empty() && isIndexArrayKey(arrayKeys.back());
                if (isIndexKey(lastKey) || inIndexArray) t.indices.push_back({i, end});
            }
            expectValue = false;
            i = std::max(end, i + 1);
            continue;
        }
        ++i;
    }
    return t;
}

template <class T>
const T& pick(const std::vector<T>& v, std::minstd_rand& rng) {
    return v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(rng)];
}

std::string replaced(const std::string& s, Span at, const std::string& with) {
    return s.substr(0, at.begin) + with + s.substr(at.end);
}

std::string nesting(std::minstd_rand& rng, std::size_t room) {
    static constexpr std::array<std::size_t, 7> depths{63, 64, 65, 256, 1000, 10000, 30000};
    std::size_t depth = depths[std::uniform_int_distribution<std::size_t>(0, depths.size() - 1)(rng)];
    const bool objects = rng() % 2 == 0;
    const std::size_t per = objects ? 7 : 2;  // {"a":…} or […]
    depth = std::min(depth, room > 0 ? (room - 1) / per : 0);
    std::string out;
    out.reserve(depth * per + 1);
    for (std::size_t i = 0; i < depth; ++i) out += objects ? "{\"a\":" : "[";
    out += "0";
    for (std::size_t i = 0; i < depth; ++i) out += objects ? "}" : "]";
    return out;
}

}  // namespace

std::string mutateGltfJson(const std::string& json, GltfMutation kind, std::minstd_rand& rng, std::size_t maxSize) {
    const Tokens t = tokenize(json);
    switch (kind) {
        case GltfMutation::InterestingNumber: {
            if (t.numbers.empty()) return json;
            static constexpr std::array<const char*, 16> numbers{
                "4294967296", "4294967297", "-1", "-4", "2147483647", "2147483648", "1e308", "-1e308", "-0", "0.5",
                "1e-320", "9007199254740993", "18446744073709551616", "65536", "1e999", "3.0"};
            return replaced(json, pick(t.numbers, rng), numbers[rng() % numbers.size()]);
        }
        case GltfMutation::IndexWrap: {
            const std::vector<Span>& from = t.indices.empty() ? t.numbers : t.indices;
            if (from.empty()) return json;
            const Span at = pick(from, rng);
            long long n = 0;
            for (std::size_t i = at.begin; i < at.end && json[i] >= '0' && json[i] <= '9' && n < 1000000; ++i)
                n = n * 10 + (json[i] - '0');
            const long long wraps[] = {n + (1LL << 32), n + (1LL << 31), -n - 1, n + (1LL << 33)};
            return replaced(json, at, std::to_string(wraps[rng() % 4]));
        }
        case GltfMutation::DeepNesting: {
            if (t.values.empty()) return json;
            const Span at = pick(t.values, rng);
            const std::size_t kept = json.size() - (at.end - at.begin);
            if (kept >= maxSize) return json;
            return replaced(json, at, nesting(rng, maxSize - kept));
        }
        case GltfMutation::WrongKind: {
            if (t.values.empty()) return json;
            static constexpr std::array<const char*, 9> kinds{"\"x\"", "null", "true", "{}", "[]", "[1,2]", "0",
                                                              "[null]", "{\"a\":1}"};
            return replaced(json, pick(t.values, rng), kinds[rng() % kinds.size()]);
        }
        case GltfMutation::HostileString: {
            if (t.strings.empty()) return json;
            static constexpr std::array<const char*, 10> strings{
                "\"../outside.png\"", "\"/etc/passwd\"", "\"tex.png%00.jpg\"", "\"%2e%2e/x.bin\"",
                "\"data:image/png;base64,!!!!\"", "\"data:application/octet-stream;base64,AAAA\"", "\"\"",
                "\"C:\\\\x.png\"", "\"file:///etc/passwd\"", "\"a%zz.png\""};
            return replaced(json, pick(t.strings, rng), strings[rng() % strings.size()]);
        }
        case GltfMutation::DuplicateValue: {
            if (t.values.empty()) return json;
            const Span at = pick(t.values, rng);
            const std::string value = json.substr(at.begin, at.end - at.begin);
            if (json.size() + value.size() + 1 > maxSize) return json;
            return json.substr(0, at.end) + "," + value + json.substr(at.end);
        }
    }
    return json;
}

std::vector<std::uint8_t> mutateGltf(const std::vector<std::uint8_t>& input, std::minstd_rand& rng, std::size_t maxSize) {
    const auto kind = static_cast<GltfMutation>(rng() % kGltfMutationCount);
    auto u32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        std::memcpy(&v, input.data() + at, 4);
        return v;
    };
    const bool glb = input.size() >= 20 && std::memcmp(input.data(), "glTF", 4) == 0 &&
                     std::memcmp(input.data() + 16, "JSON", 4) == 0;
    if (!glb) {
        if (input.empty() || maxSize == 0) return {};
        const std::string json(input.begin(), input.end());
        const std::string out = mutateGltfJson(json, kind, rng, maxSize);
        if (out == json || out.size() > maxSize) return {};
        return {out.begin(), out.end()};
    }
    const std::size_t jsonLength = std::min<std::size_t>(u32(12), input.size() - 20);
    const std::string json(input.begin() + 20, input.begin() + 20 + static_cast<std::ptrdiff_t>(jsonLength));
    const std::size_t rest = input.size() - 20 - jsonLength;  // the chunks after the JSON
    if (20 + rest + 4 > maxSize) return {};
    std::string out = mutateGltfJson(json, kind, rng, maxSize - 20 - rest - 4);
    if (out == json) return {};
    while (out.size() % 4 != 0) out += ' ';  // chunks are 4-byte aligned (glTF 2.0, GLB)
    std::vector<std::uint8_t> result(input.begin(), input.begin() + 20);
    result.insert(result.end(), out.begin(), out.end());
    result.insert(result.end(), input.end() - static_cast<std::ptrdiff_t>(rest), input.end());
    const auto total = static_cast<std::uint32_t>(result.size()), chunk = static_cast<std::uint32_t>(out.size());
    std::memcpy(result.data() + 8, &total, 4);
    std::memcpy(result.data() + 12, &chunk, 4);
    return result.size() <= maxSize ? result : std::vector<std::uint8_t>{};
}

}  // namespace mipgloss::fuzz
