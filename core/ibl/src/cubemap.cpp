#include "mipgloss/ibl/cubemap.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace mipgloss {

const char* faceName(Face f) {
    static constexpr const char* kNames[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    return kNames[static_cast<int>(f)];
}

const FaceFrame& faceFrame(Face f) {
    // Read off the table in cubemap.h: direction = axis + sc·u + tc·v.
    static constexpr std::array<FaceFrame, 6> kFrames{{
        {{0, 0, -1}, {0, -1, 0}, {1, 0, 0}},   // +X: ( 1, -tc, -sc)
        {{0, 0, 1}, {0, -1, 0}, {-1, 0, 0}},   // -X: (-1, -tc,  sc)
        {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},     // +Y: (sc,   1,  tc)
        {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},   // -Y: (sc,  -1, -tc)
        {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}},    // +Z: (sc, -tc,   1)
        {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},  // -Z: (-sc, -tc, -1)
    }};
    return kFrames[static_cast<std::size_t>(f)];
}

glm::vec2 faceCoordOnPlane(Face f, const glm::vec3& r) {
    const FaceFrame& fr = faceFrame(f);
    const float ma = glm::dot(r, fr.axis);
    return {0.5f * (glm::dot(r, fr.u) / ma + 1.0f), 0.5f * (glm::dot(r, fr.v) / ma + 1.0f)};
}

FaceCoord directionToFace(const glm::vec3& r) {
    const float ax = std::fabs(r.x), ay = std::fabs(r.y), az = std::fabs(r.z);
    // The major axis picks the face; ties go to x, then y (the GL specification leaves them to
    // the implementation).
    Face face;
    if (ax >= ay && ax >= az)
        face = r.x >= 0.0f ? Face::PX : Face::NX;
    else if (ay >= az)
        face = r.y >= 0.0f ? Face::PY : Face::NY;
    else
        face = r.z >= 0.0f ? Face::PZ : Face::NZ;
    const glm::vec2 st = faceCoordOnPlane(face, r);
    return {face, st.x, st.y};
}

glm::vec3 faceToDirection(Face face, float s, float t) {
    const FaceFrame& fr = faceFrame(face);
    return glm::normalize(fr.axis + (2.0f * s - 1.0f) * fr.u + (2.0f * t - 1.0f) * fr.v);
}

glm::vec3 texelDirection(Face face, int x, int y, int size) {
    const float inv = 1.0f / static_cast<float>(size);
    return faceToDirection(face, (static_cast<float>(x) + 0.5f) * inv,
                           (static_cast<float>(y) + 0.5f) * inv);
}

namespace {
// Solid angle subtended by the face-plane rectangle [0,x]×[0,y] at distance 1 (signed).
double areaElement(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }
}  // namespace

double faceRectSolidAngle(double u0, double v0, double u1, double v1) {
    return areaElement(u0, v0) - areaElement(u0, v1) - areaElement(u1, v0) + areaElement(u1, v1);
}

double texelSolidAngle(int x, int y, int size) {
    const double inv = 2.0 / size;
    return faceRectSolidAngle(x * inv - 1.0, y * inv - 1.0, (x + 1) * inv - 1.0,
                              (y + 1) * inv - 1.0);
}

CubeMap::CubeMap(int size, Rgb fill) : size_(size) {
    assert(size >= 0);
    const auto n = static_cast<std::size_t>(size + 2) * static_cast<std::size_t>(size + 2);
    for (auto& f : faces_) f.assign(n, fill);
}

TexelRef resolveTexel(Face f, int x, int y, int size) {
    if (x >= 0 && y >= 0 && x < size && y < size) return {f, x, y};
    return texelOf(directionToFace(texelDirection(f, x, y, size)), size);
}

TexelRef texelOf(const FaceCoord& c, int size) {
    const float m = static_cast<float>(size);
    return {c.face, std::clamp(static_cast<int>(std::floor(c.s * m)), 0, size - 1),
            std::clamp(static_cast<int>(std::floor(c.t * m)), 0, size - 1)};
}

void CubeMap::makeSeamless() {
    const int m = size_;
    if (m == 0) return;
    auto interior = [&](const TexelRef& r) { return at(r.face, r.x, r.y); };
    for (Face f : kAllFaces) {
        for (int i = 0; i < m; ++i) {
            at(f, -1, i) = interior(resolveTexel(f, -1, i, m));
            at(f, m, i) = interior(resolveTexel(f, m, i, m));
            at(f, i, -1) = interior(resolveTexel(f, i, -1, m));
            at(f, i, m) = interior(resolveTexel(f, i, m, m));
        }
        // A border corner sits at a cube corner, where three texels meet: use their mean.
        for (int cy : {-1, m}) {
            for (int cx : {-1, m}) {
                const int ix = cx < 0 ? 0 : m - 1;
                const int iy = cy < 0 ? 0 : m - 1;
                at(f, cx, cy) = (at(f, ix, iy) + interior(resolveTexel(f, cx, iy, m)) +
                                 interior(resolveTexel(f, ix, cy, m))) /
                                3.0f;
            }
        }
    }
}

Rgb CubeMap::sample(Face f, float s, float t) const {
    const float m = static_cast<float>(size_);
    const float x = std::clamp(s * m - 0.5f, -1.0f, m);
    const float y = std::clamp(t * m - 0.5f, -1.0f, m);
    const int x0 = std::min(static_cast<int>(std::floor(x)), size_ - 1);
    const int y0 = std::min(static_cast<int>(std::floor(y)), size_ - 1);
    const float fx = x - static_cast<float>(x0);
    const float fy = y - static_cast<float>(y0);
    // x0, y0 in [-1, size-1]: the border makes x0+1, y0+1 valid without tests.
    const Rgb a = at(f, x0, y0), b = at(f, x0 + 1, y0);
    const Rgb c = at(f, x0, y0 + 1), d = at(f, x0 + 1, y0 + 1);
    return (a * (1.0f - fx) + b * fx) * (1.0f - fy) + (c * (1.0f - fx) + d * fx) * fy;
}

Rgb CubeMap::sample(const glm::vec3& dir) const {
    const FaceCoord c = directionToFace(dir);
    return sample(c.face, c.s, c.t);
}

glm::dvec3 CubeMap::weightedMean() const {
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (int y = 0; y < size_; ++y) {
        for (int x = 0; x < size_; ++x) {
            const double w = texelSolidAngle(x, y, size_);
            total += 6.0 * w;
            for (Face f : kAllFaces) sum += w * glm::dvec3(at(f, x, y));
        }
    }
    return total > 0.0 ? sum / total : sum;
}

int fullChainLevelCount(int baseSize) {
    int levels = 1;
    while (baseSize > 1) {
        baseSize /= 2;
        ++levels;
    }
    return levels;
}

int levelSize(int baseSize, int level) { return std::max(1, baseSize >> level); }

}  // namespace mipgloss
