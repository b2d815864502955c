/* mdr_core.h - the MDR contact law of Zunker and Kamrin (adhesive elastic-perfectly plastic spheres; Parts I and II,
 * J. Mech. Phys. Solids 183 (2024) 105492 and 105493), one contact at a time, as docs/laws/mdr.md specifies it:
 * equations (M1)-(M39) there, cited by number here. Compiles as C and as OpenCL C, in fp32 and fp64, like every law.
 *
 * What is here: the fixed-count forms of exp, acos's integral, the cube root and the two adhesive solves (F1-F5),
 * one side of a contact - a sphere pressed on a rigid flat (M5-M27, and Part II's bulk split and force, M10, M35) -,
 * a particle's step from the sums its contacts left (M31, M34), the mean surface displacement (M33), where the flat
 * sits between two spheres (M3), the damping (M38) and the wall magnifier (M39); and a driver that walks one contact
 * (a pair, a sphere on a wall, a sphere between six planes) along a prescribed approach, step by step - the cases of
 * tools/peer_mdr/cases.py that LAMMPS and tools/peer_mdr/mdr_reference.py walk. tests/test_mdr.c runs that driver in
 * the reference (reference/mdr.c) and in an OpenCL kernel and compares it with the Python reference and with the
 * closed forms.
 *
 * The law of a run is built on this core: laws/mdr.h (a contact), mdr_particle.h (a particle's step and the penalty's
 * triplets); docs/laws/mdr.md "The law in a run".
 *
 * Determinism: only + - * / sqrt, floor and scaling by powers of two (frexp, ldexp: exact), fixed counts of terms and
 * Newton steps from starts the inputs fix; constants are integers or ratios of integers, rounded once to `real` in C
 * and in OpenCL C alike (a decimal literal might round twice, to double then to float, in one and once in the other).
 */
#ifndef DEM_MDR_CORE_H
#define DEM_MDR_CORE_H
#include "../dem_real.h"

#ifdef __OPENCL_C_VERSION__
#define mdr_floor(x) floor(x)
#define mdr_ldexp(x, e) ldexp((x), (e))
DEM_INLINE real mdr_frexp(real x, int *e)
{
    int k;
    real m = frexp(x, &k);
    *e = k;
    return m;
}
#elif DEM_REAL_SIZE == 8
#define mdr_floor(x) floor(x)
#define mdr_ldexp(x, e) ldexp((x), (e))
#define mdr_frexp(x, e) frexp((x), (e))
#else
#define mdr_floor(x) floorf(x)
#define mdr_ldexp(x, e) ldexpf((x), (e))
#define mdr_frexp(x, e) frexpf((x), (e))
#endif

/* pi, rounded once to real (0x1.921fb54442d18p+1 is the double nearest pi, exact as written) */
#define MDR_PI ((real)0x1.921fb54442d18p+1)

/* ---- fixed-count functions (docs/laws/mdr.md "Only + - * / sqrt, fixed counts") ---- */

/* (F1) exp(x) for the bounded arguments of the law (|x| < 100): x = n ln2 + r, |r| <= ln2/2, Cody-Waite (ln2_hi has
 * 15 significant bits, so n ln2_hi is exact for |n| < 512 in fp32 too), exp(r) = 1 + r(1 + r/2(1 + r/3(...(1 + r/13))))
 * (13 nested terms), times 2^n (exact). A NaN comes back as it is (its n would not be an int). */
DEM_INLINE real mdr_exp(real x)
{
    if (!(x == x))
        return x;
    const real ln2_hi = (real)0x1.62e4p-1, ln2_lo = (real)0x1.7f7d1cf79abcap-20, inv_ln2 = (real)0x1.71547652b82fep+0;
    real nf = mdr_floor(x * inv_ln2 + (real)1 / (real)2);
    real r = (x - nf * ln2_hi) - nf * ln2_lo;
    real p = (real)1;
    for (int k = 13; k >= 1; k--)
        p = (real)1 + r * p / (real)k;
    return mdr_ldexp(p, (int)nf);
}

/* atan(t) for 0 <= t <= 1: two halvings of the angle (t <- t/(1 + sqrt(1 + t^2))) to t <= tan(pi/16), then atan's
 * odd series to t^25 (13 terms), times 4 */
DEM_INLINE real mdr_atan01(real t)
{
    t = t / ((real)1 + dem_sqrt((real)1 + t * t));
    t = t / ((real)1 + dem_sqrt((real)1 + t * t));
    real t2 = t * t;
    real s = (real)1 / (real)25;
    for (int k = 11; k >= 0; k--)
        s = s * -t2 + (real)1 / (real)(2 * k + 1);
    return (real)4 * t * s;
}

