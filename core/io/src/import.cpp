// Environment import: a file or folder -> a sanitised, seamless cube (import.h). The pieces live
// beside it: decode.cpp (pixels and colour), face_files.cpp (six face files), layouts.cpp (crosses
// and strips), latlong.cpp and latlong_*.cpp (lat-long conversion).
#include "mipgloss/io/import.h"

#include "decode.h"
#include "face_files.h"
#include "latlong.h"
#include "layouts.h"
#include "text.h"

#include "mipgloss/ibl/resample.h"

#include <algorithm>
#include <memory>
#include <set>

namespace mipgloss {

namespace fs = std::filesystem;
using namespace io_detail;

namespace {

ImportedEnvironment finish(CubeMap cube, ImportReport report, int faceSize, const Progress& progress) {
    if (faceSize > 0 && faceSize != cube.size()) cube = resampleCube(cube, faceSize);
    cube.makeSeamless();
    reportProgress(progress, "import", 1.0f);
    return {std::move(cube), std::move(report)};
}

// A single image's layout: the one asked for, else the one its proportions say (throws EnvError
// naming `file` when they say none).
EnvLayout layoutOf(const ImportOptions& options, int width, int height, const fs::path& file) {
    return options.layout == EnvLayout::Auto ? detectLayout(width, height, file) : options.layout;
}

// A lat-long's face size: the one asked for, else a quarter of its width.
int latLongFaceSize(const ImportOptions& options, int width) {
    return options.faceSize > 0 ? options.faceSize : std::max(1, width / 4);
}

ImportedEnvironment fromSingleImage(const Image& img, const fs::path& file, const ImportOptions& options,
                                    ImportReport report, const Progress& progress) {
    const EnvLayout layout = layoutOf(options, img.width, img.height, file);
    report.layout = layout;
    if (layout == EnvLayout::LatLong) {
        CubeMap cube = latLongToCube(img, latLongFaceSize(options, img.width), progress, 0.3f, 0.95f);
        return finish(std::move(cube), std::move(report), 0, progress);
    }
    CubeMap cube = cubeFromLayout(img, layout, file);
    reportProgress(progress, "import", 0.5f);
    return finish(std::move(cube), std::move(report), options.faceSize, progress);
}

ImportedEnvironment fromFaces(const std::array<fs::path, 6>& files, const ImportOptions& options,
                              ImportReport report, const Progress& progress) {
    report.layout = EnvLayout::Faces;
    CubeMap cube = cubeFromFaceFiles(files, options.handedness, report, progress);
    return finish(std::move(cube), std::move(report), options.faceSize, progress);
}

ImportedEnvironment loadDirectory(const fs::path& dir, const ImportOptions& options,
                                  const Progress& progress) {
    if (options.layout != EnvLayout::Auto && options.layout != EnvLayout::Faces)
        throw EnvError(dir, std::string("is a folder; layout ") + layoutName(options.layout) +
                                " needs a single image file");
    const auto byStem = imagesByStem(dir);
    // Every (family, prefix) that some file in the folder could belong to.
    std::vector<std::pair<FaceName, FaceSet>> groups;
    std::set<std::pair<int, std::string>> seen;
    for (const auto& [stem, files] : byStem) {
        for (const FaceName& name : familyReadings(stem)) {
            if (!seen.insert({name.family, name.prefix}).second) continue;
            groups.push_back({name, lookUpFaces(byStem, name, ".exr")});
        }
    }
    if (groups.empty())
        throw EnvError(dir, "no cube face files found; expected six image files named with one of "
                            "the families px/nx/py/ny/pz/nz, posx/negx/posy/negy/posz/negz, "
                            "right/left/top/bottom/front/back, rt/lf/up/dn/ft/bk (any common prefix)");
    // Complete sets first, then the one with the most faces; ties: shorter prefix, family order.
    std::stable_sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) {
        if (a.second.found != b.second.found) return a.second.found > b.second.found;
        if (a.first.prefix.size() != b.first.prefix.size())
            return a.first.prefix.size() < b.first.prefix.size();
        return a.first.family < b.first.family;
    });
    const auto& [name, set] = groups.front();
    if (set.found < 6) throwMissingFaces(dir, set, name, options.handedness);
    ImportReport report;
    int complete = 0;
    for (const auto& g : groups) complete += g.second.found == 6 ? 1 : 0;
    if (complete > 1)
        report.warnings.push_back(dir.string() + ": several complete sets of face files; using " +
                                  set.files[0].filename().string() + " and its siblings");
    return fromFaces(set.files, options, std::move(report), progress);
}

}  // namespace

