// Undo and redo of every kind of scene edit (scene_document.h, scene_commands.h): after undo the
// document's scene equals (Scene::operator==) the one before the edit, after redo the one after
// it; one edit is one step, continuous edits with one merge key are one step, and a failed
// environment leaves no step behind. No OpenGL.
#include "mipgloss/ui/mesh_importer.h"
#include "mipgloss/ui/scene_document.h"

#include "scene_test_support.h"

#include <gtest/gtest.h>

#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::sphereObject;

namespace {

// "a" and "b" share the material "Gold"; "c" has "Chalk" of its own.
Scene sharedScene() {
    Scene s;
    Material gold;
    gold.lambda = 2.0f;
    gold.tint = Rgb(1.0f, 0.8f, 0.3f);
    const MaterialId goldId = s.addMaterial("Gold", gold);
    Material chalk;
    chalk.lambda = 7.0f;
    chalk.mode = LookupMode::Normal;
    const MaterialId chalkId = s.addMaterial("Chalk", chalk);
    for (auto [name, x, id] : {std::tuple{"a", 0.0f, goldId}, {"b", 3.0f, goldId}, {"c", 6.0f, chalkId}}) {
        SceneObject o = sphereObject(name, x);
        o.material = id;
        s.objects.push_back(o);
    }
    return s;
}

struct Edit {
    const char* name;
    std::function<void(SceneDocument&)> apply;
    std::function<void(SceneDocument&)> prepare = {};  // an earlier edit the one under test needs
};

std::vector<Edit> everyKindOfEdit() {
    return {
        {"material λ (shared by two)", [](SceneDocument& d) {
             Material m = d.materialOf(0);
             m.lambda = 4.5f;
             d.setMaterial(0, m);
         }},
        {"material mode, tint, irradiance, grazing", [](SceneDocument& d) {
             Material m = d.materialOf(2);
             m.mode = LookupMode::Reflect;
             m.tint = Rgb(0.2f, 0.4f, 0.6f);
             m.useIrradiance = true;
             m.sharperAtGrazing = true;
             d.setMaterial(2, m);
         }},
        {"material rename",
         [](SceneDocument& d) { ASSERT_TRUE(d.setMaterialName(1, QStringLiteral("Brass"))); }},
        {"assign material", [](SceneDocument& d) { d.assignMaterial(0, d.object(2).material); }},
        {"make unique", [](SceneDocument& d) { d.makeMaterialUnique(1); }},
        {"apply a new library material", [](SceneDocument& d) {
             LibraryMaterial entry{"Velvet", Material{}};
             entry.material.lambda = 6.0f;
             d.applyLibraryMaterial(2, entry);
         }},
        {"apply a library material the scene has",
         [](SceneDocument& d) {
             LibraryMaterial entry{"Velvet", Material{}};
             entry.material.lambda = 6.0f;
             const std::size_t materials = d.scene().materials.size();
             d.applyLibraryMaterial(0, entry);  // reuses "Velvet"
             EXPECT_EQ(d.scene().materials.size(), materials);
         },
         [](SceneDocument& d) {
             LibraryMaterial entry{"Velvet", Material{}};
             entry.material.lambda = 6.0f;
             d.applyLibraryMaterial(2, entry);  // adds "Velvet"
         }},
        {"transform", [](SceneDocument& d) {
             Transform t = d.object(1).transform;
             t.translation.y = 2.0f;
             t.rotationDegrees.z = 30.0f;
             t.scale = 0.5f;
             d.setTransform(1, t);
         }},
        {"object name", [](SceneDocument& d) { d.setName(2, QStringLiteral("cube")); }},
        {"visibility", [](SceneDocument& d) { d.setVisible(0, false); }},
        {"add object with a material of its own", [](SceneDocument& d) {
             Material m;
             m.lambda = 1.0f;
             d.addObject(sphereObject("d", 9.0f), m);
         }},
        {"add object sharing a material", [](SceneDocument& d) {
             SceneObject o = sphereObject("e", 9.0f);
             o.material = d.object(2).material;
             d.addObject(o);
         }},
        {"remove the selected object", [](SceneDocument& d) {
             d.setSelected(1);
             d.removeObject(1);
         }},
        {"remove an object above the selection", [](SceneDocument& d) {
             d.setSelected(2);
             d.removeObject(0);
         }},
        {"duplicate", [](SceneDocument& d) { d.duplicateObject(0); }},
        {"environment", [](SceneDocument& d) {
             EnvironmentSettings e = d.scene().environment;
             e.builder = Builder::Box;
             e.faceSize = 64;
             d.setEnvironment(e);
         }},
        {"display", [](SceneDocument& d) {
             DisplaySettings s = d.scene().display;
             s.environmentRotationDegrees = 45.0f;
             s.exposureEv = -1.5f;
             s.backgroundLambda = 3.0f;
             s.toneMap = ToneMap::Reinhard;
             s.scattering = Scattering::Compensated;
             d.setDisplay(s);
         }},
    };
}

}  // namespace

