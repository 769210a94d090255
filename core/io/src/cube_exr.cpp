#include "mipgloss/io/cube_exr.h"

#include "decode.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/colour.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace mipgloss {

namespace fs = std::filesystem;
using namespace io_detail;

namespace {

OIIO::TypeDesc pixelType(const ExrWriteOptions& options) {
    return options.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
}

// Half files: values above the largest finite half would be stored as +Inf; clamp them instead,
// as the previewer's RGB16F upload does.
void clampForHalf(std::vector<float>& rgb, const ExrWriteOptions& options) {
    if (options.half)
        for (float& v : rgb) v = std::min(v, kHalfMax);
}

void writeRgbImage(const fs::path& file, int width, int height, std::vector<float>& rgb,
                   const ExrWriteOptions& options) {
    // OpenEXR whatever the extension, so that the compression means what it says.
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out) throw EnvError(file, "cannot create an image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 3, pixelType(options));
    spec.attribute("compression", options.compression);
    clampForHalf(rgb, options);
    // One write_scanlines call for the whole image, not write_image, which carries on after a failed
    // chunk into an OpenEXR 3.1 wait that never ends (see writeCubeEnvironmentExr).
    if (!out->open(file.string(), spec) || !out->write_scanlines(0, height, 0, OIIO::TypeDesc::FLOAT, rgb.data()) ||
        !out->close())
        throw EnvError(file, "cannot write: " + out->geterror());
}

// OpenEXR's cube map (ImfEnvmap.h, CubeMap::direction) orients the faces differently from GL:
// deriving pixel -> direction from its pixelPosition and direction functions, with (a, b) the
// pixel's position in the face image (a to the right, b down, both in [-1, 1]):
//     +X: ( 1, -b,  a)   -X: (-1, -b, -a)   +Y: ( a,  1, -b)
//     -Y: ( a, -1,  b)   +Z: (-a, -b,  1)   -Z: ( a, -b, -1)
// Against the GL table in cubemap.h, the ±X and ±Z images are GL's mirrored left-right and the
// ±Y images are GL's flipped top to bottom (OpenEXR's cube is GL's seen in a right-handed frame:
// z negated). This maps GL face texel (x, y) to the OpenEXR face image pixel holding the same
// direction.
std::pair<int, int> exrPixelOfGlTexel(Face f, int x, int y, int n) {
    if (f == Face::PY || f == Face::NY) return {x, n - 1 - y};
    return {n - 1 - x, y};
}

constexpr const char* kOrientationNote =
    "Faces stacked top to bottom in the order +X -X +Y -Y +Z -Z, y up, oriented as OpenEXR's "
    "ImfEnvmap CubeMap (the OpenGL cube-map faces with +-X and +-Z mirrored left-right and +-Y "
    "flipped top to bottom). Texel centres follow OpenGL: pixel i of an N-pixel face edge sits at "
    "(i + 0.5)/N across the face, not at i/(N - 1) as ImfEnvmap's CubeMap::direction assumes. The "
    "first mipgloss:levels MIP levels are the exported chain; further levels down to 1x1 faces are "
    "2x2 box averages of the last; rows below the six faces (non-power-of-two sizes) and the "
    "levels OpenEXR's rounding adds below the 1x1 faces (1x3, 1x1) hold the mean colour.";

}  // namespace

bool isExrCompression(const std::string& name) {
    const auto colon = name.find(':');
    const std::string base = name.substr(0, colon);
    for (const char* plain : {"none", "rle", "piz", "pxr24", "b44", "b44a"})
        if (base == plain) return colon == std::string::npos;
    if (base != "zip" && base != "zips" && base != "dwaa" && base != "dwab") return false;
    if (colon == std::string::npos) return true;
    const std::string level = name.substr(colon + 1);
    return !level.empty() && level.size() <= 4 && level.find_first_not_of("0123456789") == std::string::npos;
}

