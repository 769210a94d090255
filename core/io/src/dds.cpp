#include "mipgloss/io/dds.h"

#include "mipgloss/ibl/colour.h"
#include "mipgloss/io/atomic_write.h"
#include "mipgloss/io/cube_exr.h"
#include "mipgloss/io/import.h"

#include <OpenImageIO/imageio.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace mipgloss {

namespace fs = std::filesystem;

// DDS stores little-endian words and texels; the texel buffers below are copied as they are.
static_assert(std::endian::native == std::endian::little, "the DDS writer assumes a little-endian host");

namespace {

// Microsoft's DDS reference ("DDS_HEADER", "DDS_PIXELFORMAT", "DDS_HEADER_DXT10").
constexpr std::uint32_t kMagic = 0x20534444;  // "DDS "
constexpr std::uint32_t kFourCCDx10 = 0x30315844;  // "DX10"
constexpr std::uint32_t kDdsdCaps = 0x1, kDdsdHeight = 0x2, kDdsdWidth = 0x4, kDdsdPitch = 0x8,
                        kDdsdPixelFormat = 0x1000, kDdsdMipMapCount = 0x20000;
constexpr std::uint32_t kDdpfFourCC = 0x4;
constexpr std::uint32_t kCapsComplex = 0x8, kCapsTexture = 0x1000, kCapsMipMap = 0x400000;
constexpr std::uint32_t kCaps2CubeMap = 0x200, kCaps2AllFaces = 0xFC00;  // +X -X +Y -Y +Z -Z bits
constexpr std::uint32_t kDimensionTexture2D = 3, kMiscTextureCube = 0x4;
constexpr std::uint32_t kAlphaModeOpaque = 3;  // DDS_ALPHA_MODE_OPAQUE: A is always 1

std::uint32_t bytesPerTexel(DdsType type) { return type == DdsType::Half ? 8u : 16u; }

void put32(std::vector<unsigned char>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
std::uint32_t get32(const unsigned char* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

// The 148 bytes before the texels.
std::vector<unsigned char> headerBytes(int size, int levels, DdsType type) {
    const auto n = static_cast<std::uint32_t>(size);
    std::vector<unsigned char> h;
    h.reserve(kDdsHeaderBytes);
    put32(h, kMagic);
    put32(h, 124);  // DDS_HEADER.dwSize
    put32(h, kDdsdCaps | kDdsdHeight | kDdsdWidth | kDdsdPitch | kDdsdPixelFormat | kDdsdMipMapCount);
    put32(h, n);                        // height
    put32(h, n);                        // width
    put32(h, n * bytesPerTexel(type));  // pitch: bytes in a row of the top level
    put32(h, 0);                        // depth
    put32(h, static_cast<std::uint32_t>(levels));
    for (int i = 0; i < 11; ++i) put32(h, 0);  // dwReserved1
    put32(h, 32);                              // DDS_PIXELFORMAT.dwSize
    put32(h, kDdpfFourCC);
    put32(h, kFourCCDx10);
    for (int i = 0; i < 5; ++i) put32(h, 0);  // bit count and masks: unused with a FourCC
    put32(h, kCapsTexture | kCapsComplex | (levels > 1 ? kCapsMipMap : 0u));
    put32(h, kCaps2CubeMap | kCaps2AllFaces);
    put32(h, 0);  // caps3
    put32(h, 0);  // caps4
    put32(h, 0);  // dwReserved2
    put32(h, type == DdsType::Half ? kDxgiR16G16B16A16Float : kDxgiR32G32B32A32Float);
    put32(h, kDimensionTexture2D);
    put32(h, kMiscTextureCube);
    put32(h, 1);  // arraySize: one cube (D3D counts cubes here, not faces)
    put32(h, kAlphaModeOpaque);
    return h;
}

// One level of one face as RGBA texels in the file's type.
void packFace(const CubeMap& c, Face f, DdsType type, std::vector<unsigned char>& out) {
    const int m = c.size();
    std::vector<float> rgba(static_cast<std::size_t>(m) * static_cast<std::size_t>(m) * 4);
    std::size_t i = 0;
    for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x) {
            const Rgb& p = c.at(f, x, y);
            for (int ch = 0; ch < 3; ++ch) rgba[i++] = type == DdsType::Half ? std::min(p[ch], kHalfMax) : p[ch];
            rgba[i++] = 1.0f;
        }
    out.resize(rgba.size() * (type == DdsType::Half ? 2 : 4));
    if (type == DdsType::Float) {
        std::memcpy(out.data(), rgba.data(), out.size());
    } else {
        // OpenImageIO's float -> half conversion (Imath): round to nearest even.
        OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, rgba.data(), OIIO::TypeDesc::HALF, out.data(),
                                   static_cast<int>(rgba.size()));
    }
}

}  // namespace

const char* ddsTypeName(DdsType type) { return type == DdsType::Half ? "half" : "float"; }

bool parseDdsType(const std::string& name, DdsType& out) {
    if (name == "half") out = DdsType::Half;
    else if (name == "float") out = DdsType::Float;
    else return false;
    return true;
}

