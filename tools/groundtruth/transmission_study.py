#!/usr/bin/env python3
"""Studies of Jade's transmission term against the path tracer (docs/fidelity.md, "Studied, not adopted").

Jade's transmitted light leaves in a lobe (n+1)/(2π)·max(V·(−L), 0)^n about the light's own
direction, attenuated by a forward part and a diffused part (the diffusion approximation's slab
transmittance). Three measurements:

  slab    Mitsuba renders a slab of optical thickness τ behind the references' rough dielectric
          (GGX α 0.36, IOR 1.5), lit along its normal, seen from 0…60° off that axis: the
          physical exit lobe of a part whose faces are parallel.
  axes    On the committed back-lit references, the lobe about other axes, the weights refitted
          as fit.py's stage 2 does: `axis` (−L, Jade's), `prism` (−L refracted in through the
          entry surface, Mitsuba's ray cast from each pixel towards the light, and out through
          the pixel's normal), `exit` (refracted out only), `strict` (`prism`, but no light where a
          refraction is total; `prism` falls back to −L there), `blend B` (−L moved B of the way to
          `prism`). Needs the lobe-free terms of
            build/samples/cli/jade fidelity --scene _back --components DIR --strengths 0.3 --lobes 0
  scattered  The diffused part replaced by the scattered transmittance of a slab of the same
          reduced optical thickness and albedo, by Monte Carlo (slab_scattering.py), leaving
          as a cosine (1/π) or in a lobe; per pixel from the shading inputs (position, normal,
          path t) that the same --components run writes.
  cone    The forward part's attenuation averaged over lines in a cone about the light (through
          air gaps, floored at the local thickness, Mitsuba's ray casts) instead of Jade's one
          line along it. Needs the components of lobe 16 and the shading inputs:
            build/samples/cli/jade fidelity --scene _back --components DIR --strengths 0.3 --lobes 16

  tools/groundtruth/.venv/bin/python tools/groundtruth/transmission_study.py slab --tau 0.9,1.8,3.6
  tools/groundtruth/.venv/bin/python tools/groundtruth/transmission_study.py axes DIR
  tools/groundtruth/.venv/bin/python tools/groundtruth/transmission_study.py scattered DIR
  tools/groundtruth/.venv/bin/python tools/groundtruth/transmission_study.py cone DIR --angles 0,20,40
"""
import argparse
import glob
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fit  # noqa: E402
import gt_io  # noqa: E402
import render_reference as rr  # noqa: E402
import slab_scattering  # noqa: E402

mi = rr.mi
CFG = json.load(open(os.path.join(HERE, "scenes.json")))
ALBEDO_SCALE = json.load(open(os.path.join(HERE, "fit_result.json")))["albedo_scale"]  # MediumFit's
ANGLES = (0, 10, 20, 30, 45, 60)


def slab_radiance(tau, albedo, g, degrees, spp=4096, alpha=0.36, ior=1.5):
    """Mean radiance seen `degrees` off the normal of a slab 1 unit thick, lit from behind along it (E = 1)."""
    th = np.radians(degrees)
    T = mi.ScalarTransform4f
    scene = mi.load_dict({
        "type": "scene", "integrator": {"type": "volpath", "max_depth": 256},
        "sensor": {"type": "perspective", "fov": 0.5,
                   "to_world": T().look_at(origin=[10 * np.sin(th), 0, 10 * np.cos(th)], target=[0, 0, 0], up=[0, 1, 0]),
                   "film": {"type": "hdrfilm", "width": 4, "height": 4, "pixel_format": "rgb", "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent", "sample_count": spp}},
        "slab": {"type": "cube", "to_world": T().scale([200, 200, 0.5]),
                 "bsdf": {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha, "int_ior": ior, "ext_ior": 1.0},
                 "interior": {"type": "homogeneous", "sigma_t": {"type": "srgb", "color": [tau] * 3, "unbounded": True},
                              "albedo": rr.rgb(albedo), "scale": 1.0, "phase": {"type": "hg", "g": g}}},
        "light": {"type": "directional", "direction": [0, 0, 1], "irradiance": rr.rgb([1, 1, 1])}})
    return np.array(mi.render(scene)).reshape(-1, 3).mean(0)


