/* mdr.h - MDR, the mechanically-derived contact law of Zunker and Kamrin for adhesive elastic-perfectly plastic
 * spheres (docs/laws/mdr.md; its one-contact core: mdr_core.h), as a law unit of a run (law.h; listed in laws.h with
 * DEM_EFFECT_MDR).
 *
 * A contact presses each of its spheres on a rigid flat: a pair has two sides, the flat placed between them by (M3)
 * (side 0 the sphere of higher stable id, side 1 the other: contact_pairs evaluates a pair for the lower id, a, so
 * side 0 is b), a sphere on a wall one side. The normal force is (M4): a pair the mean of its two sides' forces, a wall
 * its side's times the magnifier (M39); then MDR's damping (M38) with DEM_EFFECT_DAMPING. The sides read their
 * spheres' apparent radius and Part II's per-particle quantities of this step (MDR_PART: mdr_begin and mdr_surface
 * made them before the contacts) and leave each sphere's share of the sums its next step starts from (M28, M29,
 * M32) in law_in.sums (6 per side, side 0's first), which contact_forces adds per particle in the canonical order.
 *
 * State: a contact's row (dem_layout.h MDR_*: the largest overlap, the penalty, the sides of (M37)) read from
 * law_in.row_in (0 for a contact that did not touch in the last step: a new one starts from zero) and written to
 * law_in.row_out (0: not written; the walls' force sum evaluates the same contacts before contact_forces commits
 * them, wall_forces.h).
 *
 * Tangential (with DEM_EFFECT_FRICTION): Mindlin's spring on the MDR contact radius, k_t = 8 G* a with a the mean of
 * the sides' radii in effect (those the damping sees), the stored force rotated into the tangent plane as
 * Hertz-Mindlin's, and Coulomb's limit mu |F_n| on the whole normal force (adhesive and damping parts included); no
 * tangential dashpot (LAMMPS's `tangential mindlin NULL 0 mu`). A decision recorded in docs/laws/mdr.md. With a whole
 * bond (mdr_core.h mdr_side_bond: the material's bond_strength) the limit is mu max(F_n + F_b, |F_n|), and a contact
 * that slides loses its bond.
 *
 * Bonds break as a whole: when one side's tension passes its F_b this step, the other side's bond breaks too (the
 * bridge is one element between the two spheres; the pair's force of this step still has the other side's tension,
 * as a bond that slides keeps this step's force). The energy is the state's after the step, so the tension a break
 * lets go is not in it (the break dissipates it).
 *
 * The penalty of a pair whose contact runs through a third sphere (M40) weights the pair's force and its sides' sums
 * (w = max(1 - p, 0)); mdr_surface computes p each step into the pair's row (mdr_particle.h).
 *
 * Energy (law_in.energy): each side's elastic energy (mdr_core.h mdr_side_energy: what it gives back unloaded from its
 * state, the springs adhesion holds in tension included), a pair's the weighted sum of its two sides', a wall's times
 * its magnifier; the series rows and the host's energies (host/physics/energy.c) take it from there.
 * Stress output: each contact's elastic normal force of the last step, kept in its row (particle_stress.h reads it).
 * law_elastic returns that kept force (its state argument); law_energy has no row to read and gives 0 (no caller uses
 * it with MDR: the energies take each row, above); law_stiffness gives the slope of a flattened contact unloading
 * (2 E* a per side with a^2 = 2 delta R), and mdr_row_slope the law's own from a contact's row, which the host's
 * time-step estimate takes where it is the larger (the closed form falls below it past about half a radius).
 */
#ifndef DEM_MDR_H
#define DEM_MDR_H
#include "law.h"
#include "mdr_core.h"
#include "hertz_mindlin.h"

#define LAW_COLUMNS_mdr(C) C(PM_MDR) C(PM_GSTAR) C(PM_MU) C(PM_TN_SIGB)

