// `mipgloss bake`: environment file -> mip chain -> a directory of EXR levels, a manifest and one
// mip-mapped cube-map EXR. The output directory is replaced atomically: everything is written to
// a temporary sibling first and renamed into place only when complete, so a failure never leaves
// a partial directory where a good one was.
#pragma once

#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/import.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace mipgloss {

struct BakeRequest {
    std::filesystem::path environment;  // empty: the embedded default environment
    Builder builder = kDefaultBuilder;
    ImportOptions import;               // import.faceSize is --size
    bool irradiance = false;
    std::filesystem::path outDir;
    // Stages "import", "build <builder>", "irradiance", "write"; false cancels (Cancelled).
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
    std::filesystem::path cubeFile;  // the single mip-mapped OpenEXR cube map
    int faceSize = 0;
    std::vector<BakedLevel> levels;
    bool irradiance = false;
    double importSeconds = 0.0, buildSeconds = 0.0, writeSeconds = 0.0;
    ImportReport report;
};

// Throws EnvError (bad input or unwritable output, naming the file) or std::invalid_argument
// (no output folder). Never leaves a partial outDir.
BakeSummary bake(const BakeRequest& request);

// The manifest.json text for a bake (exposed for tests).
std::string manifestJson(const BakeSummary& summary, Builder builder,
                         const std::string& source);

}  // namespace mipgloss