void writeFaceImage(const CubeMap& cube, Face face, const fs::path& file, const ExrWriteOptions& options) {
    const int n = cube.size();
    if (n < 1) throw EnvError(file, "the cube map is empty");
    std::vector<float> rgb(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * 3);
    std::size_t i = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const Rgb& p = cube.at(face, x, y);
            rgb[i++] = p.x;
            rgb[i++] = p.y;
            rgb[i++] = p.z;
        }
    writeRgbImage(file, n, n, rgb, options);
}

void writeFaceImages(const CubeMap& cube, const fs::path& dir, const ExrWriteOptions& options) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw EnvError(dir, "cannot create the folder: " + ec.message());
    for (Face f : kAllFaces) writeFaceImage(cube, f, dir / (std::string(faceName(f)) + ".exr"), options);
}

void prepareChainFile(const MipChain& chain, const fs::path& file) {
    const int n = chain.baseSize();
    if (n < 1) throw EnvError(file, "the mip chain is empty");
    if (chain.levelCount() > fullChainLevelCount(n))
        throw EnvError(file, "the mip chain has more levels than a face of " + std::to_string(n) + " allows");
    for (int k = 0; k < chain.levelCount(); ++k)
        if (chain.levels[static_cast<std::size_t>(k)].size() != levelSize(n, k))
            throw EnvError(file, "mip level " + std::to_string(k) + " has face size " +
                                     std::to_string(chain.levels[static_cast<std::size_t>(k)].size()) +
                                     ", expected " + std::to_string(levelSize(n, k)));
    if (file.has_parent_path()) {
        std::error_code ec;
        fs::create_directories(file.parent_path(), ec);
    }
}

