// Where mipgloss places objects (placement.h): each rule against its statement, in world space.
#include "mipgloss/scene/placement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace mipgloss;

namespace {

constexpr float kTol = 1e-5f;

// A box mesh of half-sizes `h` centred at `c` (only the bounds matter to placement).
std::shared_ptr<const Mesh> boxMesh(glm::vec3 c, glm::vec3 h) {
    auto m = std::make_shared<Mesh>();
    m->positions = {c - h, c + h};
    computeBounds(*m);
    return m;
}

SceneObject placed(const std::shared_ptr<const Mesh>& mesh, const Transform& t) {
    SceneObject o;
    o.mesh = mesh;
    o.transform = t;
    return o;
}

}  // namespace

TEST(Placement, CentredRowIsSymmetricAboutTheOriginAndSpacedByItsWidth) {
    const auto mesh = boxMesh({3.0f, 1.0f, -2.0f}, {2.0f, 1.0f, 1.0f});  // width 4
    float sum = 0.0f;
    for (int i = 0; i < 4; ++i) {
        const glm::vec3 c = placed(mesh, inCentredRow(mesh->bounds, i, 4)).worldCentre();
        EXPECT_NEAR(c.y, 0.0f, kTol);
        EXPECT_NEAR(c.z, 0.0f, kTol);
        EXPECT_NEAR(c.x, (static_cast<float>(i) - 1.5f) * 1.15f * 4.0f, kTol);
        sum += c.x;
    }
    EXPECT_NEAR(sum, 0.0f, kTol);
}

TEST(Placement, RowOfMeshesLeavesAFifthOfEachRadiusAfterIt) {
    const auto small = boxMesh({5.0f, 5.0f, 5.0f}, {1.0f, 1.0f, 1.0f});
    const auto large = boxMesh({-7.0f, 0.0f, 0.0f}, {4.0f, 4.0f, 4.0f});
    float cursor = 0.0f;
    const SceneObject a = placed(small, nextInRow(small->bounds, cursor));
    const SceneObject b = placed(large, nextInRow(large->bounds, cursor));
    EXPECT_NEAR(a.worldCentre().x - a.worldRadius(), 0.0f, kTol);  // the row starts at the origin
    const float gap = (b.worldCentre().x - b.worldRadius()) - (a.worldCentre().x + a.worldRadius());
    EXPECT_NEAR(gap, 0.2f * a.worldRadius(), 1e-4f);
    EXPECT_NEAR(b.worldCentre().y, 0.0f, kTol);
    EXPECT_NEAR(cursor, 2.2f * (a.worldRadius() + b.worldRadius()), 1e-4f);
}

TEST(Placement, GridIsSquareAndSpacedByItsRadius) {
    const auto mesh = boxMesh({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
    const float step = 2.3f * mesh->bounds.radius();
    // 5 objects: 3 columns (ceil √5), object 4 starts the second row.
    EXPECT_NEAR(inGrid(mesh->bounds, 2, 5).translation.x, 2.0f * step, kTol);
    EXPECT_NEAR(inGrid(mesh->bounds, 4, 5).translation.x, 1.0f * step, kTol);
    EXPECT_NEAR(inGrid(mesh->bounds, 4, 5).translation.y, 1.0f * step, kTol);
    EXPECT_EQ(inGrid(mesh->bounds, 0, 5).translation, glm::vec3(0.0f));
}

TEST(Placement, ImportedMeshIsSizedToTheSceneAndPlacedRightOfItWithAGap) {
    Scene scene;
    const auto unit = boxMesh({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
    for (int i = 0; i < 3; ++i) scene.objects.push_back(placed(unit, inCentredRow(unit->bounds, i, 3)));
    const float typical = scene.objects[0].worldRadius();
    const Bounds before = sceneBounds(scene);

    // 100× larger: scaled down to the typical radius.
    const auto huge = boxMesh({50.0f, 0.0f, 0.0f}, {100.0f, 100.0f, 100.0f});
    const SceneObject big = placed(huge, besideScene(scene, *huge));
    EXPECT_NEAR(big.worldRadius(), typical, 1e-4f);
    EXPECT_NEAR(big.worldCentre().x - big.worldRadius(), before.max.x + 0.2f * typical, 1e-3f);
    EXPECT_NEAR(big.worldCentre().y, before.centre().y, 1e-4f);
    EXPECT_NEAR(big.worldCentre().z, before.centre().z, 1e-4f);

    // Twice as large: within 4×, keeps its size.
    const auto twice = boxMesh({0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f});
    EXPECT_EQ(besideScene(scene, *twice).scale, 1.0f);

    // Alone: its own size, at the origin.
    const Transform alone = besideScene(Scene{}, *huge);
    EXPECT_EQ(alone.scale, 1.0f);
    EXPECT_NEAR(placed(huge, alone).worldCentre().x, 0.0f, 1e-3f);
}

TEST(Placement, DuplicateSitsBesideItsOriginalWithoutOverlapping) {
    const auto mesh = boxMesh({1.0f, 2.0f, 3.0f}, {1.0f, 1.0f, 1.0f});
    Transform t;
    t.scale = 2.0f;
    t.translation = {4.0f, 5.0f, 6.0f};
    const SceneObject original = placed(mesh, t);
    const SceneObject copy = placed(mesh, besideOriginal(original));
    EXPECT_EQ(copy.transform.scale, original.transform.scale);
    EXPECT_NEAR(copy.worldCentre().x - original.worldCentre().x, 2.4f * original.worldRadius(), 1e-4f);
    EXPECT_NEAR(copy.worldCentre().y, original.worldCentre().y, kTol);
    EXPECT_GT(glm::length(copy.worldCentre() - original.worldCentre()), 2.0f * original.worldRadius());
}
