#include "render_command.h"

#include "frame_pattern.h"
#include "material_args.h"
#include "offscreen_session.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/assets/asset.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/framing.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/io/image_file.h"
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/assets/mesh_files.h"
#include "mipgloss/scene/placement.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/assets/textures.h"
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
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
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
                  [--coat-roughness R] [--size WxH] [--env-size N] [--builder NAME]
                  [--exposure EV] [--tonemap linear|reinhard|aces] [--background-lambda L]
                  [--no-background] [--yaw DEG] [--pitch DEG] [--samples N] [--no-settle | --no-stack] [--quiet]
                  [--spin DEG] [--turntable N] [--turntable-spin object|environment]
                  [--compare-builder NAME] [--compare-env FILE]
                  [--aov AOV.exr] --out IMAGE.png|IMAGE.exr|PATTERN
  mipgloss bench-render [--objects N] [--size WxH] [--frames F] [--mesh FILE | --million]

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
  --size WxH     image size (default 1024x384 for the default scene, else 800x600); at most
                 what the OpenGL can draw (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE,
                 GL_MAX_VIEWPORT_DIMS), and --samples at most GL_MAX_SAMPLES
  --yaw DEG --pitch DEG
                 the camera's angles (the scene is framed again from there)
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
  sharing one lambda (the paper: the per-object statement is free), ratio printed. With --mesh:
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
    std::vector<std::shared_ptr<const LobeStackEntry>> lobes;
    if (none || !environment.filter) return lobes;
    const int baseSize = environment.filter->baseSize();
    std::vector<int> indices = lobesInUse(scene, baseSize);
    if (everything) {
        const std::vector<int> ahead = lobesNear(indices, baseSize);
        indices.insert(indices.end(), ahead.begin(), ahead.end());
    }
    for (int index : indices) lobes.push_back(std::make_shared<const LobeStackEntry>(makeStackEntry(environment, index)));
    return lobes;
}

