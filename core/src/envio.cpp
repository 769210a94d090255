#include "mipgloss/envio.h"

#include "mipgloss/parallel.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

namespace mipgloss {

namespace fs = std::filesystem;

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

namespace {

constexpr double kPi = std::numbers::pi;

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// "+X", "-X", ... for messages.
const char* faceLabel(Face f) {
    static constexpr const char* kLabels[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    return kLabels[static_cast<int>(f)];
}

// ---------------------------------------------------------------------------------------------
// Images: decoded to linear float RGB and sanitised, row 0 at the top.

struct Image {
    int width = 0;
    int height = 0;
    std::vector<Rgb> px;
    const Rgb& at(int x, int y) const {
        return px[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)];
    }
};

// The exact sRGB EOTF (IEC 61966-2-1), in double.
float srgbToLinear(double c) {
    return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

const std::vector<float>& srgbTable(int bits) {
    static const std::vector<float> t8 = [] {
        std::vector<float> t(256);
        for (std::size_t i = 0; i < t.size(); ++i) t[i] = srgbToLinear(static_cast<double>(i) / 255.0);
        return t;
    }();
    static const std::vector<float> t16 = [] {
        std::vector<float> t(65536);
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = srgbToLinear(static_cast<double>(i) / 65535.0);
        return t;
    }();
    return bits == 8 ? t8 : t16;
}

struct SanitiseCounts {
    std::size_t nan = 0, inf = 0, negative = 0;
};

// NaN -> 0, negative (including -Inf) -> 0, +Inf -> the largest finite value of the image.
SanitiseCounts sanitise(std::vector<Rgb>& px) {
    SanitiseCounts n;
    float maxFinite = 0.0f;
    for (const Rgb& p : px)
        for (int c = 0; c < 3; ++c)
            if (std::isfinite(p[c])) maxFinite = std::max(maxFinite, p[c]);
    for (Rgb& p : px) {
        for (int c = 0; c < 3; ++c) {
            float& v = p[c];
            if (std::isnan(v)) {
                v = 0.0f;
                ++n.nan;
            } else if (v < 0.0f) {
                v = 0.0f;
                ++n.negative;
            } else if (std::isinf(v)) {
                v = maxFinite;
                ++n.inf;
            }
        }
    }
    return n;
}

void addCounts(ImportReport& report, const fs::path& file, const SanitiseCounts& n) {
    if (n.nan + n.inf + n.negative == 0) return;
    report.nanCount += n.nan;
    report.infCount += n.inf;
    report.negativeCount += n.negative;
    std::ostringstream msg;
    msg << file.string() << ": replaced " << n.nan << " NaN value(s) by 0, " << n.inf
        << " infinite value(s) by the largest finite value and " << n.negative
        << " negative value(s) by 0";
    report.warnings.push_back(msg.str());
}

// Reads the first subimage of an opened input. `name` is what error messages call it.
Image readOpened(OIIO::ImageInput& in, const fs::path& name) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw EnvError(name, "image has no pixels (" + sizeText(spec.width, spec.height) + ")");
    if (spec.depth > 1) throw EnvError(name, "volume images are not environments");
    const int nc = std::min(spec.nchannels, 3);
    const std::size_t count = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
    const auto base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
    const bool integer = base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::INT8 ||
                         base == OIIO::TypeDesc::UINT16 || base == OIIO::TypeDesc::INT16 ||
                         base == OIIO::TypeDesc::UINT32 || base == OIIO::TypeDesc::INT32;

    std::vector<float> values(count * static_cast<std::size_t>(nc));
    auto fail = [&] {
        std::string err = in.geterror();
        if (err.empty()) err = "unknown error";
        return EnvError(name, "cannot read the pixels (corrupt or truncated file?): " + err);
    };
    // LDR formats are sRGB-encoded: decode through an exact table, linear inside from here on.
    if (base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::UINT16) {
        const int bits = base == OIIO::TypeDesc::UINT8 ? 8 : 16;
        const std::vector<float>& table = srgbTable(bits);
        if (bits == 8) {
            std::vector<std::uint8_t> raw(values.size());
            if (!in.read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, raw.data())) throw fail();
            for (std::size_t i = 0; i < raw.size(); ++i) values[i] = table[raw[i]];
        } else {
            std::vector<std::uint16_t> raw(values.size());
            if (!in.read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT16, raw.data())) throw fail();
            for (std::size_t i = 0; i < raw.size(); ++i) values[i] = table[raw[i]];
        }
    } else {
        if (!in.read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, values.data())) throw fail();
        if (integer)
            for (float& v : values) v = srgbToLinear(std::clamp(static_cast<double>(v), 0.0, 1.0));
    }

    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.px.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const float* p = &values[i * static_cast<std::size_t>(nc)];
        // Grey (and grey + alpha) replicate the first channel; a third channel makes RGB.
        img.px[i] = nc >= 3 ? Rgb(p[0], p[1], p[2]) : Rgb(p[0]);
    }
    return img;
}

// Colour as stored: alpha is ignored, so it must not be multiplied in.
const OIIO::ImageSpec& readConfig() {
    static const OIIO::ImageSpec config = [] {
        OIIO::ImageSpec c;
        c.attribute("oiio:UnassociatedAlpha", 1);
        return c;
    }();
    return config;
}

Image readImageFile(const fs::path& file, ImportReport& report) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw EnvError(file, "file not found");
    if (fs::is_directory(file, ec)) throw EnvError(file, "is a directory, expected an image file");
    const auto bytes = fs::file_size(file, ec);
    if (ec) throw EnvError(file, "cannot read the file: " + ec.message());
    if (bytes == 0) throw EnvError(file, "file is empty (0 bytes)");
    auto in = OIIO::ImageInput::open(file.string(), &readConfig());
    if (!in) {
        std::string err = OIIO::geterror();
        if (err.empty()) err = "unknown error";
        throw EnvError(file, "not a readable image: " + err);
    }
    Image img = readOpened(*in, file);
    in->close();
    addCounts(report, file, sanitise(img.px));
    report.files.push_back(file);
    return img;
}

// ---------------------------------------------------------------------------------------------
// Face-naming families.

struct Family {
    const char* description;
    std::array<const char*, 6> tokens;  // GL order +X -X +Y -Y +Z -Z
};
// right/left/top/bottom/front/back and rt/lf/up/dn/ft/bk map right=+X, top=+Y, front=+Z.
constexpr std::array<Family, 4> kFamilies{{
    {"px/nx/py/ny/pz/nz", {"px", "nx", "py", "ny", "pz", "nz"}},
    {"posx/negx/posy/negy/posz/negz", {"posx", "negx", "posy", "negy", "posz", "negz"}},
    {"right/left/top/bottom/front/back", {"right", "left", "top", "bottom", "front", "back"}},
    {"rt/lf/up/dn/ft/bk", {"rt", "lf", "up", "dn", "ft", "bk"}},
}};

