#include "mipgloss/io/image_file.h"

#include "mipgloss/io/atomic_write.h"
#include "mipgloss/io/import.h"

#include <OpenImageIO/imageio.h>

namespace mipgloss {

void writeFloatChannels(const std::filesystem::path& file, int width, int height,
                        const std::vector<std::string>& names, const std::vector<float>& values) {
    const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * names.size();
    if (width <= 0 || height <= 0 || names.empty() || values.size() != expected)
        throw EnvError(file, "nothing to write (empty image or mismatched channels)");
    // The writer is chosen by the target's extension; the pixels go to the temporary file.
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw EnvError(file, "cannot create an image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, static_cast<int>(names.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    spec.alpha_channel = -1;  // no channel is alpha, whatever its name
    spec.attribute("compression", "zip");
    writeAtomicallyByPath(file, [&](const std::filesystem::path& temporary) {
        if (!out->open(temporary.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, values.data()) ||
            !out->close())
            throw EnvError(file, "cannot write: " + out->geterror());
    });
}

}  // namespace mipgloss
