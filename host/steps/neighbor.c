/* neighbor.c - the neighbour-row steps (common/neighbor.h): the rows' lengths and starts, the slots of the rows
 * being built, the fill, and the commit (history carried into the new rows, which become current; pair-record
 * offsets; x_build). Written once for every backend. */
#include "backend.h"

int dem_stage_nbr_count(const dem_backend_ops *o, dem_backend *b, int *slots)
{
    dem_core *c = DEM_CORE(b);
    /* the scan's block sums in the incoming pairs' (free until the commit scans them) */
    dem_bufref count = {TABLE_NEW, ROW_COUNT}, start = {TABLE_NEW, ROW_START}, sums = {TABLE_ONE, BUF_IN_BLOCK_SUM};
    return o->fill_int(b, count, 0, (size_t)c->n) || dem_launch(o, b, K_nbr_count) ||
           dem_stage_scan(o, b, count, start, sums, c->n) ||
           o->read(b, start, (size_t)c->n * sizeof(int), slots, sizeof *slots, 1);
}

int dem_stage_nbr_reserve(const dem_backend_ops *o, dem_backend *b, int slots)
{
    dem_core *c = DEM_CORE(b);
    int set = 1 - c->cur;
    if (c->maxn[set] == slots)
        return 0;
    for (int id = 0; id < ROW__COUNT; id++) { /* the lists; the counts and starts keep their size (and contents) */
        size_t bytes = dem_row_bytes(c, id, slots);
        if (bytes != c->row_bytes[set][id] && o->alloc(b, TABLE_NEW, set, id, bytes, NULL))
            return 1;
    }
    c->maxn[set] = slots;
    return 0;
}

int dem_stage_nbr_build(const dem_backend_ops *o, dem_backend *b)
{
    dem_bufref fill = {TABLE_ONE, BUF_NBR_FILL};
    return o->fill_int(b, fill, 0, (size_t)DEM_CORE(b)->n) || dem_launch(o, b, K_nbr_build) ||
           dem_launch(o, b, K_nbr_sort);
}

/* Buffer id's contents into its copy old (grown to id's size first), for pair_index to carry (0, or 1 on failure);
 * nothing for a buffer the run does not have */
static int copy_to_old(const dem_backend_ops *o, dem_backend *b, int id, int old)
{
    dem_core *c = DEM_CORE(b);
    return (c->bytes[old] != c->bytes[id] && o->alloc(b, TABLE_ONE, 0, old, c->bytes[id], NULL)) ||
           (c->bytes[id] && o->copy(b, (dem_bufref){TABLE_ONE, id}, (dem_bufref){TABLE_ONE, old}, c->bytes[id]));
}

