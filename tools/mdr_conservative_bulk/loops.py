#!/usr/bin/python3
"""A bulk response that keeps energy? Two variants of MDR's Part II, neither of them libdem's law, walked round the
closed loops of tools/peer_mdr/energy_loop.py in the Python reference (docs/laws/mdr.md "A conservative bulk
response, tried"):

own        (M10) gives each side its own approach: while psi < psi_b the whole increment goes to the side's bulk
           spring (delta_MDR stays, or follows delta down once delta falls below it), instead of the particle's
           mean surface displacement (M33); (M35)'s bulk force as published, with this step's A_con and V_geo.
potential  the own split, and a bulk force that is the gradient of one energy per particle, kappa dV^2 / (2 V_geo)
           with dV = sum over its sides of A_c delta_BULK, all at this step's positions: on side k
           p (A_c + delta_BULK dA_c/ddelta) + p^2 / (2 kappa) pi delta (2 R - delta), p = kappa dV / V_geo (the last
           term: V_geo's own change with the caps, left out where V_geo is held at V_o).

The published law (lagged, as libdem and LAMMPS have it, and with this step's A_con and V_geo) is printed beside
them. Work put into the sphere per loop [J]; a conservative law gives 0 on the later loops, whose states repeat, and
0 in the translation loops' limit (2 W(h/2) - W(h)) in both senses. About 5 s.
usage: loops.py
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "peer_mdr"))
import cases as C  # noqa: E402
import mdr_reference as M  # noqa: E402
import energy_loop as E  # noqa: E402


def mdr_force_own(mat, s, p, delta):
    """The published side with the own split (its whole increment as the 'mean' of (M10)), without its bulk force."""
    keep = p.ddelta_bar
    p.ddelta_bar = delta - s.delta
    f, _ = M.side_force(mat, s, p, delta)
    p.ddelta_bar = keep
    return f - (p.Acon0 * s.delta_bulk * mat.kappa * s.Ac / p.Vgeo if s.delta_bulk > 0.0 else 0.0)


def variant_forces(path, potential):
    mat = M.Material(C.E, C.NU, C.Y, 0.0, C.PSI_B, 0.0)
    p = M.Particle(C.R, 1.0)
    sides = [M.Side() for _ in range(6)]
    vo = 4.0 / 3.0 * math.pi * C.R ** 3
    forces = [(0.0,) * 6]
    for u in path[1:]:
        p.begin_step(mat)
        d = [p.R - (C.R - u[k]) for k in range(6)]
        f = [mdr_force_own(mat, sides[k], p, d[k]) for k in range(6)]
        vraw = 4.0 / 3.0 * math.pi * p.R ** 3 - p.Vcaps
        vg = min(vraw, vo)
        dv = sum(s.Ac * s.delta_bulk for s in sides if s.delta_bulk > 0.0)
        pr = mat.kappa * dv / vg
        for k, s in enumerate(sides):
            if not potential:
                f[k] += mat.kappa * s.delta_bulk * s.Ac * p.Acon1 / vg if s.delta_bulk > 0.0 else 0.0
                continue
            if s.delta_bulk > 0.0:
                da = math.pi * (2.0 * p.R - 2.0 * d[k]) if s.yielded else math.pi * p.R
                f[k] += pr * (s.Ac + s.delta_bulk * da)
            if vraw < vo and d[k] > 0.0:
                f[k] += pr * pr / (2.0 * mat.kappa) * math.pi * d[k] * (2.0 * p.R - d[k])
        forces.append(tuple(f[k] * (1.0 + math.exp(10.7 * sides[k].deltao / p.Ro - 10.0)) for k in range(6)))
    return forces


LAWS = (("published (lagged A_con, V_geo)", lambda path: E.reference_forces(path)),
        ("published, this step's A_con, V_geo", lambda path: E.reference_forces(path, current=True)),
        ("own split", lambda path: variant_forces(path, False)),
        ("own split + potential bulk", lambda path: variant_forces(path, True)))


def main():
    print("# squeeze loops (tools/peer_mdr/energy_loop.py): law, m per step, work of loops 1, 2, 3 [J]")
    for step in E.STEPS:
        pieces, n0, per = E.squeeze_pieces(step)
        path = E.walk(pieces)
        for who, forces in LAWS:
            w = E.loop_work(path, n0, per, forces(path))
            print(f"{who},{step:.3g},{w[0]:.4e},{w[1]:.4e},{w[2]:.4e}")
    print("# translation loops: law, sense, loop 3's work at 1e-7, 5e-8, 2.5e-8 m per step, and the limit [J]")
    for who, forces in LAWS:
        for sense in ("forward", "reverse"):
            ws = []
            for step in E.TSTEPS:
                pieces, n0, per = E.translate_pieces(step, sense == "reverse")
                path = E.walk(pieces)
                ws.append(E.loop_work(path, n0, per, forces(path))[2])
            print(f"{who},{sense},{ws[0]:.4e},{ws[1]:.4e},{ws[2]:.4e},{2.0 * ws[2] - ws[1]:.4e}")


if __name__ == "__main__":
    main()
