#!/usr/bin/python3
"""The Python package (python/libdem), run by `make test` (after `make python-lib` builds build/pic/libdem.so).

- output: Run on HDF5 files written here in dem run's layout (app/output.c): series, walls by name, frames, the
  contact network, a run in parts joined by step (and parts out of order or with one missing refused);
- analysis: force against displacement from first contact on a force ramp whose contact row is known; coordination
  numbers of a hand-made network with and without rattlers and wall contacts; the volume of a sphere cut by a box
  against the closed forms (half, quarter, eighth, a cap); the packing fraction of a die between punches;
- tablet: a synthetic press cycle whose transmission over the loading rows, radial ratio, recovery and ejection
  friction and punch force are known by construction (pressures printed in MPa);
- the command lines (python3 -m libdem fd / coordination / report, tools/plot_tablet.py);
- a real run: build/dem presses one sphere between a floor and a piston; the piston's force against its displacement
  from first contact follows Hertz's law (two contacts in series) and the coordination number is 2 with walls, 0
  without;
- sim: the ctypes structures' sizes and offsets and the functions' signatures against include/dem.h (a C program
  and gcc's -aux-info), then a sphere pressed into a plane (the wall force is Hertz's at the overlap), a free flight
  (x advances by v dt after set('v')), a position written and read back, and the contact network; a small bed on
  the reference and on PoCL, bit for bit.
"""
import math
import os
import re
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
import libdem  # noqa: E402
from libdem import analysis, tablet  # noqa: E402
from libdem.output import OutputError, Run  # noqa: E402

PY = sys.executable  # the command lines below run under the Python running this file


def write_run(path, time, walls, wall_position, wall_force, radius, step=None, wall_normal_force=None,
              frames=None, contacts=None, model="as in the scene", extra=None):
    """An HDF5 file in dem run's layout. walls: list of dicts (name, normal, radius=0 for a plane, cup_radius,
    cup_depth); frames: dict time, step, position [f, n, 3]; contacts: per frame a list of (i, j) (j = -1 - wall)."""
    nw = len(walls)
    with h5py.File(path, "w") as f:
        f.attrs["model"] = np.bytes_(model)
        f.attrs["units"] = np.bytes_("SI: m, kg, s, N, Pa, J")
        s = f.create_group("series")
        n = len(time)
        s["time"] = np.asarray(time, dtype=float)
        s["time"].attrs["units"] = np.bytes_("s")
        s["step"] = np.asarray(step if step is not None else np.arange(n), dtype=float)
        for k in ("kinetic", "elastic"):
            s[k] = np.zeros(n)
        s["wall_position"] = np.asarray(wall_position, dtype=float).reshape(n, nw, 3)
        s["wall_position"].attrs["units"] = np.bytes_("m")
        s["wall_force"] = np.asarray(wall_force, dtype=float).reshape(n, nw, 3)
        s["wall_force"].attrs["units"] = np.bytes_("N")
        s["wall_normal_force"] = (np.zeros((n, nw)) if wall_normal_force is None
                                  else np.asarray(wall_normal_force, dtype=float))
        s.attrs["wall_names"] = np.bytes_("\n".join(w["name"] for w in walls))
        s["wall_radius"] = np.array([w.get("radius", 0.0) for w in walls])
        s["wall_height"] = np.zeros(nw)
        s["wall_cup_radius"] = np.array([w.get("cup_radius", 0.0) for w in walls])
        s["wall_cup_depth"] = np.array([w.get("cup_depth", 0.0) for w in walls])
        s["wall_normal"] = np.array([w["normal"] for w in walls], dtype=float)
        for k, v in (extra or {}).items():
            s[k] = v
        f.create_group("particles")["radius"] = np.asarray(radius, dtype=float)
        f["particles/material"] = np.zeros(len(radius), dtype=np.int32)
        if frames is not None:
            g = f.create_group("frames")
            g["time"], g["step"] = np.asarray(frames["time"], float), np.asarray(frames["step"], float)
            g["position"] = np.asarray(frames["position"], dtype=float)
            g["position"].attrs["units"] = np.bytes_("m")
        if contacts is not None:
            c = f.create_group("contacts")
            start, pairs, ids = [], [], []
            for net in contacts:
                start.append(len(ids))
                pairs.append(sum(1 for i, j in net if j >= 0))
                ids += sorted(net, key=lambda e: (e[1] < 0, e))
            c["frame_start"], c["frame_pairs"] = np.array(start, np.int64), np.array(pairs, np.int64)
            c["ids"] = np.array(ids, dtype=np.int32).reshape(-1, 2)
            data = np.zeros((len(ids), 12))
            data[:, 0] = 1e-6 * (1 + np.arange(len(ids)))  # overlaps, to see the rows come back in order
            c["data"] = data
            c["normal_force"] = np.zeros(len(ids))


# the hand-made network: a triangle 0-1-2; 3 touches 0 and 5; 5 touches only 3; 4 touches nothing but two walls;
# 5 also touches wall 0
NETWORK = [(0, 1), (1, 2), (0, 2), (0, 3), (3, 5), (4, -1), (4, -2), (5, -1)]


class OutputTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.d = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def plain(self, path, t0=0, n=11, step0=0, walls=None, frames=None, contacts=None, value=0.0):
        walls = walls or [dict(name="floor", normal=[0, 0, 1]), dict(name="piston", normal=[0, 0, -1])]
        t = t0 + 0.1 * np.arange(n)
        pos = np.zeros((n, len(walls), 3))
        pos[:, 1, 2] = 1.0 - 0.01 * (step0 + np.arange(n))
        force = np.zeros((n, len(walls), 3))
        force[:, 1, 2] = value
        write_run(path, t, walls, pos, force, [0.001] * 6, step=step0 + np.arange(n), frames=frames,
                  contacts=contacts)
        return path

    def test_series_walls_units(self):
        p = self.plain(os.path.join(self.d, "a.h5"))
        r = Run(p)
        self.assertEqual(r.wall_names, ["floor", "piston"])
        self.assertIsInstance(r.wall_names, list)
        w = r.wall("piston")
        self.assertEqual((w.kind, w.index), ("plane", 1))
        np.testing.assert_array_equal(w.normal, [0, 0, -1])
        self.assertEqual(w.position.shape, (11, 3))
        self.assertAlmostEqual(w.position[3, 2], 0.97)
        self.assertEqual(r.units["wall_force"], "N")
        self.assertEqual(r.units["time"], "s")
        self.assertEqual(len(r.series["time"]), 11)
        with self.assertRaises(KeyError):
            r.wall("lid")
        with self.assertRaises(OutputError):
            r.contacts(0)

    def test_frames_and_contacts(self):
        n = 6
        pos = np.arange(2 * n * 3, dtype=float).reshape(2, n, 3)
        frames = dict(time=[0.0, 0.5], step=[0, 5], position=pos)
        p = self.plain(os.path.join(self.d, "f.h5"), frames=frames, contacts=[[(0, 1)], NETWORK])
        r = Run(p)
        self.assertEqual(len(r.frames), 2)
        np.testing.assert_array_equal(r.frame(-1)["position"], pos[1])
        np.testing.assert_array_equal(r.frames[0]["position"], pos[0])
        self.assertEqual(r.frame(1)["time"], 0.5)
        c = r.contacts(1)
        self.assertEqual(c["npairs"], 5)
        np.testing.assert_array_equal(c["i"], [0, 0, 0, 1, 3, 4, 4, 5])
        np.testing.assert_array_equal(c["j"], [1, 2, 3, 2, 5, -2, -1, -1])
        np.testing.assert_array_equal(c["wall"], [-1, -1, -1, -1, -1, 1, 0, 0])
        np.testing.assert_allclose(c["overlap"], 1e-6 * np.arange(2, 10))  # frame 1 starts at row 1
        with self.assertRaises(IndexError):
            r.frame(2)

    def test_coordination_number(self):
        p = self.plain(os.path.join(self.d, "c.h5"), frames=dict(time=[0], step=[0], position=np.zeros((1, 6, 3))),
                       contacts=[NETWORK])
        # 5 pairs over 6 spheres: 10 / 6; without rattlers 5 goes (1 contact), then 3 (1 left), then 4 (none):
        # the triangle, 6 / 3; with walls every sphere has 2 or more: (10 + 3) / 6
        z = analysis.coordination_number
        self.assertAlmostEqual(z(p), 10 / 6)
        self.assertAlmostEqual(z(p, rattlers=False), 2.0)
        self.assertAlmostEqual(z(p, walls=True), 13 / 6)
        self.assertAlmostEqual(z(p, walls=True, rattlers=False), 13 / 6)
        counts, kept = analysis.contact_counts([i for i, _ in NETWORK], [j for _, j in NETWORK], 6, walls=False,
                                               rattlers=False)
        np.testing.assert_array_equal(kept, [1, 1, 1, 0, 0, 0])
        np.testing.assert_array_equal(counts, [2, 2, 2, 0, 0, 0])
        out = subprocess.run([PY, "-m", "libdem", "coordination", p, "--no-rattlers"], cwd=os.path.join(ROOT, "python"),
                             capture_output=True, text=True, check=True).stdout
        self.assertIn("Z = 2 over 3 spheres", out)
        out = subprocess.run([PY, "-m", "libdem", "coordination", p, "--walls"], cwd=os.path.join(ROOT, "python"),
                             capture_output=True, text=True, check=True).stdout
        self.assertIn(f"Z = {13 / 6:.6g} over 6 spheres", out)

    def test_force_displacement_ramp(self):
        # a piston (normal -z) moving down 0.5 mm a row; the spheres push it from row 7 on, F = 3 N/mm^1.5 d^1.5
        n, v = 20, 5e-4
        walls = [dict(name="floor", normal=[0, 0, 1]), dict(name="piston", normal=[0, 0, -1])]
        pos = np.zeros((n, 2, 3))
        pos[:, 1, 2] = 0.02 - v * np.arange(n)
        d_true = np.maximum(v * (np.arange(n) - 7), 0)
        fz = 3.0 * (d_true * 1e3) ** 1.5
        fz[7] = 0.01  # the first contact, just touching
        force = np.zeros((n, 2, 3))
        force[:, 1, 2] = fz  # pushed back up: along -normal
        force[:, 1, 0] = 0.1 * fz  # friction across it does not count
        p = os.path.join(self.d, "ramp.h5")
        write_run(p, 0.01 * np.arange(n), walls, pos, force, [0.001])
        d, f = analysis.force_displacement(p, "piston")
        np.testing.assert_allclose(d, v * (np.arange(n) - 7), atol=1e-15)
        np.testing.assert_allclose(f, fz)
        self.assertEqual(d[7], 0.0)
        with self.assertRaises(ValueError):
            analysis.force_displacement(p, "floor")  # never touched
        csv = os.path.join(self.d, "fd.csv")
        subprocess.run([PY, "-m", "libdem", "fd", p, "--wall", "piston", "-o", csv], cwd=os.path.join(ROOT, "python"),
                       capture_output=True, text=True, check=True)
        with open(csv) as fh:
            self.assertEqual(fh.readline().strip(), "time [s],step,displacement [m],force [N]")
        a = np.loadtxt(csv, delimiter=",", skiprows=1)
        np.testing.assert_allclose(a[:, 2], d, atol=1e-12)
        np.testing.assert_allclose(a[:, 3], f, rtol=1e-8)

    def test_restart_parts(self):
        fr1 = dict(time=[0.0, 0.5, 1.0], step=[0, 5, 10], position=np.zeros((3, 6, 3)))
        fr2 = dict(time=[1.0, 1.5], step=[10, 15], position=np.ones((2, 6, 3)))
        p1 = self.plain(os.path.join(self.d, "p1.h5"), n=11, frames=fr1, value=1.0)
        # the restart went back to a checkpoint at step 7: its rows replace the first part's from there
        p2 = self.plain(os.path.join(self.d, "p2.h5"), t0=0.7, n=9, step0=7, frames=fr2, value=2.0)
        r = Run([p1, p2])
        np.testing.assert_array_equal(r.series["step"], np.arange(16))
        np.testing.assert_array_equal(r.wall("piston").force[:, 2], [1.0] * 7 + [2.0] * 9)
        np.testing.assert_array_equal(r.frame_step, [0, 5, 10, 15])
        np.testing.assert_array_equal(r.frame(2)["position"], np.ones((6, 3)))
        np.testing.assert_array_equal(r.frame(1)["position"], np.zeros((6, 3)))
        p3 = self.plain(os.path.join(self.d, "p3.h5"), n=3, step0=20)
        with self.assertRaisesRegex(OutputError, "missing"):
            Run([p1, p3])
        with self.assertRaisesRegex(OutputError, "order they ran"):
            Run([p2, p1])

    def test_sphere_box_volume(self):
        r = 0.002
        v = 4 / 3 * math.pi * r**3
        big = 1.0
        cases = [([0, 0, 0], [-big] * 3, [big] * 3, v),  # inside
                 ([0, 0, 0], [0, -big, -big], [big] * 2 + [big], v / 2),  # on a face
                 ([0, 0, 0], [0, 0, -big], [big] * 3, v / 4),  # on an edge
                 ([0, 0, 0], [0, 0, 0], [big] * 3, v / 8),  # in a corner
                 ([0.3 * r, 0, 0], [-big] * 3, [0.5 * r, big, big], None),  # a cap cut off at x = 0.5 r
                 ([0, 0, 0], [3 * r] * 3, [big] * 3, 0.0)]
        h = r - 0.2 * r  # the cap beyond the face, height r - 0.2 r
        for c, lo, hi, want in cases:
            if want is None:
                want = v - math.pi * h * h * (3 * r - h) / 3
            got = analysis.sphere_box_volume([c], [r], lo, hi)[0]
            self.assertAlmostEqual(got / v, want / v, delta=1e-7, msg=f"{c} in {lo}..{hi}")
        # the eight octants about a point off the centre along every axis, each cut at a slant: they add up to the
        # sphere
        c0 = np.array([0.3, -0.4, 0.5]) * r
        parts = [analysis.sphere_box_volume([[0, 0, 0]], [r], np.where(o, c0, -big), np.where(o, big, c0))[0]
                 for o in np.array(np.meshgrid([0, 1], [0, 1], [0, 1])).reshape(3, -1).T.astype(bool)]
        self.assertEqual(len(parts), 8)
        self.assertAlmostEqual(sum(parts) / v, 1.0, delta=1e-9)
        self.assertTrue(all(0 < q < v / 2 for q in parts))

    def test_packing_fraction(self):
        R, gap = 0.004, 0.003
        walls = [dict(name="die", normal=[0, 0, 1], radius=R), dict(name="lower", normal=[0, 0, 1]),
                 dict(name="upper", normal=[0, 0, -1])]
        pos = np.zeros((2, 3, 3))
        pos[:, 2, 2] = [0.01, gap]  # the upper punch comes down to the gap
        radius = np.full(10, 0.0005)
        x = np.zeros((1, 10, 3))
        x[0, :, 2] = 0.001
        p = os.path.join(self.d, "pack.h5")
        write_run(p, [0, 1], walls, pos, np.zeros((2, 3, 3)), radius, step=[0, 100],
                  frames=dict(time=[1], step=[100], position=x))
        want = 10 * 4 / 3 * math.pi * 0.0005**3 / (math.pi * R * R * gap)
        self.assertAlmostEqual(analysis.packing_fraction(p), want, places=12)
        # a box about one sphere: its volume over the box's
        lo, hi = [-0.001, -0.001, 0.0005], [0.001, 0.001, 0.0015]
        self.assertAlmostEqual(analysis.packing_fraction(p, lo=lo, hi=hi),
                               10 * 4 / 3 * math.pi * 0.0005**3 / (0.002 * 0.002 * 0.001), places=9)


