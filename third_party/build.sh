#!/usr/bin/env bash
# Everything the README's two commands need before they run: Debian packages, test meshes,
# configure and build (Release, Ninja) into build/. Idempotent and incremental.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/third_party/install_deps.sh"
bash "$root/third_party/fetch_assets.sh"
# The web renderer's test needs: headless Chromium and web/'s npm packages (docs/web.md). What
# cannot be installed is said here and the build goes on: tests/test_web.cpp then fails under
# CI=true (skips elsewhere), naming it.
bash "$root/third_party/install_web.sh" ||
  echo "jade: warning: the web renderer's test cannot run (above); the rest of the build goes on" >&2
jobs=$(nproc 2>/dev/null || echo 2)
# The fast part of the asan preset (build-asan-subset/: the bad-input and CPU maths tests under
# ASan + UBSan), which the suite in build/ runs as the test asan_subset. JADE_ASAN_SUBSET=OFF
# leaves it out (the test too).
asan_subset=${JADE_ASAN_SUBSET:-ON}
if [ "$asan_subset" = ON ]; then
  (cd "$root" && cmake --preset asan-subset >/dev/null && cmake --build --preset asan-subset)
fi
# The viewer is on: install_deps.sh installed GLFW and ImGui (JADE_CMAKE_ARGS can turn it off).
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DJADE_WITH_GLFW=ON \
      -DJADE_ASAN_SUBSET="$asan_subset" ${JADE_CMAKE_ARGS:-} >/dev/null
cmake --build "$root/build" -j "$jobs"
