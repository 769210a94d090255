#include "mipgloss/scene/mesh.h"

#include "mikktspace.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

namespace mipgloss {

bool Mesh::isValid() const {
    if (normals.size() != positions.size() || indices.size() % 3 != 0) return false;
    if (!uvs.empty() && uvs.size() != positions.size()) return false;
    if (!tangents.empty() && tangents.size() != positions.size()) return false;
    if (!uvs1.empty() && uvs1.size() != positions.size()) return false;
    if (!colours.empty() && colours.size() != positions.size()) return false;
    for (const glm::vec2& t : uvs)
        if (!std::isfinite(t.x) || !std::isfinite(t.y)) return false;
    for (std::uint32_t i : indices)
        if (i >= positions.size()) return false;
    auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    for (const glm::vec3& p : positions)
        if (!finite(p)) return false;
    for (const glm::vec3& n : normals)
        if (!finite(n) || std::abs(glm::length(n) - 1.0f) > 1e-4f) return false;
    return true;
}

Mesh makeSphere(int rings, int segments) {
    rings = std::max(rings, 2);
    segments = std::max(segments, 3);
    Mesh mesh;
    mesh.name = "sphere";
    // y-up: a vertex at each pole, rings - 1 circles of `segments` vertices between.
    auto direction = [](double theta, double phi) {
        return glm::vec3(
            glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    };
    mesh.positions.emplace_back(0.0f, 1.0f, 0.0f);
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s)
            mesh.positions.push_back(direction(std::numbers::pi * r / rings, 2.0 * std::numbers::pi * s / segments));
    mesh.positions.emplace_back(0.0f, -1.0f, 0.0f);
    const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    auto at = [&](int r, int s) { return static_cast<std::uint32_t>(1 + (r - 1) * segments + s % segments); };
    // Counter-clockwise seen from outside.
    for (int s = 0; s < segments; ++s) mesh.indices.insert(mesh.indices.end(), {0u, at(1, s + 1), at(1, s)});
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s)
            mesh.indices.insert(mesh.indices.end(),
                                {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r + 1, s)});
    for (int s = 0; s < segments; ++s)
        mesh.indices.insert(mesh.indices.end(), {south, at(rings - 1, s), at(rings - 1, s + 1)});
    mesh.normals.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) mesh.normals.push_back(glm::normalize(p));
    computeBounds(mesh);
    return mesh;
}

bool isZeroAreaTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    // A float coordinate holds ~7 digits: a height below 1e-7 of the longest edge is collinear.
    constexpr double kDegenerateHeight = 1e-7;
    const glm::dvec3 pa(a), pb(b), pc(c);
    const glm::dvec3 e0 = pb - pa, e1 = pc - pa, e2 = pc - pb;
    const glm::dvec3 n = glm::cross(e0, e1);
    const double longest2 = std::max({glm::dot(e0, e0), glm::dot(e1, e1), glm::dot(e2, e2)});
    // height = |n| / longest <= k * longest
    return glm::dot(n, n) <= kDegenerateHeight * kDegenerateHeight * longest2 * longest2;
}

