// The scene a user edits: objects (a mesh, a placement, a material) and the environment settings.
// GL-free and Qt-free; the renderer reads it, the window edits it, scene files store it.
//
// A material is the paper's per-object state (Ashikhmin & Ghosh 2002, §4): a minimum mip level λ
// (GL_TEXTURE_MIN_LOD) and the lookup direction, the reflection vector or the surface normal.
#pragma once

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/mesh.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <array>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <unordered_map>
#include <string_view>
#include <vector>

namespace mipgloss {

enum class LookupMode { Reflect, Normal };
const char* lookupModeName(LookupMode mode);  // "reflect", "normal"
bool parseLookupMode(const std::string& text, LookupMode& out);

// How the picture's linear colour becomes the screen's (tonemap.frag): linear clips at 1 (no tone
// mapping: the 3D Commerce certification's), Reinhard x/(1 + x) per channel, ACES (Narkowicz's
// fit), Khronos PBR Neutral (keeps base colours as authored below its knee; the glTF Sample
// Viewer's) and AgX (Sobotka's, in Wrensch's polynomial fit; Blender's default).
enum class ToneMap { Linear, Reinhard, Aces, PbrNeutral, Agx };
inline constexpr std::array<ToneMap, 5> kAllToneMaps = {ToneMap::Linear, ToneMap::Reinhard, ToneMap::Aces,
                                                       ToneMap::PbrNeutral, ToneMap::Agx};
const char* toneMapName(ToneMap map);  // "linear", "reinhard", "aces", "pbr-neutral", "agx"
bool parseToneMap(const std::string& text, ToneMap& out);


// An image a material reads (an asset's texture, asset.h): a file, or image `image` of a glTF file
// (a .glb's binary chunk, a data URI) when `image` >= 0. `channel` picks the one channel a scalar
// map reads (0 R, 1 G, 2 B, 3 A: glTF keeps roughness in G and metallic in B); colour maps read RGB
// and ignore it. No file: no texture.
struct TextureRef {
    std::string file;
    int image = -1;
    int channel = 0;

    bool empty() const { return file.empty(); }
    // The one name for this image, shared by every material that reads it (the texture caches'
    // key, the messages): the file, or "file#image 3".
    std::string key() const;
    bool operator==(const TextureRef&) const = default;
};

// How a material's alpha (base colour factor × texture alpha) cuts it: glTF's alphaMode. Blend
// is drawn over what is behind it (the renderer draws blended objects after the opaque ones and
// the background, farthest first, without writing depth; docs/assets.md).
enum class AlphaMode { Opaque, Mask, Blend };
const char* alphaModeName(AlphaMode mode);  // "opaque", "mask", "blend"
bool parseAlphaMode(const std::string& text, AlphaMode& out);

// The texture maps of a layered material, glTF's metallic–roughness set (docs/assets.md). Each map
// multiplies its factor in Layers (base colour, metallic, roughness) or here (emissive); a map
// without a file reads 1. The roughness map gives every fragment its own lobe (the lobe stack
// serves any λ per fragment, lobes.h).
inline constexpr float kMaxNormalScale = 10.0f;  // |normalScale| at most (a steeper tilt is noise)
inline constexpr float kMaxEmissive = 1e20f;     // the radiance range the renderer holds (radiance-range.md)

// How a material reads one of its maps (glTF's textureInfo, its sampler and KHR_texture_transform):
// which UV set, the transform applied to it, the wrap modes and whether magnification and
// minification take the nearest texel. The default is glTF's: set 0, no transform, repeat, linear.
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };
const char* textureWrapName(TextureWrap wrap);  // "repeat", "clamp", "mirror"
bool parseTextureWrap(const std::string& text, TextureWrap& out);
struct TextureSampling {
    int texCoord = 0;  // TEXCOORD_0 or TEXCOORD_1
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    bool nearestMagnify = false, nearestMinify = false;
    // KHR_texture_transform: uv' = T(offset) · R(rotation) · S(scale) · uv, rotation in radians
    // counter-clockwise in UV space (the extension's matrix).
    glm::vec2 offset{0.0f}, scale{1.0f};
    float rotation = 0.0f;