// A guess that a stem is `prefix + token` of a family.
struct FaceName {
    int family;
    std::string prefix;  // lower case
};

// Every way a (lower-case) stem can be read as a family member, longest token first.
std::vector<FaceName> familyReadings(const std::string& stemLower) {
    std::vector<std::pair<std::size_t, FaceName>> found;
    for (int fam = 0; fam < static_cast<int>(kFamilies.size()); ++fam) {
        for (const char* token : kFamilies[static_cast<std::size_t>(fam)].tokens) {
            const std::string t = token;
            if (stemLower.size() >= t.size() &&
                stemLower.compare(stemLower.size() - t.size(), t.size(), t) == 0)
                found.push_back({t.size(), {fam, stemLower.substr(0, stemLower.size() - t.size())}});
        }
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<FaceName> out;
    for (auto& f : found) out.push_back(std::move(f.second));
    return out;
}

const std::set<std::string>& imageExtensions() {
    static const std::set<std::string> exts = [] {
        std::set<std::string> e;
        // "openexr:exr,sxr,mxr;jpeg:jpg,jpe,jpeg,jif,jfif,jfi;..."
        const std::string list = OIIO::get_string_attribute("extension_list");
        std::size_t pos = 0;
        while (pos < list.size()) {
            const std::size_t end = std::min(list.find(';', pos), list.size());
            const std::string entry = list.substr(pos, end - pos);
            const std::size_t colon = entry.find(':');
            std::size_t p = colon == std::string::npos ? 0 : colon + 1;
            while (p < entry.size()) {
                const std::size_t comma = std::min(entry.find(',', p), entry.size());
                if (comma > p) e.insert("." + lower(entry.substr(p, comma - p)));
                p = comma + 1;
            }
            pos = end + 1;
        }
        for (const char* x : {".exr", ".hdr", ".png", ".jpg", ".jpeg", ".tif", ".tiff"}) e.insert(x);
        return e;
    }();
    return exts;
}

// Image files of a folder by lower-case stem.
std::map<std::string, std::vector<fs::path>> imagesByStem(const fs::path& dir) {
    std::map<std::string, std::vector<fs::path>> out;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        if (!entry.is_regular_file(ec)) continue;
        const fs::path& p = entry.path();
        if (!imageExtensions().count(lower(p.extension().string()))) continue;
        out[lower(p.stem().string())].push_back(p);
    }
    for (auto& [stem, files] : out) std::sort(files.begin(), files.end());
    return out;
}

struct FaceSet {
    std::array<fs::path, 6> files;  // GL order as named (before any handedness change)
    int found = 0;
};

FaceSet lookUpFaces(const std::map<std::string, std::vector<fs::path>>& byStem, const FaceName& name,
                    const std::string& preferredExt) {
    FaceSet set;
    const Family& fam = kFamilies[static_cast<std::size_t>(name.family)];
    for (std::size_t i = 0; i < 6; ++i) {
        const auto it = byStem.find(name.prefix + fam.tokens[i]);
        if (it == byStem.end()) continue;
        fs::path pick = it->second.front();
        for (const fs::path& p : it->second)
            if (lower(p.extension().string()) == preferredExt) pick = p;
        set.files[i] = pick;
        ++set.found;
    }
    return set;
}

[[noreturn]] void throwMissingFaces(const fs::path& where, const FaceSet& set, const FaceName& name,
                                   Handedness handedness) {
    const Family& fam = kFamilies[static_cast<std::size_t>(name.family)];
    std::string reason;
    for (std::size_t i = 0; i < 6; ++i) {
        if (!set.files[i].empty()) continue;
        Face face = kAllFaces[i];
        if (handedness == Handedness::Left && (face == Face::PZ || face == Face::NZ))
            face = face == Face::PZ ? Face::NZ : Face::PZ;
        if (!reason.empty()) reason += "; ";
        reason += std::string("missing face ") + faceLabel(face) + ": no file named " +
                  name.prefix + fam.tokens[i] + ".<image extension>";
    }
    reason += " (naming family " + std::string(fam.description) + ")";
    throw EnvError(where, reason);
}

// ---------------------------------------------------------------------------------------------
// Faces and single images -> cube.

// How a square block of an image becomes a face: face texel (x, y) reads image texel T(x, y).
enum class Place {
    AsIs,           // (x, y)
    Mirror,         // (n-1-x, y): left-right
    Rotate180,      // (n-1-x, n-1-y)
    Transpose,      // (y, x)
    AntiTranspose,  // (n-1-y, n-1-x)
};

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

CubeMap cubeFromFaceFiles(const std::array<fs::path, 6>& files, Handedness handedness,
                          ImportReport& report, const ProgressFn& progress) {
    std::array<Image, 6> images;
    for (std::size_t i = 0; i < 6; ++i) {
        images[i] = readImageFile(files[i], report);
        const Image& img = images[i];
        if (img.width != img.height)
            throw EnvError(files[i], "face image is " + sizeText(img.width, img.height) +
                                         ", cube faces must be square");
        if (i > 0 && img.width != images[0].width)
            throw EnvError(files[i], "face image is " + sizeText(img.width, img.height) + " but " +
                                         files[0].string() + " is " +
                                         sizeText(images[0].width, images[0].height) +
                                         "; all six faces must have the same size");
        if (progress) progress(0.9f * static_cast<float>(i + 1) / 6.0f);
    }
    const int n = images[0].width;
    CubeMap cube(n);
    // Right-handed names go to their GL faces as they are. A left-handed skybox is the mirror
    // image: front and back swap, the side faces read mirrored left-right, top anti-transposed
    // and bottom transposed (envio.h gives the measurement and Irrlicht's geometry behind it).
    using enum Face;
    static constexpr std::array<Face, 6> kRightFace{PX, NX, PY, NY, PZ, NZ};
    static constexpr std::array<Place, 6> kRightPlace{Place::AsIs, Place::AsIs, Place::AsIs,
                                                     Place::AsIs, Place::AsIs, Place::AsIs};
    static constexpr std::array<Face, 6> kLeftFace{PX, NX, PY, NY, NZ, PZ};
    static constexpr std::array<Place, 6> kLeftPlace{Place::Mirror, Place::Mirror,
                                                    Place::AntiTranspose, Place::Transpose,
                                                    Place::Mirror, Place::Mirror};
    const bool left = handedness == Handedness::Left;
    for (std::size_t i = 0; i < 6; ++i)
        copyFace(images[i], 0, 0, n, cube, left ? kLeftFace[i] : kRightFace[i],
                 left ? kLeftPlace[i] : kRightPlace[i]);
    return cube;
}

