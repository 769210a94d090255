// `mipgloss bench stack`: the lobe stack's build time, GPU memory and read error at any λ
// (bench_stack.cpp; docs/lobe-stack.md keeps its tables).
#pragma once

#include "cli_args.h"

namespace mipgloss::app {

extern const char* kStackBenchUsage;

// Runs the benchmark; throws UsageError on bad arguments, EnvError on unreadable files.
int runStackBench(Args args);

}  // namespace mipgloss::app
