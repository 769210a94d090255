// `bake()` for real (bake.h): the embedded default environment and a committed HDRI, baked at small
// face sizes into a temporary folder, then the folder read back: the files bake.h promises, the
// manifest's numbers against the λ ↔ n mapping (phong.h), the cube EXR against the chain, and the
// atomic replacement of the output folder when a bake fails.
#include "mipgloss/io/bake.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/cube_exr.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

using test::TempDir;

using test::readText;
using test::writeBytes;

// The names in `dir` (not recursive), sorted.
std::vector<std::string> namesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Entries beside `outDir` whose name starts with outDir's name and a dot: bake's temporary
// siblings ("<out>.partial-N", "<out>.old-N").
std::vector<std::string> temporarySiblings(const fs::path& outDir) {
    std::vector<std::string> found;
    const std::string prefix = outDir.filename().string() + ".";
    for (const auto& entry : fs::directory_iterator(outDir.parent_path())) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) == 0) found.push_back(name);
    }
    return found;
}

// A tiny reader for the manifest: the JSON bake writes is flat enough for regular expressions.
std::string stringField(const std::string& json, const std::string& key) {
    std::smatch m;
    if (!std::regex_search(json, m, std::regex("\"" + key + "\": \"([^\"]*)\""))) return "<missing " + key + ">";
    return m[1];
}
double numberField(const std::string& json, const std::string& key) {
    std::smatch m;
    if (!std::regex_search(json, m, std::regex("\"" + key + "\": ([-+0-9.eE]+)"))) return std::nan("");
    return std::stod(m[1]);
}

// A manifest number: a JSON number, or null (NaN here).
double jsonNumberOrNull(const std::string& text) { return text == "null" ? std::nan("") : std::stod(text); }

struct ManifestLevel {
    int level = -1, size = -1;
    bool read = false;
    std::string phongExponentText, lambdaText;  // as written: a number or "null"
    double phongExponent = std::nan(""), lambda = std::nan("");
    std::string dir;
};
std::vector<ManifestLevel> manifestLevels(const std::string& json) {
    std::vector<ManifestLevel> levels;
    const std::regex entry(
        "\\{\"level\": ([0-9]+), \"size\": ([0-9]+), \"read\": (true|false), \"phong_exponent\": (null|[-+0-9.eE]+), "
        "\"lambda\": (null|[-+0-9.eE]+), \"dir\": \"([^\"]*)\"\\}");
    for (auto it = std::sregex_iterator(json.begin(), json.end(), entry); it != std::sregex_iterator(); ++it) {
        const std::smatch& m = *it;
        ManifestLevel l;
        l.level = std::stoi(m[1]);
        l.size = std::stoi(m[2]);
        l.read = m[3] == "true";
        l.phongExponentText = m[4];
        l.lambdaText = m[5];
        l.phongExponent = jsonNumberOrNull(m[4]);
        l.lambda = jsonNumberOrNull(m[5]);
        l.dir = m[6];
        levels.push_back(l);
    }
    return levels;
}

