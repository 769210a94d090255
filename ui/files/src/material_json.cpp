#include "material_json.h"

#include "mipgloss/ui/scene_file.h"

#include "mipgloss/ibl/specular.h"

#include <QJsonDocument>

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace mipgloss::ui {

namespace {

// Version 1 scene files clamped λ to [0, 16] (its old kMaxLambda), so they may hold anything in there.
constexpr double kLegacyMaxLambda = 16.0;
// "phongExponent" agrees with λ when within this relative difference (see scene_file.h).
constexpr double kExponentTolerance = 1e-4;

}  // namespace

std::string keyName(const std::string& where, const char* key) {
    return where.empty() ? std::string(key) : where + "." + key;
}

std::string jsonText(const QJsonValue& v) {
    if (v.isObject()) return "an object";
    const QByteArray text = QJsonDocument(QJsonArray{v}).toJson(QJsonDocument::Compact);
    return text.mid(1, text.size() - 2).toStdString();  // without the array's brackets
}

QJsonArray vec3ToJson(const glm::vec3& v) { return QJsonArray{v.x, v.y, v.z}; }

namespace {

QJsonObject textureToJson(const TextureRef& t, const std::filesystem::path& fileForPaths) {
    QJsonObject out{
        {"file", QString::fromStdString(fileForPaths.empty() ? t.file : relativePathForScene(t.file, fileForPaths))},
        {"channel", t.channel},
    };
    if (t.image >= 0) out.insert("image", t.image);
    return out;
}

QJsonObject mapsToJson(const MaterialMaps& m, const std::filesystem::path& fileForPaths) {
    QJsonObject out;
    const std::pair<const char*, const TextureRef*> textures[] = {
        {"baseColorTexture", &m.baseColor}, {"metallicTexture", &m.metallic},   {"roughnessTexture", &m.roughness},
        {"normalTexture", &m.normal},       {"occlusionTexture", &m.occlusion}, {"emissiveTexture", &m.emissive},
    };
    for (const auto& [key, ref] : textures)
        if (!ref->empty()) out.insert(QLatin1String(key), textureToJson(*ref, fileForPaths));
    out.insert("normalScale", m.normalScale);
    out.insert("occlusionStrength", m.occlusionStrength);
    out.insert("emissiveFactor", vec3ToJson(m.emissiveFactor));
    out.insert("baseAlpha", m.baseAlpha);
    out.insert("alphaMode", alphaModeName(m.alphaMode));
    out.insert("alphaCutoff", m.alphaCutoff);
    out.insert("doubleSided", m.doubleSided);
    // How each map is read (MapSlot order), written only when one differs from glTF's default.
    if (std::any_of(m.sampling.begin(), m.sampling.end(), [](const TextureSampling& s) { return s != TextureSampling{}; })) {
        QJsonArray sampling;
        for (const TextureSampling& s : m.sampling)
            sampling.append(QJsonObject{{"texCoord", s.texCoord},
                                        {"wrapS", textureWrapName(s.wrapS)},
                                        {"wrapT", textureWrapName(s.wrapT)},
                                        {"nearestMagnify", s.nearestMagnify},
                                        {"nearestMinify", s.nearestMinify},
                                        {"offset", QJsonArray{s.offset.x, s.offset.y}},
                                        {"scale", QJsonArray{s.scale.x, s.scale.y}},
                                        {"rotation", s.rotation}});
        out.insert("sampling", sampling);
    }
    return out;
}

}  // namespace

QJsonObject materialToJson(const Material& m, const std::filesystem::path& fileForPaths) {
    const double exponent = lambdaToExponent(static_cast<double>(m.lambda));
    QJsonObject out{
        {"lambda", m.lambda},
        {"phongExponent", std::isinf(exponent) ? QJsonValue(QJsonValue::Null) : QJsonValue(exponent)},
        {"mode", lookupModeName(m.mode)},
        {"useIrradiance", m.useIrradiance},
        {"tint", vec3ToJson(m.tint)},
        {"sharperAtGrazing", m.sharperAtGrazing},
    };
    if (!m.layered) return out;
    const Layers& l = m.layers;
    // The lobes' exponents are for a reader of the file, like "phongExponent"; roughness decides.
    auto exponentJson = [](double n) { return std::isinf(n) ? QJsonValue(QJsonValue::Null) : QJsonValue(n); };
    out.insert("layers", QJsonObject{
                             {"baseColor", vec3ToJson(l.baseColor)},
                             {"metallic", l.metallic},
                             {"roughness", l.roughness},
                             {"specularExponent", exponentJson(roughnessToExponent(l.roughness))},
                             {"specular", l.specular},
                             {"specularColor", vec3ToJson(l.specularColor)},
                             {"specularWeight", l.specularWeight},
                             {"coat", l.coat},
                             {"coatRoughness", l.coatRoughness},
                             {"coatExponent", exponentJson(roughnessToExponent(l.coatRoughness))},
                         });
    if (!(l.maps == MaterialMaps{})) {
        QJsonObject layers = out.value("layers").toObject();
        layers.insert("maps", mapsToJson(l.maps, fileForPaths));
        out.insert("layers", layers);
    }
    return out;
}

void JsonReader::warn(const std::string& text) const {
    if (warnings_) warnings_->push_back(file_.string() + ": " + text);
}

QJsonObject JsonReader::document(const QByteArray& json, const char* format, const std::string& noun,
                                 int newestVersion, int& version) const {
    QJsonParseError parseError;
    const QJsonDocument doc = QJsonDocument::fromJson(json, &parseError);
    if (parseError.error != QJsonParseError::NoError)
        fail("not valid JSON at byte " + std::to_string(parseError.offset) + ": " +
             parseError.errorString().toStdString());
    if (!doc.isObject()) fail("not a " + noun + ": the top level is not a JSON object");
    const QJsonObject root = doc.object();
    const QJsonValue formatValue = root.value("format");
    if (formatValue.toString() != QLatin1String(format))
        fail("not a " + noun + ": " +
             (formatValue.isUndefined() ? std::string("it has no \"format\"")
                                        : "\"format\" is " + jsonText(formatValue) + ", not \"" + format + "\""));
    version = integer(root, "version", "", -1);
    if (version < 1) fail("missing or invalid \"version\"");
    if (version > newestVersion)
        fail(noun + " version " + std::to_string(version) + " is newer than this program reads (" +
             std::to_string(newestVersion) + ")");
    return root;
}

QJsonObject JsonReader::object(const QJsonObject& parent, const char* key, const std::string& where,
                               bool required) const {
    const QJsonValue v = parent.value(QLatin1String(key));
    if (v.isUndefined()) {
        if (required) fail("missing \"" + where + "\"");
        return {};
    }
    if (!v.isObject()) fail("\"" + where + "\" must be an object");
    return v.toObject();
}

double JsonReader::number(const QJsonObject& o, const char* key, const std::string& where,
                          double fallback) const {
    const QJsonValue v = o.value(QLatin1String(key));
    if (v.isUndefined()) return fallback;
    return finite(v, keyName(where, key));
}

double JsonReader::finite(const QJsonValue& v, const std::string& where) const {
    if (!v.isDouble()) fail("\"" + where + "\" must be a number");
    const double d = v.toDouble();
    if (!std::isfinite(d)) fail("\"" + where + "\" is not a finite number");
    return d;
}

int JsonReader::integer(const QJsonObject& o, const char* key, const std::string& where, int fallback) const {
    const double d = number(o, key, where, fallback);
    if (d != std::floor(d) || std::abs(d) > 1e9) fail("\"" + keyName(where, key) + "\" must be a whole number");
    return static_cast<int>(d);
}

bool JsonReader::boolean(const QJsonObject& o, const char* key, const std::string& where, bool fallback) const {
    const QJsonValue v = o.value(QLatin1String(key));
    if (v.isUndefined()) return fallback;
    if (!v.isBool()) fail("\"" + keyName(where, key) + "\" must be true or false");
    return v.toBool();
}

std::string JsonReader::string(const QJsonObject& o, const char* key, const std::string& where,
                               const std::string* fallback) const {
    const QJsonValue v = o.value(QLatin1String(key));
    if (v.isUndefined()) {
        if (!fallback) fail("missing \"" + keyName(where, key) + "\"");
        return *fallback;
    }
    if (!v.isString()) fail("\"" + keyName(where, key) + "\" must be a string");
    return v.toString().toStdString();
}

glm::vec3 JsonReader::vec3(const QJsonObject& o, const char* key, const std::string& where,
                           glm::vec3 fallback) const {
    const QJsonValue v = o.value(QLatin1String(key));
    if (v.isUndefined()) return fallback;
    const std::string name = keyName(where, key);
    if (!v.isArray() || v.toArray().size() != 3) fail("\"" + name + "\" must be an array of three numbers");
    const QJsonArray a = v.toArray();
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const std::string item = name + "[" + std::to_string(i) + "]";
        const double d = finite(a.at(i), item);
        // Held as float: a larger number would become infinite and could not be saved again.
        if (std::abs(d) > static_cast<double>(std::numeric_limits<float>::max()))
            fail("\"" + item + "\" is " + std::to_string(d) + ", beyond single precision");
        out[i] = static_cast<float>(d);
    }
    return out;
}

