// The scene's edits as undo commands (Qt's undoframework example): each keeps the value before
// and after, and redo()/undo() apply one or the other through SceneEdits (SceneDocument's steps),
// then emit changed() once. Made only by SceneDocument's public setters (scene_document.h), which
// push a command only when the edit changes something.
//
// Indices. A command names an object by its index. That is safe because the stack replays edits
// in order: when a command runs, the scene is exactly what it was when the command was made (or,
// for undo, right after it ran).
//
// Merging (id()/mergeWith(), ReplaceCommand): commands of the same kind, for the same target, pushed
// one after the other with the same non-zero MergeKey become one step, whose "before" is the first
// command's and "after" the last one's; a merged step that ends where it began is obsolete and
// leaves the stack.
#pragma once

#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/scene_document.h"

#include <QUndoCommand>

#include <optional>
#include <utility>
#include <string>

namespace mipgloss::ui {

// The commands' only way to change the document: its steps (scene_document.h, private), each
// changing the scene and emitting its targeted signals, and notifyChanged (changed(), once per
// step of the stack).
struct SceneEdits {
    static void insertMaterialAt(SceneDocument& d, std::size_t position, const NamedMaterial& material) {
        d.insertMaterialAt(position, material);
    }
    static void removeMaterial(SceneDocument& d, MaterialId id) { d.removeMaterial(id); }
    static void replaceMaterial(SceneDocument& d, MaterialId id, const Material& material) {
        d.replaceMaterial(id, material);
    }
    static void renameMaterial(SceneDocument& d, MaterialId id, const std::string& name) { d.renameMaterial(id, name); }
    static void setObjectMaterial(SceneDocument& d, int index, MaterialId id) { d.setObjectMaterial(index, id); }
    static void replaceTransform(SceneDocument& d, int index, const Transform& t) { d.replaceTransform(index, t); }
    static void replaceName(SceneDocument& d, int index, const std::string& name) { d.replaceName(index, name); }
    static void replaceVisible(SceneDocument& d, int index, bool visible) { d.replaceVisible(index, visible); }
    static void insertObject(SceneDocument& d, int index, SceneObject object) {
        d.insertObject(index, std::move(object));
    }
    static void takeObject(SceneDocument& d, int index) { d.takeObject(index); }
    static void replaceEnvironment(SceneDocument& d, const EnvironmentSettings& s) { d.replaceEnvironment(s); }
    static void replaceDisplay(SceneDocument& d, const DisplaySettings& s) { d.replaceDisplay(s); }
    static void notifyChanged(SceneDocument& d) { d.notifyChanged(); }
};

// Command ids for QUndoCommand::id(): the kinds that merge, and -1 for those that never do.
enum SceneCommandId : int {
    kNeverMerges = -1,
    kMaterialCommandId = 1001,
    kTransformCommandId,
    kEnvironmentCommandId,
    kDisplayCommandId,
};

// One value replaced by another: a material's parameters or name, a placement, an object's name or
// visibility, the environment or the display settings. Derived classes apply a value to their
// target and name the step; merging, and dropping a merged step that ends where it began, are here.
template <class Value, int Id>
class ReplaceCommand : public QUndoCommand {
public:
    ReplaceCommand(SceneDocument* document, const Value& before, const Value& after,
                   SceneDocument::MergeKey merge)
        : document_(document), before_(before), after_(after), merge_(merge) {}
    void redo() override {
        apply(after_);
        SceneEdits::notifyChanged(*document_);
    }
    void undo() override {
        apply(before_);
        SceneEdits::notifyChanged(*document_);
    }
    int id() const override { return Id; }
    bool mergeWith(const QUndoCommand* other) override {
        // The same id is the same derived class.
        const auto* next = static_cast<const ReplaceCommand*>(other);
        if (merge_ == 0 || next->merge_ != merge_ || !sameTarget(*next)) return false;
        after_ = next->after_;
        setObsolete(after_ == before_);
        updateText();
        return true;
    }
    const Value& after() const { return after_; }

protected:
    virtual void apply(const Value& value) = 0;
    // For merging: whether `other` (of the same class) edits the same thing.
    virtual bool sameTarget(const ReplaceCommand& /*other*/) const { return true; }
    virtual void updateText() = 0;  // derived constructors call it too

