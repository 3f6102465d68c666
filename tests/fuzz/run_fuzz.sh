#!/usr/bin/env bash
# Builds the `fuzz` preset and runs every libFuzzer target for SECONDS each, JOBS at a time
# (default 2), then prints executions, coverage (cov = covered edges, ft = features) and
# corpus size per target. Exit status 1 when any target found a crash, leak, timeout or OOM.
#
#   tests/fuzz/run_fuzz.sh 600                  # ten minutes per target
#   JOBS=1 TARGETS="fuzz_ply fuzz_glb" tests/fuzz/run_fuzz.sh 60
#
# Layout under build-fuzz/fuzz/:
#   seeds/<target>/      regenerated every run from tests/data (good and bad files), the bunny
#                        (assets/bunny00.off, cut down to a few hundred vertices and written as
#                        OFF, PLY and OBJ) and command lines for fuzz_cli_args
#   corpus/<target>/     the growing corpus, kept between runs (delete it to start over)
#   artifacts/<target>/  crash-*, leak-*, timeout-*, oom-* inputs (the summary counts those of
#                        this run); reproduce one with
#                        build-fuzz/tests/fuzz/<target> build-fuzz/fuzz/artifacts/<target>/crash-...
#   logs/<target>.log    libFuzzer's output
set -euo pipefail

seconds=${1:?usage: run_fuzz.sh SECONDS (per target)}
root=$(cd "$(dirname "$0")/../.." && pwd)
build="$root/build-fuzz"
work="$build/fuzz"
jobs=${JOBS:-2}
targets=(${TARGETS:-fuzz_off fuzz_ply fuzz_obj fuzz_gltf fuzz_glb fuzz_cli_args})

cd "$root"
if [ "${SKIP_BUILD:-0}" != 1 ]; then
  [ -f "$build/CMakeCache.txt" ] || cmake --preset fuzz >/dev/null
  cmake --build --preset fuzz --target jade_fuzz
fi
[ -s assets/bunny00.off ] || bash third_party/fetch_assets.sh || echo "run_fuzz: no bunny, seeding without it"