void computeVertexNormals(Mesh& mesh) {
    // The cross product of two edges is the face normal scaled by twice the area: summing them
    // weights each face by its area.
    std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
        const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
        sum[a] += n;
        sum[b] += n;
        sum[c] += n;
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t v = 0; v < sum.size(); ++v) {
        const double length = glm::length(sum[v]);
        mesh.normals[v] =
            length > 0.0 && std::isfinite(length) ? glm::vec3(sum[v] / length) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void fillMissingNormals(Mesh& mesh) {
    const auto zero = [](const glm::vec3& n) { return n == glm::vec3(0.0f); };
    if (mesh.normals.size() == mesh.positions.size() && std::none_of(mesh.normals.begin(), mesh.normals.end(), zero))
        return;
    std::vector<glm::vec3> authored = std::move(mesh.normals);
    computeVertexNormals(mesh);
    for (std::size_t v = 0; v < authored.size() && v < mesh.normals.size(); ++v)
        if (!zero(authored[v])) mesh.normals[v] = authored[v];
}

Mesh makeUvSphere(int rings, int segments) {
    rings = std::max(rings, 2);
    segments = std::max(segments, 3);
    Mesh mesh;
    mesh.name = "sphere";
    for (int r = 0; r <= rings; ++r) {
        const double theta = std::numbers::pi * r / rings;
        for (int s = 0; s <= segments; ++s) {
            const double phi = 2.0 * std::numbers::pi * s / segments;
            const glm::vec3 p(glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
            mesh.positions.push_back(p);
            mesh.normals.push_back(r == 0 ? glm::vec3(0, 1, 0) : r == rings ? glm::vec3(0, -1, 0) : glm::normalize(p));
            mesh.uvs.emplace_back(static_cast<float>(s) / static_cast<float>(segments),
                                  static_cast<float>(r) / static_cast<float>(rings));
        }
    }
    auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
    // Counter-clockwise seen from outside (as makeSphere); no triangles of zero area at the poles.
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            if (r > 0) mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1)});
            if (r + 1 < rings) mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r + 1, s + 1), at(r + 1, s)});
        }
    computeBounds(mesh);
    computeTangents(mesh);
    return mesh;
}

namespace {

// MikkTSpace's view of a mesh (third_party/mikktspace: the reference implementation, unmodified):
// the corners' attributes in, one tangent per corner out.
struct TangentJob {
    const Mesh* mesh = nullptr;
    const std::vector<glm::vec2>* uvs = nullptr;  // the set the normal map reads
    std::vector<glm::vec4> corners;  // per triangle corner: xyz, w the bitangent's sign

    static TangentJob& of(const SMikkTSpaceContext* context) { return *static_cast<TangentJob*>(context->m_pUserData); }
    std::uint32_t vertex(int face, int corner) const {
        return mesh->indices[static_cast<std::size_t>(face) * 3 + static_cast<std::size_t>(corner)];
    }
};

int mikkFaceCount(const SMikkTSpaceContext* context) {
    return static_cast<int>(TangentJob::of(context).mesh->indices.size() / 3);
}
int mikkCornerCount(const SMikkTSpaceContext*, int) { return 3; }
void mikkPosition(const SMikkTSpaceContext* context, float out[], int face, int corner) {
    const TangentJob& job = TangentJob::of(context);
    const glm::vec3& p = job.mesh->positions[job.vertex(face, corner)];
    out[0] = p.x, out[1] = p.y, out[2] = p.z;
}
void mikkNormal(const SMikkTSpaceContext* context, float out[], int face, int corner) {
    const TangentJob& job = TangentJob::of(context);
    const glm::vec3& n = job.mesh->normals[job.vertex(face, corner)];
    out[0] = n.x, out[1] = n.y, out[2] = n.z;
}
// glTF's v runs down the image; MikkTSpace's bitangent follows v, and glTF's (the normal map's +Y)
// points up the image. So v is given as 1 − v, as Blender gives its v-up UVs to the same code (the
// tangents glTF exporters write and bakers bake against): the tangent is unchanged, the sign is
// glTF's.
void mikkTexCoord(const SMikkTSpaceContext* context, float out[], int face, int corner) {
    const TangentJob& job = TangentJob::of(context);
    const glm::vec2& uv = (*job.uvs)[job.vertex(face, corner)];
    out[0] = uv.x, out[1] = 1.0f - uv.y;
}
void mikkSetTangent(const SMikkTSpaceContext* context, const float tangent[], float sign, int face, int corner) {
    TangentJob& job = TangentJob::of(context);
    job.corners[static_cast<std::size_t>(face) * 3 + static_cast<std::size_t>(corner)] =
        glm::vec4(tangent[0], tangent[1], tangent[2], sign < 0.0f ? -1.0f : 1.0f);
}

// Any unit tangent perpendicular to `normal` (a vertex no triangle uses).
glm::vec4 anyTangent(const glm::vec3& normal) {
    const glm::vec3 t = glm::cross(std::abs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0), normal);
    return glm::vec4(glm::normalize(t), 1.0f);
}

}  // namespace

