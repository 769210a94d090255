// Writing plain float images with named channels (OpenEXR through OpenImageIO): the linear
// renders and the per-pixel accounts of `mipgloss render` (--out FILE.exr, --aov FILE.exr).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace mipgloss {

// `values` holds width × height pixels of names.size() floats each, top row first. 32-bit float,
// zip-compressed. Throws EnvError naming the file when it cannot be written.
void writeFloatChannels(const std::filesystem::path& file, int width, int height,
                        const std::vector<std::string>& names, const std::vector<float>& values);

}  // namespace mipgloss
