#!/usr/bin/env python3
"""Calibrates what Material::from_medium leaves free against the path-traced references.

Input: the separate terms of Jade's shading per training scene, written by
  build/samples/cli/jade fidelity --set train --components COMPONENTS [--fit SPREAD.json]
(the diffuse terms use the spread_strength of --fit; pass the same value as --spread-strength)
(diffuse with albedo R_d per strength, specular, transmission of weight 1 per lobe with
normal_mix 0 and 1). Jade's image is linear in the rest:
  image = albedo_scale * D_s + S + sum over parts p (ballistic b, diffused d) of
          w_p * ((1 - m) * T_{p,n,0} + m * T_{p,n,1})
Stage 1 fits albedo_scale and strength on the front- and side-lit scenes (where the
transmission lobe is zero or nearly so) by LDR FLIP inside the object mask (flip-evaluator on
sRGB). Stage 2, with stage 1's values, takes for each lobe n and normal_mix m the ballistic and
diffused weights that fit the back-lit scenes' thin-region and object means (least squares,
relative to the reference), and keeps the (n, m) whose solution has the lowest mean masked FLIP
on the side- and back-lit scenes plus --thin-weight times the mean relative error of the thin
region's radiance (the criterion the tests assert). With --criterion thin-band the
weights of each (n, m) are instead those that put the most training thin regions within 25 % of
the reference in every channel (the issue's acceptance band), the lowest FLIP + thin error among
them, and (n, m) is chosen by that count first. Writes the result as JSON (the values
from_medium's defaults take, docs/fidelity.md).

  tools/groundtruth/.venv/bin/python tools/groundtruth/fit.py COMPONENTS --out tools/groundtruth/fit_result.json
"""
import argparse
import glob
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gt_io  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def flip_masked(ref_srgb, test_linear, mask):
    import flip_evaluator as flip
    test = gt_io.linear_to_srgb(test_linear).astype(np.float32)
    emap, _, _ = flip.evaluate(ref_srgb, np.ascontiguousarray(test), "LDR", inputsRGB=True, applyMagma=False)
    emap = np.asarray(emap)
    if emap.ndim == 3:
        emap = emap[:, :, 0]
    return float(emap[mask].mean())


def load_scene(components, refs, name):
    rec = json.load(open(os.path.join(refs, name + ".json")))
    f = rec["files"]
    s = {"name": name, "light": rec["light_name"],
         "ref_srgb": np.ascontiguousarray(gt_io.read_png_rgb01(os.path.join(refs, f["png"])).astype(np.float32)),
         "ref_linear": gt_io.read_exr_rgb(os.path.join(refs, f["exr"])),
         "mask": gt_io.read_mask(os.path.join(refs, f["mask"])),
         "thin": gt_io.read_mask(os.path.join(refs, f["thin"])), "terms": {}}
    for path in glob.glob(os.path.join(components, name + "__*.exr")):
        term = os.path.basename(path)[len(name) + 2:-4]
        s["terms"][term] = gt_io.read_exr_rgb(path)
    return s


def thin_error(scene, image):
    if scene["light"] != "back" or not scene["thin"].any():
        return 0.0
    ref = scene["ref_linear"][scene["thin"]].mean(axis=0)
    got = image[scene["thin"]].mean(axis=0)
    return float(np.mean(np.abs(got - ref) / np.maximum(ref, 1e-3)))


def thin_ratio(scene, image):
    """The thin region's mean radiance per channel, relative to the reference's."""
    return image[scene["thin"]].mean(axis=0) / scene["ref_linear"][scene["thin"]].mean(axis=0)


def in_band(ratio):
    """Within 25 % of the reference in every channel: the acceptance band tests/test_fidelity.cpp asserts."""
    return bool(np.all(np.abs(ratio - 1) <= 0.25))


