#include "mipgloss/ui/library_file.h"

#include "mipgloss/ui/atomic_file.h"

#include "material_json.h"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QStandardPaths>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include <map>
#include <system_error>

namespace fs = std::filesystem;

namespace mipgloss::ui {

namespace {

class Reader : public JsonReader {
public:
    Reader(const fs::path& file, LibraryFileReport* report)
        : JsonReader(file, report ? &report->warnings : nullptr) {}

    [[noreturn]] void fail(const std::string& reason) const override { throw LibraryFileError(file(), reason); }
};

// Why `material` could not be written so that it loads again, or "".
std::string unsavableMaterial(const Material& material) {
    if (!isValidLambda(static_cast<double>(material.lambda)))
        return "λ " + show(material.lambda) + " is not in [0, " + show(kMaxLambda) + "]";
    const glm::vec3& tint = material.tint;
    if (glm::any(glm::isnan(tint)) || glm::any(glm::isinf(tint)) || glm::any(glm::lessThan(tint, glm::vec3(0.0f))))
        return "the tint must be finite and not negative";
    return layersProblem(material.layers);
}

}  // namespace

QByteArray libraryToJson(const MaterialLibrary& library) {
    QJsonArray materials;
    for (const LibraryMaterial& entry : library.entries) {
        QJsonObject material = materialToJson(entry.material);
        material.insert("name", QString::fromStdString(entry.name));
        materials.append(material);
    }
    const QJsonObject root{{"format", kLibraryFormat}, {"version", kLibraryVersion}, {"materials", materials}};
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

MaterialLibrary libraryFromJson(const QByteArray& json, const fs::path& file, LibraryFileReport* report) {
    LibraryFileReport local;
    const Reader reader(file, &local);
    int version = 0;  // every version up to kLibraryVersion reads the same way
    const QJsonObject root = reader.document(json, kLibraryFormat, "material library", kLibraryVersion, version);

    const QJsonValue materials = root.value("materials");
    if (!materials.isArray()) reader.fail("\"materials\" must be an array");
    const QJsonArray array = materials.toArray();
    MaterialLibrary library;
    std::map<std::string, std::string> whereNamed;  // name -> the key that first named it
    for (qsizetype i = 0; i < array.size(); ++i) {
        const std::string where = "materials[" + std::to_string(i) + "]";
        if (!array.at(i).isObject()) reader.fail("\"" + where + "\" must be an object");
        const QJsonObject m = array.at(i).toObject();
        LibraryMaterial entry;
        entry.name = reader.string(m, "name", where, nullptr);
        if (const std::string problem = materialNameProblem(entry.name); !problem.empty())
            reader.fail("\"" + where + ".name\" " + jsonText(m.value("name")) + ": " + problem);
        if (const auto first = whereNamed.find(entry.name); first != whereNamed.end())
            reader.fail("\"" + where + ".name\" \"" + entry.name + "\" is already the name of \"" +
                        first->second + "\"; names must be unique");
        whereNamed.emplace(entry.name, where);
        entry.material = reader.material(m, where);
        library.entries.push_back(std::move(entry));
    }
    if (report) report->warnings.insert(report->warnings.end(), local.warnings.begin(), local.warnings.end());
    return library;
}

MaterialLibrary loadLibrary(const fs::path& file, LibraryFileReport* report) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw LibraryFileError(file, kFileNotFound);
    if (fs::is_directory(file, ec)) throw LibraryFileError(file, "is a folder, not a library file");
    QFile in(QString::fromStdString(file.string()));
    if (!in.open(QIODevice::ReadOnly)) throw LibraryFileError(file, "cannot read: " + in.errorString().toStdString());
    const QByteArray bytes = in.readAll();
    if (in.error() != QFileDevice::NoError)
        throw LibraryFileError(file, "cannot read: " + in.errorString().toStdString());
    return libraryFromJson(bytes, file, report);
}

void saveLibrary(const MaterialLibrary& library, const fs::path& file) {
    // Never write a file that would not load again.
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < library.entries.size(); ++i) {
        const LibraryMaterial& entry = library.entries[i];
        const std::string where = "cannot save material " + std::to_string(i + 1) + " \"" + entry.name + "\": ";
        if (const std::string problem = materialNameProblem(entry.name); !problem.empty())
            throw LibraryFileError(file, where + problem);
        if (!seen.emplace(entry.name, i).second)
            throw LibraryFileError(file, where + "the name is already material " +
                                             std::to_string(seen[entry.name] + 1) + "'s");
        if (const std::string problem = unsavableMaterial(entry.material); !problem.empty())
            throw LibraryFileError(file, where + problem);
    }
    try {
        writeFileAtomically(file, libraryToJson(library));
    } catch (const FileError& e) {
        throw LibraryFileError(file, e.reason());
    }
}

fs::path defaultLibraryPath() {
    return fs::path(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation).toStdString()) /
           "library.json";
}

}  // namespace mipgloss::ui
