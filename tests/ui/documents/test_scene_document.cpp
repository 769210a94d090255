// SceneDocument (signals only on change, selection bookkeeping, duplicates sharing meshes) and
// SceneListModel (QAbstractItemModelTester, rows moved rather than reset, visibility, names and
// materials through the model, library materials dropped onto rows).
#include "mipgloss/ui/material_mime.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_list_model.h"

#include "scene_test_support.h"

#include <gtest/gtest.h>

#include <QAbstractItemModelTester>
#include <QItemSelectionModel>
#include <QLocale>
#include <QMimeData>
#include <QSignalSpy>
#include <QUndoStack>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
using mipgloss::test::sphereMesh;
using mipgloss::test::sphereObject;

namespace {

// Collects what QAbstractItemModelTester reports (it warns in the "qt.modeltest" category) while
// alive, so a broken model fails the test instead of only printing.
class ModelTestWarnings {
public:
    ModelTestWarnings() { previous_ = qInstallMessageHandler(&ModelTestWarnings::handle); }
    ~ModelTestWarnings() { qInstallMessageHandler(previous_); }
    ModelTestWarnings(const ModelTestWarnings&) = delete;
    ModelTestWarnings& operator=(const ModelTestWarnings&) = delete;
    static std::vector<std::string>& messages() {
        static std::vector<std::string> m;
        return m;
    }

private:
    static void handle(QtMsgType type, const QMessageLogContext& context, const QString& text) {
        if (type != QtDebugMsg && context.category && std::string(context.category) == "qt.modeltest")
            messages().push_back(text.toStdString());
    }
    QtMessageHandler previous_ = nullptr;
};

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

Scene threeSpheres() {
    Scene s;
    for (const SceneObject& o : {sphereObject("a", 0.0f), sphereObject("b", 3.0f), sphereObject("c", 6.0f)})
        s.addObject(o, Material{});
    return s;
}

}  // namespace

TEST(SceneDocument, SettersEmitOnlyOnChange) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    QSignalSpy material(&doc, &SceneDocument::materialChanged);
    QSignalSpy transform(&doc, &SceneDocument::transformChanged);
    QSignalSpy object(&doc, &SceneDocument::objectChanged);
    QSignalSpy environment(&doc, &SceneDocument::environmentChanged);
    QSignalSpy display(&doc, &SceneDocument::displayChanged);
    QSignalSpy selection(&doc, &SceneDocument::selectionChanged);
    QSignalSpy changed(&doc, &SceneDocument::changed);

    // The same values again: nothing.
    doc.setMaterial(1, doc.materialOf(1));
    doc.setTransform(1, doc.object(1).transform);
    doc.setVisible(1, true);
    doc.setName(1, QStringLiteral("b"));
    doc.setEnvironment(doc.scene().environment);
    doc.setDisplay(doc.scene().display);
    doc.setSelected(-1);
    EXPECT_EQ(material.count() + transform.count() + object.count() + environment.count() +
                  display.count() + selection.count() + changed.count(),
              0);

    Material m = doc.materialOf(1);
    m.lambda = 2.5f;
    doc.setMaterial(1, m);
    ASSERT_EQ(material.count(), 1);
    EXPECT_EQ(material.at(0).at(0).toInt(), 1);
    doc.setMaterial(1, m);  // again: no second signal
    EXPECT_EQ(material.count(), 1);

    Transform t = doc.object(2).transform;
    t.scale = 2.0f;
    doc.setTransform(2, t);
    EXPECT_EQ(transform.count(), 1);
    doc.setVisible(0, false);
    doc.setName(0, QStringLiteral("renamed"));
    EXPECT_EQ(object.count(), 2);
    EXPECT_EQ(doc.object(0).name, "renamed");

    EnvironmentSettings e = doc.scene().environment;
    e.builder = Builder::Box;
    doc.setEnvironment(e);
    DisplaySettings d = doc.scene().display;
    d.exposureEv = 1.0f;
    doc.setDisplay(d);
    EXPECT_EQ(environment.count(), 1);
    EXPECT_EQ(display.count(), 1);

    doc.setSelected(2);
    doc.setSelected(2);
    EXPECT_EQ(selection.count(), 1);
    // changed(): every mutation above, never selection.
    EXPECT_EQ(changed.count(), 1 + 1 + 2 + 1 + 1);
}