/* (F2) h(u) = acos(1 - 2u) - 2 (1 - 2u) sqrt(u (1 - u)) for u in [0, 1/2] (M7), with full relative precision at small
 * u: t = tan(theta/2) = sqrt(u/(1-u)), halved twice (t <- t/(1 + sqrt(1 + t^2))) to t <= tan(pi/16); theta/4 =
 * atan(t) by its odd series to t^25 (13 terms); phi = 2 theta; h = (phi - sin phi)/2 = phi^3/12 (1 - phi^2/(4 5)
 * (1 - phi^2/(6 7)(...))) to phi^29 */
DEM_INLINE real mdr_h(real u)
{
    if (!(u > (real)0))
        return (real)0;
    real phi = (real)4 * mdr_atan01(dem_sqrt(u / ((real)1 - u)));
    real p2 = phi * phi;
    real q = (real)1;
    for (int k = 13; k >= 1; k--)
        q = (real)1 - p2 * q / (real)((2 * k + 2) * (2 * k + 3));
    return phi * p2 * q / (real)12;
}

/* (F5) y^(1/3) for y > 0: y = m 2^e (exact), e = 3 q + r, m' = m 2^r in [1/2, 4); a quadratic start within 4 %,
 * 5 Newton steps, times 2^q. (Start coefficients: docs/laws/mdr.md's rounded to multiples of 2^-12, 2606/4096,
 * 1611/4096 and 166/4096, exact in fp32.) */
DEM_INLINE real mdr_cbrt(real y)
{
    int e;
    real m = mdr_frexp(y, &e);
    int q = e / 3, r = e - 3 * q;
    if (r < 0)
        r += 3, q -= 1;
    m = mdr_ldexp(m, r);
    real x = (real)2606 / (real)4096 + m * ((real)1611 / (real)4096 - (real)166 / (real)4096 * m);
    for (int k = 0; k < 5; k++)
        x = x - (x * x * x - m) / ((real)3 * x * x);
    return mdr_ldexp(x, q);
}

/* ---- the one-dimensional elliptical indenter (M5-M9) ---- */

/* (M7) the force of the half-ellipse of height A and width B pressed to depth d into springs of stiffness E* per
 * unit length, without adhesion */
DEM_INLINE real mdr_f_na(real d, real A, real B, real es)
{
    return d > (real)0 ? es * A * B / (real)4 * mdr_h(d / A) : (real)0;
}
/* (M6) its contact half-width at depth d */
DEM_INLINE real mdr_a_of_depth(real d, real A, real B)
{
    return d > (real)0 ? B / A * dem_sqrt(d * (A - d)) : (real)0;
}
/* (M5) the profile's depth at x = a */
DEM_INLINE real mdr_g_of_a(real a, real A, real B)
{
    real w2 = B * B / (real)4 - a * a;
    real g = A / (real)2 - A / B * dem_sqrt(w2 > (real)0 ? w2 : (real)0);
    return g > (real)0 ? g : (real)0;
}
/* (M26) P(a) = 2 E* A^2 a^3 + pi gamma B^2 a^2 - pi gamma B^4/4: negative below the critical radius */
DEM_INLINE real mdr_crit_poly(real a, real A, real B, real es, real gamma)
{
    return (real)2 * es * A * A * a * a * a + MDR_PI * gamma * B * B * a * a - MDR_PI * gamma * B * B * B * B / (real)4;
}
/* (F3) the critical radius a_c = (B/2) z, z the positive root of kappa z^3 + z^2 - 1 = 0, kappa = E* A^2/(pi gamma B):
 * Newton from z0 = min(1, cbrt(1/kappa)), above the root; the cubic is convex and rising, so 5 steps fall onto it */
DEM_INLINE real mdr_crit_radius(real A, real B, real es, real gamma)
{
    real kap = es * A * A / (MDR_PI * gamma * B);
    real z = mdr_cbrt((real)1 / kap);
    if (z > (real)1)
        z = (real)1;
    for (int k = 0; k < 5; k++)
        z = z - ((kap * z + (real)1) * z * z - (real)1) / (((real)3 * kap * z + (real)2) * z);
    return B / (real)2 * z;
}
/* f(a) = d - g(a) + sqrt(c a), c = 2 pi gamma / E* (M25), with w = sqrt(B^2/4 - a^2) and sqrt(c a) */
DEM_INLINE real mdr_f_adh(real a, real d, real A, real B, real c, real *w, real *sq)
{
    real w2 = B * B / (real)4 - a * a;
    *w = dem_sqrt(w2 > (real)0 ? w2 : (real)0);
    *sq = dem_sqrt(c * a);
    return d - A / (real)2 + A / B * *w + *sq;
}
/* (F4) the radius of (M25): the root of the concave f in [a_c, a0], or 0 when f(a_c) < 0 (no root: the contact lets go,
 * M27). Start at the root of f's quadratic model at the fold (not above a0); 5 Newton steps fall onto the root from
 * above. Guards for rounding at the fold (f(a_c) = 0, a0 not above a_c, f' not negative): the iterate stays in
 * [a_c, a0], so no step divides by zero or leaves the contact's range */
