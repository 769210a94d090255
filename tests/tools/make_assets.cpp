// mipgloss_make_assets OUTDIR: writes the demo assets README renders and the asset tests read
// (their sources are this file; tests/assets/SOURCES.md), each with analytic content:
//   checker_sphere.glb   a UV sphere, base colour an 8 × 4 checker of red and teal (sRGB PNG,
//                        embedded), roughness from the metallic–roughness map's G rising from
//                        0.05 at u = 0 to 0.95 at u = 1, dielectric
//   tiles.gltf           a quad of tiles with external images (tiles_color.png, tiles_normal.png:
//                        bevelled tile edges) and a missing occlusion image (a warning, drawn
//                        without it)
//   crate.obj, crate.mtl a cube with UVs, map_Kd a checker, map_Pr a roughness stripe image
// With --big: big.glb, the benchmark asset: a UV sphere of 1,000,000 triangles with four
// 4096² textures (base colour, metallic–roughness, normal, occlusion) as external PNGs of noise
// (incompressible, as photographed textures are), for `mipgloss bench-render --mesh big.glb`.
#include "gltf_writer.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace fs = std::filesystem;
using namespace mipgloss;
using namespace mipgloss::test;

namespace {

TestImage checker(int width, int height, int cellsX, int cellsY) {
    return makeImage(width, height, 3, [&](int x, int y) -> std::vector<std::uint8_t> {
        const bool odd = ((x * cellsX / width) + (y * cellsY / height)) % 2 == 1;
        return odd ? std::vector<std::uint8_t>{200, 30, 30} : std::vector<std::uint8_t>{20, 160, 170};
    });
}

void checkerSphere(const fs::path& dir) {
    GltfWriter w;
    const int base = w.addTexture(w.addImage(encodePng(checker(256, 128, 8, 4))));
    const TestImage mr = makeImage(256, 8, 3, [](int x, int) -> std::vector<std::uint8_t> {
        const double u = (x + 0.5) / 256.0;
        return {255, static_cast<std::uint8_t>(std::lround(255.0 * (0.05 + 0.9 * u))), 0};
    });
    const int roughness = w.addTexture(w.addImage(encodePng(mr)));
    const int material = w.addMaterial(pbrMaterial("Checker gradient", {1, 1, 1, 1}, 1.0, 1.0, base, roughness));
    w.addToScene(w.addNode(w.addMesh(texturedSphere(), material)));
    w.writeGlb(dir / "checker_sphere.glb");
}

void tiles(const fs::path& dir) {
    const int n = 256, cells = 4;
    writePng(makeImage(n, n, 3, [&](int x, int y) -> std::vector<std::uint8_t> {
                 const int cx = x * cells / n, cy = y * cells / n;
                 const int shade = 120 + 40 * ((cx * 7 + cy * 3) % 4);
                 return {static_cast<std::uint8_t>(shade), static_cast<std::uint8_t>(shade * 0.8),
                         static_cast<std::uint8_t>(shade * 0.6)};
             }),
             dir / "tiles_color.png");
    // Bevels: the last 8 texels before each tile edge slope at 45° (tangent-space normal ±x or ±y).
    const int cell = n / cells, bevel = 8;
    writePng(makeImage(n, n, 3, [&](int x, int y) -> std::vector<std::uint8_t> {
                 const int px = x % cell, py = y % cell;
                 double nx = 0, ny = 0;
                 if (px < bevel) nx = -0.7071; else if (px >= cell - bevel) nx = 0.7071;
                 // y runs down the image; the tangent space's +y is v's opposite (glTF: +y up).
                 if (py < bevel) ny = 0.7071; else if (py >= cell - bevel) ny = -0.7071;
                 const double nz = std::sqrt(std::max(0.0, 1.0 - nx * nx - ny * ny));
                 auto enc = [](double c) { return static_cast<std::uint8_t>(std::lround(127.5 * (c + 1.0))); };
                 return {enc(nx), enc(ny), enc(nz)};
             }),
             dir / "tiles_normal.png");
    GltfWriter w;
    const int color = w.addTexture(w.addImage({}, "tiles_color.png"));
    const int normal = w.addTexture(w.addImage({}, "tiles_normal.png"));
    const int occlusion = w.addTexture(w.addImage({}, "tiles_occlusion_missing.png"));
    tinygltf::Material m = pbrMaterial("Glazed tiles", {1, 1, 1, 1}, 0.0, 0.2, color, -1, normal);
    m.occlusionTexture.index = occlusion;
    const int material = w.addMaterial(m);
    Mesh quad = texturedQuad();
    computeTangents(quad);
    w.addToScene(w.addNode(w.addMesh(quad, material), {}, {}, {0.0, 0.0, 0.0, 1.0}));
    w.writeGltf(dir / "tiles.gltf");
}

void crate(const fs::path& dir) {
    writePng(checker(128, 128, 4, 4), dir / "crate_color.png");
    writePng(makeImage(128, 128, 1, [](int x, int) -> std::vector<std::uint8_t> {
                 return {static_cast<std::uint8_t>(x < 64 ? 40 : 220)};
             }),
             dir / "crate_roughness.png");
    std::ofstream(dir / "crate.mtl") << "# mipgloss demo crate\n"
                                        "newmtl Crate\nKd 1 1 1\nPr 1\nPm 0\nmap_Kd crate_color.png\n"
                                        "map_Pr crate_roughness.png\n";
    std::ofstream obj(dir / "crate.obj");
    obj << "# mipgloss demo crate: a cube with UVs\nmtllib crate.mtl\n";
    const float c[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    for (const auto& p : c) obj << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    obj << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    obj << "vn 0 0 -1\nvn 0 0 1\nvn -1 0 0\nvn 1 0 0\nvn 0 -1 0\nvn 0 1 0\n";
    obj << "usemtl Crate\ns off\n";
    const int faces[6][4] = {{2, 1, 4, 3}, {5, 6, 7, 8}, {1, 5, 8, 4}, {6, 2, 3, 7}, {1, 2, 6, 5}, {8, 7, 3, 4}};
    for (int f = 0; f < 6; ++f) {
        obj << "f";
        for (int k = 0; k < 4; ++k) obj << ' ' << faces[f][k] << '/' << k + 1 << '/' << f + 1;
        obj << '\n';
    }
}

void big(const fs::path& dir) {
    const int n = 4096;
    std::uint32_t state = 12345u;
    auto noise = [&]() { state = state * 1664525u + 1013904223u; return static_cast<std::uint8_t>(state >> 24); };
    const char* names[4] = {"big_color.png", "big_mr.png", "big_normal.png", "big_occlusion.png"};
    for (int k = 0; k < 4; ++k)
        writePng(makeImage(n, n, 3, [&](int, int) -> std::vector<std::uint8_t> {
                     const std::uint8_t a = noise();
                     if (k == 2) return {static_cast<std::uint8_t>(112 + a / 8), static_cast<std::uint8_t>(112 + a / 8), 250};
                     return {a, noise(), noise()};
                 }),
                 dir / names[k]);
    GltfWriter w;
    int t[4];
    for (int k = 0; k < 4; ++k) t[k] = w.addTexture(w.addImage({}, names[k]));
    tinygltf::Material m = pbrMaterial("Big", {1, 1, 1, 1}, 1.0, 1.0, t[0], t[1], t[2]);
    m.occlusionTexture.index = t[3];
    // rings × segments quads less the poles' degenerate halves: 2·500·1000 − 2·1000 ≈ 1.0e6.
    Mesh sphere = texturedSphere(501, 1000);
    computeTangents(sphere);
    w.addToScene(w.addNode(w.addMesh(sphere, w.addMaterial(m))));
    w.writeGlb(dir / "big.glb");
    std::cout << "big.glb: " << sphere.triangleCount() << " triangles, 4 textures of " << n << "²\n";
}

}  // namespace

int main(int argc, char** argv) {
    const bool withBig = argc == 3 && std::string(argv[1]) == "--big";
    if (argc != 2 && !withBig) {
        std::cerr << "usage: mipgloss_make_assets [--big] OUTDIR\n";
        return 2;
    }
    try {
        const fs::path dir = argv[argc - 1];
        fs::create_directories(dir);
        checkerSphere(dir);
        tiles(dir);
        crate(dir);
        std::cout << "wrote checker_sphere.glb, tiles.gltf, crate.obj to " << dir.string() << '\n';
        if (withBig) big(dir);
    } catch (const std::exception& e) {
        std::cerr << "mipgloss_make_assets: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
