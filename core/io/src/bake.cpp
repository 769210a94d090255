#include "mipgloss/io/bake.h"

#include "mipgloss/io/atomic_write.h"
#include "mipgloss/io/cube_exr.h"
#include "mipgloss/io/dds.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/parallel.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/default_env.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <random>
#include <sstream>
#include <system_error>
#include <thread>

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

// A file in the staging folder named as it would have been in the output folder, for messages (the
// staging folder is gone by the time the user reads them); other paths unchanged.
fs::path inOutput(const fs::path& file, const fs::path& staging, const fs::path& out) {
    const fs::path rel = file.lexically_relative(staging);
    if (rel.empty() || *rel.begin() == "..") return file;
    return rel == "." ? out : out / rel;
}

// Removes a directory tree, ignoring errors (cleanup after a failure).
void removeQuietly(const fs::path& p) {
    std::error_code ec;
    fs::remove_all(p, ec);
}

// Runs the file writers, in parallel on the thread pool or one at a time, and reports progress
// from the calling thread as files finish (Progress's contract). The first error stops the rest
// from starting and is rethrown once the running ones have finished; so is a cancel. Nothing here
// removes files: the caller drops the whole staging folder.
void runWriters(const std::vector<std::function<void()>>& writers, bool parallel, const Progress& progress) {
    const int total = static_cast<int>(writers.size());
    std::mutex mutex;
    std::condition_variable changed;
    int done = 0;
    bool finished = false;
    std::atomic<bool> stop{false};
    std::exception_ptr error;
    auto writeOne = [&](int i) {
        if (stop.load()) return;
        try {
            writers[static_cast<std::size_t>(i)]();
        } catch (...) {
            std::lock_guard lock(mutex);
            if (!error) error = std::current_exception();
            stop = true;
        }
        {
            std::lock_guard lock(mutex);
            ++done;
        }
        changed.notify_one();
    };
    auto report = [&](int count) {
        return !progress || progress("write", static_cast<float>(count) / static_cast<float>(std::max(1, total)));
    };

    if (!parallel || total < 2) {
        for (int i = 0; i < total && !stop; ++i) {
            writeOne(i);
            if (!error && !report(i + 1)) stop = true;
        }
        if (error) std::rethrow_exception(error);
        if (stop) throw Cancelled{};
        return;
    }

    std::thread runner([&] {
        parallelFor(0, total, writeOne);
        {
            std::lock_guard lock(mutex);
            finished = true;
        }
        changed.notify_one();
    });
    std::exception_ptr progressError;  // a Progress that throws: stop, wait, rethrow
    int reported = 0;
    std::unique_lock lock(mutex);
    while (true) {
        changed.wait(lock, [&] { return finished || done != reported; });
        const int now = done;
        const bool end = finished;
        if (now != reported && !stop) {
            reported = now;
            lock.unlock();
            bool goOn = false;
            try {
                goOn = report(now);
            } catch (...) {
                progressError = std::current_exception();
            }
            if (!goOn) stop = true;
            lock.lock();
        }
        reported = now;
        if (end) break;
    }
    lock.unlock();
    runner.join();
    if (error) std::rethrow_exception(error);
    if (progressError) std::rethrow_exception(progressError);
    if (stop) throw Cancelled{};
}

}  // namespace

const char* bakeFormatName(BakeFormat format) { return format == BakeFormat::Exr ? "exr" : "dds"; }

