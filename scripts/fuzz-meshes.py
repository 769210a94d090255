#!/usr/bin/env python3
"""Mutation fuzzer run from outside (issue 11's "Must show"): damaged mesh, scene and library files
through `mipgloss render` / `mipgloss library list`.

Seeds: the OBJ files of tests/assets/meshes, the glTF fuzz target's seeds (tests/fuzz/corpus/
gltf_import: .gltf and .glb, through `render --mesh` and `library import-gltf`, mutated in their
JSON's structure as tests/fuzz/gltf_mutator.h does: wrapped indices, odd numbers, deep nesting,
wrong kinds, hostile URIs, repeated indices), and small files this script writes itself in every
format we read (OBJ, OFF ASCII and binary, PLY ASCII and binary little/big endian, STL ASCII and
binary, OM as OpenMesh 9 writes it, a scene JSON and a material library JSON). Each case is a seed with byte mutations (bit
flips, random or "interesting" bytes, inserts, deletes, duplicated chunks, truncation) or a
format-aware mutation (header counts made huge, negative or zero, property and list types made
nonsense, list sizes changed, elements duplicated or reordered, face indices out of range, OM
chunk header fields, topology indices and chunk sizes changed, JSON values of the wrong type or
size). Every case runs with a time limit and an address-space limit,
and is classified:

  ok        exit 0
  refused   exit 1..127 with the case's file name on stderr
  nameless  exit 1..127 without the file name on stderr
  crash     killed by a signal (segmentation fault, abort, ...)
  hang      still running at the time limit (killed)
  no-display  the X server could not be reached, after retries (the machine, not the file: never
            counted as a crash; the run exits 3, incomplete)

It prints a table per format (with the slowest case and the largest peak memory) and exits 1 when
any case crashed, hung or was refused without the file's name; the failing cases are copied to
OUT/failures/. Deterministic for a given --seed.

usage: scripts/fuzz-meshes.sh [--build DIR] [--cases N] [--jobs J] [--timeout S] [--seed K]
                              [--formats obj,ply-ascii,...] [--out DIR]
(the .sh wrapper runs this under xvfb-run when there is no display)
"""

import argparse
import concurrent.futures
import json
import os
import random
import re
import resource
import shutil
import signal
import struct
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# ---------------------------------------------------------------------------------------------
# Seeds: a small closed mesh (a UV sphere of 4 rings and 6 segments: 20 vertices, 36 triangles)
# plus one quad, so that polygons are exercised.


