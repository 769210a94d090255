#!/usr/bin/env bash
# The package on bare Debian 12 (docs/packaging.md). Not part of CI: it downloads a Debian root and
# builds everything in it (tens of minutes). Needs root (debootstrap, chroot, mounts).
#
#   scripts/test-package.sh [SOURCE]      build the package from a fresh `git clone SOURCE` (default:
#                                         this repository, i.e. its committed HEAD) by running
#                                         scripts/package.sh in one bare root, then test it in another
#   scripts/test-package.sh --deb FILE    skip the build; test FILE
#
# Two throwaway roots made by `debootstrap --variant=minbase bookworm` from the mirror apt uses here
# (a pristine copy is kept in build/package/roots/pristine for reruns). In the install root, with
# no recommendations and nothing else installed:
#   apt install ./mipgloss_*.deb; every library of both programs and of Qt's xcb plugin resolves;
#   mipgloss --version, mipgloss-gui --version and --help with no display; a bake of the embedded
#   default; mipgloss render and mipgloss-gui --screenshot on an X server run outside the root (so
#   no X server package can bring a library the package forgot); the pictures are not flat;
# then, with xvfb, xauth, desktop-file-utils, appstream and shared-mime-info added:
#   xvfb-run -a mipgloss render and mipgloss-gui --screenshot; desktop-file-validate; appstreamcli
#   validate --no-net; the manual pages and the MIME XML installed and read by the MIME database;
#   apt remove, then purge: no file of the package left and no new unowned file naming mipgloss.
# On the host: lintian with no errors. One PASS/FAIL line per check; exits 1 when any fails.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
[ "$(id -u)" -eq 0 ] || { echo "test-package: needs root (debootstrap, chroot)" >&2; exit 2; }

source_repo=$repo
deb=""
case "${1:-}" in
  --deb) deb=$(realpath "${2:?--deb needs a file}") ;;
  -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
  "") ;;
  *) source_repo=$1 ;;
esac

work=$repo/build/package/test
roots=$repo/build/package/roots
mkdir -p "$work" "$roots"
rm -f "$work/checks.log"
failures=0
check() {  # check NAME COMMAND...: runs the command, prints PASS or FAIL with the name
  local name=$1; shift
  echo "=== $name" >>"$work/checks.log"
  if "$@" >"$work/check.log" 2>&1; then
    echo "PASS  $name"
  else
    echo "FAIL  $name"; sed 's/^/      /' "$work/check.log" | tail -25
    failures=$((failures + 1))
  fi
  cat "$work/check.log" >>"$work/checks.log"
}

# Host tools.
scripts/apt-install-missing.sh test-package debootstrap lintian git openimageio-tools xvfb xauth

source scripts/bare-root.sh
cleanup() {
  bare_root_cleanup
  [ -z "${xvfb_pid:-}" ] || kill "$xvfb_pid" 2>/dev/null || true
}
trap cleanup EXIT

# --- 1. Build the package from a clean clone in one bare root -----------------------------------
if [ -z "$deb" ]; then
  fresh_root build
  build_root=$roots/build
  git clone --quiet "$source_repo" "$build_root/root/mipgloss"
  echo "test-package: building in a bare root from $(git -C "$build_root/root/mipgloss" log -1 --format='%h %s' | cut -c1-70)"
  start=$(date +%s)
  check "scripts/package.sh in a bare bookworm root" \
    in_root "$build_root" "cd /root/mipgloss && scripts/package.sh"
  echo "      build time: $(( $(date +%s) - start )) s (apt and compile)"
  built=$(ls "$build_root"/root/mipgloss/build/package/mipgloss_*_*.deb 2>/dev/null | head -1 || true)
  [ -n "$built" ] || { echo "FAIL  no package was written"; exit 1; }
  cp "$built" "$work/"
  deb=$work/$(basename "$built")
fi
case $(basename "$deb") in
  mipgloss_*_*.deb) echo "PASS  file name $(basename "$deb") ($(du -h "$deb" | cut -f1), installed $(dpkg-deb -f "$deb" Installed-Size) KiB)" ;;
  *) echo "FAIL  file name $(basename "$deb") is not mipgloss_<version>_<arch>.deb"; failures=$((failures + 1)) ;;
