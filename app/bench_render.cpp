// `mipgloss bench-render`: the viewer's renderer offscreen, timed (its usage: render_command.cpp's
// kRenderUsage).
#include "bench_render.h"

#include "cli_report.h"
#include "material_args.h"
#include "offscreen_session.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/assets/mesh_files.h"
#include "mipgloss/assets/textures.h"
#include "mipgloss/scene/chain_needs.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/framing.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/scene/placement.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/offscreen.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace mipgloss::app {

namespace {

// A big mesh: load time, first frame (with the upload) and steady frame time, with and without
// multisampling: is it interactive?
// Every byte of `files`, read as a program that does nothing with them would: the floor under
// any load time.
double readMilliseconds(const std::vector<fs::path>& files, std::uintmax_t& bytes) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<char> buffer(1 << 20);
    bytes = 0;
    for (const fs::path& f : files) {
        std::ifstream in(f, std::ios::binary);
        while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
            bytes += static_cast<std::uintmax_t>(in.gcount());
    }
    return millisecondsSince(start);
}

int benchOneMesh(ui::OffscreenRenderer& renderer, const fs::path& path, int frames, int width, int height) {
    // An asset's files: itself (a .gltf's .bin buffers are read by the load below, not here) and
    // its external textures; the time to read them is what "on screen" is compared with.
    auto start = std::chrono::steady_clock::now();
    const Asset asset = loadAsset(path);
    const double loadMs = millisecondsSince(start);
    printWarnings(asset.warnings);
    Scene scene;
    Material material;
    material.lambda = 3.0f;
    addAsset(scene, asset, path.string(), Transform{}, material);
    std::vector<fs::path> files{path};
    for (const TextureRef& t : texturesOf(scene))
        if (t.image < 0) files.push_back(t.file);
    std::uintmax_t bytes = 0;
    const double readMs = readMilliseconds(files, bytes);
    start = std::chrono::steady_clock::now();
    const auto textures = std::make_shared<TextureCache>();  // this command's
    renderer.setTextures(textures);
    printWarnings(textures->load(texturesOf(scene), asset.images));
    const double decodeMs = millisecondsSince(start);
    std::size_t triangles = 0, vertices = 0;
    for (const SceneObject& o : scene.objects) triangles += o.mesh->triangleCount(), vertices += o.mesh->vertexCount();
    auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(scene.environment, chainNeeds(scene, scene.environment.faceSize)));
    OrbitCamera camera = framingCamera(scene, static_cast<float>(width) / static_cast<float>(height));
    start = std::chrono::steady_clock::now();
    renderer.render(scene, camera, environment, width, height);
    renderer.finish();
    const double firstMs = millisecondsSince(start);
    const double onScreenMs = loadMs + decodeMs + firstMs;
    std::cout << "renderer: " << renderer.glDescription() << "\n"
              << path.string() << ": " << triangles << " triangles, " << vertices << " vertices, "
              << scene.objects.size() << " parts, " << textures->images() << " textures ("
              << textures->bytes() / 1000000 << " MB decoded)\n"
              << "read the files alone (" << files.size() << " files, " << bytes / 1000000 << " MB): " << readMs << " ms\n"
              << "load (parse, validate, normals, tangents): " << loadMs << " ms\n"
              << "decode textures (OpenImageIO, in parallel): " << decodeMs << " ms\n"
              << "first frame (with uploads and mipmaps): " << firstMs << " ms\n"
              << "on screen in " << onScreenMs << " ms = " << onScreenMs / std::max(readMs, 1e-3)
              << " x the time to read its files\n";
    for (const int samples : {4, 0}) {
        scene.display.samples = samples;
        renderer.render(scene, camera, environment, width, height);
        start = std::chrono::steady_clock::now();
        for (int f = 0; f < frames; ++f) {
            camera.orbit(2.0f, 0.0f);  // a turning view, as when the user drags
            renderer.render(scene, camera, environment, width, height);
            renderer.finish();
        }
        std::cout << "frame, " << (samples ? "4x MSAA" : "no MSAA") << ", " << width << "x" << height
                  << ": " << millisecondsSince(start) / frames << " ms\n";
    }
    std::cout << "texture uploads: " << renderer.counters().textureUploads << ", mesh uploads: "
              << renderer.counters().meshUploads << '\n';
    return 0;
}

}  // namespace

