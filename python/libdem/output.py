"""Reading what `dem run` writes: one HDF5 file, or the files of a run continued with `dem run --restart`.

The layout (app/output.c writes it; `h5ls -r RUN.h5` lists it):
  /series       one row per sample: time [s], step, kinetic, elastic, potential, total [J], contacts, coordination,
                wall_contacts, (with a scene's `sample`) strain, stress [Pa], (MC-strain) mc_iterations, mc_capped;
                with walls: wall_position [rows, walls, 3] m, wall_force [rows, walls, 3] N (the force each wall
                receives), wall_normal_force [rows, walls] N, and per wall (not per row) wall_radius, wall_height,
                wall_cup_radius, wall_cup_depth [m], wall_normal; the attribute wall_names (one newline-joined
                string, in the walls' order)
  /particles    radius [m], material (per sphere), input_index (with particle_order: spatial)
  /frames       time, step and each output field per frame: position, velocity, angular_velocity, force, torque
                [frames, n, 3], stress [frames, n, 6]; under mdr with the field radius, apparent_radius [frames, n]
                (the radius each sphere's contacts see; /particles/radius is the radius as created)
  /contacts     (the field `contacts`) the contact network of every frame, ragged: frame_start, frame_pairs, ids
                [rows, 2] (j = -1 - wall for a wall contact), data [rows, 12], normal_force [rows]
  /walls        the walls as triangle meshes for ParaView
Every dataset with a unit carries it as its attribute `units`.

A run in parts (`--restart`) is given as its files in the order they ran: their series are joined by step number, a
later file's rows replacing the earlier's from its first step on (a restart from an earlier checkpoint repeats
steps), and so are their frames; a gap between two parts, parts out of order, or files of different runs are
refused (OutputError).
"""
import math
import os

import h5py
import numpy as np

# the per-wall datasets of /series that are not rows
WALL_SHAPE = ("wall_radius", "wall_height", "wall_cup_radius", "wall_cup_depth", "wall_normal")


class OutputError(ValueError):
    """A file that is not a dem run output, or parts that do not continue each other."""


def _text(v):
    if isinstance(v, bytes):
        return v.decode(errors="replace")
    if isinstance(v, np.ndarray) and v.dtype.kind in "SO" and v.size == 1:
        return _text(v.reshape(-1)[0])
    return v if isinstance(v, str) else str(v)


def _attr(v):
    """an HDF5 attribute as text or a Python number"""
    if isinstance(v, (bytes, str)):
        return _text(v)
    a = np.asarray(v)
    if a.dtype.kind in "SOU":
        return _text(a.reshape(-1)[0]) if a.size == 1 else [_text(x) for x in a.reshape(-1)]
    return a.item() if a.size == 1 else a


def _units(dset):
    u = dset.attrs.get("units")
    return _text(u) if u is not None else None


class _Part:
    """One output file: its series read whole; frames and contacts read when asked for."""

    def __init__(self, path):
        self.path = os.fspath(path)
        try:
            f = h5py.File(self.path, "r")
        except OSError as e:
            raise OutputError(f"cannot open {self.path}: {e}") from None
        with f:
            if "series" not in f or "time" not in f["series"]:
                raise OutputError(f"{self.path}: no /series/time: not an output of dem run")
            self.attrs = {k: _attr(v) for k, v in f.attrs.items()}
            s = f["series"]
            n = len(s["time"])
            self.units = {}
            self.series, self.shape = {}, {}
            for k, d in s.items():
                if not isinstance(d, h5py.Dataset):
                    continue
                if k in WALL_SHAPE:
                    self.shape[k] = d[()]
                elif d.shape and d.shape[0] == n:
                    self.series[k] = d[()]
                else:
                    continue
                u = _units(d)
                if u:
                    self.units[k] = u
            if "step" not in self.series:  # outputs without a step column: the row number
                self.series["step"] = np.arange(n, dtype=float)
            raw = s.attrs.get("wall_names")
            self.wall_names = _text(raw).split("\n") if raw is not None and _text(raw) else []
            self.series_attrs = {k: _attr(v) for k, v in s.attrs.items() if k != "wall_names"}
            p = f.get("particles")
            self.particles = {k: d[()] for k, d in p.items() if isinstance(d, h5py.Dataset)} if p is not None else {}
            fr = f.get("frames")
            self.frame_time = fr["time"][()] if fr is not None and "time" in fr else np.zeros(0)
            self.frame_step = fr["step"][()] if fr is not None and "step" in fr else np.zeros(0)
            self.frame_fields = [k for k in fr.keys() if k not in ("time", "step")] if fr is not None else []
            for k in self.frame_fields:
                u = _units(fr[k])
                if u:
                    self.units[k] = u
            if fr is not None and "time" in fr:
                self.units.setdefault("frame_time", _units(fr["time"]) or "s")
            self.has_contacts = "contacts" in f


