// `mipgloss render`'s flags as a value (pbrt's options struct): parsed once by a pure function
// (no OpenGL, no file opened), which the headless tests call; runRender does the work.
#pragma once

#include "cli_args.h"
#include "frame_pattern.h"
#include "material_args.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/scene/turntable.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mipgloss::app {

// Every flag given; unset optionals keep the scene's own value.
struct RenderOptions {
    std::optional<std::filesystem::path> scene, environment, out, aov, library;
    std::vector<std::filesystem::path> meshes;
    std::optional<std::string> libraryMaterial;
    std::optional<float> lambda;  // from --lambda or --exponent (lambdaFlag says which)
    std::string lambdaFlag;
    LayerFlags layers;
    std::optional<LookupMode> mode;
    std::optional<float> exposure, backgroundLambda, yaw, pitch, spin, envRotation;
    std::optional<Rgb> background;     // --background: the backdrop, the environment hidden
    std::optional<std::string> camera; // --camera: a glTF camera of the (first) asset, by name or index
    std::optional<ToneMap> toneMap;
    std::optional<Scattering> scattering;
    std::optional<int> envSize, samples, turntable;
    std::optional<Builder> builder, compareBuilder;
    std::optional<std::filesystem::path> compareEnv;
    TurntableSpin spinKind = TurntableSpin::Object;
    bool noBackground = false, quiet = false, noSettle = false, noStack = false;
    int width = 0, height = 0;  // 0: the default for the scene (runRender)
    FramePattern frames;        // with --turntable: --out parsed as a frame pattern

    bool compare() const { return compareBuilder || compareEnv; }
    // The first picture written: --out, or frame 0 of its pattern with --turntable.
    std::filesystem::path firstOut() const { return turntable ? std::filesystem::path(frames.format(0)) : *out; }
};

// The flags of `mipgloss render`, checked against each other (--out given, --library with
// --material, no two that do not go together); a UsageError naming the flag otherwise. What the
// OpenGL can draw and whether the files exist are checked once there is a context.
RenderOptions parseRenderOptions(Args args);

}  // namespace mipgloss::app
