#!/usr/bin/env python3
"""Path-traced references of Jade's scenes with Mitsuba 3 (scalar_rgb, CPU).

For every scene <mesh>_<medium>_<light> of scenes.json this writes into --out
(default tools/groundtruth/references/):
  <scene>.exr   linear RGB, half float, ZIP (OpenEXR python bindings)
  <scene>.png   sRGB 8 bit of the linear image (clamped, no tone map)
  <scene>.json  the fully resolved record (camera, light as Jade takes it, medium per
                mesh unit, spp, timings, jade_render_args, ...)
and once per mesh (view): <mesh>_mask.png, <mesh>_thin.png, <mesh>_masks.json; for the sets
that list "scenes" (regimes) also <mesh>_<light>_away.png: surfaces facing away from the light.

Run with tools/groundtruth/.venv/bin/python (see setup_venv.sh and README.md).
"""
import argparse
import json
import math
import os
import shlex
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
sys.path.insert(0, str(HERE))
import gt_io  # noqa: E402

import mitsuba as mi  # noqa: E402

mi.set_variant("scalar_rgb")

MAX_DEPTH = 256
DEFAULT_SPP = 512
THIN_RAYS = 64
THIN_HALF_ANGLE_DEG = 60.0
THIN_OFFSET_PER_DIAGONAL = 1e-4
THIN_SEED = 1
CACHE = HERE / ".cache"


