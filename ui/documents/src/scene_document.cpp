#include "mipgloss/ui/scene_document.h"

#include "mipgloss/assets/textures.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/placement.h"
#include "mipgloss/ui/background_worker.h"
#include "scene_commands.h"

#include <QFileInfo>
#include <QUndoStack>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

namespace mipgloss::ui {

namespace {

bool validLambda(float lambda) { return isValidLambda(static_cast<double>(lambda)); }

// A λ for an object or display arriving without a previous value (addObject, resetScene):
// outside [0, kMaxLambda] it becomes the nearest end, NaN the mirror.
float admittedLambda(float lambda) {
    if (std::isnan(lambda)) return 0.0f;
    return std::clamp(lambda, 0.0f, static_cast<float>(kMaxLambda));
}

// The tint is kept non-negative and finite (it multiplies linear HDR colour).
Material sanitized(Material m) {
    for (int c = 0; c < 3; ++c)
        m.tint[c] = std::isfinite(m.tint[c]) ? std::max(m.tint[c], 0.0f) : 1.0f;
    return m;
}

// Layer values arriving without a previous value: each into [0, 1], NaN the default's.
Layers admittedLayers(Layers l) {
    const Layers defaults;
    auto unit = [](float v, float fallback) { return std::isnan(v) ? fallback : std::clamp(v, 0.0f, 1.0f); };
    for (int c = 0; c < 3; ++c) l.baseColor[c] = unit(l.baseColor[c], defaults.baseColor[c]);
    l.metallic = unit(l.metallic, defaults.metallic);
    l.roughness = unit(l.roughness, defaults.roughness);
    l.specular = unit(l.specular, defaults.specular);
    for (int c = 0; c < 3; ++c)
        l.specularColor[c] = std::isnan(l.specularColor[c]) ? defaults.specularColor[c]
                                                            : std::clamp(l.specularColor[c], 0.0f, kMaxSpecularColour);
    l.specularWeight = unit(l.specularWeight, defaults.specularWeight);
    l.coat = unit(l.coat, defaults.coat);
    l.coatRoughness = unit(l.coatRoughness, defaults.coatRoughness);
    return l;
}

Material admitted(Material m) {
    m = sanitized(m);
    m.lambda = admittedLambda(m.lambda);
    m.layers = admittedLayers(m.layers);
    return m;
}

bool isFinite(const Transform& t) {
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(t.translation[c]) || !std::isfinite(t.rotationDegrees[c])) return false;
    return std::isfinite(t.scale);
}

}  // namespace

SceneDocument::MergeKey SceneDocument::newMergeKey() {
    static std::atomic<MergeKey> last{0};
    return ++last;
}

SceneDocument::SceneDocument(QObject* parent)
    : QObject(parent),
      undoStack_(new QUndoStack(this)),
      textures_(std::make_shared<TextureCache>()),
      textureWorker_(new BackgroundWorker(this)) {}

// ---------------------------------------------------------------------------------------------
// Texture maps: decoded into the document's cache, on its worker or at once.

std::vector<TextureRef> SceneDocument::texturesToDecode(const Scene& scene) const {
    std::vector<TextureRef> missing;
    for (const TextureRef& t : texturesOf(scene))
        if (!textures_->find(t) && textures_->problem(t).empty() && !texturesDecoding_.count(t.key()))
            missing.push_back(t);
    return missing;
}

namespace {

QStringList decodeInto(TextureCache& cache, const std::vector<TextureRef>& refs) {
    QStringList warnings;
    for (const std::string& w : cache.load(refs)) warnings << QString::fromStdString(w);
    return warnings;
}

}  // namespace

QStringList SceneDocument::decodeTexturesNow(const Scene& scene) {
    const std::vector<TextureRef> missing = texturesToDecode(scene);
    return missing.empty() ? QStringList() : decodeInto(*textures_, missing);
}

void SceneDocument::decodeTexturesLater(const Scene& scene) {
    const std::vector<TextureRef> missing = texturesToDecode(scene);
    if (missing.empty()) return;
    for (const TextureRef& t : missing) texturesDecoding_.insert(t.key());
    textureWorker_->start([textures = textures_, missing](Job&) { return decodeInto(*textures, missing); },
                          [this, missing](JobOutcome<QStringList>&& outcome, const Job&) {
                              for (const TextureRef& t : missing) texturesDecoding_.erase(t.key());
                              QStringList warnings = outcome.value.value_or(QStringList());
                              if (!outcome.error.isEmpty()) warnings << outcome.error;
                              emit texturesDecoded(warnings);
                          });
}

