#include "mipgloss/scene/chain_needs.h"
#include "mipgloss/scene/lobes.h"

#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/layered.h"

#include <algorithm>
#include <cmath>

namespace mipgloss {

ChainNeeds chainNeeds(const Scene& scene, int faceSize) {
    const int baseFaceSize = std::max(faceSize, 1);
    ChainNeeds needs;
    const int last = lastReadLevel(baseFaceSize);
    // The deepest chain level some lobe in the scene is read at while λ moves (a fractional
    // level blends floor and floor + 1).
    double deepest = 0.0;
    auto reach = [&](float lambda) {
        const double level = chainLevelForExponent(lambdaToExponent(lambda), baseFaceSize);
        if (std::isfinite(level)) deepest = std::max(deepest, level);
    };
    if (scene.display.showBackground) reach(scene.display.backgroundLambda);
    for (const SceneObject& object : scene.objects) {
        if (!object.visible) continue;
        const Material& m = scene.materialOf(object);
        if (m.layered) {
            // The irradiance map, when asked, replaces the diffuse base's lookup only.
            needs.irradiance = needs.irradiance || m.useIrradiance;
        } else if (m.mode == LookupMode::Normal && m.useIrradiance) {
            needs.irradiance = true;
            continue;  // the irradiance map replaces the chain for this object
        }
        for (const double lambda : lambdasOf(m)) reach(static_cast<float>(lambda));
    }
    needs.lastFilteredLevel = std::min(last, static_cast<int>(std::ceil(deepest - 1e-9)));
    needs.remainderReach = remainderReach(scene, baseFaceSize);
    return needs;
}

}  // namespace mipgloss
