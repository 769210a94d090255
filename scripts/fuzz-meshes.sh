#!/usr/bin/env bash
# Issue 11's mutation fuzzer, run from outside: damaged OBJ, OFF, PLY (ASCII and binary), STL,
# scene and library files through `mipgloss render` and `mipgloss library list`; exits non-zero on
# any crash, hang or refusal that does not name the file. The work is in scripts/fuzz-meshes.py
# (its --help lists the options); this runs it under xvfb-run when there is no X display.
#
# usage: scripts/fuzz-meshes.sh [--build DIR] [--cases N] [--jobs J] [--timeout S] [--seed K] ...
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [[ -z "${DISPLAY:-}" ]]; then
  command -v xvfb-run >/dev/null || { echo "fuzz-meshes: no X display and no xvfb-run (apt install xvfb)" >&2; exit 2; }
  export QT_QPA_PLATFORM=xcb
  exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" python3 "$here/fuzz-meshes.py" "$@"
fi
export QT_QPA_PLATFORM="${QT_QPA_PLATFORM:-xcb}"
exec python3 "$here/fuzz-meshes.py" "$@"
