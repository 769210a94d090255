// Scene files: JSON, format "mipgloss-scene", version 1.
//
//   {
//     "format": "mipgloss-scene", "version": 1,
//     "environment": {"source": "env/sky.exr" | "builtin:courtyard", "layout": "auto",
//                     "handedness": "right", "faceSize": 128, "builder": "phong",
//                     "rotationDegrees": 0},
//     "display": {"showBackground": true, "backgroundLambda": 0, "exposureEv": 0,
//                 "toneMap": "aces", "samples": 4},
//     "objects": [{"name": "bunny", "mesh": "meshes/bunny.obj" | "builtin:teapot" | "builtin:sphere",
//                  "visible": true,
//                  "transform": {"translation": [x, y, z], "rotationDegrees": [x, y, z], "scale": 1},
//                  "material": {"lambda": 3, "mode": "reflect" | "normal", "useIrradiance": false,
//                               "tint": [r, g, b], "sharperAtGrazing": false}}]
//   }
//
// Paths: saved relative to the scene file's folder when the file lies inside it or at most two
// levels above it (so a project folder moved as a whole keeps working), absolute otherwise; loaded
// relative to the scene file's folder. A loaded scene's meshSource and environment source are
// absolute paths (or builtin:...), so saving elsewhere relativises them afresh.
//
// Loading is all-or-nothing: the whole file is checked and every mesh loaded (a path used twice is
// loaded once and shared) before a Scene is returned. Errors (SceneFileError: not JSON, wrong
// format or version, a wrong type, a non-finite number, a missing or broken mesh file, a missing
// environment file, an unknown name) name the scene file and the problem. Out-of-range values with
// an obvious nearest one (λ outside [0, kMaxLambda], face size, samples, background λ, exposure)
// are clamped with a warning in the report. Optional keys default to the values in scene.h.
#pragma once

#include "mipgloss/io/file_error.h"
#include "mipgloss/scene/scene.h"

#include <QByteArray>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss::ui {

inline constexpr const char* kSceneFormat = "mipgloss-scene";
inline constexpr int kSceneVersion = 1;

class SceneFileError : public FileError {
public:
    using FileError::FileError;
};

struct SceneFileReport {
    std::vector<std::string> warnings;  // one line each, naming the file
};

// The JSON text for `scene`, paths written relative to `sceneFile`'s folder (see above).
QByteArray sceneToJson(const Scene& scene, const std::filesystem::path& sceneFile);
// Parses JSON text as if read from `sceneFile` (which resolves the relative paths and names the
// file in errors) and loads the meshes. Throws SceneFileError.
Scene sceneFromJson(const QByteArray& json, const std::filesystem::path& sceneFile,
                    SceneFileReport* report = nullptr);

// Writes atomically (a temporary file renamed over the target). Throws SceneFileError.
void saveScene(const Scene& scene, const std::filesystem::path& file);
// Reads and loads. Throws SceneFileError.
Scene loadScene(const std::filesystem::path& file, SceneFileReport* report = nullptr);

// How paths are written and read (exposed for the tests).
std::string relativePathForScene(const std::filesystem::path& target,
                                 const std::filesystem::path& sceneFile);
std::filesystem::path resolvePathForScene(const std::string& stored,
                                          const std::filesystem::path& sceneFile);

}  // namespace mipgloss::ui
