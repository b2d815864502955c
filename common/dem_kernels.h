/* dem_kernels.h - every kernel's argument list, written once.
 *
 * From each list below come, by the macros at the end of this file:
 *   - the OpenCL kernel (kernels/program.cl makes every kernel of DEM_KERNEL_LIST with DEM_KERNEL),
 *   - the work-item function's signature (common/<family>.h: DEM_ITEM(name) { body }; the family headers are listed
 *     once, in common/dem_families.h),
 *   - the reference loop (reference/loops.c: DEM_REF_LOOP of every kernel) and its declarations in both precisions
 *     (reference/ref_kernels.h),
 *   - the host's argument setting (host/opencl/cl_backend.c) and the reference backend's call (reference/backend_ref.c),
 *     which look each argument's value up by its source (the last field) in the buffer and scalar registries
 *     (common/dem_buffers.h).
 * Adding an argument is one line here (and its use in the item's body); an argument whose source is not in a
 * registry, or whose element type disagrees with it, does not compile.
 *
 * An entry is A(kind, type, name, source); the first entry of a list is written F(...) (it takes no leading comma).
 * Kinds:
 *   I, R       an int / a real scalar; source: a DEM_SCALARS id (the host converts a real with a plain cast)
 *   BIN, BOUT  a buffer read / written; source: a DEM_BUFFERS id
 *   CIN, COUT  a neighbour-row buffer of the current row set; source: a DEM_ROWS id
 *   NIN, NOUT  the same of the row set being built (the new rows, before they become current)
 *   AIN, AOUT  a buffer named by an alias the driver sets before the launch (the scan's operands); source: a
 *              DEM_ALIASES id
 * Every work-item function is called as name_item(fx, i, <the list>): fx the effect mask (DEM_EFFECTS in a kernel,
 * a run-time value in the reference), i the item, 0 <= i < DEM_ITEMS_<name> (an expression of the list's names).
 */
#ifndef DEM_KERNELS_H
#define DEM_KERNELS_H
#ifdef DEM_REAL_SIZE /* the host, which has no precision, uses the lists only */
#include "dem_real.h"
#include "dem_internal_bits.h" /* DEM_EFFECTS, the host-only bits */
#endif

/* ---- the kernels, in the order of their families ---- */
#define DEM_KERNEL_LIST(K)                                                                                           \
    K(bin_bounds) K(bin_index) K(scan_block_sum) K(scan_block_sums) K(scan_apply) K(bin_scatter) K(bin_sort) K(nbr_count) K(nbr_build) K(nbr_sort)          \
    K(pair_index) K(contact_pairs) K(contact_forces) K(contact_rows) K(wall_reduce_block) K(wall_reduce_mid) K(wall_reduce_final)                        \
    K(integrate_kick_drift) K(integrate_kick_kick_drift) K(integrate_kick) K(stress_trace) K(stress_tensor)          \
    K(mc_strain_disp) K(mc_strain_update) K(spring_forces) K(pressure_forces) K(hinge_forces) K(channel_gather) K(rider_place)  \
    K(patch_build) K(patch_forces) K(patch_gather) K(mdr_begin) K(mdr_surface) K(halo_pack) K(halo_unpack) K(halo_pack_rows) K(halo_unpack_rows)   \
    K(move_mark) K(move_check)

/* ---- binning.h ---- */
#define DEM_ARGS_bin_bounds(F, A)                                                                                    \
    F(I, int, n, N) A(R, real, lox, LOX) A(R, real, loy, LOY) A(R, real, loz, LOZ) A(R, real, inv_cell, INV_CELL)    \
    A(I, int, dcx, DCX) A(I, int, dcy, DCY) A(I, int, dcz, DCZ) A(BIN, real, x, X) A(BOUT, int, flags, FLAGS)
#define DEM_ITEMS_bin_bounds n
#define DEM_ARGS_bin_index(F, A)                                                                                     \
    F(I, int, n, N) A(R, real, lox, LOX) A(R, real, loy, LOY) A(R, real, loz, LOZ) A(R, real, inv_cell, INV_CELL)    \
    A(I, int, dcx, DCX) A(I, int, dcy, DCY) A(I, int, dcz, DCZ) A(I, int, cx0, CX0) A(I, int, cy0, CY0)              \
    A(I, int, cz0, CZ0) A(I, int, ncx, NCX) A(I, int, ncy, NCY) A(I, int, ncz, NCZ) A(BIN, real, x, X)               \
    A(BOUT, int, cell_of, CELL_OF) A(BOUT, int, cell_count, CELL_COUNT)
