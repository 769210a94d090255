#include "mipgloss/scene/lobes.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/layered.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace mipgloss {

int lobeKey(float lambda) { return static_cast<int>(std::lround(static_cast<double>(lambda) * 1024.0)); }

std::vector<int> lobesInUse(const Scene& scene) {
    if (scene.environment.builder != Builder::Phong) return {};
    std::set<int> keys;
    auto use = [&](float lambda) {
        if (isValidLambda(lambda) && lobeKey(lambda) > 0) keys.insert(lobeKey(lambda));
    };
    if (scene.display.showBackground) use(scene.display.backgroundLambda);
    for (const SceneObject& object : scene.objects) {
        if (!object.visible || !object.mesh) continue;
        const Material& m = scene.materialOf(object);
        if (!m.layered && m.mode == LookupMode::Normal && m.useIrradiance) continue;
        for (const double lambda : lambdasOf(m)) use(static_cast<float>(lambda));
    }
    return {keys.begin(), keys.end()};
}

LobeCube makeLobeCube(const PreparedEnvironment& environment, int key) {
    if (!environment.filter) throw std::logic_error("makeLobeCube: the environment has no Phong filter");
    LobeCube lobe;
    lobe.key = key;
    lobe.exponent = lambdaToExponent(key / 1024.0);
    const int baseSize = environment.filter->baseSize();
    const int size = lobeCubeSize(lobe.exponent, baseSize);
    lobe.holdsLobe = lobeCubeHoldsLobe(lobe.exponent, baseSize);
    lobe.cube = std::make_shared<const CubeMap>(environment.filter->filter(lobe.exponent, size));
    lobe.filter = environment.filter;
    return lobe;
}

std::vector<std::shared_ptr<const LobeCube>> makeLobeCubes(const PreparedEnvironment& environment, const Scene& scene) {
    std::vector<std::shared_ptr<const LobeCube>> lobes;
    if (!environment.filter) return lobes;
    for (int key : lobesInUse(scene)) lobes.push_back(std::make_shared<const LobeCube>(makeLobeCube(environment, key)));
    return lobes;
}

}  // namespace mipgloss
