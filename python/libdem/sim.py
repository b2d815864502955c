"""Driving the C library (libdem.so, include/dem.h) through ctypes: set up from arrays, start, step, read and write
fields as numpy arrays, wall forces, energies, the contact network.

The library has no scene reader (scene files are the dem command's, app/); a simulation is set up from arrays here,
as a C program does: materials, particles, walls with their motion stages, gravity, domain, dt, effects.

Which libdem.so: $LIBDEM_PATH (a file), else libdem.so in this package's folder (make install links the installed
library there), else this source tree's build/pic/libdem.so (`make python-lib`), else the system's
(ctypes.util.find_library("dem")). A library loaded from the tree reads its kernel sources from the tree; an
installed one from PREFIX/share/libdem.

    import numpy as np
    from libdem.sim import Sim
    with Sim() as s:
        glass = s.add_material(density=2500, young=65e9, poisson=0.24, restitution=0.9, friction=0.2)
        s.add_particles([[0, 0, 0.003]], radius=0.002, material=glass)
        s.add_plane(point=[0, 0, 0], normal=[0, 0, 1], material=glass)
        s.set_gravity([0, 0, -9.81]); s.set_domain([-0.01] * 3, [0.01] * 3)
        s.set_dt(0.2 * s.time_scales()["rayleigh_time"]); s.set_effects(["hertz", "damping", "gravity", "walls"])
        s.start(backend="reference")
        s.step(1000)
        print(s.get("x"), s.wall_force(0))
"""
import ctypes
import ctypes.util
import os

import numpy as np

MAX_STAGES = 256  # DEM_MAX_STAGES
MAX_WALLS = 32  # DEM_MAX_WALLS
STATE_MAX_ARRAYS = 32  # DEM_STATE_MAX_ARRAYS
d3 = ctypes.c_double * 3


class Material(ctypes.Structure):
    _fields_ = [("density", ctypes.c_double), ("young", ctypes.c_double), ("poisson", ctypes.c_double),
                ("restitution", ctypes.c_double), ("friction", ctypes.c_double), ("mc_beta", ctypes.c_double),
                ("mc_gamma", ctypes.c_double), ("yield_stress", ctypes.c_double),
                ("rolling_friction", ctypes.c_double), ("bond_strength", ctypes.c_double),
                ("rolling_damping", ctypes.c_double), ("surface_energy", ctypes.c_double),
                ("bulk_fraction", ctypes.c_double), ("mdr_damping", ctypes.c_double)]


class MaterialPair(ctypes.Structure):
    _fields_ = [("friction", ctypes.c_double), ("restitution", ctypes.c_double),
                ("rolling_friction", ctypes.c_double), ("bond_strength", ctypes.c_double),
                ("surface_energy", ctypes.c_double)]


class Stage(ctypes.Structure):
    _fields_ = [("duration", ctypes.c_double), ("velocity", d3), ("force", ctypes.c_double),
                ("gain", ctypes.c_double), ("max_speed", ctypes.c_double), ("until_force", ctypes.c_double),
                ("until_distance", ctypes.c_double), ("until_density", ctypes.c_double), ("ramp", ctypes.c_double),
                ("after_wall", ctypes.c_int), ("after_stage", ctypes.c_int)]


class WallDesc(ctypes.Structure):
    _fields_ = [("kind", ctypes.c_int), ("material", ctypes.c_int), ("point", d3), ("normal", d3),
                ("radius", ctypes.c_double), ("nstages", ctypes.c_int), ("stages", Stage * MAX_STAGES),
                ("height", ctypes.c_double), ("cup_radius", ctypes.c_double), ("cup_depth", ctypes.c_double)]


class Config(ctypes.Structure):
    _fields_ = [("backend", ctypes.c_int), ("precision", ctypes.c_int), ("device", ctypes.c_int),
                ("local_size", ctypes.c_size_t), ("skin", ctypes.c_double), ("cell_size", ctypes.c_double),
                ("force_dt", ctypes.c_int), ("source_dir", ctypes.c_char_p), ("contacts", ctypes.c_int),
                ("sample_every", ctypes.c_long), ("reorder", ctypes.c_int), ("reorder_gain", ctypes.c_double),
                ("one_pass", ctypes.c_int)]