#define DEM_ITEMS_bin_index n
/* the scan (exclusive prefix sum of count into start) works on the buffers its aliases name */
#define DEM_ARGS_scan_block_sum(F, A)                                                                                \
    F(I, int, nblocks, SCAN_NBLOCKS) A(I, int, ncells, SCAN_ITEMS) A(AIN, int, count, SCAN_COUNT)                    \
    A(AOUT, int, block_sum, SCAN_BLOCK_SUM)
#define DEM_ITEMS_scan_block_sum nblocks
#define DEM_ARGS_scan_block_sums(F, A) F(I, int, nblocks, SCAN_NBLOCKS) A(AOUT, int, block_sum, SCAN_BLOCK_SUM)
#define DEM_ITEMS_scan_block_sums 1
#define DEM_ARGS_scan_apply(F, A)                                                                                    \
    F(I, int, nblocks, SCAN_NBLOCKS) A(I, int, ncells, SCAN_ITEMS) A(AIN, int, count, SCAN_COUNT)                    \
    A(AIN, int, block_sum, SCAN_BLOCK_SUM) A(AOUT, int, start, SCAN_START)
#define DEM_ITEMS_scan_apply nblocks
#define DEM_ARGS_bin_scatter(F, A)                                                                                   \
    F(I, int, n, N) A(BIN, int, cell_of, CELL_OF) A(BIN, int, start, CELL_START) A(BOUT, int, cell_count, CELL_COUNT) \
    A(BOUT, int, cell_particles, CELL_PARTICLES)
#define DEM_ITEMS_bin_scatter n
#define DEM_ARGS_bin_sort(F, A)                                                                                      \
    F(I, int, ncells, NCELLS) A(BIN, int, start, CELL_START) A(BOUT, int, cell_particles, CELL_PARTICLES)
#define DEM_ITEMS_bin_sort ncells

/* ---- neighbor.h ---- */
/* the partners' test, shared by the count and the fill */
#define DEM_ARGS_nbr_walk(F, A)                                                                                      \
    F(I, int, n, N) A(R, real, skin, SKIN) A(I, int, ncx, NCX) A(I, int, ncy, NCY) A(I, int, ncz, NCZ)               \
    A(BIN, real, x, X) A(BIN, real, radius, RADIUS) A(BIN, int, cell_of, CELL_OF) A(BIN, int, cell_start, CELL_START) \
    A(BIN, int, cell_particles, CELL_PARTICLES) A(BIN, int, vtri_start, VTRI_START) A(I, int, nmat, NMAT)            \
    A(BIN, int, mat, MAT) A(BIN, real, pairmat, PAIRMAT) A(BOUT, int, flags, FLAGS) A(BIN, int, sid, SID)
#define DEM_ARGS_nbr_count(F, A) DEM_ARGS_nbr_walk(F, A) A(NOUT, int, nbr_count, COUNT)
#define DEM_ITEMS_nbr_count n
#define DEM_ARGS_nbr_build(F, A)                                                                                     \
    DEM_ARGS_nbr_walk(F, A) A(NIN, int, nbr_count, COUNT) A(NIN, int, nbr_start, START)                              \
    A(NOUT, int, nbr_list, LIST) A(BOUT, int, nbr_fill, NBR_FILL)
#define DEM_ITEMS_nbr_build n
#define DEM_ARGS_nbr_sort(F, A)                                                                                      \
    F(I, int, n, N) A(NIN, int, nbr_count, COUNT) A(NIN, int, nbr_start, START) A(NOUT, int, nbr_list, LIST)         \
    A(BIN, int, nbr_fill, NBR_FILL) A(BIN, int, sid, SID) A(BOUT, int, in_count, IN_COUNT)                           \
    A(BOUT, int, own_count, OWN_COUNT) A(BOUT, int, nbr_lower, LOWER) A(BOUT, int, flags, FLAGS)
#define DEM_ITEMS_nbr_sort n
/* old_hist, old_mc_fn: the history and MC-strain's forces as the last rows numbered their pairs, copied into the
 * pair records' and the displacements' space (host/steps/neighbor.c) */
#define DEM_ARGS_pair_index(F, A)                                                                                    \
    F(I, int, n, N) A(CIN, int, nbr_start, START) A(CIN, int, nbr_count, COUNT) A(CIN, int, nbr_list, LIST)         \
    A(BOUT, int, pair_mirror, PAIR_MIRROR) A(BOUT, int, flags, FLAGS) A(BIN, int, in_start, IN_START)                \
    A(BIN, int, own_start, OWN_START) A(BOUT, int, pair_host, PAIR_HOST) A(BOUT, int, pair_guest, PAIR_GUEST)        \
    A(BOUT, int, pair_slot, PAIR_SLOT) A(BOUT, int, in_pair, IN_PAIR)                                                \
    A(BOUT, dem_byte, touch, TOUCH) A(BIN, dem_byte, old_touch, TOUCH_OLD) A(NIN, int, old_start, START)            \
    A(NIN, int, old_count, COUNT)                                                                                    \
    A(NIN, int, old_list, LIST) A(BIN, int, old_own_start, OWN_START_OLD) A(BIN, real, old_hist, PAIR)               \
    A(BOUT, real, hist, PAIR_HIST) A(BIN, int, sid, SID) A(BIN, int, old_slot, OLD_SLOT)                             \
    A(BIN, real, old_mc_fn, MC_DISP) A(BOUT, real, mc_fn, PAIR_MC_FN) A(BIN, real, old_law_st, PAIR_LAW_OLD)         \
    A(BOUT, real, law_st, PAIR_LAW) A(BIN, real, old_rspring, PAIR_RSPRING_OLD) A(BOUT, real, rspring, PAIR_RSPRING)
