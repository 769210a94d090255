// Scenes for the scene tests: one small UV sphere per material, at the origin (what lobesInUse
// and chainNeeds read is the materials, not where the objects stand).
#pragma once

#include "mipgloss/scene/mesh.h"
#include "mipgloss/scene/scene.h"

#include <memory>
#include <vector>

namespace mipgloss::test {

inline Scene spheresWearing(const std::vector<Material>& materials) {
    Scene scene;
    auto sphere = std::make_shared<const Mesh>(makeSphere(8, 16));
    for (const Material& m : materials) {
        SceneObject o;
        o.mesh = sphere;
        scene.addObject(o, m);
    }
    return scene;
}

}  // namespace mipgloss::test
