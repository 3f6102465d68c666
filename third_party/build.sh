#!/usr/bin/env bash
# Everything the README's two commands need before they run: Debian packages, test meshes,
# configure and build (Release, Ninja) into build/. Idempotent and incremental.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/third_party/install_deps.sh"
bash "$root/third_party/fetch_assets.sh"
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release ${JADE_CMAKE_ARGS:-} >/dev/null
cmake --build "$root/build" -j "$jobs"