#define DEM_ITEMS_pair_index n

/* ---- contact_forces.h ---- */
/* the two contact kernels' common head (contact_pairs walks the flat pair list: it is not given the neighbour rows,
 * which contact_forces reads, so that make bench's bytes per kernel count only what it can read) */
#define DEM_ARGS_contact_head(F, A)                                                                                  \
    F(I, int, n, N) A(I, int, nmat, NMAT) A(R, real, dt, DT) A(BIN, real, x, X)                                      \
    A(BIN, real, v, V) A(BIN, real, w, W) A(BIN, real, radius, RADIUS) A(BIN, real, invmass, INVMASS)                \
    A(BIN, int, mat, MAT) A(BIN, real, pairmat, PAIRMAT)
#define DEM_ARGS_contact_pairs(F, A)                                                                                 \
    DEM_ARGS_contact_head(F, A) A(I, int, npairs, NPAIRS) A(BIN, int, pair_host, PAIR_HOST)                          \
    A(BIN, int, pair_guest, PAIR_GUEST) A(BIN, int, pair_slot, PAIR_SLOT) A(BIN, int, pair_mirror, PAIR_MIRROR)      \
    A(BOUT, real, hist, PAIR_HIST) A(BOUT, dem_byte, touch, TOUCH) A(BOUT, real, pair, PAIR)                          \
    A(BIN, real, trace, TRACE)                                                                                       \
    A(BIN, real, invvol, INVVOL) A(BIN, real, mc_disp, MC_DISP) A(BOUT, real, mc_fn, PAIR_MC_FN)                     \
    A(I, int, sample, SERIES_SAMPLE) A(BOUT, real, pair_ela, PAIR_ELA) A(BOUT, real, law_st, PAIR_LAW)              \
    A(BOUT, real, pair_roll, PAIR_ROLL) A(BIN, real, roll_inertia, ROLL_INERTIA)                \
    A(BOUT, real, rspring, PAIR_RSPRING) A(BIN, real, mdr_part, MDR_PART) A(BOUT, real, pair_mdr_sum, PAIR_MDR_SUM)
#define DEM_ITEMS_contact_pairs npairs
/* what a particle's item reads to find its row's pairs (contact_forces, contact_rows) and to add its walls */
#define DEM_ARGS_contact_row(F, A)                                                                                   \
    A(CIN, int, nbr_start, START) A(CIN, int, nbr_count, COUNT) A(CIN, int, nbr_list, LIST)                          \
    A(BIN, dem_byte, touch, TOUCH) A(BIN, int, in_start, IN_START) A(BIN, int, in_pair, IN_PAIR)                     \
    A(BIN, int, own_start, OWN_START)
#define DEM_ARGS_contact_walls(F, A)                                                                                 \
    A(I, int, nwalls, NWALLS) A(BIN, int, wall_int, WALL_INT) A(BIN, real, wall_real, WALL_REAL)                     \
    A(BOUT, real, wall_hist, WALL_HIST) A(BOUT, real, wall_pf, WALL_PF) A(BOUT, unsigned, wall_mask, WALL_MASK)     \
    A(BIN, real, trace, TRACE) A(BIN, real, invvol, INVVOL) A(BIN, real, mc_wall_disp, MC_WALL_DISP)                 \
    A(BOUT, real, mc_wall_fn, MC_WALL_FN) A(BIN, unsigned, ride, RIDE)
#define DEM_ARGS_contact_forces(F, A)                                                                                \
    DEM_ARGS_contact_head(F, A) DEM_ARGS_contact_row(F, A)                                                           \
    A(BIN, real, pair, PAIR) A(BOUT, real, force, FORCE) A(BOUT, real, torque, TORQUE) DEM_ARGS_contact_walls(F, A)  \
    A(I, int, sample, SERIES_SAMPLE) A(I, int, row, SERIES_ROW)                                                      \
    A(BOUT, real, ring, SERIES_RING) A(BIN, real, pair_ela, PAIR_ELA) A(BIN, int, nbr_lower, LOWER)                 \
    A(BOUT, real, wall_law, WALL_LAW) A(BIN, real, pair_roll, PAIR_ROLL) A(BIN, real, roll_inertia, ROLL_INERTIA)    \
    A(BOUT, real, wall_rspring, WALL_RSPRING) A(BOUT, real, mdr_part, MDR_PART) A(BIN, real, pair_mdr_sum, PAIR_MDR_SUM)