Material JsonReader::material(const QJsonObject& o, const std::string& where) const {
    Material m;
    m.lambda = static_cast<float>(lambdaValue(o, "lambda", where));
    if (!legacyLambda_) checkExponent(o, where, m.lambda);
    const std::string reflect = lookupModeName(LookupMode::Reflect);
    const std::string mode = string(o, "mode", where, &reflect);
    if (!parseLookupMode(mode, m.mode)) fail("unknown \"" + where + ".mode\" \"" + mode + "\"");
    m.useIrradiance = boolean(o, "useIrradiance", where, m.useIrradiance);
    m.tint = vec3(o, "tint", where, m.tint);
    if (glm::any(glm::lessThan(m.tint, glm::vec3(0.0f)))) fail("\"" + where + ".tint\" has a negative component");
    m.sharperAtGrazing = boolean(o, "sharperAtGrazing", where, m.sharperAtGrazing);
    const QJsonValue layers = o.value(QLatin1String("layers"));
    if (layers.isUndefined()) return m;
    const std::string at = keyName(where, "layers");
    if (!layers.isObject()) fail("\"" + at + "\" must be an object");
    m.layered = true;
    m.layers = this->layers(layers.toObject(), at);
    return m;
}

Layers JsonReader::layers(const QJsonObject& o, const std::string& where) const {
    Layers l;
    // Each a number in [0, 1], never clamped: an absurd value is an error naming the key.
    auto unit = [&](const char* key, float fallback) {
        const double v = number(o, key, where, fallback);
        if (!(v >= 0.0 && v <= 1.0)) fail("\"" + keyName(where, key) + "\" is " + show(v) + ": it must be in [0, 1]");
        return static_cast<float>(v);
    };
    l.baseColor = vec3(o, "baseColor", where, l.baseColor);
    for (int c = 0; c < 3; ++c)
        if (!(l.baseColor[c] >= 0.0f && l.baseColor[c] <= 1.0f))
            fail("\"" + keyName(where, "baseColor") + "[" + std::to_string(c) + "]\" is " + show(l.baseColor[c]) +
                 ": a base colour component must be in [0, 1] (linear)");
    l.metallic = unit("metallic", l.metallic);
    l.roughness = unit("roughness", l.roughness);
    l.specular = unit("specular", l.specular);
    // KHR_materials_specular (scene.h): optional, so files written before it read as glTF's default.
    l.specularColor = vec3(o, "specularColor", where, l.specularColor);
    for (int c = 0; c < 3; ++c)
        if (!(l.specularColor[c] >= 0.0f && l.specularColor[c] <= kMaxSpecularColour))
            fail("\"" + keyName(where, "specularColor") + "[" + std::to_string(c) + "]\" is " + show(l.specularColor[c]) +
                 ": a specular colour component must be in [0, " + show(kMaxSpecularColour) + "]");
    l.specularWeight = unit("specularWeight", l.specularWeight);
    l.coat = unit("coat", l.coat);
    l.coatRoughness = unit("coatRoughness", l.coatRoughness);
    const QJsonValue maps = o.value(QLatin1String("maps"));
    if (!maps.isUndefined()) {
        const std::string at = keyName(where, "maps");
        if (!maps.isObject()) fail("\"" + at + "\" must be an object");
        l.maps = this->maps(maps.toObject(), at);
    }
    return l;
}