class TimeScales(ctypes.Structure):
    _fields_ = [(k, ctypes.c_double) for k in ("rayleigh_time", "recommended_dt", "max_dt", "hertz_time",
                                                "spring_period", "hinge_period", "hinge_damping_time")]


class Energy(ctypes.Structure):
    _fields_ = [("kinetic", ctypes.c_double), ("elastic", ctypes.c_double), ("potential", ctypes.c_double),
                ("total", ctypes.c_double), ("contacts", ctypes.c_long), ("wall_contacts", ctypes.c_long),
                ("patch_contacts", ctypes.c_long)]


class Stability(ctypes.Structure):
    _fields_ = [("ratio", ctypes.c_double), ("omega_dt", ctypes.c_double), ("zeta", ctypes.c_double),
                ("tangential", ctypes.c_int), ("particle", ctypes.c_int), ("contacts", ctypes.c_int),
                ("dt_advice", ctypes.c_double)]


class Contact(ctypes.Structure):
    _fields_ = [("i", ctypes.c_int), ("j", ctypes.c_int), ("overlap", ctypes.c_double), ("fn", d3), ("ft", d3),
                ("point", d3), ("extra", ctypes.c_double * 2)]


class StateArray(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("unit", ctypes.c_char_p), ("elem", ctypes.c_int), ("width", ctypes.c_int),
                ("required", ctypes.c_int), ("count", ctypes.c_size_t), ("data", ctypes.c_void_p)]


class McStats(ctypes.Structure):
    _fields_ = [(k, ctypes.c_long) for k in ("last", "max", "total", "unconverged", "first_capped", "last_capped")]


class State(ctypes.Structure):
    _fields_ = [("step", ctypes.c_long), ("rebuilds", ctypes.c_long), ("n", ctypes.c_int), ("nwalls", ctypes.c_int),
                ("real_size", ctypes.c_int), ("narrays", ctypes.c_int), ("arrays", StateArray * STATE_MAX_ARRAYS),
                ("wall_pos", d3 * MAX_WALLS), ("has_stages", ctypes.c_int), ("wall_stage", ctypes.c_int * MAX_WALLS),
                ("wall_stage_first", ctypes.c_long * MAX_WALLS), ("wall_stage_from", d3 * MAX_WALLS),
                ("npairs", ctypes.c_long), ("pair_i", ctypes.POINTER(ctypes.c_int)),
                ("pair_j", ctypes.POINTER(ctypes.c_int)), ("pair_hist", ctypes.c_void_p),
                ("pair_rec", ctypes.c_void_p), ("has_hist", ctypes.c_int), ("has_mc", ctypes.c_int),
                ("pair_mc_fn", ctypes.c_void_p), ("pair_mc_disp", ctypes.c_void_p), ("has_law", ctypes.c_int),
                ("pair_law", ctypes.c_void_p), ("has_rspring", ctypes.c_int), ("pair_rspring", ctypes.c_void_p),
                ("mc", McStats),
                ("npatch", ctypes.c_long), ("patch_i", ctypes.POINTER(ctypes.c_int)),
                ("patch_t", ctypes.POINTER(ctypes.c_int)), ("patch_hist", ctypes.c_void_p),
                ("patch_side", ctypes.POINTER(ctypes.c_int))]


