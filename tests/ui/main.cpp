// GoogleTest main for the UI's tests, one per room (tests/CMakeLists.txt): one application for the
// whole run, the one the room needs (MIPGLOSS_TEST_APPLICATION): QCoreApplication for the files and
// documents (no display), QGuiApplication for the renderer, QApplication for the widgets; with
// OpenGL, the 4.1 core default format set before any context or widget exists.
#include <gtest/gtest.h>

#include <QStandardPaths>

#if defined(MIPGLOSS_HEADLESS_TESTS)
#include <QCoreApplication>
#define MIPGLOSS_TEST_APPLICATION QCoreApplication
#else
#include "mipgloss/ui/gl_format.h"
#if defined(MIPGLOSS_RENDER_TESTS)
#include <QGuiApplication>
#define MIPGLOSS_TEST_APPLICATION QGuiApplication
#else
#include <QApplication>
#define MIPGLOSS_TEST_APPLICATION QApplication
#endif
#endif

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

// Under AddressSanitizer (the asan preset), with OpenGL: no leak check at exit for this binary.
// Mesa's llvmpipe driver is unloaded before LeakSanitizer runs, so the few hundred bytes it keeps
// (one realloc and two callocs per process) have no module or function left to suppress them by. ASan still
// checks every access of these tests; the core test binaries keep the leak check, and the
// preset's ASAN_OPTIONS, which do not name detect_leaks, add to this rather than replace it.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MIPGLOSS_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define MIPGLOSS_UNDER_ASAN 1
#endif
#if defined(MIPGLOSS_HEADLESS_TESTS)
#undef MIPGLOSS_UNDER_ASAN  // no OpenGL here: the leak check stays
#endif
#ifdef MIPGLOSS_UNDER_ASAN
extern "C" const char* __asan_default_options() { return "detect_leaks=0"; }
#endif

namespace {

// The programs these tests start (`mipgloss render`, the library writer) draw with the same Mesa
// driver: they get the same exemption through the environment they inherit.
void exemptChildrenFromLeakCheck() {
#ifdef MIPGLOSS_UNDER_ASAN
    const char* given = std::getenv("ASAN_OPTIONS");
    std::string options = given ? std::string(given) + ":" : std::string();
    setenv("ASAN_OPTIONS", (options + "detect_leaks=0").c_str(), 1);
#endif
}

}  // namespace

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    exemptChildrenFromLeakCheck();
    // Test discovery at build time runs without a display: listing needs no application.
    if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
#if !defined(MIPGLOSS_HEADLESS_TESTS)
    mipgloss::ui::setDefaultSurfaceFormat();
#endif
    // Library, autosave and recent files go to $HOME/.qttest (QStandardPaths' test mode), never the
    // user's own folders; and $HOME is a fresh folder for this process, because ctest runs each
    // test in its own process, two at a time, and tests that clear or count autosaves and recent
    // files must not see each other's.
    char home[] = "/tmp/mipgloss-ui-test-XXXXXX";
    const bool ownHome = mkdtemp(home) != nullptr;
    if (ownHome) setenv("HOME", home, 1);
    QStandardPaths::setTestModeEnabled(true);
    int result = 0;
    {
        MIPGLOSS_TEST_APPLICATION app(argc, argv);
        result = RUN_ALL_TESTS();
    }
    if (ownHome) {
        std::error_code ignored;
        std::filesystem::remove_all(home, ignored);
    }
    return result;
}