class TabletTest(unittest.TestCase):
    """A synthetic press cycle: 5 rows of approach, 10 of loading (upper pressure 1..10 MPa, lower 0.8 of it),
    5 of dwell (lower 0.9), 5 of unloading (lower 1.2), then the lower punch ejects against 2 N of die friction,
    its force 2 N plus a 10 N inertial spike at one row."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        R = 0.004
        self.area = area = math.pi * R * R
        walls = [dict(name="die", normal=[0, 0, 1], radius=R), dict(name="lower", normal=[0, 0, 1]),
                 dict(name="upper", normal=[0, 0, -1])]
        p_up = np.array([0.0] * 5 + list(range(1, 11)) + [10.0] * 5 + [8, 6, 4, 2, 0] + [0.0] * 10) * 1e6
        ratio = np.array([0.8] * 15 + [0.9] * 5 + [1.2] * 5 + [1.0] * 10)
        n = len(p_up)
        z_up = np.empty(n)
        z_up[:15] = 0.008 - 0.0002 * np.arange(15)  # moving in through the loading
        z_up[15:20] = z_up[14]
        z_up[20:] = z_up[14] + 0.00001 * np.arange(1, n - 19)  # backing off
        z_lo = np.zeros(n)
        z_lo[25:] = 0.0005 * np.arange(1, 11)  # ejecting
        z_up[25:] = z_up[24] + 0.01  # gone
        pos = np.zeros((n, 3, 3))
        pos[:, 1, 2], pos[:, 2, 2] = z_lo, z_up
        force = np.zeros((n, 3, 3))
        force[:, 2, 2] = p_up * area  # the powder pushes the upper punch up
        force[:, 1, 2] = -ratio * p_up * area  # and the lower one down
        force[25:, 0, 2] = 2.0  # the die dragged up by the compact sliding out
        force[25:, 1, 2] = -2.0
        force[26, 1, 2] = -12.0
        gap = z_up - z_lo
        fnorm = np.zeros((n, 3))
        fnorm[:, 0] = 0.4 * p_up * 2 * math.pi * R * gap
        self.gap, self.k_max, self.k_rel = gap, 14, 24
        self.radius = np.full(50, 0.0004)
        self.path = os.path.join(self.tmp.name, "press.h5")
        write_run(self.path, 1e-3 * np.arange(n), walls, pos, force, self.radius, wall_normal_force=fnorm)

    def tearDown(self):
        self.tmp.cleanup()

    def test_numbers(self):
        c = tablet.analyse(self.path)
        self.assertEqual(c["k_max"], 14)
        self.assertAlmostEqual(c["p_max"], 10e6, delta=1e-3)
        # over the loading rows only: the old median over every loaded row gave (0.8 + 0.9) / 2
        self.assertAlmostEqual(c["ratio"], 0.8, places=12)
        self.assertAlmostEqual(c["radial_ratio"], 0.4, places=12)
        self.assertAlmostEqual(c["recovery"], (self.gap[24] - self.gap[14]) / self.gap[14], places=12)
        self.assertAlmostEqual(c["max_ejection_friction"], 2.0, places=12)
        self.assertAlmostEqual(c["max_ejection_punch"], 12.0, places=12)
        solid = 50 * 4 / 3 * math.pi * 0.0004**3
        self.assertAlmostEqual(c["dens"][14], solid / (self.area * self.gap[14]), places=12)

    def test_recovery_not_let_go(self):
        # the same cycle cut at row 22, the punch still pressing (6 MPa): no recovery, and its lower bound the gap's
        # growth to the last row
        with h5py.File(self.path, "r") as f:
            keep = {k: f["series"][k][()] for k in f["series"] if f["series"][k].shape[:1] == (35,)}
        c = tablet.analyse(self.path)
        self.assertAlmostEqual(c["recovery_min"], c["recovery"], places=15)  # let go: the bound is the recovery
        with h5py.File(self.path, "r+") as f:
            for k, v in keep.items():
                del f["series"][k]
                f["series"].create_dataset(k, data=v[:22])
        c = tablet.analyse(self.path)
        self.assertTrue(math.isnan(c["recovery"]))
        self.assertAlmostEqual(c["recovery_min"], (self.gap[21] - self.gap[14]) / self.gap[14], places=12)
        self.assertGreater(c["recovery_min"], 0)
        kv = dict(tablet.numbers(c))
        self.assertTrue(math.isnan(kv["elastic_recovery"]))
        self.assertEqual(kv["elastic_recovery_min"], c["recovery_min"])

    def test_quasi_static(self):
        # kinetic / elastic energy is checked only where the upper punch presses at half its largest or more while
        # loading and 10 % or more after it: rows 2 (no pressure) and 7 (3 MPa, loading) move fast and do not count;
        # row 22 (4 MPa, unloading) is the largest that counts
        c = tablet.analyse(self.path)
        self.assertTrue(math.isnan(c["max_kinetic_ratio"]))  # no elastic energy in the series: no ratio
        self.assertIsNone(tablet.quasi_static_warning(c, "p"))
        n = 35
        kinetic, elastic = np.zeros(n), np.ones(n)
        kinetic[2], kinetic[7], kinetic[10], kinetic[22] = 5.0, 4.0, 0.001, 0.3
        with h5py.File(self.path, "r+") as f:
            f["series"]["kinetic"][...] = kinetic
            f["series"]["elastic"][...] = elastic
        c = tablet.analyse(self.path)
        self.assertEqual(c["k_ke"], 22)
        self.assertEqual(c["max_kinetic_ratio"], 0.3)
        self.assertEqual(dict(tablet.numbers(c))["max_kinetic_ratio"], 0.3)
        w = tablet.quasi_static_warning(c, "p")
        self.assertIn("not quasi-static", w)
        self.assertIn("0.3 of the elastic energy", w)
        self.assertIn("at 4 MPa (after the largest pressure)", w)
        self.assertIn("the elastic recovery", w)
        kinetic[22] = 0.5 * tablet.QUASI  # calm enough: the largest that counts is now below QUASI
        with h5py.File(self.path, "r+") as f:
            f["series"]["kinetic"][...] = kinetic
        c = tablet.analyse(self.path)
        self.assertEqual(c["max_kinetic_ratio"], 0.05)
        self.assertIsNone(tablet.quasi_static_warning(c, "p"))
        kinetic[12] = 0.2  # 8 MPa while loading: counts, and names the figures read over the loading
        with h5py.File(self.path, "r+") as f:
            f["series"]["kinetic"][...] = kinetic
        c = tablet.analyse(self.path)
        w = tablet.quasi_static_warning(c, "p")
        self.assertIn("0.2 of the elastic energy", w)
        self.assertIn("at 8 MPa (loading)", w)
        self.assertIn("the density and Heckel fit", w)

    def test_report_line_mpa(self):
        png = os.path.join(self.tmp.name, "r.png")
        for cmd in ([PY, "-m", "libdem", "report", self.path, "-o", png],
                    [PY, os.path.join(ROOT, "tools", "plot_tablet.py"), self.path, "-o", png]):
            out = subprocess.run(cmd, cwd=os.path.join(ROOT, "python"), capture_output=True, text=True,
                                 check=True).stdout
            kv = dict(w.split("=", 1) for w in out.split())
            self.assertEqual(float(kv["max_upper_mpa"]), 10.0)
            self.assertEqual(float(kv["transmission"]), 0.8)
            self.assertEqual(float(kv["radial_mpa"]), 4.0)
            self.assertEqual(float(kv["max_ejection_friction_n"]), 2.0)
            self.assertEqual(float(kv["max_ejection_punch_n"]), 12.0)
            self.assertNotIn("max_upper_pa", kv)
            self.assertTrue(os.path.getsize(png) > 0)
            os.unlink(png)
        # the same cycle ejected by drawing the die down 0.5 mm per row instead (the lower punch stays): the die's
        # axial force is the friction, 3 N, the lower punch's 3 N with a 5 N spike
        h = h5py.File(self.path, "r+")
        pos, force = h["series/wall_position"], h["series/wall_force"]
        p, fo = pos[()], force[()]
        p[25:, 1, 2] = 0.0
        p[25:, 0, 2] = -0.0005 * np.arange(1, 11)
        fo[25:, 0, 2], fo[25:, 1, 2] = 3.0, -3.0
        fo[27, 1, 2] = -8.0
        pos[...], force[...] = p, fo
        h.close()
        c = tablet.analyse(self.path)
        self.assertTrue(c["eject_by_die"])
        self.assertAlmostEqual(c["max_ejection_friction"], 3.0, places=12)
        self.assertAlmostEqual(c["max_ejection_punch"], 8.0, places=12)
        self.assertAlmostEqual(float(c["eject_travel"][-1]), 0.005, places=12)
        bad = subprocess.run([PY, os.path.join(ROOT, "tools", "plot_tablet.py"), self.path, "--upper", "lid"],
                             capture_output=True, text=True)
        self.assertNotEqual(bad.returncode, 0)
        self.assertIn("plot_tablet: no wall named 'lid'", bad.stderr)


class DiametralTest(unittest.TestCase):
    """The press cycle of TabletTest followed by a diametral compression: two platens (plane walls platen_a, platen_b
    along -x and +x) close on a hand-made tablet - rings of spheres (r 0.1 mm) whose outermost centres lie 0.9 mm
    from the axis, in five layers 0.1 mm apart - so D = 2 mm and t = 0.6 mm; the platen force rises to 5 N, falls
    (the crack) and rises to 7 N (the halves crushed): tensile strength 2 F / (pi D t) = 2.6526 MPa with F = 5 N. A
    second frame, after the platens touched, must not be the one measured. A tablet more than twice as thick as the gap
    where the upper punch let go has come apart: no tensile strength."""

    def test_tensile_strength(self):
        with tempfile.TemporaryDirectory() as d:
            n = 30
            walls = [dict(name="die", normal=[0, 0, 1], radius=0.0011), dict(name="lower", normal=[0, 0, 1]),
                     dict(name="upper", normal=[0, 0, -1]), dict(name="platen_a", normal=[-1, 0, 0]),
                     dict(name="platen_b", normal=[1, 0, 0])]
            pos, force = np.zeros((n, 5, 3)), np.zeros((n, 5, 3))
            pos[:, 2, 2] = 0.001 - 1e-5 * np.minimum(np.arange(n), 5)  # the upper punch presses, rows 1-5
            force[1:6, 2, 2] = np.arange(1, 6)
            pos[:, 3, 0], pos[:, 4, 0] = 0.0012, -0.0012
            close = np.arange(n) >= 15
            pos[close, 3, 0] -= 1e-5 * np.arange(1, 16)
            pos[close, 4, 0] += 1e-5 * np.arange(1, 16)
            # touches at row 16, cracks after 5 N (down to 3.5 N: below 80 % of it), then crushes the halves up to 7 N
            f = np.concatenate([np.zeros(16), np.linspace(1, 5, 5), [3.5, 3.0], np.linspace(4, 7, 4), [6.5, 6.0, 6.0]])
            force[:, 3, 0], force[:, 4, 0] = f, -f
            x = []
            for layer in range(5):
                for ring, count in ((0.0009, 40), (0.0006, 24), (0.0003, 12), (0.0, 1)):
                    for k in range(count):
                        a = 2 * math.pi * k / count
                        x.append([ring * math.cos(a), ring * math.sin(a), 0.0001 * layer])
            x = np.array(x)
            messy = x * 1.5
            frames = dict(time=[0.010, 0.025], step=[10, 25], position=[x, messy])
            path = os.path.join(d, "brazil.h5")
            radius = np.full(len(x), 0.0001)
            write_run(path, 1e-3 * np.arange(n), walls, pos, force, radius, frames=frames)
            c = tablet.analyse(path)
            dia = c["dia"]
            self.assertAlmostEqual(dia["diameter"], 0.002, places=15)
            self.assertAlmostEqual(dia["thickness"], 0.0006, places=15)
            self.assertEqual(dia["peak"], 5.0)  # the failure load, not the 7 N of the crushed halves
            self.assertTrue(dia["failed"])
            self.assertEqual(dia["largest"], 7.0)
            self.assertAlmostEqual(dia["tensile"], 2 * 5.0 / (math.pi * 0.002 * 0.0006), places=6)
            self.assertAlmostEqual(dia["after_peak"], 1.2, places=12)
            solid = len(x) * 4 / 3 * math.pi * 0.0001**3
            self.assertAlmostEqual(dia["density"], solid / (math.pi * 0.001**2 * 0.0006), places=12)
            out = subprocess.run([PY, "-m", "libdem", "report", path, "-o", os.path.join(d, "b.png")],
                                 cwd=os.path.join(ROOT, "python"), capture_output=True, text=True, check=True).stdout
            kv = dict(w.split("=", 1) for w in out.split())
            self.assertAlmostEqual(float(kv["tensile_mpa"]), 2.65258, places=5)
            self.assertEqual(float(kv["max_platen_n"]), 5.0)
            self.assertEqual(float(kv["tablet_failed"]), 1.0)
            self.assertTrue(dia["whole"])
            self.assertEqual(float(kv["tablet_whole"]), 1.0)
            # a compact that came apart out of the die: its spheres spread along the axis to 2.1 times the gap where
            # the upper punch let go (0.95 mm): no tablet, no tensile strength, whatever the platens meet
            flown = x * np.array([1.0, 1.0, 0.0021 / 0.0004])
            write_run(path, 1e-3 * np.arange(n), walls, pos, force, radius,
                      frames=dict(time=[0.010, 0.025], step=[10, 25], position=[flown, messy]))
            gone = tablet.analyse(path)["dia"]
            self.assertAlmostEqual(gone["thickness"], 0.0023, places=12)
            self.assertFalse(gone["whole"])
            self.assertTrue(math.isnan(gone["tensile"]))
            # a tablet that never cracks (the force only rises): its largest force, marked so
            force[16:, 3, 0] = np.linspace(1, 7, n - 16)
            force[16:, 4, 0] = -force[16:, 3, 0]
            write_run(path, 1e-3 * np.arange(n), walls, pos, force, radius, frames=frames)
            dia = tablet.analyse(path)["dia"]
            self.assertFalse(dia["failed"])
            self.assertEqual(dia["peak"], 7.0)
            # a run stopped before the platens touched (SIGTERM, --stop-after): the press part alone, with a note
            force[:, 3:, :] = 0.0
            write_run(path, 1e-3 * np.arange(n), walls, pos, force, radius, frames=frames)
            c = tablet.analyse(path)
            self.assertIsNone(c["dia"])
            self.assertTrue(c["platens_untouched"])
            self.assertAlmostEqual(c["p_max"] / (5.0 / (math.pi * 0.0011**2)), 1.0, places=12)  # the bore's area
            rep = subprocess.run([PY, "-m", "libdem", "report", path, "-o", os.path.join(d, "c.png")],
                                 cwd=os.path.join(ROOT, "python"), capture_output=True, text=True, check=True)
            kv = dict(w.split("=", 1) for w in rep.stdout.split())
            self.assertNotIn("tensile_mpa", kv)
            self.assertNotIn("tablet_whole", kv)
            self.assertAlmostEqual(float(kv["max_upper_mpa"]), 5.0 / (math.pi * 0.0011**2) * 1e-6, places=4)
            self.assertIn("the platens (platen_a, platen_b) never touched the tablet", rep.stderr)
            self.assertIn("the press part is reported alone", rep.stderr)


SQUEEZE = """name: one sphere squeezed by a piston
precision: fp64
backend: reference
effects: [hertz, damping, walls]
materials:
  - {name: gel, density: 1000, young: 1.0e7, poisson: 0.3, restitution: 0.5, friction: 0.3}
  - {name: steel, density: 7800, young: 2.0e11, poisson: 0.3, restitution: 0.5, friction: 0.3}
