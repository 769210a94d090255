// The lobe stack: exact normalized Phong lobes of the environment at λ = j/8 (j = 1 … 63), so
// neighbouring lobes are 2^¼ apart in exponent (phong.h: n ∝ 4^−λ). Any lobe n between two
// entries is read as the blend of its neighbours with the weight that gives the blend the lobe's
// mean cosine (band 1, as chainLevelForExponent does for the chain's 4× steps): 0.2–0.5 % off the
// lobe on held-out maps where the chain's 4× steps are 10–58 % off (docs/lobe-stack.md). So any
// λ, per object or per fragment, reads its own lobe the moment it changes, with no settle step.
//
// Each entry is a cube of face stackEntryFaceSize(n) (builders.h: σ ≈ 3.6 texels, so bilinear reads
// between its centres stay within about 1 %) and is read at its base level only: the renderer
// packs the entries into one 2D atlas, each face with its one-texel border (lobeStackAtlas), and a
// fragment whose footprint is wider than its lobe reads the wider lobe the footprint makes
// (docs/lobe-stack.md), never a box mip. Entries are made only for the lobes the scene shows
// (lobesInUse) and, in the window, then every other, nearest first (lobesNear). Pure C++: the
// window makes them on its worker, `render` directly.
#pragma once

#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/scene.h"

#include <glm/vec3.hpp>

#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace mipgloss {

// Entries per chain level (λ unit): 8, so neighbours are 4^(1/8) = 2^¼ apart in exponent.
inline constexpr int kStackStepsPerLevel = 8;
// Entry indices run 1 … kStackLast; entry kStackLast (λ = 7.875) is n = 0, the uniform hemisphere
// (n(λ) reaches 0 at λ = 7.79). Index 0 (λ = 0) would be the mirror, which the chain's level 0 holds.
inline constexpr int kStackLast = 63;
inline constexpr int kStackSlots = kStackLast + 1;  // uniform array length in the shaders

double stackLambda(int index);    // index / 8
double stackExponent(int index);  // lambdaToExponent(index / 8)
// The sharpest entry a base of face N makes: the first whose lobe its cube holds at full width
// (stackEntryHoldsLobe: √(32 n) ≤ min(2N, 1024)). Lobes sharper than it (and the mirror) are read
// from the chain.
int stackTop(int baseSize);

// Lobe n as mix(entry[sharper], entry[wider], widerWeight). With u = 1/(n + 2) = 1 − Λ(n) (the
// lobe's mean cosine is Λ = (n+1)/(n+2)), the weight is (u − u_sharper) / (u_wider − u_sharper),
// so the blend has n's mean cosine. None for n above stackExponent(stackTop), for ∞ and for NaN.
struct StackBlend {
    int sharper = 0;
    int wider = 0;
    double widerWeight = 0.0;
};
std::optional<StackBlend> stackBlend(double exponent, int baseSize);

// The lobe a pixel shows when its lookup direction spans the footprint dx, dy (the direction's
// change to the next pixel across and down, radians): the lobe's mean of 1 − cos θ plus the
// footprint's, u = 1/(n+2) + (|dx|² + |dy|²)/24 (a box of sides dx, dy has second moment
// (|dx|² + |dy|²)/12 and 1 − cos θ ≈ θ²/2), n' = 1/u − 2. The same formula is in lobe_stack.glsl.
double footprintExponent(double exponent, double dx, double dy);

struct LobeStackEntry {
    int index = 0;            // the stack entry (λ = index / 8)
    double exponent = 0.0;    // the lobe it holds, stackExponent(index)
    // Made from the smooth remainder (bright_lights.h, withoutBrightLights) instead of the whole
    // environment: what a GGX layer that shades the bright lights apart reads (remainderEntries).
    bool remainder = false;
    std::shared_ptr<const CubeMap> cube;
    std::shared_ptr<const PhongFilter> filter;  // the environment it was made from (its whole filter, either kind)
};

// Entries of both kinds in one map or atlas: a remainder entry's key is its index + kStackSlots.
inline constexpr int kRemainderKeyOffset = kStackSlots;
inline int stackKey(int index, bool remainder) { return remainder ? index + kRemainderKeyOffset : index; }
inline int stackKey(const LobeStackEntry& entry) { return stackKey(entry.index, entry.remainder); }
inline bool isRemainderKey(int key) { return key >= kRemainderKeyOffset; }
inline int stackKeyIndex(int key) { return isRemainderKey(key) ? key - kRemainderKeyOffset : key; }

// The least α at which a GGX layer shades the bright lights apart: α = 2/N for a base of face N,
// a half-vector lobe one texel wide (a light stands for texels of about 2/N rad). A sharper layer
// reads the lights in the environment, through the whole stack or the chain: its lookups, sharper
// than a texel, would subtract a light's disc from bilinear texels that do not hold it. Measured
// (docs/material-truth.md, "The near-mirror range"): from 4/N, r 0.1–0.125 at face 128 and r 0.1 at
// 256 went from 7–105 % to 0.6–21 % on sunrise and studio; r 0.05 at 256 (below both) blew up to
// 45–83 % when every layer shaded them apart.
inline double lightsApartMinAlpha(int baseSize) { return 2.0 / static_cast<double>(baseSize > 1 ? baseSize : 1); }

