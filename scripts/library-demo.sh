#!/usr/bin/env bash
# The material library from the command line, on a fresh library in a temporary folder (issue 9's
# "Must show"): add five materials from mirror to diffuse, list them, render a held-out mesh (the
# Stanford bunny of tests/assets, not the default teapot) with each, write thumbnails, rename and
# remove one, refuse a corrupt library and leave it byte for byte as it was, and kill
# `mipgloss library add` with SIGKILL at random moments 50 times. Prints each check; exits
# non-zero on the first failure. Needs oiiotool (openimageio-tools) for the picture checks and an
# X display for rendering (without one it re-runs itself under xvfb-run).
#
# usage: scripts/library-demo.sh [BUILD_DIR]   (default build/dev; the build must have the UI)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-$root/build/dev}" && pwd)"
mipgloss="$build/app/mipgloss"
bunny="$root/tests/assets/meshes/bunny_npm_lowres.obj"
[[ -x "$mipgloss" ]] || { echo "library-demo: no $mipgloss; build first (cmake --build $build)" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "library-demo: needs oiiotool (apt install openimageio-tools)" >&2; exit 2; }
if [[ -z "${DISPLAY:-}" && -z "${LIBRARY_DEMO_UNDER_XVFB:-}" ]]; then
  export LIBRARY_DEMO_UNDER_XVFB=1 QT_QPA_PLATFORM=xcb
  exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$0" "$build"
fi
export QT_QPA_PLATFORM="${QT_QPA_PLATFORM:-xcb}"

work="$(mktemp -d "${TMPDIR:-/tmp}/mipgloss-library-demo.XXXXXX")"
trap 'rm -rf "$work"' EXIT
lib="$work/library.json"
checks=0
ok() { checks=$((checks + 1)); echo "ok    $*"; }
fail() { echo "FAIL  $*" >&2; exit 1; }
# Runs mipgloss quietly, keeping stdout and stderr for the checks; sets $rc.
run() { set +e; "$mipgloss" "$@" >"$work/out" 2>"$work/err"; rc=$?; set -e; }
# The mean |step| between horizontally neighbouring pixels, over the whole picture and the three
# channels, in grey levels of 255 (the background is flat, so it adds nothing but the silhouette).
neighbour_step() {
  oiiotool "$1" --dup --cshift +1+0 --sub --abs --printstats |
    awk '/Stats Avg/ { printf "%.2f", ($3 + $4 + $5) / 3 * 255 }'
}
# The luminance standard deviation of a picture, in grey levels.
deviation() {
  oiiotool "$1" --printstats | awk '/Stats StdDev/ { printf "%.2f", ($3 + $4 + $5) / 3 }'
}

echo "library-demo: $mipgloss, working in $work"
echo
echo "== a fresh library: five materials from mirror to diffuse"
names=(mirror glossy satin matte diffuse)
flags=("--lambda 0" "--lambda 2 --tint 1,0.78,0.34" "--lambda 4 --grazing" "--lambda 6"
       "--lambda 7 --mode normal --irradiance")
for i in "${!names[@]}"; do
  # shellcheck disable=SC2086  # the flags are words
  run library add "$lib" --name "${names[$i]}" ${flags[$i]}
  [[ $rc -eq 0 ]] || fail "library add ${names[$i]}: exit $rc: $(cat "$work/err")"
  ok "library add ${names[$i]} ${flags[$i]}: $(cat "$work/out")"
done

echo
echo "== list"
run library list "$lib"
[[ $rc -eq 0 ]] || fail "library list: exit $rc"
sed 's/^/      /' "$work/out"
[[ "$(cut -f1 "$work/out" | paste -sd,)" == "mirror,glossy,satin,matte,diffuse" ]] ||
  fail "library list does not show the five in order"