DEM_INLINE real mdr_adhesive_radius(real d, real A, real B, real es, real gamma, real a0)
{
    real c = (real)2 * MDR_PI * gamma / es, w, sq;
    real ac = mdr_crit_radius(A, B, es, gamma);
    real fc = mdr_f_adh(ac, d, A, B, c, &w, &sq);
    if (fc < (real)0)
        return (real)0;
    if (!(a0 > ac) || !(fc > (real)0)) /* no room above the fold, or the root is the fold itself */
        return ac < a0 ? ac : a0;
    real f2 = -(A / B) * (B * B / (real)4) / (w * w * w) - sq / ((real)4 * ac * ac);
    real a = f2 < (real)0 ? ac + dem_sqrt((real)2 * fc / -f2) : a0;
    if (!(a < a0))
        a = a0;
    for (int k = 0; k < 5; k++) { /* each step kept in [a_c, a0]: a rounding that left f' ~ 0 cannot throw it out */
        real f = mdr_f_adh(a, d, A, B, c, &w, &sq);
        real df = -A * a / (B * w) + c / ((real)2 * sq);
        real next = df < (real)0 ? a - f / df : a;
        a = next > a0 ? a0 : next < ac ? ac : next;
    }
    return a;
}

/* ---- the material, a particle, a side (M1, M30, M37) ---- */

/* MDR's material: derived on the host in double and rounded once to real (mdr_material_from: the same order
 * mdr_walk's callers pass) */
typedef struct {
    real es;    /* E* = E/(1 - nu^2) of one sphere on a rigid flat [Pa] (M1) */
    real g;     /* shear modulus G = E/(2(1 + nu)) [Pa] */
    real kappa; /* bulk modulus E/(3(1 - 2 nu)) [Pa] */
    real nu;    /* Poisson's ratio */
    real y;     /* yield stress Y [Pa] */
    real gamma; /* surface energy [J/m^2] */
    real psi_b; /* free-surface fraction below which the bulk response starts (Part II) */
    real damp;  /* damping coefficient eta_d (M38) */
    real sigb;  /* pi sigma_b of the bonds its yielded contacts form (a solid bridge over the plastic contact area:
                   mdr_side_force; 0, no bonds: every path of the published law). Not one of the 8 reals of
                   mdr_material_from: laws/mdr.h sets it from the pair table's PM_TN_SIGB [Pa] */
} mdr_material;

/* A particle's MDR state (M30-M34, M36): radii, and the sums of its contacts, this step's and the last one's */
typedef struct {
    real ro, r;        /* radius at creation, apparent radius [m] */
    real dr_avg;       /* running mean of the radius increment (M34) [m] */
    real acon0;        /* the contact area A_con of the last step [m^2] */
    real vcaps, eps_sum, dr_num, dr_den, acon1, atot_sum; /* this step's sums (M28, M29, M32) */
    real psi, velas, vgeo; /* free-surface fraction, elastic and geometric volumes of this step (M31) */
    real ddelta_bar;   /* mean surface displacement increment of this step (M33) [m] */
} mdr_particle;

/* One side of a contact: what it remembers (M37) */
typedef struct {
    real delta, deltao;         /* its share of the apparent overlap at the last step, and against R_o [m] */
    real delta_mdr, delta_bulk; /* the split (M10) [m] */
    real ac;                    /* last step's contact area (M33) [m^2] */
    real deltamax;              /* largest delta_mdr [m] */
    real yielded;               /* 1 once yielded (M12), else 0; 2: yielded, its bond broken (MDR_BROKEN) */
    real ca;                    /* area intercept fixed at yield (M12) [m^2] */
    real a_adh;                 /* the adhesive contact radius (M20-M27) [m] */
    real eps_c;                 /* this contact's last strain (M32) */
    real deltap;                /* plastic overlap at which the side's force vanishes (M18) [m] */
} mdr_side;

/* The yield flag's values: a side that yielded is MDR_YIELDED (its bond whole, where the material bonds) or
 * MDR_BROKEN (its bond broke, and it has not yielded further since); both are > 0, so every test of yield reads them
 * alike, and a run without bonds never sees MDR_BROKEN (its bits stay the published law's) */
#define MDR_YIELDED ((real)1)
#define MDR_BROKEN ((real)2)

DEM_INLINE mdr_side mdr_side_new(void)
{
    mdr_side s;
    s.delta = s.deltao = s.delta_mdr = s.delta_bulk = s.ac = s.deltamax = (real)0;
    s.yielded = s.ca = s.a_adh = s.eps_c = s.deltap = (real)0;
    return s;
}

DEM_INLINE void mdr_particle_clear_sums(mdr_particle *p)
{
    p->vcaps = p->eps_sum = p->dr_num = p->dr_den = p->acon1 = p->atot_sum = (real)0;
}