TEST(SceneDocument, InvalidLambdaIsRefused) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    QSignalSpy material(&doc, &SceneDocument::materialChanged);
    QSignalSpy display(&doc, &SceneDocument::displayChanged);
    Material m;
    m.lambda = 2.0f;
    doc.setMaterial(0, m);
    ASSERT_EQ(material.count(), 1);
    // NaN, negative and huge λ are refused: the last good value stays and nothing is emitted.
    for (float bad : {1000.0f, 8.001f, -3.0f, -0.0001f, std::numeric_limits<float>::quiet_NaN(),
                      std::numeric_limits<float>::infinity()}) {
        m.lambda = bad;
        doc.setMaterial(0, m);
        EXPECT_EQ(doc.materialOf(0).lambda, 2.0f) << bad;
    }
    EXPECT_EQ(material.count(), 1);
    // The ends of [0, kMaxLambda] are fine.
    m.lambda = static_cast<float>(kMaxLambda);
    doc.setMaterial(0, m);
    EXPECT_EQ(doc.materialOf(0).lambda, 8.0f);
    m.lambda = 0.0f;
    doc.setMaterial(0, m);
    EXPECT_EQ(doc.materialOf(0).lambda, 0.0f);
    // The edit's other fields still apply alongside a refused λ.
    m.lambda = -1.0f;
    m.mode = LookupMode::Normal;
    doc.setMaterial(0, m);
    EXPECT_EQ(doc.materialOf(0).mode, LookupMode::Normal);
    EXPECT_EQ(doc.materialOf(0).lambda, 0.0f);

    // The background's λ likewise.
    DisplaySettings d = doc.scene().display;
    d.backgroundLambda = 1.5f;
    doc.setDisplay(d);
    EXPECT_EQ(doc.scene().display.backgroundLambda, 1.5f);
    const int displayed = static_cast<int>(display.count());
    d.backgroundLambda = std::numeric_limits<float>::quiet_NaN();
    doc.setDisplay(d);
    d.backgroundLambda = 17.0f;
    doc.setDisplay(d);
    EXPECT_EQ(doc.scene().display.backgroundLambda, 1.5f);
    EXPECT_EQ(display.count(), displayed);

    // Objects and scenes arriving whole have no last good value: clamped to [0, kMaxLambda], NaN
    // to the mirror.
    Scene scene = threeSpheres();
    scene.materialOf(scene.objects[0]).lambda = 16.0f;
    scene.materialOf(scene.objects[1]).lambda = std::numeric_limits<float>::quiet_NaN();
    scene.materialOf(scene.objects[2]).lambda = -1.0f;
    scene.display.backgroundLambda = 12.0f;
    doc.resetScene(scene);
    EXPECT_EQ(doc.materialOf(0).lambda, 8.0f);
    EXPECT_EQ(doc.materialOf(1).lambda, 0.0f);
    EXPECT_EQ(doc.materialOf(2).lambda, 0.0f);
    EXPECT_EQ(doc.scene().display.backgroundLambda, 8.0f);
    SceneObject extra = doc.object(0);
    Material absurd;
    absurd.lambda = 100.0f;
    EXPECT_EQ(doc.materialOf(doc.addObject(extra, absurd)).lambda, 8.0f);
}

// Layer values out of [0, 1] or NaN are refused like a bad λ: the last good layers stay, nothing is
// emitted; a scene arriving whole has them brought into range (NaN: the default's).
TEST(SceneDocument, InvalidLayersAreRefusedAndTheLastGoodOnesKept) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    Material m;
    m.layered = true;
    m.layers.metallic = 1.0f;
    doc.setMaterial(0, m);
    ASSERT_TRUE(doc.materialOf(0).layered);
    QSignalSpy material(&doc, &SceneDocument::materialChanged);
    for (auto bad : {+[](Layers& l) { l.metallic = std::numeric_limits<float>::quiet_NaN(); },
                     +[](Layers& l) { l.roughness = 1.5f; }, +[](Layers& l) { l.coat = -0.5f; },
                     +[](Layers& l) { l.baseColor.b = 3.0f; }}) {
        Material b = m;
        bad(b.layers);
        doc.setMaterial(0, b);
        EXPECT_EQ(doc.materialOf(0).layers, m.layers);
    }
    EXPECT_EQ(material.count(), 0);

    Scene scene = threeSpheres();
    Material& arriving = scene.materialOf(scene.objects[1]);
    arriving.layered = true;
    arriving.layers.roughness = 4.0f;
    arriving.layers.coat = std::numeric_limits<float>::quiet_NaN();
    doc.resetScene(scene);
    EXPECT_EQ(doc.materialOf(1).layers.roughness, 1.0f);
    EXPECT_EQ(doc.materialOf(1).layers.coat, Layers{}.coat);
    EXPECT_TRUE(isValidMaterial(doc.materialOf(1)));
}