esac

# --- 2. lintian (on the host) -------------------------------------------------------------------
lintian --display-info "$deb" 2>&1 | grep -v "running with root privileges" >"$work/lintian.txt" || true
sed 's/^/      /' "$work/lintian.txt"
check "lintian: no errors" bash -c "! grep -q '^E:' '$work/lintian.txt'"

# --- 3. Install in another bare root, nothing else installed -------------------------------------
fresh_root install
root=$roots/install
find "$root/usr" | sed "s|^$root||" | sort >"$work/usr-before.txt"
cp "$deb" "$root/tmp/"
check "apt install ./$(basename "$deb") --no-install-recommends" \
  in_root "$root" "cd /tmp && apt-get install -y -qq --no-install-recommends ./$(basename "$deb")"
check "the declared dependencies are installed (qt6-qpa-plugins, a GL driver)" \
  in_root "$root" "dpkg -s qt6-qpa-plugins libgl1-mesa-dri libglx-mesa0 | grep -c 'Status: install ok' | grep -qx 3"
check "every library of the programs, the xcb plugin and the GL driver resolves" \
  in_root "$root" "! ldd /usr/bin/mipgloss /usr/bin/mipgloss-gui \
      /usr/lib/*/qt6/plugins/platforms/libqxcb.so /usr/lib/*/qt6/plugins/xcbglintegrations/*.so \
      /usr/lib/*/dri/swrast_dri.so | grep 'not found'"
check "mipgloss --version" in_root "$root" "mipgloss --version | grep -q '^mipgloss [0-9]'"
check "mipgloss-gui --version and --help without a display" \
  in_root "$root" "mipgloss-gui --version | grep -q '^mipgloss-gui [0-9]' && mipgloss-gui --help | grep -q -- --screenshot"
check "mipgloss bake (the embedded default)" \
  in_root "$root" "mipgloss bake --quiet --irradiance --out /tmp/bake && test -s /tmp/bake/manifest.json && test -s /tmp/bake/environment_mips.exr && test -s /tmp/bake/level0/px.exr"

# An X server outside the root: the root holds only the package and what it depends on.
display=:$((90 + RANDOM % 9))
Xvfb "$display" -screen 0 1280x1024x24 -noreset -nolisten tcp >"$work/xvfb.log" 2>&1 &
xvfb_pid=$!
sleep 2
mkdir -p "$root/tmp/.X11-unix"
mount --bind /tmp/.X11-unix "$root/tmp/.X11-unix"
mounted+=("$root/tmp/.X11-unix")
not_flat() {  # not_flat PNG: some colour channel's standard deviation above 2 % of full scale
  oiiotool --stats "$1" | awk '/Stats StdDev/ {
      scale = 1; if (match($0, /\(of [0-9]+\)/)) scale = substr($0, RSTART + 4, RLENGTH - 5)
      for (i = 3; i <= 5; i++) if ($i / scale > m) m = $i / scale }
    END {print "largest stddev " m " of full scale"; exit !(m > 0.02)}'
}
check "mipgloss render, package dependencies only (X server outside the root)" \
  in_root "$root" "DISPLAY=$display mipgloss render --out /tmp/render-deps-only.png"
check "  its picture is not flat" not_flat "$root/tmp/render-deps-only.png"
check "mipgloss-gui --screenshot, package dependencies only" \
  in_root "$root" "DISPLAY=$display mipgloss-gui --screenshot /tmp/gui-deps-only.png"
check "  its picture is not flat" not_flat "$root/tmp/gui-deps-only.png"
umount -l "$root/tmp/.X11-unix"; unset 'mounted[${#mounted[@]}-1]'
kill "$xvfb_pid"; unset xvfb_pid

# --- 4. As a user would run it, and the desktop files -------------------------------------------
check "test tools installed (xvfb xauth desktop-file-utils appstream shared-mime-info)" \
  in_root "$root" "apt-get install -y -qq --no-install-recommends xvfb xauth desktop-file-utils appstream shared-mime-info"
