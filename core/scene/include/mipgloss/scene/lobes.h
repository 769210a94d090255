// The settled picture: once a material's λ rests, the object is drawn from a cube that holds its
// own lobe exactly (builders.h, lobeCubeSize: σ ≈ 3.6 texels, so bilinear reads between its
// centres stay within about 1 %), instead of the chain's blend of two levels whose lobes are 4×
// apart (10–58 % off it at half levels, measured by mipgloss bench, docs/chain-schedule.md). One cube per distinct lobe in use,
// made only for lobes the scene shows. Pure C++: the window makes them on its worker, `render`
// directly.
#pragma once

#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/scene.h"

#include <memory>
#include <vector>

namespace mipgloss {

// A material's λ as a lobe key: λ within 1/1024 share a lobe (as they share a sampler).
int lobeKey(float lambda);

struct LobeCube {
    int key = 0;              // lobeKey of the λ it was made for
    double exponent = 0.0;    // the lobe it holds, lambdaToExponent(λ)
    bool holdsLobe = false;   // σ is at least 3.6 of its texels (lobeCubeHoldsLobe): exact reads
    std::shared_ptr<const CubeMap> cube;
    std::shared_ptr<const PhongFilter> filter;  // the environment it was made from
};

// The lobes the scene shows that the chain cannot show exactly: the λ of every visible object
// (not a mirror, not using the irradiance map) and of the background when shown and blurred,
// one per key, in ascending key order. Empty when the environment's builder is not the default
// (the other builders are there to be compared as they are).
std::vector<int> lobesInUse(const Scene& scene);

// The lobe cube for `key` (λ = key / 1024) from the environment's filter. The environment must
// have been prepared with the default builder (filter set). Throws Cancelled if asked.
LobeCube makeLobeCube(const PreparedEnvironment& environment, int key);

// Every lobe cube the scene shows (lobesInUse), made now: the settled picture in one call, for
// `mipgloss render` and the tests (the window makes them one by one on its worker). Empty when
// the environment has no filter.
std::vector<std::shared_ptr<const LobeCube>> makeLobeCubes(const PreparedEnvironment& environment, const Scene& scene);

}  // namespace mipgloss
