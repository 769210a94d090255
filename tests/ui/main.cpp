// GoogleTest main for the Qt/OpenGL tests: one QApplication for the whole run, and the OpenGL 4.1
// core default format set before any context or widget exists.
#include "mipgloss/ui/gl_format.h"

#include <gtest/gtest.h>

#include <QApplication>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <QStandardPaths>

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    // Test discovery at build time runs without a display: listing needs no application.
    if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
    mipgloss::ui::setDefaultSurfaceFormat();
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
        QApplication app(argc, argv);
        result = RUN_ALL_TESTS();
    }
    if (ownHome) {
        std::error_code ignored;
        std::filesystem::remove_all(home, ignored);
    }
    return result;
}
