#include "scene_commands.h"

#include <QFileInfo>

#include <utility>

namespace mipgloss::ui {

// Marks a step's text for translation (lupdate) in SceneDocument's context, where tr() below looks
// it up.
#define EDIT_TEXT(text) QT_TRANSLATE_NOOP("mipgloss::ui::SceneDocument", text)

namespace {

// The texts belong with SceneDocument's own (Add, Duplicate, ...) for translators.
QString tr(const char* text) { return SceneDocument::tr(text); }

QString qstr(const std::string& name) { return QString::fromStdString(name); }

QString objectName(const SceneDocument* document, int index) {
    return document->isValidIndex(index) ? qstr(document->object(index).name) : QString();
}

QString materialName(const SceneDocument* document, MaterialId id) {
    const NamedMaterial* named = document->scene().findMaterial(id);
    return named ? qstr(named->name) : QString();
}

// The text naming the one field an edit changed, or `several` when more (or none) changed.
class ChangedField {
public:
    explicit ChangedField(const char* several) : text_(several), several_(several) {}
    void note(bool differs, const char* text) {
        if (differs) text_ = ++count_ == 1 ? text : several_;
    }
    QString text() const { return tr(text_); }

private:
    const char* text_;
    const char* several_;
    int count_ = 0;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Materials

SetMaterialCommand::SetMaterialCommand(SceneDocument* document, MaterialId id, const Material& before,
                                       const Material& after, SceneDocument::MergeKey merge)
    : ReplaceCommand(document, before, after, merge), material_(id), name_(materialName(document, id)) {
    updateText();
}

void SetMaterialCommand::apply(const Material& value) { SceneEdits::replaceMaterial(*document_, material_, value); }

bool SetMaterialCommand::sameTarget(const ReplaceCommand& other) const {
    return static_cast<const SetMaterialCommand&>(other).material_ == material_;
}

void SetMaterialCommand::updateText() {
    // "Change λ of Gold"; several fields at once: "Edit material Gold".
    ChangedField field(EDIT_TEXT("Edit material %1"));
    field.note(before_.lambda != after_.lambda, EDIT_TEXT("Change λ of %1"));
    field.note(before_.mode != after_.mode, EDIT_TEXT("Change lookup of %1"));
    field.note(before_.useIrradiance != after_.useIrradiance, EDIT_TEXT("Change irradiance map use of %1"));
    field.note(before_.tint != after_.tint, EDIT_TEXT("Change tint of %1"));
    field.note(before_.sharperAtGrazing != after_.sharperAtGrazing,
               EDIT_TEXT("Change grazing sharpening of %1"));
    setText(field.text().arg(name_));
}

RenameMaterialCommand::RenameMaterialCommand(SceneDocument* document, MaterialId id, const std::string& before,
                                             const std::string& after)
    : ReplaceCommand(document, before, after, 0), material_(id) {
    updateText();
}

void RenameMaterialCommand::apply(const std::string& name) { SceneEdits::renameMaterial(*document_, material_, name); }

void RenameMaterialCommand::updateText() {
    setText(tr("Rename material %1 to %2").arg(qstr(before_), qstr(after_)));
}

AssignMaterialCommand::AssignMaterialCommand(SceneDocument* document, int index, MaterialId before,
                                             MaterialId after, std::optional<NamedMaterial> added,
                                             const QString& text)
    : document_(document), index_(index), before_(before), after_(after), added_(std::move(added)) {
    setText(text);
}

void AssignMaterialCommand::redo() {
    if (added_) SceneEdits::insertMaterialAt(*document_, document_->scene().materials.size(), *added_);
    SceneEdits::setObjectMaterial(*document_, index_, after_);
    SceneEdits::notifyChanged(*document_);
}

void AssignMaterialCommand::undo() {
    SceneEdits::setObjectMaterial(*document_, index_, before_);
    if (added_) SceneEdits::removeMaterial(*document_, added_->id);
    SceneEdits::notifyChanged(*document_);
}

// ---------------------------------------------------------------------------------------------
// Objects

SetTransformCommand::SetTransformCommand(SceneDocument* document, int index, const Transform& before,
                                         const Transform& after, SceneDocument::MergeKey merge)
    : ReplaceCommand(document, before, after, merge), index_(index), name_(objectName(document, index)) {
    updateText();
}

void SetTransformCommand::apply(const Transform& value) { SceneEdits::replaceTransform(*document_, index_, value); }

bool SetTransformCommand::sameTarget(const ReplaceCommand& other) const {
    return static_cast<const SetTransformCommand&>(other).index_ == index_;
}

void SetTransformCommand::updateText() {
    ChangedField field(EDIT_TEXT("Place %1"));
    field.note(before_.translation != after_.translation, EDIT_TEXT("Move %1"));
    field.note(before_.rotationDegrees != after_.rotationDegrees, EDIT_TEXT("Rotate %1"));
    field.note(before_.scale != after_.scale, EDIT_TEXT("Scale %1"));
    setText(field.text().arg(name_));
}

SetObjectNameCommand::SetObjectNameCommand(SceneDocument* document, int index, const std::string& before,
                                           const std::string& after)
    : ReplaceCommand(document, before, after, 0), index_(index) {
    updateText();
}

void SetObjectNameCommand::apply(const std::string& name) { SceneEdits::replaceName(*document_, index_, name); }

void SetObjectNameCommand::updateText() { setText(tr("Rename %1 to %2").arg(qstr(before_), qstr(after_))); }

SetVisibleCommand::SetVisibleCommand(SceneDocument* document, int index, bool visible)
    : ReplaceCommand(document, !visible, visible, 0), index_(index), name_(objectName(document, index)) {
    updateText();
}

void SetVisibleCommand::apply(const bool& visible) { SceneEdits::replaceVisible(*document_, index_, visible); }

void SetVisibleCommand::updateText() { setText((after_ ? tr("Show %1") : tr("Hide %1")).arg(name_)); }

InsertObjectCommand::InsertObjectCommand(SceneDocument* document, int index, SceneObject object,
                                         std::optional<NamedMaterial> added, const QString& text)
    : document_(document), index_(index), object_(std::move(object)), added_(std::move(added)) {
    setText(text);
}

void InsertObjectCommand::redo() {
    if (added_) SceneEdits::insertMaterialAt(*document_, document_->scene().materials.size(), *added_);
    SceneEdits::insertObject(*document_, index_, object_);
    SceneEdits::notifyChanged(*document_);
    document_->setSelected(index_);
}

void InsertObjectCommand::undo() {
    SceneEdits::takeObject(*document_, index_);
    if (added_) SceneEdits::removeMaterial(*document_, added_->id);
    SceneEdits::notifyChanged(*document_);
}

RemoveObjectCommand::RemoveObjectCommand(SceneDocument* document, int index)
    : document_(document), index_(index), object_(document->object(index)) {
    setText(tr("Remove %1").arg(qstr(object_.name)));
}

void RemoveObjectCommand::redo() {
    SceneEdits::takeObject(*document_, index_);
    SceneEdits::notifyChanged(*document_);
}

void RemoveObjectCommand::undo() {
    SceneEdits::insertObject(*document_, index_, object_);
    SceneEdits::notifyChanged(*document_);
    document_->setSelected(index_);
}

// ---------------------------------------------------------------------------------------------
// Environment and display

SetEnvironmentCommand::SetEnvironmentCommand(SceneDocument* document, const EnvironmentSettings& before,
                                             const EnvironmentSettings& after, SceneDocument::MergeKey merge)
    : ReplaceCommand(document, before, after, merge) {
    updateText();
}

void SetEnvironmentCommand::apply(const EnvironmentSettings& value) { SceneEdits::replaceEnvironment(*document_, value); }

void SetEnvironmentCommand::undo() {
    ReplaceCommand::undo();
    // QUndoStack deletes a command that is obsolete after its undo().
    if (withdrawn_) setObsolete(true);
}

void SetEnvironmentCommand::updateText() {
    if (before_.source != after_.source) {
        const QString name = after_.source == kBuiltinEnvironment
                                 ? tr("courtyard")
                                 : QFileInfo(QString::fromStdString(after_.source)).fileName();
        setText(tr("Open environment %1").arg(name));
        return;
    }
    ChangedField field(EDIT_TEXT("Change environment"));
    field.note(before_.layout != after_.layout, EDIT_TEXT("Change environment layout"));
    field.note(before_.handedness != after_.handedness, EDIT_TEXT("Change face image orientation"));
    field.note(before_.faceSize != after_.faceSize, EDIT_TEXT("Change face size"));
    field.note(before_.builder != after_.builder, EDIT_TEXT("Change mip builder"));
    setText(field.text());
}

SetDisplayCommand::SetDisplayCommand(SceneDocument* document, const DisplaySettings& before,
                                     const DisplaySettings& after, SceneDocument::MergeKey merge)
    : ReplaceCommand(document, before, after, merge) {
    updateText();
}

void SetDisplayCommand::apply(const DisplaySettings& value) { SceneEdits::replaceDisplay(*document_, value); }

void SetDisplayCommand::updateText() {
    ChangedField field(EDIT_TEXT("Change display settings"));
    field.note(before_.showBackground != after_.showBackground,
               after_.showBackground ? EDIT_TEXT("Show background") : EDIT_TEXT("Hide background"));
    field.note(before_.backgroundLambda != after_.backgroundLambda, EDIT_TEXT("Change background blur"));
    field.note(before_.backdrop != after_.backdrop, EDIT_TEXT("Change backdrop colour"));
    field.note(before_.exposureEv != after_.exposureEv, EDIT_TEXT("Change exposure"));
    field.note(before_.toneMap != after_.toneMap, EDIT_TEXT("Change tone map"));
    field.note(before_.samples != after_.samples, EDIT_TEXT("Change multisampling"));
    field.note(before_.scattering != after_.scattering, after_.scattering == Scattering::Compensated
                                                            ? EDIT_TEXT("Keep bounced light")
                                                            : EDIT_TEXT("Single scattering"));
    field.note(before_.environmentRotationDegrees != after_.environmentRotationDegrees,
               EDIT_TEXT("Rotate environment"));
    setText(field.text());
}

}  // namespace mipgloss::ui
