#include "library_command.h"

#include "cli_report.h"
#include "library_options.h"
#include "material_args.h"
#include "offscreen_session.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/textures.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/library.h"
#include "mipgloss/ui/atomic_file.h"
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/thumbnail.h"

#include <QIODevice>
#include <QImage>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <charconv>
#include <sstream>

namespace fs = std::filesystem;

namespace mipgloss::app {

const char* const kLibraryUsage = R"(
  mipgloss library list LIB.mglib [--json]
  mipgloss library add LIB.mglib --name NAME [--lambda L | --exponent N] [--mode reflect|normal]
                       [--tint R,G,B] [--irradiance] [--grazing]
                       [--base-color R,G,B] [--metallic M] [--roughness R] [--specular F0]
                       [--coat W] [--coat-roughness R] [--specular-weight W] [--specular-color R,G,B]
  mipgloss library import-gltf LIB.mglib ASSET
  mipgloss library remove LIB.mglib NAME
  mipgloss library rename LIB.mglib OLD NEW
  mipgloss library thumbnails LIB.mglib [--env FILE] [--size PX] [--env-size N] --out DIR

library: the material library files mipgloss-gui keeps (format "mipgloss-library", docs/library.md).
  Every change is written atomically (the file is the old one or the new one, whatever happens),
  and a file that cannot be read (corrupt, a newer version, not a library) is refused, named,
  and left as it is.
  list           one material a line, tab-separated: name, lambda, Phong exponent n (mirror for
                 lambda 0), mode, tint (linear R,G,B), then "irradiance" and "sharper-at-grazing"
                 when set; a layered material: name, "layered", then base-color R,G,B, metallic,
                 roughness, specular, coat, coat-roughness (and "irradiance"); --json prints the
                 library as JSON instead
  add            adds material NAME (a missing LIB.mglib is created; a name already there is an
                 error); --lambda L (0 = mirror .. 8, default 0) or --exponent N (Phong, >= 0,
                 "mirror"), --mode (default reflect; normal with a high lambda is the paper's
                 diffuse), --tint (default 1,1,1), --irradiance (normal mode: the irradiance map
                 instead of the chain), --grazing (sharper toward grazing angles); any of
                 --base-color, --metallic, --roughness, --specular, --coat, --coat-roughness,
                 --specular-weight, --specular-color makes it a layered material (as for render; --lambda/--exponent then set its
                 glossy layer's lobe, --irradiance its diffuse base from the irradiance map)
  import-gltf    adds every material of ASSET (glTF .gltf/.glb, or OBJ with its MTL) under its
                 name in the file (" 2", " 3" after a name the library has), layered, with its
                 texture maps referring to the asset's images by absolute path (docs/assets.md)
  remove         removes material NAME
  rename         renames material OLD to NEW (NEW must be free)
  thumbnails     one PNG per material in DIR (created if missing), PX x PX pixels (default
                 256): a sphere wearing it in front of the environment (--env FILE as for bake,
                 default the embedded one; --env-size N its base face size, default 128), named
                 after the material made file-name safe (DIR/<name>.png); needs an X display
)";

namespace {

// One library subcommand's LIB.mglib, and the rule that a library that cannot be read is never
// written: `load` throws, so nothing after it runs.
MaterialLibrary load(const fs::path& file) {
    ui::LibraryFileReport report;
    MaterialLibrary library = ui::loadLibrary(file, &report);
    printWarnings(report.warnings);
    return library;
}

ui::LibraryFileError nameTaken(const fs::path& file, const std::string& name) {
    return ui::LibraryFileError(file, "a material named \"" + name + "\" is already in the library");
}

ui::LibraryFileError noSuchName(const fs::path& file, const std::string& name) {
    return ui::LibraryFileError(file, "no material named \"" + name + "\"");
}

std::string exponentText(float lambda) {
    const double n = lambdaToExponent(static_cast<double>(lambda));
    if (std::isinf(n)) return "mirror";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, n >= 100.0 ? "%.0f" : "%.3g", n);
    return buffer;
}

// The shortest text that reads back as the same float (so `list` round-trips every value).
std::string numberText(float value) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, value).ptr;
    return std::string(text, end);
}

// A layered material's values, tab-separated as `list` prints them (every one, so a script can
// read them back).
std::string layersText(const Layers& l, const std::string& separator) {
    return "base-color " + numberText(l.baseColor.r) + ',' + numberText(l.baseColor.g) + ',' +
           numberText(l.baseColor.b) + separator + "metallic " + numberText(l.metallic) + separator + "roughness " +
           numberText(l.roughness) + separator + "specular " + numberText(l.specular) + separator + "coat " +
           numberText(l.coat) + separator + "coat-roughness " + numberText(l.coatRoughness);
}

