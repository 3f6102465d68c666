#!/usr/bin/env bash
# Fetches the classic test meshes from Debian's libcgal-demo package into assets/ (git-ignored).
# The package is downloaded, not installed (it would pull in Qt): only the meshes are unpacked.
# Idempotent: does nothing when the meshes are present.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dest="${JADE_ASSETS:-$root/assets}"
mapfile -t meshes < <(sed -e 's/#.*//' -e 's/[[:space:]]*$//' -e '/^$/d' "$root/third_party/assets.txt")
have=1
for m in "${meshes[@]}"; do [ -s "$dest/$m" ] || have=0; done
[ $have -eq 1 ] && { echo "jade: assets present in $dest"; exit 0; }
mkdir -p "$dest"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
if ! apt-get download libcgal-demo >/dev/null 2>&1; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  apt-get download libcgal-demo >/dev/null
fi
dpkg-deb -x libcgal-demo_*.deb pkg
members=()
for m in "${meshes[@]}"; do members+=("data/meshes/$m"); done
tar -xzf pkg/usr/share/doc/libcgal-dev/data.tar.gz "${members[@]}"
for m in "${meshes[@]}"; do mv "data/meshes/$m" "$dest/$m.part" && mv "$dest/$m.part" "$dest/$m"; done
echo "jade: fetched ${meshes[*]} into $dest (from Debian libcgal-demo, LGPL/GPL data; see third_party/ASSETS.md)"