P = ctypes.POINTER
_sim = ctypes.c_void_p  # dem_sim *
_i, _l, _d, _u, _sz = ctypes.c_int, ctypes.c_long, ctypes.c_double, ctypes.c_uint, ctypes.c_size_t
# name: (restype, argtypes), exactly as include/dem.h declares them (tests/test_python.py checks them against it)
SIGNATURES = {
    "dem_create": (_sim, []),
    "dem_destroy": (None, [_sim]),
    "dem_error": (ctypes.c_char_p, [_sim]),
    "dem_config_default": (None, [P(Config)]),
    "dem_add_material": (_i, [_sim, P(Material)]),
    "dem_set_material_pair": (_i, [_sim, ctypes.c_int, ctypes.c_int, P(MaterialPair)]),
    "dem_add_particle": (_i, [_sim, P(_d), P(_d), _d, _i]),
    "dem_set_particle_flags": (_i, [_sim, _i, _u]),
    "dem_add_wall": (_i, [_sim, P(WallDesc)]),
    "dem_add_box": (_i, [_sim, P(_d), P(_d), _i]),
    "dem_set_gravity": (_i, [_sim, P(_d)]),
    "dem_set_domain": (_i, [_sim, P(_d), P(_d)]),
    "dem_set_dt": (_i, [_sim, _d]),
    "dem_set_effects": (_i, [_sim, _u]),
    "dem_effects": (_u, [_sim]),
    "dem_effect_bit": (_i, [ctypes.c_char_p]),
    "dem_time_scales_get": (_i, [_sim, _d, P(TimeScales)]),
    "dem_start": (_i, [_sim, P(Config)]),
    "dem_step": (_i, [_sim, _l]),
    "dem_count": (_i, [_sim]),
    "dem_wall_count": (_i, [_sim]),
    "dem_step_index": (_l, [_sim]),
    "dem_time": (_d, [_sim]),
    "dem_dt": (_d, [_sim]),
    "dem_describe": (ctypes.c_char_p, [_sim]),
    "dem_field_bytes": (_sz, [_sim, _i]),
    "dem_get_field": (_i, [_sim, _i, P(_d)]),
    "dem_wall_force": (_i, [_sim, _i, P(_d)]),
    "dem_wall_normal_force": (_i, [_sim, _i, P(_d)]),
    "dem_wall_position": (_i, [_sim, _i, P(_d)]),
    "dem_energy": (_i, [_sim, P(Energy)]),
    "dem_stability_get": (_i, [_sim, P(Stability)]),
    "dem_contacts_get": (_i, [_sim, P(P(Contact)), P(_l), P(_l)]),
    "dem_state_get": (_i, [_sim, P(State)]),
    "dem_state_set": (_i, [_sim, P(State)]),
    "dem_state_free": (None, [P(State)]),
    "dem_device_count": (_i, []),
}

# fields (dem_field) by name, with their values per particle (or per wall)
FIELDS = {"x": (0, 3), "v": (1, 3), "w": (2, 3), "force": (3, 3), "torque": (4, 3), "wall_force": (10, 3),
          "stress": (17, 6), "stress_trace": (18, 1), "wall_normal_force": (27, 1),
          "radius": (29, 1)}
# the fields set() writes: the state's arrays of the same names (dem_state_get / dem_state_set)
WRITABLE = ("x", "v", "w")
BACKENDS = {"reference": 0, "opencl": 1}
PRECISIONS = {"fp32": 4, "fp64": 8, 32: 4, 64: 8}
ERRORS = {-1: "DEM_ERR_ARG", -2: "DEM_ERR_NOMEM", -3: "DEM_ERR_DEVICE", -4: "DEM_ERR_DOMAIN", -5: "DEM_ERR_DT",
          -6: "DEM_ERR_STATE"}


class DemError(RuntimeError):
    """A libdem call that failed: code (a negative DEM_ERR_*) and the library's reason (dem_error)."""

    def __init__(self, code, message):
        super().__init__(f"{message} ({ERRORS.get(code, code)})")
        self.code = code


def library_path():
    """The libdem.so this module loads (the search order of the module's docstring), or None."""
    env = os.environ.get("LIBDEM_PATH")
    if env:
        return env
    here = os.path.dirname(os.path.abspath(__file__))
    for p in (os.path.join(here, "libdem.so"), os.path.join(here, "..", "..", "build", "pic", "libdem.so")):
        if os.path.exists(p):
            return os.path.normpath(p)
    return ctypes.util.find_library("dem")


_lib = None
_free = ctypes.CDLL(None).free  # what dem_contacts_get's array is freed with
_free.restype, _free.argtypes = None, [ctypes.c_void_p]