// Where each face sits in a single-image layout, in face-size cells, indexed by GL face.
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
constexpr const char* kAcceptedProportions =
    "accepted proportions: 2:1 lat-long, 4:3 horizontal cross, 3:4 vertical cross, "
    "6:1 horizontal strip, 1:6 vertical strip, or six square face files";

EnvLayout detectLayout(const Image& img, const fs::path& file) {
    // Within 2 % of a known proportion: the layout's own check then names an exact mismatch.
    const double ratio = static_cast<double>(img.width) / static_cast<double>(img.height);
    for (const Proportion& p : kProportions) {
        const double want = static_cast<double>(p.w) / static_cast<double>(p.h);
        if (std::fabs(ratio / want - 1.0) < 0.02) return p.layout;
    }
    throw EnvError(file, "cannot tell the layout of a " + sizeText(img.width, img.height) +
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

// ---------------------------------------------------------------------------------------------
// Lat-long -> cube.
//
// Each cube texel is the solid-angle weighted mean of the lat-long image over its footprint on
// the sphere. The integral is a quadrature: every lat-long pixel is cut into ku × kv strata, the
// image is interpolated bilinearly (wrapping in u) at each stratum's centre, and the stratum
// carries its exact solid angle, Δφ·(cos θ0 − cos θ1). Each stratum belongs to the texel whose
// footprint holds its direction, so the conversion neither aliases (a texel averages every
// stratum it covers) nor leaves holes, and its weighted mean is the image's own. The strata are
// spaced at most half the angular width of the smallest cube texel (a corner texel: (2/N)/3 rad)
// so every texel receives several; a texel that still gets none takes a bilinear sample at its
// centre. Bright pixels are handled apart (BrightSplit below).
//
// The loop gathers rather than scatters: each face row is one task, and a texel visits the
// strata inside a conservative (θ, φ) box around its footprint, so no two tasks write the same
// texel and the result does not depend on the thread count.

struct LatLongSampler {
    int width, height;
    // The image with a row above and below holding the pole values (each the mean of the row
    // next to it), so bilinear interpolation in the first and last half rows runs to the pole's
    // single value instead of clamping, which would smear row 0's variation in φ over the pole.
    std::vector<Rgb> padded;
    int ku, kv;  // strata per pixel in u and v
    int nu, nv;  // total strata across the width and down the height
    struct Column { float cosPhi, sinPhi; int i0, i1; float fx; };
    struct Row { float cosTheta, sinTheta; int p0, p1; float fy; double weight; };
    std::vector<Column> cols;
    std::vector<Row> rows;

    LatLongSampler(const Image& img, int faceSize) : width(img.width), height(img.height) {
        const std::size_t w = static_cast<std::size_t>(width);
        padded.resize(w * static_cast<std::size_t>(height + 2));
        std::copy(img.px.begin(), img.px.end(), padded.begin() + static_cast<std::ptrdiff_t>(w));
        glm::dvec3 top(0.0), bottom(0.0);
        for (int i = 0; i < width; ++i) {
            top += glm::dvec3(img.at(i, 0));
            bottom += glm::dvec3(img.at(i, height - 1));
        }
        std::fill_n(padded.begin(), w, Rgb(top / static_cast<double>(width)));
        std::fill_n(padded.end() - static_cast<std::ptrdiff_t>(w), w, Rgb(bottom / static_cast<double>(width)));

        const double texel = (2.0 / faceSize) / 3.0;  // smallest texel's angular width
        ku = std::max(1, static_cast<int>(std::ceil(2.0 * (2.0 * kPi / width) / texel)));
        kv = std::max(1, static_cast<int>(std::ceil(2.0 * (kPi / height) / texel)));
        nu = width * ku;
        nv = height * kv;
        cols.resize(static_cast<std::size_t>(nu));
        for (int a = 0; a < nu; ++a) {
            const double u = (a + 0.5) / nu;
            const double phi = 2.0 * kPi * (u - 0.5);
            cols[static_cast<std::size_t>(a)] = column(u);
            cols[static_cast<std::size_t>(a)].cosPhi = static_cast<float>(std::cos(phi));
            cols[static_cast<std::size_t>(a)].sinPhi = static_cast<float>(std::sin(phi));
        }
        rows.resize(static_cast<std::size_t>(nv));
        for (int b = 0; b < nv; ++b) {
            const double v = (b + 0.5) / nv;
            Row& r = rows[static_cast<std::size_t>(b)];
            r = row(v);
            r.cosTheta = static_cast<float>(std::cos(kPi * v));
            r.sinTheta = static_cast<float>(std::sin(kPi * v));
            r.weight = std::cos(kPi * b / nv) - std::cos(kPi * (b + 1) / nv);
        }
    }

    // Bilinear interpolation weights at u (wrapping) and v (padded rows; pole rows at v = 0, 1).
    Column column(double u) const {
        const double x = u * width - 0.5;
        const double fl = std::floor(x);
        const int i0 = (static_cast<int>(fl) % width + width) % width;
        return {0.0f, 0.0f, i0, (i0 + 1) % width, static_cast<float>(x - fl)};
    }
    Row row(double v) const {
        const double y = std::clamp(v * height - 0.5, -0.5, height - 0.5);  // row 0's centre at 0
        Row r{};
        if (y < 0.0) {  // between the top pole (y = -1/2) and row 0
            r.p0 = 0;
            r.p1 = 1;
            r.fy = static_cast<float>(2.0 * (y + 0.5));
        } else if (y > height - 1) {  // between the last row and the bottom pole
            r.p0 = height;
            r.p1 = height + 1;
            r.fy = static_cast<float>(2.0 * (y - (height - 1)));
        } else {
            const double fl = std::floor(y);
            r.p0 = static_cast<int>(fl) + 1;
            r.p1 = std::min(r.p0 + 1, height);
            r.fy = static_cast<float>(y - fl);
        }
        return r;
    }

    const Rgb& at(int i, int p) const {
        return padded[static_cast<std::size_t>(p) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)];
    }
    Rgb value(const Column& c, const Row& r) const {
        const Rgb a = at(c.i0, r.p0), b = at(c.i1, r.p0);
        const Rgb d = at(c.i0, r.p1), e = at(c.i1, r.p1);
        return (a * (1.0f - c.fx) + b * c.fx) * (1.0f - r.fy) + (d * (1.0f - c.fx) + e * c.fx) * r.fy;
    }

    // Bilinear sample at a direction (the fallback for a texel without strata).
    Rgb sample(const glm::vec3& dir) const {
        const double u = 0.5 + std::atan2(static_cast<double>(dir.z), static_cast<double>(dir.x)) / (2.0 * kPi);
        const double v = std::acos(std::clamp(static_cast<double>(dir.y), -1.0, 1.0)) / kPi;
        return value(column(u), row(v));
    }
};

void convertTexel(const LatLongSampler& ll, CubeMap& cube, Face f, int x, int y) {
    const int n = cube.size();
    const float inv = 1.0f / static_cast<float>(n);
    // Sample the texel's boundary: extremes of θ and φ over the footprint lie on it unless a
    // pole is inside, which is tested separately.
    constexpr int kPerEdge = 4;
    std::array<glm::vec3, 4 * kPerEdge> boundary;
    for (int i = 0; i < kPerEdge; ++i) {
        const float a = static_cast<float>(i) / kPerEdge;
        const float x0 = static_cast<float>(x), y0 = static_cast<float>(y);
        boundary[static_cast<std::size_t>(i)] = faceToDirection(f, (x0 + a) * inv, y0 * inv);
        boundary[static_cast<std::size_t>(kPerEdge + i)] = faceToDirection(f, (x0 + 1) * inv, (y0 + a) * inv);
        boundary[static_cast<std::size_t>(2 * kPerEdge + i)] = faceToDirection(f, (x0 + 1 - a) * inv, (y0 + 1) * inv);
        boundary[static_cast<std::size_t>(3 * kPerEdge + i)] = faceToDirection(f, x0 * inv, (y0 + 1 - a) * inv);
    }
    const glm::vec3 centre = texelDirection(f, x, y, n);
    const double phiC = std::atan2(static_cast<double>(centre.z), static_cast<double>(centre.x));
    // Azimuths relative to the centre's, compared through a pseudo-angle (monotonic in the angle
    // over (-π, π]) so that only the two extremes need an atan2.
    const double uc = std::cos(phiC), us = std::sin(phiC);
    auto pseudo = [](double sn, double cs) {
        const double d = std::fabs(sn) + std::fabs(cs);
        return d > 0.0 ? std::copysign(1.0 - cs / d, sn) : 0.0;
    };
    // θ from the points of least and greatest y, through atan2 (acos loses digits near the poles);
    // the segment length from the chord (a dot product near 1 loses them too).
    glm::dvec3 top(0.0, -2.0, 0.0), bottom(0.0, 2.0, 0.0);
    double maxChord = 0.0;
    double pMin = 0.0, pMax = 0.0;
    glm::dvec2 atMin(1.0, 0.0), atMax(1.0, 0.0);  // (cos, sin) of the extreme relative azimuths
    for (std::size_t i = 0; i < boundary.size(); ++i) {
        const glm::dvec3 d(boundary[i]);
        if (d.y > top.y) top = d;
        if (d.y < bottom.y) bottom = d;
        const double cs = d.x * uc + d.z * us, sn = d.z * uc - d.x * us;
        const double p = pseudo(sn, cs);
        if (p < pMin) {
            pMin = p;
            atMin = {cs, sn};
        }
        if (p > pMax) {
            pMax = p;
            atMax = {cs, sn};
        }
        maxChord = std::max(maxChord, glm::length(d - glm::dvec3(boundary[(i + 1) % boundary.size()])));
    }
    auto polar = [](const glm::dvec3& d) { return std::atan2(std::hypot(d.x, d.z), d.y); };
    double thetaMin = polar(top);
    double thetaMax = polar(bottom);
    const double dMin = pMin < 0.0 ? std::atan2(atMin.y, atMin.x) : 0.0;
    const double dMax = pMax > 0.0 ? std::atan2(atMax.y, atMax.x) : 0.0;
    const double seg = 2.0 * std::asin(std::min(1.0, 0.5 * maxChord));
    // Between two boundary samples the boundary strays at most seg/2 in angle, so θ at most seg/2
    // and φ at most (seg/2)/sin θ.
    const double margin = 0.5 * seg + 1e-5;
    thetaMin -= margin;
    thetaMax += margin;
    // A pole inside or on the texel: θ reaches 0 (or π) and φ takes every value.
    auto holds = [&](const glm::vec3& pole) {
        const FaceCoord c = directionToFace(pole);
        const float eps = 1e-4f * inv;
        return c.face == f && c.s >= static_cast<float>(x) * inv - eps &&
               c.s <= static_cast<float>(x + 1) * inv + eps && c.t >= static_cast<float>(y) * inv - eps &&
               c.t <= static_cast<float>(y + 1) * inv + eps;
    };
    if (holds({0.0f, 1.0f, 0.0f})) thetaMin = 0.0;
    if (holds({0.0f, -1.0f, 0.0f})) thetaMax = kPi;
    bool fullPhi = thetaMin <= 0.0 || thetaMax >= kPi;
    double phiLo = 0.0, phiHi = 0.0;
    if (!fullPhi) {
        const double sinMin = std::min(std::sin(thetaMin), std::sin(thetaMax));
        const double phiMargin = margin / sinMin;
        phiLo = phiC + dMin - phiMargin;
        phiHi = phiC + dMax + phiMargin;
        fullPhi = phiHi - phiLo >= kPi;
    }
    int aLo = 0, aHi = ll.nu - 1;
    if (!fullPhi) {
        aLo = static_cast<int>(std::floor((phiLo / (2.0 * kPi) + 0.5) * ll.nu - 0.5));
        aHi = static_cast<int>(std::ceil((phiHi / (2.0 * kPi) + 0.5) * ll.nu - 0.5));
        if (aHi - aLo + 1 >= ll.nu) {
            aLo = 0;
            aHi = ll.nu - 1;
        }
    }
    const int bLo = std::max(0, static_cast<int>(std::floor(std::max(thetaMin, 0.0) / kPi * ll.nv - 0.5)));
    const int bHi = std::min(ll.nv - 1, static_cast<int>(std::ceil(std::min(thetaMax, kPi) / kPi * ll.nv - 0.5)));

    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    const float fn = static_cast<float>(n);
    for (int b = bLo; b <= bHi; ++b) {
        const LatLongSampler::Row& r = ll.rows[static_cast<std::size_t>(b)];
        for (int a = aLo; a <= aHi; ++a) {
            const int ai = a < 0 ? a + ll.nu : (a >= ll.nu ? a - ll.nu : a);
            const LatLongSampler::Column& c = ll.cols[static_cast<std::size_t>(ai)];
            const glm::vec3 dir(r.sinTheta * c.cosPhi, r.cosTheta, r.sinTheta * c.sinPhi);
            const FaceCoord fc = directionToFace(dir);
            if (fc.face != f) continue;
            // The same rule as resolveTexel: each direction belongs to exactly one texel.
            const int tx = std::clamp(static_cast<int>(std::floor(fc.s * fn)), 0, n - 1);
            const int ty = std::clamp(static_cast<int>(std::floor(fc.t * fn)), 0, n - 1);
            if (tx != x || ty != y) continue;
            sum += r.weight * glm::dvec3(ll.value(c, r));
            wsum += r.weight;
        }
    }
    cube.at(f, x, y) = wsum > 0.0 ? Rgb(sum / wsum) : ll.sample(centre);
}

// The few pixels far above the image's mean (a sun) carry much of its energy, and the ratio
// Σw·L/Σw above scales each texel's strata by Ω_texel/Σw, which is 1 only up to how the strata
// tile the texel: a percent or two for one stratum's worth of sun. So the image is split into
// min(L, T), converted as above, and the sparse excess max(L - T, 0), whose energy is splatted
// exactly: each excess pixel is cut into sub-strata far smaller than a texel, each carrying its
// exact solid angle times the excess, and a texel adds (its energy)/Ω_texel. Σ Ω·value is then
// the image's own weighted sum for the excess, and constants and smooth images are unaffected.
struct BrightSplit {
    Image clamped;
    struct Pixel { int i, j; Rgb excess; };
    std::vector<Pixel> excess;
};

BrightSplit splitBright(const Image& img) {
    BrightSplit out{img, {}};
    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    std::vector<float> peaks(img.px.size());
    for (int j = 0; j < img.height; ++j) {
        const double w = std::cos(kPi * j / img.height) - std::cos(kPi * (j + 1) / img.height);
        for (int i = 0; i < img.width; ++i) {
            const Rgb& p = img.at(i, j);
            sum += w * glm::dvec3(p);
            wsum += w;
            peaks[static_cast<std::size_t>(j) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(i)] =
                std::max({p.x, p.y, p.z});
        }
    }
    const glm::dvec3 mean = sum / wsum;
    // 16× the brightest channel's mean, raised if need be so that at most 2 % of pixels exceed it.
    float threshold = static_cast<float>(16.0 * std::max({mean.x, mean.y, mean.z}));
    const std::size_t cap = img.px.size() / 50;
    if (cap > 0 && cap < peaks.size()) {
        std::nth_element(peaks.begin(), peaks.end() - static_cast<std::ptrdiff_t>(cap), peaks.end());
        threshold = std::max(threshold, *(peaks.end() - static_cast<std::ptrdiff_t>(cap)));
    }
    if (!(threshold > 0.0f)) return out;
    for (int j = 0; j < img.height; ++j)
        for (int i = 0; i < img.width; ++i) {
            Rgb& p = out.clamped.px[static_cast<std::size_t>(j) * static_cast<std::size_t>(img.width) +
                                    static_cast<std::size_t>(i)];
            if (std::max({p.x, p.y, p.z}) <= threshold) continue;
            out.excess.push_back({i, j, glm::max(p - Rgb(threshold), Rgb(0.0f))});
            p = glm::min(p, Rgb(threshold));
        }
    return out;
}

// Adds the excess pixels' energy to the texels under them (see BrightSplit).
void splatExcess(const std::vector<BrightSplit::Pixel>& pixels, int width, int height, CubeMap& cube) {
    if (pixels.empty()) return;
    const int n = cube.size();
    // Sub-strata at most 1/4 of the narrowest texel's width, (2/N)/3.
    const double texel = (2.0 / n) / 3.0;
    const int su = std::max(1, static_cast<int>(std::ceil(4.0 * (2.0 * kPi / width) / texel)));
    const int sv = std::max(1, static_cast<int>(std::ceil(4.0 * (kPi / height) / texel)));
    using Energy = std::vector<std::pair<std::uint64_t, glm::dvec3>>;
    const int chunks = std::min(static_cast<int>(pixels.size()), 64);
    std::vector<Energy> parts(static_cast<std::size_t>(chunks));
    parallelFor(0, chunks, [&](int c) {
        std::map<std::uint64_t, glm::dvec3> acc;
        // Neighbouring sub-strata mostly share a texel: sum runs before touching the map.
        std::uint64_t runKey = std::numeric_limits<std::uint64_t>::max();
        glm::dvec3 run(0.0);
        const std::size_t begin = pixels.size() * static_cast<std::size_t>(c) / static_cast<std::size_t>(chunks);
        const std::size_t end = pixels.size() * static_cast<std::size_t>(c + 1) / static_cast<std::size_t>(chunks);
        for (std::size_t k = begin; k < end; ++k) {
            const BrightSplit::Pixel& p = pixels[k];
            const double dphi = 2.0 * kPi / (static_cast<double>(width) * su);
            for (int b = 0; b < sv; ++b) {
                const double t0 = kPi * (p.j + static_cast<double>(b) / sv) / height;
                const double t1 = kPi * (p.j + static_cast<double>(b + 1) / sv) / height;
                const double w = dphi * (std::cos(t0) - std::cos(t1));
                const double theta = 0.5 * (t0 + t1);
                for (int a = 0; a < su; ++a) {
                    const double phi = 2.0 * kPi * ((p.i + (a + 0.5) / su) / width - 0.5);
                    const glm::vec3 dir(static_cast<float>(std::sin(theta) * std::cos(phi)),
                                        static_cast<float>(std::cos(theta)),
                                        static_cast<float>(std::sin(theta) * std::sin(phi)));
                    const FaceCoord fc = directionToFace(dir);
                    const int tx = std::clamp(static_cast<int>(std::floor(fc.s * static_cast<float>(n))), 0, n - 1);
                    const int ty = std::clamp(static_cast<int>(std::floor(fc.t * static_cast<float>(n))), 0, n - 1);
                    const std::uint64_t key = (static_cast<std::uint64_t>(fc.face) * static_cast<std::uint64_t>(n) +
                                               static_cast<std::uint64_t>(ty)) * static_cast<std::uint64_t>(n) +
                                              static_cast<std::uint64_t>(tx);
                    if (key != runKey) {
                        if (runKey != std::numeric_limits<std::uint64_t>::max()) acc[runKey] += run;
                        runKey = key;
                        run = glm::dvec3(0.0);
                    }
                    run += w * glm::dvec3(p.excess);
                }
            }
        }
        if (runKey != std::numeric_limits<std::uint64_t>::max()) acc[runKey] += run;
        parts[static_cast<std::size_t>(c)].assign(acc.begin(), acc.end());
    });
    const std::uint64_t un = static_cast<std::uint64_t>(n);
    for (const Energy& part : parts)
        for (const auto& [key, energy] : part) {
            const int x = static_cast<int>(key % un), y = static_cast<int>((key / un) % un);
            const Face f = kAllFaces[static_cast<std::size_t>(key / (un * un))];
            cube.at(f, x, y) += Rgb(energy / texelSolidAngle(x, y, n));
        }
}

CubeMap latLongToCube(const Image& img, int faceSize, const ProgressFn& progress, float p0, float p1) {
    const BrightSplit split = splitBright(img);
    const LatLongSampler ll(split.clamped, faceSize);
    CubeMap cube(faceSize);
    const int rowsTotal = 6 * faceSize;
    // Chunks so that progress is reported from the calling thread only.
    const int chunks = std::min(rowsTotal, 20);
    for (int c = 0; c < chunks; ++c) {
        const int begin = rowsTotal * c / chunks, end = rowsTotal * (c + 1) / chunks;
        parallelFor(begin, end, [&](int row) {
            const Face f = kAllFaces[static_cast<std::size_t>(row / faceSize)];
            const int y = row % faceSize;
            for (int x = 0; x < faceSize; ++x) convertTexel(ll, cube, f, x, y);
        });
        if (progress) progress(p0 + (p1 - p0) * static_cast<float>(c + 1) / static_cast<float>(chunks));
    }
    splatExcess(split.excess, img.width, img.height, cube);
    return cube;
}

// ---------------------------------------------------------------------------------------------

ImportedEnvironment finish(CubeMap cube, ImportReport report, int faceSize, const ProgressFn& progress) {
    if (faceSize > 0 && faceSize != cube.size()) cube = resampleCube(cube, faceSize);
    cube.makeSeamless();
    if (progress) progress(1.0f);
    return {std::move(cube), std::move(report)};
}

ImportedEnvironment fromSingleImage(const Image& img, const fs::path& file, const ImportOptions& options,
                                    ImportReport report, const ProgressFn& progress) {
    EnvLayout layout = options.layout;
    if (layout == EnvLayout::Auto) layout = detectLayout(img, file);
    report.layout = layout;
    if (layout == EnvLayout::LatLong) {
        const int n = options.faceSize > 0 ? options.faceSize : std::max(1, img.width / 4);
        CubeMap cube = latLongToCube(img, n, progress, 0.3f, 0.95f);
        return finish(std::move(cube), std::move(report), 0, progress);
    }
    CubeMap cube = cubeFromLayout(img, layout, file);
    if (progress) progress(0.5f);
    return finish(std::move(cube), std::move(report), options.faceSize, progress);
}

ImportedEnvironment fromFaces(const std::array<fs::path, 6>& files, const ImportOptions& options,
                              ImportReport report, const ProgressFn& progress) {
    report.layout = EnvLayout::Faces;
    CubeMap cube = cubeFromFaceFiles(files, options.handedness, report, progress);
    return finish(std::move(cube), std::move(report), options.faceSize, progress);
}

ImportedEnvironment loadDirectory(const fs::path& dir, const ImportOptions& options,
                                  const ProgressFn& progress) {
    if (options.layout != EnvLayout::Auto && options.layout != EnvLayout::Faces)
        throw EnvError(dir, std::string("is a folder; layout ") + layoutName(options.layout) +
                                " needs a single image file");
    const auto byStem = imagesByStem(dir);
    // Every (family, prefix) that some file in the folder could belong to.
    std::vector<std::pair<FaceName, FaceSet>> groups;
    std::set<std::pair<int, std::string>> seen;
    for (const auto& [stem, files] : byStem) {
        for (const FaceName& name : familyReadings(stem)) {
            if (!seen.insert({name.family, name.prefix}).second) continue;
            groups.push_back({name, lookUpFaces(byStem, name, ".exr")});
        }
    }
    if (groups.empty())
        throw EnvError(dir, "no cube face files found; expected six image files named with one of "
                            "the families px/nx/py/ny/pz/nz, posx/negx/posy/negy/posz/negz, "
                            "right/left/top/bottom/front/back, rt/lf/up/dn/ft/bk (any common prefix)");
    // Complete sets first, then the one with the most faces; ties: shorter prefix, family order.
    std::stable_sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) {
        if (a.second.found != b.second.found) return a.second.found > b.second.found;
        if (a.first.prefix.size() != b.first.prefix.size())
            return a.first.prefix.size() < b.first.prefix.size();
        return a.first.family < b.first.family;
    });
    const auto& [name, set] = groups.front();
    if (set.found < 6) throwMissingFaces(dir, set, name, options.handedness);
    ImportReport report;
    int complete = 0;
    for (const auto& g : groups) complete += g.second.found == 6 ? 1 : 0;
    if (complete > 1)
        report.warnings.push_back(dir.string() + ": several complete sets of face files; using " +
                                  set.files[0].filename().string() + " and its siblings");
    return fromFaces(set.files, options, std::move(report), progress);
}

}  // namespace