DEM_INLINE mdr_side mdr_side_load(DEM_CONST_GLOBAL real *v)
{
    mdr_side s;
    s.delta = v[0], s.deltao = v[1], s.delta_mdr = v[2], s.delta_bulk = v[3], s.ac = v[4], s.deltamax = v[5];
    s.yielded = v[6], s.ca = v[7], s.a_adh = v[8], s.eps_c = v[9], s.deltap = v[10];
    return s;
}
DEM_INLINE void mdr_side_store(DEM_GLOBAL real *v, const mdr_side *s)
{
    v[0] = s->delta, v[1] = s->deltao, v[2] = s->delta_mdr, v[3] = s->delta_bulk, v[4] = s->ac, v[5] = s->deltamax;
    v[6] = s->yielded, v[7] = s->ca, v[8] = s->a_adh, v[9] = s->eps_c, v[10] = s->deltap;
}
/* A particle's row (MDR_PART), mdr_particle's order */
DEM_INLINE mdr_particle mdr_particle_load(DEM_CONST_GLOBAL real *v)
{
    mdr_particle p;
    p.ro = v[0], p.r = v[1], p.dr_avg = v[2], p.acon0 = v[3];
    p.vcaps = v[4], p.eps_sum = v[5], p.dr_num = v[6], p.dr_den = v[7], p.acon1 = v[8], p.atot_sum = v[9];
    p.psi = v[10], p.velas = v[11], p.vgeo = v[12], p.ddelta_bar = v[13];
    return p;
}
DEM_INLINE void mdr_particle_store(DEM_GLOBAL real *v, const mdr_particle *p)
{
    v[0] = p->ro, v[1] = p->r, v[2] = p->dr_avg, v[3] = p->acon0;
    v[4] = p->vcaps, v[5] = p->eps_sum, v[6] = p->dr_num, v[7] = p->dr_den, v[8] = p->acon1, v[9] = p->atot_sum;
    v[10] = p->psi, v[11] = p->velas, v[12] = p->vgeo, v[13] = p->ddelta_bar;
}
/* The sums one side leaves for its particle (the particle's sums were cleared before the side) */
DEM_INLINE void mdr_sums_out(real *out, const mdr_particle *p)
{
    out[0] = p->vcaps, out[1] = p->eps_sum, out[2] = p->dr_num, out[3] = p->dr_den, out[4] = p->acon1;
    out[5] = p->atot_sum;
}
/* The sphere of particle i as a side of this step's contacts sees it: its row with the sums cleared */
DEM_INLINE mdr_particle mdr_particle_at(DEM_CONST_GLOBAL real *part, int i)
{
    mdr_particle p = mdr_particle_load(part + MDR_P_STRIDE * i);
    mdr_particle_clear_sums(&p);
    return p;
}

/* Side k's overlap share of a pair of apparent overlap delta (M3) given the pair's row (0: a new contact) and the
 * radii of side 0's and side 1's spheres: the largest overlap raised to delta first. mdr_surface and the force use it
 * alike, so both see the same bits. */
DEM_INLINE real mdr_pair_side_share(int k, real delta, DEM_CONST_GLOBAL real *row, real r0, real r1)
{
    real cmax = row ? row[MDR_CMAX] : (real)0;
    if (delta >= cmax)
        cmax = delta;
    real dp0 = row ? row[MDR_S0 + MDR_SIDE * 0 + 10] : (real)0, dp1 = row ? row[MDR_S0 + MDR_SIDE * 1 + 10] : (real)0;
    return mdr_pair_share(k, delta, cmax, r0, r1, dp0, dp1);
}

/* A pair's elastic energy: both sides' (mdr_core.h mdr_side_energy), the contact's weight w on their indenters (the
 * bulk's carries it already); side 0's sphere p0 (the higher stable id), side 1's p1 */
