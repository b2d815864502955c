/* dem_buffers.h - the one registry of device buffers and kernel scalars: name, element type, size rule, the
 * effect that gates it, the field it is read and written as, and what it starts from. The backends create, grow,
 * look up and destroy buffers by walking it (backend/backend.c); the kernels' argument lists (dem_kernels.h) name their
 * sources here. Host only: the kernels see plain pointers.
 *
 * Size rules are expressions of the dimensions N (particles), NMAT (materials), NW (walls), NC (cells held: those of
 * the particles' bounding box at a build, binning.h, with room to spare; host/steps/binning.c), NBS (scan
 * blocks of the cells), NBR (reduction blocks of the particles), NMR (groups of
 * DEM_REDUCE_FAN of those blocks: the middle level of the wall-force tree), MAXN (slots of the row set the buffer belongs to:
 * its rows are packed one after the other, row i from start[i], so MAXN is what all its rows hold together, with
 * room to spare: host/core/rebuild.c row_capacity), MAXC (slots of the current row set: for a buffer laid out like the rows
 * but written before it is read after each rebuild, so held once and not in both sets; host/steps/neighbor.c grows it with
 * the current set), PAIRS (pair
 * records allocated), LAWP and LAWW (the reals of a contact's law state per pair and per particle-wall slot:
 * DEM_LAW_PAIR_W, DEM_LAW_WALL_W), NS (springs), NT (triangles), NH (hinges), NR (riders), MAXP, MAXPO and MAXV (capacity of the
 * sphere patch rows, of the old ones a rebuild carries history from, of the vertex rows: patch_contacts.h), NHALO
 * (message rows of a run split over ranks: those it sends and those it receives, halo.h; 0 in one process), in
 * elements.
 * Gate: the effect bit (dem_effects.h) without which the buffer is empty; 0 for always; DEM_GATE_LAZY for a buffer
 * made when first needed (the output stress tensor).
 * Init: what create uploads: SETUP(member) of dem_setup (the host's copy in the run's precision, made by sim_pack;
 * an int or unsigned buffer's member is checked to be of its element type: backend/backend.c), or NONE (zero-filled).
 * Move: how the buffer follows its particles when they are stored anew (host/core/reorder.c) and, next, when they
 * migrate between ranks: STAY (not by particle, or rewritten before it is read after a rebuild: cells, in/own counts,
 * the pair-sized arrays, the walls' partial sums, the membrane, patch and rider tables of runs that never reorder),
 * P(per) (particle-major: `per` elements per particle, the first N * per elements; a tail past them stays), or
 * G(per) (groups of N items of `per` elements each, e.g. one group per wall or per ring row). ORDER (where each stable
 * id is stored) stays: reorder.c makes it anew from the moved SID. A buffer sized by particles that is read before it
 * is written after a rebuild and says STAY changes the bits of tests/test_particle_order.c.
 * Checkpoint: NO, or CK(name, width, unit) / CK_OPT(name, width, unit): saved whole, in the callers' particle order,
 * by dem_state_get and put back by dem_state_set (host/core/state.c), as the dataset /state/<name> of a checkpoint
 * (app/checkpoint.c; width: elements per row of the dataset, unit its attribute). A state must hold a CK array at the
 * run's size; a CK_OPT one may be missing (older checkpoints: zero until it is computed). The name is the dataset's:
 * renaming one breaks the loading of older checkpoints.
 */
#ifndef DEM_BUFFERS_H
#define DEM_BUFFERS_H
#include "dem_layout.h"
#include "dem_internal_bits.h" /* the effect bits, DEM_KEEP_* among them */
#include "exact_sum.h"         /* EXACT_WORDS: the walls' partial sums are exact accumulators */

/* element types */
enum { DEM_ELEM_REAL, DEM_ELEM_INT, DEM_ELEM_UINT, DEM_ELEM_BYTE };
/* how a buffer follows its particles (the registry's move column) */
enum { DEM_MOVE_STAY, DEM_MOVE_P, DEM_MOVE_G };
#define DEM_GATE_LAZY 0x80000000u

/* A checkpointed per-particle buffer of the test build only (tests/test_extra_buffer.c): it proves that such a
 * buffer is its registry line plus where it is first computed (here the setup's 0, 1, ..., n - 1). */
