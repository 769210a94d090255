// `mipgloss bench`: build time and error against the exact normalized Phong convolution of each
// builder's chain, per face size and environment.
#pragma once

#include "bench_options.h"

namespace mipgloss::app {

// Prints the tables; 0, or throws (a UsageError for --plot in a build without Qt).
int runBench(const BenchOptions& options);

}  // namespace mipgloss::app
