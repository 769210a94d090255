// Writing cubes and chains to OpenEXR, and reading the cube file back. Pixels read back follow the
// import's one sanitising rule (import.h).
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/io/import.h"

#include <filesystem>
#include <string>

namespace mipgloss {

// The compression of these writers when not told otherwise: zip, OpenEXR's usual. `mipgloss
// bake` asks for none instead (kBakeExrCompression in bake.h, where the measurements are cited).
inline constexpr const char* kDefaultExrCompression = "zip";

// Whether OpenImageIO's OpenEXR writer knows the compression. Lossless: none, rle, zips, zip, piz.
// Lossy: pxr24 (rounds float to 24 bits; lossless for half), b44 and b44a (half only; float
// channels are stored uncompressed), dwaa and dwab (lossy for float as well as half). zip, zips,
// dwaa and dwab take a level after a colon ("zip:9", "dwaa:45").
bool isExrCompression(const std::string& name);

struct ExrWriteOptions {
    std::string compression = kDefaultExrCompression;
    // Store 16-bit half instead of 32-bit float. Values above 65504 (the largest finite half) are
    // clamped to it; half keeps 11 significant bits (relative rounding error at most 2^-11).
    bool half = false;
};

// Writes one face of the cube as an OpenEXR file (GL orientation, row 0 = t 0), and all six as
// DIR/{px,nx,py,ny,pz,nz}.exr. Throws EnvError on failure.
void writeFaceImage(const CubeMap& cube, Face face, const std::filesystem::path& file,
                    const ExrWriteOptions& options = {});
void writeFaceImages(const CubeMap& cube, const std::filesystem::path& dir, const ExrWriteOptions& options = {});

// What both cube-file writers (this one and writeCubeDds) require before they open a file: a chain
// of at most 1 + floor(log2 N) levels of sizes levelSize(N, k). Creates the file's folder. Throws
// EnvError naming the file.
void prepareChainFile(const MipChain& chain, const std::filesystem::path& file);

// Writes one standard file: a mip-mapped, tiled OpenEXR cube environment map (OpenEXR's envmap
// attribute "cube", faces stacked vertically in the order +X -X +Y -Y +Z -Z, RGB, float and the
// default compression unless `options` says otherwise)
// that OpenImageIO's iinfo recognises. Throws EnvError on failure.
//
// Orientation: the faces are converted to OpenEXR's cube convention (ImfEnvmap.cpp,
// CubeMap::direction), which is GL's seen in a right-handed frame: with (a, b) a pixel's position
// in its face image (a rightwards, b downwards, in [-1, 1]) the pixel looks along
//     +X (1, -b, a)  -X (-1, -b, -a)  +Y (a, 1, -b)  -Y (a, -1, b)  +Z (-a, -b, 1)  -Z (a, -b, -1)
// i.e. GL's ±X and ±Z faces mirrored left-right and ±Y flipped top to bottom. One deviation is
// kept, and stated in the file's "mipgloss:orientation" attribute: pixel i of an N-pixel face
// sits at a = (2i + 1)/N - 1 as in GL, where ImfEnvmap puts it at 2i/(N - 1) - 1 (edge pixels
// centred on the cube's edges); resampling to that would cost exact round trips.
// OpenEXR's MIP levels halve N × 6N down to 1 × 1, so the file has 1 + floor(log2 6N) levels:
// the chain's levels first ("mipgloss:levels" says how many), 2×2 box averages down to 1 × 6 if
// the chain stops early, then the levels below the 1×1 faces (1 × 3 and 1 × 1 for a power-of-two
// N) holding the mean colour, as do the rows below the faces when N is not a power of two (level
// k is N >> k wide and 6N >> k high, faces stacked from the top: ImfEnvmap's sizeOfFace
// = min(w, h / 6)). "oiio:updirection" = "y"
// is set, but OpenImageIO's OpenEXR writer drops oiio:* attributes; "mipgloss:orientation" says
// y is up.
void writeCubeEnvironmentExr(const MipChain& chain, const std::filesystem::path& file,
                             const ExrWriteOptions& options = {});
// Reads such a file back (tests, round trips): the chain's levels, in GL orientation again. Also
// reads other OpenEXR cube maps (the levels whose faces halve down to 1×1). Throws EnvError.
MipChain readCubeEnvironmentExr(const std::filesystem::path& file);

}  // namespace mipgloss