    glm::mat3 uvTransform() const;
    bool operator==(const TextureSampling&) const = default;
};
// The maps in MaterialMaps's order, each one's TextureSampling at its index.
enum class MapSlot { BaseColor, Metallic, Roughness, Normal, Occlusion, Emissive };
inline constexpr int kMaterialMapCount = 6;

struct MaterialMaps {
    TextureRef baseColor;   // sRGB RGBA: colour × Layers::baseColor, alpha × baseAlpha
    TextureRef metallic;    // linear, one channel × Layers::metallic
    TextureRef roughness;   // linear, one channel × Layers::roughness
    TextureRef normal;      // tangent space, RGB in [0, 1] → [−1, 1], XY × normalScale
    TextureRef occlusion;   // linear R: 1 + strength·(R − 1) multiplies every lookup
    TextureRef emissive;    // sRGB RGB × emissiveFactor
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;
    Rgb emissiveFactor{0.0f};  // linear radiance added (glTF's emissiveFactor, ≥ 0), × the emissive map
    float baseAlpha = 1.0f;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    // glTF's doubleSided: false draws only the faces whose front (counter-clockwise) faces the
    // viewer. True by default, as every mesh format but glTF means it (open meshes show inside).
    bool doubleSided = true;
    // How each map is read (MapSlot order); metallic and roughness share glTF's one texture.
    std::array<TextureSampling, kMaterialMapCount> sampling{};
    const TextureSampling& samplingOf(MapSlot slot) const { return sampling[static_cast<std::size_t>(slot)]; }
    TextureSampling& samplingOf(MapSlot slot) { return sampling[static_cast<std::size_t>(slot)]; }

    bool anyTexture() const;
    // Whether drawing needs the maps at all: a texture, emission, or an alpha cut (the renderer
    // draws such materials with a program of their own).
    bool inUse() const;
    // Every texture the maps read, in the order of the fields (empty ones left out).
    std::vector<TextureRef> textures() const;
    bool operator==(const MaterialMaps&) const = default;
};

// A layered material (layered.h): a diffuse base under a glossy specular layer with Fresnel, and
// an optional clear coat over both, set the way glTF and Substance set them (metallic–roughness).
// Every value, each base colour component too, is in [0, 1] (a surface reflects at most what
// reaches it; isValidLayers).
struct Layers {
    Rgb baseColor{0.8f};         // linear: the diffuse colour of a dielectric, F0 of a metal
    float metallic = 0.0f;       // 0 dielectric, 1 metal (in between: a blend of the two)
    float roughness = 0.5f;      // the specular lobe, n = roughnessToExponent (specular.h)
    float specular = 0.04f;      // F0 of the dielectric part
    float coat = 0.0f;           // clear coat weight (0: none)
    float coatRoughness = 0.05f; // its lobe; its F0 is kDielectricF0
    MaterialMaps maps;           // texture maps (assets); none by default
    // KHR_materials_specular (layered.h, dielectricFresnel): the dielectric's F0 is
    // min(specular · specularColor, 1) · specularWeight and its F90 specularWeight; the metal is
    // untouched. specularColor is in [0, kMaxSpecularColour] (the extension bounds it only by the
    // clamp to 1 after the product), specularWeight in [0, 1].
    Rgb specularColor{1.0f};
    float specularWeight = 1.0f;

    bool operator==(const Layers&) const = default;
};
// The largest specularColor component: F0 = 1 at an ior of 1.02 (F0 0.0001) and beyond.
inline constexpr float kMaxSpecularColour = 10000.0f;

struct Material {
    // The artist's blur: the Phong exponent n(λ) of phong.h, the same lobe under any environment
    // and face size (λ = 0 a mirror). The renderer shows it from the lobe stack (lobes.h), and
    // through the chain until the stack's entries for it are made.
    float lambda = 0.0f;
    LookupMode mode = LookupMode::Reflect;
    // Normal mode only: look up the accurate irradiance map (E/π, irradiance.h) instead of the
    // chain at λ. Off by default: the paper's diffuse is the chain at a high λ.
    bool useIrradiance = false;
    Rgb tint{1.0f};  // specular colour, multiplies the lookup
    // λ falls toward 0 as the view grazes the surface, per fragment: the sharpening of glossy
    // reflections at grazing angles the paper wished for (§6). Off by default.
    bool sharperAtGrazing = false;

