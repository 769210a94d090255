#include "render_command.h"

#include "cli_report.h"
#include "material_args.h"
#include "offscreen_session.h"
#include "render_options.h"

#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/assets/mesh_files.h"
#include "mipgloss/assets/textures.h"
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/io/image_file.h"
#include "mipgloss/scene/chain_needs.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/framing.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/scene/placement.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/scene/turntable.h"
#include "mipgloss/ui/atomic_file.h"
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/offscreen.h"
#include "mipgloss/ui/scene_file.h"

#include <QFileInfo>
#include <QIODevice>
#include <QImage>
#include <QImageWriter>
#include <QString>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace mipgloss::app {

const char* const kRenderUsage = R"(
  mipgloss render [SCENE.mipgloss] [--env FILE] [--mesh FILE]... [--library LIB.mglib --material NAME]
                  [--lambda L | --exponent N] [--mode reflect|normal]
                  [--base-color R,G,B] [--metallic M] [--roughness R] [--specular F0] [--coat W]
                  [--coat-roughness R] [--specular-weight W] [--specular-color R,G,B] [--scattering single|compensated]
                  [--size WxH] [--env-size N] [--builder NAME]
                  [--exposure EV] [--tonemap linear|reinhard|aces|pbr-neutral|agx] [--background-lambda L]
                  [--no-background] [--background R,G,B] [--env-rotation DEG]
                  [--yaw DEG] [--pitch DEG] [--camera NAME|INDEX] [--samples N] [--no-settle | --no-stack] [--quiet]
                  [--spin DEG] [--turntable N] [--turntable-spin object|environment]
                  [--compare-builder NAME] [--compare-env FILE]
                  [--aov AOV.exr] --out IMAGE.png|IMAGE.exr|PATTERN
  mipgloss bench-render [--objects N] [--size WxH] [--frames F] [--no-stack] [--mesh FILE | --million]

