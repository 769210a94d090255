// Scene files: round trips, relative paths, shared meshes, version 1 λ keeping its look, and every
// user error naming the file.
#include "mipgloss/assets/default_scene.h"
#include "mipgloss/assets/mesh_files.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/ui/scene_file.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
namespace fs = std::filesystem;

namespace {

fs::path bunnyPath() { return test::asset("meshes/bunny_npm_lowres.obj"); }

void writeText(const fs::path& file, const std::string& text) {
    QFile out(QString::fromStdString(file.string()));
    ASSERT_TRUE(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
    out.write(text.data(), static_cast<qint64>(text.size()));
}

// A minimal valid scene with one object using `mesh`, and `materialJson` as its material: from
// version 3 on, the one entry of "materials" (named "thing"), before that inside the object.
std::string oneObjectScene(const std::string& mesh, const std::string& materialJson = "{}",
                           int version = kSceneVersion) {
    const std::string head = R"({"format": "mipgloss-scene", "version": )" + std::to_string(version) +
                             R"(, "environment": {"source": "builtin:courtyard"},)";
    if (version >= kSceneVersionNamedMaterials) {
        const std::string fields = materialJson.substr(1, materialJson.size() - 2);  // without { }
        return head + R"( "materials": [{"name": "thing")" + (fields.find(':') != std::string::npos ? ", " : "") +
               fields + R"(}], "objects": [{"name": "thing", "mesh": ")" + mesh +
               R"(", "material": "thing"}]})";
    }
    return head + R"( "objects": [{"name": "thing", "mesh": ")" + mesh + R"(", "material": )" +
           materialJson + "}]}";
}

// Where the one material of oneObjectScene is, as error messages name it.
std::string materialKey(const std::string& field, int version = kSceneVersion) {
    return (version >= kSceneVersionNamedMaterials ? "materials[0]." : "objects[0].material.") + field;
}

// Loads `json` written to DIR/name and returns the error message (empty if it loaded).
std::string loadError(const QTemporaryDir& dir, const std::string& name, const std::string& json,
                      SceneFileReport* report = nullptr) {
    const fs::path file = fs::path(dir.path().toStdString()) / name;
    writeText(file, json);
    try {
        (void)loadScene(file, report);
    } catch (const SceneFileError& e) {
        EXPECT_EQ(e.file(), file);
        return e.what();
    }
    return {};
}

Scene figure1WithBunny() {
    Scene scene = makeFigure1Scene();
    SceneObject bunny;
    bunny.name = "bunny";
    bunny.mesh = std::make_shared<const Mesh>(loadMesh(bunnyPath()));
    bunny.meshSource = bunnyPath().string();
    bunny.transform.translation = {4.5f, -0.25f, 1.0f};
    bunny.transform.rotationDegrees = {10.0f, -35.5f, 90.0f};
    bunny.transform.scale = 7.25f;
    Material fur;
    fur.lambda = 4.375f;
    fur.mode = LookupMode::Normal;
    fur.useIrradiance = true;
    fur.sharperAtGrazing = true;
    fur.tint = {0.9f, 0.5f, 0.125f};
    bunny.visible = false;
    scene.addObject(bunny, fur);
    scene.findMaterial(scene.objects.back().material)->libraryEntry = "Velvet";
    scene.environment.builder = Builder::Box;
    scene.environment.faceSize = 64;
    scene.display.environmentRotationDegrees = 30.0f;
    scene.environment.handedness = Handedness::Left;
    scene.display.showBackground = false;
    scene.display.backgroundLambda = 2.5f;
    scene.display.exposureEv = -1.5f;
    scene.display.toneMap = ToneMap::Reinhard;
    scene.display.samples = 8;
    scene.display.scattering = Scattering::Compensated;
    return scene;
}

}  // namespace

TEST(SceneFile, RoundTripsFigure1AndAnImportedMesh) {
    MIPGLOSS_REQUIRE_ASSET(bunnyPath());
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const fs::path file = fs::path(dir.path().toStdString()) / "figure1.json";
    const Scene scene = figure1WithBunny();
    saveScene(scene, file);

    SceneFileReport report;
    const Scene loaded = loadScene(file, &report);
    EXPECT_TRUE(report.warnings.empty());
    EXPECT_EQ(loaded.environment, scene.environment);
    EXPECT_EQ(loaded.display, scene.display);
    ASSERT_EQ(loaded.objects.size(), scene.objects.size());
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& a = scene.objects[i];
        const SceneObject& b = loaded.objects[i];
        EXPECT_EQ(b.name, a.name) << "object " << i;
        EXPECT_EQ(b.transform, a.transform) << "object " << i;
        EXPECT_EQ(loaded.materialOf(b), scene.materialOf(a)) << "object " << i;
        EXPECT_EQ(*loaded.findMaterial(b.material), *scene.findMaterial(a.material)) << "object " << i;
        EXPECT_EQ(b.visible, a.visible) << "object " << i;
        EXPECT_EQ(b.meshSource, a.meshSource) << "object " << i;
        ASSERT_TRUE(b.mesh) << "object " << i;
        EXPECT_EQ(b.mesh->triangleCount(), a.mesh->triangleCount()) << "object " << i;
        EXPECT_EQ(b.mesh->vertexCount(), a.mesh->vertexCount()) << "object " << i;
    }
    // The four teapots share one mesh again.
    for (int i = 1; i < 4; ++i) EXPECT_EQ(loaded.objects[i].mesh.get(), loaded.objects[0].mesh.get());
    EXPECT_EQ(loaded.environment.source, kBuiltinEnvironment);

    // Saving the loaded scene gives the same text: nothing drifts through a round trip.
    const fs::path again = fs::path(dir.path().toStdString()) / "again.json";
    saveScene(loaded, again);
    EXPECT_EQ(sceneToJson(loadScene(again), file), sceneToJson(loaded, file));
}