def load(path=None):
    """Loads libdem.so (path, or library_path()) and declares the functions this module calls."""
    global _lib
    if _lib is not None and path is None:
        return _lib
    path = path or library_path()
    if not path:
        raise OSError("libdem.so not found: set LIBDEM_PATH, run `make python-lib` in the source tree (build/pic/"
                      "libdem.so) or `make install`")
    lib = ctypes.CDLL(path)
    for name, (res, args) in SIGNATURES.items():
        fn = getattr(lib, name)
        fn.restype, fn.argtypes = res, args
    _lib = lib
    return lib


def _vec(v, n=3):
    a = np.ascontiguousarray(np.asarray(v, dtype=np.float64).reshape(-1))
    if a.size != n:
        raise ValueError(f"expected {n} numbers, got {a.size}")
    return a


def _ptr(a):
    return a.ctypes.data_as(P(_d))


def _stage(st):
    """a dict {duration, velocity, force, gain, max_speed, until_force, until_distance, until_density} -> Stage"""
    s = Stage()
    for k, v in st.items():
        if k == "velocity":
            s.velocity = d3(*_vec(v))
        elif k in dict(Stage._fields_):
            setattr(s, k, float(v))
        else:
            raise ValueError(f"a stage has no '{k}' (keys: {', '.join(n for n, _ in Stage._fields_)})")
    return s


