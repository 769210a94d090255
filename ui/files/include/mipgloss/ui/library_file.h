// Material library files: JSON, format "mipgloss-library", version 3 (versions 1 and 2 still load).
//
//   {
//     "format": "mipgloss-library", "version": 3,
//     "materials": [{"name": "Gold", "lambda": 3, "phongExponent": 767, "mode": "reflect",
//                    "useIrradiance": false, "tint": [1, 0.8, 0.3], "sharperAtGrazing": false,
//                    "layers": {"baseColor": [1, 0.78, 0.34], "metallic": 1, "roughness": 0.25, ...}}]
//   }
//
// The material fields are the scene file's (scene_file.h; material_json.h), with the same checks:
// λ in [0, kMaxLambda] (never silently clamped), "phongExponent" informative, tint finite and >= 0,
// every layer value in [0, 1]. Version 2 added layered materials ("layers", optional); a version 1
// file has none and loads as it always did. Version 3 added texture maps ("layers"."maps", an
// imported asset's: material_json.h), their files written as held (absolute, as imported: a
// library outlives the folder it was saved from). Files are written as version 3.
// Names must be valid (library.h materialNameProblem) and unique.
//
// Reading is all-or-nothing and never modifies the file: anything unreadable (not JSON, not a
// library, a newer version, a wrong type, an absurd value, a duplicate name) is a LibraryFileError
// naming the file and the reason. Writing is atomic (atomic_file.h): a reader, or a process killed
// at any moment, sees the old file or the new one, never a mixture.
#pragma once

#include "mipgloss/io/file_error.h"
#include "mipgloss/scene/library.h"

#include <QByteArray>

#include <filesystem>
#include <string>
#include <vector>

namespace mipgloss::ui {

inline constexpr const char* kLibraryFormat = "mipgloss-library";
inline constexpr int kLibraryVersion = 3;

class LibraryFileError : public FileError {
public:
    using FileError::FileError;
};

// What a library file held that was read anyway: a "phongExponent" that disagrees with its λ
// (the λ is used, as in scene files). One line each, naming the file.
struct LibraryFileReport {
    std::vector<std::string> warnings;
};

QByteArray libraryToJson(const MaterialLibrary& library);
// `file` names the file in errors. Throws LibraryFileError.
MaterialLibrary libraryFromJson(const QByteArray& json, const std::filesystem::path& file,
                                LibraryFileReport* report = nullptr);

// Throws LibraryFileError (including kFileNotFound, mipgloss/io/file_error.h).
MaterialLibrary loadLibrary(const std::filesystem::path& file, LibraryFileReport* report = nullptr);
// Atomic; creates the folder if missing. Refuses (LibraryFileError, the file untouched) a library
// that would not load again: an invalid or repeated name, an absurd λ or tint. Throws
// LibraryFileError.
void saveLibrary(const MaterialLibrary& library, const std::filesystem::path& file);

// The user's library: library.json in QStandardPaths::AppDataLocation (needs the application's
// organisation and name set, as mipgloss-gui does).
std::filesystem::path defaultLibraryPath();

}  // namespace mipgloss::ui