// Everything a finished bake of `chain` into `out` must hold (files, manifest, cube file).
void expectBakeFolder(const fs::path& out, const BakeSummary& summary, const MipChain& chain, Builder builder,
                      bool irradiance, const std::string& sourceSubstring) {
    const int n = chain.baseSize();
    ASSERT_GT(n, 0);
    ASSERT_TRUE(fs::is_directory(out)) << out;
    EXPECT_EQ(fs::absolute(summary.outDir).lexically_normal(), fs::absolute(out).lexically_normal());
    EXPECT_EQ(summary.faceSize, n);
    EXPECT_EQ(summary.cubeFile, summary.outDir / "environment_mips.exr");
    EXPECT_EQ(summary.irradiance, irradiance);

    // (a) The files bake.h promises: a directory of EXR faces per level, the manifest, one cube EXR
    // (and the irradiance faces when asked for); nothing else.
    std::vector<std::string> expected = {"environment_mips.exr", "manifest.json"};
    for (int k = 0; k < chain.levelCount(); ++k) expected.push_back("level" + std::to_string(k));
    if (irradiance) expected.push_back("irradiance");
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(namesIn(out), expected);
    const std::vector<std::string> faceFiles = {"nx.exr", "ny.exr", "nz.exr", "px.exr", "py.exr", "pz.exr"};
    for (int k = 0; k < chain.levelCount(); ++k) {
        const fs::path level = out / ("level" + std::to_string(k));
        ASSERT_TRUE(fs::is_directory(level)) << level;
        EXPECT_EQ(namesIn(level), faceFiles) << level;
    }
    if (irradiance) {
        EXPECT_EQ(namesIn(out / "irradiance"), faceFiles);
    }
    const std::vector<std::string> left = temporarySiblings(out);
    EXPECT_TRUE(left.empty()) << "a temporary sibling was left: " << (left.empty() ? "" : left.front());

    // (b) The manifest.
    const std::string json = readText(out / "manifest.json");
    EXPECT_EQ(stringField(json, "format"), "mipgloss-bake");
    EXPECT_EQ(stringField(json, "builder"), builderName(builder));
    EXPECT_NE(stringField(json, "source").find(sourceSubstring), std::string::npos) << stringField(json, "source");
    EXPECT_EQ(stringField(json, "cube_file"), "environment_mips.exr");
    EXPECT_EQ(numberField(json, "face_size"), static_cast<double>(n));
    const std::vector<ManifestLevel> levels = manifestLevels(json);
    ASSERT_EQ(static_cast<int>(levels.size()), chain.levelCount()) << json;
    ASSERT_EQ(static_cast<int>(summary.levels.size()), chain.levelCount());
    EXPECT_EQ(chain.levelCount(), fullChainLevelCount(n)) << "a full chain down to 1×1";
    for (int k = 0; k < chain.levelCount(); ++k) {
        SCOPED_TRACE("manifest level " + std::to_string(k));
        const ManifestLevel& l = levels[static_cast<std::size_t>(k)];
        EXPECT_EQ(l.level, k);
        EXPECT_EQ(l.size, levelSize(n, k));
        EXPECT_EQ(l.size, chain.levels[static_cast<std::size_t>(k)].size());
        EXPECT_EQ(l.dir, "level" + std::to_string(k));
        // The schedule (phong.h): levels 0..lastReadLevel are read, the rest are box steps.
        const int last = lastReadLevel(n);
        const BakedLevel& summaryLevel = summary.levels[static_cast<std::size_t>(k)];
        EXPECT_EQ(l.read, k <= last);
        EXPECT_EQ(summaryLevel.read, k <= last);
        if (k == 0) {
            // The mirror: n = ∞ is written as null, its λ is 0.
            EXPECT_EQ(l.phongExponentText, "null");
            EXPECT_EQ(summaryLevel.phongExponent, kMirrorExponent);
            EXPECT_EQ(l.lambda, 0.0);
        } else if (k <= last) {
            // The manifest prints 10 significant digits: relative tolerance 1e-9 (the rounding is
            // at most 5e-10 of the value).
            const double declared = levelExponent(n, k);
            EXPECT_NEAR(l.phongExponent, declared, 1e-9 * declared);
            EXPECT_EQ(summaryLevel.phongExponent, declared);
            // Written out: M²/32 for a face of M >= 16, 1 at the last read level.
            const double analytic = k == last ? 1.0 : static_cast<double>(l.size) * l.size / 32.0;
            EXPECT_EQ(declared, analytic);
            // λ is the fixed-meaning λ of that lobe (exponentToLambda), and maps back to it.
            const double lambda = exponentToLambda(declared);
            EXPECT_NEAR(l.lambda, lambda, 1e-9 * lambda);
            EXPECT_EQ(summaryLevel.lambda, lambda);
            EXPECT_NEAR(lambdaToExponent(l.lambda), declared, 1e-8 * declared);
        } else {
            EXPECT_EQ(l.phongExponentText, "null") << "never read: no lobe";
            EXPECT_EQ(l.lambdaText, "null");
            EXPECT_TRUE(std::isnan(summaryLevel.phongExponent));
            EXPECT_TRUE(std::isnan(summaryLevel.lambda));
        }
    }
    if (irradiance) {
        EXPECT_NE(json.find("\"irradiance\": {\"dir\": \"irradiance\", \"face_size\": " +
                            std::to_string(std::min(kIrradianceFaceSize, n))),
                  std::string::npos)
            << json;
    } else {
        EXPECT_NE(json.find("\"irradiance\": null"), std::string::npos) << json;
    }

    // (c) The cube EXR reads back as the chain. The file stores 32-bit float (cube_exr.h) and the
    // orientation change only moves texels, so the tolerance is zero: every texel bit-equal (the
    // half-float rounding of 2^-11 relative would apply only to a half file).
    const MipChain back = readCubeEnvironmentExr(out / "environment_mips.exr");
    ASSERT_EQ(back.levelCount(), chain.levelCount());
    int mismatches = 0;
    for (int k = 0; k < chain.levelCount(); ++k) {
        const CubeMap& a = chain.levels[static_cast<std::size_t>(k)];
        const CubeMap& b = back.levels[static_cast<std::size_t>(k)];
        ASSERT_EQ(b.size(), a.size()) << "level " << k;
        for (Face f : kAllFaces)
            for (int y = 0; y < a.size(); ++y)
                for (int x = 0; x < a.size(); ++x)
                    if (a.at(f, x, y) != b.at(f, x, y) && ++mismatches <= 5)
                        ADD_FAILURE() << "level " << k << " face " << faceName(f) << " texel (" << x << ", " << y
                                      << "): chain " << a.at(f, x, y).r << " file " << b.at(f, x, y).r;
    }
    EXPECT_EQ(mismatches, 0);

    // The per-level face files are the chain too (float EXR, read back through the face importer).
    for (int k = 0; k < chain.levelCount(); ++k) {
        const CubeMap faces = loadEnvironment(out / ("level" + std::to_string(k))).cube;
        const CubeMap& a = chain.levels[static_cast<std::size_t>(k)];
        ASSERT_EQ(faces.size(), a.size()) << "level " << k;
        for (Face f : kAllFaces)
            for (int y = 0; y < a.size(); ++y)
                for (int x = 0; x < a.size(); ++x)
                    ASSERT_EQ(faces.at(f, x, y), a.at(f, x, y))
                        << "level" << k << "/" << faceName(f) << ".exr texel (" << x << ", " << y << ")";
    }
}

}  // namespace

