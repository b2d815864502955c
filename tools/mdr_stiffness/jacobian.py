"""tools/mdr_stiffness/jacobian.py - does the time-step estimate (dem_stability_get, host/physics/stability.c) bound
the highest frequency of a held MDR compact? The compact of tools/mdr_energy_box/box.yaml (64 spheres pressed to
100 MPa, then held) is run to T in the reference (fp64); there the one-step stiffness K = -dF/dx is measured by
finite differences: from the same saved state (dem_state_get / dem_state_set, every history kept), each sphere's
position is moved by +h and by -h along each axis, one step is taken, and the change of every sphere's force over
the unmoved step's gives a column. The highest frequency is sqrt of the largest |eigenvalue| of M^-1 K (taken for
+h, -h and their mean); the estimate's is omega_dt / dt of its worst particle.
usage: python3 jacobian.py PSIB [T_MS] [H] [ES]   (PSIB the bulk fraction; T in ms, default 1.0; h in m, default
1e-10; ES: E* of a sphere pair [Pa], to table the pairs' measured stiffness against law_stiffness's closed form and
the stiffest sphere's blocks). tests/test_python.py MdrStiffnessTest runs measure() at psi_b 0."""
import ctypes
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python"))
from libdem import sim as S  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


class Stability(ctypes.Structure):
    _fields_ = [("ratio", ctypes.c_double), ("omega_dt", ctypes.c_double), ("zeta", ctypes.c_double),
                ("tangential", ctypes.c_int), ("particle", ctypes.c_int), ("contacts", ctypes.c_int),
                ("dt_advice", ctypes.c_double)]


def state_array(st, name):
    arr = next(st.arrays[k] for k in range(st.narrays) if st.arrays[k].name == name.encode())
    return np.ctypeslib.as_array(ctypes.cast(arr.data, ctypes.POINTER(ctypes.c_double)), shape=(arr.count,))


