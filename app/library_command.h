// `mipgloss library`: list, add, remove, rename and thumbnail the materials of a library file
// (library_file.h). Only built with the UI (the file code and the renderer live in mipgloss_ui).
#pragma once

#include "cli_args.h"

namespace mipgloss::app {

// 0, or throws: UsageError for bad usage, anything else (a LibraryFileError naming the file) for
// bad input (main() prints the message and exits with 2 or 1). A library that cannot be read is
// refused by every subcommand and never written.
int runLibrary(Args args, const char* argv0);

extern const char* const kLibraryUsage;

}  // namespace mipgloss::app