    SceneDocument* document_;
    Value before_, after_;

private:
    SceneDocument::MergeKey merge_;
};

// The parameters of one material (the same for every object that uses it).
class SetMaterialCommand : public ReplaceCommand<Material, kMaterialCommandId> {
public:
    SetMaterialCommand(SceneDocument* document, MaterialId id, const Material& before,
                       const Material& after, SceneDocument::MergeKey merge);

private:
    void apply(const Material& value) override;
    bool sameTarget(const ReplaceCommand& other) const override;
    void updateText() override;
    MaterialId material_;
    QString name_;  // the material's, for the text
};

class RenameMaterialCommand : public ReplaceCommand<std::string, kNeverMerges> {
public:
    RenameMaterialCommand(SceneDocument* document, MaterialId id, const std::string& before,
                          const std::string& after);

private:
    void apply(const std::string& name) override;
    void updateText() override;
    MaterialId material_;
};

// Object `index` uses another material; `added`, when given, is a material the step adds to the
// scene first (make unique, a library material new to the scene) and removes again on undo.
class AssignMaterialCommand : public QUndoCommand {
public:
    AssignMaterialCommand(SceneDocument* document, int index, MaterialId before, MaterialId after,
                          std::optional<NamedMaterial> added, const QString& text);
    void redo() override;
    void undo() override;

private:
    SceneDocument* document_;
    int index_;
    MaterialId before_, after_;
    std::optional<NamedMaterial> added_;
};

class SetTransformCommand : public ReplaceCommand<Transform, kTransformCommandId> {
public:
    SetTransformCommand(SceneDocument* document, int index, const Transform& before,
                        const Transform& after, SceneDocument::MergeKey merge);

private:
    void apply(const Transform& value) override;
    bool sameTarget(const ReplaceCommand& other) const override;
    void updateText() override;
    int index_;
    QString name_;  // the object's, for the text
};

class SetObjectNameCommand : public ReplaceCommand<std::string, kNeverMerges> {
public:
    SetObjectNameCommand(SceneDocument* document, int index, const std::string& before, const std::string& after);

private:
    void apply(const std::string& name) override;
    void updateText() override;
    int index_;
};

class SetVisibleCommand : public ReplaceCommand<bool, kNeverMerges> {
public:
    SetVisibleCommand(SceneDocument* document, int index, bool visible);

private:
    void apply(const bool& visible) override;
    void updateText() override;
    int index_;
    QString name_;  // the object's, for the text
};

// Adds an object at `index` (add, duplicate, import) and selects it; `added`, when given, is its
// own new material, added with it and removed with it on undo.
class InsertObjectCommand : public QUndoCommand {
public:
    InsertObjectCommand(SceneDocument* document, int index, SceneObject object,
                        std::optional<NamedMaterial> added, const QString& text);
    void redo() override;
    void undo() override;

private:
    SceneDocument* document_;
    int index_;
    SceneObject object_;
    std::optional<NamedMaterial> added_;
};

// Removes object `index`; undo puts it back where it was and selects it. Its material stays in the
// scene (unused materials may stay, scene.h), so nothing else needs restoring.
class RemoveObjectCommand : public QUndoCommand {
public:
    RemoveObjectCommand(SceneDocument* document, int index);
    void redo() override;
    void undo() override;

private:
    SceneDocument* document_;
    int index_;
    SceneObject object_;
};

class SetEnvironmentCommand : public ReplaceCommand<EnvironmentSettings, kEnvironmentCommandId> {
public:
    SetEnvironmentCommand(SceneDocument* document, const EnvironmentSettings& before,
                          const EnvironmentSettings& after, SceneDocument::MergeKey merge);
    void undo() override;
    // The next undo() is the last: the command makes itself obsolete, so the stack drops it.
    void withdraw() { withdrawn_ = true; }

private:
    void apply(const EnvironmentSettings& value) override;
    void updateText() override;
    bool withdrawn_ = false;
};

class SetDisplayCommand : public ReplaceCommand<DisplaySettings, kDisplayCommandId> {
public:
    SetDisplayCommand(SceneDocument* document, const DisplaySettings& before, const DisplaySettings& after,
                      SceneDocument::MergeKey merge);

private:
    void apply(const DisplaySettings& value) override;
    void updateText() override;
};

}  // namespace mipgloss::ui
