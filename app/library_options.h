// `mipgloss library`'s subcommands' flags as values, parsed by pure functions (no library file
// opened) the headless tests call; library_command.cpp does the work.
#pragma once

#include "cli_args.h"

#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/scene.h"

#include <filesystem>
#include <optional>
#include <string>

namespace mipgloss::app {

// The one positional argument every subcommand starts with: `library COMMAND LIB.mglib`.
std::filesystem::path libraryArgument(Args& args, const std::string& command);
// A material name a library takes (materialNameProblem), else a UsageError naming `flag`.
std::string requireName(const std::string& flag, const std::string& name);

// library add LIB.mglib --name NAME [material flags]
struct LibraryAddOptions {
    std::filesystem::path file;
    std::string name;
    Material material;  // the flags applied (layered when a layer flag was given)
};
LibraryAddOptions parseLibraryAddOptions(Args args);

// library thumbnails LIB.mglib --out DIR [--env FILE] [--size N] [--env-size N]
struct LibraryThumbnailOptions {
    std::filesystem::path file, outDir;
    EnvironmentSettings environment;
    int size = 256;
};
LibraryThumbnailOptions parseLibraryThumbnailOptions(Args args);

}  // namespace mipgloss::app
