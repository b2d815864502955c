"""python3 -m libdem: command lines over the package.

  python3 -m libdem report RUN.h5 [MORE.h5 ...] [-o PNG] [--die NAME] [--upper NAME] [--lower NAME]
      the tablet report of a press cycle (libdem.tablet): a PNG and one line of key=value numbers
  python3 -m libdem fd RUN.h5 [MORE.h5 ...] --wall NAME [-o CSV]
      a plane wall's (a piston's, a punch's) force against its displacement from first contact, as CSV
      (default: on standard output)
  python3 -m libdem coordination RUN.h5 [MORE.h5 ...] [--frame K] [--no-rattlers] [--walls]
      the coordination number of one frame's contact network (default: the last frame)
Several files are the parts of a run continued with `dem run --restart`, in the order they ran.
"""
import argparse
import sys

from . import analysis, tablet
from .output import OutputError, Run


def _report(a):
    print(tablet.report(a.run, a.output, a.die, a.upper, a.lower))


def _fd(a):
    run = Run(a.run)
    d, f = analysis.force_displacement(run, a.wall)
    s = run.series
    out = open(a.output, "w") if a.output else sys.stdout
    try:
        out.write("time [s],step,displacement [m],force [N]\n")
        for t, st, x, y in zip(s["time"], s["step"], d, f):
            out.write(f"{t:.9g},{st:.0f},{x:.9g},{y:.9g}\n")
    finally:
        if a.output:
            out.close()
    if a.output:
        k = int((d < 0).sum())
        print(f"fd: wrote {a.output} ({len(d)} rows; first contact at row {k}, t = {s['time'][k]:.6g} s; largest "
              f"force {f.max():.6g} N at displacement {d[int(f.argmax())]:.6g} m)")


def _coordination(a):
    run = Run(a.run)
    c = run.contacts(a.frame)
    counts, kept = analysis.contact_counts(c["i"], c["j"], len(run.radius), walls=a.walls, rattlers=not a.no_rattlers)
    z = float(counts[kept].sum() / kept.sum()) if kept.any() else float("nan")
    k = a.frame % len(run.frames)
    what = ("walls included" if a.walls else "sphere pairs only") + (
        f", {int((~kept).sum())} rattlers left out" if a.no_rattlers else ", rattlers included")
    print(f"coordination: frame {k} (t = {c['time']:.6g} s): Z = {z:.6g} over {int(kept.sum())} spheres ({what}; "
          f"{c['npairs']} pairs, {len(c['i']) - c['npairs']} wall contacts in the frame)")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m libdem", description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    runs = dict(nargs="+", help="HDF5 file written by dem run (several: a run and its --restart continuations, "
                                "in order)")
    p = sub.add_parser("report", help="the tablet report of a press cycle (PNG and numbers)")
    p.add_argument("run", **runs)
    p.add_argument("-o", "--output", help="PNG file (default: RUN_tablet.png)")
    p.add_argument("--die", help="the die's wall name (default: the first cylinder)")
    p.add_argument("--upper", default="upper", help="the upper punch's wall name")
    p.add_argument("--lower", default="lower", help="the lower punch's wall name")
    p.set_defaults(fn=_report)
    p = sub.add_parser("fd", help="a wall's force against displacement from first contact, CSV")
    p.add_argument("run", **runs)
    p.add_argument("--wall", required=True, help="the wall's name (a plane: a piston, a punch)")
    p.add_argument("-o", "--output", help="CSV file (default: standard output)")
    p.set_defaults(fn=_fd)
    p = sub.add_parser("coordination", help="coordination number of a frame's contact network")
    p.add_argument("run", **runs)
    p.add_argument("--frame", type=int, default=-1, help="frame index (negative: from the end; default: the last)")
    p.add_argument("--no-rattlers", action="store_true", help="leave out spheres with fewer than 2 contacts "
                   "(repeatedly)")
    p.add_argument("--walls", action="store_true", help="count contacts with walls too")
    p.set_defaults(fn=_coordination)
    a = ap.parse_args(argv)
    try:
        a.fn(a)
    except (OutputError, ValueError, KeyError, IndexError) as e:
        msg = e.args[0] if isinstance(e, KeyError) and e.args else e
        sys.exit(f"libdem {a.cmd}: {msg}")


if __name__ == "__main__":
    main()