// How many entries past a lobe's wider neighbour the scene asks for, for pixels whose footprint
// widens the lobe (footprintExponent): 4, half a level, holds lobes down to 2^(−5/4) ≈ 0.42 of n.
// Pixels the footprint would widen further show that widest lobe (lobe_stack.glsl,
// footprintLimitedExponent), so the picture does not depend on which other entries are made; the
// AOV does not call them exact. On a 512² sphere
// at n = 1024, 94 % of the pixels are widened by more than 1 % (test_settled_picture.cpp).
inline constexpr int kFootprintReach = 4;
// The grazing option and the window's prefetch (lobesNear) ask for no entry whose cube face is
// larger than this: the near-mirror entries of a base of 512 or more (faces 527–1024) would take
// 153 MB and 12 s; they are made only for a lobe in use.
inline constexpr int kGrazingLargestFace = 512;

// The entries the scene shows, ascending: for the λ of every visible object (not a mirror, not
// using the irradiance map) and of the background when shown and blurred, the two entries its
// lobe blends and kFootprintReach wider ones; for an object with the grazing option every entry
// from stackTop (or the first of faces up to kGrazingLargestFace) to its own λ's and those.
// Empty when the environment's builder is not the default (the other builders are there to be
// compared as they are). `baseSize`: the environment's face size.
std::vector<int> lobesInUse(const Scene& scene, int baseSize);
// The entries a GGX layer of `roughness` reads with `lookups` lookups per fragment (ggx_sampling.h,
// lookupExponentRange): from its sharpest lookup's sharper neighbour (never before
// firstEntryMadeAhead: sharper lookups read the chain) to kFootprintReach past its widest one's
// wider neighbour, ascending. With a roughness map (`mapped`), any roughness up to it: every entry
// from firstEntryMadeAhead on. None for the mirror (roughness 0).
std::vector<int> ggxEntries(double roughness, int lookups, int baseSize, bool mapped = false);
// The stack entry holding the sharpest lookup of a GGX layer seen head-on (its sharper
// neighbour), when the stack makes it (from firstEntryMadeAhead on); −1 otherwise (near-mirror
// layers: sharper than the stack).
int ggxHeadOnEntry(double roughness, int lookups, int baseSize);
// Whether the stack holds such a layer's lookups, so they need never read the chain: true when
// ggxHeadOnEntry is made; false with a roughness map (any fragment may be sharper). object.frag's
// readGgx then reads the atlas alone, in its own loop: a lookup sharper than the layer's first
// entry (toward grazing, where the GGX lobe is squeezed across the plane of incidence, 2α·N·v)
// reads that entry.
bool ggxLookupsHeld(double roughness, int lookups, int baseSize, bool mapped = false);
// Whether a GGX layer's `lookups` are the fitted lobes (ggx_fitted_lobes.h, readsFittedLobes)
// rather than its visible normals, where the stack holds them (ggxLookupsHeld): not with a
// roughness map (its fragments read the chain, at any roughness). The entries it reads, its
// head-on entry and whether the stack holds it are then the fitted lobes' (ggxEntries, ggxHeadOnEntry).
bool ggxReadsFittedLobes(double roughness, int lookups, bool mapped = false);
// The lookups a GGX layer reads per fragment, of the display's `lookups` (K): K, unless the layer
// shades the bright lights apart (`lightsShaded` and α ≥ lightsApartMinAlpha) and the stack does
// not hold its K lookups (ggxLookupsHeld): then the most of K/2, K/4, …, 1 that it holds (K when
// it holds none; with a roughness map, K). Why: each such lookup takes the lights in its lobe out
// of what it reads (object.frag, lightsThrough, as a disc through the lookup's Phong lobe). A
// lookup sharper than the stack's first entry reads the chain's base instead, whose bilinear texels
// hold a light otherwise than that disc does: one pixel in a few hundred of a polished layer (r
// 0.125–0.15 at face 128, 0.1 at 256) read a sun or a soft box 5–40 % wrong. Fewer, wider lookups
// read entries whose lobe is the one subtracted. Chosen on `city` (docs/material-truth.md, "How
// many lookups a polished layer reads"); it also halves those layers' frame.
int ggxLayerLookups(double roughness, int lookups, int baseSize, bool mapped, bool lightsShaded);
// The remainder entries such a layer reads: ggxEntries from ggxHeadOnEntry on (none when not
// held). Its lookups sharper than that, toward grazing, read that entry: the sharp entries
// (faces up to 512, seconds each) are made once, for the whole environment, not twice.
std::vector<int> remainderEntriesOf(double roughness, int lookups, int baseSize);
// Whether a GGX layer's lookups read the remainder entries (the environment without its bright
// lights) instead of the whole environment less each light through each lookup. Both give
// lookups + the lights through the exact BRDF; they differ in where the lights' model (each a disc
// at its texels' mean, bright_lights.h) shows. Subtracted from each lookup, the model's error
// cancels wherever a lookup's lobe blurs the light as the BRDF does; with the remainder it is
// shown whole. So the remainder is read only where every light is no wider than the layer's
// half-vector lobe, ρ ≤ α (its reflected lobe is about 2α wide), and the layer shades the lights
// apart (α ≥ lightsApartMinAlpha) and its lookups are held (ggxLookupsHeld). Measured against the
// truth in docs/material-truth.md ("Lights taken out").
bool ggxReadsRemainder(double roughness, int lookups, int baseSize, bool mapped, double widestLightRadius);
// The widest α of the scene's GGX layers that would read the remainder if the lights were narrow
// enough (every condition of ggxReadsRemainder but the lights'); 0 when none would.
double remainderReach(const Scene& scene, int baseSize);
// The remainder entries the scene's GGX layers read (ascending indices, not keys):
// remainderEntriesOf every visible layer that reads them (ggxReadsRemainder), when the display
// shades the lights.
std::vector<int> remainderEntries(const Scene& scene, int baseSize, const std::vector<PointLight>& lights);
// The first entry of a face up to kGrazingLargestFace: where what is made ahead begins.
int firstEntryMadeAhead(int baseSize);
// The entries within `reach` steps of those in use (`inUse`, ascending: lobesInUse), not in use and
// from firstEntryMadeAhead on, nearest first: what the window makes after the lobes in use (by
// default the whole stack), so a slider moving anywhere reads exact lobes at once. With nothing in
// use, every such entry from the wide end.
std::vector<int> lobesNear(const std::vector<int>& inUse, int baseSize, int reach = kStackSlots);

