/* dem_internal_bits.h - the bits of the effect mask that the host alone sets: what a run keeps on the device and
 * MC-strain's reach. They travel in the same mask as the public DEM_EFFECT_* and DEM_MCS_* bits of
 * include/dem_effects.h (the kernels get the whole mask as DEM_EFFECTS, the reference at run time), so they are
 * declared for the host, the reference and the kernels alike, but a caller never sets them (dem_set_effects and
 * dem_set_mc_stress_convention refuse them): this header is not installed. Compiles as C and as OpenCL C.
 */
#ifndef DEM_INTERNAL_BITS_H
#define DEM_INTERNAL_BITS_H
#include "../include/dem_effects.h"

/* MC-strain contact distance (LIGGGHTS' option, seed 000 section 3: enlarged radii can make new contacts): a pair
 * whose centres are closer than PM_MC_REACH (r_i + r_j) is an MC-strain contact as soon as its overlap plus the
 * induced displacements is positive, even with a gap. Set by the host when mc_strain runs with a reach above 1
 * (dem_set_mc_strain_reach); compiled in with the effects. Off: only geometric overlaps. */
enum { DEM_MC_REACH = 2048 };

/* A run that reads the contact network (dem_config.contacts, dem_contacts_get) or sums the walls' forces every step
 * (a servo stage) keeps the force from every wall on every particle (WALL_PF: 3 reals per particle and wall); other
 * runs do not hold that buffer (the walls' sums evaluate the wall contacts themselves: common/wall_forces.h). Set by
 * the host, compiled in with the effects. */
enum { DEM_KEEP_WALL_FORCES = 262144 };

/* A run that samples a series row every few steps (dem_config.sample_every <= DEM_SAMPLE_KEEP) keeps each touching
 * pair's elastic energy of a sampled step (PAIR_ELA: 1 real per pair), computed by contact_pairs from the elastic
 * force it already has; contact_forces adds them. Other runs hold no such buffer, and contact_forces computes each
 * energy from the overlap (a division and a square root per pair): the same bits either way (common/series.h). */
enum { DEM_KEEP_PAIR_ENERGY = 524288 };

/* A run that holds ghosts (copies of other ranks' particles: host/mpi/halo.c, sim_set_ghosts) marks them in GHOST
 * (1 per ghost, by particle), and the walls' sums leave them out (common/wall_forces.h): each rank then sums its own
 * particles' wall forces only, and the ranks' exact sums merge to the one-process bits. Set by the host. */
enum { DEM_HAS_GHOSTS = 33554432 };

/* A run that may join the two contact passes into one (dem_config.one_pass, common/contact_rows.h): it holds a second
 * copy of the pairs' touching flags (TOUCH_NEXT) and, with friction (DEM_ONE_PASS_HIST), of their histories
 * (PAIR_HIST_NEXT), which contact_rows writes and the host then swaps with the current ones. Set by the host only for
 * the laws contact_rows takes, and not in a rank's part of a split run that holds ghosts (every step of a part takes
 * the two passes: host/core/step_loop.c). */
enum { DEM_ONE_PASS = 134217728, DEM_ONE_PASS_HIST = 268435456 };
/* the effects whose runs keep the two passes: per-pair results beside the force that other kernels read */
#define DEM_ONE_PASS_REFUSED                                                                                            \
    (DEM_EFFECT_MC_STRAIN | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_ADHESION | DEM_EFFECT_MDR | DEM_EFFECT_ROLLING_SPRING)

/* Test-only contact laws (common/laws/laws.h), compiled in a test build (-DDEM_TEST_LAWS: tests/test_law_toy.c) and
 * nowhere else: their effect bits, above every other. */
#ifdef DEM_TEST_LAWS
enum { DEM_EFFECT_TEST_SPRING = 1048576 /* common/laws/linear_spring.h */ };
#define DEM_EFFECT_TEST_LAWS DEM_EFFECT_TEST_SPRING
#else
#define DEM_EFFECT_TEST_LAWS 0
#endif

/* The laws with memory (common/laws/law.h): a run with one of them keeps a law state per contact (PAIR_LAW,
 * WALL_LAW: common/dem_buffers.h), of DEM_LAW_PAIR_W reals per pair and DEM_LAW_WALL_W per particle-wall slot: one
 * (Thornton-Ning's largest overlap, or with JKR adhesion largest contact radius) or MDR's rows (dem_layout.h MDR_*) */
#define DEM_LAW_STATE_BITS (DEM_EFFECT_THORNTON_NING | DEM_EFFECT_MDR)
#define DEM_LAW_PAIR_W(fx) (((fx) & DEM_EFFECT_MDR) ? MDR_PAIR_STRIDE : 1)
#define DEM_LAW_WALL_W(fx) (((fx) & DEM_EFFECT_MDR) ? MDR_WALL_STRIDE : 1)
/* which real of a contact's row law_elastic takes as its state (particle_stress.h): Thornton-Ning's one, MDR's
 * elastic normal force of the last step */
#define DEM_LAW_PAIR_ELASTIC(fx) (((fx) & DEM_EFFECT_MDR) ? MDR_FEL_PAIR : 0)
#define DEM_LAW_WALL_ELASTIC(fx) (((fx) & DEM_EFFECT_MDR) ? MDR_FEL_WALL : 0)

/* Every bit the host sets on its own: none of them is a caller's effect or convention bit. */
#define DEM_INTERNAL_BITS                                                                                               \
    (DEM_MC_REACH | DEM_KEEP_WALL_FORCES | DEM_KEEP_PAIR_ENERGY | DEM_HAS_GHOSTS | DEM_ONE_PASS | DEM_ONE_PASS_HIST)
#ifndef __OPENCL_VERSION__
_Static_assert((DEM_INTERNAL_BITS & (DEM_EFFECT_ALL | DEM_MCS_MASK)) == 0,
               "a host-only bit of the effect mask overlaps a caller's effect or convention bit");
_Static_assert((DEM_EFFECT_TEST_LAWS & (DEM_INTERNAL_BITS | DEM_EFFECT_ALL | DEM_MCS_MASK)) == 0,
               "a test law's effect bit overlaps another bit of the mask");
#endif

/* The mask a kernel is compiled with (the host passes -DDEM_EFFECTS=<mask>) */
#ifndef DEM_EFFECTS
#define DEM_EFFECTS DEM_EFFECT_CLASSICAL
#endif
#endif /* DEM_INTERNAL_BITS_H */
