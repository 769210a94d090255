#include "mipgloss/io/texture.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

namespace mipgloss {

namespace {

std::string extensionForMime(const std::string& mime, const std::string& name) {
    if (mime == "image/png") return ".png";
    if (mime == "image/jpeg") return ".jpg";
    if (mime == "image/webp") return ".webp";
    const std::string ext = std::filesystem::path(name).extension().string();
    return ext.empty() ? ".png" : ext;
}

// Spreads `channels` 8-bit values a pixel, stored 4 bytes apart, into RGBA in place.
void expandToRgba(std::uint8_t* rgba, std::uint64_t pixels, int channels) {
    for (std::uint64_t i = 0; i < pixels; ++i) {
        std::uint8_t* q = &rgba[i * 4];
        switch (channels) {
            case 1: q[1] = q[2] = q[0]; q[3] = 255; break;
            case 2: q[3] = q[1]; q[1] = q[2] = q[0]; break;
            case 3: q[3] = 255; break;
            default: break;
        }
    }
}

// One 2×2 box halving of a w × h RGBA8 image (odd sizes rounded up, the last row or column
// counted once), into `half`.
void halveOnce(const std::vector<std::uint8_t>& rgba, int w, int h, std::vector<std::uint8_t>& half) {
    const int hw = (w + 1) / 2, hh = (h + 1) / 2;
    half.assign(static_cast<std::size_t>(hw) * static_cast<std::size_t>(hh) * 4, 0);
    for (int y = 0; y < hh; ++y)
        for (int x = 0; x < hw; ++x)
            for (int c = 0; c < 4; ++c) {
                unsigned sum = 0, count = 0;
                for (int dy = 0; dy < 2; ++dy)
                    for (int dx = 0; dx < 2; ++dx) {
                        const int sx = 2 * x + dx, sy = 2 * y + dy;
                        if (sx >= w || sy >= h) continue;
                        sum += rgba[(static_cast<std::size_t>(sy) * w + sx) * 4 + c];
                        ++count;
                    }
                half[(static_cast<std::size_t>(y) * hw + x) * 4 + c] = static_cast<std::uint8_t>((sum + count / 2) / count);
            }
}

// How many halvings bring w × h within maxSize on a side (downsizeTexture's loop, counted); k
// halvings, each rounding up, give ⌈w / 2^k⌉ × ⌈h / 2^k⌉ (fittedTextureSize).
int halvingsToFit(int w, int h, int maxSize) {
    int k = 0;
    while (w > maxSize || h > maxSize) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        ++k;
    }
    return k;
}

void checkDimensions(const OIIO::ImageSpec& spec, const std::string& name) {
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw TextureError(name, "the image has no pixels (" + std::to_string(spec.width) + " x " +
                                     std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) + " channels)");
    const std::uint64_t pixels = static_cast<std::uint64_t>(spec.width) * static_cast<std::uint64_t>(spec.height);
    if (pixels > kMaxTexturePixels || spec.depth > 1)
        throw TextureError(name, "the image is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                                     " pixels, more than a texture may have (" + std::to_string(kMaxTexturePixels) +
                                     ")");
}

std::string readError(OIIO::ImageInput& in) {
    const std::string err = in.geterror();
    return "cannot read the pixels (truncated or corrupt image)" + (err.empty() ? std::string() : ": " + err);
}

// Rows y0 … y0 + rows of the image as `channels` 8-bit values a pixel, 4 bytes apart, into `rgba`.
// Read as the file stores them (every channel, its own type, contiguous) and converted here:
// OpenImageIO's read_scanlines, asked for another type or layout, converts through a scratch
// buffer of 64 MiB per call (ImageInput::read_scanlines' chunk), whatever the rows asked for; a
// band of a few rows then maps 64 MiB each time (a 16384-row image halved to 4096 would map it
// 4096 times; one test's 1300 small bands took three minutes under AddressSanitizer). The
// conversion is the one read_scanlines applies (convert_image). A file whose channels differ in
// type (no single native type to read), or with more than four channels (the band as stored
// would then outgrow its RGBA strip many times over), is read the converting way.
bool readBand(OIIO::ImageInput& in, int y0, int rows, int channels, std::vector<std::uint8_t>& stored, std::uint8_t* rgba) {
    const OIIO::ImageSpec& spec = in.spec();
    const int ybegin = spec.y + y0, yend = ybegin + rows;
    if (!spec.channelformats.empty() || spec.nchannels > 4)
        return in.read_scanlines(0, 0, ybegin, yend, 0, 0, channels, OIIO::TypeDesc::UINT8, rgba, 4);
    const auto pixelBytes = static_cast<OIIO::stride_t>(spec.pixel_bytes(true));
    stored.resize(static_cast<std::size_t>(pixelBytes) * static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(rows));
    if (!in.read_scanlines(0, 0, ybegin, yend, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, stored.data())) return false;
    return OIIO::convert_image(channels, spec.width, rows, 1, stored.data(), spec.format, pixelBytes, pixelBytes * spec.width,
                               OIIO::AutoStride, rgba, OIIO::TypeDesc::UINT8, 4, 4 * static_cast<OIIO::stride_t>(spec.width),
                               OIIO::AutoStride);
}

TextureImage readOpened(OIIO::ImageInput& in, const std::string& name, int maxSize) {
    const OIIO::ImageSpec& spec = in.spec();
    checkDimensions(spec, name);
    maxSize = std::max(maxSize, 1);
    const std::uint64_t pixels = static_cast<std::uint64_t>(spec.width) * static_cast<std::uint64_t>(spec.height);
    const int channels = std::min(spec.nchannels, 4);
    TextureImage image;
    image.width = image.fileWidth = spec.width;
    image.height = image.fileHeight = spec.height;
    image.channels = channels;
    const int halvings = halvingsToFit(spec.width, spec.height, maxSize);
    if (halvings == 0 || spec.tile_width > 0) {
        // Read straight into the RGBA buffer (4 bytes a pixel, the file's channels first), then
        // fill in the rest in place: no second copy of the image.
        image.rgba.resize(pixels * 4);
        if (!in.read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, image.rgba.data(), 4))
            throw TextureError(name, readError(in));
        expandToRgba(image.rgba.data(), pixels, channels);
        downsizeTexture(image, maxSize);
    } else {
        // Larger than maxSize (the header says so before a pixel is decoded): read it in bands of
        // 2^halvings rows, each band halved to one row as it comes. A band starts at a multiple
        // of its height, so every 2 × 2 box of every level lies inside one band and the result is
        // downsizeTexture's on the whole image, byte for byte; but the full-size image is never
        // held (a 16384² texture held 1 GiB of RGBA to keep 64 MiB).
        const int band = 1 << halvings;
        const TextureSize out = fittedTextureSize({spec.width, spec.height}, maxSize);
        image.rgba.resize(out.rgbaBytes());
        std::vector<std::uint8_t> strip, half, stored;
        for (int row = 0, y0 = 0; y0 < spec.height; ++row, y0 += band) {
            const int rows = std::min(band, spec.height - y0);
            const std::uint64_t stripPixels = static_cast<std::uint64_t>(spec.width) * static_cast<std::uint64_t>(rows);
            strip.assign(stripPixels * 4, 0);
            if (!readBand(in, y0, rows, channels, stored, strip.data())) throw TextureError(name, readError(in));
            expandToRgba(strip.data(), stripPixels, channels);
            int w = spec.width, h = rows;
            for (int i = 0; i < halvings; ++i) {
                halveOnce(strip, w, h, half);
                strip.swap(half);
                w = (w + 1) / 2;
                h = (h + 1) / 2;
            }
            std::copy(strip.begin(), strip.end(), image.rgba.begin() + static_cast<std::ptrdiff_t>(row) * out.width * 4);
        }
        image.width = out.width;
        image.height = out.height;
    }
    if (image.width != image.fileWidth || image.height != image.fileHeight)
        image.warnings.push_back(name + ": texture of " + std::to_string(image.fileWidth) + " x " +
                                 std::to_string(image.fileHeight) + " downsized to " + std::to_string(image.width) +
                                 " x " + std::to_string(image.height) + " (the limit is " + std::to_string(maxSize) +
                                 " on a side)");
    return image;
}

