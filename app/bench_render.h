// `mipgloss bench-render`: frame times of the viewer's renderer offscreen (many objects with
// distinct lobes against one shared lobe), or the time a big mesh or asset takes to be on screen.
// Only built with the UI.
#pragma once

#include "cli_args.h"

#include <filesystem>
#include <optional>

namespace mipgloss::app {

struct BenchRenderOptions {
    int objects = 16, frames = 20, width = 960, height = 540;
    std::optional<std::filesystem::path> mesh;
    bool million = false;  // a generated sphere of a million triangles instead of --mesh
    // Off: every lobe read from the chain, the picture before the lobe stack's entries exist (the
    // frames this bench timed before it made them); on, the settled picture the window shows.
    bool stack = true;
};

// Pure: the flags into the options, or a UsageError naming the flag.
BenchRenderOptions parseBenchRenderOptions(Args args);

// 0, or throws: UsageError for bad usage, anything else for bad input or no OpenGL.
int runRenderBench(Args args, const char* argv0);

}  // namespace mipgloss::app
