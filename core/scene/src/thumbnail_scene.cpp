#include "mipgloss/scene/thumbnail_scene.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/mesh.h"

#include <glm/trigonometric.hpp>

#include <cmath>
#include <memory>

namespace mipgloss {

namespace {

// The background's blur: enough that a mirror's reflection reads as a soft picture of the
// surroundings behind a sharp sphere, not a busy one that hides its silhouette.
constexpr float kBackgroundLambda = 2.0f;
// The sphere's silhouette spans this fraction of the thumbnail's height.
constexpr float kSphereFill = 0.84f;

// One sphere mesh for every thumbnail: the renderer keys its GPU meshes by the mesh object, so
// a shared one is uploaded once per renderer. 48 × 96 quads: smooth at a few hundred pixels.
const std::shared_ptr<const Mesh>& thumbnailSphere() {
    static const auto sphere = std::make_shared<const Mesh>(makeSphere(48, 96));
    return sphere;
}

const std::shared_ptr<const Mesh>& texturedThumbnailSphere() {
    static const auto sphere = std::make_shared<const Mesh>(makeUvSphere(48, 96));
    return sphere;
}

}  // namespace

Scene thumbnailScene(const Material& material, const EnvironmentSettings& settings) {
    Scene scene;
    scene.environment = settings;
    SceneObject object;
    object.name = "sphere";
    // A textured material on a sphere with UVs (its maps wrap once around it), others on the
    // plain sphere every thumbnail has always used.
    object.mesh = material.layered && material.layers.maps.anyTexture() ? texturedThumbnailSphere() : thumbnailSphere();
    object.meshSource = "builtin:sphere";
    scene.addObject(object, material);
    scene.display.showBackground = true;
    scene.display.backgroundLambda = kBackgroundLambda;
    return scene;
}

OrbitCamera thumbnailCamera() {
    OrbitCamera camera;
    camera.pitchDegrees = 20.0f;  // slightly from above: the sphere shows the sky and the ground
    // A unit sphere seen from distance d has a silhouette of half-height 1/√(d² − 1) on the image
    // plane at unit depth; the frame's half-height there is tan(fov/2).
    const float halfHeight = kSphereFill * std::tan(0.5f * glm::radians(camera.fovYDegrees));
    camera.distance = std::sqrt(1.0f + 1.0f / (halfHeight * halfHeight));
    return camera;
}

ChainNeeds thumbnailNeeds(int baseFaceSize) {
    // The chain level λ reads grows with λ (phong.h), so the widest lobe, kMaxLambda, reaches the
    // deepest level any material can; chainNeeds counts the background's λ as well. Irradiance
    // too, for materials that ask for it.
    Material widest;
    widest.lambda = static_cast<float>(kMaxLambda);
    ChainNeeds needs = chainNeeds(thumbnailScene(widest), baseFaceSize);
    needs.irradiance = true;
    return needs;
}

}  // namespace mipgloss
