#!/usr/bin/env bash
# Installs the Khronos glTF Validator (npm package gltf-validator, run by Node.js) into DEST
# (default build/gltf-validator), for the tests that validate what `jade bake` writes.
# Idempotent: does nothing when it is there. Exit 77 (the tests skip) only when there is no
# Node.js at all; any other failure is an error.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dest="${1:-$root/build/gltf-validator}"
version=2.0.0-dev.3.10
if ! command -v node >/dev/null 2>&1; then
  echo "jade: no Node.js (node) on this machine: the glTF Validator cannot run" >&2
  exit 77
fi
if [ -f "$dest/node_modules/gltf-validator/package.json" ] &&
   grep -q "\"version\": \"$version\"" "$dest/node_modules/gltf-validator/package.json"; then
  exit 0
fi
if ! command -v npm >/dev/null 2>&1; then
  echo "jade: installing Debian's npm (Node.js is here, npm is not)" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends npm >/dev/null ||
    { echo "jade: cannot install npm: gltf-validator@$version cannot be installed" >&2; exit 1; }
fi
mkdir -p "$dest"
# A lock per folder: test binaries may start this at the same time.
exec 9>"$dest/.install.lock"
flock 9
[ -f "$dest/node_modules/gltf-validator/package.json" ] &&
  grep -q "\"version\": \"$version\"" "$dest/node_modules/gltf-validator/package.json" && exit 0
npm install --prefix "$dest" --no-save --no-audit --no-fund --loglevel=error "gltf-validator@$version" >&2
echo "jade: installed gltf-validator@$version into $dest" >&2