TEST(Undo, EveryKindOfEditRoundTrips) {
    for (const Edit& edit : everyKindOfEdit()) {
        SCOPED_TRACE(edit.name);
        SceneDocument doc;
        doc.resetScene(sharedScene());
        if (edit.prepare) edit.prepare(doc);
        QUndoStack* stack = doc.undoStack();
        const int steps = stack->count();
        const Scene before = doc.scene();
        edit.apply(doc);
        const Scene after = doc.scene();
        EXPECT_NE(after, before) << "the edit changed nothing";
        ASSERT_EQ(stack->count(), steps + 1) << "one edit, one step";
        EXPECT_FALSE(stack->undoText().isEmpty());
        stack->undo();
        EXPECT_EQ(doc.scene(), before);
        stack->redo();
        EXPECT_EQ(doc.scene(), after);
        stack->undo();
        EXPECT_EQ(doc.scene(), before);
    }
}

// All the edits one after another: undoing them one by one passes through every intermediate
// scene back to the first, redoing them through every one to the last.
TEST(Undo, ASequenceOfEditsUndoesAndRedoesStepByStep) {
    SceneDocument doc;
    doc.resetScene(sharedScene());
    std::vector<Scene> states{doc.scene()};
    QUndoStack* stack = doc.undoStack();
    for (const Edit& edit : everyKindOfEdit()) {
        for (const auto& step : {edit.prepare, edit.apply}) {
            if (!step) continue;
            step(doc);
            // Some edits find their work done by an earlier one (Velvet applied twice): no step.
            if (doc.scene() != states.back()) states.push_back(doc.scene());
            ASSERT_EQ(stack->count(), static_cast<int>(states.size()) - 1) << edit.name;
        }
    }
    ASSERT_GE(states.size(), 15u);
    for (std::size_t i = states.size() - 1; i > 0; --i) {
        stack->undo();
        EXPECT_EQ(doc.scene(), states[i - 1]) << "after undoing step " << i;
    }
    for (std::size_t i = 1; i < states.size(); ++i) {
        stack->redo();
        EXPECT_EQ(doc.scene(), states[i]) << "after redoing step " << i;
    }
}

TEST(Undo, TextsNameTheEdit) {
    SceneDocument doc;
    doc.resetScene(sharedScene());
    Material m = doc.materialOf(0);
    m.lambda = 3.0f;
    doc.setMaterial(0, m);
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Change λ of Gold"));
    m.tint = Rgb(0.5f);
    doc.setMaterial(0, m);
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Change tint of Gold"));
    doc.setMaterialName(0, QStringLiteral("Brass"));
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Rename material Gold to Brass"));
    doc.removeObject(2);
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Remove c"));
    Transform t = doc.object(0).transform;
    t.translation.x += 1.0f;
    doc.setTransform(0, t);
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Move a"));
    DisplaySettings d = doc.scene().display;
    d.environmentRotationDegrees = 90.0f;
    doc.setDisplay(d);
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Rotate environment"));
}

