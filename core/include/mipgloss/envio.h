// Environment import and export (OpenImageIO). Files -> CubeMap (linear float RGB, GL face
// orientation) and CubeMap/MipChain -> files. The lat-long orientation convention lives here.
//
// Lat-long (equirectangular) convention, the one Blender and three.js use, converted to y-up:
//     u = 0.5 + atan2(z, x) / (2π)      (u across the width; the image centre looks along +X)
//     v = acos(y) / π                    (v = 0 is the top row, the zenith +Y)
#pragma once

#include "mipgloss/cubemap.h"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss {

// A user-caused problem with a file: what() names the file and the reason.
class EnvError : public std::runtime_error {
public:
    EnvError(const std::filesystem::path& file, const std::string& reason);
    const std::filesystem::path& file() const { return file_; }
    const std::string& reason() const { return reason_; }

private:
    std::filesystem::path file_;
    std::string reason_;
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

// Face-file naming families. `Handedness::Left` is for skyboxes made for left-handed engines
// (Irrlicht, Direct3D samples): front/back are swapped and every face is mirrored left-right.
enum class Handedness { Right, Left };

struct ImportOptions {
    EnvLayout layout = EnvLayout::Auto;
    Handedness handedness = Handedness::Right;
    int faceSize = 0;  // 0: keep the native face size (lat-long: width / 4)
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

// Resamples a cube to another face size: area-weighted when shrinking, bilinear when growing.
CubeMap resampleCube(const CubeMap& cube, int size);

// Writes the six faces as float OpenEXR files DIR/{px,nx,py,ny,pz,nz}.exr (GL orientation,
// row 0 = t 0). Throws EnvError on failure.
void writeFaceImages(const CubeMap& cube, const std::filesystem::path& dir);

// Writes one standard file: a mip-mapped, tiled OpenEXR cube environment map (OpenEXR's envmap
// attribute "cube", faces stacked vertically) that OpenImageIO's iinfo and texture system
// recognise. Throws EnvError on failure.
void writeCubeEnvironmentExr(const MipChain& chain, const std::filesystem::path& file);
// Reads such a file back (tests, round trips). Throws EnvError.
MipChain readCubeEnvironmentExr(const std::filesystem::path& file);

}  // namespace mipgloss
