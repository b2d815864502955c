/* dem_effects.h - the effect mask: which physics a run simulates ("simulate only the effects a scene calls for").
 *
 * Declared once for the public API (include/dem.h, which it completes: both are installed), the host, the
 * reference and the kernels (the program is built with -I<source dir>/include). In kernels the mask is the
 * compile-time constant DEM_EFFECTS (the host passes -DDEM_EFFECTS=<mask> when it builds the program), so every
 * `if (fx & DEM_EFFECT_...)` on an effect that is off is folded away and its code does not exist in the binary. The
 * reference receives the same mask at run time and takes the same branches, so the two stay bit-identical for every
 * mask. This header holds the bits a caller sets (effects and the MC-stress convention); the bits the host alone
 * sets in the same mask (what a run keeps, MC-strain's reach) and DEM_EFFECTS's default are in
 * common/dem_internal_bits.h, which is not installed.
 */
#ifndef DEM_EFFECTS_H
#define DEM_EFFECTS_H

#ifdef __cplusplus
extern "C" {
#endif

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
    DEM_EFFECT_SPRINGS = 4096, /* damped linear springs between particles (seed 001 Eq. 6-7, the membrane's
                                  stretching): common/springs.h. Above the convention bits below, which sit at
                                  128..1024, and the host's 2048 (common/dem_internal_bits.h) */
    DEM_EFFECT_PRESSURE = 8192, /* a pressure on triangles of particles (seed 001 Eq. 18, the membrane's confining
                                   stress): common/pressure.h */
    DEM_EFFECT_BENDING = 16384, /* hinges between pairs of triangles (seed 001 Eq. 8-16, the membrane's bending):
                                   common/bending.h */
    DEM_EFFECT_PATCHES = 32768, /* spheres touch triangles of particles as surfaces (seed 001 Eq. 17 and Table 1, the
                                   membrane's patch contacts): common/patch_contacts.h; the triangles' vertices then
                                   touch no particle as spheres */
    DEM_EFFECT_RIDERS = 65536, /* particles ride on walls (dem_attach_to_wall; common/riders.h) and do not touch the
                                  wall they ride on (contact_geometry.h: wall_met) */
    DEM_EFFECT_CONSTRAINTS = 131072, /* particles keep velocity components (DEM_PARTICLE_HOLD_V*: a prescribed
                                        motion along some axes, free along the others; common/integrate.h) */
    DEM_EFFECT_THORNTON_NING = 2097152, /* elastic-perfectly plastic normal law of Thornton and Ning (Hertz up to the
                                           limiting contact pressure, then a linear plastic branch; unloading along a
                                           Hertz curve of the flattened radius): common/laws/thornton_ning.h; needs a
                                           yield_stress; excludes mc_stress, mc_strain and patches. Above the host's
                                           bits 262144 and 524288 and the test laws' 1048576 */
    DEM_EFFECT_ROLLING = 4194304, /* rolling resistance of constant torque (Ai et al. 2011, model A): each contact
                                     resists the relative rolling of its bodies with mu_r r* f_n; needs friction:
                                     common/rolling.h */
    DEM_EFFECT_ROLLING_SPRING = 8388608, /* rolling resistance by a spring per contact (Ai et al. 2011, model C, the
                                            elastic-plastic spring-dashpot): the torque grows with the relative
                                            rotation up to model A's mu_r r* f_n, with a dashpot below it; needs
                                            rolling: common/rolling.h */
    DEM_EFFECT_MDR = 16777216, /* the mechanically-derived contact model of Zunker and Kamrin for adhesive
                                  elastic-perfectly plastic spheres (apparent overlap, plastic yield, adhesion, the
                                  bulk response of a confined sphere and the radius that keeps its volume):
                                  common/laws/mdr.h, docs/laws/mdr.md; needs each particle material's yield_stress;
                                  excludes mc_stress, mc_strain, thornton_ning and patches */
    DEM_EFFECT_ADHESION = 67108864, /* JKR adhesion of thornton_ning's contacts (Johnson, Kendall and Roberts 1971;
                                       the flattened contact's as Thornton and Ning 1998): the pair's work of
                                       adhesion from its materials' surface_energy; needs thornton_ning and a
                                       material with surface_energy > 0; a pair may not also bond
                                       (common/laws/thornton_ning.h). Above the host's bit 33554432 */
    DEM_EFFECT_ALL = 127 | 4096 | 8192 | 16384 | 32768 | 65536 | 131072 | 2097152 | 4194304 | 8388608 | 16777216 |
                     67108864
};
/* Bit positions an effect name can have (dem_effect_name): 0..26; 7..11 are the convention bits and 18..20 and 25 the
 * host's and the test laws' bits, not effects. */
#define DEM_EFFECT_COUNT 27
/* The effects whose forces reach particles through the contribution channel (common/springs.h) */
#define DEM_EFFECT_CHANNEL (DEM_EFFECT_SPRINGS | DEM_EFFECT_PRESSURE | DEM_EFFECT_BENDING)

/* MC-stress pressure convention: how the pressure of Eq. 10 is built from the traces of Eq. 9. Seed 000 can be read
 * several ways (docs/multicontact.md quotes the passages); each reading is a compiled branch. The bits sit above the
 * effect bits and travel with them (the kernels get effects | convention as DEM_EFFECTS, the reference at run time);
 * they are set with dem_set_mc_stress_convention and mean nothing without DEM_EFFECT_MC_STRESS. */
enum {
    DEM_MCS_OWN_IN = 128,        /* the contact's own term stays in both traces (Eq. 9 sums every contact; the
                                    appendix adds every pair before pass 2; Eq. 11 counts all four). Off: left out,
                                    so two spheres are exactly classical */
    DEM_MCS_LEVER_CENTRES = 256, /* the trace's lever is the centre-to-centre distance d = r_i + r_j - delta (a wall:
                                    to the centre's mirror image, 2 (r - delta)), as the appendix's BranchVector[i,j]
                                    and Eq. 11's P_4 = (4/V) f d. Off: centre to contact point (r - delta/2; a wall
                                    r - delta), Eq. 9's branch vector */
    DEM_MCS_SCALE_TEXT = 512,    /* P_ij = -(tr_i + tr_j) / 3, Eq. 10's text */
    DEM_MCS_SCALE_TRACE = 1024,  /* P_ij = -(tr_i + tr_j) / 2, the mean trace: Eq. 11's P_4 = tr of one particle.
                                    Neither scale bit: -(tr_i + tr_j) / 6, the appendix's 1/6 (the mean pressure) */
    DEM_MCS_MASK = 128 | 256 | 512 | 1024,
    /* The default: the reading under which Eq. 11 holds exactly (own term in, centre-to-centre lever, mean trace);
     * docs/multicontact.md gives the measurements behind the choice. */
    DEM_MCS_DEFAULT = 128 | 256 | 1024,
    /* The reading shipped before (contact's own term out, contact-point lever, appendix's 1/6) */
    DEM_MCS_APPENDIX_OWN_OUT = 0
};

#ifdef __cplusplus
}
#endif
#endif /* DEM_EFFECTS_H */
