#!/usr/bin/python3
"""Compaction curves of one press scene under several contact models, side by side (`make tablet-models`).

usage: tools/plot_tablet_models.py RUN.h5 [RUN.h5 ...] [-o models.png] [--table models.md] [--times times.txt]

Each RUN.h5 is a `dem run SCENE --model M` of the same press (tools/tablet_models.sh, `make tablet-models`); a run
continued with `dem run --restart` is its files joined by '+' in the order they ran (A.h5+B.h5: plot_tablet.py joins
their series by step, and the log numbers below are the largest over the parts' logs); the
press quantities are tools/plot_tablet.py's (analyse): upper punch pressure over the bore, relative density between
the punches, the Heckel line fitted over the upper half of the loading. Panels: pressure against relative density
(loading and unloading), the Heckel plot, pressure against the upper punch's travel, and the kinetic over the
elastic energy against time (a compact at rest has it falling; numerical heat or a ringing model keeps it up).
The table (Markdown, --table) has per model: wall time (--times: lines "model exit-status seconds") and its ratio to
the classical run's, the relative density at the largest pressure, the Heckel yield pressure, the transmission
ratio (lower / upper punch), the radial over the axial pressure, the elastic recovery of the gap, kinetic / elastic
energy at the end of the dwell, and from the run's log next to it (RUN.log) the largest overlap, the largest mean
overlap and how close dt came to the step's stability bound (dem run's report). Uses Debian's python3-h5py,
python3-numpy and python3-matplotlib.
"""
import argparse
import math
import os
import re
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_tablet import analyse  # noqa: E402


def log_numbers(run):
    """dem run's end-of-run report in RUN.log: largest overlap, largest mean overlap [%], stability ratio; for a run
    in parts (a list of files), the largest of each over the parts' logs and their warnings together."""
    if not isinstance(run, str):
        parts = [log_numbers(p) for p in run]
        out = {k: max((p[k] for p in parts if math.isfinite(p[k])), default=math.nan)
               for k in ("largest", "mean", "stability")}
        out["warnings"] = sum(p["warnings"] for p in parts)
        return out
    path = (run[:-3] if run.endswith(".h5") else run) + ".log"
    out = dict(largest=math.nan, mean=math.nan, stability=math.nan, warnings=0)
    if not os.path.exists(path):
        return out
    text = open(path, errors="replace").read()
    m = re.search(r"overlaps at the frames: largest ([0-9.eE+-]+) %.*?largest mean over the touching pairs "
                  r"([0-9.eE+-]+) %", text)
    if m:
        out["largest"], out["mean"] = float(m.group(1)), float(m.group(2))
    m = re.search(r"time step at the frames' overlaps: at most ([0-9.eE+-]+) of the estimated stability bound", text)
    if m:
        out["stability"] = float(m.group(1))
    out["warnings"] = len(re.findall(r"^dem: warning:", text, flags=re.M))
    return out


def stopped_note(last, c):
    """' (to t ms)' for a run whose last part dem run stopped on a signal (make tablet-models TABLET_TIME): not done"""
    path = (last[:-3] if last.endswith(".h5") else last) + ".log"
    if os.path.exists(path) and re.search(r"^dem: stopped by signal", open(path, errors="replace").read(), re.M):
        return f" (to {1e3 * c['t'][-1]:.3g} ms)"
    return ""


def label_of(c, run):
    return c["model"] if c["model"] and c["model"] != "as in the scene" else os.path.basename(run[0])[:-3]


def recovery_text(r):
    """The elastic recovery for the table; where the run ended before the punch let go, its lower bound"""
    if math.isfinite(r["recovery"]):
        return f"{100 * r['recovery']:.1f} %"
    return f">= {100 * r['recovery_min']:.1f} % (not let go)"


def dwell_end(c):
    """the last row of the dwell: from the largest pressure on, the first row where the upper punch stands (the
    same travel as the next row's: the peak may come at the punch's last moving row) and the last it stands there"""
    k, tr = c["k_max"], c["travel_up"]
    still = np.nonzero((np.arange(len(tr) - 1) >= k) & (np.abs(np.diff(tr)) <= 1e-12))[0]
    if not len(still):
        return k
    j = int(still[0])
    moved = np.nonzero((np.arange(len(tr)) > j) & (np.abs(tr - tr[j]) > 1e-12))[0]
    return int(moved[0]) - 1 if len(moved) else len(tr) - 1


