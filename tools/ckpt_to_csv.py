#!/usr/bin/python3
"""Writes the particles of a dem checkpoint as a scene CSV (x, y, z, radius, vx, vy, vz), e.g. a settled packing.

usage: tools/ckpt_to_csv.py RUN.ckpt.h5 OUT.csv [--comment TEXT ...] [--still]

The CSV carries a provenance header (# lines): the checkpoint, its scene, step and time, and any --comment lines.
--still writes zero velocities. Load it in a scene with `csv: OUT.csv`. Run it with /usr/bin/python3 (h5py).
"""
import argparse
import sys

import h5py


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("checkpoint")
    ap.add_argument("csv")
    ap.add_argument("--comment", action="append", default=[], help="a provenance line for the header")
    ap.add_argument("--still", action="store_true", help="write zero velocities")
    a = ap.parse_args()
    try:
        f = h5py.File(a.checkpoint, "r")
    except OSError as e:
        sys.exit(f"ckpt_to_csv: cannot open {a.checkpoint}: {e}")
    with f:
        st = f["state"]
        x, v, r = st["x"][:], st["v"][:], st["radius"][:]
        path = f["scene/path"][()]
        path = path.decode() if isinstance(path, bytes) else str(path)
        step, time = int(st.attrs["step"]), float(st.attrs["time"])
    with open(a.csv, "w") as out:
        for c in a.comment:
            out.write(f"# {c}\n")
        out.write(f"# From checkpoint {a.checkpoint} of scene {path} at step {step}, t = {time:.6g} s "
                  f"(libdem tools/ckpt_to_csv.py). Units: m, m/s.\n")
        out.write("x,y,z,radius,vx,vy,vz\n")
        for i in range(len(r)):
            vel = (0.0, 0.0, 0.0) if a.still else tuple(v[i])
            out.write(",".join(repr(float(q)) for q in (*x[i], r[i], *vel)) + "\n")
    print(f"ckpt_to_csv: wrote {len(r)} particles to {a.csv}")


if __name__ == "__main__":
    main()
