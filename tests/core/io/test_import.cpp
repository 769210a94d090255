#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"
#include "mipgloss/io/cube_exr.h"
#include "mipgloss/io/latlong.h"
#include "mipgloss/ibl/resample.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <unistd.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = std::numbers::pi;

using test::TempDir;

// Writes interleaved pixels (any OIIO-convertible type) to a file whose format the extension picks.
void writeImage(const fs::path& file, int w, int h, int channels, OIIO::TypeDesc fileType,
                OIIO::TypeDesc dataType, const void* data) {
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(w, h, channels, fileType);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // write colour as given, not divided by alpha
    ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(dataType, data)) << out->geterror();
    ASSERT_TRUE(out->close()) << out->geterror();
}

void writeFloatRgb(const fs::path& file, int w, int h, const std::vector<Rgb>& px) {
    writeImage(file, w, h, 3, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT, px.data());
}

// A value that differs for every face and texel, so misplaced or misoriented faces show.
Rgb marker(int face, int x, int y) {
    return {0.1f + 0.1f * static_cast<float>(face), 0.01f * static_cast<float>(x) + 0.5f,
            0.001f * static_cast<float>(y) + 0.25f};
}

// The face image that marker() paints for face index `face`, n × n.
std::vector<Rgb> markerFace(int face, int n) {
    std::vector<Rgb> px;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) px.push_back(marker(face, x, y));
    return px;
}

// A lat-long image whose pixel centres hold f(direction).
std::vector<Rgb> latLongFromFunction(int w, int h, const std::function<Rgb(const glm::dvec3&)>& f) {
    std::vector<Rgb> px;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) px.push_back(f(latLongDirection((i + 0.5) / w, (j + 0.5) / h)));
    return px;
}

struct LatLong {
    int w = 0, h = 0;
    std::vector<Rgb> px;
};

LatLong readLatLong(const fs::path& file) {
    LatLong ll;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) return ll;
    ll.w = in->spec().width;
    ll.h = in->spec().height;
    ll.px.resize(static_cast<std::size_t>(ll.w) * static_cast<std::size_t>(ll.h));
    in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, ll.px.data());
    return ll;
}

// The lat-long's own solid-angle weighted mean (rows weighted by cos θ0 − cos θ1), negatives
// clamped as the importer does.
glm::dvec3 latLongMean(const LatLong& ll) {
    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    for (int j = 0; j < ll.h; ++j) {
        const double w = std::cos(kPi * j / ll.h) - std::cos(kPi * (j + 1) / ll.h);
        for (int i = 0; i < ll.w; ++i) {
            const Rgb p = glm::max(ll.px[static_cast<std::size_t>(j * ll.w + i)], Rgb(0.0f));
            sum += w * glm::dvec3(p);
            wsum += w;
        }
    }
    return sum / wsum;
}

// The brightest texel's direction.
glm::vec3 brightestDirection(const CubeMap& c) {
    float best = -1.0f;
    glm::vec3 dir(0.0f);
    for (Face f : kAllFaces)
        for (int y = 0; y < c.size(); ++y)
            for (int x = 0; x < c.size(); ++x) {
                const Rgb v = c.at(f, x, y);
                if (v.x + v.y + v.z > best) {
                    best = v.x + v.y + v.z;
                    dir = texelDirection(f, x, y, c.size());
                }
            }
    return dir;
}

// Real HDRIs are converted once per test run (about half a second each at face size 256).
const CubeMap& loadedAsset(const fs::path& file) {
    static std::map<fs::path, CubeMap> cache;
    auto it = cache.find(file);
    if (it == cache.end()) it = cache.emplace(file, loadEnvironment(file).cube).first;
    return it->second;
}

// Expects the loader to throw EnvError naming `file`, with a reason that mentions `needle`.
void expectEnvError(const fs::path& load, const ImportOptions& options, const fs::path& file,
                    const std::string& needle) {
    try {
        loadEnvironment(load, options);
        ADD_FAILURE() << "no EnvError for " << load;
    } catch (const EnvError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what, e.file().string() + ": " + e.reason());
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(e.reason().find(needle), std::string::npos) << what;
    }
}

struct FamilyCase {
    std::string prefix;
    std::array<std::string, 6> names;  // in GL order: +X -X +Y -Y +Z -Z
    std::string ext;
};

