#include "gltf_writer.h"

#include <OpenImageIO/imageio.h>

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace mipgloss::test {

TestImage makeImage(int width, int height, int channels,
                    const std::function<std::vector<std::uint8_t>(int x, int y)>& texel) {
    TestImage image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels.reserve(static_cast<std::size_t>(width) * height * channels);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::vector<std::uint8_t> t = texel(x, y);
            for (int c = 0; c < channels; ++c) image.pixels.push_back(t[static_cast<std::size_t>(c)]);
        }
    return image;
}

void writePng(const TestImage& image, const std::filesystem::path& file) {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw std::runtime_error("no PNG writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8);
    // The texels are straight alpha, as glTF's images are (OpenImageIO would divide them by alpha).
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) ||
        !out->close())
        throw std::runtime_error("cannot write " + file.string() + ": " + out->geterror());
}

std::vector<unsigned char> encodePng(const TestImage& image) {
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("mipgloss-png-" + std::to_string(::getpid()) + "-" +
                                        std::to_string(reinterpret_cast<std::uintptr_t>(&image)) + ".png");
    writePng(image, file);
    std::ifstream in(file, std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(file);
    return bytes;
}

Mesh texturedSphere(int rings, int segments) {
    Mesh mesh;
    mesh.name = "sphere";
    for (int r = 0; r <= rings; ++r) {
        const float v = static_cast<float>(r) / static_cast<float>(rings);
        const float theta = v * glm::pi<float>();
        for (int s = 0; s <= segments; ++s) {
            const float u = static_cast<float>(s) / static_cast<float>(segments);
            const float phi = u * glm::two_pi<float>();
            const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            mesh.positions.push_back(p);
            mesh.normals.push_back(p);
            mesh.uvs.emplace_back(u, v);
        }
    }
    const auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            // Counter-clockwise seen from outside.
            if (r > 0) mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r + 1, s), at(r, s + 1)});
            if (r + 1 < rings) mesh.indices.insert(mesh.indices.end(), {at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)});
        }
    computeBounds(mesh);
    return mesh;
}

Mesh texturedQuad() {
    Mesh mesh;
    mesh.name = "quad";
    mesh.positions = {{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
    mesh.normals.assign(4, glm::vec3(0, 0, 1));
    mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh.indices = {0, 3, 2, 0, 2, 1};
    computeBounds(mesh);
    return mesh;
}

GltfWriter::GltfWriter() {
    model_.asset.version = "2.0";
    model_.asset.generator = "mipgloss tests";
    model_.buffers.emplace_back();
    model_.scenes.emplace_back();
    model_.defaultScene = 0;
}

int GltfWriter::addAccessor(const void* data, std::size_t bytes, int componentType, int type, std::size_t count,
                            int target, const std::vector<double>& min, const std::vector<double>& max) {
    std::vector<unsigned char>& buffer = model_.buffers[0].data;
    while (buffer.size() % 4 != 0) buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model_.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model_.bufferViews.size()) - 1;
    accessor.componentType = componentType;
    accessor.type = type;
    accessor.count = count;
    accessor.minValues = min;
    accessor.maxValues = max;
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size()) - 1;
}

int GltfWriter::addImage(const std::vector<unsigned char>& png, const std::string& uri) {
    tinygltf::Image image;
    if (uri.empty()) {
        std::vector<unsigned char>& buffer = model_.buffers[0].data;
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = buffer.size();
        view.byteLength = png.size();
        buffer.insert(buffer.end(), png.begin(), png.end());
        model_.bufferViews.push_back(view);
        image.bufferView = static_cast<int>(model_.bufferViews.size()) - 1;
        image.mimeType = "image/png";
    } else {
        image.uri = uri;
    }
    model_.images.push_back(image);
    return static_cast<int>(model_.images.size()) - 1;
}

int GltfWriter::addTexture(int image) {
    tinygltf::Texture texture;
    texture.source = image;
    model_.textures.push_back(texture);
    return static_cast<int>(model_.textures.size()) - 1;
}

int GltfWriter::addMaterial(const tinygltf::Material& material) {
    model_.materials.push_back(material);
    return static_cast<int>(model_.materials.size()) - 1;
}

