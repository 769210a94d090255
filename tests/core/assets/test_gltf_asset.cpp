// glTF assets (core/assets/src/formats/gltf.cpp, asset.h) on files the tests write themselves with
// tinygltf's writer (tests/tools/gltf_writer.h): positions, normals and tangents baked through the
// node hierarchy, UVs as glTF has them, the metallic–roughness materials and their texture maps
// (embedded and external images, decoded by a TextureCache), the primitive modes, and hostile
// files, each refused with an AssetError that names the file and the element at fault.
#include "gltf_writer.h"
#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/textures.h"
#include "mipgloss/scene/layered.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <tuple>
#include <unistd.h>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::test;
namespace fs = std::filesystem;

namespace {

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << "'" << (part) << "' not in: " << (text)

std::span<const unsigned char> bytesOf(const std::string& text) {
    return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

Asset loadGlb(GltfWriter& writer, const fs::path& file = "models/thing.glb") {
    const std::vector<unsigned char> bytes = writer.glb();
    return loadGltfFromMemory(bytes, file);
}

// The AssetError loading `bytes` as `file` throws, checked to name the file; fails the test when
// it throws none (or anything else).
std::string refusal(std::span<const unsigned char> bytes, const fs::path& file = "bad/hostile.glb") {
    try {
        loadGltfFromMemory(bytes, file);
    } catch (const AssetError& e) {
        EXPECT_EQ(e.file(), file);
        EXPECT_CONTAINS(e.what(), file.string());
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw something other than an AssetError: " << e.what();
        return {};
    }
    ADD_FAILURE() << "loaded, expected an AssetError";
    return {};
}

std::string refusal(GltfWriter& writer) { return refusal(writer.glb()); }

// A folder of its own under the system's temporary folder, removed with everything in it.
class TempDir {
public:
    TempDir() {
        static int counter = 0;
        path_ = fs::temp_directory_path() /
                ("mipgloss-gltf-test-" + std::to_string(::getpid()) + "-" + std::to_string(++counter));
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance, const std::string& what = {}) {
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

// A unit quaternion (x, y, z, w) turning `angle` radians about `axis`, and the same turn applied
// to a vector by Rodrigues' formula (not through glm's quaternion code the reader uses).
std::vector<double> quaternion(glm::dvec3 axis, double angle) {
    axis = glm::normalize(axis);
    const double s = std::sin(angle / 2);
    return {axis.x * s, axis.y * s, axis.z * s, std::cos(angle / 2)};
}
glm::dvec3 rotate(glm::dvec3 v, glm::dvec3 axis, double angle) {
    axis = glm::normalize(axis);
    return v * std::cos(angle) + glm::cross(axis, v) * std::sin(angle) + axis * glm::dot(axis, v) * (1 - std::cos(angle));
}

// The triangle x + y + z = 1 (corners on the axes), wound counter-clockwise seen from its normal
// (1, 1, 1)/√3, which each corner has: a plane no axis scale leaves alone.
Mesh tiltedTriangle() {
    Mesh mesh;
    mesh.name = "tilted";
    mesh.positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    mesh.normals.assign(3, glm::normalize(glm::vec3(1, 1, 1)));
    mesh.uvs = {{0, 0}, {1, 0}, {0, 1}};
    mesh.indices = {0, 1, 2};
    computeBounds(mesh);
    return mesh;
}

// Each triangle's normal from its winding (counter-clockwise front), unit.
glm::vec3 windingNormal(const Mesh& mesh, std::size_t triangle) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * triangle]]), b(mesh.positions[mesh.indices[3 * triangle + 1]]),
        c(mesh.positions[mesh.indices[3 * triangle + 2]]);
    return glm::vec3(glm::normalize(glm::cross(b - a, c - a)));
}

// texturedQuad's corners are told apart by their UVs: the quad's vertex index of an output vertex.
int quadCorner(glm::vec2 uv) {
    const std::array<glm::vec2, 4> uvs = {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)};
    for (std::size_t i = 0; i < uvs.size(); ++i)
        if (uv == uvs[i]) return static_cast<int>(i);
    return -1;
}

// A 4 × 4 RGB checker of 2 × 2 cells: blue where (x/2 + y/2) is even, red where odd.
TestImage checker4() {
    return makeImage(4, 4, 3, [](int x, int y) -> std::vector<std::uint8_t> {
        return ((x / 2 + y / 2) % 2) ? std::vector<std::uint8_t>{255, 0, 0} : std::vector<std::uint8_t>{0, 0, 255};
    });
}

// A plain colour image.
TestImage plain(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    return makeImage(2, 2, 3, [=](int, int) -> std::vector<std::uint8_t> { return {r, g, b}; });
}

std::array<std::uint8_t, 4> texel(const TextureImage& image, int x, int y) {
    const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)) * 4;
    return {image.rgba[at], image.rgba[at + 1], image.rgba[at + 2], image.rgba[at + 3]};
}

// The textured quad under one node with a translation, a rotation and a non-uniform scale, below a
// parent node that translates it again: world = parent · T · R · S.
const glm::dvec3 kParentT(10, 0, 0), kT(1, 2, 3), kS(2, 3, 4), kAxis(0, 0, 1);
const double kAngle = std::acos(-1.0) / 2;  // 90° about +z

GltfWriter transformedQuad() {
    GltfWriter w;
    const int mesh = w.addMesh(texturedQuad(), -1);
    const int child = w.addNode(mesh, {kT.x, kT.y, kT.z}, {kS.x, kS.y, kS.z}, quaternion(kAxis, kAngle));
    const int parent = w.addNode(-1, {kParentT.x, kParentT.y, kParentT.z});
    w.model().nodes[static_cast<std::size_t>(parent)].children = {child};
    w.addToScene(parent);
    return w;
}

void expectTransformedQuad(const Asset& asset) {
    EXPECT_TRUE(asset.warnings.empty()) << asset.warnings.front();
    ASSERT_EQ(asset.parts.size(), 1u);
    EXPECT_EQ(asset.parts[0].material, -1);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    const Mesh quad = texturedQuad();
    ASSERT_EQ(mesh.vertexCount(), 4u);
    ASSERT_EQ(mesh.uvs.size(), 4u);
    ASSERT_EQ(mesh.triangleCount(), 2u);
    std::vector<int> corner(4);
    for (std::size_t v = 0; v < 4; ++v) {
        // UVs as the file has them (glTF's v runs down: no flip), so each names its quad corner.
        corner[v] = quadCorner(mesh.uvs[v]);
        ASSERT_GE(corner[v], 0) << "UV " << mesh.uvs[v].x << ", " << mesh.uvs[v].y << " is none of the quad's";
        const glm::dvec3 p(quad.positions[static_cast<std::size_t>(corner[v])]);
        const glm::dvec3 expected = kParentT + kT + rotate(kS * p, kAxis, kAngle);
        expectNear(mesh.positions[v], glm::vec3(expected), 1e-6f, "vertex " + std::to_string(v));
        // The quad's normal +z: under S (z × 4) and a turn about z it stays +z.
        expectNear(mesh.normals[v], {0, 0, 1}, 1e-6f);
    }
    // The same two triangles, each as the file winds it (any rotation of its corners).
    auto canonical = [](std::array<int, 3> t) {
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        return t;
    };
    std::vector<std::array<int, 3>> got, want;
    for (std::size_t t = 0; t < 2; ++t) {
        got.push_back(canonical({corner[mesh.indices[3 * t]], corner[mesh.indices[3 * t + 1]], corner[mesh.indices[3 * t + 2]]}));
        want.push_back(canonical({static_cast<int>(quad.indices[3 * t]), static_cast<int>(quad.indices[3 * t + 1]),
                                  static_cast<int>(quad.indices[3 * t + 2])}));
    }
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want);
}

// A GLB put together by hand: the header, the JSON chunk (padded with spaces) and, when `bin` is
// not empty, the BIN chunk; the lengths are the true ones unless given.
std::vector<unsigned char> assembleGlb(std::string json, const std::vector<unsigned char>& bin,
                                       std::int64_t binChunkLength = -1) {
    while (json.size() % 4 != 0) json += ' ';
    const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
    std::vector<unsigned char> out;
    out.reserve(total);
    auto u32 = [&](std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(total));
    u32(static_cast<std::uint32_t>(json.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), json.begin(), json.end());
    if (!bin.empty()) {
        u32(static_cast<std::uint32_t>(binChunkLength >= 0 ? binChunkLength : static_cast<std::int64_t>(bin.size())));
        u32(0x004E4942);
        out.insert(out.end(), bin.begin(), bin.end());
    }
    return out;
}