// --size WxH: two whole numbers of at least 1, or a UsageError naming the flag and the value. What
// the OpenGL can draw is checked once a context exists (checkRenderSize).
void parseSize(const std::string& flag, const std::string& text, int& w, int& h) {
    const auto x = text.find('x');
    auto whole = [&](const std::string& part, const char* axis) {
        char* end = nullptr;
        errno = 0;
        const long long v = part.empty() ? 0 : std::strtoll(part.c_str(), &end, 10);
        if (part.empty() || *end != '\0' || errno == ERANGE || v > 1'000'000'000)
            throw UsageError(flag + " needs WxH, two whole numbers such as 800x600, got '" + text + "'");
        if (v < 1) throw UsageError(flag + " " + text + ": the " + axis + " " + part + " must be at least 1");
        return static_cast<int>(v);
    };
    if (x == std::string::npos)
        throw UsageError(flag + " needs WxH, two whole numbers such as 800x600, got '" + text + "'");
    w = whole(text.substr(0, x), "width");
    h = whole(text.substr(x + 1), "height");
}

// Refuses, before anything is drawn, a size or a sample count this OpenGL cannot draw
// (RenderSizeLimits), naming the flag, the value and the limit.
void checkRenderSize(const ui::OffscreenRenderer& renderer, const std::string& sizeFlag, int w, int h,
                     std::optional<int> samples) {
    const ui::RenderSizeLimits limits = renderer.maxRenderSize();
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    if (w > limits.maxWidth)
        throw UsageError(sizeFlag + " " + size + ": the width " + std::to_string(w) + " is beyond this OpenGL's limit of " +
                         std::to_string(limits.maxWidth) + " (" + limits.widthLimit + ")");
    if (h > limits.maxHeight)
        throw UsageError(sizeFlag + " " + size + ": the height " + std::to_string(h) + " is beyond this OpenGL's limit of " +
                         std::to_string(limits.maxHeight) + " (" + limits.heightLimit + ")");
    if (samples && *samples > limits.maxSamples)
        throw UsageError("--samples " + std::to_string(*samples) + " is beyond this OpenGL's limit of " +
                         std::to_string(limits.maxSamples) + " (GL_MAX_SAMPLES)");
}

std::string lowerExtension(const fs::path& file) {
    std::string s = file.extension().string();
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
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

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
    bool noBackground = false, quiet = false, noSettle = false, noStack = false;
    int width = 0, height = 0;
    std::optional<float> spin;
    std::optional<int> turntable;
    TurntableSpin spinKind = TurntableSpin::Object;
    std::optional<Builder> compareBuilder;
    std::optional<fs::path> compareEnv;
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
        else if (a == "--exposure") exposure = parseFloat(a, value(), -kMaxExposureEv, kMaxExposureEv);
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
            parseSize(a, value(), width, height);
        } else if (a == "--spin") {
            spin = parseFloat(a, value(), -36000.0f, 36000.0f);
        } else if (a == "--turntable") {
            const std::string v = value();
            char* end = nullptr;
            errno = 0;
            const long n = std::strtol(v.c_str(), &end, 10);
            if (v.empty() || *end != '\0' || errno == ERANGE || n < 1 || n > 3600)
                throw UsageError("--turntable needs a whole number of frames from 1 to 3600, got '" + v + "'");
            turntable = static_cast<int>(n);
        } else if (a == "--turntable-spin") {
            const std::string v = value();
            if (!parseTurntableSpin(v, spinKind))
                throw UsageError("--turntable-spin is object or environment, got '" + v + "'");
        } else if (a == "--compare-builder") {
            const std::string name = value();
            Builder b;
            if (!parseBuilder(name, b)) throw UsageError("unknown builder '" + name + "' for --compare-builder");
            compareBuilder = b;
        } else if (a == "--compare-env") {
            compareEnv = value();
        } else if (a == "--no-background") noBackground = true;
        else if (a == "--quiet") quiet = true;
        else if (a == "--no-settle") noSettle = true;
        else if (a == "--no-stack") noStack = true;
        else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else if (!scenePath) scenePath = a;
        else throw UsageError("more than one scene given");
    }
    if (!outPath) throw UsageError("render needs --out IMAGE");
    if (libraryPath.has_value() != libraryMaterial.has_value())
        throw UsageError("--library LIB.mglib and --material NAME go together");
    const bool compare = compareBuilder || compareEnv;
    const char* const compareFlag = compareBuilder ? "--compare-builder" : "--compare-env";
    if (compare && turntable) throw UsageError(std::string(compareFlag) + " and --turntable do not go together (one picture or a turn)");
    if (compare && aovPath) throw UsageError(std::string(compareFlag) + " and --aov do not go together (the AOV of which half?)");
    if (turntable && aovPath) throw UsageError("--turntable and --aov do not go together");
    if (noSettle && noStack) throw UsageError("--no-settle and --no-stack do not go together (the stack ahead, or none?)");
    // With --turntable, --out names the frames (frame_pattern.h); the first frame's name stands
    // for all of them in the checks below.
    FramePattern frames;
    if (turntable) {
        if (const std::string problem = parseFramePattern(outPath->string(), frames); !problem.empty())
            throw UsageError("--out " + outPath->string() + " with --turntable: " + problem);
    }
    const fs::path firstOut = turntable ? fs::path(frames.format(0)) : *outPath;
    checkImageFormat("--out", firstOut);
    // Read before the OpenGL session starts, so a bad library is reported at once.
    const std::optional<LibraryMaterial> libraryMaterialEntry =
        libraryPath ? std::optional(libraryEntry(*libraryPath, *libraryMaterial)) : std::nullopt;
    OffscreenSession session(argv0, "render");
    ui::OffscreenRenderer& renderer = session.renderer();
    // Before anything is loaded or drawn: what the OpenGL cannot draw, and a folder that cannot
    // take the pictures.
    checkRenderSize(renderer, "--size", width, height, samples);
    checkWritableFolder(firstOut);
    if (aovPath) checkWritableFolder(*aovPath);

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
    EncodedImages keptImages;  // the assets' embedded images, from the parse that read them
    if (!meshPaths.empty()) {
        scene.objects.clear();
        float cursor = 0.0f;
        for (const fs::path& p : meshPaths) {
            // An asset (glTF, OBJ with MTL) brings its parts and materials; a plain mesh is one part.
            const Asset asset = loadAsset(p);
            keptImages.insert(asset.images.begin(), asset.images.end());
            if (!quiet)
                for (const std::string& w : asset.warnings) std::cerr << "mipgloss: warning: " << w << '\n';
            addAsset(scene, asset, p.string(), nextInRow(assetBounds(asset), cursor), Material{});
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
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const bool linear = lowerExtension(firstOut) == ".exr";

    // The materials' texture maps, decoded on worker threads (textures.h); one that cannot be read
    // is a warning, and the maps reading it are drawn without it.
    const auto texturesStart = std::chrono::steady_clock::now();
    const auto textures = std::make_shared<TextureCache>();  // this command's
    renderer.setTextures(textures);
    for (const std::string& w : textures->load(texturesOf(scene), keptImages))
        if (!quiet) std::cerr << "mipgloss: warning: " << w << '\n';
    const double textureSeconds = secondsSince(texturesStart);

    const auto start = std::chrono::steady_clock::now();
    auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(scene.environment, needsFor(scene, scene.environment.faceSize)));
    const double prepareSeconds = secondsSince(start);
    if (!quiet)
        for (const std::string& w : environment->report.warnings)
            std::cerr << "mipgloss: warning: " << w << '\n';

    // The scene's own camera (its field of view and framing as saved; --size gives the aspect),
    // unless its objects were replaced; else framed. --yaw/--pitch frame again from there.
    OrbitCamera camera = scene.camera && meshPaths.empty() ? *scene.camera : framingCamera(scene, aspect);
    if (yaw || pitch) {
        if (yaw) camera.yawDegrees = *yaw;
        if (pitch) camera.pitchDegrees = *pitch;
        camera.frame(sceneBounds(scene), aspect);
    }
    const float rotation = scene.display.environmentRotationDegrees;
    // The scene turned by `degrees` (turntable.h): the camera to draw through, the scene's
    // environment rotation set to match.
    auto turned = [&](double degrees) {
        const TurnedView view = turnedView(camera, rotation, spinKind, static_cast<float>(degrees));
        scene.display.environmentRotationDegrees = view.environmentRotationDegrees;
        return view.camera;
    };

    // The settled picture: each lobe in use from the lobe stack. Made once: turning the view
    // changes no lobe.
    const auto lobesStart = std::chrono::steady_clock::now();
    const std::vector<std::shared_ptr<const LobeStackEntry>> lobes =
        lobeStackFor(*environment, scene, noSettle, noStack);
    const double lobeSeconds = secondsSince(lobesStart);
    renderer.setLobes(lobes);
    // The status line, with the counters of the render that was `plain` (a comparison's left half).
    ui::RenderCounters plainCounters;
    auto report = [&](const std::string& what, const std::string& extra) {
        if (quiet) return;
        const ui::RenderCounters& c = plainCounters;
        std::cerr << "mipgloss: " << what << ": " << width << "x" << height << ", " << scene.objects.size()
                  << " objects (" << c.objectsDrawn << " drawn, " << c.objectsCulled
                  << " culled), environment " << environment->settings.faceSize << "² "
                  << builderName(environment->settings.builder) << " filtered through level "
                  << environment->lastFilteredLevel << " of " << environment->levelCount() - 1
                  << (environment->irradiance ? ", irradiance" : "") << ", " << lobes.size()
                  << " lobe stack entries made in " << lobeSeconds << " s (" << static_cast<double>(c.stackBytes) / 1e6
                  << " MB on the GPU; " << c.objectsSettled
                  << " objects settled), environment prepared in " << prepareSeconds << " s"
                  << (c.textureUploads > 0 ? ", " + std::to_string(textures->images()) + " textures decoded in " +
                                                 std::to_string(textureSeconds) + " s (" +
                                                 std::to_string(c.textureBytes / 1000000) + " MB on the GPU)"
                                           : std::string())
                  << extra << "; "
                  << renderer.glDescription() << '\n';
    };

    if (turntable) {
        // N frames of a whole turn: frame i at --spin + 360·i/N, so the last is one step before
        // the first and the loop is seamless.
        const auto framesStart = std::chrono::steady_clock::now();
        const double first = spin.value_or(0.0f);
        for (int i = 0; i < *turntable; ++i) {
            const double degrees = first + 360.0 * i / *turntable;
            const fs::path file = frames.format(i);
            writePicture(draw(renderer, scene, turned(degrees), environment, width, height, linear, file), file);
            plainCounters = renderer.counters();
            if (!quiet)
                std::cerr << "mipgloss: frame " << i + 1 << "/" << *turntable << " (" << degrees << "°): "
                          << file.string() << '\n';
        }
        const double framesSeconds = secondsSince(framesStart);
        std::ostringstream extra;
        extra << "; " << *turntable << " frames, " << turntableSpinName(spinKind) << " spin, in " << framesSeconds
              << " s (" << framesSeconds / *turntable << " s a frame)";
        report(outPath->string(), extra.str());
        return 0;
    }

    const OrbitCamera view = spin ? turned(*spin) : camera;
    const auto drawStart = std::chrono::steady_clock::now();
    Picture picture = draw(renderer, scene, view, environment, width, height, linear, *outPath);
    plainCounters = renderer.counters();
    std::ostringstream extra;
    if (compare) {
        // The right half: the same scene and camera, the environment built the other way (or
        // from the other file) at the same face size, its own lobe stack made for it.
        EnvironmentSettings other = scene.environment;
        if (compareBuilder) other.builder = *compareBuilder;
        if (compareEnv) other.source = compareEnv->string();
        const auto otherStart = std::chrono::steady_clock::now();
        auto otherEnvironment = std::make_shared<const PreparedEnvironment>(
            prepareEnvironment(other, needsFor(scene, other.faceSize)));
        if (!quiet)
            for (const std::string& w : otherEnvironment->report.warnings)
                std::cerr << "mipgloss: warning: " << w << '\n';
        renderer.setLobes(lobeStackFor(*otherEnvironment, scene, noSettle, noStack));
        const double otherSeconds = secondsSince(otherStart);
        picture = besideEachOther(std::move(picture), draw(renderer, scene, view, otherEnvironment, width, height,
                                                           linear, *outPath));
        extra << "; right half: environment " << (compareEnv ? compareEnv->string() : other.source) << " "
              << builderName(other.builder) << ", prepared with its lobe stack in " << otherSeconds << " s";
    }
    writePicture(picture, *outPath);
    if (spin) extra << "; " << turntableSpinName(spinKind) << " spin " << *spin << "°";
    extra << "; drawn and written in " << secondsSince(drawStart) << " s";
    if (aovPath) {
        const ui::AovImage aov = renderer.renderAov(scene, view, environment, width, height);
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
    report(outPath->string(), extra.str());
    return 0;
}

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

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
    for (const std::string& w : asset.warnings) std::cerr << "mipgloss: warning: " << w << '\n';
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
    for (const std::string& w : textures->load(texturesOf(scene), asset.images)) std::cerr << "mipgloss: warning: " << w << '\n';
    const double decodeMs = millisecondsSince(start);
    std::size_t triangles = 0, vertices = 0;
    for (const SceneObject& o : scene.objects) triangles += o.mesh->triangleCount(), vertices += o.mesh->vertexCount();
    auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(scene.environment, needsFor(scene, scene.environment.faceSize)));
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
            parseSize(a, value(), width, height);
        } else throw UsageError("unknown option '" + a + "'");
    }
    OffscreenSession session(argv0, "bench-render");
    ui::OffscreenRenderer& renderer = session.renderer();
    checkRenderSize(renderer, "--size", width, height, std::nullopt);
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
