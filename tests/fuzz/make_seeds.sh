#!/usr/bin/env bash
# Regenerates the small seed files in tests/fuzz/corpus/ (committed; run again only to change
# them). Needs oiiotool (openimageio-tools), python3 and g++ with OpenMesh (for the .om seed) and
# tinygltf with OpenImageIO (the glTF seeds, written by tests/tools/gltf_writer.cpp).
# Each environment and mesh seed starts with the selector byte of entries.h: byte % 5 picks the
# extension (environment .exr .hdr .png .jpg .tif; mesh .obj .off .ply .stl .om).
set -euo pipefail
cd "$(dirname "$0")"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
env=corpus/environment_import mesh=corpus/mesh_import
mkdir -p "$env" "$mesh" corpus/scene_file corpus/library_file

# --- environments: every layout auto-detection knows, tiny, in each format -----------------
selector() { printf "\\x$(printf %02x "$1")"; }       # one raw byte
seed_env() { # name ext-index image-file
  { selector "$2"; cat "$3"; } > "$env/$1"; }
img() { # out size [oiiotool args...]: a gradient so faces differ
  local out=$1 size=$2; shift 2
  oiiotool --nosoftwareattrib --pattern fill:topleft=0.1,0.2,0.3:topright=4,0.5,0.1:bottomleft=0,1,0.2:bottomright=0.7,0.7,9 "$size" 3 "$@" -o "$out"; }
img "$tmp/ll.exr" 16x8 -d half --compression zip;        seed_env latlong-zip.exr 0 "$tmp/ll.exr"
img "$tmp/ll.exr" 16x8 -d float --compression piz;       seed_env latlong-piz.exr 0 "$tmp/ll.exr"
img "$tmp/hc.exr" 16x12 -d half --compression rle;       seed_env hcross-rle.exr 0 "$tmp/hc.exr"
img "$tmp/vc.exr" 12x16 -d half --compression none;      seed_env vcross.exr 0 "$tmp/vc.exr"
img "$tmp/hs.exr" 24x4 -d half --compression b44;        seed_env hstrip-b44.exr 0 "$tmp/hs.exr"
img "$tmp/vs.exr" 4x24 -d half --compression dwaa;       seed_env vstrip-dwaa.exr 0 "$tmp/vs.exr"
img "$tmp/ll.exr" 16x8 -d half --tile 8 8;               seed_env latlong-tiled.exr 0 "$tmp/ll.exr"
img "$tmp/ll.hdr" 16x8;                                   seed_env latlong.hdr 1 "$tmp/ll.hdr"
img "$tmp/hc.hdr" 16x12;                                  seed_env hcross.hdr 1 "$tmp/hc.hdr"
img "$tmp/ll.png" 16x8 -d uint8;                          seed_env latlong.png 2 "$tmp/ll.png"
img "$tmp/hs.png" 24x4 -d uint16;                         seed_env hstrip-16bit.png 2 "$tmp/hs.png"
oiiotool --nosoftwareattrib "$tmp/ll.png" --ch R,A=1.0 -o "$tmp/ga.png";     seed_env latlong-grey-alpha.png 2 "$tmp/ga.png"
img "$tmp/vc.jpg" 12x16 -d uint8;                         seed_env vcross.jpg 3 "$tmp/vc.jpg"
# A real JPEG (baseline, 512² face from tests/assets): the decoder paths a synthetic one misses.
seed_env irrlicht2-up-face.jpg 3 ../assets/cubemaps/irrlicht2/irrlicht2_up.jpg
img "$tmp/ll.tif" 16x8 -d float;                          seed_env latlong-float.tif 4 "$tmp/ll.tif"
img "$tmp/hc.tif" 16x12 -d uint8 --compression lzw;       seed_env hcross-lzw.tif 4 "$tmp/hc.tif"
img "$tmp/vs.tif" 16x96 -d half --tile 16 16;             seed_env vstrip-tiled-half.tif 4 "$tmp/vs.tif"
# Layout forced by the selector's bits 3-5 (hcross on a lat-long image: a refusal) and the 8²
# face-size bit 6.
{ selector $((0 | 2 << 3)); cat "$tmp/ll.exr"; } > "$env/forced-hcross-on-latlong.exr"
{ selector $((2 | 0x40)); cat "$tmp/ll.png"; } > "$env/latlong-facesize8.png"