// One primitive's vertices in order (no indices) and its mode, positions only: the primitive
// tests' files.
std::string positionsOnlyGltf(const std::vector<glm::vec3>& positions, int mode) {
    std::vector<unsigned char> bin(positions.size() * 12);
    std::memcpy(bin.data(), positions.data(), bin.size());
    static const char* const kBase64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string b64;
    for (std::size_t i = 0; i < bin.size(); i += 3) {
        const std::uint32_t n = (std::uint32_t(bin[i]) << 16) | (i + 1 < bin.size() ? std::uint32_t(bin[i + 1]) << 8 : 0) |
                                (i + 2 < bin.size() ? std::uint32_t(bin[i + 2]) : 0);
        b64 += kBase64[(n >> 18) & 63];
        b64 += kBase64[(n >> 12) & 63];
        b64 += i + 1 < bin.size() ? kBase64[(n >> 6) & 63] : '=';
        b64 += i + 2 < bin.size() ? kBase64[n & 63] : '=';
    }
    const std::string n = std::to_string(positions.size()), bytes = std::to_string(bin.size());
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"name": "strip", "primitives": [{"attributes": {"POSITION": 0}, "mode": )" + std::to_string(mode) + R"(}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": )" + n + R"(}],
  "bufferViews": [{"buffer": 0, "byteLength": )" + bytes + R"(}],
  "buffers": [{"byteLength": )" + bytes + R"(, "uri": "data:application/octet-stream;base64,)" + b64 + R"("}]})";
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Geometry

TEST(GltfAsset, GlbPositionsAreBakedThroughTheNodeHierarchy) {
    GltfWriter w = transformedQuad();
    expectTransformedQuad(loadGlb(w));
}

TEST(GltfAsset, GltfWithItsBufferAsADataUriLoadsAsTheGlbDoes) {
    GltfWriter w = transformedQuad();
    const std::string text = w.gltf();
    ASSERT_NE(text.find("data:application/octet-stream;base64,"), std::string::npos);
    const Asset asset = loadGltfFromMemory(bytesOf(text), "models/thing.gltf");
    expectTransformedQuad(asset);
    GltfWriter w2 = transformedQuad();
    const Asset fromGlb = loadGlb(w2);
    ASSERT_EQ(asset.parts.size(), fromGlb.parts.size());
    EXPECT_EQ(asset.parts[0].mesh->positions, fromGlb.parts[0].mesh->positions);
    EXPECT_EQ(asset.parts[0].mesh->uvs, fromGlb.parts[0].mesh->uvs);
    EXPECT_EQ(asset.parts[0].mesh->indices, fromGlb.parts[0].mesh->indices);
}

TEST(GltfAsset, NormalsFollowTheInverseTransposeUnderNonUniformScale) {
    GltfWriter w;
    const glm::dvec3 scale(2, 1, 0.5), axis(1, 0, 0);
    const double angle = 0.5;
    w.addToScene(w.addNode(w.addMesh(tiltedTriangle(), -1), {0.5, -1, 2}, {scale.x, scale.y, scale.z}, quaternion(axis, angle)));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.triangleCount(), 1u);
    // The surface's normal after the transform, from its transformed corners' winding.
    const glm::vec3 surface = windingNormal(mesh, 0);
    // Analytically: the plane x + y + z = 1 scaled is x/2 + y + 2z = 1, normal ∝ (1/2, 1, 2), turned.
    const glm::vec3 expected(glm::normalize(rotate(glm::dvec3(0.5, 1, 2), axis, angle)));
    expectNear(surface, expected, 1e-6f);
    for (std::size_t v = 0; v < 3; ++v) {
        EXPECT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-6f);
        expectNear(mesh.normals[v], expected, 1e-6f, "normal " + std::to_string(v));
        for (std::size_t k = 1; k < 3; ++k) {
            const glm::vec3 edge = glm::normalize(mesh.positions[(v + k) % 3] - mesh.positions[v]);
            EXPECT_NEAR(glm::dot(mesh.normals[v], edge), 0.0f, 1e-6f);
        }
    }
}

TEST(GltfAsset, MirroringNodeKeepsFrontFacesFront) {
    GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(tiltedTriangle(), -1), {}, {-1, 1, 1}));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.triangleCount(), 1u);
    const glm::vec3 expected = glm::normalize(glm::vec3(-1, 1, 1));
    // The winding was swapped: the front face's normal from the winding is the stored normal.
    expectNear(windingNormal(mesh, 0), expected, 1e-6f);
    for (std::size_t v = 0; v < 3; ++v) {
        expectNear(mesh.normals[v], expected, 1e-6f);
        EXPECT_GT(glm::dot(windingNormal(mesh, 0), mesh.normals[v]), 0.9999f);
    }
}

// ---------------------------------------------------------------------------------------------
// Materials

TEST(GltfMaterials, NamesAreKeptDefaultedAndMadeUnique) {
    GltfWriter w;
    const int a = w.addMaterial(pbrMaterial("Paint", {1, 1, 1, 1}, 0, 0.5));
    w.addMaterial(pbrMaterial("", {1, 1, 1, 1}, 0, 0.5));
    w.addMaterial(pbrMaterial("Paint", {1, 1, 1, 1}, 0, 0.5));
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), a)));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.materials.size(), 3u);  // every material of the file, used or not
    EXPECT_EQ(asset.materials[0].name, "Paint");
    EXPECT_EQ(asset.materials[1].name, "Material 1");
    EXPECT_EQ(asset.materials[2].name, "Paint 2");
    ASSERT_EQ(asset.parts.size(), 1u);
    EXPECT_EQ(asset.parts[0].material, 0);
    for (const AssetMaterial& m : asset.materials) {
        EXPECT_TRUE(m.material.layered);
        EXPECT_TRUE(isValidMaterial(m.material));
    }
}

TEST(GltfMaterials, FactorsAndEmbeddedTexturesMapToLayers) {
    GltfWriter w;
    w.addImage(encodePng(plain(10, 20, 30)));
    const int image = w.addImage(encodePng(checker4()));
    const int texture = w.addTexture(image);
    tinygltf::Material m = pbrMaterial("Paint", {0.5, 0.25, 0.125, 0.75}, 0.3, 0.6, texture, texture, texture);
    m.normalTexture.scale = 0.5;
    m.occlusionTexture.index = texture;
    m.occlusionTexture.strength = 0.25;
    m.emissiveTexture.index = texture;
    m.emissiveFactor = {0.1, 0.2, 0.3};
    m.extensions["KHR_materials_emissive_strength"] =
        tinygltf::Value(tinygltf::Value::Object{{"emissiveStrength", tinygltf::Value(4.0)}});
    m.alphaMode = "MASK";
    m.alphaCutoff = 0.3;
    w.model().extensionsUsed = {"KHR_materials_emissive_strength"};
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
    const Asset asset = loadGlb(w, "models/paint.glb");
    EXPECT_TRUE(asset.warnings.empty()) << asset.warnings.front();
    ASSERT_EQ(asset.materials.size(), 1u);
    const Material& material = asset.materials[0].material;
    EXPECT_TRUE(isValidMaterial(material));
    const Layers& l = material.layers;
    EXPECT_EQ(l.baseColor, Rgb(0.5f, 0.25f, 0.125f));  // exact: each a float the file holds
    EXPECT_FLOAT_EQ(l.maps.baseAlpha, 0.75f);
    EXPECT_FLOAT_EQ(l.metallic, 0.3f);
    EXPECT_FLOAT_EQ(l.roughness, 0.6f);
    EXPECT_FLOAT_EQ(l.specular, 0.04f);
    // Embedded: the file itself and the image's index in it.
    const TextureRef embedded{"models/paint.glb", image, 0};
    EXPECT_EQ(l.maps.baseColor, embedded);
    // One metallic-roughness image: roughness in G (channel 1), metallic in B (channel 2).
    EXPECT_EQ(l.maps.roughness, (TextureRef{"models/paint.glb", image, 1}));
    EXPECT_EQ(l.maps.metallic, (TextureRef{"models/paint.glb", image, 2}));
    EXPECT_EQ(l.maps.normal, embedded);
    EXPECT_FLOAT_EQ(l.maps.normalScale, 0.5f);
    EXPECT_EQ(l.maps.occlusion, embedded);
    EXPECT_FLOAT_EQ(l.maps.occlusionStrength, 0.25f);
    EXPECT_EQ(l.maps.emissive, embedded);
    // emissiveFactor × emissiveStrength (4), within float rounding of the products.
    EXPECT_NEAR(l.maps.emissiveFactor.r, 0.4f, 1e-6f);
    EXPECT_NEAR(l.maps.emissiveFactor.g, 0.8f, 1e-6f);
    EXPECT_NEAR(l.maps.emissiveFactor.b, 1.2f, 1e-6f);
    EXPECT_EQ(l.maps.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(l.maps.alphaCutoff, 0.3f);
    EXPECT_EQ(l.coat, 0.0f);  // no clearcoat extension
}

TEST(GltfMaterials, EmissiveWithoutStrengthIsTheFactor) {
    GltfWriter w;
    tinygltf::Material m = pbrMaterial("Glow", {1, 1, 1, 1}, 0, 0.5);
    m.emissiveFactor = {0.1, 0.2, 0.3};
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.materials.size(), 1u);
    EXPECT_EQ(asset.materials[0].material.layers.maps.emissiveFactor, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(asset.materials[0].material.layers.maps.alphaMode, AlphaMode::Opaque);
}

// BLEND and doubleSided are read as the file says (drawn as blending and one-sided; the pictures:
// tests/app/cli/test_gltf_conformance.cpp), with no warning; glTF's doubleSided defaults to false.
TEST(GltfMaterials, BlendAndDoubleSidedAreReadWithoutAWarning) {
    GltfWriter w;
    tinygltf::Material glass = pbrMaterial("Glass", {1, 1, 1, 0.5}, 0, 0.1);
    glass.alphaMode = "BLEND";
    glass.doubleSided = true;
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(glass))));
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("Plain", {1, 1, 1, 1}, 0, 0.5)))));
    const Asset asset = loadGlb(w, "models/glass.glb");
    ASSERT_EQ(asset.materials.size(), 2u);
    const MaterialMaps& blended = asset.materials[0].material.layers.maps;
    EXPECT_EQ(blended.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(blended.baseAlpha, 0.5f);
    EXPECT_TRUE(blended.doubleSided);
    EXPECT_TRUE(blended.inUse()) << "a blended material needs its alpha: the maps' program";
    EXPECT_FALSE(asset.materials[1].material.layers.maps.doubleSided) << "glTF's default";
    EXPECT_TRUE(asset.warnings.empty()) << asset.warnings.front();
}