#define DEM_ITEMS_contact_forces n
/* contact_rows.h: the two passes in one, for the steps nothing reads the records of (no record, the history and
 * touching flags read from one copy and written to the other) */
#define DEM_ARGS_contact_rows(F, A)                                                                                  \
    DEM_ARGS_contact_head(F, A) DEM_ARGS_contact_row(F, A) A(BIN, int, nbr_lower, LOWER)                             \
    A(BOUT, dem_byte, touch_next, TOUCH_NEXT) A(BIN, real, hist, PAIR_HIST) A(BOUT, real, hist_next, PAIR_HIST_NEXT) \
    A(BOUT, real, force, FORCE) A(BOUT, real, torque, TORQUE) DEM_ARGS_contact_walls(F, A)                           \
    A(BOUT, real, law_st, PAIR_LAW) A(BOUT, real, wall_law, WALL_LAW) A(BIN, real, roll_inertia, ROLL_INERTIA)       \
    A(BIN, real, rspring, PAIR_RSPRING) A(BOUT, real, wall_rspring, WALL_RSPRING) A(BIN, real, mdr_part, MDR_PART)
#define DEM_ITEMS_contact_rows n

/* ---- wall_forces.h ---- */
#define DEM_ARGS_wall_reduce_block(F, A)                                                                             \
    F(I, int, n, N) A(I, int, nwalls, NWALLS) A(I, int, nblocks, NBLOCKS_RED) A(I, int, nmat, NMAT) A(R, real, dt, DT) \
    A(BIN, real, x, X) A(BIN, real, v, V) A(BIN, real, w, W) A(BIN, real, radius, RADIUS)                            \
    A(BIN, real, invmass, INVMASS) A(BIN, int, mat, MAT) A(BIN, real, pairmat, PAIRMAT) A(BIN, int, wall_int, WALL_INT) \
    A(BIN, real, wall_real, WALL_REAL) A(BIN, real, wall_hist, WALL_HIST) A(BIN, unsigned, wall_mask, WALL_MASK)     \
    A(BIN, real, trace, TRACE) A(BIN, real, invvol, INVVOL) A(BIN, real, mc_wall_disp, MC_WALL_DISP)                 \
    A(BIN, unsigned, ride, RIDE) A(BIN, real, wall_pf, WALL_PF) A(BOUT, unsigned, partial, PARTIAL)                  \
    A(BIN, real, wall_law, WALL_LAW) A(BIN, real, mdr_part, MDR_PART) A(BIN, unsigned, ghost, GHOST)
#define DEM_ITEMS_wall_reduce_block (nblocks * nwalls)
#define DEM_ARGS_wall_reduce_mid(F, A)                                                                               \
    F(I, int, nwalls, NWALLS) A(I, int, nblocks, NBLOCKS_RED) A(I, int, nmid, NMID_RED)                                 \
    A(BIN, unsigned, partial, PARTIAL) A(BOUT, unsigned, mid, PARTIAL_MID)
#define DEM_ITEMS_wall_reduce_mid (nmid * nwalls)
#define DEM_ARGS_wall_reduce_final(F, A)                                                                             \
    F(I, int, nwalls, NWALLS) A(I, int, nmid, NMID_RED) A(BIN, unsigned, mid, PARTIAL_MID)                           \
    A(BOUT, real, wall_force, WALL_FORCE) A(BOUT, real, wall_nforce, WALL_NFORCE)
#define DEM_ITEMS_wall_reduce_final nwalls

/* ---- integrate.h ---- */
#define DEM_ARGS_integrate_kick_drift(F, A)                                                                          \
    F(I, int, n, N) A(R, real, dt, DT) A(R, real, gx, GX) A(R, real, gy, GY) A(R, real, gz, GZ)                      \
    A(R, real, half_skin2, HALF_SKIN2) A(BOUT, real, x, X) A(BOUT, real, v, V) A(BOUT, real, w, W)                   \
    A(BIN, real, force, FORCE) A(BIN, real, torque, TORQUE) A(BIN, real, invmass, INVMASS)                           \
    A(BIN, real, invinertia, INVINERTIA) A(BIN, real, x_build, X_BUILD) A(BOUT, int, flags, FLAGS)                  \
    A(BIN, unsigned, hold, HOLD)
