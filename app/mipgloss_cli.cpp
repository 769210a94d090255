// The `mipgloss` command line: bake, bench, and (with the UI) render, bench-render. Thin: everything it does lives in mipgloss::core.
#include "mipgloss/io/bake.h"
#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/phong.h"

#include "cli_args.h"

#ifdef MIPGLOSS_WITH_UI
#include "render_command.h"
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
                [--handedness right|left] [--irradiance] [--quiet]
  mipgloss bench [--env FILE]... [--sizes 128,256,512,1024] [--builders a,b,...]
                 [--repeat R]
  mipgloss --help | --version

bake: builds the mip chain of an environment and writes
  DIR/level<k>/{px,nx,py,ny,pz,nz}.exr   every level, float, OpenGL face orientation, row 0 = t 0
  DIR/irradiance/{px..nz}.exr           E(N)/pi, with --irradiance
  DIR/environment_mips.exr              one mip-mapped OpenEXR cube environment map
  DIR/manifest.json                     builder, face size, per level: size, lambda, Phong exponent
  The directory is replaced only when the bake is complete.
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
  --quiet        no progress on stderr

bench: times every builder at each face size and prints, per level, the relative RMS error
  against the exact reference convolution at the declared exponent (texel centres, solid-angle
  weighted), with the run time and its ratio to the box filter. Timings are printed, never
  asserted.
  --env FILE     environment(s) to use (repeatable; default: the embedded default)
  --sizes LIST   face sizes (default 128,256,512)
  --builders LIST builders to time (default: all but reference, which is the truth)
  --repeat R     timing runs per builder, the median is reported (default 3)

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
        else if (a == "--quiet") quiet = true;
        else if (a == "--help" || a == "-h") { std::cout << kUsage; return 0; }
        else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else if (req.environment.empty()) req.environment = a;
        else throw UsageError("more than one environment given ('" + req.environment.string() + "', '" + a + "')");
    }
    if (req.outDir.empty()) throw UsageError("bake needs --out DIR");
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
    std::printf("  import %.3f s, build %.3f s, write %.3f s\n", s.importSeconds, s.buildSeconds, s.writeSeconds);
    std::printf("  cube map file: %s\n  manifest: %s\n", s.cubeFile.c_str(), (s.outDir / "manifest.json").c_str());
    return 0;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

int runBench(Args args) {
    std::vector<fs::path> envs;
    std::vector<int> sizes{128, 256, 512};
    std::vector<Builder> builders{Builder::Phong, Builder::Box, Builder::Paper};
    int repeat = 3;
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
        else if (a == "--help" || a == "-h") { std::cout << kUsage; return 0; }
        else throw UsageError("unknown option '" + a + "'");
    }
    std::printf("# mipgloss bench: time and relative RMS error vs the exact reference, per level\n");
    std::printf("# error = sqrt(sum Omega |L - L_ref|^2) / sqrt(sum Omega |L_ref|^2) over texel centres, at\n");
    std::printf("# n = lambdaToExponent(level); time = median of %d runs on %d threads\n", repeat,
                static_cast<int>(std::thread::hardware_concurrency()));
    std::vector<std::pair<std::string, CubeMap>> loaded;
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
        for (const auto& [name, base] : bases) {
            const auto tr = std::chrono::steady_clock::now();
            const MipChain truth = buildReferenceChain(base);
            const double refTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - tr).count();
            std::printf("\n## %s, face %d (reference chain: %.2f s)\n", name.c_str(), size, refTime);
            std::fflush(stdout);
            std::printf("%-8s %9s %8s |", "builder", "time s", "x box");
            for (int k = 1; k < truth.levelCount(); ++k) std::printf(" L%-5d", k);
            std::printf(" | %7s %7s %9s %9s\n", "median", "worst", "mean off", "bord/int");
            std::map<Builder, double> times;
            for (const Builder m : builders) {
                std::vector<double> t;
                MipChain chain;
                for (int r = 0; r < repeat; ++r) {
                    const auto t0 = std::chrono::steady_clock::now();
                    chain = buildChain(base, m);
                    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
                }
                times[m] = median(t);
            }
            for (const Builder m : builders) {
                const MipChain chain = buildChain(base, m);
                const double boxTime = times.count(Builder::Box) ? times[Builder::Box] : 0.0;
                std::printf("%-8s %9.4f %8.1f |", builderName(m), times[m], boxTime > 0 ? times[m] / boxTime : 0.0);
                std::vector<double> errs;
                double worstMean = 0.0, worstBorderRatio = 0.0;
                for (int k = 1; k < truth.levelCount(); ++k) {
                    const LevelError e = compareCubes(chain.levels[static_cast<std::size_t>(k)],
                                                      truth.levels[static_cast<std::size_t>(k)]);
                    errs.push_back(e.relRms);
                    worstMean = std::max(worstMean, std::fabs(e.meanRelDiff));
                    if (e.hasInterior && e.relRmsBorder > 1e-4)  // below 0.01 % both are rounding
                        worstBorderRatio = std::max(worstBorderRatio, e.relRmsBorder / e.relRmsInterior);
                    std::printf(" %5.2f%%", 100.0 * e.relRms);
                }
                std::printf(" | %6.2f%% %6.2f%% %8.2f%% %9.2f\n", 100.0 * median(errs),
                            100.0 * *std::max_element(errs.begin(), errs.end()), 100.0 * worstMean, worstBorderRatio);
            }
            // Diffuse: the paper's normal lookup into the 1×1 level vs E/π, against the exact E/π.
            // The exact cosine convolution costs O(N²) per output texel, so it runs at face <= 128.
            if (size > 128) continue;
            const CubeMap exactIrr = referenceConvolution(base, 1.0, kIrradianceFaceSize);
            const CubeMap irr = computeIrradiance(base);
            const auto ti = std::chrono::steady_clock::now();
            computeIrradiance(base);
            const double irrTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - ti).count();
            const MipChain box = buildBoxChain(base);
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
            std::cout << kUsage;
#ifdef MIPGLOSS_WITH_UI
            std::cout << app::kRenderUsage;
#endif
            return 0;
        }
        if (cmd == "--version") {
            std::cout << "mipgloss " << MIPGLOSS_VERSION << "\n";
            return 0;
        }
        if (cmd == "bake") return runBake(Args(argc, argv, 2));
        if (cmd == "bench") return runBench(Args(argc, argv, 2));
#ifdef MIPGLOSS_WITH_UI
        if (cmd == "render") return app::runRender(Args(argc, argv, 2), argv[0]);
        if (cmd == "bench-render") return app::runRenderBench(Args(argc, argv, 2), argv[0]);
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
