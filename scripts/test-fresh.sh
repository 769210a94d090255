#!/usr/bin/env bash
# README's two commands on bare Debian 12 machines, as a new user runs them (issue 22). Not part of
# CI (it downloads a Debian root and builds everything twice: 20 to 40 minutes on two cores); in
# scripts/nightly.sh, and run by hand before landing anything that changes an install step, a
# preset or a dependency. Needs root (debootstrap, chroot, mounts).
#
#   scripts/test-fresh.sh [SOURCE [BRANCH]]   clone BRANCH (default main) of SOURCE (default this
#                                             repository: its committed history, not the work tree)
#
# Each command runs in its own fresh root, made by `debootstrap --variant=minbase bookworm` from the
# mirror apt uses here, with git, ca-certificates and sudo added and nothing else, on a clean clone:
#   1. scripts/run-default.sh (no display, no window): exit status 0, and build/default-scene.png
#      and the bake written;
#   2. CI=true bash .ci/run: exit status 0 (every phase: dev, asan, fuzz).
# Then, against this machine: the packages installed here that the roots do not have (what a step
# could be passing with only here), and every tool the two commands' scripts call, found in the
# roots. Prints one PASS/FAIL line per check with each command's exit status and time; logs in
# build/fresh/. Exits 1 when any check fails.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
[ "$(id -u)" -eq 0 ] || { echo "test-fresh: needs root (debootstrap, chroot)" >&2; exit 2; }
case "${1:-}" in -h|--help) sed -n '2,19p' "$0"; exit 0 ;; esac
source_repo=${1:-$repo}
branch=${2:-main}

work=$repo/build/fresh
roots=$work/roots
mkdir -p "$work" "$roots"
failures=0
holds() { "$@" >/dev/null 2>&1 && echo 0 || echo 1; }  # 0 when the command succeeds, else 1
verdict() {  # verdict NAME STATUS [DETAIL]
  if [ "$2" -eq 0 ]; then echo "PASS  $1${3:+  ($3)}"; else echo "FAIL  $1${3:+  ($3)}"; failures=$((failures + 1)); fi
}

scripts/apt-install-missing.sh test-fresh debootstrap git
source scripts/bare-root.sh

# A bare root NAME with a clean clone at /root/mipgloss; sets `head` to the clone's head. (Not
# in a $(...) subshell: fresh_root's mounts must be recorded in this shell to be undone.)
root_with_clone() {
  fresh_root "$1"
  in_root "$roots/$1" "apt-get install -y -qq --no-install-recommends git ca-certificates sudo" >"$work/$1-base.log" 2>&1
  git clone --quiet --branch "$branch" "$source_repo" "$roots/$1/root/mipgloss"
  head=$(git -C "$roots/$1/root/mipgloss" log -1 --format='%h %s' | cut -c1-72)
}

# Runs COMMAND in the clone of root NAME, its output to build/fresh/NAME.log; sets `status` and `took`.
# The root's X servers (xvfb-run -a, from :99 up) share this machine's abstract socket namespace,
# where an X server of the host on the same number takes their clients: twice a test in the root
# failed with "could not connect to display :99" while a host xvfb-run ran. Lock files for :99 to
# :149 in the root's /tmp make its xvfb-run start at :150.
run_in() {
  local start=$SECONDS n
  for n in $(seq 99 149); do : >"$roots/$1/tmp/.X$n-lock"; done
  status=0
  in_root "$roots/$1" "cd /root/mipgloss && $2" >"$work/$1.log" 2>&1 || status=$?
  took=$((SECONDS - start))
}

root_with_clone default
echo "test-fresh: 1. scripts/run-default.sh in a bare root, clone of $head"
run_in default "MIPGLOSS_NO_WINDOW=1 scripts/run-default.sh"
verdict "scripts/run-default.sh exits 0" "$status" "exit status $status, ${took} s, log build/fresh/default.log"
[ "$status" -eq 0 ] || tail -30 "$work/default.log" | sed 's/^/      /'
picture=$roots/default/root/mipgloss/build/default-scene.png
verdict "  it wrote build/default-scene.png" "$(holds test -s "$picture")" "$(du -h "$picture" 2>/dev/null | cut -f1)"
verdict "  it wrote the bake (build/default-bake/manifest.json)" \
  "$(holds test -s "$roots/default/root/mipgloss/build/default-bake/manifest.json")"
cp "$picture" "$work/" 2>/dev/null || true

root_with_clone tests
echo "test-fresh: 2. CI=true bash .ci/run in another bare root, clone of $head"
run_in tests "CI=true bash .ci/run"
verdict "CI=true bash .ci/run exits 0" "$status" "exit status $status, ${took} s, log build/fresh/tests.log"
[ "$status" -eq 0 ] || grep -E "FAILED|Failed|failed|ERROR|error:" "$work/tests.log" | tail -30 | sed 's/^/      /'
grep -E "^run-tests: .* phase took|tests passed" "$work/tests.log" | sed 's/^/      /' || true

# 3. What this machine has and the roots lack, and the tools the two commands' scripts call.
dpkg-query -W -f='${db:Status-Abbrev} ${Package}\n' | awk '$1 == "ii" {print $2}' | sort >"$work/host-packages.txt"
for r in default tests; do
  in_root "$roots/$r" "dpkg-query -W -f='\${db:Status-Abbrev} \${Package}\n'" | awk '$1 == "ii" {print $2}' | sort >"$work/$r-packages.txt"
done
comm -23 "$work/host-packages.txt" "$work/tests-packages.txt" >"$work/host-only-packages.txt"
echo "      $(wc -l <"$work/host-only-packages.txt") packages installed here and not in the tests root after .ci/run" \
     "(build/fresh/host-only-packages.txt); the root has $(wc -l <"$work/tests-packages.txt")"
tools="apt-get dpkg-query sudo git cmake ctest ninja c++ nproc xvfb-run xauth Xvfb clang clang++ llvm-symbolizer"
missing_tools=$(in_root "$roots/tests" "for t in $tools; do command -v \$t >/dev/null || echo \$t; done")
verdict "every tool the scripts call is in the tests root ($tools)" "$(holds test -z "$missing_tools")" \
  "${missing_tools:+missing: $missing_tools}"

if [ "$failures" -eq 0 ]; then echo "test-fresh: all checks passed"; else echo "test-fresh: $failures check(s) failed"; fi
[ "$failures" -eq 0 ]
