#include "mipgloss/ui/scene_file.h"

#include "mipgloss/assets/asset.h"
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/assets/mesh_files.h"

#include "mipgloss/ui/atomic_file.h"

#include "material_json.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/phong.h"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <system_error>

namespace fs = std::filesystem;

namespace mipgloss::ui {

namespace {

constexpr const char* kBuiltinPrefix = "builtin:";
constexpr const char* kBuiltinTeapot = "builtin:teapot";
constexpr const char* kBuiltinSphere = "builtin:sphere";

// Sensible bounds for the values that are clamped on load (see scene_file.h).
constexpr int kMinFaceSize = 4, kMaxFaceSize = 4096;
constexpr int kMaxSamples = 16;

bool isBuiltin(const std::string& s) { return s.rfind(kBuiltinPrefix, 0) == 0; }

// A saved camera's limits (scene_file.h): the orbit camera's own pitch limit and zoom range.
constexpr float kMaxCameraPitch = 89.0f;
constexpr float kMaxCameraDistance = 1e9f;

// What makes a camera unfit for a file: its key and the reason, or an empty key when nothing does.
struct CameraProblem {
    std::string key, reason;
};
CameraProblem cameraProblem(const OrbitCamera& c) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(c.target[i]))
            return {"camera.target[" + std::to_string(i) + "]", show(c.target[i]) + " is not a finite number"};
    if (!(c.distance > 0.0f && c.distance <= kMaxCameraDistance))
        return {"camera.distance", show(c.distance) + " is not in (0, " + show(kMaxCameraDistance) + "]"};
    if (!std::isfinite(c.yawDegrees)) return {"camera.yawDegrees", show(c.yawDegrees) + " is not a finite number"};
    if (!(std::abs(c.pitchDegrees) <= kMaxCameraPitch))
        return {"camera.pitchDegrees", show(c.pitchDegrees) + " is not in [-" + show(kMaxCameraPitch) + ", " +
                                           show(kMaxCameraPitch) + "]"};
    if (!(c.fovYDegrees >= kMinCameraFovY && c.fovYDegrees <= kMaxCameraFovY))
        return {"camera.fovYDegrees", show(c.fovYDegrees) + " is not in [" + show(kMinCameraFovY) + ", " +
                                          show(kMaxCameraFovY) + "]"};
    return {};
}

fs::path absoluteNormal(const fs::path& p) {
    std::error_code ec;
    fs::path a = fs::absolute(p, ec);
    return (ec ? p : a).lexically_normal();
}

// Reads one scene file's JSON, collecting warnings; every error names the file and the key.
class Reader : public JsonReader {
public:
    Reader(const fs::path& file, SceneFileReport* report)
        : JsonReader(file, report ? &report->warnings : nullptr), report_(report) {}

    [[noreturn]] void fail(const std::string& reason) const override { throw SceneFileError(file(), reason); }

    // How λ is read: version 1 files meant a mip level of their own face size (scene_file.h).
    void setLambdaMeaning(int version, int faceSize) {
        setLegacyLambda(version <= kSceneVersionLegacyLambda, faceSize);
    }

    EnvironmentSettings environment(const QJsonObject& o) const {
        EnvironmentSettings s;
        const std::string where = "environment";
        const std::string builtin = kBuiltinEnvironment;
        const std::string source = string(o, "source", where, &builtin);
        if (source.empty()) fail("\"environment.source\" is empty");
        if (isBuiltin(source)) {
            if (source != kBuiltinEnvironment)
                fail("unknown built-in environment \"" + source + "\" (there is " + builtin + ")");
            s.source = source;
        } else {
            const fs::path resolved = resolvePathForScene(source, file());
            std::error_code ec;
            if (!fs::exists(resolved, ec))
                fail("environment \"" + source + "\" not found (looked for " + resolved.string() + ")");
            s.source = resolved.string();
        }
        const std::string autoLayout = layoutName(EnvLayout::Auto);
        const std::string layout = string(o, "layout", where, &autoLayout);
        if (!parseLayout(layout, s.layout)) fail("unknown \"environment.layout\" \"" + layout + "\"");
        const std::string right = "right";
        const std::string hand = string(o, "handedness", where, &right);
        if (!parseHandedness(hand, s.handedness))
            fail("\"environment.handedness\" must be \"right\" or \"left\", not \"" + hand + "\"");
        s.faceSize = clamped(integer(o, "faceSize", where, s.faceSize), kMinFaceSize, kMaxFaceSize,
                             "environment.faceSize");
        const std::string defaultBuilder = builderName(kDefaultBuilder);
        const std::string builder = string(o, "builder", where, &defaultBuilder);
        if (!parseBuilder(builder, s.builder)) fail("unknown \"environment.builder\" \"" + builder + "\"");
        return s;
    }

