#include "mipgloss/ibl/parallel.h"

#include <tbb/info.h>
#include <tbb/parallel_for.h>

namespace mipgloss {

void parallelFor(int begin, int end, const std::function<void(int)>& body) {
    if (end <= begin) return;
    tbb::parallel_for(begin, end, [&](int i) { body(i); });
}

int workerCount() { return tbb::info::default_concurrency(); }

}  // namespace mipgloss
