// An environment made ready for rendering: imported once, its chain built once per builder, its
// irradiance map computed only when the scene asks for it. Pure C++; the window runs these off
// the UI thread, the command line and the tests call them directly.
#pragma once

#include "mipgloss/ibl/bright_lights.h"
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/chain_needs.h"
#include "mipgloss/scene/scene.h"

#include <functional>
#include <memory>
#include <string>

namespace mipgloss {

// True when two settings read the same file the same way (source, face size, layout,
// handedness): what a new chain or builder can reuse.
bool sameImport(const EnvironmentSettings& a, const EnvironmentSettings& b);

struct PreparedEnvironment {
    EnvironmentSettings settings;  // what it was made from
    std::shared_ptr<const CubeMap> base;
    ImportReport report;
    // Null in an early environment (EnvironmentImported): the import alone, before the chain.
    std::shared_ptr<const MipChain> chain;
    // Levels 0..lastFilteredLevel carry the builder's filter; deeper ones the box filter (see
    // ChainNeeds in scene.h).
    int lastFilteredLevel = -1;
    std::shared_ptr<const CubeMap> irradiance;  // null until some object needs it
    // The base's bright texels as points of energy (bright_lights.h), made with the import: the
    // layered materials shade them with their exact BRDF.
    std::vector<PointLight> lights;
    // The default builder's energy pyramid of this import, for stack entries (lobes.h); null for
    // the other builders.
    std::shared_ptr<const PhongFilter> filter;
    // The same for the smooth remainder (withoutBrightLights), for the GGX layers' lookups; made
    // only when some layer reads it (wantsRemainder).
    std::shared_ptr<const PhongFilter> remainderFilter;
    double importSeconds = 0.0, buildSeconds = 0.0, irradianceSeconds = 0.0;

    int levelCount() const { return chain ? chain->levelCount() : 0; }
    // False for an early environment: the base is there, the chain (and filter) not yet.
    bool complete() const { return chain != nullptr; }
    // True when the import (source, size, layout, handedness) matches.
    bool sameImport(const EnvironmentSettings& other) const;
    // True when layers up to α = reach read a remainder filter of it (lobes.h, ggxReadsRemainder):
    // the default builder, some bright lights, none wider than reach.
    bool wantsRemainder(double reach) const;
    // True when nothing has to be built for these settings and needs.
    bool satisfies(const EnvironmentSettings& other, const ChainNeeds& needs) const;
};


// Called by prepareEnvironment, on its thread, as soon as a new import exists and before the
// chain is built (at face 1024 the pyramid and chain take about as long as the import, or longer): an early environment holding
// the settings, base, report and importSeconds, with no chain, filter or irradiance map. The
// previewer draws it at once (renderer.h: the base as the mirror, GL's box mips of it for λ > 0)
// instead of keeping the old environment until the whole chain is done. Not called when
// `previous`'s import is reused: then the previous environment, chain and all, is the better
// picture until the new chain exists.
//
// A callback rather than two calls (import, then build): what to reuse from `previous` (import,
// filter, chain, irradiance) stays decided in one function, callers that want only the finished
// environment (the command line, the tests) do not change, and the window's worker stays one job
// with one cancellation flag, so "the newest request wins" is still one rule.
using EnvironmentImported = std::function<void(const std::shared_ptr<const PreparedEnvironment>& early)>;

// Imports (the embedded default when settings.source is kBuiltinEnvironment) and builds what
// `needs` asks for. Reuses `previous`'s import, chain or irradiance where they still fit, so a
// change of builder does not re-read the file and a new λ beyond the filtered levels rebuilds
// only the chain. Progress stages: "import", "build" (the filter's pyramid and the chain),
// "irradiance", then "done". Throws EnvError (bad file), std::invalid_argument (unknown builder),
// Cancelled.
PreparedEnvironment prepareEnvironment(const EnvironmentSettings& settings, const ChainNeeds& needs,
                                       const PreparedEnvironment* previous = nullptr,
                                       const Progress& progress = {},
                                       const EnvironmentImported& onImported = {});


}  // namespace mipgloss
