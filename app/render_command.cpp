#include "render_command.h"

#include "material_args.h"
#include "offscreen_session.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/framing.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/io/image_file.h"
#include "mipgloss/scene/mesh.h"
#include "mipgloss/scene/placement.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/atomic_file.h"
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/offscreen.h"
#include "mipgloss/ui/scene_file.h"

#include <QFileInfo>
#include <QIODevice>
#include <QImage>
#include <QString>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include <unistd.h>

namespace fs = std::filesystem;

namespace mipgloss::app {

const char* const kRenderUsage = R"(
  mipgloss render [SCENE.mipgloss] [--env FILE] [--mesh FILE]... [--library LIB.mglib --material NAME]
                  [--lambda L | --exponent N] [--mode reflect|normal]
                  [--base-color R,G,B] [--metallic M] [--roughness R] [--specular F0] [--coat W]
                  [--coat-roughness R] [--size WxH] [--env-size N] [--builder NAME]
                  [--exposure EV] [--tonemap linear|reinhard|aces] [--background-lambda L]
                  [--no-background] [--yaw DEG] [--pitch DEG] [--samples N] [--quiet]
                  [--aov AOV.exr] --out IMAGE.png|IMAGE.exr
  mipgloss bench-render [--objects N] [--size WxH] [--frames F] [--mesh FILE | --million]

render: draws a scene offscreen with the viewer's OpenGL renderer (needs an X display; under
  CI: xvfb-run). With no scene and no mesh: the default scene (the paper's Figure 1). With --env
  alone: just the environment. Meshes are placed in a row and framed whatever their scale.
  SCENE.mipgloss a scene saved by mipgloss-gui (older .json scenes too)
  --env FILE     environment (as for bake); replaces the scene's
  --mesh FILE    a mesh (OBJ, OFF, PLY, STL, OM), repeatable; replaces the scene's objects
  --library LIB.mglib --material NAME
                 every object wears material NAME of the library (one shared material);
                 --lambda, --exponent and --mode, when given too, change it
  --lambda L     every object's blur λ: the Phong lobe n = 3*128^2*4^-L - 1, the same at any
                 face size (0 = mirror; 0 to 8)
  --exponent N   every object's lobe by its Phong exponent instead (N >= 0; "mirror" or inf)
  --mode M       reflect (reflection vector) or normal (surface normal) for every object
  --base-color R,G,B  --metallic M  --roughness R  --specular F0  --coat W  --coat-roughness R
                 every object wears a layered material (docs/layered-materials.md): a diffuse
                 base of colour R,G,B (linear, 0 to 1) under a glossy layer with Fresnel (F0
                 --specular, default 0.04; a metal's F0 is its base colour), and a clear coat of
                 weight W; roughness 0 (mirror) to 1; --lambda/--exponent then set the glossy
                 layer's lobe instead of --roughness. Defaults: 0.8,0.8,0.8, 0, 0.5, 0.04, 0, 0.05
  --size WxH     image size (default 1024x384 for the default scene, else 800x600)
  --env-size N   base face size of the cube (default: the scene's, 128)
  --builder NAME mip builder (default phong; --method is the old name)
  --out FILE     output image: .exr writes the linear, scene-referred picture (float RGB,
                 before exposure and tone mapping); other extensions (PNG, ...) the tone-mapped one
  --aov FILE.exr per pixel, float channels dirX dirY dirZ (the unit direction the environment is
                 read at, in the frame of `mipgloss bake`'s faces), exponent (the Phong exponent
                 of the lobe shown; 0 where no object, inf for a mirror) and exact (1 where the
                 pixel is meant to equal that lobe at that direction); with a layered material,
                 per layer X in diffuse, specular, coat: X.dirX X.dirY X.dirZ (the direction it
                 read), X.exponent (its lobe; 1 for diffuse) and X.weight.R/G/B (what its lobe is
                 multiplied by), and NdotV; a pixel marked exact is then Σ weight ⊙ lobe(dir),
                 and the single-lobe channels describe its specular layer
  The picture is the settled one: every material's own lobe cube is made first.

bench-render: frame time of N teapots with N different lambdas against the same N teapots
  sharing one lambda (the paper: the per-object statement is free), ratio printed. With --mesh:
  load time, first frame and frame time of that one mesh (is a big scan interactive?); --million:
  the same for a generated sphere of a million triangles, written and read as binary PLY.
)";

namespace {

bool parseSize(const std::string& text, int& w, int& h) {
    const auto x = text.find('x');
    if (x == std::string::npos) return false;
    try {
        w = std::stoi(text.substr(0, x));
        h = std::stoi(text.substr(x + 1));
    } catch (...) {
        return false;
    }
    return w >= 1 && h >= 1 && w <= 16384 && h <= 16384;
}

// Entry `name` of library `file`. Throws LibraryFileError naming the file.
LibraryMaterial libraryEntry(const fs::path& file, const std::string& name) {
    ui::LibraryFileReport report;
    const MaterialLibrary library = ui::loadLibrary(file, &report);
    for (const std::string& w : report.warnings) std::cerr << "mipgloss: warning: " << w << '\n';
    if (const LibraryMaterial* entry = library.find(name)) return *entry;
    std::string names;
    for (const LibraryMaterial& e : library.entries) names += (names.empty() ? "\"" : ", \"") + e.name + "\"";
    throw ui::LibraryFileError(
        file, "no material named \"" + name + "\"" +
                  (names.empty() ? std::string(" (the library is empty)") : " (there are " + names + ")"));
}

// PNG, JPEG... through the atomic write, the format from the extension as QImage::save(path) picks it.
void saveImage(const QImage& image, const fs::path& file) {
    const QByteArray format = QFileInfo(QString::fromStdString(file.string())).suffix().toLower().toLatin1();
    ui::writeFileAtomically(file, [&](QIODevice& device) { return image.save(&device, format.constData()); });
}

}  // namespace

int runRender(Args args, const char* argv0) {
    std::optional<fs::path> scenePath, envPath, outPath;
    std::vector<fs::path> meshPaths;
    std::optional<float> lambda, exposure, backgroundLambda, yaw, pitch;
    std::optional<fs::path> aovPath, libraryPath;
    std::optional<std::string> libraryMaterial;
    std::optional<LookupMode> mode;
    std::string lambdaFlag;
    LayerFlags layerFlags;
    std::optional<ToneMap> toneMap;
    std::optional<int> envSize, samples;
    std::optional<Builder> builder;
    bool noBackground = false, quiet = false;
    int width = 0, height = 0;
    while (!args.empty()) {
        const std::string a = args.next();
        auto value = [&] { return args.value(a); };
        if (a == "--env") envPath = value();
        else if (a == "--mesh") meshPaths.emplace_back(value());
        else if (a == "--out") outPath = value();
        else if (a == "--lambda") lambda = parseLambda(a, value()), lambdaFlag = a;
        else if (a == "--exponent") lambda = parseExponentAsLambda(a, value()), lambdaFlag = a;
        else if (readLayerFlag(a, value, layerFlags)) continue;
        else if (a == "--library") libraryPath = value();
        else if (a == "--material") libraryMaterial = value();
        else if (a == "--aov") aovPath = value();
        else if (a == "--exposure") exposure = parseFloat(a, value(), -20.0f, 20.0f);
        else if (a == "--background-lambda") backgroundLambda = parseLambda(a, value());
        else if (a == "--yaw") yaw = parseFloat(a, value(), -360.0f, 360.0f);
        else if (a == "--pitch") pitch = parseFloat(a, value(), -89.0f, 89.0f);
        else if (a == "--env-size") envSize = static_cast<int>(parseFloat(a, value(), 1.0f, 4096.0f));
        else if (a == "--samples") samples = static_cast<int>(parseFloat(a, value(), 0.0f, 16.0f));
        else if (a == "--builder" || a == "--method") {
            const std::string name = value();
            Builder b;
            if (!parseBuilder(name, b)) throw UsageError("unknown builder '" + name + "'");
            builder = b;
        } else if (a == "--mode") {
            mode = parseMode(a, value());
        } else if (a == "--tonemap") {
            ToneMap t;
            if (!parseToneMap(value(), t)) throw UsageError("--tonemap is linear, reinhard or aces");
            toneMap = t;
        } else if (a == "--size") {
            if (!parseSize(value(), width, height)) throw UsageError("--size needs WxH, e.g. 800x600");
        } else if (a == "--no-background") noBackground = true;
        else if (a == "--quiet") quiet = true;
        else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else if (!scenePath) scenePath = a;
        else throw UsageError("more than one scene given");
    }
    if (!outPath) throw UsageError("render needs --out IMAGE");
    if (libraryPath.has_value() != libraryMaterial.has_value())
        throw UsageError("--library LIB.mglib and --material NAME go together");
    // Read before the OpenGL session starts, so a bad library is reported at once.
    const std::optional<LibraryMaterial> libraryMaterialEntry =
        libraryPath ? std::optional(libraryEntry(*libraryPath, *libraryMaterial)) : std::nullopt;
    OffscreenSession session(argv0, "render");
    ui::OffscreenRenderer& renderer = session.renderer();

    // The scene: a file, meshes, the environment alone, or the default.
    Scene scene;
    if (scenePath) {
        ui::SceneFileReport report;
        scene = ui::loadScene(*scenePath, &report);
        if (!quiet)
            for (const std::string& w : report.warnings) std::cerr << "mipgloss: warning: " << w << '\n';
    } else if (!meshPaths.empty() || envPath) {
        scene.display = DisplaySettings{};
    } else {
        scene = makeFigure1Scene();
        if (width == 0) width = 1024, height = 384;
    }
    if (!meshPaths.empty()) {
        scene.objects.clear();
        float cursor = 0.0f;
        for (const fs::path& p : meshPaths) {
            MeshReport report;
            auto mesh = std::make_shared<const Mesh>(loadMesh(p, &report));
            if (!quiet)
                for (const std::string& w : report.warnings) std::cerr << "mipgloss: warning: " << w << '\n';
            SceneObject object;
            object.name = mesh->name;
            object.meshSource = p.string();
            object.transform = nextInRow(mesh->bounds, cursor);
            object.mesh = std::move(mesh);
            scene.addObject(std::move(object), Material{});
        }
    }
    if (libraryMaterialEntry) {
        // One material, shared by every object; the scene's own go.
        scene.materials.clear();
        const MaterialId id =
            scene.addMaterial(libraryMaterialEntry->name, libraryMaterialEntry->material, libraryMaterialEntry->name);
        for (SceneObject& object : scene.objects) object.material = id;
    }
    if (envPath) scene.environment.source = envPath->string();
    if (envSize) scene.environment.faceSize = *envSize;
    if (builder) scene.environment.builder = *builder;
    for (NamedMaterial& m : scene.materials) {
        // With a layer flag every material is layered, --lambda/--exponent its specular lobe.
        if (layerFlags.any() || (lambda && m.material.layered)) {
            applyLayerFlags(layerFlags, lambda, lambdaFlag, m.material);
        } else if (lambda) {
            m.material.lambda = *lambda;
        }
        if (mode) m.material.mode = *mode;
    }
    if (exposure) scene.display.exposureEv = *exposure;
    if (toneMap) scene.display.toneMap = *toneMap;
    if (backgroundLambda) scene.display.backgroundLambda = *backgroundLambda;
    if (noBackground) scene.display.showBackground = false;
    if (samples) scene.display.samples = *samples;
    if (width == 0) width = 800, height = 600;

    const auto start = std::chrono::steady_clock::now();
    auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(scene.environment, needsFor(scene, scene.environment.faceSize)));
    const double prepareSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!quiet)
        for (const std::string& w : environment->report.warnings)
            std::cerr << "mipgloss: warning: " << w << '\n';

    OrbitCamera camera = framingCamera(scene, static_cast<float>(width) / static_cast<float>(height));
    if (yaw || pitch) {
        if (yaw) camera.yawDegrees = *yaw;
        if (pitch) camera.pitchDegrees = *pitch;
        camera.frame(sceneBounds(scene), static_cast<float>(width) / static_cast<float>(height));
    }
    // The settled picture: each lobe in use from its own cube.
    const auto lobesStart = std::chrono::steady_clock::now();
    const std::vector<std::shared_ptr<const LobeCube>> lobes = makeLobeCubes(*environment, scene);
    const double lobeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - lobesStart).count();
    renderer.setLobes(lobes);
    const QImage image = renderer.render(scene, camera, environment, width, height);
    if (image.isNull()) throw std::runtime_error(outPath->string() + ": the render failed");
    auto lower = [](std::string s) {
        for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    if (lower(outPath->extension().string()) == ".exr") {
        int w = 0, h = 0;
        const std::vector<glm::vec4> hdr = renderer.lastHdr(w, h);
        std::vector<float> rgb;
        rgb.reserve(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
        for (int y = h - 1; y >= 0; --y)  // lastHdr is bottom row first; the file top row first
            for (int x = 0; x < w; ++x) {
                const glm::vec4& p = hdr[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
                rgb.insert(rgb.end(), {p.r, p.g, p.b});
            }
        writeFloatChannels(*outPath, w, h, {"R", "G", "B"}, rgb);
    } else {
        saveImage(image, *outPath);
    }
    if (aovPath) {
        const ui::AovImage aov = renderer.renderAov(scene, camera, environment, width, height);
        // The single-lobe account, and for a scene with a layered material each layer's (render's
        // usage text): X.dirX X.dirY X.dirZ X.exponent X.weight.R X.weight.G X.weight.B, and NdotV.
        std::vector<std::string> names{"dirX", "dirY", "dirZ", "exponent", "exact"};
        const std::pair<const char*, const ui::AovImage::Layer*> layers[] = {
            {"diffuse", &aov.diffuse}, {"specular", &aov.specular}, {"coat", &aov.coat}};
        if (aov.layered) {
            for (const auto& [layer, data] : layers)
                for (const char* field : {".dirX", ".dirY", ".dirZ", ".exponent", ".weight.R", ".weight.G", ".weight.B"})
                    names.push_back(std::string(layer) + field);
            names.push_back("NdotV");
        }
        std::vector<float> values;
        values.reserve(static_cast<std::size_t>(aov.width) * static_cast<std::size_t>(aov.height) * names.size());
        for (int y = aov.height - 1; y >= 0; --y)
            for (int x = 0; x < aov.width; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(aov.width) + static_cast<std::size_t>(x);
                values.insert(values.end(), {aov.direction[i].x, aov.direction[i].y, aov.direction[i].z, aov.exponent[i], aov.exact[i]});
                if (!aov.layered) continue;
                for (const auto& [layer, data] : layers) {
                    const glm::vec3& d = data->direction[i];
                    const glm::vec3& w = data->weight[i];
                    values.insert(values.end(), {d.x, d.y, d.z, data->exponent[i], w.r, w.g, w.b});
                }
                values.push_back(aov.cosView[i]);
            }
        writeFloatChannels(*aovPath, aov.width, aov.height, names, values);
    }
    if (!quiet) {
        const ui::RenderCounters& c = renderer.counters();
        std::cerr << "mipgloss: " << outPath->string() << ": " << width << "x" << height << ", "
                  << scene.objects.size() << " objects (" << c.objectsDrawn << " drawn, "
                  << c.objectsCulled << " culled), environment " << environment->settings.faceSize
                  << "² " << builderName(environment->settings.builder) << " filtered through level "
                  << environment->lastFilteredLevel << " of " << environment->levelCount() - 1
                  << (environment->irradiance ? ", irradiance" : "") << ", " << lobes.size()
                  << " lobe cube(s) made in " << lobeSeconds << " s (" << c.objectsSettled
                  << " objects settled), environment prepared in " << prepareSeconds << " s; " << renderer.glDescription() << '\n';
    }
    return 0;
}

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// A big mesh: load time, first frame (with the upload) and steady frame time, with and without
// multisampling: is it interactive?
int benchOneMesh(ui::OffscreenRenderer& renderer, const fs::path& path, int frames, int width, int height) {
    auto start = std::chrono::steady_clock::now();
    auto mesh = std::make_shared<const Mesh>(loadMesh(path));
    const double loadMs = millisecondsSince(start);
    Scene scene;
    SceneObject object;
    object.name = mesh->name;
    object.mesh = mesh;
    Material material;
    material.lambda = 3.0f;
    scene.addObject(object, material);
    auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(scene.environment, needsFor(scene, scene.environment.faceSize)));
    OrbitCamera camera = framingCamera(scene, static_cast<float>(width) / static_cast<float>(height));
    start = std::chrono::steady_clock::now();
    renderer.render(scene, camera, environment, width, height);
    renderer.finish();
    const double firstMs = millisecondsSince(start);
    std::cout << "renderer: " << renderer.glDescription() << "\n"
              << path.string() << ": " << mesh->triangleCount() << " triangles, " << mesh->vertexCount()
              << " vertices\nload (read, validate, normals): " << loadMs << " ms\n"
              << "first frame (with upload): " << firstMs << " ms\n";
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
    return 0;
}

}  // namespace

