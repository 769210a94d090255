#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"

#include "mipgloss/io/default_env.h"
#include "mipgloss/ibl/irradiance.h"

#include <algorithm>
#include <chrono>

namespace mipgloss {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

bool sameImport(const EnvironmentSettings& a, const EnvironmentSettings& b) {
    return a.source == b.source && a.faceSize == b.faceSize && a.layout == b.layout && a.handedness == b.handedness;
}

bool PreparedEnvironment::sameImport(const EnvironmentSettings& other) const {
    return base && mipgloss::sameImport(settings, other);
}

bool PreparedEnvironment::satisfies(const EnvironmentSettings& other, const ChainNeeds& needs) const {
    return sameImport(other) && chain && settings.builder == other.builder &&
           lastFilteredLevel >= std::min(needs.lastFilteredLevel, levelCount() - 1) &&
           (!needs.irradiance || irradiance) && (!wantsRemainder(needs.remainderReach) || remainderFilter);
}

bool PreparedEnvironment::wantsRemainder(double reach) const {
    return settings.builder == Builder::Phong && !lights.empty() && reach > 0.0 && widestLight(lights) <= reach;
}

PreparedEnvironment prepareEnvironment(const EnvironmentSettings& settings, const ChainNeeds& needs,
                                       const PreparedEnvironment* previous,
                                       const Progress& progress, const EnvironmentImported& onImported) {
    PreparedEnvironment out;
    out.settings = settings;

    // 1. Import, unless the previous one read the same file the same way.
    if (previous && previous->sameImport(settings)) {
        out.base = previous->base;
        out.report = previous->report;
        out.lights = previous->lights;
        out.importSeconds = previous->importSeconds;
    } else {
        const auto start = std::chrono::steady_clock::now();
        reportProgress(progress, "import", 0.0f);
        ImportedEnvironment imported;
        if (settings.source == kBuiltinEnvironment) {
            imported = loadDefaultEnvironment(settings.faceSize);
        } else {
            ImportOptions options;
            options.layout = settings.layout;
            options.handedness = settings.handedness;
            options.faceSize = settings.faceSize;
            imported = loadEnvironment(settings.source, options, progress);
        }
        out.base = std::make_shared<const CubeMap>(std::move(imported.cube));
        out.report = std::move(imported.report);
        out.lights = brightLights(*out.base);
        out.importSeconds = secondsSince(start);
        out.settings.faceSize = out.base->size();
        // The early environment: this import alone, to draw while the chain is built.
        if (onImported) onImported(std::make_shared<const PreparedEnvironment>(out));
    }
    out.settings.faceSize = out.base->size();

    // The filter stack entries are made from: kept with the import, made for the default builder.
    if (settings.builder == Builder::Phong) {
        if (previous && previous->filter && previous->sameImport(settings))
            out.filter = previous->filter;
        else {
            reportProgress(progress, "build", 0.0f);  // the pyramid reports nothing of its own
            out.filter = std::make_shared<const PhongFilter>(*out.base);
        }
    }

    // The remainder's filter, when the scene's layers read it: kept with the import once made.
    if (settings.builder == Builder::Phong) {
        if (previous && previous->remainderFilter && previous->sameImport(settings))
            out.remainderFilter = previous->remainderFilter;
        else if (out.wantsRemainder(needs.remainderReach))
            out.remainderFilter = std::make_shared<const PhongFilter>(withoutBrightLights(*out.base));
    }

    // 2. The chain: kept when the builder matches and it is filtered deep enough. Otherwise built
    // with the filter through max(needed, what the previous chain had), so the range never shrinks
    // (going back and forth with a slider builds at most once per new level).
    const int levels = fullChainLevelCount(out.base->size());
    const int needed = std::clamp(needs.lastFilteredLevel, 0, levels - 1);
    const bool sameBuilderChain = previous && previous->chain && previous->sameImport(settings) &&
                                  previous->settings.builder == settings.builder;
    if (sameBuilderChain && previous->lastFilteredLevel >= needed) {
        out.chain = previous->chain;
        out.lastFilteredLevel = previous->lastFilteredLevel;
        out.buildSeconds = previous->buildSeconds;
    } else {
        const int through = sameBuilderChain ? std::max(needed, previous->lastFilteredLevel) : needed;
        const auto start = std::chrono::steady_clock::now();
        BuildOptions options;
        options.lastFilteredLevel = through;
        options.progress = progress;
        out.chain = std::make_shared<const MipChain>(
            settings.builder == Builder::Phong ? buildPhongChain(*out.base, options, out.filter.get())
                                               : buildChain(*out.base, settings.builder, options));
        out.lastFilteredLevel = through;
        out.buildSeconds = secondsSince(start);
    }

    // 3. Irradiance only when some object reads it; kept once made for this import.
    if (previous && previous->irradiance && previous->sameImport(settings)) {
        out.irradiance = previous->irradiance;
        out.irradianceSeconds = previous->irradianceSeconds;
    } else if (needs.irradiance) {
        reportProgress(progress, "irradiance", 0.0f);
        const auto start = std::chrono::steady_clock::now();
        out.irradiance = std::make_shared<const CubeMap>(computeIrradiance(*out.base));
        out.irradianceSeconds = secondsSince(start);
    }
    reportProgress(progress, "done", 1.0f);
    return out;
}

}  // namespace mipgloss
