// mipgloss_replay_truth_dump ENV FACE ROUGHNESS DUMP.csv: a metal row's pixels as `mipgloss bench
// truth --dump` wrote them (each pixel's normal and view at its centre), replayed through the CPU
// model of a held GGX layer's fitted lobes (object.frag, readGgx: ggx_fitted_lobes.h, each lobe
// the exact normalized Phong lobe over the base faces, referenceLobeAt; the albedo table's A + B)
// for a white metal, against the truth (material_truth.h) on the same pixels. Per N·v bin of width
// 0.2: relative RMS and Σ model / Σ truth − 1, and the dump's own picture against its truth (green).
// What the fit gives apart from the GPU's stack, lights and footprint: where both are off alike,
// the fit is; where only the picture is, the renderer is (docs/material-truth.md, "Refits tried").
// The whole environment is read through the lobes (no lights taken out): compare maps without a
// sun (forest), or the picture with `--lights off`.
#include "core/scene/fitted_lobes_model.h"
#include "mipgloss/ibl/colour.h"
#include "mipgloss/ibl/ggx_fitted_lobes.h"
#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/io/import.h"
#include "mipgloss/scene/material_truth.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace mipgloss;

namespace {

constexpr int kBins = 5;

// Squared error, squared truth and the two sums, per N·v bin.
struct Bins {
    std::array<double, kBins> error{}, truth2{}, model{}, truth{};
    void add(int bin, double m, double t) {
        error[static_cast<std::size_t>(bin)] += (m - t) * (m - t);
        truth2[static_cast<std::size_t>(bin)] += t * t;
        model[static_cast<std::size_t>(bin)] += m;
        truth[static_cast<std::size_t>(bin)] += t;
    }
    void print(const char* name) const {
        double e = 0.0, t = 0.0;
        for (int b = 0; b < kBins; ++b) {
            e += error[static_cast<std::size_t>(b)];
            t += truth2[static_cast<std::size_t>(b)];
        }
        std::printf("%-22s all %5.2f %%", name, 100.0 * std::sqrt(e / t));
        for (std::size_t b = 0; b < kBins; ++b)
            if (truth2[b] > 0.0)
                std::printf(" | %.1f: %5.1f %% %+5.1f %%", 0.2 * static_cast<double>(b), 100.0 * std::sqrt(error[b] / truth2[b]),
                            100.0 * (model[b] / truth[b] - 1.0));
        std::printf("\n");
    }
};

// The white metal's specular as the renderer's held loop reads it: the fitted lobes' mean
// (fitted_lobes_model.h) times the albedo table's A + B.
double fittedModel(const CubeMap& base, double roughness, const glm::dvec3& n, const glm::dvec3& v) {
    const GgxAlbedoTable::Albedo a = GgxAlbedoTable::shared().at(roughness, glm::dot(n, v));
    return (a.a + a.b) * test::fittedLobesMean(base, roughness, n, v);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 5) {
        std::cerr << "usage: mipgloss_replay_truth_dump ENV FACE ROUGHNESS DUMP.csv\n";
        return 2;
    }
    try {
        const double roughness = std::stod(argv[3]);
        if (!readsFittedLobes(roughness, kFittedLobeCount)) {
            std::cerr << "roughness " << roughness << " has no fitted lobes (ggx_fitted_lobes.h)\n";
            return 2;
        }
        ImportOptions options;
        options.faceSize = std::stoi(argv[2]);
        const CubeMap base = loadEnvironment(argv[1], options).cube;
        const RadianceTree tree(base);
        Layers metal;
        metal.baseColor = Rgb(1.0f);
        metal.metallic = 1.0f;
        metal.roughness = static_cast<float>(roughness);
        std::ifstream in(argv[4]);
        if (!in) throw std::runtime_error(std::string("cannot read ") + argv[4]);
        std::string line;
        std::getline(in, line);  // x,y,cos_view,shown_rgb,truth_rgb,karis_rgb,n_xyz,v_xyz
        Bins model, picture;
        int row = 1;
        while (std::getline(in, line)) {
            ++row;
            std::vector<double> c;
            std::stringstream fields(line);
            for (std::string field; std::getline(fields, field, ',');) c.push_back(std::stod(field));
            if (c.size() < 18) throw std::runtime_error(std::string(argv[4]) + " line " + std::to_string(row) + ": no normal and view (a dump from before they were written)");
            const glm::dvec3 n(c[12], c[13], c[14]), v(c[15], c[16], c[17]);
            const int bin = std::min(kBins - 1, static_cast<int>(c[2] / 0.2));
            model.add(bin, fittedModel(base, roughness, n, v), materialTruth(tree, metal, n, v).specular.y);
            picture.add(bin, c[4], c[7]);
        }
        model.print("fitted lobes (CPU)");
        picture.print("the dump's picture");
    } catch (const std::exception& e) {
        std::cerr << "mipgloss_replay_truth_dump: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
