// OBJ assets with their MTL libraries (core/assets/src/formats/obj_asset.cpp, asset.h), on files
// written here: parts by material, UVs turned v-down, authored and computed normals, smoothing
// groups, the MTL values as layered materials, and hostile files refused naming the line.
#include "mipgloss/assets/asset.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

std::span<const unsigned char> bytesOf(const std::string& text) {
    return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

Asset loadObj(const std::string& obj, const std::vector<NamedBytes>& libraries = {},
              const fs::path& file = "models/thing.obj") {
    return loadObjAssetFromMemory(bytesOf(obj), file, libraries);
}

// The AssetError loading `obj` as "bad/thing.obj" throws; fails the test when it throws none.
std::string refusal(const std::string& obj) {
    try {
        loadObj(obj, {}, "bad/thing.obj");
    } catch (const AssetError& e) {
        EXPECT_EQ(e.file(), fs::path("bad/thing.obj"));
        return e.what();
    }
    ADD_FAILURE() << "loaded, expected an AssetError:\n" << obj;
    return {};
}

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE((text).find(part), std::string::npos) << "'" << (part) << "' not in: " << (text)

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The unit cube [0, 1]³, faces wound outward. Each quad's fan diagonal (its 1st and 3rd corners)
// joins two of the alternate corners 1, 3, 6, 8, so every corner is in the same number of
// triangles on each of its three faces: area-weighted normals come out exactly along the diagonals.
const std::string kCubeVertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
const std::string kCubeFaces = "f 1 4 3 2\nf 6 7 8 5\nf 1 2 6 5\nf 8 7 3 4\nf 1 5 8 4\nf 3 7 6 2\n";

const std::string kLibrary =
    "# two materials and one no face uses\n"
    "newmtl Red\nKd 1 0 0\n"
    "newmtl Blue\nKd 0 0 1\nnorm blue_n.png\n"
    "newmtl Unused\n";

}  // namespace

TEST(ObjAsset, TexturedQuadHasItsPositionsAndUvsFlippedToVDown) {
    const Asset asset = loadObj("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
                                "vt 0 0\nvt 1 0\nvt 1 0.75\nvt 0 0.75\n"
                                "f 1/1 2/2 3/3 4/4\n");
    ASSERT_EQ(asset.parts.size(), 1u);
    EXPECT_EQ(asset.parts[0].name, "thing");  // no material: named after the file
    EXPECT_EQ(asset.parts[0].material, -1);
    EXPECT_TRUE(asset.materials.empty());
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    EXPECT_EQ(mesh.name, "thing");
    ASSERT_EQ(mesh.vertexCount(), 4u);
    ASSERT_EQ(mesh.triangleCount(), 2u);
    const std::vector<glm::vec3> positions{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
    // OBJ's v points up, glTF's (Mesh::uvs) down: v' = 1 − v, exactly for these values.
    const std::vector<glm::vec2> uvs{{0, 1}, {1, 1}, {1, 0.25f}, {0, 0.25f}};
    for (std::size_t v = 0; v < 4; ++v) {
        EXPECT_EQ(mesh.positions[v], positions[v]) << v;
        EXPECT_EQ(mesh.uvs[v], uvs[v]) << v;
        expectNear(mesh.normals[v], {0, 0, 1}, 1e-6f);
    }
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));  // a fan
    EXPECT_EQ(mesh.bounds.min, glm::vec3(0, 0, 0));
    EXPECT_EQ(mesh.bounds.max, glm::vec3(2, 1, 0));
    EXPECT_TRUE(mesh.tangents.empty());  // no normal map
}

TEST(ObjAsset, AuthoredNormalsAreKeptNormalisedAndZeroOnesComputed) {
    // The face's own normal is +Z; the file says otherwise at corners 1 and 2, and nothing
    // usable (a zero vector) at corner 3.
    const Asset asset = loadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                "vn 1 0 1\nvn 0 3 0\nvn 0 0 0\n"
                                "f 1//1 2//2 3//3\n");
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.vertexCount(), 3u);
    const float h = std::sqrt(0.5f);
    expectNear(mesh.normals[0], {h, 0, h}, 1e-6f);
    expectNear(mesh.normals[1], {0, 1, 0}, 1e-6f);
    expectNear(mesh.normals[2], {0, 0, 1}, 1e-6f);
    EXPECT_TRUE(mesh.uvs.empty());  // no corner has a vt
}

TEST(ObjAsset, SmoothingGroupOffGivesFlatFaces) {
    const Asset asset = loadObj(kCubeVertices + "s off\n" + kCubeFaces);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    EXPECT_EQ(mesh.vertexCount(), 24u);  // each face its own four corners
    ASSERT_EQ(mesh.triangleCount(), 12u);
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                        c = mesh.positions[mesh.indices[t + 2]];
        const glm::vec3 faceNormal = glm::normalize(glm::cross(b - a, c - a));
        // Outward: the normal points away from the cube's centre.
        EXPECT_GT(glm::dot(faceNormal, a - glm::vec3(0.5f)), 0.0f);
        for (std::size_t k = 0; k < 3; ++k) expectNear(mesh.normals[mesh.indices[t + k]], faceNormal, 1e-6f);
    }
}