# --- meshes: every format and flavour the reader accepts, and the damage the tests know -----
python3 - "$mesh" <<'PY'
import struct, sys, os
out = sys.argv[1]
V = [(0,0,0),(1,0,0),(0,1,0),(0,0,1)]
F = [(0,2,1),(0,1,3),(0,3,2),(1,2,3)]
def seed(name, ext, data):
    idx = [".obj",".off",".ply",".stl",".om"].index(ext)
    open(os.path.join(out, name), "wb").write(bytes([idx]) + data)
obj = "# tetrahedron\n" + "".join(f"v {x} {y} {z}\n" for x,y,z in V) + "vn 0 0 1\nvt 0 0\n" \
      + "".join(f"f {a+1} {b+1} {c+1}\n" for a,b,c in F)
seed("tetra.obj", ".obj", obj.encode())
seed("quad-slashes.obj", ".obj", b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf -4//1 -3//1 -1//1\n")
seed("truncated.obj", ".obj", obj.encode()[:len(obj)//2])
off = "OFF\n4 4 6\n" + "".join(f"{x} {y} {z}\n" for x,y,z in V) + "".join(f"3 {a} {b} {c}\n" for a,b,c in F)
seed("tetra.off", ".off", off.encode())
seed("colour.off", ".off", b"COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n")
hdr = lambda fmt: (f"ply\nformat {fmt} 1.0\ncomment fuzz seed\nelement vertex 4\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n").encode()
seed("tetra-ascii.ply", ".ply", hdr("ascii") + ("".join(f"{x} {y} {z}\n" for x,y,z in V) + "".join(f"3 {a} {b} {c}\n" for a,b,c in F)).encode())
for fmt, e in (("binary_little_endian","<"),("binary_big_endian",">")):
    body = b"".join(struct.pack(e+"3f",*v) for v in V) + b"".join(struct.pack(e+"B3i",3,*f) for f in F)
    seed(f"tetra-{fmt}.ply", ".ply", hdr(fmt) + body)
seed("normals-double.ply", ".ply", b"ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\nproperty list uint8 uint32 vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n")
stl = "solid t\n" + "".join("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {V[i][0]} {V[i][1]} {V[i][2]}\n" for i in f) + "endloop\nendfacet\n" for f in F) + "endsolid t\n"
seed("tetra-ascii.stl", ".stl", stl.encode())
binstl = b"fuzz seed".ljust(80, b" ") + struct.pack("<I", len(F)) + b"".join(
    struct.pack("<3f", 0,0,0) + b"".join(struct.pack("<3f", *V[i]) for i in f) + b"\0\0" for f in F)
seed("tetra-binary.stl", ".stl", binstl)
PY
cat > "$tmp/om.cpp" <<'CPP'
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
int main(int, char** argv) {
    OpenMesh::TriMesh_ArrayKernelT<> m;
    OpenMesh::VertexHandle v[4] = {m.add_vertex({0, 0, 0}), m.add_vertex({1, 0, 0}), m.add_vertex({0, 1, 0}), m.add_vertex({0, 0, 1})};
    m.add_face(v[0], v[2], v[1]); m.add_face(v[0], v[1], v[3]); m.add_face(v[0], v[3], v[2]); m.add_face(v[1], v[2], v[3]);
    return OpenMesh::IO::write_mesh(m, argv[1]) ? 0 : 1;
}
CPP
g++ -std=c++17 -o "$tmp/om" "$tmp/om.cpp" -lOpenMeshCore && "$tmp/om" "$tmp/tetra.om"
{ selector 4; cat "$tmp/tetra.om"; } > "$mesh/tetra.om"
# The hostile PLY headers that crashed OpenMesh before validation (tests/assets/meshes/hostile).
for f in ply-ascii_0011 ply-binary-le_0009 ply-binary-be_0012; do
  [ -f ../assets/meshes/hostile/$f.ply ] && { selector 2; cat ../assets/meshes/hostile/$f.ply; } > "$mesh/hostile-$f.ply"
done

# --- assets: glTF (GLB and .gltf) written by the tests' GltfWriter, OBJ + MTL pairs ----------
# gltf_import: the whole input is the file. Needs libtinygltf-dev and OpenImageIO (the PNGs).
gl=corpus/gltf_import mtl=corpus/mtl_import
mkdir -p "$gl" "$mtl"
cat > "$tmp/gltf_seeds.cpp" <<'CPP'
#include "gltf_writer.h"
#include <fstream>
namespace mipgloss {
// The one mesh.cpp function gltf_writer.cpp calls, so this links without the scene library.
void computeBounds(Mesh& mesh) {
    if (mesh.positions.empty()) return;
    mesh.bounds = {mesh.positions[0], mesh.positions[0]};
    for (const glm::vec3& p : mesh.positions) mesh.bounds.min = glm::min(mesh.bounds.min, p), mesh.bounds.max = glm::max(mesh.bounds.max, p);
}
}  // namespace mipgloss
using namespace mipgloss;
using namespace mipgloss::test;
namespace fs = std::filesystem;
static void save(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }
int main(int, char** argv) {
    const fs::path out = argv[1];
    const TestImage tiny = makeImage(2, 2, 3, [](int x, int y) -> std::vector<std::uint8_t> {
        return {static_cast<std::uint8_t>(255 * x), static_cast<std::uint8_t>(255 * y), 128};
    });
    Mesh tri;  // one triangle with UVs and tangents
    tri.name = "tri";
    tri.positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tri.normals.assign(3, glm::vec3(0.57735f));
    tri.uvs = {{0, 0}, {1, 0}, {0, 1}};
    tri.tangents.assign(3, glm::vec4(0.70710678f, -0.70710678f, 0, 1));
    tri.indices = {0, 1, 2};
    computeBounds(tri);
    {   // GLB: the quad with an embedded PNG read by every map, emissive strength and clear coat.
        GltfWriter w;
        const int t = w.addTexture(w.addImage(encodePng(tiny)));
        tinygltf::Material m = pbrMaterial("Paint", {0.8, 0.5, 0.2, 1}, 0.5, 0.4, t, t, t);
        m.occlusionTexture.index = t;
        m.emissiveTexture.index = t;
        m.emissiveFactor = {1, 0.5, 0.25};
        m.alphaMode = "MASK";
        m.alphaCutoff = 0.25;
        m.extensions["KHR_materials_emissive_strength"] =
            tinygltf::Value(tinygltf::Value::Object{{"emissiveStrength", tinygltf::Value(2.0)}});
        m.extensions["KHR_materials_clearcoat"] = tinygltf::Value(tinygltf::Value::Object{
            {"clearcoatFactor", tinygltf::Value(1.0)}, {"clearcoatRoughnessFactor", tinygltf::Value(0.1)}});
        w.model().extensionsUsed = {"KHR_materials_emissive_strength", "KHR_materials_clearcoat"};
        w.addToScene(w.addNode(w.addMesh(texturedQuad(), w.addMaterial(m)), {0, 1, 0}, {1, 2, 1}));
        w.writeGlb(out / "quad-textured.glb");
    }
    {   // GLB: a triangle with tangents under a mirroring parent; a second primitive of lines.
        GltfWriter w;
        const int t = w.addTexture(w.addImage(encodePng(tiny)));
        const int mesh = w.addMesh(tri, w.addMaterial(pbrMaterial("", {1, 1, 1, 1}, 0, 1, -1, -1, t)));
        tinygltf::Primitive lines = w.model().meshes[0].primitives[0];
        lines.mode = TINYGLTF_MODE_LINE;
        w.model().meshes[0].primitives.push_back(lines);
        const int child = w.addNode(mesh, {1, 2, 3}, {}, {0, 0.38268343, 0, 0.92387953});
        const int parent = w.addNode(-1, {}, {-1, 1, 1});
        w.model().nodes[static_cast<std::size_t>(parent)].children = {child};
        w.addToScene(parent);
        w.writeGlb(out / "mirrored-tangents.glb");
    }
    {   // .gltf: the buffer as a data URI, a strip without normals, an external image, blend.
        GltfWriter w;
        const int t = w.addTexture(w.addImage({}, "base%20colour.png"));
        tinygltf::Material m = pbrMaterial("Glass", {1, 1, 1, 0.5}, 0, 0.05, t);
        m.alphaMode = "BLEND";
        Mesh strip;
        strip.name = "strip";
        strip.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
        strip.uvs = {{0, 0}, {1, 0}, {0, 0.5f}, {1, 0.5f}, {0, 1}};
        strip.indices = {0, 1, 2, 3, 4};
        const int mesh = w.addMesh(strip, w.addMaterial(m), false);
        w.model().meshes[0].primitives[0].mode = TINYGLTF_MODE_TRIANGLE_STRIP;
        w.addToScene(w.addNode(mesh));
        save(out / "strip-data-uri.gltf", w.gltf());
    }
    {   // .gltf: a fan, positions only, no scene (its root nodes are drawn), a matrix node.
        GltfWriter w;
        Mesh fan;
        fan.name = "fan";
        fan.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}};
        fan.indices = {0, 1, 2, 3, 4};
        const int mesh = w.addMesh(fan, -1, false);
        w.model().meshes[0].primitives[0].mode = TINYGLTF_MODE_TRIANGLE_FAN;
        const int node = w.addNode(mesh);
        w.model().nodes[static_cast<std::size_t>(node)].matrix = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
        w.model().scenes.clear();
        w.model().defaultScene = -1;
        save(out / "fan-no-scene.gltf", w.gltf());
    }
}
CPP
g++ -std=c++20 -O1 -I ../tools -I ../../core/scene/include -I ../../core/io/include "$tmp/gltf_seeds.cpp" ../tools/gltf_writer.cpp \
    -o "$tmp/gltf_seeds" -ltinygltf -lOpenImageIO -lOpenImageIO_Util
