// The environment the tools show when no file is given: "Courtyard" by Greg Zaal (HDRI Haven, CC0;
// see resources/NOTICE.md), a 512×256 float lat-long OpenEXR compiled into the core library, so
// that no installed data file is needed.
#pragma once

#include "mipgloss/io/import.h"

#include <span>

namespace mipgloss {

// Decodes the embedded lat-long and converts it to a cube of the given face size (its native size
// is 128). Throws EnvError only if the build embedded a broken file.
ImportedEnvironment loadDefaultEnvironment(int faceSize = 128);

// The embedded OpenEXR file, byte for byte (resources/env/default_env.exr).
std::span<const unsigned char> defaultEnvironmentBytes();

}  // namespace mipgloss