# ------------------------------------------------------------------------------ seeds --
rm -rf "$work/seeds"
mkdir -p "$work/seeds" "$work/logs"
seed() {  # seed TARGET FILES...
  local t=$1; shift
  mkdir -p "$work/seeds/$t"
  for f in "$@"; do [ -f "$f" ] && cp "$f" "$work/seeds/$t/"; done
  return 0
}
shopt -s nullglob
d=tests/data
seed fuzz_off $d/*.off $d/bad/*.off
seed fuzz_ply $d/*.ply $d/bad/*.ply
seed fuzz_obj $d/*.obj $d/bad/*.obj
seed fuzz_gltf $d/*.gltf $d/bad/*.gltf
seed fuzz_glb $d/*.glb $d/bad/*.glb
if [ -s assets/bunny00.off ]; then
  # A patch of the bunny (~200 faces within 0.05 units of the first face's first vertex, ~7 KB)
  # as OFF, ASCII PLY and OBJ.
  awk -v R=0.05 -v dir="$work/seeds" '
    function near(i) { split(pos[i], p, " "); return (p[1]-cx)^2 + (p[2]-cy)^2 + (p[3]-cz)^2 < R * R }
    BEGIN { k = 0; nf = 0 }
    { sub(/\r$/, "") }
    NF == 0 || $1 ~ /^#/ { next }
    state == 0 { state = 1; next }                                  # "OFF"
    state == 1 { nv = $1; state = 2; next }                         # counts
    state == 2 && seen < nv { pos[seen++] = $1 " " $2 " " $3; next }
    $1 == 3 {
      if (!centred) { split(pos[$2], q, " "); cx = q[1]; cy = q[2]; cz = q[3]; centred = 1 }
      if (!(near($2) && near($3) && near($4))) next
      for (i = 2; i <= 4; i++) { if (!($i in id)) { id[$i] = k; order[k++] = $i }; c[i] = id[$i] }
      face[nf++] = c[2] " " c[3] " " c[4]
    }
    END {
      off = dir "/fuzz_off/bunny_patch.off"; ply = dir "/fuzz_ply/bunny_patch.ply"; obj = dir "/fuzz_obj/bunny_patch.obj"
      print "OFF\n" k " " nf " 0" > off
      print "ply\nformat ascii 1.0\nelement vertex " k "\nproperty float x\nproperty float y\nproperty float z" > ply
      print "element face " nf "\nproperty list uchar int vertex_indices\nend_header" > ply
      for (v = 0; v < k; v++) { print pos[order[v]] > off; print pos[order[v]] > ply; print "v " pos[order[v]] > obj }
      for (i = 0; i < nf; i++) {
        print "3 " face[i] > off; print "3 " face[i] > ply
        split(face[i], t, " "); print "f " t[1] + 1 " " t[2] + 1 " " t[3] + 1 > obj
      }
    }' assets/bunny00.off
fi
mkdir -p "$work/seeds/fuzz_cli_args"
n=0
while IFS= read -r line; do
  printf '%s' "$line" >"$work/seeds/fuzz_cli_args/cmd$n.txt"
  n=$((n + 1))
done <<'EOF'
bake mesh.off --out out.glb
bake mesh.off --out out.glb --quality draft --ao-rays 16 --seed 7 --method exact --epsilon 0.01
bake mesh.ply --out=out.gltf --material marble --mm-per-unit 2.5 --d 0.1 --strength 0.5 --ao-iid
bake mesh.glb --out out.glb --ao-distance 0.2 --ao-epsilon 1e-5 --method clustered --quality high
bake mesh.off --out out.glb --device lavapipe --validation --verbose
bake mesh.off --out out.glb --ao-rays 0
bake mesh.off --out out.glb --ao-rays abc
bake mesh.off --out out.glb --quality ultra
bake mesh.off --out out.glb --method x
bake mesh.off --out out.glb --epsilon -1
bake mesh.off --out out.glb --d 0
bake mesh.off --out out.glb --material nosuch
bake mesh.off
bake --out out.glb
bake a.off b.off --out out.glb
bake mesh.off --out
bake mesh.off --bogus --out out.glb
bake mesh.off --validation=1 --out out.glb
bake --help
info
info mesh.off
info mesh.off --materials
info a.off b.off
info --device
info --help --verbose
EOF

# ------------------------------------------------------------------------------- run --
max_len() {
  case $1 in
    fuzz_off | fuzz_ply | fuzz_glb) echo 16384 ;;
    fuzz_obj) echo 8192 ;;
    fuzz_gltf) echo 32768 ;;
    fuzz_cli_args) echo 512 ;;
  esac
}
run_one() {
  local t=$1 dict="$root/tests/fuzz/${1#fuzz_}.dict"
  [ "$t" = fuzz_glb ] && dict="$root/tests/fuzz/gltf.dict"
  mkdir -p "$work/corpus/$t" "$work/artifacts/$t"
  # Leaks are findings too (LSan runs at the end of every input that grew the heap).
  "$build/tests/fuzz/$t" -max_total_time="$seconds" -max_len="$(max_len "$t")" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -print_final_stats=1 -dict="$dict" -artifact_prefix="$work/artifacts/$t/" \
    "$work/corpus/$t" "$work/seeds/$t" >"$work/logs/$t.log" 2>&1 || true
}
stamp="$work/.started"
touch "$stamp"
echo "run_fuzz: ${#targets[@]} targets, $seconds s each, $jobs at a time; logs in $work/logs"
running=0
for t in "${targets[@]}"; do
  run_one "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait

# --------------------------------------------------------------------------- summary --
status=0
printf '\n%-15s %12s %8s %8s %8s %8s  %s\n' target executions exec/s cov ft corpus findings
for t in "${targets[@]}"; do
  log="$work/logs/$t.log"
  execs=$(sed -n 's/^stat::number_of_executed_units: //p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: //p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | grep -E ' cov: ' | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(sed -n 's/.* corp: \([0-9]*\)\/.*/\1/p' <<<"$last")
  found=$(find "$work/artifacts/$t" -type f -newer "$stamp" | wc -l)
  printf '%-15s %12s %8s %8s %8s %8s  %s\n' "$t" "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}" "$found"
  if [ "$found" -gt 0 ] || grep -qE '^==[0-9]+==ERROR|^SUMMARY: |==jade-fuzz== FINDING' "$log"; then
    status=1
    find "$work/artifacts/$t" -type f -newer "$stamp" | sed 's/^/    /'
  fi
done
exit $status