void writeFaceFiles(const TempDir& dir, const FamilyCase& fc, int n) {
    for (int i = 0; i < 6; ++i)
        writeFloatRgb(dir / (fc.prefix + fc.names[static_cast<std::size_t>(i)] + fc.ext), n, n,
                      markerFace(i, n));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Face files.

TEST(FaceImport, EveryNamingFamilyPlacesEachFileOnItsGlFace) {
    const std::vector<FamilyCase> cases = {
        {"", {"px", "nx", "py", "ny", "pz", "nz"}, ".exr"},
        {"sky-", {"posx", "negx", "posy", "negy", "posz", "negz"}, ".exr"},
        {"Env_", {"Right", "Left", "Top", "Bottom", "Front", "Back"}, ".tif"},
        {"irrlicht2_", {"RT", "lf", "up", "dn", "ft", "bk"}, ".exr"},
    };
    constexpr int kN = 4;
    for (const FamilyCase& fc : cases) {
        TempDir dir;
        writeFaceFiles(dir, fc, kN);
        // Through any one face file, and through the folder.
        for (const fs::path& load : {dir / (fc.prefix + fc.names[3] + fc.ext), dir.path()}) {
            const ImportedEnvironment env = loadEnvironment(load);
            ASSERT_EQ(env.cube.size(), kN);
            EXPECT_EQ(env.report.layout, EnvLayout::Faces);
            EXPECT_EQ(env.report.files.size(), 6u);
            for (int i = 0; i < 6; ++i)
                for (int y = 0; y < kN; ++y)
                    for (int x = 0; x < kN; ++x)
                        ASSERT_EQ(env.cube.at(kAllFaces[static_cast<std::size_t>(i)], x, y), marker(i, x, y))
                            << fc.names[static_cast<std::size_t>(i)] << " via " << load << " at " << x << "," << y;
        }
    }
}

TEST(FaceImport, LeftHandedSwapsFrontAndBackAndMirrors) {
    TempDir dir;
    const FamilyCase fc{"box_", {"rt", "lf", "up", "dn", "ft", "bk"}, ".exr"};
    constexpr int kN = 5;
    writeFaceFiles(dir, fc, kN);
    ImportOptions options;
    options.handedness = Handedness::Left;
    const CubeMap c = loadEnvironment(dir / "box_ft.exr", options).cube;
    constexpr int m = kN - 1;
    for (int y = 0; y < kN; ++y) {
        for (int x = 0; x < kN; ++x) {
            // File index: rt 0, lf 1, up 2, dn 3, ft 4, bk 5.
            EXPECT_EQ(c.at(Face::PX, x, y), marker(0, m - x, y));
            EXPECT_EQ(c.at(Face::NX, x, y), marker(1, m - x, y));
            EXPECT_EQ(c.at(Face::PY, x, y), marker(2, m - y, m - x));  // anti-transposed
            EXPECT_EQ(c.at(Face::NY, x, y), marker(3, y, x));          // transposed
            EXPECT_EQ(c.at(Face::PZ, x, y), marker(5, m - x, y));      // back -> +Z
            EXPECT_EQ(c.at(Face::NZ, x, y), marker(4, m - x, y));      // front -> -Z
        }
    }
}

TEST(FaceImport, FaceSizeOptionResamplesTheFaces) {
    TempDir dir;
    for (int i = 0; i < 6; ++i)
        writeFloatRgb(dir / (std::string(faceName(kAllFaces[static_cast<std::size_t>(i)])) + ".exr"), 8, 8,
                      std::vector<Rgb>(64, Rgb(0.25f * static_cast<float>(i))));
    ImportOptions options;
    options.faceSize = 3;
    const CubeMap c = loadEnvironment(dir.path(), options).cube;
    ASSERT_EQ(c.size(), 3);
    for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(c.at(kAllFaces[static_cast<std::size_t>(i)], 1, 2).y, 0.25f * static_cast<float>(i), 1e-6f);
}

namespace {
// Mean |difference| across the 12 cube edges divided by the mean between neighbours inside faces.
double seamRatio(const CubeMap& c) {
    auto diff = [](const Rgb& a, const Rgb& b) {
        const Rgb d = glm::abs(a - b);
        return static_cast<double>(d.x + d.y + d.z) / 3.0;
    };
    const int n = c.size();
    double seam = 0.0, inner = 0.0;
    long seamCount = 0, innerCount = 0;
    for (Face f : kAllFaces) {
        for (int i = 0; i < n; ++i) {
            const std::array<std::array<int, 4>, 4> edges{{{0, i, -1, i}, {n - 1, i, n, i}, {i, 0, i, -1}, {i, n - 1, i, n}}};
            for (const auto& e : edges) {
                const TexelRef r = resolveTexel(f, e[2], e[3], n);
                seam += diff(c.at(f, e[0], e[1]), c.at(r.face, r.x, r.y));
                ++seamCount;
            }
            for (int j = 0; j + 1 < n; ++j) {
                inner += diff(c.at(f, j, i), c.at(f, j + 1, i)) + diff(c.at(f, i, j), c.at(f, i, j + 1));
                innerCount += 2;
            }
        }
    }
    return (seam / static_cast<double>(seamCount)) / (inner / static_cast<double>(innerCount));
}
}  // namespace

TEST(FaceImport, Irrlicht2SkyboxIsSeamlessAsLeftHanded) {
    // Measured: right-handed 9.4 (discontinuous), left-handed 1.24 (continuous; the rest is the
    // JPEG and the edge geometry). See import.h and docs/conventions.md, "Handedness".
    const fs::path up = test::asset("cubemaps/irrlicht2/irrlicht2_up.jpg");
    MIPGLOSS_REQUIRE_ASSET(up);
    ImportOptions left;
    left.handedness = Handedness::Left;
    const double rightRatio = seamRatio(loadEnvironment(up).cube);
    const double leftRatio = seamRatio(loadEnvironment(up, left).cube);
    EXPECT_GT(rightRatio, 5.0);
    EXPECT_LT(leftRatio, 1.5);
}

// ---------------------------------------------------------------------------------------------
// Crosses and strips: assembled here from the documented layouts, read back exactly.

namespace {
struct Cell {
    Face face;
    int col, row;
    bool rotate180;
};

// Paints the marker cube into a layout image of cols × rows cells of size n.
std::vector<Rgb> assemble(int cols, int rows, int n, const std::vector<Cell>& cells) {
    std::vector<Rgb> px(static_cast<std::size_t>(cols * n * rows * n), Rgb(-1.0f));
    const int w = cols * n;
    for (const Cell& c : cells)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const int fx = c.rotate180 ? n - 1 - x : x, fy = c.rotate180 ? n - 1 - y : y;
                px[static_cast<std::size_t>((c.row * n + y) * w + c.col * n + x)] =
                    marker(static_cast<int>(c.face), fx, fy);
            }
    // Unused cells stay black, not negative.
    for (Rgb& p : px)
        if (p.x < 0.0f) p = Rgb(0.0f);
    return px;
}

void expectMarkerCube(const CubeMap& c, int n, const std::string& what) {
    ASSERT_EQ(c.size(), n) << what;
    for (Face f : kAllFaces)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                ASSERT_EQ(c.at(f, x, y), marker(static_cast<int>(f), x, y))
                    << what << " face " << faceName(f) << " at " << x << "," << y;
}
}  // namespace

