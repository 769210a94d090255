// What the view's gestures do to the orbit camera, beyond orbit, pan and zoom (camera.h): framing
// one object, zooming toward the point under the cursor. Pure functions, GL-free and Qt-free, so the
// window's gestures are tested without a window.
#pragma once

#include "mipgloss/scene/bounds.h"
#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/picking.h"
#include "mipgloss/scene/scene.h"

#include <glm/vec3.hpp>

#include <optional>

namespace mipgloss {

// The point a zoom at the cursor aims at: where `ray` first meets a visible object's picking sphere
// (picking.h, firstHit), else where it crosses the plane through the camera's target facing the camera
// (what an orbit turns about), else nullopt (the ray runs parallel to that plane or away from it).
std::optional<glm::vec3> zoomPivot(const Scene& scene, const OrbitCamera& camera, const Ray& ray);

// Zooms by `factor` (< 1 closer, as OrbitCamera::zoom) while `pivot` stays under the same pixel:
// the camera's position and its target both scale about `pivot` by `factor`, and the view
// direction is unchanged, so the ray from the camera through `pivot` keeps its direction.
// Non-positive or non-finite factors change nothing; the distance is clamped as zoom() clamps it.
void zoomToward(OrbitCamera& camera, const glm::vec3& pivot, float factor);

}  // namespace mipgloss