TEST(SceneDocument, MaterialIsSanitised) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    Material m;
    m.tint = Rgb(-1.0f, std::numeric_limits<float>::quiet_NaN(), 0.5f);
    doc.setMaterial(0, m);
    EXPECT_EQ(doc.materialOf(0).tint, Rgb(0.0f, 1.0f, 0.5f));
    // A non-finite transform is refused; the object keeps its placement.
    Transform t;
    t.translation.x = std::numeric_limits<float>::infinity();
    doc.setTransform(0, t);
    EXPECT_EQ(doc.object(0).transform.translation.x, 0.0f);
}

TEST(SceneDocument, AddObjectSelectsIt) {
    SceneDocument doc;
    QSignalSpy objects(&doc, &SceneDocument::objectsChanged);
    QSignalSpy selection(&doc, &SceneDocument::selectionChanged);
    QSignalSpy changed(&doc, &SceneDocument::changed);
    EXPECT_EQ(doc.addObject(sphereObject("a", 0.0f)), 0);
    EXPECT_EQ(doc.addObject(sphereObject("b", 3.0f)), 1);
    EXPECT_EQ(doc.selected(), 1);
    EXPECT_EQ(objects.count(), 2);
    EXPECT_EQ(changed.count(), 2);
    ASSERT_EQ(selection.count(), 2);
    EXPECT_EQ(selection.at(1).at(0).toInt(), 1);
}

TEST(SceneDocument, DuplicateSharesMeshAndSitsBeside) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    Material m;
    m.lambda = 4.0f;
    m.mode = LookupMode::Normal;
    doc.setMaterial(1, m);
    Transform t = doc.object(1).transform;
    t.scale = 0.5f;
    doc.setTransform(1, t);
    QSignalSpy objects(&doc, &SceneDocument::objectsChanged);
    QSignalSpy changed(&doc, &SceneDocument::changed);

    const int copy = doc.duplicateObject(1);
    ASSERT_EQ(copy, 2);
    EXPECT_EQ(doc.objectCount(), 4);
    EXPECT_EQ(doc.selected(), copy);
    EXPECT_EQ(objects.count(), 1);
    EXPECT_EQ(changed.count(), 1);
    const SceneObject& original = doc.object(1);
    const SceneObject& duplicate = doc.object(copy);
    EXPECT_EQ(duplicate.mesh.get(), original.mesh.get()) << "the mesh must be shared, not copied";
    EXPECT_EQ(duplicate.name, "b copy");
    EXPECT_EQ(duplicate.material, original.material);
    EXPECT_EQ(duplicate.meshSource, original.meshSource);
    // 1.2 world bounding diameters along +x. The bounding sphere holds the mesh's box: radius √3
    // for the unit sphere, so at scale 0.5 the diameter is √3.
    const float diameter = 2.0f * original.worldRadius();
    EXPECT_NEAR(diameter, std::sqrt(3.0f), 1e-4f);
    EXPECT_NEAR(duplicate.transform.translation.x - original.transform.translation.x,
                1.2f * diameter, 1e-5f);
    EXPECT_EQ(duplicate.transform.translation.y, original.transform.translation.y);
    EXPECT_EQ(duplicate.transform.scale, original.transform.scale);
    EXPECT_EQ(doc.object(3).name, "c");  // the rest keep their order
    EXPECT_EQ(doc.duplicateObject(17), -1);
}

