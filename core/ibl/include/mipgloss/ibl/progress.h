// The one shape of progress for long work (import, chain builds, irradiance, bake): the stage
// being worked on and the fraction of it done, called from the thread that asked for the work.
// Returning false asks the work to stop; it then throws Cancelled from that thread, leaving
// nothing half made behind (each caller keeps what it had).
#pragma once

#include <functional>
#include <string>

namespace mipgloss {

using Progress = std::function<bool(const std::string& stage, float fraction)>;

// Thrown by work whose Progress asked it to stop.
struct Cancelled {};

// Reports to `progress` (if any) and throws Cancelled when it asks to stop.
inline void reportProgress(const Progress& progress, const std::string& stage, float fraction) {
    if (progress && !progress(stage, fraction)) throw Cancelled{};
}

}  // namespace mipgloss
