// What a scene needs from its environment: how many levels carry the builder's filter and whether
// the irradiance map is made ("skip what the scene doesn't need"). The renderer and the builder
// agree through this one type.
#pragma once

#include "mipgloss/scene/scene.h"

namespace mipgloss {

// What the environment chain must provide for this scene (renderer and builder agree on it).
// Levels up to `lastFilteredLevel` are reached through some λ (an object's, or the background's,
// mapped to the chain by chainLevelForExponent), so they get the builder's lobe filter; deeper
// levels are reached only by minification of small or distant objects, where the pixel footprint
// is itself an average, and get the cheap box filter.
// `irradiance`: some visible object in normal mode asks for the irradiance map.
// A face size below 1 (a scene's not yet known) counts as 1. The filtered range only grows in
// whole levels and, once built, is kept (see prepareEnvironment).
// `remainderReach`: the widest α of the layers that would read the environment without its bright
// lights (lobes.h, remainderReach; 0: none), so the default builder also filters that remainder
// when the environment's lights are no wider (PreparedEnvironment::wantsRemainder).
struct ChainNeeds {
    int lastFilteredLevel = 0;
    bool irradiance = false;
    double remainderReach = 0.0;
    bool operator==(const ChainNeeds&) const = default;
};
ChainNeeds chainNeeds(const Scene& scene, int baseFaceSize);

}  // namespace mipgloss
