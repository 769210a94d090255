// A scene document's texture maps (scene_document.h): decoded into the document's own cache, on
// its BackgroundWorker or at once, never into another document's (textures.h: a cache is its
// caller's, not the process's).
#include "gltf_writer.h"
#include "mipgloss/assets/textures.h"
#include "mipgloss/ui/scene_document.h"

#include <gtest/gtest.h>

#include <QSignalSpy>
#include <QTemporaryDir>

#include <filesystem>
#include <string>

using namespace mipgloss;
using namespace mipgloss::ui;
namespace fs = std::filesystem;

namespace {

// One object whose layered material reads `file` as its base colour.
Scene sceneReading(const TextureRef& map) {
    Scene scene;
    Material material;
    material.layered = true;
    material.layers.maps.baseColor = map;
    SceneObject object;
    object.name = "sphere";
    object.mesh = std::make_shared<const Mesh>(makeUvSphere(4, 8));
    scene.addObject(std::move(object), material);
    return scene;
}

TextureRef writtenMap(const QTemporaryDir& dir, const char* name) {
    const fs::path file = fs::path(dir.path().toStdString()) / name;
    test::writePng(test::makeImage(2, 2, 3, [](int, int) -> std::vector<std::uint8_t> { return {10, 20, 30}; }), file);
    return TextureRef{file.string(), -1, 0};
}

}  // namespace

TEST(SceneDocumentTextures, EachDocumentDecodesIntoItsOwnCache) {
    QTemporaryDir dir;
    const TextureRef map = writtenMap(dir, "grey.png");
    SceneDocument first, second;
    ASSERT_NE(first.textures(), nullptr);
    EXPECT_NE(first.textures(), second.textures());
    EXPECT_TRUE(first.decodeTexturesNow(sceneReading(map)).isEmpty());
    EXPECT_NE(first.textures()->find(map), nullptr);
    EXPECT_EQ(second.textures()->find(map), nullptr) << "a map one document decoded is not another's";
}

TEST(SceneDocumentTextures, DecodedOnTheWorkerArriveWithTheirWarnings) {
    QTemporaryDir dir;
    const TextureRef map = writtenMap(dir, "grey.png");
    const TextureRef missing{(fs::path(dir.path().toStdString()) / "none.png").string(), -1, 0};
    SceneDocument document;
    QSignalSpy arrived(&document, &SceneDocument::texturesDecoded);
    Scene scene = sceneReading(map);
    scene.materials.front().material.layers.maps.emissive = missing;
    document.decodeTexturesLater(scene);
    EXPECT_TRUE(document.decodingTextures());
    document.decodeTexturesLater(scene);  // already on the way: nothing more asked
    ASSERT_TRUE(arrived.wait(10000));
    EXPECT_FALSE(document.decodingTextures());
    ASSERT_EQ(arrived.count(), 1);
    const QStringList warnings = arrived.front().front().toStringList();
    ASSERT_EQ(warnings.size(), 1);
    EXPECT_TRUE(warnings.front().contains(QString::fromStdString(missing.file))) << warnings.front().toStdString();
    EXPECT_NE(document.textures()->find(map), nullptr);
    EXPECT_NE(document.textures()->problem(missing), "");
    // Everything is now decoded or refused: nothing left to ask for.
    document.decodeTexturesLater(scene);
    EXPECT_FALSE(document.decodingTextures());
}