    DisplaySettings display(const QJsonObject& o) const {
        DisplaySettings d;
        const std::string where = "display";
        d.showBackground = boolean(o, "showBackground", where, d.showBackground);
        d.backdrop = vec3(o, "backdrop", where, d.backdrop);
        for (int c = 0; c < 3; ++c)
            if (!(d.backdrop[c] >= 0.0f && d.backdrop[c] <= 1.0f))
                fail("\"display.backdrop[" + std::to_string(c) + "]\" is " + show(d.backdrop[c]) + ", not in [0, 1]");
        d.backgroundLambda = static_cast<float>(lambdaValue(o, "backgroundLambda", where));
        d.exposureEv = static_cast<float>(clamped(number(o, "exposureEv", where, d.exposureEv),
                                                  -static_cast<double>(kMaxExposureEv),
                                                  static_cast<double>(kMaxExposureEv),
                                                  "display.exposureEv"));
        const std::string aces = toneMapName(ToneMap::Aces);
        const std::string map = string(o, "toneMap", where, &aces);
        if (!parseToneMap(map, d.toneMap)) fail("unknown \"display.toneMap\" \"" + map + "\"");
        // Absent in files before it: the specification's single scattering, as they were drawn.
        const std::string single = scatteringName(Scattering::Single);
        const std::string scattering = string(o, "scattering", where, &single);
        if (!parseScattering(scattering, d.scattering)) fail("unknown \"display.scattering\" \"" + scattering + "\"");
        const int samples =
            clamped(integer(o, "samples", where, d.samples), 1, kMaxSamples, "display.samples");
        // Multisampling takes powers of two.
        d.samples = static_cast<int>(std::bit_floor(static_cast<unsigned>(samples)));
        if (d.samples != samples)
            warn("\"display.samples\" " + std::to_string(samples) + " is not a power of two; using " +
                 std::to_string(d.samples));
        return d;
    }

    // An angle in degrees, kept in [−180°, 180°]; 0 when absent.
    float rotation(const QJsonObject& o, const char* key, const std::string& where) const {
        return static_cast<float>(std::remainder(number(o, key, where, 0.0), 360.0));
    }

    Transform transform(const QJsonObject& o, const std::string& where) const {
        Transform t;
        t.translation = vec3(o, "translation", where, t.translation);
        t.rotationDegrees = vec3(o, "rotationDegrees", where, t.rotationDegrees);
        t.scale = static_cast<float>(number(o, "scale", where, t.scale));
        if (!(t.scale > 0.0f)) fail("\"" + where + ".scale\" must be positive");
        return t;
    }

    // The saved view (version 6): every key required and checked, nothing clamped (scene_file.h).
    OrbitCamera camera(const QJsonObject& o) const {
        const std::string where = "camera";
        for (const char* key : {"target", "distance", "yawDegrees", "pitchDegrees", "fovYDegrees"})
            if (!o.contains(QLatin1String(key))) fail("missing \"" + keyName(where, key) + "\"");
        OrbitCamera c;
        c.target = vec3(o, "target", where, c.target);
        c.distance = static_cast<float>(number(o, "distance", where, c.distance));
        c.yawDegrees = static_cast<float>(number(o, "yawDegrees", where, c.yawDegrees));
        c.pitchDegrees = static_cast<float>(number(o, "pitchDegrees", where, c.pitchDegrees));
        c.fovYDegrees = static_cast<float>(number(o, "fovYDegrees", where, c.fovYDegrees));
        c.rollDegrees = rotation(o, "rollDegrees", where);  // optional: 0 in files before it
        if (const CameraProblem p = cameraProblem(c); !p.key.empty()) fail("\"" + p.key + "\" " + p.reason);
        return c;
    }

