// DirectDraw Surface (DDS) cube maps for engines: the whole mip chain in one file, RGBA half or
// float, with the DX10 header (what cmft writes and most engines load). Written by a small writer
// of our own (no DDS library); read back by our own reader for tests and round trips, since
// OpenImageIO 2.4 reads no float DDS (docs/bake-output.md).
//
// Layout (little-endian, as Microsoft's "Programming Guide for DDS" lays it out):
//
//     "DDS " | DDS_HEADER (124 bytes) | DDS_HEADER_DXT10 (20 bytes) | data
//     data  = face +X: level 0, level 1, ... level L-1 | face -X: ... | +Y | -Y | +Z | -Z
//     level = M rows of M texels, row 0 first; texel = R G B A (A = 1)
//
// with DXGI_FORMAT_R16G16B16A16_FLOAT or R32G32B32A32_FLOAT (there is no three-channel 16-bit
// DXGI format), D3D10_RESOURCE_DIMENSION_TEXTURE2D, D3D10_RESOURCE_MISC_TEXTURECUBE, arraySize 1
// (one cube), DDSCAPS2_CUBEMAP with all six face bits, and the chain's level count.
//
// Orientation: none is changed. Direct3D's cube-map face selection (+X: u = -z/|x|, v = -y/|x|,
// and so on) is OpenGL's table (docs/conventions.md), with u, v = s, t and v = 0 the first row in
// memory, as t = 0 is in GL. So our faces go in as they are: D3D face i = our face i, texel (x, y)
// of a level = row y, column x. A shader that samples this file with direction r reads what
// mipgloss shows for r. Half values above 65504 (the largest finite half) are clamped to it, as
// the previewer's RGB16F upload does.
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace mipgloss {

enum class DdsType { Half, Float };

const char* ddsTypeName(DdsType type);                     // "half", "float"
bool parseDdsType(const std::string& name, DdsType& out);  // false for anything else

// DXGI format numbers (dxgiformat.h) and the header flags the writer sets.
inline constexpr std::uint32_t kDxgiR32G32B32A32Float = 2;
inline constexpr std::uint32_t kDxgiR16G16B16A16Float = 10;
inline constexpr std::uint32_t kDdsHeaderBytes = 4 + 124 + 20;  // magic, DDS_HEADER, DXT10 header

// Writes the chain (every level, each face size levelSize(N, k)) as one DDS cube map. The file
// appears whole or not at all: it is written beside itself and renamed into place. Throws
// EnvError naming the file.
void writeCubeDds(const MipChain& chain, const std::filesystem::path& file, DdsType type = DdsType::Half);

// The header fields of a DDS cube file, as stored.
struct DdsHeader {
    std::uint32_t flags = 0, height = 0, width = 0, pitchOrLinearSize = 0, depth = 0, mipMapCount = 0;
    std::uint32_t pixelFormatFlags = 0, fourCC = 0, caps = 0, caps2 = 0;
    std::uint32_t dxgiFormat = 0, resourceDimension = 0, miscFlag = 0, arraySize = 0, miscFlags2 = 0;
};

struct DdsCube {
    DdsHeader header;
    MipChain chain;  // GL faces, values as stored (half widened to float), borders made seamless
    float minAlpha = 0.0f, maxAlpha = 0.0f;
};

// Reads what writeCubeDds writes (DX10 header, RGBA half or float, one cube with its mips). Checks
// the header and that the file is exactly as long as it says before allocating anything. Throws
// EnvError naming the file.
DdsCube readCubeDds(const std::filesystem::path& file);

}  // namespace mipgloss
