// Scene files: round trips, relative paths, shared meshes, and every user error naming the file.
#include "mipgloss/ui/scene_file.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <filesystem>
#include <string>

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

// A minimal valid scene with one object using `mesh`, and `materialJson` as its material.
std::string oneObjectScene(const std::string& mesh, const std::string& materialJson = "{}") {
    return R"({"format": "mipgloss-scene", "version": 1,
               "environment": {"source": "builtin:courtyard"},
               "objects": [{"name": "thing", "mesh": ")" +
           mesh + R"(", "material": )" + materialJson + "}]}";
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
    bunny.material.lambda = 4.375f;
    bunny.material.mode = LookupMode::Normal;
    bunny.material.useIrradiance = true;
    bunny.material.sharperAtGrazing = true;
    bunny.material.tint = {0.9f, 0.5f, 0.125f};
    bunny.visible = false;
    scene.objects.push_back(bunny);
    scene.environment.builder = Builder::Box;
    scene.environment.faceSize = 64;
    scene.environment.rotationDegrees = 30.0f;
    scene.environment.handedness = Handedness::Left;
    scene.display.showBackground = false;
    scene.display.backgroundLambda = 2.5f;
    scene.display.exposureEv = -1.5f;
    scene.display.toneMap = ToneMap::Reinhard;
    scene.display.samples = 8;
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
        EXPECT_EQ(b.material, a.material) << "object " << i;
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
    EXPECT_EQ(root.value("version").toInt(), 1);
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
        loadError(dir, "future.json", R"({"format": "mipgloss-scene", "version": 7})");
    EXPECT_NE(newer.find("future.json"), std::string::npos) << newer;
    EXPECT_NE(newer.find("version 7"), std::string::npos) << newer;

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
    EXPECT_NE(type.find("objects[0].material.lambda"), std::string::npos) << type;
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

TEST(SceneFile, AbsurdValuesAreClampedWithAWarning) {
    QTemporaryDir dir;
    SceneFileReport report;
    const std::string error = loadError(
        dir, "absurd.json",
        R"({"format": "mipgloss-scene", "version": 1,
            "environment": {"faceSize": 100000},
            "display": {"samples": 6},
            "objects": [{"mesh": "builtin:sphere", "material": {"lambda": 1000}},
                        {"mesh": "builtin:sphere", "material": {"lambda": -2}}]})",
        &report);
    ASSERT_TRUE(error.empty()) << error;
    const Scene scene = loadScene(fs::path(dir.path().toStdString()) / "absurd.json");
    EXPECT_EQ(scene.objects[0].material.lambda, kMaxLambda);
    EXPECT_EQ(scene.objects[1].material.lambda, 0.0f);
    EXPECT_EQ(scene.environment.faceSize, 4096);
    EXPECT_EQ(scene.display.samples, 4);
    EXPECT_EQ(scene.objects[0].mesh.get(), scene.objects[1].mesh.get());
    ASSERT_EQ(report.warnings.size(), 4u);
    for (const std::string& w : report.warnings)
        EXPECT_NE(w.find("absurd.json"), std::string::npos) << w;
    EXPECT_NE(report.warnings[2].find("objects[0].material.lambda"), std::string::npos)
        << report.warnings[2];
}
