"""tools/mdr_stiffness/jacobian.py - does the time-step estimate (dem_stability_get, host/physics/stability.c) bound
the highest frequency of a held MDR compact? The compact of tools/mdr_energy_box/box.yaml (64 spheres pressed to
100 MPa, then held) is run to T in the reference (fp64); there the one-step stiffness K = -dF/dx is measured by
finite differences: from the same saved state (dem_state_get / dem_state_set, every history kept), each sphere's
position is moved by +h and by -h along each axis, one step is taken, and the change of every sphere's force over
the unmoved step's gives a column. The highest frequency is sqrt of the largest |eigenvalue| of M^-1 K (taken for
+h, -h and their mean); the estimate's is omega_dt / dt of its worst particle.
It also names the sphere of the stiffest row (its radii, place and its block's largest eigenvalue [N/m]).
usage: python3 jacobian.py PSIB [T_MS] [H]   (PSIB the bulk fraction; T in ms, default 1.0; h in m, default 1e-10).
tests/test_python.py MdrStiffnessTest runs measure() at psi_b 0."""
import ctypes
import os
import re
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python"))
from libdem import sim as S  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def state_array(st, name):
    arr = next(st.arrays[k] for k in range(st.narrays) if st.arrays[k].name == name.encode())
    return np.ctypeslib.as_array(ctypes.cast(arr.data, ctypes.POINTER(ctypes.c_double)), shape=(arr.count,))


def measure(psib, t_ms=1.0, h=1e-10, out=print):
    """Runs the box at bulk fraction psib to t_ms, prints the table through out and returns (the estimate's omega dt,
    the largest measured omega dt over +h, -h and their mean)."""
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
    density = float(re.search(r"density: ([0-9.e+-]+)", text).group(1))  # the spheres' material, the first
    mass = density * 4.0 / 3.0 * np.pi * ro**3

    def force_after_step():
        s._check(lib.dem_state_set(s._s, ctypes.byref(st0)))
        s.step(1)
        return s.get("force").reshape(-1).copy()

    f0 = force_after_step()
    stab = s.stability()
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
    km_ = 0.5 * (kp + km)
    w = int(np.argmax(minv * np.sum(np.abs(km_), axis=1)) // 3)
    blk = km_[3 * w:3 * w + 3, 3 * w:3 * w + 3]
    out(f"stiffest row: sphere {w}, apparent radius {rad[w]:.4g} m (own {ro[w]:.4g}), at {pos[w]} m, its block's "
        f"largest eigenvalue {np.linalg.eigvalsh(0.5 * (blk + blk.T))[-1]:.4g} N/m")
    out(f"psi_b {psib}, t {1e3 * s.time:.4f} ms, dt {dt:.4g} s, {n} spheres, h {h:g} m")
    out(f"estimate: omega_dt {stab['omega_dt']:.5g} (ratio {stab['ratio']:.4g}, particle {stab['particle']}, "
          f"{stab['contacts']} contacts): omega {stab['omega_dt'] / dt:.5g} rad/s")
    largest = 0.0
    for name, k in (("+h", kp), ("-h", km), ("mean", 0.5 * (kp + km))):
        lam = np.linalg.eigvals(minv[:, None] * k)
        big = lam[np.argmax(np.abs(lam))]
        asym = np.max(np.abs(k - k.T)) / np.max(np.abs(k))
        rows = np.max(minv * np.sum(np.abs(k), axis=1))
        out(f"{name:>4}: largest |eig| of M^-1 K {abs(big):.5g} ({big:.4g}): omega {np.sqrt(abs(big)):.5g} rad/s, "
              f"omega dt {np.sqrt(abs(big)) * dt:.5g}, over the estimate's {np.sqrt(abs(big)) * dt / stab['omega_dt']:.4g}; "
              f"largest row sum of |M^-1 K| {rows:.4g} (omega dt {np.sqrt(rows) * dt:.4g}); |K - K^T| / |K| {asym:.3g}")
        largest = max(largest, np.sqrt(abs(big)) * dt)
    s.close()
    return stab["omega_dt"], largest


def main():
    measure(sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 1.0,
            float(sys.argv[3]) if len(sys.argv) > 3 else 1e-10)


if __name__ == "__main__":
    main()