// glTF's textures are straight (unassociated) alpha: OpenImageIO multiplies colour by alpha on
// decode unless told not to, which would darken an opaque material's colour wherever its alpha is
// below one and give masked leaves dark fringes (docs/assets.md).
OIIO::ImageSpec straightAlpha() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

}  // namespace

void downsizeTexture(TextureImage& image, int maxSize) {
    maxSize = std::max(maxSize, 1);
    std::vector<std::uint8_t> half;
    while (image.width > maxSize || image.height > maxSize) {
        halveOnce(image.rgba, image.width, image.height, half);
        image.rgba.swap(half);
        image.width = (image.width + 1) / 2;
        image.height = (image.height + 1) / 2;
    }
}

// A JPEG cut short: libjpeg fills the missing rows with grey and OpenImageIO reports no error, so
// the picture would show a grey patch without a word (issue 34). Every JPEG ends with an
// end-of-image marker (FF D9) after its last scan (FF DA); in the scans' entropy-coded data a 0xFF
// byte is always followed by 00 or a restart marker, so FF D9 there is the real end. "" when
// `bytes` is not a JPEG or ends as one should.
static std::string truncatedJpegProblem(std::span<const unsigned char> bytes) {
    if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return {};
    std::size_t lastScan = 0;
    for (std::size_t i = 2; i + 1 < bytes.size(); ++i)
        if (bytes[i] == 0xFF && bytes[i + 1] == 0xDA) lastScan = i;
    if (lastScan == 0) return "a JPEG without image data (no scan): truncated";
    for (std::size_t i = lastScan + 2; i + 1 < bytes.size(); ++i)
        if (bytes[i] == 0xFF && bytes[i + 1] == 0xD9) return {};
    return "a truncated JPEG (" + std::to_string(bytes.size()) + " bytes, no end-of-image marker after its last scan)";
}