TEST(GltfMaterials, ClearcoatGivesTheCoatLayer) {
    GltfWriter w;
    tinygltf::Material m = pbrMaterial("Car paint", {0.6, 0.05, 0.02, 1}, 0, 0.45);
    m.extensions["KHR_materials_clearcoat"] = tinygltf::Value(tinygltf::Value::Object{
        {"clearcoatFactor", tinygltf::Value(0.75)}, {"clearcoatRoughnessFactor", tinygltf::Value(0.125)}});
    w.model().extensionsUsed = {"KHR_materials_clearcoat"};
    w.model().extensionsRequired = {"KHR_materials_clearcoat"};  // read, so no refusal
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
    const Asset asset = loadGlb(w);
    EXPECT_TRUE(asset.warnings.empty()) << asset.warnings.front();
    ASSERT_EQ(asset.materials.size(), 1u);
    EXPECT_FLOAT_EQ(asset.materials[0].material.layers.coat, 0.75f);
    EXPECT_FLOAT_EQ(asset.materials[0].material.layers.coatRoughness, 0.125f);
}

// How each map is read: its texture's sampler (wrap modes, nearest filters), its UV set, and
// KHR_texture_transform (whose texCoord overrides the textureInfo's); TEXCOORD_1 and COLOR_0 are
// read into the mesh. The transform is the extension's T·R·S: its own example (offset (0, 1),
// rotation π/2, scale 0.5: "the lower left quadrant, rotated clockwise 90°") takes the UV corners
// (0, 0), (1, 0), (0, 1), (1, 1) to (0, 1), (0, 0.5), (0.5, 1), (0.5, 0.5).
TEST(GltfMaterials, SamplersUvSetsTransformsAndVertexColoursAreRead) {
    GltfWriter w;
    const int image = w.addImage(encodePng(checker4()));
    const int clamped = w.addTexture(image);
    const int mirrored = w.addTexture(image);
    tinygltf::Sampler clamp, mirror;
    clamp.wrapS = clamp.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    clamp.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
    mirror.wrapS = TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
    mirror.minFilter = TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
    w.model().samplers = {clamp, mirror};
    w.model().textures[static_cast<std::size_t>(clamped)].sampler = 0;
    w.model().textures[static_cast<std::size_t>(mirrored)].sampler = 1;
    tinygltf::Material m = pbrMaterial("Sampled", {1, 1, 1, 1}, 0, 0.5, clamped);
    m.emissiveTexture.index = mirrored;
    m.emissiveTexture.texCoord = 1;
    m.pbrMetallicRoughness.baseColorTexture.extensions["KHR_texture_transform"] = tinygltf::Value(tinygltf::Value::Object{
        {"offset", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(0.0), tinygltf::Value(1.0)})},
        {"rotation", tinygltf::Value(1.57079632679)},
        {"scale", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(0.5), tinygltf::Value(0.5)})},
        {"texCoord", tinygltf::Value(1)}});
    w.model().extensionsUsed = {"KHR_texture_transform"};
    Mesh quad = texturedQuad();
    quad.uvs1 = quad.uvs;
    quad.colours.assign(quad.vertexCount(), glm::vec4(0.25f, 0.5f, 1.0f, 0.75f));
    w.addToScene(w.addNode(w.addMesh(quad, w.addMaterial(m))));
    const Asset asset = loadGlb(w);
    EXPECT_TRUE(asset.warnings.empty()) << asset.warnings.front();
    const MaterialMaps& maps = asset.materials.at(0).material.layers.maps;
    const TextureSampling& base = maps.samplingOf(MapSlot::BaseColor);
    EXPECT_EQ(base.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(base.wrapT, TextureWrap::ClampToEdge);
    EXPECT_TRUE(base.nearestMagnify);
    EXPECT_FALSE(base.nearestMinify);
    EXPECT_EQ(base.texCoord, 1) << "KHR_texture_transform's texCoord wins";
    const glm::mat3 t = base.uvTransform();
    for (const auto& [from, to] : {std::pair{glm::vec2(0, 0), glm::vec2(0, 1)}, std::pair{glm::vec2(1, 0), glm::vec2(0, 0.5f)},
                                   std::pair{glm::vec2(0, 1), glm::vec2(0.5f, 1)}, std::pair{glm::vec2(1, 1), glm::vec2(0.5f, 0.5f)}}) {
        const glm::vec3 got = t * glm::vec3(from, 1.0f);
        EXPECT_NEAR(got.x, to.x, 1e-6f) << from.x << ", " << from.y;
        EXPECT_NEAR(got.y, to.y, 1e-6f) << from.x << ", " << from.y;
    }
    const TextureSampling& emissive = maps.samplingOf(MapSlot::Emissive);
    EXPECT_EQ(emissive.wrapS, TextureWrap::MirroredRepeat);
    EXPECT_EQ(emissive.wrapT, TextureWrap::Repeat);
    EXPECT_TRUE(emissive.nearestMinify);
    EXPECT_EQ(emissive.texCoord, 1);
    EXPECT_EQ(emissive.uvTransform(), glm::mat3(1.0f));
    const Mesh& mesh = *asset.parts.at(0).mesh;
    ASSERT_EQ(mesh.uvs1.size(), mesh.vertexCount());
    ASSERT_EQ(mesh.colours.size(), mesh.vertexCount());
    EXPECT_EQ(mesh.colours[2], glm::vec4(0.25f, 0.5f, 1.0f, 0.75f));
    EXPECT_TRUE(mesh.isValid());
}

// The coat's textures are not dropped in silence: one warning names each, the file and the material.
TEST(GltfMaterials, ClearcoatTexturesAreNamedInAWarning) {
    GltfWriter w;
    tinygltf::Material m = pbrMaterial("Car paint", {0.6, 0.05, 0.02, 1}, 0, 0.45);
    const tinygltf::Value texture(tinygltf::Value::Object{{"index", tinygltf::Value(0)}});
    m.extensions["KHR_materials_clearcoat"] = tinygltf::Value(tinygltf::Value::Object{
        {"clearcoatFactor", tinygltf::Value(1.0)}, {"clearcoatTexture", texture}, {"clearcoatNormalTexture", texture}});
    w.model().extensionsUsed = {"KHR_materials_clearcoat"};
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
    const Asset asset = loadGlb(w, "models/car.glb");
    ASSERT_EQ(asset.warnings.size(), 2u);
    EXPECT_CONTAINS(asset.warnings[0], "models/car.glb");
    EXPECT_CONTAINS(asset.warnings[0], "material 0");
    EXPECT_CONTAINS(asset.warnings[0], "clearcoatTexture");
    EXPECT_CONTAINS(asset.warnings[1], "clearcoatNormalTexture");
}

