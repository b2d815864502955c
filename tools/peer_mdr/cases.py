"""The MDR peer check's cases, shared by the LAMMPS driver (lammps_single.py, lammps_die.py) and the
independent reference (mdr_reference.py), so that both walk the same prescribed path step by step.

Units are SI throughout (m, s, kg, N, Pa, J/m^2).

Material: MCC-like, after Zunker et al., Powder Technology 2025 (doi:10.1016/j.powtec.2025.120972): E 5 GPa,
nu 0.4, density 1560 kg/m^3, particle friction 0.7, wall friction 0.1. The yield stress is NOT taken from that
paper (not reachable from here): Y = 190 MPa keeps the E/Y ratio of LAMMPS's own MCC example
(examples/granular/in.tableting.200: E 5 MPa, Y 0.19 MPa, gamma 2 J/m^2, psi_b 0.5, damping 0.2), which scales
E and Y down together. Surface energy 2 J/m^2 (that example's value) for the adhesive cases.
"""

E = 5.0e9          # Young's modulus, Pa
NU = 0.4           # Poisson's ratio
Y = 1.9e8          # yield stress, Pa (see the module docstring)
RHO = 1560.0       # density, kg/m^3
PSI_B = 0.5        # bulk-response trigger: free-area fraction below which Part II's bulk force starts
DAMP = 0.2         # MDR damping coefficient (LAMMPS 'damping mdr 1': eta = DAMP*sqrt(2 m_eff E* a))
GAMMA_ADH = 2.0    # surface energy of the adhesive cases, J/m^2
GAMMA_STRONG = 50.0  # exaggerated, so that the tensile branch spans a few hundred steps, not a few dozen

R = 0.5e-3         # sphere radius of the single-contact cases, m
DT = 1.0e-6        # time step of the prescribed path, s
STEP = 7.5e-9      # approach per step while moving, m (speed STEP/DT = 7.5 mm/s)
DUMP_EVERY = 1     # steps between rows of the CSVs (every step: the tensile branch is short)

# Single-contact cases (a case's 'Y' replaces the yield stress above). 'path' lists the approach (centre
# displacement towards the partner or wall, m) at the ends of the four phases, each a straight run at STEP per
# step from first touch: loading beyond yield; unloading past zero force while the spheres still overlap (the
# contact and its history stay); reloading past the first maximum (elastic along the unloading line, then plastic
# again); unloading out of contact (with adhesion: the tensile branch and the pull-off). A pair's overlap is shared
# by two spheres, so its path is twice the wall's: each sphere sees about 15 % of its radius at the first maximum,
# 22.5 % at the second.
SINGLE = {
    "pair_g0":  dict(kind="pair", gamma=0.0,       path=(0.30 * R, 0.18 * R, 0.45 * R, -0.05 * R)),
    "pair_adh": dict(kind="pair", gamma=GAMMA_ADH, path=(0.30 * R, 0.18 * R, 0.45 * R, -0.05 * R)),
    "wall_g0":  dict(kind="wall", gamma=0.0,       path=(0.15 * R, 0.09 * R, 0.225 * R, -0.03 * R)),
    "wall_adh": dict(kind="wall", gamma=GAMMA_ADH, path=(0.15 * R, 0.09 * R, 0.225 * R, -0.03 * R)),
    "pair_adh50": dict(kind="pair", gamma=GAMMA_STRONG, path=(0.30 * R, 0.18 * R, 0.45 * R, -0.05 * R)),
    "wall_adh50": dict(kind="wall", gamma=GAMMA_STRONG, path=(0.15 * R, 0.09 * R, 0.225 * R, -0.03 * R)),
    # two unequal spheres (0.5 and 0.3 mm): the flat sits off the middle (M3) and the two sides yield apart
    "pair_uneq": dict(kind="pair", gamma=GAMMA_ADH, R2=0.6 * R, path=(0.24 * R, 0.15 * R, 0.36 * R, -0.04 * R)),
    # one sphere between six planes that close in together: past about 19 % of R the free-surface fraction psi
    # falls below psi_b and Part II's bulk force takes over; no damping (the planes move, the sphere does not)
    "box_g0":   dict(kind="box", gamma=0.0, damp=0.0, path=(0.20 * R, 0.12 * R, 0.24 * R, -0.06 * R)),
    # a sphere pressed almost its radius into a wall, as deep as spheres go in a compact at 100 MPa (the tablets of
    # docs/tableting.md reach overlaps of 108-115 % of the radius as created): the apparent overlap reaches 1.24 R,
    # the radius grows 25 %, psi falls to 0.67 (one contact: above psi_b, so no bulk response). Y 60 MPa, the yield
    # stress of scenes/tablet_strength_mdr.yaml. No deeper: past an approach of R the centre crosses the plane and
    # LAMMPS's region wall loses the contact
    "wall_deep": dict(kind="wall", gamma=0.0, Y=6.0e7, path=(0.97 * R, 0.80 * R, 0.99 * R, -0.03 * R)),
}


def material_of(spec):
    """A single case's MDR parameters (E, nu, Y, gamma, psi_b, damping): the module's, but for the case's own
    'Y' and 'damp' where it gives them. What LAMMPS, the Python reference and the C core's walk are each given."""
    return E, NU, spec.get("Y", Y), spec["gamma"], PSI_B, spec.get("damp", DAMP)

def phase_steps(path):
    """Steps of each phase: |change of approach| / STEP, rounded."""
    ends = [0.0]
    n = []
    for k in range(len(path)):
        n.append(int(round(abs(path[k] - ends[k]) / STEP)))
        ends.append(ends[k] + (1.0 if path[k] > ends[k] else -1.0) * STEP * n[k])
    return n


def phase_ends(path):
    """The approach where each phase really ends: whole steps of STEP from where the previous one ended (a phase
    that starts where the last one was meant to end, not where it got, makes LAMMPS's next run start with a jump;
    its setup then sees a position no step walked through, and the MDR history's unguarded maxima keep it)."""
    n = phase_steps(path)
    ends = [0.0]
    for k in range(len(path)):
        sign = 1.0 if path[k] > ends[k] else -1.0
        ends.append(ends[k] + sign * STEP * n[k])
    return ends


def approach_at(path, step):
    """Approach (m) after `step` steps of the whole path, as LAMMPS's 'fix move variable' sets it: each phase
    is its own 'run', the displacement is start + sign*STEP*elapsed."""
    ends = phase_ends(path)
    n = phase_steps(path)
    s = step
    for k in range(len(path)):
        if s <= n[k] or k == len(path) - 1:
            sign = 1.0 if ends[k + 1] > ends[k] else -1.0
            return ends[k] + sign * STEP * s
        s -= n[k]
    raise AssertionError


# Die compaction (lammps_die.py): a small cylindrical die, spheres of 0.40-0.60 mm radius, poured under gravity,
# then the upper punch moves down at constant speed to a force limit and back.
DIE = dict(
    n=300,                 # spheres
    r_min=0.40e-3, r_max=0.60e-3,
    die_radius=3.0e-3,     # m
    mass_scale=100.0,      # density x100 during the press (quasi-static at a larger time step)
    mu_p=0.7, mu_w=0.1,    # friction, particle-particle and particle-wall
    gamma_w=0.0,           # surface energy at the walls
    punch_speed=0.02,      # m/s, upper punch, both ways
    p_max=150e6,           # Pa: punch pressure at which loading stops
    seed=45,
)