# ---------------------------------------------------------------- vectors
def normalize(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def fmt3(v):
    return ",".join(f"{x:.9g}" for x in v)


# ---------------------------------------------------------------- mesh
_mesh_cache = {}


def load_mesh(name, mesh_cfg):
    """OFF -> binary PLY with area-weighted vertex normals, cached in .cache/."""
    if name in _mesh_cache:
        return _mesh_cache[name]
    off = REPO / mesh_cfg["file"]
    V, F = gt_io.read_off(off)
    N = gt_io.area_weighted_normals(V, F)
    vol = gt_io.signed_volume(V, F)
    CACHE.mkdir(parents=True, exist_ok=True)
    ply = CACHE / f"{name}.ply"
    if not ply.exists() or ply.stat().st_mtime < off.stat().st_mtime:
        gt_io.write_ply_binary(ply, V, N, F)
    # bbox of the vertices referenced by faces (= all vertices for these meshes)
    used = np.unique(F)
    bmin = V[used].min(axis=0)
    bmax = V[used].max(axis=0)
    info = {
        "file": mesh_cfg["file"],
        "ply": ply,
        "vertices": int(len(V)),
        "triangles": int(len(F)),
        "bbox_min": bmin.tolist(),
        "bbox_max": bmax.tolist(),
        "diagonal": float(np.linalg.norm(bmax - bmin)),
        "signed_volume": vol,
        # +1: CCW triangles give outward normals (closed mesh, positive volume)
        "outward_sign": 1.0 if vol >= 0 else -1.0,
    }
    _mesh_cache[name] = info
    return info


# ---------------------------------------------------------------- scene record
def camera_for(mesh, mesh_cfg, cfg):
    fov = float(cfg["fov_y_degrees"])
    bmin, bmax = np.array(mesh["bbox_min"]), np.array(mesh["bbox_max"])
    target = 0.5 * (bmin + bmax)
    radius = 0.5 * mesh["diagonal"]
    dist = 1.05 * radius / math.sin(math.radians(fov) / 2.0)
    view = normalize(mesh_cfg["view"])
    eye = target + dist * view
    up = normalize(mesh_cfg["up"])
    return {"eye": eye.tolist(), "target": target.tolist(), "up": up.tolist(),
            "fov_y_degrees": fov, "distance": dist}


def camera_frame(cam):
    f = normalize(np.array(cam["target"]) - np.array(cam["eye"]))
    r = normalize(np.cross(f, cam["up"]))
    u = np.cross(r, f)
    return r, u, -f  # x right, y up, z towards the eye


def light_world(light_cfg, cam):
    r, u, b = camera_frame(cam)
    c = np.asarray(light_cfg["camera_dir"], dtype=np.float64)
    towards = normalize(c[0] * r + c[1] * u + c[2] * b)
    irr = light_cfg["irradiance"]
    if np.isscalar(irr):
        irr = [float(irr)] * 3
    return towards, [float(x) for x in irr]


def point_light(light_cfg, cam, mesh):
    """Point light at bbox centre + distance_per_diagonal * diagonal * towards; intensity I per
    mesh unit (E = I / r^2): given, or irradiance_at_centre * distance^2."""
    r, u, b = camera_frame(cam)
    c = np.asarray(light_cfg["camera_dir"], dtype=np.float64)
    towards = normalize(c[0] * r + c[1] * u + c[2] * b)
    dist = float(light_cfg["distance_per_diagonal"]) * mesh["diagonal"]
    pos = 0.5 * (np.array(mesh["bbox_min"]) + np.array(mesh["bbox_max"])) + dist * towards
    i = light_cfg.get("intensity")
    i = float(light_cfg["irradiance_at_centre"]) * dist * dist if i is None else float(i)
    return {"type": "point", "position": pos.tolist(), "intensity": [i, i, i], "towards_light_from_centre": towards.tolist(),
            "distance_from_centre": dist, "irradiance_at_centre": i / (dist * dist),
            "camera_dir": light_cfg["camera_dir"], "distance_per_diagonal": light_cfg["distance_per_diagonal"]}


def medium_per_unit(med_cfg, diagonal, mm_per_unit=None):
    if "sigma_s_prime_per_mm" in med_cfg:  # physical units: sigma per mm * mm per unit
        if not mm_per_unit:
            raise SystemExit("a medium in mm needs the mesh's mm_per_unit")
        ss = np.array(med_cfg["sigma_s_prime_per_mm"], dtype=np.float64) * mm_per_unit
        sa = np.array(med_cfg["sigma_a_per_mm"], dtype=np.float64) * mm_per_unit
    else:
        ss = np.array(med_cfg["sigma_s_per_diagonal"], dtype=np.float64) / diagonal
        sa = np.array(med_cfg["sigma_a_per_diagonal"], dtype=np.float64) / diagonal
    return {"sigma_s": ss.tolist(), "sigma_a": sa.tolist(), "g": float(med_cfg["g"]),
            "ior": float(med_cfg["ior"]), "roughness": float(med_cfg["roughness"])}


def jade_args(cam, res, towards, irr, point=None):
    light = f"point:{fmt3(point['position'])}:{fmt3(point['intensity'])}" if point else f"dir:{fmt3(towards)}:{fmt3(irr)}"
    return ["--eye", fmt3(cam["eye"]), "--target", fmt3(cam["target"]), "--up", fmt3(cam["up"]),
            "--fov", f"{cam['fov_y_degrees']:g}", "--size", f"{res[0]}x{res[1]}", "--light", light]


# ---------------------------------------------------------------- mitsuba scene
def rgb(v):
    return {"type": "rgb", "value": [float(x) for x in v]}


def sensor_dict(cam, res):
    return {
        "type": "perspective",
        "fov_axis": "y",
        "fov": float(cam["fov_y_degrees"]),
        "near_clip": 1e-3 * cam["distance"],
        "far_clip": 1e3 * cam["distance"],
        "to_world": mi.ScalarTransform4f().look_at(origin=cam["eye"], target=cam["target"], up=cam["up"]),
        "film": {"type": "hdrfilm", "width": int(res[0]), "height": int(res[1]),
                 "pixel_format": "rgb", "rfilter": {"type": "box"}},
        "sampler": {"type": "independent", "sample_count": 16},
    }


def build_scene(mesh, cam, res, towards=None, irr=None, medium=None, point=None):
    shape = {"type": "ply", "filename": str(mesh["ply"]), "face_normals": False}
    if medium is not None:
        ss = np.array(medium["sigma_s"])
        sa = np.array(medium["sigma_a"])
        st = ss + sa
        shape["bsdf"] = {"type": "roughdielectric", "distribution": "ggx",
                         "alpha": medium["roughness"] ** 2,
                         "int_ior": medium["ior"], "ext_ior": 1.0}
        # 'srgb' + unbounded: the 'rgb' type rejects values > 1 (reflectance check)
        shape["interior"] = {"type": "homogeneous",
                             "sigma_t": {"type": "srgb", "color": st.tolist(), "unbounded": True}, "albedo": rgb(ss / st),
                             "scale": 1.0, "phase": {"type": "hg", "g": medium["g"]}}
    else:
        shape["bsdf"] = {"type": "diffuse"}
    d = {"type": "scene",
         "integrator": {"type": "volpath", "max_depth": MAX_DEPTH},
         "sensor": sensor_dict(cam, res),
         "object": shape}
    if point is not None:
        d["light"] = {"type": "point", "position": point["position"], "intensity": rgb(point["intensity"])}
    elif towards is not None:
        d["light"] = {"type": "directional", "direction": (-np.asarray(towards)).tolist(),
                      "irradiance": rgb(irr)}
    return mi.load_dict(d)


# ---------------------------------------------------------------- masks
def hammersley_cone(n, half_angle_deg):
    """n unit directions (local frame, +z axis) uniform in solid angle within the cone."""
    i = np.arange(n)
    u1 = (i + 0.5) / n
    u2 = np.array([int(f"{k:032b}"[::-1], 2) / 2.0 ** 32 for k in i])  # radical inverse base 2
    return u1, u2


def primary_rays(name, mesh, cam, res):
    """The scene without material and, per pixel centre: hit?, hit point, outward interpolated normal."""
    scene = build_scene(mesh, cam, res)
    if name not in _primary:
        sensor = scene.sensors()[0]
        W, H, sign = int(res[0]), int(res[1]), mesh["outward_sign"]
        cover, P, Nn = np.zeros((H, W), dtype=bool), np.zeros((H, W, 3)), np.zeros((H, W, 3))
        for y in range(H):
            for x in range(W):
                ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f((x + 0.5) / W, (y + 0.5) / H), mi.Point2f(0.5))
                si = scene.ray_intersect(ray)
                if si.is_valid():
                    cover[y, x] = True
                    P[y, x] = [si.p[0], si.p[1], si.p[2]]
                    n = si.sh_frame.n
                    Nn[y, x] = [sign * n[0], sign * n[1], sign * n[2]]
        _primary[name] = (cover, P, Nn)
    return scene, _primary[name]


