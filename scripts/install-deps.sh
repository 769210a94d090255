#!/usr/bin/env bash
# Installs what a fresh Debian 12 machine lacks to build and test mipgloss (apt, only the missing).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev openimageio-tools libglm-dev libopenmesh-dev libtbb-dev
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev qt6-svg-dev libgl-dev
  libgtest-dev libbenchmark-dev xvfb xauth libgl1-mesa-dri qt6-qpa-plugins
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: everything is installed"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
