#!/usr/bin/python3
"""The die compaction of lammps_die.py run by libdem's MDR law (common/laws/mdr.h), from the same packing
(OUTDIR/die_packing.csv, the spheres when LAMMPS's upper punch starts), and compared with LAMMPS's punch force
(OUTDIR/die_force.csv): the recipe of tools/peer_mdr/README.md "Comparing a libdem MDR press with this die".

The same: spheres, die (radius 3 mm about z), punches (planes at z = 0 and at the packing's header z), MDR's
material (cases.py: E, nu, Y, psi_b, damping; surface energy GAMMA_ADH between spheres, gamma_w at the walls),
friction mu_p between spheres and mu_w at the walls (a material pair), density x mass_scale, gravity 9.81 m/s^2,
dt 1e-6 s, punch speed down to LAMMPS's largest travel (it stopped at its first force check above p_max's force),
then up until the punch's force is zero.
Not the same, by design: the tangential law. LAMMPS's die runs `tangential linear_history` (k_t = 2/7 E r_mean,
its dashpot equal to the normal one); libdem's MDR law has Mindlin's spring on the MDR contact radius (k_t = 8 G* a)
and no tangential dashpot (laws/mdr.h). And libdem starts the packing's contacts afresh (LAMMPS's carry the
pour's history: small elastic overlaps under the spheres' weight).

Writes OUTDIR/libdem_die_force.csv (punch travel, upper and lower force, solid fraction) and prints the comparison
(largest relative difference of the upper force over the loading rows above 5 % of the peak; travel at 50 % and 100 %
of the peak; the solid fraction at which the release's force falls to 1 % and to 0).

usage: libdem_die.py OUTDIR [reference|opencl] [fp64|fp32]
"""
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
import cases as C  # noqa: E402
from libdem.sim import Sim  # noqa: E402

D = C.DIE
DT = 1.0e-6
EVERY = 100  # steps between rows (LAMMPS's fix print)


def read_csv(path):
    head, rows = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                head.append(line)
            elif line[0].isdigit() or line[0] == "-":
                rows.append([float(x) for x in line.split(",")])
    return head, rows


