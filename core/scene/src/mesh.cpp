#include "mipgloss/scene/mesh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

namespace mipgloss {

bool Mesh::isValid() const {
    if (normals.size() != positions.size() || indices.size() % 3 != 0) return false;
    if (!uvs.empty() && uvs.size() != positions.size()) return false;
    if (!tangents.empty() && tangents.size() != positions.size()) return false;
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

void computeTangents(Mesh& mesh) {
    const std::size_t n = mesh.positions.size();
    if (mesh.uvs.size() != n || mesh.normals.size() != n) {
        mesh.tangents.clear();
        return;
    }
    // Per triangle: T, B with dp1 = du1·T + dv1·B, dp2 = du2·T + dv2·B (Lengyel), each corner's
    // share weighted by its angle, as MikkTSpace weights them.
    std::vector<glm::dvec3> tangent(n, glm::dvec3(0.0)), bitangent(n, glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t v[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        const glm::dvec3 p0(mesh.positions[v[0]]), p1(mesh.positions[v[1]]), p2(mesh.positions[v[2]]);
        const glm::dvec2 t0(mesh.uvs[v[0]]), t1(mesh.uvs[v[1]]), t2(mesh.uvs[v[2]]);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
        const glm::dvec2 d1 = t1 - t0, d2 = t2 - t0;
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20) || !std::isfinite(det)) continue;
        const glm::dvec3 ft = (e1 * d2.y - e2 * d1.y) / det;
        const glm::dvec3 fb = (e2 * d1.x - e1 * d2.x) / det;
        const glm::dvec3 ps[3] = {p0, p1, p2};
        for (int c = 0; c < 3; ++c) {
            const glm::dvec3 a = ps[(c + 1) % 3] - ps[c], b = ps[(c + 2) % 3] - ps[c];
            const double la = glm::length(a), lb = glm::length(b);
            if (!(la > 0.0 && lb > 0.0)) continue;
            const double angle = std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
            tangent[v[c]] += angle * ft;
            bitangent[v[c]] += angle * fb;
        }
    }
    mesh.tangents.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 normal(mesh.normals[i]);
        glm::dvec3 tan = tangent[i] - normal * glm::dot(normal, tangent[i]);
        double length = glm::length(tan);
        if (!(length > 1e-12) || !std::isfinite(length)) {
            // Any direction perpendicular to the normal.
            tan = glm::cross(std::abs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), normal);
            length = glm::length(tan);
        }
        tan /= length;
        const double handedness = glm::dot(glm::cross(normal, tan), bitangent[i]) < 0.0 ? -1.0 : 1.0;
        mesh.tangents[i] = glm::vec4(glm::vec3(tan), static_cast<float>(handedness));
    }
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
