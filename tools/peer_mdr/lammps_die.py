#!/usr/bin/python3
"""A small MDR die compaction in LAMMPS: cases.DIE's spheres (polydisperse, seeded) inserted at random without
overlap in a cylindrical die, poured under gravity, then the upper punch moves down at constant speed until its
force reaches p_max times the die's cross-section, and back up at the same speed until it leaves the compact.

Particles: pair_style granular mdr (cases.py's material, surface energy GAMMA_ADH), tangential linear_history
(k_t = 2/7 E r_mean, friction mu_p), damping mdr 1. Walls (die: region cylinder; punches: region plane) with
fix wall/gran/region, mdr, surface energy gamma_w, friction mu_w. Newton off (MDR needs it). Masses scaled by
DIE['mass_scale'] (density x100) so that the press runs in minutes on one core at dt = 1e-6 s.

Writes OUTDIR/die_packing.csv (the spheres when the punch starts: id, x, y, z, radius: the scene to load in a
libdem comparison), OUTDIR/die_force.csv (punch force against punch displacement) and the LAMMPS input and log in
OUTDIR/lammps_die/.

usage: lammps_die.py LMP_COMMAND OUTDIR
"""
import math
import os
import random
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as C  # noqa: E402
from lammps_single import lammps_version  # noqa: E402

D = C.DIE
DT = 1.0e-6
CHUNK = 500          # steps between force checks during the press


def packing():
    """Random sequential insertion without overlap into a cylinder, bottom up (seeded: the same spheres on every
    machine)."""
    rng = random.Random(D["seed"])
    rd = D["die_radius"]
    spheres = []
    z_lo = 0.0
    # insert into a tall column with a solid fraction of about 0.2
    vol = sum(4.0 / 3.0 * math.pi * ((D["r_min"] + D["r_max"]) / 2) ** 3 for _ in range(D["n"]))
    height = vol / (0.20 * math.pi * rd * rd)
    cells = {}
    h = 2.0 * D["r_max"]

    def key(x, y, z):
        return (int(math.floor(x / h)), int(math.floor(y / h)), int(math.floor(z / h)))

    while len(spheres) < D["n"]:
        r = rng.uniform(D["r_min"], D["r_max"])
        for _ in range(100000):
            rho = (rd - r) * math.sqrt(rng.random())
            phi = rng.uniform(0.0, 2.0 * math.pi)
            x, y = rho * math.cos(phi), rho * math.sin(phi)
            z = rng.uniform(z_lo + r, z_lo + height - r)
            kx, ky, kz = key(x, y, z)
            ok = True
            for i in range(kx - 1, kx + 2):
                for j in range(ky - 1, ky + 2):
                    for k in range(kz - 1, kz + 2):
                        for (xs, ys, zs, rs) in cells.get((i, j, k), ()):
                            if (xs - x) ** 2 + (ys - y) ** 2 + (zs - z) ** 2 < (r + rs) ** 2 * 1.0001:
                                ok = False
                                break
                        if not ok:
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if ok:
                spheres.append((x, y, z, r))
                cells.setdefault((kx, ky, kz), []).append((x, y, z, r))
                break
        else:
            raise RuntimeError("packing: no room left")
    return spheres, height


def write_data(path, spheres, height):
    rd = D["die_radius"]
    rho = C.RHO * D["mass_scale"]
    with open(path, "w") as f:
        f.write("MDR die compaction, tools/peer_mdr/lammps_die.py\n\n")
        f.write(f"{len(spheres)} atoms\n1 atom types\n\n")
        f.write(f"{-1.2 * rd!r} {1.2 * rd!r} xlo xhi\n{-1.2 * rd!r} {1.2 * rd!r} ylo yhi\n")
        f.write(f"{-0.5e-3!r} {height + 2e-3!r} zlo zhi\n\nAtoms # sphere\n\n")
        for i, (x, y, z, r) in enumerate(spheres):
            f.write(f"{i + 1} 1 {2 * r!r} {rho!r} {x!r} {y!r} {z!r}\n")


