#!/usr/bin/env python3
"""Rumpf's tensile strength of a bonded tablet, from its contacts: a check of the diametral compression's figure by
theory, with nothing fitted (docs/tableting.md "Bonds and tensile strength").

Usage: rumpf_check.py CHECKPOINT.h5 --young E --poisson NU --yield P_Y --bond SIGMA_B [--axis 0 0 1]

CHECKPOINT.h5 is a thornton_ning run's checkpoint (dem run --stop-after N, taken with the tablet out of the die and
before the platens touch it) of spheres of one material. For every contact it holds the largest overlap delta_m
(negated where the bond broke); from it, as common/laws/thornton_ning.h does (Thornton and Ning 1998), the plastic
contact radius a_p (a_p^2 = (2 F_m + F_y) / (2 pi p_y), F_m = F_y + pi p_y r* (delta_m - delta_y)) and the bond's
strength F_b = sigma_b pi a_p^2 of each whole bond. Rumpf (1962) for an agglomerate of spheres bonded at their
contacts: sigma_t = (1 - eps) k F / (pi d^2), with k bonds per sphere, F their mean strength and d the spheres'
diameter (here the Sauter mean d32 = sum d^3 / sum d^2 of a polydisperse bed), eps the tablet's porosity out of the
die (libdem.tablet.tablet_size: its diameter and thickness). The form is the Society of Powder Technology Japan's
statement of Rumpf's equation; a 9/8 prefactor also circulates and is not used here.
"""
import argparse
import math
import sys

import h5py
import numpy as np

from libdem import tablet


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("checkpoint")
    ap.add_argument("--young", type=float, required=True)
    ap.add_argument("--poisson", type=float, required=True)
    ap.add_argument("--yield", dest="py", type=float, required=True)
    ap.add_argument("--bond", type=float, required=True)
    ap.add_argument("--axis", type=float, nargs=3, default=[0.0, 0.0, 1.0])
    a = ap.parse_args(argv[1:])
    with h5py.File(a.checkpoint, "r") as f:
        st = f["state"]
        if "pair_law" not in st:
            sys.exit(f"rumpf_check: {a.checkpoint} keeps no law states (not a thornton_ning run)")
        x, r = st["x"][()].reshape(-1, 3), st["radius"][()]
        pi, pj, law = st["pair_i"][()], st["pair_j"][()], st["pair_law"][()]
    es = a.young / (2 * (1 - a.poisson**2))  # two spheres of one material
    rs = r[pi] * r[pj] / (r[pi] + r[pj])
    dy = (math.pi * a.py / (2 * es)) ** 2 * rs
    fy = 4.0 / 3.0 * es * np.sqrt(rs) * dy**1.5
    dm = np.abs(law)
    yielded = dm > dy
    whole = yielded & (law > 0)
    fm = fy + math.pi * a.py * rs * (dm - dy)
    apl = np.sqrt((2 * fm + fy) / (2 * math.pi * a.py))
    fb = np.where(whole, a.bond * math.pi * apl**2, 0.0)
    n = len(r)
    diam, thick = tablet.tablet_size(x, r, np.asarray(a.axis) / np.linalg.norm(a.axis))
    solid = float(np.sum(4.0 / 3.0 * math.pi * r**3))
    density = solid / (math.pi * diam * diam / 4 * thick)
    d32 = float(np.sum((2 * r) ** 3) / np.sum((2 * r) ** 2))
    k = 2.0 * np.count_nonzero(whole) / n
    fmean = float(np.mean(fb[whole])) if np.any(whole) else 0.0
    sigma = density * k * fmean / (math.pi * d32 * d32)
    print(f"contacts {len(law)}, yielded {np.count_nonzero(yielded)}, whole bonds {np.count_nonzero(whole)} "
          f"(broken {np.count_nonzero(yielded & (law < 0))}); bonds per sphere k {k:.3f}; mean bond strength "
          f"{fmean:.4g} N (mean a_p {float(np.mean(apl[whole])) if np.any(whole) else 0:.4g} m); d32 {d32:.4g} m; "
          f"tablet D {diam:.4g} m, t {thick:.4g} m, relative density {density:.4f}")
    print(f"rumpf_tensile_mpa={1e-6 * sigma:.4g}")


if __name__ == "__main__":
    main(sys.argv)