"$tmp/gltf_seeds" "$gl"
# The writer pretty-prints .gltf JSON: compacted, the fuzzer's mutations land on content.
for f in "$gl"/*.gltf; do
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); open(sys.argv[1],"w").write(json.dumps(d,separators=(",",":")))' "$f"
done

# mtl_import: a selector byte (bit 0 set: the OBJ read without its library), the OBJ text, a 0
# byte, the MTL text (entries.h). The OBJ names its library "fuzz.mtl", as the entry gives it.
python3 - "$mtl" <<'PY'
import os, sys
out = sys.argv[1]
def seed(name, obj, mtl=None, selector=0):
    data = bytes([selector]) + obj.encode() + (b"\0" + mtl.encode() if mtl is not None else b"")
    open(os.path.join(out, name), "wb").write(data)
cube_v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
cube_n = "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n"
faces = [(1,4,3,2),(5,6,7,8),(1,2,6,5),(4,8,7,3),(1,5,8,4),(2,3,7,6)]
def f(i, q, n=True):
    return "f " + " ".join(f"{v}/{k+1}" + (f"/{i+1}" if n else "") for k, v in enumerate(q)) + "\n"
obj = "# two materials\nmtllib fuzz.mtl\n" + cube_v + cube_n + "usemtl Red\ns off\n" + "".join(f(i, q) for i, q in enumerate(faces[:3])) \
      + "usemtl Blue\ns 1\n" + "".join(f(i, q, False) for i, q in enumerate(faces[3:], 3)) + "usemtl Nowhere\nf 1 2 3\n"
mtl = ("# every key the reader knows\nnewmtl Red\nKd 1 0 0\nKs 1 1 1\nNs 250\nKe 0.5\nd 1\nPm 0.25\nmap_Kd -blendu on -o 0.5 0.5 red tex.png\n"
       "map_Ns shine.png\nmap_Ks spec.png\nmap_d alpha.png\n"
       "newmtl Blue\nKd 0 0 1\nPr 0.3\nTr 0.5\nmap_Pr -imfchan g rough.png\nmap_Pm -imfchan b -mm 0 1 metal.png\n"
       "map_Ke glow.png\nnorm -bm 2 -s 1 1 1 n.png\nbump -bm -0.5 b.png\nmap_Bump -clamp on c:\\textures\\nb.png\n"
       "newmtl Red\nd -halo 0.5\n")
seed("cube-two-materials.bin", obj, mtl)
seed("cube-without-library.bin", obj, mtl, selector=1)
seed("quad-negative-indices.bin", "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n"
     "usemtl M\nf -4/-2/-1 -3/-1/-1 -2/-1/-1 -1/-2/-1\n", "newmtl M\nKd 0.5 0.5 0.5\nbump n.png\n")
seed("obj-only.bin", "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
seed("bad-mtl-value.bin", "mtllib fuzz.mtl\nusemtl A\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "newmtl A\nKd 1 nan 0\n")
PY

# --- scene and library files ----------------------------------------------------------------
sc=corpus/scene_file
cat > $sc/v3-full.mipgloss <<'J'
{"format": "mipgloss-scene", "version": 3,
 "environment": {"source": "builtin:courtyard", "layout": "auto", "handedness": "left", "faceSize": 64,
                 "builder": "phong", "rotationDegrees": 30},
 "display": {"showBackground": true, "backgroundLambda": 2.5, "exposureEv": -1, "toneMap": "reinhard", "samples": 4},
 "materials": [{"name": "gold", "library": "Gold", "lambda": 3, "phongExponent": 767, "mode": "reflect",
                "useIrradiance": false, "tint": [1, 0.8, 0.3], "sharperAtGrazing": true},
               {"name": "chalk", "lambda": 7, "mode": "normal", "useIrradiance": true}],
 "objects": [{"name": "ball", "mesh": "builtin:sphere", "visible": true,
              "transform": {"translation": [1, 2, 3], "rotationDegrees": [0, 90, 0], "scale": 0.5},
              "material": "gold"},
             {"name": "ball 2", "mesh": "builtin:sphere", "visible": false, "material": "chalk"},
             {"name": "pot", "mesh": "builtin:sphere", "material": "gold"}]}
J
cat > $sc/v4-full.mipgloss <<'J'
{"format": "mipgloss-scene", "version": 4,
 "environment": {"source": "builtin:courtyard", "layout": "auto", "handedness": "left", "faceSize": 64,
                 "builder": "phong"},
 "display": {"showBackground": true, "backgroundLambda": 2.5, "exposureEv": -1, "toneMap": "reinhard", "samples": 4,
             "environmentRotationDegrees": 30},
 "materials": [{"name": "gold", "library": "Gold", "lambda": 3, "phongExponent": 767, "mode": "reflect",
                "useIrradiance": false, "tint": [1, 0.8, 0.3], "sharperAtGrazing": true},
               {"name": "chalk", "lambda": 7, "mode": "normal", "useIrradiance": true}],
 "objects": [{"name": "ball", "mesh": "builtin:sphere", "visible": true,
              "transform": {"translation": [1, 2, 3], "rotationDegrees": [0, 90, 0], "scale": 0.5},
              "material": "gold"},
             {"name": "pot", "mesh": "builtin:sphere", "material": "gold"}]}
J
cat > $sc/v6-camera.mipgloss <<'J'
{"format": "mipgloss-scene", "version": 6,
 "environment": {"source": "builtin:courtyard", "faceSize": 32, "builder": "box"},
 "display": {"environmentRotationDegrees": -45},
 "materials": [{"name": "paint", "lambda": 0, "layers": {"baseColor": [0.6, 0.05, 0.02], "roughness": 0.45, "coat": 1}},
               {"name": "gold", "lambda": 3, "tint": [1, 0.8, 0.3]}],
 "objects": [{"name": "ball", "mesh": "builtin:sphere", "material": "paint",
              "transform": {"translation": [0.5, 0, -1], "rotationDegrees": [0, 30, 0], "scale": 2}},
             {"name": "pot", "mesh": "builtin:teapot", "material": "gold"}],
 "camera": {"target": [0.25, 0.5, -0.5], "distance": 6.5, "yawDegrees": -30, "pitchDegrees": 25, "fovYDegrees": 40}}
J
cat > $sc/v2-object-materials.json <<'J'
{"format": "mipgloss-scene", "version": 2, "environment": {"source": "builtin:courtyard"},
 "objects": [{"name": "a", "mesh": "builtin:sphere", "material": {"lambda": 4, "phongExponent": 191, "tint": [0.5, 0.5, 0.5]}},
             {"name": "a", "mesh": "builtin:sphere", "material": {"lambda": 0, "phongExponent": null}}]}
J
cat > $sc/v1-legacy-lambda.json <<'J'
{"format": "mipgloss-scene", "version": 1, "environment": {"source": "builtin:courtyard", "faceSize": 256},
 "display": {"backgroundLambda": 9},
 "objects": [{"mesh": "builtin:sphere", "material": {"lambda": 5.5, "mode": "normal"}}]}
J
cat > $sc/missing-files.mipgloss <<'J'
{"format": "mipgloss-scene", "version": 3, "environment": {"source": "env/sky.exr", "layout": "hcross"},
 "materials": [{"name": "m"}], "objects": [{"name": "bunny", "mesh": "meshes/bunny.obj", "material": "m"}]}
J
cat > $sc/clamped.mipgloss <<'J'
{"format": "mipgloss-scene", "version": 3, "environment": {"faceSize": 100000}, "display": {"samples": 64, "exposureEv": 1e9},
 "materials": [{"name": "m", "lambda": 1, "phongExponent": 5}], "objects": [{"mesh": "builtin:sphere", "material": "m"}]}
J
printf '{"format": "mipgloss-scene", ' > $sc/truncated.json
printf '{"format": "mipgloss-scene", "version": 7}' > $sc/future.json
lb=corpus/library_file
cat > $lb/two.mglib <<'J'
{"format": "mipgloss-library", "version": 1,
 "materials": [{"name": "Gold", "lambda": 3, "phongExponent": 767, "mode": "reflect", "useIrradiance": false,
                "tint": [1, 0.8, 0.3], "sharperAtGrazing": false},
               {"name": "Chalk", "lambda": 7.5, "phongExponent": 1.2, "mode": "normal", "useIrradiance": true, "tint": [1, 1, 1]}]}
J
cat > $lb/layered.mglib <<'J'
{"format": "mipgloss-library", "version": 2, "materials": [
  {"name": "Car paint", "lambda": 0, "layers": {"baseColor": [0.6, 0.05, 0.02], "metallic": 0, "roughness": 0.45,
   "specularExponent": 8.7, "specular": 0.05, "coat": 1, "coatRoughness": 0.03, "coatExponent": 457000}},
  {"name": "Gold", "layers": {"baseColor": [1, 0.766, 0.336], "metallic": 1, "roughness": 0, "specularExponent": null}}]}
J
printf '{"format": "mipgloss-library", "version": 1, "materials": []}' > $lb/empty.mglib
printf '{"format": "mipgloss-library", "version": 1, "materials": [{"name": "A"}, {"name": "A"}]}' > $lb/duplicate.mglib
printf '{"format": "mipgloss-library", "version": 1, "materials": [{"name": "M", "lambda": 2, "phongExponent": 12345}]}' > $lb/exponent-disagrees.mglib
printf '{"format": "mipgloss-library", "version": 1, "materials": [{"name": "\\u00e9t\\u00e9 / gl\\u00f6ss", "lambda": 0, "phongExponent": null}]}' > $lb/unicode-name.mglib
printf '{"format": "mipgloss-library", "version": 2}' > $lb/future.mglib
echo "seeds: $(find corpus -type f | wc -l) files, $(du -sk corpus | cut -f1) KiB"