// ---------------------------------------------------------------------------------------------
// Edits: each pushes one command, or nothing when it would change nothing.

void SceneDocument::pushInsert(int index, SceneObject object, std::optional<NamedMaterial> added,
                               const QString& text) {
    undoStack_->push(new InsertObjectCommand(this, index, std::move(object), std::move(added), text));
}

int SceneDocument::addObject(SceneObject object, const Material& material) {
    NamedMaterial own = scene_.newMaterial(object.name, admitted(material));
    object.material = own.id;
    const QString text = tr("Add %1").arg(QString::fromStdString(object.name));
    pushInsert(objectCount(), std::move(object), std::move(own), text);
    return objectCount() - 1;
}

int SceneDocument::addObject(SceneObject object, const std::string& materialName, const Material& material) {
    NamedMaterial own = scene_.newMaterial(materialName, admitted(material));
    object.material = own.id;
    const QString text = tr("Add %1").arg(QString::fromStdString(object.name));
    pushInsert(objectCount(), std::move(object), std::move(own), text);
    return objectCount() - 1;
}

int SceneDocument::addObject(SceneObject object) {
    if (scene_.findMaterial(object.material)) {
        const QString text = tr("Add %1").arg(QString::fromStdString(object.name));
        pushInsert(objectCount(), std::move(object), std::nullopt, text);
        return objectCount() - 1;
    }
    return addObject(std::move(object), Material{});
}

void SceneDocument::removeObject(int index) {
    if (!isValidIndex(index)) return;
    undoStack_->push(new RemoveObjectCommand(this, index));
}

int SceneDocument::duplicateObject(int index) {
    if (!isValidIndex(index)) return -1;
    SceneObject copy = object(index);  // shares the mesh (shared_ptr<const Mesh>) and the material
    const QString text = tr("Duplicate %1").arg(QString::fromStdString(copy.name));
    copy.name += " copy";
    copy.transform = besideOriginal(copy);
    pushInsert(index + 1, std::move(copy), std::nullopt, text);
    return index + 1;
}

void SceneDocument::setMaterial(int index, const Material& material, MergeKey merge) {
    if (!isValidIndex(index)) return;
    const NamedMaterial* named = namedMaterialOf(index);
    if (!named) return;
    const Material& current = named->material;
    Material m = sanitized(material);
    if (!validLambda(m.lambda)) m.lambda = current.lambda;  // refused: the last good λ stays
    if (!isValidLayers(m.layers)) m.layers = current.layers;  // so do the last good layers
    if (current == m) return;
    undoStack_->push(new SetMaterialCommand(this, named->id, current, m, merge));
}

void SceneDocument::setTransform(int index, const Transform& transform, MergeKey merge) {
    if (!isValidIndex(index) || !isFinite(transform)) return;
    const Transform& current = object(index).transform;
    if (current == transform) return;
    undoStack_->push(new SetTransformCommand(this, index, current, transform, merge));
}

void SceneDocument::setVisible(int index, bool visible) {
    if (!isValidIndex(index) || object(index).visible == visible) return;
    undoStack_->push(new SetVisibleCommand(this, index, visible));
}

void SceneDocument::setName(int index, const QString& name) {
    if (!isValidIndex(index)) return;
    const std::string value = name.toStdString();
    if (object(index).name == value) return;
    undoStack_->push(new SetObjectNameCommand(this, index, object(index).name, value));
}

bool SceneDocument::setMaterialName(int index, const QString& name) {
    if (!isValidIndex(index)) return false;
    const NamedMaterial* named = namedMaterialOf(index);
    if (!named) return false;
    const std::string value = name.trimmed().toStdString();
    if (value == named->name) return true;
    if (!materialNameProblem(value).empty()) return false;
    if (scene_.findMaterialNamed(value)) return false;
    undoStack_->push(new RenameMaterialCommand(this, named->id, named->name, value));
    return true;
}

void SceneDocument::assignMaterial(int index, MaterialId id) {
    if (!isValidIndex(index) || !scene_.findMaterial(id) || object(index).material == id) return;
    const QString text = tr("Give %1 the material %2")
                             .arg(QString::fromStdString(object(index).name),
                                  QString::fromStdString(scene_.findMaterial(id)->name));
    undoStack_->push(new AssignMaterialCommand(this, index, object(index).material, id, std::nullopt, text));
}

