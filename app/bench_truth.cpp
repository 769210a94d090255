// `mipgloss bench truth`: the layered material's picture against its truth (material_truth.h),
// per pixel, and what each lookup costs (its usage: kTruthBenchUsage; docs/material-truth.md keeps
// the tables).
#include "bench_truth.h"

#include "cli_report.h"
#include "offscreen_session.h"

#include "mipgloss/ibl/bright_lights.h"
#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/ibl/parallel.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/scene/material_truth.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/offscreen.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss::app {

const char* kTruthBenchUsage = R"(  mipgloss bench truth --env FILE [--env FILE]... [--env-sizes 128,256] [--sizes 384,96]
                       [--lookups 4,8,16] [--lights on|off|both] [--roughness 0.05,0.2,0.3,0.6,0.7,1]
                       [--pixels P] [--frames F] [--truth-at area|centre] [--truth-positions S] [--no-taps] [--dump DIR]
                       [--scattering single|compensated]

bench truth: a sphere in each layered material (a dielectric, base colour 0.8, 0.1, 0.1, and a metal,
  0.95, 0.64, 0.54, at each roughness), drawn by the renderer with K lookups per GGX layer, against
  the glTF 2.0 BRDF integrated over the same decoded environment (material_truth.h) at P pixels of
  the object (every k-th), and the exact Karis split sum on the same pixels. Per row (K, or K:m
  where a polished layer reads m of them: lobes.h, ggxLayerLookups): relative RMS
  over the object, the worst N·v bin of width 0.2, the median pixel's relative error, for the picture
  and for Karis, the frame time (ms, F frames, the material alone on llvmpipe or the GPU), Σ shown /
  Σ truth, and the worst pixel's share of the picture's squared error (top1: near 1, one pixel is
  the RMS).
  --env FILE        an environment, repeatable (required)
  --env-sizes LIST  base face sizes (default 128,256)
  --sizes LIST      image sides: the sphere fills the image (default 384,96)
  --lookups LIST    lookups per GGX layer (default 4,8,16)
  --lights WHICH    the bright texels shaded as lights: on (default), off, or both (rows "L" on, "-" off)
  --roughness LIST  roughness values (default 0.05,0.2,0.3,0.6,0.7,1)
  --pixels P        truth pixels per case (default 800)
  --frames F        timed frames per row (default 5)
  --truth-at WHERE  each pixel's truth over its area (default: the mean over S×S positions, as a
                    path tracer's box filter, S from the change of R across it against the lobe),
                    or at its centre ("centre")
  --truth-positions S  with --truth-at area, at most S positions per side (default 4)
  --no-taps         each pixel shaded at its centre, its lobes widened by the footprint, not at
                    taps along the footprint (DisplaySettings::footprintTaps)
  --dump DIR        each row's pixels as CSV in DIR (x, y, N·v, shown, truth, Karis, RGB each;
                    the normal and view at the pixel's centre, their change to the next pixels)
  --scattering S    single (default: the glTF specification's BRDF) or compensated (multiple
                    scattering, ggx_sampling.h): the picture, the truth and Karis all so
)";

namespace {

std::vector<double> parseNumbers(const std::string& flag, const std::string& text, double least, double most) {
    std::vector<double> out;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !(v >= least && v <= most))
            throw UsageError(flag + ": '" + item + "' is not a number from " + std::to_string(least) + " to " +
                             std::to_string(most));
        out.push_back(v);
    }
    if (out.empty()) throw UsageError(flag + " needs at least one value");
    return out;
}

struct Errors {
    double rms = 0.0, worstBin = 0.0, median = 0.0, ratio = 0.0;  // ratio: Σ shown / Σ truth (luminance)
    // The worst pixel's share of the squared error: near 1, the RMS is that one pixel (a light
    // reflected at the rim), and whether the sample holds it.
    double worstShare = 0.0;
};

