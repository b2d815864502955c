#!/usr/bin/python3
"""Checks the walls' surfaces in a dem run's XDMF output against the walls' geometry in its HDF5 file: the "walls"
grid has one triangle mesh per frame (read through the XDMF's own hyperslabs), every wall has triangles, and in the
first and last frame a plane's vertices lie in its plane (or on its cup's sphere inside the cup's rim), a cylinder's
at its radius from its axis and along its height. The plane's or axis' point is the wall's position in the series'
first row (time 0), at the last frame moved as the mesh moved, which must be a rigid translation by the wall's travel.
usage: xdmf_walls_check.py RUN.xmf [triangles=T] [WALL=VX,VY,VZ ...]
  triangles=T: the walls' meshes have T triangles in all;
  WALL=VX,VY,VZ (a wall's name as in /series wall_names, and its constant velocity from the first frame): that wall's
  mesh at the last frame must be the first frame's moved by the velocity times the time between them; every other
  wall must not move."""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

xmf = sys.argv[1]
velocity, triangles = {}, None
for a in sys.argv[2:]:
    name, v = a.split("=")
    if name == "triangles":
        triangles = int(v)
    else:
        velocity[name] = np.array([float(c) for c in v.split(",")])
root = ET.parse(xmf).getroot()
folder = os.path.dirname(xmf)
problems = []


def fail(msg):
    sys.exit(f"xdmf_walls_check: {xmf}: {msg}")


def read(item, f):
    """The array a DataItem names: an HDF dataset, or a hyperslab (start, stride, count rows) of one"""
    if item.get("ItemType") == "HyperSlab":
        sel, data = list(item)
        rows = np.array([int(v) for v in sel.text.split()]).reshape(3, -1)
        whole = read(data, f)
        idx = tuple(slice(s, s + c * st, st) for s, st, c in zip(*rows))
        return whole[idx].reshape([int(v) for v in item.get("Dimensions").split()])
    fname, path = item.text.strip().split(":", 1)
    if os.path.join(folder, fname) != f.filename and fname != os.path.basename(f.filename):
        fail(f"{fname} is not the run's file")
    return f[path][()]


walls_grid = [g for g in root.iter("Grid") if g.get("Name") == "walls"]
if len(walls_grid) != 1 or walls_grid[0].get("CollectionType") != "Temporal":
    fail("no temporal 'walls' grid")
frames = [g for g in walls_grid[0] if g.tag == "Grid"]
particle_frames = [g for g in root.iter("Grid") if (g.get("Name") or "").startswith("frame ")]
if len(frames) != len(particle_frames) or len(frames) < 2:
    fail(f"{len(frames)} wall frames for {len(particle_frames)} particle frames (at least 2 needed)")
h5 = h5py.File(os.path.join(folder, frames[0].find("Geometry/DataItem/DataItem[2]").text.split(":")[0]), "r")
names = h5["series"].attrs["wall_names"]
names = (names.decode() if isinstance(names, bytes) else names).split("\n")
nw = len(names)
normal = h5["series/wall_normal"][()]
radius, height = h5["series/wall_radius"][()], h5["series/wall_height"][()]
cup_r, cup_d = h5["series/wall_cup_radius"][()], h5["series/wall_cup_depth"][()]


def mesh(g):
    tri = read(g.find("Topology/DataItem"), h5)
    pts = read(g.find("Geometry/DataItem"), h5)
    wall = read(g.find("Attribute[@Name='wall']/DataItem"), h5)
    t = float(g.find("Time").get("Value"))
    if tri.shape != (int(g.find("Topology").get("NumberOfElements")), 3) or wall.shape != (tri.shape[0],):
        fail(f"triangles {tri.shape}, walls {wall.shape}")
    if tri.min() < 0 or tri.max() >= len(pts):
        fail("a triangle's vertex is not a point of the mesh")
    return tri, pts, wall, t


