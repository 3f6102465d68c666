#!/usr/bin/env python3
"""Compare a test image with a reference.

  compare.py REF TEST [--mask M.png] [--region THIN.png] [--json OUT] [--ppd PPD]

REF / TEST: .png (sRGB 8 bit) or .exr (linear). Metrics:
  flip, flip_masked      LDR FLIP (flip-evaluator) on the sRGB images (an .exr is encoded to
                         sRGB first: clamp [0,1], IEC 61966-2-1, no tone map), default 67 ppd;
                         masked = mean of the FLIP error map inside --mask
  rmse, psnr (+ _masked) in sRGB [0,1], over all channels
  region_mean_linear     mean LINEAR radiance per channel over --region for ref and test
                         (from the .exr when given one, or when an .exr sits next to the .png;
                         otherwise the sRGB values are decoded), and test/ref ratio
Importable: compare_images(ref_path, test_path, mask=None, region=None) -> dict
"""
import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import gt_io  # noqa: E402


def _load(path):
    """(srgb01 HxWx3, linear HxWx3, linear_source)"""
    p = Path(path)
    if p.suffix.lower() == ".exr":
        lin = gt_io.read_exr_rgb(p)
        return gt_io.linear_to_srgb(lin), lin, str(p)
    srgb = gt_io.read_png_rgb01(p)
    exr = p.with_suffix(".exr")
    if exr.exists():
        return srgb, gt_io.read_exr_rgb(exr), str(exr)
    return srgb, gt_io.srgb_to_linear(srgb), "srgb-decoded " + str(p)


def _mask(m):
    if m is None:
        return None
    if isinstance(m, np.ndarray):
        return m.astype(bool)
    return gt_io.read_mask(m)


def _rmse_psnr(a, b, m=None):
    d = (a - b) ** 2
    if m is not None:
        if not m.any():
            return None, None
        d = d[m]
    mse = float(d.mean())
    rmse = math.sqrt(mse)
    psnr = float("inf") if mse == 0 else 10.0 * math.log10(1.0 / mse)
    return rmse, psnr


def compare_images(ref_path, test_path, mask=None, region=None, ppd=None):
    import flip_evaluator as flip
    ref_s, ref_l, ref_src = _load(ref_path)
    tst_s, tst_l, tst_src = _load(test_path)
    if ref_s.shape != tst_s.shape:
        raise ValueError(f"size mismatch: {ref_s.shape} vs {tst_s.shape}")
    m = _mask(mask)
    r = _mask(region)
    params = {} if ppd is None else {"ppd": float(ppd)}
    emap, flip_mean, used = flip.evaluate(np.ascontiguousarray(ref_s, dtype=np.float32),
                                          np.ascontiguousarray(tst_s, dtype=np.float32),
                                          "LDR", inputsRGB=True, applyMagma=False, parameters=params)
    emap = np.asarray(emap)
    if emap.ndim == 3:
        emap = emap[:, :, 0]
    out = {"reference": str(ref_path), "test": str(test_path),
           "mask": None if mask is None or isinstance(mask, np.ndarray) else str(mask),
           "region": None if region is None or isinstance(region, np.ndarray) else str(region),
           "flip": float(flip_mean), "ppd": float(used.get("ppd", 67.0)) if isinstance(used, dict) else None}
    out["rmse"], out["psnr"] = _rmse_psnr(ref_s, tst_s)
    if m is not None:
        out["mask_pixels"] = int(m.sum())
        out["flip_masked"] = float(emap[m].mean()) if m.any() else None
        out["rmse_masked"], out["psnr_masked"] = _rmse_psnr(ref_s, tst_s, m)
    if r is not None:
        out["region_pixels"] = int(r.sum())
        if r.any():
            rm = ref_l[r].mean(axis=0)
            tm = tst_l[r].mean(axis=0)
            out["region_mean_linear"] = {"ref": rm.tolist(), "test": tm.tolist(),
                                         "ratio_test_over_ref": [float(t / x) if x > 0 else None
                                                                 for t, x in zip(tm, rm)],
                                         "ref_source": ref_src, "test_source": tst_src}
            out["flip_region"] = float(emap[r].mean())
    return out


def summary_line(d):
    s = f"FLIP {d['flip']:.4f}  RMSE {d['rmse']:.4f}  PSNR {d['psnr']:.2f} dB"
    if "flip_masked" in d and d["flip_masked"] is not None:
        s += f" | masked({d['mask_pixels']} px) FLIP {d['flip_masked']:.4f} RMSE {d['rmse_masked']:.4f} PSNR {d['psnr_masked']:.2f} dB"
    if "region_mean_linear" in d:
        rm = d["region_mean_linear"]
        s += (f" | region({d['region_pixels']} px) ref [{', '.join(f'{x:.4f}' for x in rm['ref'])}]"
              f" test [{', '.join(f'{x:.4f}' for x in rm['test'])}]")
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("ref")
    ap.add_argument("test")
    ap.add_argument("--mask")
    ap.add_argument("--region")
    ap.add_argument("--json")
    ap.add_argument("--ppd", type=float, default=None, help="FLIP pixels per degree (default 67)")
    a = ap.parse_args()
    d = compare_images(a.ref, a.test, a.mask, a.region, ppd=a.ppd)
    print(summary_line(d))
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(d, fh, indent=2)


if __name__ == "__main__":
    main()
