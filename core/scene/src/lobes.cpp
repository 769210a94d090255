#include "mipgloss/scene/lobes.h"

#include "mipgloss/ibl/ggx_fitted_lobes.h"
#include "mipgloss/ibl/ggx_sampling.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/layered.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace mipgloss {

double stackLambda(int index) { return static_cast<double>(index) / kStackStepsPerLevel; }

double stackExponent(int index) { return lambdaToExponent(stackLambda(index)); }

int stackTop(int baseSize) {
    for (int j = 1; j <= kStackLast; ++j)
        if (stackEntryHoldsLobe(stackExponent(j), baseSize)) return j;
    return kStackLast;
}

namespace {

// 1 − Λ(n) = 1/(n + 2): the lobe's mean of 1 − cos θ, the quantity the blend and the footprint add.
double oneMinusMeanCosine(double exponent) { return 1.0 / (exponent + 2.0); }

}  // namespace

std::optional<StackBlend> stackBlend(double exponent, int baseSize) {
    const int top = stackTop(baseSize);
    if (!(exponent >= 0.0) || exponent > stackExponent(top)) return std::nullopt;  // NaN, ∞, too sharp
    // The sharper neighbour: the last entry (from top on) whose lobe is at least as sharp.
    int sharper = std::clamp(static_cast<int>(std::floor(exponentToLambda(exponent) * kStackStepsPerLevel)), top, kStackLast);
    while (sharper > top && stackExponent(sharper) < exponent) --sharper;
    while (sharper < kStackLast && stackExponent(sharper + 1) >= exponent) ++sharper;
    const int wider = std::min(sharper + 1, kStackLast);
    const double u = oneMinusMeanCosine(exponent);
    const double u0 = oneMinusMeanCosine(stackExponent(sharper)), u1 = oneMinusMeanCosine(stackExponent(wider));
    const double weight = u1 > u0 ? std::clamp((u - u0) / (u1 - u0), 0.0, 1.0) : 0.0;
    return StackBlend{sharper, wider, weight};
}

int firstEntryMadeAhead(int baseSize) {
    int first = stackTop(baseSize);
    while (first < kStackLast && stackEntryFaceSize(stackExponent(first), baseSize) > kGrazingLargestFace) ++first;
    return first;
}

double footprintExponent(double exponent, double dx, double dy) {
    if (!(exponent >= 0.0)) return exponent;
    const double u = (std::isinf(exponent) ? 0.0 : oneMinusMeanCosine(exponent)) + (dx * dx + dy * dy) / 24.0;
    return u > 0.0 ? std::max(1.0 / u - 2.0, 0.0) : exponent;
}

namespace {

// The λ the scene reads single lobes at, and whether each wants every sharper entry (the grazing
// option); the GGX layers' roughness (their lookups' entries: ggxEntries), and whether a roughness
// map gives fragments every roughness up to it.
struct LambdaInUse {
    double lambda;
    bool grazing;
};
struct GgxInUse {
    double roughness;
    bool mapped;
};

struct LobesOfScene {
    std::vector<LambdaInUse> lambdas;
    std::vector<GgxInUse> ggx;
};

LobesOfScene lobesOfScene(const Scene& scene) {
    LobesOfScene out;
    if (scene.environment.builder != Builder::Phong) return out;
    auto use = [&](double lambda, bool grazing) {
        if (isValidLambda(lambda) && lambda > 0.0) out.lambdas.push_back({lambda, grazing});
    };
    if (scene.display.showBackground) use(scene.display.backgroundLambda, false);
    for (const SceneObject& object : scene.objects) {
        if (!object.visible || !object.mesh) continue;
        const Material& m = scene.materialOf(object);
        if (!m.layered) {
            if (m.mode == LookupMode::Normal && m.useIrradiance) continue;
            use(m.lambda, m.sharperAtGrazing && m.mode == LookupMode::Reflect);
            continue;
        }
        // The diffuse base's n = 1 lobe, then the GGX layers.
        if (!m.useIrradiance) use(diffuseLambda(), false);
        out.ggx.push_back({m.layers.roughness, !m.layers.maps.roughness.empty()});
        if (hasCoat(m.layers)) out.ggx.push_back({m.layers.coatRoughness, false});
    }
    return out;
}

// The lookups a layer reads with the scene's K (ggxLayerLookups).
int layerLookups(const Scene& scene, const GgxInUse& layer, int baseSize) {
    return ggxLayerLookups(layer.roughness, scene.display.ggxLookups, baseSize, layer.mapped, scene.display.brightLights);
}

// The lobes a layer of `roughness` reads over N·v: its K lookups' (unless it reads only its mean
// lobe) and its mean lobe's (where it reads it: meanLobeShare).
ExponentRange layerExponentRange(double roughness, int lookups, bool mapped) {
    const double share = mapped ? 0.0 : meanLobeShare(roughness);
    ExponentRange range{0.0, std::numeric_limits<double>::infinity()};
    if (share < 1.0)
        range = ggxReadsFittedLobes(roughness, lookups, mapped) ? fittedLobeExponentRange(roughness)
                                                               : lookupExponentRange(roughness * roughness, lookups);
    if (share > 0.0) {
        const ExponentRange mean = meanLobeExponentRange(roughness);
        range.sharpest = std::max(range.sharpest, mean.sharpest);
        range.widest = std::min(range.widest, mean.widest);
    }
    return range;
}

}  // namespace