DEM_INLINE real mdr_pair_energy(const mdr_material *m, real w, const mdr_side *s0, const mdr_side *s1,
                                const mdr_particle *p0, const mdr_particle *p1)
{
    real b0, b1, e0 = mdr_side_energy(m, s0, p0, &b0), e1 = mdr_side_energy(m, s1, p1, &b1);
    return w * (e0 + e1) + (b0 + b1);
}
/* A wall contact's: its side's, times the magnifier of this step (taken as constant over the unloading) */
DEM_INLINE real mdr_wall_energy(const mdr_material *m, const mdr_side *s, const mdr_particle *p)
{
    real b0, e0 = mdr_side_energy(m, s, p, &b0);
    return e0 * mdr_wall_magnifier(s->deltao, p->ro) + b0;
}
/* The same from a pair's row and a wall slot's (the host's energies, host/physics/energy.c) */
DEM_INLINE real mdr_pair_row_energy(const mdr_material *m, DEM_CONST_GLOBAL real *row, const mdr_particle *p0,
                                    const mdr_particle *p1)
{
    real w = (real)1 - row[MDR_PEN];
    mdr_side s0 = mdr_side_load(row + MDR_S0), s1 = mdr_side_load(row + MDR_S0 + MDR_SIDE);
    return mdr_pair_energy(m, w > (real)0 ? w : (real)0, &s0, &s1, p0, p1);
}
DEM_INLINE real mdr_wall_row_energy(const mdr_material *m, DEM_CONST_GLOBAL real *row, const mdr_particle *p)
{
    mdr_side s = mdr_side_load(row + MDR_S0);
    return mdr_wall_energy(m, &s, p);
}

/* The material of a contact's pair-table row: MDR's 8 reals and the bond strength (PM_TN_SIGB, pi sigma_b: the
 * smaller of the two materials', so a tool's steel, 0, bonds to nothing) */
DEM_INLINE mdr_material mdr_material_of(DEM_CONST_GLOBAL real *pm)
{
    mdr_material m = mdr_material_from(pm + PM_MDR);
    m.sigb = pm[PM_TN_SIGB];
    return m;
}

