// The process's own memory figures from Linux's /proc/self/status, for the benchmarks and
// `mipgloss-gui --time-to-first-frame`. 0 where the file or the field is missing.
#pragma once

#include <fstream>
#include <string>

namespace mipgloss::app {

// A field of /proc/self/status in MiB: "VmHWM" (the resident high-water mark) or "VmRSS"
// (resident now).
inline double processStatusMiB(const char* field) {
    std::ifstream status("/proc/self/status");
    std::string line;
    const std::string key = std::string(field) + ":";
    while (std::getline(status, line))
        if (line.rfind(key, 0) == 0) return std::stod(line.substr(key.size())) / 1024.0;  // kB
    return 0.0;
}

}  // namespace mipgloss::app
