#!/usr/bin/env bash
# Packs what a bare x86-64 machine with an NVIDIA driver and no network needs to run Jade's
# benchmarks: a lean `jade` (no images, no Embree, no viewer: few shared libraries), every shared
# library it loads including glibc and the Vulkan loader, run through the packed dynamic loader
# so the target's own libraries do not matter, and the test meshes. Writes .gpu_pack/ in the
# repository root (git-ignored); tools/gpu_pack/run.sh runs the benches from there.
#
#   bash tools/gpu_pack/pack.sh          # here (builds build-pack/, ~3 min on 2 cores)
#   then, on the GPU machine:  bash tools/gpu_pack/run.sh [OUT_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
pack="$root/.gpu_pack"
bash "$root/third_party/fetch_assets.sh" >/dev/null
cmake -S "$root" -B "$root/build-pack" -G Ninja -DCMAKE_BUILD_TYPE=Release -DJADE_WITH_OIIO=OFF -DJADE_WITH_GLFW=OFF \
  -DJADE_BUILD_TESTS=OFF -DJADE_INSTALL=OFF -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON >/dev/null
cmake --build "$root/build-pack" --target jade_cli -j "$(nproc)"
rm -rf "$pack"
mkdir -p "$pack/bin" "$pack/lib" "$pack/assets"
cp "$root/build-pack/samples/cli/jade" "$pack/bin/"
# Every library the binary loads, and the Vulkan loader it opens through libvulkan.so.1.
libs=$(ldd "$pack/bin/jade" | grep -o '/[^ ]*\.so[^ ]*' | sort -u)
for lib in $libs; do cp -L "$lib" "$pack/lib/"; done
cp -L "$(ldconfig -p | awk '/libvulkan.so.1 /{print $NF; exit}')" "$pack/lib/"
cp "$root/assets/bunny00.off" "$root/assets/ChineseDragon-10kv.off" "$pack/assets/"
size=$(du -sm "$pack" | cut -f1)
echo "jade gpu pack: $pack, $size MiB ($(ls "$pack/lib" | wc -l) libraries)"
if [ "$size" -gt 60 ]; then
  echo "jade gpu pack: over the 60 MiB a device call carries" >&2
  exit 1
fi
