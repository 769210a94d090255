#!/usr/bin/env bash
# Builds the Debian package build/package/mipgloss_<version>_<arch>.deb (and its -dbgsym package)
# with debhelper from packaging/debian (docs/packaging.md): installs the Build-Depends with apt when
# any is missing, builds a release with Debian's hardening flags and writes the package.
#
#   scripts/package.sh [--incremental]
#
# --incremental keeps the previous build folder (build/package/mipgloss-<version>/obj-*) instead of
# starting clean: for trying packaging changes, not for a package to ship.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$(pwd)
out=$src/build/package
incremental=0
for arg in "$@"; do
  case $arg in
    --incremental) incremental=1 ;;
    *) echo "usage: scripts/package.sh [--incremental]" >&2; exit 2 ;;
  esac
done

# One version: the package's (packaging/debian/changelog) must be the project's (CMakeLists.txt).
project_version=$(sed -n 's/^project(mipgloss VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
deb_version=$(sed -n '1s/^mipgloss (\([^)]*\)).*/\1/p' packaging/debian/changelog)
if [[ "${deb_version%-*}" != "$project_version" ]]; then
  echo "package: packaging/debian/changelog says $deb_version, CMakeLists.txt says $project_version;" \
       "add a changelog entry (dch -v $project_version-1)" >&2
  exit 1
fi

# The source package directory: a copy of the sources (not build/ or .git) with packaging/debian as
# debian/, so nothing the build writes (debian/mipgloss, debian/.debhelper, obj-*) lands in the
# source tree. --incremental keeps the obj-* build folder (tar keeps the files' times, so only what
# changed is rebuilt).
stage=$out/mipgloss-$project_version
mkdir -p "$stage"
find "$stage" -mindepth 1 -maxdepth 1 ! -name 'obj-*' -exec rm -rf {} +
[[ $incremental -eq 1 ]] || rm -rf "$stage"/obj-*
tar -C "$src" --exclude=./build --exclude=./.git --exclude=./debian -cf - . | tar -C "$stage" -xf -
cp -a packaging/debian "$stage/debian"

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if ! command -v dpkg-checkbuilddeps >/dev/null || ! (cd "$stage" && dpkg-checkbuilddeps 2>/dev/null); then
  echo "package: installing the build dependencies (apt-get build-dep)"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends dpkg-dev
  DEBIAN_FRONTEND=noninteractive $sudo apt-get build-dep -y -qq --no-install-recommends "$stage"
fi

arch=$(dpkg --print-architecture)
deb=$out/mipgloss_${deb_version}_${arch}.deb
rm -f "$deb" "$out/mipgloss-dbgsym_${deb_version}_${arch}.deb"
flags=(-b -us -uc)
[[ $incremental -eq 1 ]] && flags+=(--no-pre-clean)
(cd "$stage" && dpkg-buildpackage "${flags[@]}" -j"$(nproc)")
test -f "$deb"
echo "package: $deb ($(du -h "$deb" | cut -f1))"