TEST(ObjAsset, SmoothingGroupSharesComputedNormalsAcrossFaces) {
    const Asset asset = loadObj(kCubeVertices + "s 1\n" + kCubeFaces);
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_TRUE(mesh.isValid());
    ASSERT_EQ(mesh.vertexCount(), 8u);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    // Three faces of equal weight meet at each corner: the normal is the cube's diagonal there.
    for (std::size_t v = 0; v < 8; ++v)
        expectNear(mesh.normals[v], (mesh.positions[v] - glm::vec3(0.5f)) * (2.0f / std::sqrt(3.0f)), 1e-6f);
}

TEST(ObjAsset, TwoMaterialsGiveTwoPartsWithTheirMaterialsByName) {
    const Asset asset = loadObj("mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                "usemtl Red\nf 1 2 3\nusemtl Blue\nf 2 4 3\nusemtl Red\nf 1 2 4\n",
                                {{"lib.mtl", bytesOf(kLibrary)}});
    EXPECT_TRUE(asset.warnings.empty()) << asset.warnings.front();
    ASSERT_EQ(asset.materials.size(), 3u);
    ASSERT_EQ(asset.parts.size(), 2u);  // in the order of first use, Red's faces together
    for (const AssetPart& part : asset.parts) {
        ASSERT_GE(part.material, 0);
        EXPECT_EQ(asset.materials[static_cast<std::size_t>(part.material)].name, part.name);
        EXPECT_EQ(part.mesh->name, part.name);
        EXPECT_TRUE(part.mesh->isValid());
    }
    EXPECT_EQ(asset.parts[0].name, "Red");
    EXPECT_EQ(asset.parts[0].mesh->triangleCount(), 2u);
    EXPECT_EQ(asset.parts[1].name, "Blue");
    EXPECT_EQ(asset.parts[1].mesh->triangleCount(), 1u);
    EXPECT_EQ(asset.materials[static_cast<std::size_t>(asset.parts[1].material)].material.layers.baseColor,
              Rgb(0, 0, 1));
}

TEST(ObjAsset, NormalMappedPartWithUvsGetsTangents) {
    const Asset asset = loadObj("mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                "usemtl Blue\nf 1/1 2/2 3/3\n",
                                {{"lib.mtl", bytesOf(kLibrary)}});
    ASSERT_EQ(asset.parts.size(), 1u);
    const Mesh& mesh = *asset.parts[0].mesh;
    EXPECT_EQ(mesh.tangents.size(), mesh.positions.size());
    EXPECT_TRUE(mesh.isValid());
}

TEST(ObjAsset, MtlValuesMapToLayeredMaterials) {
    const std::string mtl =
        "newmtl Painted metal\n"
        "Ks 1 1 1\n"  // no place in metallic–roughness: the dielectric F0 stays 0.04
        "Kd 0.2 0.4 1.5\n"
        "Pr 0.3\nNs 100\n"  // Pr wins over Ns, whichever comes first
        "Pm 1.5\n"
        "Ke 2 0 -1\n"
        "d 0.25\n"
        "map_Kd textures\\wood grain.png\n"
        "norm -bm 0.5 n.png\n"
        "map_Pr -imfchan g -o 0.5 0.5 rough.png\n"
        "newmtl Shiny\nNs 10\nTr 0.25\nmap_Ke glow.png\n"
        "newmtl Shiny\n";
    const fs::path folder = "/assets/car";
    const std::vector<AssetMaterial> materials = parseMtl(bytesOf(mtl), folder / "car.mtl", folder);
    ASSERT_EQ(materials.size(), 3u);

    EXPECT_EQ(materials[0].name, "Painted metal");
    EXPECT_TRUE(materials[0].material.layered);
    const Layers& painted = materials[0].material.layers;
    EXPECT_EQ(painted.baseColor, Rgb(0.2f, 0.4f, 1.0f));  // clamped to [0, 1]
    EXPECT_FLOAT_EQ(painted.specular, 0.04f);
    EXPECT_FLOAT_EQ(painted.roughness, 0.3f);
    EXPECT_FLOAT_EQ(painted.metallic, 1.0f);
    EXPECT_EQ(painted.maps.emissiveFactor, Rgb(2, 0, 0));  // negatives to 0, no upper clamp at 2
    EXPECT_FLOAT_EQ(painted.maps.baseAlpha, 0.25f);
    EXPECT_EQ(painted.maps.alphaMode, AlphaMode::Blend);
    EXPECT_EQ(painted.maps.baseColor.file, "/assets/car/textures/wood grain.png");
    EXPECT_EQ(painted.maps.normal.file, "/assets/car/n.png");
    EXPECT_FLOAT_EQ(painted.maps.normalScale, 0.5f);
    EXPECT_EQ(painted.maps.roughness.file, "/assets/car/rough.png");
    EXPECT_EQ(painted.maps.roughness.channel, 1);
    EXPECT_EQ(painted.maps.roughness.image, -1);

    EXPECT_EQ(materials[1].name, "Shiny");
    const Layers& shiny = materials[1].material.layers;
    // r(n) = (0.37 / (n + 0.37))^(1/4) (specular.h, kRoughnessFit = 0.37).
    EXPECT_NEAR(shiny.roughness, std::pow(0.37 / 10.37, 0.25), 1e-6);
    EXPECT_FLOAT_EQ(shiny.maps.baseAlpha, 0.75f);  // Tr is 1 − d
    EXPECT_EQ(shiny.maps.alphaMode, AlphaMode::Blend);
    EXPECT_EQ(shiny.maps.emissive.file, "/assets/car/glow.png");
    EXPECT_EQ(shiny.maps.emissiveFactor, Rgb(1.0f));  // no Ke: the map shows as it is

    EXPECT_EQ(materials[2].name, "Shiny 2");  // names stay unique
    EXPECT_EQ(materials[2].material.layers, Layers{});
}

