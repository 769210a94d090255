#!/usr/bin/env bash
# Install, build (dev preset: tests, strict warnings) and run every test. GL tests need an X
# display, so the whole run goes under one Xvfb server.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset dev >/dev/null
cmake --build --preset dev -j"$(nproc)"
export QT_QPA_PLATFORM=xcb
xvfb-run -a -s "-screen 0 1280x1024x24" ctest --preset dev -j"$(nproc)" "$@"
