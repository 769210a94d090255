#include "mipgloss/ibl/builders.h"

#include "lobe_filter.h"
#include "mipgloss/ibl/parallel.h"
#include "mipgloss/ibl/phong.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mipgloss {

namespace {

// The stack entries' size limits: at least 16 (32 below n = 1), at most twice the base and 1024.
constexpr int kMinStackEntryFace = 16;
// Below n = 1 the kernel (R·ω)^n is nearly a step at the horizon (0.76 at R·ω = 0.01 for n = 0.06),
// so a small bright source leaves an edge in the lobe, which 16² blurs: interior.exr at n = 0.06
// read 2.9 % off at 16², 1.8 % at 32², for 0.05 s per entry (docs/lobe-stack.md).
constexpr int kMinSteepStackEntryFace = 32;
constexpr int kMaxStackEntryFace = 1024;
int stackEntryFaceCap(int baseSize) { return std::min(2 * std::max(baseSize, 1), kMaxStackEntryFace); }

// Weights of an area-proportional box from `from` texels to `to` texels along one axis:
// destination texel d covers [d·from/to, (d+1)·from/to) of the source.
struct AxisWeights {
    std::vector<int> first;                 // first source texel per destination texel
    std::vector<std::vector<float>> weight;  // normalized weights from `first` on
};
AxisWeights boxWeights(int from, int to) {
    AxisWeights w;
    w.first.resize(static_cast<std::size_t>(to));
    w.weight.resize(static_cast<std::size_t>(to));
    const double ratio = static_cast<double>(from) / to;
    for (int d = 0; d < to; ++d) {
        const double a = d * ratio, b = (d + 1) * ratio;
        const int i0 = static_cast<int>(std::floor(a));
        const int i1 = std::min(from - 1, static_cast<int>(std::ceil(b)) - 1);
        w.first[static_cast<std::size_t>(d)] = i0;
        for (int i = i0; i <= i1; ++i) {
            const double overlap = std::min<double>(b, i + 1) - std::max<double>(a, i);
            w.weight[static_cast<std::size_t>(d)].push_back(static_cast<float>(overlap / ratio));
        }
    }
    return w;
}

// Area-proportional box resampling of a row-major RGB image (2×2 averaging when halving).
std::vector<Rgb> boxResample(const std::vector<Rgb>& src, int srcSize, int dstSize) {
    const AxisWeights w = boxWeights(srcSize, dstSize);
    std::vector<Rgb> dst(static_cast<std::size_t>(dstSize) * static_cast<std::size_t>(dstSize));
    parallelFor(0, dstSize, [&](int y) {
        const auto& wy = w.weight[static_cast<std::size_t>(y)];
        const int y0 = w.first[static_cast<std::size_t>(y)];
        for (int x = 0; x < dstSize; ++x) {
            const auto& wx = w.weight[static_cast<std::size_t>(x)];
            const int x0 = w.first[static_cast<std::size_t>(x)];
            glm::dvec3 sum(0.0);
            for (std::size_t j = 0; j < wy.size(); ++j)
                for (std::size_t i = 0; i < wx.size(); ++i)
                    sum += static_cast<double>(wy[j] * wx[i]) *
                           glm::dvec3(src[static_cast<std::size_t>(y0 + static_cast<int>(j)) * srcSize +
                                          static_cast<std::size_t>(x0 + static_cast<int>(i))]);
            dst[static_cast<std::size_t>(y) * dstSize + static_cast<std::size_t>(x)] = Rgb(sum);
        }
    });
    return dst;
}

std::vector<Rgb> faceImage(const CubeMap& c, Face f) {
    const int m = c.size();
    std::vector<Rgb> img(static_cast<std::size_t>(m) * static_cast<std::size_t>(m));
    for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x) img[static_cast<std::size_t>(y) * m + static_cast<std::size_t>(x)] = c.at(f, x, y);
    return img;
}


class BuildProgress {
public:
    explicit BuildProgress(const BuildOptions& o) : fn_(o.progress) {}
    void report(float fraction) const { reportProgress(fn_, "build", fraction); }

private:
    const mipgloss::Progress& fn_;
};

bool filtered(const BuildOptions& o, int baseSize, int level) {
    return level <= lastReadLevel(baseSize) && (o.lastFilteredLevel < 0 || level <= o.lastFilteredLevel);
}

CubeMap seamlessCopy(const CubeMap& c) {
    CubeMap copy = c;
    copy.makeSeamless();
    return copy;
}


}  // namespace

const char* builderName(Builder builder) {
    switch (builder) {
        case Builder::Phong: return "phong";
        case Builder::Box: return "box";
        case Builder::Paper: return "paper";
        case Builder::Reference: return "reference";
    }
    return "phong";
}

bool parseBuilder(std::string_view text, Builder& out) {
    for (Builder b : kAllBuilders) {
        if (text == builderName(b)) {
            out = b;
            return true;
        }
    }
    return false;
}

