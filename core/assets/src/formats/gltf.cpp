// The glTF 2.0 reader (asset.h): tinygltf parses the JSON and the GLB container; every index,
// count, offset and stride it hands us is checked here before a byte is read, because tinygltf
// checks only the JSON's shape (an accessor may point past its buffer, an index past its vertices).
#include "mipgloss/assets/asset.h"

#include "formats/asset_files.h"
#include "formats/gltf_json_check.h"
#include "formats/mesh_formats.h"
#include "formats/reading.h"

#include "mipgloss/io/file_error.h"

#include <tiny_gltf.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <string_view>

namespace fs = std::filesystem;

namespace mipgloss {

namespace {

// The extensions this reader honours; a file that requires any other is refused by name.
const std::set<std::string> kSupportedExtensions = {
    "KHR_mesh_quantization",           // integer attributes: read through the accessor's type
    "KHR_materials_emissive_strength", // multiplies emissiveFactor
    "KHR_materials_clearcoat",         // the coat layer (its factors; its textures are named in a warning)
    "KHR_materials_ior",               // the dielectric's F0
    "KHR_materials_specular",          // the dielectric's F0 colour and weight (its factors; its textures named)
    "KHR_texture_transform",           // each map's UV offset, rotation, scale and set
};

// The most nodes deep a hierarchy may be (a cycle or a corrupt file beyond it).
constexpr int kMaxNodeDepth = 256;
// The most vertices and triangles all parts together may hold. Nodes may share a mesh, each
// placement a copy here (asset.h), so a file of a few kilobytes could otherwise ask for billions
// (400 nodes × 120 primitives of one shared mesh: 21.6 million triangles from 17 KB). 2^25 of each
// is ~1.6 GB of mesh, more than any asset an artist previews.
constexpr std::size_t kMaxAssetVertices = std::size_t(1) << 25;
constexpr std::size_t kMaxAssetTriangles = std::size_t(1) << 25;
// What placements may add beyond the file's own geometry (each mesh's vertices and triangles
// counted once): a file's data is bounded by its size, so this is what bounds a small file's
// memory. A 710 KB glTF placing one 20 000-vertex mesh 1 600 times asked for 32 million vertices
// and peaked at 3.2 GB drawing them (issue 34). At 2^23 past the file's own, positions alone
// peaked at 1.46 GB drawn; 2^22 leaves room for every attribute (normals, two UV sets, tangents,
// colours) under 2 GB and still lets a thousand bolts or a hundred chairs repeat.
constexpr std::size_t kMaxPlacedBeyondTheFile = std::size_t(1) << 22;

bool isImageFile(const std::string& path) {
    const std::string ext = meshfile::lowerExtension(path);
    for (const char* e : {".png", ".jpg", ".jpeg", ".webp", ".ktx", ".ktx2", ".bmp", ".gif", ".tga", ".exr", ".hdr",
                          ".tif", ".tiff", ".dds"})
        if (ext == e) return true;
    return false;
}

// What tinygltf may read besides the file itself: external buffers (their bytes are the
// geometry), but not external images, which the texture cache decodes later (and only if a
// material uses them); with no folder (loadGltfFromMemory) nothing at all.
struct FileAccess {
    FileAccess(bool external, bool images) : readExternal(external), readImages(images) {}
    bool readExternal;
    bool readImages;
    // Bytes of external files read so far for this asset: tinygltf keeps a copy per reference, so
    // 12 000 images naming one 365 KB file (a 217 KB glTF) held 4.4 GB. Past kMaxExternalBytes the
    // read is refused, naming the file (issue 34: any input under 1 MB stays under 2 GB).
    std::size_t bytesRead = 0;
    // The images' files (absolute, normalized), whatever their extension: never read here.
    std::set<std::string> imageFiles;
};
constexpr std::size_t kMaxExternalBytes = std::size_t(1) << 30;

// Paths come joined to the asset's absolute folder; a relative one (an asset read with no folder)
// would resolve against the working directory, which an asset never names: not read.
bool fileExists(const std::string& path, void* user) {
    const auto* access = static_cast<const FileAccess*>(user);
    std::error_code ec;
    return access->readExternal && fs::path(path).is_absolute() && fs::is_regular_file(path, ec);
}

std::string expandFilePath(const std::string& path, void*) { return path; }  // no shell expansion, ever

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* access = static_cast<FileAccess*>(user);
    if (!access->readExternal) {
        if (err) *err += "external file '" + path + "' is not read from memory\n";
        return false;
    }
    if (!access->readImages &&
        (isImageFile(path) || access->imageFiles.count(fs::path(path).lexically_normal().string())))
        return false;  // decoded later, by the texture cache
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && access->bytesRead + size > kMaxExternalBytes) {
        if (err)
            *err += "its buffers and images name more than " + std::to_string(kMaxExternalBytes >> 20) +
                    " MiB of files in all (each reference is a copy), reached at '" + path + "'\n";
        return false;
    }
    if (!ec) access->bytesRead += static_cast<std::size_t>(size);
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (err) *err += "cannot open '" + path + "'\n";
        return false;
    }
    out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "mipgloss never writes through the glTF reader\n";
    return false;
}

// Keeps each image's encoded bytes (decoded later with OpenImageIO, off the UI thread). `user` is
// the model being read: tinygltf (2.7) hands over an image's buffer view without checking it
// against its buffer, so the view is checked here before a byte of it is read.
bool keepImageBytes(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                    const unsigned char* bytes, int size, void* user) {
    const auto* model = static_cast<const tinygltf::Model*>(user);
    if (image->bufferView >= 0) {
        const auto view = static_cast<std::size_t>(image->bufferView);
        const tinygltf::BufferView* bv = view < model->bufferViews.size() ? &model->bufferViews[view] : nullptr;
        const tinygltf::Buffer* buffer = bv && bv->buffer >= 0 && static_cast<std::size_t>(bv->buffer) < model->buffers.size()
                                             ? &model->buffers[static_cast<std::size_t>(bv->buffer)] : nullptr;
        if (!buffer || bv->byteOffset > buffer->data.size() || bv->byteLength > buffer->data.size() - bv->byteOffset ||
            bv->byteLength > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
            if (err)
                *err += "image " + std::to_string(index) + ": its buffer view " + std::to_string(image->bufferView) +
                        (bv ? " (" + std::to_string(bv->byteOffset) + " + " + std::to_string(bv->byteLength) +
                                  " bytes) reaches past the end of its buffer"
                            : " is not in the file") + "\n";
            return false;
        }
    }
    image->image.assign(bytes, bytes + std::max(size, 0));
    image->as_is = true;
    return true;
}

std::uint32_t readU32(std::span<const unsigned char> bytes, std::size_t at) {
    return static_cast<std::uint32_t>(bytes[at]) | static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
           static_cast<std::uint32_t>(bytes[at + 2]) << 16 | static_cast<std::uint32_t>(bytes[at + 3]) << 24;
}

