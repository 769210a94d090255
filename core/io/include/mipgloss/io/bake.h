// `mipgloss bake`: environment file -> mip chain -> a folder of files, in one of two formats:
//
//   exr (default)  DIR/level<k>/{px..nz}.exr, DIR/environment_mips.exr (one mip-mapped OpenEXR
//                  cube map), DIR/irradiance/{px..nz}.exr with the irradiance map
//   dds            DIR/environment_mips.dds (one DDS cube map holding the whole chain, dds.h),
//                  DIR/irradiance.dds with the irradiance map
//
// and DIR/manifest.json in both. The files are written in parallel, each by its own writer, into a
// temporary sibling of DIR, which is renamed into place only when every file is complete: a
// failure or a cancel never leaves a partial folder where a good one was (docs/bake-output.md).
#pragma once

#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/cube_exr.h"
#include "mipgloss/io/dds.h"
#include "mipgloss/io/import.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace mipgloss {

enum class BakeFormat { Exr, Dds };

// bake's EXR compression: none. Filtered float texels have full-entropy mantissas, so OpenEXR's
// lossless compressions save 2-15 % of the bytes at 8-25 times the write time (sunset.exr at 1024:
// none 202 MB in 0.28 s, zip 188 MB in 4.2 s, piz 172 MB in 6.7 s; docs/bake-output.md).
inline constexpr const char* kBakeExrCompression = "none";

const char* bakeFormatName(BakeFormat format);                     // "exr", "dds"
bool parseBakeFormat(const std::string& name, BakeFormat& out);  // false for anything else

struct BakeRequest {
    std::filesystem::path environment;  // empty: the embedded default environment
    Builder builder = kDefaultBuilder;
    ImportOptions import;               // import.faceSize is --size
    bool irradiance = false;
    std::filesystem::path outDir;
    BakeFormat format = BakeFormat::Exr;
    ExrWriteOptions exr{kBakeExrCompression, false};  // format exr: compression, pixel type
    DdsType ddsType = DdsType::Half;    // format dds
    // Files are written in parallel (one task per file on the thread pool); false writes them one
    // at a time, in the same order, with the same bytes (tests compare the two).
    bool parallelWrite = true;
    // Stages "import", "build <builder>", "irradiance", "write", "done", always called from the
    // thread that called bake(); false cancels (Cancelled).
    Progress progress;
};

struct BakedLevel {
    int level = 0;
    int size = 0;
    // The lobe the level holds (phong.h's schedule): ∞ at level 0 (the mirror), NaN for levels
    // the previewer never reads; and the artist's λ that means that lobe (NaN when not read).
    double phongExponent = 0.0;
    double lambda = 0.0;
    bool read = false;
};

struct BakeSummary {
    std::filesystem::path outDir;
    std::filesystem::path cubeFile;  // the single mip-mapped cube map: environment_mips.exr or .dds
    BakeFormat format = BakeFormat::Exr;
    ExrWriteOptions exr;              // as requested (format exr)
    DdsType ddsType = DdsType::Half;  // as requested (format dds)
    int faceSize = 0;
    std::vector<BakedLevel> levels;
    bool irradiance = false;
    double importSeconds = 0.0, buildSeconds = 0.0, writeSeconds = 0.0;
    int filesWritten = 0;              // image files, not counting the manifest
    std::uintmax_t bytesWritten = 0;   // their sizes added up
    ImportReport report;
};

// Throws EnvError (bad input or unwritable output, naming the file), Cancelled, or
// std::invalid_argument (no output folder, or an EXR compression OpenImageIO does not write).
// Never leaves a partial outDir.
BakeSummary bake(const BakeRequest& request);

// The manifest.json text for a bake (exposed for tests).
std::string manifestJson(const BakeSummary& summary, Builder builder, const std::string& source);

}  // namespace mipgloss
