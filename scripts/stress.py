#!/usr/bin/env python3
"""Stress cases of issue 11 (README "Hardening"): each either works or is refused with a message
naming the file, never an abort. Prints one line per case: outcome, exit status, wall time, peak
resident memory of the command (the child's ru_maxrss), and the last three lines it printed.

    scripts/stress.sh [BUILD_DIR]      (runs this under one Xvfb; default build/dev)

Cases (inputs are generated into a temporary folder; stdlib only):
  - a 10-million-triangle mesh (binary PLY, a 2236 x 2236 grid of quads bent into a dome), loaded
    and drawn (`mipgloss bench-render --mesh`: load time, first frame, frame time);
  - 200 objects in one scene (`bench-render --objects 200`: 200 teapots, 3.2 M triangles);
  - a scene file of 10 MB (30 000 objects sharing one small mesh, 200-byte names), rendered;
  - 1x1 and 2x1 environments (`bake` and `render --env`): a 1x1 image has no layout and is
    refused; a 2x1 lat-long is a cube of 1x1 faces;
  - a 16384 x 8192 half-float lat-long (`bake --size 256`).
Exit status 1 if any case crashed (a signal) or hung (over the timeout), or a refusal does not name
its file.
"""
import json
import os
import resource
import struct
import subprocess
import sys
import tempfile
import time

build = sys.argv[1] if len(sys.argv) > 1 else "build/dev"
cli = os.path.join(build, "app", "mipgloss")
TIMEOUT = 900


def run_case(name, args, must_name=None):
    """Runs one command in a fresh child and reports it."""
    wrapper = (
        "import resource, subprocess, sys, time\n"
        "t = time.monotonic()\n"
        "try:\n"
        "    p = subprocess.run(sys.argv[2:], capture_output=True, text=True, timeout=int(sys.argv[1]))\n"
        "    rc, out = p.returncode, (p.stdout + p.stderr)\n"
        "except subprocess.TimeoutExpired:\n"
        "    rc, out = 'hang', ''\n"
        "peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024\n"
        "print(repr((rc, time.monotonic() - t, peak, out)))\n"
    )
    res = subprocess.run([sys.executable, "-c", wrapper, str(TIMEOUT)] + args, capture_output=True, text=True)
    rc, wall, peak, out = eval(res.stdout.strip().splitlines()[-1])
    lines = [l for l in out.splitlines() if l.strip() and "XDG_RUNTIME_DIR" not in l]
    last = " | ".join(l.strip() for l in lines[-3:])
    if rc == "hang":
        outcome = "HANG"
    elif isinstance(rc, int) and rc < 0:
        outcome = "CRASH"
    elif rc == 0:
        outcome = "works"
    elif must_name and must_name not in out:
        outcome = "NAMELESS"
    else:
        outcome = "refused"
    print(f"{outcome:8} {name:44} exit {rc!s:5} {wall:7.1f} s {peak:8.0f} MiB  {last[:400]}")
    sys.stdout.flush()
    return outcome in ("works", "refused")


def write_dome_ply(path, n):
    """An n x n grid of vertices bent into a dome: 2 (n-1)^2 triangles, binary little-endian PLY."""
    faces = (n - 1) * (n - 1)
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
                 "property float y\nproperty float z\nelement face %d\n"
                 "property list uchar int vertex_indices\nend_header\n" % (n * n, 2 * faces)).encode())
        row = struct.Struct("<3f")
        for j in range(n):
            v = j / (n - 1) * 2 - 1
            f.write(b"".join(row.pack(u, 1.0 - 0.5 * (u * u + v * v), v)
                             for u in (i / (n - 1) * 2 - 1 for i in range(n))))
        tri = struct.Struct("<B3i")
        for j in range(n - 1):
            base = j * n
            f.write(b"".join(tri.pack(3, base + i, base + n + i, base + i + 1) +
                             tri.pack(3, base + i + 1, base + n + i, base + n + i + 1) for i in range(n - 1)))


def write_exr(path, width, height, pixel_type="half"):
    subprocess.run(["oiiotool", "--pattern", "fill:topleft=4,3,2:topright=1,1,1:bottomleft=0.1,0.1,0.2:"
                    "bottomright=0.2,0.1,0.1", f"{width}x{height}", "3", "-d", pixel_type,
                    "--compression", "zip", "-o", path], check=True)


def main():
    ok = True
    with tempfile.TemporaryDirectory(prefix="mipgloss-stress-") as tmp:
        # 10 M triangles: 2237^2 vertices, 2 * 2236^2 = 9.999 M triangles.
        big = os.path.join(tmp, "dome10m.ply")
        write_dome_ply(big, 2237)
        print(f"# {big}: {os.path.getsize(big) / 2**20:.0f} MiB")
        ok &= run_case("10M-triangle mesh (bench-render --mesh)",
                       [cli, "bench-render", "--mesh", big, "--frames", "2", "--size", "640x480"], big)

        ok &= run_case("200 objects (bench-render --objects 200)",
                       [cli, "bench-render", "--objects", "200", "--frames", "2", "--size", "640x480"])

        # A 10 MB scene (format 3, docs: ui/files/include/mipgloss/ui/scene_file.h): 30 000 objects sharing
        # one tetrahedron and one material, each with a 200-byte name.
        tetra = os.path.join(tmp, "tetra.obj")
        with open(tetra, "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
        scene = {"format": "mipgloss-scene", "version": 3,
                 "environment": {"source": "builtin:courtyard", "faceSize": 128},
                 "materials": [{"name": "m", "lambda": 3, "mode": "reflect"}],
                 "objects": [{"name": ("object %05d " % i).ljust(200, "x"), "mesh": "tetra.obj",
                              "transform": {"translation": [i % 200 * 1.5, i // 200 * 1.5, 0.0]},
                              "material": "m"} for i in range(30000)]}
        scene_file = os.path.join(tmp, "huge.mipgloss")
        with open(scene_file, "w") as f:
            json.dump(scene, f, indent=1)
        print(f"# {scene_file}: {os.path.getsize(scene_file) / 2**20:.1f} MiB, 30000 objects")
        ok &= run_case("10 MB scene file (render)",
                       [cli, "render", scene_file, "--size", "320x240", "--out", os.path.join(tmp, "s.png")],
                       scene_file)

        for w, h in ((1, 1), (2, 1)):
            env = os.path.join(tmp, f"env{w}x{h}.exr")
            write_exr(env, w, h, "float")
            ok &= run_case(f"{w}x{h} environment (bake)",
                           [cli, "bake", env, "--out", os.path.join(tmp, f"bake{w}"), "--quiet"], env)
            ok &= run_case(f"{w}x{h} environment (render)",
                           [cli, "render", "--env", env, "--size", "320x240", "--out",
                            os.path.join(tmp, f"r{w}.png")], env)

        huge = os.path.join(tmp, "latlong16k.exr")
        write_exr(huge, 16384, 8192)
        ok &= run_case("16384x8192 environment (bake --size 256)",
                       [cli, "bake", huge, "--size", "256", "--out", os.path.join(tmp, "bake16k"), "--quiet"], huge)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
