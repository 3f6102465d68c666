#!/usr/bin/env python3
"""Writes the LDR-FLIP test pairs and the reference's answers for tests/test_flip.cpp.

Run from anywhere:  python3 tools/flip/make_expected.py
It re-runs itself inside a venv (/tmp/flipvenv, or $FLIP_VENV) holding NVIDIA's reference
implementation (PyPI `flip-evaluator`) and numpy, creating the venv if needed. Outputs, in
tests/data/flip/: <pair>_ref.png/.ppm and <pair>_test.png/.ppm (8-bit sRGB; the C++ test
reads the binary PPM copies, the PNGs are for people) and expected.json with, per pair,
the reference's mean LDR-FLIP, a masked mean and a few per-pixel values [x, y, value].
The images are generated from a fixed seed, so a re-run writes the same files.
"""
import json
import os
import re
import struct
import subprocess
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
OUT = os.path.join(ROOT, "tests", "data", "flip")
VENV = os.environ.get("FLIP_VENV", "/tmp/flipvenv")


def ensure_venv():
    py = os.path.join(VENV, "bin", "python")
    if os.path.realpath(sys.prefix) == os.path.realpath(VENV):
        return
    if not os.path.exists(py):
        subprocess.check_call([sys.executable, "-m", "venv", VENV])
    subprocess.check_call([py, "-m", "pip", "install", "-q", "flip-evaluator==1.7", "numpy"])
    os.execv(py, [py, os.path.abspath(__file__)] + sys.argv[1:])


def write_png(path, img):
    """Minimal 8-bit RGB PNG writer (no filter), so no imaging package is needed."""
    h, w, _ = img.shape
    raw = b"".join(b"\x00" + img[y].tobytes() for y in range(h))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def write_ppm(path, img):
    h, w, _ = img.shape
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (w, h))
        f.write(img.tobytes())


def make_pairs(np):
    rng = np.random.default_rng(20200713)
    pairs = {}
    W, H = 64, 48
    ys, xs = np.mgrid[0:H, 0:W].astype(np.float64)

    # Smooth colour gradient against a copy with +-12 code values of uniform noise.
    grad = np.stack([xs / (W - 1), ys / (H - 1), 0.5 + 0.4 * np.sin(xs / 9.0)], axis=-1)
    grad8 = np.round(grad * 255).astype(np.uint8)
    noisy8 = np.clip(grad8.astype(int) + rng.integers(-12, 13, grad8.shape), 0, 255).astype(np.uint8)
    pairs["gradient_noise"] = (grad8, noisy8)

    # A vertical dark/light edge, and the same edge one pixel to the right.
    edge = np.full((H, W, 3), 40, np.uint8)
    edge[:, 30:] = 210
    shifted = np.full((H, W, 3), 40, np.uint8)
    shifted[:, 31:] = 210
    pairs["edge_shift"] = (edge, shifted)

    # An orange patch on grey against a yellow-green (hue-shifted) patch; patch touches the border.
    patch = np.full((H, W, 3), 128, np.uint8)
    patch[8:40, 20:64] = (220, 120, 40)
    hue = np.full((H, W, 3), 128, np.uint8)
    hue[8:40, 20:64] = (160, 200, 40)
    pairs["hue_shift"] = (patch, hue)

    # Identical textured images: FLIP must be exactly 0.
    tex = np.clip(grad8.astype(int) + rng.integers(-60, 61, grad8.shape), 0, 255).astype(np.uint8)
    pairs["identical"] = (tex, tex.copy())

    # Tiny 8x8 random pair (every pixel is within a filter radius of the border).
    a = rng.integers(0, 256, (8, 8, 3)).astype(np.uint8)
    b = np.clip(a.astype(int) + rng.integers(-50, 51, a.shape), 0, 255).astype(np.uint8)
    pairs["tiny"] = (a, b)
    return pairs


def main():
    ensure_venv()
    import numpy as np
    import flip_evaluator as flip

    os.makedirs(OUT, exist_ok=True)
    expected = {"reference": "flip-evaluator 1.7, evaluate(ref, test, 'LDR')", "pairs": {}}
    # Run the tiny pair also at a lower ppd to exercise the ppd parameter (smaller kernels).
    pairs = make_pairs(np)
    runs = [(name, name, None) for name in pairs] + [("tiny_ppd30", "tiny", 30.0)]
    for name, img in pairs.items():
        for role, im in zip(("ref", "test"), img):
            write_png(os.path.join(OUT, f"{name}_{role}.png"), im)
            write_ppm(os.path.join(OUT, f"{name}_{role}.ppm"), im)

    for run_index, (run_name, pair, ppd) in enumerate(runs):
        ref8, test8 = pairs[pair]
        # Same conversion as the reference's 8-bit loader: float(c) / 255.0f in float32.
        # evaluate() converts sRGB to linear in place, so pass fresh copies.
        ref = ref8.astype(np.float32) / np.float32(255.0)
        test = test8.astype(np.float32) / np.float32(255.0)
        params = {} if ppd is None else {"ppd": ppd}
        fmap, mean, used = flip.evaluate(ref.copy(), test.copy(), "LDR", applyMagma=False, parameters=params)
        fmap = np.asarray(fmap, dtype=np.float64)
        if fmap.ndim == 3:  # some versions return H x W x 1 without the magma map
            fmap = fmap[:, :, 0]
        h, w = fmap.shape
        # Masked mean over the left half of the columns (the C++ test builds the same mask).
        masked = float(fmap[:, : w // 2].mean())
        pts = {(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1), (w // 2, h // 2)}
        iy, ix = np.unravel_index(int(np.argmax(fmap)), fmap.shape)
        pts.add((int(ix), int(iy)))
        rng = np.random.default_rng(run_index)
        for _ in range(4):
            pts.add((int(rng.integers(0, w)), int(rng.integers(0, h))))
        expected["pairs"][run_name] = {
            "reference": f"{pair}_ref.ppm",
            "test": f"{pair}_test.ppm",
            "ppd": float(used["ppd"]),
            "default_ppd": ppd is None,
            "mean": float(mean),
            "mean_float64": float(fmap.mean()),
            "masked_left_half_mean": masked,
            "pixels": [[x, y, float(fmap[y, x])] for x, y in sorted(pts)],
        }
        print(f"{run_name:16s} ppd={used['ppd']:.4f} mean={mean:.6f} max={fmap.max():.4f}")

    # One pixel [x, y, value] per line keeps the file short and its diffs readable.
    text = json.dumps(expected, indent=1)
    text = re.sub(r"\[\s+(\d+),\s+(\d+),\s+([-0-9.e]+)\s+\]", r"[\1, \2, \3]", text)
    with open(os.path.join(OUT, "expected.json"), "w") as f:
        f.write(text + "\n")


if __name__ == "__main__":
    main()
