// Lat-long -> cube: latLongToCube against the conversion it replaced (latLongToCubeQuadrature),
// measured in the same run on the same image (docs/latlong-conversion.md has the table):
//   LatLongToCube/<map>/<N>      each shared HDRI (tests/assets/env, 1024 × 512) to faces of 64,
//                                256 and 512
//   LatLongToCube/8k/<N>         an 8192 × 4096 map made from sunset.exr by bilinear upsampling
//   LatLongToCube/512x256/1024   sunset.exr box-filtered to 512 × 256, up to faces of 1024
// One iteration runs the new conversion, then the old; the time reported is the new one's.
// Counters: old_s (the old one's time), ratio (new/old), gather (1 when latLongMethod is Gather),
// ns_per_pixel and ns_per_texel (the new one's), mean_err and mean_err_old (|cube's weighted
// mean / image's − 1|, largest channel), rms_vs_old and max_vs_old (texel by texel, relative RMS
// as compareCubes and largest relative difference against max(old, 1 % of its mean)).
// Timings are printed, never asserted; the tests check correctness (test_latlong.cpp).
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/io/latlong.h"
#include "latlong_quadrature.h"
#include "cube_compare.h"

#include <OpenImageIO/imageio.h>

#include <benchmark/benchmark.h>

#include <glm/common.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

using mipgloss::test::maxRelDiff;

namespace {

constexpr double kPi = std::numbers::pi;

struct LatLong {
    int w = 0, h = 0;
    std::vector<Rgb> px;
    LatLongView view() const { return {w, h, px}; }
    const Rgb& at(int i, int j) const { return px[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)]; }
};

fs::path envDir() { return fs::path(__FILE__).parent_path().parent_path() / "assets" / "env"; }

LatLong readMap(const std::string& name) {
    LatLong ll;
    auto in = OIIO::ImageInput::open((envDir() / (name + ".exr")).string());
    if (!in) return ll;
    ll.w = in->spec().width;
    ll.h = in->spec().height;
    ll.px.resize(static_cast<std::size_t>(ll.w) * static_cast<std::size_t>(ll.h));
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, ll.px.data())) return {};
    for (Rgb& p : ll.px) p = glm::max(p, Rgb(0.0f));
    return ll;
}

// The image read bilinearly at (x, y) in pixel units (centres at integers), wrapping in x.
Rgb bilinear(const LatLong& ll, double x, double y) {
    y = std::clamp(y, 0.0, static_cast<double>(ll.h - 1));
    const int i0 = static_cast<int>(std::floor(x)), j0 = std::min(static_cast<int>(y), ll.h - 2);
    const float fx = static_cast<float>(x - i0), fy = static_cast<float>(y - j0);
    const int a = (i0 % ll.w + ll.w) % ll.w, b = (a + 1) % ll.w;
    return (ll.at(a, j0) * (1.0f - fx) + ll.at(b, j0) * fx) * (1.0f - fy) +
           (ll.at(a, j0 + 1) * (1.0f - fx) + ll.at(b, j0 + 1) * fx) * fy;
}

// sunset.exr bilinearly upsampled to w × h (a stand-in for an 8k download: the size, not the detail).
LatLong upsampled(const LatLong& src, int w, int h) {
    LatLong out{w, h, std::vector<Rgb>(static_cast<std::size_t>(w) * static_cast<std::size_t>(h))};
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            out.px[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)] =
                bilinear(src, (i + 0.5) * src.w / w - 0.5, (j + 0.5) * src.h / h - 0.5);
    return out;
}

// 2 × 2 box average.
LatLong halved(const LatLong& src) {
    LatLong out{src.w / 2, src.h / 2, {}};
    for (int j = 0; j < out.h; ++j)
        for (int i = 0; i < out.w; ++i)
            out.px.push_back(0.25f * (src.at(2 * i, 2 * j) + src.at(2 * i + 1, 2 * j) + src.at(2 * i, 2 * j + 1) +
                                      src.at(2 * i + 1, 2 * j + 1)));
    return out;
}

const LatLong& source(const std::string& name) {
    static std::map<std::string, LatLong> cache;
    auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    LatLong ll;
    if (name == "8k")
        ll = upsampled(source("sunset"), 8192, 4096);
    else if (name == "512x256")
        ll = halved(source("sunset"));
    else
        ll = readMap(name);
    return cache.emplace(name, std::move(ll)).first->second;
}

glm::dvec3 imageMean(const LatLong& ll) {
    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    for (int j = 0; j < ll.h; ++j) {
        const double w = std::cos(kPi * j / ll.h) - std::cos(kPi * (j + 1) / ll.h);
        glm::dvec3 row(0.0);
        for (int i = 0; i < ll.w; ++i) row += glm::dvec3(ll.at(i, j));
        sum += w * row;
        wsum += w * ll.w;
    }
    return sum / wsum;
}

double meanError(const CubeMap& cube, const glm::dvec3& want) {
    const glm::dvec3 got = cube.weightedMean();
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(got[c] / want[c] - 1.0));
    return worst;
}

using Clock = std::chrono::steady_clock;
double secondsBetween(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

void LatLongToCube(benchmark::State& state, const std::string& name, int faceSize) {
    const LatLong& ll = source(name);
    if (ll.px.empty()) {
        state.SkipWithError(("cannot read " + name).c_str());
        return;
    }
    double newSeconds = 0.0, oldSeconds = 0.0;
    CubeMap fresh, old;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        fresh = latLongToCube(ll.view(), faceSize);
        const auto t1 = Clock::now();
        old = latLongToCubeQuadrature(ll.view(), faceSize);
        const auto t2 = Clock::now();
        newSeconds += secondsBetween(t0, t1);
        oldSeconds += secondsBetween(t1, t2);
        state.SetIterationTime(secondsBetween(t0, t1));
    }
    const double iterations = static_cast<double>(state.iterations());
    const glm::dvec3 want = imageMean(ll);
    const LevelError e = compareCubes(fresh, old);
    state.counters["old_s"] = oldSeconds / iterations;
    state.counters["ratio"] = newSeconds / oldSeconds;
    state.counters["gather"] = latLongMethod(ll.w, ll.h, faceSize) == LatLongMethod::Gather ? 1.0 : 0.0;
    state.counters["ns_per_pixel"] = 1e9 * newSeconds / iterations / (static_cast<double>(ll.w) * ll.h);
    state.counters["ns_per_texel"] = 1e9 * newSeconds / iterations / (6.0 * faceSize * faceSize);
    state.counters["mean_err"] = meanError(fresh, want);
    state.counters["mean_err_old"] = meanError(old, want);
    state.counters["rms_vs_old"] = e.relRms;
    state.counters["max_vs_old"] = maxRelDiff(fresh, old);
}

// Registered at start-up: the eight maps at 64, 256, 512, then the 8k and the small map.
const bool registered = [] {
    std::vector<std::pair<std::string, int>> cases;
    for (const char* map : {"city", "courtyard", "forest", "interior", "night", "studio", "sunrise", "sunset"})
        for (int n : {64, 256, 512}) cases.emplace_back(map, n);
    for (int n : {64, 256, 512}) cases.emplace_back("8k", n);
    cases.emplace_back("512x256", 1024);
    for (const auto& [map, n] : cases)
        benchmark::RegisterBenchmark(("LatLongToCube/" + map + "/" + std::to_string(n)).c_str(),
                                     [map = map, n = n](benchmark::State& s) { LatLongToCube(s, map, n); })
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(1);
    return true;
}();

}  // namespace
