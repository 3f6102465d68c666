#!/usr/bin/env python3
"""A procedural human head in millimetres, written as OFF (tests/data/head.off).

An implicit surface (smooth union of ellipsoid-like signed distance fields: cranium, face and
jaw, chin, brow, cheekbones, nose, lips, neck stub, eye sockets carved out, and two ears: thin
rounded discs ~60 mm tall, ~32 mm wide, ~6.4 mm thick, flared away from the skull so that light
passes through their back part) polygonised with marching cubes (scikit-image) on a
rectilinear grid that is fine (1.0 mm) across the ears and the nose and 2.0 mm elsewhere, then
decimated (quadric edge collapse, pyfqmr) to ~28k vertices, which keeps the ears' and the nose's
detail. Axes: +x = the head's left side (the viewer's right seen from the front), +y up, +z out of
the face; bbox 170 x 255 x 225 mm (diagonal 380 mm). Deterministic (no randomness).

The result is checked: one connected component, every edge shared by exactly two triangles
(closed 2-manifold), no degenerate triangles, positive signed volume (CCW = outward).

  make_head.py [--out tests/data/head.off] [--fine 1.0] [--coarse 2.0] [--target-vertices 28000]
"""
import argparse
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent


# ---------------------------------------------------------------- SDF primitives
def ellipsoid(p, c, r):
    """Approximate SDF of an axis-aligned ellipsoid (Quilez): exact on the surface, good near it."""
    q = (p - np.asarray(c, float)) / np.asarray(r, float)
    k0 = np.linalg.norm(q, axis=-1)
    k1 = np.linalg.norm(q / np.asarray(r, float), axis=-1)
    return k0 * (k0 - 1.0) / np.maximum(k1, 1e-12)


def rotated(p, c, R):
    """Coordinates of p in the frame with origin c and rows of R as axes."""
    return (p - np.asarray(c, float)) @ np.asarray(R, float).T


def smin(a, b, k):
    h = np.maximum(k - np.abs(a - b), 0.0) / k
    return np.minimum(a, b) - h * h * k * 0.25


def smax(a, b, k):
    return -smin(-a, -b, k)


def ear(p, side):
    """A rounded thin disc: in-plane ellipse (half-axes 14 x 28 mm) + rim radius 2.2 mm,
    half-thickness 1.0 + 2.2 = 3.2 mm. Flared 35 deg: the front edge meets the skull, the back
    edge stands ~20 mm off it. side = +1 (x > 0) or -1."""
    a = np.radians(35.0)
    u = np.array([side * np.sin(a), 0.0, -np.cos(a)])   # in plane, backwards and outwards
    v = np.array([0.0, 1.0, 0.0])
    w = np.array([side * np.cos(a), 0.0, np.sin(a)])     # normal, outwards and forwards
    q = rotated(p, [side * 77.0, -8.0, -12.0], [u, v, w])
    r2 = np.array([14.0, 28.0])
    qq = q[..., :2] / r2
    k0 = np.linalg.norm(qq, axis=-1)
    k1 = np.linalg.norm(qq / r2, axis=-1)
    d_ell = k0 * (k0 - 1.0) / np.maximum(k1, 1e-12)
    d_slab = np.abs(q[..., 2]) - 1.0
    out = np.sqrt(np.maximum(d_ell, 0.0) ** 2 + np.maximum(d_slab, 0.0) ** 2)
    return out + np.minimum(np.maximum(d_ell, d_slab), 0.0) - 2.2