def geometry(mesh_name):
    """Per pixel of the back-lit view: position, normal, and the normal where the light enters (0: none)."""
    cache = os.path.join(HERE, ".cache", f"{mesh_name}_lobe_geometry.npz")
    if os.path.exists(cache):
        return np.load(cache)
    mc = CFG["meshes"][mesh_name]
    mesh = rr.load_mesh(mesh_name, mc)
    cam = rr.camera_for(mesh, mc, CFG)
    towards, _ = rr.light_world(CFG["lights"]["back"], cam)
    W, H = CFG["resolution"]
    scene = rr.build_scene(mesh, cam, (W, H))
    sensor, sign = scene.sensors()[0], mesh["outward_sign"]
    P, N, NE = np.zeros((H, W, 3)), np.zeros((H, W, 3)), np.zeros((H, W, 3))
    for y in range(H):
        for x in range(W):
            ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f((x + .5) / W, (y + .5) / H), mi.Point2f(.5))
            si = scene.ray_intersect(ray)
            if not si.is_valid():
                continue
            P[y, x] = [si.p[i] for i in range(3)]
            N[y, x] = [sign * si.sh_frame.n[i] for i in range(3)]
            o = P[y, x] - rr.THIN_OFFSET_PER_DIAGONAL * mesh["diagonal"] * N[y, x]
            entry = scene.ray_intersect(mi.Ray3f(mi.Point3f(*o), mi.Vector3f(*towards)))
            if entry.is_valid():
                NE[y, x] = [sign * entry.sh_frame.n[i] for i in range(3)]
    os.makedirs(os.path.dirname(cache), exist_ok=True)
    np.savez(cache, P=P, N=N, NE=NE, towards=towards, eye=np.array(cam["eye"]))
    return np.load(cache)


def unit(v):
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-12)


def refract(i, n, eta):
    """GLSL refract(): i and n unit, n against i; second result False on total internal reflection."""
    c = -np.sum(i * n, -1, keepdims=True)
    k = 1 - eta * eta * (1 - c * c)
    return unit(eta * i + (eta * c - np.sqrt(np.maximum(k, 0))) * n), k[..., 0] > 0


def lobe_cosine(scene, kind, blend):
    g = geometry(scene["name"].split("_")[0])
    ior = CFG["media"][scene["name"].split("_")[1]]["ior"]
    v = unit(g["eye"] - g["P"])
    i = -g["towards"] * np.ones_like(v)
    if kind == "axis":
        d = i
    elif kind == "exit":
        d, ok = refract(i, -g["N"], ior)
        d = np.where(ok[..., None], d, i)
    else:
        inside, ok_in = refract(i, g["NE"], 1 / ior)
        out, ok_out = refract(inside, -g["N"], ior)
        ok = ok_in & ok_out & (np.abs(g["NE"]).sum(-1) > 0)
        if kind == "strict":  # no light where either refraction is total or no entry was found
            return np.where(ok, np.maximum(np.sum(v * out, -1), 0), 0)
        d = np.where(ok[..., None], out, i) if kind == "prism" else unit(np.where(ok[..., None], i + blend * (out - i), i))
    return np.maximum(np.sum(v * d, -1), 0)


def study(scenes, kind, n, blend=0.0, normal_mix=0.25):
    parts = []
    for s in scenes:
        lobe = ((n + 1) * lobe_cosine(s, kind, blend) ** n)[..., None]  # the n = 0 terms carry 1/(2π)
        tb = ((1 - normal_mix) * s["terms"]["transmission_b_n0_m0"] + normal_mix * s["terms"]["transmission_b_n0_m1"]) * lobe
        td = ((1 - normal_mix) * s["terms"]["transmission_d_n0_m0"] + normal_mix * s["terms"]["transmission_d_n0_m1"]) * lobe
        parts.append((s, ALBEDO_SCALE * s["terms"]["diffuse_s0.3"] + s["terms"]["specular"], tb, td))
    label = f"{kind} {blend:g}" if kind == "blend" else kind
    report(parts, f"{label}, n {n:g}")


