#!/usr/bin/env bash
# The main job on the embedded default scene: install, build (release), bake the default
# environment with the default builder and print where the result went.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)"
out="${1:-$PWD/build/default-bake}"
build/release/app/mipgloss bake --irradiance --out "$out"