class Wall:
    """One wall's series, by name: position [rows, 3] m, force [rows, 3] N (what the particles exert on it),
    normal_force [rows] N (the sum of the particles' force components along their contact normals: a die's radial
    force, a plane's normal force), time and step of the rows; and its shape: kind ('plane' or 'cylinder'), normal
    (a plane's normal towards the particles, a cylinder's axis), radius, height, cup_radius, cup_depth [m]."""

    def __init__(self, run, index):
        s = run.series
        self.name, self.index = run.wall_names[index], index
        self.time, self.step = s["time"], s["step"]
        self.position = s["wall_position"][:, index, :]
        self.force = s["wall_force"][:, index, :]
        wn = s.get("wall_normal_force")
        self.normal_force = wn[:, index] if wn is not None else np.full(len(self.time), np.nan)
        sh = run.wall_shape
        self.radius = float(sh["wall_radius"][index]) if "wall_radius" in sh else 0.0
        self.height = float(sh["wall_height"][index]) if "wall_height" in sh else 0.0
        self.cup_radius = float(sh["wall_cup_radius"][index]) if "wall_cup_radius" in sh else 0.0
        self.cup_depth = float(sh["wall_cup_depth"][index]) if "wall_cup_depth" in sh else 0.0
        self.normal = np.asarray(sh["wall_normal"][index], dtype=float) if "wall_normal" in sh else None
        self.kind = "cylinder" if self.radius > 0 else "plane"

    def __repr__(self):
        return f"Wall({self.name!r}, {self.kind}, {len(self.time)} rows)"


class _Frames:
    """run.frames: len(), indexing (negative from the end) and iteration over run.frame(k); .time and .step."""

    def __init__(self, run):
        self._run = run

    def __len__(self):
        return len(self._run._frame_at)

    def __getitem__(self, k):
        return self._run.frame(k)

    def __iter__(self):
        return (self._run.frame(k) for k in range(len(self)))

    @property
    def time(self):
        return self._run.frame_time

    @property
    def step(self):
        return self._run.frame_step