// The GLB container's chunks against its length and the bytes there are, before tinygltf reads
// it: tinygltf (2.7) lets a BIN chunk end up to its own 8-byte header past the file's end. "" when
// the container holds together (tinygltf's own checks then say the rest).
std::string glbContainerProblem(std::span<const unsigned char> bytes) {
    if (bytes.size() < 20) return "shorter than a GLB header (" + std::to_string(bytes.size()) + " bytes)";
    const std::uint64_t length = readU32(bytes, 8), jsonLength = readU32(bytes, 12);
    if (length > bytes.size())
        return "its header says " + std::to_string(length) + " bytes, but the file has " + std::to_string(bytes.size()) +
               " (truncated)";
    const std::uint64_t jsonEnd = 20 + jsonLength;
    if (jsonEnd > length)
        return "its JSON chunk (" + std::to_string(jsonLength) + " bytes) reaches past the end of the file's " +
               std::to_string(length) + " bytes";
    if (jsonEnd + 8 <= length) {
        const std::uint64_t binLength = readU32(bytes, static_cast<std::size_t>(jsonEnd));
        if (jsonEnd + 8 + binLength > length)
            return "its second chunk (" + std::to_string(binLength) + " bytes from byte " + std::to_string(jsonEnd + 8) +
                   ") reaches past the end of the file's " + std::to_string(length) + " bytes";
    }
    return {};
}

// A file that requires an extension this reader does not honour is refused by its name.
void refuseUnreadRequired(const std::vector<std::string>& required, const fs::path& file) {
    for (const std::string& e : required)
        if (!kSupportedExtensions.count(e))
            throw AssetError(file, "requires the extension " + e + ", which mipgloss does not read");
}

// The names in the JSON's "extensionsRequired" array, read before tinygltf parses the file: a file
// that requires an extension we do not read (Draco, meshopt) is refused by that name, where
// tinygltf would first fail on what the extension replaces ("accessor[0] invalid bufferView").
// A plain scan, not a parse: it only decides which refusal to give.
std::vector<std::string> requiredExtensions(std::string_view json) {
    std::vector<std::string> names;
    const std::size_t key = json.find("\"extensionsRequired\"");
    if (key == std::string_view::npos) return names;
    std::size_t at = json.find_first_not_of(" \t\r\n", key + 20);
    if (at == std::string_view::npos || json[at] != ':') return names;
    at = json.find_first_not_of(" \t\r\n", at + 1);
    if (at == std::string_view::npos || json[at] != '[') return names;
    const std::size_t end = json.find(']', at);
    if (end == std::string_view::npos) return names;
    for (std::size_t open = json.find('"', at); open < end; open = json.find('"', open)) {
        const std::size_t close = json.find('"', open + 1);
        if (close == std::string_view::npos || close > end || close - open > 256) break;
        names.emplace_back(json.substr(open + 1, close - open - 1));
        open = close + 1;
    }
    return names;
}

// The JSON text of a .gltf, or of a .glb's first chunk (its length checked by glbContainerProblem).
std::string_view jsonOf(std::span<const unsigned char> bytes, bool binary) {
    if (!binary) return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
    return {reinterpret_cast<const char*>(bytes.data()) + 20, std::min<std::size_t>(readU32(bytes, 12), bytes.size() - 20)};
}

tinygltf::Model parseModel(std::span<const unsigned char> bytes, const fs::path& file, FileAccess access) {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keepImageBytes, &model);
    loader.SetFsCallbacks(tinygltf::FsCallbacks{fileExists, expandFilePath, readWholeFile, writeWholeFile, &access});
    std::string err, warn;
    const std::string folder = fs::absolute(file).parent_path().string();
    if (bytes.size() > 0xffffffffu) throw AssetError(file, "the file is larger than 4 GiB, more than glTF can address");
    const auto length = static_cast<unsigned>(bytes.size());
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    const std::string notReadable = binary ? "not a readable GLB file" : "not a readable glTF file";
    bool ok = false;
    if (binary)
        if (const std::string problem = glbContainerProblem(bytes); !problem.empty())
            throw AssetError(file, notReadable + ": " + problem);
    refuseUnreadRequired(requiredExtensions(jsonOf(bytes, binary)), file);
    // Before tinygltf: it recurses per level of nesting and reads indices as plain ints.
    std::set<std::string> imageUris;
    if (const gltfjson::Problem problem = gltfjson::problem(jsonOf(bytes, binary), kSupportedExtensions, &imageUris);
        !problem.empty())
        throw AssetError(file, problem.notJson ? notReadable + ": " + problem.text : problem.text);
    // As tinygltf joins them to the folder (with a '/', an absolute URI too).
    for (const std::string& uri : imageUris) access.imageFiles.insert(fs::path(folder + "/" + uri).lexically_normal().string());
    try {
        if (binary) {
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), length, folder);
        } else {
            ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()), length,
                                            folder);
        }
    } catch (const std::bad_alloc&) {
        throw;  // out of memory: the caller's own message
    } catch (const std::exception& e) {
        // tinygltf 2.7 lets a few library exceptions out (a vector's range check): named here.
        throw AssetError(file, notReadable + ": " + e.what());
    }
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        std::replace(err.begin(), err.end(), '\n', ';');
        throw AssetError(file, notReadable + (err.empty() ? std::string() : ": " + err));
    }
    return model;
}

std::string element(const char* kind, std::size_t index, const std::string& name) {
    return std::string(kind) + " " + std::to_string(index) + (name.empty() ? "" : " (\"" + name + "\")");
}

std::size_t componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

int componentsOf(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;
    }
}

// One component as a float: floats as they are, integers normalised when the accessor says so
// (glTF 2.0 §3.11: max(c / 127, −1) for BYTE, c / 255 for UNSIGNED_BYTE, ...), else their value.
float componentValue(const unsigned char* p, int componentType, bool normalized) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
        case TINYGLTF_COMPONENT_TYPE_BYTE: { std::int8_t v; std::memcpy(&v, p, 1); return normalized ? std::max(v / 127.0f, -1.0f) : v; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { std::uint8_t v = *p; return normalized ? v / 255.0f : v; }
        case TINYGLTF_COMPONENT_TYPE_SHORT: { std::int16_t v; std::memcpy(&v, p, 2); return normalized ? std::max(v / 32767.0f, -1.0f) : v; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0f : v; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, p, 4); return normalized ? static_cast<float>(v / 4294967295.0) : static_cast<float>(v); }
        default: return 0.0f;
    }
}