TEST(SceneFile, PathsAreRelativeToTheSceneFileAndSurviveAMove) {
    MIPGLOSS_REQUIRE_ASSET(bunnyPath());
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const fs::path project = fs::path(dir.path().toStdString()) / "project";
    fs::create_directories(project / "meshes");
    fs::create_directories(project / "scenes");
    fs::copy_file(bunnyPath(), project / "meshes" / "bunny.obj");

    Scene scene;
    const auto mesh = std::make_shared<const Mesh>(loadMesh(project / "meshes" / "bunny.obj"));
    for (const char* name : {"left", "right"}) {
        SceneObject o;
        o.name = name;
        o.mesh = mesh;
        o.meshSource = (project / "meshes" / "bunny.obj").string();
        scene.objects.push_back(o);
    }
    SceneObject sphere;
    sphere.name = "ball";
    sphere.mesh = std::make_shared<const Mesh>(makeSphere(8, 16));
    sphere.meshSource = "builtin:sphere";
    scene.objects.push_back(sphere);
    const fs::path file = project / "scenes" / "two.json";
    saveScene(scene, file);

    const QJsonObject root = QJsonDocument::fromJson([&] {
                                 QFile in(QString::fromStdString(file.string()));
                                 EXPECT_TRUE(in.open(QIODevice::ReadOnly));
                                 return in.readAll();
                             }())
                                 .object();
    EXPECT_EQ(root.value("format").toString(), QStringLiteral("mipgloss-scene"));
    EXPECT_EQ(root.value("version").toInt(), kSceneVersion);
    const QJsonArray objects = root.value("objects").toArray();
    ASSERT_EQ(objects.size(), 3);
    EXPECT_EQ(objects.at(0).toObject().value("mesh").toString(), QStringLiteral("../meshes/bunny.obj"));
    EXPECT_EQ(objects.at(2).toObject().value("mesh").toString(), QStringLiteral("builtin:sphere"));
    EXPECT_EQ(root.value("environment").toObject().value("source").toString(),
              QStringLiteral("builtin:courtyard"));

    // Move the whole project: the scene still finds its mesh, loaded once and shared.
    const fs::path moved = fs::path(dir.path().toStdString()) / "elsewhere";
    fs::rename(project, moved);
    const Scene loaded = loadScene(moved / "scenes" / "two.json");
    ASSERT_EQ(loaded.objects.size(), 3u);
    EXPECT_EQ(fs::path(loaded.objects[0].meshSource), (moved / "meshes" / "bunny.obj").lexically_normal());
    EXPECT_EQ(loaded.objects[0].mesh.get(), loaded.objects[1].mesh.get());
    EXPECT_EQ(loaded.objects[2].mesh->triangleCount(), makeSphere().triangleCount());

    // Far away (more than two folders up): absolute.
    EXPECT_EQ(relativePathForScene("/a/b/c/mesh.obj", "/x/y/z/w/scene.json"), "/a/b/c/mesh.obj");
    EXPECT_EQ(relativePathForScene("/x/y/mesh.obj", "/x/y/z/w/scene.json"), "../../mesh.obj");
    EXPECT_EQ(resolvePathForScene("../m.obj", "/x/y/scene.json"), fs::path("/x/m.obj"));
}

TEST(SceneFile, BadJsonNamesTheFile) {
    QTemporaryDir dir;
    const std::string error = loadError(dir, "broken.json", R"({"format": "mipgloss-scene", )");
    EXPECT_NE(error.find("broken.json"), std::string::npos) << error;
    EXPECT_NE(error.find("not valid JSON"), std::string::npos) << error;

    const std::string notScene = loadError(dir, "other.json", R"({"hello": 1})");
    EXPECT_NE(notScene.find("other.json"), std::string::npos) << notScene;
    EXPECT_NE(notScene.find("format"), std::string::npos) << notScene;

    const std::string newer =
        loadError(dir, "future.json", R"({"format": "mipgloss-scene", "version": 8})");
    EXPECT_NE(newer.find("future.json"), std::string::npos) << newer;
    EXPECT_NE(newer.find("version 8"), std::string::npos) << newer;

    try {
        (void)loadScene(fs::path(dir.path().toStdString()) / "absent.json");
        ADD_FAILURE() << "no error for a missing scene file";
    } catch (const SceneFileError& e) {
        EXPECT_NE(std::string(e.what()).find("absent.json"), std::string::npos) << e.what();
    }
}