void writeCubeEnvironmentExr(const MipChain& chain, const fs::path& file, const ExrWriteOptions& options) {
    prepareChainFile(chain, file);
    const int n = chain.baseSize();

    // OpenEXR's MIP levels halve each dimension of the N × 6N image (rounding down) until both are
    // 1, so the file has 1 + floor(log2 6N) levels. Level k holds the faces of size N >> k stacked
    // from the top (ImfEnvmap's sizeOfFace = min(w, h / 6)); chain levels the caller did not give
    // are box-filtered from the last one; levels below the 1×1 faces hold the mean colour.
    std::vector<CubeMap> cubes(chain.levels.begin(), chain.levels.end());
    while (cubes.back().size() > 1) cubes.push_back(boxDownsample(cubes.back(), cubes.back().size() / 2));
    Rgb mean(0.0f);
    for (Face f : kAllFaces) mean += cubes.back().at(f, 0, 0) / 6.0f;

    // OpenEXR whatever the extension: the envmap attribute is OpenEXR's.
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out) throw EnvError(file, "cannot create an OpenEXR writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(n, 6 * n, 3, pixelType(options));
    const int tile = std::min(64, n);  // OpenEXR wants one tile size for every level
    spec.tile_width = tile;
    spec.tile_height = tile;
    spec.attribute("compression", options.compression);
    spec.attribute("textureformat", "CubeFace Environment");  // -> OpenEXR envmap = cube
    spec.attribute("oiio:updirection", "y");
    spec.attribute("mipgloss:orientation", kOrientationNote);
    spec.attribute("mipgloss:levels", chain.levelCount());
    auto fail = [&](const std::string& what) { return EnvError(file, what + ": " + out->geterror()); };
    if (!out->open(file.string(), spec, OIIO::ImageOutput::Create)) throw fail("cannot open for writing");

    int w = n, h = 6 * n;
    for (int level = 0;; ++level) {
        if (level > 0) {
            OIIO::ImageSpec ls = spec;
            ls.width = ls.full_width = w;
            ls.height = ls.full_height = h;
            if (!out->open(file.string(), ls, OIIO::ImageOutput::AppendMIPLevel))
                throw fail("cannot add MIP level " + std::to_string(level));
        }
        std::vector<float> rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
        auto put = [&](int px, int py, const Rgb& v) {
            const std::size_t i = (static_cast<std::size_t>(py) * static_cast<std::size_t>(w) +
                                   static_cast<std::size_t>(px)) * 3;
            rgb[i] = v.x;
            rgb[i + 1] = v.y;
            rgb[i + 2] = v.z;
        };
        if (level < static_cast<int>(cubes.size())) {
            const CubeMap& c = cubes[static_cast<std::size_t>(level)];
            const int m = c.size();
            for (int py = 6 * m; py < h; ++py)  // rows below the faces (non-power-of-two bases)
                for (int px = 0; px < w; ++px) put(px, py, mean);
            for (std::size_t fi = 0; fi < 6; ++fi) {
                const Face f = kAllFaces[fi];
                for (int y = 0; y < m; ++y)
                    for (int x = 0; x < m; ++x) {
                        const auto [ex, ey] = exrPixelOfGlTexel(f, x, y, m);
                        put(ex, static_cast<int>(fi) * m + ey, c.at(f, x, y));
                    }
            }
        } else {
            for (int py = 0; py < h; ++py)
                for (int px = 0; px < w; ++px) put(px, py, mean);
        }
        clampForHalf(rgb, options);
        // One write_tiles call per level, stopping at the first failure. OpenImageIO's write_image
        // writes in chunks and carries on after a failed one, and OpenEXR 3.1 then waits forever
        // for the tile buffer that the failed chunk never released (a full disk hung the bake).
        if (!out->write_tiles(0, w, 0, h, 0, 1, OIIO::TypeDesc::FLOAT, rgb.data()))
            throw fail("cannot write MIP level " + std::to_string(level));
        if (w == 1 && h == 1) break;
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    if (!out->close()) throw fail("cannot finish the file");
}

MipChain readCubeEnvironmentExr(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw EnvError(file, kFileNotFound);
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) throw EnvError(file, "not a readable image: " + OIIO::geterror());
    if (!OIIO::Strutil::iequals(in->spec().get_string_attribute("textureformat"), "CubeFace Environment"))
        throw EnvError(file, "not a cube-face environment map (no envmap=cube attribute)");
    const int levels = in->spec().get_int_attribute("mipgloss:levels", 0);
    MipChain chain;
    for (int level = 0; in->seek_subimage(0, level); ++level) {
        const OIIO::ImageSpec& spec = in->spec();
        const int m = std::min(spec.width, spec.height / 6);
        if (m < 1 || (levels > 0 && level >= levels)) break;
        if (level > 0 && m != levelSize(chain.baseSize(), level)) break;
        const int nc = std::min(spec.nchannels, 3);
        std::vector<float> px(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                              static_cast<std::size_t>(nc));
        if (!in->read_image(0, level, 0, nc, OIIO::TypeDesc::FLOAT, px.data()))
            throw EnvError(file, "cannot read MIP level " + std::to_string(level) + ": " + in->geterror());
        // Gathered in GL order, then sanitised by the one rule every reader uses (decode.h).
        std::vector<Rgb> texels(6 * static_cast<std::size_t>(m) * static_cast<std::size_t>(m));
        for (std::size_t fi = 0; fi < 6; ++fi) {
            const Face f = kAllFaces[fi];
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x) {
                    const auto [ex, ey] = exrPixelOfGlTexel(f, x, y, m);
                    const std::size_t i = (static_cast<std::size_t>(static_cast<int>(fi) * m + ey) *
                                               static_cast<std::size_t>(spec.width) +
                                           static_cast<std::size_t>(ex)) *
                                          static_cast<std::size_t>(nc);
                    texels[(fi * static_cast<std::size_t>(m) + static_cast<std::size_t>(y)) *
                               static_cast<std::size_t>(m) + static_cast<std::size_t>(x)] =
                        nc >= 3 ? Rgb(px[i], px[i + 1], px[i + 2]) : Rgb(px[i]);
                }
        }
        sanitiseRows(texels, m);
        CubeMap c(m);
        for (std::size_t fi = 0; fi < 6; ++fi)
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x)
                    c.at(kAllFaces[fi], x, y) =
                        texels[(fi * static_cast<std::size_t>(m) + static_cast<std::size_t>(y)) *
                                   static_cast<std::size_t>(m) + static_cast<std::size_t>(x)];
        c.makeSeamless();
        chain.levels.push_back(std::move(c));
        if (m == 1) break;
    }
    if (chain.levels.empty()) throw EnvError(file, "holds no cube faces");
    return chain;
}

}  // namespace mipgloss