TEST(CrossImport, CrossesAndStripsRoundTripExactly) {
    using enum Face;
    constexpr int kN = 6;
    struct Layout {
        EnvLayout layout;
        int cols, rows;
        std::vector<Cell> cells;
    };
    const std::vector<Layout> layouts = {
        {EnvLayout::HorizontalCross, 4, 3,
         {{PY, 1, 0, false}, {NX, 0, 1, false}, {PZ, 1, 1, false}, {PX, 2, 1, false}, {NZ, 3, 1, false}, {NY, 1, 2, false}}},
        {EnvLayout::VerticalCross, 3, 4,
         {{PY, 1, 0, false}, {NX, 0, 1, false}, {PZ, 1, 1, false}, {PX, 2, 1, false}, {NY, 1, 2, false}, {NZ, 1, 3, true}}},
        {EnvLayout::HorizontalStrip, 6, 1,
         {{PX, 0, 0, false}, {NX, 1, 0, false}, {PY, 2, 0, false}, {NY, 3, 0, false}, {PZ, 4, 0, false}, {NZ, 5, 0, false}}},
        {EnvLayout::VerticalStrip, 1, 6,
         {{PX, 0, 0, false}, {NX, 0, 1, false}, {PY, 0, 2, false}, {NY, 0, 3, false}, {PZ, 0, 4, false}, {NZ, 0, 5, false}}},
    };
    TempDir dir;
    for (const Layout& l : layouts) {
        const fs::path file = dir / (std::string(layoutName(l.layout)) + ".exr");
        writeFloatRgb(file, l.cols * kN, l.rows * kN, assemble(l.cols, l.rows, kN, l.cells));
        const ImportedEnvironment detected = loadEnvironment(file);
        EXPECT_EQ(detected.report.layout, l.layout);
        expectMarkerCube(detected.cube, kN, std::string("auto ") + layoutName(l.layout));
        ImportOptions options;
        options.layout = l.layout;
        expectMarkerCube(loadEnvironment(file, options).cube, kN, layoutName(l.layout));
    }
}

TEST(CrossImport, VerticalCrossIsSeamlessForASmoothEnvironment) {
    // Independent of the test's own layout table: a smooth function assembled as a vertical cross
    // and loaded must be continuous across every edge.
    constexpr int kN = 16;
    const CubeMap truth = test::cubeFromFunction(kN, [](const glm::vec3& d) {
        return Rgb(1.0f) + 0.5f * Rgb(d.x, d.y, d.z);
    });
    std::vector<Rgb> px(static_cast<std::size_t>(3 * kN * 4 * kN), Rgb(0.0f));
    auto put = [&](Face f, int col, int row, bool rot) {
        for (int y = 0; y < kN; ++y)
            for (int x = 0; x < kN; ++x)
                px[static_cast<std::size_t>((row * kN + y) * 3 * kN + col * kN + x)] =
                    rot ? truth.at(f, kN - 1 - x, kN - 1 - y) : truth.at(f, x, y);
    };
    put(Face::PY, 1, 0, false);
    put(Face::NX, 0, 1, false);
    put(Face::PZ, 1, 1, false);
    put(Face::PX, 2, 1, false);
    put(Face::NY, 1, 2, false);
    put(Face::NZ, 1, 3, true);
    TempDir dir;
    writeFloatRgb(dir / "vcross.exr", 3 * kN, 4 * kN, px);
    EXPECT_LT(seamRatio(loadEnvironment(dir / "vcross.exr").cube), 1.5);
}

// ---------------------------------------------------------------------------------------------
// Lat-long.

TEST(LatLongImport, ConstantStaysConstantIncludingThePoles) {
    TempDir dir;
    const Rgb c(0.3f, 0.5f, 0.7f);
    writeFloatRgb(dir / "const.exr", 64, 32, std::vector<Rgb>(64 * 32, c));
    for (int faceSize : {0, 7, 48}) {  // native 16, smaller, much finer than the image
        ImportOptions options;
        options.faceSize = faceSize;
        const ImportedEnvironment env = loadEnvironment(dir / "const.exr", options);
        EXPECT_EQ(env.report.layout, EnvLayout::LatLong);
        const int n = env.cube.size();
        EXPECT_EQ(n, faceSize > 0 ? faceSize : 16);
        for (Face f : kAllFaces)
            for (int y = -1; y <= n; ++y)  // borders included
                for (int x = -1; x <= n; ++x)
                    for (int ch = 0; ch < 3; ++ch)
                        ASSERT_NEAR(env.cube.at(f, x, y)[ch], c[ch], 1e-5f)
                            << "size " << n << " face " << faceName(f) << " at " << x << "," << y;
    }
}

