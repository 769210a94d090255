// The `mipgloss` command line: bake, bench, and (with the UI) render, bench-render, library. Thin: everything it does lives in mipgloss::core.
#include "mipgloss/io/bake.h"
#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"

#include "bench_import.h"
#include "bench_stack.h"
#include "cli_args.h"

#ifdef MIPGLOSS_WITH_UI
#include "library_command.h"
#include "render_command.h"
#endif
#ifdef MIPGLOSS_WITH_PLOT
#include "bench_plot.h"
#endif

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace mipgloss;
using mipgloss::app::Args;
using mipgloss::app::UsageError;

namespace {

const char* kUsage = R"(mipgloss )" MIPGLOSS_VERSION R"( - blurry reflections from one cube-map mip chain

usage:
  mipgloss bake [ENV] --out DIR [--builder NAME] [--size N] [--layout L]
                [--handedness right|left] [--irradiance] [--format exr|dds]
                [--dds-type half|float] [--exr-compression C] [--exr-type float|half]
                [--serial-write] [--quiet]
  mipgloss bench [--env FILE]... [--sizes 128,256,512] [--builders a,b,...]
                 [--repeat R] [--directions D] [--no-half] [--no-centre] [--shortcuts] [--plot FILE.svg]
  mipgloss bench import [--env FILE] [--widths 2048,8192,16384] [--faces 256,512,1024] [--dir DIR]
  mipgloss bench stack [--env FILE]... [--sizes 128,256] [--directions D] [--first-level L]
  mipgloss --help | --version

bake: builds the mip chain of an environment and writes, with --format exr (the default),
  DIR/level<k>/{px,nx,py,ny,pz,nz}.exr   every level, float, OpenGL face orientation, row 0 = t 0
  DIR/irradiance/{px..nz}.exr           E(N)/pi, with --irradiance
  DIR/environment_mips.exr              one mip-mapped OpenEXR cube environment map
  or, with --format dds,
  DIR/environment_mips.dds              one DDS cube map (DX10 header) holding every level: faces
                                        +X -X +Y -Y +Z -Z, each with its mips, as engines load it
  DIR/irradiance.dds                    E(N)/pi, with --irradiance
  and in both
  DIR/manifest.json                     builder, face size, per level: size, lambda, Phong exponent
  The files are written in parallel; the directory is replaced only when the bake is complete.
  See docs/bake-output.md for the layouts and the compression measurements.
  ENV            environment: a lat-long (2:1) HDR, a cross (4:3 or 3:4), a strip (6:1 or
                 1:6), a folder of six face images, or one face image of a named family
                 (px/nx.., posx/negx.., right/left/top/bottom/front/back, rt/lf/up/dn/ft/bk).
                 EXR, HDR, PNG, JPEG, TIFF. Omitted: the embedded default environment.
  --out DIR      output directory (required)
  --builder NAME mip builder (--method is the old name): phong (default; cross-face Phong lobes), box (per-face 2x2, what
                 glGenerateMipmap does), paper (Ashikhmin & Ghosh 2002 with texture borders),
                 reference (exact convolution; slow)
  --size N       resample the input to base face size N (default: native; lat-long: width/4;
                 embedded default: 128)
  --layout L     override layout detection: auto, faces, hcross, vcross, hstrip, vstrip, latlong
  --handedness H right (default) or left: for skyboxes made for left-handed engines (Irrlicht,
                 Direct3D samples) front/back are swapped and faces mirrored
  --irradiance   also write the irradiance map (normal lookup for diffuse materials)
  --format F     exr (default) or dds
  --dds-type T   with --format dds: half (default; DXGI R16G16B16A16_FLOAT, values clamped to
                 65504) or float (R32G32B32A32_FLOAT)
  --exr-compression C
                 with --format exr: OpenEXR compression, default none (filtered float texels
                 barely compress: zip saves 7 % of the bytes at 15x the write time); lossless:
                 none, rle, zips, zip, piz; lossy: pxr24 (float), b44, b44a (half), dwaa, dwab;
                 zip, zips, dwaa, dwab take a level, e.g. zip:9
  --exr-type T   with --format exr: float (default) or half (11 significant bits, clamped to 65504)
  --serial-write write the files one at a time (to measure what writing in parallel gains)
  --quiet        no progress on stderr

bench: builds the chain of each environment at each face size N with every builder and prints
  its build time (median of R runs) and its ratio to the box builder's, then, per read level k
  (1 .. the first level of 8-15 texels; n_k = levelExponent(N,k)), two errors in % against the
  exact normalized Phong convolution of the base at n_k (relative RMS over RGB):
    centre  at the level's texel centres (solid-angle weighted), and
    read    the chain read between centres as the GPU reads it (seamless bilinear) at uniformly
            random directions: what the picture shows.
  Half levels k+0.5: the trilinear blend of two levels against the lobe the renderer means there
  while lambda moves (n with chainLevelForExponent(n,N) = k+0.5) and against the single Phong lobe
  the blend matches best (golden-section search on log n). Then a summary of worst errors per
  builder. The exact lobes are slow (minutes at N = 512). Timings are printed, never asserted.
  --env FILE      environment (repeatable; default: the embedded default environment)
  --sizes LIST    base face sizes, each >= 16 (default 128,256,512)
  --builders LIST builders to measure (default phong,box,paper; reference is the truth)
  --repeat R      timed builds per builder, the median is reported (default 3)
  --directions D  random directions for the between-centres errors (default 1500)
  --no-half       skip the half-level rows (their best-fit search is the slowest part)
  --no-centre     skip the centre errors and the reference chain they need (printed as 0.00);
                  the read errors need only the exact lobes at the directions (use at 1024)
  --shortcuts     also build the default chain with each of its shortcuts changed (pyramid floor
                  64, finer source, lobe cut 1e-3, no half-size filtering): what each one costs
  --plot FILE.svg also draw error against time: x = build time, y = worst between-centres error
                  over read levels, both log scale, one labelled marker per builder, size and
                  environment; writes FILE.svg and FILE.png beside it (needs a build with Qt)

Exit status: 0 on success, 1 on bad input (the message names the file), 2 on bad usage.
)";