TEST(SceneFile, MissingOrBrokenMeshNamesBothFiles) {
    QTemporaryDir dir;
    const std::string missing = loadError(dir, "scene.json", oneObjectScene("meshes/nothere.obj"));
    EXPECT_NE(missing.find("scene.json"), std::string::npos) << missing;
    EXPECT_NE(missing.find("nothere.obj"), std::string::npos) << missing;
    EXPECT_NE(missing.find("not found"), std::string::npos) << missing;

    writeText(fs::path(dir.path().toStdString()) / "empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const std::string broken = loadError(dir, "scene2.json", oneObjectScene("empty.obj"));
    EXPECT_NE(broken.find("scene2.json"), std::string::npos) << broken;
    EXPECT_NE(broken.find("empty.obj"), std::string::npos) << broken;

    const std::string builtin = loadError(dir, "scene3.json", oneObjectScene("builtin:dragon"));
    EXPECT_NE(builtin.find("builtin:dragon"), std::string::npos) << builtin;

    const std::string env = loadError(
        dir, "scene4.json",
        R"({"format": "mipgloss-scene", "version": 1, "environment": {"source": "sky/none.exr"}})");
    EXPECT_NE(env.find("scene4.json"), std::string::npos) << env;
    EXPECT_NE(env.find("none.exr"), std::string::npos) << env;
}

TEST(SceneFile, NonFiniteNumbersAndWrongTypesAreRejected) {
    QTemporaryDir dir;
    // NaN is not JSON: the parser refuses it.
    const std::string nan =
        loadError(dir, "nan.json", oneObjectScene("builtin:sphere", R"({"lambda": NaN})"));
    EXPECT_NE(nan.find("nan.json"), std::string::npos) << nan;
    // 1e999 overflows to infinity (or is refused by the parser): an error either way.
    const std::string inf = loadError(
        dir, "inf.json",
        R"({"format": "mipgloss-scene", "version": 1, "objects": [{"mesh": "builtin:sphere",
            "transform": {"scale": 1e999}}]})");
    EXPECT_NE(inf.find("inf.json"), std::string::npos) << inf;
    // A string where a number belongs names the key.
    const std::string type =
        loadError(dir, "type.json", oneObjectScene("builtin:sphere", R"({"lambda": "3"})"));
    EXPECT_NE(type.find("type.json"), std::string::npos) << type;
    EXPECT_NE(type.find(materialKey("lambda")), std::string::npos) << type;
    const std::string tint = loadError(
        dir, "tint.json", oneObjectScene("builtin:sphere", R"({"tint": [1, 2]})"));
    EXPECT_NE(tint.find("tint"), std::string::npos) << tint;
    const std::string mode = loadError(
        dir, "mode.json", oneObjectScene("builtin:sphere", R"({"mode": "sideways"})"));
    EXPECT_NE(mode.find("sideways"), std::string::npos) << mode;
    const std::string scale = loadError(
        dir, "scale.json",
        R"({"format": "mipgloss-scene", "version": 1, "objects": [{"mesh": "builtin:sphere",
            "transform": {"scale": 0}}]})");
    EXPECT_NE(scale.find("scale"), std::string::npos) << scale;
}

TEST(SceneFile, AbsurdSettingsAreClampedWithAWarning) {
    QTemporaryDir dir;
    SceneFileReport report;
    const std::string error = loadError(
        dir, "absurd.json",
        R"({"format": "mipgloss-scene", "version": 2,
            "environment": {"faceSize": 100000},
            "display": {"samples": 6},
            "objects": [{"mesh": "builtin:sphere", "material": {"lambda": 8}},
                        {"mesh": "builtin:sphere", "material": {"lambda": 0}}]})",
        &report);
    ASSERT_TRUE(error.empty()) << error;
    const Scene scene = loadScene(fs::path(dir.path().toStdString()) / "absurd.json");
    EXPECT_EQ(scene.materialOf(scene.objects[0]).lambda, 8.0f);
    EXPECT_EQ(scene.materialOf(scene.objects[1]).lambda, 0.0f);
    EXPECT_EQ(scene.environment.faceSize, 4096);
    EXPECT_EQ(scene.display.samples, 4);
    EXPECT_EQ(scene.objects[0].mesh.get(), scene.objects[1].mesh.get());
    ASSERT_EQ(report.warnings.size(), 2u);  // the face size, the samples not a power of two
    for (const std::string& w : report.warnings)
        EXPECT_NE(w.find("absurd.json"), std::string::npos) << w;
}

namespace {

std::string jsonNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

// A hand-written version 1 file: face size `faceSize`, background λ `background`, and one sphere
// per material λ (old meaning).
std::string versionOneScene(int faceSize, double background, const std::vector<double>& lambdas) {
    std::string objects;
    for (double l : lambdas) {
        if (!objects.empty()) objects += ", ";
        objects += R"({"mesh": "builtin:sphere", "material": {"lambda": )" + jsonNumber(l) + "}}";
    }
    return R"({"format": "mipgloss-scene", "version": 1,
               "environment": {"source": "builtin:courtyard", "faceSize": )" +
           std::to_string(faceSize) + R"(},
               "display": {"backgroundLambda": )" + jsonNumber(background) + R"(},
               "objects": [)" + objects + "]}";
}

fs::path writeScene(const QTemporaryDir& dir, const std::string& name, const std::string& json) {
    const fs::path file = fs::path(dir.path().toStdString()) / name;
    writeText(file, json);
    return file;
}

}  // namespace