DEM_INLINE law_result mdr_force(unsigned fx, law_in c, law_ctx ctx)
{
    mdr_material m = mdr_material_of(c.pm);
    law_result r;
    r.active = 1;
    r.st = (real)0;
    real cmax = c.row_in ? c.row_in[MDR_CMAX] : (real)0;
    if (c.delta >= cmax)
        cmax = c.delta;
    int pair = c.site == LAW_AT_PAIR;
    /* side 0 (a pair's sphere b, or the wall's sphere a) and side 1 (a pair's sphere a) */
    mdr_side s0 = c.row_in ? mdr_side_load(c.row_in + MDR_S0) : mdr_side_new(), s1 = mdr_side_new();
    mdr_particle p0 = mdr_particle_at(ctx.mdr_part, pair ? c.b : c.a), p1 = p0;
    real fel, eta = (real)0, at, w = (real)1, fb;
    if (pair) {
        if (c.row_in)
            s1 = mdr_side_load(c.row_in + MDR_S0 + MDR_SIDE);
        p1 = mdr_particle_at(ctx.mdr_part, c.a);
        real d0 = mdr_pair_share(0, c.delta, cmax, p0.r, p1.r, s0.deltap, s1.deltap);
        real d1 = mdr_pair_share(1, c.delta, cmax, p0.r, p1.r, s0.deltap, s1.deltap);
        /* (M40) this step's penalty, which mdr_surface left in the row before the contacts (a new contact's too) */
        real pen = c.row_out ? c.row_out[MDR_PEN] : (real)0;
        w = (real)1 - pen;
        if (!(w > (real)0))
            w = (real)0;
        real a0, a1, y0 = s0.yielded, y1 = s1.yielded;
        real f0 = mdr_side_force(&m, &s0, &p0, d0, w, &a0);
        real f1 = mdr_side_force(&m, &s1, &p1, d1, w, &a1);
        if ((y0 == MDR_YIELDED && s0.yielded == MDR_BROKEN) || (y1 == MDR_YIELDED && s1.yielded == MDR_BROKEN)) {
            if (s0.yielded == MDR_YIELDED) /* the bridge breaks as a whole */
                s0.yielded = MDR_BROKEN;
            if (s1.yielded == MDR_YIELDED)
                s1.yielded = MDR_BROKEN;
        }
        fel = w * ((f0 + f1) / (real)2); /* (M4) */
        fb = w * ((mdr_side_bond(&m, &s0, p0.r) + mdr_side_bond(&m, &s1, p1.r)) / (real)2); /* the same mean */
        if (fx & DEM_EFFECT_DAMPING)
            eta = m.damp * dem_sqrt(c.mstar * (real)2 * m.es * (a0 + a1)); /* (M38) */
        at = (a0 + a1) / (real)2;
    } else {
        real a0;
        real f0 = mdr_side_force(&m, &s0, &p0, c.delta, (real)1, &a0); /* no third body obstructs a wall contact */
        real mag = mdr_wall_magnifier(s0.deltao, p0.ro);
        fel = f0 * mag; /* (M4), (M39) */
        fb = mdr_side_bond(&m, &s0, p0.r) * mag;
        if (fx & DEM_EFFECT_DAMPING)
            eta = m.damp * dem_sqrt(c.mstar * m.es / (real)2 * a0); /* (M38) */
        at = a0;
    }
    real vn = v3_dot(c.vrel, c.n); /* < 0 while approaching */
    real fn = fel - eta * vn;
    r.fel = fel;
    r.force = v3_scale(c.n, fn);
    r.ft = v3_zero();
    r.hist = v3_zero();
    if (fx & DEM_EFFECT_FRICTION) {
        vec3 vt = v3_sub(c.vrel, v3_scale(c.n, vn));
        real kt = hm_tangential_stiffness(c.pm[PM_GSTAR], at);
        vec3 ft = v3_sub(hm_rotate_history(c.hist, c.n), v3_scale(vt, kt * c.dt));
        /* Coulomb on the whole normal force; a whole bond adds its strength to the load friction resists (never less
         * than the published |F_n|: a bond in deep tension, or pulled past F_b by the damping, keeps that), and a
         * bonded contact that slides loses its bond (mdr_core.h mdr_side_bond) */
        real fabs_n = fn < (real)0 ? -fn : fn, fbond = fn + fb;
        real fmax = c.pm[PM_MU] * (fb > (real)0 && fbond > fabs_n ? fbond : fabs_n);
        real ft2 = v3_dot(ft, ft);
        if (ft2 > fmax * fmax) {
            ft = ft2 > (real)0 ? v3_scale(ft, fmax / dem_sqrt(ft2)) : ft;
            if (fb > (real)0) { /* the bridge sheared off */
                if (s0.yielded == MDR_YIELDED)
                    s0.yielded = MDR_BROKEN;
                if (s1.yielded == MDR_YIELDED)
                    s1.yielded = MDR_BROKEN;
            }
        }
        r.hist = ft;
        r.ft = ft;
        r.force = v3_add(r.force, ft);
    }
    r.ela = (real)0;
    if (c.energy)
        r.ela = pair ? mdr_pair_energy(&m, w, &s0, &s1, &p0, &p1) : mdr_wall_energy(&m, &s0, &p0);
    if (c.sums) {
        mdr_sums_out(c.sums, &p0);
        if (pair)
            mdr_sums_out(c.sums + MDR_NSUM, &p1);
    }
    if (c.row_out) {
        c.row_out[MDR_CMAX] = cmax;
        c.row_out[pair ? MDR_FEL_PAIR : MDR_FEL_WALL] = fel; /* the stress output's (particle_stress.h) */
        mdr_side_store(c.row_out + MDR_S0, &s0);
        if (pair)
            mdr_side_store(c.row_out + MDR_S0 + MDR_SIDE, &s1);
    }
    return r;
}

/* The elastic normal force is the contact's history, not a function of its overlap: the one mdr_force kept in the
 * contact's row in the last force pass (MDR_FEL_PAIR, MDR_FEL_WALL), which the caller hands in as st
 * (DEM_LAW_PAIR_ELASTIC) */