std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

int parsePositive(const std::string& flag, const std::string& value) {
    char* end = nullptr;
    const long v = std::strtol(value.c_str(), &end, 10);
    if (end == value.c_str() || *end != '\0' || v < 1 || v > 16384)
        throw UsageError(flag + " needs a whole number from 1 to 16384, got '" + value + "'");
    return static_cast<int>(v);
}


int runBake(Args args) {
    BakeRequest req;
    bool quiet = false;
    std::string ddsOption, exrOption;  // the last format-specific option given, to refuse a mismatch
    while (!args.empty()) {
        const std::string a = args.next();
        if (a == "--out") req.outDir = args.value(a);
        else if (a == "--builder" || a == "--method") {
            const std::string v = args.value(a);
            if (!parseBuilder(v, req.builder)) throw UsageError("unknown builder '" + v + "'");
        }
        else if (a == "--size") req.import.faceSize = parsePositive(a, args.value(a));
        else if (a == "--layout") {
            const std::string v = args.value(a);
            if (!parseLayout(v, req.import.layout)) throw UsageError("unknown layout '" + v + "'");
        } else if (a == "--handedness") {
            const std::string v = args.value(a);
            if (!parseHandedness(v, req.import.handedness))
                throw UsageError("--handedness is right or left, got '" + v + "'");
        } else if (a == "--irradiance") req.irradiance = true;
        else if (a == "--format") {
            const std::string v = args.value(a);
            if (!parseBakeFormat(v, req.format)) throw UsageError("--format is exr or dds, got '" + v + "'");
        } else if (a == "--dds-type") {
            const std::string v = args.value(a);
            if (!parseDdsType(v, req.ddsType)) throw UsageError("--dds-type is half or float, got '" + v + "'");
            ddsOption = a;
        } else if (a == "--exr-compression") {
            const std::string v = args.value(a);
            if (!isExrCompression(v)) throw UsageError("unknown OpenEXR compression '" + v + "'");
            req.exr.compression = v;
            exrOption = a;
        } else if (a == "--exr-type") {
            const std::string v = args.value(a);
            if (v != "float" && v != "half") throw UsageError("--exr-type is float or half, got '" + v + "'");
            req.exr.half = v == "half";
            exrOption = a;
        } else if (a == "--serial-write") req.parallelWrite = false;
        else if (a == "--quiet") quiet = true;
        else if (a == "--help" || a == "-h") { std::cout << kUsage; return 0; }
        else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else if (req.environment.empty()) req.environment = a;
        else throw UsageError("more than one environment given ('" + req.environment.string() + "', '" + a + "')");
    }
    if (req.outDir.empty()) throw UsageError("bake needs --out DIR");
    if (req.format == BakeFormat::Exr && !ddsOption.empty()) throw UsageError(ddsOption + " needs --format dds");
    if (req.format == BakeFormat::Dds && !exrOption.empty()) throw UsageError(exrOption + " needs --format exr");
    const bool tty = isatty(STDERR_FILENO) != 0;
    std::string lastStage;
    int lastPercent = -1;
    if (!quiet)
        req.progress = [&](const std::string& stage, float f) {
            const int percent = static_cast<int>(f * 100.0f);
            if (stage == lastStage && (percent == lastPercent || (!tty && percent < 100 && percent - lastPercent < 25)))
                return true;
            if (tty) std::fprintf(stderr, "\r%-24s %3d%%%s", stage.c_str(), percent, percent >= 100 ? "\n" : "");
            else std::fprintf(stderr, "%s %d%%\n", stage.c_str(), percent);
            lastStage = stage;
            lastPercent = percent;
            return true;
        };
    const BakeSummary s = bake(req);
    for (const std::string& w : s.report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::printf("baked %s (%s, face %d, %zu levels, builder %s) into %s\n",
                req.environment.empty() ? "the embedded default environment" : req.environment.c_str(),
                layoutName(s.report.layout), s.faceSize, s.levels.size(), builderName(req.builder), s.outDir.c_str());
    std::printf("  import %.3f s, build %.3f s, write %.3f s (%d files, %.1f MB, %s)\n", s.importSeconds,
                s.buildSeconds, s.writeSeconds, s.filesWritten, static_cast<double>(s.bytesWritten) / 1e6,
                s.format == BakeFormat::Dds
                    ? (std::string("dds ") + ddsTypeName(s.ddsType)).c_str()
                    : ("exr " + std::string(s.exr.half ? "half " : "float ") + s.exr.compression).c_str());
    std::printf("  cube map file: %s\n  manifest: %s\n", s.cubeFile.c_str(), (s.outDir / "manifest.json").c_str());
    return 0;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

// Golden-section search on log n in [lo, hi] (to 1 % in n) for the lobe whose exact convolution
// (reducedTruth) is closest to `read` in relative RMS.
double bestFitExponent(const std::vector<Rgb>& read, const CubeMap& base,
                                          const std::vector<glm::vec3>& dirs, double lo, double hi,
                                          std::map<int, CubeMap>& reduced) {
    auto cost = [&](double logN) { return relativeRms(read, reducedTruth(base, std::exp(logN), dirs, reduced)); };
    double a = std::log(lo), b = std::log(hi);
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - phi * (b - a), d = a + phi * (b - a);
    double fc = cost(c), fd = cost(d);
    while (b - a > 0.01) {
        if (fc < fd) {
            b = d; d = c; fd = fc; c = b - phi * (b - a); fc = cost(c);
        } else {
            a = c; c = d; fc = fd; d = a + phi * (b - a); fd = cost(d);
        }
    }
    return std::exp(0.5 * (a + b));
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

int runBench(Args args) {
    std::vector<fs::path> envs;
    std::vector<int> sizes{128, 256, 512};
    std::vector<Builder> builders{Builder::Phong, Builder::Box, Builder::Paper};
    int repeat = 3;
    int directionCount = 1500;
    bool halfLevels = true;
    bool shortcuts = false;
    bool centres = true;
    fs::path plot;
    while (!args.empty()) {
        const std::string a = args.next();
        if (a == "--env") envs.emplace_back(args.value(a));
        else if (a == "--sizes") {
            sizes.clear();
            for (const auto& s : splitList(args.value(a))) sizes.push_back(parsePositive(a, s));
        } else if (a == "--builders" || a == "--methods") {
            builders.clear();
            for (const auto& name : splitList(args.value(a))) {
                Builder b;
                if (!parseBuilder(name, b)) throw UsageError("unknown builder '" + name + "'");
                builders.push_back(b);
            }
        } else if (a == "--repeat") repeat = parsePositive(a, args.value(a));
        else if (a == "--directions") directionCount = parsePositive(a, args.value(a));
        else if (a == "--no-half") halfLevels = false;
        else if (a == "--shortcuts") shortcuts = true;
        else if (a == "--no-centre") centres = false;
        else if (a == "--plot") {
            plot = args.value(a);
#ifndef MIPGLOSS_WITH_PLOT
            throw UsageError("--plot needs Qt (Qt6 Gui and Svg); this mipgloss was built without them "
                             "(configure with MIPGLOSS_BUILD_UI=ON, or with qt6-svg-dev installed)");
#endif
        } else if (a == "--help" || a == "-h") { std::cout << kUsage; return 0; }
        else throw UsageError("unknown option '" + a + "'");
    }
    if (sizes.empty()) throw UsageError("--sizes needs at least one size");
    if (builders.empty()) throw UsageError("--builders needs at least one builder");
    for (int size : sizes)
        if (lastReadLevel(size) < 1) throw UsageError("--sizes: face " + std::to_string(size) + " has no read level below the base (needs 16 or more)");

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
        std::vector<app::BenchPlotPoint> points;
        for (const BenchRow& r : rows) points.push_back({builderName(r.builder), r.env, r.size, r.seconds, r.worstRead});
        std::string sizeList;
        for (int s : sizes) sizeList += (sizeList.empty() ? "" : ",") + std::to_string(s);
        const fs::path png = app::writeBenchPlot(
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

}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc < 2) {
            std::cerr << kUsage;
            return 2;
        }
        const std::string cmd = argv[1];
        if (cmd == "--help" || cmd == "-h" || cmd == "help") {
            std::cout << kUsage << app::kImportBenchUsage << app::kStackBenchUsage;
#ifdef MIPGLOSS_WITH_UI
            std::cout << app::kRenderUsage << app::kLibraryUsage;
#endif
            return 0;
        }
        if (cmd == "--version") {
            std::cout << "mipgloss " << MIPGLOSS_VERSION << "\n";
            return 0;
        }
        if (cmd == "bake") return runBake(Args(argc, argv, 2));
        if (cmd == "bench" && argc > 2 && std::string(argv[2]) == "import")
            return app::runImportBench(Args(argc, argv, 3));
        if (cmd == "bench" && argc > 2 && std::string(argv[2]) == "stack")
            return app::runStackBench(Args(argc, argv, 3));
        if (cmd == "bench") return runBench(Args(argc, argv, 2));
#ifdef MIPGLOSS_WITH_UI
        if (cmd == "render") return app::runRender(Args(argc, argv, 2), argv[0]);
        if (cmd == "bench-render") return app::runRenderBench(Args(argc, argv, 2), argv[0]);
        if (cmd == "library") return app::runLibrary(Args(argc, argv, 2), argv[0]);
#endif
        throw UsageError("unknown command '" + cmd + "'");
    } catch (const UsageError& e) {
        std::cerr << "mipgloss: " << e.what() << "\n(see mipgloss --help)\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "mipgloss: error: " << e.what() << "\n";
        return 1;
    }
}