def measure(psib, t_ms=1.0, h=1e-10, es=None, out=print):
    """Runs the box at bulk fraction psib to t_ms, prints the table through out and returns (the estimate's omega dt,
    the largest measured omega dt over +h, -h and their mean); es (E* of a sphere pair) adds the pairs' table."""
    with open(os.path.join(ROOT, "tools", "mdr_energy_box", "box.yaml")) as f:
        text = f.read()
    text = text.replace("PSIB", psib).replace("DAMP", "0.2").replace("DTR", "0.05")
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "box.yaml")
        with open(path, "w") as f:
            f.write(text)
        s = S.Sim.from_scene(path)
    s.start("reference", "fp64")
    lib = s._lib
    lib.dem_stability_get.restype = ctypes.c_int
    lib.dem_stability_get.argtypes = [ctypes.c_void_p, ctypes.POINTER(Stability)]
    dt = s.dt
    target = int(round(t_ms * 1e-3 / dt))
    while s.step_index < target:
        s.step(min(20000, target - s.step_index))
    n = s.count
    st0 = S.State()
    s._check(lib.dem_state_get(s._s, ctypes.byref(st0)))
    x = state_array(st0, "x")
    if not np.array_equal(x, s.get("x").reshape(-1)):
        sys.exit("jacobian: the state's positions are not in the API's order")
    ro = state_array(st0, "mdr_particle").reshape(n, -1)[:, 0].copy()
    mass = 1540.0 * 4.0 / 3.0 * np.pi * ro**3

    def force_after_step():
        s._check(lib.dem_state_set(s._s, ctypes.byref(st0)))
        s.step(1)
        return s.get("force").reshape(-1).copy()

    f0 = force_after_step()
    stab = Stability()
    s._check(lib.dem_stability_get(s._s, ctypes.byref(stab)))
    kp, km = np.zeros((3 * n, 3 * n)), np.zeros((3 * n, 3 * n))
    for j in range(3 * n):
        keep = x[j]
        x[j] = keep + h
        kp[:, j] = -(force_after_step() - f0) / h
        x[j] = keep - h
        km[:, j] = (force_after_step() - f0) / h
        x[j] = keep
    minv = np.repeat(1.0 / mass, 3)
    pos = x.reshape(n, 3).copy()
    lib.dem_state_free(ctypes.byref(st0))
    rad = s.get("radius").reshape(-1)
    if es is not None:  # the pairs' stiffness, -n^T K_ij n, against law_stiffness's 2 E* sqrt(2 r* delta)
        km_ = 0.5 * (kp + km)
        rows = []
        for i in range(n):
            for j in range(i + 1, n):
                blk = km_[3 * i:3 * i + 3, 3 * j:3 * j + 3]
                if not np.any(blk):
                    continue
                dvec = pos[j] - pos[i]
                dist = np.linalg.norm(dvec)
                nv = dvec / dist
                delta = rad[i] + rad[j] - dist
                rstar = rad[i] * rad[j] / (rad[i] + rad[j])
                kest = 2 * es * np.sqrt(2 * rstar * max(delta, 0.0))
                rows.append((-nv @ blk @ nv, kest, i, j, delta / rstar, np.linalg.norm(blk)))
        rows.sort(key=lambda r: -r[0] / max(r[1], 1e-300))
        for r in rows[:8]:
            out(f"pair {r[2]}-{r[3]}: k true {r[0]:.4g} N/m, estimate {r[1]:.4g}, ratio {r[0] / max(r[1], 1e-300):.3g}, "
                  f"delta/r* {r[4]:.3g}, |K_ij| {r[5]:.3g}")
        out(f"{len(rows)} pairs; median ratio {np.median([r[0] / max(r[1], 1e-300) for r in rows]):.3g}")
        w = np.argmax(minv * np.sum(np.abs(km_), axis=1)) // 3
        blk = km_[3 * w:3 * w + 3, 3 * w:3 * w + 3]
        off = sum(km_[3 * w:3 * w + 3, 3 * j:3 * j + 3] for j in range(n) if j != w)
        ev, vec = np.linalg.eigh(0.5 * (blk + blk.T))
        out(f"largest row: sphere {w}, r {rad[w]:.4g} (own {ro[w]:.4g}), force {f0[3 * w:3 * w + 3]} N, mass {mass[w]:.4g}, at {pos[w]}, diagonal block eigenvalues "
              f"{ev} (the largest along {vec[:, -1]}); diagonal + the off-diagonal blocks (the walls' share):\n"
              f"{blk + off}")
        for j in range(n):
            b = km_[3 * w:3 * w + 3, 3 * j:3 * j + 3]
            if j != w and np.any(b):
                dv = pos[j] - pos[w]
                out(f"  {j}: |K| {np.linalg.norm(b):.3g}, gap {np.linalg.norm(dv) - rad[w] - rad[j]:.3g} m")
    out(f"psi_b {psib}, t {1e3 * s.time:.4f} ms, dt {dt:.4g} s, {n} spheres, h {h:g} m")
    out(f"estimate: omega_dt {stab.omega_dt:.5g} (ratio {stab.ratio:.4g}, particle {stab.particle}, "
          f"{stab.contacts} contacts): omega {stab.omega_dt / dt:.5g} rad/s")
    largest = 0.0
    for name, k in (("+h", kp), ("-h", km), ("mean", 0.5 * (kp + km))):
        lam = np.linalg.eigvals(minv[:, None] * k)
        big = lam[np.argmax(np.abs(lam))]
        asym = np.max(np.abs(k - k.T)) / np.max(np.abs(k))
        rows = np.max(minv * np.sum(np.abs(k), axis=1))
        out(f"{name:>4}: largest |eig| of M^-1 K {abs(big):.5g} ({big:.4g}): omega {np.sqrt(abs(big)):.5g} rad/s, "
              f"omega dt {np.sqrt(abs(big)) * dt:.5g}, over the estimate's {np.sqrt(abs(big)) * dt / stab.omega_dt:.4g}; "
              f"largest row sum of |M^-1 K| {rows:.4g} (omega dt {np.sqrt(rows) * dt:.4g}); |K - K^T| / |K| {asym:.3g}")
        largest = max(largest, np.sqrt(abs(big)) * dt)
    s.close()
    return stab.omega_dt, largest


def main():
    measure(sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 1.0,
            float(sys.argv[3]) if len(sys.argv) > 3 else 1e-10, float(sys.argv[4]) if len(sys.argv) > 4 else None)


if __name__ == "__main__":
    main()