// KHR_materials_ior: F0 = ((ior − 1)/(ior + 1))², so 1.5 is glTF's 0.04 and 2 is 1/9; an ior below
// 1 is a warning and 1.5 stays.
TEST(GltfMaterials, IorSetsTheDielectricsF0) {
    for (const auto& [ior, f0, warned] : {std::tuple{1.5, 0.04f, false}, std::tuple{2.0, 1.0f / 9.0f, false},
                                          std::tuple{1.0, 0.0f, false}, std::tuple{0.5, 0.04f, true}}) {
        GltfWriter w;
        tinygltf::Material m = pbrMaterial("Glass", {1, 1, 1, 1}, 0, 0.1);
        m.extensions["KHR_materials_ior"] = tinygltf::Value(tinygltf::Value::Object{{"ior", tinygltf::Value(ior)}});
        w.model().extensionsUsed = {"KHR_materials_ior"};
        w.model().extensionsRequired = {"KHR_materials_ior"};
        w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
        const Asset asset = loadGlb(w);
        EXPECT_NEAR(asset.materials.at(0).material.layers.specular, f0, 1e-6f) << "ior " << ior;
        EXPECT_EQ(asset.warnings.size(), warned ? 1u : 0u) << "ior " << ior;
    }
}

// KHR_materials_specular: its two factors become the layers' specular weight and colour (with
// KHR_materials_ior's F0 beside them); absent, glTF's defaults; out of range, a warning and the
// default; its textures named in a warning (the model holds one value per material).
TEST(GltfMaterials, SpecularExtensionSetsTheDielectricsWeightAndColour) {
    using Object = tinygltf::Value::Object;
    using Array = tinygltf::Value::Array;
    auto load = [](const Object& specular) {
        GltfWriter w;
        tinygltf::Material m = pbrMaterial("Satin", {0.5, 0.5, 0.5, 1}, 0, 0.4);
        m.extensions["KHR_materials_specular"] = tinygltf::Value(specular);
        m.extensions["KHR_materials_ior"] = tinygltf::Value(Object{{"ior", tinygltf::Value(2.0)}});
        w.model().extensionsUsed = {"KHR_materials_specular", "KHR_materials_ior"};
        w.model().extensionsRequired = {"KHR_materials_specular"};
        w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
        return loadGlb(w);
    };
    const Asset set = load(Object{{"specularFactor", tinygltf::Value(0.25)},
                                  {"specularColorFactor", tinygltf::Value(Array{tinygltf::Value(1.0), tinygltf::Value(0.5),
                                                                                tinygltf::Value(12.0)})}});
    const Layers& l = set.materials.at(0).material.layers;
    EXPECT_FLOAT_EQ(l.specularWeight, 0.25f);
    EXPECT_EQ(l.specularColor, Rgb(1.0f, 0.5f, 12.0f));
    EXPECT_NEAR(l.specular, 1.0f / 9.0f, 1e-6f);
    EXPECT_TRUE(set.warnings.empty()) << set.warnings.front();
    // The dielectric's F0: min(F0_ior · colour, 1) · weight, per channel.
    const Rgb f0 = dielectricFresnel(l).f0;
    EXPECT_NEAR(f0.r, 0.25f / 9.0f, 1e-6f);
    EXPECT_NEAR(f0.g, 0.125f / 9.0f, 1e-6f);
    EXPECT_NEAR(f0.b, 0.25f, 1e-6f);
    EXPECT_FLOAT_EQ(specularF90(l), 0.25f);

    const Asset defaults = load(Object{});
    EXPECT_EQ(defaults.materials.at(0).material.layers.specularColor, Rgb(1.0f));
    EXPECT_FLOAT_EQ(defaults.materials.at(0).material.layers.specularWeight, 1.0f);

    const Asset bad = load(Object{{"specularFactor", tinygltf::Value(1.5)},
                                  {"specularColorFactor", tinygltf::Value(Array{tinygltf::Value(1.0)})},
                                  {"specularTexture", tinygltf::Value(Object{{"index", tinygltf::Value(0)}})}});
    EXPECT_FLOAT_EQ(bad.materials.at(0).material.layers.specularWeight, 1.0f);
    EXPECT_EQ(bad.materials.at(0).material.layers.specularColor, Rgb(1.0f));
    ASSERT_EQ(bad.warnings.size(), 3u);
    EXPECT_CONTAINS(bad.warnings[0], "specularFactor");
    EXPECT_CONTAINS(bad.warnings[1], "specularColorFactor");
    EXPECT_CONTAINS(bad.warnings[2], "specularTexture");
    EXPECT_CONTAINS(bad.warnings[2], "Satin");
}

TEST(GltfMaterials, ExternalImagesAreFilesBesideTheGltfWithTheUriDecoded) {
    TempDir dir;
    writePng(checker4(), dir.path() / "wood grain.png");
    GltfWriter w;
    const int color = w.addTexture(w.addImage({}, "wood%20grain.png"));
    const int missing = w.addTexture(w.addImage({}, "textures/missing.png"));
    tinygltf::Material m = pbrMaterial("Wood", {1, 1, 1, 1}, 0, 0.7, color);
    m.occlusionTexture.index = missing;
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m))));
    w.writeGltf(dir.path() / "model.gltf");
    const Asset asset = loadAsset(dir.path() / "model.gltf");
    ASSERT_EQ(asset.materials.size(), 1u);
    const MaterialMaps& maps = asset.materials[0].material.layers.maps;
    const TextureRef wood{(dir.path() / "wood grain.png").lexically_normal().string(), -1, 0};
    const TextureRef gone{(dir.path() / "textures" / "missing.png").lexically_normal().string(), -1, 0};
    EXPECT_EQ(maps.baseColor, wood);
    EXPECT_EQ(maps.occlusion, gone);

    // Decoded by a texture cache: the checker's texels read back; the missing file is a warning
    // naming it, and its map has no image.
    TextureCache cache;
    const std::vector<std::string> warnings = cache.load(maps.textures());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_CONTAINS(warnings[0], gone.file);
    EXPECT_EQ(cache.find(gone), nullptr);
    EXPECT_NE(cache.problem(gone), "");
    const auto image = cache.find(wood);
    ASSERT_NE(image, nullptr);
    ASSERT_EQ(image->width, 4);
    ASSERT_EQ(image->height, 4);
    EXPECT_EQ(texel(*image, 0, 0), (std::array<std::uint8_t, 4>{0, 0, 255, 255}));
    EXPECT_EQ(texel(*image, 2, 0), (std::array<std::uint8_t, 4>{255, 0, 0, 255}));
    EXPECT_EQ(texel(*image, 1, 3), (std::array<std::uint8_t, 4>{255, 0, 0, 255}));
    EXPECT_EQ(texel(*image, 3, 3), (std::array<std::uint8_t, 4>{0, 0, 255, 255}));
}

// ---------------------------------------------------------------------------------------------
// Embedded images

TEST(GltfTextures, EmbeddedImageBytesAndMimeTypeComeBackAndDecode) {
    TempDir dir;
    const std::vector<unsigned char> red = encodePng(plain(200, 0, 0)), board = encodePng(checker4());
    GltfWriter w;
    w.addImage(red);
    const int image = w.addImage(board);
    const int texture = w.addTexture(image);
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("Board", {1, 1, 1, 1}, 0, 0.5, texture)))));
    const fs::path file = dir.path() / "board.glb";
    w.writeGlb(file);

    const std::vector<EncodedImage> images = gltfImages(file);
    ASSERT_EQ(images.size(), 2u);
    EXPECT_EQ(images[static_cast<std::size_t>(image)].mimeType, "image/png");
    EXPECT_EQ(images[static_cast<std::size_t>(image)].bytes, board);
    EXPECT_EQ(images[0].bytes, red);
    EXPECT_THROW(gltfImages(dir.path() / "none.glb"), AssetError);

    const Asset asset = loadAsset(file);
    ASSERT_EQ(asset.materials.size(), 1u);
    const TextureRef ref = asset.materials[0].material.layers.maps.baseColor;
    EXPECT_EQ(ref, (TextureRef{file.string(), image, 0}));
    TextureCache cache;
    const std::vector<std::string> warnings = cache.load({ref});
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    const auto decoded = cache.find(ref);
    ASSERT_NE(decoded, nullptr);
    ASSERT_EQ(decoded->width, 4);
    ASSERT_EQ(decoded->height, 4);
    EXPECT_EQ(texel(*decoded, 0, 0), (std::array<std::uint8_t, 4>{0, 0, 255, 255}));
    EXPECT_EQ(texel(*decoded, 3, 0), (std::array<std::uint8_t, 4>{255, 0, 0, 255}));
    EXPECT_EQ(texel(*decoded, 0, 2), (std::array<std::uint8_t, 4>{255, 0, 0, 255}));
    EXPECT_EQ(texel(*decoded, 2, 2), (std::array<std::uint8_t, 4>{0, 0, 255, 255}));
}