// ---------------------------------------------------------------------------------------------

ImportedEnvironment loadEnvironment(const fs::path& path, const ImportOptions& options,
                                    const ProgressFn& progress) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw EnvError(path, "file not found");
    if (progress) progress(0.0f);
    if (fs::is_directory(path, ec)) return loadDirectory(path, options, progress);

    // A member of a face-naming family with siblings next to it is one face of six.
    const bool mayBeFace = options.layout == EnvLayout::Auto || options.layout == EnvLayout::Faces;
    if (mayBeFace) {
        const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
        const auto byStem = imagesByStem(dir);
        const std::string ext = lower(path.extension().string());
        std::vector<std::pair<FaceName, FaceSet>> partial;
        for (const FaceName& name : familyReadings(lower(path.stem().string()))) {
            FaceSet set = lookUpFaces(byStem, name, ext);
            if (set.found == 6) return fromFaces(set.files, options, {}, progress);
            partial.push_back({name, std::move(set)});
        }
        std::stable_sort(partial.begin(), partial.end(),
                         [](const auto& a, const auto& b) { return a.second.found > b.second.found; });
        if (!partial.empty() && (partial.front().second.found > 1 || options.layout == EnvLayout::Faces))
            throwMissingFaces(path, partial.front().second, partial.front().first, options.handedness);
        if (options.layout == EnvLayout::Faces)
            throw EnvError(path, "the name does not belong to a face-naming family "
                                 "(px/nx/..., posx/negx/..., right/left/top/bottom/front/back, "
                                 "rt/lf/up/dn/ft/bk)");
    }

    ImportReport report;
    const Image img = readImageFile(path, report);
    if (progress) progress(0.3f);
    return fromSingleImage(img, path, options, std::move(report), progress);
}