DEM_INLINE mdr_particle mdr_particle_new(real radius)
{
    mdr_particle p;
    p.ro = p.r = radius;
    p.dr_avg = p.acon0 = (real)0;
    mdr_particle_clear_sums(&p);
    p.psi = (real)1;
    p.velas = p.vgeo = (real)4 / (real)3 * MDR_PI * radius * radius * radius;
    p.ddelta_bar = (real)0;
    return p;
}

/* (M31, M34, M36) a particle's step from the sums its contacts left in the last one: volumes, free-surface fraction,
 * the radius that keeps the volume; then the sums restart. Returns 1 when the radius would have grown past 1.5 R_o
 * and was held (the cap LAMMPS's implementation has too): from there the particle's volume is no longer kept, its
 * contacts flatten on into overlaps (M16)-(M17) were not made for, and a compact that goes on being pressed can leave
 * the law's range (a press at psi_b 0 went non-finite 205 steps after the sphere that failed met the cap: docs/laws/
 * mdr.md "Range"); 0 otherwise */
DEM_INLINE int mdr_particle_begin(mdr_particle *p, const mdr_material *m)
{
    int capped = 0;
    real r = p->r, four_pi_3 = (real)4 / (real)3 * MDR_PI;
    real vo = four_pi_3 * p->ro * p->ro * p->ro;
    real vgeo = four_pi_3 * r * r * r - p->vcaps;
    p->vgeo = vgeo < vo ? vgeo : vo;
    p->velas = vo * ((real)1 + p->eps_sum);
    real atot = (real)4 * MDR_PI * r * r + p->atot_sum;
    p->psi = (atot - p->acon1) / atot;
    if (m->psi_b < p->psi) {
        real wc = p->psi > (real)1 / (real)10 ? (real)1 / ((real)1 + mdr_exp((real)-75 * (p->psi - (real)1 / (real)5)))
                                              : (real)0;
        real dr = p->dr_num / (p->dr_den - (real)4 * MDR_PI * r * r) * wc;
        if (dr > (real)0) {
            p->dr_avg += (dr - p->dr_avg) / (real)10;
            if (r + dr < (real)3 / (real)2 * p->ro)
                p->r = r + p->dr_avg;
            else
                capped = 1;
        }
    }
    p->acon0 = p->acon1;
    mdr_particle_clear_sums(p);
    p->ddelta_bar = (real)0;
    return capped;
}

/* (M33) one contact's share of the particle's mean surface displacement increment, at the step's start */
DEM_INLINE void mdr_surface_motion(mdr_particle *p, const mdr_side *s, real delta_now)
{
    if (p->acon0 != (real)0)
        p->ddelta_bar += s->ac / p->acon0 * (delta_now - s->delta);
}

/* (M11) the mean contact pressure on the yield surface of a side whose largest MDR overlap is dm, on radius r */
DEM_INLINE real mdr_yield_pressure(const mdr_material *m, real dm, real r)
{
    return m->y * ((real)7 / (real)4 * mdr_exp((real)-22 / (real)5 * dm / r) + (real)1);
}

/* (M14) a yielded side's largest contact radius squared, a_max^2 (the shape's and the bond's, mdr_side_bond) */
DEM_INLINE real mdr_amax2(const mdr_side *s, real r)
{
    real dm = s->deltamax;
    return (real)2 * dm * r - dm * dm + s->ca / MDR_PI;
}

/* (M13-M17) the indenter of a side on apparent radius r after its yield test: its shape A, B, its largest contact
 * radius amax, the compliance dr of (M16) (0 while elastic) and the depth de of its MDR overlap (py: (M11)) */
DEM_INLINE void mdr_side_shape(const mdr_material *m, const mdr_side *s, real r, real py, real *A, real *B,
                               real *amax, real *dr, real *de)
{
    real dm = s->deltamax;
    if (!(s->yielded > (real)0)) { /* (M13) */
        *A = (real)4 * r, *B = (real)2 * r;
        *de = s->delta_mdr;
        *amax = dem_sqrt(dm * r);
        *dr = (real)0;
    } else { /* (M14-M17) */
        real am = dem_sqrt(mdr_amax2(s, r));
        real a = (real)4 * py * am / m->es;
        *amax = am, *A = a, *B = (real)2 * am;
        real fmax = MDR_PI * py * am * am;
        real zr = r - (dm - a / (real)2);
        real q = dem_sqrt(am * am + zr * zr);
        real d = fmax / ((real)2 * MDR_PI * am * am * m->g * q) *
                 ((real)2 * am * am * (m->nu - (real)1) + ((real)1 - (real)2 * m->nu) * zr * (q - zr)); /* (M16) */
        *dr = d;
        *de = (s->delta_mdr - dm + a / (real)2 + d) / ((real)1 + (real)2 * d / a); /* (M17) */
    }
}