std::vector<int> ggxEntries(double roughness, int lookups, int baseSize, bool mapped) {
    std::vector<int> out;
    if (!(roughness > 0.0) || lookups < 1) return out;
    const ExponentRange range = layerExponentRange(roughness, lookups, mapped);
    const int first = firstEntryMadeAhead(baseSize);
    const auto sharp = stackBlend(range.sharpest, baseSize);
    const auto wide = stackBlend(range.widest, baseSize);
    const int from = mapped ? first : std::max(first, sharp ? sharp->sharper : first);
    const int to = std::min((wide ? wide->wider : first) + kFootprintReach, kStackLast);
    for (int j = from; j <= to; ++j) out.push_back(j);
    return out;
}

int ggxHeadOnEntry(double roughness, int lookups, int baseSize) {
    if (!(roughness > 0.0) || lookups < 1) return -1;
    // Head-on, the lookups' lobes are the layer's own width; toward grazing the GGX lobe is
    // squeezed across the plane of incidence (2α·N·v) and its lookups sharpen past any stack.
    // The mean lobe (meanLobeShare) is read at every N·v from the stack: its sharpest too.
    const double alpha = roughness * roughness, share = meanLobeShare(roughness);
    double sharpest = share > 0.0 ? meanLobeExponentRange(roughness).sharpest : 0.0;
    const bool fitted = ggxReadsFittedLobes(roughness, lookups);
    if (share < 1.0 && fitted) sharpest = std::max(sharpest, fittedLobeSharpestHeadOn(roughness));
    for (int k = 0; share < 1.0 && !fitted && k < lookups; ++k) {
        const GgxLookup g = ggxLookup(alpha, glm::dvec3(0.0, 0.0, 1.0), ggxSequence(k, lookups));
        if (g.weight > 0.0) sharpest = std::max(sharpest, lookupExponent(g.pdf, lookups));
    }
    const auto sharp = stackBlend(sharpest, baseSize);
    return sharp && sharp->sharper >= firstEntryMadeAhead(baseSize) ? sharp->sharper : -1;
}

bool ggxReadsFittedLobes(double roughness, int lookups, bool mapped) {
    return !mapped && readsFittedLobes(roughness, lookups);
}

bool ggxLookupsHeld(double roughness, int lookups, int baseSize, bool mapped) {
    return !mapped && ggxHeadOnEntry(roughness, lookups, baseSize) >= 0;
}

int ggxLayerLookups(double roughness, int lookups, int baseSize, bool mapped, bool lightsShaded) {
    if (lookups <= 1 || mapped || !lightsShaded || !(roughness > 0.0)) return lookups;
    if (roughness * roughness < lightsApartMinAlpha(baseSize) || ggxLookupsHeld(roughness, lookups, baseSize)) return lookups;
    for (int fewer = lookups / 2; fewer >= 1; fewer /= 2)
        if (ggxLookupsHeld(roughness, fewer, baseSize)) return fewer;
    return lookups;
}

std::vector<int> remainderEntriesOf(double roughness, int lookups, int baseSize) {
    const int first = ggxHeadOnEntry(roughness, lookups, baseSize);
    std::vector<int> out;
    if (first < 0) return out;
    for (int j : ggxEntries(roughness, lookups, baseSize))
        if (j >= first) out.push_back(j);
    return out;
}

