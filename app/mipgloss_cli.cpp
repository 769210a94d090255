// The `mipgloss` command line: bake, bench, and (with the UI) render, bench-render, library. Thin:
// each command's flags are parsed by its own pure parser (*_options.h), everything it does lives in
// mipgloss::core; the benches are in their own files (bench_*.cpp).
#include "mipgloss/io/bake.h"
#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/import.h"

#include "bake_options.h"
#include "bench_chain.h"
#include "bench_import.h"
#include "bench_stack.h"
#ifdef MIPGLOSS_WITH_UI
#include "bench_truth.h"
#endif
#include "cli_args.h"
#include "cli_report.h"

#ifdef MIPGLOSS_WITH_UI
#include "bench_render.h"
#include "library_command.h"
#include "render_command.h"
#endif

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <unistd.h>

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


// Progress on stderr unless --quiet: on a terminal one line per stage redrawn in place, else a
// line per stage at most every 25 %.
int runBake(app::BakeOptions options) {
    BakeRequest& req = options.request;
    const bool tty = isatty(STDERR_FILENO) != 0;
    std::string lastStage;
    int lastPercent = -1;
    if (!options.quiet)
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
    app::printWarnings(s.report.warnings);
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
            std::cout << app::kRenderUsage << app::kLibraryUsage << "\n" << app::kTruthBenchUsage;
#endif
            return 0;
        }
        if (cmd == "--version") {
            std::cout << "mipgloss " << MIPGLOSS_VERSION << "\n";
            return 0;
        }
        if (cmd == "bake") {
            app::BakeOptions options = app::parseBakeOptions(Args(argc, argv, 2));
            if (options.help) return std::cout << kUsage, 0;
            return runBake(std::move(options));
        }
        if (cmd == "bench" && argc > 2 && std::string(argv[2]) == "import")
            return app::runImportBench(Args(argc, argv, 3));
        if (cmd == "bench" && argc > 2 && std::string(argv[2]) == "stack")
            return app::runStackBench(Args(argc, argv, 3));
#ifdef MIPGLOSS_WITH_UI
        if (cmd == "bench" && argc > 2 && std::string(argv[2]) == "truth")
            return app::runTruthBench(Args(argc, argv, 3));
#endif
        if (cmd == "bench") {
            const app::BenchOptions options = app::parseBenchOptions(Args(argc, argv, 2));
            if (options.help) return std::cout << kUsage, 0;
            return app::runBench(options);
        }
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
