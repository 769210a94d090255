#include "mipgloss/scene/turntable.h"

#include <cmath>

namespace mipgloss {

namespace {
// An angle in degrees in [−180°, 180°], computed in double so large turns lose no precision.
float wrapped(double degrees) { return static_cast<float>(std::remainder(degrees, 360.0)); }
}  // namespace

const char* turntableSpinName(TurntableSpin spin) {
    switch (spin) {
        case TurntableSpin::Object: return "object";
        case TurntableSpin::Environment: return "environment";
    }
    return "object";
}

bool parseTurntableSpin(std::string_view name, TurntableSpin& out) {
    for (TurntableSpin s : {TurntableSpin::Object, TurntableSpin::Environment})
        if (name == turntableSpinName(s)) {
            out = s;
            return true;
        }
    return false;
}

TurnedView turnedView(const OrbitCamera& camera, float environmentRotationDegrees, TurntableSpin spin,
                      float degrees) {
    TurnedView v{camera, environmentRotationDegrees};
    const double turn = static_cast<double>(degrees);
    switch (spin) {
        case TurntableSpin::Object:
            // The camera and the environment both turn by −θ about the target (turntable.h).
            v.camera.yawDegrees = wrapped(static_cast<double>(camera.yawDegrees) - turn);
            v.environmentRotationDegrees = wrapped(static_cast<double>(environmentRotationDegrees) - turn);
            break;
        case TurntableSpin::Environment:
            v.environmentRotationDegrees = wrapped(static_cast<double>(environmentRotationDegrees) + turn);
            break;
    }
    return v;
}

}  // namespace mipgloss
