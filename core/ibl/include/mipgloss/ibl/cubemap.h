// The cube map value type and the one place that knows OpenGL's face orientation.
//
// Face order and orientation follow the OpenGL 4.5 specification (section 8.13, cube map
// face selection, table 8.19). For a direction r with major axis ma:
//
//     face  sc    tc        the face images laid out as a horizontal cross
//     +X    -rz   -ry       (each face exactly as stored, row 0 at the top):
//     -X    +rz   -ry
//     +Y    +rx   +rz                 +----+
//     -Y    +rx   -rz                 | PY |
//     +Z    +rx   -ry            +----+----+----+----+
//     -Z    -rx   -ry            | NX | PZ | PX | NZ |
//                                +----+----+----+----+
//     s = (sc/|ma| + 1)/2                 | NY |
//     t = (tc/|ma| + 1)/2                 +----+
//
// Texel (x, y) of a face of size M is centred at s = (x + 1/2)/M, t = (y + 1/2)/M; row y = 0 is
// t = 0. Every sampler, builder and importer goes through `directionToFace` and `faceToDirection`.
//
// Edges are handled by one mechanism: each face is stored with a one-texel border (the paper's
// texture borders, done in memory). `makeSeamless` fills the border from the neighbouring faces
// through the two orientation functions, so bilinear sampling never tests bounds. A builder that
// needs a different border (the paper's own construction) writes it directly.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mipgloss {

enum class Face : std::uint8_t { PX = 0, NX = 1, PY = 2, NY = 3, PZ = 4, NZ = 5 };
inline constexpr int kFaceCount = 6;
inline constexpr std::array<Face, 6> kAllFaces{Face::PX, Face::NX, Face::PY,
                                               Face::NY, Face::PZ, Face::NZ};

// The rows of all six faces of a size × size cube as one range, face by face (+X's rows first),
// for loops that hand out rows: cubeRows(size) of them; faceRowOf(row, size) says which face and
// which row of it (the one place that decodes the number).
struct FaceRow {
    Face face;
    int y;
};
inline constexpr int cubeRows(int size) { return kFaceCount * size; }
inline FaceRow faceRowOf(int row, int size) {
    return {kAllFaces[static_cast<std::size_t>(row / size)], row % size};
}

// Short file-name stem for a face: "px", "nx", "py", "ny", "pz", "nz".
const char* faceName(Face f);

using Rgb = glm::vec3;

// A point on a face: s, t in [0, 1] (OpenGL's face coordinates).
struct FaceCoord {
    Face face;
    float s;
    float t;
};

// The table above as a frame per face: a point (s, t) of face f looks along
//     axis + (2s - 1)·u + (2t - 1)·v,
// so sc = r·u, tc = r·v and ma = r·axis for a direction r on that face. Every orientation
// question in mipgloss (both functions below, the lobe filter's face-local frames, the paper's
// unfolded neighbours, the tests' footprint LOD) reads this one table.
struct FaceFrame {
    glm::vec3 u, v, axis;
};
const FaceFrame& faceFrame(Face f);

// Direction (need not be normalized, must be non-zero) -> face and (s, t), per the table above.
FaceCoord directionToFace(const glm::vec3& dir);

// (s, t) of the point where the line along `dir` meets face f's plane (dir·axis > 0). Outside
// [0, 1] when dir is on another face: how GL differentiates face coordinates, and how borders
// find their neighbours.
glm::vec2 faceCoordOnPlane(Face f, const glm::vec3& dir);

// Face and (s, t) -> unit direction. s and t may lie outside [0, 1]: the point is then on the
// face's plane extended beyond the cube, which is how borders find their neighbours.
glm::vec3 faceToDirection(Face face, float s, float t);

// Unit direction through the centre of texel (x, y) of a size-M face.
glm::vec3 texelDirection(Face face, int x, int y, int size);

// Exact solid angle of texel (x, y) of a size-M face (docs/conventions.md, "Solid angles": A(x, y) = atan2(xy, sqrt(x²+y²+1))).
double texelSolidAngle(int x, int y, int size);

// Solid angle of the planar rectangle [u0,u1]×[v0,v1] on a face plane (face coords in [-1, 1]).
double faceRectSolidAngle(double u0, double v0, double u1, double v1);

// Six square float-RGB faces, each stored with a one-texel border.
class CubeMap {
public:
    CubeMap() = default;
    explicit CubeMap(int size, Rgb fill = Rgb(0.0f));

    int size() const { return size_; }
    bool empty() const { return size_ == 0; }

    // Interior texel, 0 <= x, y < size. Border texels are reached with x or y = -1 or size.
    Rgb& at(Face f, int x, int y) { return faces_[idx(f)][offset(x, y)]; }
    const Rgb& at(Face f, int x, int y) const { return faces_[idx(f)][offset(x, y)]; }

    // Fills every face's border from its neighbours (see the header comment). Corner border
    // texels get the mean of the three texels that meet at the cube corner, as GL's seamless
    // filtering does.
    void makeSeamless();

    // Bilinear sample at a direction, crossing face edges through the border.
    Rgb sample(const glm::vec3& dir) const;
    // Bilinear sample at face coordinates (s, t in [0, 1]).
    Rgb sample(Face f, float s, float t) const;

    // Solid-angle weighted mean over the sphere, in double precision.
    glm::dvec3 weightedMean() const;

    // Raw storage of a face including its border, row-major, (size+2)² texels.
    const std::vector<Rgb>& faceStorage(Face f) const { return faces_[idx(f)]; }

private:
    static std::size_t idx(Face f) { return static_cast<std::size_t>(f); }
    std::size_t offset(int x, int y) const {
        return static_cast<std::size_t>(y + 1) * static_cast<std::size_t>(size_ + 2) +
               static_cast<std::size_t>(x + 1);
    }

    int size_ = 0;
    std::array<std::vector<Rgb>, 6> faces_;
};

// Where an out-of-range texel (x or y equal to -1 or size) of face f lies on the cube: the texel of
// the neighbouring face that contains the direction through its centre on the extended face plane.
struct TexelRef {
    Face face;
    int x;
    int y;
};
TexelRef resolveTexel(Face f, int x, int y, int size);

// The texel of a size-M face that holds the point: floor(s·M), floor(t·M), clamped to the face so
// that s or t = 1 (a point on the far edge) stays on it. The one rule by which a direction belongs
// to exactly one texel.
TexelRef texelOf(const FaceCoord& c, int size);

// A full mip chain, level 0 the base, down to 1×1. Level k has size max(1, floor(N / 2^k)), as in
// OpenGL; a non-power-of-two base keeps that rule.
struct MipChain {
    std::vector<CubeMap> levels;
    int baseSize() const { return levels.empty() ? 0 : levels.front().size(); }
    int levelCount() const { return static_cast<int>(levels.size()); }
};

// Number of levels of a full chain for base size N (1 + floor(log2 N)).
int fullChainLevelCount(int baseSize);
// Size of level k for base N.
int levelSize(int baseSize, int level);

}  // namespace mipgloss
