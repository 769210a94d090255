// The DDS cube-map writer and reader (dds.h). OpenImageIO 2.4 reads no float DDS (it answers
// "Unsupported compression type" for DX10 R16G16B16A16_FLOAT and R32G32B32A32_FLOAT, and for the
// legacy D3DFMT float FourCCs too), so the file is checked here byte by byte against Microsoft's
// layout, decoded by this test's own offsets (not the library's reader), and then round-tripped
// through readCubeDds. docs/bake-output.md records the same files checked by NVIDIA Texture Tools'
// nvddsinfo.
#include "mipgloss/io/dds.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/import.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

using test::readText;
using test::TempDir;
using test::writeBytes;

std::uint32_t word(const std::string& bytes, std::size_t offset) {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + offset, 4);  // x86-64 and every host we build on: little-endian
    return v;
}

// Texel (x, y) of level k, face f, channel c as stored, found by Microsoft's layout: after the
// 148 header bytes, face 0 with levels 0..L-1, then face 1, ...; each level row 0 first, RGBA.
float storedValue(const std::string& bytes, int base, int levels, Face f, int k, int x, int y, int c,
                  DdsType type) {
    const std::size_t texelBytes = type == DdsType::Half ? 8 : 16;
    std::size_t texelsPerFace = 0;
    for (int j = 0; j < levels; ++j)
        texelsPerFace += static_cast<std::size_t>(levelSize(base, j)) * static_cast<std::size_t>(levelSize(base, j));
    std::size_t before = static_cast<std::size_t>(f) * texelsPerFace;
    for (int j = 0; j < k; ++j)
        before += static_cast<std::size_t>(levelSize(base, j)) * static_cast<std::size_t>(levelSize(base, j));
    const std::size_t m = static_cast<std::size_t>(levelSize(base, k));
    const std::size_t offset = 148 + (before + static_cast<std::size_t>(y) * m + static_cast<std::size_t>(x)) * texelBytes +
                               static_cast<std::size_t>(c) * (texelBytes / 4);
    float v = 0.0f;
    if (type == DdsType::Float) {
        std::memcpy(&v, bytes.data() + offset, 4);
    } else {
        OIIO::convert_pixel_values(OIIO::TypeDesc::HALF, bytes.data() + offset, OIIO::TypeDesc::FLOAT, &v, 1);
    }
    return v;
}

// A chain whose every texel says where it is: R = face, G = level, B = 64·y + x (small integers,
// exact in half as well as float). Base 8: levels 8, 4, 2, 1; base 6: 6, 3, 1.
MipChain labelledChain(int base) {
    MipChain chain;
    for (int k = 0; k < fullChainLevelCount(base); ++k) {
        CubeMap c(levelSize(base, k));
        for (Face f : kAllFaces)
            for (int y = 0; y < c.size(); ++y)
                for (int x = 0; x < c.size(); ++x)
                    c.at(f, x, y) = Rgb(static_cast<float>(f), static_cast<float>(k), static_cast<float>(64 * y + x));
        c.makeSeamless();
        chain.levels.push_back(std::move(c));
    }
    return chain;
}

const char* typeName(DdsType t) { return t == DdsType::Half ? "half" : "float"; }

}  // namespace