def report(parts, label):
    """Fits w_b, w_2 of base + w_b·part_b + w_2·part_2 as fit.py's stage 2 does; prints FLIP and thin regions."""
    wb, wd = fit.stage2_weights(parts, np.linspace(0, 3, 301))
    flips, within = [], 0
    for s, base, tb, td in parts:
        img = base + wb * tb + wd * td
        flips.append(fit.flip_masked(s["ref_srgb"], img, s["mask"]))
        within += fit.in_band(fit.thin_ratio(s, img))
    print(f"{label:34s} w_b {wb:.3f} w_2 {wd:.3f}  back-lit mean masked FLIP {np.mean(flips):.4f}, "
          f"thin regions within 25 % {within}/{len(parts)}", flush=True)


def read_rgba(path):
    import OpenEXR
    with OpenEXR.File(path) as f:
        return np.asarray(f.channels()["RGBA"].pixels, dtype=np.float64)


def shading_inputs(s, components, normal_mix):
    """Per pixel of a back-lit scene, from the shading inputs of `jade fidelity --components`: the
    medium record, the light's geometry factor times its irradiance (both crossings of the boundary and
    the normal mix), V·(−L) and Jade's path t."""
    rec = json.load(open(os.path.join(HERE, "references", s["name"] + ".json")))
    med = rec["medium"]
    pos = read_rgba(os.path.join(components, s["name"] + "__inputs_position.exr"))
    npath = read_rgba(os.path.join(components, s["name"] + "__inputs_normal_path.exr"))
    v = unit(np.array(rec["camera"]["eye"]) - pos[..., :3])
    nrm = unit(npath[..., :3])
    towards = np.array(rec["light"]["towards_light"])
    f0 = ((med["ior"] - 1) / (med["ior"] + 1)) ** 2
    grazing = max(1 - med["roughness"] ** 2, f0)  # shading.glsl's boundary_transmittance

    def crossing(c):
        return 1 - (f0 + (grazing - f0) * (1 - np.clip(c, 0, 1)) ** 5)

    n_dot_l = np.sum(nrm * towards, -1)
    geometry_factor = ((1 - normal_mix) + normal_mix * np.maximum(-n_dot_l, 0)) * crossing(-n_dot_l) * \
        crossing(np.sum(nrm * v, -1)) * (pos[..., 3] > 0.5)
    c = geometry_factor[..., None] * np.array(rec["light"]["irradiance"])
    return med, c, np.maximum(-np.sum(v * towards, -1), 0), npath[..., 3:4]


def lobe(mu, n):
    return ((n + 1) / (2 * np.pi) * mu ** n)[..., None]


def base_image(s):
    return ALBEDO_SCALE * s["terms"]["diffuse_s0.3"] + s["terms"]["specular"]


def scattered_study(scenes, components, taus, hists, n, k, exit_lobe, normal_mix=0.25):
    """Forward part e^{−kσ_t t}·lobe_n plus the Monte Carlo slab's scattered transmittance at the
    same reduced optical thickness and albedo, leaving as a cosine (exit_lobe None) or in a lobe."""
    parts = []
    for s in scenes:
        med, c, mu, t = shading_inputs(s, components, normal_mix)
        ss, sa, g = np.array(med["sigma_s"]), np.array(med["sigma_a"]), med["g"]
        reduced_s = ss * (1 - g)
        forward = c * lobe(mu, n) * np.exp(-k * (ss + sa) * t)
        tau = (reduced_s + sa) * t
        scattered = slab_scattering.scattered_transmittance(taus, hists, tau, reduced_s / (reduced_s + sa))
        scattered = c * scattered * (1 / np.pi if exit_lobe is None else lobe(mu, exit_lobe))
        parts.append((s, base_image(s), forward, scattered))
    report(parts, f"k {k:g}, n {n:g}, scattered {'cosine' if exit_lobe is None else f'lobe {exit_lobe:g}'}")


