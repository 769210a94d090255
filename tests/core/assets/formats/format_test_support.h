// What the mesh format readers' tests share (tests/core/assets/formats/): bytes as a span, the
// reason a reader refuses them with, and binary values in either byte order.
#pragma once

#include "mipgloss/assets/mesh_files.h"
#include "formats/mesh_formats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>

namespace mipgloss::test {

inline std::span<const unsigned char> asBytes(const std::string& s) {
    return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

// The MeshError `parse` throws on `bytes` named `file`; fails the test when it throws none.
template <typename Parse>
std::string refusal(Parse parse, const std::string& bytes, const std::string& file) {
    try {
        parse(asBytes(bytes), file);
    } catch (const MeshError& e) {
        EXPECT_EQ(e.file(), std::filesystem::path(file));
        return e.reason();
    }
    ADD_FAILURE() << file << " was read, expected a MeshError";
    return {};
}

#define EXPECT_CONTAINS(text, part) EXPECT_NE((text).find(part), std::string::npos) << "'" << (part) << "' not in: " << (text)

template <typename T>
void put(std::string& bytes, T value, bool bigEndian) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (bigEndian) std::reverse(raw, raw + sizeof(T));
    bytes.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

}  // namespace mipgloss::test
