// What the `mipgloss` commands print besides their results, said one way: warnings (a file that
// could be read in part, a map drawn without its image) and elapsed times.
#pragma once

#include <chrono>
#include <iostream>
#include <string>
#include <vector>

namespace mipgloss::app {

inline double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return 1e3 * secondsSince(start);
}

// Each as "mipgloss: warning: ..." on stderr, unless `quiet`.
inline void printWarnings(const std::vector<std::string>& warnings, bool quiet = false) {
    if (quiet) return;
    for (const std::string& w : warnings) std::cerr << "mipgloss: warning: " << w << '\n';
}

}  // namespace mipgloss::app
