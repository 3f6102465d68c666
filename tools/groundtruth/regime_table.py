#!/usr/bin/env python3
"""Mean masked LDR FLIP per regime and light, from `jade fidelity --json F`: the scenes grouped by
the medium's optical size, σ_t × the mesh's diagonal (the mean over R, G and B, from each
reference's record), training and validation apart from the held-out regimes. Prints Markdown
(docs/fidelity.md, *Regimes*); the lowest mean of each row in bold.

  build/samples/cli/jade fidelity --json /tmp/fidelity.json
  python3 tools/groundtruth/regime_table.py /tmp/fidelity.json
"""
import argparse
import collections
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
MODES = ["lambert", "tm", "default", "separable", "burley"]
REGIMES = ["20–60 (training)", "20–60 (validation)", "held out, < 200", "held out, 200–500", "held out, ≥ 500"]
LIGHTS = [("front", "front"), ("side", "side"), ("back", "back"), ("backpoint", "back, point")]


def regime(record, scene_set):
    """The scene's row group: its set for the committed scenes, its σ_t × diagonal bin if held out."""
    if scene_set != "regimes":
        return f"20–60 ({'training' if scene_set == 'train' else scene_set})"
    m = record["medium"]
    optical = sum(s + a for s, a in zip(m["sigma_s"], m["sigma_a"])) / 3.0 * record["diagonal"]
    return "held out, < 200" if optical < 200 else ("held out, 200–500" if optical < 500 else "held out, ≥ 500")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("fidelity_json", help="the output of jade fidelity --json")
    ap.add_argument("--references", default=str(HERE / "references"))
    a = ap.parse_args()
    refs = Path(a.references)
    groups = collections.defaultdict(list)
    for s in json.load(open(a.fidelity_json))["scenes"]:
        groups[(regime(json.load(open(refs / f"{s['scene']}.json")), s["set"]), s["light"])].append(s)
    print("| σ_t × diagonal | light | scenes | " + " | ".join(MODES) + " | default nearer than Lambert |")
    print("|---|---|---|" + "---|" * len(MODES) + "---|")
    for key in REGIMES:
        for light, label in LIGHTS:
            scenes = groups.get((key, light))
            if not scenes:
                continue
            means = {m: sum(s[m]["flip_masked"] for s in scenes) / len(scenes) for m in MODES}
            best = min(means.values())
            cells = [f"**{means[m]:.3f}**" if means[m] == best else f"{means[m]:.3f}" for m in MODES]
            nearer = sum(s["default"]["flip_masked"] < s["lambert"]["flip_masked"] for s in scenes)
            print(f"| {key} | {label} | {len(scenes)} | " + " | ".join(cells) + f" | {nearer} of {len(scenes)} |")


if __name__ == "__main__":
    main()