// Relative RMS over the pixels, the worst N·v bin of width 0.2, the median relative error.
Errors errorsOf(const std::vector<glm::dvec3>& shown, const std::vector<glm::dvec3>& truth,
                const std::vector<double>& cosView) {
    Errors e;
    double num = 0.0, den = 0.0;
    double binNum[5] = {}, binDen[5] = {};
    double worst = 0.0;
    std::vector<double> each;
    for (std::size_t i = 0; i < shown.size(); ++i) {
        const glm::dvec3 d = shown[i] - truth[i];
        const double dd = glm::dot(d, d), tt = glm::dot(truth[i], truth[i]);
        worst = std::max(worst, dd);
        num += dd;
        den += tt;
        const int bin = std::clamp(static_cast<int>(cosView[i] / 0.2), 0, 4);
        binNum[bin] += dd;
        binDen[bin] += tt;
        if (tt > 0.0) each.push_back(std::sqrt(dd / tt));
    }
    e.rms = den > 0.0 ? std::sqrt(num / den) : 0.0;
    e.worstShare = num > 0.0 ? worst / num : 0.0;
    double sumShown = 0.0, sumTruth = 0.0;
    for (std::size_t i = 0; i < shown.size(); ++i) {
        sumShown += shown[i].x + shown[i].y + shown[i].z;
        sumTruth += truth[i].x + truth[i].y + truth[i].z;
    }
    e.ratio = sumTruth > 0.0 ? sumShown / sumTruth : 0.0;
    for (int b = 0; b < 5; ++b)
        if (binDen[b] > 0.0) e.worstBin = std::max(e.worstBin, std::sqrt(binNum[b] / binDen[b]));
    if (!each.empty()) {
        std::nth_element(each.begin(), each.begin() + static_cast<std::ptrdiff_t>(each.size() / 2), each.end());
        e.median = each[each.size() / 2];
    }
    return e;
}

// One row's pixels, for looking at where the error is: DIR/map-face-side-material-K.csv.
void dumpPixels(const std::string& folder, const std::string& map, int face, int side, const std::string& material,
                int lookups, int width, const std::vector<std::size_t>& sample, const std::vector<double>& cosView,
                const std::vector<glm::dvec3>& shown, const std::vector<glm::dvec3>& truth,
                const std::vector<glm::dvec3>& karis, const std::vector<PixelGeometry>& geometry) {
    std::filesystem::create_directories(folder);
    std::string name = map + "-" + std::to_string(face) + "-" + std::to_string(side) + "-" + material + "-" +
                       std::to_string(lookups) + ".csv";
    std::replace(name.begin(), name.end(), ' ', '_');
    const std::filesystem::path path = std::filesystem::path(folder) / name;
    std::FILE* out = std::fopen(path.string().c_str(), "w");
    if (!out) throw std::runtime_error("bench truth: cannot write " + path.string());
    std::fprintf(out, "x,y,cos_view,shown_r,shown_g,shown_b,truth_r,truth_g,truth_b,karis_r,karis_g,karis_b,n_x,n_y,n_z,v_x,v_y,v_z,"
                      "dndx_x,dndx_y,dndx_z,dndy_x,dndy_y,dndy_z,dvdx_x,dvdx_y,dvdx_z,dvdy_x,dvdy_y,dvdy_z\n");
    for (std::size_t j = 0; j < sample.size(); ++j) {
        const std::size_t i = sample[j];
        const PixelGeometry& g = geometry[j];
        std::fprintf(out, "%zu,%zu,%.5f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.7f,%.7f,%.7f,%.7f,%.7f,%.7f",
                     i % static_cast<std::size_t>(width), i / static_cast<std::size_t>(width), cosView[j], shown[j].x,
                     shown[j].y, shown[j].z, truth[j].x, truth[j].y, truth[j].z, karis[j].x, karis[j].y, karis[j].z,
                     g.n.x, g.n.y, g.n.z, g.v.x, g.v.y, g.v.z);
        for (const glm::dvec3& d : {g.dndx, g.dndy, g.dvdx, g.dvdy}) std::fprintf(out, ",%.7g,%.7g,%.7g", d.x, d.y, d.z);
        std::fprintf(out, "\n");
    }
    std::fclose(out);
}

Scene sphereScene(const Layers& layers, int lookups, bool lights, Scattering scattering, bool taps) {
    static const auto sphere = std::make_shared<const Mesh>(makeSphere(128, 256));
    Scene scene;
    SceneObject object;
    object.name = "sphere";
    object.mesh = sphere;
    Material m;
    m.layered = true;
    m.layers = layers;
    scene.addObject(object, m);
    scene.display.showBackground = false;
    scene.display.samples = 0;
    scene.display.ggxLookups = lookups;
    scene.display.brightLights = lights;
    scene.display.scattering = scattering;
    scene.display.footprintTaps = taps;
    return scene;
}

}  // namespace