// ---------------------------------------------------------------------------------------------
// Primitives

TEST(GltfPrimitives, TriangleStripIsConvertedKeepingEveryTriangleFront) {
    // Two columns of three: a strip of four triangles, every one facing +z when the odd ones'
    // first two corners are swapped (glTF 2.0 §3.7.2.1).
    const std::vector<glm::vec3> strip = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0}};
    const std::string text = positionsOnlyGltf(strip, TINYGLTF_MODE_TRIANGLE_STRIP);
    const Asset asset = loadGltfFromMemory(bytesOf(text), "strip.gltf");
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.triangleCount(), 4u);  // n − 2
    for (std::size_t t = 0; t < 4; ++t) expectNear(windingNormal(mesh, t), {0, 0, 1}, 1e-6f);
    // No NORMAL in the file: computed, unit, the plane's.
    for (const glm::vec3& n : mesh.normals) {
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
        expectNear(n, {0, 0, 1}, 1e-6f);
    }
    EXPECT_TRUE(mesh.uvs.empty());
    EXPECT_TRUE(mesh.tangents.empty());
}

TEST(GltfPrimitives, TriangleFanIsConvertedKeepingEveryTriangleFront) {
    // The centre, then five rim points counter-clockwise: four triangles facing +z.
    const std::vector<glm::vec3> fan = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}};
    const std::string text = positionsOnlyGltf(fan, TINYGLTF_MODE_TRIANGLE_FAN);
    const Asset asset = loadGltfFromMemory(bytesOf(text), "fan.gltf");
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.triangleCount(), 4u);  // n − 2
    for (std::size_t t = 0; t < 4; ++t) {
        expectNear(windingNormal(mesh, t), {0, 0, 1}, 1e-6f);
        EXPECT_EQ(mesh.positions[mesh.indices[3 * t]], glm::vec3(0, 0, 0));  // every one from the centre
    }
}

TEST(GltfPrimitives, PointsAndLinesAreLeftOutWithAWarning) {
    GltfWriter w;
    const int mesh = w.addMesh(texturedQuad(), -1);
    tinygltf::Primitive lines = w.model().meshes[static_cast<std::size_t>(mesh)].primitives[0];
    lines.mode = TINYGLTF_MODE_LINE;
    tinygltf::Primitive points = lines;
    points.mode = TINYGLTF_MODE_POINTS;
    w.model().meshes[static_cast<std::size_t>(mesh)].primitives.push_back(lines);
    w.model().meshes[static_cast<std::size_t>(mesh)].primitives.push_back(points);
    w.addToScene(w.addNode(mesh));
    const Asset asset = loadGlb(w, "models/lines.glb");
    ASSERT_EQ(asset.parts.size(), 1u);  // the triangles only
    EXPECT_EQ(asset.parts[0].mesh->triangleCount(), 2u);
    ASSERT_EQ(asset.warnings.size(), 2u);
    EXPECT_CONTAINS(asset.warnings[0], "models/lines.glb");
    EXPECT_CONTAINS(asset.warnings[0], "primitive 1");
    EXPECT_CONTAINS(asset.warnings[0], "mode 1");
    EXPECT_CONTAINS(asset.warnings[1], "primitive 2");
    EXPECT_CONTAINS(asset.warnings[1], "mode 0");
}

TEST(GltfPrimitives, MissingNormalsAreComputed) {
    GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(tiltedTriangle(), -1, /*withNormals=*/false)));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    for (const glm::vec3& n : mesh.normals) {
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
        expectNear(n, glm::normalize(glm::vec3(1, 1, 1)), 1e-6f);
    }
}

TEST(GltfPrimitives, UnusedVerticesAreDroppedAndZeroNormalsComputed) {
    // Vertex 3 is in no triangle; vertex 1's normal in the file is zero.
    Mesh m;
    m.name = "partly used";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
    m.normals = {{0, 0, 1}, {0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    m.indices = {0, 1, 2};
    GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(m, -1)));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.vertexCount(), 3u);
    EXPECT_EQ(mesh.bounds.max, glm::vec3(1, 1, 0));  // the unused vertex is not in the bounds
    for (std::size_t v = 0; v < 3; ++v) expectNear(mesh.normals[v], {0, 0, 1}, 1e-6f);
    EXPECT_EQ(mesh.uvs, (std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}}));
}

TEST(GltfPrimitives, NormalMappedPrimitiveWithoutTangentsGetsThem) {
    GltfWriter w;
    const int texture = w.addTexture(w.addImage(encodePng(plain(128, 128, 255))));
    const int material = w.addMaterial(pbrMaterial("Bumpy", {1, 1, 1, 1}, 0, 0.5, -1, -1, texture));
    w.addToScene(w.addNode(w.addMesh(tiltedTriangle(), material), {}, {1, 2, 3}));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.tangents.size(), mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const glm::vec3 t(mesh.tangents[v]);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-4f) << v;
        EXPECT_NEAR(glm::dot(t, mesh.normals[v]), 0.0f, 1e-4f) << v;
        EXPECT_EQ(std::abs(mesh.tangents[v].w), 1.0f) << v;
    }
    // Without a normal map no tangents are made.
    GltfWriter plainWriter;
    plainWriter.addToScene(plainWriter.addNode(plainWriter.addMesh(tiltedTriangle(), -1)));
    EXPECT_TRUE(loadGlb(plainWriter).parts.at(0).mesh->tangents.empty());
}

TEST(GltfPrimitives, TangentsInTheFileAreKept) {
    GltfWriter w;
    const int texture = w.addTexture(w.addImage(encodePng(plain(128, 128, 255))));
    const int material = w.addMaterial(pbrMaterial("Bumpy", {1, 1, 1, 1}, 0, 0.5, -1, -1, texture));
    Mesh quad = texturedQuad();
    // Not what computeTangents would give (+x): +y, with a left-handed bitangent.
    quad.tangents.assign(4, glm::vec4(0, 1, 0, -1));
    w.addToScene(w.addNode(w.addMesh(quad, material)));
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    ASSERT_EQ(mesh.tangents.size(), 4u);
    for (const glm::vec4& t : mesh.tangents) EXPECT_EQ(t, glm::vec4(0, 1, 0, -1));
}

// ---------------------------------------------------------------------------------------------
// Hostile files: each refused by an AssetError naming the file and the element

namespace {

// The quad's accessors as GltfWriter::addMesh makes them, with its buffer views in the same order.
constexpr int kPositionAccessor = 0, kUvAccessor = 2, kIndexAccessor = 3;

GltfWriter plainQuad() {
    GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), -1)));
    return w;
}

template <typename T>
void poke(GltfWriter& w, int accessor, std::size_t element, const T& value) {
    tinygltf::Model& m = w.model();
    const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(accessor)];
    const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
    std::memcpy(m.buffers[0].data.data() + v.byteOffset + a.byteOffset + element * sizeof(T), &value, sizeof(T));
}

}  // namespace

TEST(GltfHostile, AccessorPastTheEndOfItsBufferViewIsRefused) {
    GltfWriter w = plainQuad();
    w.model().accessors[kUvAccessor].count += 1;
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "accessor 2");
    EXPECT_CONTAINS(what, "past the end of its buffer view");
}

TEST(GltfHostile, AccessorOffsetPastItsBufferViewIsRefused) {
    GltfWriter w = plainQuad();
    w.model().accessors[kPositionAccessor].byteOffset = 1u << 30;
    EXPECT_CONTAINS(refusal(w), "accessor 0");
}

TEST(GltfHostile, BufferViewPastItsBufferIsRefused) {
    GltfWriter w = plainQuad();
    // The normals' view, from its offset to 4 bytes past the buffer's end.
    w.model().bufferViews[1].byteLength = w.model().buffers[0].data.size() - w.model().bufferViews[1].byteOffset + 4;
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "buffer view 1");
    EXPECT_CONTAINS(what, "past the end of its buffer");
}

