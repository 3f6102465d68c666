#!/usr/bin/env python3
"""The README's contact sheet: path-traced | lambert | tm (poster) | default, per scene.

  build/samples/cli/jade fidelity --images IMAGES
  tools/groundtruth/.venv/bin/python tools/groundtruth/contact_sheet.py IMAGES --out docs/fidelity_contact.png

The peers' sheet (docs/peers.md): --columns reference,filament,filament-flat,default
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gt_io  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = ["bunny_jewel_front", "bunny_jewel_back", "camel_wax_back", "elephant_jade_back", "dragon_jewel_back",
          "head_skin1_back", "hand_skin1_back"]
COLUMNS = ["reference", "lambert", "tm", "default"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("images")
    ap.add_argument("--references", default=os.path.join(HERE, "references"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--columns", default=",".join(COLUMNS),
                    help="reference, then jade fidelity's modes (the SCENE__MODE.png of IMAGES)")
    a = ap.parse_args()
    rows = []
    for scene in a.scenes.split(","):
        tiles = []
        for col in a.columns.split(","):
            path = os.path.join(a.references, scene + ".png") if col == "reference" else \
                os.path.join(a.images, f"{scene}__{col}.png")
            tiles.append(gt_io.read_png(path)[:, :, :3])
        rows.append(np.concatenate(tiles, axis=1))
    sheet = np.concatenate(rows, axis=0)
    gt_io.write_png(a.out, sheet)
    print(f"wrote {a.out}: rows {a.scenes}; columns {a.columns}")


if __name__ == "__main__":
    main()
