// `mipgloss bench truth`: a layered material's picture against the glTF BRDF integrated over the
// environment, per pixel, with the exact Karis split sum beside it and the frame time per lookup
// count (bench_truth.cpp; docs/material-truth.md keeps its tables).
#pragma once

#include "cli_args.h"

namespace mipgloss::app {

extern const char* kTruthBenchUsage;

// Runs the benchmark; throws UsageError on bad arguments, EnvError on unreadable files.
int runTruthBench(Args args);

}  // namespace mipgloss::app