MaterialId SceneDocument::makeMaterialUnique(int index) {
    if (!isValidIndex(index)) return kNoMaterial;
    const NamedMaterial* named = namedMaterialOf(index);
    if (!named) return kNoMaterial;
    if (scene_.usersOf(named->id) <= 1) return named->id;
    const NamedMaterial copy = scene_.newMaterial(named->name, named->material, named->libraryEntry);
    const QString text = tr("Give %1 a material of its own").arg(QString::fromStdString(object(index).name));
    undoStack_->push(new AssignMaterialCommand(this, index, named->id, copy.id, copy, text));
    return copy.id;
}

void SceneDocument::applyLibraryMaterial(int index, const LibraryMaterial& entry) {
    if (!isValidIndex(index)) return;
    const Material wanted = admitted(entry.material);
    MaterialId id = kNoMaterial;
    for (const NamedMaterial& m : scene_.materials)
        if (m.libraryEntry == entry.name && m.material == wanted) id = m.id;
    std::optional<NamedMaterial> added;
    if (id == kNoMaterial) {
        added = scene_.newMaterial(entry.name, wanted, entry.name);
        id = added->id;
    }
    if (object(index).material == id) return;
    const QString text = tr("Apply %1 to %2")
                             .arg(QString::fromStdString(entry.name),
                                  QString::fromStdString(object(index).name));
    undoStack_->push(
        new AssignMaterialCommand(this, index, object(index).material, id, std::move(added), text));
}

void SceneDocument::setEnvironment(const EnvironmentSettings& settings, MergeKey merge) {
    if (scene_.environment == settings) return;
    undoStack_->push(new SetEnvironmentCommand(this, scene_.environment, settings, merge));
}

void SceneDocument::setDisplay(const DisplaySettings& settings, MergeKey merge) {
    DisplaySettings d = settings;
    if (!validLambda(d.backgroundLambda))
        d.backgroundLambda = scene_.display.backgroundLambda;  // refused: the last good λ stays
    if (scene_.display == d) return;
    undoStack_->push(new SetDisplayCommand(this, scene_.display, d, merge));
}

void SceneDocument::withdrawFailedEnvironment(const EnvironmentSettings& failed,
                                              const EnvironmentSettings& fallback) {
    if (!(scene_.environment == failed)) return;  // moved on meanwhile
    auto asksForFailed = [&](const QUndoCommand* command) {
        const auto* step = dynamic_cast<const SetEnvironmentCommand*>(command);
        return step && !step->isObsolete() && step->after() == failed;
    };
    // The newest steps that asked for it: undone (their undo puts back what was asked before) and
    // dropped from the stack.
    while (undoStack_->index() > 0) {
        const QUndoCommand* latest = undoStack_->command(undoStack_->index() - 1);
        if (!asksForFailed(latest)) break;
        // The stack's own command; command() only hands it out const.
        static_cast<SetEnvironmentCommand*>(const_cast<QUndoCommand*>(latest))->withdraw();
        const int index = undoStack_->index();
        undoStack_->undo();
        if (undoStack_->index() == index) break;  // a macro is open: the stack refuses to undo
    }
    if (!(scene_.environment == failed)) return;
    // Under later edits: put the fallback back as it is, and let Undo pass over the old steps.
    for (int i = 0; i < undoStack_->index(); ++i)
        if (asksForFailed(undoStack_->command(i)))
            const_cast<QUndoCommand*>(undoStack_->command(i))->setObsolete(true);
    replaceEnvironment(fallback);
    notifyChanged();
}

void SceneDocument::resetScene(Scene scene, FileCameras cameras) {
    fileCameras_ = std::move(cameras);
    for (NamedMaterial& m : scene.materials) m.material = admitted(m.material);
    for (SceneObject& o : scene.objects)
        if (!scene.findMaterial(o.material)) o.material = scene.addMaterial(o.name, Material{});
    scene.display.backgroundLambda = admittedLambda(scene.display.backgroundLambda);
    undoStack_->clear();
    const bool environmentDiffers = !(scene_.environment == scene.environment);
    const bool displayDiffers = !(scene_.display == scene.display);
    const int before = selected_;
    emit aboutToReset();
    scene_ = std::move(scene);
    selected_ = -1;
    emit sceneReset();
    emit objectsChanged();
    emit materialsChanged();
    if (environmentDiffers) emit environmentChanged();
    if (displayDiffers) emit displayChanged();
    emit changed();
    if (selected_ != before) emit selectionChanged(selected_);
}

void SceneDocument::setSelected(int index) {
    if (!isValidIndex(index)) index = -1;
    if (selected_ == index) return;
    selected_ = index;
    emit selectionChanged(selected_);
}

// ---------------------------------------------------------------------------------------------
// The commands' steps