std::uint32_t duplicateVertex(Mesh& mesh, std::uint32_t vertex) {
    const auto copy = [vertex](auto& values) {
        if (!values.empty()) values.push_back(values[vertex]);
    };
    copy(mesh.positions);
    copy(mesh.normals);
    copy(mesh.uvs);
    copy(mesh.tangents);
    copy(mesh.uvs1);
    copy(mesh.colours);
    return static_cast<std::uint32_t>(mesh.positions.size() - 1);
}

void computeTangents(Mesh& mesh, int uvSet, const glm::mat3& uvTransform) {
    const std::size_t n = mesh.positions.size();
    mesh.tangents.clear();
    const std::vector<glm::vec2>& set = uvSet == 1 ? mesh.uvs1 : mesh.uvs;
    if (set.size() != n || mesh.normals.size() != n) return;
    // The UVs the map is sampled at: its frame is the derivative of the position along them.
    std::vector<glm::vec2> transformed;
    if (uvTransform != glm::mat3(1.0f)) {
        transformed.reserve(n);
        for (const glm::vec2& uv : set) transformed.emplace_back(uvTransform * glm::vec3(uv, 1.0f));
    }
    const std::vector<glm::vec2>& uvs = transformed.empty() ? set : transformed;
    TangentJob job;
    job.mesh = &mesh;
    job.uvs = &uvs;
    job.corners.assign(mesh.indices.size(), glm::vec4(0.0f));
    SMikkTSpaceInterface callbacks{};
    callbacks.m_getNumFaces = mikkFaceCount;
    callbacks.m_getNumVerticesOfFace = mikkCornerCount;
    callbacks.m_getPosition = mikkPosition;
    callbacks.m_getNormal = mikkNormal;
    callbacks.m_getTexCoord = mikkTexCoord;
    callbacks.m_setTSpaceBasic = mikkSetTangent;
    SMikkTSpaceContext context{&callbacks, &job};
    if (!mesh.indices.empty() && !genTangSpaceDefault(&context)) {
        // MikkTSpace could not allocate its working memory: every vertex some tangent, so the
        // mesh still draws (its normal map is then not the baker's).
        for (std::size_t c = 0; c < job.corners.size(); ++c) job.corners[c] = anyTangent(mesh.normals[mesh.indices[c]]);
    }

    // One tangent per vertex: a vertex whose corners MikkTSpace gave different tangents (a mirrored
    // UV seam, a hard edge of the UV layout) becomes one vertex per tangent, as the reference's
    // users (Blender, the glTF exporters) split them.
    std::vector<glm::vec4> tangents(n, glm::vec4(0.0f));
    std::vector<bool> assigned(n, false);
    std::vector<std::vector<std::pair<glm::vec4, std::uint32_t>>> copies(n);  // a vertex's other tangents
    for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
        const std::uint32_t v = mesh.indices[c];
        const glm::vec4& t = job.corners[c];
        if (!assigned[v]) {
            tangents[v] = t;
            assigned[v] = true;
            continue;
        }
        if (tangents[v] == t) continue;
        auto& others = copies[v];
        const auto same = std::find_if(others.begin(), others.end(), [&](const auto& o) { return o.first == t; });
        if (same != others.end()) {
            mesh.indices[c] = same->second;
            continue;
        }
        const std::uint32_t copy = duplicateVertex(mesh, v);
        tangents.push_back(t);
        others.emplace_back(t, copy);
        mesh.indices[c] = copy;
    }
    for (std::size_t v = 0; v < n; ++v)
        if (!assigned[v]) tangents[v] = anyTangent(mesh.normals[v]);
    mesh.tangents = std::move(tangents);
}

void computeBounds(Mesh& mesh) {
    if (mesh.positions.empty()) {
        mesh.bounds = {};
        return;
    }
    Bounds b{mesh.positions[0], mesh.positions[0]};
    for (const glm::vec3& p : mesh.positions) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    mesh.bounds = b;
}

}  // namespace mipgloss