bool parseBakeFormat(const std::string& name, BakeFormat& out) {
    if (name == "exr") out = BakeFormat::Exr;
    else if (name == "dds") out = BakeFormat::Dds;
    else return false;
    return true;
}

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
    o << "  \"file_format\": \"" << bakeFormatName(summary.format) << "\",\n";
    if (summary.format == BakeFormat::Exr)
        o << "  \"exr\": {\"compression\": \"" << jsonEscape(summary.exr.compression) << "\", \"pixel_type\": \""
          << (summary.exr.half ? "half" : "float") << "\"},\n";
    else
        o << "  \"dds\": {\"dxgi_format\": \""
          << (summary.ddsType == DdsType::Half ? "R16G16B16A16_FLOAT" : "R32G32B32A32_FLOAT")
          << "\", \"face_order\": \"+X -X +Y -Y +Z -Z, each with its mips\", \"orientation\": \"as the OpenGL faces; "
             "Direct3D samples a cube map by the same table\"},\n";
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
          << ", \"dir\": "
          << (summary.format == BakeFormat::Exr ? "\"level" + std::to_string(l.level) + "\"" : std::string("null")) << "}"
          << (i + 1 < summary.levels.size() ? "," : "") << "\n";
    }
    o << "  ],\n";
    if (summary.irradiance)
        o << "  \"irradiance\": {"
          << (summary.format == BakeFormat::Exr ? "\"dir\": \"irradiance\"" : "\"file\": \"irradiance.dds\"")
          << ", \"face_size\": "
          << std::min(kIrradianceFaceSize, summary.faceSize) << ", \"quantity\": \"E(N)/pi\"},\n";
    else
        o << "  \"irradiance\": null,\n";
    o << "  \"sanitized\": {\"nan\": " << summary.report.nanCount << ", \"inf\": " << summary.report.infCount
      << ", \"negative\": " << summary.report.negativeCount
      << ", \"huge\": " << summary.report.hugeCount << "}\n";
    o << "}\n";
    return o.str();
}

BakeSummary bake(const BakeRequest& request) {
    if (request.outDir.empty()) throw std::invalid_argument("no output directory given");
    if (request.format == BakeFormat::Exr && !isExrCompression(request.exr.compression))
        throw std::invalid_argument("unknown OpenEXR compression '" + request.exr.compression + "'");
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
    for (int k = 0; k < chain.levelCount(); ++k) {
        BakedLevel level;
        level.level = k;
        level.size = chain.levels[static_cast<std::size_t>(k)].size();
        level.read = k <= lastReadLevel(summary.faceSize);
        level.phongExponent = levelExponent(summary.faceSize, k);
        level.lambda = level.read ? exponentToLambda(level.phongExponent) : std::numeric_limits<double>::quiet_NaN();
        summary.levels.push_back(level);
    }
    summary.format = request.format;
    summary.exr = request.exr;
    summary.ddsType = request.ddsType;
    summary.irradiance = request.irradiance;
    summary.cubeFile = out / (request.format == BakeFormat::Exr ? "environment_mips.exr" : "environment_mips.dds");
    const fs::path staging = temporaryBeside(out, "partial");
    try {
        fs::create_directories(staging);
        // One writer per file, the largest first so that the pool ends together. Each owns its
        // OpenImageIO ImageOutput (or FILE) and reads the chain only, so they share nothing.
        std::vector<std::function<void()>> writers;
        const fs::path cubeFile = staging / summary.cubeFile.filename();
        if (request.format == BakeFormat::Exr) {
            writers.emplace_back([&] { writeCubeEnvironmentExr(chain, cubeFile, request.exr); });
            auto addFaces = [&](const CubeMap& cube, const fs::path& dir) {
                fs::create_directories(dir);
                for (Face f : kAllFaces)
                    writers.emplace_back([&cube, f, dir, &request] {
                        writeFaceImage(cube, f, dir / (std::string(faceName(f)) + ".exr"), request.exr);
                    });
            };
            for (int k = 0; k < chain.levelCount(); ++k)
                addFaces(chain.levels[static_cast<std::size_t>(k)], staging / ("level" + std::to_string(k)));
            if (request.irradiance) addFaces(irradiance, staging / "irradiance");
        } else {
            writers.emplace_back([&] { writeCubeDds(chain, cubeFile, request.ddsType); });
            if (request.irradiance)
                writers.emplace_back([&] {
                    MipChain one;
                    one.levels.push_back(irradiance);
                    writeCubeDds(one, staging / "irradiance.dds", request.ddsType);
                });
        }
        report("write", 0.0f);
        runWriters(writers, request.parallelWrite, request.progress);
        for (const auto& entry : fs::recursive_directory_iterator(staging))
            if (entry.is_regular_file()) {
                ++summary.filesWritten;
                summary.bytesWritten += entry.file_size();
            }

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
            old = temporaryBeside(out, "old");
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
        throw EnvError(e.path1().empty() ? out : inOutput(e.path1(), staging, out), e.code().message());
    } catch (const FileError& e) {
        removeQuietly(staging);
        throw EnvError(inOutput(e.file(), staging, out), e.reason());
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