TEST(GltfHostile, StrideSmallerThanTheElementIsRefused) {
    GltfWriter w = plainQuad();
    w.model().bufferViews[0].byteStride = 8;  // positions: 12-byte elements
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "buffer view 0");
    EXPECT_CONTAINS(what, "stride");
}

TEST(GltfHostile, IndexPastTheVerticesIsRefused) {
    GltfWriter w = plainQuad();
    poke<std::uint32_t>(w, kIndexAccessor, 4, 4);  // the quad has vertices 0..3
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "accessor 3");
    EXPECT_CONTAINS(what, "index 4 is 4");
}

TEST(GltfHostile, PrimitiveMaterialOutOfRangeIsRefused) {
    GltfWriter w = plainQuad();
    w.model().meshes[0].primitives[0].material = 4;
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "mesh 0");
    EXPECT_CONTAINS(what, "material 4");
}

TEST(GltfHostile, TextureIndexOutOfRangeIsRefused) {
    GltfWriter w;
    w.addMaterial(pbrMaterial("Fine", {1, 1, 1, 1}, 0, 0.5));
    const int material = w.addMaterial(pbrMaterial("Broken", {1, 1, 1, 1}, 0, 0.5, 5));
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), material)));
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "material 1");
    EXPECT_CONTAINS(what, "texture 5");
}

TEST(GltfHostile, TextureImageIndexOutOfRangeIsRefused) {
    GltfWriter w;
    const int texture = w.addTexture(w.addImage(encodePng(plain(1, 2, 3))));
    w.model().textures[static_cast<std::size_t>(texture)].source = 3;
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("M", {1, 1, 1, 1}, 0, 0.5, texture)))));
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "texture 0");
    EXPECT_CONTAINS(what, "image 3");
}

TEST(GltfHostile, NodeThatIsItsOwnChildIsRefused) {
    GltfWriter w = plainQuad();
    w.model().nodes[0].children = {0};
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "node 0");
    EXPECT_CONTAINS(what, "cycle");
}

TEST(GltfHostile, TwoNodeCycleIsRefused) {
    GltfWriter w = plainQuad();
    const int second = w.addNode(-1);
    w.model().nodes[0].children = {second};
    w.model().nodes[static_cast<std::size_t>(second)].children = {0};
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "node 0");
    EXPECT_CONTAINS(what, "cycle");
}

TEST(GltfHostile, NodeReachedTwiceIsDrawnOnceWithAWarning) {
    // Each of 64 levels names the next twice: 2^63 paths to the last node, were each walked.
    GltfWriter w;
    const int mesh = w.addMesh(texturedQuad(), -1);
    const int levels = 64;
    for (int i = 0; i < levels; ++i) w.addNode(i == levels - 1 ? mesh : -1);
    for (int i = 0; i + 1 < levels; ++i) w.model().nodes[static_cast<std::size_t>(i)].children = {i + 1, i + 1};
    w.addToScene(0);
    const Asset asset = loadGlb(w, "models/shared.glb");
    ASSERT_EQ(asset.parts.size(), 1u);
    ASSERT_EQ(asset.warnings.size(), static_cast<std::size_t>(levels - 1));  // once per node reached again
    EXPECT_CONTAINS(asset.warnings[0], "models/shared.glb");
    EXPECT_CONTAINS(asset.warnings[0], "node 63");
    EXPECT_CONTAINS(asset.warnings[0], "more than one parent");
}

TEST(GltfHostile, ChildNodeOutOfRangeIsRefusedNamingItsParent) {
    GltfWriter w = plainQuad();
    w.model().nodes[0].children = {3};
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "node 0");
    EXPECT_CONTAINS(what, "node 3");
}

TEST(GltfHostile, RequiredUnknownExtensionIsRefusedByName) {
    GltfWriter w = plainQuad();
    w.model().extensionsUsed = {"EXT_mipgloss_imaginary"};
    w.model().extensionsRequired = {"EXT_mipgloss_imaginary"};
    EXPECT_CONTAINS(refusal(w), "EXT_mipgloss_imaginary");
    // Used but not required: drawn without it, with a warning naming it.
    GltfWriter used = plainQuad();
    used.model().extensionsUsed = {"EXT_mipgloss_imaginary"};
    const Asset asset = loadGlb(used);
    ASSERT_EQ(asset.warnings.size(), 1u);
    EXPECT_CONTAINS(asset.warnings[0], "EXT_mipgloss_imaginary");
}

// Nothing a still preview leaves out is dropped in silence: animations, skins, morph targets and
// the scenes besides the default are each named once, with the file.
TEST(GltfMaterials, AnimationsSkinsMorphTargetsAndOtherScenesAreNamed) {
    GltfWriter w = plainQuad();
    tinygltf::Animation wave;
    wave.name = "Wave";
    tinygltf::AnimationSampler sampler;
    sampler.input = sampler.output = 0;
    wave.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = 0;
    channel.target_path = "translation";
    wave.channels.push_back(channel);
    w.model().animations.push_back(wave);
    w.model().skins.emplace_back().joints = {0};
    w.model().meshes[0].primitives[0].targets.push_back({{"POSITION", 0}});
    tinygltf::Scene other;
    other.name = "Other";
    other.nodes = {0};
    w.model().scenes.push_back(other);
    const Asset asset = loadGlb(w, "models/rigged.glb");
    ASSERT_EQ(asset.warnings.size(), 4u);
    for (const char* what : {"animation", "skin", "morph targets", "scenes"}) {
        const bool named = std::any_of(asset.warnings.begin(), asset.warnings.end(), [&](const std::string& s) {
            return s.find(what) != std::string::npos && s.find("models/rigged.glb") != std::string::npos;
        });
        EXPECT_TRUE(named) << what;
    }
}

// A Draco-compressed file: its primitive's accessors have no buffer view (the extension holds the
// data), which tinygltf refuses first ("accessor[0] invalid bufferView"). The refusal names the
// extension instead, from a .gltf and a .glb alike.
TEST(GltfHostile, DracoCompressedFileIsRefusedByTheExtensionsName) {
    GltfWriter w = plainQuad();
    w.model().extensionsUsed = {"KHR_draco_mesh_compression"};
    w.model().extensionsRequired = {"KHR_draco_mesh_compression"};
    for (tinygltf::Accessor& a : w.model().accessors) a.bufferView = -1;
    EXPECT_CONTAINS(refusal(w), "requires the extension KHR_draco_mesh_compression");
    const std::string json = w.gltf();
    EXPECT_CONTAINS(refusal(std::span(reinterpret_cast<const unsigned char*>(json.data()), json.size()), "draco.gltf"),
                    "requires the extension KHR_draco_mesh_compression");
}

TEST(GltfHostile, NonFinitePositionIsRefused) {
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        GltfWriter w = plainQuad();
        poke<float>(w, kPositionAccessor, 4, bad);  // vertex 1's y
        const std::string what = refusal(w);
        EXPECT_CONTAINS(what, "accessor 0");
        EXPECT_CONTAINS(what, "not finite");
    }
}

TEST(GltfHostile, PositionsThatTheNodeCarriesPastFloatAreRefused) {
    GltfWriter w = plainQuad();
    w.model().nodes[0].scale = {1e300, 1, 1};  // finite in the file, infinite as a float position
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "node 0");
}

TEST(GltfHostile, SparseAccessorIsRefused) {
    GltfWriter w = plainQuad();
    tinygltf::Accessor& a = w.model().accessors[kPositionAccessor];
    a.sparse.isSparse = true;
    a.sparse.count = 1;
    a.sparse.indices.bufferView = w.model().accessors[kIndexAccessor].bufferView;
    a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.sparse.values.bufferView = a.bufferView;
    a.sparse.indices.byteOffset = 0;  // tinygltf 2.7 leaves them uninitialized
    a.sparse.values.byteOffset = 0;
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "accessor 0");
    EXPECT_CONTAINS(what, "sparse");
}