def read_times(path):
    """wall times of the runs that succeeded: lines 'name exit-status seconds' -> {name: seconds}"""
    times = {}
    if path and os.path.exists(path):
        for line in open(path):
            w = line.split()
            if len(w) == 3 and w[1] == "0":
                times[w[0]] = float(w[2])
    return times


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="HDF5 files written by dem run, one per model (a run continued by "
                    "--restart: its files joined by '+')")
    ap.add_argument("-o", "--output", default="models.png", help="PNG file")
    ap.add_argument("--table", help="Markdown table to write")
    ap.add_argument("--times", help="wall times: lines 'model exit-status seconds' (tools/tablet_models.sh)")
    a = ap.parse_args()
    times = read_times(a.times)
    fig, ax = plt.subplots(2, 2, figsize=(11, 8.5))
    rows = []
    for arg in a.runs:
        # a file whose name holds '+' is taken whole
        run = [arg] if os.path.exists(arg) else arg.split("+")
        try:
            c = analyse(run)
        except SystemExit as e:
            if "never pressed" not in str(e):  # a missing file, parts out of order, ...: an error
                raise
            # a run stopped before its punch pressed (make tablet-models TABLET_TIME): nothing to draw yet
            print(f"plot_tablet_models: {arg} left out: {e}", file=sys.stderr)
            continue
        name = label_of(c, run) + stopped_note(run[-1], c)
        k, r = c["k_max"], c["k_rel"]
        end = r if r is not None else len(c["t"]) - 1
        line, = ax[0, 0].plot(c["dens"][: k + 1], 1e-6 * c["p_up"][: k + 1], label=name)
        ax[0, 0].plot(c["dens"][k: end + 1], 1e-6 * c["p_up"][k: end + 1], ls="--", color=line.get_color(), lw=0.8)
        ax[0, 1].plot(1e-6 * c["p_up"][c["load"]], c["heckel"], ".", ms=2, color=line.get_color(),
                      label=f"{name}: yield {1e-6 * c['yield_p']:.3g} MPa")
        if math.isfinite(c["slope"]):
            pp = np.linspace(0.5 * c["p_max"], c["p_max"], 10)
            ax[0, 1].plot(1e-6 * pp, c["slope"] * pp + c["intercept"], "-", color=line.get_color(), lw=0.8)
        ax[1, 0].plot(1e3 * c["travel_up"][: end + 1], 1e-6 * c["p_up"][: end + 1], color=line.get_color(), label=name)
        with np.errstate(divide="ignore", invalid="ignore"):
            heat = c["kinetic"] / c["elastic"]
        ok = np.isfinite(heat) & (heat > 0) & (c["elastic"] > 1e-6 * np.nanmax(c["elastic"]))
        ax[1, 1].semilogy(1e3 * c["t"][ok], heat[ok], color=line.get_color(), lw=0.8, label=name)
        d = dwell_end(c)
        lg = log_numbers(run)
        rows.append(dict(name=name, wall=times.get(name, math.nan), dens=c["dens"][k], p_max=c["p_max"],
                         yield_p=c["yield_p"], ratio=c["ratio"], radial=c["radial_ratio"], recovery=c["recovery"],
                         recovery_min=c["recovery_min"],
                         heat=heat[d] if math.isfinite(heat[d]) else math.nan,
                         d_press=c["dens"][c["load"]] if len(c["load"]) else c["dens"][k: k + 1],
                         t_press=1e3 * (c["travel_up"][c["load"][0]] if len(c["load"]) else 0.0), **lg))
    if not rows:
        sys.exit("plot_tablet_models: no run to draw")
    # the curves from where the first run's punch begins to press (the loose fill before it says nothing)
    d0 = min(float(np.min(r["d_press"])) for r in rows)
    ax[0, 0].set_xlim(left=max(0.0, d0 - 0.02))
    ax[1, 0].set_xlim(left=max(0.0, min(r["t_press"] for r in rows) - 0.05))
    ax[0, 0].set(xlabel="relative density D", ylabel="upper punch pressure [MPa]",
                 title="compaction (solid) and unloading (dashed)")
    ax[0, 1].set(xlabel="upper punch pressure [MPa]", ylabel="ln 1/(1 - D)", title="Heckel plot, fitted above half")
    ax[1, 0].set(xlabel="upper punch travel [mm]", ylabel="upper punch pressure [MPa]", title="pressure against travel")
    ax[1, 1].set(xlabel="time [ms]", ylabel="kinetic / elastic energy", title="how still the compact is")
    for p in ax.flat:
        p.legend(fontsize=8)
    fig.suptitle("the same press under each contact model", fontsize=11)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    base = next((r["wall"] for r in rows if r["name"] == "classical"), math.nan)
    head = ("| model | wall time [s] | x classical | D at the largest pressure | largest pressure [MPa] | Heckel yield "
            "[MPa] | lower / upper | radial / axial | elastic recovery | kinetic / elastic, end of dwell | largest "
            "overlap / r | largest mean overlap / r | dt / stability bound (estimate) |\n|---|" + "---:|" * 12 + "\n")
    body = "".join(
        f"| {r['name']} | {r['wall']:.4g} | {r['wall'] / base:.2f} | {r['dens']:.4f} | {1e-6 * r['p_max']:.2f} | "
        f"{1e-6 * r['yield_p']:.3g} | {r['ratio']:.3f} | {r['radial']:.3f} | {recovery_text(r)} | "
        f"{r['heat']:.1e} | {r['largest']:.3g} % | {r['mean']:.3g} % | {r['stability']:.3g} |\n" for r in rows)
    if a.table:
        with open(a.table, "w") as f:
            f.write(head + body)
    print(f"png={a.output}" + (f" table={a.table}" if a.table else ""))
    sys.stdout.write(head + body)


if __name__ == "__main__":
    main()