// ---------------------------------------------------------------------------------------------

ImportedEnvironment loadEnvironment(const fs::path& path, const ImportOptions& options,
                                    const Progress& progress) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw EnvError(path, kFileNotFound);
    reportProgress(progress, "import", 0.0f);
    if (fs::is_directory(path, ec)) return loadDirectory(path, options, progress);

    // A member of a face-naming family with siblings next to it is one face of six.
    const bool mayBeFace = options.layout == EnvLayout::Auto || options.layout == EnvLayout::Faces;
    if (mayBeFace) {
        const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
        const auto byStem = imagesByStem(dir);
        const std::string ext = lower(path.extension().string());
        std::vector<std::pair<FaceName, FaceSet>> partial;
        for (const FaceName& name : familyReadings(lower(path.stem().string()))) {
            FaceSet set = lookUpFaces(byStem, name, ext);
            if (set.found == 6) return fromFaces(set.files, options, {}, progress);
            partial.push_back({name, std::move(set)});
        }
        std::stable_sort(partial.begin(), partial.end(),
                         [](const auto& a, const auto& b) { return a.second.found > b.second.found; });
        if (!partial.empty() && (partial.front().second.found > 1 || options.layout == EnvLayout::Faces))
            throwMissingFaces(path, partial.front().second, partial.front().first, options.handedness);
        if (options.layout == EnvLayout::Faces)
            throw EnvError(path, "the name does not belong to a face-naming family "
                                 "(px/nx/..., posx/negx/..., right/left/top/bottom/front/back, "
                                 "rt/lf/up/dn/ft/bk)");
    }

    // A lat-long that the scatter converts is converted strip by strip as it is decoded
    // (latlong.h, LatLongStream): the panorama is never whole in memory, and the conversion runs
    // beside the decode. Anything else is decoded whole first.
    ImportReport report;
    std::unique_ptr<LatLongStream> stream;
    const ChooseStrips choose = [&](int width, int height) -> StripConsumer {
        EnvLayout layout;
        try {
            layout = layoutOf(options, width, height, path);
        } catch (const EnvError&) {
            return {};  // decoded whole, refused by fromSingleImage as before
        }
        const int n = latLongFaceSize(options, width);
        if (layout != EnvLayout::LatLong || !latLongStreams(width, height, n)) return {};
        stream = std::make_unique<LatLongStream>(width, height, n);
        return [&stream](int y0, int y1, std::span<const Rgb> rows) { stream->addStrip(y0, y1, rows); };
    };
    // The decode's share of the bar is known only once the header has chosen: streamed, the
    // decode carries the conversion (to 0.8); whole, the conversion comes after it (from 0.3).
    const Progress decodeProgress = [&](const std::string& stage, float f) {
        return !progress || progress(stage, f * (stream ? 0.8f : 0.3f));
    };
    const Image img = readImageFile(path, report, decodeProgress, 0.0f, 1.0f, choose);
    if (stream) {
        report.layout = EnvLayout::LatLong;
        CubeMap cube = stream->finish(progress, 0.8f, 0.95f);
        return finish(std::move(cube), std::move(report), 0, progress);
    }
    reportProgress(progress, "import", 0.3f);
    return fromSingleImage(img, path, options, std::move(report), progress);
}

ImportedEnvironment loadEnvironmentFromMemory(std::span<const unsigned char> bytes, const std::string& name,
                                              const ImportOptions& options, const Progress& progress) {
    if (options.layout == EnvLayout::Faces) throw EnvError(name, "six face files cannot come from memory");
    ImportReport report;
    const Image img = readImageMemory(bytes, name, report, progress, 0.0f, 0.3f);
    reportProgress(progress, "import", 0.3f);
    return fromSingleImage(img, name, options, std::move(report), progress);
}

DecodedImage decodeImage(const fs::path& file, ImportReport* report, const Progress& progress) {
    ImportReport local;
    return readImageFile(file, report ? *report : local, progress, 0.0f, 1.0f);
}

}  // namespace mipgloss
