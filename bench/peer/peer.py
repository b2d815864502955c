#!/usr/bin/python3
"""make bench-peer's helpers (bench/peer/run.sh calls them with the Python scripts/find_python.sh finds: they need
h5py).

  peer.py pour POUR.h5 DENSITY                is the poured bed at rest? (its last series row and frame)
  peer.py lammps BED.csv DATA STL DENSITY     LIGGGHTS' inputs from the bed: a data file (atom_style granular,
                                              with velocities) and the floor as an ASCII STL of two triangles;
                                              prints the box's top z
  peer.py report --json OUT --bed BED.csv --density RHO [--meta K=V ...] --liggghts RANKS:LOG ...
                --dem PRECISION:OUT.h5:LOG:LOG_1STEP:PROCESS_S:PROCESS_1STEP_S ...
                                              the floor-force check and the table (also into OUT); exits 1 when a
                                              floor force is more than 2 % from LIGGGHTS' 2-rank run
"""
import argparse
import json
import math
import re
import sys

G = 9.81
BOX = (0.0, 0.1)        # the side walls (x and y) [m]
PAD = 1.0e-3            # LIGGGHTS' box reaches this far past the walls and under the floor [m]
TOLERANCE = 0.02        # floor forces must agree to this fraction


def read_csv(path):
    """The bed: rows of floats keyed by the header's column names (# lines skipped)."""
    cols, rows = None, []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if cols is None:
                cols = [c.strip() for c in line.split(",")]
                continue
            rows.append([float(x) for x in line.split(",")])
    if cols is None or not rows:
        sys.exit(f"peer.py: {path}: no particles")
    return {c: [r[k] for r in rows] for k, c in enumerate(cols)}


def series_last(path):
    """The last row of a dem output's series: {name: value}, floor force z, and the time."""
    import h5py
    with h5py.File(path, "r") as f:
        s = f["series"]
        row = {k: float(s[k][-1]) for k in ("time", "step", "kinetic", "contacts", "wall_contacts") if k in s}
        names = s.attrs["wall_names"]
        names = (names.decode() if isinstance(names, bytes) else str(names)).split("\n")
        wf = s["wall_force"][-1]
        row["floor_fz"] = float(wf[names.index("floor")][2])
        row["n"] = len(f["particles/radius"])
    return row


def cmd_pour(path, density):
    """Is the poured bed at rest? Its kinetic energy at the last series rows, the rms and largest speeds."""
    import h5py
    with h5py.File(path, "r") as f:
        s = f["series"]
        t, ke = s["time"][:], s["kinetic"][:]
        r = f["particles/radius"][:]
        v = f["frames/velocity"][-1]
    mass = sum(4.0 / 3.0 * math.pi * q ** 3 for q in r) * float(density)
    vrms = math.sqrt(2 * ke[-1] / mass)
    vmax = max(math.sqrt(a * a + b * b + c * c) for a, b, c in v)
    prev = f" ({ke[-2]:.3g} J at t = {t[-2]:.4g} s)" if len(t) > 1 else ""
    print(f"bench-peer: pour ends at t = {t[-1]:.4g} s with kinetic energy {ke[-1]:.3g} J{prev}: an rms speed of "
          f"{1e3 * vrms:.3g} mm/s, fastest grain {1e3 * vmax:.3g} mm/s{'' if vrms < 1e-2 else '  (NOT SETTLED)'}")
    return 0


def cmd_lammps(csv, data, stl, density):
    density = float(density)
    b = read_csv(csv)
    n = len(b["x"])
    r = b["radius"] if "radius" in b else [d / 2 for d in b["diameter"]]
    ztop = max(z + q for z, q in zip(b["z"], r))
    zhi = math.ceil((ztop + 5e-3) * 1e3) / 1e3   # 5 mm of headroom, whole mm
    lo, hi = BOX[0] - PAD, BOX[1] + PAD
    zero = [0.0] * n
    vx, vy, vz = (b.get(k, zero) for k in ("vx", "vy", "vz"))
    with open(data, "w") as f:
        f.write(f"LIGGGHTS data file from {csv} (libdem bench/peer/peer.py)\n\n")
        f.write(f"{n} atoms\n1 atom types\n\n")
        f.write(f"{lo!r} {hi!r} xlo xhi\n{lo!r} {hi!r} ylo yhi\n{-PAD!r} {zhi!r} zlo zhi\n\n")
        f.write("Atoms\n\n")
        for i in range(n):   # atom_style granular: id type diameter density x y z
            f.write(f"{i + 1} 1 {2 * r[i]!r} {density!r} {b['x'][i]!r} {b['y'][i]!r} {b['z'][i]!r}\n")
        f.write("\nVelocities\n\n")
        for i in range(n):   # id vx vy vz wx wy wz
            f.write(f"{i + 1} {vx[i]!r} {vy[i]!r} {vz[i]!r} 0 0 0\n")
    a, c = BOX
    with open(stl, "w") as f:   # the floor z = 0 over the box, normal up
        f.write("solid floor\n")
        for tri in (((a, a), (c, a), (c, c)), ((a, a), (c, c), (a, c))):
            f.write("  facet normal 0 0 1\n    outer loop\n")
            for x, y in tri:
                f.write(f"      vertex {x!r} {y!r} 0.0\n")
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid floor\n")
    print(zhi)
    return 0