def write_input(path, height):
    rd = D["die_radius"]
    r_mean = 0.5 * (D["r_min"] + D["r_max"])
    kt = 2.0 / 7.0 * C.E * r_mean
    area = math.pi * rd * rd
    f_max = D["p_max"] * area
    v = D["punch_speed"]
    mdr_p = (f"mdr {C.E!r} {C.NU!r} {C.Y!r} {C.GAMMA_ADH!r} {C.PSI_B!r} {C.DAMP!r} damping mdr 1 "
             f"tangential linear_history {kt!r} 1.0 {D['mu_p']!r}")
    mdr_w = (f"granular mdr {C.E!r} {C.NU!r} {C.Y!r} {D['gamma_w']!r} {C.PSI_B!r} {C.DAMP!r} damping mdr 1 "
             f"tangential linear_history {kt!r} 1.0 {D['mu_w']!r}")
    top = height + 1e-3
    lines = f"""# written by tools/peer_mdr/lammps_die.py
units si
atom_style sphere 1
atom_modify map array
comm_modify vel yes
newton off
boundary f f f
read_data die.data
neighbor {0.5 * D['r_max']!r} bin
neigh_modify every 1 delay 0 check yes
timestep {DT!r}
pair_style granular
pair_coeff * * {mdr_p}
variable disp_upper equal 0.0
region lowerPunch plane 0 0 0 0 0 1 side in units box
region upperPunch plane 0 0 {top!r} 0 0 -1 side in units box move NULL NULL v_disp_upper units box
region die cylinder z 0 0 {rd!r} -1 1 side in units box
fix lowerPunch all wall/gran/region {mdr_w} region lowerPunch contacts
fix upperPunch all wall/gran/region {mdr_w} region upperPunch contacts
fix die all wall/gran/region {mdr_w} region die contacts
compute fUp all reduce sum f_upperPunch[4]
compute fLo all reduce sum f_lowerPunch[4]
compute ztop all reduce max z
variable fup equal -c_fUp
variable flo equal c_fLo
fix 1 all nve/sphere
velocity all set 0 0 -0.3 units box
fix grav all gravity 9.81 vector 0 0 -1
compute ke all ke
thermo_style custom step atoms ke c_ztop v_fup v_flo
thermo 5000
thermo_modify lost error norm no
# pour and settle
run 60000
variable ztopnow equal c_ztop
run 20000
# start the punch just above the highest sphere: it moves down from top - gap
variable gap equal {top!r}-(${{ztopnow}}+{D['r_max']!r})
variable s0 equal step
variable s0 equal ${{s0}}
write_dump all custom die_start.dump id x y z radius modify format float %.17g
variable disp_upper equal -v_gap-{v!r}*(step-v_s0)*dt
variable pdisp equal -v_disp_upper-v_gap
fix out all print 100 "${{pdisp}},${{fup}},${{flo}}" file die_force_raw.csv screen no title "punch_disp_m,upper_force_N,lower_force_N"
label press
run {CHUNK} post no
if "${{fup}} < {f_max!r}" then "jump SELF press"
# back up at the same speed until the punch has left the compact
variable dmax equal v_pdisp
variable dmax equal ${{dmax}}
variable s1 equal step
variable s1 equal ${{s1}}
variable disp_upper equal -v_gap-v_dmax+{v!r}*(step-v_s1)*dt
label release
run {CHUNK} post no
if "${{fup}} > 0.0" then "jump SELF release"
run 5000 post no
"""
    with open(path, "w") as f:
        f.write(lines)
    return f_max, area


def main():
    lmp, outdir = sys.argv[1], sys.argv[2]
    wd = os.path.join(outdir, "lammps_die")
    os.makedirs(wd, exist_ok=True)
    version = lammps_version(lmp)
    spheres, height = packing()
    write_data(os.path.join(wd, "die.data"), spheres, height)
    f_max, area = write_input(os.path.join(wd, "in.die"), height)
    t0 = time.time()
    r = subprocess.run(shlex.split(lmp) + ["-in", "in.die", "-log", "log.lammps", "-screen", "none"], cwd=wd)
    wall = time.time() - t0
    if r.returncode != 0:
        sys.exit(f"lammps_die: LAMMPS failed (see {wd}/log.lammps)")
    # the packing at the punch's start, for a libdem scene of the same press
    with open(os.path.join(wd, "die_start.dump")) as f:
        lines = f.read().split("\n")
    n = int(lines[3])
    atoms = sorted((line.split() for line in lines[9:9 + n]), key=lambda v: int(v[0]))
    # the upper punch starts r_max above the highest centre (in.die: 'gap')
    z_start = max(float(v[3]) for v in atoms) + D["r_max"]
    v_solid = sum(4.0 / 3.0 * math.pi * float(v[4]) ** 3 for v in atoms)
    with open(os.path.join(outdir, "die_packing.csv"), "w") as f:
        f.write(f"# MDR die compaction, LAMMPS {version}: the spheres when the upper punch starts (after the pour)\n"
                f"# die radius {D['die_radius']!r} m, lower punch z = 0, upper punch z = {z_start!r} m, density "
                f"{C.RHO!r} kg/m^3 x mass scale {D['mass_scale']!r}\nid,x_m,y_m,z_m,radius_m\n")
        for v in atoms:
            f.write(",".join(v) + "\n")
    rows = []
    with open(os.path.join(wd, "die_force_raw.csv")) as f:
        for line in f:
            if line[0].isdigit() or line[0] == "-":
                rows.append([float(x) for x in line.split(",")])
    with open(os.path.join(outdir, "die_force.csv"), "w") as f:
        f.write(f"# MDR die compaction, LAMMPS {version}, tools/peer_mdr/lammps_die.py: {D['n']} spheres "
                f"r {D['r_min']:g}-{D['r_max']:g} m, die radius {D['die_radius']:g} m (area {area:.6g} m^2), "
                f"E {C.E:g} Pa, nu {C.NU:g}, Y {C.Y:g} Pa, gamma {C.GAMMA_ADH:g} J/m^2 (walls "
                f"{D['gamma_w']:g}), psi_b {C.PSI_B:g}, damping mdr {C.DAMP:g}, friction {D['mu_p']:g} / wall "
                f"{D['mu_w']:g}, density {C.RHO:g} kg/m^3 x {D['mass_scale']:g}, dt {DT:g} s, punch speed "
                f"{D['punch_speed']:g} m/s, stop at {f_max:.6g} N\n"
                f"# punch_disp_m: upper punch travel from where it starts, z = {z_start:.9g} m (downwards > 0); "
                "forces on the punches (compressive > 0); solid_fraction: the spheres' initial volume (MDR keeps "
                "it) over the die's volume between the punches\n"
                "punch_disp_m,upper_force_N,lower_force_N,solid_fraction\n")
        for d, fu, fl in rows:
            f.write(f"{d!r},{fu!r},{fl!r},{v_solid / (area * (z_start - d))!r}\n")
    fpk, dpk = max((r_[1], r_[0]) for r_ in rows)
    print(f"lammps_die: {D['n']} spheres, peak punch force {fpk:.1f} N ({fpk / area / 1e6:.1f} MPa) at solid "
          f"fraction {v_solid / (area * (z_start - dpk)):.3f} (start {v_solid / (area * z_start):.3f}), "
          f"{len(rows)} rows, {wall:.0f} s -> {outdir}/die_force.csv, {outdir}/die_packing.csv")


if __name__ == "__main__":
    main()