    // Layered (layered.h) instead of the paper's single lobe: `layers` decides the look, and of
    // the fields above only useIrradiance counts (the diffuse base from the irradiance map rather
    // than the chain's n = 1 lobe). Off: the single lobe above, exactly as before.
    bool layered = false;
    Layers layers;

    bool operator==(const Material&) const = default;
};

// The one rule for what a material may hold: a valid λ (phong.h, isValidLambda) and a tint whose
// components are finite and not negative (it multiplies linear HDR colour). Files refuse what
// breaks it, naming the field (material_json); the documents never hold it.
bool isValidMaterial(const Material& material);
// Every layer value (each base colour component too) in [0, 1]. Checked whether or not
// the material is layered, so a file never holds a bad value waiting to be switched on.
bool isValidLayers(const Layers& layers);
// What breaks that rule, in words ("metallic 1.5 is not in [0, 1]"), or "" when nothing does.
std::string layersProblem(const Layers& layers);

// A scene's materials are named and shared: an object refers to one by id, several objects may
// refer to the same one, and editing it changes every object that uses it. Ids are unique within a
// scene and never reused while it is open; names are unique within a scene too (scene files refer
// to materials by name). 0 is no material: the object is drawn with Material{} (a mirror).
using MaterialId = std::uint32_t;
inline constexpr MaterialId kNoMaterial = 0;

struct NamedMaterial {
    MaterialId id = kNoMaterial;
    std::string name;
    Material material;
    std::string libraryEntry;  // the library entry it was applied from, "" if none

    bool operator==(const NamedMaterial&) const = default;
};

// `base` if `taken(base)` is false, otherwise the first of "base 2", "base 3", ... that is free.
// An empty base is "Material".
std::string uniqueName(const std::string& base, const std::function<bool(const std::string&)>& taken);

// uniqueName for many names in a row, in linear time: each base remembers the next suffix to
// try, where uniqueName would try "base 2", "base 3", ... again for every alike name (an asset of
// 30 000 parts named alike took seconds). take() marks its result taken.
class UniqueNames {
public:
    void reserve(const std::string& name) { taken_.insert(name); }  // already in use
    std::string take(const std::string& base);

private:
    std::unordered_set<std::string> taken_;
    std::unordered_map<std::string, int> next_;
};

struct Transform {
    glm::vec3 translation{0.0f};
    glm::vec3 rotationDegrees{0.0f};  // about Z first, then X, then Y (matrix())
    float scale = 1.0f;               // uniform, so normals need no inverse transpose

    glm::mat4 matrix() const;  // T · Ry · Rx · Rz · S
    bool operator==(const Transform&) const = default;
};

struct SceneObject {
    std::string name;
    std::shared_ptr<const Mesh> mesh;
    std::string meshSource;  // the file it came from, or "builtin:teapot" / "builtin:sphere"
    // The part of an asset file (asset.h: a glTF primitive as placed by its nodes, or an OBJ's
    // faces of one material) the mesh is; -1: the mesh is the whole file, read by loadMesh.
    int meshPart = -1;
    Transform transform;
    MaterialId material = kNoMaterial;
    bool visible = true;

    // World-space bounding sphere of the mesh under the transform.
    glm::vec3 worldCentre() const;
    float worldRadius() const;

    bool operator==(const SceneObject&) const = default;  // the same mesh is the same pointer
};

inline constexpr const char* kBuiltinEnvironment = "builtin:courtyard";

struct EnvironmentSettings {
    std::string source = kBuiltinEnvironment;  // a file path, or the embedded default
    EnvLayout layout = EnvLayout::Auto;
    Handedness handedness = Handedness::Right;
    int faceSize = 128;                        // the base level's face size after import
    Builder builder = kDefaultBuilder;
    bool operator==(const EnvironmentSettings&) const = default;
};

// The exposure's range, everywhere it is set (panel, scene files, `render --exposure`): wide
// enough to show a map stored at 1e-30 or 1e30 at its own brightness (±99.7 EV), since the renderer
// holds any radiance (docs/radiance-range.md), and 2^±120 stays well inside float's range.
inline constexpr float kMaxExposureEv = 120.0f;