def cone_paths(s, components, rays, half_angle):
    """Per covered pixel (row-major index into the image): the medium's share of `rays` lines in the
    cone of `half_angle` degrees about the light (air gaps left out, as Jade's light-depth layers do),
    floored at the pixel's inward-cone thickness (32 rays in the 60° cone about −n). Surface points
    and normals come from Mitsuba's primary rays: the components' EXRs are half floats, too coarse
    on the dragon (~170 units across). Ray casts by Mitsuba's vectorised LLVM variant."""
    rec = json.load(open(os.path.join(HERE, "references", s["name"] + ".json")))
    covered = read_rgba(os.path.join(components, s["name"] + "__inputs_position.exr"))[..., 3] > 0.5
    mesh = rr.load_mesh(rec["mesh"], CFG["meshes"][rec["mesh"]])
    scene = mi.load_dict({"type": "scene", "o": {"type": "ply", "filename": str(mesh["ply"]), "face_normals": False}})

    def cast(o, d):
        ray = mi.Ray3f(mi.Point3f(*[mi.Float(o[:, i].astype(np.float32)) for i in range(3)]),
                       mi.Vector3f(*[mi.Float(np.ascontiguousarray(d[:, i]).astype(np.float32)) for i in range(3)]))
        si = scene.ray_intersect(ray)
        return si, np.array(si.is_valid()), np.where(np.array(si.is_valid()), np.array(si.t), 0.0)

    idx = np.flatnonzero(covered.ravel())
    cam = rec["camera"]
    H, W = covered.shape
    eye = np.array(cam["eye"])
    f = unit(np.array(cam["target"]) - eye)
    r = unit(np.cross(f, cam["up"]))
    u = np.cross(r, f)
    th = np.tan(np.radians(cam["fov_y_degrees"]) / 2)
    y, x = np.divmod(idx, W)
    d = unit(f + (((x + 0.5) / W * 2 - 1) * th * W / H)[:, None] * r + ((1 - (y + 0.5) / H * 2) * th)[:, None] * u)
    si, hit, _ = cast(np.broadcast_to(eye, d.shape), d)
    P = np.stack([np.array(si.p[i]) for i in range(3)], 1)
    N = mesh["outward_sign"] * np.stack([np.array(si.sh_frame.n[i]) for i in range(3)], 1)
    keep = hit
    idx, P, N = idx[keep], P[keep], N[keep]
    origin = P - rr.THIN_OFFSET_PER_DIAGONAL * mesh["diagonal"] * N

    def cone(axis, n, degrees):  # uniform in solid angle, Hammersley; axis (m, 3)
        u1, u2 = rr.hammersley_cone(n, degrees)
        ct = 1 - u1 * (1 - np.cos(np.radians(degrees)))
        st, ph = np.sqrt(1 - ct * ct), 2 * np.pi * u2
        t = unit(np.cross(axis, np.where(np.abs(axis[:, 1:2]) < 0.9, [[0.0, 1, 0]], [[1.0, 0, 0]])))
        b = np.cross(axis, t)
        return [st[k] * np.cos(ph[k]) * t + st[k] * np.sin(ph[k]) * b + ct[k] * axis for k in range(n)]

    thickness = np.zeros(len(idx))
    count = np.zeros(len(idx))
    for dk in cone(-N, 32, 60):
        _, v, t = cast(origin, dk)
        thickness += t
        count += v
    thickness /= np.maximum(count, 1)
    towards = np.broadcast_to(np.array(rec["light"]["towards_light"]), N.shape)
    eps = 2 * rr.THIN_OFFSET_PER_DIAGONAL * mesh["diagonal"]
    paths = np.zeros((len(idx), rays))
    for k, dk in enumerate(cone(towards, rays, half_angle)):
        o, inside, alive = origin.copy(), np.ones(len(idx), bool), np.ones(len(idx), bool)
        for _ in range(8):  # in and out of the medium: up to four parts along the line
            _, v, t = cast(o, dk)
            paths[:, k] += np.where(alive & inside & v, t, 0.0)
            alive &= v
            o = o + (t + eps)[:, None] * dk
            inside = ~inside
    return idx, np.maximum(paths, thickness[:, None])


