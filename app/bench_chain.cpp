// `mipgloss bench`: each builder's chain timed and measured against the exact Phong lobes (its
// usage: mipgloss_cli.cpp's kUsage).
#include "bench_chain.h"

#include "cli_report.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"

#ifdef MIPGLOSS_WITH_PLOT
#include "bench_plot.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace mipgloss::app {

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// The lobe chain level k stands for, level 0 (the mirror) counted as N²/32: a finite end for the
// best-fit search's range.
double heldExponent(int baseSize, int level) {
    if (level == 0) return static_cast<double>(baseSize) * baseSize / 32.0;
    return levelExponent(baseSize, level);
}

// The exact lobe n at `dirs` from a copy of the base reduced (area-proportional box) until its
// texels are about σ/16 of the lobe (face ≥ 25·√n, ≥ 32): the best-fit search only, where wide
// lobes from the full base would cost minutes. The bench prints how far this truth is from the
// full base's at the lobes the renderer means; the best fit's printed error is against the full base.
std::vector<Rgb> reducedTruth(const CubeMap& base, double exponent, const std::vector<glm::vec3>& dirs,
                              std::map<int, CubeMap>& reduced) {
    const double wanted = std::max(32.0, 25.0 * std::sqrt(exponent));
    int s = base.size();
    while (s % 2 == 0 && s / 2 >= wanted) s /= 2;
    if (s == base.size()) return referenceLobeAt(base, exponent, dirs);
    auto it = reduced.find(s);
    if (it == reduced.end()) it = reduced.emplace(s, boxDownsample(base, s)).first;
    return referenceLobeAt(it->second, exponent, dirs);
}

// The lobe in [lo, hi] whose exact convolution (reducedTruth) is closest to `read` in relative
// RMS: golden-section search on log n (metrics.h), to 1 % in n.
double bestFitExponent(const std::vector<Rgb>& read, const CubeMap& base, const std::vector<glm::vec3>& dirs,
                       double lo, double hi, std::map<int, CubeMap>& reduced) {
    auto cost = [&](double logN) { return relativeRms(read, reducedTruth(base, std::exp(logN), dirs, reduced)); };
    return std::exp(goldenSectionMinimum(cost, std::log(lo), std::log(hi), 0.01));
}

std::string fmtExponent(double n) {
    char buf[32];
    if (n >= 100) std::snprintf(buf, sizeof buf, "%.0f", n);
    else std::snprintf(buf, sizeof buf, "%.3g", n);
    return buf;
}

struct BenchRow {
    std::string env;
    int size = 0;
    Builder builder = Builder::Phong;
    double seconds = 0.0, ratioToBox = 0.0;
    double worstCentre = 0.0, worstRead = 0.0;
    double worstHalfMeant = 0.0, worstHalfFit = 0.0;
};

}  // namespace