    // Built-ins and files, each loaded once per scene file and shared by the objects using it.
    std::shared_ptr<const Mesh> mesh(const std::string& source, const std::string& where,
                                     std::string& meshSource, int part = -1) {
        if (isBuiltin(source)) {
            meshSource = source;
            auto& cached = cache_[source];
            if (!cached) {
                if (source == kBuiltinTeapot)
                    cached = std::make_shared<const Mesh>(defaultTeapot());
                else if (source == kBuiltinSphere)
                    cached = std::make_shared<const Mesh>(makeSphere());
                else
                    fail("\"" + where + ".mesh\": unknown built-in mesh \"" + source +
                         "\" (there are builtin:teapot and builtin:sphere)");
            }
            return cached;
        }
        const fs::path resolved = resolvePathForScene(source, file());
        meshSource = resolved.string();
        if (part >= 0) return assetPart(resolved, part, where);
        auto& cached = cache_[meshSource];
        if (cached) return cached;
        std::error_code ec;
        if (!fs::is_regular_file(resolved, ec))
            fail("mesh file \"" + source + "\" of " + where + " not found (looked for " +
                 resolved.string() + ")");
        try {
            MeshReport meshReport;
            cached = std::make_shared<const Mesh>(loadMesh(resolved, &meshReport));
            for (const std::string& w : meshReport.warnings) warn(w);
        } catch (const MeshError& e) {
            fail("mesh of " + where + ": " + e.what());
        }
        return cached;
    }

private:
    // Part `part` of an asset file (asset.h), each file read once per scene file.
    std::shared_ptr<const Mesh> assetPart(const fs::path& resolved, int part, const std::string& where) {
        auto& cached = assets_[resolved.string()];
        if (!cached) {
            std::error_code ec;
            if (!fs::is_regular_file(resolved, ec))
                fail("asset file \"" + resolved.string() + "\" of " + where + " not found");
            try {
                cached = std::make_shared<const Asset>(loadAsset(resolved));
                for (const std::string& w : cached->warnings) warn(w);
                if (report_ && !cached->cameras.empty()) report_->cameras[resolved.string()] = cached->cameras;
            } catch (const FileError& e) {
                fail("asset of " + where + ": " + e.what());
            }
        }
        if (static_cast<std::size_t>(part) >= cached->parts.size())
            fail("\"" + where + "\": part " + std::to_string(part) + " of " + resolved.string() + ", which has " +
                 std::to_string(cached->parts.size()) + " parts (the file changed since the scene was saved?)");
        return cached->parts[static_cast<std::size_t>(part)].mesh;
    }

    SceneFileReport* report_;
    std::map<std::string, std::shared_ptr<const Mesh>> cache_;
    std::map<std::string, std::shared_ptr<const Asset>> assets_;
};

}  // namespace

std::string relativePathForScene(const fs::path& target, const fs::path& sceneFile) {
    const std::string text = target.string();
    if (text.empty() || isBuiltin(text)) return text;
    const fs::path absolute = absoluteNormal(target);
    const fs::path relative = absolute.lexically_relative(absoluteNormal(sceneFile).parent_path());
    if (relative.empty()) return absolute.generic_string();
    int ups = 0;
    for (const fs::path& part : relative) ups += part == ".." ? 1 : 0;
    return ups <= 2 ? relative.generic_string() : absolute.generic_string();
}

fs::path resolvePathForScene(const std::string& stored, const fs::path& sceneFile) {
    if (isBuiltin(stored)) return stored;
    const fs::path p(stored);
    if (p.is_absolute()) return p.lexically_normal();
    return (absoluteNormal(sceneFile).parent_path() / p).lexically_normal();
}