namespace {

// Opens `file` (its header read, no pixels), or throws naming it.
std::unique_ptr<OIIO::ImageInput> openFile(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw TextureError(file, kFileNotFound);
    const OIIO::ImageSpec config = straightAlpha();
    auto in = OIIO::ImageInput::open(file.string(), &config);
    if (!in) {
        std::string err = OIIO::geterror();
        throw TextureError(file, "not a readable image" + (err.empty() ? std::string() : ": " + err));
    }
    return in;
}

// Opens `bytes` through `reader` (which must outlive what is returned), or throws naming it.
std::unique_ptr<OIIO::ImageInput> openMemory(OIIO::Filesystem::IOMemReader& reader, std::span<const unsigned char> bytes,
                                             const std::string& nameForMessages, const std::string& mimeType) {
    if (bytes.empty()) throw TextureError(nameForMessages, "the image is empty (0 bytes)");
    if (const std::string problem = truncatedJpegProblem(bytes); !problem.empty()) throw TextureError(nameForMessages, problem);
    const std::string fakeName = "embedded" + extensionForMime(mimeType, nameForMessages);
    // With a configuration, OpenImageIO 2.4's readers take the proxy from it (the argument alone is
    // dropped when they read the configuration).
    OIIO::ImageSpec config = straightAlpha();
    OIIO::Filesystem::IOProxy* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto in = OIIO::ImageInput::open(fakeName, &config, &reader);
    if (!in) {
        std::string err = OIIO::geterror();
        throw TextureError(nameForMessages, "not a readable image" + (err.empty() ? std::string() : ": " + err));
    }
    return in;
}

bool isJpegFile(const std::filesystem::path& file) {
    std::ifstream head(file, std::ios::binary);
    unsigned char magic[2] = {0, 0};
    return head.read(reinterpret_cast<char*>(magic), 2) && magic[0] == 0xFF && magic[1] == 0xD8;
}

TextureSize sizeOf(OIIO::ImageInput& in, const std::string& name) {
    checkDimensions(in.spec(), name);
    return {in.spec().width, in.spec().height};
}

}  // namespace

TextureImage decodeTexture(const std::filesystem::path& file, int maxSize) {
    if (isJpegFile(file)) {  // (a missing file is not one: openFile refuses it below)
        // A JPEG is read once, into memory, where its end is checked and it is decoded.
        std::ifstream head(file, std::ios::binary);
        const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(head)), std::istreambuf_iterator<char>());
        return decodeTextureFromMemory(bytes, file.string(), "image/jpeg", maxSize);
    }
    return readOpened(*openFile(file), file.string(), maxSize);
}

TextureImage decodeTextureFromMemory(std::span<const unsigned char> bytes, const std::string& nameForMessages,
                                     const std::string& mimeType, int maxSize) {
    OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(bytes.data()), bytes.size());
    return readOpened(*openMemory(reader, bytes, nameForMessages, mimeType), nameForMessages, maxSize);
}

TextureSize textureSize(const std::filesystem::path& file) {
    return sizeOf(*openFile(file), file.string());
}

TextureSize textureSizeFromMemory(std::span<const unsigned char> bytes, const std::string& nameForMessages,
                                  const std::string& mimeType) {
    OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(bytes.data()), bytes.size());
    return sizeOf(*openMemory(reader, bytes, nameForMessages, mimeType), nameForMessages);
}

TextureSize fittedTextureSize(TextureSize size, int maxSize) {
    const long long band = 1LL << halvingsToFit(size.width, size.height, std::max(maxSize, 1));  // ≤ 2^31
    return {static_cast<int>((size.width + band - 1) / band), static_cast<int>((size.height + band - 1) / band)};
}

}  // namespace mipgloss
