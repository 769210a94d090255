// The renderer's GPU resources (renderer_impl.h): samplers by chain level, the split-sum table,
// texture maps, cube uploads, meshes and the frame's targets.
#include "renderer_impl.h"

#include "mipgloss/ibl/ggx_fitted_lobes.h"
#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/ibl/specular.h"

#include <algorithm>
#include <set>

namespace mipgloss::ui {

namespace {
// A chain level (GL_TEXTURE_MIN_LOD) as a sampler key: levels within 1/1024 share a sampler.
int levelKey(float level) { return static_cast<int>(std::lround(level * 1024.0f)); }
}  // namespace

// The sampler reading the chain from `level` on (GL_TEXTURE_MIN_LOD = level).
GLuint Renderer::Impl::sampler(float level) {
    const int key = levelKey(level);
    auto it = samplers.find(key);
    if (it != samplers.end()) return it->second;
    GLuint s = 0;
    gl->glGenSamplers(1, &s);
    gl->glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl->glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    gl->glSamplerParameterf(s, GL_TEXTURE_MIN_LOD, static_cast<float>(key) / 1024.0f);
    gl->glSamplerParameterf(s, GL_TEXTURE_MAX_LOD, 1000.0f);
    ++counters.samplersCreated;
    samplers.emplace(key, s);
    return s;
}

// The sampler a material map is read with (glTF's sampler: wrap modes, nearest or linear), with
// the anisotropy every map's texture has; one per distinct combination.
GLuint Renderer::Impl::mapSampler(const TextureSampling& sampling) {
    const int key = static_cast<int>(sampling.wrapS) | static_cast<int>(sampling.wrapT) << 2 |
                    (sampling.nearestMagnify ? 16 : 0) | (sampling.nearestMinify ? 32 : 0);
    auto it = mapSamplers.find(key);
    if (it != mapSamplers.end()) return it->second;
    auto wrap = [](TextureWrap w) {
        return w == TextureWrap::ClampToEdge ? GL_CLAMP_TO_EDGE : w == TextureWrap::MirroredRepeat ? GL_MIRRORED_REPEAT : GL_REPEAT;
    };
    GLuint s = 0;
    gl->glGenSamplers(1, &s);
    gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_S, wrap(sampling.wrapS));
    gl->glSamplerParameteri(s, GL_TEXTURE_WRAP_T, wrap(sampling.wrapT));
    gl->glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, sampling.nearestMagnify ? GL_NEAREST : GL_LINEAR);
    gl->glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, sampling.nearestMinify ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR);
    // Anisotropy only where both filters are linear: llvmpipe's anisotropic sampling blends
    // texels a nearest filter keeps apart.
    if (maxAnisotropy > 1.0f && !sampling.nearestMinify && !sampling.nearestMagnify)
        gl->glSamplerParameterf(s, 0x84FE /* GL_TEXTURE_MAX_ANISOTROPY */, maxAnisotropy);
    mapSamplers.emplace(key, s);
    return s;
}

