// Fuzz entries for the core parsers: environment images (OpenImageIO behind
// loadEnvironmentFromMemory) and meshes (our validation in front of OpenMesh).
#include "entries.h"

#include "mipgloss/io/import.h"
#include "mipgloss/scene/mesh.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace mipgloss::fuzz {
namespace {

// A message must name the file: the GUI and the command line show nothing else.
std::string namesFile(const std::string& what, const std::string& name, const char* kind) {
    if (what.find(name) != std::string::npos) return {};
    return std::string(kind) + " does not name the file '" + name + "': " + what;
}

constexpr std::array<const char*, 5> kImageExtensions = {".exr", ".hdr", ".png", ".jpg", ".tif"};
constexpr std::array<EnvLayout, 8> kLayouts = {
    EnvLayout::Auto, EnvLayout::Auto, EnvLayout::HorizontalCross, EnvLayout::VerticalCross,
    EnvLayout::HorizontalStrip, EnvLayout::VerticalStrip, EnvLayout::LatLong, EnvLayout::Auto};

// Images whose header asks for more pixels than this are skipped: decoding a legitimately huge
// image is slow, not a bug, and would drown the fuzzer in timeouts and memory-limit reports (the
// import's own refusal of headers beyond the machine's memory is tested in tests/core/io).
constexpr long long kMaxPixels = 512LL * 512LL;

bool headerTooLarge(Bytes file, const std::string& name) {
    OIIO::Filesystem::IOMemReader reader(const_cast<std::uint8_t*>(file.data()), file.size());
    OIIO::ImageSpec config;
    void* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto in = OIIO::ImageInput::open(name, &config, &reader);
    if (!in) {
        (void)OIIO::geterror();  // clear the thread's error, or it accumulates over runs
        return false;           // the import will refuse it; that is what we want to see
    }
    const OIIO::ImageSpec& spec = in->spec();
    const long long pixels = static_cast<long long>(spec.width) * spec.height * std::max(spec.depth, 1);
    in->close();
    return pixels > kMaxPixels || spec.width > 8192 || spec.height > 8192;
}

}  // namespace

std::string environmentImport(Bytes data) {
    if (data.empty()) return {};
    const std::uint8_t selector = data[0];
    const Bytes file = data.subspan(1);
    const std::string name = std::string("fuzz-environment") + kImageExtensions[selector % 5];
    ImportOptions options;
    options.layout = kLayouts[(selector >> 3) & 7];
    options.faceSize = (selector & 0x40) ? 8 : 0;  // 8: the resampling path; 0: native size
    if (!file.empty() && headerTooLarge(file, name)) return {};
    try {
        const ImportedEnvironment env = loadEnvironmentFromMemory(file, name, options);
        if (env.cube.empty()) return "an imported environment is empty";
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < env.cube.size(); ++y)
                for (int x = 0; x < env.cube.size(); ++x) {
                    const Rgb c = env.cube.at(static_cast<Face>(f), x, y);
                    for (int k = 0; k < 3; ++k)
                        if (!std::isfinite(c[k]) || c[k] < 0.0f)
                            return "an imported texel is not finite and non-negative (the sanitising rule)";
                }
        for (const std::string& w : env.report.warnings)
            if (std::string p = namesFile(w, name, "a warning"); !p.empty()) return p;
    } catch (const EnvError& e) {
        return namesFile(e.what(), name, "an EnvError");
    }
    return {};
}

std::string meshImport(Bytes data) {
    static constexpr std::array<const char*, 5> kExtensions = {".obj", ".off", ".ply", ".stl", ".om"};
    if (data.empty()) return {};
    const std::string name = std::string("fuzz-mesh") + kExtensions[data[0] % 5];
    try {
        MeshReport report;
        const Mesh mesh = loadMeshFromMemory(data.subspan(1), name, &report);
        if (!mesh.isValid()) return "a loaded mesh breaks the Mesh invariants";
        if (mesh.triangleCount() == 0) return "a loaded mesh has no triangles";
        for (const std::string& w : report.warnings)
            if (std::string p = namesFile(w, name, "a warning"); !p.empty()) return p;
    } catch (const MeshError& e) {
        return namesFile(e.what(), name, "a MeshError");
    }
    return {};
}

}  // namespace mipgloss::fuzz