MaterialMaps JsonReader::maps(const QJsonObject& o, const std::string& where) const {
    MaterialMaps m;
    auto texture = [&](const char* key, TextureRef& out) {
        const QJsonValue v = o.value(QLatin1String(key));
        if (v.isUndefined()) return;
        const std::string at = keyName(where, key);
        if (!v.isObject()) fail("\"" + at + "\" must be an object");
        const QJsonObject t = v.toObject();
        const std::string stored = string(t, "file", at, nullptr);
        if (stored.empty()) fail("\"" + keyName(at, "file") + "\" is empty");
        out.file = resolvePathForScene(stored, file()).string();
        out.image = integer(t, "image", at, -1);
        if (out.image < -1) fail("\"" + keyName(at, "image") + "\" is " + show(out.image) + ": an image index is >= 0");
        out.channel = integer(t, "channel", at, 0);
        if (out.channel < 0 || out.channel > 3)
            fail("\"" + keyName(at, "channel") + "\" is " + show(out.channel) + ": a channel is 0 (R) to 3 (A)");
    };
    texture("baseColorTexture", m.baseColor);
    texture("metallicTexture", m.metallic);
    texture("roughnessTexture", m.roughness);
    texture("normalTexture", m.normal);
    texture("occlusionTexture", m.occlusion);
    texture("emissiveTexture", m.emissive);
    auto ranged = [&](const char* key, float fallback, double lo, double hi) {
        const double v = number(o, key, where, fallback);
        if (!(v >= lo && v <= hi))
            fail("\"" + keyName(where, key) + "\" is " + show(v) + ": it must be in [" + show(lo) + ", " + show(hi) + "]");
        return static_cast<float>(v);
    };
    m.normalScale = ranged("normalScale", m.normalScale, -kMaxNormalScale, kMaxNormalScale);
    m.occlusionStrength = ranged("occlusionStrength", m.occlusionStrength, 0.0, 1.0);
    m.baseAlpha = ranged("baseAlpha", m.baseAlpha, 0.0, 1.0);
    m.alphaCutoff = ranged("alphaCutoff", m.alphaCutoff, 0.0, 1.0);
    m.emissiveFactor = vec3(o, "emissiveFactor", where, m.emissiveFactor);
    for (int c = 0; c < 3; ++c)
        if (!(m.emissiveFactor[c] >= 0.0f && m.emissiveFactor[c] <= kMaxEmissive))
            fail("\"" + keyName(where, "emissiveFactor") + "[" + std::to_string(c) + "]\" is " +
                 show(m.emissiveFactor[c]) + ": emitted radiance is in [0, " + show(kMaxEmissive) + "]");
    const std::string opaque = alphaModeName(AlphaMode::Opaque);
    const std::string mode = string(o, "alphaMode", where, &opaque);
    if (!parseAlphaMode(mode, m.alphaMode))
        fail("\"" + keyName(where, "alphaMode") + "\" is \"" + mode + "\": it is opaque, mask or blend");
    m.doubleSided = boolean(o, "doubleSided", where, m.doubleSided);
    if (const QJsonValue v = o.value(QLatin1String("sampling")); !v.isUndefined()) {
        const std::string at = keyName(where, "sampling");
        if (!v.isArray() || v.toArray().size() != kMaterialMapCount)
            fail("\"" + at + "\" must be an array of " + std::to_string(kMaterialMapCount) + " objects, one per map");
        const QJsonArray a = v.toArray();
        for (int i = 0; i < kMaterialMapCount; ++i) {
            const std::string item = at + "[" + std::to_string(i) + "]";
            if (!a.at(i).isObject()) fail("\"" + item + "\" must be an object");
            const QJsonObject so = a.at(i).toObject();
            TextureSampling& s = m.sampling[static_cast<std::size_t>(i)];
            s.texCoord = integer(so, "texCoord", item, 0);
            if (s.texCoord != 0 && s.texCoord != 1) fail("\"" + keyName(item, "texCoord") + "\" is " + show(s.texCoord) + ": a UV set is 0 or 1");
            for (const auto& [key, wrap] : {std::pair{"wrapS", &s.wrapS}, std::pair{"wrapT", &s.wrapT}}) {
                const std::string repeat = textureWrapName(TextureWrap::Repeat);
                const std::string name = string(so, key, item, &repeat);
                if (!parseTextureWrap(name, *wrap))
                    fail("\"" + keyName(item, key) + "\" is \"" + name + "\": it is repeat, clamp or mirror");
            }
            s.nearestMagnify = boolean(so, "nearestMagnify", item, false);
            s.nearestMinify = boolean(so, "nearestMinify", item, false);
            for (const auto& [key, pair] : {std::pair{"offset", &s.offset}, std::pair{"scale", &s.scale}}) {
                const QJsonValue pv = so.value(QLatin1String(key));
                if (pv.isUndefined()) continue;
                if (!pv.isArray() || pv.toArray().size() != 2) fail("\"" + keyName(item, key) + "\" must be two numbers");
                for (int c = 0; c < 2; ++c) {
                    const double d = finite(pv.toArray().at(c), keyName(item, key) + "[" + std::to_string(c) + "]");
                    if (std::abs(d) > 1e6) fail("\"" + keyName(item, key) + "\" is beyond 1e6");
                    (*pair)[c] = static_cast<float>(d);
                }
            }
            s.rotation = static_cast<float>(std::remainder(finite(so.value(QLatin1String("rotation")).isUndefined()
                                                                      ? QJsonValue(0.0)
                                                                      : so.value(QLatin1String("rotation")),
                                                                  keyName(item, "rotation")),
                                                           2.0 * std::numbers::pi));
        }
    }
    return m;
}

