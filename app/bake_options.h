// `mipgloss bake`'s flags as a value, parsed by a pure function (no file opened) the headless
// tests call; main's runBake does the work.
#pragma once

#include "cli_args.h"

#include "mipgloss/io/bake.h"

namespace mipgloss::app {

struct BakeOptions {
    BakeRequest request;  // everything but its progress callback
    bool quiet = false;   // no progress on stderr
    bool help = false;    // --help: print the usage, do nothing else
};

// The flags of `mipgloss bake`, checked against each other (--out given, one environment, the
// DDS and EXR options only with their format); a UsageError naming the flag otherwise.
BakeOptions parseBakeOptions(Args args);

}  // namespace mipgloss::app
