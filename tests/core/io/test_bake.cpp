// `bake()` for real (bake.h): the embedded default environment and a committed HDRI, baked at small
// face sizes into a temporary folder, then the folder read back: the files bake.h promises, the
// manifest's numbers against the λ ↔ n mapping (phong.h), the cube EXR against the chain, the DDS
// format, parallel writes against serial ones, the atomic replacement of the output folder when a
// bake fails (in the import, cancelled, or a file that cannot be written), and the command line's
// refusal of bad bake options.
#include "mipgloss/io/bake.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/cube_exr.h"
#include "mipgloss/io/dds.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
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

// Every regular file under `dir`, by path relative to it, with its bytes.
std::map<std::string, std::string> filesUnder(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) files[fs::relative(entry.path(), dir).string()] = readText(entry.path());
    return files;
}

// An OpenEXR file's bytes with the value of its capDate attribute (the "YYYY:MM:DD HH:MM:SS" that
// OpenImageIO stamps on every file it writes) zeroed, so that files written in different seconds
// compare equal when everything else is; other bytes pass through unchanged.
std::string withoutCapDate(std::string bytes) {
    static const std::string key("capDate\0string\0", 15);
    const std::size_t at = bytes.find(key);
    if (at != std::string::npos && at + key.size() + 4 + 19 <= bytes.size())
        std::fill_n(bytes.begin() + static_cast<std::ptrdiff_t>(at + key.size() + 4), 19, '\0');
    return bytes;
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

// A first bake (default environment, face 8) into `out`, with a marker file added that a later
// successful bake must remove and a failed one must leave; its manifest text.
std::string bakeAnOldFolder(const fs::path& out) {
    BakeRequest first;
    first.import.faceSize = 8;
    first.outDir = out;
    bake(first);
    writeBytes(out / "marker.txt", "from the first bake\n");
    return readText(out / "manifest.json");
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
    const std::string oldManifest = bakeAnOldFolder(out);
    ASSERT_FALSE(oldManifest.empty());

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

namespace {

// Lowers the size of the largest file this process may write (RLIMIT_FSIZE, which binds root as
// well, unlike folder permissions), so that a larger file fails with EFBIG mid-write as on a full
// disk; restores the limit and SIGXFSZ's handler on destruction.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &saved_);
        previous_ = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG from write() instead of the fatal signal
        rlimit lowered = saved_;
        lowered.rlim_cur = bytes;
        applied_ = setrlimit(RLIMIT_FSIZE, &lowered) == 0;
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &saved_);
        std::signal(SIGXFSZ, previous_);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;
    bool applied() const { return applied_; }

private:
    rlimit saved_{};
    void (*previous_)(int) = SIG_DFL;
    bool applied_ = false;
};

// The `mipgloss` command line: MIPGLOSS_CLI where the build names it, else the one the build puts
// beside this test's folder (<build>/app/mipgloss for <build>/tests/mipgloss_io_tests).
fs::path cliPath() {
#ifdef MIPGLOSS_CLI
    return MIPGLOSS_CLI;
#else
    return fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "app" / "mipgloss";
#endif
}

// Runs `mipgloss ARGS` with stdout and stderr into `log`; its exit status (-1 if it did not exit).
int runCli(const std::string& args, const fs::path& log) {
    const std::string command = "'" + cliPath().string() + "' " + args + " > '" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

// Byte for byte, every file, apart from the time of day OpenImageIO writes into each EXR header.
TEST(Bake, ParallelWritesGiveTheSameBytesAsSerialOnes) {
    TempDir dir;
    struct Case {
        const char* what;
        BakeFormat format;
        ExrWriteOptions exr;
        std::size_t files;  // with the manifest
    };
    // Base 32: levels 32 .. 1 (6), irradiance on.
    for (const Case& c : {Case{"exr, bake's compression", BakeFormat::Exr, {kBakeExrCompression, false}, 6 * 6 + 6 + 2},
                          Case{"exr zip half (OpenEXR's own threads compress)", BakeFormat::Exr, {"zip", true}, 6 * 6 + 6 + 2},
                          Case{"dds", BakeFormat::Dds, {}, 3}}) {
        SCOPED_TRACE(c.what);
        BakeRequest request;
        request.import.faceSize = 32;
        request.irradiance = true;
        request.format = c.format;
        request.exr = c.exr;
        request.outDir = dir / "parallel";
        request.parallelWrite = true;
        const BakeSummary parallel = bake(request);
        request.outDir = dir / "serial";
        request.parallelWrite = false;
        const BakeSummary serial = bake(request);
        const auto a = filesUnder(dir / "parallel");
        const auto b = filesUnder(dir / "serial");
        EXPECT_EQ(a.size(), c.files);
        ASSERT_EQ(a.size(), b.size());
        int stamped = 0;
        for (const auto& [name, bytes] : a) {
            ASSERT_TRUE(b.count(name)) << name << " only in the parallel bake";
            EXPECT_TRUE(withoutCapDate(bytes) == withoutCapDate(b.at(name)))
                << name << " differs (" << bytes.size() << " and " << b.at(name).size() << " bytes)";
            if (withoutCapDate(bytes) != bytes) ++stamped;
        }
        // Only the EXR files carry a timestamp; the DDS files and the manifest are compared whole.
        EXPECT_EQ(stamped, c.format == BakeFormat::Exr ? static_cast<int>(c.files) - 1 : 0);
        EXPECT_EQ(parallel.filesWritten, static_cast<int>(c.files) - 1) << "image files, the manifest not counted";
        EXPECT_EQ(parallel.bytesWritten, serial.bytesWritten);
        std::uintmax_t images = 0;
        for (const auto& [name, bytes] : a)
            if (name != "manifest.json") images += bytes.size();
        EXPECT_EQ(parallel.bytesWritten, images);
    }
}

TEST(Bake, AFileThatCannotBeWrittenLeavesTheOldFolder) {
    TempDir dir;
    const fs::path out = dir / "baked";
    const std::string oldManifest = bakeAnOldFolder(out);

    struct Case {
        BakeFormat format;
        std::string compression;
    };
    for (const Case& c : {Case{BakeFormat::Exr, kBakeExrCompression}, Case{BakeFormat::Exr, "zip"},
                          Case{BakeFormat::Dds, ""}}) {
        for (const bool parallel : {true, false}) {
            const BakeFormat format = c.format;
            SCOPED_TRACE(std::string(bakeFormatName(format)) + " " + c.compression + (parallel ? ", parallel" : ", serial"));
            BakeRequest request;
            request.import.faceSize = 64;
            request.format = format;
            if (format == BakeFormat::Exr) request.exr.compression = c.compression;
            request.parallelWrite = parallel;
            request.outDir = out;
            std::string refusal;  // printed once the limit is lifted (stdout may be a file)
            {
                // 100 kB: every 64² level face (49 kB of float RGB) fits; the cube file does not
                // (the EXR's level 0 alone is 64 × 384 float RGB = 295 kB, which zip shrinks by a
                // few per cent only; the half DDS is 262 kB).
                FileSizeLimit limit(100 * 1024);
                ASSERT_TRUE(limit.applied());
                try {
                    bake(request);
                    ADD_FAILURE() << "a bake wrote a file larger than the file size limit";
                } catch (const EnvError& e) {
                    EXPECT_EQ(e.file().filename().string(),
                              format == BakeFormat::Exr ? "environment_mips.exr" : "environment_mips.dds")
                        << e.what();
                    refusal = e.what();
                }
            }
            std::printf("    refused as it should be: %s\n", refusal.c_str());
            EXPECT_TRUE(fs::exists(out / "marker.txt"));
            EXPECT_EQ(readText(out / "manifest.json"), oldManifest);
            EXPECT_TRUE(fs::is_directory(out / "level3"));
            const auto left = temporarySiblings(out);
            EXPECT_TRUE(left.empty()) << "temporary sibling left behind: " << (left.empty() ? "" : left.front());
        }
    }
    // Without the limit the same bake goes through and replaces the folder.
    BakeRequest again;
    again.import.faceSize = 64;
    again.format = BakeFormat::Dds;
    again.outDir = out;
    bake(again);
    EXPECT_FALSE(fs::exists(out / "marker.txt"));
    EXPECT_TRUE(fs::exists(out / "environment_mips.dds"));
}

TEST(Bake, DdsFormatWritesTheChainAndIrradianceAsCubeFiles) {
    TempDir dir;
    constexpr int kSize = 16;
    BakeRequest request;
    request.import.faceSize = kSize;
    request.irradiance = true;
    request.format = BakeFormat::Dds;
    request.ddsType = DdsType::Float;
    request.outDir = dir / "baked";
    const BakeSummary summary = bake(request);
    EXPECT_EQ(summary.cubeFile, summary.outDir / "environment_mips.dds");
    EXPECT_EQ(namesIn(request.outDir), (std::vector<std::string>{"environment_mips.dds", "irradiance.dds", "manifest.json"}));

    // Float: the chain bit for bit, every level.
    const CubeMap base = loadDefaultEnvironment(kSize).cube;
    const MipChain chain = buildChain(base, kDefaultBuilder);
    const DdsCube file = readCubeDds(request.outDir / "environment_mips.dds");
    ASSERT_EQ(file.chain.levelCount(), chain.levelCount());
    EXPECT_EQ(file.header.mipMapCount, static_cast<std::uint32_t>(fullChainLevelCount(kSize)));
    for (int k = 0; k < chain.levelCount(); ++k)
        for (Face f : kAllFaces)
            for (int y = 0; y < levelSize(kSize, k); ++y)
                for (int x = 0; x < levelSize(kSize, k); ++x)
                    ASSERT_EQ(file.chain.levels[static_cast<std::size_t>(k)].at(f, x, y),
                              chain.levels[static_cast<std::size_t>(k)].at(f, x, y))
                        << "level " << k << " " << faceName(f) << " (" << x << ", " << y << ")";
    const DdsCube irradiance = readCubeDds(request.outDir / "irradiance.dds");
    const CubeMap expected = computeIrradiance(base);
    ASSERT_EQ(irradiance.chain.levelCount(), 1);
    ASSERT_EQ(irradiance.chain.baseSize(), expected.size());
    for (Face f : kAllFaces)
        for (int y = 0; y < expected.size(); ++y)
            for (int x = 0; x < expected.size(); ++x)
                ASSERT_EQ(irradiance.chain.levels[0].at(f, x, y), expected.at(f, x, y)) << faceName(f);

    // The manifest says what was written; no level folders.
    const std::string json = readText(request.outDir / "manifest.json");
    EXPECT_EQ(stringField(json, "file_format"), "dds");
    EXPECT_EQ(stringField(json, "cube_file"), "environment_mips.dds");
    EXPECT_EQ(stringField(json, "dxgi_format"), "R32G32B32A32_FLOAT");
    EXPECT_NE(json.find("\"irradiance\": {\"file\": \"irradiance.dds\""), std::string::npos) << json;
    EXPECT_EQ(manifestLevels(json).size(), 0u) << "level entries with a folder: there are none";
    const std::regex nullDir("\"dir\": null");
    EXPECT_EQ(std::distance(std::sregex_iterator(json.begin(), json.end(), nullDir), std::sregex_iterator()),
              chain.levelCount());
}

TEST(Bake, ExrCompressionAndPixelTypeAreApplied) {
    TempDir dir;
    BakeRequest request;
    request.import.faceSize = 16;
    request.exr = {"piz", true};
    request.outDir = dir / "baked";
    bake(request);
    const std::string json = readText(request.outDir / "manifest.json");
    EXPECT_EQ(stringField(json, "file_format"), "exr");
    EXPECT_EQ(stringField(json, "compression"), "piz");
    EXPECT_EQ(stringField(json, "pixel_type"), "half");
    for (const fs::path& file : {request.outDir / "level0" / "px.exr", request.outDir / "environment_mips.exr"}) {
        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in) << file;
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF) << file;
        EXPECT_EQ(in->spec().get_string_attribute("compression"), "piz") << file;
    }
    // bake's default: float, kBakeExrCompression.
    request.exr = BakeRequest().exr;
    bake(request);
    auto in = OIIO::ImageInput::open((request.outDir / "level0" / "px.exr").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(in->spec().get_string_attribute("compression"), kBakeExrCompression);
    // A compression OpenImageIO does not write is refused before anything is written.
    request.exr.compression = "lzma";
    request.outDir = dir / "never";
    EXPECT_THROW(bake(request), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir / "never"));
}

