#include "mipgloss/scene/chain_needs.h"

#include "mipgloss/ibl/cubemap.h"

#include <algorithm>
#include <cmath>

namespace mipgloss {

ChainNeeds chainNeeds(const Scene& scene, int levelCount) {
    ChainNeeds needs;
    const int last = std::max(levelCount - 1, 0);
    float highest = scene.display.showBackground ? scene.display.backgroundLambda : 0.0f;
    for (const SceneObject& object : scene.objects) {
        if (!object.visible) continue;
        const Material& m = object.material;
        if (m.mode == LookupMode::Normal && m.useIrradiance) {
            needs.irradiance = true;
            continue;  // the irradiance map replaces the chain for this object
        }
        highest = std::max(highest, m.lambda);
    }
    // A fractional λ blends floor(λ) and floor(λ) + 1.
    const float clamped = std::clamp(highest, 0.0f, static_cast<float>(last));
    needs.lastFilteredLevel = std::min(last, static_cast<int>(std::ceil(clamped)));
    return needs;
}

ChainNeeds needsFor(const Scene& scene, int baseFaceSize) {
    return chainNeeds(scene, fullChainLevelCount(std::max(baseFaceSize, 1)));
}

}  // namespace mipgloss