// The GGX albedo table (ggx_sampling.h) as an RGB32F texture on TextureUnit::SplitSum, its
// lobes' mean directions as an RG32F one on TextureUnit::LobeMean and the fitted lobes' nodes
// (ggx_fitted_lobes.h) as an RGBA32F 2D array on TextureUnit::FittedLobes, made the first time a layered
// material is drawn (building the table takes about 0.1 s, which no single-lobe scene pays).
void Renderer::Impl::bindSplitSum() {
    auto upload = [&](GLuint& texture, GLint internalFormat, GLenum format, const float* nodes) {
        gl->glGenTextures(1, &texture);
        gl->glBindTexture(GL_TEXTURE_2D, texture);
        gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, GgxAlbedoTable::kCosSteps, GgxAlbedoTable::kRoughnessSteps, 0,
                         format, GL_FLOAT, nodes);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    };
    if (splitSumTexture == 0) {
        const GgxAlbedoTable& table = GgxAlbedoTable::shared();
        upload(splitSumTexture, GL_RGB32F, GL_RGB, table.nodes().data());
        upload(lobeMeanTexture, GL_RG32F, GL_RG, table.meanNodes().data());
        const std::vector<float> fitted = fittedLobeLayers();
        gl->glGenTextures(1, &fittedLobesTexture);
        gl->glBindTexture(GL_TEXTURE_2D_ARRAY, fittedLobesTexture);
        gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA32F, kFittedCosNodes, kFittedRoughnessNodes, 2 * kFittedLobeCount, 0,
                         GL_RGBA, GL_FLOAT, fitted.data());
        gl->glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    auto bind = [&](TextureUnit unit, GLuint texture) {
        gl->glActiveTexture(GL_TEXTURE0 + unitIndex(unit));
        gl->glBindTexture(GL_TEXTURE_2D, texture);
        gl->glBindSampler(unitIndex(unit), 0);
    };
    bind(TextureUnit::SplitSum, splitSumTexture);
    bind(TextureUnit::LobeMean, lobeMeanTexture);
    gl->glActiveTexture(GL_TEXTURE0 + unitIndex(TextureUnit::FittedLobes));
    gl->glBindTexture(GL_TEXTURE_2D_ARRAY, fittedLobesTexture);
    gl->glBindSampler(unitIndex(TextureUnit::FittedLobes), 0);
    gl->glActiveTexture(GL_TEXTURE0);
}

// The GL texture of map `ref` (sRGB or linear), uploaded the first time; 0 when its image is
// not decoded (yet, or refused: TextureCache::problem).
GLuint Renderer::Impl::mapTexture(const TextureRef& ref, bool srgb) {
    if (ref.empty()) return 0;
    const auto key = std::make_pair(ref.key(), srgb);  // the image, whatever channel a map reads
    const std::shared_ptr<const TextureImage> decoded = textures ? textures->find(ref) : nullptr;
    auto it = mapTextures.find(key);
    if (it != mapTextures.end() && it->second.image == decoded) return it->second.texture;
    if (it != mapTextures.end()) {
        gl->glDeleteTextures(1, &it->second.texture);
        mapTextures.erase(it);
    }
    if (!decoded || decoded->width <= 0 || decoded->height <= 0) return 0;
    GpuTexture g;
    g.image = decoded;
    gl->glGenTextures(1, &g.texture);
    gl->glBindTexture(GL_TEXTURE_2D, g.texture);
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->glTexImage2D(GL_TEXTURE_2D, 0, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, decoded->width, decoded->height, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, decoded->rgba.data());
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->glGenerateMipmap(GL_TEXTURE_2D);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (maxAnisotropy < 0.0f) {
        // GL_TEXTURE_MAX_ANISOTROPY (core in 4.6, EXT_texture_filter_anisotropic before).
        GLfloat most = 0.0f;
        gl->glGetFloatv(0x84FF /* GL_MAX_TEXTURE_MAX_ANISOTROPY */, &most);
        maxAnisotropy = gl->glGetError() == GL_NO_ERROR ? std::min(most, 16.0f) : 0.0f;
    }
    if (maxAnisotropy > 1.0f) gl->glTexParameterf(GL_TEXTURE_2D, 0x84FE /* GL_TEXTURE_MAX_ANISOTROPY */, maxAnisotropy);
    ++counters.textureUploads;
    counters.textureBytes += decoded->bytes() * 4 / 3;
    return mapTextures[key] = g, g.texture;
}

// Frees the map textures no material of `scene` reads any more.
void Renderer::Impl::collectMapTextures(const Scene& scene) {
    std::set<std::string> used;
    for (const TextureRef& t : texturesOf(scene)) used.insert(t.key());
    for (auto it = mapTextures.begin(); it != mapTextures.end();) {
        if (!used.count(it->first.first)) {
            counters.textureBytes -= std::min(counters.textureBytes, it->second.image->bytes() * 4 / 3);
            gl->glDeleteTextures(1, &it->second.texture);
            it = mapTextures.erase(it);
        } else {
            ++it;
        }
    }
}

