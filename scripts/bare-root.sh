# Sourced by the scripts that test on bare Debian 12 roots (test-package.sh, test-fresh.sh).
# Needs root. The caller sets `roots` (where the roots live) and `work` (where logs go) first.
#
#   fresh_root NAME   a fresh bare root at $roots/NAME: a copy of a pristine
#                     `debootstrap --variant=minbase bookworm` (made once, kept in
#                     $roots/pristine for reruns) from the mirror apt uses here, with the host's
#                     apt sources, its resolver and the kernel file systems mounted
#   in_root ROOT CMD  runs CMD with bash in ROOT with a clean environment (root's, no display)
# Mounts are undone on exit (bare_root_cleanup, set as the EXIT trap; a caller with its own trap
# calls it from there). Call fresh_root in the script's own shell, never in a $(...) subshell: the
# mounts it records would be forgotten with the subshell and left in place.

# The mirror apt uses here (deb822 .sources or a one-line sources.list), for debootstrap.
mirror=$(sed -n 's/^URIs:[[:space:]]*\([^[:space:]]*debian\/*\)$/\1/p' /etc/apt/sources.list.d/*.sources 2>/dev/null | head -1)
[ -n "$mirror" ] || mirror=$(awk '$1 == "deb" && $3 ~ /^bookworm$/ {print $2; exit}' /etc/apt/sources.list 2>/dev/null || true)
[ -n "$mirror" ] || mirror=http://deb.debian.org/debian

mounted=()
bare_root_cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[$i]}" 2>/dev/null || true; done
}

# Unmounts whatever is mounted under `root` (a root left by an earlier run that did not end
# cleanly), deepest first, then removes it without ever crossing into another file system: a
# bind mount of the host's /dev, /proc or /sys under it must never be emptied by rm.
remove_root() {
  local root m
  root=$(realpath -m "$1")
  for m in $(awk -v r="$root/" 'index($2 "/", r) == 1 {print $2}' /proc/self/mounts | sort -r); do
    umount -l "$m" || { echo "bare-root: cannot unmount $m; not removing $root" >&2; exit 1; }
  done
  if awk -v r="$root/" 'index($2 "/", r) == 1 {found = 1} END {exit !found}' /proc/self/mounts; then
    echo "bare-root: something is still mounted under $root; not removing it" >&2
    exit 1
  fi
  rm -rf --one-file-system "$root"
}
trap bare_root_cleanup EXIT

fresh_root() {
  local root=$roots/$1
  if [ ! -e "$roots/pristine/.complete" ]; then
    remove_root "$roots/pristine"
    echo "bare-root: debootstrap --variant=minbase bookworm $mirror" >&2
    debootstrap --variant=minbase bookworm "$roots/pristine" "$mirror" >"$work/debootstrap.log" 2>&1 ||
      { tail "$work/debootstrap.log"; exit 1; }
    touch "$roots/pristine/.complete"
  fi
  remove_root "$root"
  cp -a "$roots/pristine" "$root"
  rm -f "$root/.complete"
  rm -f "$root"/etc/apt/sources.list "$root"/etc/apt/sources.list.d/*
  cp /etc/apt/sources.list.d/*.sources "$root/etc/apt/sources.list.d/" 2>/dev/null || true
  cp /etc/apt/sources.list "$root/etc/apt/" 2>/dev/null || true
  cp -L /etc/resolv.conf "$root/etc/resolv.conf"
  local fs
  for fs in proc sys dev dev/pts; do
    mount --bind "/$fs" "$root/$fs"
    mounted+=("$root/$fs")
  done
  chroot "$root" apt-get update -qq
}

in_root() { chroot "$1" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 \
  DEBIAN_FRONTEND=noninteractive bash -c "$2"; }
