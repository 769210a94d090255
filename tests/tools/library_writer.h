// What tests/tools/library_writer writes, shared with the test that kills it
// (tests/ui/test_library_kill.cpp): material i of its endless loop.
#pragma once

#include "mipgloss/scene/library.h"

#include <string>

namespace mipgloss::test {

inline LibraryMaterial libraryWriterEntry(int i) {
    LibraryMaterial entry;
    entry.name = "m" + std::to_string(i);
    entry.material.lambda = 0.875f * static_cast<float>(i % 9);  // 0 .. 7, exact in binary
    entry.material.mode = i % 3 == 2 ? LookupMode::Normal : LookupMode::Reflect;
    entry.material.tint = Rgb(1.0f, 0.5f + 0.0625f * static_cast<float>(i % 8), 0.25f);
    entry.material.sharperAtGrazing = i % 2 == 1;
    return entry;
}

}  // namespace mipgloss::test
