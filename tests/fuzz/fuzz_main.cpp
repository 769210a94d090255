// One libFuzzer target: MIPGLOSS_FUZZ_ENTRY names the entry (entries.h). A broken contract
// aborts, so libFuzzer keeps the input as a crash like any sanitizer report.
#include "entries.h"

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string problem = mipgloss::fuzz::MIPGLOSS_FUZZ_ENTRY({data, size});
    if (!problem.empty()) {
        std::fprintf(stderr, "contract broken: %s\n", problem.c_str());
        std::abort();
    }
    return 0;
}