#ifdef DEM_TEST_EXTRA_BUFFER
#define DEM_BUFFERS_TEST(ENTRY)                                                                                         \
    ENTRY(TEST_EXTRA, INT, N, 0, -1, SETUP(identity), PARTICLES, P(1), CK(test_extra, 1, NULL))
#else
#define DEM_BUFFERS_TEST(ENTRY)
#endif

/* ENTRY(ID, element, count, gate, field, init, part, move, checkpoint) - buffers that exist once; part: what they
 * hold, for the memory report (dem_memory_part in dem.h: PARTICLES, PAIRS, WALLS, CELLS, OUTPUT, MESH; the row sets
 * are ROWS) */
#define DEM_BUFFERS(ENTRY)                                                                                              \
    ENTRY(X, REAL, 3 * N, 0, DEM_FIELD_X, SETUP(x), PARTICLES, P(3), CK(x, 3, "m"))                                     \
    ENTRY(V, REAL, 3 * N, 0, DEM_FIELD_V, SETUP(v), PARTICLES, P(3), CK(v, 3, "m/s"))                                   \
    ENTRY(W, REAL, 3 * N, 0, DEM_FIELD_W, SETUP(w), PARTICLES, P(3), CK(w, 3, "rad/s"))                                 \
    ENTRY(FORCE, REAL, 3 * N, 0, DEM_FIELD_FORCE, NONE, PARTICLES, P(3), CK(force, 3, "N"))                             \
    ENTRY(TORQUE, REAL, 3 * N, 0, DEM_FIELD_TORQUE, NONE, PARTICLES, P(3), CK(torque, 3, "N m"))                        \
    ENTRY(RADIUS, REAL, N, 0, DEM_FIELD_RADIUS, SETUP(radius), PARTICLES, P(1), NO)                                     \
    ENTRY(INVMASS, REAL, N, 0, -1, SETUP(invmass), PARTICLES, P(1), NO)                                                 \
    ENTRY(INVINERTIA, REAL, N, 0, -1, SETUP(invinertia), PARTICLES, P(1), NO)                                           \
    ENTRY(INVVOL, REAL, N, 0, -1, SETUP(invvol), PARTICLES, P(1), NO)                                                   \
    ENTRY(ROLL_INERTIA, REAL, N, DEM_EFFECT_ROLLING_SPRING, -1, SETUP(roll_inertia), PARTICLES, P(1), NO)               \
    ENTRY(MDR_PART, REAL, MDR_P_STRIDE * N, DEM_EFFECT_MDR, -1, SETUP(mdr_part), PARTICLES, P(MDR_P_STRIDE), CK(mdr_particle, MDR_P_STRIDE, NULL)) \
    ENTRY(R_BUILD, REAL, N, DEM_EFFECT_MDR, -1, SETUP(radius), PARTICLES, P(1), NO)                                    \
    ENTRY(X_BUILD, REAL, 3 * N, 0, DEM_FIELD_X_BUILD, SETUP(x), PARTICLES, P(3), NO)                                    \
    ENTRY(MAT, INT, N, 0, -1, SETUP(mat), PARTICLES, P(1), NO)                                                          \
    ENTRY(SID, INT, N, 0, -1, SETUP(sid), PARTICLES, P(1), NO)                                                          \
    ENTRY(GHOST, UINT, N, DEM_HAS_GHOSTS, -1, SETUP(ghost), PARTICLES, P(1), NO)                                        \
    ENTRY(ORDER, INT, N, 0, -1, SETUP(order), PARTICLES, STAY, NO)                                                      \
    ENTRY(LOWER, INT, N, 0, -1, NONE, PARTICLES, STAY, NO)                                                              \
    ENTRY(NBR_FILL, INT, N, 0, -1, NONE, ROWS, STAY, NO)                                                                \
    ENTRY(OLD_SLOT, INT, N, 0, -1, SETUP(identity), PARTICLES, P(1), NO)                                                \
    ENTRY(PAIRMAT, REAL, PM_STRIDE * NMAT * NMAT, 0, -1, SETUP(pairmat), PARTICLES, STAY, NO)                           \
    ENTRY(WALL_INT, INT, WI_STRIDE * NW, 0, -1, SETUP(wall_int), WALLS, STAY, NO)                                       \
    ENTRY(WALL_REAL, REAL, W_STRIDE * NW, 0, DEM_FIELD_WALL_REAL, SETUP(wall_real), WALLS, STAY, NO)                    \
    ENTRY(WALL_HIST, REAL, 3 * N * NW, DEM_EFFECT_FRICTION, DEM_FIELD_WALL_HIST, NONE, WALLS, P(3 * NW), CK(wall_hist, 1, "N")) \
    ENTRY(WALL_PF, REAL, 3 * N * NW, DEM_KEEP_WALL_FORCES, DEM_FIELD_WALL_PF, NONE, WALLS, G(3), CK_OPT(wall_pf, 1, "N")) \
    ENTRY(WALL_MASK, UINT, N, 0, DEM_FIELD_WALL_MASK, NONE, WALLS, P(1), CK(wall_mask, 1, NULL))                        \
    ENTRY(WALL_LAW, REAL, LAWW * N * NW, DEM_LAW_STATE_BITS, -1, NONE, WALLS, P(LAWW * NW), CK(wall_law, 1, "m"))       \
    ENTRY(WALL_RSPRING, REAL, 3 * N * NW, DEM_EFFECT_ROLLING_SPRING, -1, NONE, WALLS, P(3 * NW), CK(wall_rspring, 1, "N m")) \
    ENTRY(PARTIAL, UINT, EXACT_WORDS * WP_STRIDE * NBR * NW, 0, -1, NONE, WALLS, STAY, NO)                              \
    ENTRY(PARTIAL_MID, UINT, EXACT_WORDS * WP_STRIDE * NMR * NW, 0, -1, NONE, WALLS, STAY, NO)                          \
    ENTRY(WALL_FORCE, REAL, 3 * NW, 0, DEM_FIELD_WALL_FORCE, NONE, WALLS, STAY, CK(wall_force, 3, "N"))                 \
    ENTRY(WALL_NFORCE, REAL, NW, 0, DEM_FIELD_WALL_NORMAL_FORCE, NONE, WALLS, STAY, CK_OPT(wall_normal_force, 1, "N"))  \
    ENTRY(SERIES_RING, REAL, SE_STRIDE * N * NSR, DEM_GATE_LAZY, -1, NONE, OUTPUT, G(SE_STRIDE), NO)                    \
    ENTRY(SERIES_WALL, REAL, WP_STRIDE * NW * NSR, DEM_GATE_LAZY, -1, NONE, OUTPUT, STAY, NO)                           \
    ENTRY(CELL_OF, INT, N, 0, -1, NONE, CELLS, STAY, NO)                                                                \
    ENTRY(CELL_COUNT, INT, NC, 0, -1, NONE, CELLS, STAY, NO)                                                            \
    ENTRY(CELL_START, INT, NC + 1, 0, DEM_FIELD_CELL_START, NONE, CELLS, STAY, NO)                                      \
    ENTRY(CELL_PARTICLES, INT, N, 0, DEM_FIELD_CELL_PARTICLES, NONE, CELLS, STAY, NO)                                   \
    ENTRY(BLOCK_SUM, INT, NBS, 0, -1, NONE, CELLS, STAY, NO)                                                            \
    ENTRY(FLAGS, INT, FLAG_COUNT, 0, DEM_FIELD_FLAGS, NONE, PARTICLES, STAY, NO)                                        \
    ENTRY(IN_COUNT, INT, N, 0, -1, NONE, PARTICLES, STAY, NO)                                                           \
    ENTRY(IN_START, INT, N + 1, 0, DEM_FIELD_IN_START, NONE, PARTICLES, STAY, NO)                                       \
    ENTRY(IN_BLOCK_SUM, INT, (N + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK, 0, -1, NONE, PARTICLES, STAY, NO)               \
    ENTRY(OWN_COUNT, INT, N, 0, -1, NONE, PARTICLES, STAY, NO)                                                          \
    ENTRY(OWN_START, INT, N + 1, 0, -1, NONE, PARTICLES, P(1), NO)                                                      \
    ENTRY(OWN_BLOCK_SUM, INT, (N + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK, 0, -1, NONE, PARTICLES, STAY, NO)              \
    ENTRY(PAIR_HOST, INT, PAIRS, 0, -1, NONE, PAIRS, STAY, NO)                                                          \
    ENTRY(PAIR_GUEST, INT, PAIRS, 0, -1, NONE, PAIRS, STAY, NO)                                                         \
    ENTRY(PAIR_SLOT, INT, PAIRS, DEM_EFFECT_MC_STRAIN, -1, NONE, PAIRS, STAY, NO)                                       \
    ENTRY(IN_PAIR, INT, PAIRS, 0, DEM_FIELD_IN_PAIR, NONE, PAIRS, STAY, NO)                                             \
    ENTRY(PAIR_MIRROR, INT, PAIRS, DEM_EFFECT_MC_STRAIN, -1, NONE, PAIRS, STAY, NO)                                     \
    ENTRY(TOUCH, BYTE, PAIRS, 0, DEM_FIELD_TOUCH, NONE, PAIRS, STAY, NO)                                                \
    ENTRY(TOUCH_OLD, BYTE, PAIRS, 0, -1, NONE, PAIRS, STAY, NO)                                                         \
    ENTRY(TOUCH_NEXT, BYTE, PAIRS, DEM_ONE_PASS, -1, NONE, PAIRS, STAY, NO)                                             \
    ENTRY(PAIR, REAL, PR_STRIDE * PAIRS, 0, DEM_FIELD_PAIR_RECORDS, NONE, PAIRS, STAY, NO)                              \
    ENTRY(PAIR_ELA, REAL, PAIRS, DEM_KEEP_PAIR_ENERGY, -1, NONE, PAIRS, STAY, NO)                                       \
    ENTRY(PAIR_MC_FN, REAL, PAIRS, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_FORCE, NONE, PAIRS, STAY, NO)                     \
    ENTRY(PAIR_HIST, REAL, 3 * PAIRS, DEM_EFFECT_FRICTION, DEM_FIELD_HIST, NONE, PAIRS, STAY, NO)                       \
    ENTRY(PAIR_HIST_NEXT, REAL, 3 * PAIRS, DEM_ONE_PASS_HIST, -1, NONE, PAIRS, STAY, NO)                                \
    ENTRY(PAIR_LAW, REAL, LAWP * PAIRS, DEM_LAW_STATE_BITS, -1, NONE, PAIRS, STAY, NO)                                  \
    ENTRY(PAIR_MDR_SUM, REAL, 2 * MDR_NSUM * PAIRS, DEM_EFFECT_MDR, -1, NONE, PAIRS, STAY, NO)                          \
    ENTRY(PAIR_ROLL, REAL, 3 * PAIRS, DEM_EFFECT_ROLLING, -1, NONE, PAIRS, STAY, NO)                                     \
    ENTRY(PAIR_LAW_OLD, REAL, LAWP * PAIRS, DEM_LAW_STATE_BITS, -1, NONE, PAIRS, STAY, NO)                              \
    ENTRY(PAIR_RSPRING, REAL, 3 * PAIRS, DEM_EFFECT_ROLLING_SPRING, -1, NONE, PAIRS, STAY, NO)                          \
    ENTRY(PAIR_RSPRING_OLD, REAL, 3 * PAIRS, DEM_EFFECT_ROLLING_SPRING, -1, NONE, PAIRS, STAY, NO)                      \
    ENTRY(OWN_START_OLD, INT, N + 1, 0, -1, NONE, PARTICLES, STAY, NO)                                                  \
    ENTRY(TRACE, REAL, N, DEM_EFFECT_MC_STRESS, DEM_FIELD_STRESS_TRACE, NONE, PARTICLES, P(1), NO)                      \
    ENTRY(STRESS, REAL, ST_STRIDE * N, DEM_GATE_LAZY, DEM_FIELD_STRESS, NONE, OUTPUT, P(ST_STRIDE), NO)                 \
    ENTRY(MC_WALL_FN, REAL, N * NW, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_WALL_FORCE, NONE, WALLS, P(NW), CK(wall_mc_fn, 1, "N")) \
    ENTRY(MC_WALL_DISP, REAL, N * NW, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_WALL_DISP, NONE, WALLS, P(NW), CK_OPT(wall_mc_disp, 1, "m")) \
    ENTRY(MC_DISP, REAL, MAXC > PAIRS ? MAXC : PAIRS, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_DISP, NONE, ROWS, STAY, NO)    \
    ENTRY(SPRING_INT, INT, 2 * NS, DEM_EFFECT_SPRINGS, -1, SETUP(spring_int), MESH, STAY, NO)                           \
    ENTRY(SPRING_REAL, REAL, SP_STRIDE * NS, DEM_EFFECT_SPRINGS, -1, SETUP(spring_real), MESH, STAY, NO)                \
    ENTRY(TRI, INT, 3 * NT, (DEM_EFFECT_PRESSURE | DEM_EFFECT_PATCHES), -1, SETUP(tri), MESH, STAY, NO)                 \
    ENTRY(HINGE_INT, INT, 4 * NH, DEM_EFFECT_BENDING, -1, SETUP(hinge_int), MESH, STAY, NO)                             \
    ENTRY(HINGE_REAL, REAL, HG_STRIDE * NH, DEM_EFFECT_BENDING, -1, SETUP(hinge_real), MESH, STAY, NO)                  \
    ENTRY(CHAN_SLOT, INT, 2 * NS + 3 * NT + 4 * NH, DEM_EFFECT_CHANNEL, -1, SETUP(chan_slot), MESH, STAY, NO)           \
    ENTRY(CHAN_START, INT, N + 1, DEM_EFFECT_CHANNEL, -1, SETUP(chan_start), MESH, STAY, NO)                            \
    ENTRY(CHAN_REC, REAL, 3 * (2 * NS + 3 * NT + 4 * NH), DEM_EFFECT_CHANNEL, -1, NONE, MESH, STAY, NO)                 \
    ENTRY(RIDER_INT, INT, 2 * NR, 0, -1, SETUP(rider_int), MESH, STAY, NO)                                              \
    ENTRY(RIDER_OFF, REAL, 3 * NR, 0, -1, SETUP(rider_off), MESH, STAY, NO)                                             \
    ENTRY(RIDE, UINT, N, DEM_EFFECT_RIDERS, -1, SETUP(ride), MESH, P(1), NO)                                            \
    ENTRY(HOLD, UINT, N, DEM_EFFECT_CONSTRAINTS, -1, SETUP(hold), MESH, P(1), NO)                                       \
    ENTRY(VTRI_START, INT, N + 1, DEM_EFFECT_PATCHES, -1, SETUP(vtri_start), MESH, STAY, NO)                            \
    ENTRY(VTRI_LIST, INT, 3 * NT, DEM_EFFECT_PATCHES, -1, SETUP(vtri_list), MESH, STAY, NO)                             \
    ENTRY(PCOUNT, INT, N, DEM_EFFECT_PATCHES, -1, NONE, MESH, P(1), NO)                                                 \
    ENTRY(PLIST, INT, N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH, P(MAXP), NO)                                        \
    ENTRY(PHIST, REAL, 3 * N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH, P(3 * MAXP), NO)                               \
    ENTRY(PTOUCH, BYTE, N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH, P(MAXP), NO)                                      \
    ENTRY(PREC, REAL, PK_STRIDE * N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH, STAY, NO)                               \
    ENTRY(OLD_PCOUNT, INT, N, DEM_EFFECT_PATCHES, -1, NONE, MESH, STAY, NO)                                             \
    ENTRY(OLD_PLIST, INT, N * MAXPO, DEM_EFFECT_PATCHES, -1, NONE, MESH, STAY, NO)                                      \
    ENTRY(OLD_PHIST, REAL, 3 * N * MAXPO, DEM_EFFECT_PATCHES, -1, NONE, MESH, STAY, NO)                                 \
    ENTRY(OLD_PTOUCH, BYTE, N * MAXPO, DEM_EFFECT_PATCHES, -1, NONE, MESH, STAY, NO)                                    \
    ENTRY(VCOUNT, INT, N, DEM_EFFECT_PATCHES, -1, NONE, MESH, STAY, NO)                                                 \
    ENTRY(VLIST, INT, N * MAXV, DEM_EFFECT_PATCHES, -1, NONE, MESH, STAY, NO)                                           \
    ENTRY(HALO_IDX, INT, NHALO, 0, -1, NONE, PARTICLES, STAY, NO)                                                       \
    ENTRY(HALO_BUF, REAL, HALO_W * NHALO, 0, -1, NONE, PARTICLES, STAY, NO)                                             \
    ENTRY(MOVE_X0, REAL, 3 * N, DEM_HAS_GHOSTS, -1, NONE, PARTICLES, P(3), NO)                                          \
    ENTRY(MOVE_PREV, REAL, 3 * N, DEM_HAS_GHOSTS, -1, NONE, PARTICLES, P(3), NO)                                        \
    ENTRY(MOVE_MAX, REAL, 2 * NBR, DEM_HAS_GHOSTS, -1, NONE, PARTICLES, STAY, NO)                                       \
    DEM_BUFFERS_TEST(ENTRY)

/* ENTRY(ID, element, count, gate, field) - neighbour-row buffers: two sets, the current rows and the rows being built
 * (swapped at each rebuild); the field names the current set's. Row i is list[start[i] .. start[i] + count[i]),
 * start the exclusive prefix sum of count (start[n]: the slots in use); a value kept per row slot (MC_DISP, held for
 * the current set only) is at the same index. */
#define DEM_ROWS(ENTRY)                                                                                                  \
    ENTRY(COUNT, INT, N, 0, DEM_FIELD_NBR_COUNT)                                                                        \
    ENTRY(START, INT, N + 1, 0, DEM_FIELD_NBR_START)                                                                    \
    ENTRY(LIST, INT, MAXN, 0, DEM_FIELD_NBR_LIST)

/* ENTRY(ID) - a kernel argument whose buffer the driver chooses at each launch (the scan's operands, the per-particle
 * buffer a split run's halo_pack_rows and halo_unpack_rows copy) */
#define DEM_ALIASES(ENTRY) ENTRY(SCAN_COUNT) ENTRY(SCAN_BLOCK_SUM) ENTRY(SCAN_START) ENTRY(HALO_ROWS)

/* ENTRY(ID) - scalar kernel arguments (the cells: NCELLS in use, NCX..NCZ in use per axis from the domain's cell
 * CX0..CZ0 on, DCX..DCZ the domain's per axis: binning.h) */
#define DEM_SCALARS_INT(ENTRY)                                                                                       \
    ENTRY(N) ENTRY(NMAT) ENTRY(NWALLS) ENTRY(NCELLS) ENTRY(NBLOCKS_RED) ENTRY(NMID_RED) ENTRY(NCX) ENTRY(NCY) ENTRY(NCZ) ENTRY(DCX)     \
    ENTRY(DCY) ENTRY(DCZ) ENTRY(CX0) ENTRY(CY0) ENTRY(CZ0) ENTRY(NSPRINGS)                                              \
    ENTRY(NTRIANGLES) ENTRY(NHINGES) ENTRY(NRIDERS) ENTRY(MAXP) ENTRY(MAXPO) ENTRY(MAXV)                                \
    ENTRY(SCAN_ITEMS) ENTRY(SCAN_NBLOCKS) ENTRY(NPAIRS)                                                                 \
    ENTRY(SERIES_ROW) ENTRY(SERIES_SAMPLE) ENTRY(NSEND) ENTRY(NRECV) ENTRY(HALO_WIDTH)
#define DEM_SCALARS_REAL(ENTRY)                                                                                      \
    ENTRY(DT) ENTRY(SKIN) ENTRY(HALF_SKIN2) ENTRY(INV_CELL) ENTRY(LOX) ENTRY(LOY) ENTRY(LOZ) ENTRY(GX) ENTRY(GY)        \
    ENTRY(GZ) ENTRY(MC_TOL) ENTRY(PRESSURE) ENTRY(REACH) ENTRY(RMAX)

#define DEM_ENUM_BUF(id, elem, count, gate, field, init, part, move, ckpt) BUF_##id,
#define DEM_ENUM_ROW(id, elem, count, gate, field) ROW_##id,
#define DEM_ENUM_ID(id) id,
enum { DEM_BUFFERS(DEM_ENUM_BUF) BUF__COUNT };
enum { DEM_ROWS(DEM_ENUM_ROW) ROW__COUNT };
#define DEM_ENUM_ALIAS(id) ALIAS_##id,
enum { DEM_ALIASES(DEM_ENUM_ALIAS) ALIAS__COUNT };
#define DEM_ENUM_SI(id) SI_##id,
#define DEM_ENUM_SR(id) SR_##id,
enum { DEM_SCALARS_INT(DEM_ENUM_SI) SI__COUNT };
enum { DEM_SCALARS_REAL(DEM_ENUM_SR) SR__COUNT };
#undef DEM_ENUM_BUF
#undef DEM_ENUM_ROW
#undef DEM_ENUM_ID
#undef DEM_ENUM_ALIAS
#undef DEM_ENUM_SI
#undef DEM_ENUM_SR

/* element types of the registry, for the kernels' lists to be checked against (backend/backend.c) */
#define DEM_ELEM_OF_real DEM_ELEM_REAL
#define DEM_ELEM_OF_int DEM_ELEM_INT
#define DEM_ELEM_OF_unsigned DEM_ELEM_UINT
#define DEM_ELEM_OF_dem_byte DEM_ELEM_BYTE
#endif /* DEM_BUFFERS_H */
