// Private: the normalized-Phong-lobe convolution machinery shared by the `phong` and `reference`
// builders and by irradiance (n = 1).
//
// The sphere is represented by source texels, each a point carrying energy. Geometry is stored in
// a face-local frame (a, b, c) = (sc, tc, 1)/|(sc, tc, 1)|, identical for the six faces, so one
// array serves all faces; a direction R is rotated into each face's frame once per output texel.
//
// Culling: source texels are grouped in square nodes; each node has a bounding cone on the
// sphere. For an output direction R and lobe support half-angle α, a breadth-first walk over
// nodes (crossing face edges through resolveTexel, the cube's one edge mechanism) visits exactly
// the connected set of nodes whose cones meet the support cap.
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace mipgloss::detail {


// Node grid of a source level: nodes of group×group texels on a face of `size` texels.
struct NodeGrid {
    int size = 0;      // source texels per face side
    int group = 1;     // texels per node side (divides size)
    int nodes = 0;     // nodes per face side
    std::vector<glm::vec3> axis;   // 6·nodes², world-space unit cone axis
    std::vector<float> cosRadius;  // nodes², cone half-angle (same on every face)
    std::vector<float> sinRadius;
};
NodeGrid makeNodeGrid(int size);

// A source level: per texel, energy E = Σ Ω·L (RGB) placed at its energy-weighted direction, and
// solid angle Ω placed at its geometric centroid. At the base (`energyDir` empty) both directions
// are the texel centre.
struct LobeSource {
    int size = 0;
    NodeGrid grid;
    std::vector<glm::vec3> geoDir;  // size², face-local unit geometric centroid
    std::vector<float> omega;       // size², solid angle
    std::array<std::vector<Rgb>, 6> energy;          // size² per face
    std::array<std::vector<glm::vec3>, 6> energyDir;  // size² per face, face-local unit; empty at base
    // Unnormalized first moments, kept only to build the next coarser level exactly.
    std::vector<glm::vec3> geoMoment;
    std::array<std::vector<glm::vec3>, 6> energyMoment;
};

// Level 0 source: texel centres and exact solid angles.
LobeSource baseSource(const CubeMap& base);
// Next coarser source (size/2, size must be even): energies and solid angles summed over 2×2,
// directions the normalized first moments (luminance-weighted for energy), so a small bright
// source keeps its true direction however coarse the level.
LobeSource coarsenSource(const LobeSource& fine);

// Lobe support: the cosine below which (R·ω)^n < cutoff.
double supportCosine(double exponent, double cutoff);

// Values on each face's texel grid of `size`, extended by `border` texels on every side onto the
// face's own plane beyond its edges (index -border .. size+border-1).
struct FaceGrid {
    FaceGrid(int s, int b) : size(s), border(b) {
        for (auto& f : values) f.resize(static_cast<std::size_t>(extent()) * static_cast<std::size_t>(extent()));
    }
    int size;
    int border;
    std::array<std::vector<Rgb>, 6> values;
    int extent() const { return size + 2 * border; }
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y + border) * static_cast<std::size_t>(extent()) +
               static_cast<std::size_t>(x + border);
    }
    Rgb& at(Face f, int x, int y) { return values[static_cast<std::size_t>(f)][index(x, y)]; }
    const Rgb& at(Face f, int x, int y) const { return values[static_cast<std::size_t>(f)][index(x, y)]; }
};

// Normalized Phong convolution of `src` at exponent n, evaluated at the texel centres of a
// face grid of `size` (with `border`): Σ w(R·e)·E / Σ w(R·g)·Ω with w = (R·ω)^n cut at `cutoff`
// (float weights from a table, double sums).
FaceGrid convolveGrid(const LobeSource& src, double exponent, int size, int border, double cutoff);

// The same on a cube of outSize, borders filled.
CubeMap convolve(const LobeSource& src, double exponent, int outSize, double cutoff);

// The same sum evaluated on the half-size grid (with a six-texel border beyond the face edges)
// and brought to outSize (even) by cubic B-spline interpolation, clamped at 0: a quarter of the
// cost, for lobes at least 3 output texels wide (σ), whose half-size samples are far above
// their Nyquist rate (docs/chain-schedule.md measures what it costs).
CubeMap convolveUpsampled(const LobeSource& src, double exponent, int outSize, double cutoff);

// The exact sum at the base, in double precision with exact weights exp(n·log(R·ω)), at any
// direction: Σ w(R·ω)·L·Ω / Σ w(R·ω)·Ω over the base texels. Keeps a reference to `base`.
class ExactLobe {
public:
    ExactLobe(const CubeMap& base, double exponent, double cutoff);
    Rgb at(const glm::dvec3& direction) const;  // direction need not be normalized

private:
    const CubeMap& base_;
    double exponent_;
    NodeGrid grid_;
    std::vector<glm::dvec3> dir_;  // face-local texel centres, shared by the six faces
    std::vector<double> omega_;
    double xmax_ = 1.0;
    float cosA_ = 0.0f, sinA_ = 0.0f;
};

// That sum at the texel centres of a face of size outSize, borders filled.
CubeMap convolveExact(const CubeMap& base, double exponent, int outSize, double cutoff);

}  // namespace mipgloss::detail
