// An environment made ready for rendering: imported once, its chain built once per builder, its
// irradiance map computed only when the scene asks for it. Pure C++; the window runs these off
// the UI thread, the command line and the tests call them directly.
#pragma once

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/cubemap.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/chain_needs.h"
#include "mipgloss/scene/scene.h"

#include <functional>
#include <memory>
#include <string>

namespace mipgloss {

struct PreparedEnvironment {
    EnvironmentSettings settings;  // what it was made from (rotation is a draw-time uniform)
    std::shared_ptr<const CubeMap> base;
    ImportReport report;
    std::shared_ptr<const MipChain> chain;
    // Levels 0..lastFilteredLevel carry the builder's filter; deeper ones the box filter (see
    // ChainNeeds in scene.h).
    int lastFilteredLevel = -1;
    std::shared_ptr<const CubeMap> irradiance;  // null until some object needs it
    // The default builder's energy pyramid of this import, for lobe cubes (lobes.h); null for
    // the other builders.
    std::shared_ptr<const PhongFilter> filter;
    double importSeconds = 0.0, buildSeconds = 0.0, irradianceSeconds = 0.0;

    int levelCount() const { return chain ? chain->levelCount() : 0; }
    // True when the import (source, size, layout, handedness) matches.
    bool sameImport(const EnvironmentSettings& other) const;
    // True when nothing has to be built for these settings and needs.
    bool satisfies(const EnvironmentSettings& other, const ChainNeeds& needs) const;
};


// Imports (the embedded default when settings.source is kBuiltinEnvironment) and builds what
// `needs` asks for. Reuses `previous`'s import, chain or irradiance where they still fit, so a
// change of builder does not re-read the file and a new λ beyond the filtered levels rebuilds
// only the chain. Throws EnvError (bad file), std::invalid_argument (unknown builder),
// Cancelled.
PreparedEnvironment prepareEnvironment(const EnvironmentSettings& settings, const ChainNeeds& needs,
                                       const PreparedEnvironment* previous = nullptr,
                                       const Progress& progress = {});


}  // namespace mipgloss