// Entry `index` from the environment's filter, or with `remainder` from its remainder's (prepared
// with ChainNeeds::remainder). The environment must have been prepared with the default builder
// (filter set). Throws Cancelled if asked.
LobeStackEntry makeStackEntry(const PreparedEnvironment& environment, int index, bool remainder = false);

// Every entry the scene shows (lobesInUse, then the remainderEntries when the environment has its
// remainder), made now, for `mipgloss render` and the tests (the window makes them on its worker).
// Empty when the environment has no filter.
std::vector<std::shared_ptr<const LobeStackEntry>> makeStackEntries(const PreparedEnvironment& environment, const Scene& scene);

// Lobe n at `direction` as the renderer reads it from these entries: each entry bilinear between
// its face's texel centres (CubeMap::sample), the neighbours blended by stackBlend. The CPU twin
// of lobe_stack.glsl's stackRead, for tests and the bench; empty when an entry it needs is missing.
std::optional<Rgb> readLobeStack(const std::map<int, std::shared_ptr<const LobeStackEntry>>& entries, double exponent,
                                 int baseSize, const glm::vec3& direction);

// Where the renderer's 2D atlas holds each entry: a block of 3 × 2 faces, each face (size + 2)²
// texels with its border, face f at column f % 3 and row f / 3 of the block; blocks shelf-packed,
// largest first, in rows no wider than `maxWidth` (or the widest block).
struct AtlasPlacement {
    int index = 0;
    int size = 0;  // face size without border
    int x = 0, y = 0;  // the block's first texel
};
struct LobeStackAtlas {
    int width = 0, height = 0;
    std::vector<AtlasPlacement> placed;  // one per entry given, in the order given
    double megabytes(int bytesPerTexel) const { return static_cast<double>(width) * height * bytesPerTexel / 1e6; }
};
// `entries`: (index, face size) pairs.
LobeStackAtlas lobeStackAtlas(const std::vector<std::pair<int, int>>& entries, int maxWidth = 4096);

// The entries' texels as the renderer sends them (GL_RGB9_E5: a shared exponent, 9-bit mantissas,
// each texel's largest channel within 2^-10, the others within 2^-10 of it): every face with its
// border at its place in `atlas`, RGB, row 0 first, zero between blocks; each entry multiplied by
// the power of two 2^k that brings its largest value into [32704, 65408), just under the format's
// 65408, so no environment's absolute scale matters (docs/lobe-stack.md). The shader multiplies
// it back by `scales` (one per entry given, 2^-k; 1 for an entry that is all zero).
struct PackedLobeStack {
    LobeStackAtlas atlas;
    std::vector<float> texels;
    std::vector<float> scales;
};
// `entries`: (index, cube) pairs, cubes with their one-texel borders filled (CubeMap::faceStorage).
PackedLobeStack packLobeStack(const std::vector<std::pair<int, const CubeMap*>>& entries, int maxWidth = 4096);

}  // namespace mipgloss