TEST(SceneDocument, RemoveFixesSelection) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    QSignalSpy selection(&doc, &SceneDocument::selectionChanged);

    // Removing an object before the selected one: the selection follows its object.
    doc.setSelected(2);
    doc.removeObject(0);
    EXPECT_EQ(doc.selected(), 1);
    EXPECT_EQ(doc.object(doc.selected()).name, "c");

    // Removing the selected last object: the new last one is selected.
    doc.removeObject(1);
    EXPECT_EQ(doc.selected(), 0);
    EXPECT_EQ(doc.object(0).name, "b");

    // Removing an object after the selected one: unchanged.
    doc.addObject(sphereObject("d", 9.0f));
    doc.setSelected(0);
    const int before = static_cast<int>(selection.count());
    doc.removeObject(1);
    EXPECT_EQ(doc.selected(), 0);
    EXPECT_EQ(selection.count(), before);

    // Removing the only object clears the selection.
    doc.removeObject(0);
    EXPECT_EQ(doc.objectCount(), 0);
    EXPECT_EQ(doc.selected(), -1);
    EXPECT_EQ(selection.last().at(0).toInt(), -1);

    doc.removeObject(5);  // out of range: ignored
    EXPECT_EQ(doc.objectCount(), 0);
}

TEST(SceneDocument, ResetClearsSelectionAndSignalsOnlyRealChanges) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    doc.setSelected(1);
    QSignalSpy objects(&doc, &SceneDocument::objectsChanged);
    QSignalSpy environment(&doc, &SceneDocument::environmentChanged);
    QSignalSpy selection(&doc, &SceneDocument::selectionChanged);
    doc.resetScene(threeSpheres());  // same settings
    EXPECT_EQ(objects.count(), 1);
    EXPECT_EQ(environment.count(), 0);
    EXPECT_EQ(selection.count(), 1);
    EXPECT_EQ(doc.selected(), -1);
    Scene other = threeSpheres();
    other.environment.faceSize = 64;
    doc.resetScene(other);
    EXPECT_EQ(environment.count(), 1);
}

TEST(SceneListModel, PassesModelTesterThroughEdits) {
    ModelTestWarnings warnings;
    ModelTestWarnings::messages().clear();
    SceneDocument doc;
    SceneListModel model(&doc);
    QAbstractItemModelTester tester(&model, QAbstractItemModelTester::FailureReportingMode::Warning);
    EXPECT_EQ(model.rowCount(), 0);
    doc.resetScene(threeSpheres());
    EXPECT_EQ(model.rowCount(), 3);
    doc.addObject(sphereObject("d", 9.0f));
    doc.duplicateObject(0);
    doc.removeObject(2);
    doc.setVisible(0, false);
    doc.setName(1, QStringLiteral("x"));
    Material m;
    m.lambda = 5.0f;
    doc.setMaterial(1, m);
    EXPECT_EQ(model.rowCount(), doc.objectCount());
    for (int row = 0; row < model.rowCount(); ++row)
        EXPECT_EQ(model.data(model.index(row)).toString().toStdString(), doc.object(row).name);
    doc.resetScene(Scene{});
    EXPECT_EQ(model.rowCount(), 0);
    EXPECT_TRUE(ModelTestWarnings::messages().empty()) << joined(ModelTestWarnings::messages());
}

TEST(SceneListModel, CheckStateEditsVisibilityAndEditRoleRenames) {
    ModelTestWarnings warnings;
    ModelTestWarnings::messages().clear();
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    SceneListModel model(&doc);
    QAbstractItemModelTester tester(&model, QAbstractItemModelTester::FailureReportingMode::Warning);
    QSignalSpy dataChanged(&model, &QAbstractItemModel::dataChanged);
    const QModelIndex i = model.index(1);
    EXPECT_TRUE(model.flags(i) & Qt::ItemIsUserCheckable);
    EXPECT_EQ(model.data(i, Qt::CheckStateRole).toInt(), Qt::Checked);
    EXPECT_TRUE(model.setData(i, Qt::Unchecked, Qt::CheckStateRole));
    EXPECT_FALSE(doc.object(1).visible);
    EXPECT_EQ(model.data(i, Qt::CheckStateRole).toInt(), Qt::Unchecked);
    ASSERT_EQ(dataChanged.count(), 1);
    EXPECT_EQ(dataChanged.at(0).at(0).value<QModelIndex>().row(), 1);

    EXPECT_TRUE(model.setData(i, QStringLiteral("  bunny "), Qt::EditRole));
    EXPECT_EQ(doc.object(1).name, "bunny");
    EXPECT_FALSE(model.setData(i, QStringLiteral("   "), Qt::EditRole)) << "empty names refused";
    EXPECT_EQ(doc.object(1).name, "bunny");
    EXPECT_TRUE(ModelTestWarnings::messages().empty()) << joined(ModelTestWarnings::messages());
}