#define DEM_ITEMS_integrate_kick_drift n
/* the last step's kick and this step's kick and drift in one pass over the particles (host/core/step_loop.c) */
#define DEM_ARGS_integrate_kick_kick_drift(F, A) DEM_ARGS_integrate_kick_drift(F, A)
#define DEM_ITEMS_integrate_kick_kick_drift n
#define DEM_ARGS_integrate_kick(F, A)                                                                                \
    F(I, int, n, N) A(R, real, dt, DT) A(R, real, gx, GX) A(R, real, gy, GY) A(R, real, gz, GZ)                      \
    A(BOUT, real, v, V) A(BOUT, real, w, W) A(BIN, real, force, FORCE) A(BIN, real, torque, TORQUE)                  \
    A(BIN, real, invmass, INVMASS) A(BIN, real, invinertia, INVINERTIA) A(BIN, unsigned, hold, HOLD)                 \
    A(BIN, real, x, X) A(I, int, sample, SERIES_SAMPLE) A(I, int, row, SERIES_ROW) A(BOUT, real, ring, SERIES_RING)  \
    A(I, int, nwalls, NWALLS) A(BIN, real, wall_force, WALL_FORCE) A(BIN, real, wall_nforce, WALL_NFORCE)            \
    A(BOUT, real, ring_wall, SERIES_WALL)
#define DEM_ITEMS_integrate_kick n

/* ---- particle_stress.h ---- */
/* the two stress kernels' common head: they differ only in what they write */
#define DEM_ARGS_stress_head(F, A)                                                                                   \
    F(I, int, n, N) A(CIN, int, nbr_start, START) A(I, int, nmat, NMAT) A(BIN, real, x, X) A(BIN, real, radius, RADIUS)  \
    A(BIN, real, invvol, INVVOL) A(BIN, int, mat, MAT) A(BIN, real, pairmat, PAIRMAT)                                \
    A(CIN, int, nbr_count, COUNT) A(CIN, int, nbr_list, LIST) A(I, int, nwalls, NWALLS)                              \
    A(BIN, int, wall_int, WALL_INT) A(BIN, real, wall_real, WALL_REAL) A(BIN, unsigned, ride, RIDE)                  \
    A(BIN, int, nbr_lower, LOWER) A(BIN, int, own_start, OWN_START) A(BIN, int, in_start, IN_START)                  \
    A(BIN, int, in_pair, IN_PAIR) A(BIN, dem_byte, touch, TOUCH) A(BIN, real, law_st, PAIR_LAW)                      \
    A(BIN, unsigned, wall_mask, WALL_MASK) A(BIN, real, wall_law, WALL_LAW)
#define DEM_ARGS_stress_trace(F, A)                                                                                  \
    DEM_ARGS_stress_head(F, A) A(BOUT, real, trace, TRACE)
#define DEM_ITEMS_stress_trace n
#define DEM_ARGS_stress_tensor(F, A)                                                                                 \
    DEM_ARGS_stress_head(F, A) A(BOUT, real, stress, STRESS)
#define DEM_ITEMS_stress_tensor n

/* ---- mc_strain.h ---- */
#define DEM_ARGS_mc_strain_disp(F, A)                                                                                \
    F(I, int, n, N) A(CIN, int, nbr_start, START) A(I, int, nmat, NMAT) A(BIN, real, x, X) A(BIN, real, radius, RADIUS)  \
    A(BIN, int, mat, MAT) A(BIN, real, pairmat, PAIRMAT) A(CIN, int, nbr_count, COUNT) A(CIN, int, nbr_list, LIST)   \
    A(I, int, nwalls, NWALLS) A(BIN, int, wall_int, WALL_INT) A(BIN, real, wall_real, WALL_REAL)                     \
    A(BIN, real, fn, PAIR_MC_FN) A(BIN, real, wall_fn, MC_WALL_FN) A(BOUT, real, disp, MC_DISP)                      \
    A(BOUT, real, wall_disp, MC_WALL_DISP) A(BIN, unsigned, ride, RIDE) A(BIN, int, nbr_lower, LOWER)                \
    A(BIN, int, own_start, OWN_START) A(BIN, int, in_start, IN_START) A(BIN, int, in_pair, IN_PAIR)