ImportedEnvironment loadEnvironmentFromMemory(std::span<const unsigned char> bytes, const std::string& name,
                                              const ImportOptions& options, const ProgressFn& progress) {
    if (bytes.empty()) throw EnvError(name, "file is empty (0 bytes)");
    if (options.layout == EnvLayout::Faces) throw EnvError(name, "six face files cannot come from memory");
    OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
    // With a configuration, OpenImageIO 2.4 takes the proxy from it, not from the argument.
    OIIO::ImageSpec config = readConfig();
    void* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto in = OIIO::ImageInput::open(name, &config, &reader);
    if (!in) {
        std::string err = OIIO::geterror();
        if (err.empty()) err = "unknown error";
        throw EnvError(name, "not a readable image: " + err);
    }
    ImportReport report;
    Image img = readOpened(*in, name);
    in->close();
    addCounts(report, name, sanitise(img.px));
    report.files.push_back(name);
    if (progress) progress(0.3f);
    return fromSingleImage(img, name, options, std::move(report), progress);
}

// ---------------------------------------------------------------------------------------------
// Resampling.

CubeMap resampleCube(const CubeMap& cube, int size) {
    const int n = cube.size();
    if (size == n) return cube;
    CubeMap out(size);
    if (size > n) {
        // Growing: bilinear through the borders, so samples near an edge see the neighbour.
        CubeMap src = cube;
        src.makeSeamless();
        parallelFor(0, 6 * size, [&](int row) {
            const Face f = kAllFaces[static_cast<std::size_t>(row / size)];
            const int y = row % size;
            const float inv = 1.0f / static_cast<float>(size);
            for (int x = 0; x < size; ++x)
                out.at(f, x, y) = src.sample(f, (static_cast<float>(x) + 0.5f) * inv,
                                             (static_cast<float>(y) + 0.5f) * inv);
        });
    } else {
        // Shrinking: each output texel is the exact solid-angle weighted mean of the source
        // texels under its footprint, partial texels weighted by the solid angle of the overlap.
        const double scale = static_cast<double>(n) / size;
        auto plane = [&](double texels) { return 2.0 * texels / n - 1.0; };
        parallelFor(0, 6 * size, [&](int row) {
            const Face f = kAllFaces[static_cast<std::size_t>(row / size)];
            const int y = row % size;
            const double y0 = y * scale, y1 = (y + 1) * scale;
            for (int x = 0; x < size; ++x) {
                const double x0 = x * scale, x1 = (x + 1) * scale;
                glm::dvec3 sum(0.0);
                double wsum = 0.0;
                const int syEnd = std::min(n, static_cast<int>(std::ceil(y1 - 1e-9)));
                const int sxEnd = std::min(n, static_cast<int>(std::ceil(x1 - 1e-9)));
                for (int sy = static_cast<int>(std::floor(y0)); sy < syEnd; ++sy) {
                    const double oy0 = std::max(y0, static_cast<double>(sy));
                    const double oy1 = std::min(y1, static_cast<double>(sy + 1));
                    if (oy1 <= oy0) continue;
                    for (int sx = static_cast<int>(std::floor(x0)); sx < sxEnd; ++sx) {
                        const double ox0 = std::max(x0, static_cast<double>(sx));
                        const double ox1 = std::min(x1, static_cast<double>(sx + 1));
                        if (ox1 <= ox0) continue;
                        const double w = faceRectSolidAngle(plane(ox0), plane(oy0), plane(ox1), plane(oy1));
                        sum += w * glm::dvec3(cube.at(f, sx, sy));
                        wsum += w;
                    }
                }
                out.at(f, x, y) = Rgb(sum / wsum);
            }
        });
    }
    out.makeSeamless();
    return out;
}