TEST(Undo, EditsWithOneMergeKeyAreOneStep) {
    SceneDocument doc;
    doc.resetScene(sharedScene());
    QUndoStack* stack = doc.undoStack();
    const float start = doc.materialOf(0).lambda;
    const SceneDocument::MergeKey drag = SceneDocument::newMergeKey();
    Material m = doc.materialOf(0);
    for (int step = 1; step <= 20; ++step) {  // a slider drag: many values, one key
        m.lambda = start + 0.1f * static_cast<float>(step);
        doc.setMaterial(0, m, drag);
    }
    EXPECT_EQ(stack->count(), 1);
    EXPECT_EQ(stack->undoText(), QStringLiteral("Change λ of Gold"));
    stack->undo();
    EXPECT_EQ(doc.materialOf(0).lambda, start);
    stack->redo();
    EXPECT_FLOAT_EQ(doc.materialOf(0).lambda, start + 2.0f);

    // Another key, no key, or another material: new steps.
    m.lambda = 1.0f;
    doc.setMaterial(0, m, SceneDocument::newMergeKey());
    EXPECT_EQ(stack->count(), 2);
    m.lambda = 1.5f;
    doc.setMaterial(0, m);
    m.lambda = 1.25f;
    doc.setMaterial(0, m);
    EXPECT_EQ(stack->count(), 4) << "key 0 never merges";
    const SceneDocument::MergeKey shared = SceneDocument::newMergeKey();
    doc.setMaterial(0, m, shared);  // no change: nothing pushed
    Material chalk = doc.materialOf(2);
    chalk.lambda = 6.0f;
    doc.setMaterial(2, chalk, shared);
    m.lambda = 0.5f;
    doc.setMaterial(0, m, shared);
    EXPECT_EQ(stack->count(), 6) << "the same key on another material is another step";

    // A merged step that comes back to where it began is dropped.
    const Scene before = doc.scene();
    const SceneDocument::MergeKey back = SceneDocument::newMergeKey();
    Transform t = doc.object(1).transform;
    const Transform original = t;
    t.translation.x += 1.0f;
    doc.setTransform(1, t, back);
    EXPECT_EQ(stack->count(), 7);
    doc.setTransform(1, original, back);
    EXPECT_EQ(stack->count(), 6);
    EXPECT_EQ(doc.scene(), before);

    // Environment and display steps merge the same way (a face size box, a rotation drag).
    const SceneDocument::MergeKey resize = SceneDocument::newMergeKey();
    for (int size : {32, 64, 256}) {
        EnvironmentSettings e = doc.scene().environment;
        e.faceSize = size;
        doc.setEnvironment(e, resize);
    }
    const SceneDocument::MergeKey rotate = SceneDocument::newMergeKey();
    for (int degrees = 1; degrees <= 30; ++degrees) {
        DisplaySettings d = doc.scene().display;
        d.environmentRotationDegrees = static_cast<float>(degrees);
        doc.setDisplay(d, rotate);
    }
    const SceneDocument::MergeKey expose = SceneDocument::newMergeKey();
    for (float ev : {0.5f, 1.0f, 1.5f}) {
        DisplaySettings d = doc.scene().display;
        d.exposureEv = ev;
        doc.setDisplay(d, expose);
    }
    EXPECT_EQ(stack->count(), 9);
    stack->undo();
    stack->undo();
    stack->undo();
    EXPECT_EQ(doc.scene(), before);
}

TEST(Undo, UndoEmitsWhatTheEditDid) {
    SceneDocument doc;
    doc.resetScene(sharedScene());
    Material m = doc.materialOf(0);
    m.lambda = 5.0f;
    doc.setMaterial(0, m);
    QSignalSpy material(&doc, &SceneDocument::materialChanged);
    QSignalSpy changed(&doc, &SceneDocument::changed);
    QSignalSpy objects(&doc, &SceneDocument::objectsChanged);
    doc.undoStack()->undo();
    ASSERT_EQ(material.count(), 2) << "both users of Gold";
    EXPECT_EQ(material.at(0).at(0).toInt(), 0);
    EXPECT_EQ(material.at(1).at(0).toInt(), 1);
    EXPECT_EQ(changed.count(), 1);
    EXPECT_EQ(objects.count(), 0);

    doc.duplicateObject(2);
    QSignalSpy inserted(&doc, &SceneDocument::objectInserted);
    QSignalSpy removed(&doc, &SceneDocument::objectRemoved);
    QSignalSpy reset(&doc, &SceneDocument::sceneReset);
    doc.undoStack()->undo();
    doc.undoStack()->redo();
    ASSERT_EQ(removed.count(), 1);
    EXPECT_EQ(removed.at(0).at(0).toInt(), 3);
    ASSERT_EQ(inserted.count(), 1);
    EXPECT_EQ(inserted.at(0).at(0).toInt(), 3);
    EXPECT_EQ(reset.count(), 0);
    EXPECT_EQ(doc.selected(), 3) << "redoing an add selects it again";
}

TEST(Undo, NewSceneClearsTheStack) {
    SceneDocument doc;
    doc.resetScene(sharedScene());
    doc.setName(0, QStringLiteral("x"));
    ASSERT_TRUE(doc.undoStack()->canUndo());
    doc.resetScene(sharedScene());
    EXPECT_EQ(doc.undoStack()->count(), 0);
}

