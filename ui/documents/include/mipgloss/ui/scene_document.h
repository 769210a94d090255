// The edited scene, shared by the window's panels and the viewport. Setters emit their signal only
// when the value changes (Qt's setX / xChanged habit), so two-way bindings are safe. The scene
// itself stays a plain value (mipgloss::Scene); meshes are shared, never copied, by duplicates.
//
// Undo. Every edit made through the public setters is a QUndoCommand (scene_commands.h) pushed
// onto undoStack(); the command applies it through the private mutators below, which change the
// scene and emit the targeted signals, and nothing else. So undo and redo emit exactly what the
// edit did, and undoing returns the scene to a value equal (Scene::operator==) to the one before
// the edit: material ids, the materials' order and the objects' order included. Edits that change
// nothing push nothing. resetScene (New, Open) is not an edit: it clears the stack.
//
// One step per interaction. setMaterial, setTransform, setEnvironment and setDisplay take a
// MergeKey: consecutive edits of the same target (the same material, object, the environment or
// the display settings) carrying the same non-zero key merge into one undo step, and a merge that
// comes back to the value before the step drops the step. The panels take a key per interaction
// (a slider drag, a visit to a spin box: edit_sessions.h); 0, the default, never merges.
//
// The document never holds an invalid λ (phong.h's isValidLambda: finite, in [0, kMaxLambda]).
// setMaterial and setDisplay refuse one (NaN, negative, above kMaxLambda): the λ keeps its last
// good value, the edit's other fields still apply, and nothing is emitted if nothing else
// changed. The document has no error channel, so the refusal is silent; the widgets never send
// such a value (material_panel.h, the environment panel's background box) and scene files reject
// one on load (scene_file.h). addObject and resetScene have no previous value to keep: they bring
// an out-of-range λ to the nearest end of [0, kMaxLambda] and a NaN one to 0 (the mirror).
//
// Signals. Object rows come in pairs, before and after the change (objectAboutToBeInserted /
// objectInserted, objectAboutToBeRemoved / objectRemoved, aboutToReset / sceneReset), so a model
// can tell its views exactly which row moves (scene_list_model.h); objectsChanged follows each of
// them for those that only need to know that the list changed. A removed selected object hands
// the selection on (to the object that takes its row, or the new last one) before it is removed,
// so a view never sees its current row disappear. changed() comes once per edit, after the
// targeted signals.
#pragma once

#include "mipgloss/assets/asset.h"
#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/library.h"
#include "mipgloss/scene/scene.h"

#include <QObject>
#include <QString>
#include <QStringList>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

class QUndoStack;

namespace mipgloss {
class TextureCache;  // mipgloss/assets/textures.h
}

namespace mipgloss::ui {

class BackgroundWorker;

class SceneDocument : public QObject {
    Q_OBJECT
public:
    // Edits carrying the same non-zero key merge into one undo step (see above).
    using MergeKey = std::uint64_t;
    static MergeKey newMergeKey();  // never returned before in this process, never 0

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
    // The same with the new material named `materialName` (an asset's material, named as in its file).
    int addObject(SceneObject object, const std::string& materialName, const Material& material);
    int addObject(SceneObject object);
    void removeObject(int index);
    int duplicateObject(int index);  // placed beside the original, same mesh and material (shared)
    // Edits the material object `index` uses, so every object sharing it changes.
    void setMaterial(int index, const Material& material, MergeKey merge = 0);
    void setTransform(int index, const Transform& transform, MergeKey merge = 0);
    void setVisible(int index, bool visible);
    void setName(int index, const QString& name);

    // Materials. setMaterialName renames the material object `index` uses (for every object that
    // shares it); the name is trimmed, and refused (false, no change) when it is not a valid
    // material name (library.h's materialNameProblem) or another material of the scene has it.
    bool setMaterialName(int index, const QString& name);
    // Object `index` uses material `id` from now on; an id not in the scene changes nothing.
    void assignMaterial(int index, MaterialId id);
    // Gives object `index` a copy of its material of its own ("Gold" -> "Gold 2", the same
    // parameters and library entry) when others share it; returns the material it uses after.
    MaterialId makeMaterialUnique(int index);
    // Gives object `index` the library entry's material: a scene material that came from the same
    // entry with the same parameters is reused, otherwise a new one named after the entry (made
    // unique) and remembering it is added.
    void applyLibraryMaterial(int index, const LibraryMaterial& entry);