// ---------------------------------------------------------------------------------------------
// Export.

namespace {

void writeFloatImage(const fs::path& file, int width, int height, const std::vector<float>& rgb) {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw EnvError(file, "cannot create an image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    if (!out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) ||
        !out->close())
        throw EnvError(file, "cannot write: " + out->geterror());
}

// OpenEXR's cube map (ImfEnvmap.h, CubeMap::direction) orients the faces differently from GL:
// deriving pixel -> direction from its pixelPosition and direction functions, with (a, b) the
// pixel's position in the face image (a to the right, b down, both in [-1, 1]):
//     +X: ( 1, -b,  a)   -X: (-1, -b, -a)   +Y: ( a,  1, -b)
//     -Y: ( a, -1,  b)   +Z: (-a, -b,  1)   -Z: ( a, -b, -1)
// Against the GL table in cubemap.h, the ±X and ±Z images are GL's mirrored left-right and the
// ±Y images are GL's flipped top to bottom (OpenEXR's cube is GL's seen in a right-handed frame:
// z negated). This maps GL face texel (x, y) to the OpenEXR face image pixel holding the same
// direction.
std::pair<int, int> exrPixelOfGlTexel(Face f, int x, int y, int n) {
    if (f == Face::PY || f == Face::NY) return {x, n - 1 - y};
    return {n - 1 - x, y};
}

constexpr const char* kOrientationNote =
    "Faces stacked top to bottom in the order +X -X +Y -Y +Z -Z, y up, oriented as OpenEXR's "
    "ImfEnvmap CubeMap (the OpenGL cube-map faces with +-X and +-Z mirrored left-right and +-Y "
    "flipped top to bottom). Texel centres follow OpenGL: pixel i of an N-pixel face edge sits at "
    "(i + 0.5)/N across the face, not at i/(N - 1) as ImfEnvmap's CubeMap::direction assumes. The "
    "first mipgloss:levels MIP levels are the exported chain; further levels down to 1x1 faces are "
    "2x2 box averages of the last; rows below the six faces (non-power-of-two sizes) and the "
    "levels OpenEXR's rounding adds below the 1x1 faces (1x3, 1x1) hold the mean colour.";

}  // namespace