/* The tension a side's bond holds, F_b = sigma_b pi a_max^2 (0 without bonds, or with its bond broken): a side that
 * yielded has formed a solid bridge over its plastic contact area pi a_max^2 (a_max its largest contact radius, M14:
 * at the turn its indenter carries pi p_y a_max^2). Unloaded past its dent (the indenter's depth de < 0) it is a flat
 * circular contact of radius a_max pulled apart: F = 2 E* a_max de, until this tension would pass F_b, which breaks
 * the bond (MDR_BROKEN) until the side yields further. The bridge pulls beside the adhesive springs (M21) where there
 * are any (their forces add, and so do their energies: one potential, so a pull conserves energy until the break).
 * laws/mdr.h adds F_b to the load friction resists, breaks the bond of a contact that slides (as laws/thornton_ning.h's
 * bond) and a pair's two sides' bonds together (docs/laws/mdr.md "Bonds") */
DEM_INLINE real mdr_side_bond(const mdr_material *m, const mdr_side *s, real r)
{
    if (!(m->sigb > (real)0) || !(s->yielded == MDR_YIELDED))
        return (real)0;
    return m->sigb * mdr_amax2(s, r);
}

/* H(u) = the integral of h (M7) from 0 to u, u in [0, 1/2]: with 1 - 2u = cos t, (sin t - t cos t - sin^3 t / 3)/2,
 * written as its series t^5/15 (1 - t^2 c_3 (1 - t^2 c_4 (...))) to t^31, c_k = (g_k/g_{k-1})/(2k (2k + 1)),
 * g_k = (9^k - 1)/4 - 2k (exact integers): no cancellation at small t; t = 2 atan(sqrt(u/(1 - u))) as (F2) takes it.
 * 5.6e-16 relative on [1e-12, 1/2] in double against quadrature (mpmath). */
DEM_INLINE real mdr_hint(real u)
{
    const long g[14] = {16L, 176L, 1632L, 14752L, 132848L, 1195728L, 10761664L, 96855104L, 871696080L, 7845264880L,
                        70607384096L, 635466457056L, 5719198113712L, 51472783023632L}; /* g_2 .. g_15 */
    real t = (real)2 * mdr_atan01(dem_sqrt(u / ((real)1 - u)));
    real t2 = t * t, q = (real)1;
    for (int k = 15; k >= 3; k--)
        q = (real)1 - t2 * ((real)g[k - 2] / (real)g[k - 3]) / (real)(2 * k * (2 * k + 1)) * q;
    return t2 * t2 * t / (real)15 * q;
}

/* One side: a sphere of apparent radius p->r pressed on a rigid flat by delta (M10-M35), its contact weighted by w
 * (M40: 1 - the penalty, at least 0; 1 for a contact no third particle obstructs). Returns F_MDR + F_BULK [N] (the
 * caller weights the contact's force by w, (M4)) and the contact radius the damping sees (*a_damp); updates the side
 * and adds to the particle's sums, the weighted ones weighted (M28, M32; the stored area too, (M37)) */