// Version 1 stored λ against the face size it was saved with: n = 3·N²·4^−λ − 1. Loading keeps
// that lobe, so the material looks as it did.
TEST(SceneFile, VersionOneLambdaKeepsItsLookThroughTheSavedFaceSize) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    SceneFileReport report;
    const Scene big =
        loadScene(writeScene(dir, "v1_512.json", versionOneScene(512, 3.0, {3.0, 0.0, 5.5})), &report);
    EXPECT_TRUE(report.warnings.empty());
    ASSERT_EQ(big.objects.size(), 3u);
    EXPECT_EQ(big.environment.faceSize, 512);
    const double n3 = 3.0 * 512.0 * 512.0 * std::pow(4.0, -3.0) - 1.0;  // 12287
    EXPECT_NEAR(lambdaToExponent(big.materialOf(big.objects[0]).lambda), n3, 1e-9 * n3);
    EXPECT_NEAR(big.materialOf(big.objects[0]).lambda, 1.0, 1e-6) << "512 = 4·128: two levels sharper";
    EXPECT_EQ(big.materialOf(big.objects[1]).lambda, 0.0f) << "the mirror stays a mirror";
    const double n55 = 3.0 * 512.0 * 512.0 * std::pow(4.0, -5.5) - 1.0;
    EXPECT_NEAR(lambdaToExponent(big.materialOf(big.objects[2]).lambda), n55, 1e-6 * n55);
    EXPECT_NEAR(lambdaToExponent(big.display.backgroundLambda), n3, 1e-9 * n3);

    // At the reference size 128 the old and new meanings agree: λ unchanged.
    const Scene ref =
        loadScene(writeScene(dir, "v1_128.json", versionOneScene(128, 2.25, {3.0, 0.0, 6.75})));
    EXPECT_FLOAT_EQ(ref.materialOf(ref.objects[0]).lambda, 3.0f);
    EXPECT_EQ(ref.materialOf(ref.objects[1]).lambda, 0.0f);
    EXPECT_FLOAT_EQ(ref.materialOf(ref.objects[2]).lambda, 6.75f);
    EXPECT_FLOAT_EQ(ref.display.backgroundLambda, 2.25f);

    // A small face size: λ_old beyond that size's n = 0 point (old λ up to 16 was allowed) is n = 0.
    const Scene small =
        loadScene(writeScene(dir, "v1_32.json", versionOneScene(32, 0.0, {1.0, 16.0})));
    const double n1 = 3.0 * 32.0 * 32.0 / 4.0 - 1.0;  // 767
    EXPECT_NEAR(lambdaToExponent(small.materialOf(small.objects[0]).lambda), n1, 1e-6 * n1);
    EXPECT_NEAR(small.materialOf(small.objects[0]).lambda, 3.0, 1e-6) << "32 = 128/4: two levels blurrier";
    EXPECT_EQ(lambdaToExponent(small.materialOf(small.objects[1]).lambda), 0.0);
    EXPECT_TRUE(isValidLambda(small.materialOf(small.objects[1]).lambda));
    EXPECT_EQ(small.display.backgroundLambda, 0.0f);

    // Without a face size a version 1 file meant 128 (the old default): unchanged.
    const Scene bare = loadScene(writeScene(dir, "v1_bare.json", oneObjectScene("builtin:sphere",
                                                                               R"({"lambda": 4.5})", 1)));
    EXPECT_FLOAT_EQ(bare.materialOf(bare.objects[0]).lambda, 4.5f);

    // Saved again, it is a version 2 file with the converted λ, which then loads unchanged.
    const fs::path resaved = fs::path(dir.path().toStdString()) / "resaved.json";
    saveScene(big, resaved);
    const Scene again = loadScene(resaved);
    EXPECT_EQ(again.materialOf(again.objects[0]), big.materialOf(big.objects[0]));
    EXPECT_EQ(again.display, big.display);
}

// Version 2 stores λ exactly, and a "phongExponent" beside it: n(λ), null for the mirror.
TEST(SceneFile, RoundTripKeepsLambdaExactly) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const std::vector<float> lambdas = {0.0f, 1e-6f, static_cast<float>(exponentToLambda(1024.0)),
                                        3.14159274f, 7.7924814f, 8.0f};
    Scene scene;
    for (float l : lambdas) {
        SceneObject o;
        o.name = "sphere";
        o.mesh = std::make_shared<const Mesh>(makeSphere(8, 16));
        o.meshSource = "builtin:sphere";
        Material m;
        m.lambda = l;
        scene.addObject(o, m);
    }
    scene.environment.faceSize = 512;  // λ does not depend on it
    scene.display.backgroundLambda = 2.0f / 3.0f;
    const fs::path file = fs::path(dir.path().toStdString()) / "v2.json";
    saveScene(scene, file);

    SceneFileReport report;
    const Scene loaded = loadScene(file, &report);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    ASSERT_EQ(loaded.objects.size(), lambdas.size());
    for (std::size_t i = 0; i < lambdas.size(); ++i)
        EXPECT_EQ(loaded.materialOf(loaded.objects[i]).lambda, lambdas[i]) << i;
    EXPECT_EQ(loaded.display.backgroundLambda, scene.display.backgroundLambda);

    QFile in(QString::fromStdString(file.string()));
    ASSERT_TRUE(in.open(QIODevice::ReadOnly));
    const QJsonObject root = QJsonDocument::fromJson(in.readAll()).object();
    EXPECT_EQ(root.value("version").toInt(), kSceneVersion);
    const QJsonArray materials = root.value("materials").toArray();
    ASSERT_EQ(materials.size(), static_cast<qsizetype>(lambdas.size()));
    const QJsonValue mirror = materials.at(0).toObject().value("phongExponent");
    EXPECT_TRUE(mirror.isNull()) << "the mirror's exponent is null (∞)";
    const QJsonValue n1024 = materials.at(2).toObject().value("phongExponent");
    ASSERT_TRUE(n1024.isDouble());
    EXPECT_NEAR(n1024.toDouble(), 1024.0, 1024.0 * 1e-6);
    const QJsonValue zero = materials.at(5).toObject().value("phongExponent");
    EXPECT_EQ(zero.toDouble(-1.0), 0.0);
}

