#include "mipgloss/io/default_env.h"

#include <cstddef>

// Generated at build time from resources/env/default_env.exr (core/cmake/embed_file.cmake).
namespace mipgloss::embedded {
extern const unsigned char default_env_exr[];
extern const std::size_t default_env_exr_size;
}  // namespace mipgloss::embedded

namespace mipgloss {

std::span<const unsigned char> defaultEnvironmentBytes() {
    return {embedded::default_env_exr, embedded::default_env_exr_size};
}

ImportedEnvironment loadDefaultEnvironment(int faceSize) {
    ImportOptions options;
    options.layout = EnvLayout::LatLong;
    options.faceSize = faceSize;
    // Read from memory through OpenImageIO's IOProxy: no temporary file.
    return loadEnvironmentFromMemory(defaultEnvironmentBytes(), "default_env.exr", options);
}

}  // namespace mipgloss
