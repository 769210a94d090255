#!/usr/bin/env bash
# Installs clang with its sanitizer and libFuzzer runtimes (libclang-rt-14-dev is only a
# recommendation of clang on Debian 12) and llvm-symbolizer (package llvm, not even recommended)
# when missing: the asan, fuzz and tsan presets need them, and the sanitizers' suppressions need
# symbolized stacks (scripts/sanitizer-env.sh).
set -euo pipefail
missing=()
for p in clang libclang-rt-14-dev llvm; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-clang: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