// "phongExponent" is information: λ decides; a disagreeing one is a warning, an absurd one an error.
TEST(SceneFile, PhongExponentIsCheckedAgainstLambda) {
    QTemporaryDir dir;
    SceneFileReport report;
    const std::string ok = loadError(
        dir, "agree.json",
        oneObjectScene("builtin:sphere", R"({"lambda": 3, "phongExponent": 767})"), &report);
    EXPECT_TRUE(ok.empty()) << ok;
    EXPECT_TRUE(report.warnings.empty());
    const std::string mirror = loadError(
        dir, "mirror.json", oneObjectScene("builtin:sphere", R"({"lambda": 0, "phongExponent": null})"),
        &report);
    EXPECT_TRUE(mirror.empty()) << mirror;
    EXPECT_TRUE(report.warnings.empty());

    const fs::path file = writeScene(
        dir, "stale.json", oneObjectScene("builtin:sphere", R"({"lambda": 2, "phongExponent": 767})"));
    const Scene stale = loadScene(file, &report);
    EXPECT_EQ(stale.materialOf(stale.objects[0]).lambda, 2.0f) << "λ decides";
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("stale.json"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find(materialKey("phongExponent")), std::string::npos)
        << report.warnings[0];

    for (const char* bad : {"-1", "-0.5", "\"767\"", "[1]", "true"}) {
        const std::string error = loadError(
            dir, "badn.json",
            oneObjectScene("builtin:sphere", std::string(R"({"lambda": 3, "phongExponent": )") + bad + "}"));
        EXPECT_NE(error.find("badn.json"), std::string::npos) << bad << ": " << error;
        EXPECT_NE(error.find(materialKey("phongExponent")), std::string::npos)
            << bad << ": " << error;
    }
}

