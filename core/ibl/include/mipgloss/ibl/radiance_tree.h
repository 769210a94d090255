// The environment as a tree of texel groups, for integrating any lobe against it to a stated
// accuracy in a few thousand terms instead of 6N² (docs/material-truth.md): the independent
// integrator behind the truth of a material (material_truth.h). It shares nothing with the
// renderer's filters (lobe_filter.h, lobes.h) but the decoded base cube.
//
// Level 0 is the base: one node per texel, its energy Ω·L at its centre. Each coarser level
// groups 2×2 nodes of a face: energy summed, placed at the luminance-weighted mean direction of
// its children (so a sun inside a coarse node stays where it is), with the node's angular radius
// (the largest angle from its geometric centre to its corners). A walk from the coarsest level
// accepts a node as one point of energy when the integrand cannot vary much across it:
//     radius ≤ tolerance · max(width, angle(node, centre) − radius)
// where `centre` and `width` say where the integrand is sharp (a lobe's peak and angular width:
// a GGX lobe's tail falls as θ⁻⁴, so its relative change across a node at angle θ is about
// 4·radius/θ), and a node the horizon plane cuts is split down to `horizonRadius`. Nodes wholly
// below the horizon are skipped. The sum Σ g(ω_node)·E_node is then the midpoint rule on an
// adapted mesh: exact for a constant environment's total energy at every tolerance, and
// converging as tolerance² where g is smooth (tests/core/ibl/test_material_truth.cpp measures it).
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <glm/vec3.hpp>

#include <functional>
#include <vector>

namespace mipgloss {

// Where the integrand is sharp: a lobe about `centre` (unit) of angular width `width` (radians),
// cut by the plane through the origin with normal `horizon` (unit; what lies below it is not
// visited). A lobe longer than it is wide (GGX's reflected lobe toward grazing: 2α along the plane
// of incidence, 2α·N·v across it) also says `length` (its extent along the plane, from the centre)
// and `across` (unit, normal to that plane): nodes within `length` of the centre and a few widths
// of the plane are split to tolerance · width, as the peak is, not by their distance from the
// centre (which would take the lobe's whole width in one node a few widths along it).
struct RadianceFocus {
    glm::dvec3 centre{0.0, 0.0, 1.0};
    double width = 1.0;
    glm::dvec3 horizon{0.0, 0.0, 1.0};
    double length = 0.0;
    glm::dvec3 across{0.0};
};
struct RadianceAccuracy {
    double tolerance = 0.1;        // radius / distance at which a node is taken whole
    double horizonRadius = 0.004;  // a node the horizon cuts is split down to this radius (radians)
};

class RadianceTree {
public:
    explicit RadianceTree(const CubeMap& base);

    using Focus = RadianceFocus;
    using Accuracy = RadianceAccuracy;
    // Calls visit(direction, energy) once per accepted node: direction unit, energy = Σ Ω·L (RGB).
    using Visit = std::function<void(const glm::dvec3& direction, const glm::dvec3& energy)>;
    void walk(const Focus& focus, const Visit& visit, const Accuracy& accuracy = {}) const;
    // How many nodes walk() accepted at its last call from this thread is not kept (the tree is
    // shared between threads); walkCount() walks again and counts, for the bench and the tests.
    std::size_t walkCount(const Focus& focus, const Accuracy& accuracy = {}) const;

    glm::dvec3 totalEnergy() const;

private:
    struct Level {
        int size = 0;
        std::vector<glm::dvec3> energy;     // 6·size², face-major, row-major
        std::vector<glm::dvec3> direction;  // where the energy is placed (unit)
        std::vector<glm::dvec3> centre;     // geometric centre (unit)
        std::vector<double> sinRadius, radius;
    };
    void visitNode(int level, int face, int x, int y, const Focus& focus, const Accuracy& accuracy,
                   const Visit& visit) const;
    std::vector<Level> levels_;  // [0] the base, then coarser
};

}  // namespace mipgloss
