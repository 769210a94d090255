#!/usr/bin/env bash
# Install, build (dev preset: tests, strict warnings) and run every test; then the hardening phases
# (README "Hardening"): the suite again under AddressSanitizer + UBSan (asan preset, the scope
# scripts/run-sanitizers.sh gives and why), and each libFuzzer target for a short fixed time from
# that same build. The whole suite under ASan, ThreadSanitizer and long fuzzing are in
# scripts/nightly.sh. MIPGLOSS_HARDENING=0 skips the hardening phases (a quick local run);
# arguments go to the dev phase's ctest. Each phase prints its time.
set -euo pipefail
cd "$(dirname "$0")/.."
phase_start=$SECONDS
phase_done() { echo "run-tests: $1 phase took $((SECONDS - phase_start)) s"; phase_start=$SECONDS; }

scripts/install-deps.sh
cmake --preset dev >/dev/null
cmake --build --preset dev -j"$(nproc)"
export QT_QPA_PLATFORM=xcb
# -noreset: by default Xvfb resets when its last client leaves, and a client that connects during
# the reset is dropped ("could not connect to display :99"; xorg/xserver#1102). With ctest -j2
# there are moments with no window open; CI failed once on exactly that. Every xvfb-run here says it.
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --preset dev -j"$(nproc)" "$@"
phase_done dev
[ "${MIPGLOSS_HARDENING:-1}" = 1 ] || exit 0

scripts/run-sanitizers.sh asan
phase_done asan
scripts/run-fuzz.sh "${MIPGLOSS_FUZZ_SECONDS:-20}"
phase_done fuzz
