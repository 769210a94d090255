#include "mipgloss/scene/scene.h"

#include "mipgloss/scene/placement.h"

#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace mipgloss {

const char* lookupModeName(LookupMode mode) {
    return mode == LookupMode::Normal ? "normal" : "reflect";
}

bool parseLookupMode(const std::string& text, LookupMode& out) {
    if (text == "reflect" || text == "reflection") {
        out = LookupMode::Reflect;
        return true;
    }
    if (text == "normal") {
        out = LookupMode::Normal;
        return true;
    }
    return false;
}

bool isValidMaterial(const Material& material) {
    if (!isValidLambda(static_cast<double>(material.lambda))) return false;
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(material.tint[c]) || material.tint[c] < 0.0f) return false;
    return isValidLayers(material.layers);
}

bool isValidLayers(const Layers& layers) { return layersProblem(layers).empty(); }

std::string layersProblem(const Layers& layers) {
    const std::pair<const char*, float> values[] = {
        {"base colour red", layers.baseColor.r}, {"base colour green", layers.baseColor.g},
        {"base colour blue", layers.baseColor.b}, {"metallic", layers.metallic},
        {"roughness", layers.roughness},          {"specular", layers.specular},
        {"coat", layers.coat},                    {"coat roughness", layers.coatRoughness},
        {"specular weight", layers.specularWeight},
    };
    for (const auto& [name, value] : values)
        if (!(std::isfinite(value) && value >= 0.0f && value <= 1.0f)) {
            std::ostringstream text;
            text << name << ' ' << value << " is not in [0, 1]";
            return text.str();
        }
    for (int c = 0; c < 3; ++c)
        if (!(std::isfinite(layers.specularColor[c]) && layers.specularColor[c] >= 0.0f &&
              layers.specularColor[c] <= kMaxSpecularColour)) {
            std::ostringstream text;
            const char* channel[] = {"red", "green", "blue"};
            text << "specular colour " << channel[c] << ' ' << layers.specularColor[c] << " is not in [0, "
                 << kMaxSpecularColour << "]";
            return text.str();
        }
    const MaterialMaps& m = layers.maps;
    const std::pair<const char*, float> maps[] = {
        {"base alpha", m.baseAlpha},
        {"alpha cutoff", m.alphaCutoff},
        {"occlusion strength", m.occlusionStrength},
    };
    for (const auto& [name, value] : maps)
        if (!(std::isfinite(value) && value >= 0.0f && value <= 1.0f)) {
            std::ostringstream text;
            text << name << ' ' << value << " is not in [0, 1]";
            return text.str();
        }
    // A normal map's scale may be negative (a flipped green channel) but stays a tilt, not a blow-up.
    if (!(std::isfinite(m.normalScale) && std::abs(m.normalScale) <= kMaxNormalScale)) {
        std::ostringstream text;
        text << "normal scale " << m.normalScale << " is not in [-" << kMaxNormalScale << ", " << kMaxNormalScale << "]";
        return text.str();
    }
    for (float e : {m.emissiveFactor.r, m.emissiveFactor.g, m.emissiveFactor.b})
        if (!(std::isfinite(e) && e >= 0.0f && e <= kMaxEmissive)) {
            std::ostringstream text;
            text << "emissive " << e << " is not in [0, " << kMaxEmissive << "]";
            return text.str();
        }
    for (const TextureRef& t : m.textures())
        if (t.channel < 0 || t.channel > 3) return "texture " + t.key() + " reads channel " + std::to_string(t.channel) + " (0 to 3)";
    return {};
}

std::string TextureRef::key() const {
    return image < 0 ? file : file + "#image " + std::to_string(image);
}

const char* alphaModeName(AlphaMode mode) {
    switch (mode) {
        case AlphaMode::Opaque: return "opaque";
        case AlphaMode::Mask: return "mask";
        case AlphaMode::Blend: return "blend";
    }
    return "opaque";
}

bool parseAlphaMode(const std::string& text, AlphaMode& out) {
    for (AlphaMode m : {AlphaMode::Opaque, AlphaMode::Mask, AlphaMode::Blend})
        if (text == alphaModeName(m)) {
            out = m;
            return true;
        }
    return false;
}

bool MaterialMaps::anyTexture() const { return !textures().empty(); }