DEM_INLINE real mdr_side_force(const mdr_material *m, mdr_side *s, mdr_particle *p, real delta, real w, real *a_damp)
{
    real r = p->r, ro = p->ro;
    real ddelta = delta - s->delta;
    s->delta = delta;
    real deltao = delta - (r - ro);
    real ddeltao = deltao - s->deltao;
    s->deltao = deltao;
    real dd_mdr = ddelta, dd_bulk = (real)0;
    if (p->psi < m->psi_b) { /* (M10) the bulk response takes its share */
        real lim = delta - s->delta_mdr;
        dd_mdr = ddelta - p->ddelta_bar < lim ? ddelta - p->ddelta_bar : lim;
        dd_bulk = p->ddelta_bar;
    }
    s->delta_mdr += dd_mdr;
    real dm_before = s->deltamax; /* a side that goes past it yields further: a bond anew (below) */
    real db = s->delta_bulk + dd_bulk;
    s->delta_bulk = db > (real)0 ? db : (real)0;
    if (s->delta_mdr > s->deltamax)
        s->deltamax = s->delta_mdr;
    real dm = s->deltamax;
    real py = mdr_yield_pressure(m, dm, r); /* (M11) */
    if (!(s->yielded > (real)0) && s->delta_mdr >= dm) { /* (M12) */
        real p_hertz = (real)4 * m->es * dem_sqrt(s->delta_mdr) / ((real)3 * MDR_PI * dem_sqrt(r));
        if (p_hertz > py) {
            real dy = s->delta_mdr;
            s->yielded = MDR_YIELDED;
            s->ca = MDR_PI * (dy * dy - dy * r);
        }
    }
    real A, B, de, amax, dr;
    mdr_side_shape(m, s, r, py, &A, &B, &amax, &dr, &de);
    if (s->yielded > (real)0)
        s->deltap = dm - (A / (real)2 + dr); /* (M18) */
    real a_na = mdr_a_of_depth(de, A, B);
    real a_cap = (real)99 / (real)100 * amax;
    real a_prev = s->a_adh < a_cap ? s->a_adh : a_cap; /* (M20) */
    real f;
    if (!(m->gamma > (real)0)) {
        f = mdr_f_na(de, A, B, m->es);
        s->a_adh = a_na;
        *a_damp = a_na;
    } else if (s->delta_mdr >= dm || a_na >= a_prev) { /* (M22) compressive: the springs all in contact */
        f = mdr_f_na(de, A, B, m->es);
        s->a_adh = (real)99 / (real)100 * a_na;
        *a_damp = a_na;
    } else {
        real g = mdr_g_of_a(a_prev, A, B);
        real lmax = dem_sqrt((real)2 * MDR_PI * a_prev * m->gamma / m->es); /* (M23) */
        real a = a_prev;
        if (de + lmax - g < (real)0) { /* (M25-M27) the edge springs would overstretch: the radius recedes */
            a = mdr_crit_poly(a_prev, A, B, m->es, m->gamma) < (real)0
                    ? (real)0
                    : mdr_adhesive_radius(de, A, B, m->es, m->gamma, a_prev);
            s->a_adh = a;
        }
        if (a > (real)0) { /* (M21) */
            g = mdr_g_of_a(a, A, B);
            f = mdr_f_na(g, A, B, m->es) + (real)2 * m->es * (de - g) * a;
        } else {
            f = (real)0;
        }
        *a_damp = a;
    }
    if (m->sigb > (real)0 && s->yielded > (real)0) { /* the bond over the plastic contact area (mdr_side_bond) */
        if (s->delta_mdr > dm_before)
            s->yielded = MDR_YIELDED; /* yielding further: bonded anew over the new plastic area */
        if (s->yielded == MDR_YIELDED && de < (real)0) {
            real ften = (real)2 * m->es * amax * de; /* a flat circular contact of radius a_max pulled apart */
            if (ften < -(m->sigb * amax * amax))
                s->yielded = MDR_BROKEN;
            else
                f = f + ften, *a_damp = amax; /* beside the adhesive springs (M21), if any */
        }
    }
    /* (M28, M29, M32, M35) areas, cap volume, strain and the radius update's sums */
    real ac = s->yielded > (real)0 ? MDR_PI * ((real)2 * delta * r - delta * delta) + s->ca : MDR_PI * delta * r;
    if (ac < (real)0)
        ac = (real)0;
    p->atot_sum += w * (ac - (real)2 * MDR_PI * r * (dm + s->delta_bulk));
    p->acon1 += w * ac;
    s->ac = w * ac;
    real f_bulk = s->delta_bulk > (real)0 ? p->acon0 * s->delta_bulk * m->kappa * ac / p->vgeo : (real)0;
    p->vcaps += MDR_PI / (real)3 * delta * delta * ((real)3 * r - delta);
    real eps_c = -(w * (f + f_bulk)) * (ro - deltao) / ((real)3 * m->kappa * p->velas);
    p->eps_sum += eps_c;
    if (s->delta_mdr >= dm && s->yielded > (real)0 && f > (real)0) {
        real vo = (real)4 / (real)3 * MDR_PI * ro * ro * ro;
        p->dr_num -= vo * (eps_c - s->eps_c);
        p->dr_num -= w * MDR_PI * ddeltao * ((real)2 * deltao * ro - deltao * deltao + r * r - ro * ro);
        p->dr_den += w * (real)2 * MDR_PI * r * (deltao + r - ro);
    }
    s->eps_c = eps_c;
    return f + f_bulk;
}

/* The elastic energy a side gives back when unloaded from its state: (M7)'s force integrated along (M17)'s map from
 * the indenter's depth de to 0, (1 + 2 dr/A) E* A^2 B / 4 H(de/A). A side whose springs are held at a radius a
 * beyond the compressive one (M21, cases 2 and 3 of mdr_side_force: after the step a = min(a_adh, 0.99 a_max) >
 * a_na(de)) stores the springs' energy at the depth g = g(a) where a is compressive, plus what its force, linear in de
 * at fixed a (slope 2 E* a), adds from g to de: F_na(g) (de - g) + E* a (de - g)^2, along the same map (the 1D springs'
 * sum of squares, >= 0: it is the energy a pull-off sets free). A side whose bond pulls (de < 0, mdr_side_bond) adds
 * the bridge's linear spring, E* a_max de^2 along the map. *bulk gets the bulk spring's F_BULK delta_BULK / 2
 * (M35, with the side's stored area, which carries the contact's weight) of the particle p of this step. */