TEST(LatLongImport, LinearEnvironmentGivesLinearFunctionOfTexelDirections) {
    // L = c + a·ω. A texel holds the mean of L over its footprint, c + a·ω̄. With h = 2/N the
    // texel's angular width at a face centre, ω̄ differs from the centre direction by
    //  - second order, ≲ h²/4: the footprint's curvature and its solid-angle density gradient;
    //  - first order from the quadrature: whole strata, spaced at most (h/3)/2 = h/6 (half the
    //    narrowest, corner texel), are assigned to a texel, shifting its centroid ≲ h/12;
    //  - the bilinear lat-long interpolation, ≲ (π/H)²/8, negligible here.
    // Tolerance per channel: |a_row|·(h²/4 + h/12). Measured worst: 0.32, 0.57, 0.84 of it.
    const glm::dvec3 c(1.0, 1.5, 2.0);
    const glm::dmat3 a(0.5, -0.25, 0.125, 0.25, 0.5, -0.5, -0.125, 0.375, 0.25);  // columns
    auto L = [&](const glm::dvec3& d) { return Rgb(c + a * d); };
    TempDir dir;
    writeFloatRgb(dir / "linear.exr", 256, 128, latLongFromFunction(256, 128, L));
    double aNorm = 0.0;  // largest row norm: max over channels of |a_row · ω|
    for (int r = 0; r < 3; ++r) aNorm = std::max(aNorm, glm::length(glm::dvec3(a[0][r], a[1][r], a[2][r])));
    for (int n : {16, 32, 64}) {
        ImportOptions options;
        options.faceSize = n;
        const CubeMap cube = loadEnvironment(dir / "linear.exr", options).cube;
        const double h = 2.0 / n;
        const double tol = aNorm * (h * h / 4.0 + h / 12.0);
        double worst = 0.0;
        for (Face f : kAllFaces)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const Rgb want = L(glm::dvec3(texelDirection(f, x, y, n)));
                    const Rgb got = cube.at(f, x, y);
                    for (int ch = 0; ch < 3; ++ch) {
                        worst = std::max(worst, std::fabs(static_cast<double>(got[ch] - want[ch])));
                        ASSERT_NEAR(got[ch], want[ch], tol)
                            << "N " << n << " face " << faceName(f) << " at " << x << "," << y << " ch " << ch;
                    }
                }
        RecordProperty("worst_error_N" + std::to_string(n), std::to_string(worst / tol));
    }
}

TEST(LatLongImport, WeightedMeanMatchesTheLatLong) {
    // sunrise.exr has a one-pixel sun of ~28000: its energy must survive the conversion too.
    for (const char* name : {"env/sunset.exr", "env/sunrise.exr"}) {
        const fs::path file = test::asset(name);
        MIPGLOSS_REQUIRE_ASSET(file);
        const glm::dvec3 want = latLongMean(readLatLong(file));
        const glm::dvec3 got = loadedAsset(file).weightedMean();
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch] / want[ch], 1.0, 0.005) << name << " channel " << ch;
    }
}

TEST(LatLongImport, SunLandsAboveTheHorizonWhereTheLatLongPutsIt) {
    for (const char* name : {"env/sunset.exr", "env/sunrise.exr"}) {
        const fs::path file = test::asset(name);
        MIPGLOSS_REQUIRE_ASSET(file);
        const LatLong ll = readLatLong(file);
        std::size_t best = 0;
        for (std::size_t i = 0; i < ll.px.size(); ++i) {
            const Rgb p = ll.px[i], q = ll.px[best];
            if (p.x + p.y + p.z > q.x + q.y + q.z) best = i;
        }
        const int bi = static_cast<int>(best) % ll.w, bj = static_cast<int>(best) / ll.w;
        const glm::dvec3 sun = latLongDirection((bi + 0.5) / ll.w, (bj + 0.5) / ll.h);
        EXPECT_GT(sun.y, 0.0) << name;
        const CubeMap& cube = loadedAsset(file);
        const int n = cube.size();
        const glm::dvec3 got(brightestDirection(cube));
        EXPECT_GT(got.y, 0.0) << name;
        // Within two texels (2 · 2/N rad) of the lat-long's sun.
        EXPECT_LT(std::acos(std::min(1.0, glm::dot(got, sun))), 4.0 / n) << name;
        // And the energy within four texels of it is the lat-long's (measured within 0.4 %).
        const double cone = 8.0 / n;
        auto near = [&](const glm::dvec3& d) { return std::acos(std::min(1.0, glm::dot(d, sun))) < cone; };
        double want = 0.0, have = 0.0;
        for (int j = 0; j < ll.h; ++j) {
            const double w = 2.0 * kPi / ll.w * (std::cos(kPi * j / ll.h) - std::cos(kPi * (j + 1) / ll.h));
            for (int i = 0; i < ll.w; ++i) {
                if (!near(latLongDirection((i + 0.5) / ll.w, (j + 0.5) / ll.h))) continue;
                const Rgb p = glm::max(ll.px[static_cast<std::size_t>(j * ll.w + i)], Rgb(0.0f));
                want += w * static_cast<double>(p.x + p.y + p.z);
            }
        }
        for (Face f : kAllFaces)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    if (!near(glm::dvec3(texelDirection(f, x, y, n)))) continue;
                    const Rgb p = cube.at(f, x, y);
                    have += texelSolidAngle(x, y, n) * static_cast<double>(p.x + p.y + p.z);
                }
        EXPECT_NEAR(have / want, 1.0, 0.01) << name;
    }
}

// ---------------------------------------------------------------------------------------------
// Decoding and sanitising.

TEST(ImportDecode, EightBitPngIsSrgbDecoded) {
    TempDir dir;
    // 2:1 grey PNG at 128 -> lat-long -> constant cube at the sRGB EOTF of 128/255.
    const std::vector<std::uint8_t> grey(8 * 4, 128);
    writeImage(dir / "grey.png", 8, 4, 1, OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT8, grey.data());
    const CubeMap c = loadEnvironment(dir / "grey.png").cube;
    for (Face f : kAllFaces)
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(c.at(f, 0, 0)[ch], 0.2158605f, 1e-6f);
    // RGB + alpha: alpha ignored; 0 and 255 map to 0 and 1.
    std::vector<std::uint8_t> rgba;
    for (int i = 0; i < 8 * 4; ++i) rgba.insert(rgba.end(), {0, 128, 255, 17});
    writeImage(dir / "rgba.png", 8, 4, 4, OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT8, rgba.data());
    const Rgb v = loadEnvironment(dir / "rgba.png").cube.at(Face::PZ, 1, 1);
    EXPECT_NEAR(v.x, 0.0f, 1e-6f);
    EXPECT_NEAR(v.y, 0.2158605f, 1e-6f);
    EXPECT_NEAR(v.z, 1.0f, 1e-6f);
}

