#!/usr/bin/env bash
# Big environments, measured in one run (issue "Big environments, fast"): an 8192×4096 half-float,
# zip-compressed lat-long made from the held-out tests/assets/env/sunset.exr, then
#   - OpenImageIO's own decode time of it (the yardstick, `mipgloss bench import`'s oiio column),
#   - the previewer's first frame with the default scene and with the 8k map, and its peak memory,
#   - `mipgloss bake --size 512` of it, wall time,
# and the bounds: first frame <= default's + 1.5 × decode, bake <= 2 × decode, peak <= 800 MiB.
# Then the conversion's accuracy tests (LatLongConversion.*, the decode tests).
# Usage: scripts/big-environment-demo.sh [BUILD_DIR]   (default build/dev; needs Xvfb)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/dev}
cli=$build/app/mipgloss
gui=$build/app/mipgloss-gui
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export QT_QPA_PLATFORM=xcb HOME=$work/home XDG_RUNTIME_DIR=$work/run
mkdir -p "$HOME" "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
fails=0
check() {  # check NAME VALUE OP BOUND
    if awk -v v="$2" -v b="$4" "BEGIN { exit !(v $3 b) }"; then
        echo "PASS  $1: $2 $3 $4"
    else
        echo "FAIL  $1: $2 not $3 $4"
        fails=$((fails + 1))
    fi
}

echo "== making the 8192x4096 half-float zip input from tests/assets/env/sunset.exr"
"$cli" bench import --env tests/assets/env/sunset.exr --widths 8192 --faces 512 --dir "$work" --keep \
    | tee "$work/bench.txt"
input=$work/latlong_8192.exr
row=$(grep '^8192x4096' "$work/bench.txt" | head -1)
oiio=$(awk '{print $4}' <<<"$row")

echo "== the previewer, first frame (default scene, then the 8k map)"
run_gui() { xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$gui" --time-to-first-frame "$@" 2>/dev/null; }
default_line=$(run_gui)
echo "default scene: $default_line"
big_line=$(run_gui "$input")
echo "8k map:        $big_line"
default_ms=$(sed -n 's/^first frame: \([0-9]*\) ms.*/\1/p' <<<"$default_line")
big_ms=$(sed -n 's/^first frame: \([0-9]*\) ms.*/\1/p' <<<"$big_line")
peak=$(sed -n 's/.*peak memory \([0-9]*\) MiB.*/\1/p' <<<"$big_line")

echo "== mipgloss bake --size 512"
start=$(date +%s.%N)
"$cli" bake "$input" --size 512 --out "$work/bake" --quiet
bake_s=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
echo "bake wall: $bake_s s"

echo "== bounds (decode = OpenImageIO's own read, $oiio s)"
check "first frame with the 8k map (ms)" "$big_ms" "<=" "$(awk -v d="$default_ms" -v o="$oiio" 'BEGIN { printf "%.0f", d + 1500 * o }')"
check "bake --size 512 (s)" "$bake_s" "<=" "$(awk -v o="$oiio" 'BEGIN { printf "%.2f", 2 * o }')"
check "previewer peak memory with the 8k map (MiB)" "$peak" "<=" 800

echo "== accuracy of the conversion and the decode (tests)"
if "$build/tests/mipgloss_io_tests" --gtest_filter='LatLongConversion.*:LatLongImport.*:Decode*' --gtest_brief=1; then
    echo "PASS  conversion and decode tests"
else
    echo "FAIL  conversion and decode tests"
    fails=$((fails + 1))
fi
[ "$fails" -eq 0 ] && echo "all checks passed" || { echo "$fails check(s) failed"; exit 1; }
