#!/usr/bin/env python3
"""Collects references/*.json into references/summary.json and prints a table:
render seconds (min / median / max / total), per-mesh mask pixel counts, and the mean
linear radiance over the thin mask (and over the object mask) of every scene.

  summarize.py [--refs DIR] [--set regimes]   (--set: only that set, into summary_<set>.json)
"""
import argparse
import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import gt_io  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--refs", default=str(HERE / "references"))
    ap.add_argument("--set", help="only this set's scenes (output summary_<set>.json)")
    a = ap.parse_args()
    refs = Path(a.refs)
    scenes = {}
    masks = {}
    for p in sorted(refs.glob("*.json")):
        if p.name.endswith("_masks.json"):
            d = json.load(open(p))
            masks[d["mesh"]] = {"object_pixels": d["object_pixels"], "thin_pixels": d["thin_pixels"],
                                "tau": d["thin_thickness_per_diagonal"], "rays": d["rays_per_pixel"],
                                "seconds": d["seconds"]}
            continue
        d = json.load(open(p))
        if "scene" not in d:
            continue
        lin = gt_io.read_exr_rgb(refs / d["files"]["exr"])
        obj = gt_io.read_mask(refs / d["files"]["mask"])
        thin = gt_io.read_mask(refs / d["files"]["thin"])
        away = gt_io.read_mask(refs / d["files"]["away"]) if "away" in d["files"] else None
        scenes[d["scene"]] = {
            "set": d["set"], "spp": d["spp"], "render_seconds": d["render_seconds"],
            "half_vs_half_flip": d.get("halves", {}).get("flip"),
            "half_vs_half_flip_masked": d.get("halves", {}).get("flip_masked"),
            "mean_linear_object": lin[obj].mean(axis=0).round(5).tolist(),
            "mean_linear_thin": lin[thin].mean(axis=0).round(5).tolist() if thin.any() else None,
            "thin_over_object": (lin[thin].mean(axis=0) / np.maximum(lin[obj].mean(axis=0), 1e-9)).round(3).tolist()
            if thin.any() else None,
        }
        if away is not None:
            scenes[d["scene"]]["mean_linear_away"] = lin[away].mean(axis=0).round(6).tolist() if away.any() else None
            scenes[d["scene"]]["away_pixels"] = int(away.sum())
            scenes[d["scene"]]["thin_pixels"] = int(thin.sum())
    if a.set:
        scenes = {k: v for k, v in scenes.items() if v["set"] == a.set}
    t = np.array([s["render_seconds"] for s in scenes.values()])
    out = {"scenes": scenes, "masks": masks,
           "render_seconds": {"count": int(len(t)), "min": float(t.min()), "median": float(np.median(t)),
                              "max": float(t.max()), "total": float(t.sum())} if len(t) else None}
    hf = [s["half_vs_half_flip"] for s in scenes.values() if s["half_vs_half_flip"] is not None]
    hm = [s["half_vs_half_flip_masked"] for s in scenes.values() if s["half_vs_half_flip_masked"] is not None]
    if hf:
        out["half_vs_half_flip"] = {"min": min(hf), "median": float(np.median(hf)), "max": max(hf),
                                    "masked_min": min(hm), "masked_median": float(np.median(hm)),
                                    "masked_max": max(hm)}
        print("half-vs-half FLIP", json.dumps(out["half_vs_half_flip"]))
    with open(refs / (f"summary_{a.set}.json" if a.set else "summary.json"), "w") as fh:
        json.dump(out, fh, indent=2)
    print(json.dumps(out["render_seconds"]))
    for m, d in masks.items():
        print(f"mask {m:9s} object {d['object_pixels']:6d} px  thin {d['thin_pixels']:5d} px")
    for n, s in scenes.items():
        away = f"  away {s['mean_linear_away']}" if "mean_linear_away" in s else ""
        print(f"{n:26s} {s['render_seconds']:6.1f} s  object {s['mean_linear_object']}  thin {s['mean_linear_thin']}{away}")


if __name__ == "__main__":
    main()