DEM_INLINE real mdr_elastic(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return st;
}
/* Not defined for MDR (a plastic contact's recoverable energy needs its row): its callers refuse an MDR run */
DEM_INLINE real mdr_energy(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return (real)0;
}
DEM_INLINE real mdr_energy_kept(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real fel, real st)
{
    return (real)0;
}
/* The normal slope at delta of a contact flattened and unloading (meant as a bound; it is one only to about half a
 * radius: mdr_row_slope below): both sides (delta/2 each on R = 2 r*) flattened and unloading, 2 E* a per
 * side with a = sqrt(2 (delta/2) R), the mean of the two: E* sqrt(2 r* delta); times 2 for (M17)'s map from the
 * apparent overlap to the indenter's depth, whose slope 1/(1 + 2 dR/A) grows as the contact flattens (to 2 where the
 * compliance dR of (M16) reaches -A/4); Mindlin's k_t = 8 G* a with the same a */
DEM_INLINE void mdr_stiffness(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real *kn, real *kt)
{
    real a = dem_sqrt((real)2 * rstar * delta);
    *kn = (real)2 * pm[PM_MDR] * a;
    *kt = hm_tangential_stiffness(pm[PM_GSTAR], a);
}
/* The law's own normal slope at a contact (the host's stability estimate, host/physics/stability.c; mdr_stiffness's
 * closed form is no bound past an overlap of about half a radius: docs/design.md "The time step under compaction"):
 * the elastic force of the next step with the contact's overlap moved by +eps and by -eps from delta, every other
 * contact held (its own share of the particles' mean surface displacement (M33) included), on copies of the row's
 * sides and of the particles p0, p1 (a pair's, side 0 on p0; a wall's: p0 alone, its magnifier (M39) at the moved
 * state), over eps; the larger of the loading and unloading slopes. pair: 1 a pair, 0 a wall; row: its law row. */
DEM_INLINE real mdr_row_force_at(const mdr_material *m, DEM_CONST_GLOBAL real *row, int pair, const mdr_particle *q0,
                                 const mdr_particle *q1, real delta)
{
    mdr_side s0 = mdr_side_load(row + MDR_S0), s1 = mdr_side_load(row + MDR_S0 + MDR_SIDE);
    mdr_particle p0 = *q0, p1 = *q1;
    real a0, a1;
    mdr_particle_clear_sums(&p0);
    mdr_particle_clear_sums(&p1);
    p0.ddelta_bar = p1.ddelta_bar = (real)0;
    if (!pair) {
        mdr_surface_motion(&p0, &s0, delta);
        real f0 = mdr_side_force(m, &s0, &p0, delta, (real)1, &a0);
        return f0 * mdr_wall_magnifier(s0.deltao, p0.ro);
    }
    real cmax = row[MDR_CMAX] > delta ? row[MDR_CMAX] : delta;
    real d0 = mdr_pair_share(0, delta, cmax, p0.r, p1.r, s0.deltap, s1.deltap);
    real d1 = mdr_pair_share(1, delta, cmax, p0.r, p1.r, s0.deltap, s1.deltap);
    real w = (real)1 - row[MDR_PEN];
    if (!(w > (real)0))
        w = (real)0;
    mdr_surface_motion(&p0, &s0, d0);
    mdr_surface_motion(&p1, &s1, d1);
    real f0 = mdr_side_force(m, &s0, &p0, d0, w, &a0), f1 = mdr_side_force(m, &s1, &p1, d1, w, &a1);
    return w * ((f0 + f1) / (real)2);
}
DEM_INLINE real mdr_row_slope(const mdr_material *m, DEM_CONST_GLOBAL real *row, int pair, const mdr_particle *p0,
                              const mdr_particle *p1, real delta, real eps)
{
    real f = mdr_row_force_at(m, row, pair, p0, p1, delta);
    real up = (mdr_row_force_at(m, row, pair, p0, p1, delta + eps) - f) / eps;
    real down = (f - mdr_row_force_at(m, row, pair, p0, p1, delta - eps)) / eps;
    up = up < (real)0 ? -up : up;
    down = down < (real)0 ? -down : down;
    return up > down ? up : down;
}
#endif /* DEM_MDR_H */
