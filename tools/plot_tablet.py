#!/usr/bin/python3
"""The tablet report of a press cycle run by dem run: one PNG and a few numbers.

usage: tools/plot_tablet.py RUN.h5 [MORE.h5 ...] [-o RUN_tablet.png] [--die NAME] [--upper NAME] [--lower NAME]

A command line over the Python package (python/libdem/tablet.py, `python3 -m libdem report`), which says what each
number is: punch pressures over the bore, relative density between the punches, the Heckel line, the transmission
ratio over the loading, the radial die-wall pressure, the elastic recovery, and the ejection's die-wall friction
with the lower punch's force apart. A run continued with `dem run --restart` is given as its files in order.
Prints one line of `key=value` pairs (pressures in MPa). Uses Debian's python3-h5py, python3-numpy and
python3-matplotlib.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from libdem import tablet  # noqa: E402
from libdem.output import OutputError  # noqa: E402


def fail(msg):
    sys.exit(f"plot_tablet: {msg}")


def analyse(run, die_name=None, upper="upper", lower="lower"):
    """libdem.tablet.analyse (SI values, pressures in Pa), ending the program with its reason on an error (the
    tools that import it, tools/plot_tablet_models.py and plot_tablet_mass_scale.py, rely on that)."""
    try:
        return tablet.analyse(run, die_name, upper, lower)
    except (OutputError, tablet.TabletError) as e:
        fail(e)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", nargs="+", help="HDF5 file written by dem run (several: a run and its --restart "
                    "continuations, in order)")
    ap.add_argument("-o", "--output", help="PNG file (default: RUN_tablet.png)")
    ap.add_argument("--die", help="the die's wall name (default: the first cylinder)")
    ap.add_argument("--upper", default="upper", help="the upper punch's wall name")
    ap.add_argument("--lower", default="lower", help="the lower punch's wall name")
    a = ap.parse_args()
    try:
        print(tablet.report(a.run, a.output, a.die, a.upper, a.lower))
    except (OutputError, tablet.TabletError) as e:
        fail(e)


if __name__ == "__main__":
    main()
