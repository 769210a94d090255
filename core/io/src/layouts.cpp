#include "layouts.h"

#include "text.h"

#include <array>
#include <cmath>
#include <string>

namespace mipgloss {

const char* layoutName(EnvLayout layout) {
    switch (layout) {
        case EnvLayout::Auto: return "auto";
        case EnvLayout::Faces: return "faces";
        case EnvLayout::HorizontalCross: return "hcross";
        case EnvLayout::VerticalCross: return "vcross";
        case EnvLayout::HorizontalStrip: return "hstrip";
        case EnvLayout::VerticalStrip: return "vstrip";
        case EnvLayout::LatLong: return "latlong";
    }
    return "auto";
}

bool parseLayout(const std::string& text, EnvLayout& out) {
    static constexpr EnvLayout kAll[] = {EnvLayout::Auto,          EnvLayout::Faces,
                                         EnvLayout::HorizontalCross, EnvLayout::VerticalCross,
                                         EnvLayout::HorizontalStrip, EnvLayout::VerticalStrip,
                                         EnvLayout::LatLong};
    for (EnvLayout l : kAll) {
        if (text == layoutName(l)) {
            out = l;
            return true;
        }
    }
    return false;
}

const char* handednessName(Handedness h) { return h == Handedness::Left ? "left" : "right"; }

bool parseHandedness(const std::string& text, Handedness& out) {
    for (Handedness h : {Handedness::Right, Handedness::Left}) {
        if (text == handednessName(h)) {
            out = h;
            return true;
        }
    }
    return false;
}

namespace io_detail {

namespace fs = std::filesystem;

void copyFace(const Image& img, int x0, int y0, int n, CubeMap& cube, Face f, Place place) {
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            int sx = x, sy = y;
            switch (place) {
                case Place::AsIs: break;
                case Place::Mirror: sx = n - 1 - x; break;
                case Place::Rotate180: sx = n - 1 - x; sy = n - 1 - y; break;
                case Place::Transpose: sx = y; sy = x; break;
                case Place::AntiTranspose: sx = n - 1 - y; sy = n - 1 - x; break;
            }
            cube.at(f, x, y) = img.at(x0 + sx, y0 + sy);
        }
    }
}


// Where each face sits in a single-image layout, in face-size cells, indexed by GL face.
namespace {

struct Cell {
    int col, row;
    Place place;
};
using Cells = std::array<Cell, 6>;

struct Proportion {
    EnvLayout layout;
    int w, h;
    const char* description;
    Cells cells;  // unused for lat-long
};
constexpr Place kAsIs = Place::AsIs;
constexpr Proportion kProportions[] = {
    {EnvLayout::LatLong, 2, 1, "lat-long", {}},
    // Exactly the picture in cubemap.h: PY above PZ, row NX PZ PX NZ, NY below PZ.
    {EnvLayout::HorizontalCross, 4, 3, "horizontal cross",
     {{{2, 1, kAsIs}, {0, 1, kAsIs}, {1, 0, kAsIs}, {1, 2, kAsIs}, {1, 1, kAsIs}, {3, 1, kAsIs}}}},
    // Its middle column, with -Z hung below -Y turned 180° so that its edge meets -Y's.
    {EnvLayout::VerticalCross, 3, 4, "vertical cross",
     {{{2, 1, kAsIs}, {0, 1, kAsIs}, {1, 0, kAsIs}, {1, 2, kAsIs}, {1, 1, kAsIs}, {1, 3, Place::Rotate180}}}},
    {EnvLayout::HorizontalStrip, 6, 1, "horizontal strip",
     {{{0, 0, kAsIs}, {1, 0, kAsIs}, {2, 0, kAsIs}, {3, 0, kAsIs}, {4, 0, kAsIs}, {5, 0, kAsIs}}}},
    {EnvLayout::VerticalStrip, 1, 6, "vertical strip",
     {{{0, 0, kAsIs}, {0, 1, kAsIs}, {0, 2, kAsIs}, {0, 3, kAsIs}, {0, 4, kAsIs}, {0, 5, kAsIs}}}},
};
}  // namespace

constexpr const char* kAcceptedProportions =
    "accepted proportions: 2:1 lat-long, 4:3 horizontal cross, 3:4 vertical cross, "
    "6:1 horizontal strip, 1:6 vertical strip, or six square face files";

EnvLayout detectLayout(int width, int height, const fs::path& file) {
    // Within 2 % of a known proportion: the layout's own check then names an exact mismatch.
    const double ratio = static_cast<double>(width) / static_cast<double>(height);
    for (const Proportion& p : kProportions) {
        const double want = static_cast<double>(p.w) / static_cast<double>(p.h);
        if (std::fabs(ratio / want - 1.0) < 0.02) return p.layout;
    }
    throw EnvError(file, "cannot tell the layout of a " + sizeText(width, height) +
                             " image; " + kAcceptedProportions);
}

CubeMap cubeFromLayout(const Image& img, EnvLayout layout, const fs::path& file) {
    const Proportion* prop = nullptr;
    for (const Proportion& p : kProportions)
        if (p.layout == layout) prop = &p;
    const int n = img.width / prop->w;
    if (n < 1 || img.width != n * prop->w || img.height != n * prop->h)
        throw EnvError(file, std::string("a ") + prop->description + " image must be " +
                                 std::to_string(prop->w) + ":" + std::to_string(prop->h) +
                                 " with square faces (width divisible by " +
                                 std::to_string(prop->w) + "), but this one is " +
                                 sizeText(img.width, img.height));
    CubeMap cube(n);
    for (std::size_t i = 0; i < 6; ++i) {
        const Cell& c = prop->cells[i];
        copyFace(img, c.col * n, c.row * n, n, cube, kAllFaces[i], c.place);
    }
    return cube;
}
}  // namespace io_detail
}  // namespace mipgloss
