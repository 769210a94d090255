#include "mipgloss/assets/asset.h"

#include "formats/asset_files.h"
#include "formats/mesh_formats.h"
#include "formats/reading.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <iterator>
#include <string_view>

namespace fs = std::filesystem;

namespace mipgloss {

namespace {

using meshfile::lowerExtension;

constexpr std::array<const char*, 3> kAssetExtensions = {".gltf", ".glb", ".obj"};

// The OBJ's mtllib names and whether it has texture coordinates: what makes it an asset.
struct ObjOutline {
    std::vector<std::string> libraries;
    bool hasUvs = false;
};

ObjOutline outline(std::span<const unsigned char> bytes) {
    ObjOutline out;
    std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string_view::npos) continue;
        line.remove_prefix(first);
        if (line.rfind("vt", 0) == 0 && line.size() > 2 && (line[2] == ' ' || line[2] == '\t')) out.hasUvs = true;
        if (line.rfind("mtllib", 0) == 0 && line.size() > 6 && (line[6] == ' ' || line[6] == '\t')) {
            std::string_view rest = line.substr(6);
            while (!rest.empty()) {
                const std::size_t a = rest.find_first_not_of(" \t\r");
                if (a == std::string_view::npos) break;
                rest.remove_prefix(a);
                if (rest.front() == '#') break;  // a comment ends the line
                const std::size_t b = std::min(rest.find_first_of(" \t\r"), rest.size());
                out.libraries.emplace_back(rest.substr(0, b));
                rest.remove_prefix(b);
            }
        }
    }
    return out;
}

}  // namespace

std::vector<unsigned char> readAssetFile(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw AssetError(path, kFileNotFound);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw AssetError(path, "cannot open the file");
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::span<const char* const> assetExtensions() { return kAssetExtensions; }

std::vector<const char*> importExtensions() {
    std::vector<const char*> out(meshExtensions().begin(), meshExtensions().end());
    for (const char* e : kAssetExtensions)
        if (std::find_if(out.begin(), out.end(), [&](const char* o) { return std::string_view(o) == e; }) == out.end())
            out.push_back(e);
    return out;
}

bool isAssetFile(const fs::path& path) {
    const std::string ext = lowerExtension(path);
    return std::find_if(kAssetExtensions.begin(), kAssetExtensions.end(),
                        [&](const char* e) { return ext == e; }) != kAssetExtensions.end();
}

Asset loadAsset(const fs::path& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".gltf" || ext == ".glb") return loadGltfFile(path);
    if (ext == ".obj") {
        const std::vector<unsigned char> bytes = readAssetFile(path);
        const ObjOutline o = outline(bytes);
        if (!o.libraries.empty() || o.hasUvs) {
            std::vector<std::vector<unsigned char>> libraryBytes;
            std::vector<NamedBytes> libraries;
            for (const std::string& name : o.libraries) {
                std::error_code ec;
                const fs::path mtl = path.parent_path() / name;
                if (!fs::is_regular_file(mtl, ec)) continue;  // the reader warns
                libraryBytes.push_back(readAssetFile(mtl));
            }
            std::size_t k = 0;
            for (const std::string& name : o.libraries) {
                std::error_code ec;
                if (!fs::is_regular_file(path.parent_path() / name, ec)) continue;
                libraries.push_back(NamedBytes{name, libraryBytes[k++]});
            }
            return loadObjAssetFromMemory(bytes, path, libraries);
        }
    }
    // A plain mesh: one part, the default material.
    MeshReport report;
    Mesh mesh = loadMesh(path, &report);
    if (mesh.name.empty()) mesh.name = path.stem().string();
    Asset asset;
    asset.wholeFile = true;
    asset.warnings = std::move(report.warnings);
    AssetPart part;
    part.name = mesh.name;
    part.mesh = std::make_shared<const Mesh>(std::move(mesh));
    asset.parts.push_back(std::move(part));
    return asset;
}

LibraryMaterial libraryEntryOf(const AssetMaterial& material) {
    return {materialNameProblem(material.name).empty() ? material.name : "Material", material.material};
}

OrbitCamera viewThrough(const AssetCamera& camera, const Transform& placement, const Bounds& scene) {
    const glm::mat4 m = placement.matrix();
    const glm::mat3 turn(m);  // rotation × uniform scale: directions keep their angles
    const glm::vec3 position(m * glm::vec4(camera.position, 1.0f));
    const glm::vec3 forward = glm::normalize(turn * camera.forward);
    const glm::vec3 up = glm::normalize(turn * camera.up);
    const float ahead = glm::dot(scene.centre() - position, forward);
    return cameraThrough(position, forward, up, camera.fovYDegrees, std::max(ahead, 1e-3f * std::max(scene.radius(), 1e-6f)));
}

Bounds assetBounds(const Asset& asset) {
    Bounds b;
    bool first = true;
    for (const AssetPart& part : asset.parts) {
        if (!part.mesh || part.mesh->positions.empty()) continue;
        if (first) b = part.mesh->bounds;
        b.min = glm::min(b.min, part.mesh->bounds.min);
        b.max = glm::max(b.max, part.mesh->bounds.max);
        first = false;
    }
    return b;
}

std::vector<int> addAsset(Scene& scene, const Asset& asset, const std::string& source, const Transform& placement,
                          const Material& fallback) {
    std::vector<MaterialId> ids(asset.materials.size(), kNoMaterial);
    std::vector<int> added;
    // As Scene::addMaterial names and numbers them, in linear time for the whole asset (one
    // material per part without one: 30 000 such parts took seconds through addMaterial).
    UniqueNames names;
    for (const NamedMaterial& m : scene.materials) names.reserve(m.name);
    MaterialId next = scene.nextMaterialId();
    auto addMaterial = [&](const std::string& name, const Material& material) {
        NamedMaterial m;
        m.id = next++;
        m.name = names.take(name);
        m.material = material;
        scene.materials.push_back(std::move(m));
        return scene.materials.back().id;
    };
    for (std::size_t k = 0; k < asset.parts.size(); ++k) {
        const AssetPart& part = asset.parts[k];
        SceneObject object;
        object.name = part.name;
        object.mesh = part.mesh;
        object.meshSource = source;
        object.meshPart = asset.wholeFile ? -1 : static_cast<int>(k);
        object.transform = placement;
        if (part.material >= 0 && static_cast<std::size_t>(part.material) < ids.size()) {
            MaterialId& id = ids[static_cast<std::size_t>(part.material)];
            const AssetMaterial& m = asset.materials[static_cast<std::size_t>(part.material)];
            if (id == kNoMaterial) id = addMaterial(m.name, m.material);
            object.material = id;
        } else {
            object.material = addMaterial(object.name, fallback);  // one of its own, as Scene::addObject gives
        }
        scene.objects.push_back(std::move(object));
        added.push_back(static_cast<int>(scene.objects.size()) - 1);
    }
    return added;
}

}  // namespace mipgloss
