"""libdem: read and analyse what `dem run` writes, and drive the C library from Python.

    import libdem
    run = libdem.Run("out/press.h5")                     # or Run(["a.h5", "b.h5"]): a run continued by --restart
    d, f = libdem.analysis.force_displacement(run, "piston")
    z = libdem.analysis.coordination_number(run, rattlers=False)

Modules: output (Run: series, walls by name, frames, contact network), analysis (force against displacement from
first contact, coordination number, packing fraction), tablet (the press cycle's report), sim (the C library through
ctypes; imported on first use, since it loads libdem.so). python/README.md has the details.
"""
from . import analysis, output, tablet  # noqa: F401
from .output import OutputError, Run, Wall  # noqa: F401

__version__ = "0.1.0"  # libdem's DEM_VERSION (include/dem.h)
__all__ = ["Run", "Wall", "OutputError", "analysis", "output", "tablet", "sim"]


def __getattr__(name):
    if name == "sim":  # loads libdem.so: only when asked for
        import importlib

        return importlib.import_module(".sim", __name__)
    raise AttributeError(f"module 'libdem' has no attribute '{name}'")
