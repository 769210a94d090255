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
// Assets (asset.h): refused with an AssetError naming the file, or parts whose meshes are valid and
// non-empty, each part's material in range, every material valid (isValidMaterial) with every
// texture channel in 0..3, and every warning naming the file.
// gltf_import: the whole input is a .glb or .gltf file's bytes (loadGltfFromMemory, "fuzz.glb";
// from memory nothing external is ever read).
std::string gltfImport(Bytes data);
// mtl_import: the first byte is the selector (bit 0 set: the OBJ is read without its library);
// the rest is split at its first 0 byte into OBJ text and MTL text (none when there is no 0).
// The OBJ is read as "fuzz.obj" with the MTL as its library "fuzz.mtl" (loadObjAssetFromMemory;
// an AssetError may name either file), and the MTL alone through parseMtl.
std::string mtlImport(Bytes data);

// Entry by target name ("environment_import", "mesh_import", "gltf_import", "mtl_import",
// "scene_file", "library_file");
// nullptr for an unknown name or one not built (the scene and library entries need Qt).
using Entry = std::string (*)(Bytes);
Entry entryNamed(std::string_view target);

}  // namespace mipgloss::fuzz
