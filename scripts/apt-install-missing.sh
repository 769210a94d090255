#!/usr/bin/env bash
# apt-install-missing.sh WHO PACKAGE...: installs (apt, no recommends) those of the Debian packages
# that are not installed, and says so under the name WHO; nothing when all are. The one place the
# scripts install packages (install-deps.sh, install-clang.sh, test-package.sh, test-fresh.sh).
# Runs apt through sudo unless it is root already.
set -euo pipefail
who=${1:?usage: apt-install-missing.sh WHO PACKAGE...}
shift
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "$who: everything is installed"
  exit 0
fi
echo "$who: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