TEST(ImportDecode, FloatFormatsStayLinearAndSixteenBitIsSrgbDecoded) {
    TempDir dir;
    // Radiance HDR (RGBE: 2.5 and 0.75 are exact) and float TIFF are linear already.
    writeFloatRgb(dir / "env.hdr", 8, 4, std::vector<Rgb>(32, Rgb(2.5f, 0.75f, 0.0f)));
    writeFloatRgb(dir / "env.tif", 8, 4, std::vector<Rgb>(32, Rgb(2.5f, 0.75f, 0.0f)));
    for (const char* name : {"env.hdr", "env.tif"}) {
        const Rgb v = loadEnvironment(dir / name).cube.at(Face::NY, 0, 1);
        EXPECT_NEAR(v.x, 2.5f, 1e-6f) << name;
        EXPECT_NEAR(v.y, 0.75f, 1e-6f) << name;
    }
    // 16-bit PNG: the exact EOTF of 32768/65535 (IEC 61966-2-1: ((c + 0.055)/1.055)^2.4).
    const std::vector<std::uint16_t> grey(8 * 4, 32768);
    writeImage(dir / "grey16.png", 8, 4, 1, OIIO::TypeDesc::UINT16, OIIO::TypeDesc::UINT16, grey.data());
    const double c = 32768.0 / 65535.0;
    const float want = static_cast<float>(std::pow((c + 0.055) / 1.055, 2.4));
    EXPECT_NEAR(loadEnvironment(dir / "grey16.png").cube.at(Face::PX, 0, 0).z, want, 1e-6f);
}

TEST(ImportDecode, NanInfAndNegativeValuesAreReplacedAndCounted) {
    TempDir dir;
    std::vector<Rgb> px(16 * 8, Rgb(0.5f));
    const float inf = std::numeric_limits<float>::infinity();
    px[3].x = std::numeric_limits<float>::quiet_NaN();
    px[9].y = inf;
    px[10].z = inf;
    px[20] = Rgb(-1.0f, 0.5f, -inf);
    px[30].x = 4.0f;  // the largest finite value: +Inf no longer takes it
    const fs::path file = dir / "bad values.exr";
    writeFloatRgb(file, 16, 8, px);
    const ImportedEnvironment env = loadEnvironment(file);
    EXPECT_EQ(env.report.nanCount, 1u);
    EXPECT_EQ(env.report.infCount, 2u);
    EXPECT_EQ(env.report.negativeCount, 2u);
    ASSERT_EQ(env.report.warnings.size(), 1u);
    EXPECT_NE(env.report.warnings[0].find(file.string()), std::string::npos) << env.report.warnings[0];
    const int n = env.cube.size();
    float maxValue = 0.0f;
    for (Face f : kAllFaces)
        for (int y = -1; y <= n; ++y)
            for (int x = -1; x <= n; ++x)
                for (int ch = 0; ch < 3; ++ch) {
                    const float v = env.cube.at(f, x, y)[ch];
                    ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << faceName(f) << " " << x << "," << y;
                    maxValue = std::max(maxValue, v);
                }
    EXPECT_LE(maxValue, 4.0f);
    // The +Inf values became their row neighbours' 0.5 (not the image's largest, 4), and the
    // warning says how much energy each rule changed.
    EXPECT_NE(env.report.warnings[0].find("by the mean of their row neighbours"), std::string::npos) << env.report.warnings[0];
}

TEST(ImportDecode, ReplacingNegativesKeepsTheImagesEnergy) {
    // A held-out HDRI with ringing of its own kind made: every pixel beside a bright one gets a
    // negative lobe of a tenth of it (as a sharpening filter leaves), written as float. The rule
    // takes each negative from the nearest positive values in its row: the sanitised image's sum
    // equals the signed sum of what was written, within float rounding, where clamping to 0 (the
    // old rule) added the negatives' whole magnitude.
    TempDir dir;
    MIPGLOSS_REQUIRE_ASSET(test::asset("env/courtyard.exr"));
    const DecodedImage map = decodeImage(test::asset("env/courtyard.exr"));
    std::vector<Rgb> px = map.px;
    double signedSum = 0.0, negatives = 0.0;
    for (int y = 0; y < map.height; ++y)
        for (int x = 1; x + 1 < map.width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * map.width + x;
            if (map.px[i].x > 20.0f && x % 7 == 0) px[i + 1] = -0.1f * map.px[i];
        }
    for (const Rgb& p : px) {
        signedSum += static_cast<double>(p.x) + p.y + p.z;
        for (int c = 0; c < 3; ++c) negatives += std::max(0.0f, -p[c]);
    }
    ASSERT_GT(negatives, 0.0) << "the map has pixels above 20 to ring beside";
    const fs::path file = dir / "ringing.exr";
    writeFloatRgb(file, map.width, map.height, px);
    ImportReport report;
    const DecodedImage got = decodeImage(file, &report);
    double sum = 0.0;
    for (const Rgb& p : got.px) sum += static_cast<double>(p.x) + p.y + p.z;
    std::printf("[ import ] ringing: negatives %.4g of a signed sum %.6g (%.3f %%); sanitised sum %.6g (%.2e off); "
                "%s\n", negatives, signedSum, 100.0 * negatives / signedSum, sum, (sum - signedSum) / signedSum,
                report.warnings.empty() ? "" : report.warnings[0].c_str());
    EXPECT_NEAR(sum / signedSum, 1.0, 1e-5);
    EXPECT_GT(report.negativeCount, 0u);
}

// ---------------------------------------------------------------------------------------------
// Errors: each names the file and says what is wrong.