ok "library list: five lines, in the order added"
run library list "$lib" --json
[[ $rc -eq 0 && "$(grep -c '"name"' "$work/out")" -eq 5 ]] || fail "library list --json"
cmp -s "$work/out" "$lib" || fail "library list --json differs from the file the library wrote"
ok "library list --json: the library's JSON, byte for byte the file as saved"

echo
echo "== render the bunny (a held-out mesh) with each material"
step=()
for name in "${names[@]}"; do
  run render --mesh "$bunny" --library "$lib" --material "$name" --no-background --size 400x300 \
      --out "$work/bunny-$name.png" --quiet
  [[ $rc -eq 0 ]] || fail "render --material $name: exit $rc: $(cat "$work/err")"
  step+=("$(neighbour_step "$work/bunny-$name.png")")
  ok "render --library --material $name: bunny-$name.png, mean neighbour step ${step[-1]} grey levels"
done
for i in "${!names[@]}"; do
  for j in "${!names[@]}"; do
    if (( i < j )) && cmp -s "$work/bunny-${names[$i]}.png" "$work/bunny-${names[$j]}.png"; then
      fail "the ${names[$i]} and ${names[$j]} pictures are identical"
    fi
  done
done
ok "the five pictures all differ"
# Sharper: the mirror shows the environment's own detail, twice as fast as the normal turns; the
# diffuse lobe (λ 7 by the normal, n = 2) is a low-pass filter of it (docs/library.md).
awk -v m="${step[0]}" -v d="${step[4]}" 'BEGIN { exit !(m > 2 * d) }' ||
  fail "the mirror's picture (${step[0]}) is not sharper than the diffuse one's (${step[4]})"
ok "mirror sharper than diffuse: neighbour step ${step[0]} against ${step[4]} (more than twice)"

echo
echo "== thumbnails"
run library thumbnails "$lib" --size 128 --out "$work/thumbs"
[[ $rc -eq 0 ]] || fail "library thumbnails: exit $rc: $(cat "$work/err")"
[[ "$(ls "$work/thumbs" | paste -sd,)" == "diffuse.png,glossy.png,matte.png,mirror.png,satin.png" ]] ||
  fail "thumbnails: $(ls "$work/thumbs" | paste -sd' ')"
for name in "${names[@]}"; do
  dev="$(deviation "$work/thumbs/$name.png")"
  awk -v d="$dev" 'BEGIN { exit !(d > 5) }' || fail "thumbnail $name.png is flat (deviation $dev)"
  ok "thumbs/$name.png: 128x128, not flat (deviation $dev grey levels)"
done
cmp -s "$work/thumbs/mirror.png" "$work/thumbs/diffuse.png" && fail "mirror and diffuse thumbnails are identical"
ok "the mirror's thumbnail differs from the diffuse one's"

echo
echo "== rename and remove"
run library rename "$lib" satin "brushed steel"
[[ $rc -eq 0 ]] || fail "rename: exit $rc: $(cat "$work/err")"
ok "library rename satin \"brushed steel\": $(cat "$work/out")"
run library remove "$lib" matte
[[ $rc -eq 0 ]] || fail "remove: exit $rc: $(cat "$work/err")"
ok "library remove matte: $(cat "$work/out")"
run library list "$lib"
[[ "$(cut -f1 "$work/out" | paste -sd,)" == "mirror,glossy,brushed steel,diffuse" ]] ||
  fail "after rename and remove: $(cut -f1 "$work/out" | paste -sd,)"
ok "library list: mirror, glossy, brushed steel, diffuse"

