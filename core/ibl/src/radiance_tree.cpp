#include "mipgloss/ibl/radiance_tree.h"

#include "mipgloss/ibl/colour.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mipgloss {

namespace {

// The point (s, t) of face f in double precision (faceToDirection's frame).
glm::dvec3 facePoint(Face f, double s, double t) {
    const FaceFrame& fr = faceFrame(f);
    return glm::normalize(glm::dvec3(fr.axis) + (2.0 * s - 1.0) * glm::dvec3(fr.u) + (2.0 * t - 1.0) * glm::dvec3(fr.v));
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
}

double lum(const glm::dvec3& e) { return 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z; }

// Whether a node at `c` of angular radius r is too coarse for the integrand about the focus:
// wider than tolerance · (its distance from the lobe, at least the lobe's width); in a long lobe's
// core band (RadianceFocus::length) wider than tolerance · width.
constexpr double kCoreBandWidths = 3.0;
bool tooCoarse(const glm::dvec3& c, double r, const RadianceFocus& focus, const RadianceAccuracy& accuracy) {
    const double distance = angleBetween(focus.centre, c) - r;
    if (focus.length > focus.width && distance < focus.length &&
        std::abs(glm::dot(c, focus.across)) - std::sin(std::min(r, 1.5707963267948966)) < kCoreBandWidths * focus.width)
        return r > accuracy.tolerance * focus.width;
    return r > accuracy.tolerance * std::max(focus.width, distance);
}

}  // namespace

RadianceTree::RadianceTree(const CubeMap& base) {
    const int n = base.size();
    if (n <= 0) return;
    // Node geometry from the base texels it covers: [x0, x1) × [y0, y1) at level ℓ's span 2^ℓ.
    auto geometry = [n](Level& level, int span) {
        const std::size_t count = static_cast<std::size_t>(kFaceCount) * level.size * level.size;
        level.centre.resize(count);
        level.radius.resize(count);
        level.sinRadius.resize(count);
        for (Face f : kAllFaces)
            for (int y = 0; y < level.size; ++y)
                for (int x = 0; x < level.size; ++x) {
                    const double s0 = static_cast<double>(x * span) / n, s1 = static_cast<double>(std::min((x + 1) * span, n)) / n;
                    const double t0 = static_cast<double>(y * span) / n, t1 = static_cast<double>(std::min((y + 1) * span, n)) / n;
                    const glm::dvec3 c = facePoint(f, 0.5 * (s0 + s1), 0.5 * (t0 + t1));
                    double r = 0.0;
                    for (double s : {s0, s1})
                        for (double t : {t0, t1}) r = std::max(r, angleBetween(c, facePoint(f, s, t)));
                    const std::size_t i = (static_cast<std::size_t>(f) * level.size + y) * level.size + x;
                    level.centre[i] = c;
                    level.radius[i] = r;
                    level.sinRadius[i] = std::sin(std::min(r, 1.5707963267948966));
                }
    };
    Level level0;
    level0.size = n;
    geometry(level0, 1);
    level0.energy.resize(level0.centre.size());
    level0.direction = level0.centre;
    for (Face f : kAllFaces)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const std::size_t i = (static_cast<std::size_t>(f) * n + y) * n + x;
                level0.energy[i] = glm::dvec3(base.at(f, x, y)) * texelSolidAngle(x, y, n);
            }
    levels_.push_back(std::move(level0));
    for (int span = 2; levels_.back().size > 1; span *= 2) {
        const Level& fine = levels_.back();
        Level coarse;
        coarse.size = (fine.size + 1) / 2;
        geometry(coarse, span);
        coarse.energy.assign(coarse.centre.size(), glm::dvec3(0.0));
        coarse.direction.resize(coarse.centre.size());
        for (Face f : kAllFaces)
            for (int y = 0; y < coarse.size; ++y)
                for (int x = 0; x < coarse.size; ++x) {
                    const std::size_t i = (static_cast<std::size_t>(f) * coarse.size + y) * coarse.size + x;
                    glm::dvec3 moment(0.0);
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx) {
                            const int cx = 2 * x + dx, cy = 2 * y + dy;
                            if (cx >= fine.size || cy >= fine.size) continue;
                            const std::size_t j = (static_cast<std::size_t>(f) * fine.size + cy) * fine.size + cx;
                            coarse.energy[i] += fine.energy[j];
                            moment += lum(fine.energy[j]) * fine.direction[j];
                        }
                    const double m = glm::length(moment);
                    coarse.direction[i] = m > 0.0 ? moment / m : coarse.centre[i];
                }
        levels_.push_back(std::move(coarse));
    }
}

glm::dvec3 RadianceTree::totalEnergy() const {
    glm::dvec3 sum(0.0);
    if (levels_.empty()) return sum;
    for (const glm::dvec3& e : levels_.back().energy) sum += e;
    return sum;
}

