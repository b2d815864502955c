#!/usr/bin/python3
"""Does MDR's bulk response give back more work than it takes? Closed loops of one sphere between six planes, in
LAMMPS and in the Python reference (mdr_reference.py), no damping, no adhesion. Two kinds of loop
(docs/laws/mdr.md "Energy"):

Squeeze loops. The six planes close in together to U0 = 0.21 R, past the point (about 0.19 R) where the sphere's
free-surface fraction falls below psi_b and Part II's bulk response acts (M10, M33, M35). Then the planes walk LOOPS
square loops in (u_x, u_y): both x planes in by A, both y planes in by A, the x planes back out by A, the y planes
back out by A. Each plane's inward travel times its force (trapezoidal rule) summed over the planes and the loop is
the work put into the sphere, W. After the first loop (which yields the x and y sides further) every loop walks the
same states, so a conservative law gives W = 0 up to the quadrature and a dissipative one W > 0. W < 0 is work the
law makes. Walked at 1e-7 and 5e-8 m a step (0.1 and 0.05 m/s at cases.DT); the Python reference also walks it with
the bulk force (M35) taking this step's A_con and V_geo in place of last step's (M36: both lag by a step, as LAMMPS
has them), to show where the work comes from: the lag, in proportion to the step.

Translation loops. The planes close in to unequal depths (DEPTHS), then the sphere moves round squares of side A in
(x, y) relative to them, in both senses, at 1e-7, 5e-8 and 2.5e-8 m a step. What remains of a loop's work as the
step goes to zero (2 W(h/2) - W(h)) changes sign with the sense: the bulk response's stiffness is not symmetric, so
some closed paths get work out of it, lag or no lag. The same loops with psi_b 0 (no bulk response) are the control.

tests/test_mdr_run.c test_box_loop and test_translate_loop walk the same paths through libdem and check the work
against the LAMMPS figures printed here.

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

U0 = 0.21 * C.R     # where the squeeze loops start: bulk response on
A = 0.01 * C.R      # a loop's side
LOOPS = 3
STEPS = (1.0e-7, 5.0e-8)   # m per step of the squeeze loops
# The translation loops: the six planes (+x, -x, +y, -y, +z, -z) close in to unequal depths in NC steps, then the
# sphere moves round a square of side A in (x, y) relative to them, at three step lengths, in both senses
DEPTHS = tuple(f * C.R for f in (0.25, 0.17, 0.22, 0.20, 0.23, 0.19))
NC = 1250
TSTEPS = (1.0e-7, 5.0e-8, 2.5e-8)
PLANES = ("xp", "xm", "yp", "ym", "zp", "zm")  # plane k faces the sphere from +-axis k // 2 (+ for even k)


def walk(pieces):
    """The planes' approaches u[0..5] at every step of a list of straight pieces (steps, rate per step of each
    plane), each piece from where the last ended: u = start + rate * j (as LAMMPS's equal-style variables have it)."""
    path = [(0.0,) * 6]
    for n, rate in pieces:
        start = path[-1]
        path += [tuple(start[q] + rate[q] * j for q in range(6)) for j in range(1, n + 1)]
    return path


def squeeze_pieces(step):
    """Both x planes in by A, both y planes in by A, the x planes back out, the y planes back out; from U0."""
    n0, na = int(round(U0 / step)), int(round(A / step))
    pieces = [(n0, (step,) * 6)]
    for _ in range(LOOPS):
        for ax, sign in ((0, 1), (1, 1), (0, -1), (1, -1)):
            pieces.append((na, tuple(sign * step if q // 2 == ax else 0.0 for q in range(6))))
    return pieces, n0, 4 * na


def translate_pieces(step, reverse):
    """The sphere moved round a square in (x, y) relative to the planes: +x, +y, -x, -y (reverse: +y, +x, -y, -x).
    Moving the sphere by +s along an axis brings that axis's + plane in by s and takes its - plane out by s."""
    na = int(round(A / step))
    pieces = [(NC, tuple(d / NC for d in DEPTHS))]
    legs = ((1, 1), (0, 1), (1, -1), (0, -1)) if reverse else ((0, 1), (1, 1), (0, -1), (1, -1))
    for _ in range(LOOPS):
        for ax, sign in legs:
            pieces.append((na, tuple((sign * step if q % 2 == 0 else -sign * step) if q // 2 == ax else 0.0
                                     for q in range(6))))
    return pieces, NC, 4 * na


def loop_work(path, n0, per, forces):
    """Work put into the sphere over each loop: the planes' travel inwards times their repulsive forces forces[k]
    (trapezoidal rule), summed over the planes and over a loop."""
    out, w = [], 0.0
    for k in range(n0 + 1, len(path)):
        for q in range(6):
            w += 0.5 * (forces[k][q] + forces[k - 1][q]) * (path[k][q] - path[k - 1][q])
        if (k - n0) % per == 0:
            out.append(w)
            w = 0.0
    return out


def reference_forces(path, current=False, psi_b=C.PSI_B):
    """The Python reference on the path: each plane's repulsive force. current: the bulk force takes this step's
    A_con and V_geo."""
    mat = M.Material(C.E, C.NU, C.Y, 0.0, psi_b, 0.0)
    p = M.Particle(C.R, 1.0)
    sides = [M.Side() for _ in range(6)]
    forces = [(0.0,) * 6]
    vo = 4.0 / 3.0 * math.pi * C.R ** 3
    for u in path[1:]:
        p.begin_step(mat)
        d = [p.R - (C.R - u[k]) for k in range(6)]
        for k in range(6):
            p.add_surface_motion(sides[k], d[k])
        f = [M.side_force(mat, sides[k], p, d[k])[0] for k in range(6)]
        if current:
            vgeo = min(4.0 / 3.0 * math.pi * p.R ** 3 - p.Vcaps, vo)
            for k, s in enumerate(sides):
                if s.delta_bulk > 0.0:
                    f[k] += mat.kappa * s.delta_bulk * s.Ac * (p.Acon1 / vgeo - p.Acon0 / p.Vgeo)
        # the wall magnifier (M39), as LAMMPS applies it (about 1 + 5e-4 here)
        forces.append(tuple(f[k] * (1.0 + math.exp(10.7 * sides[k].deltao / p.Ro - 10.0)) for k in range(6)))
    return forces


def lammps_forces(lmp, wd, pieces):
    """LAMMPS on the path: one run per straight piece, each plane a region moved by its own equal-style variable."""
    os.makedirs(wd, exist_ok=True)
    R = C.R
    mdr = f"mdr {C.E!r} {C.NU!r} {C.Y!r} 0.0 {C.PSI_B!r} 0.0 damping mdr 1 tangential linear_nohistory 0 0"
    lines = ["units si", "atom_style sphere", "atom_modify map array", "newton off", "comm_modify vel yes",
             "boundary f f f", f"region box block {-4 * R!r} {4 * R!r} {-4 * R!r} {4 * R!r} {-4 * R!r} {4 * R!r}",
             "create_box 1 box", "create_atoms 1 single 0 0 0", f"set atom * diameter {2 * R!r} density {C.RHO!r}",
             f"neighbor {0.5 * R!r} bin", "neigh_modify every 1 delay 0 check yes", "pair_style granular",
             f"pair_coeff * * {mdr}", f"timestep {C.DT!r}"]
    lines += [f"variable u{name} equal 0.0" for name in PLANES]
    lines += [f"variable m{name} equal {'-' if k % 2 == 0 else ''}v_u{name}" for k, name in enumerate(PLANES)]
    for k, name in enumerate(PLANES):
        ax, sg = k // 2, 1 if k % 2 == 0 else -1
        pos, normal, mv = [0, 0, 0], [0, 0, 0], ["NULL"] * 3
        pos[ax], normal[ax], mv[ax] = sg * R, -sg, f"v_m{name}"
        lines += [f"region {name} plane {pos[0]!r} {pos[1]!r} {pos[2]!r} {normal[0]} {normal[1]} {normal[2]} "
                  f"side in units box move {' '.join(mv)} units box",
                  f"fix w{name} all wall/gran/region granular {mdr} region {name} contacts"]
    # the force on the sphere along each plane's axis (f_w..[2..4]: x, y, z)
    cols = " ".join(f"f_w{name}[{2 + k // 2}]" for k, name in enumerate(PLANES))
    lines += ["fix m1 all move linear 0 0 0", f"dump d all custom 1 dump.loop id {cols}",
              "dump_modify d format float %.17g", "thermo 100000"]
    path, at = walk(pieces), 0  # each piece starts where walk() has the last one end
    for n, rate in pieces:
        for q, name in enumerate(PLANES):
            lines.append(f"variable u{name} equal {path[at][q]!r}" + (f"+{rate[q]!r}*elapsed" if rate[q] else ""))
        lines.append(f"run {n}")
        at += n
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
            # a + plane pushes the sphere along -axis, a - plane along +axis: the repulsive force of each
            rows[step_no] = tuple((-1.0 if k % 2 == 0 else 1.0) * float(v[1 + k]) for k in range(6))
            i += 10
        else:
            i += 1
    os.remove(os.path.join(wd, "dump.loop"))
    return [rows.get(s, (0.0,) * 6) for s in range(len(path))]


def runs_of(lmp, outdir, tag, pieces, current=True):
    """The work per loop on one path: LAMMPS (unless lmp is "-"), the reference, and (current) the reference with
    this step's A_con and V_geo; and whether LAMMPS and the reference agree to 1e-6 of the first loop's work."""
    path = walk(pieces[0])
    n0, per = pieces[1], pieces[2]
    runs = [("reference", reference_forces(path))]
    if current:
        runs.append(("reference, this step's A_con and V_geo in (M35)", reference_forces(path, current=True)))
    if lmp != "-":
        runs.insert(0, ("LAMMPS", lammps_forces(lmp, os.path.join(outdir, f"lammps_loop_{tag}"), pieces[0])))
    work = [(who, loop_work(path, n0, per, forces)) for who, forces in runs]
    ok = lmp == "-" or all(abs(a - b) <= 1e-6 * abs(work[0][1][0]) for a, b in zip(work[0][1], work[1][1]))
    return work, ok


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
        work, agree = runs_of(lmp, outdir, k, squeeze_pieces(step))
        ok = ok and agree
        for who, w in work:
            lines.append(f"{who},{step:.4g},{w[0]:.9e},{w[1]:.9e},{w[2]:.9e},{w[2] / w[0]:.3e}")
    depths = ", ".join(f"{d / C.R:g}" for d in DEPTHS)
    lines += [f"# translation loops: the same sphere between six planes closed in to unequal depths (+x, -x, +y, -y, "
              f"+z, -z: {depths} R) in {NC} steps, then moved round {LOOPS} squares of side {A / C.R:g} R in (x, y) "
              "relative to the planes: forward +x, +y, -x, -y; reverse +y, +x, -y, -x",
              "# work put into the sphere per loop [J]; 'limit' rows: 2 W(h/2) - W(h) from the two shortest steps "
              "(the part in proportion to the step taken out)",
              "who,sense,step_m,loop_1,loop_2,loop_3"]
    for sense in ("forward", "reverse"):
        by_who = {}
        for k, step in enumerate(TSTEPS):
            work, agree = runs_of(lmp, outdir, f"{sense}_{k}", translate_pieces(step, sense == "reverse"))
            ok = ok and agree
            for who, w in work:
                by_who.setdefault(who, []).append(w)
                lines.append(f"{who},{sense},{step:.4g},{w[0]:.9e},{w[1]:.9e},{w[2]:.9e}")
        for who, ws in by_who.items():
            lim = [2.0 * b - a for a, b in zip(ws[-2], ws[-1])]
            lines.append(f"{who},{sense},limit,{lim[0]:.9e},{lim[1]:.9e},{lim[2]:.9e}")
    # the control: the same loops with psi_b 0, where the bulk response never acts (the reference alone)
    lines.append("# the same with psi_b 0 (no bulk response; the reference): who,sense,step_m,loop_1,loop_2,loop_3")
    for sense in ("forward", "reverse"):
        ws = []
        for step in TSTEPS[1:]:
            pieces, n0, per = translate_pieces(step, sense == "reverse")
            path = walk(pieces)
            ws.append(loop_work(path, n0, per, reference_forces(path, psi_b=0.0)))
            lines.append(f"reference psi_b 0,{sense},{step:.4g},{ws[-1][0]:.9e},{ws[-1][1]:.9e},{ws[-1][2]:.9e}")
        lim = [2.0 * b - a for a, b in zip(ws[0], ws[1])]
        lines.append(f"reference psi_b 0,{sense},limit,{lim[0]:.9e},{lim[1]:.9e},{lim[2]:.9e}")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(outdir, "energy_loop.txt"), "w") as f:
        f.write(text)
    print(text, end="")
    if not ok:
        sys.exit("energy_loop: LAMMPS and the reference differ by more than 1e-6 of the first loop's work")


if __name__ == "__main__":
    main()