def liggghts_log(path):
    """From a LIGGGHTS log: loop time, procs, steps, atoms, Ave neighs/atom, and the last thermo row."""
    text = open(path).read()
    m = re.search(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", text)
    if not m:
        sys.exit(f"peer.py: {path}: no 'Loop time' line (did LIGGGHTS finish?)")
    out = {"loop_s": float(m.group(1)), "procs": int(m.group(2)), "steps": int(m.group(3)),
           "n": int(m.group(4))}
    nb = re.search(r"Ave neighs/atom = (\S+)", text)
    out["neighs_per_atom"] = float(nb.group(1)) if nb else None
    # thermo block: header 'Step Atoms KinEng ...' then rows up to 'Loop time'
    head = None
    for line in text[:m.start()].splitlines():
        w = line.split()
        if w and w[0] == "Step":
            head, last = w, None
        elif head and len(w) == len(head):
            try:
                last = [float(x) for x in w]
            except ValueError:
                pass
    if not head or last is None:
        sys.exit(f"peer.py: {path}: no thermo rows")
    row = dict(zip(head, last))
    out["step"] = int(row["Step"])
    # LIGGGHTS heads the columns without the c_ / f_ of in.peer's c_ke, f_floor[3], c_zsum
    out["kinetic"] = row["ke"] + row["rke"] if "ke" in row and "rke" in row else None
    out["floor_fz"] = row["floor[3]"]
    out["contacts_per_particle"] = row["zsum"] / out["n"] if "zsum" in row else None
    ver = re.search(r"LIGGGHTS \(Version ([^,)]+)", text)
    out["version"] = ver.group(1) if ver else None
    return out


def dem_log(path):
    """From a dem run's stderr (--progress): the steps phase's wall time, steps, and the final rate."""
    text = open(path).read()
    m = re.search(r"at step (\d+); ([0-9.]+) s wall time", text)
    if not m:
        sys.exit(f"peer.py: {path}: no 'wall time' line (did the run finish?)")
    return {"steps_end": int(m.group(1)), "steps_s": float(m.group(2))}


def cmd_report(a):
    """The floor-force check, then the table; both also into a.json. Returns 1 when a floor force is off."""
    b = read_csv(a.bed)
    r = b["radius"] if "radius" in b else [d / 2 for d in b["diameter"]]
    weight = sum(4.0 / 3.0 * math.pi * q ** 3 for q in r) * a.density * G
    rows = []
    for spec in a.liggghts:
        ranks, log = spec.split(":", 1)
        L = liggghts_log(log)
        rows.append({"code": "LIGGGHTS", "config": f"{ranks} MPI rank" + ("s" if ranks != "1" else ""),
                     "ranks": int(ranks), "n": L["n"], "steps": L["steps"], "seconds": L["loop_s"],
                     "rate": L["n"] * L["steps"] / L["loop_s"], "floor_fz": L["floor_fz"], "kinetic": L["kinetic"],
                     "contacts_per_particle": L["contacts_per_particle"], "neighs_per_atom": L["neighs_per_atom"],
                     "timing": "LIGGGHTS' Loop time (the run's steps, set-up excluded)", "log": log})
        a.meta.append(f"liggghts_version={L['version']}")
    for spec in a.dem:
        prec, h5, log, log1, proc, proc1 = spec.split(":")
        full, one = dem_log(log), dem_log(log1)
        last = series_last(h5)
        steps, secs, n = full["steps_end"] - one["steps_end"], full["steps_s"] - one["steps_s"], last["n"]
        rows.append({"code": "libdem (PoCL)", "config": prec, "n": n, "steps": steps, "seconds": secs,
                     "rate": n * steps / secs, "floor_fz": last["floor_fz"], "kinetic": last["kinetic"],
                     "contacts_per_particle": 2 * last["contacts"] / n, "neighs_per_atom": None,
                     "timing": f"steps phase of the {full['steps_end']}-step run ({full['steps_s']:.2f} s) less that "
                               f"of a 1-step run ({one['steps_s']:.2f} s), so {steps} steps without the first "
                               f"step's one-off costs and the output",
                     "process_s": float(proc), "process_1step_s": float(proc1),
                     "setup_s": float(proc1) - one["steps_s"], "log": log, "output": h5})
    ref = next((q for q in rows if q["code"] == "LIGGGHTS" and q.get("ranks") == 2), None)
    if ref is None:
        sys.exit("peer.py: report needs the 2-rank LIGGGHTS run")
    meta = dict(m.split("=", 1) for m in a.meta)

    # physics first: every run's floor force against LIGGGHTS' 2-rank run
    print(f"\nFloor force after the steps (z of the force the floor receives; the bed weighs {weight:.6f} N):")
    bad = 0
    for q in rows:
        q["ratio"] = q["rate"] / ref["rate"]
        q["floor_diff"] = (q["floor_fz"] - ref["floor_fz"]) / abs(ref["floor_fz"])
        ok = abs(q["floor_diff"]) <= TOLERANCE
        bad += not ok
        print(f"  {q['code']:14s} {q['config']:11s} {q['floor_fz']:12.6f} N  {100 * q['floor_diff']:+7.3f} % "
              f"against LIGGGHTS 2 ranks  ({-q['floor_fz'] / weight:.4f} of the weight){'' if ok else '  BEYOND 2 %'}")

    print("Kinetic energy after the steps (translational + rotational): " +
          ", ".join(f"{q['code']} {q['config']} {q['kinetic']:.4g} J" for q in rows if q["kinetic"] is not None))
    print(f"\nMachine: {meta.get('cpu', '?')}, nproc {meta.get('nproc', '?')}. "
          f"{meta.get('liggghts_version', 'LIGGGHTS ?')}; {meta.get('pocl', 'PoCL ?')}; {meta.get('libdem', '?')}.")
    print(f"Bed: {ref['n']} spheres from {a.bed}; {ref['steps']} steps of dt = {meta.get('dt', '?')} s.")
    rmin = min(r)
    meta["neighbours"] = (f"LIGGGHTS: neighbor {meta.get('skin', '?')} bin (skin {1e3 * float(meta.get('skin', 'nan')):g} "
                          f"mm), neigh_modify delay 0 (checked every step, rebuilt once a particle moved half the "
                          f"skin), newton off; libdem: its default skin 0.3 x the smallest radius = "
                          f"{1e3 * 0.3 * rmin:.3g} mm, rebuilt once a particle moved half of it")
    print(f"Neighbours: {meta['neighbours']}")
    if meta.get("damping"):
        print(f"Damping: {meta['damping']}")
    print()
    print("| code | ranks / precision | particle-steps/s | ratio to LIGGGHTS 2 ranks | contacts per particle "
          "| neighbour pairs per particle |")
    print("|---|---|---:|---:|---:|---:|")
    for q in rows:
        nb = f"{q['neighs_per_atom']:.2f}" if q["neighs_per_atom"] is not None else "-"
        print(f"| {q['code']} | {q['config']} | {q['rate']:.3g} | {q['ratio']:.2f} | "
              f"{q['contacts_per_particle']:.2f} | {nb} |")
    print()
    print("  contacts per particle: 2 x touching pairs / particles after the steps (walls not counted; LIGGGHTS: "
          "compute contact/atom summed). Neighbour pairs: LIGGGHTS' 'Ave neighs/atom' (its half list, each pair "
          "once, within the cut-off plus the skin; libdem does not report its rows).")
    for q in rows:
        extra = (f"; whole process {q['process_s']:.1f} s, set-up {q['setup_s']:.1f} s" if "setup_s" in q else "")
        print(f"  {q['code']} {q['config']}: {q['seconds']:.2f} s for {q['steps']} steps; {q['timing']}{extra}")
    with open(a.json, "w") as f:
        json.dump({"meta": meta, "bed_weight_n": weight, "tolerance": TOLERANCE, "runs": rows,
                   "floor_force_ok": bad == 0}, f, indent=2)
    print(f"\nbench-peer: wrote {a.json}")
    if bad:
        print(f"bench-peer: FAILED: {bad} run(s) put a floor force more than {100 * TOLERANCE:g} % from LIGGGHTS' "
              "(the timings are not comparable until the physics agrees)", file=sys.stderr)
        return 1
    return 0


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    cmd, args = sys.argv[1], sys.argv[2:]
    if cmd == "pour" and len(args) == 2:
        return cmd_pour(*args)
    if cmd == "lammps" and len(args) == 4:
        return cmd_lammps(*args)
    if cmd == "report":
        ap = argparse.ArgumentParser(prog="peer.py report")
        ap.add_argument("--json", required=True)
        ap.add_argument("--bed", required=True)
        ap.add_argument("--density", type=float, required=True)
        ap.add_argument("--meta", action="append", default=[], help="KEY=VALUE for the table's header")
        ap.add_argument("--liggghts", action="append", default=[], help="RANKS:LOG")
        ap.add_argument("--dem", action="append", default=[],
                        help="PRECISION:OUT.h5:LOG:LOG_1STEP:PROCESS_S:PROCESS_1STEP_S")
        return cmd_report(ap.parse_args(args))
    sys.exit(__doc__)


if __name__ == "__main__":
    sys.exit(main())