QByteArray sceneToJson(const Scene& scene, const fs::path& sceneFile) {
    const EnvironmentSettings& e = scene.environment;
    QJsonObject environment{
        {"source", QString::fromStdString(relativePathForScene(e.source, sceneFile))},
        {"layout", layoutName(e.layout)},
        {"handedness", handednessName(e.handedness)},
        {"faceSize", e.faceSize},
        {"builder", builderName(e.builder)},
    };
    const DisplaySettings& d = scene.display;
    QJsonObject display{
        {"showBackground", d.showBackground}, {"backdrop", vec3ToJson(d.backdrop)},
        {"backgroundLambda", d.backgroundLambda},
        {"exposureEv", d.exposureEv},         {"toneMap", toneMapName(d.toneMap)},
        {"samples", d.samples},
        {"environmentRotationDegrees", d.environmentRotationDegrees},
        {"scattering", scatteringName(d.scattering)},
    };
    // The materials the objects use, once each, in the scene's order.
    QJsonArray materials;
    for (const NamedMaterial& named : scene.materials) {
        if (scene.usersOf(named.id) == 0) continue;
        QJsonObject material = materialToJson(named.material, sceneFile);
        material.insert("name", QString::fromStdString(named.name));
        if (!named.libraryEntry.empty()) material.insert("library", QString::fromStdString(named.libraryEntry));
        materials.append(material);
    }
    QJsonArray objects;
    for (const SceneObject& o : scene.objects) {
        const NamedMaterial* named = scene.findMaterial(o.material);
        QJsonObject transform{
            {"translation", vec3ToJson(o.transform.translation)},
            {"rotationDegrees", vec3ToJson(o.transform.rotationDegrees)},
            {"scale", o.transform.scale},
        };
        QJsonObject object{
            {"name", QString::fromStdString(o.name)},
            {"mesh", QString::fromStdString(relativePathForScene(o.meshSource, sceneFile))},
            {"visible", o.visible},
            {"transform", transform},
        };
        if (o.meshPart >= 0) object.insert("part", o.meshPart);
        if (named) object.insert("material", QString::fromStdString(named->name));
        objects.append(object);
    }
    QJsonObject root{
        {"format", kSceneFormat}, {"version", kSceneVersion}, {"environment", environment},
        {"display", display},     {"materials", materials}, {"objects", objects},
    };
    if (const std::optional<OrbitCamera>& c = scene.camera) {
        root.insert("camera", QJsonObject{
                                  {"target", vec3ToJson(c->target)},
                                  {"distance", c->distance},
                                  {"yawDegrees", c->yawDegrees},
                                  {"pitchDegrees", c->pitchDegrees},
                                  {"fovYDegrees", c->fovYDegrees},
                                  {"rollDegrees", c->rollDegrees},
                              });
    }
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

Scene sceneFromJson(const QByteArray& json, const fs::path& sceneFile, SceneFileReport* report) {
    SceneFileReport local;
    Reader reader(sceneFile, &local);
    int version = 0;
    const QJsonObject root = reader.document(json, kSceneFormat, "scene", kSceneVersion, version);

    Scene scene;
    scene.environment = reader.environment(reader.object(root, "environment", "environment", false));
    reader.setLambdaMeaning(version, scene.environment.faceSize);
    scene.display = reader.display(reader.object(root, "display", "display", false));
    // Versions 1 to 3 kept the rotation with the environment (scene_file.h).
    scene.display.environmentRotationDegrees =
        version >= kSceneVersionRotationInDisplay
            ? reader.rotation(reader.object(root, "display", "display", false), "environmentRotationDegrees", "display")
            : reader.rotation(reader.object(root, "environment", "environment", false), "rotationDegrees", "environment");

    // Version 3: named materials, referred to by name from the objects.
    const QJsonValue materials = root.value("materials");
    if (version >= kSceneVersionNamedMaterials) {
        if (!materials.isUndefined() && !materials.isArray()) reader.fail("\"materials\" must be an array");
        const QJsonArray array = materials.toArray();
        for (qsizetype i = 0; i < array.size(); ++i) {
            const std::string where = "materials[" + std::to_string(i) + "]";
            if (!array.at(i).isObject()) reader.fail("\"" + where + "\" must be an object");
            const QJsonObject m = array.at(i).toObject();
            const std::string name = reader.string(m, "name", where, nullptr);
            if (name.empty()) reader.fail("\"" + where + ".name\" is empty");
            if (scene.findMaterialNamed(name))
                reader.fail("\"" + where + ".name\" \"" + name + "\" names a second material");
            const std::string none;
            const std::string library = reader.string(m, "library", where, &none);
            scene.addMaterial(name, reader.material(m, where), library);
        }
    }

    const QJsonValue objects = root.value("objects");
    if (!objects.isUndefined() && !objects.isArray()) reader.fail("\"objects\" must be an array");
    const QJsonArray array = objects.toArray();
    for (qsizetype i = 0; i < array.size(); ++i) {
        const std::string where = "objects[" + std::to_string(i) + "]";
        if (!array.at(i).isObject()) reader.fail("\"" + where + "\" must be an object");
        const QJsonObject o = array.at(i).toObject();
        SceneObject object;
        const std::string fallbackName = "object " + std::to_string(i + 1);
        object.name = reader.string(o, "name", where, &fallbackName);
        object.visible = reader.boolean(o, "visible", where, true);
        object.transform = reader.transform(reader.object(o, "transform", where + ".transform", false),
                                            where + ".transform");
        if (version >= kSceneVersionNamedMaterials) {
            const std::string none;
            const std::string name = reader.string(o, "material", where, &none);
            if (name.empty()) {
                object.material = scene.addMaterial(object.name, Material{});
            } else {
                const NamedMaterial* named = scene.findMaterialNamed(name);
                if (!named)
                    reader.fail("\"" + where + ".material\" \"" + name + "\" is not in \"materials\"");
                object.material = named->id;
            }
        } else {
            // Versions 1 and 2 kept a material inside each object: it becomes one of its own.
            object.material = scene.addMaterial(
                object.name, reader.material(reader.object(o, "material", where + ".material", false),
                                             where + ".material"));
        }
        const std::string source = reader.string(o, "mesh", where, nullptr);
        object.meshPart = reader.integer(o, "part", where, -1);
        if (object.meshPart < -1) reader.fail("\"" + where + ".part\" is " + std::to_string(object.meshPart) + ": a part is >= 0");
        object.mesh = reader.mesh(source, where + " (\"" + object.name + "\")", object.meshSource, object.meshPart);
        scene.objects.push_back(std::move(object));
    }
    // Version 6: the saved view; older files have none and are framed when opened.
    if (version >= kSceneVersionCamera && root.contains(QLatin1String("camera")))
        scene.camera = reader.camera(reader.object(root, "camera", "camera", true));
    if (report) {
        report->warnings.insert(report->warnings.end(), local.warnings.begin(), local.warnings.end());
        report->cameras.merge(local.cameras);
    }
    return scene;
}

void saveScene(const Scene& scene, const fs::path& file) {
    // Never write a file that would not load again.
    auto checkLambda = [&](float lambda, const std::string& where) {
        if (!isValidLambda(static_cast<double>(lambda)))
            throw SceneFileError(file, "cannot save \"" + where + "\" " + show(lambda) +
                                           ": a blur λ must be in [0, " + show(kMaxLambda) + "]");
    };
    checkLambda(scene.display.backgroundLambda, "display.backgroundLambda");
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        if (o.meshSource.empty())
            throw SceneFileError(file, "object \"" + o.name + "\" has no mesh file to refer to");
        checkLambda(scene.materialOf(o).lambda, "objects[" + std::to_string(i) + "].material.lambda");
        if (const std::string problem = layersProblem(scene.materialOf(o).layers); !problem.empty())
            throw SceneFileError(file, "cannot save \"objects[" + std::to_string(i) + "].material.layers\": " + problem);
    }
    if (scene.camera) {
        if (const CameraProblem p = cameraProblem(*scene.camera); !p.key.empty())
            throw SceneFileError(file, "cannot save \"" + p.key + "\": " + p.reason);
    }
    try {
        writeFileAtomically(file, sceneToJson(scene, file));
    } catch (const FileError& e) {
        throw SceneFileError(file, e.reason());
    }
}

Scene loadScene(const fs::path& file, SceneFileReport* report) {
    QFile in(QString::fromStdString(file.string()));
    if (!in.exists()) throw SceneFileError(file, kFileNotFound);
    if (!in.open(QIODevice::ReadOnly))
        throw SceneFileError(file, "cannot read: " + in.errorString().toStdString());
    return sceneFromJson(in.readAll(), file, report);
}

}  // namespace mipgloss::ui
