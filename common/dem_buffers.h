/* dem_buffers.h - the one registry of device buffers and kernel scalars (issue 18): name, element type, size rule, the
 * effect that gates it, the field it is read and written as, and what it starts from. The backends create, grow,
 * look up and destroy buffers by walking it (backend/backend.c); the kernels' argument lists (dem_kernels.h) name their
 * sources here. Host only: the kernels see plain pointers.
 *
 * Size rules are expressions of the dimensions N (particles), NMAT (materials), NW (walls), NC (cells held: those of
 * the particles' bounding box at a build, binning.h, with room to spare; host/steps/binning.c), NBS (scan
 * blocks of the cells), NBR (reduction blocks of the particles), MAXN (slots of the row set the buffer belongs to:
 * its rows are packed one after the other, row i from start[i], so MAXN is what all its rows hold together, with
 * room to spare: host/core/rebuild.c row_capacity), MAXC (slots of the current row set: for a buffer laid out like the rows
 * but written before it is read after each rebuild, so held once and not in both sets; host/steps/neighbor.c grows it with
 * the current set), PAIRS (pair
 * records allocated), NS (springs), NT (triangles), NH (hinges), NR (riders), MAXP, MAXPO and MAXV (capacity of the
 * sphere patch rows, of the old ones a rebuild carries history from, of the vertex rows: patch_contacts.h), in
 * elements.
 * Gate: the effect bit (dem_effects.h) without which the buffer is empty; 0 for always; DEM_GATE_LAZY for a buffer
 * made when first needed (the output stress tensor).
 * Init: what create uploads: SETUP(member) of dem_setup, or NONE (zero-filled).
 */
#ifndef DEM_BUFFERS_H
#define DEM_BUFFERS_H
#include "dem_layout.h"
#include "../include/dem_effects.h"

/* element types */
enum { DEM_ELEM_REAL, DEM_ELEM_INT, DEM_ELEM_UINT, DEM_ELEM_BYTE };
#define DEM_GATE_LAZY 0x80000000u

/* ENTRY(ID, element, count, gate, field, init, part) - buffers that exist once; part: what they hold, for the memory
 * report (dem_memory_part in dem.h: PARTICLES, PAIRS, WALLS, CELLS, OUTPUT, MESH; the row sets are ROWS) */
