// Small scenes for the document, model and undo tests, without file I/O.
#pragma once

#include "mipgloss/scene/scene.h"

#include <memory>
#include <string>

namespace mipgloss::test {

// One sphere mesh shared by every object (so scenes built twice compare equal).
inline std::shared_ptr<const Mesh> sphereMesh() {
    static const auto mesh = std::make_shared<const Mesh>(makeSphere(8, 16));
    return mesh;
}

// A unit sphere (world radius √3 with its box, scaled by the transform) at x.
inline SceneObject sphereObject(const std::string& name, float x) {
    SceneObject o;
    o.name = name;
    o.mesh = sphereMesh();
    o.meshSource = "builtin:sphere";
    o.transform.translation = {x, 0.0f, 0.0f};
    return o;
}

}  // namespace mipgloss::test