def small_mesh():
    import math
    rings, segs = 4, 6
    pos = [(0.0, 1.0, 0.0)]
    for r in range(1, rings):
        th = math.pi * r / rings
        for s in range(segs):
            ph = 2 * math.pi * s / segs
            pos.append((math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)))
    pos.append((0.0, -1.0, 0.0))
    south = len(pos) - 1

    def at(r, s):
        return 1 + (r - 1) * segs + s % segs

    faces = [(0, at(1, s + 1), at(1, s)) for s in range(segs)]
    for r in range(1, rings - 1):
        for s in range(segs):
            faces.append((at(r, s), at(r, s + 1), at(r + 1, s + 1)))
            faces.append((at(r, s), at(r + 1, s + 1), at(r + 1, s)))
    faces += [(south, at(rings - 1, s), at(rings - 1, s + 1)) for s in range(segs)]
    # A separate quad beside the sphere (a polygon for the formats that hold them).
    q = len(pos)
    pos += [(2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (3.0, 1.0, 0.0), (2.0, 1.0, 0.0)]
    quads = [(q, q + 1, q + 2, q + 3)]
    return pos, faces, quads


def seed_obj(pos, tris, quads):
    out = ["# small seed\n", "o seed\n"]
    out += ["v %.6g %.6g %.6g\n" % p for p in pos]
    out += ["vt 0.5 0.5\n", "vn 0 1 0\n"]
    out += ["f %d %d %d\n" % tuple(i + 1 for i in f) for f in tris[:-2]]
    out += ["f %d/1/1 %d/1/1 %d/1/1\n" % tuple(i + 1 for i in f) for f in tris[-2:]]
    out += ["f " + " ".join("-%d" % (len(pos) - i) for i in f) + "\n" for f in quads]
    return "".join(out).encode()


def seed_off_ascii(pos, tris, quads):
    faces = tris + quads
    out = ["OFF\n", "# comment\n", "%d %d 0\n" % (len(pos), len(faces))]
    out += ["%.6g %.6g %.6g\n" % p for p in pos]
    out += ["%d %s\n" % (len(f), " ".join(str(i) for i in f)) for f in faces]
    return "".join(out).encode()


def seed_off_binary(pos, tris, quads):
    # OpenMesh's binary OFF (what writeMesh writes): little-endian int32 counts, float32
    # coordinates, int32 valence and indices.
    faces = tris + quads
    out = b"OFF BINARY\n" + struct.pack("<iii", len(pos), len(faces), 0)
    for p in pos:
        out += struct.pack("<fff", *p)
    for f in faces:
        out += struct.pack("<i", len(f)) + struct.pack("<%di" % len(f), *f)
    return out


# A triangle as OpenMesh's .om writer writes it (84 bytes).
SEED_OM = bytes.fromhex(
    "4f4d544203000000010000000300000000160000000000000000000000000000"
    "803f0000000000000000000000000000803f00000000f8160201000500ff0402"
    "000101ff0000000302ffe006050103e80604 1c00".replace(" ", ""))
# A square pyramid as a polygon mesh ('P': a quad and four triangles; 144 bytes), and a
# tetrahedron with every optional chunk OpenMesh 9 writes for a triangle mesh: vertex and face
# normals and colours, texture coordinates, vertex status, custom vertex, face and mesh
# properties (401 bytes). Both written by OpenMesh 9.0's write_mesh.
SEED_OM_POLYGONS = bytes.fromhex(
    "4f4d504205000000050000000800000000160000000000000000000000000000803f00000000000000000000803f0000"
    "803f00000000000000000000803f000000000000003f0000003f0000803ff8160203000b00040402000e03030601000c"
    "02020000000801010a04010501020700010f04040904020302030d0403010304e0060b0503010fe806060a090d0f1c00")
SEED_OM_CHUNKS = bytes.fromhex(
    "4f4d544204000000040000000600000000160000000000000000000000000000803f0000000000000000000000000000"
    "803f0000000000000000000000000000803f20163acd13bf3acd13bf3acd13bfeada313ff23202bff23202bff23202bf"
    "eada313ff23202bff13202bff13202bfe9da313f80100a141e0a141e0a141e0a141e400e0000003f0000803e0000003f"
    "0000803e0000003f0000803e0000003f0000803ef8160202000900020401000b02030000000601010803010301030500"
    "010a0302010202070303e00609030b07e8060408010728160000000000000000000080bf00000000000080bf00000000"
    "000080bf00000000000000003acd133f3acd133f3acd133f881028323c28323c28323c28323c60000000000000000000"
    "0000000000000000c200076d79666c6f617405666c6f61741000000000000000000000000000000000000000ca00056d"
    "79696e7407696e7433325f741000000000000000000000000000000000000000c6c0056d797374720b7374643a3a7374"
    "72696e6707000000050068656c6c6f1c00")


def ply_header(fmt, nv, nf, extra=False):
    h = "ply\nformat %s 1.0\ncomment seed\nelement vertex %d\n" % (fmt, nv)
    h += "property float x\nproperty float y\nproperty float z\n"
    if extra:
        h += "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n"
    h += "element face %d\nproperty list uchar int vertex_indices\n" % nf
    if extra:
        h += "element material 1\nproperty float shininess\n"
    return h + "end_header\n"


def seed_ply_ascii(pos, tris, quads, extra=False):
    faces = tris + quads
    out = ply_header("ascii", len(pos), len(faces), extra)
    for p in pos:
        out += "%.6g %.6g %.6g" % p + (" 0 1 0 200" if extra else "") + "\n"
    out += "".join("%d %s\n" % (len(f), " ".join(str(i) for i in f)) for f in faces)
    if extra:
        out += "0.5\n"
    return out.encode()


def seed_ply_binary(pos, tris, quads, endian, extra=False):
    faces = tris + quads
    e = "<" if endian == "little" else ">"
    out = ply_header("binary_%s_endian" % endian, len(pos), len(faces), extra).encode()
    for p in pos:
        out += struct.pack(e + "fff", *p)
        if extra:
            out += struct.pack(e + "fffB", 0.0, 1.0, 0.0, 200)
    for f in faces:
        out += struct.pack(e + "B%di" % len(f), len(f), *f)
    if extra:
        out += struct.pack(e + "f", 0.5)
    return out


def seed_stl_ascii(pos, tris):
    out = ["solid seed\n"]
    for f in tris:
        out.append("  facet normal 0 0 0\n    outer loop\n")
        out += ["      vertex %.6g %.6g %.6g\n" % pos[i] for i in f]
        out.append("    endloop\n  endfacet\n")
    out.append("endsolid seed\n")
    return "".join(out).encode()


def seed_stl_binary(pos, tris):
    out = b"binary seed".ljust(80, b" ") + struct.pack("<I", len(tris))
    for f in tris:
        out += struct.pack("<fff", 0, 0, 0)
        for i in f:
            out += struct.pack("<fff", *pos[i])
        out += b"\0\0"
    return out


def seed_scene(mesh_name):
    return json.dumps({
        "format": "mipgloss-scene", "version": 3,
        "environment": {"source": "builtin:courtyard", "layout": "auto", "handedness": "right",
                        "faceSize": 16, "builder": "phong", "rotationDegrees": 0},
        "display": {"showBackground": True, "backgroundLambda": 0, "exposureEv": 0,
                    "toneMap": "linear", "samples": 0},
        "materials": [{"name": "gloss", "lambda": 3, "mode": "reflect", "useIrradiance": False,
                       "tint": [1, 0.8, 0.5], "sharperAtGrazing": False}],
        "objects": [{"name": "a", "mesh": mesh_name, "visible": True, "material": "gloss",
                     "transform": {"translation": [0, 0, 0], "rotationDegrees": [0, 30, 0],
                                   "scale": 1}},
                    {"name": "b", "mesh": "builtin:sphere", "visible": True, "material": "gloss",
                     "transform": {"translation": [2, 0, 0], "rotationDegrees": [0, 0, 0],
                                   "scale": 0.5}}],
    }, indent=2).encode()


def seed_library():
    return json.dumps({
        "format": "mipgloss-library", "version": 1,
        "materials": [
            {"name": "mirror", "lambda": 0, "phongExponent": None, "mode": "reflect",
             "useIrradiance": False, "tint": [1, 1, 1], "sharperAtGrazing": False},
            {"name": "glossy", "lambda": 2, "phongExponent": 3071, "mode": "reflect",
             "useIrradiance": False, "tint": [1, 0.78, 0.34], "sharperAtGrazing": False},
            {"name": "diffuse", "lambda": 7, "phongExponent": 2, "mode": "normal",
             "useIrradiance": True, "tint": [0.5, 0.5, 0.5], "sharperAtGrazing": True}],
    }, indent=2).encode()


# ---------------------------------------------------------------------------------------------
# Mutations

INTERESTING_BYTES = [0, 0xff, 0x7f, 0x80, ord("\n"), ord("\r"), ord(" "), ord("-"), ord("9"), ord("#"),
                     ord("e"), ord("."), ord("/")]
HUGE_NUMBERS = ["0", "-1", "-2147483648", "2147483647", "2147483648", "4294967295", "4294967296",
                "18446744073709551615", "99999999999999999999999", "1e9", "1e30", "100000000",
                "3000000000", "nan", "inf", "-0", "0x10", "+7", "", "abc", "1.5"]
BAD_TYPES = ["float128", "list", "int64", "uint64", "x", "", "vertex_indices", "float32x", "char8",
             "end_header", "element", "property"]


def byte_mutation(data, rng):
    data = bytearray(data)
    for _ in range(rng.choice([1, 1, 1, 2, 3, 8])):
        kind = rng.randrange(8)
        n = len(data)
        if n == 0:
            data += bytes([rng.randrange(256)])
            continue
        at = rng.randrange(n)
        if kind == 0:  # flip a bit
            data[at] ^= 1 << rng.randrange(8)
        elif kind == 1:  # a random byte
            data[at] = rng.randrange(256)
        elif kind == 2:  # an interesting byte
            data[at] = rng.choice(INTERESTING_BYTES)
        elif kind == 3:  # insert bytes
            data[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
        elif kind == 4:  # delete a range
            del data[at:at + rng.randint(1, 32)]
        elif kind == 5:  # duplicate a chunk
            chunk = data[at:at + rng.randint(1, 64)]
            to = rng.randrange(n)
            data[to:to] = chunk
        elif kind == 6:  # truncate
            del data[at:]
        else:  # overwrite 4 bytes with an interesting 32-bit value (binary counts, indices)
            value = rng.choice([0, 1, 0xffffffff, 0x7fffffff, 0x80000000, 0x10000, 0xfffffffe, 3, 255])
            data[at:at + 4] = struct.pack(rng.choice("<>") + "I", value)
    return bytes(data)


def header_split(data, marker):
    i = data.find(marker)
    if i < 0:
        return data, b""
    j = data.find(b"\n", i)
    j = len(data) if j < 0 else j + 1
    return data[:j], data[j:]


def replace_random_number(text, rng, limit=None):
    nums = [m for m in re.finditer(r"-?\d+(\.\d+)?", text[:limit] if limit else text)]
    if not nums:
        return text
    m = rng.choice(nums)
    return text[:m.start()] + rng.choice(HUGE_NUMBERS) + text[m.end():]


def ply_mutation(data, rng):
    head, body = header_split(data, b"end_header")
    lines = head.decode("latin-1").split("\n")
    kind = rng.randrange(10)
    if kind == 0:  # an element count
        idx = [i for i, l in enumerate(lines) if l.startswith("element")]
        if idx:
            i = rng.choice(idx)
            parts = lines[i].split(" ")
            parts[-1] = rng.choice(HUGE_NUMBERS)
            lines[i] = " ".join(parts)
    elif kind == 1:  # a property type
        idx = [i for i, l in enumerate(lines) if l.startswith("property")]
        if idx:
            i = rng.choice(idx)
            parts = lines[i].split(" ")
            parts[rng.randrange(1, len(parts))] = rng.choice(BAD_TYPES + ["uchar", "int", "double", "short"])
            lines[i] = " ".join(parts)
    elif kind == 2:  # duplicate a header line
        i = rng.randrange(1, max(2, len(lines) - 1))
        lines.insert(i, lines[i])
    elif kind == 3:  # delete a header line
        if len(lines) > 2:
            del lines[rng.randrange(1, len(lines) - 1)]
    elif kind == 4:  # move a line (a property before any element, end_header too early)
        if len(lines) > 3:
            line = lines.pop(rng.randrange(1, len(lines) - 1))
            lines.insert(rng.randrange(1, len(lines)), line)
    elif kind == 5:  # the format line
        idx = [i for i, l in enumerate(lines) if l.startswith("format")]
        if idx:
            lines[idx[0]] = "format " + rng.choice(["ascii", "binary_little_endian", "binary_big_endian",
                                                    "binary", "ascii 2.0", ""]) + rng.choice([" 1.0", ""])
    elif kind == 6:  # end_header hidden in a comment or glued to a word
        lines.insert(rng.randrange(1, len(lines)), rng.choice(["comment end_header", "xend_header",
                                                               "end_headerx", "property float end_header"]))
        if rng.random() < 0.5:
            lines = [l for l in lines if l.strip() != "end_header"]
    elif kind == 7:  # list sizes in the body
        if b"format ascii" in head:
            blines = body.split(b"\n")
            if len(blines) > 2:
                i = rng.randrange(len(blines) - 1)
                parts = blines[i].split(b" ")
                parts[0] = rng.choice(HUGE_NUMBERS).encode()
                blines[i] = b" ".join(parts)
                body = b"\n".join(blines)
        else:
            # the uchar list count of a face: faces follow the vertices at the end of the file
            if len(body) > 20:
                at = rng.randrange(len(body) // 2, len(body))
                body = body[:at] + bytes([rng.choice([0, 1, 2, 4, 255, 128])]) + body[at + 1:]
    elif kind == 8:  # a face index out of range
        if b"format ascii" in head:
            blines = body.split(b"\n")
            idx = [i for i, l in enumerate(blines) if l.startswith(b"3 ") or l.startswith(b"4 ")]
            if idx:
                i = rng.choice(idx)
                parts = blines[i].split(b" ")
                parts[rng.randrange(1, len(parts))] = rng.choice(HUGE_NUMBERS).encode()
                blines[i] = b" ".join(parts)
                body = b"\n".join(blines)
        elif len(body) > 8:
            at = rng.randrange(len(body) - 4)
            body = body[:at] + struct.pack("<i", rng.choice([-1, 2 ** 31 - 1, 1000, 21])) + body[at + 4:]
    else:  # a list index type or an extra list property
        lines.insert(rng.randrange(1, len(lines)), rng.choice([
            "property list uint int vertex_indices", "property list int int vertex_indices",
            "property list uchar float vertex_indices", "property list float int vertex_indices",
            "property list uchar int extra", "element face 4294967295", "element vertex 0",
            "property list uint16 int vertex_indices", "element vertex 1000000000"]))
    return "\n".join(lines).encode("latin-1") + body


def off_mutation(data, rng):
    text = data.decode("latin-1")
    kind = rng.randrange(4)
    if data.startswith(b"OFF BINARY"):
        data = bytearray(data)
        at = 11 + 4 * rng.randrange(3) if kind < 2 else rng.randrange(11, len(data) - 4)
        data[at:at + 4] = struct.pack("<i", rng.choice([-1, 0, 2 ** 31 - 1, 10 ** 9, 3, 1000, 65536]))
        return bytes(data)
    lines = text.split("\n")
    if kind == 0:  # the counts line
        lines[2] = replace_random_number(lines[2], rng)
    elif kind == 1:  # a face valence
        idx = [i for i, l in enumerate(lines) if l.startswith("3 ") or l.startswith("4 ")]
        if idx:
            i = rng.choice(idx)
            lines[i] = rng.choice(HUGE_NUMBERS) + lines[i][1:]
    elif kind == 2:  # the magic
        lines[0] = rng.choice(["COFF", "NOFF", "STOFF", "4OFF", "nOFF", "CNOFF", "OFFx", "OFF BINARY", "OF",
                               "STCN4nOFF", "nOFF 1000000000"])
    else:  # any number
        i = rng.randrange(len(lines))
        lines[i] = replace_random_number(lines[i], rng)
    return "\n".join(lines).encode("latin-1")


def om_chunks(data):
    """(header offset, entity, type, data offset, data size) of each chunk of a well-formed OM
    seed, walked as the format says (OpenMesh's OMFormat.hh); stops at anything it does not know."""
    nv, nf, ne = struct.unpack_from("<III", data, 4)
    counts = {0: nv, 1: 1, 2: nf, 4: ne, 6: 2 * ne}
    out, at = [], 16
    while at + 2 <= len(data):
        h = struct.unpack_from("<H", data, at)[0]
        entity, ctype, is_float, dim, bits = (h >> 2) & 7, (h >> 5) & 15, (h >> 10) & 1, ((h >> 11) & 7) + 1, h >> 14
        if entity == 7 or entity not in counts:
            break
        p = at + 2
        if h & 2:  # named
            p += 1 + data[p]
        if ctype == 6:  # custom: the type name (version 2.2), a uint32 size, the bytes
            p += 1 + data[p]
            size = struct.unpack_from("<I", data, p)[0]
            p += 4
        elif ctype == 7:
            size = counts[entity] * (1 << bits) * (3 if entity == 6 else 1)
        elif ctype == 3:
            size = counts[entity] * 4
        else:
            size = counts[entity] * dim * ((4 << bits) if is_float else (1 << bits))
        out.append((at, entity, ctype, p, size))
        at = p + size
    return out


def om_mutation(data, rng):
    """Header counts, chunk header fields, topology indices and chunk boundaries of an OM file."""
    data = bytearray(data)
    chunks = om_chunks(bytes(data))
    kind = rng.randrange(6)
    if kind == 0 or not chunks:  # a header count
        at = 4 + 4 * rng.randrange(3)
        data[at:at + 4] = struct.pack("<I", rng.choice([0, 1, 2, 0xffffffff, 0x7fffffff, 0x10000, 1000,
                                                        struct.unpack_from("<I", data, at)[0] + 1]))
    elif kind == 1:  # a field of a chunk header: name, entity, type, float, dimension or size code
        at = rng.choice(chunks)[0]
        h = struct.unpack_from("<H", data, at)[0]
        shift, width = rng.choice([(0, 1), (1, 1), (2, 3), (5, 4), (10, 1), (11, 3), (14, 2)])
        h = (h & ~(((1 << width) - 1) << shift)) | (rng.randrange(1 << width) << shift)
        data[at:at + 2] = struct.pack("<H", h)
    elif kind == 2:  # an index in a topology chunk
        topo = [c for c in chunks if c[2] == 7 and c[4] > 0]
        if topo:
            _, _, _, p, size = rng.choice(topo)
            at = p + rng.randrange(size)
            data[at] = rng.choice([0x7f, 0x80, 0xff, 0xfe, 0, 1, 2, 3, 5, 6, 7, 8, 100])
    elif kind == 3:  # cut at a chunk boundary, or inside one
        at, _, _, p, size = rng.choice(chunks)
        del data[rng.choice([at, at + 1, p, p + max(size // 2, 1), p + size]):]
    elif kind == 4:  # a chunk twice, or moved after the others
        at, _, _, p, size = rng.choice(chunks)
        chunk = data[at:p + size]
        if rng.random() < 0.5:
            data[p + size:p + size] = chunk
        else:
            del data[at:p + size]
            data[-2:-2] = chunk
    else:  # the version byte, the mesh kind, or a custom chunk's size
        custom = [c for c in chunks if c[2] == 6]
        r = rng.random()
        if custom and r < 0.4:
            p = rng.choice(custom)[3]
            data[p - 4:p] = struct.pack("<I", rng.choice([0, 0xffffffff, 0x7fffffff, 1000, 3]))
        elif r < 0.7:
            data[3] = rng.choice([0x00, 0x20, 0x40, 0x41, 0x43, 0x5f, 0xff])
        else:
            data[2] = rng.choice(b"TQPX\0")
    return bytes(data)


def stl_mutation(data, rng):
    if data.startswith(b"solid seed\n"):
        lines = data.split(b"\n")
        kind = rng.randrange(3)
        if kind == 0:
            del lines[rng.randrange(len(lines))]
        elif kind == 1:
            i = rng.randrange(len(lines))
            lines[i] = replace_random_number(lines[i].decode("latin-1"), rng).encode("latin-1")
        else:
            i = rng.randrange(len(lines))
            lines.insert(i, rng.choice([b"outer loop", b"endsolid", b"solid", b"vertex 1 2", b"facet"]))
        return b"\n".join(lines)
    data = bytearray(data)
    value = rng.choice([0, 1, 0xffffffff, 0x7fffffff, 10 ** 8, len(data) // 50, 12])
    data[80:84] = struct.pack("<I", value)
    if rng.random() < 0.5:
        data = data[:rng.randrange(len(data))]
    return bytes(data)


def obj_mutation(data, rng):
    lines = data.split(b"\n")
    kind = rng.randrange(4)
    idx = [i for i, l in enumerate(lines) if l.startswith(b"f ")]
    if kind == 0 and idx:
        i = rng.choice(idx)
        parts = lines[i].split(b" ")
        parts[rng.randrange(1, len(parts))] = rng.choice(HUGE_NUMBERS + ["1/999999", "1//-5", "1/2/3/4"]).encode()
        lines[i] = b" ".join(parts)
    elif kind == 1:
        lines.insert(rng.randrange(len(lines)), rng.choice([
            b"mtllib /etc/passwd", b"mtllib missing.mtl", b"usemtl x", b"vt 1e999 2", b"vn nan nan nan",
            b"f", b"f 1", b"v", b"g", b"s off", b"f " + b" ".join(b"1" for _ in range(5000)),
            b"f 1/1/1 2/2/2 3/3/3", b"l 1 2", b"vp 1 2 3"]))
    elif kind == 2:
        i = rng.randrange(len(lines))
        lines[i] = replace_random_number(lines[i].decode("latin-1"), rng).encode("latin-1")
    else:
        del lines[rng.randrange(len(lines)):]
    return b"\n".join(lines)


JSON_ODD_VALUES = [None, True, -1, 0, 1e308, -1e308, 1e-320, 2 ** 63, "", "x" * 5000, [], {}, [1, 2],
                   [float("nan")] if False else [1e999 if False else 3.4e38], "builtin:", "builtin:nothing",
                   "/", "/dev/zero", "/proc/self/mem", "../../../../etc/passwd", "seed.ply", "nonexistent.obj",
                   "\u0000", "\u2028", 9999999, -9999999, 4294967296]


def json_mutation(data, rng):
    try:
        doc = json.loads(data)
    except ValueError:
        return byte_mutation(data, rng)
    paths = []

    def walk(v, path):
        paths.append(path)
        if isinstance(v, dict):
            for k, x in v.items():
                walk(x, path + [k])
        elif isinstance(v, list):
            for i, x in enumerate(v):
                walk(x, path + [i])

    walk(doc, [])
    for _ in range(rng.choice([1, 1, 2, 3])):
        path = rng.choice(paths[1:]) if len(paths) > 1 else []
        parent = doc
        try:
            for p in path[:-1]:
                parent = parent[p]
            key = path[-1]
            kind = rng.randrange(4)
            if kind == 0:
                parent[key] = rng.choice(JSON_ODD_VALUES)
            elif kind == 1 and isinstance(parent, dict):
                del parent[key]
            elif kind == 2 and isinstance(parent, list):
                parent.extend([parent[key]] * rng.choice([1, 10, 200]))
            else:
                v = parent[key]
                parent[key] = [v, v] if rng.random() < 0.5 else {"x": v}
        except (KeyError, IndexError, TypeError):
            pass
    text = json.dumps(doc)
    if rng.random() < 0.1:  # deep nesting
        text = text[:-1] + ', "deep": ' + "[" * 5000 + "]" * 5000 + "}"
    return text.encode()


GLTF_INDEX_KEYS = (b"mesh|material|source|sampler|bufferView|buffer|index|indices|scene|camera|skin|node|"
                   b"POSITION|NORMAL|TANGENT|TEXCOORD_0|TEXCOORD_1|COLOR_0|texCoord")
GLTF_NUMBERS = [b"4294967296", b"4294967297", b"-1", b"-4", b"2147483647", b"2147483648", b"1e308", b"-1e308",
                b"-0", b"0.5", b"1e-320", b"9007199254740993", b"18446744073709551616", b"1e999", b"3.0"]
GLTF_KINDS = [b'"x"', b"null", b"true", b"{}", b"[]", b"[1,2]", b"[null]", b'{"a":1}']
GLTF_STRINGS = [b"../outside.png", b"/etc/passwd", b"tex.png%00.jpg", b"%2e%2e/x.bin", b"data:image/png;base64,!!!",
                b"data:application/octet-stream;base64,AAAA", b"", b"file:///etc/passwd", b"a%zz.png",
                b"seed.bin", b"nonexistent.png", b"C:\\\\x.png"]


def gltf_text_mutation(text, rng):
    """One structural mutation of glTF JSON text (as tests/fuzz/gltf_mutator.h does in the fuzz target)."""
    kind = rng.randrange(7)
    def sub(match, group, value):
        return text[:match.start(group)] + value + text[match.end(group):]
    if kind == 0:  # an index wrapped past the integers it may hold
        found = list(re.finditer(rb'"(?:' + GLTF_INDEX_KEYS + rb')"\s*:\s*(\d+)', text)) or \
            list(re.finditer(rb'"(?:nodes|children|joints)"\s*:\s*\[\s*(\d+)', text))
        if found:
            m = rng.choice(found)
            n = int(m.group(1))
            return sub(m, 1, str(rng.choice([n + 2 ** 32, n + 2 ** 31, -n - 1, n + 2 ** 33])).encode())
    values = list(re.finditer(rb':\s*(-?[0-9][0-9.eE+-]*|true|false|null|"[^"]*")', text))
    if kind == 1 and values:
        return sub(rng.choice(values), 1, rng.choice(GLTF_NUMBERS))
    if kind == 2 and values:
        depth = rng.choice([63, 64, 65, 300, 5000, 30000])
        nest = b'{"a":' * depth + b"0" + b"}" * depth if rng.random() < 0.5 else b"[" * depth + b"0" + b"]" * depth
        return sub(rng.choice(values), 1, nest)
    if kind == 3 and values:
        return sub(rng.choice(values), 1, rng.choice(GLTF_KINDS))
    if kind == 4:
        found = list(re.finditer(rb'"uri"\s*:\s*"([^"]*)"', text)) or list(re.finditer(rb'"name"\s*:\s*"([^"]*)"', text))
        if found:
            return sub(rng.choice(found), 1, rng.choice(GLTF_STRINGS))
    if kind == 5:  # an array of indices repeated or grown
        found = list(re.finditer(rb'\[(\s*\d+)', text))
        if found:
            m = rng.choice(found)
            return text[:m.end(1)] + (b"," + m.group(1).strip()) * rng.choice([1, 10, 1000]) + text[m.end(1):]
    # Otherwise a whole object or array of the document duplicated or dropped (json_mutation's kinds).
    return json_mutation(text, rng)


def gltf_mutation(data, rng):
    if data[:4] == b"glTF" and len(data) >= 20 and data[16:20] == b"JSON":
        length = min(struct.unpack_from("<I", data, 12)[0], len(data) - 20)
        text = gltf_text_mutation(data[20:20 + length], rng)
        text += b" " * (-len(text) % 4)
        rest = data[20 + length:]
        out = bytearray(data[:20]) + text + rest
        struct.pack_into("<II", out, 8, len(out), len(text))
        return bytes(out)
    return gltf_text_mutation(data, rng)


def gltf_seeds():
    corpus = os.path.join(ROOT, "tests", "fuzz", "corpus", "gltf_import")
    out = {".gltf": [], ".glb": []}
    for name in sorted(os.listdir(corpus)):
        ext = os.path.splitext(name)[1]
        if ext in out:
            with open(os.path.join(corpus, name), "rb") as f:
                out[ext].append(f.read())
    return out


# ---------------------------------------------------------------------------------------------
# Formats: name -> (extension, seeds, format-aware mutation, command builder)


def build_formats(work, rng_seed):
    pos, tris, quads = small_mesh()
    seeds = {
        "obj": (".obj", [seed_obj(pos, tris, quads)], obj_mutation),
        "off-ascii": (".off", [seed_off_ascii(pos, tris, quads)], off_mutation),
        "off-binary": (".off", [seed_off_binary(pos, tris, quads)], off_mutation),
        "ply-ascii": (".ply", [seed_ply_ascii(pos, tris, quads), seed_ply_ascii(pos, tris, quads, True)],
                      ply_mutation),
        "ply-binary-le": (".ply", [seed_ply_binary(pos, tris, quads, "little"),
                                   seed_ply_binary(pos, tris, quads, "little", True)], ply_mutation),
        "ply-binary-be": (".ply", [seed_ply_binary(pos, tris, quads, "big"),
                                   seed_ply_binary(pos, tris, quads, "big", True)], ply_mutation),
        "stl-ascii": (".stl", [seed_stl_ascii(pos, tris)], stl_mutation),
        "stl-binary": (".stl", [seed_stl_binary(pos, tris)], stl_mutation),
        "om": (".om", [SEED_OM, SEED_OM_POLYGONS, SEED_OM_CHUNKS], om_mutation),
        "scene": (".json", [seed_scene("seed.obj"), seed_scene("seed.ply")], json_mutation),
        "library": (".json", [seed_library()], json_mutation),
    }
    # glTF and GLB (issue 34), from the glTF fuzz target's seeds, drawn by `render --mesh` and
    # read by `library import-gltf`.
    gltf = gltf_seeds()
    seeds["gltf"] = (".gltf", gltf[".gltf"], gltf_mutation)
    seeds["glb"] = (".glb", gltf[".glb"], gltf_mutation)
    # The library imports materials: its seeds are the files that have some.
    seeds["gltf-library"] = (".gltf", [d for d in gltf[".gltf"] if b'"materials"' in d], gltf_mutation)
    seeds["glb-library"] = (".glb", [d for d in gltf[".glb"] if b'"materials"' in d], gltf_mutation)
    # The real OBJ assets too (kept for a minority of OBJ cases: they take longer to render).
    assets = os.path.join(ROOT, "tests", "assets", "meshes")
    for name in sorted(os.listdir(assets)):
        if name.endswith(".obj"):
            with open(os.path.join(assets, name), "rb") as f:
                seeds["obj"][1].append(f.read())
    # Meshes the scene seeds refer to, beside the cases.
    with open(os.path.join(work, "seed.obj"), "wb") as f:
        f.write(seed_obj(pos, tris, quads))
    with open(os.path.join(work, "seed.ply"), "wb") as f:
        f.write(seed_ply_binary(pos, tris, quads, "little"))
    return seeds


def make_case(fmt, seeds, mutate, rng):
    seed_list = seeds
    # Small seeds three times as often as the big OBJ assets.
    seed = seed_list[0] if len(seed_list) == 1 or rng.random() < 0.6 else rng.choice(seed_list)
    r = rng.random()
    if r < 0.45:
        data = byte_mutation(seed, rng)
    elif r < 0.9:
        data = mutate(seed, rng)
    else:
        data = byte_mutation(mutate(seed, rng), rng)
    return data


def command(mipgloss, fmt, case, out_png):
    if fmt == "library":
        return [mipgloss, "library", "list", case]
    if fmt.endswith("-library"):
        return [mipgloss, "library", "import-gltf", case + ".mglib", case]
    size = ["--size", "32x32", "--env-size", "16", "--quiet"]
    if fmt == "scene":
        return [mipgloss, "render", case, "--out", out_png] + size
    return [mipgloss, "render", "--mesh", case, "--out", out_png] + size


def run_case(cmd, case, timeout, mem_limit):
    # Qt aborts when the X server cannot be reached (another xvfb-run taking the display number
    # away): that is the machine, not the file, so such a run is repeated.
    # If the display is still gone after the retries the case is "no-display": it says nothing
    # about the file, and it is never counted as a crash.
    for attempt in range(4):
        result = run_once(cmd, case, timeout, mem_limit)
        if "could not connect to display" not in result[3]:
            return result
        time.sleep(0.5 * (attempt + 1))
    return ("no-display",) + tuple(result[1:])


def run_once(cmd, case, timeout, mem_limit):
    def limits():
        os.setsid()
        if mem_limit:
            resource.setrlimit(resource.RLIMIT_AS, (mem_limit, mem_limit))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))

    err_path = case + ".stderr"
    start = time.monotonic()
    with open(err_path, "wb") as err:
        import subprocess
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err, stdin=subprocess.DEVNULL,
                             preexec_fn=limits)
        timed_out = threading.Event()

        def kill():
            timed_out.set()
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass

        timer = threading.Timer(timeout, kill)
        timer.start()
        _, status, usage = os.wait4(p.pid, 0)
        timer.cancel()
        p.returncode = 0  # reaped here; keep Popen from waiting again
    seconds = time.monotonic() - start
    with open(err_path, "rb") as f:
        stderr = f.read().decode("utf-8", "replace")
    peak_mib = usage.ru_maxrss / 1024.0
    if timed_out.is_set():
        return "hang", seconds, peak_mib, stderr
    if os.WIFSIGNALED(status):
        return "crash", seconds, peak_mib, "signal %d\n%s" % (os.WTERMSIG(status), stderr)
    code = os.WEXITSTATUS(status)
    if code == 0:
        return "ok", seconds, peak_mib, stderr
    if os.path.basename(case) in stderr:
        return "refused", seconds, peak_mib, stderr
    return "nameless", seconds, peak_mib, "exit %d\n%s" % (code, stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "dev"))
    ap.add_argument("--cases", type=int, default=200, help="cases per format (default 200)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per case (default 20)")
    ap.add_argument("--mem-limit-mib", type=int, default=6144,
                    help="address-space limit per case, MiB (default 6144; 0: none)")
    ap.add_argument("--seed", type=int, default=11)
    ap.add_argument("--formats", default="", help="comma-separated subset")
    ap.add_argument("--out", default="", help="folder for the cases (default: a temporary one, removed)")
    args = ap.parse_args()

    mipgloss = os.path.join(os.path.abspath(args.build), "app", "mipgloss")
    if not os.access(mipgloss, os.X_OK):
        print("fuzz-meshes: no %s; build the mipgloss target first" % mipgloss, file=sys.stderr)
        return 2
    work = os.path.abspath(args.out) if args.out else tempfile.mkdtemp(prefix="mipgloss-fuzz.")
    os.makedirs(work, exist_ok=True)
    failures = os.path.join(work, "failures")
    formats = build_formats(work, args.seed)
    chosen = [f for f in formats if not args.formats or f in args.formats.split(",")]

    jobs = []
    for fmt in chosen:
        ext, seeds, mutate = formats[fmt]
        rng = random.Random("%d/%s" % (args.seed, fmt))
        # The unmutated seeds first: they must load (ok), or the fuzzing starts from nothing.
        for k in range(args.cases):
            data = seeds[k] if k < len(seeds) else make_case(fmt, seeds, mutate, rng)
            case = os.path.join(work, "%s_%04d%s" % (fmt, k, ext))
            with open(case, "wb") as f:
                f.write(data)
            jobs.append((fmt, k, case, k < len(seeds)))

    mem_limit = args.mem_limit_mib * 1024 * 1024 if args.mem_limit_mib else 0
    results = {}
    t0 = time.monotonic()
    done = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(run_case, command(mipgloss, fmt, case, case + ".png"), case, args.timeout,
                               mem_limit): (fmt, k, case, is_seed) for fmt, k, case, is_seed in jobs}
        for fut in concurrent.futures.as_completed(futures):
            fmt, k, case, is_seed = futures[fut]
            kind, seconds, peak, stderr = fut.result()
            results.setdefault(fmt, []).append((kind, seconds, peak, case, is_seed, stderr))
            with open(os.path.join(work, "results.tsv"), "a") as log:
                log.write("%s\t%s\t%s\t%.2f\t%.0f\n" % (fmt, os.path.basename(case), kind, seconds, peak))
            done += 1
            if kind in ("crash", "hang", "nameless", "no-display") or (is_seed and kind != "ok"):
                os.makedirs(failures, exist_ok=True)
                shutil.copy(case, failures)
                first = stderr.strip().splitlines()[:2]
                print("  %-8s %s (%.1f s): %s" % (kind.upper(), os.path.basename(case), seconds, " | ".join(first)),
                      flush=True)
            if done % 100 == 0:
                print("  ... %d/%d cases, %.0f s" % (done, len(jobs), time.monotonic() - t0), flush=True)

    kinds = ["ok", "refused", "nameless", "crash", "hang", "no-display"]
    print("\n%-14s %6s %8s %8s %6s %5s %10s %6s %10s %11s" % ("format", *kinds, "cases", "slowest s", "peak MiB"))
    bad = 0
    seeds_failed = 0
    for fmt in chosen:
        rows = results.get(fmt, [])
        counts = {k: sum(1 for r in rows if r[0] == k) for k in kinds}
        bad += counts["nameless"] + counts["crash"] + counts["hang"]
        seeds_failed += sum(1 for r in rows if r[4] and r[0] != "ok")
        print("%-14s %6d %8d %8d %6d %5d %10d %6d %10.1f %11.0f" % (
            fmt, *(counts[k] for k in kinds), len(rows), max(r[1] for r in rows), max(r[2] for r in rows)))
    print("\n%d cases in %.0f s (jobs %d, timeout %.0f s, address space %s); cases in %s" % (
        len(jobs), time.monotonic() - t0, args.jobs, args.timeout,
        "%d MiB" % args.mem_limit_mib if mem_limit else "unlimited", work))
    no_display = sum(1 for rows in results.values() for r in rows if r[0] == "no-display")
    if no_display:
        print("fuzz-meshes: %d case(s) could not reach the X display (not the files' fault; not counted as "
              "crashes): the run is incomplete, run it again" % no_display)
    if seeds_failed:
        print("fuzz-meshes: %d unmutated seed(s) did not load" % seeds_failed)
    if bad:
        print("fuzz-meshes: FAIL: %d case(s) crashed, hung or were refused without the file name (copies in %s)"
              % (bad, failures))
    else:
        print("fuzz-meshes: no crash, no hang, every refusal names the file")
    if not args.out:
        if bad or seeds_failed:
            print("(keeping %s for the failures)" % work)
        else:
            shutil.rmtree(work, ignore_errors=True)
    return 1 if bad or seeds_failed else 3 if no_display else 0


if __name__ == "__main__":
    sys.exit(main())
