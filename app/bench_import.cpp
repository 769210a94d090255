// `mipgloss bench import`: where the time and the memory of a big environment go, stage by stage
// (decode, lat-long -> cube conversion, filter, write), for lat-long inputs of several widths and
// cubes of several face sizes. Timings are printed, never asserted.
#include "bench_import.h"

#include "cli_report.h"
#include "process_memory.h"

#include "mipgloss/ibl/parallel.h"
#include "mipgloss/io/bake.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"
#include "mipgloss/io/latlong.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <vector>

namespace mipgloss::app {

namespace fs = std::filesystem;

const char* kImportBenchUsage = R"(
  mipgloss bench import [--env FILE] [--widths 2048,8192,16384] [--faces 256,512,1024]
                        [--dir DIR] [--keep] [--input FILE]

bench import: for each width W, makes a W x W/2 lat-long input from the environment (bilinear
  resampling of its lat-long, written as half-float, zip-compressed OpenEXR: what HDRI sites ship),
  then prints per face size N, each stage timed on its own:
    oiio      OpenImageIO's own whole-image read of the file as float (the floor; once per width)
    decode    mipgloss's decode of the input (by strips, into float RGB, sanitised; once per width)
    convert   lat-long -> cube at face N of the decoded image (latLongToCube)
    import    the bake's import stage: decode and conversion together, the conversion of each
              strip running while the next is decoded (what bake and the previewer do)
    filter    the chain's build (bake's build stage, default builder)
    write     bake's parallel write of every level
    bake      the whole `mipgloss bake --size N` run (decode + convert + filter + write), wall time
  and what the decode alone and the whole bake added to the resident memory at their peak (VmHWM,
  reset before each through /proc/self/clear_refs, over the resident size then).
  --env FILE    the lat-long environment the inputs are resampled from (default: the embedded
                default environment)
  --widths LIST input widths, each even and >= 64 (default 2048,8192,16384)
  --faces LIST  face sizes (default 256,512,1024)
  --dir DIR     where the inputs and bakes go (default: a new folder in the temporary directory)
  --keep        keep the inputs and bakes (default: removed at the end)
  --input FILE  measure this lat-long file as it is instead of making inputs (repeatable)
)";

namespace {

using Clock = std::chrono::steady_clock;


std::vector<int> parseSizes(const std::string& flag, const std::string& text, int minimum) {
    std::vector<int> out;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v < minimum || v > 65536)
            throw UsageError(flag + ": '" + item + "' is not a size between " + std::to_string(minimum) +
                             " and 65536");
        out.push_back(static_cast<int>(v));
    }
    if (out.empty()) throw UsageError(flag + " needs at least one size");
    return out;
}

// Peak resident memory: Linux keeps the high-water mark (VmHWM) per process; writing 5 to
// clear_refs resets it to the current resident size, so each stage gets its own peak. What the
// allocator kept from earlier stages is given back first (malloc_trim): a stage that reused it
// showed as adding nothing (the 8k bake after the 2k ones: 0 MiB).
void resetPeakMemory() {
#ifdef __GLIBC__
    ::malloc_trim(0);
#endif
    std::ofstream("/proc/self/clear_refs") << "5";
}

// What a stage added at its peak: the high-water mark over the resident size when it was reset.
// (The process still holds what earlier stages left mapped, which is not the stage's.)
double peakMemoryMiB(double residentAtReset) { return processStatusMiB("VmHWM") - residentAtReset; }

// The source read bilinearly at (u, v) in [0, 1]², wrapping in u, clamped in v.
Rgb bilinear(const DecodedImage& img, double u, double v) {
    const double x = u * img.width - 0.5, y = std::clamp(v * img.height - 0.5, 0.0, img.height - 1.0);
    const double fx = std::floor(x), fy = std::floor(y);
    const float ax = static_cast<float>(x - fx), ay = static_cast<float>(y - fy);
    const int x0 = ((static_cast<int>(fx) % img.width) + img.width) % img.width;
    const int x1 = (x0 + 1) % img.width;
    const int y0 = static_cast<int>(fy), y1 = std::min(y0 + 1, img.height - 1);
    const Rgb top = img.at(x0, y0) * (1.0f - ax) + img.at(x1, y0) * ax;
    const Rgb bottom = img.at(x0, y1) * (1.0f - ax) + img.at(x1, y1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

// Writes the source resampled to width × width/2 as half-float, zip-compressed OpenEXR, strip by
// strip (the input is never whole in memory here).
void writeInput(const DecodedImage& source, int width, const fs::path& file) {
    const int height = width / 2;
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw std::runtime_error(file.string() + ": cannot create an OpenEXR writer");
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::HALF);
    spec.attribute("compression", "zip");
    if (!out->open(file.string(), spec)) throw std::runtime_error(file.string() + ": " + out->geterror());
    constexpr int kRows = 256;
    std::vector<float> strip(static_cast<std::size_t>(width) * kRows * 3);
    for (int y0 = 0; y0 < height; y0 += kRows) {
        const int y1 = std::min(height, y0 + kRows);
        parallelFor(y0, y1, [&](int y) {
            for (int x = 0; x < width; ++x) {
                const Rgb p = bilinear(source, (x + 0.5) / width, (y + 0.5) / height);
                float* q = &strip[(static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(width) +
                                   static_cast<std::size_t>(x)) * 3];
                q[0] = p.x, q[1] = p.y, q[2] = p.z;
            }
        });
        if (!out->write_scanlines(y0, y1, 0, OIIO::TypeDesc::FLOAT, strip.data()))
            throw std::runtime_error(file.string() + ": " + out->geterror());
    }
    if (!out->close()) throw std::runtime_error(file.string() + ": " + out->geterror());
}

// The yardstick: OpenImageIO's own whole-image read of the file's first three channels as float,
// with nothing of ours around it. Seconds.
double plainReadSeconds(const fs::path& file) {
    const auto t0 = Clock::now();
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) throw std::runtime_error(file.string() + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const int nc = std::min(spec.nchannels, 3);
    std::vector<float> px(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                          static_cast<std::size_t>(nc));
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, px.data()))
        throw std::runtime_error(file.string() + ": " + in->geterror());
    return secondsSince(t0);
}

