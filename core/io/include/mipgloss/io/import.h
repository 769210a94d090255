// Environment import (OpenImageIO): files -> CubeMap (linear float RGB, GL face orientation).
// Writing cubes and chains back out is cube_exr.h.
//
// Lat-long images are converted with a filter (latlong.h gives the orientation convention and the
// conversion's accuracy).
//
// Colour: integer images (PNG, JPEG, 8/16-bit TIFF, ...) are sRGB-encoded and decoded with the
// exact sRGB EOTF (colour.h); half and float images (EXR, HDR, float TIFF) are linear and kept as they are.
// The first three channels are read; one channel (grey, grey + alpha) is replicated to RGB; alpha
// is ignored (read unassociated, so colour is never multiplied by it).
//
// Sanitising: NaN -> 0, negative (including -Inf) -> 0, a finite value above kMaxRadiance (1e20)
// -> kMaxRadiance, +Inf -> the largest value left in that image. Every replaced value is counted in the report, with one warning per file naming it. The
// same rule applies to every file mipgloss reads pixels from, the cube EXR file included.
#pragma once

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/progress.h"
#include "mipgloss/io/file_error.h"

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
const char* handednessName(Handedness h);  // "right", "left"
bool parseHandedness(const std::string& text, Handedness& out);

// The largest radiance a pixel keeps. No measured radiance comes near it (HDRIs store up to about
// 1e6, a sun in absolute units 1e9), and sums of a billion such values stay finite in single
// precision; a float near its own maximum (3.4e38) made every average over it infinite (found by
// the environment fuzzer: tests/fuzz/regressions/environment_import).
inline constexpr float kMaxRadiance = 1e20f;

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
    std::size_t hugeCount = 0;  // finite values above kMaxRadiance, lowered to it
    std::vector<std::string> warnings;                          // each names its file
};

struct ImportedEnvironment {
    CubeMap cube;  // seamless borders filled
    ImportReport report;
};


// Loads an environment: a single image (cross, strip or lat-long), a directory holding six face
// files, or one face file of a family (its five siblings are found by name). Throws EnvError.
ImportedEnvironment loadEnvironment(const std::filesystem::path& path,
                                    const ImportOptions& options = {},
                                    const Progress& progress = {});

// Loads a single image (lat-long, cross or strip) from bytes in memory, e.g. an embedded resource.
// `name` stands for the file in messages, and its extension tells OpenImageIO the format.
ImportedEnvironment loadEnvironmentFromMemory(std::span<const unsigned char> bytes,
                                              const std::string& name,
                                              const ImportOptions& options = {},
                                              const Progress& progress = {});

// A decoded, sanitised image: linear float RGB, row 0 at the top. What the import reads from a
// single image file before it converts it (decoded by strips, one copy of the image in memory; a
// header asking for more than three quarters of the machine's memory is refused before anything
// is allocated). A lat-long that the scatter converts is never decoded whole by loadEnvironment:
// each strip is converted as it is decoded (docs/big-environments.md).
struct DecodedImage {
    int width = 0;
    int height = 0;
    std::vector<Rgb> px;  // width × height, row-major
    const Rgb& at(int x, int y) const {
        return px[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
    }
};

// Decodes one image file the way loadEnvironment does (colour rule and sanitising above), for
// tools and benchmarks that time the decode on its own. Throws EnvError; Cancelled when told to.
DecodedImage decodeImage(const std::filesystem::path& file, ImportReport* report = nullptr,
                         const Progress& progress = {});

}  // namespace mipgloss
