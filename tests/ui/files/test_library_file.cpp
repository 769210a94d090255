// Material library files: round trips, and every kind of bad file refused with the file and the
// reason named and its bytes left as they were.
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ui/library_file.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
namespace fs = std::filesystem;

namespace {

void writeBytes(const fs::path& file, const QByteArray& bytes) {
    QFile out(QString::fromStdString(file.string()));
    ASSERT_TRUE(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
    ASSERT_EQ(out.write(bytes), bytes.size());
}

QByteArray readBytes(const fs::path& file) {
    QFile in(QString::fromStdString(file.string()));
    EXPECT_TRUE(in.open(QIODevice::ReadOnly)) << file;
    return in.readAll();
}

MaterialLibrary fiveMaterials() {
    MaterialLibrary library;
    const auto add = [&](const char* name, float lambda, LookupMode mode) {
        Material m;
        m.lambda = lambda;
        m.mode = mode;
        library.entries.push_back({name, m});
    };
    add("mirror", 0.0f, LookupMode::Reflect);
    add("Gold", 3.0f, LookupMode::Reflect);
    library.entries.back().material.tint = Rgb(1.0f, 0.78f, 0.34f);
    add("brushed steel", 4.37f, LookupMode::Reflect);
    library.entries.back().material.sharperAtGrazing = true;
    add("Café: matte/ish", 6.0f, LookupMode::Reflect);
    add("diffuse", 7.0f, LookupMode::Normal);
    library.entries.back().material.useIrradiance = true;
    return library;
}

// A library file with one material whose fields are `fields` (JSON text without braces).
QByteArray oneMaterial(const std::string& fields) {
    return QByteArray::fromStdString(R"({"format": "mipgloss-library", "version": 1, "materials": [{)" +
                                     fields + "}]}");
}

// Writes `bytes` to DIR/name, loads it expecting a LibraryFileError, checks the error names the
// file and that the file's bytes did not change, and returns the message.
std::string refusal(const QTemporaryDir& dir, const std::string& name, const QByteArray& bytes) {
    const fs::path file = fs::path(dir.path().toStdString()) / name;
    writeBytes(file, bytes);
    std::string message;
    try {
        (void)loadLibrary(file);
        ADD_FAILURE() << name << " loaded";
    } catch (const LibraryFileError& e) {
        EXPECT_EQ(e.file(), file);
        message = e.what();
        EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    }
    EXPECT_EQ(readBytes(file), bytes) << name << ": the bytes changed";
    return message;
}

TEST(LibraryFile, RoundTripsEveryField) {
    QTemporaryDir dir;
    const fs::path file = fs::path(dir.path().toStdString()) / "sub" / "folder" / "library.json";
    const MaterialLibrary library = fiveMaterials();
    saveLibrary(library, file);  // creates the folders
    LibraryFileReport report;
    EXPECT_EQ(loadLibrary(file, &report), library);
    EXPECT_TRUE(report.warnings.empty());
    // Through the JSON text alone too, and an empty library.
    EXPECT_EQ(libraryFromJson(libraryToJson(library), "x.json"), library);
    EXPECT_EQ(libraryFromJson(libraryToJson(MaterialLibrary{}), "x.json"), MaterialLibrary{});
}

TEST(LibraryFile, WritesTheDocumentedFields) {
    const QJsonObject root = QJsonDocument::fromJson(libraryToJson(fiveMaterials())).object();
    EXPECT_EQ(root.value("format").toString(), "mipgloss-library");
    EXPECT_EQ(root.value("version").toInt(), kLibraryVersion);
    const QJsonArray materials = root.value("materials").toArray();
    ASSERT_EQ(materials.size(), 5);
    // In the library's order.
    EXPECT_EQ(materials.at(0).toObject().value("name").toString(), "mirror");
    EXPECT_EQ(materials.at(3).toObject().value("name").toString(), QString::fromUtf8("Café: matte/ish"));
    // The mirror's exponent is null (n = ∞); the others' agree with phong.h.
    EXPECT_TRUE(materials.at(0).toObject().value("phongExponent").isNull());
    const QJsonObject gold = materials.at(1).toObject();
    EXPECT_DOUBLE_EQ(gold.value("phongExponent").toDouble(), lambdaToExponent(3.0));
    EXPECT_EQ(gold.value("mode").toString(), "reflect");
    EXPECT_EQ(materials.at(4).toObject().value("mode").toString(), "normal");
    EXPECT_TRUE(materials.at(4).toObject().value("useIrradiance").toBool());
    EXPECT_TRUE(materials.at(2).toObject().value("sharperAtGrazing").toBool());
}

TEST(LibraryFile, MissingFileIsNoSuchFile) {
    QTemporaryDir dir;
    const fs::path file = fs::path(dir.path().toStdString()) / "absent.json";
    try {
        (void)loadLibrary(file);
        ADD_FAILURE() << "no error for a missing library";
    } catch (const LibraryFileError& e) {
        EXPECT_EQ(e.file(), file);
        EXPECT_EQ(e.reason(), "file not found");
    }
    EXPECT_FALSE(fs::exists(file));
}

TEST(LibraryFile, UnreadableFilesAreRefusedAndKept) {
    QTemporaryDir dir;
    const QByteArray good = libraryToJson(fiveMaterials());
    struct Case {
        const char* name;
        QByteArray bytes;
        const char* reason;  // a part of the message
    };
    const std::vector<Case> cases{
        {"not-json.json", "this is not JSON", "not valid JSON"},
        {"truncated.json", good.left(good.size() / 2), "not valid JSON"},
        {"empty.json", "", "not valid JSON"},
        {"binary.json", QByteArray("\x89PNG\r\n\x1a\n\0\0", 10), "not valid JSON"},
        {"array.json", "[1, 2]", "top level is not a JSON object"},
        {"scene.json", R"({"format": "mipgloss-scene", "version": 3})", "\"mipgloss-scene\", not \"mipgloss-library\""},
        {"noformat.json", R"({"materials": []})", "no \"format\""},
        {"newer.json", R"({"format": "mipgloss-library", "version": 4, "materials": []})",
         "version 4 is newer than this program reads (3)"},
        {"noversion.json", R"({"format": "mipgloss-library", "materials": []})", "\"version\""},
        {"nomaterials.json", R"({"format": "mipgloss-library", "version": 1})", "\"materials\" must be an array"},
        {"materials-object.json", R"({"format": "mipgloss-library", "version": 1, "materials": {}})",
         "\"materials\" must be an array"},
        {"entry-number.json", R"({"format": "mipgloss-library", "version": 1, "materials": [3]})",
         "\"materials[0]\" must be an object"},
        {"duplicate.json", oneMaterial(R"("name": "Gold"}, {"name": "Steel"}, {"name": "Gold")"),
         "\"materials[2].name\" \"Gold\" is already the name of \"materials[0]\""},
        {"noname.json", oneMaterial(R"("lambda": 2)"), "missing \"materials[0].name\""},
        {"name-number.json", oneMaterial(R"("name": 7)"), "\"materials[0].name\" must be a string"},
        {"name-empty.json", oneMaterial(R"("name": "")"), "empty"},
        {"name-blank.json", oneMaterial(R"("name": "   ")"), "white space"},
        {"name-tab.json", oneMaterial(R"("name": "a\tb")"), "control characters"},
        {"lambda-negative.json", oneMaterial(R"("name": "a", "lambda": -1)"),
         "\"materials[0].lambda\" is -1: a blur λ must be a number in [0, 8]"},
        {"lambda-huge.json", oneMaterial(R"("name": "a", "lambda": 1e300)"), "\"materials[0].lambda\" is 1e+300"},
        {"lambda-string.json", oneMaterial(R"("name": "a", "lambda": "3")"), "\"materials[0].lambda\" is \"3\""},
        {"lambda-null.json", oneMaterial(R"("name": "a", "lambda": null)"), "\"materials[0].lambda\" is null"},
        {"exponent-negative.json", oneMaterial(R"("name": "a", "lambda": 2, "phongExponent": -5)"),
         "\"materials[0].phongExponent\" is -5"},
        {"mode.json", oneMaterial(R"("name": "a", "mode": "sideways")"),
         "unknown \"materials[0].mode\" \"sideways\""},
        {"tint-short.json", oneMaterial(R"("name": "a", "tint": [1, 2])"),
         "\"materials[0].tint\" must be an array of three numbers"},
        {"tint-negative.json", oneMaterial(R"("name": "a", "tint": [1, -2, 0])"),
         "\"materials[0].tint\" has a negative component"},
        {"tint-string.json", oneMaterial(R"("name": "a", "tint": [1, "x", 0])"),
         "\"materials[0].tint[1]\" must be a number"},
        {"irradiance.json", oneMaterial(R"("name": "a", "useIrradiance": 1)"),
         "\"materials[0].useIrradiance\" must be true or false"},
        {"grazing.json", oneMaterial(R"("name": "a", "sharperAtGrazing": "yes")"),
         "\"materials[0].sharperAtGrazing\" must be true or false"},
    };
    for (const Case& c : cases) {
        const std::string message = refusal(dir, c.name, c.bytes);
        EXPECT_NE(message.find(c.reason), std::string::npos) << c.name << ": " << message;
    }
}

TEST(LibraryFile, DisagreeingExponentIsAWarningAndTheLambdaWins) {
    LibraryFileReport report;
    const MaterialLibrary library =
        libraryFromJson(oneMaterial(R"("name": "a", "lambda": 2, "phongExponent": 5)"), "lib.json", &report);
    ASSERT_EQ(library.entries.size(), 1u);
    EXPECT_EQ(library.entries[0].material.lambda, 2.0f);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("lib.json"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("materials[0].phongExponent"), std::string::npos) << report.warnings[0];
}

TEST(LibraryFile, SaveRefusesWhatWouldNotLoadAndKeepsTheOldFile) {
    QTemporaryDir dir;
    const fs::path file = fs::path(dir.path().toStdString()) / "library.json";
    saveLibrary(fiveMaterials(), file);
    const QByteArray before = readBytes(file);
    const auto refused = [&](const MaterialLibrary& library, const std::string& reason) {
        try {
            saveLibrary(library, file);
            ADD_FAILURE() << "saved; expected " << reason;
        } catch (const LibraryFileError& e) {
            EXPECT_EQ(e.file(), file);
            EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
        }
        EXPECT_EQ(readBytes(file), before);
    };
    MaterialLibrary duplicate = fiveMaterials();
    duplicate.entries.push_back(duplicate.entries[1]);
    refused(duplicate, "material 6 \"Gold\": the name is already material 2's");
    MaterialLibrary badName = fiveMaterials();
    badName.entries[0].name = "two\nlines";
    refused(badName, "control characters");
    MaterialLibrary badLambda = fiveMaterials();
    badLambda.entries[2].material.lambda = 9.0f;
    refused(badLambda, "λ 9 is not in [0, 8]");
    MaterialLibrary badTint = fiveMaterials();
    badTint.entries[2].material.tint = Rgb(1.0f, -1.0f, 1.0f);
    refused(badTint, "tint");
}

// Layered materials (version 2): every parameter round-trips exactly, the file names them as
// material_json.h says, and a version 1 file (no "layers") loads its single-lobe materials as ever.
TEST(LibraryFile, LayeredMaterialsRoundTripEveryParameter) {
    MaterialLibrary library = fiveMaterials();
    Material paint;
    paint.layered = true;
    paint.layers = {Rgb(0.6f, 0.05f, 0.02f), 0.0f, 0.45f, 0.05f, 1.0f, 0.03f, MaterialMaps{}};
    library.entries.push_back({"car paint", paint});
    Material gold;
    gold.layered = true;
    gold.useIrradiance = true;
    gold.layers = {Rgb(1.0f, 0.766f, 0.336f), 1.0f, 0.0f, 0.04f, 0.0f, 0.05f, MaterialMaps{}};  // a mirror-smooth metal
    library.entries.push_back({"polished gold", gold});
    EXPECT_EQ(libraryFromJson(libraryToJson(library), "x.json"), library);

    const QJsonArray materials = QJsonDocument::fromJson(libraryToJson(library)).object().value("materials").toArray();
    const QJsonObject layers = materials.at(5).toObject().value("layers").toObject();
    EXPECT_DOUBLE_EQ(layers.value("roughness").toDouble(), 0.45f);
    EXPECT_DOUBLE_EQ(layers.value("coat").toDouble(), 1.0);
    EXPECT_NEAR(layers.value("specularExponent").toDouble(), 0.37 * (std::pow(0.45, -4) - 1), 1e-3);
    EXPECT_TRUE(materials.at(6).toObject().value("layers").toObject().value("specularExponent").isNull());
    EXPECT_FALSE(materials.at(0).toObject().contains("layers")) << "single-lobe materials write none";

    const MaterialLibrary old = libraryFromJson(oneMaterial(R"("name": "a", "lambda": 2)"), "v1.json");
    ASSERT_EQ(old.entries.size(), 1u);
    EXPECT_FALSE(old.entries[0].material.layered);
}

TEST(LibraryFile, OutOfRangeLayerValuesAreRefusedNamingTheKey) {
    QTemporaryDir dir;
    const std::string metallic =
        refusal(dir, "metallic.json", oneMaterial(R"("name": "a", "layers": {"metallic": 1.5})"));
    EXPECT_NE(metallic.find("materials[0].layers.metallic"), std::string::npos) << metallic;
    EXPECT_NE(metallic.find("1.5"), std::string::npos) << metallic;
    const std::string colour =
        refusal(dir, "colour.json", oneMaterial(R"("name": "a", "layers": {"baseColor": [0.5, -0.1, 0.2]})"));
    EXPECT_NE(colour.find("materials[0].layers.baseColor[1]"), std::string::npos) << colour;
    const std::string nan = refusal(dir, "nan.json", oneMaterial(R"("name": "a", "layers": {"roughness": "rough"})"));
    EXPECT_NE(nan.find("materials[0].layers.roughness"), std::string::npos) << nan;
    const std::string shape = refusal(dir, "shape.json", oneMaterial(R"("name": "a", "layers": 3)"));
    EXPECT_NE(shape.find("materials[0].layers"), std::string::npos) << shape;

    MaterialLibrary bad = fiveMaterials();
    bad.entries[1].material.layered = true;
    bad.entries[1].material.layers.coat = -0.5f;
    const fs::path file = fs::path(dir.path().toStdString()) / "save.json";
    try {
        saveLibrary(bad, file);
        ADD_FAILURE() << "saved a coat of -0.5";
    } catch (const LibraryFileError& e) {
        EXPECT_NE(std::string(e.what()).find("coat -0.5 is not in [0, 1]"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(file));
}

TEST(LibraryFile, DefaultPathIsInTheUsersDataFolder) {
    const fs::path path = defaultLibraryPath();
    EXPECT_EQ(path.filename(), "library.json");
    EXPECT_TRUE(path.is_absolute()) << path;
}

}  // namespace
