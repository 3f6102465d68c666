#!/usr/bin/env python3
"""Geometry-convention check against Jade: renders each mesh with Jade's CLI
(lambert, opaque, black background) from the reference camera (the jade_render_args'
camera part, with a head light so every visible surface is lit) and compares Jade's
silhouette (any channel > 0) with Mitsuba's coverage mask <mesh>_mask.png.

  tools/groundtruth/.venv/bin/python tools/groundtruth/check_silhouette.py [--jade PATH] [--mesh NAME]

Writes references/silhouette_check.json (IoU per mesh, at Jade's --samples 1 and 4).
"""
import argparse
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
sys.path.insert(0, str(HERE))
import gt_io  # noqa: E402
import render_reference as rr  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--jade", default=str(REPO / "build/samples/cli/jade"))
    ap.add_argument("--mesh", action="append")
    ap.add_argument("--refs", default=str(HERE / "references"))
    args = ap.parse_args()
    cfg = json.load(open(HERE / "scenes.json"))
    res = cfg["resolution"]
    refs = Path(args.refs)
    work = rr.CACHE / "silhouette"
    work.mkdir(parents=True, exist_ok=True)
    out = {}
    for name in args.mesh or list(cfg["meshes"]):
        mcfg = cfg["meshes"][name]
        mesh = rr.load_mesh(name, mcfg)
        cam = rr.camera_for(mesh, mcfg, cfg)
        head = rr.normalize(np.array(cam["eye"]) - np.array(cam["target"]))
        jargs = rr.jade_args(cam, res, head, [1.0, 1.0, 1.0])
        mask_path = refs / f"{name}_mask.png"
        if not mask_path.exists():
            rr.masks_for(name, mesh, cam, res, refs, tau=float(cfg.get("thin_thickness_per_diagonal", 0.1)))
        mask = gt_io.read_mask(mask_path)
        out[name] = {}
        for samples in (1, 4):
            png = work / f"{name}_jade_s{samples}.png"
            cmd = [args.jade, "render", str(REPO / mcfg["file"]), "--mode", "lambert", "--material", "opaque",
                   "--samples", str(samples), "--out", str(png)] + jargs
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            img = gt_io.read_png(png)
            jm = img[:, :, :3].max(axis=2) > 0
            inter = int((jm & mask).sum())
            union = int((jm | mask).sum())
            iou = inter / union if union else 0.0
            # mirrored variants, to diagnose a flip if the IoU is low
            iou_fx = (jm[:, ::-1] & mask).sum() / max(1, (jm[:, ::-1] | mask).sum())
            iou_fy = (jm[::-1, :] & mask).sum() / max(1, (jm[::-1, :] | mask).sum())
            out[name][f"samples{samples}"] = {"iou": round(iou, 4), "jade_pixels": int(jm.sum()),
                                              "mitsuba_pixels": int(mask.sum()),
                                              "iou_if_flipped_x": round(float(iou_fx), 4),
                                              "iou_if_flipped_y": round(float(iou_fy), 4)}
            print(f"{name} samples {samples}: IoU {iou:.4f} (jade {int(jm.sum())} px, mitsuba {int(mask.sum())} px; "
                  f"flipped x {iou_fx:.3f}, y {iou_fy:.3f})", flush=True)
        out[name]["command"] = " ".join(cmd[:1] + ["render", mcfg["file"]] + cmd[3:])
    with open(refs / "silhouette_check.json", "w") as fh:
        json.dump(out, fh, indent=2)


if __name__ == "__main__":
    main()