TEST(DdsWrite, HeaderIsADx10CubeMapWithEveryMipLevel) {
    TempDir dir;
    for (const int base : {8, 6, 1}) {
        for (const DdsType type : {DdsType::Half, DdsType::Float}) {
            SCOPED_TRACE(std::string("base ") + std::to_string(base) + ", " + typeName(type));
            const MipChain chain = labelledChain(base);
            const fs::path file = dir / ("cube" + std::to_string(base) + typeName(type) + ".dds");
            writeCubeDds(chain, file, type);
            const std::string b = readText(file);
            ASSERT_GE(b.size(), 148u);
            EXPECT_EQ(b.substr(0, 4), "DDS ");
            EXPECT_EQ(word(b, 4), 124u) << "DDS_HEADER.dwSize";
            const std::uint32_t flags = word(b, 8);
            for (std::uint32_t bit : {0x1u, 0x2u, 0x4u, 0x1000u, 0x20000u})  // CAPS HEIGHT WIDTH PIXELFORMAT MIPMAPCOUNT
                EXPECT_TRUE(flags & bit) << "dwFlags 0x" << std::hex << flags << " lacks 0x" << bit;
            EXPECT_EQ(word(b, 12), static_cast<std::uint32_t>(base)) << "height";
            EXPECT_EQ(word(b, 16), static_cast<std::uint32_t>(base)) << "width";
            EXPECT_EQ(word(b, 20), static_cast<std::uint32_t>(base) * (type == DdsType::Half ? 8u : 16u)) << "pitch";
            EXPECT_EQ(word(b, 28), static_cast<std::uint32_t>(chain.levelCount())) << "mip count";
            EXPECT_EQ(word(b, 76), 32u) << "DDS_PIXELFORMAT.dwSize";
            EXPECT_EQ(word(b, 80), 0x4u) << "DDPF_FOURCC";
            EXPECT_EQ(b.substr(84, 4), "DX10");
            const std::uint32_t caps = word(b, 108);
            EXPECT_TRUE(caps & 0x1000u) << "DDSCAPS_TEXTURE";
            EXPECT_TRUE(caps & 0x8u) << "DDSCAPS_COMPLEX (a cube map)";
            EXPECT_EQ((caps & 0x400000u) != 0, chain.levelCount() > 1) << "DDSCAPS_MIPMAP";
            EXPECT_EQ(word(b, 112), 0xFE00u) << "DDSCAPS2_CUBEMAP | DDSCAPS2_CUBEMAP_ALLFACES";
            EXPECT_EQ(word(b, 128), type == DdsType::Half ? 10u : 2u)
                << "DXGI_FORMAT_R16G16B16A16_FLOAT = 10, R32G32B32A32_FLOAT = 2";
            EXPECT_EQ(word(b, 132), 3u) << "D3D10_RESOURCE_DIMENSION_TEXTURE2D";
            EXPECT_EQ(word(b, 136), 0x4u) << "D3D10_RESOURCE_MISC_TEXTURECUBE";
            EXPECT_EQ(word(b, 140), 1u) << "arraySize counts cubes";
            std::size_t texels = 0;
            for (int k = 0; k < chain.levelCount(); ++k)
                texels += 6 * static_cast<std::size_t>(levelSize(base, k)) * static_cast<std::size_t>(levelSize(base, k));
            EXPECT_EQ(b.size(), 148 + texels * (type == DdsType::Half ? 8 : 16)) << "header, then the texels, nothing else";

            // Our reader reports the same fields.
            const DdsCube back = readCubeDds(file);
            EXPECT_EQ(back.header.mipMapCount, static_cast<std::uint32_t>(chain.levelCount()));
            EXPECT_EQ(back.header.dxgiFormat, type == DdsType::Half ? kDxgiR16G16B16A16Float : kDxgiR32G32B32A32Float);
            EXPECT_EQ(back.header.caps2, 0xFE00u);
            EXPECT_EQ(back.header.arraySize, 1u);
        }
    }
    // Only the file itself is left: the temporary it was written to has been renamed.
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
    EXPECT_EQ(entries, 6);
}

TEST(DdsWrite, FacesInD3dOrderEachWithItsMipsRowZeroFirst) {
    TempDir dir;
    for (const int base : {8, 6}) {
        for (const DdsType type : {DdsType::Half, DdsType::Float}) {
            SCOPED_TRACE(std::string("base ") + std::to_string(base) + ", " + typeName(type));
            const MipChain chain = labelledChain(base);
            const fs::path file = dir / "labelled.dds";
            writeCubeDds(chain, file, type);
            const std::string b = readText(file);
            int wrong = 0;
            for (int k = 0; k < chain.levelCount(); ++k)
                for (Face f : kAllFaces)
                    for (int y = 0; y < levelSize(base, k); ++y)
                        for (int x = 0; x < levelSize(base, k); ++x) {
                            const float expected[4] = {static_cast<float>(f), static_cast<float>(k),
                                                       static_cast<float>(64 * y + x), 1.0f};
                            for (int c = 0; c < 4; ++c) {
                                const float got = storedValue(b, base, chain.levelCount(), f, k, x, y, c, type);
                                if (got != expected[c] && ++wrong <= 5)
                                    ADD_FAILURE() << "face " << faceName(f) << " level " << k << " texel (" << x << ", "
                                                  << y << ") channel " << c << ": stored " << got << ", expected "
                                                  << expected[c];
                            }
                        }
            EXPECT_EQ(wrong, 0) << "every value is a small integer: exact in half and float";
        }
    }
}