#define DEM_BUFFERS(ENTRY)                                                                                               \
    ENTRY(X, REAL, 3 * N, 0, DEM_FIELD_X, SETUP(x), PARTICLES)                                                          \
    ENTRY(V, REAL, 3 * N, 0, DEM_FIELD_V, SETUP(v), PARTICLES)                                                          \
    ENTRY(W, REAL, 3 * N, 0, DEM_FIELD_W, SETUP(w), PARTICLES)                                                          \
    ENTRY(FORCE, REAL, 3 * N, 0, DEM_FIELD_FORCE, NONE, PARTICLES)                                                      \
    ENTRY(TORQUE, REAL, 3 * N, 0, DEM_FIELD_TORQUE, NONE, PARTICLES)                                                    \
    ENTRY(RADIUS, REAL, N, 0, -1, SETUP(radius), PARTICLES)                                                             \
    ENTRY(INVMASS, REAL, N, 0, -1, SETUP(invmass), PARTICLES)                                                           \
    ENTRY(INVINERTIA, REAL, N, 0, -1, SETUP(invinertia), PARTICLES)                                                     \
    ENTRY(INVVOL, REAL, N, 0, -1, SETUP(invvol), PARTICLES)                                                             \
    ENTRY(X_BUILD, REAL, 3 * N, 0, DEM_FIELD_X_BUILD, SETUP(x), PARTICLES)                                              \
    ENTRY(MAT, INT, N, 0, -1, SETUP(mat), PARTICLES)                                                                    \
    ENTRY(SID, INT, N, 0, -1, SETUP(sid), PARTICLES)                                                                    \
    ENTRY(ORDER, INT, N, 0, -1, SETUP(order), PARTICLES)                                                                \
    ENTRY(LOWER, INT, N, 0, -1, NONE, PARTICLES)                                                                        \
    ENTRY(NBR_FILL, INT, N, 0, -1, NONE, ROWS)                                                                          \
    ENTRY(OLD_SLOT, INT, N, 0, -1, SETUP(identity), PARTICLES)                                                          \
    ENTRY(PAIRMAT, REAL, PM_STRIDE * NMAT * NMAT, 0, -1, SETUP(pairmat), PARTICLES)                                     \
    ENTRY(WALL_INT, INT, WI_STRIDE * NW, 0, -1, SETUP(wall_int), WALLS)                                                 \
    ENTRY(WALL_REAL, REAL, W_STRIDE * NW, 0, DEM_FIELD_WALL_REAL, SETUP(wall_real), WALLS)                              \
    ENTRY(WALL_HIST, REAL, 3 * N * NW, DEM_EFFECT_FRICTION, DEM_FIELD_WALL_HIST, NONE, WALLS)                           \
    ENTRY(WALL_PF, REAL, 3 * N * NW, DEM_KEEP_WALL_FORCES, DEM_FIELD_WALL_PF, NONE, WALLS)                              \
    ENTRY(WALL_MASK, UINT, N, 0, DEM_FIELD_WALL_MASK, NONE, WALLS)                                                      \
    ENTRY(PARTIAL, REAL, WP_STRIDE * NBR * NW, 0, -1, NONE, WALLS)                                                      \
    ENTRY(WALL_FORCE, REAL, 3 * NW, 0, DEM_FIELD_WALL_FORCE, NONE, WALLS)                                               \
    ENTRY(WALL_NFORCE, REAL, NW, 0, DEM_FIELD_WALL_NORMAL_FORCE, NONE, WALLS)                                           \
    ENTRY(SERIES_RING, REAL, SE_STRIDE * N * NSR, DEM_GATE_LAZY, -1, NONE, OUTPUT)                                      \
    ENTRY(SERIES_WALL, REAL, WP_STRIDE * NW * NBR * NSR, DEM_GATE_LAZY, -1, NONE, OUTPUT)                               \
    ENTRY(CELL_OF, INT, N, 0, -1, NONE, CELLS)                                                                          \
    ENTRY(CELL_COUNT, INT, NC, 0, -1, NONE, CELLS)                                                                      \
    ENTRY(CELL_START, INT, NC + 1, 0, DEM_FIELD_CELL_START, NONE, CELLS)                                                \
    ENTRY(CELL_PARTICLES, INT, N, 0, DEM_FIELD_CELL_PARTICLES, NONE, CELLS)                                             \
    ENTRY(BLOCK_SUM, INT, NBS, 0, -1, NONE, CELLS)                                                                      \
    ENTRY(FLAGS, INT, FLAG_COUNT, 0, DEM_FIELD_FLAGS, NONE, PARTICLES)                                                  \
    ENTRY(IN_COUNT, INT, N, 0, -1, NONE, PARTICLES)                                                                     \
    ENTRY(IN_START, INT, N + 1, 0, DEM_FIELD_IN_START, NONE, PARTICLES)                                                 \
    ENTRY(IN_BLOCK_SUM, INT, (N + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK, 0, -1, NONE, PARTICLES)                         \
    ENTRY(OWN_COUNT, INT, N, 0, -1, NONE, PARTICLES)                                                                    \
    ENTRY(OWN_START, INT, N + 1, 0, -1, NONE, PARTICLES)                                                                \
    ENTRY(OWN_BLOCK_SUM, INT, (N + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK, 0, -1, NONE, PARTICLES)                        \
    ENTRY(PAIR_HOST, INT, PAIRS, 0, -1, NONE, PAIRS)                                                                    \
    ENTRY(PAIR_GUEST, INT, PAIRS, 0, -1, NONE, PAIRS)                                                                   \
    ENTRY(PAIR_SLOT, INT, PAIRS, DEM_EFFECT_MC_STRAIN, -1, NONE, PAIRS)                                                 \
    ENTRY(IN_PAIR, INT, PAIRS, 0, DEM_FIELD_IN_PAIR, NONE, PAIRS)                                                       \
    ENTRY(PAIR_MIRROR, INT, PAIRS, DEM_EFFECT_MC_STRAIN, -1, NONE, PAIRS)                                               \
    ENTRY(TOUCH, BYTE, PAIRS, 0, DEM_FIELD_TOUCH, NONE, PAIRS)                                                          \
    ENTRY(TOUCH_OLD, BYTE, PAIRS, 0, -1, NONE, PAIRS)                                                                   \
    ENTRY(PAIR, REAL, PR_STRIDE * PAIRS, 0, DEM_FIELD_PAIR_RECORDS, NONE, PAIRS)                                        \
    ENTRY(PAIR_ELA, REAL, PAIRS, DEM_KEEP_PAIR_ENERGY, -1, NONE, PAIRS)                                                 \
    ENTRY(PAIR_MC_FN, REAL, PAIRS, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_FORCE, NONE, PAIRS)                               \
    ENTRY(PAIR_HIST, REAL, 3 * PAIRS, DEM_EFFECT_FRICTION, DEM_FIELD_HIST, NONE, PAIRS)                                 \
    ENTRY(OWN_START_OLD, INT, N + 1, 0, -1, NONE, PARTICLES)                                                            \
    ENTRY(TRACE, REAL, N, DEM_EFFECT_MC_STRESS, DEM_FIELD_STRESS_TRACE, NONE, PARTICLES)                                \
    ENTRY(STRESS, REAL, ST_STRIDE * N, DEM_GATE_LAZY, DEM_FIELD_STRESS, NONE, OUTPUT)                                   \
    ENTRY(MC_WALL_FN, REAL, N * NW, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_WALL_FORCE, NONE, WALLS)                         \
    ENTRY(MC_WALL_DISP, REAL, N * NW, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_WALL_DISP, NONE, WALLS)                        \
    ENTRY(MC_DISP, REAL, MAXC > PAIRS ? MAXC : PAIRS, DEM_EFFECT_MC_STRAIN, DEM_FIELD_MC_DISP, NONE, ROWS)                                 \
    ENTRY(SPRING_INT, INT, 2 * NS, DEM_EFFECT_SPRINGS, -1, SETUP(spring_int), MESH)                                     \
    ENTRY(SPRING_REAL, REAL, SP_STRIDE * NS, DEM_EFFECT_SPRINGS, -1, SETUP(spring_real), MESH)                          \
    ENTRY(TRI, INT, 3 * NT, (DEM_EFFECT_PRESSURE | DEM_EFFECT_PATCHES), -1, SETUP(tri), MESH)                           \
    ENTRY(HINGE_INT, INT, 4 * NH, DEM_EFFECT_BENDING, -1, SETUP(hinge_int), MESH)                                       \
    ENTRY(HINGE_REAL, REAL, HG_STRIDE * NH, DEM_EFFECT_BENDING, -1, SETUP(hinge_real), MESH)                            \
    ENTRY(CHAN_SLOT, INT, 2 * NS + 3 * NT + 4 * NH, DEM_EFFECT_CHANNEL, -1, SETUP(chan_slot), MESH)                     \
    ENTRY(CHAN_START, INT, N + 1, DEM_EFFECT_CHANNEL, -1, SETUP(chan_start), MESH)                                      \
    ENTRY(CHAN_REC, REAL, 3 * (2 * NS + 3 * NT + 4 * NH), DEM_EFFECT_CHANNEL, -1, NONE, MESH)                           \
    ENTRY(RIDER_INT, INT, 2 * NR, 0, -1, SETUP(rider_int), MESH)                                                        \
    ENTRY(RIDER_OFF, REAL, 3 * NR, 0, -1, SETUP(rider_off), MESH)                                                       \
    ENTRY(RIDE, UINT, N, DEM_EFFECT_RIDERS, -1, SETUP(ride), MESH)                                                      \
    ENTRY(HOLD, UINT, N, DEM_EFFECT_CONSTRAINTS, -1, SETUP(hold), MESH)                                                 \
    ENTRY(VTRI_START, INT, N + 1, DEM_EFFECT_PATCHES, -1, SETUP(vtri_start), MESH)                                      \
    ENTRY(VTRI_LIST, INT, 3 * NT, DEM_EFFECT_PATCHES, -1, SETUP(vtri_list), MESH)                                       \
    ENTRY(PCOUNT, INT, N, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                                           \
    ENTRY(PLIST, INT, N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                                     \
    ENTRY(PHIST, REAL, 3 * N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                                \
    ENTRY(PTOUCH, BYTE, N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                                   \
    ENTRY(PREC, REAL, PK_STRIDE * N * MAXP, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                         \
    ENTRY(OLD_PCOUNT, INT, N, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                                       \
    ENTRY(OLD_PLIST, INT, N * MAXPO, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                                \
    ENTRY(OLD_PHIST, REAL, 3 * N * MAXPO, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                           \
    ENTRY(OLD_PTOUCH, BYTE, N * MAXPO, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                              \
    ENTRY(VCOUNT, INT, N, DEM_EFFECT_PATCHES, -1, NONE, MESH)                                                           \
    ENTRY(VLIST, INT, N * MAXV, DEM_EFFECT_PATCHES, -1, NONE, MESH)

/* ENTRY(ID, element, count, gate, field) - neighbour-row buffers: two sets, the current rows and the rows being built
 * (swapped at each rebuild); the field names the current set's. Row i is list[start[i] .. start[i] + count[i]),
 * start the exclusive prefix sum of count (start[n]: the slots in use); a value kept per row slot (MC_DISP, held for
 * the current set only) is at the same index. */
#define DEM_ROWS(ENTRY)                                                                                                  \
    ENTRY(COUNT, INT, N, 0, DEM_FIELD_NBR_COUNT)                                                                             \
    ENTRY(START, INT, N + 1, 0, DEM_FIELD_NBR_START)                                                                         \
    ENTRY(LIST, INT, MAXN, 0, DEM_FIELD_NBR_LIST)

/* ENTRY(ID) - a kernel argument whose buffer the driver chooses at each launch (the scan's operands) */
#define DEM_ALIASES(ENTRY) ENTRY(SCAN_COUNT) ENTRY(SCAN_BLOCK_SUM) ENTRY(SCAN_START)

/* ENTRY(ID) - scalar kernel arguments (the cells: NCELLS in use, NCX..NCZ in use per axis from the domain's cell
 * CX0..CZ0 on, DCX..DCZ the domain's per axis: binning.h) */
#define DEM_SCALARS_INT(ENTRY)                                                                                       \
    ENTRY(N) ENTRY(NMAT) ENTRY(NWALLS) ENTRY(NCELLS) ENTRY(NBLOCKS_RED) ENTRY(NCX) ENTRY(NCY) ENTRY(NCZ) ENTRY(DCX)      \
    ENTRY(DCY) ENTRY(DCZ) ENTRY(CX0) ENTRY(CY0) ENTRY(CZ0) ENTRY(NSPRINGS) \
    ENTRY(NTRIANGLES) ENTRY(NHINGES) ENTRY(NRIDERS) ENTRY(MAXP) ENTRY(MAXPO) ENTRY(MAXV)                            \
    ENTRY(SCAN_ITEMS) ENTRY(SCAN_NBLOCKS) ENTRY(NPAIRS)                  \
    ENTRY(SERIES_ROW) ENTRY(SERIES_SAMPLE)
#define DEM_SCALARS_REAL(ENTRY)                                                                                      \
    ENTRY(DT) ENTRY(SKIN) ENTRY(HALF_SKIN2) ENTRY(INV_CELL) ENTRY(LOX) ENTRY(LOY) ENTRY(LOZ) ENTRY(GX) ENTRY(GY)       \
    ENTRY(GZ) ENTRY(MC_TOL) ENTRY(PRESSURE) ENTRY(REACH) ENTRY(RMAX)

#define DEM_ENUM_BUF(id, elem, count, gate, field, init, part) BUF_##id,
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