tri0, p0, wall0, t0 = mesh(frames[0])
tri1, p1, wall1, t1 = mesh(frames[-1])
if not (np.array_equal(tri0, tri1) and np.array_equal(wall0, wall1)) or p0.shape != p1.shape:
    fail("the wall mesh's connectivity changes between frames")
if triangles is not None and len(tri0) != triangles:
    fail(f"{len(tri0)} triangles, expected {triangles}")
if sorted(set(wall0.tolist())) != list(range(nw)):
    fail(f"triangles of walls {sorted(set(wall0.tolist()))}, expected every one of {nw}")
# each wall's point at the start: the series' first row (written at time 0, as the first frame)
if h5["series/time"][0] != 0 or t0 != 0:
    fail("the first frame or series row is not at time 0")
pos0 = h5["series/wall_position"][0]
checked = 0
for k in range(nw):
    verts = np.unique(tri0[wall0 == k])
    if set(verts.tolist()) & set(np.unique(tri0[wall0 != k]).tolist()):
        fail(f"wall {names[k]}: shares vertices with another wall")
    n = normal[k] / np.linalg.norm(normal[k])
    move = p1[verts] - p0[verts]
    want = velocity.get(names[k], np.zeros(3)) * (t1 - t0)
    scale = np.abs(p0[verts]).max()
    # rigid: every vertex moved by the same vector, which is the wall's travel
    if np.abs(move - move[0]).max() > 1e-12 * scale:
        problems.append(f"wall {names[k]}: not moved rigidly (spread {np.abs(move - move[0]).max():.3g} m)")
    if np.abs(move[0] - want).max() > 1e-9 * scale + 1e-6 * np.abs(want).max():
        problems.append(f"wall {names[k]}: moved {move[0].tolist()} between t = {t0} and {t1}, expected {want.tolist()}")
    for x, point in ((p0[verts], pos0[k]), (p1[verts], pos0[k] + move[0])):
        d = x - point  # the wall's point at this frame: at the start, then moved as its mesh moved
        h = d @ n
        rho = np.linalg.norm(d - np.outer(h, n), axis=1)
        if radius[k] > 0:  # cylinder: every vertex at its radius from the axis, from its point along its height
            if np.abs(rho - radius[k]).max() > 1e-12 * radius[k]:
                problems.append(f"wall {names[k]}: vertices {np.abs(rho - radius[k]).max():.3g} m off the radius")
            if height[k] > 0 and (abs(h.min()) > 1e-12 * scale or abs(h.max() - height[k]) > 1e-12 * scale):
                problems.append(f"wall {names[k]}: from {h.min()} to {h.max()} m along its axis, height {height[k]}")
        else:  # plane: (x - point).n = 0, but inside a cup's rim: on the cup's sphere
            land = rho >= cup_r[k] * (1 - 1e-12)
            if np.abs(h[land]).max() > 1e-12 * scale:
                problems.append(f"wall {names[k]}: a vertex {np.abs(h[land]).max():.3g} m off its plane")
            if cup_r[k] > 0:
                R = (cup_r[k] ** 2 + cup_d[k] ** 2) / (2 * cup_d[k])
                s = np.linalg.norm(d[~land] - (R - cup_d[k]) * n, axis=1)
                if (~land).sum() < 2 or np.abs(s - R).max() > 1e-12 * scale:
                    problems.append(f"wall {names[k]}: cup vertices off its sphere")
                if abs(h.min() + cup_d[k]) > 1e-12 * scale:
                    problems.append(f"wall {names[k]}: the cup is {-h.min()} m deep, not {cup_d[k]}")
        checked += len(verts)
if problems:
    sys.exit("xdmf_walls_check: " + "; ".join(problems))
print(f"xdmf_walls_check: {xmf}: {nw} walls, {len(tri0)} triangles, {checked} vertices checked in frames at t = "
      f"{t0} and {t1}")