std::vector<int> lobesInUse(const Scene& scene, int baseSize) {
    std::set<int> entries;
    const int top = stackTop(baseSize);
    const LobesOfScene lobes = lobesOfScene(scene);
    for (const LambdaInUse& l : lobes.lambdas) {
        const auto blend = stackBlend(lambdaToExponent(l.lambda), baseSize);
        if (l.grazing) {
            // λ falls to 0 at grazing: every entry from the sharpest to this λ's, but none of
            // faces over 512 (a thin rim's near-mirror lobes would cost 150 MB and 10 s at base
            // 512; the rim reads the chain there).
            const int first = firstEntryMadeAhead(baseSize);
            const int last = std::min((blend ? blend->wider : top) + kFootprintReach, kStackLast);
            for (int j = first; j <= last; ++j) entries.insert(j);
        } else if (blend) {
            // A pixel's footprint only ever widens its lobe (footprintExponent): the entries
            // from the lobe's sharper neighbour to kFootprintReach past its wider one.
            for (int j = blend->sharper; j <= std::min(blend->wider + kFootprintReach, kStackLast); ++j) entries.insert(j);
        }
    }
    for (const GgxInUse& g : lobes.ggx) {
        const std::vector<int> range = ggxEntries(g.roughness, layerLookups(scene, g, baseSize), baseSize, g.mapped);
        entries.insert(range.begin(), range.end());
    }
    return {entries.begin(), entries.end()};
}

std::vector<int> lobesNear(const std::vector<int>& inUse, int baseSize, int reach) {
    const int first = firstEntryMadeAhead(baseSize);
    // Distance to the nearest entry in use (the wide end when none is), ascending, then index.
    std::vector<std::pair<int, int>> byDistance;
    for (int j = first; j <= kStackLast; ++j) {
        if (std::binary_search(inUse.begin(), inUse.end(), j)) continue;
        int distance = inUse.empty() ? kStackLast - j : kStackSlots;
        for (int k : inUse) distance = std::min(distance, std::abs(j - k));
        if (distance <= reach) byDistance.emplace_back(distance, j);
    }
    std::sort(byDistance.begin(), byDistance.end());
    std::vector<int> near;
    for (const auto& [distance, j] : byDistance) near.push_back(j);
    return near;
}

LobeStackEntry makeStackEntry(const PreparedEnvironment& environment, int index, bool remainder) {
    if (!environment.filter) throw std::logic_error("makeStackEntry: the environment has no Phong filter");
    if (remainder && !environment.remainderFilter)
        throw std::logic_error("makeStackEntry: the environment was prepared without its remainder");
    if (index < 1 || index > kStackLast) throw std::out_of_range("makeStackEntry: no stack entry " + std::to_string(index));
    LobeStackEntry lobe;
    lobe.index = index;
    lobe.exponent = stackExponent(index);
    lobe.remainder = remainder;
    const PhongFilter& filter = remainder ? *environment.remainderFilter : *environment.filter;
    const int size = stackEntryFaceSize(lobe.exponent, filter.baseSize());
    lobe.cube = std::make_shared<const CubeMap>(filter.filter(lobe.exponent, size));
    lobe.filter = environment.filter;
    return lobe;
}

bool ggxReadsRemainder(double roughness, int lookups, int baseSize, bool mapped, double widestLightRadius) {
    const double alpha = roughness * roughness;
    return alpha >= lightsApartMinAlpha(baseSize) && widestLightRadius <= alpha &&
           ggxLookupsHeld(roughness, lookups, baseSize, mapped);
}

double remainderReach(const Scene& scene, int baseSize) {
    double reach = 0.0;
    if (!scene.display.brightLights) return reach;
    for (const GgxInUse& g : lobesOfScene(scene).ggx)
        if (ggxReadsRemainder(g.roughness, layerLookups(scene, g, baseSize), baseSize, g.mapped, 0.0))
            reach = std::max(reach, g.roughness * g.roughness);
    return reach;
}

std::vector<int> remainderEntries(const Scene& scene, int baseSize, const std::vector<PointLight>& lights) {
    if (lights.empty() || !scene.display.brightLights) return {};
    std::set<int> entries;
    const double widest = widestLight(lights);
    for (const GgxInUse& g : lobesOfScene(scene).ggx) {
        const int lookups = layerLookups(scene, g, baseSize);
        if (!ggxReadsRemainder(g.roughness, lookups, baseSize, g.mapped, widest)) continue;
        const std::vector<int> range = remainderEntriesOf(g.roughness, lookups, baseSize);
        entries.insert(range.begin(), range.end());
    }
    return {entries.begin(), entries.end()};
}