TEST(ImportErrors, MissingFaceNamesTheFaceAndTheNamesLookedFor) {
    TempDir dir;
    const FamilyCase fc{"", {"px", "nx", "py", "ny", "pz", "nz"}, ".exr"};
    for (int i = 0; i < 5; ++i)
        writeFloatRgb(dir / (fc.names[static_cast<std::size_t>(i)] + ".exr"), 4, 4, markerFace(i, 4));
    expectEnvError(dir / "px.exr", {}, dir / "px.exr", "missing face -Z");
    expectEnvError(dir / "px.exr", {}, dir / "px.exr", "nz.");
    expectEnvError(dir.path(), {}, dir.path(), "missing face -Z");
}

TEST(ImportErrors, FacesOfDifferentSizesNameBothFiles) {
    TempDir dir;
    const FamilyCase fc{"", {"px", "nx", "py", "ny", "pz", "nz"}, ".exr"};
    for (int i = 0; i < 6; ++i) {
        const int n = i == 4 ? 8 : 4;
        writeFloatRgb(dir / (fc.names[static_cast<std::size_t>(i)] + ".exr"), n, n, markerFace(i, n));
    }
    expectEnvError(dir / "px.exr", {}, dir / "pz.exr", "8x8");
    expectEnvError(dir / "px.exr", {}, dir / "pz.exr", (dir / "px.exr").string() + " is 4x4");
}

TEST(ImportErrors, NonSquareFaceIsRefusedNamingItsSize) {
    TempDir dir;
    for (const char* name : {"px", "nx", "py", "ny", "pz", "nz"})
        writeFloatRgb(dir / (std::string(name) + ".exr"), 4, 5, std::vector<Rgb>(20, Rgb(1.0f)));
    expectEnvError(dir / "nz.exr", {}, dir / "px.exr", "4x5");
}

TEST(ImportErrors, CrossWithWrongProportions) {
    TempDir dir;
    writeFloatRgb(dir / "cross.exr", 401, 300, std::vector<Rgb>(401 * 300, Rgb(1.0f)));
    expectEnvError(dir / "cross.exr", {}, dir / "cross.exr", "401x300");
    ImportOptions vcross;
    vcross.layout = EnvLayout::VerticalCross;
    expectEnvError(dir / "cross.exr", vcross, dir / "cross.exr", "3:4");
    writeFloatRgb(dir / "odd.exr", 50, 40, std::vector<Rgb>(50 * 40, Rgb(1.0f)));
    expectEnvError(dir / "odd.exr", {}, dir / "odd.exr", "accepted proportions");
}

TEST(ImportErrors, TruncatedExrIsRefusedNamingTheFile) {
    TempDir dir;
    const fs::path file = dir / "truncated.exr";
    writeFloatRgb(file, 64, 32, latLongFromFunction(64, 32, [](const glm::dvec3& d) {
                      return Rgb(1.0 + d.x, 1.0 + d.y * d.z, 2.0 + std::sin(7.0 * d.z));
                  }));
    fs::resize_file(file, fs::file_size(file) / 2);
    expectEnvError(file, {}, file, "");
}

TEST(ImportErrors, TextFileNamedPngIsNotAReadableImage) {
    TempDir dir;
    const fs::path file = dir / "notes.png";
    std::ofstream(file) << "this is not an image\n";
    expectEnvError(file, {}, file, "not a readable image");
}

TEST(ImportErrors, ZeroByteFileIsCalledEmpty) {
    TempDir dir;
    const fs::path file = dir / "empty.exr";
    std::ofstream{file};
    expectEnvError(file, {}, file, "empty");
}

TEST(ImportErrors, MissingPathIsNotFound) {
    TempDir dir;
    expectEnvError(dir / "nowhere.hdr", {}, dir / "nowhere.hdr", "not found");
}

// ---------------------------------------------------------------------------------------------
// Resampling.

TEST(EnvResample, ShrinkKeepsTheWeightedMeanAndGrowIsBilinear) {
    const CubeMap src = test::cubeFromFunction(12, [](const glm::vec3& d) {
        return Rgb(1.0f + d.x, 2.0f + std::sin(3.0f * d.y), 1.0f + d.z * d.z);
    });
    const CubeMap small = resampleCube(src, 5);  // a non-integer ratio
    ASSERT_EQ(small.size(), 5);
    const glm::dvec3 m0 = src.weightedMean(), m1 = small.weightedMean();
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(m1[ch], m0[ch], 1e-6) << "channel " << ch;
    const CubeMap same = resampleCube(src, 12);
    EXPECT_EQ(same.faceStorage(Face::NY), src.faceStorage(Face::NY));
    // Growing a linear function: bilinear between texel centres is exact on each face plane, so
    // the error is the curvature of the map from plane to sphere, small against the texel size.
    const CubeMap lin = test::cubeFromFunction(8, [](const glm::vec3& d) { return Rgb(1.0f) + d; });
    const CubeMap big = resampleCube(lin, 20);
    for (Face f : kAllFaces)
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 20; ++x) {
                const Rgb want = Rgb(1.0f) + texelDirection(f, x, y, 20);
                ASSERT_LT(glm::length(big.at(f, x, y) - want), 0.03f) << faceName(f) << " " << x << "," << y;
            }
}

// ---------------------------------------------------------------------------------------------
// Export.