// An absurd λ is an error naming the file, the key and the value, never a clamp, and a scene holding
// one is never written. (That the session opening such a file keeps its scene is
// tests/ui/documents/test_scene_file_session.cpp's.)
TEST(SceneFile, AbsurdLambdaIsAnErrorNamingTheFileKeyAndValue) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const Scene good = makeFigure1Scene();

    struct Case {
        std::string value, shown;
        int version;
    };
    // null is not "missing": a present key must hold a number.
    const std::vector<Case> cases = {{"-1", "-1", 2},        {"1e9", "1e+09", 2}, {"8.5", "8.5", 2},
                                     {"\"abc\"", "\"abc\"", 2}, {"null", "null", 2}, {"true", "true", 2},
                                     {"-0.5", "-0.5", 1},    {"16.5", "16.5", 1}, {"\"3\"", "\"3\"", 1}};
    for (const Case& c : cases) {
        const std::string name = "absurd_v" + std::to_string(c.version) + ".json";
        // The third object holds the bad λ, after two good ones.
        const std::string json =
            R"({"format": "mipgloss-scene", "version": )" + std::to_string(c.version) + R"(,
                "objects": [{"mesh": "builtin:sphere", "material": {"lambda": 1}},
                            {"mesh": "builtin:sphere", "material": {"lambda": 2}},
                            {"mesh": "builtin:sphere", "material": {"lambda": )" + c.value + "}}]}";
        const fs::path file = writeScene(dir, name, json);
        try {
            static_cast<void>(loadScene(file));
            ADD_FAILURE() << c.value << " (version " << c.version << ") loaded";
        } catch (const SceneFileError& e) {
            const std::string what = e.what();
            EXPECT_EQ(e.file(), file);
            EXPECT_NE(what.find(name), std::string::npos) << what;
            EXPECT_NE(what.find("objects[2].material.lambda"), std::string::npos) << what;
            EXPECT_NE(what.find(c.shown), std::string::npos) << what;
        }
    }

    // The background's λ likewise.
    for (const char* bad : {"-2", "100", "\"blurry\""}) {
        const fs::path file = writeScene(
            dir, "background.json",
            std::string(R"({"format": "mipgloss-scene", "version": 2, "display": {"backgroundLambda": )") +
                bad + "}}");
        try {
            static_cast<void>(loadScene(file));
            ADD_FAILURE() << bad << " loaded";
        } catch (const SceneFileError& e) {
            EXPECT_NE(std::string(e.what()).find("background.json"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("display.backgroundLambda"), std::string::npos)
                << e.what();
        }
    }

    // Nor is a scene holding one ever written.
    Scene broken = good;
    broken.materialOf(broken.objects[1]).lambda = -1.0f;
    const fs::path out = fs::path(dir.path().toStdString()) / "never.json";
    try {
        saveScene(broken, out);
        ADD_FAILURE() << "saved a negative λ";
    } catch (const SceneFileError& e) {
        EXPECT_NE(std::string(e.what()).find("objects[1].material.lambda"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
}

// Version 3: objects sharing a material still share one after a round trip, the file holds it
// once, and its library entry survives.
TEST(SceneFile, SharedMaterialsStaySharedAndAreWrittenOnce) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const auto sphere = std::make_shared<const Mesh>(makeSphere(8, 16));
    Scene scene;
    Material gold;
    gold.lambda = 2.5f;
    gold.tint = {1.0f, 0.8f, 0.3f};
    const MaterialId shared = scene.addMaterial("gold", gold, "Gold");
    scene.addMaterial("unused", Material{});
    for (const char* name : {"a", "b", "c"}) {
        SceneObject o;
        o.name = name;
        o.mesh = sphere;
        o.meshSource = "builtin:sphere";
        o.material = shared;
        scene.objects.push_back(o);
    }
    Material own;
    own.lambda = 6.0f;
    scene.objects[2].material = scene.addMaterial("c", own);
    const fs::path file = fs::path(dir.path().toStdString()) / "shared.json";
    saveScene(scene, file);

    const Scene loaded = loadScene(file);
    ASSERT_EQ(loaded.objects.size(), 3u);
    EXPECT_EQ(loaded.objects[0].material, loaded.objects[1].material) << "a and b share one material";
    EXPECT_NE(loaded.objects[0].material, loaded.objects[2].material);
    EXPECT_EQ(loaded.materials.size(), 2u) << "the unused material is not written";
    const NamedMaterial* g = loaded.findMaterial(loaded.objects[0].material);
    ASSERT_NE(g, nullptr);
    EXPECT_EQ(g->name, "gold");
    EXPECT_EQ(g->libraryEntry, "Gold");
    EXPECT_EQ(g->material, gold);
    EXPECT_EQ(loaded.materialOf(loaded.objects[2]), own);

    QFile in(QString::fromStdString(file.string()));
    ASSERT_TRUE(in.open(QIODevice::ReadOnly));
    const QJsonObject root = QJsonDocument::fromJson(in.readAll()).object();
    EXPECT_EQ(root.value("materials").toArray().size(), 2);
    EXPECT_EQ(root.value("objects").toArray().at(1).toObject().value("material").toString(), "gold");
}

// Versions 1 and 2 kept a material inside each object: each becomes one of its own, named after
// its object and made unique.
TEST(SceneFile, OlderVersionsGiveEachObjectAMaterialOfItsOwn) {
    QTemporaryDir dir;
    const fs::path file = writeScene(dir, "v2.json", R"({"format": "mipgloss-scene", "version": 2,
        "objects": [{"name": "pot", "mesh": "builtin:sphere", "material": {"lambda": 3}},
                    {"name": "pot", "mesh": "builtin:sphere", "material": {"lambda": 3}}]})");
    const Scene scene = loadScene(file);
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_NE(scene.objects[0].material, scene.objects[1].material);
    EXPECT_EQ(scene.findMaterial(scene.objects[0].material)->name, "pot");
    EXPECT_EQ(scene.findMaterial(scene.objects[1].material)->name, "pot 2");
    EXPECT_EQ(scene.materialOf(scene.objects[1]).lambda, 3.0f);
}

// Version 4 keeps the environment's rotation with the display settings (a draw-time view, never a
// build); versions 1 to 3 kept it with the environment, and it loads from there. Either way it is
// kept in [−180°, 180°], and a file written now has it only in "display".
TEST(SceneFile, EnvironmentRotationMovedToTheDisplaySettings) {
    QTemporaryDir dir;
    for (int version : {1, 2, 3}) {
        const Scene old = loadScene(writeScene(dir, "v" + std::to_string(version) + ".json",
                                               R"({"format": "mipgloss-scene", "version": )" +
                                                   std::to_string(version) +
                                                   R"(, "environment": {"rotationDegrees": 400}})"));
        EXPECT_FLOAT_EQ(old.display.environmentRotationDegrees, 40.0f) << "version " << version;
    }
    const Scene current = loadScene(writeScene(dir, "v4.json", R"({"format": "mipgloss-scene", "version": 4,
        "display": {"environmentRotationDegrees": -190}, "environment": {"rotationDegrees": 99}})"));
    EXPECT_FLOAT_EQ(current.display.environmentRotationDegrees, 170.0f) << "display's, wrapped; not environment's";

    const fs::path file = fs::path(dir.path().toStdString()) / "saved.json";
    saveScene(current, file);
    QFile in(QString::fromStdString(file.string()));
    ASSERT_TRUE(in.open(QIODevice::ReadOnly));
    const QJsonObject root = QJsonDocument::fromJson(in.readAll()).object();
    EXPECT_EQ(root.value("version").toInt(), kSceneVersion);
    EXPECT_DOUBLE_EQ(root.value("display").toObject().value("environmentRotationDegrees").toDouble(), 170.0);
    EXPECT_FALSE(root.value("environment").toObject().contains("rotationDegrees"));

    const std::string notNumber = loadError(dir, "bad.json", R"({"format": "mipgloss-scene", "version": 4,
        "display": {"environmentRotationDegrees": "east"}})");
    EXPECT_NE(notNumber.find("bad.json"), std::string::npos) << notNumber;
    EXPECT_NE(notNumber.find("environmentRotationDegrees"), std::string::npos) << notNumber;
}

