// Helpers shared by the tests: asset paths and analytic environments.
#pragma once

#include "mipgloss/cubemap.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

namespace mipgloss::test {

inline std::filesystem::path assetDir() { return MIPGLOSS_ASSET_DIR; }
inline std::filesystem::path asset(const std::string& rel) { return assetDir() / rel; }

// A cube whose texel centres hold f(direction).
inline CubeMap cubeFromFunction(int size, const std::function<Rgb(const glm::vec3&)>& f) {
    CubeMap c(size);
    for (Face face : kAllFaces)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) c.at(face, x, y) = f(texelDirection(face, x, y, size));
    c.makeSeamless();
    return c;
}

}  // namespace mipgloss::test

#define MIPGLOSS_REQUIRE_ASSET(path)                                                   \
    do {                                                                               \
        if (!std::filesystem::exists(path)) GTEST_SKIP() << "asset missing: " << (path); \
    } while (0)