def head_sdf(p):
    d = ellipsoid(p, [0, 25, -8], [73, 90, 100])                     # cranium
    d = smin(d, ellipsoid(p, [0, -35, 22], [58, 62, 70]), 20.0)      # face, cheeks
    d = smin(d, ellipsoid(p, [0, -68, 36], [45, 30, 46]), 14.0)      # jaw
    d = smin(d, ellipsoid(p, [0, -86, 66], [20, 14, 16]), 10.0)      # chin
    d = smin(d, ellipsoid(p, [0, 16, 76], [50, 13, 20]), 12.0)       # brow ridge
    for s in (-1.0, 1.0):
        d = smin(d, ellipsoid(p, [s * 38, -14, 62], [20, 15, 18]), 10.0)  # cheekbones
    # nose: an ellipsoid tilted 25 deg (root back and up, tip forward and down) + the tip
    t = np.radians(25.0)
    Rn = [[1, 0, 0], [0, np.cos(t), -np.sin(t)], [0, np.sin(t), np.cos(t)]]
    qn = rotated(p, [0, -14, 92], Rn)
    d = smin(d, ellipsoid(qn, [0, 0, 0], [10, 25, 12]), 6.0)
    d = smin(d, ellipsoid(p, [0, -35, 108], [10, 8, 9]), 5.0)
    d = smin(d, ellipsoid(p, [0, -57, 84], [22, 7, 10]), 6.0)        # lips
    for s in (-1.0, 1.0):                                             # eye sockets
        d = smax(d, -ellipsoid(p, [s * 30, 2, 98], [15, 11, 12]), 6.0)
    # neck stub: elliptic cylinder, flat cut at y = -140
    neck = ellipsoid(p * np.array([1.0, 0.0, 1.0]), [0, 0, -18], [50, 1, 52])
    neck = np.maximum(neck, np.maximum(-(p[..., 1] + 140.0), p[..., 1] + 30.0))
    d = smin(d, neck, 22.0)
    for s in (-1.0, 1.0):
        d = smin(d, ear(p, s), 6.0)
    return d


# ---------------------------------------------------------------- grid
def axis_coords(lo, hi, fine_intervals, h_fine, h_coarse, ramp=12.0):
    """Grid coordinates from lo to hi: spacing h_fine inside the intervals, growing linearly
    to h_coarse over `ramp` mm outside them."""
    def h(t):
        dist = min([0.0 if a <= t <= b else min(abs(t - a), abs(t - b)) for a, b in fine_intervals] or [1e9])
        return h_fine + (h_coarse - h_fine) * min(dist / ramp, 1.0)
    xs = [lo]
    while xs[-1] < hi:
        xs.append(xs[-1] + h(xs[-1]))
    return np.array(xs)


def polygonise(fine, coarse, ramp=8.0):
    from skimage import measure
    # fine across the ears (x 62..90, y -40..24, z -30..6) and the nose (x -12..12, z 88..122)
    gx = axis_coords(-96.0, 96.0, [(-90.0, -62.0), (-12.0, 12.0), (62.0, 90.0)], fine, coarse, ramp)
    gy = axis_coords(-143.0, 118.0, [(-40.0, 24.0)], fine, coarse, ramp)
    gz = axis_coords(-112.0, 122.0, [(-30.0, 6.0), (88.0, 122.0)], fine, coarse, ramp)
    P = np.stack(np.meshgrid(gx, gy, gz, indexing="ij"), axis=-1)
    vol = np.empty(P.shape[:3])
    for i in range(len(gx)):  # slab by slab: bounded memory
        vol[i] = head_sdf(P[i])
    verts, faces, _, _ = measure.marching_cubes(vol, level=0.0, gradient_direction="ascent", method="lewiner")
    V = np.stack([np.interp(verts[:, k], np.arange(len(g)), g) for k, g in enumerate((gx, gy, gz))], axis=1)
    return V, faces.astype(np.int64), (len(gx), len(gy), len(gz))


# ---------------------------------------------------------------- checks
def signed_volume(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def clean(V, F):
    """Drop zero-area triangles by collapsing their shortest edge's endpoints, repeat."""
    for _ in range(10):
        area2 = np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
        bad = area2 <= 1e-4
        if not bad.any():
            break
        remap = np.arange(len(V))
        for f in F[bad]:
            e = [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])]
            a, b = min(e, key=lambda ab: np.linalg.norm(V[ab[0]] - V[ab[1]]))
            remap[max(a, b)] = remap[min(a, b)]
        F = remap[F]
        F = F[(F[:, 0] != F[:, 1]) & (F[:, 1] != F[:, 2]) & (F[:, 2] != F[:, 0])]
    used = np.unique(F)
    new = -np.ones(len(V), dtype=np.int64)
    new[used] = np.arange(len(used))
    return V[used], new[F]