MipChain buildChain(const CubeMap& base, Builder builder, const BuildOptions& options) {
    switch (builder) {
        case Builder::Box: return buildBoxChain(base, options);
        case Builder::Paper: return buildPaperChain(base, options);
        case Builder::Phong: return buildPhongChain(base, options);
        case Builder::Reference: return buildReferenceChain(base, options);
    }
    return buildPhongChain(base, options);
}


namespace {

// The paper's enlarged image for face f (Figure 2): the face in the centre of a 3M×3M image, its
// four neighbours unfolded around it, the four corner blocks filled with a copy of the opposite
// face (the paper copies "one of the available cube face textures"; which one it does not say).
std::vector<Rgb> enlargedImage(const CubeMap& c, Face f) {
    const int m = c.size();
    const int big = 3 * m;
    const FaceFrame& fr = faceFrame(f);
    const Face opposite = static_cast<Face>(static_cast<int>(f) ^ 1);
    std::vector<Rgb> img(static_cast<std::size_t>(big) * static_cast<std::size_t>(big));
    for (int by = 0; by < big; ++by) {
        for (int bx = 0; bx < big; ++bx) {
            const int x = bx - m, y = by - m;
            const bool inX = x >= 0 && x < m, inY = y >= 0 && y < m;
            Rgb v;
            if (inX && inY) {
                v = c.at(f, x, y);
            } else if (!inX && !inY) {
                v = c.at(opposite, (x + m) % m, (y + m) % m);
            } else {
                // Unfold the neighbour about the shared edge: a point δ beyond the edge in the
                // plane is δ along the neighbour face, away from the edge (exact, no perspective).
                const float sc = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(m) - 1.0f;
                const float tc = 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(m) - 1.0f;
                glm::vec3 q;
                if (!inX) {
                    const float side = sc < 0.0f ? -1.0f : 1.0f;
                    const float delta = std::fabs(sc) - 1.0f;
                    q = (1.0f - delta) * fr.axis + side * fr.u + tc * fr.v;
                } else {
                    const float side = tc < 0.0f ? -1.0f : 1.0f;
                    const float delta = std::fabs(tc) - 1.0f;
                    q = (1.0f - delta) * fr.axis + sc * fr.u + side * fr.v;
                }
                const TexelRef t = texelOf(directionToFace(q), m);
                v = c.at(t.face, t.x, t.y);
            }
            img[static_cast<std::size_t>(by) * big + static_cast<std::size_t>(bx)] = v;
        }
    }
    return img;
}

}  // namespace

MipChain buildPaperChain(const CubeMap& base, const BuildOptions& options) {
    const BuildProgress progress(options);
    const int n = base.size();
    const int levels = fullChainLevelCount(n);
    MipChain chain;
    for (int k = 0; k < levels; ++k) chain.levels.emplace_back(levelSize(n, k));
    for (Face f : kAllFaces) {
        progress.report(static_cast<float>(f) / 6.0f);
        std::vector<Rgb> big = enlargedImage(base, f);
        for (int k = 0; k < levels; ++k) {
            const int m = levelSize(n, k);
            if (k > 0) big = boxResample(big, 3 * levelSize(n, k - 1), 3 * m);
            // Cut out the centre with its one-texel border: the paper's texture border.
            for (int y = -1; y <= m; ++y)
                for (int x = -1; x <= m; ++x)
                    chain.levels[static_cast<std::size_t>(k)].at(f, x, y) =
                        big[static_cast<std::size_t>(y + m) * (3 * m) + static_cast<std::size_t>(x + m)];
        }
    }
    progress.report(1.0f);
    return chain;
}

namespace {

// The chain shape shared by the builders: level 0 is the base, each level the scene
// can reach is `filterLevel(k)`, and levels beyond BuildOptions::lastFilteredLevel get a cheap box
// step from the level before.
template <class FilterLevel>
MipChain buildConvolvedChain(const CubeMap& base, const BuildOptions& options, FilterLevel&& filterLevel) {
    const BuildProgress progress(options);
    const int n = base.size();
    const int levels = fullChainLevelCount(n);
    MipChain chain;
    chain.levels.push_back(seamlessCopy(base));
    for (int k = 1; k < levels; ++k) {
        progress.report(static_cast<float>(k - 1) / static_cast<float>(levels - 1));
        chain.levels.push_back(filtered(options, n, k) ? filterLevel(k)
                                                    : boxDownsample(chain.levels.back(), levelSize(n, k)));
    }
    progress.report(1.0f);
    return chain;
}

}  // namespace


CubeMap boxDownsample(const CubeMap& src, int dstSize) {
    CubeMap dst(dstSize);
    for (Face f : kAllFaces) {
        const std::vector<Rgb> img = boxResample(faceImage(src, f), src.size(), dstSize);
        for (int y = 0; y < dstSize; ++y)
            for (int x = 0; x < dstSize; ++x)
                dst.at(f, x, y) = img[static_cast<std::size_t>(y) * dstSize + static_cast<std::size_t>(x)];
    }
    dst.makeSeamless();
    return dst;
}