def stage2_weights(parts, wb_grid=np.linspace(0.0, 8.0, 161), fixed_wd=None):
    """Weights (w_b, w_d ≥ 0) of base + w_b·tb + w_d·td by least squares on the thin-region and object
    means, each channel relative to the reference; parts: (scene, base, tb, td) images. With fixed_wd,
    w_d is that (the derived 1) and only w_b is fitted."""
    rows, rhs = [], []
    for s, base, tb, td in parts:
        for region, weight in ((s["thin"], 1.0), (s["mask"], 0.5)):
            ref = s["ref_linear"][region].mean(axis=0)
            b = base[region].mean(axis=0)
            for c in range(3):
                k = weight / max(ref[c], 1e-3)
                rows.append([k * tb[region].mean(axis=0)[c], k * td[region].mean(axis=0)[c]])
                rhs.append(k * (ref[c] - b[c]))
    A, y = np.array(rows), np.array(rhs)
    best = None
    for wb in wb_grid:  # tiny NNLS: scan w_b, solve w_d ≥ 0 in closed form
        r = y - A[:, 0] * wb
        wd = fixed_wd if fixed_wd is not None else max(0.0, float(A[:, 1] @ r / max(A[:, 1] @ A[:, 1], 1e-30)))
        e = float(np.sum((r - A[:, 1] * wd) ** 2))
        if best is None or e < best[0]:
            best = (e, float(wb), wd)
    return best[1], best[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("components")
    ap.add_argument("--references", default=os.path.join(HERE, "references"))
    ap.add_argument("--out", default=os.path.join(HERE, "fit_result.json"))
    ap.add_argument("--thin-weight", type=float, default=0.1)
    ap.add_argument("--stage1", help="ALBEDO_SCALE,STRENGTH: skip stage 1 with these values")
    ap.add_argument("--criterion", choices=("least-squares", "thin-band"), default="least-squares",
                    help="stage 2's weights: most thin regions within 25 %% (then FLIP), or least squares of the means")
    ap.add_argument("--diffusion-weight", type=float, default=None,
                    help="keep w_d at this value (the derived 1: the dipole's own flux) and fit w_b alone; "
                         "without it both are fitted")
    ap.add_argument("--spread-strength", type=float, default=0.0,
                    help="the spread_strength the components were written with (jade fidelity --fit), recorded in the result")
    a = ap.parse_args()
    names = sorted({os.path.basename(p).split("__")[0] for p in glob.glob(os.path.join(a.components, "*__specular.exr"))})
    scenes = [load_scene(a.components, a.references, n) for n in names]
    if not scenes:
        sys.exit(f"fit.py: no components in {a.components} (run jade fidelity --set train --components DIR)")
    strengths = sorted({t[len("diffuse_s"):] for s in scenes for t in s["terms"] if t.startswith("diffuse_s")}, key=float)
    lobes = sorted({t.split("_")[2][1:] for s in scenes for t in s["terms"] if t.startswith("transmission_")}, key=float)
    t0 = time.time()

    # Stage 1: albedo_scale × strength on front and side light (no transmission).
    lit = [s for s in scenes if s["light"] in ("front", "side")]
    best1 = None
    if a.stage1:
        scale, st = float(a.stage1.split(",")[0]), a.stage1.split(",")[1]
        best1 = (float(np.mean([flip_masked(s["ref_srgb"], scale * s["terms"]["diffuse_s" + st] + s["terms"]["specular"],
                                            s["mask"]) for s in lit])), scale, st)
    else:
        for st in strengths:
            for scale in np.linspace(0.4, 1.0, 13):
                err = np.mean([flip_masked(s["ref_srgb"], scale * s["terms"]["diffuse_s" + st] + s["terms"]["specular"],
                                           s["mask"]) for s in lit])
                if best1 is None or err < best1[0]:
                    best1 = (float(err), float(scale), st)
    _, scale, st = best1
    print(f"stage 1: albedo_scale {scale:.3f}, strength {st}: mean masked FLIP {best1[0]:.4f} "
          f"over {len(lit)} front/side scenes ({time.time() - t0:.0f} s)", flush=True)

    # Stage 2: per lobe n and normal_mix m, the two transmission weights (ballistic w_b,
    # diffused w_d) by non-negative least squares on the back-lit scenes' thin-region mean and
    # object mean, each channel relative to the reference; then LDR FLIP of that solution on the
    # side- and back-lit scenes picks (n, m).
    behind = [s for s in scenes if s["light"] in ("side", "back")]
    back = [s for s in scenes if s["light"] == "back"]
    base = {s["name"]: scale * s["terms"]["diffuse_s" + st] + s["terms"]["specular"] for s in behind}

    def terms(s, n, m):
        t = lambda part, mm: s["terms"][f"transmission_{part}_n{n}_m{mm}"]
        return (1 - m) * t("b", 0) + m * t("b", 1), (1 - m) * t("d", 0) + m * t("d", 1)

    def weights(n, m):
        return stage2_weights([(s, base[s["name"]]) + terms(s, n, m) for s in back], fixed_wd=a.diffusion_weight)

    def image(s, n, m, wb, wd):
        tb, td = terms(s, n, m)
        return base[s["name"]] + wb * tb + wd * td

    def objective(n, m, wb, wd):
        errs, thin = [], []
        for s in behind:
            img = image(s, n, m, wb, wd)
            errs.append(flip_masked(s["ref_srgb"], img, s["mask"]))
            thin.append(thin_error(s, img))
        return float(np.mean(errs)) + a.thin_weight * float(np.mean(thin)), float(np.mean(errs))

    def band_weights(n, m):
        """(count, weights) of the weight pairs that put the most thin regions within 25 %."""
        # The thin-region ratios are linear in the weights: their parts once, then any weights.
        rel = [(thin_ratio(s, base[s["name"]]),) + tuple(thin_ratio(s, t) for t in terms(s, n, m)) for s in back]
        scored = []
        for wb in np.linspace(0.0, 1.5, 151):
            for wd in np.linspace(0.0, 0.3, 61):
                ratios = [b + wb * tb + wd * td for b, tb, td in rel]
                count = sum(in_band(r) for r in ratios)
                worst = max(float(np.max(np.abs(np.log(np.maximum(r, 1e-6))))) for r in ratios)
                scored.append((count, worst, float(wb), float(wd)))
        top = max(c for c, _, _, _ in scored)
        central = sorted((w, wb, wd) for c, w, wb, wd in scored if c == top)[:12]  # the most central in the band
        return top, [(wb, wd) for _, wb, wd in central]

    best2 = None  # (key, w_b, w_d, n, m, count, objective)
    for n in lobes:
        for m in (0.0, 0.25, 0.5, 0.75, 1.0):
            if a.criterion == "least-squares":
                candidates = [weights(n, m)]
                count = sum(in_band(thin_ratio(s, image(s, n, m, *candidates[0]))) for s in back)
            else:
                count, candidates = band_weights(n, m)
            best = None
            for wb, wd in candidates:
                err, flip_mean = objective(n, m, wb, wd)
                if best is None or err < best[0]:
                    best = (err, flip_mean, wb, wd)
            err, flip_mean, wb, wd = best
            print(f"  lobe {n}, normal_mix {m}: w_b {wb:.3f}, w_d {wd:.3f}: FLIP {flip_mean:.4f}, objective {err:.4f}, "
                  f"{count} training thin regions within 25 %", flush=True)
            key = (-count if a.criterion == "thin-band" else 0, err)
            if best2 is None or key < best2[0]:
                best2 = (key, wb, wd, n, m, count, err)
    _, w, wd, n, m, count, objective2 = best2
    print(f"stage 2 ({a.criterion}): transmission_weight {w:.3f}, diffusion_weight {wd:.3f}, lobe {n}, normal_mix {m}: "
          f"{count} of {len(back)} training thin regions within 25 %, objective {objective2:.4f} over {len(behind)} "
          f"side/back scenes ({time.time() - t0:.0f} s)")
    result = {"albedo_scale": scale, "strength": float(st), "spread_strength": a.spread_strength, "transmission_weight": w, "diffusion_weight": wd,
              "lobe": float(n), "normal_mix": m,
              "objective_stage1": best1[0], "objective_stage2": objective2, "thin_weight": a.thin_weight,
              "criterion": a.criterion, "training_thin_regions_within_25_percent": count,
              "training_scenes": names, "command": " ".join(sys.argv)}
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(result, f, indent=1)
    os.replace(tmp, a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
