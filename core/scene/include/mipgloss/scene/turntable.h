// Turning a scene on a turntable, as a view: which camera and environment rotation show the scene
// turned by an angle about the vertical axis through the camera's target. GL-free; the window's
// turntable and `mipgloss render --spin/--turntable` share it.
//
// Signs (the renderer's conventions: camera.h, ui/render/src/renderer_impl.h environmentRotation). The renderer looks up
// world direction d in the environment at E(φ)·d with E(φ) = Ry(−φ), φ the display's
// environmentRotationDegrees, so a larger φ turns the environment's picture by +φ about +Y. Turning
// every object by R = Ry(θ) about the target (Transform::rotationDegrees.y = θ turns an object the
// same way) under a fixed environment is the same picture as leaving the objects and turning the
// camera and the environment by R⁻¹ = Ry(−θ) about the target: the camera's yaw becomes yaw − θ
// (Ry(α) adds α to the yaw of camera.cpp's viewBack), the environment's φ becomes φ − θ (a
// direction r' = R·r of the turned scene is looked up at E(φ)·R·r = E(φ − θ)·r). The background,
// turned with the camera, stays put.
#pragma once

#include "mipgloss/scene/camera.h"

#include <string_view>

namespace mipgloss {

enum class TurntableSpin { Object, Environment };
const char* turntableSpinName(TurntableSpin spin);  // "object", "environment"
bool parseTurntableSpin(std::string_view name, TurntableSpin& out);

struct TurnedView {
    OrbitCamera camera;
    float environmentRotationDegrees = 0.0f;
};

// The view with the scene turned by `degrees` about the vertical axis through camera.target.
// Object: every object turns on a turntable under a fixed environment, which is the same picture as
// the camera orbiting by -degrees with the environment turned with it (so the background stays put);
// Environment: only the environment turns (DisplaySettings::environmentRotationDegrees).
// The angles returned are kept in [−180°, 180°]; target, distance, pitch and field of view are kept.
TurnedView turnedView(const OrbitCamera& camera, float environmentRotationDegrees, TurntableSpin spin,
                      float degrees);

}  // namespace mipgloss