TEST(Bake, DefaultEnvironmentWritesTheChainManifestAndCubeFile) {
    TempDir dir;
    constexpr int kSize = 16;
    BakeRequest request;
    request.import.faceSize = kSize;
    request.outDir = dir / "baked";
    std::vector<std::string> stages;
    request.progress = [&](const std::string& stage, float) {
        if (stages.empty() || stages.back() != stage) stages.push_back(stage);
        return true;
    };
    const BakeSummary summary = bake(request);
    // The chain the bake must have written: the same import and the same deterministic builder.
    const MipChain chain = buildChain(loadDefaultEnvironment(kSize).cube, kDefaultBuilder);
    ASSERT_EQ(chain.baseSize(), kSize);
    expectBakeFolder(request.outDir, summary, chain, kDefaultBuilder, false, "embedded default environment");
    EXPECT_NE(std::find(stages.begin(), stages.end(), "write"), stages.end());
    EXPECT_EQ(stages.back(), "done");
}

TEST(Bake, CommittedHdriWithBoxBuilderAndIrradiance) {
    const fs::path source = test::asset("env/sunset.exr");
    MIPGLOSS_REQUIRE_ASSET(source);
    TempDir dir;
    constexpr int kSize = 32;
    BakeRequest request;
    request.environment = source;
    request.builder = Builder::Box;
    request.import.faceSize = kSize;
    request.irradiance = true;
    request.outDir = dir / "nested" / "sunset_baked";  // missing parents are created
    const BakeSummary summary = bake(request);
    ImportOptions options;
    options.faceSize = kSize;
    const CubeMap base = loadEnvironment(source, options).cube;
    const MipChain chain = buildChain(base, Builder::Box);
    expectBakeFolder(request.outDir, summary, chain, Builder::Box, true, "sunset.exr");

    // The irradiance faces are computeIrradiance of the same base, bit-equal (float files).
    const CubeMap expected = computeIrradiance(base);
    const CubeMap written = loadEnvironment(request.outDir / "irradiance").cube;
    ASSERT_EQ(written.size(), std::min(kIrradianceFaceSize, kSize));
    for (Face f : kAllFaces)
        for (int y = 0; y < expected.size(); ++y)
            for (int x = 0; x < expected.size(); ++x)
                ASSERT_EQ(written.at(f, x, y), expected.at(f, x, y)) << faceName(f) << " (" << x << ", " << y << ")";
}