std::vector<std::shared_ptr<const LobeStackEntry>> makeStackEntries(const PreparedEnvironment& environment, const Scene& scene) {
    std::vector<std::shared_ptr<const LobeStackEntry>> lobes;
    if (!environment.filter) return lobes;
    const int baseSize = environment.filter->baseSize();
    for (int index : lobesInUse(scene, baseSize))
        lobes.push_back(std::make_shared<const LobeStackEntry>(makeStackEntry(environment, index)));
    if (environment.remainderFilter)
        for (int index : remainderEntries(scene, baseSize, environment.lights))
            lobes.push_back(std::make_shared<const LobeStackEntry>(makeStackEntry(environment, index, true)));
    return lobes;
}

std::optional<Rgb> readLobeStack(const std::map<int, std::shared_ptr<const LobeStackEntry>>& entries, double exponent,
                                 int baseSize, const glm::vec3& direction) {
    const auto blend = stackBlend(exponent, baseSize);
    if (!blend) return std::nullopt;
    const auto sharper = entries.find(blend->sharper), wider = entries.find(blend->wider);
    if (sharper == entries.end()) return std::nullopt;
    const Rgb a = sharper->second->cube->sample(direction);
    if (blend->widerWeight == 0.0) return a;
    if (wider == entries.end()) return std::nullopt;
    const Rgb b = wider->second->cube->sample(direction);
    return a + static_cast<float>(blend->widerWeight) * (b - a);
}

LobeStackAtlas lobeStackAtlas(const std::vector<std::pair<int, int>>& entries, int maxWidth) {
    LobeStackAtlas atlas;
    atlas.placed.resize(entries.size());
    std::vector<std::size_t> order(entries.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return entries[a].second > entries[b].second; });
    int widest = 0;
    for (const auto& e : entries) widest = std::max(widest, 3 * (e.second + 2));
    const int width = std::max(maxWidth, widest);
    int x = 0, y = 0, shelf = 0;  // the current shelf starts at y and is `shelf` tall
    for (std::size_t i : order) {
        const int w = 3 * (entries[i].second + 2), h = 2 * (entries[i].second + 2);
        if (x + w > width) {
            y += shelf;
            x = 0;
            shelf = 0;
        }
        atlas.placed[i] = AtlasPlacement{entries[i].first, entries[i].second, x, y};
        x += w;
        shelf = std::max(shelf, h);
        atlas.width = std::max(atlas.width, x);
    }
    atlas.height = y + shelf;
    return atlas;
}

PackedLobeStack packLobeStack(const std::vector<std::pair<int, const CubeMap*>>& entries, int maxWidth) {
    std::vector<std::pair<int, int>> sizes;
    for (const auto& [index, cube] : entries) sizes.emplace_back(index, cube->size());
    PackedLobeStack packed;
    packed.atlas = lobeStackAtlas(sizes, maxWidth);
    const auto atlasWidth = static_cast<std::size_t>(packed.atlas.width);
    packed.texels.assign(atlasWidth * static_cast<std::size_t>(packed.atlas.height) * 3, 0.0f);
    packed.scales.assign(entries.size(), 1.0f);
    for (std::size_t e = 0; e < entries.size(); ++e) {
        const AtlasPlacement& at = packed.atlas.placed[e];
        const CubeMap& cube = *entries[e].second;
        const int stride = cube.size() + 2;
        float largest = 0.0f;
        for (Face f : kAllFaces)
            for (const Rgb& c : cube.faceStorage(f)) largest = std::max({largest, c.r, c.g, c.b});
        // 2^k with largest·2^k in [32704, 65408): exact, and within float's range for any entry
        // (the import keeps radiance in [0, 1e20], and a map at 1e-30 still has 2^99 of room).
        const float scale = largest > 0.0f ? std::exp2(std::floor(std::log2(65408.0f / largest))) : 1.0f;
        packed.scales[e] = 1.0f / scale;
        for (Face f : kAllFaces) {
            const std::vector<Rgb>& face = cube.faceStorage(f);  // (size + 2)² with the border, row 0 first
            const int fx = at.x + (static_cast<int>(f) % 3) * stride, fy = at.y + (static_cast<int>(f) / 3) * stride;
            for (int y = 0; y < stride; ++y)
                for (int x = 0; x < stride; ++x) {
                    const Rgb& c = face[static_cast<std::size_t>(y) * static_cast<std::size_t>(stride) + static_cast<std::size_t>(x)];
                    float* t = &packed.texels[(static_cast<std::size_t>(fy + y) * atlasWidth + static_cast<std::size_t>(fx + x)) * 3];
                    t[0] = c.r * scale;
                    t[1] = c.g * scale;
                    t[2] = c.b * scale;
                }
        }
    }
    return packed;
}

}  // namespace mipgloss
