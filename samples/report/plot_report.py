#!/usr/bin/env python3
"""Plots of `jade report`: error against cost, log-log, Pareto front marked.

usage: python3 samples/report/plot_report.py DIR

Reads DIR/report.csv (written by `jade report MESH... --out DIR`) and writes into DIR:
  ao.png       AO: RMS error (vs the 4096-ray low-discrepancy GPU AO) against GPU time,
               per mesh; one line per sampling and max distance, labels = rays per vertex
  tm.png       t_m: max relative error (vs float64) against GPU time, per mesh; one line per
               material through the clustered eps, the exact pass and the auto presets
  presets.png  today's presets end to end: t_m max relative error and final-image error
               (99th percentile, 8-bit sRGB levels) against the bake's GPU time
  lut.png      translucency LUT: error of f and of the final image against the LUT's memory
  deform.png   deforming mesh: AO RMS and t_m RMS error of refit and amortised re-bakes
               (vs a from-scratch bake of each frame) against the GPU time per frame
The Pareto front (no other configuration both cheaper and more accurate) uses the same axes
and groups as summary.md: ringed in black. Files are written atomically (temp + rename).
Needs matplotlib: installed on first use (apt-get python3-matplotlib on Debian/Ubuntu when
root, else pip --user), or run the script with a python3 that has it.
"""
import csv
import math
import os
import re
import shutil
import subprocess
import sys
from collections import OrderedDict, defaultdict

SYSTEM_PYTHON = "/usr/bin/python3"


def have_matplotlib(python):
    return subprocess.call([python, "-c", "import matplotlib"], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL) == 0


def ensure_matplotlib():
    """Import matplotlib, installing it if needed; may re-run this script under /usr/bin/python3."""
    try:
        import matplotlib  # noqa: F401
        return
    except ImportError:
        pass
    reexec = os.path.exists(SYSTEM_PYTHON) and os.path.realpath(sys.executable) != os.path.realpath(SYSTEM_PYTHON)
    if reexec and have_matplotlib(SYSTEM_PYTHON):
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON] + sys.argv)
    if shutil.which("apt-get") and os.path.exists(SYSTEM_PYTHON) and hasattr(os, "geteuid") and os.geteuid() == 0:
        print("plot_report: installing python3-matplotlib with apt-get", file=sys.stderr)
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        cmd = ["apt-get", "install", "-y", "-q", "python3-matplotlib"]
        if subprocess.call(cmd, env=env) != 0:
            subprocess.call(["apt-get", "update", "-q"], env=env)
            subprocess.call(cmd, env=env)
        if have_matplotlib(SYSTEM_PYTHON):
            if reexec:
                os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON] + sys.argv)
            return
    print("plot_report: installing matplotlib with pip --user", file=sys.stderr)
    if subprocess.call([sys.executable, "-m", "pip", "install", "--user", "-q", "matplotlib"]) == 0:
        import site
        import importlib
        sys.path.append(site.getusersitepackages())
        importlib.invalidate_caches()
        return
    sys.exit("plot_report: matplotlib is missing and could not be installed; "
             "install python3-matplotlib (apt) or matplotlib (pip) and run again")


def number(s):
    try:
        return float(s)
    except ValueError:
        return math.nan


def split_method(method):
    m = re.match(r"^(.*) \((.*)\)$", method)
    return (m.group(1), m.group(2)) if m else (method, "")


def texels(value):
    m = re.match(r"^(\d+)x(\d+)$", value)
    return float(m.group(1)) * float(m.group(2)) if m else math.nan


def is_square_lut(value):
    m = re.match(r"^(\d+)x(\d+)$", value)
    return bool(m) and int(m.group(1)) == int(m.group(2)) + 1


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("gpu_ms", "wall_ms", "err_rms", "err_p99", "err_max"):
            r[k] = number(r[k])
        r["algorithm"], r["case"] = split_method(r["method"])
    return rows