// Version 5: a layered material round-trips with every parameter; a bad layer value is an error
// naming the key; an older scene (no "layers") keeps its single-lobe look.
TEST(SceneFile, LayeredMaterialsRoundTripAndBadLayersAreRefused) {
    QTemporaryDir dir;
    Scene scene;
    SceneObject ball;
    ball.name = "ball";
    ball.mesh = std::make_shared<const Mesh>(makeSphere(8, 16));
    ball.meshSource = "builtin:sphere";
    Material paint;
    paint.layered = true;
    paint.layers = {Rgb(0.1f, 0.3f, 0.7f), 0.25f, 0.4f, 0.05f, 0.8f, 0.02f, MaterialMaps{}};
    paint.layers.specularColor = Rgb(1.0f, 0.5f, 12.0f);  // KHR_materials_specular, above 1 allowed
    paint.layers.specularWeight = 0.3f;
    scene.addObject(ball, paint);
    const fs::path file = fs::path(dir.path().toStdString()) / "layered.mipgloss";
    saveScene(scene, file);
    const Scene back = loadScene(file);
    ASSERT_EQ(back.objects.size(), 1u);
    EXPECT_EQ(back.materialOf(back.objects[0]), paint);

    const std::string bad = loadError(dir, "bad.json", R"({"format": "mipgloss-scene", "version": 5,
        "materials": [{"name": "m", "layers": {"coatRoughness": -1}}],
        "objects": [{"mesh": "builtin:sphere", "material": "m"}]})");
    EXPECT_NE(bad.find("bad.json"), std::string::npos) << bad;
    EXPECT_NE(bad.find("materials[0].layers.coatRoughness"), std::string::npos) << bad;
    const std::string tint = loadError(dir, "tint.json", R"({"format": "mipgloss-scene", "version": 5,
        "materials": [{"name": "m", "layers": {"specularColor": [1, -0.5, 1]}}],
        "objects": [{"mesh": "builtin:sphere", "material": "m"}]})");
    EXPECT_NE(tint.find("materials[0].layers.specularColor[1]"), std::string::npos) << tint;
    const std::string weight = loadError(dir, "weight.json", R"({"format": "mipgloss-scene", "version": 5,
        "materials": [{"name": "m", "layers": {"specularWeight": 2}}],
        "objects": [{"mesh": "builtin:sphere", "material": "m"}]})");
    EXPECT_NE(weight.find("materials[0].layers.specularWeight"), std::string::npos) << weight;

    const Scene old = loadScene(writeScene(dir, "v4.json", R"({"format": "mipgloss-scene", "version": 4,
        "materials": [{"name": "m", "lambda": 3}], "objects": [{"mesh": "builtin:sphere", "material": "m"}]})"));
    EXPECT_FALSE(old.materialOf(old.objects[0]).layered);
    EXPECT_EQ(old.materialOf(old.objects[0]).lambda, 3.0f);
    // Written before KHR_materials_specular: glTF's defaults.
    const Scene plain = loadScene(writeScene(dir, "v5.json", R"({"format": "mipgloss-scene", "version": 5,
        "materials": [{"name": "m", "layers": {"roughness": 0.3}}], "objects": [{"mesh": "builtin:sphere", "material": "m"}]})"));
    EXPECT_EQ(plain.materialOf(plain.objects[0]).layers.specularColor, Rgb(1.0f));
    EXPECT_EQ(plain.materialOf(plain.objects[0]).layers.specularWeight, 1.0f);
}

TEST(SceneFile, MaterialNamesMustResolveAndBeUnique) {
    QTemporaryDir dir;
    const std::string unknown = loadError(dir, "unknown.json", R"({"format": "mipgloss-scene", "version": 3,
        "materials": [{"name": "gold"}],
        "objects": [{"mesh": "builtin:sphere", "material": "silver"}]})");
    EXPECT_NE(unknown.find("unknown.json"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("objects[0].material"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("silver"), std::string::npos) << unknown;
    const std::string twice = loadError(dir, "twice.json", R"({"format": "mipgloss-scene", "version": 3,
        "materials": [{"name": "gold"}, {"name": "gold", "lambda": 2}], "objects": []})");
    EXPECT_NE(twice.find("materials[1].name"), std::string::npos) << twice;
    const std::string empty = loadError(dir, "empty.json", R"({"format": "mipgloss-scene", "version": 3,
        "materials": [{"name": ""}], "objects": []})");
    EXPECT_NE(empty.find("materials[0].name"), std::string::npos) << empty;
    // No "material": a mirror of its own.
    const Scene bare = loadScene(writeScene(dir, "bare.json", R"({"format": "mipgloss-scene", "version": 3,
        "objects": [{"name": "ball", "mesh": "builtin:sphere"}]})"));
    ASSERT_EQ(bare.objects.size(), 1u);
    EXPECT_EQ(bare.materialOf(bare.objects[0]), Material{});
    EXPECT_NE(bare.findMaterial(bare.objects[0].material), nullptr);
}

