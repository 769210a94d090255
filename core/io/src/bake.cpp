#include "mipgloss/io/bake.h"

#include "mipgloss/io/cube_exr.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/phong.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <limits>
#include <sstream>
#include <system_error>

namespace mipgloss {

namespace fs = std::filesystem;

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string jsonEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out;
}

// A fresh sibling of `target` that does not exist yet.
fs::path temporarySibling(const fs::path& target, const char* tag) {
    std::random_device rd;
    for (int attempt = 0; attempt < 100; ++attempt) {
        fs::path p = target;
        p += std::string(".") + tag + "-" + std::to_string(rd() % 1000000);
        if (!fs::exists(p)) return p;
    }
    throw EnvError(target, "cannot find a free temporary name beside it");
}

// Removes a directory tree, ignoring errors (cleanup after a failure).
void removeQuietly(const fs::path& p) {
    std::error_code ec;
    fs::remove_all(p, ec);
}

}  // namespace

std::string manifestJson(const BakeSummary& summary, Builder builder, const std::string& source) {
    std::ostringstream o;
    o.precision(10);
    o << "{\n";
    o << "  \"format\": \"mipgloss-bake\",\n";
    o << "  \"builder\": \"" << builderName(builder) << "\",\n";
    o << "  \"source\": \"" << jsonEscape(source) << "\",\n";
    o << "  \"layout\": \"" << layoutName(summary.report.layout) << "\",\n";
    o << "  \"face_size\": " << summary.faceSize << ",\n";
    o << "  \"face_order\": [\"px\", \"nx\", \"py\", \"ny\", \"pz\", \"nz\"],\n";
    o << "  \"orientation\": \"OpenGL cube map faces; row 0 of each image is t = 0\",\n";
    o << "  \"lambda_to_exponent\": \"n = 3 * 128^2 * 4^-lambda - 1, lambda 0 the mirror (the same at every face size)\",\n";
    o << "  \"schedule\": \"level k holds n = M^2/32 (M its face size, sigma about 3.6 texels), n = 1 at the last read level\",\n";
    o << "  \"cube_file\": \"" << jsonEscape(summary.cubeFile.filename().string()) << "\",\n";
    o << "  \"levels\": [\n";
    for (std::size_t i = 0; i < summary.levels.size(); ++i) {
        const BakedLevel& l = summary.levels[i];
        auto number = [](double v) {
            std::ostringstream t;
            t.precision(10);
            if (std::isfinite(v)) t << v;
            else t << "null";
            return t.str();
        };
        o << "    {\"level\": " << l.level << ", \"size\": " << l.size << ", \"read\": " << (l.read ? "true" : "false")
          << ", \"phong_exponent\": " << number(l.phongExponent) << ", \"lambda\": " << number(l.lambda)
          << ", \"dir\": \"level" << l.level << "\"}"
          << (i + 1 < summary.levels.size() ? "," : "") << "\n";
    }
    o << "  ],\n";
    if (summary.irradiance)
        o << "  \"irradiance\": {\"dir\": \"irradiance\", \"face_size\": "
          << std::min(kIrradianceFaceSize, summary.faceSize) << ", \"quantity\": \"E(N)/pi\"},\n";
    else
        o << "  \"irradiance\": null,\n";
    o << "  \"sanitized\": {\"nan\": " << summary.report.nanCount << ", \"inf\": " << summary.report.infCount
      << ", \"negative\": " << summary.report.negativeCount << "}\n";
    o << "}\n";
    return o.str();
}

BakeSummary bake(const BakeRequest& request) {
    if (request.outDir.empty()) throw std::invalid_argument("no output directory given");
    auto report = [&](const std::string& stage, float f) { reportProgress(request.progress, stage, f); };

    BakeSummary summary;
    const auto t0 = std::chrono::steady_clock::now();
    ImportedEnvironment env =
        request.environment.empty()
            ? loadDefaultEnvironment(request.import.faceSize > 0 ? request.import.faceSize : 128)
            : loadEnvironment(request.environment, request.import, request.progress);
    summary.importSeconds = secondsSince(t0);
    summary.report = env.report;
    summary.faceSize = env.cube.size();

    const auto t1 = std::chrono::steady_clock::now();
    BuildOptions options;
    options.progress = [&](const std::string& stage, float f) {
        return !request.progress || request.progress(stage + " " + builderName(request.builder), f);
    };
    const MipChain chain = buildChain(env.cube, request.builder, options);
    CubeMap irradiance;
    if (request.irradiance) {
        report("irradiance", 0.0f);
        irradiance = computeIrradiance(env.cube);
        report("irradiance", 1.0f);
    }
    summary.buildSeconds = secondsSince(t1);

    const auto t2 = std::chrono::steady_clock::now();
    const fs::path out = fs::absolute(request.outDir).lexically_normal();
    std::error_code ec;
    if (!out.parent_path().empty()) fs::create_directories(out.parent_path(), ec);
    if (fs::exists(out) && !fs::is_directory(out)) throw EnvError(out, "exists and is not a directory");
    const fs::path staging = temporarySibling(out, "partial");
    try {
        fs::create_directories(staging);
        for (int k = 0; k < chain.levelCount(); ++k) {
            report("write", static_cast<float>(k) / static_cast<float>(chain.levelCount()));
            writeFaceImages(chain.levels[static_cast<std::size_t>(k)], staging / ("level" + std::to_string(k)));
            BakedLevel level;
            level.level = k;
            level.size = chain.levels[static_cast<std::size_t>(k)].size();
            level.read = k <= lastReadLevel(summary.faceSize);
            level.phongExponent = levelExponent(summary.faceSize, k);
            level.lambda = level.read ? exponentToLambda(level.phongExponent)
                                      : std::numeric_limits<double>::quiet_NaN();
            summary.levels.push_back(level);
        }
        if (request.irradiance) writeFaceImages(irradiance, staging / "irradiance");
        summary.irradiance = request.irradiance;
        summary.cubeFile = out / "environment_mips.exr";
        writeCubeEnvironmentExr(chain, staging / summary.cubeFile.filename());
        const std::string source = request.environment.empty() ? "embedded default environment"
                                                               : fs::absolute(request.environment).string();
        const fs::path manifest = staging / "manifest.json";
        FILE* f = std::fopen(manifest.c_str(), "wb");
        if (!f) throw EnvError(manifest, "cannot be created");
        const std::string text = manifestJson(summary, request.builder, source);
        const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
        if (std::fclose(f) != 0 || !ok) throw EnvError(manifest, "could not be written completely");

        // Swap the finished directory into place; the old one survives until the new one is there.
        fs::path old;
        if (fs::exists(out)) {
            old = temporarySibling(out, "old");
            fs::rename(out, old);
        }
        fs::rename(staging, out, ec);
        if (ec) {
            if (!old.empty()) fs::rename(old, out);
            throw EnvError(out, "cannot move the finished bake into place: " + ec.message());
        }
        if (!old.empty()) removeQuietly(old);
    } catch (const fs::filesystem_error& e) {
        removeQuietly(staging);
        throw EnvError(e.path1().empty() ? out : e.path1(), e.code().message());
    } catch (...) {
        removeQuietly(staging);
        throw;
    }
    summary.outDir = out;
    summary.writeSeconds = secondsSince(t2);
    report("done", 1.0f);
    return summary;
}

}  // namespace mipgloss
