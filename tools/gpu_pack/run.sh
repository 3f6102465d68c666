#!/usr/bin/env bash
# Runs Jade's benchmarks from the pack that tools/gpu_pack/pack.sh made (.gpu_pack/ in the
# repository root) on a machine with a GPU: `jade bench bake` (clustered against grid, AO against
# Embree is left out), `jade bench deform` and `jade bench render`, one log each in OUT_DIR
# (default: $OUT, else ./gpu_bench). A few minutes on a desktop GPU.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
pack="$root/.gpu_pack"
out=${1:-${OUT:-$root/gpu_bench}}
mkdir -p "$out"
[ -x "$pack/bin/jade" ] || { echo "jade gpu pack: $pack/bin/jade missing (run tools/gpu_pack/pack.sh first)" >&2; exit 1; }
# The NVIDIA driver's ICD manifest where a container mounts it, if the loader's own paths lack one.
if ! ls /usr/share/vulkan/icd.d/*nvidia* /etc/vulkan/icd.d/*nvidia* >/dev/null 2>&1; then
  for f in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/local/nvidia/icd.d/nvidia_icd.json; do
    [ -f "$f" ] && export VK_DRIVER_FILES="$f" && break
  done
fi
export JADE_ASSETS="$pack/assets"
dragon="$pack/assets/ChineseDragon-10kv.off"
status=0
run() {
  local name=$1; shift
  echo "== jade $*" | tee "$out/$name.log"
  timeout 300 "$pack/lib/ld-linux-x86-64.so.2" --library-path "$pack/lib" "$pack/bin/jade" "$@" 2>&1 | tee -a "$out/$name.log"
  local rc=${PIPESTATUS[0]}
  [ "$rc" -eq 0 ] || status=$rc
}
run info info
run bake_bunny bench bake bunny --repeat 3
run bake_dragon bench bake "$dragon" --repeat 3
run deform bench deform bunny "$dragon" --frames 8
run render bench render
exit $status
