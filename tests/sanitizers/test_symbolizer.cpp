// The sanitizer builds only (tests/CMakeLists.txt): the stacks they print are symbolized.
//
// tests/sanitizers/lsan.supp names third-party functions, and a suppression by function name
// matches only a symbolized stack. Without llvm-symbolizer the sanitizers print bare addresses,
// every such suppression silently stops matching, and the leak it names fails unrelated tests
// (issue 22: a fresh Debian 12 machine, where nothing had installed it). This test says so first,
// by name, wherever the suite runs: scripts/run-sanitizers.sh, run-fuzz.sh or ctest by hand.
#include <gtest/gtest.h>
#include <sanitizer/common_interface_defs.h>

#include <string>

namespace {

[[gnu::noinline]] void* returnAddress() { return __builtin_return_address(0); }

// The name the sanitizers' symbolizer gives to a return address inside this very function.
[[gnu::noinline]] std::string nameOfThisFunctionAsTheSanitizersSeeIt() {
    void* const pc = returnAddress();
    char name[1024] = {};
    __sanitizer_symbolize_pc(pc, "%f", name, sizeof name);
    return name;
}

}  // namespace

TEST(Sanitizers, StacksAreSymbolized) {
    const std::string name = nameOfThisFunctionAsTheSanitizersSeeIt();
    EXPECT_NE(name.find("nameOfThisFunctionAsTheSanitizersSeeIt"), std::string::npos)
        << "named '" << name << "': the sanitizers cannot name functions: install llvm-symbolizer (Debian: apt install llvm, "
           "scripts/install-clang.sh does) or point ASAN_SYMBOLIZER_PATH at it; without it the "
           "suppressions in tests/sanitizers/lsan.supp match nothing";
}
