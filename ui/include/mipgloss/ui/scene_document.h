// The edited scene, shared by the window's panels and the viewport. Setters emit their signal only
// when the value changes (Qt's setX / xChanged habit), so two-way bindings are safe. The scene
// itself stays a plain value (mipgloss::Scene); meshes are shared, never copied, by duplicates.
//
// The document never holds an invalid λ (phong.h's isValidLambda: finite, in [0, kMaxLambda]).
// setMaterial and setDisplay refuse one (NaN, negative, above kMaxLambda): the λ keeps its last
// good value, the edit's other fields still apply, and nothing is emitted if nothing else
// changed. The document has no error channel, so the refusal is silent; the widgets never send
// such a value (material_panel.h, the window's background box) and scene files reject one on
// load (scene_file.h). addObject and resetScene have no previous value to keep: they bring an
// out-of-range λ to the nearest end of [0, kMaxLambda] and a NaN one to 0 (the mirror).
#pragma once

#include "mipgloss/scene/library.h"
#include "mipgloss/scene/scene.h"

#include <QObject>
#include <QString>

class QUndoStack;

namespace mipgloss::ui {

class SceneDocument : public QObject {
    Q_OBJECT
public:
    explicit SceneDocument(QObject* parent = nullptr);

    const Scene& scene() const { return scene_; }
    // The undo stack every edit of this document (and of the library, library_document.h) is
    // pushed onto; the window's Edit menu undoes and redoes through it.
    QUndoStack* undoStack() const { return undoStack_; }
    int objectCount() const { return static_cast<int>(scene_.objects.size()); }
    const SceneObject& object(int index) const { return scene_.objects.at(static_cast<std::size_t>(index)); }
    bool isValidIndex(int index) const { return index >= 0 && index < objectCount(); }
    // What object `index` is drawn with (Scene::materialOf), and its named material (null if none).
    const Material& materialOf(int index) const { return scene_.materialOf(object(index)); }
    const NamedMaterial* namedMaterialOf(int index) const { return scene_.findMaterial(object(index).material); }

    // Objects. addObject returns the new index and selects it. The first form gives the object a
    // material of its own named after it; the second keeps the material it names, which must be
    // one of the scene's (otherwise the object gets a default material of its own).
    int addObject(SceneObject object, const Material& material);
    int addObject(SceneObject object);
    void removeObject(int index);
    int duplicateObject(int index);  // placed beside the original, same mesh and material (shared)
    // Edits the material object `index` uses, so every object sharing it changes.
    void setMaterial(int index, const Material& material);
    void setTransform(int index, const Transform& transform);
    void setVisible(int index, bool visible);
    void setName(int index, const QString& name);

    // Gives object `index` the library entry's material: a scene material that came from the same
    // entry with the same parameters is reused, otherwise a new one named after the entry (made
    // unique) and remembering it is added.
    void applyLibraryMaterial(int index, const LibraryMaterial& entry);

    void setEnvironment(const EnvironmentSettings& settings);
    void setDisplay(const DisplaySettings& settings);

    // Replaces everything (open scene, new scene).
    void resetScene(Scene scene);

    int selected() const { return selected_; }
    void setSelected(int index);  // -1 clears

signals:
    void objectsChanged();                 // added, removed, reordered or reset
    void objectChanged(int index);         // name, visibility
    void materialChanged(int index);       // emitted for every object using the edited material
    void transformChanged(int index);
    void environmentChanged();
    void displayChanged();
    void selectionChanged(int index);
    void changed();                        // any of the above except selection

private:
    QUndoStack* undoStack_ = nullptr;
    Scene scene_;
    int selected_ = -1;
};

}  // namespace mipgloss::ui