TEST(FaceExport, FaceImagesRoundTripExactly) {
    TempDir dir;
    constexpr int kN = 5;
    CubeMap cube(kN);
    for (Face f : kAllFaces)
        for (int y = 0; y < kN; ++y)
            for (int x = 0; x < kN; ++x) cube.at(f, x, y) = marker(static_cast<int>(f), x, y) * 1.7f;
    cube.makeSeamless();
    writeFaceImages(cube, dir / "out" / "faces");
    for (Face f : kAllFaces) {
        auto in = OIIO::ImageInput::open((dir / "out" / "faces" / (std::string(faceName(f)) + ".exr")).string());
        ASSERT_TRUE(in) << faceName(f);
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
        EXPECT_EQ(in->spec().get_string_attribute("compression"), "zip");
    }
    const CubeMap back = loadEnvironment(dir / "out" / "faces").cube;
    for (Face f : kAllFaces) EXPECT_EQ(back.faceStorage(f), cube.faceStorage(f)) << faceName(f);
}

namespace {
MipChain markerChain(int base, int levels) {
    MipChain chain;
    for (int k = 0; k < levels; ++k) {
        const int n = levelSize(base, k);
        CubeMap c(n);
        for (Face f : kAllFaces)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) c.at(f, x, y) = marker(static_cast<int>(f), x, y) + Rgb(static_cast<float>(k));
        c.makeSeamless();
        chain.levels.push_back(std::move(c));
    }
    return chain;
}
}  // namespace

TEST(CubeEnvExport, ThreeLevelChainRoundTripsExactly) {
    TempDir dir;
    // Base 4: levels 4, 2, 1. Base 6 (not a power of two): 6, 3, 1, where OpenEXR's levels are
    // 6x36, 3x18, 1x9 (faces in the top six rows), 1x4, 1x2, 1x1.
    struct Case { int base, fileLevels; };
    for (const Case c : {Case{4, 5}, Case{6, 6}}) {
        const MipChain chain = markerChain(c.base, 3);
        const fs::path file = dir / ("env" + std::to_string(c.base) + ".exr");
        writeCubeEnvironmentExr(chain, file);

        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().width, c.base);
        EXPECT_EQ(in->spec().height, 6 * c.base);
        EXPECT_GT(in->spec().tile_width, 0);
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
        // OpenImageIO reports OpenEXR's envmap = cube as this texture format.
        EXPECT_EQ(in->spec().get_string_attribute("textureformat"), "CubeFace Environment");
        EXPECT_FALSE(in->spec().get_string_attribute("mipgloss:orientation").empty());
        // OpenEXR halves N x 6N down to 1x1: for base 4, 4x24, 2x12, 1x6 (the chain), 1x3, 1x1.
        int levels = 0;
        while (in->seek_subimage(0, levels)) ++levels;
        EXPECT_EQ(levels, c.fileLevels) << "base " << c.base;
        in->close();

        const MipChain back = readCubeEnvironmentExr(file);
        ASSERT_EQ(back.levelCount(), 3);
        for (int k = 0; k < 3; ++k)
            for (Face f : kAllFaces)
                EXPECT_EQ(back.levels[static_cast<std::size_t>(k)].faceStorage(f),
                          chain.levels[static_cast<std::size_t>(k)].faceStorage(f))
                    << "base " << c.base << " level " << k << " face " << faceName(f);
    }
}

TEST(CubeEnvExport, FacesFollowOpenExrCubeMapOrientation) {
    // OpenEXR's ImfEnvmap (CubeMap::direction and pixelPosition) for pixel (a, b) of a face,
    // a rightwards and b downwards in [-1, 1]. A linear environment read back from the raw file
    // must match it; texel centres differ from ImfEnvmap's by up to half a texel (cube_exr.h).
    constexpr int kN = 16;
    const CubeMap cube = test::cubeFromFunction(kN, [](const glm::vec3& d) { return Rgb(2.0f) + d; });
    MipChain chain;
    chain.levels.push_back(cube);
    TempDir dir;
    writeCubeEnvironmentExr(chain, dir / "lin.exr");
    auto in = OIIO::ImageInput::open((dir / "lin.exr").string());
    ASSERT_TRUE(in);
    std::vector<Rgb> px(static_cast<std::size_t>(kN * 6 * kN));
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data()));
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < kN; ++y)
            for (int x = 0; x < kN; ++x) {
                const float a = 2.0f * (static_cast<float>(x) + 0.5f) / kN - 1.0f;
                const float b = 2.0f * (static_cast<float>(y) + 0.5f) / kN - 1.0f;
                const std::array<glm::vec3, 6> dirs{glm::vec3(1, -b, a),  glm::vec3(-1, -b, -a),
                                                    glm::vec3(a, 1, -b),  glm::vec3(a, -1, b),
                                                    glm::vec3(-a, -b, 1), glm::vec3(a, -b, -1)};
                const glm::vec3 d = glm::normalize(dirs[static_cast<std::size_t>(face)]);
                const Rgb got = px[static_cast<std::size_t>((face * kN + y) * kN + x)];
                ASSERT_LT(glm::length(got - (Rgb(2.0f) + d)), 1e-5f) << "face " << face << " at " << x << "," << y;
            }
}

// ---------------------------------------------------------------------------------------------
// The embedded default environment.

TEST(DefaultEnv, LoadsFromTheEmbeddedBytes) {
    const auto bytes = defaultEnvironmentBytes();
    ASSERT_GT(bytes.size(), 1000u);
    EXPECT_LT(bytes.size(), 600u * 1024u);
    EXPECT_EQ(bytes[0], 0x76);  // OpenEXR magic 76 2f 31 01
    EXPECT_EQ(bytes[1], 0x2f);
    const ImportedEnvironment env = loadDefaultEnvironment(32);
    EXPECT_EQ(env.cube.size(), 32);
    EXPECT_EQ(env.report.layout, EnvLayout::LatLong);
    const glm::dvec3 mean = env.cube.weightedMean();
    EXPECT_GT(mean.x, 0.1);
    EXPECT_LT(mean.x, 10.0);
    EXPECT_EQ(loadDefaultEnvironment().cube.size(), 128);
}