void writeFaceImages(const CubeMap& cube, const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw EnvError(dir, "cannot create the folder: " + ec.message());
    const int n = cube.size();
    if (n < 1) throw EnvError(dir, "the cube map is empty");
    std::vector<float> rgb(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * 3);
    for (Face f : kAllFaces) {
        std::size_t i = 0;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const Rgb& p = cube.at(f, x, y);
                rgb[i++] = p.x;
                rgb[i++] = p.y;
                rgb[i++] = p.z;
            }
        writeFloatImage(dir / (std::string(faceName(f)) + ".exr"), n, n, rgb);
    }
}

void writeCubeEnvironmentExr(const MipChain& chain, const fs::path& file) {
    const int n = chain.baseSize();
    if (n < 1) throw EnvError(file, "the mip chain is empty");
    for (int k = 0; k < chain.levelCount(); ++k)
        if (chain.levels[static_cast<std::size_t>(k)].size() != levelSize(n, k))
            throw EnvError(file, "mip level " + std::to_string(k) + " has face size " +
                                     std::to_string(chain.levels[static_cast<std::size_t>(k)].size()) +
                                     ", expected " + std::to_string(levelSize(n, k)));
    if (file.has_parent_path()) {
        std::error_code ec;
        fs::create_directories(file.parent_path(), ec);
    }

    // OpenEXR's MIP levels halve each dimension of the N × 6N image (rounding down) until both are
    // 1, so the file has 1 + floor(log2 6N) levels. Level k holds the faces of size N >> k stacked
    // from the top (ImfEnvmap's sizeOfFace = min(w, h / 6)); chain levels the caller did not give
    // are box-filtered from the last one; levels below the 1×1 faces hold the mean colour.
    std::vector<CubeMap> cubes(chain.levels.begin(), chain.levels.end());
    while (cubes.back().size() > 1) {
        const CubeMap& prev = cubes.back();
        CubeMap next(prev.size() / 2);
        for (Face f : kAllFaces)
            for (int y = 0; y < next.size(); ++y)
                for (int x = 0; x < next.size(); ++x)
                    next.at(f, x, y) = 0.25f * (prev.at(f, 2 * x, 2 * y) + prev.at(f, 2 * x + 1, 2 * y) +
                                                prev.at(f, 2 * x, 2 * y + 1) + prev.at(f, 2 * x + 1, 2 * y + 1));
        cubes.push_back(std::move(next));
    }
    Rgb mean(0.0f);
    for (Face f : kAllFaces) mean += cubes.back().at(f, 0, 0) / 6.0f;

    // OpenEXR whatever the extension: the envmap attribute is OpenEXR's.
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out) throw EnvError(file, "cannot create an OpenEXR writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(n, 6 * n, 3, OIIO::TypeDesc::FLOAT);
    const int tile = std::min(64, n);  // OpenEXR wants one tile size for every level
    spec.tile_width = tile;
    spec.tile_height = tile;
    spec.attribute("compression", "zip");
    spec.attribute("textureformat", "CubeFace Environment");  // -> OpenEXR envmap = cube
    spec.attribute("oiio:updirection", "y");
    spec.attribute("mipgloss:orientation", kOrientationNote);
    spec.attribute("mipgloss:levels", chain.levelCount());
    auto fail = [&](const std::string& what) { return EnvError(file, what + ": " + out->geterror()); };
    if (!out->open(file.string(), spec, OIIO::ImageOutput::Create)) throw fail("cannot open for writing");

    int w = n, h = 6 * n;
    for (int level = 0;; ++level) {
        if (level > 0) {
            OIIO::ImageSpec ls = spec;
            ls.width = ls.full_width = w;
            ls.height = ls.full_height = h;
            if (!out->open(file.string(), ls, OIIO::ImageOutput::AppendMIPLevel))
                throw fail("cannot add MIP level " + std::to_string(level));
        }
        std::vector<float> rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
        auto put = [&](int px, int py, const Rgb& v) {
            const std::size_t i = (static_cast<std::size_t>(py) * static_cast<std::size_t>(w) +
                                   static_cast<std::size_t>(px)) * 3;
            rgb[i] = v.x;
            rgb[i + 1] = v.y;
            rgb[i + 2] = v.z;
        };
        if (level < static_cast<int>(cubes.size())) {
            const CubeMap& c = cubes[static_cast<std::size_t>(level)];
            const int m = c.size();
            for (int py = 6 * m; py < h; ++py)  // rows below the faces (non-power-of-two bases)
                for (int px = 0; px < w; ++px) put(px, py, mean);
            for (std::size_t fi = 0; fi < 6; ++fi) {
                const Face f = kAllFaces[fi];
                for (int y = 0; y < m; ++y)
                    for (int x = 0; x < m; ++x) {
                        const auto [ex, ey] = exrPixelOfGlTexel(f, x, y, m);
                        put(ex, static_cast<int>(fi) * m + ey, c.at(f, x, y));
                    }
            }
        } else {
            for (int py = 0; py < h; ++py)
                for (int px = 0; px < w; ++px) put(px, py, mean);
        }
        if (!out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()))
            throw fail("cannot write MIP level " + std::to_string(level));
        if (w == 1 && h == 1) break;
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    if (!out->close()) throw fail("cannot finish the file");
}