class Reader {
public:
    Reader(const tinygltf::Model& model, const fs::path& file) : model_(model), file_(file) {}

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw AssetError(file_, where + ": " + what);
    }
    void warn(const std::string& what) { asset_.warnings.push_back(file_.string() + ": " + what); }

    // The bytes of accessor `index` checked against its buffer view and buffer; returns the
    // first element's address and the stride. `count` elements of `components` each.
    struct View {
        const unsigned char* data = nullptr;
        std::size_t stride = 0;
        std::size_t count = 0;
        int componentType = 0;
        int components = 0;
        bool normalized = false;
    };
    View accessorView(int index, const std::string& where) const {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
            fail(where, "refers to accessor " + std::to_string(index) + ", but the file has " +
                            std::to_string(model_.accessors.size()));
        const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
        const std::string at = element("accessor", static_cast<std::size_t>(index), a.name);
        View v;
        v.componentType = a.componentType;
        v.components = componentsOf(a.type);
        v.normalized = a.normalized;
        v.count = a.count;
        const std::size_t size = componentBytes(a.componentType);
        if (size == 0 || v.components == 0)
            fail(at, "has a component type or element type this reader does not read (" +
                         std::to_string(a.componentType) + ", " + std::to_string(a.type) + ")");
        if (a.sparse.isSparse) fail(at, "is sparse, which this reader does not read");
        if (a.count == 0) fail(at, "has no elements (count 0)");
        if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
            fail(at, "refers to buffer view " + std::to_string(a.bufferView) + ", but the file has " +
                         std::to_string(model_.bufferViews.size()));
        const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
        const std::string viewAt = element("buffer view", static_cast<std::size_t>(a.bufferView), bv.name);
        if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model_.buffers.size())
            fail(viewAt, "refers to buffer " + std::to_string(bv.buffer) + ", but the file has " +
                             std::to_string(model_.buffers.size()));
        const std::vector<unsigned char>& buffer = model_.buffers[static_cast<std::size_t>(bv.buffer)].data;
        if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
            fail(viewAt, "reaches past the end of its buffer (" + std::to_string(bv.byteOffset) + " + " +
                             std::to_string(bv.byteLength) + " bytes of " + std::to_string(buffer.size()) + ")");
        const std::size_t elementBytes = size * static_cast<std::size_t>(v.components);
        v.stride = bv.byteStride != 0 ? bv.byteStride : elementBytes;
        if (v.stride < elementBytes || v.stride > 252)
            fail(viewAt, "has a byte stride of " + std::to_string(v.stride) + " for elements of " +
                             std::to_string(elementBytes) + " bytes");
        // The last element ends at byteOffset + stride·(count − 1) + elementBytes: checked without overflow.
        const std::size_t room = bv.byteLength;
        if (a.byteOffset > room || (a.count - 1) > (room - a.byteOffset) / v.stride ||
            v.stride * (a.count - 1) + elementBytes > room - a.byteOffset)
            fail(at, "reaches past the end of its buffer view (" + std::to_string(a.count) + " elements of " +
                         std::to_string(elementBytes) + " bytes, stride " + std::to_string(v.stride) + ", from byte " +
                         std::to_string(a.byteOffset) + " of " + std::to_string(room) + ")");
        v.data = buffer.data() + bv.byteOffset + a.byteOffset;
        return v;
    }

    template <int N>
    std::vector<std::array<float, N>> readFloats(int index, const std::string& where, int minComponents = N) const {
        const View v = accessorView(index, where);
        if (v.components < minComponents || v.components > 4)
            fail(element("accessor", static_cast<std::size_t>(index), model_.accessors[static_cast<std::size_t>(index)].name),
                 "has " + std::to_string(v.components) + " components where " + where + " needs " +
                     std::to_string(N));
        std::vector<std::array<float, N>> out(v.count);
        const std::size_t size = componentBytes(v.componentType);
        for (std::size_t i = 0; i < v.count; ++i) {
            const unsigned char* p = v.data + i * v.stride;
            for (int c = 0; c < N; ++c)
                out[i][static_cast<std::size_t>(c)] =
                    c < v.components ? componentValue(p + static_cast<std::size_t>(c) * size, v.componentType, v.normalized)
                                     : 1.0f;
            for (int c = 0; c < N; ++c)
                if (!std::isfinite(out[i][static_cast<std::size_t>(c)]))
                    fail(element("accessor", static_cast<std::size_t>(index), model_.accessors[static_cast<std::size_t>(index)].name),
                         "element " + std::to_string(i) + " is not finite (NaN or infinite)");
        }
        return out;
    }

    std::vector<std::uint32_t> readIndices(int index, const std::string& where, std::size_t vertexCount) const {
        const View v = accessorView(index, where);
        const std::string at = element("accessor", static_cast<std::size_t>(index), model_.accessors[static_cast<std::size_t>(index)].name);
        if (v.components != 1 || (v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                  v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                  v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            fail(at, "holds indices that are not unsigned integer scalars");
        std::vector<std::uint32_t> out(v.count);
        for (std::size_t i = 0; i < v.count; ++i) {
            const unsigned char* p = v.data + i * v.stride;
            std::uint32_t value = 0;
            if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) value = *p;
            else if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) { std::uint16_t s; std::memcpy(&s, p, 2); value = s; }
            else std::memcpy(&value, p, 4);
            if (value >= vertexCount)
                fail(at, "index " + std::to_string(i) + " is " + std::to_string(value) + ", but " + where + " has only " +
                             std::to_string(vertexCount) + " vertices");
            out[i] = value;
        }
        return out;
    }

    // A textureInfo's image, and how it is read into `sampling`: its UV set, its texture's sampler
    // (wrap modes, nearest or linear filters) and KHR_texture_transform (which may name another
    // UV set). A UV set other than 0 and 1 is a warning; set 0 is read for it.
    template <typename Info>
    TextureRef texture(const Info& info, const std::string& where, TextureSampling& sampling) {
        sampling = {};
        if (info.index < 0) return {};
        int texCoord = info.texCoord;
        if (auto it = info.extensions.find("KHR_texture_transform"); it != info.extensions.end()) {
            const tinygltf::Value& t = it->second;
            auto numbers = [&](const char* key, glm::vec2 fallback) {
                if (!t.Has(key)) return fallback;
                const tinygltf::Value& v = t.Get(key);
                if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber()) {
                    warn(where + ": KHR_texture_transform's " + key + " is not two numbers; ignored");
                    return fallback;
                }
                const glm::dvec2 d(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble());
                if (!std::isfinite(d.x) || !std::isfinite(d.y) || std::abs(d.x) > 1e6 || std::abs(d.y) > 1e6) {
                    warn(where + ": KHR_texture_transform's " + key + " is not finite or beyond 1e6; ignored");
                    return fallback;
                }
                return glm::vec2(d);
            };
            sampling.offset = numbers("offset", sampling.offset);
            sampling.scale = numbers("scale", sampling.scale);
            if (t.Has("rotation") && t.Get("rotation").IsNumber()) {
                const double r = t.Get("rotation").GetNumberAsDouble();
                if (std::isfinite(r)) sampling.rotation = static_cast<float>(std::remainder(r, 2.0 * std::numbers::pi));
            }
            if (t.Has("texCoord") && t.Get("texCoord").IsInt()) texCoord = t.Get("texCoord").GetNumberAsInt();
        }
        if (texCoord == 0 || texCoord == 1) sampling.texCoord = texCoord;
        else warn(where + " reads UV set " + std::to_string(texCoord) + "; only sets 0 and 1 are read, and set 0 is used for it");
        return texture(info.index, where, sampling);
    }

    TextureRef texture(int index, const std::string& where, TextureSampling& sampling) {
        if (index < 0) return {};
        if (static_cast<std::size_t>(index) >= model_.textures.size())
            fail(where, "refers to texture " + std::to_string(index) + ", but the file has " +
                            std::to_string(model_.textures.size()));
        const tinygltf::Texture& t = model_.textures[static_cast<std::size_t>(index)];
        if (t.source < 0) {
            warn(element("texture", static_cast<std::size_t>(index), t.name) + " has no image (or only an extension's); drawn without it");
            return {};
        }
        if (static_cast<std::size_t>(t.source) >= model_.images.size())
            fail(element("texture", static_cast<std::size_t>(index), t.name),
                 "refers to image " + std::to_string(t.source) + ", but the file has " + std::to_string(model_.images.size()));
        if (t.sampler >= 0) {
            if (static_cast<std::size_t>(t.sampler) >= model_.samplers.size())
                fail(element("texture", static_cast<std::size_t>(index), t.name),
                     "refers to sampler " + std::to_string(t.sampler) + ", but the file has " + std::to_string(model_.samplers.size()));
            const tinygltf::Sampler& s = model_.samplers[static_cast<std::size_t>(t.sampler)];
            auto wrap = [](int mode) {
                return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? TextureWrap::ClampToEdge
                       : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TextureWrap::MirroredRepeat
                                                                       : TextureWrap::Repeat;
            };
            sampling.wrapS = wrap(s.wrapS);
            sampling.wrapT = wrap(s.wrapT);
            sampling.nearestMagnify = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
            sampling.nearestMinify = s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
                                     s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                                     s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
        }
        const tinygltf::Image& image = model_.images[static_cast<std::size_t>(t.source)];
        TextureRef ref;
        if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
            // Only the asset's folder and below are read (gltf_json_check.h; docs/assets.md).
            const std::string path = gltfjson::decodeUri(image.uri);
            if (gltfjson::leavesFolder(path)) {
                warn(element("image", static_cast<std::size_t>(t.source), image.name) + "'s URI \"" + image.uri.substr(0, 120) +
                     "\" lies outside the asset's folder (mipgloss reads only files in it or below it); " + where +
                     " drawn without it");
                return {};
            }
            ref.file = (file_.parent_path() / path).lexically_normal().string();
        } else {
            ref.file = file_.string();
            ref.image = t.source;
            // Images that are the same bytes (one buffer view) are one image to decode: four images
            // sharing a 16384² PNG were decoded four times (4.9 GB from a 35 KB GLB).
            if (image.bufferView >= 0) {
                const auto [first, added] = firstImageOfView_.try_emplace(image.bufferView, t.source);
                if (!added && model_.images[static_cast<std::size_t>(first->second)].mimeType == image.mimeType)
                    ref.image = first->second;
            }
            // Kept for the decoder (Asset::images); one with no bytes is refused when decoded.
            const tinygltf::Image& kept = model_.images[static_cast<std::size_t>(ref.image)];
            if (!kept.image.empty() && !asset_.images.count(ref.key()))
                asset_.images.emplace(ref.key(), std::make_shared<const EncodedImage>(EncodedImage{kept.image, kept.mimeType}));
        }
        return ref;
    }

    static float unit(double v) { return std::isfinite(v) ? static_cast<float>(std::clamp(v, 0.0, 1.0)) : 0.0f; }

    // asset.version "2.x" (a later minor version stays readable: glTF 2.0 §3.3), and no
    // asset.minVersion above the 2.0 this reader implements.
    void checkVersion() const {
        auto parse = [](const std::string& text, int& major, int& minor) {
            char dot = 0;
            int used = 0;
            if (text.size() > 32 || std::sscanf(text.c_str(), "%d%c%d%n", &major, &dot, &minor, &used) != 3) return false;
            return dot == '.' && static_cast<std::size_t>(used) == text.size() && major >= 0 && minor >= 0;
        };
        int major = 0, minor = 0;
        if (!parse(model_.asset.version, major, minor))
            throw AssetError(file_, "its asset.version \"" + model_.asset.version.substr(0, 32) +
                                        "\" is not a version (glTF 2.0 files say \"2.0\")");
        if (major != 2)
            throw AssetError(file_, "is glTF " + model_.asset.version + "; mipgloss reads glTF 2");
        if (!model_.asset.minVersion.empty()) {
            if (!parse(model_.asset.minVersion, major, minor))
                throw AssetError(file_, "its asset.minVersion \"" + model_.asset.minVersion.substr(0, 32) + "\" is not a version");
            if (major != 2 || minor > 0)
                throw AssetError(file_, "needs a glTF " + model_.asset.minVersion +
                                            " reader (asset.minVersion); mipgloss reads glTF 2.0");
        }
    }

    void readMaterials() {
        UniqueNames names;
        for (std::size_t m = 0; m < model_.materials.size(); ++m) {
            const tinygltf::Material& g = model_.materials[m];
            const std::string at = element("material", m, g.name);
            AssetMaterial out;
            out.name = names.take(g.name.empty() ? "Material " + std::to_string(m) : g.name);
            Material& mat = out.material;
            mat.layered = true;
            Layers& l = mat.layers;
            const auto& pbr = g.pbrMetallicRoughness;
            if (pbr.baseColorFactor.size() == 4) {
                l.baseColor = Rgb(unit(pbr.baseColorFactor[0]), unit(pbr.baseColorFactor[1]), unit(pbr.baseColorFactor[2]));
                l.maps.baseAlpha = unit(pbr.baseColorFactor[3]);
            }
            l.metallic = unit(pbr.metallicFactor);
            l.roughness = unit(pbr.roughnessFactor);
            l.specular = 0.04f;  // glTF's dielectric F0
            l.maps.baseColor = texture(pbr.baseColorTexture, at + " base colour", l.maps.samplingOf(MapSlot::BaseColor));
            const TextureRef mr =
                texture(pbr.metallicRoughnessTexture, at + " metallic-roughness", l.maps.samplingOf(MapSlot::Roughness));
            l.maps.samplingOf(MapSlot::Metallic) = l.maps.samplingOf(MapSlot::Roughness);
            if (!mr.empty()) {
                l.maps.roughness = mr;
                l.maps.roughness.channel = 1;  // G
                l.maps.metallic = mr;
                l.maps.metallic.channel = 2;  // B
            }
            l.maps.normal = texture(g.normalTexture, at + " normal", l.maps.samplingOf(MapSlot::Normal));
            l.maps.normalScale = std::isfinite(g.normalTexture.scale)
                                     ? static_cast<float>(std::clamp(g.normalTexture.scale, -double(kMaxNormalScale), double(kMaxNormalScale)))
                                     : 1.0f;
            l.maps.occlusion = texture(g.occlusionTexture, at + " occlusion", l.maps.samplingOf(MapSlot::Occlusion));
            l.maps.occlusionStrength = unit(g.occlusionTexture.strength);
            l.maps.emissive = texture(g.emissiveTexture, at + " emissive", l.maps.samplingOf(MapSlot::Emissive));
            double strength = 1.0;
            if (auto it = g.extensions.find("KHR_materials_emissive_strength"); it != g.extensions.end() &&
                                                                                 it->second.Has("emissiveStrength")) {
                const tinygltf::Value& s = it->second.Get("emissiveStrength");
                if (s.IsNumber() && std::isfinite(s.GetNumberAsDouble())) strength = std::max(0.0, s.GetNumberAsDouble());
            }
            if (g.emissiveFactor.size() == 3) {
                auto e = [&](double v) {
                    return std::isfinite(v * strength) ? static_cast<float>(std::clamp(v * strength, 0.0, double(kMaxEmissive))) : 0.0f;
                };
                l.maps.emissiveFactor = Rgb(e(g.emissiveFactor[0]), e(g.emissiveFactor[1]), e(g.emissiveFactor[2]));
            }
            if (auto it = g.extensions.find("KHR_materials_clearcoat"); it != g.extensions.end()) {
                auto number = [&](const char* key, double fallback) {
                    if (!it->second.Has(key)) return fallback;
                    const tinygltf::Value& v = it->second.Get(key);
                    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
                };
                l.coat = unit(number("clearcoatFactor", 0.0));
                l.coatRoughness = unit(number("clearcoatRoughnessFactor", 0.0));
                // The coat's textures multiply the factors per texel; the layered model holds one
                // coat per material, so they are named rather than dropped in silence.
                for (const char* map : {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"})
                    if (it->second.Has(map))
                        warn(at + ": KHR_materials_clearcoat's " + map + " is not read (the coat is its factor alone)");
            }
            // KHR_materials_ior: the dielectric's F0 = ((ior − 1)/(ior + 1))² (1.5 gives glTF's 0.04);
            // it carries into the picture and the truth through Layers::specular (gltf_brdf.h).
            if (auto it = g.extensions.find("KHR_materials_ior"); it != g.extensions.end() && it->second.Has("ior")) {
                const tinygltf::Value& v = it->second.Get("ior");
                const double ior = v.IsNumber() ? v.GetNumberAsDouble() : 1.5;
                if (std::isfinite(ior) && ior >= 1.0 && ior <= 10.0) {
                    const double r = (ior - 1.0) / (ior + 1.0);
                    l.specular = static_cast<float>(r * r);
                } else {
                    warn(at + ": KHR_materials_ior's ior " + std::to_string(ior) +
                         " is not in [1, 10]; glTF's 1.5 is used");
                }
            }
            // KHR_materials_specular: the dielectric's F0 = min(F0_ior · specularColorFactor, 1) ·
            // specularFactor and F90 = specularFactor (Layers::specularColor, specularWeight;
            // layered.h). Its two textures would multiply the factors per texel; the model holds
            // one value per material, so they are named rather than dropped in silence.
            if (auto it = g.extensions.find("KHR_materials_specular"); it != g.extensions.end()) {
                const tinygltf::Value& e = it->second;
                if (e.Has("specularFactor")) {
                    const tinygltf::Value& v = e.Get("specularFactor");
                    const double f = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
                    if (std::isfinite(f) && f >= 0.0 && f <= 1.0)
                        l.specularWeight = static_cast<float>(f);
                    else
                        warn(at + ": KHR_materials_specular's specularFactor is not a number in [0, 1]; 1 is used");
                }
                if (e.Has("specularColorFactor")) {
                    const tinygltf::Value& v = e.Get("specularColorFactor");
                    bool valid = v.IsArray() && v.ArrayLen() == 3;
                    Rgb colour(1.0f);
                    for (int c = 0; valid && c < 3; ++c) {
                        const tinygltf::Value& x = v.Get(c);
                        const double value = x.IsNumber() ? x.GetNumberAsDouble() : -1.0;
                        valid = std::isfinite(value) && value >= 0.0 && value <= double(kMaxSpecularColour);
                        colour[c] = static_cast<float>(value);
                    }
                    if (valid)
                        l.specularColor = colour;
                    else
                        warn(at + ": KHR_materials_specular's specularColorFactor is not three numbers in [0, " +
                             std::to_string(int(kMaxSpecularColour)) + "]; [1, 1, 1] is used");
                }
                for (const char* map : {"specularTexture", "specularColorTexture"})
                    if (e.Has(map))
                        warn(at + ": KHR_materials_specular's " + map + " is not read (the specular is its factors alone)");
            }
            if (g.alphaMode == "MASK") l.maps.alphaMode = AlphaMode::Mask;
            else if (g.alphaMode == "BLEND") l.maps.alphaMode = AlphaMode::Blend;
            l.maps.alphaCutoff = unit(g.alphaCutoff);
            l.maps.doubleSided = g.doubleSided;
            asset_.materials.push_back(std::move(out));
        }
    }

    glm::dmat4 localMatrix(const tinygltf::Node& node, const std::string& at) const {
        if (node.matrix.size() == 16) {
            glm::dmat4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<std::size_t>(c * 4 + r)];
            return m;
        }
        glm::dmat4 m(1.0);
        if (node.translation.size() == 3)
            m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4) {
            glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);  // w, x, y, z
            const double length = glm::length(q);
            if (!(length > 0.0) || !std::isfinite(length)) fail(at, "has a rotation that is not a unit quaternion");
            m = m * glm::mat4_cast(q / length);
        }
        if (node.scale.size() == 3) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
        return m;
    }

    // Node `index` and its children, `from` the scene or the parent naming it. glTF's nodes form
    // trees (a node has at most one parent): a node reached again, from a second parent or named
    // twice, is drawn where it was first reached only, so a file whose nodes each name the next
    // twice cannot multiply its meshes 2^depth times.
    void visit(int index, const glm::dmat4& parent, int depth, const std::string& from) {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
            fail(from, "refers to node " + std::to_string(index) + ", but the file has " + std::to_string(model_.nodes.size()));
        const auto i = static_cast<std::size_t>(index);
        const tinygltf::Node& node = model_.nodes[i];
        const std::string at = element("node", i, node.name);
        if (onPath_[i]) fail(at, "is its own ancestor (a cycle in the node hierarchy)");
        if (depth > kMaxNodeDepth) fail(at, "lies more than " + std::to_string(kMaxNodeDepth) + " nodes deep");
        if (reached_[i] != 0) {
            if (reached_[i] == 1) warn(at + " has more than one parent (glTF's nodes form trees); drawn only where first reached");
            reached_[i] = 2;
            return;
        }
        reached_[i] = 1;
        onPath_[i] = true;
        const glm::dmat4 world = parent * localMatrix(node, at);
        if (node.mesh >= 0) addMesh(node, node.mesh, world, at);
        if (node.camera >= 0) addCamera(node.camera, node.name, world, at);
        for (int child : node.children) visit(child, world, depth + 1, at);
        onPath_[i] = false;
    }

    // A camera as its node places it: −Z forward, +Y up, the node's scale dropped (glTF: cameras
    // are not scaled; their node's axes are normalized here).
    void addCamera(int index, const std::string& nodeName, const glm::dmat4& world, const std::string& nodeAt) {
        if (static_cast<std::size_t>(index) >= model_.cameras.size())
            fail(nodeAt, "refers to camera " + std::to_string(index) + ", but the file has " + std::to_string(model_.cameras.size()));
        const tinygltf::Camera& gc = model_.cameras[static_cast<std::size_t>(index)];
        const std::string at = element("camera", static_cast<std::size_t>(index), gc.name);
        if (gc.type != "perspective") {
            warn(at + " (placed by " + nodeAt + ") is " + (gc.type.empty() ? std::string("of no type") : gc.type) +
                 "; only perspective cameras are read");
            return;
        }
        const double yfov = gc.perspective.yfov;
        if (!(yfov > 0.0 && yfov < std::numbers::pi)) {
            warn(at + " has a yfov of " + std::to_string(yfov) + " radians, not in (0, π); left out");
            return;
        }
        const glm::dvec3 position(world[3]);
        glm::dvec3 forward = -glm::dvec3(world[2]);
        glm::dvec3 up = glm::dvec3(world[1]);
        up -= forward * (glm::dot(forward, up) / std::max(glm::dot(forward, forward), 1e-300));
        const double fl = glm::length(forward), ul = glm::length(up);
        if (!(fl > 1e-12 && ul > 1e-12) || !std::isfinite(fl) || !std::isfinite(ul) || !std::isfinite(position.x) ||
            !std::isfinite(position.y) || !std::isfinite(position.z)) {
            warn(at + " is placed by " + nodeAt + " with a matrix that is singular or not finite; left out");
            return;
        }
        AssetCamera camera;
        camera.name = !gc.name.empty() ? gc.name : !nodeName.empty() ? nodeName : "camera " + std::to_string(index);
        camera.position = glm::vec3(position);
        camera.forward = glm::vec3(forward / fl);
        camera.up = glm::vec3(up / ul);
        camera.fovYDegrees = static_cast<float>(yfov * 180.0 / std::numbers::pi);
        asset_.cameras.push_back(std::move(camera));
    }

    void addMesh(const tinygltf::Node& node, int meshIndex, const glm::dmat4& world, const std::string& nodeAt) {
        if (static_cast<std::size_t>(meshIndex) >= model_.meshes.size())
            fail(nodeAt, "refers to mesh " + std::to_string(meshIndex) + ", but the file has " + std::to_string(model_.meshes.size()));
        const tinygltf::Mesh& gm = model_.meshes[static_cast<std::size_t>(meshIndex)];
        for (double v : {world[0][0], world[0][1], world[0][2], world[1][0], world[1][1], world[1][2], world[2][0],
                         world[2][1], world[2][2], world[3][0], world[3][1], world[3][2]})
            if (!std::isfinite(v)) fail(nodeAt, "places its mesh with a matrix that is not finite");
        const glm::dmat3 linear(world);
        const double det = glm::determinant(linear);
        if (!(std::abs(det) > 1e-30)) {
            warn(nodeAt + " scales its mesh to nothing (a singular matrix); left out");
            return;
        }
        const glm::dmat3 normalMatrix = glm::inverseTranspose(linear);
        const std::string baseName = !node.name.empty() ? node.name : !gm.name.empty() ? gm.name : "mesh " + std::to_string(meshIndex);
        for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = gm.primitives[p];
            const std::string at = element("mesh", static_cast<std::size_t>(meshIndex), gm.name) + " primitive " + std::to_string(p);
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                prim.mode != TINYGLTF_MODE_TRIANGLE_FAN && prim.mode != -1) {
                warn(at + " draws points or lines (mode " + std::to_string(prim.mode) + "); left out");
                continue;
            }
            auto attribute = [&](const char* name) {
                auto it = prim.attributes.find(name);
                return it == prim.attributes.end() ? -1 : it->second;
            };
            const int positionAccessor = attribute("POSITION");
            if (positionAccessor < 0) fail(at, "has no POSITION attribute");
            // What the primitive will add, from its accessors' counts, before any is read.
            const std::size_t vertexCount = countOf(positionAccessor);
            totalVertices_ += vertexCount;
            totalTriangles_ += (prim.indices >= 0 ? countOf(prim.indices) : vertexCount) / 3 + 1;
            if (totalVertices_ > kMaxAssetVertices || totalTriangles_ > kMaxAssetTriangles)
                fail(at + " (placed by " + nodeAt + ")",
                     "the asset would hold more than " + std::to_string(kMaxAssetTriangles) + " triangles or " +
                         std::to_string(kMaxAssetVertices) + " vertices (a mesh placed by very many nodes?)");
            const auto [ownVertices, ownTriangles] = ownGeometry();
            if (totalVertices_ > ownVertices + kMaxPlacedBeyondTheFile || totalTriangles_ > ownTriangles + kMaxPlacedBeyondTheFile)
                fail(at + " (placed by " + nodeAt + ")",
                     "its nodes place the file's " + std::to_string(ownVertices) + " vertices and " +
                         std::to_string(ownTriangles) + " triangles so often that the asset would hold more than " +
                         std::to_string(kMaxPlacedBeyondTheFile) + " beyond them (" + std::to_string(totalVertices_) +
                         " vertices and " + std::to_string(totalTriangles_) + " triangles so far); mipgloss copies each placement");
            const auto positions = readFloats<3>(positionAccessor, at + " POSITION");
            const std::size_t n = positions.size();
            auto sameCount = [&](std::size_t count, const char* what) {
                if (count != n)
                    fail(at, std::string(what) + " has " + std::to_string(count) + " elements for " + std::to_string(n) +
                                 " positions");
            };
            Mesh mesh;
            mesh.name = gm.primitives.size() > 1 ? baseName + " " + std::to_string(p + 1) : baseName;
            mesh.positions.resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                const glm::dvec4 w = world * glm::dvec4(positions[i][0], positions[i][1], positions[i][2], 1.0);
                mesh.positions[i] = glm::vec3(w);
                if (!std::isfinite(mesh.positions[i].x) || !std::isfinite(mesh.positions[i].y) ||
                    !std::isfinite(mesh.positions[i].z))
                    fail(nodeAt, "places vertex " + std::to_string(i) + " of " + at +
                                     " beyond the range of float coordinates");
            }
            const int normalAccessor = attribute("NORMAL");
            if (normalAccessor >= 0) {
                const auto normals = readFloats<3>(normalAccessor, at + " NORMAL");
                sameCount(normals.size(), "NORMAL");
                mesh.normals.resize(n);
                for (std::size_t i = 0; i < n; ++i) {
                    const glm::dvec3 v = normalMatrix * glm::dvec3(normals[i][0], normals[i][1], normals[i][2]);
                    const double length = glm::length(v);
                    mesh.normals[i] = length > 0.0 && std::isfinite(length) ? glm::vec3(v / length) : glm::vec3(0, 0, 0);
                }
            }
            const int uvAccessor = attribute("TEXCOORD_0");
            if (uvAccessor >= 0) {
                const auto uvs = readFloats<2>(uvAccessor, at + " TEXCOORD_0");
                sameCount(uvs.size(), "TEXCOORD_0");
                mesh.uvs.resize(n);
                for (std::size_t i = 0; i < n; ++i) mesh.uvs[i] = glm::vec2(uvs[i][0], uvs[i][1]);
            }
            if (const int uv1Accessor = attribute("TEXCOORD_1"); uv1Accessor >= 0) {
                const auto uvs = readFloats<2>(uv1Accessor, at + " TEXCOORD_1");
                sameCount(uvs.size(), "TEXCOORD_1");
                mesh.uvs1.resize(n);
                for (std::size_t i = 0; i < n; ++i) mesh.uvs1[i] = glm::vec2(uvs[i][0], uvs[i][1]);
            }
            // COLOR_0: RGB or RGBA (alpha 1 where absent), linear, multiplying the base colour.
            if (const int colourAccessor = attribute("COLOR_0"); colourAccessor >= 0) {
                const auto colours = readFloats<4>(colourAccessor, at + " COLOR_0", 3);
                sameCount(colours.size(), "COLOR_0");
                mesh.colours.resize(n);
                for (std::size_t i = 0; i < n; ++i)
                    mesh.colours[i] = glm::clamp(glm::vec4(colours[i][0], colours[i][1], colours[i][2], colours[i][3]), 0.0f, 1.0f);
            }
            const int tangentAccessor = attribute("TANGENT");
            if (tangentAccessor >= 0 && normalAccessor >= 0) {
                const auto tangents = readFloats<4>(tangentAccessor, at + " TANGENT");
                sameCount(tangents.size(), "TANGENT");
                mesh.tangents.resize(n);
                for (std::size_t i = 0; i < n; ++i) {
                    const glm::dvec3 t = linear * glm::dvec3(tangents[i][0], tangents[i][1], tangents[i][2]);
                    const double length = glm::length(t);
                    const float w = (tangents[i][3] < 0.0f ? -1.0f : 1.0f) * (det < 0.0 ? -1.0f : 1.0f);
                    mesh.tangents[i] = glm::vec4(length > 0.0 ? glm::vec3(t / length) : glm::vec3(1, 0, 0), w);
                }
            }
            // Triangles: from the indices, or the vertices in order.
            std::vector<std::uint32_t> corners;
            if (prim.indices >= 0) {
                corners = readIndices(prim.indices, at, n);
            } else {
                if (n > 0xffffffffu) fail(at, "has more vertices than 32-bit indices reach");
                corners.resize(n);
                for (std::size_t i = 0; i < n; ++i) corners[i] = static_cast<std::uint32_t>(i);
            }
            mesh.indices = triangles(corners, prim.mode);
            if (det < 0.0)  // a mirroring matrix turns the winding: turn it back so front faces stay front
                for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
            dropDegenerate(mesh, at);
            if (mesh.indices.empty()) {
                warn(at + " has no triangles with area; left out");
                continue;
            }
            // No NORMAL, or a zero one: the computed one there. (The vertices are the ones left
            // after dropDegenerate, fewer than the accessors' n when it dropped any.)
            fillMissingNormals(mesh);
            if (prim.material >= 0 && static_cast<std::size_t>(prim.material) >= model_.materials.size())
                fail(at, "refers to material " + std::to_string(prim.material) + ", but the file has " +
                             std::to_string(model_.materials.size()));
            const MaterialMaps* maps =
                prim.material >= 0 ? &asset_.materials[static_cast<std::size_t>(prim.material)].material.layers.maps : nullptr;
            if (maps && !maps->normal.empty() && mesh.tangents.empty()) {
                // MikkTSpace on the UV set the normal map reads (glTF 2.0, "Meshes": tangents from
                // the texture coordinates associated with the normal texture).
                const TextureSampling& sampling = maps->samplingOf(MapSlot::Normal);
                if (!(sampling.texCoord == 1 ? mesh.uvs1 : mesh.uvs).empty())
                    computeTangents(mesh, sampling.texCoord, sampling.uvTransform());
            }
            computeBounds(mesh);
            AssetPart part;
            part.name = mesh.name;
            part.material = prim.material;
            part.mesh = std::make_shared<const Mesh>(std::move(mesh));
            asset_.parts.push_back(std::move(part));
        }
    }

    std::vector<std::uint32_t> triangles(const std::vector<std::uint32_t>& c, int mode) const {
        std::vector<std::uint32_t> out;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (std::size_t i = 0; i + 2 < c.size(); ++i) {
                if (i % 2 == 0) out.insert(out.end(), {c[i], c[i + 1], c[i + 2]});
                else out.insert(out.end(), {c[i + 1], c[i], c[i + 2]});
            }
        } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            for (std::size_t i = 1; i + 1 < c.size(); ++i) out.insert(out.end(), {c[0], c[i], c[i + 1]});
        } else {
            out.assign(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(c.size() - c.size() % 3));
        }
        return out;
    }

    // Zero-area triangles go (mesh.h, isZeroAreaTriangle), and the
    // vertices no triangle uses then, so the bounds hold only what is drawn.
    void dropDegenerate(Mesh& mesh, const std::string& at) {
        std::vector<std::uint32_t> kept;
        kept.reserve(mesh.indices.size());
        std::size_t dropped = 0;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            if (isZeroAreaTriangle(mesh.positions[mesh.indices[t]], mesh.positions[mesh.indices[t + 1]],
                                   mesh.positions[mesh.indices[t + 2]])) {
                ++dropped;
                continue;
            }
            kept.insert(kept.end(), {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]});
        }
        if (dropped > 0) warn(at + ": " + std::to_string(dropped) + " degenerate (zero-area) triangles dropped");
        mesh.indices = std::move(kept);
        std::vector<std::uint32_t> remap(mesh.positions.size(), 0xffffffffu);
        std::uint32_t next = 0;
        for (const std::uint32_t i : mesh.indices)
            if (remap[i] == 0xffffffffu) remap[i] = next++;
        // Every vertex used: the file's numbering stays (renumbering the indices without moving
        // the vertices with them would scramble the triangles).
        if (next == mesh.positions.size()) return;
        for (std::uint32_t& i : mesh.indices) i = remap[i];
        auto compact = [&](auto& values) {
            if (values.empty()) return;
            std::remove_reference_t<decltype(values)> out(next);
            for (std::size_t v = 0; v < remap.size(); ++v)
                if (remap[v] != 0xffffffffu) out[remap[v]] = values[v];
            values = std::move(out);
        };
        compact(mesh.positions);
        compact(mesh.normals);
        compact(mesh.uvs);
        compact(mesh.tangents);
        compact(mesh.uvs1);
        compact(mesh.colours);
    }

    Asset read() {
        refuseUnreadRequired(model_.extensionsRequired, file_);  // as parsed (the scan before the parse may miss one)
        for (const std::string& e : model_.extensionsUsed)
            if (!kSupportedExtensions.count(e)) warn("uses the extension " + e + ", which is not read (drawn without it)");
        // What a still preview does not draw, named once per file rather than dropped in silence.
        if (!model_.animations.empty())
            warn("has " + std::to_string(model_.animations.size()) + " animation(s); drawn at rest (animations are not played)");
        if (!model_.skins.empty())
            warn("has " + std::to_string(model_.skins.size()) + " skin(s); drawn in the bind pose (skinning is not read)");
        std::size_t morphed = 0;
        for (const tinygltf::Mesh& mesh : model_.meshes)
            for (const tinygltf::Primitive& p : mesh.primitives) morphed += p.targets.empty() ? 0 : 1;
        if (morphed > 0)
            warn(std::to_string(morphed) + " primitive(s) have morph targets; drawn with their base shape (targets are not read)");
        checkVersion();
        if (model_.defaultScene >= 0 && static_cast<std::size_t>(model_.defaultScene) >= model_.scenes.size())
            throw AssetError(file_, "its \"scene\" is " + std::to_string(model_.defaultScene) + ", but the file has " +
                                        std::to_string(model_.scenes.size()) + " scene(s)");
        if (model_.scenes.size() > 1)
            warn("has " + std::to_string(model_.scenes.size()) + " scenes; only the default one (scene " +
                 std::to_string(std::max(model_.defaultScene, 0)) + ") is drawn");
        readMaterials();
        onPath_.assign(model_.nodes.size(), false);
        reached_.assign(model_.nodes.size(), 0);
        std::vector<int> roots;
        if (!model_.scenes.empty()) {
            const int s = model_.defaultScene >= 0 && static_cast<std::size_t>(model_.defaultScene) < model_.scenes.size()
                              ? model_.defaultScene : 0;
            roots = model_.scenes[static_cast<std::size_t>(s)].nodes;
        } else {
            // No scene: every node no other node names as a child.
            std::vector<bool> child(model_.nodes.size(), false);
            for (const tinygltf::Node& node : model_.nodes)
                for (int c : node.children)
                    if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[static_cast<std::size_t>(c)] = true;
            for (std::size_t i = 0; i < model_.nodes.size(); ++i)
                if (!child[i]) roots.push_back(static_cast<int>(i));
        }
        for (int root : roots) visit(root, glm::dmat4(1.0), 0, "the scene");
        if (asset_.parts.empty()) throw AssetError(file_, "no triangles to draw (no mesh in the scene has any)");
        // Part names unique, as scene objects' are shown.
        UniqueNames partNames;
        for (AssetPart& part : asset_.parts) part.name = partNames.take(part.name);
        return std::move(asset_);
    }