TEST(GltfHostile, TruncatedGlbIsRefusedAtEveryCut) {
    GltfWriter w;
    const int texture = w.addTexture(w.addImage(encodePng(checker4())));
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("M", {1, 1, 1, 1}, 0, 0.5, texture)))));
    const std::vector<unsigned char> glb = w.glb();
    ASSERT_GT(glb.size(), 100u);
    std::vector<std::size_t> cuts = {1, 3, 4, 8, 11, 12, 16, 19, 20, 21, 24, 40, glb.size() / 2, glb.size() - 9,
                                     glb.size() - 8, glb.size() - 4, glb.size() - 1};
    for (std::size_t cut = 0; cut < glb.size(); cut += 37) cuts.push_back(cut == 0 ? 2 : cut);
    for (const std::size_t cut : cuts) {
        SCOPED_TRACE("cut at " + std::to_string(cut) + " of " + std::to_string(glb.size()));
        refusal(std::span(glb).first(cut), "bad/cut.glb");
        // The same cut with the header's length saying so: the chunks no longer fit.
        std::vector<unsigned char> patched(glb.begin(), glb.begin() + static_cast<std::ptrdiff_t>(cut));
        if (cut >= 12) {
            const auto length = static_cast<std::uint32_t>(cut);
            std::memcpy(patched.data() + 8, &length, 4);
            refusal(patched, "bad/cut.glb");
        }
    }
}

TEST(GltfHostile, BinChunkClaimingItsOwnHeaderBytesIsRefused) {
    // A BIN chunk whose length counts its 8-byte header too, so the chunk's data would run 8 bytes
    // past the end of the file; the buffer asks for all of it.
    const std::vector<unsigned char> bin(16, 0);
    const std::string json = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 24}]})";
    refusal(assembleGlb(json, bin, 24));
    const std::string ok = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 16}]})";
    refusal(assembleGlb(ok, bin, 24));  // no mesh either way; the container is what must not crash
}

TEST(GltfHostile, EmbeddedImageViewPastItsBufferIsRefused) {
    GltfWriter w;
    const int image = w.addImage(encodePng(checker4()));
    const int texture = w.addTexture(image);
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("M", {1, 1, 1, 1}, 0, 0.5, texture)))));
    tinygltf::BufferView& view = w.model().bufferViews[static_cast<std::size_t>(w.model().images[0].bufferView)];
    view.byteLength += 4096;
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "buffer view " + std::to_string(w.model().images[0].bufferView));
}

TEST(GltfHostile, BytesThatAreNotJsonAreRefused) {
    EXPECT_CONTAINS(refusal(bytesOf("this is not JSON, nor a GLB"), "bad/text.gltf"), "not a readable glTF file");
    refusal(bytesOf("{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [}"), "bad/text.gltf");
    refusal(bytesOf("glTF"), "bad/short.glb");
}

// The JSON checked before tinygltf reads it (gltf_json_check.h). A quad written by tinygltf's
// own writer (pretty-printed: "key": value), one value changed per case.
std::string quadJson() {
    GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("grey", {0.5, 0.5, 0.5, 1}, 0, 0.5)))));
    return w.gltf();
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the written JSON";
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// tinygltf 2.7 recursed once per level: 30 000 nested arrays in extras overflowed the stack.
TEST(GltfHostile, DeepNestingIsRefusedNamingTheDepthWithoutRecursing) {
    const std::string deep = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + std::string(30000, '[') +
                             std::string(30000, ']') + "}";
    const std::string why = refusal(bytesOf(deep), "bad/deep.gltf");
    EXPECT_CONTAINS(why, "nests deeper than 64 levels");
    EXPECT_CONTAINS(why, "extras");
    // Nesting a viewer's extras might hold stays readable.
    const std::string fine = replaced(quadJson(), "\"asset\": {", "\"extras\": " + std::string(40, '[') + std::string(40, ']') +
                                                                       ", \"asset\": {");
    EXPECT_EQ(loadGltfFromMemory(bytesOf(fine), "ok.gltf").parts.size(), 1u);
}

// tinygltf reads indices as int: 4294967296 became 0 (the first mesh) without a word; −1 means
// "none" to it. Every index is a whole number from 0 to 2³¹ − 1, even spelled with \u escapes.
TEST(GltfHostile, IndicesThatAreNotWholeNumbersInRangeAreRefusedByTheirPath) {
    const std::string quad = quadJson();
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"mesh\": 0", "\"mesh\": 4294967296")), "bad/wrap.gltf"),
                    "nodes[0].mesh is 4294967296: an index is a whole number from 0 to 2147483647");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"mesh\": 0", "\"\\u006desh\": 4294967296")), "bad/escaped.gltf"),
                    "nodes[0].mesh is 4294967296");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"material\": 0", "\"material\": -1")), "bad/minus.gltf"),
                    "meshes[0].primitives[0].material is -1");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"POSITION\": 0", "\"POSITION\": 0.5")), "bad/half.gltf"),
                    "meshes[0].primitives[0].attributes.POSITION is 0.500000");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"nodes\": [\n        0", "\"nodes\": [\n        \"0\"")), "bad/text.gltf"),
                    "scenes[0].nodes[0] is not a number");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"byteLength\": ", "\"byteOffset\": -4, \"byteLength\": ")), "bad/offset.gltf"),
                    "bufferViews[0].byteOffset is -4: a size or offset is a whole number");
    // The author's own extras hold what they like.
    const std::string extras = replaced(quad, "\"mesh\": 0", "\"mesh\": 0, \"extras\": {\"mesh\": \"the teapot\", \"index\": -1}");
    EXPECT_EQ(loadGltfFromMemory(bytesOf(extras), "ok.gltf").parts.size(), 1u);
}

// Found by the outside sweep's structural mutations (scripts/fuzz-meshes.py, gltf formats): a
// member of the wrong kind or an enumeration outside glTF's list was read as its default without
// a word (a primitive's "indices": {} drew it unindexed, "mode": [null] as triangles). Each is
// refused by its path; the author's extras stay free.
TEST(GltfHostile, MembersOfTheWrongKindOrOutsideTheirEnumerationAreRefusedByTheirPath) {
    const std::string quad = quadJson();
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"componentType\": 5126", "\"componentType\": 5127")), "bad/ct.gltf"),
                    "accessors[0].componentType is not one of glTF's values (5120, 5121, 5122, 5123, 5125, 5126)");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"mesh\": 0", "\"mesh\": 0, \"name\": 4294967296")), "bad/name.gltf"),
                    "nodes[0].name is not a string");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"material\": 0", "\"material\": 0, \"mode\": [null]")), "bad/mode.gltf"),
                    "meshes[0].primitives[0].mode is not a number (glTF's values: 0, 1, 2, 3, 4, 5, 6)");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"material\": 0", "\"material\": 0, \"mode\": 7")), "bad/mode7.gltf"),
                    "meshes[0].primitives[0].mode is not one of glTF's values");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"material\": 0", "\"material\": 0, \"indices\": {\"a\": 1}")), "bad/indices.gltf"),
                    "meshes[0].primitives[0].indices is not a number");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"byteLength\": ", "\"target\": 2147483648, \"byteLength\": ")), "bad/target.gltf"),
                    "bufferViews[0].target is not one of glTF's values (34962, 34963)");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"version\": \"2.0\"", "\"version\": \"2.0\", \"generator\": true")), "bad/gen.gltf"),
                    "asset.generator is not a string");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"mesh\": 0", "\"mesh\": 0, \"scale\": {\"x\": 1}")), "bad/scale.gltf"),
                    "nodes[0].scale must be numbers");
    // String enumerations: an alphaMode of "FOO" was drawn opaque without a word.
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"type\": \"VEC3\"", "\"type\": \"VEC5\"")), "bad/type.gltf"),
                    "accessors[0].type is \"VEC5\", not one of glTF's values (SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4)");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"pbrMetallicRoughness\"", "\"alphaMode\": \"FOO\", \"pbrMetallicRoughness\"")), "bad/alpha.gltf"),
                    "materials[0].alphaMode is \"FOO\", not one of glTF's values (OPAQUE, MASK, BLEND)");
    const std::string extras = replaced(quad, "\"mesh\": 0", "\"mesh\": 0, \"extras\": {\"name\": 7, \"mode\": [null], \"target\": {}}");
    EXPECT_EQ(loadGltfFromMemory(bytesOf(extras), "ok.gltf").parts.size(), 1u);
}

// glTF's schema: at least one byte, at least one element.
TEST(GltfHostile, AnEmptyBufferOrAccessorIsRefusedByItsPath) {
    const std::string quad = quadJson();
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"byteLength\": ", "\"byteLength\": 0, \"x\": ")), "bad/empty.gltf"),
                    "bufferViews[0].byteLength is 0: a byteLength is at least 1");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"count\": ", "\"count\": 0, \"x\": ")), "bad/none.gltf"),
                    "accessors[0].count is 0: a count is at least 1");
}

TEST(GltfHostile, AVectorHoldingANullIsRefusedNotDropped) {
    const std::string quad = quadJson();
    const std::string matrix = replaced(quad, "\"mesh\": 0", "\"mesh\": 0, \"matrix\": [1, 0, 0, null, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]");
    EXPECT_CONTAINS(refusal(bytesOf(matrix), "bad/matrix.gltf"), "nodes[0].matrix[3] is not a number");
}