int runRenderBench(Args args, const char* argv0) {
    int objects = 16, frames = 20, width = 960, height = 540;
    std::optional<fs::path> meshPath;
    bool million = false;
    while (!args.empty()) {
        const std::string a = args.next();
        auto value = [&] { return args.value(a); };
        if (a == "--mesh") meshPath = value();
        else if (a == "--million") million = true;
        else if (a == "--objects") objects = static_cast<int>(parseFloat(a, value(), 1, 4096));
        else if (a == "--frames") frames = static_cast<int>(parseFloat(a, value(), 1, 100000));
        else if (a == "--size") {
            if (!parseSize(value(), width, height)) throw UsageError("--size needs WxH");
        } else throw UsageError("unknown option '" + a + "'");
    }
    OffscreenSession session(argv0, "bench-render");
    ui::OffscreenRenderer& renderer = session.renderer();
    if (million) {
        // A 1M-triangle sphere written as binary PLY, then loaded like any user file.
        const fs::path file = fs::temp_directory_path() / ("mipgloss-million-" + std::to_string(::getpid()) + ".ply");
        writeMesh(makeSphere(500, 1000), file);
        const int status = benchOneMesh(renderer, file, frames, width, height);
        fs::remove(file);
        return status;
    }
    if (meshPath) return benchOneMesh(renderer, *meshPath, frames, width, height);
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
        prepareEnvironment(scene.environment, ChainNeeds{7, false}));
    const OrbitCamera camera = framingCamera(scene, static_cast<float>(width) / static_cast<float>(height));
    auto timeFrames = [&](Scene& s) {
        renderer.render(s, camera, environment, width, height);  // warm-up: uploads, samplers
        renderer.finish();
        const auto start = std::chrono::steady_clock::now();
        for (int f = 0; f < frames; ++f) {
            renderer.render(s, camera, environment, width, height);
            renderer.finish();
        }
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
               frames;
    };
    std::cout << "renderer: " << renderer.glDescription() << "\n"
              << objects << " teapots (" << objects * teapot->triangleCount() << " triangles), "
              << width << "x" << height << ", " << frames << " frames each, glFinish per frame\n";
    // Three cases, interleaved three times, medians kept (the VM's timing noise is large):
    //   shared   every object λ = 3 (one sampler)
    //   distinct λ = 3 + i/512: one sampler per object, the same levels sampled, so the
    //            difference is the per-object state change alone (the paper's claim)
    //   spread   λ from 0 to 7: also what the texture cache sees changes
    auto setLambdas = [&](auto lambdaOf) {
        for (int i = 0; i < objects; ++i)
            scene.materialOf(scene.objects[static_cast<std::size_t>(i)]).lambda = lambdaOf(i);
    };
    // And the layered material (layered.h) at the same scene: a plastic (diffuse + specular, two
    // lookups) and a coated paint (three), every object the same material, λ of the specular 3.
    auto setLayered = [&](bool on, float coat) {
        for (int i = 0; i < objects; ++i) {
            Material& m = scene.materialOf(scene.objects[static_cast<std::size_t>(i)]);
            m.layered = on;
            m.layers.baseColor = Rgb(0.7f, 0.1f, 0.05f);
            m.layers.roughness = static_cast<float>(exponentToRoughness(lambdaToExponent(3.0)));
            m.layers.coat = coat;
            m.layers.coatRoughness = 0.2f;
        }
    };
    std::vector<double> shared, distinct, spread, plastic, coated;
    for (int round = 0; round < 3; ++round) {
        setLambdas([](int) { return 3.0f; });
        shared.push_back(timeFrames(scene));
        setLambdas([](int i) { return 3.0f + static_cast<float>(i) / 512.0f; });
        distinct.push_back(timeFrames(scene));
        setLambdas([&](int i) { return 7.0f * static_cast<float>(i) / static_cast<float>(std::max(objects - 1, 1)); });
        spread.push_back(timeFrames(scene));
        setLambdas([](int) { return 3.0f; });
        setLayered(true, 0.0f);
        plastic.push_back(timeFrames(scene));
        setLayered(true, 1.0f);
        coated.push_back(timeFrames(scene));
        setLayered(false, 0.0f);
    }
    for (auto* v : {&shared, &distinct, &spread, &plastic, &coated}) std::sort(v->begin(), v->end());
    std::cout << "one shared lambda (3):          " << shared[1] << " ms/frame\n"
              << objects << " lambdas 3 + i/512:          " << distinct[1] << " ms/frame  ratio "
              << distinct[1] / shared[1] << "\n"
              << objects << " lambdas spread over 0..7:   " << spread[1] << " ms/frame  ratio "
              << spread[1] / shared[1] << "\n"
              << "layered, diffuse + specular:    " << plastic[1] << " ms/frame  ratio " << plastic[1] / shared[1]
              << "\n"
              << "layered, + clear coat:          " << coated[1] << " ms/frame  ratio " << coated[1] / shared[1]
              << "\n"
              << "samplers created: " << renderer.counters().samplersCreated << "\n";
    return 0;
}

}  // namespace mipgloss::app
