// `mipgloss bench stack`: per environment and base face size, what the lobe stack (scene/lobes.h)
// costs and how close its reads come to the lobe they claim. Timings are printed, never asserted.
#include "bench_stack.h"

#include "cli_report.h"

#include "mipgloss/ibl/builders.h"
#include "mipgloss/ibl/metrics.h"
#include "mipgloss/ibl/parallel.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/mesh.h"
#include "mipgloss/scene/lobes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mipgloss::app {

const char* kStackBenchUsage = R"(
  mipgloss bench stack [--env FILE]... [--sizes 128,256] [--directions D] [--first-level L]

bench stack: for each environment and base face size N, the lobe stack (exact lobes at lambda = j/8,
  neighbours 2^(1/4) apart in exponent; docs/lobe-stack.md):
    build     every entry from the sharpest the base holds (stackTop) to n = 0, one after another
              on this machine's cores, timed; and the entries one lambda in use asks for
    memory    the atlas the renderer packs them into (RGB9_E5, 4 bytes a texel), the full range
              and one lambda's entries
    error     the stack's read at lambda = k, k + 1/4, k + 1/2, k + 3/4 for each chain level k from
              --first-level on (each entry bilinear, neighbours blended: what the renderer reads at
              that lambda the moment it changes; in float: the GPU's shared-exponent storage adds
              at most 0.1 %) against the exact normalized Phong convolution of the base, relative
              RMS over D uniform directions; and the worst
  --env FILE       environment, repeatable (default: the embedded default environment)
  --sizes LIST     base face sizes (default 128,256)
  --directions D   directions per lambda (default 400)
  --first-level L  the first chain level whose quarter steps are read (default 1; 0 reads the
                   sharpest lobes, where the exact convolution takes longest)
)";

namespace {

using Clock = std::chrono::steady_clock;


int parseCount(const std::string& flag, const std::string& text, int minimum, int maximum) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || v < minimum || v > maximum)
        throw UsageError(flag + ": '" + text + "' is not a whole number from " + std::to_string(minimum) + " to " +
                         std::to_string(maximum));
    return static_cast<int>(v);
}

std::vector<int> parseList(const std::string& flag, const std::string& text) {
    std::vector<int> out;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(parseCount(flag, item, 16, 4096));
    if (out.empty()) throw UsageError(flag + " needs at least one size");
    return out;
}

double atlasMegabytes(const std::map<int, std::shared_ptr<const LobeStackEntry>>& entries, const std::vector<int>& indices) {
    std::vector<std::pair<int, int>> sizes;
    for (int j : indices) sizes.emplace_back(j, entries.at(j)->cube->size());
    return lobeStackAtlas(sizes).megabytes(4);
}

}  // namespace

int runStackBench(Args args) {
    std::vector<std::string> envs;
    std::vector<int> sizes{128, 256};
    int directions = 400, firstLevel = 1;
    while (!args.empty()) {
        const std::string a = args.next();
        if (a == "--env") envs.push_back(args.value(a));
        else if (a == "--sizes") sizes = parseList(a, args.value(a));
        else if (a == "--directions") directions = parseCount(a, args.value(a), 10, 100000);
        else if (a == "--first-level") firstLevel = parseCount(a, args.value(a), 0, 7);
        else throw UsageError("bench stack: unknown option '" + a + "'");
    }
    if (envs.empty()) envs.push_back("");  // the embedded default
    const auto dirs = uniformDirections(directions, 11);
    std::printf("# mipgloss bench stack: the lobe stack's cost and its read error at any lambda (%d threads)\n",
                workerCount());
    for (const std::string& env : envs) {
        for (int size : sizes) {
            const CubeMap base = env.empty() ? loadDefaultEnvironment(size).cube : [&] {
                ImportOptions options;
                options.faceSize = size;
                return loadEnvironment(env, options).cube;
            }();
            const std::string name = env.empty() ? "default" : std::filesystem::path(env).filename().string();
            PreparedEnvironment prepared;
            prepared.filter = std::make_shared<const PhongFilter>(base);
            const int top = stackTop(size);
            // Build: every entry, sharpest first, each on all cores (PhongFilter::filter is parallel).
            std::map<int, std::shared_ptr<const LobeStackEntry>> entries;
            std::vector<int> all;
            const auto start = Clock::now();
            for (int j = top; j <= kStackLast; ++j) {
                entries[j] = std::make_shared<const LobeStackEntry>(makeStackEntry(prepared, j));
                all.push_back(j);
            }
            const double fullSeconds = secondsSince(start);
            // One λ's entries: λ 3 (n = 767), a typical glossy material.
            Scene one;
            {
                SceneObject object;
                object.mesh = std::make_shared<const Mesh>(makeSphere(4, 8));
                Material m;
                m.lambda = 3.0f;
                one.addObject(object, m);
                one.display.showBackground = false;
            }
            const std::vector<int> inUse = lobesInUse(one, size);
            const auto oneStart = Clock::now();
            for (int j : inUse) (void)makeStackEntry(prepared, j);
            const double oneSeconds = secondsSince(oneStart);
            std::printf("\n## %s, base %d: entries %d..%d (n %.0f .. 0)\n", name.c_str(), size, top, kStackLast,
                        stackExponent(top));
            std::printf("build   full range %.3f s (%zu entries), lambda 3's %zu entries %.3f s\n", fullSeconds,
                        all.size(), inUse.size(), oneSeconds);
            std::printf("memory  full range %.1f MB, lambda 3's entries %.1f MB (RGB9_E5 atlas)\n",
                        atlasMegabytes(entries, all), atlasMegabytes(entries, inUse));
            std::printf("error   lambda      n       rel RMS   (stack read against the exact lobe, %d directions)\n",
                        directions);
            double worst = 0.0, worstLambda = 0.0;
            for (int k = firstLevel; k <= 7; ++k)
                for (int q = 0; q < 4; ++q) {
                    const double lambda = k + q / 4.0;
                    const double n = lambdaToExponent(lambda);
                    if (!stackBlend(n, size)) continue;
                    std::vector<Rgb> read;
                    for (const glm::vec3& d : dirs) read.push_back(*readLobeStack(entries, n, size, d));
                    const double err = relativeRms(read, referenceLobeAt(base, n, dirs));
                    if (err > worst) {
                        worst = err;
                        worstLambda = lambda;
                    }
                    std::printf("        %6.2f %9.2f   %6.3f %%\n", lambda, n, 100.0 * err);
                }
            std::printf("worst   %.3f %% at lambda %.2f\n", 100.0 * worst, worstLambda);
        }
    }
    return 0;
}

}  // namespace mipgloss::app