#define DEM_ITEMS_mc_strain_disp n
#define DEM_ARGS_mc_strain_update(F, A)                                                                              \
    F(I, int, n, N) A(CIN, int, nbr_start, START) A(I, int, nmat, NMAT) A(R, real, tol, MC_TOL) A(BIN, real, x, X)       \
    A(BIN, real, radius, RADIUS) A(BIN, int, mat, MAT) A(BIN, real, pairmat, PAIRMAT) A(CIN, int, nbr_count, COUNT)  \
    A(CIN, int, nbr_list, LIST) A(BIN, int, sid, SID) A(I, int, nwalls, NWALLS)                                      \
    A(BIN, int, wall_int, WALL_INT) A(BIN, real, wall_real, WALL_REAL) A(BIN, real, disp, MC_DISP)                   \
    A(BIN, real, wall_disp, MC_WALL_DISP) A(BOUT, real, fn, PAIR_MC_FN) A(BOUT, real, wall_fn, MC_WALL_FN)           \
    A(BOUT, int, flags, FLAGS) A(BIN, unsigned, ride, RIDE) A(BIN, int, nbr_lower, LOWER)                            \
    A(BIN, int, own_start, OWN_START) A(BIN, int, in_start, IN_START) A(BIN, int, in_pair, IN_PAIR)                  \
    A(BIN, unsigned, ghost, GHOST)
#define DEM_ITEMS_mc_strain_update n

/* ---- springs.h ---- */
#define DEM_ARGS_spring_forces(F, A)                                                                                 \
    F(I, int, nsprings, NSPRINGS) A(BIN, real, x, X) A(BIN, real, v, V) A(BIN, int, spring_int, SPRING_INT)         \
    A(BIN, real, spring_real, SPRING_REAL) A(BIN, int, chan_slot, CHAN_SLOT) A(BOUT, real, chan_rec, CHAN_REC)        \
    A(BIN, int, order, ORDER)
#define DEM_ITEMS_spring_forces nsprings
/* ---- pressure.h ---- */
#define DEM_ARGS_pressure_forces(F, A)                                                                               \
    F(I, int, ntriangles, NTRIANGLES) A(I, int, nsprings, NSPRINGS) A(R, real, pressure, PRESSURE)                  \
    A(BIN, real, x, X) A(BIN, int, tri, TRI) A(BIN, int, chan_slot, CHAN_SLOT) A(BOUT, real, chan_rec, CHAN_REC)     \
    A(BIN, int, order, ORDER)
#define DEM_ITEMS_pressure_forces ntriangles
/* ---- bending.h ---- */
#define DEM_ARGS_hinge_forces(F, A)                                                                                  \
    F(I, int, nhinges, NHINGES) A(I, int, nsprings, NSPRINGS) A(I, int, ntriangles, NTRIANGLES) A(BIN, real, x, X)  \
    A(BIN, real, v, V) A(BIN, int, hinge_int, HINGE_INT) A(BIN, real, hinge_real, HINGE_REAL)                       \
    A(BIN, int, chan_slot, CHAN_SLOT) A(BOUT, real, chan_rec, CHAN_REC) A(BIN, int, order, ORDER)
#define DEM_ITEMS_hinge_forces nhinges
#define DEM_ARGS_channel_gather(F, A)                                                                                \
    F(I, int, n, N) A(BIN, int, chan_start, CHAN_START) A(BIN, real, chan_rec, CHAN_REC) A(BOUT, real, force, FORCE) \
    A(BIN, int, sid, SID)
#define DEM_ITEMS_channel_gather n
/* ---- riders.h ---- */
#define DEM_ARGS_rider_place(F, A)                                                                                   \
    F(I, int, nriders, NRIDERS) A(BIN, int, rider_int, RIDER_INT) A(BIN, real, rider_off, RIDER_OFF)                 \
    A(BIN, real, wall_real, WALL_REAL) A(BOUT, real, x, X) A(BOUT, real, v, V) A(BIN, int, order, ORDER)
#define DEM_ITEMS_rider_place nriders
/* ---- patch_contacts.h ---- */
#define DEM_ARGS_patch_build(F, A)                                                                                   \
    F(I, int, n, N) A(I, int, maxp, MAXP) A(I, int, old_maxp, MAXPO) A(I, int, maxv, MAXV) A(R, real, skin, SKIN)    \
    A(R, real, reach, REACH) A(R, real, rmax, RMAX) A(R, real, inv_cell, INV_CELL) A(I, int, ncx, NCX)              \
    A(I, int, ncy, NCY) A(I, int, ncz, NCZ) A(BIN, real, x, X) A(BIN, real, radius, RADIUS)                          \
    A(BIN, int, cell_of, CELL_OF) A(BIN, int, cell_start, CELL_START) A(BIN, int, cell_particles, CELL_PARTICLES)    \
    A(BIN, int, tri, TRI) A(BIN, int, vtri_start, VTRI_START) A(BIN, int, vtri_list, VTRI_LIST)                      \
    A(BIN, int, old_pcount, OLD_PCOUNT) A(BIN, int, old_plist, OLD_PLIST) A(BIN, real, old_phist, OLD_PHIST)         \
    A(BIN, dem_byte, old_ptouch, OLD_PTOUCH) A(BOUT, int, pcount, PCOUNT) A(BOUT, int, plist, PLIST)                 \
    A(BOUT, real, phist, PHIST) A(BOUT, dem_byte, ptouch, PTOUCH) A(BOUT, int, vcount, VCOUNT)                       \
    A(BOUT, int, vlist, VLIST) A(BOUT, int, flags, FLAGS) A(BIN, int, sid, SID) A(BIN, int, order, ORDER)