// Sends `levels` as the texture's levels firstLevel, firstLevel + 1, … (those below stay) and
// makes the last of them its GL_TEXTURE_MAX_LEVEL. 32-bit float, as the core holds them: half
// floats clamp at 65504 (a mirror kept 0.1 % of a one-pixel sun of 1e9, an n = 1024 sphere 7 %)
// and lose everything below 6e-8 (a map at 1e-30 was black), so the picture depended on the
// environment's absolute scale. Float costs twice the memory and no measurable frame time on
// llvmpipe (docs/radiance-range.md, issue 24).
void Renderer::Impl::uploadCube(GLuint texture, const std::vector<const CubeMap*>& levels, int firstLevel) {
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    std::vector<float> face;
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const CubeMap& cube = *levels[k];
        const std::size_t level = static_cast<std::size_t>(firstLevel) + k;
        const int n = cube.size();
        face.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * 3);
        for (Face f : kAllFaces) {
            // Interior texels only; our row 0 is t = 0, which is GL's first row.
            std::size_t i = 0;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const Rgb& c = cube.at(f, x, y);
                    face[i++] = c.r;
                    face[i++] = c.g;
                    face[i++] = c.b;
                }
            gl->glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f),
                             static_cast<GLint>(level), GL_RGB32F, n, n, 0, GL_RGB, GL_FLOAT,
                             face.data());
        }
    }
    const GLint last = firstLevel + static_cast<GLint>(levels.size()) - 1;
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, last);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER,
                        last > 0 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
}

GpuMesh& Renderer::Impl::gpuMesh(const std::shared_ptr<const Mesh>& mesh) {
    auto it = meshes.find(mesh.get());
    if (it != meshes.end() && !it->second.source.expired()) return it->second;
    if (it != meshes.end()) releaseMesh(it->second);
    GpuMesh g;
    g.source = mesh;
    // Position and normal, then the asset's UV and tangent where it has them.
    const bool uvs = mesh->uvs.size() == mesh->positions.size();
    const bool tangents = mesh->tangents.size() == mesh->positions.size();
    g.uvs1 = mesh->uvs1.size() == mesh->positions.size();
    g.colours = mesh->colours.size() == mesh->positions.size();
    const std::size_t floats = 6 + (uvs ? 2 : 0) + (tangents ? 4 : 0) + (g.uvs1 ? 2 : 0) + (g.colours ? 4 : 0);
    std::vector<float> interleaved;
    interleaved.reserve(mesh->positions.size() * floats);
    for (std::size_t i = 0; i < mesh->positions.size(); ++i) {
        const glm::vec3& p = mesh->positions[i];
        const glm::vec3& n = mesh->normals[i];
        interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
        if (uvs) interleaved.insert(interleaved.end(), {mesh->uvs[i].x, mesh->uvs[i].y});
        if (tangents) {
            const glm::vec4& t = mesh->tangents[i];
            interleaved.insert(interleaved.end(), {t.x, t.y, t.z, t.w});
        }
        if (g.uvs1) interleaved.insert(interleaved.end(), {mesh->uvs1[i].x, mesh->uvs1[i].y});
        if (g.colours) {
            const glm::vec4& c = mesh->colours[i];
            interleaved.insert(interleaved.end(), {c.r, c.g, c.b, c.a});
        }
    }
    gl->glGenVertexArrays(1, &g.vao);
    gl->glBindVertexArray(g.vao);
    gl->glGenBuffers(1, &g.vbo);
    gl->glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
    gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                     interleaved.data(), GL_STATIC_DRAW);
    gl->glGenBuffers(1, &g.ibo);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo);
    gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(mesh->indices.size() * sizeof(std::uint32_t)),
                     mesh->indices.data(), GL_STATIC_DRAW);
    const auto stride = static_cast<GLsizei>(floats * sizeof(float));
    gl->glEnableVertexAttribArray(0);
    gl->glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    gl->glEnableVertexAttribArray(1);
    gl->glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                              reinterpret_cast<const void*>(3 * sizeof(float)));
    std::size_t offset = 6;
    if (uvs) {
        gl->glEnableVertexAttribArray(2);
        gl->glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset * sizeof(float)));
        offset += 2;
    }
    if (tangents) {
        gl->glEnableVertexAttribArray(3);
        gl->glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset * sizeof(float)));
        offset += 4;
    }
    if (g.uvs1) {
        gl->glEnableVertexAttribArray(4);
        gl->glVertexAttribPointer(4, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset * sizeof(float)));
        offset += 2;
    }
    if (g.colours) {
        gl->glEnableVertexAttribArray(5);
        gl->glVertexAttribPointer(5, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset * sizeof(float)));
    }
    gl->glBindVertexArray(0);
    g.indexCount = static_cast<GLsizei>(mesh->indices.size());
    ++counters.meshUploads;
    return meshes[mesh.get()] = g;
}