    void setEnvironment(const EnvironmentSettings& settings, MergeKey merge = 0);
    void setDisplay(const DisplaySettings& settings, MergeKey merge = 0);
    // The environment the document asked for, `failed` (EnvironmentManager::lastFailure()), could
    // not be used: `fallback` goes back without a step of its own.
    // The steps that asked for `failed` are withdrawn: the newest ones on the stack are undone and
    // dropped (neither Undo nor Redo offers them again), and older ones, under later edits, are
    // made obsolete (Undo passes over them without changing anything). Nothing happens when the
    // document has moved on to other settings meanwhile.
    void withdrawFailedEnvironment(const EnvironmentSettings& failed, const EnvironmentSettings& fallback);

    // Replaces everything (open scene, new scene) and clears the undo stack; `cameras` are the
    // new scene's files' cameras (below).
    void resetScene(Scene scene, FileCameras cameras = {});

    // The cameras the scene's asset files hold (glTF cameras, asset.h), by the file's absolute
    // path (SceneObject::meshSource): file data, not an edit, so no undo step; an import adds its
    // file's, resetScene replaces them all.
    void addFileCameras(const std::string& file, std::vector<AssetCamera> cameras);
    // What View → Look through offers: each camera of each file some object in the scene comes
    // from, placed as that file's first object is (an import places all of a file's parts alone
    // together; an object moved on its own takes the cameras only if it is the first), framing
    // the scene's bounds (viewThrough). In the files' order, then the cameras'.
    struct CameraView {
        QString label;  // "Camera name (file.gltf)"
        OrbitCamera view;
    };
    std::vector<CameraView> fileCameraViews() const;

    int selected() const { return selected_; }
    void setSelected(int index);  // -1 clears

    // The decoded images this document's texture maps read (textures.h): its own cache, which its
    // views draw from (Renderer::setTextures) and its imports fill; no other document's.
    const std::shared_ptr<TextureCache>& textures() const { return textures_; }
    // The maps `scene` reads that the cache lacks (not decoded, not refused, not on the way),
    // decoded on the document's BackgroundWorker; texturesDecoded follows when they arrive.
    void decodeTexturesLater(const Scene& scene);
    // The same decoded here and now (a picture written to a file waits for its maps); returns the
    // cache's warnings, each naming a map that could not be read.
    QStringList decodeTexturesNow(const Scene& scene);
    bool decodingTextures() const { return !texturesDecoding_.empty(); }

signals:
    void objectAboutToBeInserted(int index);
    void objectInserted(int index);
    void objectAboutToBeRemoved(int index);
    void objectRemoved(int index);
    void aboutToReset();
    void sceneReset();
    void objectsChanged();                 // after any of the six above
    void objectChanged(int index);         // name, visibility
    void materialChanged(int index);       // which material, its parameters or its name; for
                                           // every object using the edited material
    void materialsChanged();               // the scene's materials: one added, removed or renamed
    void transformChanged(int index);
    void environmentChanged();
    void displayChanged();
    void selectionChanged(int index);
    void changed();                        // once per edit, undo or redo, and on reset
    // Maps decodeTexturesLater asked for have arrived (views redraw); `warnings` names each one
    // that could not be read.
    void texturesDecoded(const QStringList& warnings);

private:
    // The undo commands' one door to the steps below (scene_commands.h), as LibraryEdits is the
    // library document's.
    friend struct SceneEdits;

    // The steps commands are made of: change the scene and emit the targeted signals, nothing
    // else (no changed(), no undo step).
    void insertMaterialAt(std::size_t position, const NamedMaterial& material);
    void removeMaterial(MaterialId id);
    void replaceMaterial(MaterialId id, const Material& material);
    void renameMaterial(MaterialId id, const std::string& name);
    void setObjectMaterial(int index, MaterialId id);
    void replaceTransform(int index, const Transform& transform);
    void replaceName(int index, const std::string& name);
    void replaceVisible(int index, bool visible);
    void insertObject(int index, SceneObject object);
    void takeObject(int index);
    void replaceEnvironment(const EnvironmentSettings& settings);
    void replaceDisplay(const DisplaySettings& settings);
    void notifyChanged() { emit changed(); }

    void pushInsert(int index, SceneObject object, std::optional<NamedMaterial> added, const QString& text);

    // The maps of `scene` missing from the cache and not on the worker.
    std::vector<TextureRef> texturesToDecode(const Scene& scene) const;

    QUndoStack* undoStack_ = nullptr;
    Scene scene_;
    FileCameras fileCameras_;
    int selected_ = -1;
    std::shared_ptr<TextureCache> textures_;
    BackgroundWorker* textureWorker_ = nullptr;
    std::set<std::string> texturesDecoding_;  // TextureRef keys on the worker now
};

}  // namespace mipgloss::ui
