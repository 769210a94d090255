// Helpers shared by the tests: asset paths and analytic environments.
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <functional>
#include <string>
#include <system_error>

#include <unistd.h>

namespace mipgloss::test {

// Whether this binary is built with a sanitizer (the asan and tsan presets). Tests that repeat a
// whole process many times to catch a moment (the kill tests) repeat it fewer times there: the
// sanitizer checks the code's accesses, which a few runs exercise as well as many, and a process
// start costs it about a second (0.03 s in the dev build, which keeps the full count).
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define MIPGLOSS_TEST_UNDER_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MIPGLOSS_TEST_UNDER_SANITIZER 1
#endif
#ifdef MIPGLOSS_TEST_UNDER_SANITIZER
inline constexpr bool kUnderSanitizer = true;
#else
inline constexpr bool kUnderSanitizer = false;
#endif

inline std::filesystem::path assetDir() { return MIPGLOSS_ASSET_DIR; }
inline std::filesystem::path asset(const std::string& rel) { return assetDir() / rel; }

// A fresh folder per test (named for the process and the test), removed afterwards.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("mipgloss_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// A file's bytes as a string, and bytes written to a file.
inline std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

inline void writeBytes(const std::filesystem::path& file, const std::string& bytes) {
    std::ofstream out(file, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << file;
}

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

// Committed assets are part of the test: a missing one fails the test (it never skips, so an
// accuracy test cannot pass by not running).
#define MIPGLOSS_REQUIRE_ASSET(path)                                                        \
    do {                                                                                    \
        ASSERT_TRUE(std::filesystem::exists(path)) << "committed test asset missing: " << (path); \
    } while (0)
