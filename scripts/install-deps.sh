#!/usr/bin/env bash
# Installs what a fresh Debian 12 machine lacks to build and test mipgloss (apt, only the missing).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev openimageio-tools libglm-dev libopenmesh-dev libtbb-dev libtinygltf-dev
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev qt6-svg-dev libgl-dev
  libgtest-dev libbenchmark-dev xvfb xauth libgl1-mesa-dri qt6-qpa-plugins
  python3-skimage python3-reportlab  # the 3D Commerce suite's evaluation.py (scripts/certify-3dc.sh)
)
exec "$(dirname "$0")/apt-install-missing.sh" install-deps "${packages[@]}"
