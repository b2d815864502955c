/* dem_effects.h - the effect mask: which physics a run simulates ("simulate only the effects a scene calls for").
 *
 * Declared once for the public API (include/dem.h), the host, the reference and the kernels. In kernels the mask
 * is the compile-time constant DEM_EFFECTS (the host passes -DDEM_EFFECTS=<mask> when it builds the program), so
 * every `if (fx & DEM_EFFECT_...)` on an effect that is off is folded away and its code does not exist in the
 * binary. The reference receives the same mask at run time and takes the same branches, so the two stay
 * bit-identical for every mask.
 */
#ifndef DEM_EFFECTS_H
#define DEM_EFFECTS_H

enum {
    DEM_EFFECT_HERTZ = 1,    /* Hertz normal elasticity (always on: the contact law itself) */
    DEM_EFFECT_DAMPING = 2,  /* normal and tangential viscous damping calibrated from the restitution */
    DEM_EFFECT_FRICTION = 4, /* tangential spring, Coulomb limit, torques and rotation; off: no tangential
                                history is allocated and angular velocities stay as set */
    DEM_EFFECT_GRAVITY = 8,  /* uniform body force */
    DEM_EFFECT_WALLS = 16,   /* planes and cylinders */
    DEM_EFFECT_CLASSICAL = 31,
    DEM_EFFECT_MC_STRESS = 32, /* stress-based multi-contact normal law (seed 000 Eq. 9-10): common/particle_stress.h */
    DEM_EFFECT_MC_STRAIN = 64, /* strain-based multi-contact normal law (Brodu et al., seed 000 Eq. 7-8):
                                  common/mc_strain.h; excludes mc_stress */
    DEM_EFFECT_ALL = 127
};
#define DEM_EFFECT_COUNT 7 /* number of effect bits */

#ifndef DEM_EFFECTS
#define DEM_EFFECTS DEM_EFFECT_CLASSICAL
#endif
#endif /* DEM_EFFECTS_H */