int dem_stage_nbr_commit(const dem_backend_ops *o, dem_backend *b)
{
    dem_core *c = DEM_CORE(b);
    /* The old pair numbering, touching flags, history and MC-strain forces, which pair_index carries into the new
     * (neighbor.h). The copies of the history and the forces go into buffers that hold nothing between a build and
     * the next force pass: the pair records (contact_pairs writes the record of every pair it finds touching, and
     * every reader reads a record only where the touching flag says so; 3 reals of history per pair fit in 7 of a
     * record's) and MC-strain's displacements per row slot (mc_strain_disp writes each
     * before anything reads it; a row set has two slots per pair); both grow only after pair_index has read them.
     * Using these spaces saves a buffer of its own for the history's copy (24 bytes per pair in fp64, held all the
     * run for this moment) and MC-strain's forces per row slot in both row sets (docs/design.md "Memory in a
     * compact"). The touching flags' copy is grown here to the
     * flags' capacity (which may have grown at the last commit). */
    dem_bufref hist = {TABLE_ONE, BUF_PAIR_HIST}, rec = {TABLE_ONE, BUF_PAIR};
    dem_bufref fn = {TABLE_ONE, BUF_PAIR_MC_FN}, disp = {TABLE_ONE, BUF_MC_DISP};
    if (c->bytes[BUF_PAIR_HIST] > c->bytes[BUF_PAIR] || c->bytes[BUF_PAIR_MC_FN] > c->bytes[BUF_MC_DISP])
        return dem_core_fail(c, "the pairs' copies do not fit where they are kept for a rebuild (a library bug; please "
                                "report)");
    /* the touching flags, a law's states (laws/law.h: 8 or 4 bytes per pair, in runs of such a law) and the rolling
     * springs (rolling.h: 24 or 12, with DEM_EFFECT_ROLLING_SPRING) have copy buffers of their own */
    if (copy_to_old(o, b, BUF_TOUCH, BUF_TOUCH_OLD) || copy_to_old(o, b, BUF_PAIR_LAW, BUF_PAIR_LAW_OLD) ||
        copy_to_old(o, b, BUF_PAIR_RSPRING, BUF_PAIR_RSPRING_OLD) ||
        (c->bytes[BUF_PAIR_HIST] && o->copy(b, hist, rec, c->bytes[BUF_PAIR_HIST])) ||
        (c->bytes[BUF_PAIR_MC_FN] && o->copy(b, fn, disp, c->bytes[BUF_PAIR_MC_FN])))
        return 1;
    dem_bufref own = {TABLE_ONE, BUF_OWN_START}, old_own = {TABLE_ONE, BUF_OWN_START_OLD};
    if (o->copy(b, own, old_own, c->bytes[BUF_OWN_START]))
        return 1;
    c->cur = 1 - c->cur;
    int total = 0, owned = 0;
    dem_bufref start = {TABLE_ONE, BUF_IN_START};
    dem_bufref in_count = {TABLE_ONE, BUF_IN_COUNT}, in_sums = {TABLE_ONE, BUF_IN_BLOCK_SUM};
    dem_bufref own_count = {TABLE_ONE, BUF_OWN_COUNT}, own_sums = {TABLE_ONE, BUF_OWN_BLOCK_SUM};
    if (dem_stage_scan(o, b, in_count, start, in_sums, c->n) || dem_stage_scan(o, b, own_count, own, own_sums, c->n) ||
        o->read(b, start, (size_t)c->n * sizeof(int), &total, sizeof total, 1) ||
        o->read(b, own, (size_t)c->n * sizeof(int), &owned, sizeof owned, 1))
        return 1;
    if (owned != total) /* every pair is owned by one row and mirrored in one other (pair_index checks symmetry) */
        return dem_core_fail(c, "neighbour rows list %d owned and %d incoming pairs (a library bug; please report)",
                             owned, total);
    /* 1/8 to spare: the pair arrays are two thirds of the memory, and growing them costs one allocation at a rebuild
     * (the history and flags are carried from their copies either way) */
    int grow = (size_t)total > c->pair_cap || c->bytes[BUF_PAIR] == 0;
    if (grow) {
        c->pair_cap = (size_t)total + (size_t)total / 8 + 16;
        /* the pair-sized buffers (dem_buffers.h: PAIRS) that pair_index rewrites, and the sampled step's pair
         * energies (written before they are read in that step); the records after pair_index has read the history's
         * copy from them, the flags' copy at the next commit (above) */
        static const int grown[] = {BUF_PAIR_HOST,   BUF_PAIR_GUEST, BUF_PAIR_SLOT, BUF_IN_PAIR, BUF_PAIR_MIRROR,
                                    BUF_TOUCH,       BUF_PAIR_HIST,  BUF_PAIR_ELA,  BUF_PAIR_MC_FN,
                                    BUF_PAIR_LAW,    BUF_PAIR_ROLL,  BUF_PAIR_RSPRING, BUF_PAIR_MDR_SUM,
                                    BUF_TOUCH_NEXT,  BUF_PAIR_HIST_NEXT};
        for (size_t k = 0; k < sizeof grown / sizeof grown[0]; k++)
            if (o->alloc(b, TABLE_ONE, 0, grown[k], dem_buffer_bytes(c, grown[k]), NULL))
                return 1;
    }
    c->si[SI_NPAIRS] = total;
    dem_bufref x = {TABLE_ONE, BUF_X}, xb = {TABLE_ONE, BUF_X_BUILD};
    dem_bufref rad = {TABLE_ONE, BUF_RADIUS}, rb = {TABLE_ONE, BUF_R_BUILD};
    /* the buffers laid out like the current rows but written before they are read (dem_buffers.h: MAXC, MC-strain's
     * displacements) follow the new rows' capacity; grown only, as the two sets' capacities may alternate */
    return dem_launch(o, b, K_pair_index) ||
           (grow && o->alloc(b, TABLE_ONE, 0, BUF_PAIR, dem_buffer_bytes(c, BUF_PAIR), NULL)) ||
           (dem_buffer_bytes(c, BUF_MC_DISP) > c->bytes[BUF_MC_DISP] &&
            o->alloc(b, TABLE_ONE, 0, BUF_MC_DISP, dem_buffer_bytes(c, BUF_MC_DISP), NULL)) ||
           o->copy(b, x, xb, c->bytes[BUF_X]) ||
           (c->bytes[BUF_R_BUILD] && o->copy(b, rad, rb, c->bytes[BUF_R_BUILD])); /* MDR's radii (mdr_particle.h) */
}
