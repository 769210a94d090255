// The fuzz targets' bodies, one per file format we parse or front, shared by the libFuzzer
// executables (fuzz_main.cpp) and the regression test (test_fuzz_regressions.cpp) that replays
// every committed corpus seed and crash input through the same code in the normal suite.
//
// Each entry feeds the bytes to the parser and checks the contract of its header:
//   - bad input is refused with the format's own FileError (EnvError, MeshError, SceneFileError,
//     LibraryFileError) whose message names the file;
//   - what loads satisfies the type's invariants (a valid mesh, finite non-negative texels, a
//     scene or library that saves and loads again).
// A broken contract is returned as a description; any other exception (std::bad_alloc,
// std::out_of_range, ...) escapes to the caller, and a crash or hang is the sanitizer's or
// libFuzzer's to report. Inputs are small: libFuzzer is run with -max_len (scripts/run-fuzz.sh).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace mipgloss::fuzz {

using Bytes = std::span<const std::uint8_t>;

// The first byte picks the format (its low bits index the target's extension list) and, for the
// environment, the layout and face size; the rest is the file. Empty when the contract holds.
std::string environmentImport(Bytes data);
std::string meshImport(Bytes data);
std::string sceneFile(Bytes data);     // the whole input is the JSON text
std::string libraryFile(Bytes data);   // the whole input is the JSON text

// Entry by target name ("environment_import", "mesh_import", "scene_file", "library_file");
// nullptr for an unknown name or one not built (the scene and library entries need Qt).
using Entry = std::string (*)(Bytes);
Entry entryNamed(std::string_view target);

}  // namespace mipgloss::fuzz
