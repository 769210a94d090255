// `mipgloss render` from the tests that drive it (tests/app/cli): the command, and what its
// pictures are read back with.
#pragma once

#include "cli_support.h"

#include <OpenImageIO/imageio.h>

#include <QImage>
#include <QRect>
#include <QStringList>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace mipgloss::test {

// `mipgloss render ARGS`.
inline CliResult runRender(const QStringList& args) { return runCli(QStringList{"render"} + args, 120000); }

// The bounding box of pixels that differ from the top-left corner's (the flat background).
inline QRect objectRect(const QImage& image) {
    const QRgb background = image.pixel(0, 0);
    QRect r;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (image.pixel(x, y) != background) r |= QRect(x, y, 1, 1);
    return r;
}

// One float image read back with its channel names (top row first).
struct FloatImage {
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::vector<float> values;
    float at(int x, int y, const std::string& channel) const {
        const auto c = std::find(channels.begin(), channels.end(), channel) - channels.begin();
        return values[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                          channels.size() + static_cast<std::size_t>(c)];
    }
};

inline FloatImage readFloatImage(const std::filesystem::path& file) {
    FloatImage image;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) return image;
    const OIIO::ImageSpec& spec = in->spec();
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.channelnames;
    image.values.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                        static_cast<std::size_t>(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.values.data())) image.values.clear();
    return image;
}

}  // namespace mipgloss::test