DecodedImage sourceImage(const fs::path& env, const fs::path& dir) {
    if (!env.empty()) return decodeImage(env);
    const fs::path file = dir / "default_env.exr";
    const auto bytes = defaultEnvironmentBytes();
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                static_cast<std::streamsize>(bytes.size()));
    return decodeImage(file);
}

}  // namespace

int runImportBench(Args args) {
    fs::path env, dir;
    std::vector<int> widths{2048, 8192, 16384}, faces{256, 512, 1024};
    bool keep = false;
    std::vector<fs::path> inputs;
    while (!args.empty()) {
        const std::string a = args.next();
        if (a == "--env") env = args.value(a);
        else if (a == "--widths") {
            widths = parseSizes(a, args.value(a), 64);
            for (int w : widths)
                if (w % 2 != 0) throw UsageError("--widths: " + std::to_string(w) + " is odd (inputs are 2:1)");
        } else if (a == "--faces") faces = parseSizes(a, args.value(a), 1);
        else if (a == "--dir") dir = args.value(a);
        else if (a == "--keep") keep = true;
        else if (a == "--input") inputs.emplace_back(args.value(a));
        else if (a == "--help" || a == "-h") { std::cout << kImportBenchUsage; return 0; }
        else throw UsageError("unknown option '" + a + "'");
    }
    const bool madeDir = dir.empty();
    if (madeDir) dir = fs::temp_directory_path() / ("mipgloss-bench-import-" + std::to_string(::getpid()));
    fs::create_directories(dir);

    std::printf("# mipgloss bench import: big lat-long environments, stage by stage; %u threads\n",
                std::thread::hardware_concurrency());
    DecodedImage source;
    if (inputs.empty()) {
        source = sourceImage(env, dir);
        std::printf("# source %s (%dx%d), inputs half-float zip OpenEXR in %s\n",
                    env.empty() ? "embedded default environment" : env.string().c_str(), source.width,
                    source.height, dir.string().c_str());
        for (int width : widths) inputs.push_back(dir / ("latlong_" + std::to_string(width) + ".exr"));
    }
    const bool generated = source.width > 0;  // the user's own --input files are never removed
    std::printf("# seconds per stage; +MiB = what the decode alone and the whole bake added to the resident\n"
                "# memory at their peak (VmHWM over VmRSS when reset)\n");
    std::printf("%-12s %9s %5s %8s %8s %8s %8s %8s %8s %8s %11s %10s\n", "input", "file MiB", "face", "oiio", "decode",
                "convert", "import", "filter", "write", "bake", "dec. +MiB", "bake +MiB");
    for (std::size_t w = 0; w < inputs.size(); ++w) {
        const fs::path& input = inputs[w];
        if (generated) writeInput(source, widths[w], input);
        const double fileMiB = static_cast<double>(fs::file_size(input)) / 1048576.0;

        const double oiioSeconds = plainReadSeconds(input);
        resetPeakMemory();
        const double decodeBase = processStatusMiB("VmRSS");
        auto t0 = Clock::now();
        DecodedImage image = decodeImage(input);
        const double decodeSeconds = secondsSince(t0);
        const int width = image.width, height = image.height;
        const double decodePeak = peakMemoryMiB(decodeBase);
        std::vector<double> convertSeconds;
        for (int face : faces) {
            t0 = Clock::now();
            const CubeMap cube = latLongToCube(LatLongView{image.width, image.height, image.px}, face);
            convertSeconds.push_back(secondsSince(t0));
        }
        image = DecodedImage{};  // the bakes below decode on their own

        for (std::size_t i = 0; i < faces.size(); ++i) {
            BakeRequest request;
            request.environment = input;
            request.import.faceSize = faces[i];
            request.outDir = dir / ("bake_" + std::to_string(w) + "_" + std::to_string(faces[i]));
            resetPeakMemory();
            const double bakeBase = processStatusMiB("VmRSS");
            t0 = Clock::now();
            const BakeSummary summary = bake(request);
            const double bakeSeconds = secondsSince(t0);
            const double bakePeak = peakMemoryMiB(bakeBase);
            std::printf("%-12s %9.1f %5d %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %11.0f %10.0f\n",
                        (std::to_string(width) + "x" + std::to_string(height)).c_str(), fileMiB, faces[i],
                        oiioSeconds, decodeSeconds, convertSeconds[i], summary.importSeconds, summary.buildSeconds,
                        summary.writeSeconds, bakeSeconds, decodePeak, bakePeak);
            std::fflush(stdout);
            fs::remove_all(request.outDir);
        }
        if (!keep && generated) fs::remove(input);
    }
    if (!keep && madeDir) fs::remove_all(dir);
    return 0;
}

}  // namespace mipgloss::app
