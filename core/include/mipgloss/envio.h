// Environment import and export (OpenImageIO). Files -> CubeMap (linear float RGB, GL face
// orientation) and CubeMap/MipChain -> files. The lat-long orientation convention lives here.
//
// Lat-long (equirectangular) convention, the one Blender and three.js use, converted to y-up:
//     u = 0.5 + atan2(z, x) / (2π)      (u across the width; the image centre looks along +X)
//     v = acos(y) / π                    (v = 0 is the top row, the zenith +Y)
// Checked on the shared HDRIs: the sun of sunset.exr lands at (0.81, 0.06, 0.59) and that of
// sunrise.exr at (0.80, 0.14, 0.58), both above the horizon.
//
// Lat-long -> cube is filtered: each texel is the solid-angle weighted mean of the bilinearly
// interpolated image over the texel's footprint (a quadrature of strata finer than the smallest
// texel, each weighted by its exact solid angle), so a cube coarser than the image does not
// alias and a finer one is smooth. Near the poles the interpolation runs to the pole's single
// value (the mean of the first or last row) rather than clamping, so pole texels carry no
// azimuthal streaks. The few pixels far above the mean (suns) have their excess splatted with
// exact solid-angle bookkeeping, so their energy stays where they are: the cube's weighted mean
// matches the image's within 0.002 % on sunset.exr and sunrise.exr at their native face size 256,
// and within 0.15 % on all eight shared HDRIs at 64 and 256.
//
// Colour: integer images (PNG, JPEG, 8/16-bit TIFF, ...) are sRGB-encoded and decoded with the
// exact sRGB EOTF; half and float images (EXR, HDR, float TIFF) are linear and kept as they are.
// The first three channels are read; one channel (grey, grey + alpha) is replicated to RGB; alpha
// is ignored (read unassociated, so colour is never multiplied by it).
//
// Sanitising: NaN -> 0, negative (including -Inf) -> 0, +Inf -> the largest finite value of that
// image. Every replaced value is counted in the report, with one warning per file naming it.
#pragma once

#include "mipgloss/cubemap.h"
#include "mipgloss/file_error.h"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss {

// A user-caused problem with a file: what() names the file and the reason.
class EnvError : public FileError {
public:
    using FileError::FileError;
};

enum class EnvLayout {
    Auto,             // detect from the path and the image proportions
    Faces,            // six face files
    HorizontalCross,  // 4:3, see cubemap.h
    VerticalCross,    // 3:4: the horizontal cross's middle column, NZ below NY rotated 180°
    HorizontalStrip,  // 6:1, faces left to right in GL order px nx py ny pz nz
    VerticalStrip,    // 1:6, faces top to bottom in GL order
    LatLong,          // 2:1 equirectangular
};
const char* layoutName(EnvLayout layout);
// Parses "auto", "faces", "hcross", "vcross", "hstrip", "vstrip", "latlong"; false if unknown.
bool parseLayout(const std::string& text, EnvLayout& out);

// Face-naming families (case-insensitive, after any common prefix such as "irrlicht2_" or "sky-",
// any image extension): px/nx/py/ny/pz/nz, posx/negx/posy/negy/posz/negz,
// right/left/top/bottom/front/back and rt/lf/up/dn/ft/bk (right = +X, left = -X, top = +Y,
// bottom = -Y, front = +Z, back = -Z). Face images are used as they are: image row 0 is t = 0 and
// column 0 is s = 0 of the GL face (what learnopengl-style loaders do).
//
// `Handedness::Left` is for skyboxes made for left-handed engines (Irrlicht): the world is
// mirrored, so front and back swap (front -> -Z, back -> +Z), the four side faces are mirrored
// left-right, top is anti-transposed (texel (x, y) <- image (N-1-y, N-1-x)) and bottom transposed
// (texel (x, y) <- image (y, x)). Measured on cubemaps/irrlicht2 (512² JPEG faces): mean |ΔRGB|
// between the texels facing each other across the 12 cube edges (resolveTexel), over the mean
// between neighbouring texels inside faces (0.0091):
//     right-handed, faces as they are                 0.0855 -> ratio 9.4   (seams)
//     swap front/back + mirror every face             0.0852 -> ratio 9.35  (seams at top, bottom)
//     ... and top turned 90° clockwise, bottom 90°
//         anticlockwise (= the mapping above)         0.0113 -> ratio 1.24  (continuous)
// Of the 16 combinations of top/bottom turns, only that one is continuous (the next best, 2.0,
// leaves the bottom's edges at 0.037). Seams cannot tell a world from its mirror image: the
// right-handed mapping with the same top/bottom turns also scores 1.24. Irrlicht's own
// CSkyBoxSceneNode texture coordinates settle it: taken from its left-handed frame to GL's (z
// negated), they give exactly the mapping above turned 180° about +Y (Irrlicht's "front" quad
// ends up on GL's +Z); we keep front on -Z, where a default GL camera looks.
enum class Handedness { Right, Left };

struct ImportOptions {
    EnvLayout layout = EnvLayout::Auto;
    Handedness handedness = Handedness::Right;
    int faceSize = 0;  // 0: keep the native face size (lat-long: width / 4); faces, crosses and
                       // strips are resampled with resampleCube, lat-long converted directly
};

// What the import found and did, for messages.
struct ImportReport {
    EnvLayout layout = EnvLayout::Auto;
    std::vector<std::filesystem::path> files;  // the files actually read
    std::size_t nanCount = 0, infCount = 0, negativeCount = 0;  // replaced, per file summed
    std::vector<std::string> warnings;                          // each names its file
};

struct ImportedEnvironment {
    CubeMap cube;  // seamless borders filled
    ImportReport report;
};

using ProgressFn = std::function<void(float fraction)>;

// Loads an environment: a single image (cross, strip or lat-long), a directory holding six face
// files, or one face file of a family (its five siblings are found by name). Throws EnvError.
ImportedEnvironment loadEnvironment(const std::filesystem::path& path,
                                    const ImportOptions& options = {},
                                    const ProgressFn& progress = {});

// Loads a single image (lat-long, cross or strip) from bytes in memory, e.g. an embedded resource.
// `name` stands for the file in messages, and its extension tells OpenImageIO the format.
ImportedEnvironment loadEnvironmentFromMemory(std::span<const unsigned char> bytes,
                                              const std::string& name,
                                              const ImportOptions& options = {},
                                              const ProgressFn& progress = {});

// Resamples a cube to another face size. Shrinking: each texel is the exact solid-angle weighted
// mean of the source texels under its footprint (partial texels weighted by the solid angle of
// the overlap), so the weighted mean is kept. Growing: bilinear through CubeMap::sample, so
// samples near an edge see the neighbouring face. The same size returns a copy.
CubeMap resampleCube(const CubeMap& cube, int size);

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