BenchRenderOptions parseBenchRenderOptions(Args args) {
    BenchRenderOptions o;
    while (!args.empty()) {
        const std::string a = args.next();
        auto value = [&] { return args.value(a); };
        if (a == "--mesh") o.mesh = value();
        else if (a == "--million") o.million = true;
        else if (a == "--objects") o.objects = static_cast<int>(parseFloat(a, value(), 1, 4096));
        else if (a == "--frames") o.frames = static_cast<int>(parseFloat(a, value(), 1, 100000));
        else if (a == "--size") parseSize(a, value(), o.width, o.height);
        else if (a == "--no-stack") o.stack = false;
        else throw UsageError("unknown option '" + a + "'");
    }
    return o;
}

int runRenderBench(Args args, const char* argv0) {
    const BenchRenderOptions options = parseBenchRenderOptions(std::move(args));
    const int objects = options.objects, frames = options.frames, width = options.width, height = options.height;
    OffscreenSession session(argv0, "bench-render");
    ui::OffscreenRenderer& renderer = session.renderer();
    checkRenderSize(renderer, "--size", width, height, std::nullopt);
    if (options.million) {
        // A 1M-triangle sphere written as binary PLY, then loaded like any user file.
        const fs::path file = fs::temp_directory_path() / ("mipgloss-million-" + std::to_string(::getpid()) + ".ply");
        writeMesh(makeSphere(500, 1000), file);
        const int status = benchOneMesh(renderer, file, frames, width, height);
        fs::remove(file);
        return status;
    }
    if (options.mesh) return benchOneMesh(renderer, *options.mesh, frames, width, height);
    Scene scene;
    auto teapot = std::make_shared<const Mesh>(defaultTeapot());
    for (int i = 0; i < objects; ++i) {
        SceneObject o;
        o.name = "teapot " + std::to_string(i);
        o.mesh = teapot;
        o.transform = inGrid(teapot->bounds, i, objects);
        scene.addObject(std::move(o), Material{});
    }
    auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(scene.environment, ChainNeeds{7, false, 1.0}));
    const OrbitCamera camera = framingCamera(scene, static_cast<float>(width) / static_cast<float>(height));
    // Each case times the settled picture: the lobe stack's entries its lobes read, made before
    // the clock starts, as the window's worker makes them (render_command.cpp does the same).
    auto timeFrames = [&](Scene& s) {
        renderer.setLobes(options.stack ? makeStackEntries(*environment, s) : std::vector<std::shared_ptr<const LobeStackEntry>>{});
        renderer.render(s, camera, environment, width, height);  // warm-up: uploads, samplers
        renderer.finish();
        const auto start = std::chrono::steady_clock::now();
        for (int f = 0; f < frames; ++f) {
            renderer.render(s, camera, environment, width, height);
            renderer.finish();
        }
        return millisecondsSince(start) / frames;
    };
    std::cout << "renderer: " << renderer.glDescription() << "\n"
              << objects << " teapots (" << objects * teapot->triangleCount() << " triangles), "
              << width << "x" << height << ", " << frames << " frames each, glFinish per frame, "
              << (options.stack ? "the settled picture (lobe stack made)" : "every lobe from the chain (--no-stack)") << "\n"
              << "environment: the embedded default, face " << environment->base->size() << ", "
              << environment->lights.size() << " bright lights\n";
    // Three cases, interleaved three times, medians kept (the VM's timing noise is large):
    //   shared   every object λ = 3 (one sampler)
    //   distinct λ = 3 + i/512: one sampler per object, the same levels sampled, so the
    //            difference is the per-object state change alone (the paper's claim)
    //   spread   λ from 0 to 7: also what the texture cache sees changes
    auto setLambdas = [&](auto lambdaOf) {
        for (int i = 0; i < objects; ++i)
            scene.materialOf(scene.objects[static_cast<std::size_t>(i)]).lambda = lambdaOf(i);
    };
    // And the layered material (layered.h) at the same scene: a plastic (diffuse + specular) and a
    // coated paint, every object the same material, the specular's roughness that of λ 3 (0.15: at
    // face 128 a near-mirror layer, whose sharpest lookups read the chain); and a rough plastic
    // (0.5), whose lookups the stack holds (lobes.h, ggxLookupsHeld).
    const float lambda3Roughness = static_cast<float>(exponentToRoughness(lambdaToExponent(3.0)));
    auto setLayered = [&](bool on, float coat, float roughness) {
        for (int i = 0; i < objects; ++i) {
            Material& m = scene.materialOf(scene.objects[static_cast<std::size_t>(i)]);
            m.layered = on;
            m.layers.baseColor = Rgb(0.7f, 0.1f, 0.05f);
            m.layers.roughness = roughness;
            m.layers.coat = coat;
            m.layers.coatRoughness = 0.2f;
        }
    };
    std::vector<double> shared, distinct, spread, plastic, coated, rough, plasticUntapped, coatedUntapped;
    for (int round = 0; round < 3; ++round) {
        setLambdas([](int) { return 3.0f; });
        shared.push_back(timeFrames(scene));
        setLambdas([](int i) { return 3.0f + static_cast<float>(i) / 512.0f; });
        distinct.push_back(timeFrames(scene));
        setLambdas([&](int i) { return 7.0f * static_cast<float>(i) / static_cast<float>(std::max(objects - 1, 1)); });
        spread.push_back(timeFrames(scene));
        setLambdas([](int) { return 3.0f; });
        setLayered(true, 0.0f, lambda3Roughness);
        plastic.push_back(timeFrames(scene));
        setLayered(true, 1.0f, lambda3Roughness);
        coated.push_back(timeFrames(scene));
        // The same two without taps along the pixel's footprint (DisplaySettings::footprintTaps).
        scene.display.footprintTaps = false;
        setLayered(true, 0.0f, lambda3Roughness);
        plasticUntapped.push_back(timeFrames(scene));
        setLayered(true, 1.0f, lambda3Roughness);
        coatedUntapped.push_back(timeFrames(scene));
        scene.display.footprintTaps = true;
        setLayered(true, 0.0f, 0.5f);
        rough.push_back(timeFrames(scene));
        setLayered(false, 0.0f, lambda3Roughness);
    }
    for (auto* v : {&shared, &distinct, &spread, &plastic, &coated, &rough, &plasticUntapped, &coatedUntapped})
        std::sort(v->begin(), v->end());
    std::cout << "one shared lambda (3):          " << shared[1] << " ms/frame\n"
              << objects << " lambdas 3 + i/512:          " << distinct[1] << " ms/frame  ratio "
              << distinct[1] / shared[1] << "\n"
              << objects << " lambdas spread over 0..7:   " << spread[1] << " ms/frame  ratio "
              << spread[1] / shared[1] << "\n"
              << "layered, diffuse + specular:    " << plastic[1] << " ms/frame  ratio " << plastic[1] / shared[1]
              << "\n"
              << "layered, + clear coat:          " << coated[1] << " ms/frame  ratio " << coated[1] / shared[1]
              << "\n"
              << "layered, rough (r 0.5):         " << rough[1] << " ms/frame  ratio " << rough[1] / shared[1] << "\n"
              << "layered, no footprint taps:     " << plasticUntapped[1] << " ms/frame  ratio "
              << plasticUntapped[1] / shared[1] << "  (taps cost " << plastic[1] / plasticUntapped[1] << "x)\n"
              << "+ clear coat, no taps:          " << coatedUntapped[1] << " ms/frame  ratio "
              << coatedUntapped[1] / shared[1] << "  (taps cost " << coated[1] / coatedUntapped[1] << "x)\n"
              << "samplers created: " << renderer.counters().samplersCreated << "\n";
    return 0;
}

}  // namespace mipgloss::app