MipChain readCubeEnvironmentExr(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw EnvError(file, "file not found");
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) throw EnvError(file, "not a readable image: " + OIIO::geterror());
    if (!OIIO::Strutil::iequals(in->spec().get_string_attribute("textureformat"), "CubeFace Environment"))
        throw EnvError(file, "not a cube-face environment map (no envmap=cube attribute)");
    const int levels = in->spec().get_int_attribute("mipgloss:levels", 0);
    MipChain chain;
    for (int level = 0; in->seek_subimage(0, level); ++level) {
        const OIIO::ImageSpec& spec = in->spec();
        const int m = std::min(spec.width, spec.height / 6);
        if (m < 1 || (levels > 0 && level >= levels)) break;
        if (level > 0 && m != levelSize(chain.baseSize(), level)) break;
        const int nc = std::min(spec.nchannels, 3);
        std::vector<float> px(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                              static_cast<std::size_t>(nc));
        if (!in->read_image(0, level, 0, nc, OIIO::TypeDesc::FLOAT, px.data()))
            throw EnvError(file, "cannot read MIP level " + std::to_string(level) + ": " + in->geterror());
        CubeMap c(m);
        for (std::size_t fi = 0; fi < 6; ++fi) {
            const Face f = kAllFaces[fi];
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x) {
                    const auto [ex, ey] = exrPixelOfGlTexel(f, x, y, m);
                    const std::size_t i = (static_cast<std::size_t>(static_cast<int>(fi) * m + ey) *
                                               static_cast<std::size_t>(spec.width) +
                                           static_cast<std::size_t>(ex)) *
                                          static_cast<std::size_t>(nc);
                    Rgb v = nc >= 3 ? Rgb(px[i], px[i + 1], px[i + 2]) : Rgb(px[i]);
                    for (int ch = 0; ch < 3; ++ch)
                        if (!(v[ch] >= 0.0f) || std::isinf(v[ch])) v[ch] = 0.0f;
                    c.at(f, x, y) = v;
                }
        }
        c.makeSeamless();
        chain.levels.push_back(std::move(c));
        if (m == 1) break;
    }
    if (chain.levels.empty()) throw EnvError(file, "holds no cube faces");
    return chain;
}

}  // namespace mipgloss