class Run:
    """The output of one dem run: Run("out.h5"), or Run(["a.h5", "b.h5"]) for a run continued with --restart.

    series      dict name -> numpy array over the rows (see the module's docstring)
    wall_names  list of the walls' names, in the order of the wall_* columns
    wall(name)  a Wall: position, force, normal_force series and the wall's shape
    radius      the spheres' radii [m]; material: their material ids
    frames      the frames: len(run.frames), run.frames[k] == run.frame(k); run.frame_time, run.frame_step
    frame(k)    dict: time, step, radius, material and every output field of frame k (position, velocity, ...)
    frame_field(name)  one output field over all frames, [frames, n, ...]
    contacts(k) the contact network of frame k (a run with the output field `contacts`)
    units       dict name -> unit of every series and frame field that has one
    attrs       the file's attributes (scene_name, precision, effects, dt, model, ...)
    """

    def __init__(self, paths):
        paths = [paths] if isinstance(paths, (str, bytes, os.PathLike)) else list(paths)
        if not paths:
            raise OutputError("no output file given")
        self.paths = [os.fspath(p) for p in paths]
        parts = [_Part(p) for p in self.paths]
        first = parts[0]
        self.attrs, self.wall_names, self.wall_shape = first.attrs, first.wall_names, first.shape
        self.series_attrs, self.particles = first.series_attrs, first.particles
        self.units = dict(first.units)
        self.units.setdefault("radius", "m")
        self.frame_fields = list(first.frame_fields)
        self.series = dict(first.series)
        # each frame: (part, index in that part)
        frame_at = [(0, k) for k in range(len(first.frame_time))]
        ftime, fstep = list(first.frame_time), list(first.frame_step)
        start = first.series["step"][0] if len(first.series["step"]) else -math.inf
        for i in range(1, len(parts)):
            p, prev = parts[i], self.paths[i - 1]
            r0, r1 = self.particles.get("radius"), p.particles.get("radius")
            if (p.wall_names != self.wall_names or r0 is None or r1 is None or not np.array_equal(r0, r1)
                    or p.attrs.get("model") != self.attrs.get("model")):
                raise OutputError(f"{p.path} does not continue {prev}: other walls, spheres or contact model (not a "
                                  "--restart of the same run)")
            steps = p.series["step"]
            if not len(steps):
                continue
            cut = steps[0]
            if cut <= start:
                raise OutputError(f"{p.path} starts at step {cut:.0f}, not after {prev} does (step {start:.0f}): give "
                                  "the parts in the order they ran")
            if cut > self.series["step"][-1]:
                raise OutputError(f"{p.path} starts at step {cut:.0f}, after {prev} ends (step "
                                  f"{self.series['step'][-1]:.0f}): a part between them is missing")
            keep, start = self.series["step"] < cut, cut
            self.series = {k: np.concatenate([v[keep], p.series[k]]) for k, v in self.series.items()
                           if k in p.series}
            kf = [j for j in range(len(fstep)) if fstep[j] < cut]
            frame_at = [frame_at[j] for j in kf] + [(i, k) for k in range(len(p.frame_time))]
            ftime = [ftime[j] for j in kf] + list(p.frame_time)
            fstep = [fstep[j] for j in kf] + list(p.frame_step)
            self.frame_fields = [k for k in self.frame_fields if k in p.frame_fields]
        self._parts, self._frame_at = parts, frame_at
        self.frame_time, self.frame_step = np.asarray(ftime, dtype=float), np.asarray(fstep, dtype=float)
        self.frames = _Frames(self)

    def __repr__(self):
        return (f"Run({' + '.join(self.paths)}: {len(self.radius)} spheres, {len(self.series['time'])} rows, "
                f"{len(self.frames)} frames, walls {self.wall_names})")

    @property
    def radius(self):
        return self.particles.get("radius", np.zeros(0))

    @property
    def material(self):
        return self.particles.get("material", np.zeros(0, dtype=int))

    @property
    def has_contacts(self):
        return bool(self._frame_at) and all(self._parts[i].has_contacts for i, _ in self._frame_at)

    def wall_index(self, name):
        """The index of the wall called name (its column in the wall_* series); an int is taken as the index."""
        if isinstance(name, (int, np.integer)):
            if not -len(self.wall_names) <= name < len(self.wall_names):
                raise KeyError(f"no wall {name}: the run has {len(self.wall_names)}")
            return int(name) % len(self.wall_names)
        if name in self.wall_names:
            return self.wall_names.index(name)
        raise KeyError(f"no wall named '{name}' (walls: {', '.join(self.wall_names) or 'none'})")

    def wall(self, name):
        return Wall(self, self.wall_index(name))

    def _frame_ref(self, k):
        n = len(self._frame_at)
        if not -n <= k < n:
            raise IndexError(f"frame {k} is not in 0 .. {n - 1}" if n else "the run has no frames")
        part, j = self._frame_at[k % n]
        return self._parts[part], j

    def frame(self, k=-1):
        """Frame k (negative: from the end) as a dict: time, step, radius, material and its output fields
        (position [n, 3] m, velocity, angular_velocity, force, torque [n, 3], stress [n, 6] ... as the scene's
        output.fields lists them)."""
        p, j = self._frame_ref(k)
        out = dict(time=float(p.frame_time[j]), step=float(p.frame_step[j]), radius=self.radius,
                   material=self.material)
        with h5py.File(p.path, "r") as f:
            for name in self.frame_fields:
                out[name] = f["frames"][name][j]
        return out

    def frame_field(self, name):
        """One output field over every frame, an array [frames, n, ...] (position: [frames, n, 3] m): what frame(k)
        gives for each k, read at once."""
        if name not in self.frame_fields:
            raise KeyError(f"the frames have no field '{name}' (they have: {', '.join(self.frame_fields) or 'none'})")
        rows = {}
        for part, j in self._frame_at:
            rows.setdefault(part, []).append(j)
        out = []
        for part in sorted(rows):  # the frames are in part order
            with h5py.File(self._parts[part].path, "r") as f:
                d = f["frames"][name]
                out.append(d[()][rows[part]])
        return np.concatenate(out) if out else np.zeros((0, len(self.radius)))

    def contacts(self, k=-1):
        """The contact network of frame k: a dict of arrays over its contacts, the npairs particle pairs first
        (i < j), then the particle-wall contacts: i, j (j = -1 - wall for a wall contact), wall (the wall's index,
        -1 for a pair), overlap [m], normal_force and tangential_force [n, 3] (on particle i) [N], point [n, 3] m,
        extra [n, 2] (the law's own terms), and npairs, time, step."""
        if not any(q.has_contacts for q in self._parts):
            raise OutputError(f"{' + '.join(self.paths)} has no contact network (list `contacts` in the scene's "
                              "output.fields)")
        p, j = self._frame_ref(k)
        if not p.has_contacts:
            raise OutputError(f"{p.path} has no contact network (list `contacts` in the scene's output.fields)")
        with h5py.File(p.path, "r") as f:
            c = f["contacts"]
            starts = c["frame_start"][()]
            s0 = int(starts[j])
            s1 = int(starts[j + 1]) if j + 1 < len(starts) else c["ids"].shape[0]
            ids = c["ids"][s0:s1].reshape(-1, 2)
            data = c["data"][s0:s1].reshape(-1, 12)
            npairs = int(c["frame_pairs"][j])
        i, jj = ids[:, 0].astype(np.int64), ids[:, 1].astype(np.int64)
        return dict(i=i, j=jj, wall=np.where(jj < 0, -1 - jj, -1), npairs=npairs, overlap=data[:, 0],
                    normal_force=data[:, 1:4], tangential_force=data[:, 4:7], point=data[:, 7:10],
                    extra=data[:, 10:12], time=float(p.frame_time[j]), step=float(p.frame_step[j]))