int GltfWriter::addMesh(const Mesh& mesh, int material, bool withNormals) {
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = material;
    glm::vec3 lo = mesh.positions.at(0), hi = lo;
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    primitive.attributes["POSITION"] =
        addAccessor(mesh.positions.data(), mesh.positions.size() * 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                    mesh.positions.size(), TINYGLTF_TARGET_ARRAY_BUFFER, {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
    if (withNormals && !mesh.normals.empty())
        primitive.attributes["NORMAL"] = addAccessor(mesh.normals.data(), mesh.normals.size() * 12,
                                                     TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                                     mesh.normals.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    if (!mesh.uvs.empty())
        primitive.attributes["TEXCOORD_0"] = addAccessor(mesh.uvs.data(), mesh.uvs.size() * 8, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                         TINYGLTF_TYPE_VEC2, mesh.uvs.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    if (!mesh.tangents.empty())
        primitive.attributes["TANGENT"] = addAccessor(mesh.tangents.data(), mesh.tangents.size() * 16,
                                                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4,
                                                      mesh.tangents.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    if (!mesh.uvs1.empty())
        primitive.attributes["TEXCOORD_1"] = addAccessor(mesh.uvs1.data(), mesh.uvs1.size() * 8, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                         TINYGLTF_TYPE_VEC2, mesh.uvs1.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    if (!mesh.colours.empty())
        primitive.attributes["COLOR_0"] = addAccessor(mesh.colours.data(), mesh.colours.size() * 16,
                                                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4,
                                                      mesh.colours.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    primitive.indices = addAccessor(mesh.indices.data(), mesh.indices.size() * 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                    TINYGLTF_TYPE_SCALAR, mesh.indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Mesh m;
    m.name = mesh.name;
    m.primitives.push_back(primitive);
    model_.meshes.push_back(m);
    return static_cast<int>(model_.meshes.size()) - 1;
}

int GltfWriter::addNode(int mesh, const std::vector<double>& translation, const std::vector<double>& scale,
                        const std::vector<double>& rotation) {
    tinygltf::Node node;
    node.mesh = mesh;
    node.translation = translation;
    node.scale = scale;
    node.rotation = rotation;
    model_.nodes.push_back(node);
    return static_cast<int>(model_.nodes.size()) - 1;
}

void GltfWriter::addToScene(int node) { model_.scenes[0].nodes.push_back(node); }

int GltfWriter::addCamera(const std::string& name, double yfov, const std::vector<double>& translation,
                          const std::vector<double>& rotation) {
    tinygltf::Camera camera;
    camera.name = name;
    camera.type = "perspective";
    camera.perspective.yfov = yfov;
    camera.perspective.znear = 0.1;
    model_.cameras.push_back(camera);
    tinygltf::Node node;
    node.camera = static_cast<int>(model_.cameras.size()) - 1;
    node.translation = translation;
    node.rotation = rotation;
    model_.nodes.push_back(node);
    const int index = static_cast<int>(model_.nodes.size()) - 1;
    addToScene(index);
    return index;
}

std::vector<unsigned char> GltfWriter::glb() {
    model_.buffers[0].uri.clear();
    tinygltf::TinyGLTF writer;
    std::ostringstream out;
    if (!writer.WriteGltfSceneToStream(&model_, out, false, true)) throw std::runtime_error("tinygltf cannot write the GLB");
    const std::string s = out.str();
    return {s.begin(), s.end()};
}

std::string GltfWriter::gltf() {
    tinygltf::TinyGLTF writer;
    std::ostringstream out;
    if (!writer.WriteGltfSceneToStream(&model_, out, true, false)) throw std::runtime_error("tinygltf cannot write the glTF");
    return out.str();
}

void GltfWriter::writeGlb(const std::filesystem::path& file) {
    const std::vector<unsigned char> bytes = glb();
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void GltfWriter::writeGltf(const std::filesystem::path& file) {
    const std::string text = gltf();
    std::ofstream(file, std::ios::binary) << text;
}

tinygltf::Material pbrMaterial(const std::string& name, glm::vec4 baseColor, double metallic, double roughness,
                               int baseColorTexture, int metallicRoughnessTexture, int normalTexture) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {baseColor.r, baseColor.g, baseColor.b, baseColor.a};
    m.pbrMetallicRoughness.metallicFactor = metallic;
    m.pbrMetallicRoughness.roughnessFactor = roughness;
    m.pbrMetallicRoughness.baseColorTexture.index = baseColorTexture;
    m.pbrMetallicRoughness.metallicRoughnessTexture.index = metallicRoughnessTexture;
    m.normalTexture.index = normalTexture;
    return m;
}

}  // namespace mipgloss::test