void writeCubeDds(const MipChain& chain, const fs::path& file, DdsType type) {
    prepareChainFile(chain, file);
    const int n = chain.baseSize();
    writeAtomically(file, [&](int fd) {
        const int own = ::dup(fd);  // fclose closes it, not the atomic write's descriptor
        FILE* f = own >= 0 ? ::fdopen(own, "wb") : nullptr;
        if (!f) {
            const int error = errno;
            if (own >= 0) ::close(own);
            throw EnvError(file, "cannot be created: " + std::error_code(error, std::generic_category()).message());
        }
        const std::vector<unsigned char> header = headerBytes(n, chain.levelCount(), type);
        bool ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
        std::vector<unsigned char> face;
        // Direct3D's order: each face (array slice) with its whole mip chain, then the next face.
        for (Face fc : kAllFaces)
            for (const CubeMap& level : chain.levels) {
                if (!ok) break;
                packFace(level, fc, type, face);
                ok = std::fwrite(face.data(), 1, face.size(), f) == face.size();
            }
        const int writeErrno = ok ? 0 : errno;
        if (std::fclose(f) != 0 && ok) ok = false;
        if (!ok)
            throw EnvError(file, "could not be written: " +
                                     std::error_code(writeErrno ? writeErrno : EIO, std::generic_category()).message());
    });
}

DdsCube readCubeDds(const fs::path& file) {
    std::error_code ec;
    const auto fileSize = fs::file_size(file, ec);
    if (ec) throw EnvError(file, "cannot be read: " + ec.message());
    if (fileSize < kDdsHeaderBytes) throw EnvError(file, "too short for a DDS file with a DX10 header");
    FILE* f = std::fopen(file.c_str(), "rb");
    if (!f) throw EnvError(file, "cannot be opened");
    std::array<unsigned char, kDdsHeaderBytes> h{};
    const bool headerRead = std::fread(h.data(), 1, h.size(), f) == h.size();
    auto fail = [&](const std::string& why) {
        std::fclose(f);
        return EnvError(file, why);
    };
    if (!headerRead) throw fail("cannot read the header");
    if (get32(&h[0]) != kMagic || get32(&h[4]) != 124) throw fail("not a DDS file");
    DdsCube out;
    DdsHeader& d = out.header;
    d.flags = get32(&h[8]);
    d.height = get32(&h[12]);
    d.width = get32(&h[16]);
    d.pitchOrLinearSize = get32(&h[20]);
    d.depth = get32(&h[24]);
    d.mipMapCount = get32(&h[28]);
    d.pixelFormatFlags = get32(&h[80]);
    d.fourCC = get32(&h[84]);
    d.caps = get32(&h[108]);
    d.caps2 = get32(&h[112]);
    d.dxgiFormat = get32(&h[128]);
    d.resourceDimension = get32(&h[132]);
    d.miscFlag = get32(&h[136]);
    d.arraySize = get32(&h[140]);
    d.miscFlags2 = get32(&h[144]);
    if (!(d.pixelFormatFlags & kDdpfFourCC) || d.fourCC != kFourCCDx10) throw fail("has no DX10 header");
    DdsType type;
    if (d.dxgiFormat == kDxgiR16G16B16A16Float) type = DdsType::Half;
    else if (d.dxgiFormat == kDxgiR32G32B32A32Float) type = DdsType::Float;
    else throw fail("DXGI format " + std::to_string(d.dxgiFormat) + " is not RGBA half or float");
    if (d.resourceDimension != kDimensionTexture2D || !(d.miscFlag & kMiscTextureCube) || d.arraySize != 1 ||
        (d.caps2 & (kCaps2CubeMap | kCaps2AllFaces)) != (kCaps2CubeMap | kCaps2AllFaces))
        throw fail("is not a single cube map with six faces");
    if (d.width != d.height || d.width < 1 || d.width > 65536) throw fail("has faces that are not square");
    const int n = static_cast<int>(d.width);
    const int levels = (d.flags & kDdsdMipMapCount) && d.mipMapCount > 0 ? static_cast<int>(d.mipMapCount) : 1;
    if (levels > fullChainLevelCount(n)) throw fail("has more MIP levels than its face size allows");
    // The file must hold exactly the texels the header promises: checked before allocating.
    std::uint64_t texels = 0;
    for (int k = 0; k < levels; ++k)
        texels += 6ull * static_cast<std::uint64_t>(levelSize(n, k)) * static_cast<std::uint64_t>(levelSize(n, k));
    const std::uint64_t expected = kDdsHeaderBytes + texels * bytesPerTexel(type);
    if (fileSize != expected)
        throw fail("is " + std::to_string(fileSize) + " bytes, its header says " + std::to_string(expected));

    out.chain.levels.reserve(static_cast<std::size_t>(levels));
    for (int k = 0; k < levels; ++k) out.chain.levels.emplace_back(levelSize(n, k));
    out.minAlpha = std::numeric_limits<float>::infinity();
    out.maxAlpha = -std::numeric_limits<float>::infinity();
    std::vector<unsigned char> raw;
    std::vector<float> rgba;
    for (Face fc : kAllFaces)
        for (CubeMap& level : out.chain.levels) {
            const int m = level.size();
            const std::size_t values = static_cast<std::size_t>(m) * static_cast<std::size_t>(m) * 4;
            raw.resize(values * (type == DdsType::Half ? 2 : 4));
            if (std::fread(raw.data(), 1, raw.size(), f) != raw.size()) throw fail("ends early");
            rgba.resize(values);
            if (type == DdsType::Float) std::memcpy(rgba.data(), raw.data(), raw.size());
            else
                OIIO::convert_pixel_values(OIIO::TypeDesc::HALF, raw.data(), OIIO::TypeDesc::FLOAT, rgba.data(),
                                           static_cast<int>(values));
            std::size_t i = 0;
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x, i += 4) {
                    level.at(fc, x, y) = Rgb(rgba[i], rgba[i + 1], rgba[i + 2]);
                    out.minAlpha = std::min(out.minAlpha, rgba[i + 3]);
                    out.maxAlpha = std::max(out.maxAlpha, rgba[i + 3]);
                }
        }
    std::fclose(f);
    for (CubeMap& level : out.chain.levels) level.makeSeamless();
    return out;
}

}  // namespace mipgloss
