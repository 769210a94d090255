// `mipgloss render` and `mipgloss bench-render`: the Qt renderer offscreen. Only built with the UI.
#pragma once

#include "cli_args.h"

namespace mipgloss::app {

// Both return 0, or throw: UsageError for bad usage, anything else for bad input or no OpenGL
// (main() prints the message and exits with 2 or 1).
int runRender(Args args, const char* argv0);
int runRenderBench(Args args, const char* argv0);

extern const char* const kRenderUsage;

}  // namespace mipgloss::app
