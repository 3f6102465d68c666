#!/usr/bin/env python3
"""Contact sheet of the references: one row per (mesh, medium), columns = lights
(front, side, back), each tile downsampled 2x (box). Rows top to bottom in scenes.json
order of the set's meshes then media. A set that lists "scenes" (regimes): rows of 4 tiles in
the listed order.

  make_contact.py [--set train] [--out references/contact_train.png] [--scale 2]
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
    ap.add_argument("--set", default="train")
    ap.add_argument("--refs", default=str(HERE / "references"))
    ap.add_argument("--out")
    ap.add_argument("--scale", type=int, default=2)
    a = ap.parse_args()
    cfg = json.load(open(HERE / "scenes.json"))
    st = cfg["sets"][a.set]
    refs = Path(a.refs)
    k = a.scale
    if "scenes" in st:
        grid = [st["scenes"][i:i + 4] for i in range(0, len(st["scenes"]), 4)]
    else:
        grid = [[f"{m}_{med}_{l}" for l in st["lights"]] for m in st["meshes"] for med in st["media"]]
    rows = []
    for names in grid:
        tiles = []
        for name in names:
            lin = gt_io.read_exr_rgb(refs / f"{name}.exr")
            h, w, _ = lin.shape
            lin = lin[:h // k * k, :w // k * k].reshape(h // k, k, w // k, k, 3).mean(axis=(1, 3))
            t = gt_io.linear_to_srgb8(lin)
            t[:, -1] = 64  # thin grey separators
            t[-1, :] = 64
            tiles.append(t)
        while len(tiles) < len(grid[0]):
            tiles.append(np.full_like(tiles[0], 0))
        rows.append(np.hstack(tiles))
    order = [" ".join(r) for r in grid]
    sheet = np.vstack(rows)
    out = Path(a.out) if a.out else refs / f"contact_{a.set}.png"
    gt_io.write_png(out, sheet)
    print(f"{out}: {sheet.shape[1]}x{sheet.shape[0]}; rows {order}; columns {st.get('lights', 'listed')}")


if __name__ == "__main__":
    main()