DEM_INLINE real mdr_side_energy(const mdr_material *m, const mdr_side *s, const mdr_particle *p, real *bulk)
{
    real r = p->r, A, B, amax, dr, de;
    mdr_side_shape(m, s, r, mdr_yield_pressure(m, s->deltamax, r), &A, &B, &amax, &dr, &de);
    real d = de, held = (real)0;
    if (m->gamma > (real)0) {
        real a_cap = (real)99 / (real)100 * amax;
        real a = s->a_adh < a_cap ? s->a_adh : a_cap;
        if (a > mdr_a_of_depth(de, A, B)) {
            real g = mdr_g_of_a(a, A, B), x = de - g;
            held = mdr_f_na(g, A, B, m->es) * x + m->es * a * x * x;
            d = g;
        }
    }
    if (m->sigb > (real)0 && s->yielded == MDR_YIELDED && de < (real)0) /* a bond in tension (mdr_side_force) */
        held = held + m->es * amax * de * de; /* a linear spring's, beside the adhesive springs' */
    real u = d / A;
    if (u > (real)1 / (real)2)
        u = (real)1 / (real)2;
    *bulk = s->delta_bulk > (real)0
                ? p->acon0 * s->delta_bulk * m->kappa * s->ac / p->vgeo * s->delta_bulk / (real)2
                : (real)0;
    real k = (real)1 + (real)2 * dr / A;
    return (d > (real)0 ? k * (m->es * A * A * B / (real)4) * mdr_hint(u) : (real)0) + k * held;
}

/* (M3) side k's share of a pair's apparent overlap delta: side 0 the sphere of higher id (radius r0), side 1 the
 * other; dmax the contact's largest overlap (>= delta), dp0 and dp1 the sides' plastic overlaps of the last step */
DEM_INLINE real mdr_pair_share(int k, real delta, real dmax, real r0, real r1, real dp0, real dp1)
{
    real ri = k ? r1 : r0, rj = k ? r0 : r1;
    real denom = (real)2 * (dmax - ri - rj);
    real o1 = dmax * (dmax - (real)2 * rj) / denom, o2 = dmax * (dmax - (real)2 * ri) / denom;
    real hi = o1 > o2 ? o1 : o2, lo = o1 > o2 ? o2 : o1;
    real geo = ri < rj ? hi : lo, alt = ri < rj ? lo : hi;
    real lim = (real)19 / (real)20;
    if (geo / ri > lim)
        geo = ri * lim;
    else if (alt / rj > lim)
        geo = dmax - rj * lim;
    return geo + ((k ? dp1 : dp0) - geo) * (delta - dmax) / (dp0 + dp1 - dmax);
}

/* (M39) the wall force magnifier 1 + exp(10.7 delta_o/R_o - 10) */
DEM_INLINE real mdr_wall_magnifier(real deltao, real ro)
{
    return mdr_exp((real)107 / (real)10 * deltao / ro - (real)10) + (real)1;
}

/* (M40) acos(c)/pi for c in [-1, 1], the angle as 2 atan(t), t = sqrt((1 - c)/(1 + c)), with atan(t) = pi/2 -
 * atan(1/t) for t > 1 so that mdr_atan01's series keeps its range */
DEM_INLINE real mdr_acos_over_pi(real c)
{
    if (!(c < (real)1))
        return (real)0;
    if (!(c > (real)-1))
        return (real)1;
    real t = dem_sqrt(((real)1 - c) / ((real)1 + c));
    if (t > (real)1)
        return (real)1 - (real)2 * mdr_atan01((real)1 / t) / MDR_PI;
    return (real)2 * mdr_atan01(t) / MDR_PI;
}

/* (M40) the penalty one central particle adds to the pair of the three whose centres are farthest apart:
 * 1/(1 + exp(-50 (alpha/pi - 1/2))), alpha the angle at the central particle between the unit directions to the other
 * two (c = their dot product, cos alpha) */
DEM_INLINE real mdr_penalty(real c)
{
    return (real)1 / ((real)1 + mdr_exp((real)-50 * (mdr_acos_over_pi(c) - (real)1 / (real)2)));
}

/* The material from its 8 reals in the struct's order (es, g, kappa, nu, y, gamma, psi_b, damp) */
DEM_INLINE mdr_material mdr_material_from(DEM_CONST_GLOBAL real *v)
{
    mdr_material m;
    m.es = v[0], m.g = v[1], m.kappa = v[2], m.nu = v[3], m.y = v[4], m.gamma = v[5], m.psi_b = v[6], m.damp = v[7];
    m.sigb = (real)0;
    return m;
}

/* The fixed-count functions on an array, for the tests: which 0 exp (F1), 1 h (F2), 2 the cube root (F5), 3 acos/pi,
 * 4 the penalty (M40) */
enum { MDR_FIXED_EXP = 0, MDR_FIXED_H = 1, MDR_FIXED_CBRT = 2, MDR_FIXED_ACOS = 3, MDR_FIXED_PENALTY = 4 };
DEM_INLINE void mdr_fixed(int which, int n, DEM_CONST_GLOBAL real *x, DEM_GLOBAL real *y)
{
    for (int i = 0; i < n; i++)
        y[i] = which == MDR_FIXED_EXP    ? mdr_exp(x[i])
               : which == MDR_FIXED_H    ? mdr_h(x[i])
               : which == MDR_FIXED_CBRT ? mdr_cbrt(x[i])
               : which == MDR_FIXED_ACOS ? mdr_acos_over_pi(x[i])
                                         : mdr_penalty(x[i]);
}