// Direct3D's cube-map addressing, written out from Microsoft's documentation ("Cubic Environment
// Mapping", the D3D10+ TextureCube face selection), independently of cubemap.cpp: for the major
// axis ma, u = (uc/|ma| + 1)/2 and v = (vc/|ma| + 1)/2, v = 0 the first row in memory.
struct D3dTexel {
    int face;  // 0..5 = +X -X +Y -Y +Z -Z (D3D11_TEXTURECUBE_FACE_*)
    double u, v;
};
D3dTexel d3dCubeAddress(const glm::dvec3& r) {
    const double ax = std::abs(r.x), ay = std::abs(r.y), az = std::abs(r.z);
    if (ax >= ay && ax >= az)
        return r.x > 0 ? D3dTexel{0, (-r.z / ax + 1) / 2, (-r.y / ax + 1) / 2}
                       : D3dTexel{1, (r.z / ax + 1) / 2, (-r.y / ax + 1) / 2};
    if (ay >= az)
        return r.y > 0 ? D3dTexel{2, (r.x / ay + 1) / 2, (r.z / ay + 1) / 2}
                       : D3dTexel{3, (r.x / ay + 1) / 2, (-r.z / ay + 1) / 2};
    return r.z > 0 ? D3dTexel{4, (r.x / az + 1) / 2, (-r.y / az + 1) / 2}
                   : D3dTexel{5, (-r.x / az + 1) / 2, (-r.y / az + 1) / 2};
}

TEST(DdsWrite, Direct3dAddressingFindsTheTexelMipglossShowsInThatDirection) {
    // A smooth environment, f(r) = r + 2 (positive, changes by ≤ 2/N across a texel of a size-N
    // face). A D3D sampler addressing the file with direction r lands on the texel whose centre is
    // within half a texel of r, so the stored value is within √2·(1/N)·|∇f| ≈ 1.5/N of f(r):
    // tolerance 2/N. A mirrored or flipped face would be off by up to 2 (|Δr| across the cube).
    constexpr int kN = 32;
    const MipChain chain{{test::cubeFromFunction(kN, [](const glm::vec3& r) { return r + glm::vec3(2.0f); })}};
    TempDir dir;
    writeCubeDds(chain, dir / "smooth.dds", DdsType::Float);
    const std::string b = readText(dir / "smooth.dds");
    double worst = 0.0;
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
        // Directions spread over the sphere (a spiral), every face many times.
        const double z = 1.0 - (2.0 * i + 1.0) / 2000.0, phi = i * 2.399963229728653;
        const glm::dvec3 r(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
        const D3dTexel t = d3dCubeAddress(r);
        const int x = std::min(kN - 1, static_cast<int>(t.u * kN)), y = std::min(kN - 1, static_cast<int>(t.v * kN));
        for (int c = 0; c < 3; ++c) {
            const double stored = storedValue(b, kN, 1, static_cast<Face>(t.face), 0, x, y, c, DdsType::Float);
            worst = std::max(worst, std::abs(stored - (r[c] + 2.0)));
        }
        ++checked;
    }
    EXPECT_EQ(checked, 2000);
    EXPECT_LT(worst, 2.0 / kN) << "largest |stored - f(r)| over 2000 directions addressed the Direct3D way";
}

