#!/usr/bin/env bash
# The main job on the embedded default scene (the paper's Figure 1): install what is missing,
# build (release), then
#   - render the default scene offscreen to build/default-scene.png (mipgloss render; under
#     xvfb-run when there is no display),
#   - bake the default environment's chain to build/default-bake (mipgloss bake),
#   - and, on a desktop (DISPLAY set), open the previewer on it (mipgloss-gui).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)"
bin=build/release/app
if [[ -n "${DISPLAY:-}" ]]; then
  QT_QPA_PLATFORM=xcb "$bin/mipgloss" render --out build/default-scene.png
else
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" env QT_QPA_PLATFORM=xcb \
    "$bin/mipgloss" render --out build/default-scene.png
fi
echo "default scene rendered to build/default-scene.png"
"$bin/mipgloss" bake --irradiance --quiet --out build/default-bake
echo "default environment baked to build/default-bake"
if [[ -n "${DISPLAY:-}" && -z "${MIPGLOSS_NO_WINDOW:-}" ]]; then
  exec "$bin/mipgloss-gui"
fi
