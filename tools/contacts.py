#!/usr/bin/python3
"""The force-chain distribution of a dem run: P(f/<f>) of the normal contact forces between particles.

usage: tools/contacts.py RUN.h5 [--frame F] [-o RUN.contacts.png]

Reads the contact network of one frame (the scene's output lists the field `contacts`; default: the last frame),
takes |normal force| of every touching particle pair, and draws the probability density of f/<f> on a log scale
with the exponential fitted to the strong forces (f > <f>: P ~ exp(-b f/<f>), the classic tail of granular force
networks; Radjai et al., PRL 77, 274, 1996, find b of about 1.4 in 2D). Prints the frame, the pair count, <f>, the
share of forces above the mean and b. Uses Debian's python3-h5py, numpy and matplotlib; run with /usr/bin/python3.
"""
import argparse
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="HDF5 file written by dem run (with the field contacts)")
    ap.add_argument("--frame", type=int, default=-1, help="frame index (default: the last)")
    ap.add_argument("-o", "--output", help="PNG file (default: RUN.contacts.png)")
    a = ap.parse_args()
    out = a.output or (a.run[:-3] if a.run.endswith(".h5") else a.run) + ".contacts.png"
    try:
        f = h5py.File(a.run, "r")
    except OSError as e:
        sys.exit(f"contacts: cannot open {a.run}: {e}")
    with f:
        if "contacts" not in f:
            sys.exit(f"contacts: {a.run} has no contact network (list `contacts` in the scene's output.fields)")
        c = f["contacts"]
        starts, pairs = c["frame_start"][:], c["frame_pairs"][:]
        nf = len(starts)
        fr = a.frame if a.frame >= 0 else nf + a.frame
        if not 0 <= fr < nf:
            sys.exit(f"contacts: frame {a.frame} is not in 0 .. {nf - 1}")
        s0, npair = int(starts[fr]), int(pairs[fr])
        fn = c["normal_force"][s0:s0 + npair]
        t = float(f["frames/time"][fr])
    if npair < 2:
        sys.exit(f"contacts: frame {fr} (t = {t:g} s) has {npair} particle pairs in contact: no distribution")
    mean = fn.mean()
    x = fn / mean
    hist, edges = np.histogram(x, bins=max(8, min(40, npair // 20)), density=True)
    mid = 0.5 * (edges[1:] + edges[:-1])
    tail = (mid > 1) & (hist > 0)
    b = float("nan")
    if tail.sum() >= 2:
        b = -np.polyfit(mid[tail], np.log(hist[tail]), 1)[0]
    above = float((x > 1).mean())
    print(f"contacts: frame {fr} (t = {t:.6g} s): {npair} particle pairs, <f> = {mean:.6g} N, "
          f"{100 * above:.1f} % above the mean, tail exponent b = {b:.3g}")
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.semilogy(mid[hist > 0], hist[hist > 0], "o", label=f"{npair} pairs, t = {t:.4g} s")
    if np.isfinite(b):
        xs = np.linspace(1, mid[tail].max(), 50)
        c0 = np.exp(np.polyfit(mid[tail], np.log(hist[tail]), 1)[1])
        ax.semilogy(xs, c0 * np.exp(-b * xs), "-", label=f"exp(-{b:.2f} f/<f>) for f > <f>")
    ax.set_xlabel("f / <f> (normal force between particles)")
    ax.set_ylabel("P(f / <f>)")
    ax.set_title(a.run.rsplit("/", 1)[-1])
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"contacts: wrote {out}")


if __name__ == "__main__":
    main()