_primary = {}


def masks_for(name, mesh, cam, res, out_dir, n_rays=THIN_RAYS, tau=0.1):
    t0 = time.time()
    W, H = int(res[0]), int(res[1])
    diag = mesh["diagonal"]
    scene, (cover, P, Nn) = primary_rays(name, mesh, cam, res)
    t_primary = time.time() - t0

    # cone rays: Hammersley in (cos theta, phi) + per-pixel Cranley-Patterson rotation (fixed seed)
    u1, u2 = hammersley_cone(n_rays, THIN_HALF_ANGLE_DEG)
    rng = np.random.default_rng(THIN_SEED)
    cos_max = math.cos(math.radians(THIN_HALF_ANGLE_DEG))
    ys, xs = np.nonzero(cover)
    thick = np.zeros((H, W))
    eps = THIN_OFFSET_PER_DIAGONAL * diag
    t1 = time.time()
    for y, x in zip(ys, xs):
        rot = rng.random(2)
        a = (u1 + rot[0]) % 1.0
        b = (u2 + rot[1]) % 1.0
        cos_t = 1.0 - a * (1.0 - cos_max)
        sin_t = np.sqrt(np.maximum(0.0, 1.0 - cos_t * cos_t))
        phi = 2.0 * math.pi * b
        axis = -Nn[y, x]
        # orthonormal basis (Duff et al. 2017)
        s = math.copysign(1.0, axis[2])
        aa = -1.0 / (s + axis[2])
        bb = axis[0] * axis[1] * aa
        t_ = np.array([1.0 + s * axis[0] * axis[0] * aa, s * bb, -s * axis[0]])
        b_ = np.array([bb, s + axis[1] * axis[1] * aa, -axis[1]])
        dirs = (np.outer(sin_t * np.cos(phi), t_) + np.outer(sin_t * np.sin(phi), b_)
                + np.outer(cos_t, axis))
        o = mi.Point3f(*(P[y, x] - eps * Nn[y, x]))
        tot = 0.0
        for d in dirs.tolist():
            pi = scene.ray_intersect_preliminary(mi.Ray3f(o, mi.Vector3f(d)))
            tot += pi.t if pi.is_valid() else diag
        thick[y, x] = tot / n_rays
    t_cone = time.time() - t1
    thin = cover & (thick <= tau * diag)

    gt_io.write_png(out_dir / f"{name}_mask.png", (cover * 255).astype(np.uint8))
    gt_io.write_png(out_dir / f"{name}_thin.png", (thin * 255).astype(np.uint8))
    tvals = thick[cover] / diag
    rec = {
        "mesh": name, "file": mesh["file"], "resolution": [W, H],
        "eye": cam["eye"], "target": cam["target"], "up": cam["up"], "fov_y_degrees": cam["fov_y_degrees"],
        "object_pixels": int(cover.sum()), "thin_pixels": int(thin.sum()),
        "thin_thickness_per_diagonal": tau,
        "thickness_definition": (f"mean distance of {n_rays} rays from p - {THIN_OFFSET_PER_DIAGONAL:g}*diagonal*n, "
                                 f"uniform in solid angle in the cone of half-angle {THIN_HALF_ANGLE_DEG:g} deg "
                                 "around -n (Hammersley + per-pixel Cranley-Patterson rotation, seed "
                                 f"{THIN_SEED}); miss = diagonal; n = interpolated area-weighted vertex normal, outward"),
        "rays_per_pixel": n_rays,
        "thickness_per_diagonal_quantiles": {q: float(np.quantile(tvals, float(q))) for q in
                                             ("0.01", "0.05", "0.1", "0.25", "0.5", "0.75", "0.9")},
        "signed_volume": mesh["signed_volume"], "outward_sign": mesh["outward_sign"],
        "seconds": {"primary": round(t_primary, 2), "cone": round(t_cone, 2)},
    }
    with open(out_dir / f"{name}_masks.json", "w") as fh:
        json.dump(rec, fh, indent=2)
    return rec


