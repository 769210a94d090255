// The one parallel kernel shape: a function of one index (a face row, a tile) run over a range.
// Kernels never start threads themselves.
#pragma once

#include <functional>
#include <memory>

namespace mipgloss {

// Runs body(i) for i in [begin, end) on the thread pool; returns when all are done.
void parallelFor(int begin, int end, const std::function<void(int)>& body);

// Number of worker threads the pool uses.
int workerCount();

// One piece of work at a time running on the pool beside the calling thread, for pipelines: the
// decoder converts strip k in the background while it reads strip k + 1. run() first waits for
// the piece before it, so pieces run one at a time and in order; wait() rethrows what a piece
// threw. The destructor waits as well and drops such an exception (the caller is unwinding).
class Background {
public:
    Background();
    ~Background();
    Background(const Background&) = delete;
    Background& operator=(const Background&) = delete;
    void run(std::function<void()> work);
    void wait();

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace mipgloss