particles:
  - material: gel
    spheres:
      - {x: [0, 0, 0.001], radius: 0.001}
walls:
  - {type: plane, name: floor, material: steel, point: [0, 0, 0], normal: [0, 0, 1]}
  - {type: plane, name: piston, material: steel, point: [0, 0, 0.0021], normal: [0, 0, -1],
     motion: [{velocity: [0, 0, -0.001], duration: 0.2}]}
domain: {lo: [-0.005, -0.005, -0.002], hi: [0.005, 0.005, 0.005]}
time: {dt_rayleigh: 0.2, duration: 0.2}
output: {frame_every: 0.02, series_every: 0.001, fields: [position, contacts]}
"""


class RealRunTest(unittest.TestCase):
    """One sphere (r 1 mm, E 10 MPa, nu 0.3) between a floor and a piston coming down at 1 mm/s, touching the
    sphere at z = 2 mm, 0.1 mm below its start: a run of dem (reference backend, well under a second)."""

    def test_squeeze(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "squeeze.yaml"), "w") as fh:
                fh.write(SQUEEZE)
            subprocess.run([os.path.join(ROOT, "build", "dem"), "run", "squeeze.yaml", "-o", "sq.h5", "--quiet"],
                           cwd=d, check=True)
            run = Run(os.path.join(d, "sq.h5"))
            disp, force = analysis.force_displacement(run, "piston")
            z = run.wall("piston").position[:, 2]
            true = 0.002 - z  # the piston's travel past the sphere's top
            # the zero is the first row with a force: within one row's travel (1 um) after the true contact
            self.assertLessEqual(np.max(np.abs(disp - true)[true > 0]), 1e-6 + 1e-12)
            self.assertTrue(np.all(force[true < 0] == 0))
            # two Hertz contacts in series, each at half the travel (quasi-static; damping adds under 1 %)
            estar = 1 / ((1 - 0.3**2) / 1e7 + (1 - 0.3**2) / 2e11)
            hertz = 4 / 3 * estar * math.sqrt(0.001) * (np.maximum(true, 0) / 2) ** 1.5
            sel = true > 5e-6
            self.assertLess(np.max(np.abs(force[sel] / hertz[sel] - 1)), 0.02)
            self.assertEqual(analysis.coordination_number(run, walls=True), 2.0)
            self.assertEqual(analysis.coordination_number(run), 0.0)
            self.assertTrue(math.isnan(analysis.coordination_number(run, rattlers=False)))
            self.assertEqual(analysis.coordination_number(run, frame=0, walls=True), 0.0)
            c = run.contacts(-1)
            np.testing.assert_allclose(c["overlap"], true[-1] / 2, rtol=1e-3)


def c_declarations():
    """name -> (return type, [argument types]) of the public headers' functions, by gcc's -aux-info"""
    with tempfile.TemporaryDirectory() as d:
        aux = os.path.join(d, "decl.txt")
        subprocess.run(["cc", "-std=c11", "-fsyntax-only", "-aux-info", aux, "-I", os.path.join(ROOT, "include"),
                        "-x", "c", "-"], input="#include <dem.h>\n", text=True, check=True)
        out = {}
        with open(aux) as fh:
            lines = fh.readlines()
        for line in lines:
            m = re.match(r"/\* .*include/dem\w*\.h:\d+:\w+ \*/ extern (.*?)\b(dem_\w+) \((.*)\);", line)
            if m:
                out[m.group(2)] = (m.group(1).strip(), [a.strip() for a in m.group(3).split(",")])
        return out


class SimTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        from libdem import sim

        cls.sim = sim
        path = sim.library_path()
        if not path or not os.path.exists(path):
            raise AssertionError("no libdem.so: run `make python-lib` (build/pic/libdem.so) or set LIBDEM_PATH")

    def test_layout_against_header(self):
        """every ctypes structure's size and field offsets as the C compiler lays out dem.h's"""
        sim = self.sim
        structs = {sim.Material: "dem_material", sim.Stage: "dem_stage", sim.WallDesc: "dem_wall",
                   sim.Config: "dem_config", sim.TimeScales: "dem_time_scales", sim.Energy: "dem_energy_t",
                   sim.Contact: "dem_contact", sim.StateArray: "dem_state_array", sim.McStats: "dem_mc_stats",
                   sim.State: "dem_state", sim.MaterialPair: "dem_material_pair", sim.Stability: "dem_stability"}
        lines = ["#include <stdio.h>", "#include <stddef.h>", "#include <dem.h>", "int main(void) {"]
        want = []
        for py, c in structs.items():
            lines.append(f'printf("%zu\\n", sizeof({c}));')
            want.append(__import__("ctypes").sizeof(py))
            for name, _ in py._fields_:
                lines.append(f'printf("%zu\\n", offsetof({c}, {name}));')
                want.append(getattr(py, name).offset)
        for k, v in (("DEM_MAX_STAGES", sim.MAX_STAGES), ("DEM_MAX_WALLS", sim.MAX_WALLS),
                     ("DEM_STATE_MAX_ARRAYS", sim.STATE_MAX_ARRAYS)):
            lines.append(f'printf("%d\\n", {k});')
            want.append(v)
        for name, (fid, _) in sim.FIELDS.items():
            lines.append(f'printf("%d\\n", DEM_FIELD_{name.upper()});')
            want.append(fid)
        lines.append("return 0; }")
        with tempfile.TemporaryDirectory() as d:
            src, exe = os.path.join(d, "layout.c"), os.path.join(d, "layout")
            with open(src, "w") as fh:
                fh.write("\n".join(lines) + "\n")
            subprocess.run(["cc", "-std=c11", "-I", os.path.join(ROOT, "include"), src, "-o", exe], check=True)
            got = [int(x) for x in subprocess.run([exe], capture_output=True, text=True, check=True).stdout.split()]
        self.assertEqual(got, want)

    def test_version(self):
        """the package's version (module and pyproject.toml) is the library's DEM_VERSION"""
        with open(os.path.join(ROOT, "include", "dem.h")) as fh:
            version = re.search(r'#define DEM_VERSION "([^"]+)"', fh.read()).group(1)
        self.assertEqual(libdem.__version__, version)
        with open(os.path.join(ROOT, "python", "pyproject.toml")) as fh:
            self.assertIn(f'version = "{version}"', fh.read())

    def test_signatures_against_header(self):
        import ctypes

        sim = self.sim
        P = ctypes.POINTER
        base = {"int": ctypes.c_int, "long int": ctypes.c_long, "double": ctypes.c_double,
                "unsigned int": ctypes.c_uint, "size_t": ctypes.c_size_t, "dem_field": ctypes.c_int, "void": None,
                "dem_sim *": ctypes.c_void_p, "char *": ctypes.c_char_p, "dem_contact **": P(P(sim.Contact))}
        structs = {"dem_material": sim.Material, "dem_wall": sim.WallDesc, "dem_config": sim.Config,
                   "dem_time_scales": sim.TimeScales, "dem_energy_t": sim.Energy, "dem_state": sim.State,
                   "dem_material_pair": sim.MaterialPair, "dem_stability": sim.Stability}
        for k, v in structs.items():
            base[k + " *"] = P(v)
        base.update({"double *": P(ctypes.c_double), "long int *": P(ctypes.c_long)})

        def ctype(c):
            c = re.sub(r"\bconst\b\s*", "", c).strip()
            c = re.sub(r"\s*\*", " *", c).replace("* *", "**")
            if c not in base:
                raise AssertionError(f"no ctypes type for C type '{c}'")
            return base[c]

        decl = c_declarations()
        self.assertGreater(len(decl), 90)
        for name, (res, args) in sim.SIGNATURES.items():
            self.assertIn(name, decl, f"{name} is not declared in include/")
            cres, cargs = decl[name]
            cargs = [] if cargs == ["void"] else cargs
            self.assertEqual(res, ctype(cres), f"{name}: returns {cres}")
            self.assertEqual(len(args), len(cargs), f"{name}: {cargs}")
            for a, c in zip(args, cargs):
                self.assertEqual(a, ctype(c), f"{name}: argument {c}")

    def test_sphere_on_plane(self):
        sim = self.sim
        E, nu, r, delta = 1e7, 0.3, 1e-3, 2e-5
        with sim.Sim() as s:
            gel = s.add_material(density=1000, young=E, poisson=nu, restitution=0.5, friction=0.3)
            steel = s.add_material(density=7800, young=float("inf"), poisson=0.3, restitution=0.5, friction=0.3)
            ids = s.add_particles([[0, 0, r - delta], [0.01, 0, 0.005]], radius=r, material=gel)
            np.testing.assert_array_equal(ids, [0, 1])
            self.assertEqual(s.add_plane([0, 0, 0], [0, 0, 1], steel), 0)
            s.set_domain([-0.02] * 3, [0.02] * 3)
            dt = 0.2 * s.time_scales()["rayleigh_time"]
            s.set_dt(dt)
            s.set_effects(["hertz", "walls"])
            with self.assertRaises(ValueError):
                s.set_effects(["hertz", "no_such_effect"])
            s.start(backend="reference", precision="fp64", contacts=True)
            self.assertEqual((s.count, s.wall_count), (2, 1))
            self.assertIn("reference", s.describe())
            s.step(1)
            x = s.get("x")
            self.assertEqual(x.shape, (2, 3))
            ov = r - x[0, 2]
            # a rigid wall: E* from the sphere alone; the force of the step's end, at its overlap
            hertz = 4 / 3 * E / (1 - nu * nu) * math.sqrt(r) * ov**1.5
            f = s.wall_force(0)
            self.assertAlmostEqual(-f[2] / hertz, 1.0, delta=1e-9)
            self.assertAlmostEqual(s.wall_normal_force(0) / hertz, 1.0, delta=1e-9)
            np.testing.assert_allclose(s.get("wall_force"), [f])
            np.testing.assert_allclose(s.get("force")[0], -f, rtol=1e-12)
            c = s.contacts()
            self.assertEqual((c["npairs"], list(c["i"]), list(c["j"]), list(c["wall"])), (0, [0], [-1], [0]))
            self.assertAlmostEqual(c["overlap"][0], ov, delta=1e-15)
            e = s.energy()
            self.assertEqual((e["contacts"], e["wall_contacts"]), (0, 1))
            self.assertAlmostEqual(e["elastic"] / (0.4 * hertz * ov), 1.0, delta=1e-9)  # 2/5 F delta
            # written fields: sphere 1 given a velocity flies free (no gravity): x advances by v dt a step
            s.set("v", [[0, 0, 0], [0, 0, 0.2]])
            x0 = s.get("x")
            s.step(10)
            np.testing.assert_allclose(s.get("v")[1], [0, 0, 0.2])
            self.assertAlmostEqual(s.get("x")[1, 2] - x0[1, 2], 10 * dt * 0.2, delta=1e-15)
            s.set("x", [[0, 0, 0.004], [0.01, 0, 0.005]])
            np.testing.assert_array_equal(s.get("x"), [[0, 0, 0.004], [0.01, 0, 0.005]])
            self.assertEqual(s.step_index, 11)
            with self.assertRaises(sim.DemError):
                s.wall_force(3)
            with self.assertRaises(ValueError):
                s.set("force", np.zeros((2, 3)))

    def test_backends_bitwise(self):
        """the same bed of 64 spheres falling on a plane, on the reference and on PoCL: the same bits"""
        sim = self.sim
        out = {}
        for backend in ("reference", "opencl"):
            with sim.Sim() as s:
                g = s.add_material(density=1000, young=1e7, poisson=0.3, restitution=0.5, friction=0.3)
                x = np.stack(np.meshgrid(*[np.arange(4) * 0.0021] * 3, indexing="ij"), -1).reshape(-1, 3) + 0.002
                v = np.random.default_rng(1).normal(0, 0.01, x.shape)
                s.add_particles(x, radius=0.001, material=g, v=v)
                s.add_plane([0, 0, 0], [0, 0, 1], g)
                s.set_gravity([0, 0, -9.81])
                s.set_domain([-0.01] * 3, [0.03] * 3)
                s.set_dt(0.2 * s.time_scales()["rayleigh_time"])
                s.set_effects(["hertz", "damping", "friction", "gravity", "walls"])
                s.start(backend=backend, precision="fp64")
                s.step(1000)
                out[backend] = (s.get("x"), s.get("v"), s.wall_force(0))
                self.assertGreater(s.energy()["contacts"], 0)
        for a, b in zip(out["reference"], out["opencl"]):
            np.testing.assert_array_equal(a, b)

    def test_from_scene(self):
        """a `dem run` scene driven from Python: two_spheres.yaml's set-up, configuration and steps; its first 1000
        steps give the bits `dem run --stop-after 1000` checkpoints; a bad scene is refused with file:line"""
        sim = self.sim
        scene = os.path.join(ROOT, "scenes", "two_spheres.yaml")
        with sim.Sim.from_scene(scene) as s:
            self.assertEqual((s.count, s.scene_steps), (2, 3000))
            self.assertEqual(s.scene_config["precision"], "fp64")
            s.start(**s.scene_config)
            s.step(1000)
            x, v = s.get("x"), s.get("v")
        with tempfile.TemporaryDirectory() as d:
            subprocess.run([os.path.join(ROOT, "build", "dem"), "run", scene, "-o", "t.h5", "--quiet",
                            "--stop-after", "1000"], cwd=d, check=True)
            with h5py.File(os.path.join(d, "t.ckpt.h5"), "r") as f:
                np.testing.assert_array_equal(x, f["state/x"][:].reshape(-1, 3))
                np.testing.assert_array_equal(v, f["state/v"][:].reshape(-1, 3))
            bad = os.path.join(d, "bad.yaml")
            with open(scene) as fh, open(bad, "w") as out:
                out.write(fh.read().replace("poisson: 0.46", "poisson: 0.7"))
            with self.assertRaises(sim.DemError) as e:
                sim.Sim.from_scene(bad)
            self.assertIn("bad.yaml:7: materials[0].poisson: Poisson's ratio must be in (-1, 0.5]", str(e.exception))


class MdrStiffnessTest(unittest.TestCase):
    """The time-step estimate against the highest frequency measured in a held MDR compact (tools/mdr_stiffness/
    jacobian.py: 64 spheres pressed to 100 MPa at psi_b 0, E 5 GPa, Y 60 MPa; the one-step stiffness from finite
    differences of the run itself, each sphere moved +-1e-10 m from one saved state). A sphere pushed through more
    than its own radius into a side wall is 30 times stiffer there than MDR's closed-form slope (laws/mdr.h
    mdr_stiffness), so an estimate from that slope gave omega dt 0.58 against the measured 1.48; the estimate takes
    each MDR contact's slope from the law itself (mdr_row_slope) and must not fall below the measured one."""

    def test_estimate_bounds_measured(self):
        sys.path.insert(0, os.path.join(ROOT, "tools", "mdr_stiffness"))
        import jacobian

        lines = []
        est, measured = jacobian.measure("0.0", out=lines.append)
        print("\n".join(lines))
        self.assertGreater(measured, 1.0)  # the deep wall contact is there: near the undamped bound 2
        self.assertGreaterEqual(est, measured)
        self.assertLess(est, 1.2 * measured)  # an estimate, not a bound far above the mode


if __name__ == "__main__":
    unittest.main(verbosity=2)
