// Fuzz entries for the core parsers: environment images (OpenImageIO behind
// loadEnvironmentFromMemory), meshes (our validation in front of OpenMesh) and assets (glTF
// through tinygltf, OBJ with its MTL library through our own reader).
#include "entries.h"

#include "mipgloss/io/import.h"
#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/mesh_files.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <vector>

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

// What a loaded material must hold (entries.h): valid, and every map's channel one of RGBA.
std::string materialProblem(const Material& material, const std::string& name) {
    if (!isValidMaterial(material)) return "material '" + name + "' breaks isValidMaterial";
    const MaterialMaps& m = material.layers.maps;
    for (const TextureRef* t : {&m.baseColor, &m.metallic, &m.roughness, &m.normal, &m.occlusion, &m.emissive})
        if (t->channel < 0 || t->channel > 3)
            return "material '" + name + "' reads channel " + std::to_string(t->channel) + " of " + t->key();
    return {};
}

// An asset's contract (entries.h); `names` the files its messages may name.
std::string assetProblem(const Asset& asset, std::initializer_list<std::string> names) {
    auto namesOne = [&](const std::string& what, const char* kind) -> std::string {
        for (const std::string& n : names)
            if (what.find(n) != std::string::npos) return {};
        return std::string(kind) + " names none of the files (" + *names.begin() + "...): " + what;
    };
    if (asset.parts.empty()) return "an asset loaded without parts";
    for (const AssetPart& part : asset.parts) {
        if (!part.mesh) return "part '" + part.name + "' has no mesh";
        if (!part.mesh->isValid()) return "part '" + part.name + "': its mesh breaks the Mesh invariants";
        if (part.mesh->triangleCount() == 0) return "part '" + part.name + "' has no triangles";
        if (part.material < -1 || part.material >= static_cast<int>(asset.materials.size()))
            return "part '" + part.name + "' has material " + std::to_string(part.material) + " of " +
                   std::to_string(asset.materials.size());
    }
    for (const AssetMaterial& m : asset.materials)
        if (std::string p = materialProblem(m.material, m.name); !p.empty()) return p;
    for (const std::string& w : asset.warnings)
        if (std::string p = namesOne(w, "a warning"); !p.empty()) return p;
    return {};
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

std::string gltfImport(Bytes data) {
    const std::string name = "fuzz.glb";
    try {
        const Asset asset = loadGltfFromMemory(data, name);
        return assetProblem(asset, {name});
    } catch (const AssetError& e) {
        return namesFile(e.what(), name, "an AssetError");
    }
}

std::string mtlImport(Bytes data) {
    if (data.empty()) return {};
    const bool withLibrary = (data[0] & 1) == 0;
    const Bytes rest = data.subspan(1);
    const auto zero = std::find(rest.begin(), rest.end(), std::uint8_t{0});
    const auto split = static_cast<std::size_t>(zero - rest.begin());
    const Bytes obj = rest.first(split);
    const Bytes mtl = zero == rest.end() ? Bytes() : rest.subspan(split + 1);
    const std::string objName = "fuzz.obj", mtlName = "fuzz.mtl";

    // The library alone.
    try {
        for (const AssetMaterial& m : parseMtl(mtl, mtlName, "textures"))
            if (std::string p = materialProblem(m.material, m.name); !p.empty()) return "parseMtl: " + p;
    } catch (const AssetError& e) {
        if (std::string p = namesFile(e.what(), mtlName, "parseMtl's AssetError"); !p.empty()) return p;
    }

    // The OBJ with it.
    const std::vector<NamedBytes> libraries =
        withLibrary ? std::vector<NamedBytes>{{mtlName, mtl}} : std::vector<NamedBytes>{};
    try {
        const Asset asset = loadObjAssetFromMemory(obj, objName, libraries);
        return assetProblem(asset, {objName, mtlName});
    } catch (const AssetError& e) {
        const std::string what = e.what();
        if (what.find(objName) == std::string::npos && what.find(mtlName) == std::string::npos)
            return "an AssetError names neither " + objName + " nor " + mtlName + ": " + what;
    }
    return {};
}

}  // namespace mipgloss::fuzz
