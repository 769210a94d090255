// View → Look through: the cameras an imported glTF holds, offered by name with their file, placed
// where the import put the asset, their roll kept; they follow undo and survive save and open.
#include "mipgloss/assets/asset.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/viewport.h"

#include "gltf_writer.h"
#include "test_support.h"
#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QAction>
#include <QMenu>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>

using namespace mipgloss;
using namespace mipgloss::ui;

using mipgloss::test::openWindow;
using mipgloss::test::waitUntil;

namespace {

// A unit quad at the origin seen by two perspective cameras at (0, 0, 3) looking down −Z: "front",
// upright, and "rolled", its node turned +90° about its own view axis (rolled to its left).
void writeQuadWithCameras(const std::filesystem::path& file) {
    test::GltfWriter w;
    w.addToScene(w.addNode(w.addMesh(test::texturedQuad(), w.addMaterial(test::pbrMaterial("grey", {0.5, 0.5, 0.5, 1}, 0, 0.5)))));
    for (const auto& [name, turn] : {std::pair{std::string("front"), 0.0f}, std::pair{std::string("rolled"), 90.0f}}) {
        const glm::quat q = glm::angleAxis(glm::radians(turn), glm::vec3(0, 0, 1));
        w.addCamera(name, 0.6, {0.0, 0.0, 3.0}, {q.x, q.y, q.z, q.w});
    }
    w.writeGltf(file);
}

// The menu's entries as it shows them when opened.
QList<QAction*> openMenu(MainWindow& window) {
    auto* menu = window.findChild<QMenu*>(QStringLiteral("lookThroughMenu"));
    if (!menu) return {};
    emit menu->aboutToShow();
    return menu->actions();
}

}  // namespace

TEST(FileCameras, LookThroughOffersTheImportedFilesCamerasPlacedWithTheAssetAndRolled) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const std::filesystem::path file = dir.filePath(QStringLiteral("cams.gltf")).toStdString();
    writeQuadWithCameras(file);
    auto w = openWindow();
    SceneDocument* doc = w->document();

    QList<QAction*> entries = openMenu(*w);
    ASSERT_EQ(entries.size(), 1);
    EXPECT_FALSE(entries[0]->isEnabled()) << "the demo scene's files hold no cameras";

    QSignalSpy finished(w.get(), &MainWindow::importFinished);
    w->importMeshes({QString::fromStdString(file.string())});
    ASSERT_TRUE(waitUntil([&] { return !finished.isEmpty(); }, 60000));
    const SceneObject& quad = doc->object(doc->objectCount() - 1);
    entries = openMenu(*w);
    ASSERT_EQ(entries.size(), 2);
    EXPECT_EQ(entries[0]->text(), QStringLiteral("front (cams.gltf)"));
    EXPECT_EQ(entries[1]->text(), QStringLiteral("rolled (cams.gltf)"));

    // The camera sits where the import's placement puts the file's (0, 0, 3), looks down the
    // placed −Z (the placement scales and moves, it does not turn) and keeps its roll.
    entries[1]->trigger();
    const OrbitCamera& seen = w->viewport()->camera();
    const glm::vec3 expected(quad.transform.matrix() * glm::vec4(0.0f, 0.0f, 3.0f, 1.0f));
    const float size = quad.worldRadius();
    EXPECT_LT(glm::distance(seen.position(), expected), 1e-4f * size + 1e-5f);
    EXPECT_LT(glm::distance(glm::normalize(seen.target - seen.position()), glm::vec3(0, 0, -1)), 1e-5f);
    EXPECT_NEAR(seen.rollDegrees, 90.0f, 1e-3f);
    EXPECT_NEAR(seen.fovYDegrees, 0.6f * 180.0f / 3.14159265f, 1e-3f);
    entries[0]->trigger();
    EXPECT_NEAR(w->viewport()->camera().rollDegrees, 0.0f, 1e-3f);

    // Saved and opened again: the file's cameras come back with the scene.
    const QString saved = dir.filePath(QStringLiteral("scene.json"));
    ASSERT_TRUE(w->saveScene(saved)) << w->lastMessage().toStdString();
    w->newScene();
    EXPECT_FALSE(openMenu(*w).front()->isEnabled());
    ASSERT_TRUE(w->openScene(saved)) << w->lastMessage().toStdString();
    entries = openMenu(*w);
    ASSERT_EQ(entries.size(), 2);
    entries[1]->trigger();
    EXPECT_NEAR(w->viewport()->camera().rollDegrees, 90.0f, 1e-3f);

    // Without the objects that came from the file (the import undone), it offers nothing.
    for (int i = doc->objectCount() - 1; i >= 0; --i) doc->removeObject(i);
    entries = openMenu(*w);
    ASSERT_EQ(entries.size(), 1);
    EXPECT_FALSE(entries[0]->isEnabled());
}