int runBench(const BenchOptions& options) {
#ifndef MIPGLOSS_WITH_PLOT
    if (!options.plot.empty())
        throw UsageError("--plot needs Qt (Qt6 Gui and Svg); this mipgloss was built without them "
                         "(configure with MIPGLOSS_BUILD_UI=ON, or with qt6-svg-dev installed)");
#endif
    const std::vector<fs::path>& envs = options.environments;
    const std::vector<int>& sizes = options.sizes;
    const std::vector<Builder>& builders = options.builders;
    const int repeat = options.repeat, directionCount = options.directions;
    const bool halfLevels = options.halfLevels, shortcuts = options.shortcuts, centres = options.centres;
    const fs::path& plot = options.plot;
    const std::vector<glm::vec3> dirs = uniformDirections(directionCount);
    std::printf("# mipgloss bench: chain build time and error against the exact normalized Phong convolution\n");
    std::printf("# time = median of %d builds on %d threads; x box = time / box builder's time\n", repeat,
                static_cast<int>(std::thread::hardware_concurrency()));
    std::printf("# per read level k (n_k = levelExponent(N,k)), in %%: centre = relative RMS at the level's texel\n");
    std::printf("#   centres (compareCubes against referenceConvolution, solid-angle weighted); read = relative RMS\n");
    std::printf("#   of the chain read between centres (sampleChain: seamless bilinear) at %d uniform directions\n",
                directionCount);
    if (halfLevels) {
        std::printf("# half levels, lod k+0.5: the trilinear blend against the lobe the renderer means there\n");
        std::printf("#   (n with chainLevelForExponent(n,N) = k+0.5) and against its best-fitting single lobe\n");
        std::printf("#   (phong only; golden-section search on log n, error printed against the full base)\n");
    }
    std::fflush(stdout);

    std::vector<BenchRow> rows;
    for (int size : sizes) {
        std::vector<std::pair<std::string, CubeMap>> bases;
        if (envs.empty()) {
            bases.emplace_back("default", loadDefaultEnvironment(size).cube);
        } else {
            for (const fs::path& e : envs) {
                ImportOptions o;
                o.faceSize = size;
                bases.emplace_back(e.stem().string(), loadEnvironment(e, o).cube);
            }
        }
        const int last = lastReadLevel(size);
        for (const auto& [name, base] : bases) {
            // The truths, shared by every builder: the exact level at its texel centres, the exact
            // lobe at the directions (what readError computes, once per exponent here).
            auto t0 = std::chrono::steady_clock::now();
            // Without centre errors no reference chain is built (at 1024 it takes the better part
            // of an hour here); the read errors need only the lobes at the directions.
            const MipChain truth = centres ? buildReferenceChain(base) : MipChain{};
            const double refTime = secondsSince(t0);
            t0 = std::chrono::steady_clock::now();
            std::vector<std::vector<Rgb>> levelTruth(static_cast<std::size_t>(last) + 1);
            for (int k = 1; k <= last; ++k)
                levelTruth[static_cast<std::size_t>(k)] = referenceLobeAt(base, levelExponent(size, k), dirs);
            std::vector<double> halfExponent;
            std::vector<std::vector<Rgb>> halfTruth;
            if (halfLevels)
                for (int k = 0; k < last; ++k) {
                    halfExponent.push_back(exponentForChainLevel(k + 0.5, size));
                    halfTruth.push_back(referenceLobeAt(base, halfExponent.back(), dirs));
                }
            const double truthTime = secondsSince(t0);
            std::map<int, CubeMap> reduced;  // the base box-reduced, by face size (best-fit search)
            double reducedOff = 0.0;         // reducedTruth against the full base's truth
            for (std::size_t k = 0; k < halfTruth.size(); ++k)
                reducedOff = std::max(reducedOff, relativeRms(reducedTruth(base, halfExponent[k], dirs, reduced), halfTruth[k]));
            std::printf("\n## %s, face %d: read levels 1..%d; reference chain %.2f s, lobes at the directions %.2f s\n",
                        name.c_str(), size, last, refTime, truthTime);
            if (halfLevels)
                std::printf("(best-fit search: base reduced to texels of ~sigma/16, which at the meant "
                            "lobes is within %.3f%% of the full base; fit errors printed against the full base)\n", 100 * reducedOff);
            std::printf("%-9s %8s %7s |", "level", "", "");
            for (int k = 1; k <= last; ++k) std::printf(" %11s", ("L" + std::to_string(k)).c_str());
            std::printf(" | %s\n", "worst");
            std::printf("%-9s %8s %7s |", "n_k", "", "");
            for (int k = 1; k <= last; ++k) std::printf(" %11s", fmtExponent(levelExponent(size, k)).c_str());
            std::printf(" |\n");
            std::printf("%-9s %8s %7s |", "builder", "time s", "x box");
            for (int k = 1; k <= last; ++k) std::printf(" %11s", "cent/read%");
            std::printf(" | %s\n", "cent/read%");
            std::fflush(stdout);

            std::map<Builder, double> times;
            std::map<Builder, MipChain> chains;
            std::vector<Builder> timed = builders;
            if (std::find(timed.begin(), timed.end(), Builder::Box) == timed.end()) timed.push_back(Builder::Box);
            for (const Builder m : timed) {
                std::vector<double> t;
                for (int r = 0; r < repeat; ++r) {
                    const auto tb = std::chrono::steady_clock::now();
                    chains[m] = buildChain(base, m);
                    t.push_back(secondsSince(tb));
                }
                times[m] = median(t);
            }
            std::vector<std::size_t> rowOf;
            for (const Builder m : builders) {
                const MipChain& chain = chains[m];
                BenchRow row;
                row.env = name;
                row.size = size;
                row.builder = m;
                row.seconds = times[m];
                row.ratioToBox = times[Builder::Box] > 0 ? times[m] / times[Builder::Box] : 0.0;
                std::printf("%-9s %8.4f %7.1f |", builderName(m), row.seconds, row.ratioToBox);
                for (int k = 1; k <= last; ++k) {
                    const double centre = centres ? compareCubes(chain.levels[static_cast<std::size_t>(k)],
                                                                 truth.levels[static_cast<std::size_t>(k)]).relRms
                                                  : 0.0;
                    const double read = relativeRms(readChain(chain, k, dirs), levelTruth[static_cast<std::size_t>(k)]);
                    row.worstCentre = std::max(row.worstCentre, centre);
                    row.worstRead = std::max(row.worstRead, read);
                    char cell[32];
                    std::snprintf(cell, sizeof cell, "%.2f/%.2f", 100 * centre, 100 * read);
                    std::printf(" %11s", cell);
                }
                std::printf(" | %.2f/%.2f\n", 100 * row.worstCentre, 100 * row.worstRead);
                std::fflush(stdout);
                rowOf.push_back(rows.size());
                rows.push_back(row);
            }

            if (shortcuts) {
                // What each of the default builder's shortcuts costs: the chain built with one
                // of them changed (PhongShortcuts), timed like the builders, errors as above.
                struct Variant {
                    const char* name;
                    PhongShortcuts change;
                };
                std::vector<Variant> variants{{"default", {}}};
                variants.push_back({"src>=64", {}});
                variants.back().change.minSourceSize = 64;
                variants.push_back({"src 0.28s", {}});
                variants.back().change.sourceFactor = 32.0;
                variants.push_back({"cut 1e-3", {}});
                variants.back().change.cutoff = 1e-3;
                variants.push_back({"no half", {}});
                variants.back().change.upsampleFromSize = 0;
                std::printf("shortcuts (phong with one change: src>=64 = pyramid floor 64 instead of 32; src 0.28s = "
                            "source texels 0.28 sigma instead of 0.55; cut 1e-3 instead of 1e-4; no half = faces >= 256 "
                            "filtered at full size)\n");
                for (const Variant& v : variants) {
                    std::vector<double> t;
                    MipChain chain;
                    for (int r = 0; r < repeat; ++r) {
                        const auto tb = std::chrono::steady_clock::now();
                        const PhongFilter filter(base, v.change);
                        chain = buildPhongChain(base, {}, &filter);
                        t.push_back(secondsSince(tb));
                    }
                    double worstCentre = 0.0, worstRead = 0.0;
                    std::printf("%-9s %8.4f %7.1f |", v.name, median(t),
                                times[Builder::Box] > 0 ? median(t) / times[Builder::Box] : 0.0);
                    for (int k = 1; k <= last; ++k) {
                        const double centre = centres ? compareCubes(chain.levels[static_cast<std::size_t>(k)],
                                                                     truth.levels[static_cast<std::size_t>(k)]).relRms
                                                      : 0.0;
                        const double read = relativeRms(readChain(chain, k, dirs), levelTruth[static_cast<std::size_t>(k)]);
                        worstCentre = std::max(worstCentre, centre);
                        worstRead = std::max(worstRead, read);
                        char cell[32];
                        std::snprintf(cell, sizeof cell, "%.2f/%.2f", 100 * centre, 100 * read);
                        std::printf(" %11s", cell);
                    }
                    std::printf(" | %.2f/%.2f\n", 100 * worstCentre, 100 * worstRead);
                    std::fflush(stdout);
                }
            }

            if (halfLevels) {
                std::printf("%-26s |", "half level: lod");
                for (int k = 0; k < last; ++k) std::printf(" %11.1f", k + 0.5);
                std::printf(" |\n%-26s |", "  n meant (renderer)");
                for (double e : halfExponent) std::printf(" %11s", fmtExponent(e).c_str());
                std::printf(" |\n");
                for (std::size_t b = 0; b < builders.size(); ++b) {
                    const MipChain& chain = chains[builders[b]];
                    BenchRow& row = rows[rowOf[b]];
                    // The best fit only for the default builder: the others do not hold the
                    // schedule's lobes at the levels themselves (their read errors above).
                    const bool fitThis = builders[b] == Builder::Phong;
                    std::vector<double> meant, fit, fitN;
                    for (int k = 0; k < last; ++k) {
                        const std::vector<Rgb> read = readChain(chain, k + 0.5, dirs);
                        meant.push_back(relativeRms(read, halfTruth[static_cast<std::size_t>(k)]));
                        row.worstHalfMeant = std::max(row.worstHalfMeant, meant.back());
                        if (!fitThis) continue;
                        // Searched against the reduced base, measured against the full base; the
                        // meant lobe itself is a candidate.
                        const double lo = heldExponent(size, k + 1) / 16.0, hi = heldExponent(size, k) * 16.0;
                        double n = bestFitExponent(read, base, dirs, lo, hi, reduced);
                        double err = relativeRms(read, referenceLobeAt(base, n, dirs));
                        if (meant.back() < err) {
                            n = halfExponent[static_cast<std::size_t>(k)];
                            err = meant.back();
                        }
                        fitN.push_back(n);
                        fit.push_back(err);
                        row.worstHalfFit = std::max(row.worstHalfFit, fit.back());
                    }
                    std::printf("%-26s |", (std::string("  ") + builderName(builders[b]) + " vs meant %").c_str());
                    for (double e : meant) std::printf(" %11.2f", 100 * e);
                    std::printf(" | %.2f\n", 100 * row.worstHalfMeant);
                    if (fitThis) {
                        std::printf("%-26s |", (std::string("  ") + builderName(builders[b]) + " vs best fit %").c_str());
                        for (double e : fit) std::printf(" %11.2f", 100 * e);
                        std::printf(" | %.2f\n%-26s |", 100 * row.worstHalfFit,
                                    (std::string("  ") + builderName(builders[b]) + " best-fit n").c_str());
                        for (double n : fitN) std::printf(" %11s", fmtExponent(n).c_str());
                        std::printf(" |\n");
                    }
                    std::fflush(stdout);
                }
            }

            // Diffuse: the irradiance map and the paper's normal lookup into the 1×1 box level,
            // against the exact E/π. The exact cosine convolution costs O(N²) per output texel, so
            // it runs at face <= 128 only.
            if (size > 128) continue;
            const CubeMap exactIrr = referenceConvolution(base, 1.0, kIrradianceFaceSize);
            const auto ti = std::chrono::steady_clock::now();
            const CubeMap irr = computeIrradiance(base);
            const double irrTime = secondsSince(ti);
            const MipChain& box = chains[Builder::Box];
            CubeMap paperDiffuse(exactIrr.size());
            for (Face f : kAllFaces)
                for (int y = 0; y < paperDiffuse.size(); ++y)
                    for (int x = 0; x < paperDiffuse.size(); ++x)
                        paperDiffuse.at(f, x, y) = box.levels.back().sample(texelDirection(f, x, y, paperDiffuse.size()));
            std::printf("diffuse: irradiance map %.2f%% (%.3f s), paper's 1x1 box level by normal %.2f%%\n",
                        100.0 * compareCubes(irr, exactIrr).relRms, irrTime,
                        100.0 * compareCubes(paperDiffuse, exactIrr).relRms);
        }
    }

    std::printf("\n## summary (worst over read levels; half levels: blend vs meant / vs best fit)\n");
    std::printf("%-12s %5s %-9s %9s %8s %9s %9s %9s %9s\n", "env", "face", "builder", "time s", "x box", "centre%",
                "read%", "half m%", "half f%");
    for (const BenchRow& r : rows) {
        std::printf("%-12s %5d %-9s %9.4f %8.1f %9.2f %9.2f", r.env.c_str(), r.size, builderName(r.builder), r.seconds,
                    r.ratioToBox, 100 * r.worstCentre, 100 * r.worstRead);
        if (halfLevels) std::printf(" %9.2f", 100 * r.worstHalfMeant);
        if (halfLevels && r.builder == Builder::Phong) std::printf(" %9.2f", 100 * r.worstHalfFit);
        std::printf("\n");
    }

#ifdef MIPGLOSS_WITH_PLOT
    if (!plot.empty()) {
        std::vector<BenchPlotPoint> points;
        for (const BenchRow& r : rows) points.push_back({builderName(r.builder), r.env, r.size, r.seconds, r.worstRead});
        std::string sizeList;
        for (int s : sizes) sizeList += (sizeList.empty() ? "" : ",") + std::to_string(s);
        const fs::path png = writeBenchPlot(
            points, plot, "mipgloss bench: error against build time",
            "each marker: one builder at one base face size N on one environment; y = worst relative RMS of the "
            "chain read between texel centres (" + std::to_string(directionCount) +
            " directions) over read levels 1..last, against the exact Phong lobe; x = median of " +
            std::to_string(repeat) + " builds, " + std::to_string(std::thread::hardware_concurrency()) +
            " threads; sizes " + sizeList);
        std::printf("\nplot: %s (and %s)\n", plot.c_str(), png.c_str());
    }
#else
    (void)plot;
#endif
    return 0;
}

}  // namespace mipgloss::app