def axes_of(r):
    """(group, x, y) of the Pareto front, as in summary.md; None for rows without one."""
    knob = r["knob"]
    if knob == "ao_rays":
        return (r["mesh"] + "|ao|" + r["case"], r["gpu_ms"], r["err_rms"])
    if knob in ("tm_exact", "tm_epsilon", "tm_auto"):
        return (r["mesh"] + "|tm|" + r["case"], r["gpu_ms"], r["err_max"])
    if knob == "quality":
        return (r["mesh"] + "|quality", r["gpu_ms"], r["err_max"])
    if knob in ("lut_size", "image_lut"):
        return (r["mesh"] + "|" + knob, texels(r["value"]), r["err_max"])
    if knob in ("deform_ao", "deform_tm"):
        return (r["mesh"] + "|" + knob, r["gpu_ms"], r["err_rms"])
    return None


def mark_pareto(rows):
    pts = [axes_of(r) for r in rows]
    for i, r in enumerate(rows):
        a = pts[i]
        r["pareto"] = bool(a) and not (math.isnan(a[1]) or math.isnan(a[2])) and not any(
            b and j != i and b[0] == a[0] and b[1] <= a[1] and b[2] <= a[2] and (b[1] < a[1] or b[2] < a[2])
            for j, b in enumerate(pts))


def positive(x):
    return x if x > 0 and not math.isnan(x) else math.nan


