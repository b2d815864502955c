#!/usr/bin/python3
"""Does MDR's bulk response give back more work than it takes? A closed loop of one sphere between six planes, in
LAMMPS and in the Python reference (mdr_reference.py), no damping, no adhesion.

The six planes close in together to U0 = 0.21 R, past the point (about 0.19 R) where the sphere's free-surface
fraction falls below psi_b and Part II's bulk response acts (M10, M33, M35). Then the planes walk LOOPS square loops
in (u_x, u_y): both x planes in by A, both y planes in by A, the x planes back out by A, the y planes back out by A.
Each plane's inward travel times its force (trapezoidal rule) summed over the loop is the work put into the sphere,
W. After the first loop (which yields the x and y sides further) every loop walks the same states, so a
conservative law gives W = 0 up to the quadrature and a dissipative one W > 0. W < 0 is work the law makes.

The loop is walked at two step lengths, 1e-7 and 5e-8 m (0.1 and 0.05 m/s at cases.DT; tests/test_mdr_run.c
test_box_loop walks the same path through libdem and checks its loops' work against the LAMMPS figures printed here). The Python reference also walks it with the
bulk force (M35) taking this step's A_con and V_geo in place of last step's (M36: both lag by a step, as LAMMPS
has them), to show where the work comes from.

usage: energy_loop.py LMP_COMMAND OUTDIR    (writes OUTDIR/energy_loop.txt and the LAMMPS runs in OUTDIR/lammps_loop_*)
       energy_loop.py - OUTDIR             (the Python reference alone)
"""
import math
import os
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as C  # noqa: E402
import mdr_reference as M  # noqa: E402

U0 = 0.21 * C.R     # where the loops start: bulk response on
A = 0.01 * C.R      # the loop's side
LOOPS = 3
STEPS = (1.0e-7, 5.0e-8)   # m per step


def loop_path(step):
    """The planes' approach (u_x, u_y, u_z) at every step, each step `step` long; the step where loop 1 starts; the
    steps of a loop."""
    n0 = int(round(U0 / step))
    path = [(k * step,) * 3 for k in range(n0 + 1)]
    na = int(round(A / step))
    u = [n0 * step] * 3
    for _ in range(LOOPS):
        for ax, sign in ((0, 1), (1, 1), (0, -1), (1, -1)):
            for _ in range(na):
                u[ax] += sign * step
                path.append(tuple(u))
    return path, n0, 4 * na


def loop_work(path, n0, per, forces):
    """Work put into the sphere over each loop: forces[k] = the repulsive force of a +x, +y, +z plane at step k
    (the - planes carry the same by symmetry)."""
    out, w = [], 0.0
    for k in range(n0 + 1, len(path)):
        for ax in range(3):
            w += 2.0 * 0.5 * (forces[k][ax] + forces[k - 1][ax]) * (path[k][ax] - path[k - 1][ax])
        if (k - n0) % per == 0:
            out.append(w)
            w = 0.0
    return out