def cone_study(scenes, components, half_angle, rays=16, n=16, k=0.7, normal_mix=0.25):
    """The forward part's attenuation averaged over the lines in a cone about the light (light
    scattered through small angles comes along them too) instead of Jade's one line; the diffused
    part as Jade computes it (the components of lobe n)."""
    parts = []
    for s in scenes:
        med, c, mu, t = shading_inputs(s, components, normal_mix)
        sigma_t = np.array(med["sigma_s"]) + np.array(med["sigma_a"])
        if half_angle < 0:  # Jade's own path, for reference
            attenuation = np.exp(-k * sigma_t * t)
        else:
            idx, paths = cone_paths(s, components, rays, half_angle)
            attenuation = np.zeros(t.shape[:2] + (3,))
            attenuation.reshape(-1, 3)[idx] = np.exp(-k * sigma_t * paths[..., None]).mean(1)
        terms = s["terms"]
        diffused = (1 - normal_mix) * terms[f"transmission_d_n{n}_m0"] + normal_mix * terms[f"transmission_d_n{n}_m1"]
        parts.append((s, base_image(s), c * lobe(mu, n) * attenuation, diffused))
    report(parts, "Jade's path" if half_angle < 0 else f"cone {half_angle:g}°, {rays} lines")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="what", required=True)
    sl = sub.add_parser("slab")
    sl.add_argument("--tau", default="0.9,1.8,3.6")
    sl.add_argument("--albedo", default="0.6,0.75,0.98", help="single-scattering albedo per channel (the jewel's)")
    sl.add_argument("--g", type=float, default=0.0)
    sc = sub.add_parser("axes")
    sc.add_argument("components")
    sc.add_argument("--lobes", default="4,8,16,32")
    sub.add_parser("scattered").add_argument("components")
    co = sub.add_parser("cone")
    co.add_argument("components")
    co.add_argument("--angles", default="0,20,40", help="half-angles of the cone, degrees")
    a = ap.parse_args()
    if a.what == "slab":
        albedo = [float(x) for x in a.albedo.split(",")]
        print("radiance (R G B) off the slab's normal, E = 1; in brackets L(θ)/L(0) in green, then cos^16")
        for tau in (float(t) for t in a.tau.split(",")):
            l0 = None
            for deg in ANGLES:
                L = slab_radiance(tau, albedo, a.g, deg)
                l0 = L if l0 is None else l0
                print(f"  τ {tau:4.2f}  {deg:2d}°: {L[0]:.4f} {L[1]:.4f} {L[2]:.4f}  "
                      f"[{L[1] / l0[1]:.3f}, {np.cos(np.radians(deg)) ** 16:.3f}]", flush=True)
        return
    refs = os.path.join(HERE, "references")
    pattern = "*_back__specular.exr" if a.what == "axes" else "*_back__inputs_position.exr"
    names = sorted(os.path.basename(p).split("__")[0] for p in glob.glob(os.path.join(a.components, pattern)))
    if not names:
        sys.exit(f"transmission_study.py: no back-lit components in {a.components} (see --help)")
    scenes = [fit.load_scene(a.components, refs, n) for n in names]
    if a.what == "scattered":
        taus, hists = slab_scattering.table()
        for k in (0.7, 1.0):
            for n in (8, 16):
                for exit_lobe in (None, 4, 16):
                    scattered_study(scenes, a.components, taus, hists, n, k, exit_lobe)
        return
    if a.what == "cone":
        for llvm in sorted(glob.glob("/usr/lib/x86_64-linux-gnu/libLLVM-1[4-9].so*"))[-1:]:  # Debian's
            os.environ.setdefault("DRJIT_LIBLLVM_PATH", llvm)
        mi.set_variant("llvm_ad_rgb")  # vectorised ray casts
        cone_study(scenes, a.components, -1)
        for angle in (float(x) for x in a.angles.split(",")):
            cone_study(scenes, a.components, angle)
        return
    lobes = [float(x) for x in a.lobes.split(",")]
    for kind in ("axis", "exit", "prism", "strict"):
        for n in lobes:
            study(scenes, kind, n)
    for blend in (0.2, 0.4):
        for n in (8, 16):
            study(scenes, "blend", n, blend)


if __name__ == "__main__":
    main()