class Plotter:
    def __init__(self, rows, out):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        self.plt, self.rows, self.out = plt, rows, out
        self.meshes = list(OrderedDict.fromkeys(r["mesh"] for r in rows if r["mesh"] != "(any)"))

    def figure(self, ncols, title):
        fig, axes = self.plt.subplots(1, max(ncols, 1), figsize=(5.2 * max(ncols, 1) + 0.6, 4.6), squeeze=False)
        fig.suptitle(title, fontsize=11)
        return fig, axes[0]

    def save(self, fig, name):
        fig.tight_layout()
        path = os.path.join(self.out, name)
        tmp = path + ".tmp"
        fig.savefig(tmp, dpi=90, format="png")
        self.plt.close(fig)
        os.replace(tmp, path)
        print("plot_report: wrote %s (%d KB)" % (path, os.path.getsize(path) // 1024), file=sys.stderr)

    def series(self, ax, pts, label, color, marker, x_scale=1.0, y_scale=1.0, annotate=None, line=True):
        """pts: rows in plot order. Rings the Pareto-front points."""
        xs = [r["_x"] * x_scale for r in pts]
        ys = [positive(r["_y"]) * y_scale for r in pts]
        ax.plot(xs, ys, ("-" if line else "") + marker, color=color, label=label, markersize=10 if marker == "*" else 5,
                linewidth=1.2)
        px = [x for x, y, r in zip(xs, ys, pts) if r["pareto"]]
        py = [y for x, y, r in zip(xs, ys, pts) if r["pareto"]]
        ax.plot(px, py, "o", markersize=10, markerfacecolor="none", markeredgecolor="black", markeredgewidth=1.0)
        if annotate:
            for x, y, r in zip(xs, ys, pts):
                if not math.isnan(y):
                    ax.annotate(annotate(r), (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7, color=color)

    @staticmethod
    def log_axes(ax, **labels):
        """Log-log axes with `labels` (title, xlabel, ylabel), or linear ones that say why when
        nothing drawn on them is positive (log scaling would raise): every error 0, say."""
        def positive_on(axis):
            for line in ax.get_lines():
                values = line.get_xdata() if axis == "x" else line.get_ydata()
                for v in values:
                    try:
                        if math.isfinite(float(v)) and float(v) > 0:
                            return True
                    except (TypeError, ValueError):
                        pass
            return False
        ax.set(**labels)
        if positive_on("x") and positive_on("y"):
            ax.set(xscale="log", yscale="log")
        else:
            ax.text(0.5, 0.5, "nothing to plot on log axes:\nno positive value", transform=ax.transAxes,
                    ha="center", va="center", fontsize=9, color="grey")

    def pareto_legend(self, ax, pareto=True, below=False):
        from matplotlib.ticker import FuncFormatter
        if pareto:
            ax.plot([], [], "o", markersize=10, markerfacecolor="none", markeredgecolor="black", label="Pareto front")
        if below:  # many series: under the axes, where it hides no point
            ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3, frameon=False)
        else:
            ax.legend(fontsize=7, loc="best")
        ax.grid(True, which="both", alpha=0.3)
        plain = FuncFormatter(lambda v, _: "%g" % v)
        ax.xaxis.set_major_formatter(plain)

        def minor(v, _):  # every minor tick on a short axis, 2 and 5 on a medium one, none on a long one
            lo, hi = ax.get_xlim()
            if not (lo > 0 and hi > lo):  # linear axes (log_axes found nothing positive)
                return ""
            span = math.log10(hi / lo)
            return "%g" % v if span < 1.2 or (span < 2.5 and ("%g" % v)[0] in "25") else ""
        ax.xaxis.set_minor_formatter(FuncFormatter(minor))

    def select(self, **keys):
        out = [r for r in self.rows if all((r[k] in v) if isinstance(v, tuple) else r[k] == v for k, v in keys.items())]
        return out

    def reference_note(self, knob, pattern, fallback):
        """A phrase from the notes of the first `knob` row (e.g. the reference's ray count)."""
        for r in self.select(knob=knob):
            m = re.search(pattern, r["notes"])
            if m:
                return m.group(1)
        return fallback

    def ao(self):
        ref = self.reference_note("ao_rays", r"vs (\d+)-ray", "4096")
        fig, axes = self.figure(len(self.meshes), "AO: RMS error against a %s-ray low-discrepancy GPU AO, "
                                                  "against GPU time (labels: rays per vertex)" % ref)
        colors = {}
        for ax, mesh in zip(axes, self.meshes):
            groups = defaultdict(list)
            for r in self.select(mesh=mesh, knob="ao_rays"):
                r["_x"], r["_y"] = r["gpu_ms"], r["err_rms"]
                groups[(r["case"], r["algorithm"])].append(r)
            for (case, algorithm), pts in sorted(groups.items()):
                color = colors.setdefault(case, "C%d" % len(colors))
                ld = algorithm.startswith("low")
                self.series(ax, pts, "%s, %s" % (algorithm, case.replace("d=", "max dist ")), color, "o" if ld else "x",
                            x_scale=1e-3, annotate=(lambda r: r["value"]) if ld else None)
            self.log_axes(ax, title=mesh, xlabel="GPU time (s)",
                   ylabel="AO error, RMS over vertices (absolute, AO in [0,1])")
            self.pareto_legend(ax)
        self.save(fig, "ao.png")

    def tm(self):
        sample = self.reference_note("tm_epsilon", r"on (\d+) vertices", "?")
        fig, axes = self.figure(len(self.meshes), "t_m: max relative error against float64 (%s sampled vertices), "
                                                  "against GPU time; labels: eps of the first material" % sample)
        fig.set_size_inches(fig.get_size_inches()[0], 5.4)
        for ax, mesh in zip(axes, self.meshes):
            rows = self.select(mesh=mesh, knob=("tm_exact", "tm_epsilon", "tm_auto"))
            for r in rows:
                r["_x"], r["_y"] = r["gpu_ms"], r["err_max"]
            for k, case in enumerate(OrderedDict.fromkeys(r["case"] for r in rows)):
                color = "C%d" % k
                eps = [r for r in rows if r["case"] == case and r["knob"] == "tm_epsilon"]
                self.series(ax, eps, case + ": clustered", color, "o", x_scale=1e-3,
                            annotate=(lambda r: r["value"]) if k == 0 else None)
                exact = [r for r in rows if r["case"] == case and r["knob"] == "tm_exact"]
                self.series(ax, exact, None, color, "*", x_scale=1e-3, line=False)
                auto = [r for r in rows if r["case"] == case and r["knob"] == "tm_auto"]
                self.series(ax, auto, None, color, "^", x_scale=1e-3, line=False)
            ax.plot([], [], "*", color="grey", markersize=10, label="exact (all pairs, float32)")
            ax.plot([], [], "^", color="grey", label="auto with the quality presets")
            self.log_axes(ax, title=mesh, xlabel="GPU time (s)",
                   ylabel="t_m error, max over sampled vertices (relative)")
            self.pareto_legend(ax, below=True)
        self.save(fig, "tm.png")

    def presets(self):
        fig, axes = self.figure(2, "Today's presets end to end: error against the bake's GPU time")
        for k, mesh in enumerate(self.meshes):
            color = "C%d" % k
            for ax, knob, y in ((axes[0], "quality", "err_max"), (axes[1], "image", "err_p99")):
                pts = self.select(mesh=mesh, knob=knob)
                for r in pts:
                    r["_x"], r["_y"] = r["gpu_ms"], r[y]
                self.series(ax, pts, mesh, color, "o", x_scale=1e-3, annotate=lambda r: r["value"])
        self.log_axes(axes[0], xlabel="bake GPU time (s)",
                    ylabel="t_m error, max over sampled vertices (relative)", title="t_m vs float64 (own AO + t_m)")
        self.log_axes(axes[1], xlabel="bake GPU time (s)",
                    ylabel="image error, 99th percentile (8-bit sRGB levels)", title="final image vs reference image")
        self.pareto_legend(axes[0])
        self.pareto_legend(axes[1], pareto=False)  # the image error has no front of its own: same points
        self.save(fig, "presets.png")

    def lut(self):
        fig, axes = self.figure(2, "Translucency LUT: error against memory ((N+1) x N texels, float32)")
        for ax, knob, ylabel in ((axes[0], "lut_size", "error of f(cos, t), max (absolute)"),
                                 (axes[1], "image_lut", "image error, max over pixels (8-bit sRGB levels)")):
            for k, mesh in enumerate(OrderedDict.fromkeys(r["mesh"] for r in self.select(knob=knob))):
                pts = sorted(self.select(knob=knob, mesh=mesh), key=lambda r: texels(r["value"]))
                for r in pts:
                    r["_x"], r["_y"] = texels(r["value"]), r["err_max"]
                square = [r for r in pts if is_square_lut(r["value"])]  # the (N+1) x N sweep
                other = [r for r in pts if not is_square_lut(r["value"])]  # the renderer's default
                label = "f(cos, t)" if mesh == "(any)" else mesh
                note = (lambda r: r["value"]) if k == 0 else None
                self.series(ax, square, label + ": (N+1) x N", "C%d" % k, "o", x_scale=4.0 / 1024, annotate=note)
                self.series(ax, other, label + ": default size", "C%d" % k, "*", x_scale=4.0 / 1024, line=False,
                            annotate=note)
            self.log_axes(ax, xlabel="LUT memory (KB)", ylabel=ylabel)
            self.pareto_legend(ax)
        self.save(fig, "lut.png")

    def deform(self):
        fig, axes = self.figure(2, "Deforming mesh: re-bake error per frame (vs a from-scratch bake) against GPU time "
                                   "per frame (labels: refit, amortised 1/N)")
        for ax, knob, ylabel in ((axes[0], "deform_ao", "AO error, RMS (absolute), mean over frames\n(refit: exactly 0, drawn at 1e-6)"),
                                 (axes[1], "deform_tm", "t_m error, RMS (relative), mean over frames")):
            for k, mesh in enumerate(OrderedDict.fromkeys(r["mesh"] for r in self.select(knob=knob))):
                # The refit's AO error is 0 (identical to the rebuild): drawn at the axis floor.
                pts = [r for r in self.select(knob=knob, mesh=mesh) if r["value"] != "rebuild"]
                for r in pts:
                    r["_x"], r["_y"] = r["gpu_ms"], max(r["err_rms"], 1e-6)
                self.series(ax, pts, mesh, "C%d" % k, "o", x_scale=1e-3, annotate=lambda r: r["value"])
            self.log_axes(ax, xlabel="re-bake GPU time per frame (s)", ylabel=ylabel)
            self.pareto_legend(ax)
        self.save(fig, "deform.png")


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__, file=sys.stderr)
        return 2
    out = sys.argv[1]
    path = os.path.join(out, "report.csv")
    if not os.path.exists(path):
        print("plot_report: %s: no such file (run `jade report ... --out %s` first)" % (path, out), file=sys.stderr)
        return 1
    ensure_matplotlib()
    rows = load(path)
    mark_pareto(rows)
    p = Plotter(rows, out)
    failed = False
    for knob, draw in (("ao_rays", p.ao), ("tm_epsilon", p.tm), ("quality", p.presets), ("lut_size", p.lut),
                       ("deform_ao", p.deform)):
        if p.select(knob=knob):
            try:
                draw()
            except Exception as e:  # one plot's failure must not cost the others
                print("plot_report: %s plot skipped: %s: %s" % (knob, type(e).__name__, e), file=sys.stderr)
                failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