/* ---- a contact walked along a prescribed approach (tools/peer_mdr/cases.py) ---- */
enum { MDR_WALK_PAIR = 0, MDR_WALK_WALL = 1, MDR_WALK_BOX = 2 };

/* Walks steps 0..nsteps of one contact: u[k] the approach at step k [m] (the centres' displacement towards each
 * other, or towards the wall; a box's six planes each close in by u), R the first sphere's radius, R2 the second's
 * (a pair), mass1 and mass2 their masses, dt the step. Writes per step the first sphere's overlap, apparent radius,
 * free-surface fraction and the normal force (the pair's (M4) with damping (M38); the wall's with its magnifier
 * (M39); the box's on its first plane). As tools/peer_mdr/mdr_reference.py run_case and run_box do. */
DEM_INLINE void mdr_walk(int kind, int nsteps, DEM_CONST_GLOBAL real *u, const mdr_material *m, real R, real R2,
                         real mass1, real mass2, real dt, DEM_GLOBAL real *out_delta, DEM_GLOBAL real *out_r,
                         DEM_GLOBAL real *out_psi, DEM_GLOBAL real *out_f)
{
    mdr_particle p1 = mdr_particle_new(R), p2 = mdr_particle_new(R2);
    mdr_side sides[6];
    real cmax[6];
    int nw = kind == MDR_WALK_BOX ? 6 : kind == MDR_WALK_PAIR ? 2 : 1; /* a pair: its two sides */
    for (int k = 0; k < 6; k++)
        sides[k] = mdr_side_new(), cmax[k] = (real)0;
    for (int step = 0; step <= nsteps; step++) {
        real f = (real)0, delta;
        if (step > 0) {
            mdr_particle_begin(&p1, m);
            if (kind == MDR_WALK_PAIR)
                mdr_particle_begin(&p2, m);
        }
        if (kind == MDR_WALK_PAIR)
            delta = p1.r + p2.r - (R + p2.ro - u[step]);
        else
            delta = p1.r - (R - u[step]);
        if (kind == MDR_WALK_BOX) {
            if (step > 0) {
                for (int k = 0; k < nw; k++)
                    if (delta > (real)0)
                        mdr_surface_motion(&p1, &sides[k], delta);
                for (int k = 0; k < nw; k++) {
                    if (delta > (real)0) {
                        real a;
                        if (delta >= cmax[k])
                            cmax[k] = delta;
                        real f0 = mdr_side_force(m, &sides[k], &p1, delta, (real)1, &a);
                        if (k == 0)
                            f = f0 * mdr_wall_magnifier(sides[0].deltao, p1.ro);
                    } else {
                        sides[k] = mdr_side_new(), cmax[k] = (real)0;
                    }
                }
            }
        } else if (delta > (real)0 && step > 0) {
            real v_app = (u[step] - u[step - 1]) / dt, a0, a1, fel, eta;
            if (delta >= cmax[0])
                cmax[0] = delta;
            if (kind == MDR_WALK_PAIR) {
                real d0 = mdr_pair_share(0, delta, cmax[0], p2.r, p1.r, sides[0].deltap, sides[1].deltap);
                real d1 = mdr_pair_share(1, delta, cmax[0], p2.r, p1.r, sides[0].deltap, sides[1].deltap);
                mdr_surface_motion(&p2, &sides[0], d0);
                mdr_surface_motion(&p1, &sides[1], d1);
                real f0 = mdr_side_force(m, &sides[0], &p2, d0, (real)1, &a0);
                real f1 = mdr_side_force(m, &sides[1], &p1, d1, (real)1, &a1);
                fel = (f0 + f1) / (real)2; /* (M4) */
                real meff = mass1 * mass2 / (mass1 + mass2);
                eta = m->damp * dem_sqrt(meff * (real)2 * m->es * (a0 + a1)); /* (M38) */
            } else {
                mdr_surface_motion(&p1, &sides[0], delta);
                real f0 = mdr_side_force(m, &sides[0], &p1, delta, (real)1, &a0);
                fel = f0 * mdr_wall_magnifier(sides[0].deltao, p1.ro);
                eta = m->damp * dem_sqrt(mass1 * m->es / (real)2 * a0);
            }
            f = fel + eta * v_app;
        } else if (!(delta > (real)0)) {
            for (int k = 0; k < 2; k++)
                sides[k] = mdr_side_new();
            cmax[0] = (real)0;
        }
        out_delta[step] = delta;
        out_r[step] = p1.r;
        out_psi[step] = p1.psi;
        out_f[step] = f;
    }
}
#endif /* DEM_MDR_CORE_H */