#define DEM_ITEMS_patch_build n
#define DEM_ARGS_patch_forces(F, A)                                                                                  \
    F(I, int, n, N) A(I, int, maxp, MAXP) A(I, int, nmat, NMAT) A(R, real, dt, DT) A(BIN, real, x, X)               \
    A(BIN, real, v, V) A(BIN, real, w, W) A(BIN, real, radius, RADIUS) A(BIN, real, invmass, INVMASS)                \
    A(BIN, int, mat, MAT) A(BIN, real, pairmat, PAIRMAT) A(BIN, int, tri, TRI) A(BIN, int, pcount, PCOUNT)           \
    A(BIN, int, plist, PLIST) A(BOUT, real, phist, PHIST) A(BOUT, dem_byte, ptouch, PTOUCH)                          \
    A(BOUT, real, prec, PREC) A(BOUT, real, force, FORCE) A(BOUT, real, torque, TORQUE) A(BIN, int, order, ORDER)
#define DEM_ITEMS_patch_forces n
#define DEM_ARGS_patch_gather(F, A)                                                                                  \
    F(I, int, n, N) A(I, int, maxp, MAXP) A(I, int, maxv, MAXV) A(BIN, int, tri, TRI)                                \
    A(BIN, int, vtri_start, VTRI_START) A(BIN, int, vtri_list, VTRI_LIST) A(BIN, int, pcount, PCOUNT)                \
    A(BIN, int, plist, PLIST) A(BIN, dem_byte, ptouch, PTOUCH) A(BIN, real, prec, PREC) A(BIN, int, vcount, VCOUNT)  \
    A(BIN, int, vlist, VLIST) A(BOUT, real, force, FORCE) A(BIN, int, sid, SID) A(BIN, int, order, ORDER)
#define DEM_ITEMS_patch_gather n

/* ---- mdr_particle.h ---- */
#define DEM_ARGS_mdr_begin(F, A)                                                                                     \
    F(I, int, n, N) A(I, int, nmat, NMAT) A(R, real, half_skin2, HALF_SKIN2) A(BIN, real, x, X)                      \
    A(BIN, real, x_build, X_BUILD) A(BIN, real, r_build, R_BUILD) A(BIN, int, mat, MAT)                              \
    A(BIN, real, pairmat, PAIRMAT) A(BOUT, real, mdr_part, MDR_PART) A(BOUT, real, radius, RADIUS)                   \
    A(BOUT, int, flags, FLAGS)
#define DEM_ITEMS_mdr_begin n
#define DEM_ARGS_mdr_surface(F, A)                                                                                   \
    F(I, int, n, N) A(CIN, int, nbr_start, START) A(CIN, int, nbr_count, COUNT) A(CIN, int, nbr_list, LIST)         \
    A(BIN, int, nbr_lower, LOWER) A(BIN, int, own_start, OWN_START) A(BIN, int, in_start, IN_START)                  \
    A(BIN, int, in_pair, IN_PAIR) A(BIN, dem_byte, touch, TOUCH) A(BIN, real, x, X) A(BIN, real, radius, RADIUS)     \
    A(BOUT, real, law_st, PAIR_LAW) A(I, int, nwalls, NWALLS) A(BIN, int, wall_int, WALL_INT)                        \
    A(BIN, real, wall_real, WALL_REAL) A(BIN, unsigned, ride, RIDE) A(BIN, unsigned, wall_mask, WALL_MASK)           \
    A(BIN, real, wall_law, WALL_LAW) A(BOUT, real, mdr_part, MDR_PART) A(BIN, int, sid, SID)
#define DEM_ITEMS_mdr_surface n

/* ---- halo.h ---- */
#define DEM_ARGS_halo_pack(F, A)                                                                                     \
    F(I, int, nsend, NSEND) A(BIN, int, halo_idx, HALO_IDX) A(BIN, real, x, X) A(BIN, real, v, V)                    \
    A(BIN, real, w, W) A(BIN, real, force, FORCE) A(BIN, real, torque, TORQUE) A(BOUT, real, halo_buf, HALO_BUF)     \
    A(BIN, int, order, ORDER)
