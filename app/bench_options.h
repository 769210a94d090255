// `mipgloss bench`'s flags as a value, parsed by a pure function the headless tests call;
// bench_chain.cpp does the work.
#pragma once

#include "cli_args.h"

#include "mipgloss/ibl/builders.h"

#include <filesystem>
#include <string>
#include <vector>

namespace mipgloss::app {

struct BenchOptions {
    std::vector<std::filesystem::path> environments;  // none: the embedded default environment
    std::vector<int> sizes{128, 256, 512};
    std::vector<Builder> builders{Builder::Phong, Builder::Box, Builder::Paper};
    int repeat = 3;
    int directions = 1500;
    bool halfLevels = true, centres = true, shortcuts = false;
    std::filesystem::path plot;  // empty: no plot
    bool help = false;
};

// The flags of `mipgloss bench`; a UsageError naming the flag otherwise (a face size with no read
// level below the base, an empty list).
BenchOptions parseBenchOptions(Args args);

// "a,b,,c" -> {"a", "b", "c"}.
std::vector<std::string> splitList(const std::string& s);

}  // namespace mipgloss::app
