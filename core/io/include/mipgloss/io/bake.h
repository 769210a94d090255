// `mipgloss bake`: environment file -> mip chain -> a directory of EXR levels, a manifest and one
// mip-mapped cube-map EXR. The output directory is replaced atomically: everything is written to
// a temporary sibling first and renamed into place only when complete, so a failure never leaves
// a partial directory where a good one was.
#pragma once

#include "mipgloss/io/import.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace mipgloss {

struct BakeRequest {
    std::filesystem::path environment;  // empty: the embedded default environment
    std::string method = "phong";
    ImportOptions import;               // import.faceSize is --size
    bool irradiance = false;
    std::filesystem::path outDir;
    // Progress: a stage name and the fraction of that stage done.
    std::function<void(const std::string& stage, float fraction)> progress;
};

struct BakedLevel {
    int level = 0;
    int size = 0;
    double lambda = 0.0;
    double phongExponent = 0.0;
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
// (unknown method). Never leaves a partial outDir.
BakeSummary bake(const BakeRequest& request);

// The manifest.json text for a bake (exposed for tests).
std::string manifestJson(const BakeSummary& summary, const std::string& method,
                         const std::string& source);

}  // namespace mipgloss