TEST(BakeCommand, BadFormatOptionsExitWithStatusTwo) {
    const fs::path cli = cliPath();
    ASSERT_TRUE(fs::exists(cli)) << "the mipgloss command line is built beside the tests: " << cli;
    TempDir dir;
    const fs::path log = dir / "log.txt";
    const std::string out = " --out '" + (dir / "out").string() + "'";
    for (const std::string bad :
         {"--format ktx", "--format", "--format dds --dds-type double", "--dds-type half", "--format exr --dds-type float",
          "--format dds --exr-compression zip", "--exr-compression lzma", "--exr-compression zip:x",
          "--exr-compression piz:3", "--exr-type double", "--format dds --exr-type half"}) {
        SCOPED_TRACE(bad);
        EXPECT_EQ(runCli("bake --size 8 --quiet" + out + " " + bad, log), 2) << readText(log);
        EXPECT_NE(readText(log).find("mipgloss: "), std::string::npos) << readText(log);
        EXPECT_FALSE(fs::exists(dir / "out")) << "a refused bake wrote its folder";
    }
    // The same options, well formed, bake.
    ASSERT_EQ(runCli("bake --size 8 --quiet --format dds --dds-type float" + out, log), 0) << readText(log);
    EXPECT_EQ(readCubeDds(dir / "out" / "environment_mips.dds").header.dxgiFormat, kDxgiR32G32B32A32Float);
    EXPECT_NE(readText(log).find("dds float"), std::string::npos) << readText(log);
    ASSERT_EQ(runCli("bake --size 8 --quiet --exr-compression zip:9 --exr-type half" + out, log), 0) << readText(log);
    EXPECT_EQ(stringField(readText(dir / "out" / "manifest.json"), "compression"), "zip:9");
}