int runTruthBench(Args args) {
    std::vector<std::string> envs;
    std::vector<double> faceSizes{128, 256}, sizes{384, 96}, lookups{4, 8, 16}, roughness{0.05, 0.2, 0.3, 0.6, 0.7, 1.0};
    int pixels = 800, frames = 5;
    std::string dumpFolder;
    bool truthOverArea = true;
    int truthPositions = 4;
    bool footprintTaps = true;
    std::vector<bool> lightsModes{true};
    Scattering scattering = Scattering::Single;
    while (!args.empty()) {
        const std::string a = args.next();
        if (a == "--env") envs.push_back(args.value(a));
        else if (a == "--env-sizes") faceSizes = parseNumbers(a, args.value(a), 16, 1024);
        else if (a == "--sizes") sizes = parseNumbers(a, args.value(a), 16, 2048);
        else if (a == "--lookups") lookups = parseNumbers(a, args.value(a), 1, 64);
        else if (a == "--lights") {
            const std::string v = args.value(a);
            if (v == "on") lightsModes = {true};
            else if (v == "off") lightsModes = {false};
            else if (v == "both") lightsModes = {true, false};
            else throw UsageError("--lights is on, off or both, got '" + v + "'");
        } else if (a == "--roughness") roughness = parseNumbers(a, args.value(a), 0.0, 1.0);
        else if (a == "--pixels") pixels = static_cast<int>(parseNumbers(a, args.value(a), 10, 1e6).front());
        else if (a == "--frames") frames = static_cast<int>(parseNumbers(a, args.value(a), 1, 1000).front());
        else if (a == "--dump") dumpFolder = args.value(a);
        else if (a == "--scattering") {
            const std::string v = args.value(a);
            if (!parseScattering(v, scattering)) throw UsageError("--scattering is single or compensated, got '" + v + "'");
        }
        else if (a == "--no-taps") footprintTaps = false;
        else if (a == "--truth-positions") truthPositions = static_cast<int>(parseNumbers(a, args.value(a), 1, 64).front());
        else if (a == "--truth-at") {
            const std::string v = args.value(a);
            if (v == "area") truthOverArea = true;
            else if (v == "centre") truthOverArea = false;
            else throw UsageError("--truth-at is area or centre, got '" + v + "'");
        }
        else throw UsageError("bench truth: unknown option '" + a + "'");
    }
    if (envs.empty()) throw UsageError("bench truth needs --env FILE");
    OffscreenSession session("mipgloss", "bench truth");
    ui::OffscreenRenderer& renderer = session.renderer();
    std::printf("%-14s %5s %5s %-22s %4s | %7s %7s %7s | %7s %7s %7s | %8s\n", "map", "face", "image", "material", "K",
                "rms%", "bin%", "med%", "karis%", "kbin%", "kmed%", "ms/frame  shown/truth  top1");
    for (const std::string& file : envs) {
        const std::string map = std::filesystem::path(file).stem().string();
        for (const double faceSize : faceSizes) {
            EnvironmentSettings settings;
            settings.source = file;
            settings.faceSize = static_cast<int>(faceSize);
            const auto env = std::make_shared<const PreparedEnvironment>(prepareEnvironment(settings, ChainNeeds{16, true, 1.0}));
            const RadianceTree tree(*env->base);
            {
                double energy = 0.0, total = 0.0;
                for (const PointLight& l : env->lights) energy += l.energy.g;
                const double widest = widestLight(env->lights);
                total = tree.totalEnergy().y;
                std::printf("# %s at %d²: %zu bright lights (luminance over %.3g), %.1f %% of the energy, the widest "
                            "%.4f rad\n",
                            map.c_str(), static_cast<int>(faceSize), env->lights.size(), brightThreshold(*env->base),
                            total > 0.0 ? 100.0 * energy / total : 0.0, widest);
            }
            for (const double size : sizes)
                for (const double r : roughness)
                    for (const bool metal : {false, true}) {
                        Layers layers;
                        layers.baseColor = metal ? Rgb(0.95f, 0.64f, 0.54f) : Rgb(0.8f, 0.1f, 0.1f);
                        layers.metallic = metal ? 1.0f : 0.0f;
                        layers.roughness = static_cast<float>(r);
                        // The truth once per case: the pixels' N and v come from the AOV of the
                        // first render (the same for every K).
                        std::vector<std::size_t> sample;
                        std::vector<glm::dvec3> truth, karis;
                        std::vector<double> cosView;
                        std::vector<PixelGeometry> geometry;
                        for (const double k : lookups)
                        for (const bool lightsOn : lightsModes) {
                            const Scene scene = sphereScene(layers, static_cast<int>(k), lightsOn, scattering, footprintTaps);
                            renderer.setLobes(makeStackEntries(*env, scene));
                            OrbitCamera camera;
                            camera.yawDegrees = 30.0f;
                            camera.pitchDegrees = 20.0f;
                            camera.frame(sceneBounds(scene), 1.0f);
                            const int side = static_cast<int>(size);
                            renderer.render(scene, camera, env, side, side);
                            const auto start = std::chrono::steady_clock::now();
                            for (int f = 0; f < frames; ++f) renderer.render(scene, camera, env, side, side);
                            const double ms = millisecondsSince(start) / frames;
                            int w = 0, h = 0;
                            const std::vector<glm::vec4> hdr = renderer.lastHdr(w, h);
                            if (sample.empty()) {
                                const ui::AovImage aov = renderer.renderAov(scene, camera, env, side, side);
                                std::vector<std::size_t> object;
                                for (std::size_t i = 0; i < aov.exponent.size(); ++i)
                                    if (aov.exponent[i] != 0.0f) object.push_back(i);
                                const std::size_t stride = std::max<std::size_t>(1, object.size() / static_cast<std::size_t>(pixels));
                                for (std::size_t i = 0; i < object.size(); i += stride) sample.push_back(object[i]);
                                truth.resize(sample.size());
                                karis.resize(sample.size());
                                cosView.resize(sample.size());
                                geometry.resize(sample.size());
                                const double alpha = std::max(1e-3, static_cast<double>(layers.roughness * layers.roughness));
                                parallelFor(0, static_cast<int>(sample.size()), [&](int j) {
                                    const PixelGeometry g = ui::aovPixelGeometry(aov, sample[static_cast<std::size_t>(j)]);
                                    geometry[static_cast<std::size_t>(j)] = g;
                                    const int s = truthOverArea ? areaSubdivisions(g, alpha, truthPositions) : 1;
                                    glm::dvec3 kk(0.0);
                                    for (int sy = 0; sy < s; ++sy)
                                        for (int sx = 0; sx < s; ++sx) {
                                            glm::dvec3 n, v;
                                            g.at((sx + 0.5) / s - 0.5, (sy + 0.5) / s - 0.5, n, v);
                                            // Karis compensated as Filament compensates it: its
                                            // specular × the same factor.
                                            MaterialPixel split = karisSplitSum(tree, layers, n, v);
                                            split.specular *= energyCompensation(gltfBrdfOf(layers), layers.roughness,
                                                                             glm::dot(n, v), scattering);
                                            kk += split.total();
                                        }
                                    truth[static_cast<std::size_t>(j)] = materialTruthOverPixel(tree, layers, g, s, scattering).total();
                                    karis[static_cast<std::size_t>(j)] = kk / double(s * s);
                                    cosView[static_cast<std::size_t>(j)] = std::clamp(glm::dot(g.n, g.v), 0.0, 1.0);
                                });
                            }
                            std::vector<glm::dvec3> shown;
                            for (std::size_t i : sample) shown.push_back(glm::dvec3(hdr[i]));
                            const Errors e = errorsOf(shown, truth, cosView), ke = errorsOf(karis, truth, cosView);
                            char name[64];
                            std::snprintf(name, sizeof name, "%s r %.2f %s", metal ? "metal" : "dielectric", r,
                                          lightsOn ? "L" : "-");
                            // K, and the lookups the layer reads where fewer (lobes.h, ggxLayerLookups).
                            const int read = ggxLayerLookups(r, static_cast<int>(k), static_cast<int>(faceSize), false, lightsOn);
                            char count[16];
                            if (read == static_cast<int>(k)) std::snprintf(count, sizeof count, "%d", read);
                            else std::snprintf(count, sizeof count, "%d:%d", static_cast<int>(k), read);
                            std::printf("%-14s %5d %5d %-22s %4s | %7.2f %7.2f %7.2f | %7.2f %7.2f %7.2f | %8.2f  %.4f  %5.2f\n",
                                        map.c_str(), static_cast<int>(faceSize), side, name, count,
                                        100 * e.rms, 100 * e.worstBin, 100 * e.median, 100 * ke.rms, 100 * ke.worstBin,
                                        100 * ke.median, ms, e.ratio, e.worstShare);
                            std::fflush(stdout);
                            if (!dumpFolder.empty())
                                dumpPixels(dumpFolder, map, static_cast<int>(faceSize), side, name, static_cast<int>(k),
                                           w, sample, cosView, shown, truth, karis, geometry);
                        }
                    }
        }
    }
    return 0;
}

}  // namespace mipgloss::app