void Renderer::Impl::releaseMesh(GpuMesh& g) {
    gl->glDeleteVertexArrays(1, &g.vao);
    gl->glDeleteBuffers(1, &g.vbo);
    gl->glDeleteBuffers(1, &g.ibo);
    g = GpuMesh{};
}

// Frees the GPU copies of meshes no scene object holds any more.
void Renderer::Impl::collectMeshes() {
    for (auto it = meshes.begin(); it != meshes.end();) {
        if (it->second.source.expired()) {
            releaseMesh(it->second);
            it = meshes.erase(it);
        } else {
            ++it;
        }
    }
}

void Renderer::Impl::releaseTargets() {
    if (msFbo) gl->glDeleteFramebuffers(1, &msFbo);
    if (resolveFbo) gl->glDeleteFramebuffers(1, &resolveFbo);
    if (msColour) gl->glDeleteRenderbuffers(1, &msColour);
    if (msDepth) gl->glDeleteRenderbuffers(1, &msDepth);
    if (resolveTexture) gl->glDeleteTextures(1, &resolveTexture);
    msFbo = resolveFbo = msColour = msDepth = resolveTexture = 0;
    targetWidth = targetHeight = 0;
    targetSamples = -1;
}

void Renderer::Impl::ensureTargets(int width, int height, int samples) {
    GLint maxSamples = 0;
    gl->glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    samples = std::clamp(samples, 0, static_cast<int>(maxSamples));
    if (samples == 1) samples = 0;
    if (width == targetWidth && height == targetHeight && samples == targetSamples) return;
    releaseTargets();
    gl->glGenRenderbuffers(1, &msColour);
    gl->glBindRenderbuffer(GL_RENDERBUFFER, msColour);
    // The linear picture in 32-bit float, like the cubes it reads (uploadCube): scene-referred
    // at any scale until the tone pass applies the exposure.
    gl->glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA32F, width, height);
    gl->glGenRenderbuffers(1, &msDepth);
    gl->glBindRenderbuffer(GL_RENDERBUFFER, msDepth);
    gl->glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width,
                                         height);
    gl->glGenFramebuffers(1, &msFbo);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, msFbo);
    gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msColour);
    // Depth and a stencil (the selection outline's mask).
    gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, msDepth);

    gl->glGenTextures(1, &resolveTexture);
    gl->glBindTexture(GL_TEXTURE_2D, resolveTexture);
    gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->glGenFramebuffers(1, &resolveFbo);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                               resolveTexture, 0);
    targetWidth = width;
    targetHeight = height;
    targetSamples = samples;
}

}  // namespace mipgloss::ui
