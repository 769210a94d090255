// mipgloss_benchmarks: timings, kept out of the unit suite (CTest label "bench", excluded from the
// dev test preset; run with `ctest --preset bench` or the executable itself). Every benchmark
// reports a ratio measured within one run on one machine, never an absolute time to compare
// against a constant:
//   MeshImport/{ply,obj}    loadMesh on a ~1M-triangle file vs OpenMesh's read_mesh alone on the
//                           same file (what mipgloss's checks and conversion cost on top)
//   PhongSkipLevels/k       the default builder at face 256 filtering through level k (the rest
//                           box steps, BuildOptions::lastFilteredLevel) vs filtering all levels
// Correctness is the unit tests' job; a benchmark only stops with an error when its input is not
// what it claims to time.
#include "mipgloss/ibl/builders.h"
#include "mipgloss/io/default_env.h"
#include "mipgloss/assets/mesh_files.h"
#include "mesh_files.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <benchmark/benchmark.h>

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

using namespace mipgloss;
namespace fs = std::filesystem;

namespace {

using test::append;
using test::binaryPly;
using test::objText;

using Clock = std::chrono::steady_clock;
double secondsBetween(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// The million-triangle files, written once per process into a folder removed at exit.
struct MillionTriangleFiles {
    fs::path dir;
    Mesh sphere;
    MillionTriangleFiles() {
        dir = fs::temp_directory_path() / ("mipgloss_bench_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        sphere = makeSphere(500, 1000);  // 998,000 triangles
        std::ofstream(dir / "million.ply", std::ios::binary) << binaryPly(sphere);
        std::ofstream(dir / "million.obj", std::ios::binary) << objText(sphere);
    }
    ~MillionTriangleFiles() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    static MillionTriangleFiles& get() {
        static MillionTriangleFiles files;
        return files;
    }
};

// One iteration = loadMesh then OpenMesh's read_mesh on the same file; the iteration time
// reported is loadMesh's, the ratio is summed loadMesh time over summed read_mesh time.
void MeshImport(benchmark::State& state, const char* name) {
    MillionTriangleFiles& files = MillionTriangleFiles::get();
    const fs::path file = files.dir / name;
    double loadSeconds = 0.0, readSeconds = 0.0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        const Mesh mesh = loadMesh(file);
        const auto t1 = Clock::now();
        OpenMesh::TriMesh_ArrayKernelT<> raw;
        const bool read = OpenMesh::IO::read_mesh(raw, file.string());
        const auto t2 = Clock::now();
        if (!read || mesh.triangleCount() != files.sphere.triangleCount() || raw.n_faces() != mesh.triangleCount()) {
            state.SkipWithError("the million-triangle file did not load whole");
            break;
        }
        loadSeconds += secondsBetween(t0, t1);
        readSeconds += secondsBetween(t1, t2);
        state.SetIterationTime(secondsBetween(t0, t1));
    }
    state.counters["MB"] = static_cast<double>(fs::file_size(file)) / 1e6;
    state.counters["triangles"] = static_cast<double>(files.sphere.triangleCount());
    state.counters["loadMesh_s"] = loadSeconds / static_cast<double>(state.iterations());
    state.counters["read_mesh_s"] = readSeconds / static_cast<double>(state.iterations());
    state.counters["ratio"] = readSeconds > 0.0 ? loadSeconds / readSeconds : 0.0;
}
BENCHMARK_CAPTURE(MeshImport, ply, "million.ply")->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(MeshImport, obj, "million.obj")->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(2);

const CubeMap& base256() {
    static const CubeMap base = loadDefaultEnvironment(256).cube;
    return base;
}

// One iteration = the chain filtered through level k, then the chain filtered at every level;
// the iteration time reported is the first, the ratio is the first over the second.
void PhongSkipLevels(benchmark::State& state) {
    const int through = static_cast<int>(state.range(0));
    const CubeMap& base = base256();
    double partSeconds = 0.0, allSeconds = 0.0;
    for (auto _ : state) {
        BuildOptions part;
        part.lastFilteredLevel = through;
        const auto t0 = Clock::now();
        const MipChain partial = buildChain(base, Builder::Phong, part);
        const auto t1 = Clock::now();
        const MipChain full = buildChain(base, Builder::Phong);
        const auto t2 = Clock::now();
        benchmark::DoNotOptimize(partial.levels.data());
        benchmark::DoNotOptimize(full.levels.data());
        if (partial.levelCount() != fullChainLevelCount(256) || full.levelCount() != partial.levelCount()) {
            state.SkipWithError("the chain is not full");
            break;
        }
        partSeconds += secondsBetween(t0, t1);
        allSeconds += secondsBetween(t1, t2);
        state.SetIterationTime(secondsBetween(t0, t1));
    }
    state.counters["through_level"] = through;
    state.counters["all_levels_s"] = allSeconds / static_cast<double>(state.iterations());
    state.counters["ratio_vs_all"] = allSeconds > 0.0 ? partSeconds / allSeconds : 0.0;
}
BENCHMARK(PhongSkipLevels)->Arg(0)->Arg(3)->Arg(5)->Arg(8)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
