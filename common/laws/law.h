/* law.h - what every contact law (common/laws/<law>.h) takes and returns: the interface of a law unit.
 *
 * A law is one header that gives, for the pair-table row pm of the two materials (dem_layout.h PM_*; the law names
 * the columns it reads in LAW_COLUMNS_<law>):
 *   <law>_force(fx, c, ctx)             the contact force on a (law_result) from the contact's state (law_in) and
 *                                       its context (law_ctx: what a law reads beyond the two bodies, e.g. MC-stress
 *                                       the stress traces, MC-strain the induced displacements);
 *   <law>_elastic(pm, rstar, delta, st) the elastic normal force at overlap delta given the contact's law state st
 *                                       (the stress tensor's f_H);
 *   <law>_energy(pm, rstar, delta, st)  the elastic energy stored at delta (what the contact gives back if it is
 *                                       unloaded from there; an elastic law: the work of <law>_elastic from 0),
 *                                       given the contact's law state st;
 *   <law>_energy_kept(pm, rstar, delta, fel, st)  the same given the elastic force fel its force returned
 *                                       (Hertz spares a root with it; MC-strain's is at another overlap);
 *   <law>_stiffness(pm, rstar, delta, &kn, &kt)   normal and tangential stiffness at delta (the host's stability
 *                                       estimate, host/physics/stability.c).
 * common/laws/laws.h lists the laws with their effect bits and dispatches (law_force, law_elastic, law_energy, ...);
 * the callers - particle pairs (contact_forces.h), walls (wall_forces.h), patches (patch_contacts.h), the stress
 * (particle_stress.h), the series (series.h), the host's energy.c and stability.c (compiled in double) - call only
 * those entry points.
 *
 * A law with memory (a plastic one) keeps one real per contact, its state (law_in.st in, law_result.st out; e.g. the
 * largest overlap so far, or Thornton-Ning's with JKR adhesion the largest contact radius): its effect bit is in DEM_LAW_STATE_BITS (dem_internal_bits.h), and the run then holds
 * the state of every pair (PAIR_LAW, carried across rebuilds like the tangential history: neighbor.h) and of every
 * particle-wall slot (WALL_LAW), saved in checkpoints. A new contact starts from st = 0.
 *
 * Conventions: body a and body b; n the unit vector from b to a; delta > 0 the overlap; vrel the velocity of a's
 * contact point relative to b's. Returned forces act on a (b receives the negative).
 */
#ifndef DEM_LAW_H
#define DEM_LAW_H
#include "../vec3.h"
#include "../dem_layout.h"
#include "../dem_internal_bits.h" /* the effect bits, and the host-only ones (DEM_MC_REACH) */

/* Where a contact is: each caller passes a constant, so a law's branches for the other sites fold away. */
enum { LAW_AT_PAIR = 0, LAW_AT_WALL = 1, LAW_AT_PATCH = 2 };

/* One contact's state as a law sees it */
typedef struct {
    int site;      /* LAW_AT_PAIR, LAW_AT_WALL or LAW_AT_PATCH */
    int a, b;      /* the particles (b = a at a wall or a patch) */
    real ra, rb;   /* their radii (rb = ra at a wall or a patch) [m] */
    vec3 n;        /* unit normal from b to a */
    real delta;    /* the overlap [m] (a patch: its law's overlap, patch_contacts.h) */
    real rstar;    /* effective radius [m] */
    real mstar;    /* effective mass [kg] (0: both immovable) */
    vec3 vrel;     /* velocity of a's contact point relative to b's [m/s] */
    vec3 hist;     /* the stored elastic tangential force [N] (zero when none) */
    real st;       /* the law's stored state (a law with memory; 0 for a new contact or a law without) */
    /* A law whose state is a row of reals (MDR: dem_layout.h MDR_*; set only in its runs): */
    DEM_CONST_GLOBAL real *row_in; /* the contact's row of the last step (0: a new contact, the row starts at zero) */
    DEM_GLOBAL real *row_out;      /* where the new row goes (0: not kept, e.g. the walls' force sums) */
    real *sums;                    /* where each side leaves its particle's sums (MDR: 6 per side; 0: not kept) */
    int energy;                    /* 1: the law returns the contact's elastic energy in law_result.ela (a law whose
                                      energy needs its row, MDR; the others' callers use law_energy_kept) */
    real dt;       /* time step [s] */
    DEM_CONST_GLOBAL real *pm;  /* the pair-table row of the two materials */
    DEM_CONST_GLOBAL real *pmi; /* the row of a's own material with itself (MC-stress at a wall) */
} law_in;

/* What a law reads besides the contact itself. The arrays may be any valid buffer where the law is off (its
 * effect test folds the reads away). */
typedef struct {
    DEM_CONST_GLOBAL real *trace;  /* MC-stress: each particle's stress trace (particle_stress.h) */
    DEM_CONST_GLOBAL real *invvol; /* MC-stress: each particle's 1/V [1/m^3] */
    real disp_a, disp_b;           /* MC-strain: the displacements induced at this contact in a and in b (0 for a
                                      wall's b) [m] */
    DEM_CONST_GLOBAL real *mdr_part; /* MDR: each particle's row of this step (dem_layout.h MDR_P_*) */
} law_ctx;

typedef struct {
    int active; /* 0: the law says the bodies do not touch (MC-strain's reach: a gap the induced overlap does not
                   close); the other fields are then unset */
    real fel;   /* elastic normal force at the overlap the law saw [N] */
    vec3 force; /* total contact force on a [N] */
    vec3 ft;    /* its tangential part [N] (torques) */
    vec3 hist;  /* new elastic tangential force to store [N] */
    real st;    /* new law state to store (a law with memory; 0 otherwise) */
    real ela;   /* the contact's elastic energy when law_in.energy asked (MDR) [J] */
} law_result;

/* Effective mass of two bodies given inverse masses; 0 when both are immovable (no damping then). */
DEM_INLINE real law_effective_mass(real invm_a, real invm_b)
{
    real s = invm_a + invm_b;
    return s > (real)0 ? (real)1 / s : (real)0;
}
#endif /* DEM_LAW_H */
