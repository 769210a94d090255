// `mipgloss render` and `mipgloss bench-render`: the Qt renderer offscreen. Only built with the UI.
#pragma once

#include <string>
#include <vector>

namespace mipgloss::app {

// Both return the process exit status (0 ok, 1 bad input, 2 bad usage) and print their own errors.
int runRender(const std::vector<std::string>& args, const char* argv0);
int runRenderBench(const std::vector<std::string>& args, const char* argv0);

extern const char* const kRenderUsage;

}  // namespace mipgloss::app
