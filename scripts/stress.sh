#!/usr/bin/env bash
# The stress cases of issue 11 under one Xvfb (scripts/stress.py says what each is).
# Usage: scripts/stress.sh [BUILD_DIR]   (default build/dev; takes several minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
export QT_QPA_PLATFORM=xcb
exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" python3 scripts/stress.py "${1:-build/dev}"
