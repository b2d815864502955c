#!/usr/bin/python3
"""Single MDR contacts in LAMMPS, driven by prescribed displacement: two equal spheres (pair granular mdr), one
sphere against a flat wall (fix wall/gran/region with mdr; LAMMPS's MDR refuses plain fix wall/gran), and one
sphere between six planes closing in together (Part II's confinement: the free surface shrinks below psi_b and
the bulk response starts).

Each case of cases.SINGLE loads beyond yield, unloads past zero force, reloads past the first maximum and
unloads out of contact, at the step and speed of cases.py. Writes out/peer_mdr/single_<case>.csv (force against apparent overlap) and the LAMMPS input
and log beside it.

usage: lammps_single.py LMP_COMMAND OUTDIR   (LMP_COMMAND: e.g. "env LD_LIBRARY_PATH=V/lib V/bin/lmp")
"""
import os
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as C  # noqa: E402

HEADER = ("# MDR single contact, LAMMPS {version}; case {case}: {kind}, E {E:g} Pa, nu {nu:g}, Y {Y:g} Pa, "
          "gamma {gamma:g} J/m^2, psi_b {psi_b:g}, damping mdr 1 coefficient {damp:g}, R {R:g} m, "
          "density {rho:g} kg/m^3, dt {dt:g} s\n"
          "# force_N is the normal force on the sphere (repulsive > 0; box: from the +x plane), damping included; "
          "overlap_m is the apparent overlap (current radii); psi: the sphere's free-surface fraction\n"
          "step,time_s,approach_m,overlap_m,radius_m,force_N,psi\n")


def write_input(case, spec, path):
    kind = spec["kind"]
    n = C.phase_steps(spec["path"])
    ends = C.phase_ends(spec["path"])
    R = C.R
    E, nu, Y, gamma, psi_b, damp = C.material_of(spec)
    mdr = f"mdr {E!r} {nu!r} {Y!r} {gamma!r} {psi_b!r} {damp!r} damping mdr 1 tangential linear_nohistory 0 0"
    lines = [
        "units si", "atom_style sphere", "atom_modify map array", "newton off", "comm_modify vel yes",
        "boundary f f f",
        f"region box block {-4 * R!r} {6 * R!r} {-4 * R!r} {4 * R!r} {-4 * R!r} {6 * R!r}",
        "create_box 1 box",
    ]
    if kind == "pair":
        # sphere 1 (radius R) at the origin stays put; sphere 2 (radius R2, R unless the case says) starts
        # touching and moves along -x
        R2 = spec.get("R2", R)
        lines += ["create_atoms 1 single 0 0 0", f"create_atoms 1 single {R + R2!r} 0 0"]
    elif kind == "wall":
        # one sphere touching the plane z = 0 from above, moved along -z
        lines += [f"create_atoms 1 single 0 0 {R!r}"]
    else:
        # one sphere at the origin between six planes that touch it and close in together
        lines += ["create_atoms 1 single 0 0 0"]
    lines += [
        f"set atom * diameter {2 * R!r} density {C.RHO!r}",
        f"set atom 2 diameter {2 * spec.get('R2', R)!r} density {C.RHO!r}" if kind == "pair" else "",
        f"neighbor {0.5 * R!r} bin", "neigh_modify every 1 delay 0 check yes",
        "pair_style granular", f"pair_coeff * * {mdr}",
        f"timestep {C.DT!r}",
        "variable u equal 0.0", "variable w equal 0.0",
    ]
    if kind == "pair":
        lines += ["group g1 id 1", "group g2 id 2", "fix m1 g1 move linear 0 0 0",
                  "variable dx equal -v_u", "variable vx equal -v_w",
                  "fix m2 g2 move variable v_dx NULL NULL v_vx NULL NULL"]
        dump = "dump d all custom {e} dump.single id x y z radius fx fy fz d_psi"
    elif kind == "wall":
        lines += ["region floor plane 0 0 0 0 0 1 side in units box",
                  f"fix wall all wall/gran/region granular {mdr} region floor contacts",
                  "variable dz equal -v_u", "variable vz equal -v_w",
                  "fix m1 all move variable NULL NULL v_dz NULL NULL v_vz"]
        dump = "dump d all custom {e} dump.single id x y z radius fx fy fz d_psi"
    else:
        # the planes move in by u; the force reported is the one from the +x plane (all six are alike)
        lines += ["variable m equal -v_u", "variable p equal v_u"]
        for name, pos, normal, mv in (("xp", (R, 0, 0), (-1, 0, 0), "v_m NULL NULL"),
                                      ("xm", (-R, 0, 0), (1, 0, 0), "v_p NULL NULL"),
                                      ("yp", (0, R, 0), (0, -1, 0), "NULL v_m NULL"),
                                      ("ym", (0, -R, 0), (0, 1, 0), "NULL v_p NULL"),
                                      ("zp", (0, 0, R), (0, 0, -1), "NULL NULL v_m"),
                                      ("zm", (0, 0, -R), (0, 0, 1), "NULL NULL v_p")):
            lines += [f"region {name} plane {pos[0]!r} {pos[1]!r} {pos[2]!r} {normal[0]} {normal[1]} {normal[2]} "
                      f"side in units box move {mv} units box",
                      f"fix w{name} all wall/gran/region granular {mdr} region {name} contacts"]
        lines += ["fix m1 all move linear 0 0 0"]
        dump = "dump d all custom {e} dump.single id x y z radius f_wxp[2] fy fz d_psi"
    lines += [dump.format(e=C.DUMP_EVERY), "dump_modify d format float %.17g", "thermo 10000"]
    for k in range(len(n)):
        sign = "+" if ends[k + 1] > ends[k] else "-"
        # approach u and its rate w (the velocity that the damping sees)
        lines += [f"variable u equal {ends[k]!r}{sign}{C.STEP!r}*elapsed",
                  f"variable w equal {'' if sign == '+' else '-'}{C.STEP / C.DT!r}", f"run {n[k]}"]
    with open(path, "w") as f:
        f.write(f"# {case}: written by tools/peer_mdr/lammps_single.py\n" + "\n".join(lines) + "\n")