#define DEM_ITEMS_halo_pack nsend
#define DEM_ARGS_halo_unpack(F, A)                                                                                   \
    F(I, int, nrecv, NRECV) A(I, int, nsend, NSEND) A(BIN, int, halo_idx, HALO_IDX) A(BIN, real, halo_buf, HALO_BUF) \
    A(BOUT, real, x, X) A(BOUT, real, v, V) A(BOUT, real, w, W) A(BOUT, real, force, FORCE)                          \
    A(BOUT, real, torque, TORQUE) A(BIN, int, order, ORDER)
#define DEM_ITEMS_halo_unpack nrecv
#define DEM_ARGS_halo_pack_rows(F, A)                                                                                \
    F(I, int, nsend, NSEND) A(I, int, width, HALO_WIDTH) A(BIN, int, halo_idx, HALO_IDX) A(AIN, real, rows, HALO_ROWS) \
    A(BOUT, real, halo_buf, HALO_BUF) A(BIN, int, order, ORDER)
#define DEM_ITEMS_halo_pack_rows nsend
#define DEM_ARGS_halo_unpack_rows(F, A)                                                                              \
    F(I, int, nrecv, NRECV) A(I, int, nsend, NSEND) A(I, int, width, HALO_WIDTH) A(BIN, int, halo_idx, HALO_IDX)     \
    A(BIN, real, halo_buf, HALO_BUF) A(AOUT, real, rows, HALO_ROWS) A(BIN, int, order, ORDER)
#define DEM_ITEMS_halo_unpack_rows nrecv
#define DEM_ARGS_move_mark(F, A)                                                                                     \
    F(I, int, n, N) A(BIN, real, x, X) A(BOUT, real, move_x0, MOVE_X0) A(BOUT, real, move_prev, MOVE_PREV)
#define DEM_ITEMS_move_mark n
#define DEM_ARGS_move_check(F, A)                                                                                    \
    F(I, int, n, N) A(I, int, nblocks, NBLOCKS_RED) A(BIN, real, x, X) A(BIN, unsigned, ghost, GHOST)                \
    A(BIN, real, move_x0, MOVE_X0) A(BOUT, real, move_prev, MOVE_PREV) A(BOUT, real, move_max, MOVE_MAX)
#define DEM_ITEMS_move_check nblocks

/* ---- what the lists become ---- */
/* a parameter declaration of each kind */
#define DEM_PARAM_I(type, name) int name
#define DEM_PARAM_R(type, name) real name
#define DEM_PARAM_BIN(type, name) DEM_CONST_GLOBAL type *name
#define DEM_PARAM_BOUT(type, name) DEM_GLOBAL type *name
#define DEM_PARAM_CIN DEM_PARAM_BIN
#define DEM_PARAM_COUT DEM_PARAM_BOUT
#define DEM_PARAM_NIN DEM_PARAM_BIN
#define DEM_PARAM_NOUT DEM_PARAM_BOUT
#define DEM_PARAM_AIN DEM_PARAM_BIN
#define DEM_PARAM_AOUT DEM_PARAM_BOUT
#define DEM_P_FIRST(kind, type, name, src) DEM_PARAM_##kind(type, name)
#define DEM_P_NEXT(kind, type, name, src) , DEM_PARAM_##kind(type, name)
#define DEM_N_FIRST(kind, type, name, src) name
#define DEM_N_NEXT(kind, type, name, src) , name

/* The work-item function's signature: DEM_ITEM(name) { body using the list's names, fx and i } */
#define DEM_ITEM(name) DEM_INLINE void name##_item(unsigned fx, int i, DEM_ARGS_##name(DEM_P_FIRST, DEM_P_NEXT))

#ifdef __OPENCL_C_VERSION__
/* The kernel: one work item per item, the effect mask compiled in. */
#define DEM_KERNEL(name)                                                                                             \
    __kernel void name(DEM_ARGS_##name(DEM_P_FIRST, DEM_P_NEXT))                                                     \
    {                                                                                                                \
        int i = (int)get_global_id(0);                                                                               \
        if (i < DEM_ITEMS_##name)                                                                                    \
            name##_item(DEM_EFFECTS, i DEM_ARGS_##name(DEM_N_NEXT, DEM_N_NEXT));                                     \
    }
#else
/* The reference loop: the same items in ascending order (REF: reference/ref_kernels.h). */
#define DEM_REF_PROTO(name) void REF(ref_##name)(unsigned fx, DEM_ARGS_##name(DEM_P_FIRST, DEM_P_NEXT))
#define DEM_REF_LOOP(name)                                                                                           \
    DEM_REF_PROTO(name)                                                                                              \
    {                                                                                                                \
        for (int i = 0; i < DEM_ITEMS_##name; i++)                                                                   \
            name##_item(fx, i DEM_ARGS_##name(DEM_N_NEXT, DEM_N_NEXT));                                              \
    }
#endif

#endif /* DEM_KERNELS_H */