def away_mask(name, lname, mesh, cam, res, out_dir, towards=None, point=None):
    """<mesh>_<light>_away.png: pixels whose surface (interpolated normal n at the primary hit p)
    faces away from the light, n.l < -0.1 (l = towards the light; for a point light normalise(pos - p)),
    thin pixels excluded. Returns (file name, pixel count)."""
    _, (cover, P, Nn) = primary_rays(name, mesh, cam, res)
    thin = gt_io.read_mask(out_dir / f"{name}_thin.png")
    if point is not None:
        L = np.asarray(point["position"]) - P
        L /= np.maximum(np.linalg.norm(L, axis=2, keepdims=True), 1e-30)
    else:
        L = np.broadcast_to(np.asarray(towards), P.shape)
    away = cover & ~thin & (np.einsum("ijk,ijk->ij", Nn, L) < -0.1)
    fname = f"{name}_{lname}_away.png"
    gt_io.write_png(out_dir / fname, (away * 255).astype(np.uint8))
    return fname, int(away.sum())


# ---------------------------------------------------------------- main
def scene_list(cfg, which):
    out = []
    sets = ["train", "validation"] if which == "all" else [which]
    for s in sets:
        st = cfg["sets"][s]
        if "scenes" in st:  # an explicit list of <mesh>_<medium>_<light>
            out += [(s, *n.split("_")) for n in st["scenes"]]
            continue
        for m in st["meshes"]:
            for med in st["media"]:
                for l in st["lights"]:
                    out.append((s, m, med, l))
    return out


