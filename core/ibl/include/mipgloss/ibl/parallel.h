// The one parallel kernel shape: a function of one index (a face row, a tile) run over a range.
// Kernels never start threads themselves.
#pragma once

#include <functional>

namespace mipgloss {

// Runs body(i) for i in [begin, end) on the thread pool; returns when all are done.
void parallelFor(int begin, int end, const std::function<void(int)>& body);

// Number of worker threads the pool uses.
int workerCount();

}  // namespace mipgloss
