#!/usr/bin/python3
"""The force-chain distribution of a dem run: P(f/<f>) of the normal contact forces between particles.

usage: tools/contacts.py RUN.h5 [--frame F] [-o RUN.contacts.png]

Reads the contact network of one frame (the scene's output lists the field `contacts`; default: the last frame),
takes |normal force| of every touching particle pair, and draws the probability density of f/<f> on a log scale
with the exponential fitted to the strong forces (f > <f>: P ~ exp(-b f/<f>), the classic tail of granular force
networks; Radjai et al., PRL 77, 274, 1996, find b of about 1.4 in 2D). Prints the frame, the pair count, <f>, the
share of forces above the mean and b. Reads the run with the Python package (python/libdem: libdem.Run). Uses
Debian's python3-h5py, numpy and matplotlib; run with /usr/bin/python3.
"""
import argparse
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from libdem import OutputError, Run  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="HDF5 file written by dem run (with the field contacts)")
    ap.add_argument("--frame", type=int, default=-1, help="frame index (default: the last)")
    ap.add_argument("-o", "--output", help="PNG file (default: RUN.contacts.png)")
    a = ap.parse_args()
    out = a.output or (a.run[:-3] if a.run.endswith(".h5") else a.run) + ".contacts.png"
    try:
        run = Run(a.run)
        nf = len(run.frames)
        if not -nf <= a.frame < nf:
            sys.exit(f"contacts: frame {a.frame} is not in 0 .. {nf - 1}")
        c = run.contacts(a.frame)
    except OutputError as e:
        sys.exit(f"contacts: {e}")
    fr, npair, t = a.frame % nf, c["npairs"], c["time"]
    fn = np.linalg.norm(c["normal_force"][:npair], axis=1)
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
