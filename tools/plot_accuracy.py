#!/usr/bin/env python3
"""plot_accuracy.py - what accuracy costs in time (`make accuracy`): draws bench/accuracy.c's CSV and writes its tables.

  tools/plot_accuracy.py out/accuracy.csv -o out/accuracy.png [--doc docs/accuracy.md]

One panel per case: relative error against wall time (log-log), one marker per run - the marker's shape the contact
model, its colour the time step (a fraction of the Rayleigh time), filled fp64, open fp32. The Pareto front (no other
run of the same model is both cheaper and more accurate) is drawn per model, and its knee - the front point farthest
below the straight line (in log-log) from the front's cheapest to its most accurate run - is ringed and printed as
the recommended setting. With --doc the Markdown (tables, knees, cheapest runs within 1 % and 0.1 %) is written into
that file between the markers <!-- accuracy:begin --> and <!-- accuracy:end --> (the rest of the file is kept).
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CASES = [
    ("head_on", "Hertz head-on: overlap, force, contact time vs closed form"),
    ("restitution", "restitution e = 0.5 requested"),
    ("oblique", "oblique impact, gross sliding: tangential and normal rebound"),
    ("rubber", "rubber sphere, d/r = 0.4: plate force vs converged run"),
    ("hydrogel", "514 hydrogels, 13.4 % strain: stress vs converged run"),
    ("membrane", "small triaxial (200 grains): top platen stress vs MSS_patch, finest mesh"),
]
MARKERS = {"classical": "o", "mc_stress": "s", "mc_strain": "^", "mc_strain_iterated": "D",
           "patch": "p", "particle": "h"}
FAMILY = {"classical": "classical", "mc_stress": "mc_stress", "mc_strain": "mc_strain",
          "mc_strain_iterated": "mc_strain", "patch": "MSS_patch", "particle": "MSS_particle"}
FLOOR = 1e-9  # errors below this (bit-equal to the converged run) are drawn at it


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("dt_rayleigh", "tolerance", "skin", "seconds", "value", "error", "part0", "part1", "part2"):
            r[k] = float(r[k])
        for k in ("steps", "unconverged", "iterations"):
            r[k] = int(r[k])
    return rows


def label(r):
    if r["case"] == "membrane":
        return "MSS_%s edge %.3g mm, dt %.2g t_R" % (r["model"], 1e3 * r["part0"], r["dt_rayleigh"])
    s = "%s dt %.2g t_R %s" % (r["precision"], r["dt_rayleigh"], r["model"])
    if r["model"] == "mc_strain_iterated":
        s += " tol %.0e" % r["tolerance"]
    return s


def pareto(runs):
    """runs sorted by time; those no cheaper run beats in error"""
    front, best = [], math.inf
    for r in sorted(runs, key=lambda r: (r["seconds"], r["error"])):
        if r["error"] < best:
            front.append(r)
            best = r["error"]
    return front


def knee(front):
    if len(front) < 3:
        return front[-1] if front else None
    lx = [math.log10(max(r["seconds"], 1e-6)) for r in front]
    ly = [math.log10(max(r["error"], FLOOR)) for r in front]
    x0, y0, x1, y1 = lx[0], ly[0], lx[-1], ly[-1]
    nx, ny = (y1 - y0), -(x1 - x0)  # a normal of the chord, pointing below it (cheaper and more accurate)
    norm = math.hypot(nx, ny) or 1
    best, bd = front[-1], 0
    for r, x, y in zip(front, lx, ly):
        d = ((x - x0) * nx + (y - y0) * ny) / norm
        if d > bd:
            best, bd = r, d
    return best


def measured(rows, case):
    return [r for r in rows if r["case"] == case and r["role"] in ("run", "tolerance")]


def draw(rows, out):
    fig, axes = plt.subplots(2, 4, figsize=(21, 9.5))
    cmap = plt.get_cmap("viridis")
    dts = sorted({r["dt_rayleigh"] for r in rows if r["role"] == "run"})
    colour = {d: cmap(i / max(1, len(dts) - 1)) for i, d in enumerate(dts)}
    for ax, (case, title) in zip(axes.flat, CASES):
        runs = measured(rows, case)
        for r in runs:
            c = colour.get(r["dt_rayleigh"], "grey")
            if case == "membrane":  # colour by edge: dark fine, light coarse
                c = cmap(min(1.0, (r["part0"] - 0.0015) / 0.003))
            ax.scatter(max(r["seconds"], 1e-5), max(r["error"], FLOOR), marker=MARKERS[r["model"]], s=42,
                       facecolors=c if r["precision"] == "fp64" else "none", edgecolors=c, linewidths=1.3)
        for fam in sorted({FAMILY[r["model"]] for r in runs}):
            front = pareto([r for r in runs if FAMILY[r["model"]] == fam])
            ax.plot([max(r["seconds"], 1e-5) for r in front], [max(r["error"], FLOOR) for r in front], "-",
                    color="0.6", lw=0.8, zorder=0)
            k = knee(front)
            if k:
                ax.scatter(max(k["seconds"], 1e-5), max(k["error"], FLOOR), s=190, facecolors="none",
                           edgecolors="red", linewidths=1.4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title, fontsize=9.5)
        ax.set_xlabel("wall time of the steps [s]")
        ax.set_ylabel("relative error")
        ax.grid(True, which="both", alpha=0.25)
    for ax in list(axes.flat)[len(CASES) + 1:]:
        ax.axis("off")
    ax = axes.flat[len(CASES)]
    ax.axis("off")
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], marker=m, ls="", color="k", label=n) for n, m in MARKERS.items()]
    handles += [Line2D([], [], marker="o", ls="", color=colour[d], label="dt %.2g t_R" % d) for d in dts]
    handles += [Line2D([], [], marker="o", ls="", color="k", label="fp64 (filled)"),
                Line2D([], [], ls="", label="membrane: colour = edge (dark 1.5 mm, light 4.5 mm)"),
                Line2D([], [], marker="o", ls="", mfc="none", color="k", label="fp32 (open)"),
                Line2D([], [], marker="o", ls="", mfc="none", mec="red", ms=12, label="knee of the Pareto front"),
                Line2D([], [], ls="-", color="0.6", label="Pareto front, per model")]
    ax.legend(handles=handles, loc="center", fontsize=10, frameon=False)
    fig.suptitle("What accuracy costs in time (make accuracy; errors below %g drawn at it)" % FLOOR)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def fmt_e(x):
    return "0" if x == 0 else "%.1e" % x


def markdown(rows, csv_path):
    out = []
    w = out.append
    conv = [r for r in rows if r["role"] == "converged"]
    w("Measured by `make accuracy` (%s); wall time is that of the steps alone (kernels compiled before), one run "
      "each." % csv_path)
    w("")
    w("### Recommended settings (the knee of each Pareto front) and the cheapest run within 1 % and 0.1 %")
    w("")
    w("| case | model | knee | error | time [s] | cheapest within 1 % | cheapest within 0.1 % |")
    w("|---|---|---|---:|---:|---|---|")
    for case, _ in CASES:
        runs = measured(rows, case)
        for fam in sorted({FAMILY[r["model"]] for r in runs}):
            fr = [r for r in runs if FAMILY[r["model"]] == fam]
            k = knee(pareto(fr))
            cells = []
            for bound in (1e-2, 1e-3):
                ok = sorted([r for r in fr if r["error"] <= bound], key=lambda r: r["seconds"])
                cells.append("%s (%.3g s)" % (label(ok[0]), ok[0]["seconds"]) if ok else "none")
            w("| %s | %s | %s | %s | %.3g | %s | %s |" % (case, fam, label(k), fmt_e(k["error"]), k["seconds"],
                                                          cells[0], cells[1]))
    w("")
    for case, title in CASES:
        runs = [r for r in rows if r["case"] == case and r["role"] == "run"]
        if not runs:
            continue
        if case == "membrane":
            w("### %s: %s" % (case, title))
            w("")
            for c in conv:
                if c["case"] == case:
                    w("Converged run (%s): %.9g Pa in %.3g s, %d steps." % (label(c), c["value"], c["seconds"],
                                                                            c["steps"]))
            w("")
            w("| model | edge [mm] | dt / t_R | steps | time [s] | top platen stress [Pa] | error |")
            w("|---|---:|---:|---:|---:|---:|---:|")
            for r in sorted(runs, key=lambda r: (r["model"], -r["part0"])):
                w("| MSS_%s | %.3g | %.2g | %d | %.3g | %.6g | %s |" % (r["model"], 1e3 * r["part0"], r["dt_rayleigh"],
                                                                       r["steps"], r["seconds"], r["value"],
                                                                       fmt_e(r["error"])))
            w("")
            continue
        cols = sorted({(r["model"], r["precision"]) for r in runs},
                      key=lambda c: (list(MARKERS).index(c[0]), c[1] != "fp64"))
        dts = sorted({r["dt_rayleigh"] for r in runs})
        w("### %s: %s" % (case, title))
        w("")
        for c in conv:
            if c["case"] == case:
                w("Converged run (%s): %.9g in %.3g s, %d steps." % (label(c), c["value"], c["seconds"], c["steps"]))
        if any(c["case"] == case for c in conv):
            w("")
        w("Relative error / wall time of the steps [s], per time step (rows) and model, precision (columns).")
        w("")
        w("| dt / t_R | " + " | ".join("%s %s" % c for c in cols) + " |")
        w("|---:|" + "---|" * len(cols))
        for d in dts:
            cells = []
            for c in cols:
                m = [r for r in runs if r["dt_rayleigh"] == d and (r["model"], r["precision"]) == c]
                cells.append("%s / %.3g" % (fmt_e(m[0]["error"]), m[0]["seconds"]) if m else "-")
            w("| %.2g | " % d + " | ".join(cells) + " |")
        w("")
        if case == "head_on":
            w("Parts (fp64): " + "; ".join("dt %.2g: overlap %s, force %s, contact time %s" % (
                r["dt_rayleigh"], fmt_e(r["part0"]), fmt_e(r["part1"]), fmt_e(r["part2"]))
                for r in runs if r["precision"] == "fp64") + ".")
            w("")
        if case == "oblique":
            w("Parts (fp64): " + "; ".join("dt %.2g: tangential %s, spin %s, normal %s" % (
                r["dt_rayleigh"], fmt_e(r["part0"]), fmt_e(r["part1"]), fmt_e(r["part2"]))
                for r in runs if r["precision"] == "fp64") + ".")
            w("")
        tol = [r for r in rows if r["case"] == case and r["role"] == "tolerance"]
        if tol:
            it = [r for r in runs if r["model"] == "mc_strain_iterated" and r["precision"] == "fp64"
                  and r["dt_rayleigh"] == 0.2]
            w("MC-strain iteration tolerance at dt 0.2 t_R, fp64:")
            w("")
            w("| tolerance | error | time [s] | iterations per step | steps at the cap |")
            w("|---:|---:|---:|---:|---:|")
            for r in sorted(tol + it, key=lambda r: -r["tolerance"]):
                w("| %.0e | %s | %.3g | %.2f | %d |" % (r["tolerance"], fmt_e(r["error"]), r["seconds"],
                                                        r["iterations"] / max(1, r["steps"]), r["unconverged"]))
            w("")
        skin = [r for r in rows if r["case"] == case and r["role"] == "skin"]
        if skin:
            w("Neighbour skin (cost only; the stress came out in the same bits for every skin - the run stops "
              "otherwise): " + ", ".join("%.2g r_min %.3g s" % (r["skin"], r["seconds"]) for r in skin) + ".")
            w("")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv")
    ap.add_argument("-o", "--out", default="out/accuracy.png")
    ap.add_argument("--doc", help="Markdown file whose accuracy block is rewritten")
    a = ap.parse_args()
    rows = load(a.csv)
    if not rows:
        sys.exit("plot_accuracy.py: %s holds no runs" % a.csv)
    draw(rows, a.out)
    md = markdown(rows, a.csv)
    print(md)
    if a.doc:
        begin, end = "<!-- accuracy:begin -->", "<!-- accuracy:end -->"
        try:
            text = open(a.doc).read()
        except FileNotFoundError:
            text = "# What accuracy costs in time\n\n%s\n%s\n" % (begin, end)
        if begin not in text or end not in text:
            sys.exit("plot_accuracy.py: %s lacks the markers %s ... %s" % (a.doc, begin, end))
        head, rest = text.split(begin, 1)
        tail = rest.split(end, 1)[1]
        with open(a.doc + ".tmp", "w") as f:
            f.write(head + begin + "\n" + md + "\n" + end + tail)
        import os
        os.replace(a.doc + ".tmp", a.doc)
    print("plot_accuracy.py: %s" % a.out, file=sys.stderr)


if __name__ == "__main__":
    main()