TEST(GltfHostile, ASceneTheFileLacksAndAVersionItIsNotAreRefused) {
    const std::string quad = quadJson();
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"scene\": 0", "\"scene\": 5")), "bad/scene.gltf"),
                    "its \"scene\" is 5, but the file has 1 scene(s)");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"version\": \"2.0\"", "\"version\": \"3.0\"")), "bad/v3.gltf"),
                    "is glTF 3.0; mipgloss reads glTF 2");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"version\": \"2.0\"", "\"version\": \"2.0\", \"minVersion\": \"2.1\"")),
                            "bad/min.gltf"),
                    "needs a glTF 2.1 reader (asset.minVersion)");
    EXPECT_CONTAINS(refusal(bytesOf(replaced(quad, "\"version\": \"2.0\"", "\"version\": \"two\"")), "bad/word.gltf"),
                    "asset.version \"two\" is not a version");
    // A later 2.x stays readable (glTF 2.0 §3.3: minor versions are backward compatible).
    EXPECT_EQ(loadGltfFromMemory(bytesOf(replaced(quad, "\"version\": \"2.0\"", "\"version\": \"2.1\"")), "ok.gltf").parts.size(), 1u);
}

// Only the asset's folder and below are read, for buffers (refused) and images (a warning, the map
// left out) alike; an encoded NUL is refused; never the working directory.
TEST(GltfHostile, FilesOutsideTheAssetsFolderAreNotReadAndANulIsRefused) {
    TempDir dir;
    fs::create_directories(dir.path() / "asset");
    GltfWriter w;
    w.addImage({}, "../outside.png");
    const int texture = w.addTexture(0);
    w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("wood", {1, 1, 1, 1}, 0, 0.5, texture)))));
    w.writeGltf(dir.path() / "asset" / "model.gltf");
    const Asset asset = loadAsset(dir.path() / "asset" / "model.gltf");
    EXPECT_TRUE(asset.materials.at(0).material.layers.maps.baseColor.empty());
    ASSERT_EQ(asset.warnings.size(), 1u);
    EXPECT_CONTAINS(asset.warnings[0], "image 0's URI \"../outside.png\" lies outside the asset's folder");

    const std::string quad = quadJson();
    const std::size_t uri = quad.find("\"uri\": \"data:");
    ASSERT_NE(uri, std::string::npos);
    const std::size_t end = quad.find('"', uri + 9);
    for (const std::string outside : {"/etc/passwd", "../../model.bin", "sub/../../x.bin", "%2E%2E/x.bin"}) {
        std::string text = quad;
        text.replace(uri, end + 1 - uri, "\"uri\": \"" + outside + "\"");
        EXPECT_CONTAINS(refusal(bytesOf(text), "bad/outside.gltf"), "buffers[0].uri \"" + outside + "\" lies outside the asset's folder");
    }
    std::string nul = quad;
    nul.replace(uri, end + 1 - uri, "\"uri\": \"model.bin%00.png\"");
    EXPECT_CONTAINS(refusal(bytesOf(nul), "bad/nul.gltf"), "buffers[0].uri holds an encoded NUL");
    // A '%' that is not an escape (RFC 3986) is no file name either: it would be read as itself by
    // one reader and refused by another.
    for (const std::string bad : {"a%zz.bin", "a%4.bin", "model.bin%"}) {
        std::string text = quad;
        text.replace(uri, end + 1 - uri, "\"uri\": \"" + bad + "\"");
        EXPECT_CONTAINS(refusal(bytesOf(text), "bad/percent.gltf"), "buffers[0].uri holds a '%' that is not an escape");
    }
}

// tinygltf keeps a copy of an external file per reference (12 000 images naming one 365 KB file
// held 4.4 GB): past 1 GiB of external bytes in all, the read is refused naming the file. Checked
// with a sparse 1.5 GiB file, which the check refuses by its size before reading a byte of it.
TEST(GltfHostile, ExternalFilesPastTheBudgetAreRefusedBeforeTheyAreRead) {
    TempDir dir;
    { std::ofstream(dir.path() / "big.bin", std::ios::binary) << 'x'; }
    fs::resize_file(dir.path() / "big.bin", (std::uintmax_t(3) << 29));  // 1.5 GiB, sparse
    const std::string quad = quadJson();
    const std::size_t uri = quad.find("\"uri\": \"data:");
    ASSERT_NE(uri, std::string::npos);
    std::string text = quad;
    text.replace(uri, quad.find('"', uri + 9) + 1 - uri, "\"uri\": \"big.bin\"");
    { std::ofstream(dir.path() / "big.gltf") << text; }
    try {
        loadAsset(dir.path() / "big.gltf");
        ADD_FAILURE() << "loaded";
    } catch (const AssetError& e) {
        EXPECT_CONTAINS(e.what(), "more than 1024 MiB of files in all");
        EXPECT_CONTAINS(e.what(), "big.bin");
    }
}

// Images that are the same bytes (one buffer view) are one image to decode: a 35 KB GLB whose four
// images share a 16384² PNG decoded it four times (4.9 GB).
TEST(GltfHostile, ImagesSharingABufferViewAreDecodedOnce) {
    GltfWriter w;
    const int first = w.addImage(encodePng(checker4()));
    for (int k = 0; k < 3; ++k) w.model().images.push_back(w.model().images[static_cast<std::size_t>(first)]);
    for (int k = 0; k < 4; ++k) {
        const int texture = w.addTexture(first + k);
        w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(pbrMaterial("m" + std::to_string(k), {1, 1, 1, 1}, 0, 0.5, texture)))));
    }
    const Asset asset = loadGlb(w);
    ASSERT_EQ(asset.materials.size(), 4u);
    for (const AssetMaterial& m : asset.materials)
        EXPECT_EQ(m.material.layers.maps.baseColor, asset.materials[0].material.layers.maps.baseColor) << m.name;
    EXPECT_EQ(asset.images.size(), 1u) << "one encoded image kept for the decoder";
}

// A text file named .glb: words, not the JSON parser's internals.
TEST(GltfHostile, TextThatIsNotJsonIsRefusedSayingWhere) {
    const std::string why = refusal(bytesOf("hello\nworld"), "bad/notes.glb");
    EXPECT_CONTAINS(why, "its JSON is not valid: the file is not a JSON object at line 1, column 1");
    EXPECT_EQ(why.find("json.exception"), std::string::npos) << why;
    EXPECT_CONTAINS(refusal(bytesOf("{\"asset\": {\"version\": \"2.0\"},\n \"nodes\": [}"), "bad/cut.gltf"), "at line 2, column 12");
}

TEST(GltfHostile, EmptyInputIsRefused) {
    EXPECT_CONTAINS(refusal(std::span<const unsigned char>(), "bad/empty.glb"), "empty");
}

TEST(GltfHostile, FileWithoutTrianglesIsRefused) {
    EXPECT_CONTAINS(refusal(bytesOf(R"({"asset": {"version": "2.0"}})"), "bad/nothing.gltf"), "no triangles");
}

// Nodes may share a mesh and each placement is a copy (asset.h): a small file placing one mesh
// many times is refused by its accessors' counts before the copy that would pass 2^22 vertices or
// triangles beyond the file's own (a 710 KB file asked for 32 million vertices and 3.2 GB), naming
// the primitive and the node that placed it.
TEST(GltfHostile, AMeshPlacedTooManyTimesIsRefusedBeforeItIsCopied) {
    GltfWriter w;
    Mesh sphere = texturedSphere(64, 128);  // 16,128 triangles
    const int mesh = w.addMesh(sphere, -1);
    for (int i = 0; i < 2100; ++i) w.addToScene(w.addNode(mesh));  // 33.9 million triangles
    const std::string what = refusal(w);
    EXPECT_CONTAINS(what, "mesh 0");
    // The first placement k (counting from 1) with k·per > per + 2^22, for vertices and for
    // triangles (each primitive counts one triangle more: the reader's rounding up).
    const std::size_t vertices = sphere.positions.size(), triangles = sphere.triangleCount() + 1;
    const std::size_t beyond = std::size_t(1) << 22;
    const std::size_t first = std::min((vertices + beyond) / vertices, (triangles + beyond) / triangles) + 1;
    EXPECT_CONTAINS(what, "(placed by node " + std::to_string(first - 1) + ")");
    EXPECT_CONTAINS(what, "so often that the asset would hold more than 4194304 beyond them");
}
