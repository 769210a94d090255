#!/usr/bin/env python3
"""Draws docs/rooms.svg: the rooms of mipgloss, what each holds, what it may use (its links, which the
build enforces), and how many lines each holds now. Run from the repository root:
    python3 scripts/draw-rooms.py > docs/rooms.svg
Lines are counted over a room's C++ and GLSL files (headers, sources, shaders), tests not included."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# name, folders counted, what it holds (two short lines), column, row. Row 0 is the top.
ROOMS = [
    ("app", ["app"], "mipgloss (CLI): options → work", "mipgloss-gui: the window's shell", 1, 0),
    ("ui/widgets", ["ui/widgets"], "main window (composition), panels,", "docks, viewport, message bar", 1, 1),
    ("ui/documents", ["ui/documents"], "scene/library documents, undo, the", "one worker, file session, imports", 0, 2),
    ("ui/render", ["ui/render", "resources/shaders"], "renderer in passes + shaders:", "GPU resources, object, outline, AOV", 2, 2),
    ("ui/files", ["ui/files"], "scene, library, material files", "(Qt Core only)", 0, 3),
    ("core/assets", ["core/assets"], "mesh and asset readers (glTF, OBJ,", "PLY...), textures, default scene", 1, 4),
    ("core/scene", ["core/scene"], "scene model, camera and view,", "shading plan, lobe stack, layers", 1, 5),
    ("core/io", ["core/io"], "image files (OpenImageIO on demand),", "layouts, lat-long, bake", 0, 6),
    ("core/ibl", ["core/ibl"], "the maths: cube maps, builders,", "λ ↔ n, irradiance, metrics", 2, 6),
]
# Who uses whom (a CMake link; the arrow points at what is used). Transitive links are not drawn.
LINKS = [
    ("app", "ui/widgets"), ("app", "ui/render"), ("app", "ui/files"),
    ("ui/widgets", "ui/documents"), ("ui/widgets", "ui/render"),
    ("ui/documents", "ui/files"), ("ui/files", "core/assets"), ("ui/render", "core/assets"),
    ("core/assets", "core/scene"), ("core/scene", "core/io"), ("core/scene", "core/ibl"),
    ("core/io", "core/ibl"),
]
EXTENSIONS = (".cpp", ".h", ".glsl", ".frag", ".vert")


def lines_in(folders):
    files = total = 0
    for folder in folders:
        for dirpath, _, names in os.walk(os.path.join(ROOT, folder)):
            for name in names:
                if name.endswith(EXTENSIONS):
                    with open(os.path.join(dirpath, name), encoding="utf-8", errors="replace") as f:
                        total += sum(1 for _ in f)
                    files += 1
    return files, total


W, H, BOX_W, BOX_H, COL_X, ROW_Y = 900, 730, 250, 66, [30, 325, 620], 70
TOP = 92


def box_of(name):
    for room in ROOMS:
        if room[0] == name:
            return COL_X[room[4]], TOP + room[5] * (ROW_Y + 12)
    raise KeyError(name)


def esc(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" '
       'font-family="DejaVu Sans, sans-serif">',
       '<defs><marker id="a" markerWidth="8" markerHeight="8" refX="7" refY="4" orient="auto">'
       '<path d="M0,0 L8,4 L0,8 z" fill="#777"/></marker></defs>',
       f'<rect width="{W}" height="{H}" fill="white"/>',
       '<text x="30" y="34" font-size="20" font-weight="bold">The rooms of mipgloss</text>',
       '<text x="30" y="56" font-size="12" fill="#444">Each box is a library with its own folder and '
       'source list; an arrow is a link, the only way a room sees another.</text>',
       '<text x="30" y="72" font-size="12" fill="#444">Data flows one way: files → core → GPU upload → '
       'frame. GL code holds only GL state; no room keeps process-wide mutable state.</text>']
for a, b in LINKS:
    ax, ay = box_of(a)
    bx, by = box_of(b)
    # From the user's bottom (or its side, toward a room in another column) to the used room's top.
    x1, y1 = ax + BOX_W / 2, ay + BOX_H
    x2, y2 = bx + BOX_W / 2, by
    if ay == by:  # same row: side to side
        y1 = y2 = ay + BOX_H / 2
        x1, x2 = (ax + BOX_W, bx) if ax < bx else (ax, bx + BOX_W)
    elif bx > ax:
        x1, y1 = ax + BOX_W, ay + BOX_H / 2
    elif bx < ax:
        x1, y1 = ax, ay + BOX_H / 2
    if bx != ax and by - ay > ROW_Y + 12:  # rows apart: into the side facing the user, past the rooms between
        x2, y2 = (bx + BOX_W if bx < ax else bx), by + BOX_H / 2
    out.append(f'<line x1="{x1:.0f}" y1="{y1:.0f}" x2="{x2:.0f}" y2="{y2:.0f}" stroke="#777" '
               'stroke-width="1.3" marker-end="url(#a)"/>')
for name, folders, line1, line2, col, row in ROOMS:
    x, y = box_of(name)
    files, total = lines_in(folders)
    fill = "#e8f0fb" if name.startswith("core") else "#fdf1e0" if name.startswith("ui") else "#e9f6e9"
    out.append(f'<rect x="{x}" y="{y}" width="{BOX_W}" height="{BOX_H}" rx="6" fill="{fill}" stroke="#556"/>')
    out.append(f'<text x="{x + 10}" y="{y + 18}" font-size="14" font-weight="bold">{esc(name)}</text>')
    out.append(f'<text x="{x + BOX_W - 10}" y="{y + 18}" font-size="11" fill="#555" text-anchor="end">'
               f'{files} files, {total:,} lines</text>')
    out.append(f'<text x="{x + 10}" y="{y + 37}" font-size="11">{esc(line1)}</text>')
    out.append(f'<text x="{x + 10}" y="{y + 53}" font-size="11">{esc(line2)}</text>')
legend_y = TOP + 7 * (ROW_Y + 12) + 4
out.append(f'<text x="30" y="{legend_y}" font-size="11" fill="#444">blue: no Qt (core); orange: Qt rooms '
           '(ui); green: the two executables.</text>')
out.append(f'<text x="30" y="{legend_y + 16}" font-size="11" fill="#444">Counts: C++ and GLSL under the '
           'folder (ui/render with resources/shaders), tests not included: scripts/draw-rooms.py.</text>')
out.append('</svg>')
sys.stdout.write("\n".join(out) + "\n")
