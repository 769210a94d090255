// Scene files: JSON, format "mipgloss-scene", version 6 (versions 1 to 5 still load, see below).
//
//   {
//     "format": "mipgloss-scene", "version": 6,
//     "environment": {"source": "env/sky.exr" | "builtin:courtyard", "layout": "auto",
//                     "handedness": "right", "faceSize": 128, "builder": "phong"},
//     "display": {"showBackground": true, "backgroundLambda": 0, "exposureEv": 0,
//                 "toneMap": "aces", "samples": 4, "environmentRotationDegrees": 0},
//     "materials": [{"name": "gold", "library": "Gold",
//                    "lambda": 3, "phongExponent": 767, "mode": "reflect" | "normal",
//                    "useIrradiance": false, "tint": [r, g, b], "sharperAtGrazing": false,
//                    "layers": {...} (optional, version 5: a layered material, material_json.h)}],
//     "objects": [{"name": "bunny", "mesh": "meshes/bunny.obj" | "builtin:teapot" | "builtin:sphere",
//                  "visible": true,
//                  "transform": {"translation": [x, y, z], "rotationDegrees": [x, y, z], "scale": 1},
//                  "material": "gold"}],
//     "camera": {"target": [x, y, z], "distance": 5, "yawDegrees": 0, "pitchDegrees": 10,
//                "fovYDegrees": 30} (optional, version 6)
//   }
//
// Materials (version 3). A scene stores the materials its objects use, once each, under names
// unique in the file; objects refer to one by name, and objects naming the same one share it.
// "library" (optional) is the library entry the material was applied from. A material name that is
// empty or used twice, or an object naming a material not in "materials", is an error naming the
// key. An object without "material" gets a default material (a mirror) of its own. Materials no
// object uses are not written. Versions 1 and 2 kept a "material" object inside each object; each
// becomes a material of its own named after its object (made unique: "teapot", "teapot 2").
//
// λ ("lambda", "backgroundLambda"). Versions 2 and 3 store λ with its one meaning (phong.h): the Phong
// exponent n(λ) = lambdaToExponent(λ) = 3·128²·4^−λ − 1, the same lobe under any environment and
// face size, λ = 0 the mirror. It must be a number in [0, kMaxLambda]; anything else (negative,
// above kMaxLambda, a string, null) is an error naming the file, the key (e.g.
// "objects[2].material.lambda") and the value, never a silent clamp. A missing key defaults to 0.
//
// "phongExponent" (versions 2 and 3, written for every material) is information for a reader of the file:
// lambdaToExponent(λ), null for the mirror (λ = 0). λ alone decides the look. On load it is
// optional; when present it must be null or a finite number >= 0 (anything else is an error like
// an absurd λ), and if it disagrees with λ (relative difference above 1e-4, or null against a
// λ > 0, or a number against λ = 0) the report gets a warning naming the key; λ is used. So a
// hand edit of "lambda" that forgets "phongExponent" still loads as the λ says.
//
// Version 1 files stored λ as the old per-environment blur, n = 3·N²·4^−λ − 1 against the base
// face size N they were saved with ("environment.faceSize", after the face-size clamp below; 128
// when absent). They load with the look they had: each material's λ and "display.backgroundLambda"
// are converted by
//     n = legacyLambdaToExponent(λ_old, N),   λ = exponentToLambda(n)
// (λ_old = 0 stays 0, the mirror; a face size of 128 leaves λ unchanged; λ_old beyond the old
// n = 0 point maps to n = 0, λ ≈ 7.79). Version 1 accepted λ_old in [0, 16] (its old limit);
// values outside are errors as above. "phongExponent" is not read from version 1 files.
//
// The environment's rotation (version 4) is a display setting, "display.environmentRotationDegrees":
// how the environment is turned when drawn, never what is built. Versions 1 to 3 kept it as
// "environment.rotationDegrees"; it loads into the display setting. Either is a finite number,
// kept in [−180°, 180°].
//
// The camera (version 6) is the view saved with the scene (Scene::camera); a file without it (every
// older version) is framed when opened. When present every key is required and checked: "target"
// three finite numbers, "distance" in (0, 1e9], "yawDegrees" finite, "pitchDegrees" in [−89°, 89°]
// (the orbit camera's own limit, camera.h), "fovYDegrees" in [kMinCameraFovY, kMaxCameraFovY]; a
// bad value is an error naming the file and the key ("camera.pitchDegrees"), never a clamp. Saving
// refuses a camera that would not load again.
//
// Files are always written as the newest version.
//
// Paths: saved relative to the scene file's folder when the file lies inside it or at most two
// levels above it (so a project folder moved as a whole keeps working), absolute otherwise; loaded
// relative to the scene file's folder. A loaded scene's meshSource and environment source are
// absolute paths (or builtin:...), so saving elsewhere relativises them afresh.
//
// Loading is all-or-nothing: the whole file is checked and every mesh loaded (a path used twice is
// loaded once and shared) before a Scene is returned, so a caller that replaces its scene only
// with a returned one keeps its last good state on any error. Errors (SceneFileError: not JSON,
// wrong format or version, a wrong type, a non-finite number, an absurd λ or exponent, a missing
// or broken mesh file, a missing environment file, an unknown name) name the scene file and the
// problem. Out-of-range settings with an obvious nearest one (face size, samples, exposure) are
// clamped with a warning in the report. Optional keys default to the values in scene.h.
#pragma once

#include "mipgloss/assets/asset.h"
#include "mipgloss/io/file_error.h"
#include "mipgloss/scene/scene.h"

#include <QByteArray>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss::ui {

inline constexpr const char* kSceneFormat = "mipgloss-scene";
inline constexpr int kSceneVersion = 7;
// The version that added assets: an object's "part" of an asset file (glTF, OBJ with MTL: asset.h)
// and a layered material's texture "maps" (material_json.h), their files relative as "mesh" is.
inline constexpr int kSceneVersionAssets = 7;
// The version that saved the camera ("camera", optional; older files are framed when opened).
inline constexpr int kSceneVersionCamera = 6;
// A saved camera's vertical field of view, in degrees (inclusive).
inline constexpr float kMinCameraFovY = 5.0f, kMaxCameraFovY = 120.0f;
// The version that added layered materials ("layers" in a material; files without them load alike).
inline constexpr int kSceneVersionLayered = 5;
// The version that named materials and shared them between objects.
inline constexpr int kSceneVersionNamedMaterials = 3;
// The version that moved the environment's rotation into the display settings.
inline constexpr int kSceneVersionRotationInDisplay = 4;
// The version whose λ meant a mip level of the environment's own face size (see above).
inline constexpr int kSceneVersionLegacyLambda = 1;

class SceneFileError : public FileError {
public:
    using FileError::FileError;
};

struct SceneFileReport {
    std::vector<std::string> warnings;  // one line each, naming the file
    // The cameras each asset file the objects come from holds (asset.h: glTF cameras, in the
    // file's own space), by the file's absolute path; files without cameras are left out.
    FileCameras cameras;
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