std::string describe(const Material& m) {
    if (m.layered) return "layered: " + layersText(m.layers, ", ");
    return "lambda " + numberText(m.lambda) + ", n " + exponentText(m.lambda) + ", " + lookupModeName(m.mode);
}

int list(Args args) {
    const fs::path file = libraryArgument(args, "list");
    bool json = false;
    while (!args.empty()) {
        const std::string a = args.next();
        if (a == "--json") json = true;
        else throw UsageError("library list: unknown argument '" + a + "'");
    }
    const MaterialLibrary library = load(file);
    if (json) {
        std::cout << ui::libraryToJson(library).toStdString();
        return 0;
    }
    for (const LibraryMaterial& entry : library.entries) {
        const Material& m = entry.material;
        if (m.layered) {
            std::cout << entry.name << "\tlayered\t" << layersText(m.layers, "\t")
                      << (m.useIrradiance ? "\tirradiance" : "");
            // Texture maps (an imported asset's): which parameters come from a texture.
            const MaterialMaps& maps = m.layers.maps;
            const std::pair<const char*, const TextureRef*> textures[] = {
                {"base-color", &maps.baseColor}, {"metallic", &maps.metallic},   {"roughness", &maps.roughness},
                {"normal", &maps.normal},        {"occlusion", &maps.occlusion}, {"emissive", &maps.emissive}};
            for (const auto& [what, ref] : textures)
                if (!ref->empty()) std::cout << "\t" << what << "-map " << ref->key();
            std::cout << '\n';
            continue;
        }
        std::cout << entry.name << '\t' << "lambda " << numberText(m.lambda) << '\t' << "n " << exponentText(m.lambda)
                  << '\t' << lookupModeName(m.mode) << '\t' << "tint " << numberText(m.tint.r) << ','
                  << numberText(m.tint.g) << ',' << numberText(m.tint.b) << (m.useIrradiance ? "\tirradiance" : "")
                  << (m.sharperAtGrazing ? "\tsharper-at-grazing" : "") << '\n';
    }
    return 0;
}

int add(Args args) {
    const LibraryAddOptions options = parseLibraryAddOptions(std::move(args));
    const fs::path& file = options.file;
    const std::string& name = options.name;
    const Material& material = options.material;
    if (material.useIrradiance && material.mode != LookupMode::Normal)
        printWarnings({"--irradiance shows only with --mode normal"});
    // A library that does not exist yet starts empty; one that exists and cannot be read is refused.
    std::error_code ec;
    const bool exists = fs::exists(file, ec);
    if (ec) throw ui::LibraryFileError(file, "cannot read: " + ec.message());
    MaterialLibrary library = exists ? load(file) : MaterialLibrary{};
    if (library.contains(name)) throw nameTaken(file, name);
    library.entries.push_back({name, material});
    ui::saveLibrary(library, file);
    std::cout << "added \"" << name << "\" (" << describe(material) << ") to " << file.string() << '\n';
    return 0;
}

int importGltf(Args args) {
    const fs::path file = libraryArgument(args, "import-gltf");
    if (args.empty()) throw UsageError("library import-gltf needs ASSET (a .gltf, .glb or .obj file)");
    const fs::path assetPath = fs::absolute(args.next()).lexically_normal();
    if (!args.empty()) throw UsageError("library import-gltf takes one ASSET");
    if (!isAssetFile(assetPath)) throw UsageError("library import-gltf: " + assetPath.string() + " is not a .gltf, .glb or .obj file");
    const Asset asset = loadAsset(assetPath);
    printWarnings(asset.warnings);
    if (asset.materials.empty()) throw AssetError(assetPath, "has no materials to import");
    std::error_code ec;
    const bool exists = fs::exists(file, ec);
    if (ec) throw ui::LibraryFileError(file, "cannot read: " + ec.message());
    MaterialLibrary library = exists ? load(file) : MaterialLibrary{};
    std::vector<std::string> added;
    // A map whose image file is not there is kept (the library names the file; it draws once the
    // file is put back) but said now, naming the material and the file, rather than found later.
    std::vector<std::string> missing;
    for (const AssetMaterial& m : asset.materials)
        for (const TextureRef& ref : m.material.layers.maps.textures())
            if (ref.image < 0 && !ref.empty() && !fs::is_regular_file(ref.file, ec))
                missing.push_back(assetPath.string() + ": material \"" + m.name + "\" reads " + ref.file +
                                  ", which is not there (kept: its maps draw without it until the file is)");
    printWarnings(missing);
    for (const AssetMaterial& m : asset.materials) {
        LibraryMaterial entry = libraryEntryOf(m);
        const std::string name = entry.name = library.uniqueName(entry.name);
        library.entries.push_back(std::move(entry));
        added.push_back("\"" + name + "\"" + (name == m.name ? std::string() : " (\"" + m.name + "\" in the file)") +
                        (m.material.layers.maps.anyTexture() ? ", textured" : ""));
    }
    ui::saveLibrary(library, file);  // one write: all of the asset's materials or none
    for (const std::string& a : added) std::cout << "added " << a << '\n';
    std::cout << added.size() << (added.size() == 1 ? " material" : " materials") << " from " << assetPath.string() << " added to " << file.string() << '\n';
    return 0;
}