TEST(ObjAsset, MissingLibraryIsAWarningAndPartsGetTheDefaultMaterial) {
    const Asset asset = loadObj("mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Red\nf 1 2 3\n");
    ASSERT_EQ(asset.parts.size(), 1u);
    EXPECT_EQ(asset.parts[0].material, -1);
    EXPECT_EQ(asset.parts[0].name, "thing");
    ASSERT_FALSE(asset.warnings.empty());
    EXPECT_EQ(asset.warnings[0].rfind("models/thing.obj: ", 0), 0u) << asset.warnings[0];
    EXPECT_CONTAINS(asset.warnings[0], "material library gone.mtl not found");
    for (const std::string& warning : asset.warnings) EXPECT_EQ(warning.rfind("models/thing.obj: ", 0), 0u) << warning;
}

// `mtllib tex.png` (a library that is not an MTL file) refused the whole OBJ naming only the PNG:
// now a warning naming the OBJ and the library it asked for, the OBJ drawn with the default material.
TEST(ObjAsset, UnreadableLibraryIsAWarningNamingTheObjAndTheLibrary) {
    const std::string png("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
    const std::vector<unsigned char> bytes(png.begin(), png.end());
    const Asset asset = loadObj("mtllib tex.png\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Red\nf 1 2 3\n",
                                {NamedBytes{"tex.png", bytes}});
    ASSERT_EQ(asset.parts.size(), 1u);
    EXPECT_EQ(asset.parts[0].material, -1);
    ASSERT_FALSE(asset.warnings.empty());
    EXPECT_EQ(asset.warnings[0].rfind("models/thing.obj: ", 0), 0u) << asset.warnings[0];
    EXPECT_CONTAINS(asset.warnings[0], "material library tex.png is not readable");
    EXPECT_CONTAINS(asset.warnings[0], "not an MTL text file");
}

TEST(ObjAsset, ZeroAreaFacesAreDroppedWithAWarning) {
    const Asset asset = loadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n");
    ASSERT_EQ(asset.parts.size(), 1u);
    EXPECT_EQ(asset.parts[0].mesh->triangleCount(), 1u);
    EXPECT_EQ(asset.parts[0].mesh->vertexCount(), 3u);  // vertex 4 only had the dropped face
    ASSERT_EQ(asset.warnings.size(), 1u);
    EXPECT_CONTAINS(asset.warnings[0], "1 degenerate face dropped");
}

TEST(ObjAsset, HostileFilesAreRefusedNamingTheFileAndLine) {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    EXPECT_CONTAINS(refusal(triangle + "f 1 2 4\n"), "bad/thing.obj: line 4: ");         // index past the end
    EXPECT_CONTAINS(refusal(triangle + "f 1 2\n"), "bad/thing.obj: line 4: ");           // two corners
    EXPECT_CONTAINS(refusal("v 0 0 0\nv nan 0 0\n"), "bad/thing.obj: line 2: ");          // NaN vertex
    EXPECT_CONTAINS(refusal("v 0 0 0\nf -1 -2 -3\n"), "bad/thing.obj: line 2: ");         // before the first
    EXPECT_CONTAINS(refusal(triangle + "f 1/1 2/1 3/1\n"), "bad/thing.obj: line 4: ");   // a vt never read
    EXPECT_CONTAINS(refusal(std::string("v 0 0 0\nv 1 \0 0\n", 16)), "bad/thing.obj: line 2: ");  // binary
    EXPECT_CONTAINS(refusal(triangle), "bad/thing.obj: no faces");
}

TEST(ObjAsset, MtlNonFiniteValueIsRefusedNamingTheLibraryAndLine) {
    const std::string mtl = "newmtl A\nKd 0.5 0.5 0.5\nPr inf\n";
    try {
        parseMtl(bytesOf(mtl), "models/a.mtl", "models");
        ADD_FAILURE() << "parsed, expected an AssetError";
    } catch (const AssetError& e) {
        EXPECT_CONTAINS(std::string(e.what()), "models/a.mtl: line 3: ");
    }
}