def main():
    outdir = sys.argv[1]
    backend = sys.argv[2] if len(sys.argv) > 2 else "reference"
    precision = sys.argv[3] if len(sys.argv) > 3 else "fp64"
    head, spheres = read_csv(os.path.join(outdir, "die_packing.csv"))
    z_start = float(head[1].split("upper punch z = ")[1].split(" m")[0])
    _, lam = read_csv(os.path.join(outdir, "die_force.csv"))
    rd = D["die_radius"]
    area = math.pi * rd * rd
    travel_max = max(r[0] for r in lam)  # where LAMMPS turned back
    s = Sim()
    p = s.add_material(C.RHO * D["mass_scale"], C.E, C.NU, 1.0, D["mu_p"], yield_stress=C.Y,
                       surface_energy=C.GAMMA_ADH, bulk_fraction=C.PSI_B, mdr_damping=C.DAMP)
    w = s.add_material(7800.0, float("inf"), 0.3, 1.0, D["mu_w"], surface_energy=D["gamma_w"])
    s.set_material_pair(p, w, friction=D["mu_w"])
    xs = [[v[1], v[2], v[3]] for v in spheres]
    rs = [v[4] for v in spheres]
    s.add_particles(xs, rs, p)
    v = D["punch_speed"]
    s.add_plane([0, 0, 0], [0, 0, 1], w)
    s.add_cylinder([0, 0, -1e-3], [0, 0, 1], rd, w)
    down = travel_max / v
    s.add_plane([0, 0, z_start], [0, 0, -1], w,
                stages=[{"duration": down, "velocity": [0, 0, -v]}, {"duration": 2 * down, "velocity": [0, 0, v]}])
    s.set_gravity([0, 0, -9.81])
    s.set_domain([-2 * rd, -2 * rd, -2e-3], [2 * rd, 2 * rd, z_start + 2e-3])
    s.set_dt(DT)
    s.set_effects(["hertz", "damping", "friction", "gravity", "walls", "mdr"])
    s.start(backend=backend, precision=precision, force_dt=True)
    v_solid = sum(4.0 / 3.0 * math.pi * r ** 3 for r in rs)
    rows, t0, turned, k = [], time.time(), False, 0
    n_down = int(round(down / DT))
    while True:
        s.step(EVERY)
        k += EVERY
        z = s.wall_position(2)[2]
        travel = z_start - z
        fu, fl = s.wall_normal_force(2), s.wall_normal_force(0)
        rows.append((travel, fu, fl, v_solid / (area * z)))
        turned = turned or k > n_down
        if turned and fu <= 0:
            break
        if k > 3 * n_down:
            sys.exit("libdem_die: the punch never came free")
    wall = time.time() - t0
    with open(os.path.join(outdir, "libdem_die_force.csv"), "w") as f:
        f.write(f"# the die of lammps_die.py run by libdem's MDR law ({backend} {precision}), "
                f"tools/peer_mdr/libdem_die.py; {wall:.0f} s\n"
                "punch_disp_m,upper_force_N,lower_force_N,solid_fraction\n")
        for r in rows:
            f.write(",".join(repr(x) for x in r) + "\n")
    # the comparison
    ours_load = [r for r in rows if r[0] <= travel_max + 1e-12 and not (r is rows[-1])]
    ours_load = ours_load[:n_down // EVERY]
    lam_load = [r for r in lam if r[0] <= travel_max + 1e-12][:len(lam)]
    peak_l = max(r[1] for r in lam)
    peak_o = max(r[1] for r in rows)

    def at(series, d):  # force at travel d, linear between rows (loading rows, travel increasing)
        for a, b in zip(series, series[1:]):
            if a[0] <= d <= b[0]:
                return a[1] + (b[1] - a[1]) * (d - a[0]) / (b[0] - a[0])
        return None

    lam_up = []
    for r in lam:  # LAMMPS's loading rows: travel increasing up to the turn
        if lam_up and r[0] < lam_up[-1][0]:
            break
        lam_up.append(r)
    def worst_above(frac):  # the largest |F_libdem / F_LAMMPS - 1| over the loading rows above frac of the peak
        w, wd = 0.0, 0.0
        for r in ours_load:
            fl_ = at(lam_up, r[0])
            if fl_ is not None and fl_ > frac * peak_l:
                d = abs(r[1] - fl_) / fl_
                if d > w:
                    w, wd = d, r[0]
        return w, wd

    def travel_at(series, frac, peak):
        for a, b in zip(series, series[1:]):
            if a[1] < frac * peak <= b[1]:
                return a[0] + (b[0] - a[0]) * (frac * peak - a[1]) / (b[1] - a[1])
        return float("nan")

    def release(series, frac, peak, after):
        for r in series[after:]:
            if r[1] <= frac * peak:
                return r[3]
        return float("nan")

    i_l = max(range(len(lam)), key=lambda i: lam[i][1])
    i_o = max(range(len(rows)), key=lambda i: rows[i][1])
    print(f"libdem_die: {len(rs)} spheres, {backend} {precision}, {k} steps in {wall:.0f} s")
    print(f"  peak upper force: libdem {peak_o:.1f} N at travel {rows[i_o][0] * 1e3:.4f} mm (solid fraction "
          f"{rows[i_o][3]:.4f}); LAMMPS {peak_l:.1f} N at {lam[i_l][0] * 1e3:.4f} mm ({lam[i_l][3]:.4f})")
    for frac in (0.05, 0.1, 0.25, 0.5):
        worst, worst_d = worst_above(frac)
        print(f"  loading, force above {frac:.0%} of the peak: largest |F_libdem / F_LAMMPS - 1| = {worst:.4f} "
              f"(at travel {worst_d * 1e3:.3f} mm)")
    for frac in (0.5, 1.0):
        print(f"  travel at {frac:.0%} of LAMMPS's peak: libdem {travel_at(ours_load, frac, peak_l) * 1e3:.4f} mm, "
              f"LAMMPS {travel_at(lam_up, frac, peak_l) * 1e3:.4f} mm")
    for frac in (0.01, 0.0):
        print(f"  release: solid fraction where the force falls to {frac:.0%} of the peak: libdem "
              f"{release(rows, frac, peak_o, i_o):.4f}, LAMMPS {release(lam, frac, peak_l, i_l):.4f}")
    mean_lo = [r[2] / r[1] for r in ours_load if r[1] > 0.05 * peak_o]
    mean_ll = [r[2] / r[1] for r in lam_up if r[1] > 0.05 * peak_l]
    if mean_lo and mean_ll:
        print(f"  transmission (lower / upper force) over those rows: libdem {sum(mean_lo) / len(mean_lo):.4f}, "
              f"LAMMPS {sum(mean_ll) / len(mean_ll):.4f}")


if __name__ == "__main__":
    main()