TEST(EnvProgress, ReportsMonotonicFractionsEndingAtOne) {
    TempDir dir;
    writeFloatRgb(dir / "const.exr", 64, 32, std::vector<Rgb>(64 * 32, Rgb(1.0f)));
    std::vector<float> seen;
    loadEnvironment(dir / "const.exr", {}, [&](const std::string& stage, float f) {
        EXPECT_EQ(stage, "import");
        seen.push_back(f);
        return true;
    });
    ASSERT_FALSE(seen.empty());
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
    EXPECT_FLOAT_EQ(seen.back(), 1.0f);
}

TEST(EnvProgress, ImportStopsWithCancelledWhenProgressSaysSo) {
    TempDir dir;
    writeFloatRgb(dir / "const.exr", 64, 32, std::vector<Rgb>(64 * 32, Rgb(1.0f)));
    int calls = 0;
    EXPECT_THROW(loadEnvironment(dir / "const.exr", {},
                                 [&](const std::string&, float f) { return ++calls < 3 && f < 1.0f; }),
                 Cancelled);
    EXPECT_EQ(calls, 3) << "stops at the first report that says so";
}

// Real skies with a sun (sunrise, sunset, city, interior) given the ringing a lossy DCT codec
// leaves beside a sun: over the 16 × 8 pixels around each sun pixel (over 0.3 of the brightest),
// ±1.2 % of the sun in blue and ±0.3 % in red in a checkerboard (a DCT block's ringing oscillates,
// its lobes summing to about nothing; beside the sky's values of 1 to 100 the negative ones are
// hundreds below zero, as on the held-out sky DWAB rang on). Decoding repairs it
// without painting the sky: away from the sun (beyond the ringing's blocks and the repair's reach
// of 16 pixels) every pixel's chromaticity is the file's within 2 %, in the sun's rows too (the
// first rule drained a whole row's blue: a lime band); and the map's energy (the signed sum of
// what the file holds) is kept within 0.5 %.
TEST(ImportDecode, RingingBesideARealSunLeavesTheSkysHueAndEnergy) {
  TempDir dir;
  for (const char* name : {"sunrise", "sunset", "city", "interior"}) {
    SCOPED_TRACE(name);
    const fs::path source = test::asset(std::string("env/") + name + ".exr");
    MIPGLOSS_REQUIRE_ASSET(source);
    const DecodedImage map = decodeImage(source);
    const int w = map.width, h = map.height;
    float brightest = 0.0f;  // the sun: pixels over 0.3 of the brightest
    for (const Rgb& p : map.px) brightest = std::max(brightest, p.x + p.y + p.z);
    const float sunLevel = 0.3f * brightest;
    std::vector<Rgb> px = map.px;
    std::vector<char> ringing(px.size(), 0);
    int suns = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Rgb sun = map.px[static_cast<std::size_t>(y) * w + x];
            if (!(sun.x + sun.y + sun.z > sunLevel)) continue;
            ++suns;
            for (int by = std::max(0, y - 4); by < std::min(h, y + 4); ++by)
                for (int bx = std::max(0, x - 8); bx < std::min(w, x + 8); ++bx) {
                    const std::size_t i = static_cast<std::size_t>(by) * w + bx;
                    ringing[i] = 1;
                    const Rgb& here = map.px[i];
                    if (here.x + here.y + here.z >= sunLevel) continue;
                    const float sign = (bx + by) % 2 == 0 ? -1.0f : 1.0f;
                    px[i] += sign * Rgb(0.003f * sun.x, 0.0f, 0.012f * sun.z);
                }
        }
    ASSERT_GT(suns, 0);
    double signedSum = 0.0, mostNegative = 0.0;
    for (const Rgb& p : px) {
        signedSum += static_cast<double>(p.x) + p.y + p.z;
        mostNegative = std::min({mostNegative, double(p.x), double(p.z)});
    }
    const fs::path file = dir / (std::string(name) + "-ringing.exr");
    writeFloatRgb(file, w, h, px);
    ImportReport report;
    const DecodedImage got = decodeImage(file, &report);
    ASSERT_EQ(got.width, w);
    double sum = 0.0, worstHue = 0.0;
    int worstX = 0, worstY = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const Rgb& p = got.px[i];
            sum += static_cast<double>(p.x) + p.y + p.z;
            bool near = false;  // within the repair's reach of a ringing pixel in its row
            for (int dx = -16; dx <= 16 && !near; ++dx)
                near = x + dx >= 0 && x + dx < w && ringing[i + dx] != 0;
            if (near) continue;
            const Rgb& q = map.px[i];
            const double ps = static_cast<double>(p.x) + p.y + p.z, qs = static_cast<double>(q.x) + q.y + q.z;
            if (!(qs > 0.0)) continue;
            for (int c = 0; c < 3; ++c) {
                const double shift = std::abs(p[c] / ps - q[c] / qs) / std::max(q[c] / qs, 1e-3);
                if (shift > worstHue) {
                    worstHue = shift;
                    worstX = x;
                    worstY = y;
                }
            }
        }
    std::printf("[ import ] %s, ringing beside the sun (%d sun pixels): most negative %.4g, %zu negatives; energy %.8g "
                "of the file's signed %.8g (%+.5f %%); worst chromaticity shift away from the sun %.4f %% at (%d, %d)\n",
                name, suns, mostNegative, report.negativeCount, sum, signedSum, 100.0 * (sum / signedSum - 1.0), 100.0 * worstHue,
                worstX, worstY);
    EXPECT_LT(mostNegative, -0.002 * brightest) << "large negative lobes, as the ringing the test is about";
    EXPECT_GT(report.negativeCount, 0u);
    EXPECT_LT(worstHue, 0.02);
    EXPECT_NEAR(sum / signedSum, 1.0, 0.005);
  }
}