echo
echo "== a corrupt library is refused by every command and left as it is"
corrupt="$work/corrupt.json"
head -c 300 "$lib" >"$corrupt"  # a library cut off mid-write, as a non-atomic save killed would leave it
cp "$corrupt" "$work/corrupt.orig"
# Runs `mipgloss "$@"`, which must exit 1 naming the corrupt file and leave it as it was.
refused() {
  run "$@"
  [[ $rc -eq 1 ]] || fail "mipgloss $*: exit $rc, not 1"
  grep -qF "$corrupt: " "$work/err" || fail "mipgloss $* does not name the file: $(cat "$work/err")"
  cmp -s "$corrupt" "$work/corrupt.orig" || fail "mipgloss $* changed the corrupt file"
  ok "mipgloss ${*//$work\//}: exit 1, $(sed "s|$work/||g" "$work/err")"
}
refused library list "$corrupt"
refused library list "$corrupt" --json
refused library add "$corrupt" --name new
refused library remove "$corrupt" mirror
refused library rename "$corrupt" mirror chrome
refused library thumbnails "$corrupt" --out "$work/none"
refused render --library "$corrupt" --material mirror --out "$work/none.png"
[[ ! -e "$work/none" && ! -e "$work/none.png" ]] || fail "something was written from the corrupt library"
ok "corrupt.json byte for byte as it was (cmp), nothing written from it"

echo
echo "== library add killed with SIGKILL at random moments, 50 times"
killlib="$work/kill.json"
# A run's length: the median of three `library list`, which start, read and exit as an add does.
times=()
for _ in 1 2 3; do
  start=$(date +%s%N); run library list "$lib"; end=$(date +%s%N)
  times+=($(( (end - start) / 1000000 )))
done
run_ms=$(printf '%s\n' "${times[@]}" | sort -n | sed -n 2p)
# Most of a run is the program starting; the library is read and written in its last
# milliseconds. So the kills fall at random between 0.7 and 1.1 times a run's length, where the
# reading, the writing and the exit are (the same choice as TEST(LibraryKill, ...)).
lo_ms=$(( run_ms * 7 / 10 )); hi_ms=$(( run_ms * 11 / 10 ))
echo "      one run takes about $run_ms ms here; each kill comes $lo_ms to $hi_ms ms after the start"
finished=()
killed_before=0; killed_after=0
RANDOM=9
for i in $(seq 1 50); do
  name="k$i"
  "$mipgloss" library add "$killlib" --name "$name" --lambda $((i % 8)) >/dev/null 2>&1 &
  pid=$!
  sleep "$(awk -v ms=$(( lo_ms + RANDOM % (hi_ms - lo_ms + 1) )) 'BEGIN { printf "%.3f", ms / 1000 }')"
  kill -KILL "$pid" 2>/dev/null || true
  set +e; wait "$pid" 2>/dev/null; status=$?; set -e
  [[ $status -eq 0 ]] && finished+=("$name")
  [[ $status -eq 0 || $status -eq 137 ]] || fail "add $name ended with status $status"
  if [[ -e "$killlib" ]]; then
    run library list "$killlib"
    [[ $rc -eq 0 ]] || fail "after add $name (status $status) the library does not read: $(cat "$work/err")"
  else
    : >"$work/out"
  fi
  listed="$(cut -f1 "$work/out")"
  for f in "${finished[@]}"; do
    grep -qx "$f" <<<"$listed" || fail "after add $name: $f finished but is missing"
  done
  # No partial entry: every line a whole entry of a name tried so far, with the λ it was added with.
  while IFS=$'\t' read -r n lambda _; do
    [[ "$n" =~ ^k([0-9]+)$ ]] && (( BASH_REMATCH[1] <= i )) || fail "after add $name: unexpected entry '$n'"
    [[ "$lambda" == "lambda $(( BASH_REMATCH[1] % 8 ))" ]] || fail "after add $name: $n has '$lambda'"
  done <"$work/out"
  if [[ $status -eq 137 ]]; then
    grep -qx "$name" <<<"$listed" && killed_after=$((killed_after + 1)) || killed_before=$((killed_before + 1))
  fi
done
strays="$(find "$work" -maxdepth 1 -name 'kill.json.*' | wc -l)"
ok "50 runs: ${#finished[@]} finished, $killed_before killed before their save landed, $killed_after after;" \
   "every finished add listed, no partial entry, the file read every time; $strays QSaveFile temporaries left"

echo
echo "library-demo: all $checks checks passed"
