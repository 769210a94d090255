// `mipgloss bench import`: decode, conversion, filter and write of big lat-long environments,
// timed stage by stage, with the peak memory (bench_import.cpp).
#pragma once

#include "cli_args.h"

namespace mipgloss::app {

extern const char* kImportBenchUsage;

// Runs the benchmark; throws UsageError on bad arguments, EnvError on unreadable files.
int runImportBench(Args args);

}  // namespace mipgloss::app
