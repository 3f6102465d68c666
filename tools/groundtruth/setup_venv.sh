#!/usr/bin/env bash
# Creates tools/groundtruth/.venv with the path-tracing reference harness' dependencies.
# scikit-image (marching cubes) and pyfqmr (quadric decimation) are for make_head.py only.
# Idempotent: re-running only installs what is missing. Prints the versions.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
venv="$here/.venv"
py="${PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
  "$py" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet mitsuba flip-evaluator OpenEXR numpy scikit-image pyfqmr
"$venv/bin/python" - <<'PY'
import importlib.metadata as md
for p in ("mitsuba", "drjit", "flip-evaluator", "OpenEXR", "numpy", "scikit-image", "pyfqmr"):
    try:
        print(f"{p:16s} {md.version(p)}")
    except md.PackageNotFoundError:
        print(f"{p:16s} MISSING")
import mitsuba as mi
mi.set_variant("scalar_rgb")
print("mitsuba variant  scalar_rgb OK")
PY