void SceneDocument::insertMaterialAt(std::size_t position, const NamedMaterial& material) {
    position = std::min(position, scene_.materials.size());
    scene_.materials.insert(scene_.materials.begin() + static_cast<std::ptrdiff_t>(position), material);
    emit materialsChanged();
}

void SceneDocument::removeMaterial(MaterialId id) {
    const auto it = std::find_if(scene_.materials.begin(), scene_.materials.end(),
                                 [id](const NamedMaterial& m) { return m.id == id; });
    if (it == scene_.materials.end()) return;
    scene_.materials.erase(it);
    emit materialsChanged();
}

void SceneDocument::replaceMaterial(MaterialId id, const Material& material) {
    NamedMaterial* named = scene_.findMaterial(id);
    if (!named) return;
    named->material = material;
    for (int i = 0; i < objectCount(); ++i)
        if (object(i).material == id) emit materialChanged(i);
}

void SceneDocument::renameMaterial(MaterialId id, const std::string& name) {
    NamedMaterial* named = scene_.findMaterial(id);
    if (!named) return;
    named->name = name;
    emit materialsChanged();
    for (int i = 0; i < objectCount(); ++i)
        if (object(i).material == id) emit materialChanged(i);
}

void SceneDocument::setObjectMaterial(int index, MaterialId id) {
    if (!isValidIndex(index)) return;
    scene_.objects[static_cast<std::size_t>(index)].material = id;
    emit materialChanged(index);
}

void SceneDocument::replaceTransform(int index, const Transform& transform) {
    if (!isValidIndex(index)) return;
    scene_.objects[static_cast<std::size_t>(index)].transform = transform;
    emit transformChanged(index);
}

void SceneDocument::replaceName(int index, const std::string& name) {
    if (!isValidIndex(index)) return;
    scene_.objects[static_cast<std::size_t>(index)].name = name;
    emit objectChanged(index);
}

void SceneDocument::replaceVisible(int index, bool visible) {
    if (!isValidIndex(index)) return;
    scene_.objects[static_cast<std::size_t>(index)].visible = visible;
    emit objectChanged(index);
}

void SceneDocument::insertObject(int index, SceneObject object) {
    index = std::clamp(index, 0, objectCount());
    emit objectAboutToBeInserted(index);
    scene_.objects.insert(scene_.objects.begin() + index, std::move(object));
    const int before = selected_;
    if (selected_ >= index) ++selected_;  // the selection stays with its object
    emit objectInserted(index);
    emit objectsChanged();
    if (selected_ != before) emit selectionChanged(selected_);
}

void SceneDocument::takeObject(int index) {
    if (!isValidIndex(index)) return;
    // A selected object hands the selection on first, to the object that will take its row (or
    // the new last one), so Delete pressed repeatedly empties the list and no view loses its
    // current row in the middle of the removal.
    if (selected_ == index) setSelected(index + 1 < objectCount() ? index + 1 : index - 1);
    emit objectAboutToBeRemoved(index);
    scene_.objects.erase(scene_.objects.begin() + index);
    const int before = selected_;
    if (selected_ > index) --selected_;
    emit objectRemoved(index);
    emit objectsChanged();
    if (selected_ != before) emit selectionChanged(selected_);
}

void SceneDocument::replaceEnvironment(const EnvironmentSettings& settings) {
    scene_.environment = settings;
    emit environmentChanged();
}

void SceneDocument::replaceDisplay(const DisplaySettings& settings) {
    scene_.display = settings;
    emit displayChanged();
}

void SceneDocument::addFileCameras(const std::string& file, std::vector<AssetCamera> cameras) {
    if (cameras.empty()) return;
    fileCameras_[file] = std::move(cameras);
}

std::vector<SceneDocument::CameraView> SceneDocument::fileCameraViews() const {
    std::vector<CameraView> out;
    const Bounds bounds = sceneBounds(scene_);
    for (const auto& entry : fileCameras_) {
        // A named reference, not the structured binding: clang 14 (the sanitizer build) does not
        // let a lambda capture a binding (C++20 P1091 landed in clang 16).
        const std::string& file = entry.first;
        const std::vector<AssetCamera>& cameras = entry.second;
        const auto first = std::find_if(scene_.objects.begin(), scene_.objects.end(),
                                        [&](const SceneObject& o) { return o.meshSource == file; });
        if (first == scene_.objects.end()) continue;
        const QString name = QFileInfo(QString::fromStdString(file)).fileName();
        for (const AssetCamera& camera : cameras)
            out.push_back({QStringLiteral("%1 (%2)").arg(QString::fromStdString(camera.name), name),
                           viewThrough(camera, first->transform, bounds)});
    }
    return out;
}

}  // namespace mipgloss::ui