check "xvfb-run -a mipgloss render" in_root "$root" "xvfb-run -a mipgloss render --out /tmp/render.png"
check "  its picture is not flat" not_flat "$root/tmp/render.png"
check "xvfb-run -a mipgloss-gui --screenshot" in_root "$root" "xvfb-run -a mipgloss-gui --screenshot /tmp/gui.png"
check "  its picture is not flat" not_flat "$root/tmp/gui.png"
cp "$root"/tmp/render*.png "$root"/tmp/gui*.png "$work/"
check "desktop-file-validate" in_root "$root" "desktop-file-validate /usr/share/applications/mipgloss.desktop"
check "appstreamcli validate --no-net" \
  in_root "$root" "appstreamcli validate --no-net /usr/share/metainfo/org.mipgloss.mipgloss.metainfo.xml"
check "manual pages installed" \
  in_root "$root" "zcat /usr/share/man/man1/mipgloss.1.gz | grep -q '^\.TH MIPGLOSS ' && zcat /usr/share/man/man1/mipgloss-gui.1.gz | grep -q '^\.TH MIPGLOSS-GUI '"
check "MIME XML installed and in the MIME database" \
  in_root "$root" "test -s /usr/share/mime/packages/mipgloss.xml && grep -q 'mipgloss' /usr/share/mime/globs2 && test -s /usr/share/mime/application/x-mipgloss-scene.xml && test -s /usr/share/mime/application/x-mipgloss-library.xml"
check "icons installed (hicolor 16 to 256)" \
  in_root "$root" "for s in 16 22 24 32 48 64 128 256; do test -s /usr/share/icons/hicolor/\${s}x\${s}/apps/mipgloss.png || exit 1; done"

# --- 5. Removal ----------------------------------------------------------------------------------
in_root "$root" "dpkg -L mipgloss" >"$work/package-files.txt"
left() {  # the package's paths still present: any file, and folders no other package owns
  while read -r f; do
    [ "$f" != "/." ] || continue
    if [ -e "$root$f" ] && { [ ! -d "$root$f" ] || ! in_root "$root" "dpkg -S '$f'" </dev/null >/dev/null 2>&1; }; then
      echo "left: $f"
    fi
  done <"$work/package-files.txt"
}
check "apt remove mipgloss" in_root "$root" "apt-get remove -y -qq mipgloss"
left >"$work/left-after-remove.txt"
check "  no file of the package left" bash -c "cat '$work/left-after-remove.txt'; ! test -s '$work/left-after-remove.txt'"
# apt forgets a removed package that came from a file, so the purge is dpkg's (the package has no
# conffiles: nothing is left for it, which this checks).
check "purge (dpkg --purge mipgloss)" in_root "$root" "dpkg --purge mipgloss && ! dpkg -s mipgloss >/dev/null 2>&1"
left >"$work/left-after-purge.txt"
check "  no file of the package left" bash -c "cat '$work/left-after-purge.txt'; ! test -s '$work/left-after-purge.txt'"
# find /usr before and after: of the new paths, those no package owns are caches the triggers of
# the installed packages wrote (MIME database, icon and desktop caches); none may name mipgloss.
find "$root/usr" | sed "s|^$root||" | sort >"$work/usr-after.txt"
in_root "$root" "dpkg-query -W -f='\${Package}\n' | xargs dpkg-query -L" |
  sed -E 's#^/(bin|sbin|lib|lib32|lib64|libx32)/#/usr/\1/#' | sort -u >"$work/owned.txt"
comm -13 "$work/usr-before.txt" "$work/usr-after.txt" | comm -23 - "$work/owned.txt" |
  while read -r f; do [ -d "$root$f" ] || echo "$f"; done >"$work/usr-unowned.txt"
echo "      new files in /usr that no package owns: $(wc -l <"$work/usr-unowned.txt") (trigger caches)"
check "  find /usr: none names mipgloss or holds its name" \
  bash -c "cd '$root' && ! grep -i mipgloss '$work/usr-unowned.txt' && ! sed 's|^/||' '$work/usr-unowned.txt' | xargs -r grep -l -i mipgloss"

if [ "$failures" -eq 0 ]; then echo "test-package: all checks passed"; else echo "test-package: $failures check(s) failed"; fi
[ "$failures" -eq 0 ]