bool MaterialMaps::inUse() const {
    return anyTexture() || emissiveFactor.r > 0.0f || emissiveFactor.g > 0.0f || emissiveFactor.b > 0.0f ||
           alphaMode == AlphaMode::Mask || alphaMode == AlphaMode::Blend;
}

std::vector<TextureRef> MaterialMaps::textures() const {
    std::vector<TextureRef> out;
    for (const TextureRef* t : {&baseColor, &metallic, &roughness, &normal, &occlusion, &emissive})
        if (!t->empty()) out.push_back(*t);
    return out;
}

const char* textureWrapName(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::Repeat: return "repeat";
        case TextureWrap::ClampToEdge: return "clamp";
        case TextureWrap::MirroredRepeat: return "mirror";
    }
    return "repeat";
}

bool parseTextureWrap(const std::string& text, TextureWrap& out) {
    for (TextureWrap w : {TextureWrap::Repeat, TextureWrap::ClampToEdge, TextureWrap::MirroredRepeat})
        if (text == textureWrapName(w)) {
            out = w;
            return true;
        }
    return false;
}

glm::mat3 TextureSampling::uvTransform() const {
    // Column-major, as KHR_texture_transform writes T · R · S (its R turns +u toward −v: the
    // image's v runs down, so that is counter-clockwise as the image is seen).
    const float c = std::cos(rotation), s = std::sin(rotation);
    const glm::mat3 translate(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
    const glm::mat3 rotate(c, -s, 0, s, c, 0, 0, 0, 1);
    const glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
    return translate * rotate * scaling;
}

const char* toneMapName(ToneMap map) {
    switch (map) {
        case ToneMap::Linear: return "linear";
        case ToneMap::Reinhard: return "reinhard";
        case ToneMap::Aces: return "aces";
        case ToneMap::PbrNeutral: return "pbr-neutral";
        case ToneMap::Agx: return "agx";
    }
    return "aces";
}

bool parseToneMap(const std::string& text, ToneMap& out) {
    for (ToneMap m : kAllToneMaps)
        if (text == toneMapName(m)) {
            out = m;
            return true;
        }
    return false;
}

glm::mat4 Transform::matrix() const {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translation);
    m = glm::rotate(m, glm::radians(rotationDegrees.y), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(rotationDegrees.x), glm::vec3(1, 0, 0));
    m = glm::rotate(m, glm::radians(rotationDegrees.z), glm::vec3(0, 0, 1));
    return glm::scale(m, glm::vec3(scale));
}

glm::vec3 SceneObject::worldCentre() const {
    if (!mesh) return transform.translation;
    return glm::vec3(transform.matrix() * glm::vec4(mesh->bounds.centre(), 1.0f));
}

float SceneObject::worldRadius() const {
    return mesh ? mesh->bounds.radius() * std::abs(transform.scale) : 0.0f;
}

Scene makeFigure1Scene(const std::shared_ptr<const Mesh>& teapot) {
    Scene scene;
    scene.environment.source = kBuiltinEnvironment;
    scene.environment.faceSize = 128;
    // A 128² face magnified to a window is blocky; a soft backdrop (level 2) keeps the eye on the
    // teapots, as a photographer's shallow focus would. The user can set it back to 0.
    scene.display.backgroundLambda = 2.0f;
    struct Entry {
        const char* name;
        const char* material;
        float lambda;
        LookupMode mode;
    };
    const Entry entries[] = {{"mirror (λ 0)", "Chrome", 0.0f, LookupMode::Reflect},
                             {"glossy (λ 3.5)", "Polished", 3.5f, LookupMode::Reflect},
                             {"glossy (λ 5)", "Satin", 5.0f, LookupMode::Reflect},
                             {"diffuse (λ 7, normal)", "Matte (normal)", 7.0f, LookupMode::Normal}};
    for (int i = 0; i < 4; ++i) {
        SceneObject object;
        object.name = entries[i].name;
        object.mesh = teapot;
        object.meshSource = "builtin:teapot";
        object.transform = inCentredRow(teapot->bounds, i, 4);
        Material material;
        material.lambda = entries[i].lambda;
        material.mode = entries[i].mode;
        object.material = scene.addMaterial(entries[i].material, material);
        scene.objects.push_back(std::move(object));
    }
    return scene;
}

