// Material textures (asset.h's texture maps): any image OpenImageIO reads, from a file or from
// bytes in memory (a .glb's embedded PNG or JPEG), decoded to 8-bit RGBA, the top row first
// (glTF's UV origin is the image's top left, so the renderer uploads rows in this order and reads
// at the file's UVs). 8 bits is what the formats artists use hold (PNG, JPEG); 16-bit and float
// images are rounded to 8 bits, which a roughness map's 1/255 steps (0.4 % in roughness) allow.
//
// Validation (TextureError names the file and the problem): unreadable or truncated data, no
// pixels, more than kMaxTexturePixels pixels (a corrupt header, or no texture an artist means).
// An image larger than `maxSize` on a side is halved (2×2 box) until it fits, with a warning that
// says from what size to what: the GPU memory budget (docs/assets.md). The halving is done as the
// rows are read, in bands, so decoding never holds more than the downsized image and one band:
// peak memory follows maxSize, not the file's header.
#pragma once

#include "mipgloss/io/file_error.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace mipgloss {

class TextureError : public FileError {
public:
    using FileError::FileError;
};

inline constexpr std::uint64_t kMaxTexturePixels = 1ull << 28;  // 16384²
inline constexpr int kDefaultMaxTextureSize = 4096;

struct TextureImage {
    int width = 0, height = 0;
    int channels = 0;                 // in the file (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA)
    int fileWidth = 0, fileHeight = 0;  // before any downsizing
    std::vector<std::uint8_t> rgba;   // width · height · 4, top row first
    std::vector<std::string> warnings;

    std::size_t bytes() const { return rgba.size(); }
};

TextureImage decodeTexture(const std::filesystem::path& file, int maxSize = kDefaultMaxTextureSize);
// `nameForMessages` names the image in errors and its extension (or `mimeType`, "image/png",
// "image/jpeg") tells OpenImageIO the format.
TextureImage decodeTextureFromMemory(std::span<const unsigned char> bytes, const std::string& nameForMessages,
                                     const std::string& mimeType, int maxSize = kDefaultMaxTextureSize);

// An image's size from its header alone, no pixel decoded (TextureCache plans its budget with it);
// throws TextureError as decoding would for a missing, unreadable, empty or oversized image.
struct TextureSize {
    int width = 0, height = 0;
    std::size_t rgbaBytes() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4; }
};
TextureSize textureSize(const std::filesystem::path& file);
TextureSize textureSizeFromMemory(std::span<const unsigned char> bytes, const std::string& nameForMessages,
                                  const std::string& mimeType);
// The size decoding at maxSize gives (halved until both sides fit).
TextureSize fittedTextureSize(TextureSize size, int maxSize);

// Halves `image` (2×2 box, odd sizes rounded up, the last row or column counted once) until both
// sides are at most maxSize.
void downsizeTexture(TextureImage& image, int maxSize);

}  // namespace mipgloss