TEST(Undo, RefusedAndUnchangedEditsPushNothing) {
    SceneDocument doc;
    doc.resetScene(sharedScene());
    EXPECT_FALSE(doc.setMaterialName(0, QStringLiteral("Chalk"))) << "another material has it";
    EXPECT_FALSE(doc.setMaterialName(0, QStringLiteral("   ")));
    EXPECT_TRUE(doc.setMaterialName(0, QStringLiteral(" Gold "))) << "its own name, trimmed";
    EXPECT_EQ(doc.makeMaterialUnique(2), doc.object(2).material) << "already its own";
    doc.assignMaterial(0, doc.object(0).material);
    doc.assignMaterial(0, 999);  // not a material of the scene
    Material m = doc.materialOf(0);
    m.lambda = -1.0f;  // refused λ, nothing else changed
    doc.setMaterial(0, m);
    Transform t;
    t.scale = std::numeric_limits<float>::infinity();
    doc.setTransform(0, t);
    EXPECT_EQ(doc.undoStack()->count(), 0);
    EXPECT_EQ(doc.scene(), [] {
        SceneDocument fresh;
        fresh.resetScene(sharedScene());
        return fresh.scene();
    }());
}

TEST(Undo, OneImportIsOneStep) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString triangle = dir.filePath(QStringLiteral("triangle.obj"));
    const QString quad = dir.filePath(QStringLiteral("quad.obj"));
    for (const auto& [path, text] : {std::pair{triangle, QByteArray("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")},
                                     {quad, QByteArray("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")}}) {
        QFile f(path);
        ASSERT_TRUE(f.open(QIODevice::WriteOnly));
        f.write(text);
    }
    SceneDocument doc;
    doc.resetScene(sharedScene());
    const Scene before = doc.scene();
    MeshImporter importer(&doc);
    QSignalSpy finished(&importer, &MeshImporter::finished);
    importer.import({triangle, quad, dir.filePath(QStringLiteral("absent.obj"))});
    ASSERT_EQ(finished.count(), 1) << "small files load at once";
    EXPECT_EQ(finished.at(0).at(0).toStringList().size(), 2);
    EXPECT_EQ(finished.at(0).at(1).toStringList().size(), 1);
    EXPECT_EQ(doc.objectCount(), 5);
    EXPECT_EQ(doc.scene().materials.size(), before.materials.size() + 2) << "one material each";
    EXPECT_EQ(doc.undoStack()->count(), 1);
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Import triangle.obj, quad.obj"));
    const Scene after = doc.scene();
    doc.undoStack()->undo();
    EXPECT_EQ(doc.scene(), before);
    doc.undoStack()->redo();
    EXPECT_EQ(doc.scene(), after);
}

// EnvironmentManager reports a file it could not use; the window hands the document the failed
// settings and what is still drawn. No undo step may remain that asks for the file again.
TEST(Undo, FailedEnvironmentLeavesNoStep) {
    SceneDocument doc;
    doc.resetScene(sharedScene());
    const EnvironmentSettings drawn = doc.scene().environment;
    EnvironmentSettings bad = drawn;
    bad.source = "/nowhere/broken.exr";

    // The failed open is the newest step: it goes, and Redo does not offer it.
    Material m = doc.materialOf(0);
    m.lambda = 1.0f;
    doc.setMaterial(0, m);
    const Scene beforeOpen = doc.scene();
    doc.setEnvironment(bad);
    ASSERT_EQ(doc.undoStack()->count(), 2);
    doc.withdrawFailedEnvironment(bad, drawn);
    EXPECT_EQ(doc.scene(), beforeOpen);
    EXPECT_EQ(doc.undoStack()->count(), 1);
    EXPECT_FALSE(doc.undoStack()->canRedo());
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Change λ of Gold"));

    // Edits made while the file was read stay; the open is passed over by Undo.
    doc.setEnvironment(bad);
    doc.setName(0, QStringLiteral("renamed"));
    doc.withdrawFailedEnvironment(bad, drawn);
    EXPECT_EQ(doc.scene().environment, drawn);
    EXPECT_EQ(doc.object(0).name, "renamed");
    const Scene afterFailure = doc.scene();
    doc.undoStack()->undo();  // the rename
    EXPECT_EQ(doc.object(0).name, "a");
    doc.undoStack()->undo();  // the withdrawn open: nothing changes, and it leaves the stack
    EXPECT_EQ(doc.scene().environment, drawn);
    EXPECT_EQ(doc.undoStack()->undoText(), QStringLiteral("Change λ of Gold"));
    doc.undoStack()->redo();
    EXPECT_EQ(doc.scene(), afterFailure);
    EXPECT_FALSE(doc.undoStack()->canRedo());

    // The document moved on to another environment meanwhile: nothing to withdraw.
    EnvironmentSettings other = drawn;
    other.faceSize = 256;
    doc.setEnvironment(other);
    const int steps = doc.undoStack()->count();
    doc.withdrawFailedEnvironment(bad, drawn);
    EXPECT_EQ(doc.scene().environment, other);
    EXPECT_EQ(doc.undoStack()->count(), steps);
}
