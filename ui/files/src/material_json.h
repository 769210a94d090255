// The one place for a material's JSON fields, shared by scene files (scene_file.h) and library
// files (library_file.h): "lambda", "phongExponent", "mode", "useIrradiance", "tint",
// "sharperAtGrazing", and the typed, checked reading every file of ours does. Private to mipgloss_ui.
#pragma once

#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/scene.h"

#include <QByteArray>
#include <QJsonArray>
#include <QJsonObject>
#include <QJsonValue>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace mipgloss::ui {

// "where.key", or "key" at the top level: how errors name a key.
std::string keyName(const std::string& where, const char* key);

template <class T>
std::string show(T value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

// A JSON value as it appears in the file, for error messages: 3, "abc", null, [1,2], "an object".
std::string jsonText(const QJsonValue& v);

QJsonArray vec3ToJson(const glm::vec3& v);

// A material's fields (without a name): λ, its Phong exponent for the reader (null for the mirror),
// the mode, irradiance, tint and grazing options; a layered material adds "layers":
//   {"baseColor": [r, g, b], "metallic": m, "roughness": r, "specularExponent": n | null,
//    "specular": f0, "coat": c, "coatRoughness": r, "coatExponent": n | null}
// (every value in [0, 1]; the exponents, n = roughnessToExponent, are for readers and not read).
// A file without "layers" holds the paper's single-lobe material, as every older file does.
// Texture maps (assets) go in "layers"."maps", each texture {"file", "image" (a glTF's embedded
// image), "channel"} with the file relative to `fileForPaths` as scene files write paths
// (relativePathForScene; empty: written as held), and read back resolved against the file read.
QJsonObject materialToJson(const Material& material, const std::filesystem::path& fileForPaths = {});

// Reads the values of one JSON file, each checked for its type and range; every error names the
// file and the key (fail, which each kind of file makes throw its own FileError type), warnings
// name the file too.
class JsonReader {
public:
    // `warnings` may be null (the warnings are then dropped).
    JsonReader(const std::filesystem::path& file, std::vector<std::string>* warnings)
        : file_(file), warnings_(warnings) {}
    virtual ~JsonReader() = default;
    JsonReader(const JsonReader&) = delete;
    JsonReader& operator=(const JsonReader&) = delete;

    [[noreturn]] virtual void fail(const std::string& reason) const = 0;
    void warn(const std::string& text) const;
    const std::filesystem::path& file() const { return file_; }

    // How λ is read: version 1 scene files meant a mip level of their own face size (scene_file.h).
    // Every other file has today's meaning, the default.
    void setLegacyLambda(bool legacy, int faceSize) {
        legacyLambda_ = legacy;
        legacyFaceSize_ = faceSize;
    }

    // The top of one of our files: valid JSON, an object, "format" equal to `format`, "version"
    // from 1 to `newestVersion` (returned in `version`); `noun` names the kind of file in the
    // errors ("not a scene: ...").
    QJsonObject document(const QByteArray& json, const char* format, const std::string& noun, int newestVersion,
                         int& version) const;

    QJsonObject object(const QJsonObject& parent, const char* key, const std::string& where,
                       bool required) const;
    double number(const QJsonObject& o, const char* key, const std::string& where, double fallback) const;
    double finite(const QJsonValue& v, const std::string& where) const;
    int integer(const QJsonObject& o, const char* key, const std::string& where, int fallback) const;
    bool boolean(const QJsonObject& o, const char* key, const std::string& where, bool fallback) const;
    // `fallback` null: the key is required.
    std::string string(const QJsonObject& o, const char* key, const std::string& where,
                       const std::string* fallback) const;
    glm::vec3 vec3(const QJsonObject& o, const char* key, const std::string& where, glm::vec3 fallback) const;

    // Clamps to [lo, hi] with a warning that says what was read and what is used.
    template <class T>
    T clamped(T value, T lo, T hi, const std::string& where) const {
        const T c = std::clamp(value, lo, hi);
        if (c != value)
            warn("\"" + where + "\" " + show(value) + " is outside [" + show(lo) + ", " + show(hi) +
                 "]; using " + show(c));
        return c;
    }

    // The fields of materialToJson, at `where` ("materials[2]"). Optional keys default to Material{}.
    Material material(const QJsonObject& o, const std::string& where) const;
    // A layered material's "layers" object (scene version 5, library version 2), at `where`.
    Layers layers(const QJsonObject& o, const std::string& where) const;
    // A layered material's "maps" (scene version 7, library version 3), at `where`.
    MaterialMaps maps(const QJsonObject& o, const std::string& where) const;
    // A λ (a material's or the background's) in today's meaning: an error unless the file holds a
    // number in its version's range, converted from a version 1 scene's face size (scene_file.h).
    double lambdaValue(const QJsonObject& o, const char* key, const std::string& where) const;

private:
    // "phongExponent" beside a material's λ: information, validated, checked for agreement with a
    // warning (scene_file.h).
    void checkExponent(const QJsonObject& o, const std::string& where, float lambda) const;

    std::filesystem::path file_;
    std::vector<std::string>* warnings_;
    bool legacyLambda_ = false;
    int legacyFaceSize_ = kLambdaReferenceSize;
};

}  // namespace mipgloss::ui
