"""Small image / mesh I/O helpers shared by render_reference.py and compare.py.

PNG via Mitsuba's Bitmap (no extra dependency), EXR via the OpenEXR python bindings
(half float, ZIP compression: Mitsuba's own EXR writer uses PIZ, which flip-evaluator
misdecodes).
"""
import os
from pathlib import Path

import numpy as np


# ---------------------------------------------------------------- sRGB
def linear_to_srgb(x):
    """IEC 61966-2-1 transfer function, input clamped to [0, 1]."""
    x = np.clip(np.asarray(x, dtype=np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def srgb_to_linear(s):
    s = np.clip(np.asarray(s, dtype=np.float64), 0.0, 1.0)
    return np.where(s <= 0.04045, s / 12.92, np.power((s + 0.055) / 1.055, 2.4))


def linear_to_srgb8(x):
    return np.round(linear_to_srgb(x) * 255.0).astype(np.uint8)


# ---------------------------------------------------------------- PNG
def _mi():
    import mitsuba as mi
    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    return mi


def write_png(path, img_u8):
    """img_u8: HxW (grey) or HxWx3 uint8."""
    mi = _mi()
    a = np.ascontiguousarray(img_u8, dtype=np.uint8)
    fmt = mi.Bitmap.PixelFormat.Y if a.ndim == 2 else mi.Bitmap.PixelFormat.RGB
    if a.ndim == 2:
        a = a[:, :, None]
    bmp = mi.Bitmap(a, pixel_format=fmt)
    bmp.write(str(path))


def read_png(path):
    """uint8 HxWxC array as stored (C = 1, 3 or 4)."""
    mi = _mi()
    bmp = mi.Bitmap(str(path))
    a = np.array(bmp, copy=True)
    if a.ndim == 2:
        a = a[:, :, None]
    if a.dtype != np.uint8:
        raise ValueError(f"{path}: expected an 8-bit PNG, got {a.dtype}")
    return a


def read_png_rgb01(path):
    """sRGB-encoded values in [0, 1], HxWx3 float64 (grey is replicated, alpha dropped)."""
    a = read_png(path).astype(np.float64) / 255.0
    if a.shape[2] in (1, 2):
        a = np.repeat(a[:, :, :1], 3, axis=2)
    return a[:, :, :3]


def read_mask(path):
    """Boolean HxW: True where the (grey or RGB) mask is >= 128."""
    a = read_png(path)
    return a[:, :, 0] >= 128


# ---------------------------------------------------------------- EXR
def write_exr_half_zip(path, rgb):
    import OpenEXR
    rgb = np.ascontiguousarray(np.asarray(rgb, dtype=np.float32).astype(np.float16))
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    channels = {"R": np.ascontiguousarray(rgb[:, :, 0]),
                "G": np.ascontiguousarray(rgb[:, :, 1]),
                "B": np.ascontiguousarray(rgb[:, :, 2])}
    with OpenEXR.File(header, channels) as f:
        f.write(str(path))


def read_exr_rgb(path):
    import OpenEXR
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        if "RGB" in ch:
            a = np.asarray(ch["RGB"].pixels, dtype=np.float64)
        elif "RGBA" in ch:
            a = np.asarray(ch["RGBA"].pixels, dtype=np.float64)[:, :, :3]
        else:
            a = np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in ("R", "G", "B")], axis=2)
    return a