namespace {

// Part [s0, s1] × [t0, t1] of a base texel of face f (radiance L, constant over the texel as
// decoded), split like the tree's nodes while the same rule asks, to `depth` more halvings.
void visitTexelPart(Face f, double s0, double s1, double t0, double t1, const glm::dvec3& radiance,
                    const RadianceFocus& focus, const RadianceAccuracy& accuracy, int depth,
                    const RadianceTree::Visit& visit) {
    const glm::dvec3 c = facePoint(f, 0.5 * (s0 + s1), 0.5 * (t0 + t1));
    double r = 0.0;
    for (double s : {s0, s1})
        for (double t : {t0, t1}) r = std::max(r, angleBetween(c, facePoint(f, s, t)));
    const double above = glm::dot(focus.horizon, c), sinRadius = std::sin(std::min(r, 1.5707963267948966));
    if (above < -sinRadius) return;
    const bool sharp = tooCoarse(c, r, focus, accuracy);
    const bool cut = above < sinRadius && r > accuracy.horizonRadius;
    if (depth > 0 && (sharp || cut)) {
        const double sm = 0.5 * (s0 + s1), tm = 0.5 * (t0 + t1);
        visitTexelPart(f, s0, sm, t0, tm, radiance, focus, accuracy, depth - 1, visit);
        visitTexelPart(f, sm, s1, t0, tm, radiance, focus, accuracy, depth - 1, visit);
        visitTexelPart(f, s0, sm, tm, t1, radiance, focus, accuracy, depth - 1, visit);
        visitTexelPart(f, sm, s1, tm, t1, radiance, focus, accuracy, depth - 1, visit);
        return;
    }
    const double omega = faceRectSolidAngle(2.0 * s0 - 1.0, 2.0 * t0 - 1.0, 2.0 * s1 - 1.0, 2.0 * t1 - 1.0);
    visit(c, radiance * omega);
}

// Halvings of a base texel: at least six (a texel of a 16² face, 0.1 rad, down to 0.0016 rad,
// where the horizon asks), and as many as a lobe narrower than its texels needs for its parts to
// reach tolerance · width at its peak (a lobe of r 0.05 at N·v 0.05 on a 256² face: eight), at
// most sixteen (a 2048² face's texel down to 1e-8 rad).
constexpr int kTexelDepth = 6, kDeepestTexelDepth = 16;
int texelDepthFor(double texelRadius, const RadianceFocus& focus, const RadianceAccuracy& accuracy) {
    const double finest = accuracy.tolerance * focus.width;
    if (!(finest > 0.0)) return kDeepestTexelDepth;
    const double halvings = std::ceil(std::log2(texelRadius / finest));
    return static_cast<int>(std::clamp(halvings, double(kTexelDepth), double(kDeepestTexelDepth)));
}

}  // namespace

void RadianceTree::visitNode(int level, int face, int x, int y, const Focus& focus, const Accuracy& accuracy,
                             const Visit& visit) const {
    const Level& l = levels_[static_cast<std::size_t>(level)];
    const std::size_t i = (static_cast<std::size_t>(face) * l.size + y) * l.size + x;
    const double above = glm::dot(focus.horizon, l.centre[i]);
    if (above < -l.sinRadius[i]) return;  // wholly below the horizon
    const double r = l.radius[i];
    const bool sharp = tooCoarse(l.centre[i], r, focus, accuracy);
    const bool cut = above < l.sinRadius[i] && r > accuracy.horizonRadius;
    if (sharp || cut) {
        if (level > 0) {
            const int fineSize = levels_[static_cast<std::size_t>(level - 1)].size;
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx)
                    if (2 * x + dx < fineSize && 2 * y + dy < fineSize)
                        visitNode(level - 1, face, 2 * x + dx, 2 * y + dy, focus, accuracy, visit);
        } else {
            // A base texel: its radiance is constant over it (the environment as decoded), so
            // split its area, not its value.
            const double n = l.size;
            const glm::dvec3 radiance = l.energy[i] / texelSolidAngle(x, y, l.size);
            visitTexelPart(static_cast<Face>(face), x / n, (x + 1) / n, y / n, (y + 1) / n, radiance, focus, accuracy,
                           texelDepthFor(r, focus, accuracy), visit);
        }
        return;
    }
    visit(l.direction[i], l.energy[i]);
}

void RadianceTree::walk(const Focus& focus, const Visit& visit, const Accuracy& accuracy) const {
    if (levels_.empty()) return;
    const int top = static_cast<int>(levels_.size()) - 1;
    const int size = levels_.back().size;
    for (int face = 0; face < kFaceCount; ++face)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) visitNode(top, face, x, y, focus, accuracy, visit);
}

std::size_t RadianceTree::walkCount(const Focus& focus, const Accuracy& accuracy) const {
    std::size_t count = 0;
    walk(focus, [&count](const glm::dvec3&, const glm::dvec3&) { ++count; }, accuracy);
    return count;
}

}  // namespace mipgloss
