#include "mipgloss/ibl/parallel.h"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

namespace mipgloss {

void parallelFor(int begin, int end, const std::function<void(int)>& body) {
    if (end <= begin) return;
    tbb::parallel_for(begin, end, [&](int i) { body(i); });
}

int workerCount() { return tbb::info::default_concurrency(); }

struct Background::State {
    tbb::task_group group;
    bool running = false;
};

Background::Background() : state_(std::make_unique<State>()) {}

Background::~Background() {
    try {
        wait();
    } catch (...) {
        // Unwinding already, or nobody asked: the piece's failure has no one to go to.
    }
}

void Background::run(std::function<void()> work) {
    wait();
    state_->running = true;
    state_->group.run(std::move(work));
}

void Background::wait() {
    if (!state_->running) return;
    state_->running = false;
    state_->group.wait();
}

}  // namespace mipgloss