def parse_dump(path, kind):
    rows = {}
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            natoms = int(lines[i + 3])
            atoms = {}
            for line in lines[i + 9:i + 9 + natoms]:
                v = line.split()
                atoms[int(v[0])] = [float(x) for x in v[1:]]
            rows[step] = atoms          # a run's setup repeats the previous run's last step: same values
            i += 9 + natoms
        else:
            i += 1
    out = []
    for step in sorted(rows):
        a = rows[step]
        x1, y1, z1, r1, fx1, fy1, fz1, psi = a[1]
        if kind == "pair":
            x2, y2, z2, r2 = a[2][:4]
            overlap = r1 + r2 - ((x2 - x1) ** 2 + (y2 - y1) ** 2 + (z2 - z1) ** 2) ** 0.5
            force = -fx1
        elif kind == "wall":
            overlap = r1 - z1
            force = fz1
        else:
            overlap = None          # the +x plane's overlap is R - (R - u): written by main from the path
            force = -fx1            # fx1 is the +x plane's force on the sphere here
        out.append((step, overlap, r1, force, psi))
    return out


def lammps_version(lmp):
    r = subprocess.run(shlex.split(lmp) + ["-h"], capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if line.startswith("Large-scale Atomic/Molecular Massively Parallel Simulator"):
            return line.split(" - ", 1)[1].strip()
    return "unknown"


def main():
    lmp, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    version = lammps_version(lmp)
    for case, spec in C.SINGLE.items():
        wd = os.path.join(outdir, "lammps_" + case)
        os.makedirs(wd, exist_ok=True)
        write_input(case, spec, os.path.join(wd, "in.single"))
        t0 = time.time()
        r = subprocess.run(shlex.split(lmp) + ["-in", "in.single", "-log", "log.lammps", "-screen", "none"],
                           cwd=wd)
        if r.returncode != 0:
            sys.exit(f"lammps_single: LAMMPS failed on {case} (see {wd}/log.lammps)")
        rows = parse_dump(os.path.join(wd, "dump.single"), spec["kind"])
        csv = os.path.join(outdir, f"single_{case}.csv")
        with open(csv, "w") as f:
            E, nu, Y, gamma, psi_b, damp = C.material_of(spec)
            f.write(HEADER.format(version=version, case=case, kind=spec["kind"], E=E, nu=nu, Y=Y, gamma=gamma,
                                  psi_b=psi_b, damp=damp, R=C.R, rho=C.RHO, dt=C.DT))
            for step, overlap, radius, force, psi in rows:
                u = C.approach_at(spec["path"], step)
                if overlap is None:
                    overlap = radius - (C.R - u)
                f.write(f"{step},{step * C.DT!r},{u!r},{overlap!r},{radius!r},{force!r},{psi!r}\n")
        os.remove(os.path.join(wd, "dump.single"))
        print(f"lammps_single: {case}: {sum(C.phase_steps(spec['path']))} steps in {time.time() - t0:.1f} s "
              f"-> {csv}")


if __name__ == "__main__":
    main()