def reference_forces(path, current=False):
    """The Python reference on the path. current: the bulk force takes this step's A_con and V_geo."""
    mat = M.Material(C.E, C.NU, C.Y, 0.0, C.PSI_B, 0.0)
    p = M.Particle(C.R, 1.0)
    sides = [M.Side() for _ in range(6)]
    forces = [(0.0, 0.0, 0.0)]
    vo = 4.0 / 3.0 * math.pi * C.R ** 3
    for u in path[1:]:
        p.begin_step(mat)
        d = [p.R - (C.R - u[k // 2]) for k in range(6)]
        for k in range(6):
            p.add_surface_motion(sides[k], d[k])
        f = [M.side_force(mat, sides[k], p, d[k])[0] for k in range(6)]
        if current:
            vgeo = min(4.0 / 3.0 * math.pi * p.R ** 3 - p.Vcaps, vo)
            for k, s in enumerate(sides):
                if s.delta_bulk > 0.0:
                    f[k] += mat.kappa * s.delta_bulk * s.Ac * (p.Acon1 / vgeo - p.Acon0 / p.Vgeo)
        # the wall magnifier (M39), as LAMMPS applies it (about 1 + 5e-4 here)
        forces.append(tuple(f[2 * ax] * (1.0 + math.exp(10.7 * sides[2 * ax].deltao / p.Ro - 10.0))
                            for ax in range(3)))
    return forces


def lammps_forces(lmp, wd, path, n0, step):
    """LAMMPS on the path: one run per straight piece, each plane a region moved by an equal-style variable."""
    os.makedirs(wd, exist_ok=True)
    R = C.R
    mdr = f"mdr {C.E!r} {C.NU!r} {C.Y!r} 0.0 {C.PSI_B!r} 0.0 damping mdr 1 tangential linear_nohistory 0 0"
    lines = ["units si", "atom_style sphere", "atom_modify map array", "newton off", "comm_modify vel yes",
             "boundary f f f", f"region box block {-4 * R!r} {4 * R!r} {-4 * R!r} {4 * R!r} {-4 * R!r} {4 * R!r}",
             "create_box 1 box", "create_atoms 1 single 0 0 0", f"set atom * diameter {2 * R!r} density {C.RHO!r}",
             f"neighbor {0.5 * R!r} bin", "neigh_modify every 1 delay 0 check yes", "pair_style granular",
             f"pair_coeff * * {mdr}", f"timestep {C.DT!r}",
             "variable ux equal 0.0", "variable uy equal 0.0", "variable uz equal 0.0",
             "variable mx equal -v_ux", "variable px equal v_ux", "variable my equal -v_uy", "variable py equal v_uy",
             "variable mz equal -v_uz", "variable pz equal v_uz"]
    for name, pos, normal, mv in (("xp", (R, 0, 0), (-1, 0, 0), "v_mx NULL NULL"),
                                  ("xm", (-R, 0, 0), (1, 0, 0), "v_px NULL NULL"),
                                  ("yp", (0, R, 0), (0, -1, 0), "NULL v_my NULL"),
                                  ("ym", (0, -R, 0), (0, 1, 0), "NULL v_py NULL"),
                                  ("zp", (0, 0, R), (0, 0, -1), "NULL NULL v_mz"),
                                  ("zm", (0, 0, -R), (0, 0, 1), "NULL NULL v_pz")):
        lines += [f"region {name} plane {pos[0]!r} {pos[1]!r} {pos[2]!r} {normal[0]} {normal[1]} {normal[2]} "
                  f"side in units box move {mv} units box",
                  f"fix w{name} all wall/gran/region granular {mdr} region {name} contacts"]
    lines += ["fix m1 all move linear 0 0 0",
              "dump d all custom 1 dump.loop id f_wxp[2] f_wyp[3] f_wzp[4]", "dump_modify d format float %.17g",
              "thermo 100000"]
    # straight pieces: (axes moving, sign, steps)
    pieces = [((0, 1, 2), 1, n0)]
    na = int(round(A / step))
    for _ in range(LOOPS):
        pieces += [((0,), 1, na), ((1,), 1, na), ((0,), -1, na), ((1,), -1, na)]
    k = 0
    for axes, sign, n in pieces:
        for ax in range(3):
            start = path[k][ax]
            if ax in axes:
                lines.append(f"variable u{'xyz'[ax]} equal {start!r}{'+' if sign > 0 else '-'}{step!r}*elapsed")
            else:
                lines.append(f"variable u{'xyz'[ax]} equal {start!r}")
        lines.append(f"run {n}")
        k += n
    with open(os.path.join(wd, "in.loop"), "w") as f:
        f.write("# written by tools/peer_mdr/energy_loop.py\n" + "\n".join(lines) + "\n")
    r = subprocess.run(shlex.split(lmp) + ["-in", "in.loop", "-log", "log.lammps", "-screen", "none"], cwd=wd)
    if r.returncode != 0:
        sys.exit(f"energy_loop: LAMMPS failed (see {wd}/log.lammps)")
    rows = {}
    with open(os.path.join(wd, "dump.loop")) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step_no = int(lines[i + 1])
            v = lines[i + 9].split()
            rows[step_no] = (-float(v[1]), -float(v[2]), -float(v[3]))  # the + planes push along -x, -y, -z
            i += 10
        else:
            i += 1
    os.remove(os.path.join(wd, "dump.loop"))
    return [rows.get(s, (0.0, 0.0, 0.0)) for s in range(len(path))]


def main():
    lmp, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    lines = [f"# energy_loop: one sphere (R {C.R:g} m, E {C.E:g} Pa, nu {C.NU:g}, Y {C.Y:g} Pa, psi_b {C.PSI_B:g}, "
             f"no damping, no adhesion) between six planes closed in to {U0 / C.R:g} R, then {LOOPS} square loops "
             f"of side {A / C.R:g} R in (u_x, u_y)",
             "# work put into the sphere per loop [J] (negative: the law gave back more than it took)",
             "who,step_m,loop_1,loop_2,loop_3,later_loop_over_loop_1"]
    ok = True
    for k, step in enumerate(STEPS):
        path, n0, per = loop_path(step)
        runs = [("reference", reference_forces(path)),
                ("reference, this step's A_con and V_geo in (M35)", reference_forces(path, current=True))]
        if lmp != "-":
            runs.insert(0, ("LAMMPS", lammps_forces(lmp, os.path.join(outdir, f"lammps_loop_{k}"), path, n0, step)))
        for who, forces in runs:
            w = loop_work(path, n0, per, forces)
            lines.append(f"{who},{step:.4g},{w[0]:.9e},{w[1]:.9e},{w[2]:.9e},{w[2] / w[0]:.3e}")
        if lmp != "-":
            wl, wr = loop_work(path, n0, per, runs[0][1]), loop_work(path, n0, per, runs[1][1])
            ok = ok and all(abs(a - b) <= 1e-6 * abs(wl[0]) for a, b in zip(wl, wr))
    text = "\n".join(lines) + "\n"
    with open(os.path.join(outdir, "energy_loop.txt"), "w") as f:
        f.write(text)
    print(text, end="")
    if not ok:
        sys.exit("energy_loop: LAMMPS and the reference differ by more than 1e-6 of the first loop's work")


if __name__ == "__main__":
    main()
