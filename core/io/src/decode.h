// Image decoding (OpenImageIO) into linear float RGB, and the one sanitising rule. Internal to the
// io library: the layouts, the lat-long conversion and the cube EXR reader build on it.
//
// Colour: integer images (PNG, JPEG, 8/16-bit TIFF, ...) are sRGB-encoded and decoded with the
// exact sRGB EOTF (colour.h); half and float images (EXR, HDR, float TIFF) are linear and kept as
// they are. The first three channels are read; one channel (grey, grey + alpha) is replicated to
// RGB; alpha is ignored (read unassociated, so colour is never multiplied by it).
#pragma once

#include "sanitise.h"

#include "mipgloss/io/import.h"

#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace mipgloss::io_detail {

// Adds the counts to the report with one warning naming the file (nothing when all are zero).
void addCounts(ImportReport& report, const std::filesystem::path& file, const SanitiseCounts& n);

// Where a streamed decode sends each strip: rows [y0, y1), sanitised. Called in order, one at a
// time, from a pool thread.
using StripConsumer = std::function<void(int y0, int y1, std::span<const Rgb> rows)>;
// Chosen from the image's size once the header is read: a consumer streams the image, none reads
// it whole.
using ChooseStrips = std::function<StripConsumer(int width, int height)>;

// Decodes and sanitises an image file, recording it in the report. Throws EnvError, also when the
// header asks for more memory than the machine can spare (checked before allocating). Decodes by
// strips of rows into the float RGB pixels (one copy of the image, plus one strip),
// reporting stage "import" from p0 to p1 after each strip; throws Cancelled when told to stop.
Image readImageFile(const std::filesystem::path& file, ImportReport& report, const Progress& progress = {},
                    float p0 = 0.0f, float p1 = 0.0f);
// The same, streamed when `choose` gives a consumer: then the returned image is empty (0 × 0).
// While strip k is consumed in the background, strip k + 1 is read.
Image readImageFile(const std::filesystem::path& file, ImportReport& report, const Progress& progress, float p0,
                    float p1, const ChooseStrips& choose);

// The same from bytes in memory; `name` stands for the file (its extension names the format).
Image readImageMemory(std::span<const unsigned char> bytes, const std::string& name, ImportReport& report,
                      const Progress& progress = {}, float p0 = 0.0f, float p1 = 0.0f);

}  // namespace mipgloss::io_detail