TEST(SceneListModel, TooltipNamesLambdaModeAndTriangles) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    Material m;
    m.lambda = 3.5f;
    m.mode = LookupMode::Normal;
    doc.setMaterial(2, m);
    SceneListModel model(&doc);
    const QString tip = model.data(model.index(2), Qt::ToolTipRole).toString();
    EXPECT_TRUE(tip.contains(QStringLiteral("3.50"))) << tip.toStdString();
    EXPECT_TRUE(tip.contains(QStringLiteral("normal"))) << tip.toStdString();
    const QString triangles = QLocale().toString(static_cast<qlonglong>(sphereMesh()->triangleCount()));
    EXPECT_TRUE(tip.contains(triangles)) << tip.toStdString();
    // A layered material is named by its layers, not by the single lobe's λ it does not use.
    Material paint;
    paint.layered = true;
    paint.layers = {Rgb(0.6f, 0.04f, 0.03f), 0.0f, 0.25f, 0.04f, 1.0f, 0.03f, MaterialMaps{}};
    doc.setMaterial(2, paint);
    const QString layered = model.data(model.index(2), Qt::ToolTipRole).toString();
    EXPECT_TRUE(layered.contains(QStringLiteral("base 0.60, 0.04, 0.03"))) << layered.toStdString();
    EXPECT_TRUE(layered.contains(QStringLiteral("roughness 0.25"))) << layered.toStdString();
    EXPECT_TRUE(layered.contains(QStringLiteral("coat 1.00"))) << layered.toStdString();
    EXPECT_FALSE(layered.contains(QStringLiteral("λ"))) << layered.toStdString();
}

// Adds, duplicates, removes and their undo and redo move single rows: the model never resets
// (only resetScene does), the tester finds nothing wrong, and a selection stays on its object
// while rows come and go above it.
TEST(SceneListModel, MovesRowsWithoutResettingThroughEditsAndUndo) {
    ModelTestWarnings warnings;
    ModelTestWarnings::messages().clear();
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    SceneListModel model(&doc);
    QAbstractItemModelTester tester(&model, QAbstractItemModelTester::FailureReportingMode::Warning);
    QItemSelectionModel selection(&model);
    selection.setCurrentIndex(model.index(2), QItemSelectionModel::ClearAndSelect);  // "c"
    QSignalSpy resets(&model, &QAbstractItemModel::modelAboutToBeReset);
    QSignalSpy inserted(&model, &QAbstractItemModel::rowsInserted);
    QSignalSpy removed(&model, &QAbstractItemModel::rowsRemoved);
    // Qt 6.4 reports row moves with empty selectionChanged signals; count only real changes.
    int selectionChanges = 0;
    QObject::connect(&selection, &QItemSelectionModel::selectionChanged, &model,
                     [&](const QItemSelection& selected, const QItemSelection& deselected) {
                         if (!selected.isEmpty() || !deselected.isEmpty()) ++selectionChanges;
                     });
    auto selectedName = [&] {
        const QModelIndexList rows = selection.selectedRows();
        return rows.size() == 1 ? rows.first().data().toString().toStdString() : std::string("(none)");
    };

    doc.duplicateObject(0);  // a row above "c"
    EXPECT_EQ(selectedName(), "c");
    EXPECT_EQ(selection.currentIndex().row(), 3);
    doc.addObject(sphereObject("d", 9.0f));
    doc.removeObject(1);  // the copy, above "c"
    EXPECT_EQ(selectedName(), "c");
    EXPECT_EQ(selection.currentIndex().row(), 2);
    QUndoStack* stack = doc.undoStack();
    while (stack->canUndo()) {
        stack->undo();
        EXPECT_EQ(selectedName(), "c");
    }
    while (stack->canRedo()) stack->redo();
    EXPECT_EQ(selectedName(), "c");
    EXPECT_EQ(model.rowCount(), doc.objectCount());
    for (int row = 0; row < model.rowCount(); ++row)
        EXPECT_EQ(model.data(model.index(row)).toString().toStdString(), doc.object(row).name);
    EXPECT_EQ(resets.count(), 0);
    // Inserted: the duplicate, "d", the copy back (undo), then the duplicate and "d" again (redo).
    EXPECT_EQ(inserted.count(), 2 + 1 + 2);
    // Removed: the copy, "d" and the duplicate (undo), the copy again (redo).
    EXPECT_EQ(removed.count(), 1 + 2 + 1);
    EXPECT_EQ(selectionChanges, 0) << "moved with its row, never changed";

    doc.resetScene(threeSpheres());
    EXPECT_EQ(resets.count(), 1);
    EXPECT_TRUE(ModelTestWarnings::messages().empty()) << joined(ModelTestWarnings::messages());
}