double JsonReader::lambdaValue(const QJsonObject& o, const char* key, const std::string& where) const {
    const QJsonValue v = o.value(QLatin1String(key));
    if (v.isUndefined()) return 0.0;
    const std::string name = keyName(where, key);
    const double top = legacyLambda_ ? kLegacyMaxLambda : kMaxLambda;
    const std::string range = "a blur λ must be a number in [0, " + show(top) + "]" +
                              (legacyLambda_ ? " in a version 1 file" : "");
    if (!v.isDouble()) fail("\"" + name + "\" is " + jsonText(v) + ": " + range);
    const double stored = v.toDouble();
    if (!(std::isfinite(stored) && stored >= 0.0 && stored <= top))
        fail("\"" + name + "\" is " + show(stored) + ": " + range);
    if (!legacyLambda_) return stored;
    // λ 0 is the mirror under any face size: legacy n = ∞, and λ(∞) = 0.
    return exponentToLambda(legacyLambdaToExponent(stored, legacyFaceSize_));
}

void JsonReader::checkExponent(const QJsonObject& o, const std::string& where, float lambda) const {
    const QJsonValue v = o.value(QLatin1String("phongExponent"));
    if (v.isUndefined()) return;
    const std::string name = keyName(where, "phongExponent");
    const std::string rule = "a Phong exponent must be a finite number >= 0, or null for the mirror";
    double n = kMirrorExponent;
    if (!v.isNull()) {
        if (!v.isDouble()) fail("\"" + name + "\" is " + jsonText(v) + ": " + rule);
        n = v.toDouble();
        if (!std::isfinite(n) || !isValidExponent(n)) fail("\"" + name + "\" is " + show(n) + ": " + rule);
    }
    const double expected = lambdaToExponent(static_cast<double>(lambda));
    const bool agree = std::isinf(n) ? std::isinf(expected)
                                     : std::isfinite(expected) &&
                                           std::abs(n - expected) <= kExponentTolerance * std::max(1.0, expected);
    if (!agree)
        warn("\"" + name + "\" " + jsonText(v) + " disagrees with \"" + keyName(where, "lambda") + "\" " +
             show(lambda) + " (n = " + (std::isinf(expected) ? std::string("mirror") : show(expected)) +
             "); using the λ");
}

}  // namespace mipgloss::ui