// Every level a box step from the one before: the shared chain with nothing filtered.
MipChain buildBoxChain(const CubeMap& base, const BuildOptions& options) {
    BuildOptions boxOnly = options;
    boxOnly.lastFilteredLevel = 0;
    return buildConvolvedChain(base, boxOnly, [](int) -> CubeMap { return {}; });
}

struct PhongFilter::Impl {
    int baseSize = 0;
    PhongShortcuts shortcuts;
    std::vector<detail::LobeSource> sources;  // the energy pyramid, finest first
};

PhongFilter::PhongFilter(const CubeMap& base, const PhongShortcuts& shortcuts) : impl_(std::make_unique<Impl>()) {
    impl_->baseSize = base.size();
    impl_->shortcuts = shortcuts;
    impl_->sources.push_back(detail::baseSource(base));
    // The pyramid needs exact 2×2 nesting: a non-power-of-two base coarsens only while its size
    // stays even, and lobes then filter that finer (slower, as exact) source. No level below
    // kMinSourceSize is made: filter() never uses one.
    while (impl_->sources.back().size % 2 == 0 && impl_->sources.back().size / 2 >= shortcuts.minSourceSize)
        impl_->sources.push_back(detail::coarsenSource(impl_->sources.back()));
}

PhongFilter::~PhongFilter() = default;

int PhongFilter::baseSize() const { return impl_->baseSize; }

CubeMap PhongFilter::filter(double exponent, int size) const {
    // The coarsest pyramid level whose texels are at most about half the lobe's σ (a face of
    // √(8n) texels: 1.57/√(8n) rad = 0.55 σ), and never below 32²: measured in
    // docs/chain-schedule.md, these sources cost under 0.3 % of the between-centres error.
    const PhongShortcuts& cut = impl_->shortcuts;
    const double wanted = std::max(static_cast<double>(cut.minSourceSize), std::ceil(std::sqrt(cut.sourceFactor * exponent)));
    std::size_t j = 0;
    while (j + 1 < impl_->sources.size() && impl_->sources[j + 1].size >= wanted) ++j;
    // Large faces are filtered at half size and interpolated (σ = 3.6 texels at the level is 1.8
    // at half size, sampled far above its Nyquist rate); smaller ones directly.
    if (cut.upsampleFromSize > 0 && size >= cut.upsampleFromSize && size % 2 == 0)
        return detail::convolveUpsampled(impl_->sources[j], exponent, size, cut.cutoff);
    return detail::convolve(impl_->sources[j], exponent, size, cut.cutoff);
}

int stackEntryFaceSize(double exponent, int baseSize) {
    const int cap = stackEntryFaceCap(baseSize);
    const double wanted = std::ceil(std::sqrt(32.0 * std::max(exponent, 0.0)));
    const int floor = exponent < 1.0 ? kMinSteepStackEntryFace : kMinStackEntryFace;
    return static_cast<int>(std::clamp(wanted, static_cast<double>(floor), static_cast<double>(std::max(cap, floor))));
}

bool stackEntryHoldsLobe(double exponent, int baseSize) {
    return std::isfinite(exponent) && std::sqrt(32.0 * std::max(exponent, 0.0)) <= stackEntryFaceCap(baseSize);
}

MipChain buildPhongChain(const CubeMap& base, const BuildOptions& options, const PhongFilter* given) {
    const int n = base.size();
    std::unique_ptr<PhongFilter> own;  // made on the first filtered level when none is given
    return buildConvolvedChain(base, options, [&](int k) {
        if (!given) {
            if (!own) own = std::make_unique<PhongFilter>(base);
            given = own.get();
        }
        return given->filter(levelExponent(n, k), levelSize(n, k));
    });
}

MipChain buildReferenceChain(const CubeMap& base, const BuildOptions& options) {
    const int n = base.size();
    return buildConvolvedChain(base, options, [&](int k) {
        return referenceConvolution(base, levelExponent(n, k), levelSize(n, k));
    });
}

std::vector<Rgb> referenceLobeAt(const CubeMap& base, double exponent, const std::vector<glm::vec3>& directions,
                                 double cutoff) {
    const detail::ExactLobe lobe(base, exponent, cutoff);
    std::vector<Rgb> out(directions.size());
    parallelFor(0, static_cast<int>(directions.size()), [&](int i) {
        out[static_cast<std::size_t>(i)] = lobe.at(glm::dvec3(directions[static_cast<std::size_t>(i)]));
    });
    return out;
}

CubeMap referenceConvolution(const CubeMap& base, double exponent, int outSize, double cutoff) {
    return detail::convolveExact(base, exponent, outSize, cutoff);
}

}  // namespace mipgloss
