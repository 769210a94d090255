// GoogleTest main for the Qt/OpenGL tests: one QApplication for the whole run, and the OpenGL 4.1
// core default format set before any context or widget exists.
#include "mipgloss/ui/gl_format.h"

#include <gtest/gtest.h>

#include <QApplication>

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    // Test discovery at build time runs without a display: listing needs no application.
    if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
    mipgloss::ui::setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    return RUN_ALL_TESTS();
}