TEST(DdsRoundTrip, FloatIsExactAndHalfWithinHalfRounding) {
    const fs::path source = test::asset("env/sunset.exr");
    MIPGLOSS_REQUIRE_ASSET(source);
    ImportOptions options;
    options.faceSize = 32;
    MipChain chain = buildChain(loadEnvironment(source, options).cube, kDefaultBuilder);
    // Beyond half's range: float keeps it, half stores 65504 (the largest finite half).
    chain.levels[0].at(Face::PY, 3, 4) = Rgb(1.0e6f, 70000.0f, 65504.0f);
    TempDir dir;
    for (const DdsType type : {DdsType::Float, DdsType::Half}) {
        SCOPED_TRACE(typeName(type));
        writeCubeDds(chain, dir / "sunset.dds", type);
        const DdsCube back = readCubeDds(dir / "sunset.dds");
        ASSERT_EQ(back.chain.levelCount(), chain.levelCount());
        EXPECT_EQ(back.minAlpha, 1.0f);
        EXPECT_EQ(back.maxAlpha, 1.0f);
        int wrong = 0;
        double worstRel = 0.0;
        for (int k = 0; k < chain.levelCount(); ++k) {
            const CubeMap& a = chain.levels[static_cast<std::size_t>(k)];
            const CubeMap& r = back.chain.levels[static_cast<std::size_t>(k)];
            ASSERT_EQ(r.size(), a.size());
            for (Face f : kAllFaces)
                for (int y = 0; y < a.size(); ++y)
                    for (int x = 0; x < a.size(); ++x)
                        for (int c = 0; c < 3; ++c) {
                            const float want = type == DdsType::Half ? std::min(a.at(f, x, y)[c], 65504.0f) : a.at(f, x, y)[c];
                            const float got = r.at(f, x, y)[c];
                            // Half rounds to nearest: relative error ≤ 2^-11 for normal values, absolute
                            // ≤ 2^-25 (half the subnormal spacing 2^-24) below 2^-14.
                            const double tolerance =
                                type == DdsType::Float ? 0.0 : std::max(std::ldexp(double(std::abs(want)), -11), std::ldexp(1.0, -25));
                            if (std::abs(got - want) > tolerance && ++wrong <= 5)
                                ADD_FAILURE() << "level " << k << " " << faceName(f) << " (" << x << ", " << y << ") ch "
                                              << c << ": chain " << want << ", file " << got;
                            if (want > 1e-3f) worstRel = std::max(worstRel, std::abs(got - want) / double(want));
                        }
        }
        EXPECT_EQ(wrong, 0);
        if (type == DdsType::Half) {
            EXPECT_GT(worstRel, 0.0) << "half storage rounds";  // so the float case's 0 means something
            EXPECT_EQ(back.chain.levels[0].at(Face::PY, 3, 4), Rgb(65504.0f)) << "clamped, not +Inf";
        } else {
            EXPECT_EQ(back.chain.levels[0].at(Face::PY, 3, 4), Rgb(1.0e6f, 70000.0f, 65504.0f));
        }
    }
}

TEST(DdsRead, TruncatedOrLyingFilesAreRefusedNamingTheFile) {
    TempDir dir;
    const fs::path good = dir / "good.dds";
    writeCubeDds(labelledChain(8), good, DdsType::Half);
    const std::string bytes = readText(good);
    auto expectRefused = [&](const std::string& what, const std::string& content) {
        SCOPED_TRACE(what);
        const fs::path file = dir / (what + ".dds");
        writeBytes(file, content);
        try {
            readCubeDds(file);
            ADD_FAILURE() << "read";
        } catch (const EnvError& e) {
            EXPECT_EQ(e.file(), file) << e.what();
        }
    };
    expectRefused("truncated", bytes.substr(0, bytes.size() - 1));
    expectRefused("header-only", bytes.substr(0, 148));
    std::string huge = bytes;  // claims 60000² faces: refused by size before any allocation
    const std::uint32_t big = 60000;
    std::memcpy(huge.data() + 12, &big, 4);
    std::memcpy(huge.data() + 16, &big, 4);
    expectRefused("huge", huge);
    std::string legacy = bytes;  // a FourCC other than DX10
    std::memcpy(legacy.data() + 84, "DXT5", 4);
    expectRefused("no-dx10", legacy);
    std::string array = bytes;  // two cubes
    const std::uint32_t two = 2;
    std::memcpy(array.data() + 140, &two, 4);
    expectRefused("array", array);
    expectRefused("empty", "");
}

TEST(DdsWrite, RefusesAChainWhoseLevelsDoNotHalve) {
    TempDir dir;
    MipChain chain = labelledChain(8);
    chain.levels[2] = CubeMap(3);
    EXPECT_THROW(writeCubeDds(chain, dir / "bad.dds"), EnvError);
    EXPECT_THROW(writeCubeDds(MipChain{}, dir / "empty.dds"), EnvError);
    EXPECT_FALSE(fs::exists(dir / "bad.dds"));
    EXPECT_FALSE(fs::exists(dir / "empty.dds"));
}

TEST(DdsType, ParsesItsTwoNames) {
    DdsType t = DdsType::Float;
    EXPECT_TRUE(parseDdsType("half", t));
    EXPECT_EQ(t, DdsType::Half);
    EXPECT_TRUE(parseDdsType("float", t));
    EXPECT_EQ(t, DdsType::Float);
    EXPECT_FALSE(parseDdsType("double", t));
    EXPECT_FALSE(parseDdsType("HALF", t));
    EXPECT_EQ(t, DdsType::Float) << "unchanged on failure";
    EXPECT_STREQ(ddsTypeName(DdsType::Half), "half");
}
