#!/usr/bin/env bash
# Installs clang with its sanitizer and libFuzzer runtimes (libclang-rt-14-dev is only a
# recommendation of clang on Debian 12) and llvm-symbolizer (package llvm, not even recommended)
# when missing: the asan, fuzz and tsan presets need them, and the sanitizers' suppressions need
# symbolized stacks (scripts/sanitizer-env.sh).
set -euo pipefail
exec "$(dirname "$0")/apt-install-missing.sh" install-clang clang libclang-rt-14-dev llvm