// Version 6: the camera round-trips exactly; a file without one (every older version too) has
// none; each bad value is refused naming the file and the key; saving refuses what would not load.
TEST(SceneFile, CameraRoundTripsAndBadValuesAreRefusedByKey) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    Scene scene = makeFigure1Scene();
    OrbitCamera camera;
    camera.target = {1.25f, -0.5f, 3.0f};
    camera.distance = 7.75f;
    camera.yawDegrees = -123.456f;
    camera.pitchDegrees = 89.0f;  // the orbit camera's own limit loads again
    camera.fovYDegrees = 42.5f;
    scene.camera = camera;
    const fs::path file = fs::path(dir.path().toStdString()) / "camera.mipgloss";
    saveScene(scene, file);
    const Scene back = loadScene(file);
    ASSERT_TRUE(back.camera.has_value());
    EXPECT_EQ(*back.camera, camera);

    Scene noCamera = makeFigure1Scene();
    const fs::path bare = fs::path(dir.path().toStdString()) / "bare.mipgloss";
    saveScene(noCamera, bare);
    QFile in(QString::fromStdString(bare.string()));
    ASSERT_TRUE(in.open(QIODevice::ReadOnly));
    EXPECT_FALSE(QJsonDocument::fromJson(in.readAll()).object().contains("camera"));
    EXPECT_FALSE(loadScene(bare).camera.has_value());

    // Older versions load with no camera, even one holding the key (it meant nothing then).
    const std::string cameraJson =
        R"("camera": {"target": [0, 1, 2], "distance": 3, "yawDegrees": 4, "pitchDegrees": 5, "fovYDegrees": 35})";
    for (int version = 1; version < kSceneVersionCamera; ++version) {
        const Scene old = loadScene(writeScene(dir, "v" + std::to_string(version) + ".json",
                                               R"({"format": "mipgloss-scene", "version": )" +
                                                   std::to_string(version) + ", " + cameraJson + "}"));
        EXPECT_FALSE(old.camera.has_value()) << "version " << version;
    }
    const Scene six = loadScene(writeScene(dir, "v6.json", R"({"format": "mipgloss-scene", "version": 6, )" +
                                                                cameraJson + "}"));
    ASSERT_TRUE(six.camera.has_value());
    EXPECT_EQ(six.camera->target, glm::vec3(0.0f, 1.0f, 2.0f));
    EXPECT_EQ(six.camera->fovYDegrees, 35.0f);
    // A newer version is still refused.
    const std::string future = loadError(dir, "future.json", R"({"format": "mipgloss-scene", "version": )" +
                                                                 std::to_string(kSceneVersion + 1) + "}");
    EXPECT_NE(future.find("future.json"), std::string::npos) << future;
    EXPECT_NE(future.find("version"), std::string::npos) << future;

    // Each bad value: the file and the key named, nothing loaded.
    struct Bad {
        const char* key;
        std::string camera;
    };
    const std::string good = R"("target": [0, 0, 0], "distance": 5, "yawDegrees": 0, "pitchDegrees": 10, "fovYDegrees": 30)";
    auto with = [&](const std::string& key, const std::string& value) {
        std::string fields = good;
        const std::size_t at = fields.find("\"" + key + "\": ");
        const std::size_t from = at + key.size() + 4;
        const std::size_t to = key == "target" ? fields.find(']', from) + 1 : fields.find_first_of(",}", from);
        fields.replace(from, (to == std::string::npos ? fields.size() : to) - from, value);
        return fields;
    };
    const std::vector<Bad> bad = {
        {"camera.target", with("target", "[0, 1]")},
        {"camera.target[1]", with("target", R"([0, "up", 0])")},
        {"camera.target[2]", with("target", "[0, 0, 1e39]")},  // beyond single precision
        {"camera.distance", with("distance", "0")},
        {"camera.distance", with("distance", "-2")},
        {"camera.distance", with("distance", "1e39")},  // infinite as a float
        {"camera.distance", with("distance", "1e30")},
        {"camera.distance", with("distance", "null")},
        {"camera.yawDegrees", with("yawDegrees", "1e300")},
        {"camera.yawDegrees", with("yawDegrees", R"("left")")},
        {"camera.pitchDegrees", with("pitchDegrees", "89.5")},
        {"camera.pitchDegrees", with("pitchDegrees", "-90")},
        {"camera.fovYDegrees", with("fovYDegrees", "4")},
        {"camera.fovYDegrees", with("fovYDegrees", "150")},
        {"camera.fovYDegrees", with("fovYDegrees", "0")},
        {"camera.fovYDegrees", R"("target": [0, 0, 0], "distance": 5, "yawDegrees": 0, "pitchDegrees": 10)"},
    };
    for (const Bad& b : bad) {
        const std::string error = loadError(dir, "bad.mipgloss", R"({"format": "mipgloss-scene", "version": 6,
            "objects": [{"mesh": "builtin:sphere"}], "camera": {)" + b.camera + "}}");
        EXPECT_NE(error.find("bad.mipgloss"), std::string::npos) << b.camera << ": " << error;
        EXPECT_NE(error.find(std::string("\"") + b.key), std::string::npos) << b.camera << ": " << error;
    }
    const std::string notObject = loadError(dir, "bad.mipgloss", R"({"format": "mipgloss-scene", "version": 6,
        "camera": [1, 2]})");
    EXPECT_NE(notObject.find("\"camera\""), std::string::npos) << notObject;

    // Saving never writes a camera that would not load again.
    for (float pitch : {90.0f, std::nanf("")}) {
        scene.camera->pitchDegrees = pitch;
        const fs::path refused = fs::path(dir.path().toStdString()) / "refused.mipgloss";
        try {
            saveScene(scene, refused);
            ADD_FAILURE() << "saved a camera with pitch " << pitch;
        } catch (const SceneFileError& e) {
            EXPECT_NE(std::string(e.what()).find("camera.pitchDegrees"), std::string::npos) << e.what();
        }
        EXPECT_FALSE(fs::exists(refused));
    }
}

// The exposure's range (kMaxExposureEv) shows a map stored at 1e-30 at its own brightness
// (+99.66 EV): kept as written; beyond the range it is clamped with a warning naming the key.
TEST(SceneFile, ExposureKeepsAMapAt1em30VisibleAndClampsBeyondTheRange) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const fs::path file = fs::path(dir.path().toStdString()) / "dim.mipgloss";
    Scene scene = makeFigure1Scene();
    scene.display.exposureEv = 99.66f;
    saveScene(scene, file);
    EXPECT_EQ(loadScene(file).display.exposureEv, 99.66f);
    const std::string json = R"({"format": "mipgloss-scene", "version": 6, "display": {"exposureEv": -500},
        "materials": [{"name": "m", "lambda": 1}], "objects": [{"mesh": "builtin:sphere", "material": "m"}]})";
    writeText(file, json);
    SceneFileReport report;
    EXPECT_EQ(loadScene(file, &report).display.exposureEv, -kMaxExposureEv);
    ASSERT_FALSE(report.warnings.empty());
    EXPECT_NE(report.warnings.front().find("display.exposureEv"), std::string::npos) << report.warnings.front();
}
