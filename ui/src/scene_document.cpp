#include "mipgloss/ui/scene_document.h"

#include "mipgloss/ibl/phong.h"

#include <QUndoStack>

#include <algorithm>
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

bool isFinite(const Transform& t) {
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(t.translation[c]) || !std::isfinite(t.rotationDegrees[c])) return false;
    return std::isfinite(t.scale);
}

}  // namespace

namespace {
Material admitted(Material m) {
    m = sanitized(m);
    m.lambda = admittedLambda(m.lambda);
    return m;
}
}  // namespace

SceneDocument::SceneDocument(QObject* parent) : QObject(parent), undoStack_(new QUndoStack(this)) {}

void SceneDocument::applyLibraryMaterial(int index, const LibraryMaterial& entry) {
    if (!isValidIndex(index)) return;
    const Material wanted = admitted(entry.material);
    MaterialId id = kNoMaterial;
    for (const NamedMaterial& m : scene_.materials)
        if (m.libraryEntry == entry.name && m.material == wanted) id = m.id;
    if (id == kNoMaterial) id = scene_.addMaterial(entry.name, wanted, entry.name);
    SceneObject& o = scene_.objects[static_cast<std::size_t>(index)];
    if (o.material == id) return;
    o.material = id;
    emit materialChanged(index);
    emit changed();
}


int SceneDocument::addObject(SceneObject object, const Material& material) {
    object.material = scene_.addMaterial(object.name, admitted(material));
    return addObject(std::move(object));
}

int SceneDocument::addObject(SceneObject object) {
    if (!scene_.findMaterial(object.material)) object.material = scene_.addMaterial(object.name, Material{});
    scene_.objects.push_back(std::move(object));
    const int index = objectCount() - 1;
    emit objectsChanged();
    emit changed();
    setSelected(index);
    return index;
}

void SceneDocument::removeObject(int index) {
    if (!isValidIndex(index)) return;
    scene_.objects.erase(scene_.objects.begin() + index);
    // The selection follows its object; a removed selection passes to the object that took its
    // row (or the new last one), so Delete pressed repeatedly empties the list.
    const int before = selected_;
    if (selected_ > index)
        --selected_;
    else if (selected_ == index)
        selected_ = std::min(index, objectCount() - 1);
    emit objectsChanged();
    emit changed();
    if (selected_ != before) emit selectionChanged(selected_);
}

int SceneDocument::duplicateObject(int index) {
    if (!isValidIndex(index)) return -1;
    SceneObject copy = object(index);  // shares the mesh: shared_ptr<const Mesh>
    copy.name += " copy";
    // Beside the original along +x, 1.2 world bounding diameters away, so the two never overlap.
    copy.transform.translation.x += 1.2f * 2.0f * copy.worldRadius();
    const int newIndex = index + 1;
    scene_.objects.insert(scene_.objects.begin() + newIndex, std::move(copy));
    if (selected_ >= newIndex) ++selected_;  // keeps the index valid until setSelected below
    emit objectsChanged();
    emit changed();
    setSelected(newIndex);
    return newIndex;
}

void SceneDocument::setMaterial(int index, const Material& material) {
    if (!isValidIndex(index)) return;
    const MaterialId id = scene_.objects[static_cast<std::size_t>(index)].material;
    NamedMaterial* named = scene_.findMaterial(id);
    if (!named) return;
    Material& current = named->material;
    Material m = sanitized(material);
    if (!validLambda(m.lambda)) m.lambda = current.lambda;  // refused: the last good λ stays
    if (current == m) return;
    current = m;
    for (int i = 0; i < objectCount(); ++i)
        if (object(i).material == id) emit materialChanged(i);
    emit changed();
}

void SceneDocument::setTransform(int index, const Transform& transform) {
    if (!isValidIndex(index) || !isFinite(transform)) return;
    Transform& current = scene_.objects[static_cast<std::size_t>(index)].transform;
    if (current == transform) return;
    current = transform;
    emit transformChanged(index);
    emit changed();
}

void SceneDocument::setVisible(int index, bool visible) {
    if (!isValidIndex(index)) return;
    bool& current = scene_.objects[static_cast<std::size_t>(index)].visible;
    if (current == visible) return;
    current = visible;
    emit objectChanged(index);
    emit changed();
}

void SceneDocument::setName(int index, const QString& name) {
    if (!isValidIndex(index)) return;
    std::string& current = scene_.objects[static_cast<std::size_t>(index)].name;
    const std::string value = name.toStdString();
    if (current == value) return;
    current = value;
    emit objectChanged(index);
    emit changed();
}

void SceneDocument::setEnvironment(const EnvironmentSettings& settings) {
    if (scene_.environment == settings) return;
    scene_.environment = settings;
    emit environmentChanged();
    emit changed();
}

void SceneDocument::setDisplay(const DisplaySettings& settings) {
    DisplaySettings d = settings;
    if (!validLambda(d.backgroundLambda))
        d.backgroundLambda = scene_.display.backgroundLambda;  // refused: the last good λ stays
    if (scene_.display == d) return;
    scene_.display = d;
    emit displayChanged();
    emit changed();
}

void SceneDocument::resetScene(Scene scene) {
    for (NamedMaterial& m : scene.materials) m.material = admitted(m.material);
    for (SceneObject& o : scene.objects)
        if (!scene.findMaterial(o.material)) o.material = scene.addMaterial(o.name, Material{});
    scene.display.backgroundLambda = admittedLambda(scene.display.backgroundLambda);
    const bool environmentDiffers = !(scene_.environment == scene.environment);
    const bool displayDiffers = !(scene_.display == scene.display);
    const int before = selected_;
    scene_ = std::move(scene);
    selected_ = -1;
    emit objectsChanged();
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

}  // namespace mipgloss::ui