# ---------------------------------------------------------------- meshes
def read_off(path):
    """(V float64 Nx3, F int64 Mx3). Polygons are fan-triangulated, order kept (CCW as in the file)."""
    with open(path, "r") as fh:
        toks = []
        for line in fh:
            line = line.split("#", 1)[0].strip()
            if line:
                toks.extend(line.split())
    if not toks[0].upper().endswith("OFF"):
        raise ValueError(f"{path}: not an OFF file")
    i = 1
    if toks[0].upper() != "OFF":
        # e.g. "OFF37706" glued header, unusual; treat rest of token as a count
        raise ValueError(f"{path}: unsupported OFF header {toks[0]}")
    nv, nf = int(toks[i]), int(toks[i + 1])
    i += 3
    V = np.array(toks[i:i + 3 * nv], dtype=np.float64).reshape(nv, 3)
    i += 3 * nv
    tris = []
    rest = toks[i:]
    # fast path: all triangles
    arr = None
    if len(rest) >= 4 * nf:
        try:
            cand = np.array(rest[:4 * nf], dtype=np.int64).reshape(nf, 4)
            if np.all(cand[:, 0] == 3):
                arr = cand[:, 1:]
        except ValueError:
            arr = None
    if arr is None:
        j = 0
        for _ in range(nf):
            k = int(rest[j])
            idx = [int(x) for x in rest[j + 1:j + 1 + k]]
            j += 1 + k
            # skip optional colour values: they are not integers followed by a count;
            # OFF files here carry none, so a colour would break parsing loudly below.
            for t in range(1, k - 1):
                tris.append((idx[0], idx[t], idx[t + 1]))
        arr = np.array(tris, dtype=np.int64)
    return V, arr


def area_weighted_normals(V, F):
    """Normalised sum of the unnormalised face normals (cross products) of the incident triangles."""
    e1 = V[F[:, 1]] - V[F[:, 0]]
    e2 = V[F[:, 2]] - V[F[:, 0]]
    fn = np.cross(e1, e2)
    N = np.zeros_like(V)
    for c in range(3):
        np.add.at(N, F[:, c], fn)
    ln = np.linalg.norm(N, axis=1, keepdims=True)
    ln[ln == 0] = 1.0
    return N / ln


def signed_volume(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", a, np.cross(b, c))) / 6.0)


def write_ply_binary(path, V, N, F):
    nv, nf = len(V), len(F)
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"element vertex {nv}\n"
              "property float x\nproperty float y\nproperty float z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              f"element face {nf}\n"
              "property list uchar int vertex_indices\nend_header\n")
    vdata = np.hstack([V, N]).astype("<f4")
    fdt = np.dtype([("n", "u1"), ("i", "<i4", (3,))])
    fdata = np.empty(nf, dtype=fdt)
    fdata["n"] = 3
    fdata["i"] = F
    tmp = str(path) + ".tmp"
    with open(tmp, "wb") as fh:
        fh.write(header.encode("ascii"))
        fh.write(vdata.tobytes())
        fh.write(fdata.tobytes())
    os.replace(tmp, path)


# ---------------------------------------------------------------- noise floor
def half_noise(img0, img1, mask_path, thin_path, away_path=None):
    """LDR FLIP (sRGB PNG values) and linear means between two independent half renders."""
    import flip_evaluator as flip
    a = (linear_to_srgb8(img0) / 255.0).astype(np.float32)
    b = (linear_to_srgb8(img1) / 255.0).astype(np.float32)
    emap, fmean, _ = flip.evaluate(a, b, "LDR", applyMagma=False)
    emap = np.asarray(emap)
    emap = emap[:, :, 0] if emap.ndim == 3 else emap
    out = {"flip": float(fmean)}
    if Path(mask_path).exists():
        m = read_mask(mask_path)
        out["flip_masked"] = float(emap[m].mean())
        out["mean_linear_object_each"] = [img0[m].mean(axis=0).round(5).tolist(), img1[m].mean(axis=0).round(5).tolist()]
    if Path(thin_path).exists():
        t = read_mask(thin_path)
        if t.any():
            out["flip_thin"] = float(emap[t].mean())
            out["mean_linear_thin_each"] = [img0[t].mean(axis=0).round(5).tolist(), img1[t].mean(axis=0).round(5).tolist()]
    if away_path and Path(away_path).exists():
        t = read_mask(away_path)
        if t.any():
            out["flip_away"] = float(emap[t].mean())
            out["mean_linear_away_each"] = [img0[t].mean(axis=0).round(6).tolist(), img1[t].mean(axis=0).round(6).tolist()]
    return out