def main():
    global MAX_DEPTH
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--set", default="all", choices=["train", "validation", "all", "regimes"],
                    help="all = train + validation; regimes (held out) only by name")
    ap.add_argument("--scene", action="append", help="only this scene (repeatable); <mesh>_<medium>_<light>")
    ap.add_argument("--spp", type=int, default=DEFAULT_SPP)
    ap.add_argument("--seed", type=int, default=0, help="sampler seed (noise-floor runs use another)")
    ap.add_argument("--out", default=str(HERE / "references"))
    ap.add_argument("--scenes-json", default=str(HERE / "scenes.json"))
    ap.add_argument("--no-masks", action="store_true", help="skip the mask / thin-mask pass")
    ap.add_argument("--masks-only", action="store_true")
    ap.add_argument("--skip-existing", action="store_true", help="skip scenes whose .json exists")
    ap.add_argument("--thin-rays", type=int, default=THIN_RAYS)
    ap.add_argument("--halves", action="store_true",
                    help="render spp/2 with seed and seed+1, store the average and the half-vs-half FLIP")
    ap.add_argument("--merge", metavar="DIR",
                    help="no rendering: average --out's scenes with DIR's (same scenes, other seed)")
    ap.add_argument("--max-depth", type=int, default=None, help="default: the medium's max_depth, else 256")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0 = all cores)")
    args = ap.parse_args()

    if args.threads:
        import drjit as dr
        dr.set_thread_count(args.threads)

    cfg = json.load(open(args.scenes_json))
    tau = float(cfg.get("thin_thickness_per_diagonal", 0.1))
    res = cfg["resolution"]
    out_dir = Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)

    todo = scene_list(cfg, args.set)
    if args.scene:
        want = set(args.scene)
        todo = [t for t in todo if f"{t[1]}_{t[2]}_{t[3]}" in want]
        missing = want - {f"{t[1]}_{t[2]}_{t[3]}" for t in todo}
        if missing:
            sys.exit(f"unknown scene(s) (or not in --set {args.set}): {sorted(missing)}")

    cmdline = " ".join(shlex.quote(a) for a in [os.path.relpath(sys.argv[0], REPO)] + sys.argv[1:])
    done_masks = set()
    for (set_name, mname, medname, lname) in todo:
        mesh_cfg = cfg["meshes"][mname]
        mesh = load_mesh(mname, mesh_cfg)
        cam = camera_for(mesh, mesh_cfg, cfg)
        if not args.no_masks and mname not in done_masks:
            mp = out_dir / f"{mname}_masks.json"
            if not (args.skip_existing and mp.exists()):
                r = masks_for(mname, mesh, cam, res, out_dir, n_rays=args.thin_rays, tau=tau)
                print(f"[masks] {mname}: object {r['object_pixels']} px, thin {r['thin_pixels']} px "
                      f"(tau {tau}), {r['seconds']}", flush=True)
            done_masks.add(mname)
        if args.masks_only:
            continue
        scene_name = f"{mname}_{medname}_{lname}"
        if args.skip_existing and (out_dir / f"{scene_name}.json").exists():
            print(f"[skip] {scene_name}")
            continue
        lcfg, med_cfg = cfg["lights"][lname], cfg["media"][medname]
        MAX_DEPTH = args.max_depth or int(med_cfg.get("max_depth", 256))
        point = point_light(lcfg, cam, mesh) if lcfg.get("type") == "point" else None
        towards, irr = light_world(lcfg, cam) if point is None else (None, None)
        mmpu = mesh_cfg.get("mm_per_unit")
        medium = medium_per_unit(med_cfg, mesh["diagonal"], mmpu)
        away = None
        if "scenes" in cfg["sets"][set_name]:
            away = away_mask(mname, lname, mesh, cam, res, out_dir, towards, point)
            print(f"[away] {away[0]}: {away[1]} px", flush=True)
        halves = None
        spp_total, seeds = args.spp, [args.seed]
        if args.merge:
            # average this folder's render with an independent one (other seed) in --merge DIR
            rec0 = json.load(open(out_dir / f"{scene_name}.json"))
            rec1 = json.load(open(Path(args.merge) / f"{scene_name}.json"))
            if "halves" in rec0 or "halves" in rec1 or rec0["seed"] == rec1["seed"]:
                sys.exit(f"{scene_name}: already merged or same seed; not merging")
            img0 = gt_io.read_exr_rgb(out_dir / f"{scene_name}.exr")
            img1 = gt_io.read_exr_rgb(Path(args.merge) / f"{scene_name}.exr")
            secs_each = [rec0["render_seconds"], rec1["render_seconds"]]
            spp_each = [rec0["spp"], rec1["spp"]]
            seeds = [rec0["seed"], rec1["seed"]]
            cmds = [rec0["command"], rec1["command"], cmdline]
        elif args.halves:
            scene = build_scene(mesh, cam, res, towards, irr, medium, point)
            imgs, secs_each = [], []
            for sd in (args.seed, args.seed + 1):
                t0 = time.time()
                imgs.append(np.array(mi.render(scene, spp=args.spp // 2, seed=sd), dtype=np.float64))
                secs_each.append(round(time.time() - t0, 2))
            img0, img1 = imgs
            spp_each = [args.spp // 2] * 2
            seeds = [args.seed, args.seed + 1]
            cmds = [cmdline]
        else:
            scene = build_scene(mesh, cam, res, towards, irr, medium, point)
            t0 = time.time()
            img = np.array(mi.render(scene, spp=args.spp, seed=args.seed), dtype=np.float64)
            secs = time.time() - t0
        if args.merge or args.halves:
            img = 0.5 * (img0 + img1) if spp_each[0] == spp_each[1] else \
                (spp_each[0] * img0 + spp_each[1] * img1) / sum(spp_each)
            spp_total = int(sum(spp_each))
            secs = float(sum(secs_each))
            halves = gt_io.half_noise(img0, img1, out_dir / f"{mname}_mask.png", out_dir / f"{mname}_thin.png",
                                out_dir / away[0] if away else None)
            halves.update({"spp_each": spp_each, "seeds": seeds, "render_seconds_each": secs_each})
            cmdline_rec = " ; ".join(cmds)
        else:
            cmdline_rec = cmdline
        gt_io.write_exr_half_zip(out_dir / f"{scene_name}.exr", img)
        gt_io.write_png(out_dir / f"{scene_name}.png", gt_io.linear_to_srgb8(img))
        rec = {
            "scene": scene_name, "set": set_name, "mesh": mname, "medium_name": medname, "light_name": lname,
            "mesh_file": mesh["file"], "vertices": mesh["vertices"], "triangles": mesh["triangles"],
            "diagonal": mesh["diagonal"], "bbox_min": mesh["bbox_min"], "bbox_max": mesh["bbox_max"],
            "camera": {"eye": cam["eye"], "target": cam["target"], "up": cam["up"],
                       "fov_y_degrees": cam["fov_y_degrees"], "fov_axis": "y",
                       "framing": "bounding sphere (radius diagonal/2) fills the vertical fov with 5% margin"},
            "resolution": list(res),
            "light": point or {"type": "directional", "towards_light": towards.tolist(), "irradiance": irr,
                               "camera_dir": cfg["lights"][lname]["camera_dir"]},
            "medium": medium,
            **({"mm_per_unit": mmpu, "size_mm": mesh_cfg.get("size_mm"), "medium_per_mm": med_cfg,
                "medium_units": "per mesh unit (sigma_per_mm * mm_per_unit); Jensen et al. 2001 table 2: "
                                "sigma_s = reduced sigma_s' with g = 0",
                "sigma_t_times_diagonal": (np.add(medium["sigma_s"], medium["sigma_a"]) * mesh["diagonal"]).round(2).tolist()}
               if "sigma_s_prime_per_mm" in med_cfg else
               {"medium_per_diagonal": med_cfg, "medium_units": "per mesh unit (sigma_per_diagonal / diagonal)"}),
            "bsdf": {"type": "roughdielectric", "distribution": "ggx", "alpha": medium["roughness"] ** 2,
                     "int_ior": medium["ior"], "ext_ior": 1.0},
            "vertex_normals": "normalised sum of unnormalised face normals (area-weighted)",
            "integrator": {"type": "volpath", "max_depth": MAX_DEPTH, "rr_depth": 5},
            "reconstruction_filter": "box", "sampler": "independent",
            "spp": spp_total, "seed": seeds[0], "seeds": seeds, "max_depth": MAX_DEPTH,
            "render_seconds": round(secs, 2),
            "mitsuba_version": mi.__version__, "variant": mi.variant(),
            "command": cmdline_rec,
            "jade_render_args": jade_args(cam, res, towards, irr, point),
            "files": {"exr": f"{scene_name}.exr", "png": f"{scene_name}.png",
                      "mask": f"{mname}_mask.png", "thin": f"{mname}_thin.png"},
        }
        if away:
            rec["files"]["away"] = away[0]
            rec["away_definition"] = "object, not thin, n.l < -0.1 (n interpolated normal, l towards the light at p)"
        if halves is not None:
            rec["halves"] = halves
        with open(out_dir / f"{scene_name}.json", "w") as fh:
            json.dump(rec, fh, indent=2)
        nf = f", half-vs-half FLIP {halves['flip']:.4f} (masked {halves['flip_masked']:.4f})" if halves else ""
        print(f"[render] {scene_name}: {secs:.1f} s, spp {spp_total}{nf}, mean {img.mean(axis=(0, 1)).round(4).tolist()}",
              flush=True)


if __name__ == "__main__":
    main()
