#!/usr/bin/env bash
# The Khronos 3D Commerce viewer certification (test plan V1.1.1), as far as its files allow:
# every reference view of the suite's models drawn by `mipgloss render` as the test plan asks, and
# scored by the suite's own evaluation/evaluation.py (SSIM and PSNR). docs/certification.md says
# what each step follows and what cannot be run.
#
#   scripts/certify-3dc.sh [--env FILE] [--suite DIR] [--out DIR] [--mipgloss EXE] [--rotation DEG]
#
#   --env FILE      the lighting (default: the suite's proxy-env/Neutral-proxy.hdr, a stand-in
#                   for Neutral.hdr, which the suite's copy lacks; SOURCES.md there)
#   --suite DIR     the suite as Khronos publishes it (default: ../shared/3dc-certification
#                   beside the repository; MIPGLOSS_3DC_SUITE overrides it)
#   --out DIR       where the candidates c-*.png go (default: a new temporary folder)
#   --mipgloss EXE  the command-line program (default: build/dev/app/mipgloss)
#   --rotation DEG  the environment's turn about +Y (default -90: the studio's gap between its two
#                   silks faces the model's cameras, as reference-render-creation.adoc asks)
#
# Prints one line per view (model, view, SSIM, PSNR, thresholds, margins, pass or fail), the views
# that cannot run and why, then "N passed, M failed". Exit 0 only when every view that runs passes;
# 1 when one fails; 77 when the suite or its Python (Debian's python3-skimage) is not there.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD

suite=${MIPGLOSS_3DC_SUITE:-$repo/../shared/3dc-certification}
env=""
out=""
mipgloss=$repo/build/dev/app/mipgloss
rotation=-90
while [ $# -gt 0 ]; do
  case "$1" in
    --env) env=$2; shift 2 ;;
    --suite) suite=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --mipgloss) mipgloss=$2; shift 2 ;;
    --rotation) rotation=$2; shift 2 ;;
    *) echo "certify-3dc: unknown option '$1' (see the top of $0)" >&2; exit 2 ;;
  esac
done

if [ ! -f "$suite/evaluation/evaluation.py" ]; then
  echo "certify-3dc: no suite at $suite (evaluation/evaluation.py missing): nothing certified" >&2
  exit 77
fi
# Debian's Python, where python3-skimage is installed (a python3 earlier on PATH may not have it).
python=/usr/bin/python3
if ! "$python" -c "import skimage, numpy, reportlab" 2>/dev/null; then
  echo "certify-3dc: $python lacks scikit-image or reportlab (scripts/install-deps.sh installs them)" >&2
  exit 77
fi
[ -x "$mipgloss" ] || { echo "certify-3dc: no program at $mipgloss (build first)" >&2; exit 2; }
env=${env:-$suite/proxy-env/Neutral-proxy.hdr}
[ -f "$env" ] || { echo "certify-3dc: no environment at $env" >&2; exit 2; }
if [ -z "$out" ]; then out=$(mktemp -d "${TMPDIR:-/tmp}/mipgloss-3dc.XXXXXX"); fi
mkdir -p "$out"
echo "certify-3dc: suite $suite, environment $env (turned $rotation°), candidates in $out"

# Each reference render rr-MODEL[-K|-LIGHT].png is one view: rr-MODEL-K through the model's
# camera K, rr-MODEL through its one camera. rr-MODEL-LIGHT is lit by another of the suite's
# lighting files (Cannon, Street, Studio), none of which the suite's copy has.
skipped=()
for reference in "$suite"/models/*/rr-*.png; do
  folder=$(dirname "$reference")
  model=$(basename "$folder")
  view=$(basename "$reference" .png)
  view=${view#rr-}
  suffix=${view#"$model"}
  suffix=${suffix#-}
  case "$suffix" in
    "") camera=0 ;;
    [0-9]) camera=camera$suffix ;;
    *) skipped+=("$model $suffix: lit by the suite's $suffix lighting file, which is not in its copy (SOURCES.md)")
       continue ;;
  esac
  gltf="$folder/glTF/$model.gltf"
  # The plan: the model's own glTF camera, 1024 x 1024, a white background, no tone mapping
  # (linear, clipped), the Sample Viewer's gamma 2.2 output encoding (below).
  "$mipgloss" render --mesh "$gltf" --camera "$camera" --env "$env" --env-rotation "$rotation" \
    --background 1,1,1 --tonemap linear --size 1024x1024 --quiet --out "$out/srgb-$view.png"
  # mipgloss writes sRGB; the references are the glTF Sample Viewer 1.0.7's pow(c, 1/2.2) of the
  # same linear colour. Decoded and encoded again in float, then 8 bits.
  oiiotool "$out/srgb-$view.png" --colorconvert sRGB linear --powc 0.45454545 -d uint8 -o "$out/c-$view.png"
  rm -f "$out/srgb-$view.png"
done

# The suite's own scoring, unmodified; the stand-in sewar module only satisfies its import.
report=$(cd "$suite/evaluation" && PYTHONPATH="$repo/scripts/certify${PYTHONPATH:+:$PYTHONPATH}" \
  "$python" -W ignore evaluation.py --rep "$suite" "$out")
# evaluation.py prints per view: its name, "ssim VALUE [Passed|Failed]", "psnr VALUE [...]". Its
# thresholds are evaluate_passed's (SSIM > 0.70, PSNR > 20, as thresholds.csv).
printf '%s\n' "$report" | "$python" -c '
import re, sys
lines = [l.strip() for l in sys.stdin if l.strip()]
passed = failed = 0
i = 0
while i < len(lines):
    name = lines[i]
    m = {}
    j = i + 1
    while j < len(lines) and re.match(r"^(ssim|psnr)\s", lines[j]):
        key, value, verdict = re.match(r"^(\w+)\s+(\S+)\s*\[?(\w*)\]?", lines[j]).groups()
        m[key] = (float(value), verdict)
        j += 1
    i = j
    if not m:
        continue
    ssim, psnr = m["ssim"][0], m["psnr"][0]
    ok = m["ssim"][1] == "Passed" and m["psnr"][1] == "Passed"
    verdict = "pass" if ok else "FAIL"
    passed += ok
    failed += not ok
    print(f"{name:<22} SSIM {ssim:.4f} (> 0.70, margin {ssim - 0.70:+.4f})  "
          f"PSNR {psnr:6.2f} dB (> 20, margin {psnr - 20:+6.2f})  {verdict}")
print(f"{passed} passed, {failed} failed", file=open("/dev/fd/3", "w"))
' 3>"$out/summary.txt"
for s in "${skipped[@]}"; do echo "not run: $s"; done
summary=$(cat "$out/summary.txt")
echo "$summary"
case "$summary" in
  "0 passed, 0 failed") echo "certify-3dc: no view was scored" >&2; exit 1 ;;
  *", 0 failed") exit 0 ;;
  *) exit 1 ;;
esac
