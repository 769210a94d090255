#!/usr/bin/env bash
# Runs each libFuzzer target (tests/fuzz) for a fixed time: scripts/run-fuzz.sh [seconds] [target...]
# (default 25 s each, all targets). CI runs it briefly from scripts/run-tests.sh; for a long run,
# e.g. an hour each:  scripts/run-fuzz.sh 3600   (README "Hardening").
#
# Builds the fuzz preset first (the asan build, build/asan). The committed seeds
# (tests/fuzz/corpus/<target>) are only read; what libFuzzer learns goes to
# build/asan/fuzz/corpus/<target> and is kept between runs, so longer runs start where the last
# stopped. A crash, hang (an input over 10 s), leak or broken contract stops that target and
# leaves the input in build/asan/fuzz/artifacts/<target>/; the script then exits 1 after trying
# the other targets. Make a found input a regression test by copying it (once fixed) to
# tests/fuzz/regressions/<target>/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-25}
shift || true
all=(environment_import mesh_import gltf_import mtl_import scene_file library_file)
targets=("${@:-${all[@]}}")

scripts/install-clang.sh
source scripts/sanitizer-env.sh
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j"$(nproc)"

root=$PWD
sup=$root/tests/sanitizers
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$sup/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$sup/ubsan.supp"

declare -A max_len=([environment_import]=65536 [mesh_import]=16384 [gltf_import]=16384 [mtl_import]=8192
                     [scene_file]=8192 [library_file]=8192)
declare -A dict=([mesh_import]=mesh.dict [gltf_import]=gltf.dict [mtl_import]=mtl.dict [scene_file]=json.dict
                  [library_file]=json.dict)
failed=()
for t in "${targets[@]}"; do
  exe=build/asan/tests/fuzz/fuzz_$t
  [ -x "$exe" ] || { echo "run-fuzz: no target $t ($exe)" >&2; exit 2; }
  work=build/asan/fuzz/corpus/$t
  artifacts=build/asan/fuzz/artifacts/$t/
  mkdir -p "$work" "$artifacts"
  args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 -max_len="${max_len[$t]}"
        -artifact_prefix="$artifacts" -print_final_stats=1)
  [ -n "${dict[$t]:-}" ] && args+=(-dict="tests/fuzz/dict/${dict[$t]}")
  echo "run-fuzz: $t for ${seconds}s"
  if ! "$exe" "${args[@]}" "$work" "tests/fuzz/corpus/$t" > "build/asan/fuzz/$t.log" 2>&1; then
    failed+=("$t")
    echo "run-fuzz: $t FAILED; input in $artifacts, log build/asan/fuzz/$t.log:" >&2
    grep -E "ERROR|contract broken|SUMMARY|Test unit written" "build/asan/fuzz/$t.log" | head -20 >&2
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build/asan/fuzz/$t.log" | tr '\n' ' '
    echo "corpus $(ls "$work" | wc -l) files"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "run-fuzz: failed: ${failed[*]}" >&2
  exit 1
fi
