// Writing cubes and chains to OpenEXR, and reading the cube file back. Pixels read back follow the
// import's one sanitising rule (import.h).
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/io/import.h"

#include <filesystem>

namespace mipgloss {

// Writes the six faces as float OpenEXR files DIR/{px,nx,py,ny,pz,nz}.exr (GL orientation,
// row 0 = t 0). Throws EnvError on failure.
void writeFaceImages(const CubeMap& cube, const std::filesystem::path& dir);

// Writes one standard file: a mip-mapped, tiled OpenEXR cube environment map (OpenEXR's envmap
// attribute "cube", faces stacked vertically in the order +X -X +Y -Y +Z -Z, float RGB, zip)
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
void writeCubeEnvironmentExr(const MipChain& chain, const std::filesystem::path& file);
// Reads such a file back (tests, round trips): the chain's levels, in GL orientation again. Also
// reads other OpenEXR cube maps (the levels whose faces halve down to 1×1). Throws EnvError.
MipChain readCubeEnvironmentExr(const std::filesystem::path& file);

}  // namespace mipgloss
