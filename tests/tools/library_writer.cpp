// The child the kill-safety test kills (tests/ui/test_library_kill.cpp): from an empty library, adds
// libraryWriterEntry(0), (1), ... and saves the library after each (saveLibrary: the atomic write)
// in an endless loop, until it is killed. Prints "writing" once, just before the first save, so
// the test can kill it at a chosen moment after the writes began.
#include "tools/library_writer.h"

#include "mipgloss/ui/library_file.h"

#include <cstdio>
#include <exception>
#include <filesystem>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: mipgloss_library_writer LIB.mglib\n");
        return 2;
    }
    const std::filesystem::path file = argv[1];
    mipgloss::MaterialLibrary library;
    std::printf("writing\n");
    std::fflush(stdout);
    try {
        for (int i = 0;; ++i) {
            library.entries.push_back(mipgloss::test::libraryWriterEntry(i));
            mipgloss::ui::saveLibrary(library, file);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "mipgloss_library_writer: %s\n", e.what());
        return 1;
    }
}