class Sim:
    """One simulation (a dem_sim). Set it up, start() it, step() it; close() (or a with block) frees it."""

    _s = None

    def __init__(self, library=None):
        self._lib = load(library)
        self._s = self._lib.dem_create()
        if not self._s:
            raise MemoryError("dem_create failed")
        self.started = False

    @classmethod
    def from_scene(cls, path, library=None):
        """A simulation built from a `dem run` scene file, with every check `dem check` makes, not yet started.
        Its scene_config holds the scene's backend, precision and device (start(**sim.scene_config)) and scene_steps
        the steps of its duration. Needs the library of the source tree (make python-lib), which holds the scene
        reader; the installed library keeps no YAML reader. A bad scene raises DemError with "file:line: field:
        reason"."""
        self = cls.__new__(cls)
        self._lib = load(library)
        self.started, self._s = False, None
        fn = getattr(self._lib, "dem_scene_open", None)
        if fn is None:
            raise OSError("this libdem.so has no scene reader (dem_scene_open): use the source tree's, make python-lib")
        fn.restype = _sim
        fn.argtypes = [ctypes.c_char_p, P(Config), P(_l), ctypes.c_char_p, _sz]
        c, steps, err = Config(), _l(0), ctypes.create_string_buffer(4096)
        self._s = fn(os.fsencode(path), ctypes.byref(c), ctypes.byref(steps), err, len(err))
        if not self._s:
            raise DemError(-1, err.value.decode(errors="replace"))
        back = {v: k for k, v in BACKENDS.items()}
        self.scene_config = {"backend": back.get(c.backend, "opencl"), "precision": "fp64" if c.precision == 8
                             else "fp32", "device": c.device}
        self.scene_steps = steps.value
        return self

    def close(self):
        if self._s:
            self._lib.dem_destroy(self._s)
            self._s = None

    __del__ = close

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _check(self, rc):
        if rc < 0:
            raise DemError(rc, (self._lib.dem_error(self._s) or b"").decode(errors="replace"))
        return rc

    # ---- set-up ----
    def add_material(self, density, young, poisson, restitution, friction, mc_beta=0.0, mc_gamma=0.0,
                     yield_stress=0.0, rolling_friction=0.0, bond_strength=0.0, rolling_damping=0.0,
                     surface_energy=0.0, bulk_fraction=0.0, mdr_damping=0.0):
        """A material [kg/m^3, Pa, -, -, -]; returns its id. young=float('inf'): rigid (walls only). yield_stress
        [Pa]: the limiting contact pressure of the thornton_ning law (0: does not yield); rolling_friction: mu_r of
        the rolling effect; bond_strength [Pa]: sigma_b of the bonds its yielded contacts form (thornton_ning, mdr);
        rolling_damping: eta_r of the rolling_spring effect's dashpot; surface_energy [J/m^2], bulk_fraction
        (psi_b) and mdr_damping (eta_d): the mdr law's (yield_stress is then its Y)."""
        m = Material(density, young, poisson, restitution, friction, mc_beta, mc_gamma, yield_stress, rolling_friction,
                     bond_strength, rolling_damping, surface_energy, bulk_fraction, mdr_damping)
        return self._check(self._lib.dem_add_material(self._s, ctypes.byref(m)))

    def set_material_pair(self, a, b, friction=float("nan"), restitution=float("nan"), rolling_friction=float("nan"),
                          bond_strength=float("nan"), surface_energy=float("nan")):
        """Materials a and b take this friction, restitution, rolling friction, bond strength or work of adhesion
        (surface_energy [J/m^2], the adhesion effect) instead of the rule's (NaN: the mean; for the bond strength the
        smaller of the two; for the work of adhesion the geometric mean)."""
        p = MaterialPair(friction, restitution, rolling_friction, bond_strength, surface_energy)
        return self._check(self._lib.dem_set_material_pair(self._s, a, b, ctypes.byref(p)))

    def add_particles(self, x, radius, material, v=None):
        """Spheres at x [n, 3] m with radius (one or n) [m] of material (one id or n), velocities v [n, 3] m/s
        (None: at rest); returns their ids."""
        x = np.ascontiguousarray(np.asarray(x, dtype=np.float64).reshape(-1, 3))
        n = len(x)
        r = np.broadcast_to(np.asarray(radius, dtype=np.float64), (n,))
        mat = np.broadcast_to(np.asarray(material, dtype=np.int64), (n,))
        vel = None if v is None else np.ascontiguousarray(np.asarray(v, dtype=np.float64).reshape(n, 3))
        ids = np.empty(n, dtype=np.int64)
        for k in range(n):
            xv = np.ascontiguousarray(x[k])
            vv = None if vel is None else np.ascontiguousarray(vel[k])
            ids[k] = self._check(self._lib.dem_add_particle(self._s, _ptr(xv), None if vv is None else _ptr(vv),
                                                            float(r[k]), int(mat[k])))
        return ids

    def set_particle_flags(self, i, flags):
        """DEM_PARTICLE_* flags: 1 no rotation, 2 fixed, 4/8/16 hold vx/vy/vz."""
        self._check(self._lib.dem_set_particle_flags(self._s, int(i), int(flags)))

    def _wall(self, kind, material, point, normal, radius=0.0, height=0.0, stages=(), cup_radius=0.0, cup_depth=0.0):
        if len(stages) > MAX_STAGES:
            raise ValueError(f"at most {MAX_STAGES} stages")
        w = WallDesc()
        w.kind, w.material, w.point, w.normal = kind, int(material), d3(*_vec(point)), d3(*_vec(normal))
        w.radius, w.height, w.cup_radius, w.cup_depth = radius, height, cup_radius, cup_depth
        w.nstages = len(stages)
        for k, st in enumerate(stages):
            w.stages[k] = _stage(st)
        return self._check(self._lib.dem_add_wall(self._s, ctypes.byref(w)))

    def add_plane(self, point, normal, material, stages=(), cup_radius=0.0, cup_depth=0.0):
        """A plane wall through point, its normal towards the particles; stages: its motion, a list of dicts
        (duration, velocity, force, gain, max_speed, until_force, until_distance, until_density; dem_stage).
        Returns its id."""
        return self._wall(0, material, point, normal, stages=stages, cup_radius=cup_radius, cup_depth=cup_depth)

    def add_cylinder(self, point, axis, radius, material, height=0.0, stages=()):
        """A cylinder wall (particles inside) of inner radius [m] about axis through point; height 0: endless."""
        return self._wall(1, material, point, axis, radius=radius, height=height, stages=stages)

    def add_box(self, lo, hi, material):
        """Six planes enclosing [lo, hi] (x-, x+, y-, y+, z-, z+); returns the first one's id."""
        lo, hi = _vec(lo), _vec(hi)
        return self._check(self._lib.dem_add_box(self._s, _ptr(lo), _ptr(hi), int(material)))

    def set_gravity(self, g):
        g = _vec(g)
        self._check(self._lib.dem_set_gravity(self._s, _ptr(g)))

    def set_domain(self, lo, hi):
        lo, hi = _vec(lo), _vec(hi)
        self._check(self._lib.dem_set_domain(self._s, _ptr(lo), _ptr(hi)))

    def set_dt(self, dt):
        self._check(self._lib.dem_set_dt(self._s, float(dt)))

    def set_effects(self, effects):
        """The physics: a list of names ("hertz", "damping", "friction", "gravity", "walls", ...) or a mask."""
        if not isinstance(effects, (int, np.integer)):
            mask = 0
            for name in effects:
                bit = self._lib.dem_effect_bit(name.encode())
                if bit < 0:
                    raise ValueError(f"no effect '{name}'")
                mask |= 1 << bit
            effects = mask
        self._check(self._lib.dem_set_effects(self._s, int(effects)))

    @property
    def effects(self):
        return self._lib.dem_effects(self._s)

    def time_scales(self, hertz_velocity=1.0):
        """dem_time_scales of the current particles and materials, a dict [s]."""
        ts = TimeScales()
        self._check(self._lib.dem_time_scales_get(self._s, float(hertz_velocity), ctypes.byref(ts)))
        return {k: getattr(ts, k) for k, _ in TimeScales._fields_}

    def start(self, backend="reference", precision="fp64", device=None, source_dir=None, contacts=False,
              force_dt=False):
        """Validates the set-up, builds the backend ("reference" or "opencl"), computes the initial forces.
        contacts=True lets contacts() read the contact network of a run with walls."""
        c = Config()
        self._lib.dem_config_default(ctypes.byref(c))
        c.backend, c.precision = BACKENDS[backend], PRECISIONS[precision]
        if device is not None:
            c.device = int(device)
        if source_dir is not None:
            self._source_dir = os.fsencode(source_dir)  # kept alive while the library may read it
            c.source_dir = self._source_dir
        c.contacts, c.force_dt = int(bool(contacts)), int(bool(force_dt))
        self._check(self._lib.dem_start(self._s, ctypes.byref(c)))
        self.started, self._real = True, c.precision

    def step(self, nsteps=1):
        self._check(self._lib.dem_step(self._s, int(nsteps)))

    # ---- reading ----
    @property
    def count(self):
        return self._check(self._lib.dem_count(self._s))

    @property
    def wall_count(self):
        return self._check(self._lib.dem_wall_count(self._s))

    @property
    def time(self):
        return self._lib.dem_time(self._s)

    @property
    def step_index(self):
        return self._lib.dem_step_index(self._s)

    @property
    def dt(self):
        return self._lib.dem_dt(self._s)

    def describe(self):
        return (self._lib.dem_describe(self._s) or b"").decode(errors="replace")

    def get(self, field):
        """A field as a float64 array: x, v, w, force, torque [n, 3], stress [n, 6], stress_trace [n], radius [n] (as
        the contacts see it: MDR's apparent radius under mdr), wall_force [walls, 3], wall_normal_force [walls] (SI
        units, dem.h's DEM_FIELD_*)."""
        fid, width = FIELDS[field]
        if not self.started:
            raise DemError(-6, "get() needs a started simulation (start())")
        out = np.empty(self._lib.dem_field_bytes(self._s, fid) // self._real, dtype=np.float64)
        if out.size:
            self._check(self._lib.dem_get_field(self._s, fid, _ptr(out)))
        return out.reshape(-1, width) if width > 1 else out

    def set(self, field, values):
        """Writes positions x, velocities v or angular velocities w [n, 3] (after start(): through dem_state_get /
        dem_state_set, which keeps everything else - contacts and their history, step, walls - and rebuilds the
        neighbour rows). Values are rounded to the run's precision."""
        if field not in WRITABLE:
            raise ValueError(f"set() writes {', '.join(WRITABLE)}, not '{field}'")
        if not self.started:
            raise DemError(-6, "set() needs a started simulation; before start() give the values to add_particles")
        vals = np.asarray(values, dtype=np.float64).reshape(-1, 3)
        st = State()
        self._check(self._lib.dem_state_get(self._s, ctypes.byref(st)))
        try:
            arr = next((st.arrays[k] for k in range(st.narrays) if st.arrays[k].name == field.encode()), None)
            if arr is None or not arr.data:
                raise DemError(-1, f"the state has no array '{field}'")
            if arr.count != vals.size:
                raise ValueError(f"{field}: {len(vals)} rows given, the run has {arr.count // 3}")
            ctype = ctypes.c_double if st.real_size == 8 else ctypes.c_float
            buf = np.ctypeslib.as_array(ctypes.cast(arr.data, P(ctype)), shape=(arr.count,))
            buf[:] = vals.reshape(-1)
            self._check(self._lib.dem_state_set(self._s, ctypes.byref(st)))
        finally:
            self._lib.dem_state_free(ctypes.byref(st))

    def wall_force(self, wall):
        """The force wall received in the last step [N] (3)."""
        f = np.zeros(3)
        self._check(self._lib.dem_wall_force(self._s, int(wall), _ptr(f)))
        return f

    def wall_normal_force(self, wall):
        """The wall's normal force in the last step [N]: a die's radial force, a plane's normal force."""
        f = ctypes.c_double()
        self._check(self._lib.dem_wall_normal_force(self._s, int(wall), ctypes.byref(f)))
        return f.value

    def wall_position(self, wall):
        p = np.zeros(3)
        self._check(self._lib.dem_wall_position(self._s, int(wall), _ptr(p)))
        return p

    def energy(self):
        """Energies [J] and contact counts (dem_energy), a dict."""
        e = Energy()
        self._check(self._lib.dem_energy(self._s, ctypes.byref(e)))
        return {k: getattr(e, k) for k, _ in Energy._fields_}

    def stability(self):
        """How close dt is to the explicit step's stability bound at the current overlaps (dem_stability_get), a dict:
        ratio, omega_dt, zeta, tangential, particle, contacts, dt_advice [s]."""
        st = Stability()
        self._check(self._lib.dem_stability_get(self._s, ctypes.byref(st)))
        return {k: getattr(st, k) for k, _ in Stability._fields_}

    def contacts(self):
        """The contact network now, with the keys of libdem.Run.contacts: i, j (j = -1 - wall for a wall
        contact), wall, npairs, overlap, normal_force, tangential_force, point, extra. A run with walls needs
        start(contacts=True)."""
        p, count, npairs = P(Contact)(), ctypes.c_long(), ctypes.c_long()
        self._check(self._lib.dem_contacts_get(self._s, ctypes.byref(p), ctypes.byref(count), ctypes.byref(npairs)))
        try:
            n = count.value
            a = (np.ctypeslib.as_array(ctypes.cast(p, P(ctypes.c_uint8)), shape=(n * ctypes.sizeof(Contact),))
                 .view(np.dtype({"names": [k for k, _ in Contact._fields_],
                                 "formats": ["i4", "i4", "f8", ("f8", 3), ("f8", 3), ("f8", 3), ("f8", 2)],
                                 "offsets": [getattr(Contact, k).offset for k, _ in Contact._fields_],
                                 "itemsize": ctypes.sizeof(Contact)})).copy()) if n else None
        finally:
            _free(ctypes.cast(p, ctypes.c_void_p))
        if a is None:
            z3 = np.zeros((0, 3))
            return dict(i=np.zeros(0, np.int64), j=np.zeros(0, np.int64), wall=np.zeros(0, np.int64), npairs=0,
                        overlap=np.zeros(0), normal_force=z3, tangential_force=z3, point=z3, extra=np.zeros((0, 2)))
        i, j = a["i"].astype(np.int64), a["j"].astype(np.int64)
        return dict(i=i, j=j, wall=np.where(j < 0, -1 - j, -1), npairs=npairs.value, overlap=a["overlap"],
                    normal_force=a["fn"], tangential_force=a["ft"], point=a["point"], extra=a["extra"])


def device_count():
    """The OpenCL devices over all platforms (dem_device_count)."""
    return load().dem_device_count()
