#!/usr/bin/env bash
# What does not fit CI's 30 minutes (README "Hardening"): the whole suite under AddressSanitizer +
# UBSan (CI runs a measured part of it, scripts/run-sanitizers.sh), the ThreadSanitizer run of the
# tests of the background workers (its own build, build/tsan), and a longer fuzzing run of every
# target (default 10 minutes each; scripts/nightly.sh SECONDS to change), and README's two commands
# on bare Debian 12 roots (scripts/test-fresh.sh, as root). Each phase builds what it needs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/run-sanitizers.sh asan-full
scripts/run-sanitizers.sh tsan
scripts/run-fuzz.sh "${1:-600}"
if [ "$(id -u)" -eq 0 ]; then scripts/test-fresh.sh; else sudo scripts/test-fresh.sh; fi
