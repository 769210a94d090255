// Scene files with assets (scene version 7): an object keeps the part of its asset file it is,
// a material its texture maps, both paths relative to the scene file like every mesh's, so a
// folder of scene and asset moves together (issue 21: "scene files reference the asset by
// relative path; the asset is not copied in").
#include "gltf_writer.h"
#include "mipgloss/assets/asset.h"
#include "mipgloss/ui/scene_file.h"

#include <gtest/gtest.h>

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <filesystem>
#include <string>

using namespace mipgloss;
using namespace mipgloss::ui;
namespace fs = std::filesystem;

namespace {

// Two meshes (two parts), two materials: one with an embedded base colour image and a
// metallic–roughness one, the other with an external normal map.
void writeAsset(const fs::path& dir) {
    const test::TestImage tiny = test::makeImage(4, 4, 3, [](int x, int y) -> std::vector<std::uint8_t> {
        return {static_cast<std::uint8_t>(60 * x), static_cast<std::uint8_t>(60 * y), 128};
    });
    test::writePng(tiny, dir / "maps" / "bumps.png");
    test::GltfWriter w;
    const int base = w.addTexture(w.addImage(test::encodePng(tiny)));
    const int normal = w.addTexture(w.addImage({}, "maps/bumps.png"));
    const int painted = w.addMaterial(test::pbrMaterial("Painted", {0.8f, 0.7f, 0.6f, 1}, 0.0, 0.4, base, base));
    const int bumpy = w.addMaterial(test::pbrMaterial("Bumpy", {1, 1, 1, 1}, 1.0, 0.3, -1, -1, normal));
    Mesh quad = test::texturedQuad();
    w.addToScene(w.addNode(w.addMesh(test::texturedSphere(8, 16), painted)));
    w.addToScene(w.addNode(w.addMesh(quad, bumpy), {3.0, 0.0, 0.0}));
    w.writeGlb(dir / "thing.glb");
}

TEST(AssetSceneFile, PartsAndMapsRoundTripAndTheFolderMovesWithTheScene) {
    QTemporaryDir tmp;
    ASSERT_TRUE(tmp.isValid());
    const fs::path dir = fs::path(tmp.path().toStdString()) / "project";
    fs::create_directories(dir / "maps");
    writeAsset(dir);
    const Asset asset = loadAsset(dir / "thing.glb");
    ASSERT_EQ(asset.parts.size(), 2u);
    Scene scene;
    addAsset(scene, asset, (dir / "thing.glb").string(), Transform{}, Material{});
    ASSERT_EQ(scene.objects.size(), 2u);
    const fs::path sceneFile = dir / "scene.mipgloss";
    saveScene(scene, sceneFile);

    // Relative paths in the file: the asset beside the scene, the external map under maps/.
    QFile f(QString::fromStdString(sceneFile.string()));
    ASSERT_TRUE(f.open(QIODevice::ReadOnly));
    const QJsonObject root = QJsonDocument::fromJson(f.readAll()).object();
    EXPECT_EQ(root.value("version").toInt(), kSceneVersion);
    const QJsonArray objects = root.value("objects").toArray();
    EXPECT_EQ(objects.at(0).toObject().value("mesh").toString(), QStringLiteral("thing.glb"));
    EXPECT_EQ(objects.at(1).toObject().value("part").toInt(), 1);
    const QByteArray text = QJsonDocument(root).toJson();
    EXPECT_TRUE(text.contains("\"maps/bumps.png\"")) << text.toStdString();

    // Moved, folder and all: everything found again, equal to what was saved.
    const fs::path moved = fs::path(tmp.path().toStdString()) / "elsewhere";
    fs::rename(dir, moved);
    SceneFileReport report;
    const Scene loaded = loadScene(moved / "scene.mipgloss", &report);
    ASSERT_EQ(loaded.objects.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(loaded.objects[i].meshPart, static_cast<int>(i));
        EXPECT_EQ(loaded.objects[i].meshSource, (moved / "thing.glb").string());
        EXPECT_EQ(loaded.objects[i].mesh->positions, scene.objects[i].mesh->positions);
        EXPECT_EQ(loaded.objects[i].mesh->uvs, scene.objects[i].mesh->uvs);
    }
    const Material& painted = loaded.materialOf(loaded.objects[0]);
    EXPECT_TRUE(painted.layered);
    EXPECT_EQ(painted.layers.maps.baseColor.file, (moved / "thing.glb").string());
    EXPECT_EQ(painted.layers.maps.baseColor.image, 0);
    EXPECT_EQ(painted.layers.maps.roughness.channel, 1);
    EXPECT_EQ(painted.layers.maps.metallic.channel, 2);
    const Material& bumpy = loaded.materialOf(loaded.objects[1]);
    EXPECT_EQ(bumpy.layers.maps.normal.file, (moved / "maps" / "bumps.png").string());
    EXPECT_EQ(bumpy.layers.maps.normal.image, -1);
    EXPECT_EQ(loaded.findMaterial(loaded.objects[0].material)->name, "Painted");
    EXPECT_EQ(loaded.findMaterial(loaded.objects[1].material)->name, "Bumpy");
}

// A part the asset no longer has (the file changed) is an error naming the object and the file;
// a bad channel in the maps names its key.
TEST(AssetSceneFile, APartPastTheAssetAndABadChannelAreRefusedByName) {
    QTemporaryDir tmp;
    ASSERT_TRUE(tmp.isValid());
    const fs::path dir = tmp.path().toStdString();
    fs::create_directories(dir / "maps");
    writeAsset(dir);
    auto sceneWith = [&](const std::string& object, const std::string& material) {
        const fs::path file = dir / "s.mipgloss";
        QFile f(QString::fromStdString(file.string()));
        EXPECT_TRUE(f.open(QIODevice::WriteOnly));
        f.write(("{\"format\": \"mipgloss-scene\", \"version\": 7, \"materials\": [" + material +
                 "], \"objects\": [" + object + "]}")
                    .c_str());
        f.close();
        try {
            loadScene(file);
        } catch (const SceneFileError& e) {
            return std::string(e.what());
        }
        return std::string("loaded");
    };
    const std::string past = sceneWith(R"({"name": "lamp", "mesh": "thing.glb", "part": 5})", "");
    EXPECT_NE(past.find("lamp"), std::string::npos) << past;
    EXPECT_NE(past.find("part 5"), std::string::npos) << past;
    EXPECT_NE(past.find("thing.glb"), std::string::npos) << past;
    const std::string channel = sceneWith(
        R"({"name": "lamp", "mesh": "thing.glb", "part": 0, "material": "m"})",
        R"({"name": "m", "layers": {"maps": {"roughnessTexture": {"file": "maps/bumps.png", "channel": 7}}}})");
    EXPECT_NE(channel.find("roughnessTexture.channel"), std::string::npos) << channel;
}

}  // namespace