render: draws a scene offscreen with the viewer's OpenGL renderer (needs an X display; under
  CI: xvfb-run). With no scene and no mesh: the default scene (the paper's Figure 1). With --env
  alone: just the environment. Meshes are placed in a row and framed whatever their scale.
  SCENE.mipgloss a scene saved by mipgloss-gui (older .json scenes too); drawn through the
                 camera saved with it, if any (with --size's aspect), else framed
  --env FILE     environment (as for bake); replaces the scene's
  --mesh FILE    a mesh (OBJ, OFF, PLY, STL, OM) or an asset (glTF .gltf/.glb, OBJ with MTL),
                 repeatable; replaces the scene's objects. An asset brings its parts, placed as
                 its file places them, and its materials with their texture maps (a map that is
                 missing is a warning, drawn without it); material flags given here override
                 the materials' values (the maps stay)
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
  --specular-weight W  --specular-color R,G,B
                 KHR_materials_specular: the dielectric's F0 becomes min(F0 * R,G,B, 1) * W and
                 its grazing F90 W (W 0: a purely diffuse surface); a metal is untouched.
                 Defaults 1 and 1,1,1 (glTF's plain material)
  --scattering single|compensated
                 single (default): every layered material is the glTF specification's BRDF,
                 which loses the light its microfacets bounce (a white metal of roughness 1
                 returns 60 to 90 %); compensated: that light kept (Fdez-Aguera 2019), the
                 specular times 1 + F0 (1 - E)/E, E its albedo
  --size WxH     image size (default 1024x384 for the default scene, else 800x600); at most
                 what the OpenGL can draw (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE,
                 GL_MAX_VIEWPORT_DIMS), and --samples at most GL_MAX_SAMPLES
  --yaw DEG --pitch DEG
                 the camera's angles (the scene is framed again from there)
  --camera NAME|INDEX
                 look through a camera of the first --mesh glTF file (its name, or its index in
                 the order the file's scene reaches them, from 0): position, orientation with its
                 roll and vertical field of view as the file places it; --size gives the aspect
  --background R,G,B
                 hide the environment and lay the picture over this colour, as the screen shows
                 it (sRGB-encoded, each 0 to 1; 1,1,1 is white), whatever the exposure and tone
                 map; without it a hidden background (--no-background) is mid grey
  --env-rotation DEG
                 the environment turned by DEG about the vertical axis (its reflections and the
                 background)
  --spin DEG     the scene turned by DEG about the vertical axis through the camera's target:
                 the objects on a turntable under the fixed environment (the background stays),
                 or with --turntable-spin environment only the environment
  --turntable N  N frames of a whole turn (frame i at 360*i/N degrees, after --spin: a seamless
                 loop), 1 to 3600; --out is then a printf pattern with one integer conversion,
                 e.g. frames/turn_%03d.png or %d.exr, each frame written whole or not at all
  --turntable-spin object|environment
                 what --turntable and --spin turn (default object)
  --compare-builder NAME  --compare-env FILE
                 one picture: the left half (columns 0 to W/2-1) the render as it is, the right
                 half the same scene and camera with the environment built by builder NAME
                 and/or from FILE (same face size); a PNG gets a 1-pixel divider in the right
                 half's first column, an EXR stays pure data. Not with --turntable or --aov
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
  The picture is the settled one: the lobe stack's entries every lobe in use reads (exact lobes
                 2^(1/4) apart, blended; each pixel's lobe widened by its footprint) are made first.
  --no-settle    the picture the window shows while a slider moves instead: from the whole stack
                 as the window makes it ahead (every entry of faces up to 512), so the instant
                 path can be checked from outside (it is the settled picture: no entry besides
                 those in use is read)
  --no-stack     the picture the window shows before any entry has arrived: every glossy lobe
                 read from the chain's levels (its AOV marks only mirrors and the irradiance map
                 exact)

bench-render: frame time of N teapots with N different lambdas against the same N teapots
  sharing one lambda (the paper: the per-object statement is free), ratio printed, and the same
  teapots in layered materials (a plastic, with a coat, a rough plastic; the first two also
  without taps along each pixel's footprint, the ratio printed): each case the settled
  picture, its lobe stack's entries made before the clock starts (--no-stack: every lobe from the
  chain, the picture before they exist). With --mesh:
  load time, first frame and frame time of that one mesh or asset (is a big scan interactive?), and
  for an asset the time to decode its textures and the ratio of the time to the first frame to
  the time to read its files alone; --million: the same for a generated sphere of a million
  triangles, written and read as binary PLY (a textured one: tests/tools/make_assets --big).
)";

namespace {

// The lobe stack's entries a render reads from: those the scene's lobes read (the settled
// picture); with `everything`, also every other the window makes ahead (--no-settle); none with
// `none` (--no-stack).
std::vector<std::shared_ptr<const LobeStackEntry>> lobeStackFor(const PreparedEnvironment& environment, const Scene& scene,
                                                          bool everything, bool none) {
    if (none || !environment.filter) return {};
    std::vector<std::shared_ptr<const LobeStackEntry>> lobes = makeStackEntries(environment, scene);
    if (everything) {
        const int baseSize = environment.filter->baseSize();
        for (int index : lobesNear(lobesInUse(scene, baseSize), baseSize))
            lobes.push_back(std::make_shared<const LobeStackEntry>(makeStackEntry(environment, index)));
    }
    return lobes;
}

// An output picture's format from its extension: .exr (linear float) or one Qt writes, else a
// UsageError naming the flag (checked before anything is drawn).
void checkImageFormat(const std::string& flag, const fs::path& file) {
    const std::string ext = lowerExtension(file);
    if (ext == ".exr") return;
    const QByteArray format = QByteArray::fromStdString(ext.empty() ? ext : ext.substr(1));
    if (format.isEmpty() || !QImageWriter::supportedImageFormats().contains(format))
        throw UsageError(flag + " " + file.string() + ": no image format for '" + ext + "' (.exr, .png, .jpg, ...)");
}

// Refuses an output whose folder cannot take a file, naming it, before anything is drawn (a
// turntable never stops half-written for want of a folder). A missing folder is made when the
// first file is written (writeAtomically), so then its nearest existing parent must take one.
void checkWritableFolder(const fs::path& file) {
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    fs::path existing = folder;
    std::error_code ec;
    while (!fs::exists(existing, ec) && existing != existing.parent_path())
        existing = existing.has_parent_path() ? existing.parent_path() : fs::path(".");
    if (!fs::is_directory(existing, ec))
        throw std::runtime_error(folder.string() + ": cannot write " + file.filename().string() + " there: " +
                                 existing.string() + " is not a folder");
    // Only trying tells (permissions, a read-only mount, root's rights): a nameless file, as the
    // atomic write makes, or a named probe where the file system has none.
    int fd = ::open(existing.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
    if (fd < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) {
        std::string probe = (existing / ".mipgloss-probe-XXXXXX").string();
        fd = ::mkstemp(probe.data());
        if (fd >= 0) ::unlink(probe.c_str());
    }
    if (fd < 0)
        throw std::runtime_error(folder.string() + ": cannot write " + file.filename().string() + " there: " +
                                 std::strerror(errno));
    ::close(fd);
}

// PNG, JPEG... through the atomic write, the format from the extension as QImage::save(path) picks it.
void saveImage(const QImage& image, const fs::path& file) {
    const QByteArray format = QFileInfo(QString::fromStdString(file.string())).suffix().toLower().toLatin1();
    ui::writeFileAtomically(file, [&](QIODevice& device) { return image.save(&device, format.constData()); });
}

// One render: the tone-mapped picture and, when asked, the linear one (bottom row first).
struct Picture {
    QImage image;
    std::vector<glm::vec4> hdr;
    int width = 0, height = 0;
};

Picture draw(ui::OffscreenRenderer& renderer, const Scene& scene, const OrbitCamera& camera,
             const std::shared_ptr<const PreparedEnvironment>& environment, int width, int height, bool linear,
             const fs::path& out) {
    Picture p;
    p.image = renderer.render(scene, camera, environment, width, height);
    if (p.image.isNull()) throw std::runtime_error(out.string() + ": the render failed");
    p.width = width;
    p.height = height;
    if (linear) {
        int w = 0, h = 0;
        p.hdr = renderer.lastHdr(w, h);
        if (w != width || h != height) throw std::runtime_error(out.string() + ": the render failed");
    }
    return p;
}

// .exr: the linear picture (float RGB); anything else the tone-mapped one. Atomically either way.
void writePicture(const Picture& p, const fs::path& file) {
    if (lowerExtension(file) == ".exr") {
        std::vector<float> rgb;
        rgb.reserve(static_cast<std::size_t>(p.width) * static_cast<std::size_t>(p.height) * 3);
        for (int y = p.height - 1; y >= 0; --y)  // hdr is bottom row first; the file top row first
            for (int x = 0; x < p.width; ++x) {
                const glm::vec4& c = p.hdr[static_cast<std::size_t>(y) * static_cast<std::size_t>(p.width) +
                                           static_cast<std::size_t>(x)];
                rgb.insert(rgb.end(), {c.r, c.g, c.b});
            }
        writeFloatChannels(file, p.width, p.height, {"R", "G", "B"}, rgb);
    } else {
        saveImage(p.image, file);
    }
}

// The comparison: columns [0, W/2) from `left`, [W/2, W) from `right`; the tone-mapped picture
// gets a 1-pixel divider in the right half's first column, the linear one stays data.
Picture besideEachOther(Picture left, const Picture& right) {
    const int half = left.width / 2;
    for (int y = 0; y < left.height; ++y) {
        auto* to = reinterpret_cast<QRgb*>(left.image.scanLine(y));
        const auto* from = reinterpret_cast<const QRgb*>(right.image.constScanLine(y));
        std::copy(from + half, from + left.width, to + half);
        if (half < left.width) to[half] = qRgb(255, 255, 255);
    }
    if (!left.hdr.empty())
        for (int y = 0; y < left.height; ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(left.width);
            std::copy(right.hdr.begin() + static_cast<std::ptrdiff_t>(row + static_cast<std::size_t>(half)),
                      right.hdr.begin() + static_cast<std::ptrdiff_t>(row + static_cast<std::size_t>(left.width)),
                      left.hdr.begin() + static_cast<std::ptrdiff_t>(row + static_cast<std::size_t>(half)));
        }
    return left;
}

// Entry `name` of library `file`. Throws LibraryFileError naming the file.
LibraryMaterial libraryEntry(const fs::path& file, const std::string& name) {
    ui::LibraryFileReport report;
    const MaterialLibrary library = ui::loadLibrary(file, &report);
    printWarnings(report.warnings);
    if (const LibraryMaterial* entry = library.find(name)) return *entry;
    std::string names;
    for (const LibraryMaterial& e : library.entries) names += (names.empty() ? "\"" : ", \"") + e.name + "\"";
    throw ui::LibraryFileError(
        file, "no material named \"" + name + "\"" +
                  (names.empty() ? std::string(" (the library is empty)") : " (there are " + names + ")"));
}

// The scene `options` ask for: a file, meshes, the environment alone, or the default (whose
// picture is 1024x384 unless --size says), with the flags' changes made. Warnings on stderr.
// The glTF camera --camera names: in the first --mesh asset, by name, else by index.
struct FileCamera {
    AssetCamera camera;
    Transform placement;  // the asset's, as addAsset placed it
};

AssetCamera chooseCamera(const Asset& asset, const fs::path& file, const std::string& wanted) {
    for (const AssetCamera& c : asset.cameras)
        if (c.name == wanted) return c;
    if (!wanted.empty() && wanted.find_first_not_of("0123456789") == std::string::npos && wanted.size() < 9) {
        const std::size_t index = std::stoul(wanted);
        if (index < asset.cameras.size()) return asset.cameras[index];
    }
    std::string names;
    for (std::size_t i = 0; i < asset.cameras.size(); ++i)
        names += (i ? ", " : "") + std::to_string(i) + " \"" + asset.cameras[i].name + "\"";
    throw AssetError(file, "has no camera \"" + wanted + "\"" +
                               (names.empty() ? std::string(" (it has no perspective camera)") : " (its cameras: " + names + ")"));
}

Scene sceneToRender(const RenderOptions& o, const std::optional<LibraryMaterial>& libraryMaterial, int& width,
                    int& height, EncodedImages& keptImages, std::optional<FileCamera>& fileCamera) {
    Scene scene;
    if (o.scene) {
        ui::SceneFileReport report;
        scene = ui::loadScene(*o.scene, &report);
        printWarnings(report.warnings, o.quiet);
    } else if (!o.meshes.empty() || o.environment) {
        scene.display = DisplaySettings{};
    } else {
        scene = makeFigure1Scene();
        if (width == 0) width = 1024, height = 384;
    }
    if (width == 0) width = 800, height = 600;
    if (!o.meshes.empty()) {
        scene.objects.clear();
        float cursor = 0.0f;
        for (const fs::path& p : o.meshes) {
            // An asset (glTF, OBJ with MTL) brings its parts and materials; a plain mesh is one part.
            const Asset asset = loadAsset(p);
            printWarnings(asset.warnings, o.quiet);
            keptImages.insert(asset.images.begin(), asset.images.end());  // from the parse that read them
            const Transform placement = nextInRow(assetBounds(asset), cursor);
            addAsset(scene, asset, p.string(), placement, Material{});
            if (o.camera && !fileCamera) fileCamera = FileCamera{chooseCamera(asset, p, *o.camera), placement};
        }
    }
    if (libraryMaterial) {
        // One material, shared by every object; the scene's own go.
        scene.materials.clear();
        const MaterialId id = scene.addMaterial(libraryMaterial->name, libraryMaterial->material, libraryMaterial->name);
        for (SceneObject& object : scene.objects) object.material = id;
    }
    if (o.environment) scene.environment.source = o.environment->string();
    if (o.envSize) scene.environment.faceSize = *o.envSize;
    if (o.builder) scene.environment.builder = *o.builder;
    for (NamedMaterial& m : scene.materials) {
        // With a layer flag every material is layered, --lambda/--exponent its specular lobe.
        if (o.layers.any() || (o.lambda && m.material.layered)) {
            applyLayerFlags(o.layers, o.lambda, o.lambdaFlag, m.material);
        } else if (o.lambda) {
            m.material.lambda = *o.lambda;
        }
        if (o.mode) m.material.mode = *o.mode;
    }
    if (o.exposure) scene.display.exposureEv = *o.exposure;
    if (o.toneMap) scene.display.toneMap = *o.toneMap;
    if (o.scattering) scene.display.scattering = *o.scattering;
    if (o.backgroundLambda) scene.display.backgroundLambda = *o.backgroundLambda;
    if (o.noBackground) scene.display.showBackground = false;
    if (o.background) scene.display.showBackground = false, scene.display.backdrop = *o.background;
    if (o.envRotation) scene.display.environmentRotationDegrees = *o.envRotation;
    if (o.samples) scene.display.samples = *o.samples;
    return scene;
}

// The scene's own camera (its field of view and framing as saved; --size gives the aspect),
// unless its objects were replaced; else framed. --yaw/--pitch frame again from there.
OrbitCamera cameraToRender(const RenderOptions& o, const Scene& scene, float aspect,
                           const std::optional<FileCamera>& fileCamera) {
    if (fileCamera) return viewThrough(fileCamera->camera, fileCamera->placement, sceneBounds(scene));
    OrbitCamera camera = scene.camera && o.meshes.empty() ? *scene.camera : framingCamera(scene, aspect);
    if (o.yaw || o.pitch) {
        if (o.yaw) camera.yawDegrees = *o.yaw;
        if (o.pitch) camera.pitchDegrees = *o.pitch;
        camera.frame(sceneBounds(scene), aspect);
    }
    return camera;
}

// --aov: the single-lobe account, and for a scene with a layered material each layer's (render's
// usage text): X.dirX X.dirY X.dirZ X.exponent X.weight.R X.weight.G X.weight.B, and NdotV.
void writeAov(const ui::AovImage& aov, const fs::path& file) {
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
    writeFloatChannels(file, aov.width, aov.height, names, values);
}

// How long the work before the first picture took.
struct PrepareTimes {
    double textures = 0.0, environment = 0.0, lobes = 0.0;
};

// The status line: `counters` are those of the render that was plain (a comparison's left half).
void reportRender(const std::string& what, const std::string& extra, int width, int height, const Scene& scene,
                  const PreparedEnvironment& environment, std::size_t lobes, const PrepareTimes& times,
                  const TextureCache& textures, const ui::RenderCounters& c, const ui::OffscreenRenderer& renderer) {
    std::cerr << "mipgloss: " << what << ": " << width << "x" << height << ", " << scene.objects.size()
              << " objects (" << c.objectsDrawn << " drawn, " << c.objectsCulled
              << " culled), environment " << environment.settings.faceSize << "² "
              << builderName(environment.settings.builder) << " filtered through level "
              << environment.lastFilteredLevel << " of " << environment.levelCount() - 1
              << (environment.irradiance ? ", irradiance" : "") << ", " << lobes
              << " lobe stack entries made in " << times.lobes << " s (" << static_cast<double>(c.stackBytes) / 1e6
              << " MB on the GPU; " << c.objectsSettled
              << " objects settled), environment prepared in " << times.environment << " s"
              << (c.textureUploads > 0 ? ", " + std::to_string(textures.images()) + " textures decoded in " +
                                             std::to_string(times.textures) + " s (" +
                                             std::to_string(c.textureBytes / 1000000) + " MB on the GPU)"
                                       : std::string())
              << extra << "; "
              << renderer.glDescription() << '\n';
}

}  // namespace

int runRender(Args args, const char* argv0) {
    const RenderOptions o = parseRenderOptions(std::move(args));
    const fs::path firstOut = o.firstOut();
    checkImageFormat("--out", firstOut);
    // Read before the OpenGL session starts, so a bad library is reported at once.
    const std::optional<LibraryMaterial> libraryMaterialEntry =
        o.library ? std::optional(libraryEntry(*o.library, *o.libraryMaterial)) : std::nullopt;
    OffscreenSession session(argv0, "render");
    ui::OffscreenRenderer& renderer = session.renderer();
    // Before anything is loaded or drawn: what the OpenGL cannot draw, and a folder that cannot
    // take the pictures.
    int width = o.width, height = o.height;
    checkRenderSize(renderer, "--size", width, height, o.samples);
    checkWritableFolder(firstOut);
    if (o.aov) checkWritableFolder(*o.aov);
    EncodedImages keptImages;  // the assets' embedded images, kept from the parse that read them
    std::optional<FileCamera> fileCamera;
    Scene scene = sceneToRender(o, libraryMaterialEntry, width, height, keptImages, fileCamera);
    const bool linear = lowerExtension(firstOut) == ".exr";

    // The materials' texture maps, decoded on worker threads (textures.h); one that cannot be read
    // is a warning, and the maps reading it are drawn without it.
    PrepareTimes times;
    const auto texturesStart = std::chrono::steady_clock::now();
    const auto textures = std::make_shared<TextureCache>();  // this command's
    renderer.setTextures(textures);
    printWarnings(textures->load(texturesOf(scene), keptImages), o.quiet);
    times.textures = secondsSince(texturesStart);

    const auto start = std::chrono::steady_clock::now();
    auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(scene.environment, chainNeeds(scene, scene.environment.faceSize)));
    times.environment = secondsSince(start);
    printWarnings(environment->report.warnings, o.quiet);

    const OrbitCamera camera = cameraToRender(o, scene, static_cast<float>(width) / static_cast<float>(height), fileCamera);
    const float rotation = scene.display.environmentRotationDegrees;
    // The scene turned by `degrees` (turntable.h): the camera to draw through, the scene's
    // environment rotation set to match.
    auto turned = [&](double degrees) {
        const TurnedView view = turnedView(camera, rotation, o.spinKind, static_cast<float>(degrees));
        scene.display.environmentRotationDegrees = view.environmentRotationDegrees;
        return view.camera;
    };

    // The settled picture: each lobe in use from the lobe stack. Made once: turning the view
    // changes no lobe.
    const auto lobesStart = std::chrono::steady_clock::now();
    const std::vector<std::shared_ptr<const LobeStackEntry>> lobes =
        lobeStackFor(*environment, scene, o.noSettle, o.noStack);
    times.lobes = secondsSince(lobesStart);
    renderer.setLobes(lobes);
    ui::RenderCounters plainCounters;
    auto report = [&](const std::string& extra) {
        if (!o.quiet)
            reportRender(o.out->string(), extra, width, height, scene, *environment, lobes.size(), times, *textures,
                         plainCounters, renderer);
    };

    std::ostringstream extra;
    if (o.turntable) {
        // N frames of a whole turn: frame i at --spin + 360·i/N, so the last is one step before
        // the first and the loop is seamless.
        const auto framesStart = std::chrono::steady_clock::now();
        for (int i = 0; i < *o.turntable; ++i) {
            const double degrees = o.spin.value_or(0.0f) + 360.0 * i / *o.turntable;
            const fs::path file = o.frames.format(i);
            writePicture(draw(renderer, scene, turned(degrees), environment, width, height, linear, file), file);
            plainCounters = renderer.counters();
            if (!o.quiet)
                std::cerr << "mipgloss: frame " << i + 1 << "/" << *o.turntable << " (" << degrees << "°): "
                          << file.string() << '\n';
        }
        const double framesSeconds = secondsSince(framesStart);
        extra << "; " << *o.turntable << " frames, " << turntableSpinName(o.spinKind) << " spin, in " << framesSeconds
              << " s (" << framesSeconds / *o.turntable << " s a frame)";
        report(extra.str());
        return 0;
    }

    const OrbitCamera view = o.spin ? turned(*o.spin) : camera;
    const auto drawStart = std::chrono::steady_clock::now();
    Picture picture = draw(renderer, scene, view, environment, width, height, linear, *o.out);
    plainCounters = renderer.counters();
    if (o.compare()) {
        // The right half: the same scene and camera, the environment built the other way (or
        // from the other file) at the same face size, its own lobe stack made for it.
        EnvironmentSettings other = scene.environment;
        if (o.compareBuilder) other.builder = *o.compareBuilder;
        if (o.compareEnv) other.source = o.compareEnv->string();
        const auto otherStart = std::chrono::steady_clock::now();
        auto otherEnvironment = std::make_shared<const PreparedEnvironment>(
            prepareEnvironment(other, chainNeeds(scene, other.faceSize)));
        printWarnings(otherEnvironment->report.warnings, o.quiet);
        renderer.setLobes(lobeStackFor(*otherEnvironment, scene, o.noSettle, o.noStack));
        const double otherSeconds = secondsSince(otherStart);
        picture = besideEachOther(std::move(picture), draw(renderer, scene, view, otherEnvironment, width, height,
                                                           linear, *o.out));
        extra << "; right half: environment " << (o.compareEnv ? o.compareEnv->string() : other.source) << " "
              << builderName(other.builder) << ", prepared with its lobe stack in " << otherSeconds << " s";
    }
    writePicture(picture, *o.out);
    if (o.spin) extra << "; " << turntableSpinName(o.spinKind) << " spin " << *o.spin << "°";
    extra << "; drawn and written in " << secondsSince(drawStart) << " s";
    if (o.aov) writeAov(renderer.renderAov(scene, view, environment, width, height), *o.aov);
    report(extra.str());
    return 0;
}

}  // namespace mipgloss::app