def check(V, F):
    """Raises unless the mesh is a closed, connected, oriented 2-manifold without degenerate triangles."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    key = np.sort(e, axis=1)
    uk, cnt = np.unique(key, axis=0, return_counts=True)
    if not np.all(cnt == 2):
        raise SystemExit(f"non-manifold: {np.sum(cnt != 2)} edges not shared by exactly two triangles")
    ud, dcnt = np.unique(e, axis=0, return_counts=True)
    if not np.all(dcnt == 1):
        raise SystemExit("inconsistent orientation: a directed edge appears twice")
    area2 = np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
    if area2.min() <= 1e-4:
        raise SystemExit(f"{np.sum(area2 <= 1e-4)} degenerate (area < 5e-5 mm^2) triangles")
    # connected components (union-find over edges)
    parent = np.arange(len(V))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    for a, b in uk:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[ra] = rb
    comps = len({find(i) for i in range(len(V))})
    if comps != 1:
        raise SystemExit(f"{comps} connected components")
    # vertex manifoldness: the triangles around each vertex form one fan (Euler check per component)
    chi = len(V) - len(uk) + len(F)
    vol = signed_volume(V, F)
    if vol <= 0:
        raise SystemExit(f"signed volume {vol} <= 0")
    return {"vertices": len(V), "triangles": len(F), "edges": len(uk), "euler": chi, "components": comps,
            "signed_volume_mm3": vol, "min_double_area": float(area2.min())}


def write_off(path, V, F):
    with open(path, "w") as fh:
        fh.write(f"OFF\n{len(V)} {len(F)} 0\n")
        fh.write("".join(f"{x:.3f} {y:.3f} {z:.3f}\n" for x, y, z in V))
        fh.write("".join(f"3 {a} {b} {c}\n" for a, b, c in F))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(REPO / "tests/data/head.off"))
    ap.add_argument("--fine", type=float, default=1.0, help="grid spacing (mm) across the ears and the nose")
    ap.add_argument("--coarse", type=float, default=2.0, help="grid spacing (mm) elsewhere")
    ap.add_argument("--target-vertices", type=int, default=28000,
                    help="quadric decimation (pyfqmr) down to about this many vertices; 0 = none")
    a = ap.parse_args()
    V, F, shape = polygonise(a.fine, a.coarse)
    n_mc = len(V)
    if a.target_vertices and len(V) > a.target_vertices:
        import pyfqmr  # quadric edge collapse (Garland-Heckbert), deterministic
        s = pyfqmr.Simplify()
        s.setMesh(V, F)
        s.simplify_mesh(target_count=2 * a.target_vertices - 4, aggressiveness=5.0, preserve_border=True,
                        verbose=False)
        V, F, _ = s.getMesh()
        V, F = np.asarray(V, dtype=np.float64), np.asarray(F, dtype=np.int64)
    if signed_volume(V, F) < 0:
        F = F[:, ::-1].copy()
    # the OFF stores 3 decimals: round first so the checks see the written mesh
    V = np.round(V, 3)
    V, F = clean(V, F)
    info = check(V, F)
    write_off(a.out, V, F)
    lo, hi = V.min(axis=0), V.max(axis=0)
    print(f"grid {shape}, marching cubes {n_mc} vertices; {info}")
    print(f"bbox min {lo.round(1).tolist()} max {hi.round(1).tolist()} size {(hi - lo).round(1).tolist()} "
          f"diagonal {np.linalg.norm(hi - lo):.1f} mm; wrote {a.out} ({Path(a.out).stat().st_size / 1e6:.2f} MB)")


if __name__ == "__main__":
    main()
