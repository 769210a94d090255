// Test assets made by the tests themselves (issue 21: "tinygltf writes them"): glTF files built
// with tinygltf's own writer from meshes and PNG images we make, so every expectation is known
// analytically (a checker's colours at known UVs, a roughness gradient, a tilted normal map).
// Also used by tests/tools/make_assets.cpp, which writes the demo assets README renders.
#pragma once

#include "mipgloss/scene/mesh.h"

#include <tiny_gltf.h>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace mipgloss::test {

// An 8-bit image and its PNG encoding (OpenImageIO).
struct TestImage {
    int width = 0, height = 0, channels = 4;
    std::vector<std::uint8_t> pixels;  // top row first
};
TestImage makeImage(int width, int height, int channels,
                    const std::function<std::vector<std::uint8_t>(int x, int y)>& texel);
std::vector<unsigned char> encodePng(const TestImage& image);
void writePng(const TestImage& image, const std::filesystem::path& file);

// A UV sphere of radius 1 with glTF UVs: u = longitude / 2π (from +X toward −Z... as atan2(−z, x)),
// v = colatitude / π (0 at +Y, the top, as glTF's v runs down the image), a seam column doubled.
Mesh texturedSphere(int rings = 48, int segments = 96);
// The quad z = 0, x, y in [−1, 1], normal +Z, UV (0, 0) at (−1, 1) and (1, 1) at (1, −1).
Mesh texturedQuad();

class GltfWriter {
public:
    GltfWriter();
    // An image embedded in the buffer (mimeType image/png), or, with `uri`, referred to by it.
    int addImage(const std::vector<unsigned char>& png, const std::string& uri = {});
    int addTexture(int image);
    int addMaterial(const tinygltf::Material& material);
    // The mesh's positions, normals (unless `withNormals` is false), UVs (both sets), tangents,
    // vertex colours, indices.
    int addMesh(const Mesh& mesh, int material, bool withNormals = true);
    int addNode(int mesh, const std::vector<double>& translation = {}, const std::vector<double>& scale = {},
                const std::vector<double>& rotation = {});
    void addToScene(int node);
    // A perspective camera of vertical field `yfov` (radians) on a node of its own at
    // `translation`, turned by the quaternion `rotation` (x, y, z, w), added to the scene; returns
    // the node.
    int addCamera(const std::string& name, double yfov, const std::vector<double>& translation,
                  const std::vector<double>& rotation = {0.0, 0.0, 0.0, 1.0});

    tinygltf::Model& model() { return model_; }
    std::vector<unsigned char> glb();
    std::string gltf();  // JSON, the buffer as a data URI
    void writeGlb(const std::filesystem::path& file);
    void writeGltf(const std::filesystem::path& file);

private:
    int addAccessor(const void* data, std::size_t bytes, int componentType, int type, std::size_t count, int target,
                    const std::vector<double>& min = {}, const std::vector<double>& max = {});
    tinygltf::Model model_;
};

// A metallic–roughness material: base colour factor, roughness and metallic factors, and the
// textures given (-1: none).
tinygltf::Material pbrMaterial(const std::string& name, glm::vec4 baseColor, double metallic, double roughness,
                               int baseColorTexture = -1, int metallicRoughnessTexture = -1, int normalTexture = -1);

}  // namespace mipgloss::test