private:
    const tinygltf::Model& model_;
    fs::path file_;
    Asset asset_;
    std::size_t totalVertices_ = 0, totalTriangles_ = 0;
    std::optional<std::pair<std::size_t, std::size_t>> ownGeometry_;

    // An accessor's element count as the file gives it (0 for none or one out of range), read
    // before any of its data.
    std::size_t countOf(int accessor) const {
        return accessor >= 0 && static_cast<std::size_t>(accessor) < model_.accessors.size()
                   ? model_.accessors[static_cast<std::size_t>(accessor)].count
                   : 0;
    }

    // The file's own vertices and triangles: every mesh's primitives once, an accessor shared by
    // primitives once (what the file's bytes hold, however often nodes place it).
    std::pair<std::size_t, std::size_t> ownGeometry() {
        if (!ownGeometry_) {
            std::set<int> positions, indices;
            std::size_t vertices = 0, triangles = 0;
            for (const tinygltf::Mesh& m : model_.meshes)
                for (const tinygltf::Primitive& prim : m.primitives) {
                    const auto it = prim.attributes.find("POSITION");
                    const int position = it == prim.attributes.end() ? -1 : it->second;
                    if (positions.insert(position).second) vertices += countOf(position);
                    if (prim.indices >= 0 ? indices.insert(prim.indices).second : true)
                        triangles += (prim.indices >= 0 ? countOf(prim.indices) : countOf(position)) / 3 + 1;
                }
            ownGeometry_ = {vertices, triangles};
        }
        return *ownGeometry_;
    }
    std::map<int, int> firstImageOfView_;  // a buffer view's first image (texture())
    std::vector<bool> onPath_;          // the nodes from the root to the one visited
    std::vector<unsigned char> reached_;  // 0 not yet, 1 reached, 2 reached again (warned)
};

}  // namespace

Asset loadGltfFromMemory(std::span<const unsigned char> bytes, const fs::path& file) {
    if (bytes.empty()) throw AssetError(file, "file is empty (0 bytes)");
    const tinygltf::Model model = parseModel(bytes, file, FileAccess(false, false));
    return Reader(model, file).read();
}

Asset loadGltfFile(const fs::path& path) {
    const std::vector<unsigned char> bytes = readAssetFile(path);
    if (bytes.empty()) throw AssetError(path, "file is empty (0 bytes)");
    const tinygltf::Model model = parseModel(bytes, path, FileAccess(true, false));
    return Reader(model, path).read();
}

std::vector<EncodedImage> gltfImages(const fs::path& file) {
    const std::vector<unsigned char> bytes = readAssetFile(file);
    const tinygltf::Model model = parseModel(bytes, file, FileAccess(true, true));
    std::vector<EncodedImage> images;
    images.reserve(model.images.size());
    for (const tinygltf::Image& i : model.images) images.push_back(EncodedImage{i.image, i.mimeType});
    return images;
}

}  // namespace mipgloss
