#include "decode.h"

#include "text.h"
#include "mipgloss/ibl/colour.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace mipgloss::io_detail {

namespace fs = std::filesystem;

namespace {

const std::vector<float>& srgbTable(int bits) {
    static const std::vector<float> t8 = [] {
        std::vector<float> t(256);
        for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<float>(srgbToLinear(static_cast<double>(i) / 255.0));
        return t;
    }();
    static const std::vector<float> t16 = [] {
        std::vector<float> t(65536);
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = static_cast<float>(srgbToLinear(static_cast<double>(i) / 65535.0));
        return t;
    }();
    return bits == 8 ? t8 : t16;
}


// Reads the first subimage of an opened input; `name` is what error messages call it.
Image readOpened(OIIO::ImageInput& in, const fs::path& name) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw EnvError(name, "image has no pixels (" + sizeText(spec.width, spec.height) + ")");
    if (spec.depth > 1) throw EnvError(name, "volume images are not environments");
    const int nc = std::min(spec.nchannels, 3);
    const std::size_t count = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
    const auto base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
    const bool integer = base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::INT8 ||
                         base == OIIO::TypeDesc::UINT16 || base == OIIO::TypeDesc::INT16 ||
                         base == OIIO::TypeDesc::UINT32 || base == OIIO::TypeDesc::INT32;

    std::vector<float> values(count * static_cast<std::size_t>(nc));
    auto fail = [&] {
        std::string err = in.geterror();
        if (err.empty()) err = "unknown error";
        return EnvError(name, "cannot read the pixels (corrupt or truncated file?): " + err);
    };
    // LDR formats are sRGB-encoded: decode through an exact table, linear inside from here on.
    if (base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::UINT16) {
        const int bits = base == OIIO::TypeDesc::UINT8 ? 8 : 16;
        const std::vector<float>& table = srgbTable(bits);
        if (bits == 8) {
            std::vector<std::uint8_t> raw(values.size());
            if (!in.read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, raw.data())) throw fail();
            for (std::size_t i = 0; i < raw.size(); ++i) values[i] = table[raw[i]];
        } else {
            std::vector<std::uint16_t> raw(values.size());
            if (!in.read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT16, raw.data())) throw fail();
            for (std::size_t i = 0; i < raw.size(); ++i) values[i] = table[raw[i]];
        }
    } else {
        if (!in.read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, values.data())) throw fail();
        if (integer)
            for (float& v : values) v = static_cast<float>(srgbToLinear(std::clamp(static_cast<double>(v), 0.0, 1.0)));
    }

    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.px.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const float* p = &values[i * static_cast<std::size_t>(nc)];
        // Grey (and grey + alpha) replicate the first channel; a third channel makes RGB.
        img.px[i] = nc >= 3 ? Rgb(p[0], p[1], p[2]) : Rgb(p[0]);
    }
    return img;
}

// Colour as stored: alpha is ignored, so it must not be multiplied in.
const OIIO::ImageSpec& readConfig() {
    static const OIIO::ImageSpec config = [] {
        OIIO::ImageSpec c;
        c.attribute("oiio:UnassociatedAlpha", 1);
        return c;
    }();
    return config;
}

// The end every read shares: the input as opened (null: OpenImageIO refused it), decoded,
// sanitised, counted and recorded in the report.
Image readInput(std::unique_ptr<OIIO::ImageInput> in, const fs::path& name, ImportReport& report) {
    if (!in) {
        std::string err = OIIO::geterror();
        if (err.empty()) err = "unknown error";
        throw EnvError(name, "not a readable image: " + err);
    }
    Image img = readOpened(*in, name);
    in->close();
    addCounts(report, name, sanitise(img.px));
    report.files.push_back(name);
    return img;
}

}  // namespace

SanitiseCounts sanitise(std::span<Rgb> px) {
    SanitiseCounts n;
    float maxFinite = 0.0f;
    for (const Rgb& p : px)
        for (int c = 0; c < 3; ++c)
            if (std::isfinite(p[c])) maxFinite = std::max(maxFinite, p[c]);
    for (Rgb& p : px) {
        for (int c = 0; c < 3; ++c) {
            float& v = p[c];
            if (std::isnan(v)) {
                v = 0.0f;
                ++n.nan;
            } else if (v < 0.0f) {
                v = 0.0f;
                ++n.negative;
            } else if (std::isinf(v)) {
                v = maxFinite;
                ++n.inf;
            }
        }
    }
    return n;
}

void addCounts(ImportReport& report, const fs::path& file, const SanitiseCounts& n) {
    if (n.nan + n.inf + n.negative == 0) return;
    report.nanCount += n.nan;
    report.infCount += n.inf;
    report.negativeCount += n.negative;
    std::ostringstream msg;
    msg << file.string() << ": replaced " << n.nan << " NaN value(s) by 0, " << n.inf
        << " infinite value(s) by the largest finite value and " << n.negative
        << " negative value(s) by 0";
    report.warnings.push_back(msg.str());
}

Image readImageFile(const fs::path& file, ImportReport& report) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw EnvError(file, "file not found");
    if (fs::is_directory(file, ec)) throw EnvError(file, "is a directory, expected an image file");
    const auto bytes = fs::file_size(file, ec);
    if (ec) throw EnvError(file, "cannot read the file: " + ec.message());
    if (bytes == 0) throw EnvError(file, "file is empty (0 bytes)");
    return readInput(OIIO::ImageInput::open(file.string(), &readConfig()), file, report);
}

Image readImageMemory(std::span<const unsigned char> bytes, const std::string& name, ImportReport& report) {
    if (bytes.empty()) throw EnvError(name, "file is empty (0 bytes)");
    OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(bytes.data()), bytes.size());
    // With a configuration, OpenImageIO 2.4 takes the proxy from it, not from the argument.
    OIIO::ImageSpec config = readConfig();
    void* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    return readInput(OIIO::ImageInput::open(name, &config, &reader), name, report);
}

}  // namespace mipgloss::io_detail
