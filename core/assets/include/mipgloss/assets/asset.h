// Assets as artists have them (issue 21, docs/assets.md): glTF 2.0 (.gltf with external or
// embedded buffers and images, .glb) read with tinygltf, and OBJ with its MTL library read by our
// own parser. An asset is parts (meshes with UVs, authored normals and tangents, each drawn with
// one material) and named layered materials with texture maps (scene.h, MaterialMaps).
//
// glTF: every triangle primitive of the default scene (or of every root node when the file has no
// scene), placed by its node's world matrix (positions by the matrix, normals by its inverse
// transpose, tangents by its upper 3×3), so a part's mesh needs no transform of its own. Missing
// normals are computed (area-weighted, flat where the primitive has no shared vertices); missing
// tangents are computed from the UVs (computeTangents) when the material has a normal map.
// Materials: the metallic–roughness core (base colour factor and texture, metallic and roughness
// factors and their texture, G and B), normal texture and scale, occlusion and strength, emissive
// factor and texture, alpha mode and cutoff; KHR_materials_clearcoat's factor and roughness when
// present. Extensions the file requires and we do not read are refused by name.
//
// OBJ + MTL: v, vt, vn and f (v, v/vt, v//vn, v/vt/vn; negative indices count back), usemtl,
// mtllib, s (smoothing groups: where a face has no vn, its corners share a computed normal only
// with faces of its own group; "s off" faces are flat; faces before any s line are one group).
// MTL: newmtl, Kd, Ns (to roughness), Ke, d/Tr (below 1: blend), Pr (wins over Ns), Pm, map_Kd,
// map_Pr, map_Pm, map_Ke, bump/map_Bump/norm (with -bm), -imfchan; each texture path relative to
// the MTL file. Ks, map_Ks, map_Ns and map_d have no place in the metallic–roughness model: Ks is
// ignored, the maps are warnings. OBJ's v axis points up: it is flipped to glTF's.
//
// Hostile files: every count, index and offset is checked against what holds it before it is
// used; a refusal (AssetError) names the file and the element (mesh, primitive, accessor, buffer
// view, image, line) at fault. A texture whose file is missing or does not decode is a warning
// when the textures are decoded (TextureCache), and the part is drawn without it.
#pragma once

#include "mipgloss/scene/library.h"
#include "mipgloss/assets/mesh_files.h"
#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/scene.h"

#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mipgloss {

class AssetError : public FileError {
public:
    using FileError::FileError;
};

struct AssetMaterial {
    std::string name;   // as in the file ("Material 3" when it has none), unique within the asset
    Material material;  // layered, with maps
};

// The material as a library entry: its name, or "Material" where that cannot be a library
// material's name (library.h, materialNameProblem); the caller makes it unique in its library.
LibraryMaterial libraryEntryOf(const AssetMaterial& material);

struct AssetPart {
    std::string name;  // glTF: the node's (or mesh's) name, " 2", " 3" for more primitives; OBJ: the material's
    std::shared_ptr<const Mesh> mesh;
    int material = -1;                 // index into Asset::materials, -1: none (the default material)
};

// A glTF camera as its node places it (world space; the file's own units): a perspective camera
// looks along its node's −Z with +Y up. Orthographic cameras are not read (a warning names them).
struct AssetCamera {
    std::string name;      // the camera's name, or its node's, or "camera N"
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit
    glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, perpendicular to forward
    float fovYDegrees = 45.0f;             // yfov
};

// The cameras of several asset files, by each file's absolute path (SceneObject::meshSource).
using FileCameras = std::map<std::string, std::vector<AssetCamera>>;

// The orbit camera that looks through `camera` once its asset is placed by `placement` (addAsset),
// its target on the view axis as far ahead as `scene`'s centre (at least a thousandth of the
// scene's radius ahead).
OrbitCamera viewThrough(const AssetCamera& camera, const Transform& placement, const Bounds& scene);

// An image as the file holds it (PNG, JPEG, ...) and its MIME type ("image/png"...), for decoding
// (TextureCache).
struct EncodedImage {
    std::vector<unsigned char> bytes;
    std::string mimeType;
};
// Encoded images by TextureRef::key() ("file#image 3").
using EncodedImages = std::map<std::string, std::shared_ptr<const EncodedImage>>;

struct Asset {
    std::vector<AssetPart> parts;
    std::vector<AssetMaterial> materials;
    std::vector<AssetCamera> cameras;   // glTF: in the order the scene's nodes reach them
    std::vector<std::string> warnings;  // one line each, naming the file
    // Read by loadMesh (a plain mesh file): its one part is the whole file (SceneObject::meshPart -1).
    bool wholeFile = false;
    // The glTF's embedded images the materials read, kept from the parse that read the asset, so
    // decoding them (TextureCache::load) never parses the file again (gltfio's loader hands its
    // resource loader the buffers the same way).
    EncodedImages images;
};

// The box of all parts (the file's own placement of them).
Bounds assetBounds(const Asset& asset);

// Adds the asset's parts to `scene` as objects, all under the one `placement` (so they stay where
// the file put them relative to each other), meshSource `source` and meshPart their index (-1
// for a whole file). Each asset material is added once under a free name (uniqueName) and shared
// by its parts; a part without one gets `fallback` as a material of its own. Returns the indices
// of the objects added.
std::vector<int> addAsset(Scene& scene, const Asset& asset, const std::string& source, const Transform& placement,
                          const Material& fallback);

// .gltf, .glb, and .obj (an OBJ is an asset when it names an MTL library or has texture
// coordinates; otherwise loadAsset reads it as loadMesh does, as one part without a material).
bool isAssetFile(const std::filesystem::path& path);
std::span<const char* const> assetExtensions();  // ".gltf", ".glb", ".obj"
// Everything the window imports and `render --mesh` reads: meshExtensions() and assetExtensions(),
// each once.
std::vector<const char*> importExtensions();

// Loads an asset; the format from the extension. Throws AssetError (MeshError for a plain mesh).
Asset loadAsset(const std::filesystem::path& path);

// glTF from bytes (a .glb when they start with "glTF", else JSON); `file` names it in messages
// and its folder resolves external buffers and images (none: external references are refused).
Asset loadGltfFromMemory(std::span<const unsigned char> bytes, const std::filesystem::path& file);

// The material library of an OBJ (an .mtl file's text), each texture path resolved against
// `folder`. Unknown keys are skipped; a bad value throws AssetError naming the line.
std::vector<AssetMaterial> parseMtl(std::span<const unsigned char> bytes, const std::filesystem::path& file,
                                    const std::filesystem::path& folder);

// An OBJ with its MTL libraries from memory; `mtlFiles` gives each library's bytes by the name the
// OBJ's mtllib line uses (a library not there is a warning, its materials drawn as the default).
struct NamedBytes {
    std::string name;
    std::span<const unsigned char> bytes;
};
Asset loadObjAssetFromMemory(std::span<const unsigned char> bytes, const std::filesystem::path& file,
                             std::span<const NamedBytes> mtlFiles);

// Every image of a glTF file, encoded, in the file's order (an external image's bytes are read
// too): one parse of the file, for a caller that has no Asset to take them from (a scene file
// naming a glTF's image; TextureCache::load parses each such file once per call). Nothing is
// cached here. Throws AssetError when the file cannot be read.
std::vector<EncodedImage> gltfImages(const std::filesystem::path& file);

}  // namespace mipgloss