int remove(Args args) {
    const fs::path file = libraryArgument(args, "remove");
    if (args.empty()) throw UsageError("library remove needs NAME");
    const std::string name = args.next();
    if (!args.empty()) throw UsageError("library remove takes one NAME");
    MaterialLibrary library = load(file);
    const int index = library.indexOf(name);
    if (index < 0) throw noSuchName(file, name);
    library.entries.erase(library.entries.begin() + index);
    ui::saveLibrary(library, file);
    std::cout << "removed \"" << name << "\" from " << file.string() << '\n';
    return 0;
}

int rename(Args args) {
    const fs::path file = libraryArgument(args, "rename");
    if (args.empty()) throw UsageError("library rename needs OLD and NEW");
    const std::string from = args.next();
    if (args.empty()) throw UsageError("library rename needs NEW");
    const std::string to = requireName("NEW", args.next());
    if (!args.empty()) throw UsageError("library rename takes OLD and NEW only");
    MaterialLibrary library = load(file);
    LibraryMaterial* entry = library.find(from);
    if (!entry) throw noSuchName(file, from);
    if (from == to) {
        std::cout << "\"" << from << "\" keeps its name; " << file.string() << " is unchanged\n";
        return 0;
    }
    if (library.contains(to)) throw nameTaken(file, to);
    entry->name = to;
    ui::saveLibrary(library, file);
    std::cout << "renamed \"" << from << "\" to \"" << to << "\" in " << file.string() << '\n';
    return 0;
}

int thumbnails(Args args, const char* argv0) {
    const LibraryThumbnailOptions options = parseLibraryThumbnailOptions(std::move(args));
    const fs::path& file = options.file;
    const fs::path& outDir = options.outDir;
    const EnvironmentSettings& settings = options.environment;
    const int size = options.size;
    const MaterialLibrary library = load(file);
    if (library.entries.empty()) {
        std::cout << file.string() << " has no materials; no thumbnails written\n";
        return 0;
    }
    OffscreenSession session(argv0, "library thumbnails");
    // One prepared environment serves every material (thumbnailNeeds).
    const auto environment = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(settings, thumbnailNeeds(settings.faceSize)));
    printWarnings(environment->report.warnings);
    const std::vector<std::string> names = thumbnailFileNames(library);
    const auto textures = std::make_shared<TextureCache>();  // this command's decoded maps
    for (std::size_t i = 0; i < library.entries.size(); ++i) {
        const LibraryMaterial& entry = library.entries[i];
        const QImage image = ui::renderThumbnail(session.renderer(), textures, entry.material, environment, size);
        const fs::path png = outDir / (names[i] + ".png");
        if (image.isNull()) throw std::runtime_error(png.string() + ": the render failed");
        ui::writeFileAtomically(png, [&](QIODevice& device) { return image.save(&device, "PNG"); });
        std::cout << png.string() << '\t' << entry.name << '\n';
    }
    return 0;
}

}  // namespace

int runLibrary(Args args, const char* argv0) {
    if (args.empty()) throw UsageError("library needs a subcommand: list, add, import-gltf, remove, rename or thumbnails");
    const std::string command = args.next();
    if (command == "list") return list(std::move(args));
    if (command == "add") return add(std::move(args));
    if (command == "remove") return remove(std::move(args));
    if (command == "import-gltf") return importGltf(std::move(args));
    if (command == "rename") return rename(std::move(args));
    if (command == "thumbnails") return thumbnails(std::move(args), argv0);
    if (command == "--help" || command == "-h") {
        std::cout << kLibraryUsage;
        return 0;
    }
    throw UsageError("unknown library subcommand '" + command + "' (list, add, import-gltf, remove, rename, thumbnails)");
}

}  // namespace mipgloss::app