// Removing the selected object hands the selection on before the row goes, so a view following
// the document never sees its current row removed.
TEST(SceneDocument, RemovedSelectionIsHandedOnFirst) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    doc.setSelected(1);
    std::vector<std::string> order;
    QObject::connect(&doc, &SceneDocument::selectionChanged, &doc,
            [&](int index) { order.push_back("selected " + std::to_string(index)); });
    QObject::connect(&doc, &SceneDocument::objectAboutToBeRemoved, &doc,
            [&](int index) { order.push_back("removing " + std::to_string(index)); });
    doc.removeObject(1);
    // "c" (row 2) takes the selection, then row 1 goes and "c" is row 1.
    EXPECT_EQ(order, (std::vector<std::string>{"selected 2", "removing 1", "selected 1"}));
    EXPECT_EQ(doc.object(doc.selected()).name, "c");
}

TEST(SceneListModel, ShowsMaterialsAndAppliesDroppedLibraryMaterials) {
    SceneDocument doc;
    doc.resetScene(threeSpheres());
    SceneListModel model(&doc);
    EXPECT_EQ(model.data(model.index(1), SceneListModel::MaterialNameRole).toString(), QStringLiteral("b"));
    EXPECT_EQ(model.data(model.index(1), Qt::EditRole).toString(), QStringLiteral("b")) << "the edit role stays the name";
    EXPECT_TRUE(model.data(model.index(1), Qt::ToolTipRole).toString().startsWith(QStringLiteral("b · ")));

    LibraryMaterial gold{"Gold", Material{}};
    gold.material.lambda = 2.5f;
    gold.material.tint = Rgb(1.0f, 0.8f, 0.3f);
    std::unique_ptr<QMimeData> mime(materialMimeData(gold));
    EXPECT_TRUE(model.mimeTypes().contains(QString::fromLatin1(kMaterialMimeType)));
    EXPECT_FALSE(model.canDropMimeData(mime.get(), Qt::CopyAction, 1, 0, {})) << "between rows: nothing to apply to";
    QSignalSpy dataChanged(&model, &QAbstractItemModel::dataChanged);
    ASSERT_TRUE(model.dropMimeData(mime.get(), Qt::CopyAction, -1, -1, model.index(1)));
    EXPECT_EQ(doc.materialOf(1), gold.material);
    EXPECT_EQ(doc.namedMaterialOf(1)->libraryEntry, "Gold");
    EXPECT_EQ(model.data(model.index(1), SceneListModel::MaterialNameRole).toString(), QStringLiteral("Gold"));
    ASSERT_GE(dataChanged.count(), 1);
    EXPECT_EQ(dataChanged.last().at(0).value<QModelIndex>().row(), 1);

    QMimeData text;
    text.setText(QStringLiteral("Gold"));
    EXPECT_FALSE(model.dropMimeData(&text, Qt::CopyAction, -1, -1, model.index(0)));
    doc.undoStack()->undo();
    EXPECT_EQ(model.data(model.index(1), SceneListModel::MaterialNameRole).toString(), QStringLiteral("b"));
}
