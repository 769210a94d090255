#!/usr/bin/env bash
# Generated tangents against Blender's (docs/assets.md, "Tangents"): each glTF given is imported by
# Blender and exported with its MikkTSpace tangents (TANGENT); mipgloss then draws that export
# through each of its cameras twice, with the supplied tangents and with TANGENT removed (its own
# MikkTSpace), and prints the relative RMS difference over the object's pixels. Not part of the
# test suite (Blender is a peer to compare with, not a dependency): apt install blender first.
#
#   xvfb-run -a scripts/tangents-vs-blender.sh [--env FILE] MODEL.gltf...
set -euo pipefail
cd "$(dirname "$0")/.."
env=tests/assets/env/studio.exr
if [ "${1:-}" = "--env" ]; then env=$2; shift 2; fi
mipgloss=${MIPGLOSS:-build/dev/app/mipgloss}
work=$(mktemp -d "${TMPDIR:-/tmp}/mipgloss-tangents.XXXXXX")
trap 'rm -rf "$work"' EXIT
for model in "$@"; do
  name=$(basename "$model" .gltf)
  blender -b -P scripts/tangents/blender_export.py -- "$model" "$work/$name.gltf" >/dev/null 2>&1
  /usr/bin/python3 - "$work/$name.gltf" "$work/$name-generated.gltf" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
for mesh in j["meshes"]:
    for p in mesh["primitives"]:
        p["attributes"].pop("TANGENT", None)
json.dump(j, open(sys.argv[2], "w"))
PY
  cameras=$(/usr/bin/python3 -c "import json,sys; print(len(json.load(open(sys.argv[1])).get('cameras', [])))" "$work/$name.gltf")
  for ((k = 0; k < cameras; ++k)); do
    for v in "$name" "$name-generated"; do
      "$mipgloss" render --mesh "$work/$v.gltf" --camera "$k" --env "$env" --no-background --size 512x512 --quiet \
        --out "$work/$v-$k.exr" 2>/dev/null
      oiiotool "$work/$v-$k.exr" --ch R,G,B -d float --compression none -o "$work/$v-$k.tif"
    done
    /usr/bin/python3 - "$work/$name-$k.tif" "$work/$name-generated-$k.tif" "$name camera $k" <<'PY'
import sys, numpy as np, tifffile
supplied, generated = (tifffile.imread(f).astype(np.float64) for f in sys.argv[1:3])
mask = (supplied.sum(-1) > 0) | (generated.sum(-1) > 0)
d = generated[mask] - supplied[mask]
print(f"{sys.argv[3]}: {mask.sum()} object pixels, relative RMS {100 * np.sqrt((d ** 2).mean()) / np.sqrt((supplied[mask] ** 2).mean()):.4f} %")
PY
  done
done