struct DisplaySettings {
    bool showBackground = true;
    // What is behind the objects when the background is hidden: a colour as the screen shows it
    // (sRGB-encoded, each in [0, 1]), laid under the tone-mapped picture, so exposure and the tone
    // map never change it (the certification's white is 1, 1, 1; docs/certification.md).
    Rgb backdrop{0.5f};
    float backgroundLambda = 0.0f;  // the background's own blur, as a material's λ (phong.h)
    float exposureEv = 0.0f;        // linear colour × 2^EV before tone mapping, |EV| ≤ kMaxExposureEv
    ToneMap toneMap = ToneMap::Aces;
    int samples = 4;                // multisampling
    // Turns the environment about +Y when drawing (objects' reflections and the background). A
    // view of the environment, not a property of it: it never asks for a build.
    float environmentRotationDegrees = 0.0f;
    // Lookups per GGX layer and fragment (ggx_sampling.h): what a layered material's picture costs
    // and how close it is to the material's truth (`mipgloss bench truth` measures both).
    int ggxLookups = kGgxLookups;
    // The environment's bright texels shaded as lights with the exact BRDF (bright_lights.h); off:
    // the lookups read them with the rest (for `mipgloss bench truth` to show what they buy).
    bool brightLights = true;
    // Each pixel of a polished layered material shaded at taps along its footprint's long axis, so
    // it is the material's mean over its area (lookup_plan.h, drawsFootprintTaps); off: at its
    // centre, every lobe widened by the footprint (for `bench-render --no-taps` and `bench truth
    // --no-taps` to show what they cost and buy).
    bool footprintTaps = true;
    // Multiple scattering (ggx_sampling.h): off, every layered material is the glTF specification's
    // single-scattering BRDF; compensated, rough metals keep the energy their microfacets bounce.
    Scattering scattering = Scattering::Single;
    bool operator==(const DisplaySettings&) const = default;
};

struct Scene {
    std::vector<SceneObject> objects;
    std::vector<NamedMaterial> materials;  // in the order they were added; unused ones may stay
    EnvironmentSettings environment;
    DisplaySettings display;
    // The view saved with the scene; none: frame the scene when it is opened.
    std::optional<OrbitCamera> camera;

    const NamedMaterial* findMaterial(MaterialId id) const;
    NamedMaterial* findMaterial(MaterialId id);
    const NamedMaterial* findMaterialNamed(std::string_view name) const;
    // What `object` is drawn with: its material's parameters, Material{} when it has none.
    const Material& materialOf(const SceneObject& object) const;
    // The same, to edit; throws std::out_of_range when the object has no material.
    Material& materialOf(const SceneObject& object);
    // A material under uniqueName(name) with a fresh id, not yet added (an undoable edit adds it).
    NamedMaterial newMaterial(const std::string& name, const Material& material,
                              const std::string& libraryEntry = {}) const;
    // Adds newMaterial(name, material, libraryEntry) and returns its id.
    MaterialId addMaterial(const std::string& name, const Material& material,
                           const std::string& libraryEntry = {});
    // Appends `object` with a material of its own named after it; returns its index.
    int addObject(SceneObject object, const Material& material);
    // How many objects use material `id`.
    int usersOf(MaterialId id) const;
    MaterialId nextMaterialId() const;  // one above the largest id in use

    bool operator==(const Scene&) const = default;
};

// The paper's Figure 1: four teapots in a row, λ = 0 (mirror), 3.5 and 5.0 looked up by the
// reflection vector and λ = 7.0 by the normal, under a 128² cube from the embedded environment.
// The mesh is the caller's: the default scene's is the embedded teapot (mipgloss/assets/
// default_scene.h, makeFigure1Scene() reads it), which the scene model never parses itself.
Scene makeFigure1Scene(const std::shared_ptr<const Mesh>& teapot);

// World bounds of the visible objects (empty scene: a unit box at the origin).
Bounds sceneBounds(const Scene& scene);
// The world-space box of one object: its mesh box's eight corners under its transform; nullopt
// when it has no mesh. sceneBounds is the union of its visible objects'.
std::optional<Bounds> objectBounds(const SceneObject& object);


}  // namespace mipgloss