TEST(Bake, FailedBakeLeavesTheOldFolderThenASuccessfulOneReplacesIt) {
    TempDir dir;
    const fs::path out = dir / "baked";
    BakeRequest first;
    first.import.faceSize = 8;
    first.outDir = out;
    bake(first);
    const std::string oldManifest = readText(out / "manifest.json");
    ASSERT_FALSE(oldManifest.empty());
    writeBytes(out / "marker.txt", "from the first bake\n");

    auto expectOldFolderIntact = [&](const std::string& after) {
        SCOPED_TRACE(after);
        EXPECT_TRUE(fs::exists(out / "marker.txt"));
        EXPECT_EQ(readText(out / "manifest.json"), oldManifest);
        EXPECT_TRUE(fs::exists(out / "environment_mips.exr"));
        EXPECT_TRUE(fs::is_directory(out / "level3"));
        const auto left = temporarySiblings(out);
        EXPECT_TRUE(left.empty()) << "temporary sibling left behind: " << (left.empty() ? "" : left.front());
    };

    // 1. A truncated copy of a committed HDRI: the import fails, naming the file.
    const fs::path source = test::asset("env/sunset.exr");
    MIPGLOSS_REQUIRE_ASSET(source);
    const std::string bytes = readText(source);
    const fs::path truncated = dir / "truncated_sunset.exr";
    writeBytes(truncated, bytes.substr(0, bytes.size() / 3));
    BakeRequest broken;
    broken.environment = truncated;
    broken.import.faceSize = 16;
    broken.outDir = out;
    try {
        bake(broken);
        ADD_FAILURE() << "a truncated EXR baked";
    } catch (const EnvError& e) {
        EXPECT_NE(std::string(e.what()).find(truncated.string()), std::string::npos) << e.what();
    }
    expectOldFolderIntact("after a truncated input");

    // 2. A failure after the staging folder exists: cancelled while writing the levels. The
    // staging sibling must be removed and the old folder kept.
    BakeRequest cancelled;
    cancelled.import.faceSize = 16;
    cancelled.outDir = out;
    bool sawWrite = false;
    cancelled.progress = [&](const std::string& stage, float fraction) {
        if (stage == "write" && fraction > 0.0f) {
            sawWrite = true;
            return false;  // after level 0's faces are in the staging folder
        }
        return true;
    };
    EXPECT_THROW(bake(cancelled), Cancelled);
    EXPECT_TRUE(sawWrite);
    expectOldFolderIntact("after a bake cancelled mid-write");

    // 3. A successful bake replaces the folder: the marker is gone, the manifest is the new one.
    BakeRequest second;
    second.import.faceSize = 16;
    second.builder = Builder::Paper;
    second.outDir = out;
    const BakeSummary summary = bake(second);
    EXPECT_FALSE(fs::exists(out / "marker.txt")) << "the old folder's content survived the replacement";
    const std::string newManifest = readText(out / "manifest.json");
    EXPECT_NE(newManifest, oldManifest);
    EXPECT_EQ(stringField(newManifest, "builder"), "paper");
    EXPECT_EQ(numberField(newManifest, "face_size"), 16.0);
    EXPECT_EQ(summary.faceSize, 16);
    EXPECT_TRUE(temporarySiblings(out).empty());
}

TEST(Bake, BadInputErrorNamesTheFile) {
    TempDir dir;
    struct Case {
        const char* what;
        fs::path file;
        std::string bytes;  // empty: do not create the file
    };
    for (const Case& c : {Case{"missing file", dir / "nowhere" / "sky.exr", ""},
                          Case{"not an image", dir / "garbage.exr", "this is not an OpenEXR file\n"},
                          Case{"empty file", dir / "empty.hdr", std::string()}}) {
        SCOPED_TRACE(c.what);
        if (std::string(c.what) == "not an image") writeBytes(c.file, c.bytes);
        if (std::string(c.what) == "empty file") writeBytes(c.file, "");
        BakeRequest request;
        request.environment = c.file;
        request.outDir = dir / "out";
        try {
            bake(request);
            ADD_FAILURE() << c.file << " baked";
        } catch (const EnvError& e) {
            EXPECT_NE(std::string(e.what()).find(c.file.filename().string()), std::string::npos) << e.what();
            EXPECT_NE(e.file().string().find(c.file.filename().string()), std::string::npos) << e.file();
        }
        EXPECT_FALSE(fs::exists(dir / "out")) << "a failed bake created its output folder";
        EXPECT_TRUE(temporarySiblings(dir / "out").empty());
    }
    // No output folder: invalid_argument, nothing written.
    BakeRequest noOut;
    noOut.import.faceSize = 8;
    EXPECT_THROW(bake(noOut), std::invalid_argument);
}