std::string uniqueName(const std::string& base, const std::function<bool(const std::string&)>& taken) {
    const std::string stem = base.empty() ? std::string("Material") : base;
    if (!taken(stem)) return stem;
    for (int n = 2;; ++n) {
        std::string candidate = stem + " " + std::to_string(n);
        if (!taken(candidate)) return candidate;
    }
}

std::string UniqueNames::take(const std::string& base) {
    const std::string stem = base.empty() ? std::string("Material") : base;
    std::string name = stem;
    if (taken_.count(name)) {
        int& next = next_[stem];
        next = std::max(next, 2);
        do name = stem + " " + std::to_string(next++);
        while (taken_.count(name));
    }
    taken_.insert(name);
    return name;
}

const NamedMaterial* Scene::findMaterial(MaterialId id) const {
    if (id == kNoMaterial) return nullptr;
    // Ids are handed out one above the largest (nextMaterialId), so a scene built by adding holds
    // material id at position id − 1 (or near it, after removals): looked there first, since every
    // object's draw asks (a linear search per object was 62 % of drawing 30 000 parts).
    if (id > 0 && !materials.empty()) {
        const std::size_t guess = std::min(static_cast<std::size_t>(id - 1), materials.size() - 1);
        if (materials[guess].id == id) return &materials[guess];
    }
    for (const NamedMaterial& m : materials)
        if (m.id == id) return &m;
    return nullptr;
}

NamedMaterial* Scene::findMaterial(MaterialId id) {
    return const_cast<NamedMaterial*>(std::as_const(*this).findMaterial(id));
}

const NamedMaterial* Scene::findMaterialNamed(std::string_view name) const {
    for (const NamedMaterial& m : materials)
        if (m.name == name) return &m;
    return nullptr;
}

const Material& Scene::materialOf(const SceneObject& object) const {
    static const Material kDefault{};
    const NamedMaterial* m = findMaterial(object.material);
    return m ? m->material : kDefault;
}

Material& Scene::materialOf(const SceneObject& object) {
    NamedMaterial* m = findMaterial(object.material);
    if (!m) throw std::out_of_range("object \"" + object.name + "\" has no material");
    return m->material;
}

MaterialId Scene::nextMaterialId() const {
    MaterialId largest = kNoMaterial;
    for (const NamedMaterial& m : materials) largest = std::max(largest, m.id);
    return largest + 1;
}

NamedMaterial Scene::newMaterial(const std::string& name, const Material& material,
                                 const std::string& libraryEntry) const {
    NamedMaterial m;
    m.id = nextMaterialId();
    m.name = uniqueName(name, [this](const std::string& n) { return findMaterialNamed(n) != nullptr; });
    m.material = material;
    m.libraryEntry = libraryEntry;
    return m;
}

MaterialId Scene::addMaterial(const std::string& name, const Material& material,
                              const std::string& libraryEntry) {
    materials.push_back(newMaterial(name, material, libraryEntry));
    return materials.back().id;
}

int Scene::addObject(SceneObject object, const Material& material) {
    object.material = addMaterial(object.name, material);
    objects.push_back(std::move(object));
    return static_cast<int>(objects.size()) - 1;
}

int Scene::usersOf(MaterialId id) const {
    return static_cast<int>(std::count_if(objects.begin(), objects.end(),
                                          [id](const SceneObject& o) { return o.material == id; }));
}

Bounds sceneBounds(const Scene& scene) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    Bounds out{glm::vec3(inf), glm::vec3(-inf)};
    bool any = false;
    for (const SceneObject& object : scene.objects) {
        if (!object.visible) continue;
        const std::optional<Bounds> b = objectBounds(object);
        if (!b) continue;
        out.min = glm::min(out.min, b->min);
        out.max = glm::max(out.max, b->max);
        any = true;
    }
    if (!any) return Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
    return out;
}

std::optional<Bounds> objectBounds(const SceneObject& object) {
    if (!object.mesh) return std::nullopt;
    constexpr float inf = std::numeric_limits<float>::infinity();
    Bounds out{glm::vec3(inf), glm::vec3(-inf)};
    // The eight corners of the mesh box under the transform.
    const glm::mat4 m = object.transform.matrix();
    const Bounds& b = object.mesh->bounds;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                          (corner & 4) ? b.max.z : b.min.z);
        const glm::vec3 w(m * glm::vec4(p, 1.0f));
        out.min = glm::min(out.min, w);
        out.max = glm::max(out.max, w);
    }
    return out;
}


}  // namespace mipgloss
