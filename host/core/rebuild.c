/* rebuild.c - the neighbour rows' rebuild (sim_rebuild): the storage order first when due (reorder.c), the skin
 * (fixed or chosen from the cost model, and its probe), the binning and its out-of-domain report, the rows' capacity
 * with room to spare, the patch rows; and the counts and grid a caller reads of it. */
#include "sim.h"
#include "dem_layout.h"
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int sim_rebuild_traced(dem_sim *s);

static int report_out_of_domain(dem_sim *s, int slot)
{
    int id = sim_api(s, slot); /* the caller's id of the particle stored there (host/core/reorder.c) */
    if (s->said_ids) /* a part of a split run: the whole run's id */
        id = (int)s->said_ids[id];
    int rs = s->setup.real_size;
    double p[3] = {NAN, NAN, NAN};
    unsigned char *buf = malloc((size_t)3 * s->n * rs);
    if (buf && dem_stage_read_field(s->ops, s->be, DEM_FIELD_X, buf, (size_t)3 * s->n * rs) == 0)
        for (int d = 0; d < 3; d++)
            p[d] = rs == 8 ? ((double *)buf)[3 * slot + d] : ((float *)buf)[3 * slot + d];
    free(buf);
    s->report.err_particle = id;
    /* under MDR, a radius held at the law's cap before it (step_loop.c): where a compact left the law's range */
    char mdr[256] = "";
    if (s->report.mdr_capped_step >= 0)
        snprintf(mdr, sizeof mdr,
                 "; before it, at step %ld, particle %ld's apparent radius had met MDR's cap of 1.5 times its own, "
                 "past which the law no longer keeps a sphere's volume (docs/laws/mdr.md \"Range\")",
                 s->report.mdr_capped_step, s->report.mdr_capped_particle);
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) /* a value that overflowed or was never a number */
        return sim_fail(s, DEM_ERR_DOMAIN,
                        "step %ld: particle %d: its position became non-finite (%g, %g, %g): a velocity or force "
                        "overflowed or was not a number (check the time step, overlaps and parameters)%s",
                        s->run.step, id, p[0], p[1], p[2], mdr);
    return sim_fail(s, DEM_ERR_DOMAIN,
                    "step %ld: particle %d at (%g, %g, %g) m is outside the binning domain [%g,%g]x[%g,%g]x[%g,%g] "
                    "(the domain rounded up to whole cells of %g m) or not finite; enlarge the domain or check the "
                    "set-up (time step, overlaps)%s",
                    s->run.step, id, p[0], p[1], p[2], s->domain.lo[0], s->domain.grid_hi[0], s->domain.lo[1], s->domain.grid_hi[1], s->domain.lo[2],
                    s->domain.grid_hi[2], s->domain.grid_cell, mdr);
}

int sim_rebuild(dem_sim *s)
{
    int e = sim_rebuild_traced(s);
    if (!e) {
        const dem_core *c = DEM_CORE(s->be);
        s->trace.nrebuild = sim_copy_trace(c, s->trace.rebuild_at, c->ntrace, s->trace.rebuild, 0);
        s->trace.rebuild_len = c->ntrace - s->trace.rebuild_at;
    }
    return e;
}

/* The patch rows (common/patch_contacts.h), built again with wider rows or a wider reach until nothing overflowed */
static int patch_rows(dem_sim *s)
{
    for (int first = 1;; first = 0) {
        int flags[FLAG_COUNT];
        if (dem_stage_patch_build(s->ops, s->be, first, s->rows.maxp, s->rows.maxv, s->rows.reach))
            return sim_be_fail(s);
        if (sim_read_flags(s, flags))
            return DEM_ERR_DEVICE;
        if (flags[FLAG_PATCH_NEEDED] <= s->rows.maxp && flags[FLAG_VROW_NEEDED] <= s->rows.maxv && !flags[FLAG_PATCH_REACH])
            return 0;
        while (s->rows.maxp < flags[FLAG_PATCH_NEEDED])
            s->rows.maxp *= 2;
        while (s->rows.maxv < flags[FLAG_VROW_NEEDED])
            s->rows.maxv *= 2;
        if (flags[FLAG_PATCH_REACH])
            s->rows.reach *= 1.5;
        flags[FLAG_PATCH_NEEDED] = flags[FLAG_VROW_NEEDED] = flags[FLAG_PATCH_REACH] = 0;
        if (dem_stage_write_field(s->ops, s->be, DEM_FIELD_FLAGS, flags, sizeof flags))
            return sim_be_fail(s);
    }
}

/* The skin of the rows about to be built. Fixed by dem_config.skin, or chosen (docs/design.md "The neighbour skin"):
 * a rebuild costs about as much as R steps, and each r_min of skin adds B of a step's cost (R / B =
 * DEM_SKIN_COST_RATIO, measured); the particles moved up to s/2 in the n steps since the last rebuild (its trigger,
 * or less when a probe rebuilds), so about u = s / (2 n) per step, and 1 + B s / r_min + R 2 u / s is least at
 * s = sqrt(R / B r_min s_old / n). Any skin gives the same bits (rows list every pair within reach; one that does
 * not touch adds nothing): this only moves the time between the steps and the rebuilds. */
static void skin_choose(dem_sim *s)
{
    if (s->rows.skin_lo < s->rows.skin_hi && s->rows.skin_built >= 0 && s->run.step > s->rows.skin_built) {
        double best = sqrt(DEM_SKIN_COST_RATIO * s->rmin * s->rows.skin_now / (double)(s->run.step - s->rows.skin_built));
        s->rows.skin_now = best < s->rows.skin_lo ? s->rows.skin_lo : best > s->rows.skin_hi ? s->rows.skin_hi : best;
    }
    s->rows.skin_built = s->run.step;
    dem_core *c = DEM_CORE(s->be);
    c->sr[SR_SKIN] = s->rows.skin_now + s->rows.skin_extra;
    c->sr[SR_HALF_SKIN2] = 0.25 * s->rows.skin_now * s->rows.skin_now;
}

/* An automatic skin above its lower end is tried smaller once the rows have lasted DEM_SKIN_PROBE steps. */
int sim_skin_probe_due(const dem_sim *s)
{
    return s->rows.skin_now > s->rows.skin_lo && s->rows.skin_built >= 0 && s->run.step - s->rows.skin_built >= DEM_SKIN_PROBE;
}

/* The slots of a row set for a build whose rows need `need` together: 1/8 to spare, so that a packing that
 * tightens grows them at one rebuild in several, not at each. The rows are packed (dem_buffers.h DEM_ROWS): each
 * slot is an int (MC-strain's displacements per slot are held for the current set only: MAXC), not each
 * as long as the longest: a compact in the press lists 17-23 partners in its longest row and about 8 in its mean one
 * (docs/design.md "Memory in a compact"). */
static int row_capacity(int need)
{
    return need + need / 8 + 16;
}

static int sim_rebuild_traced(dem_sim *s)
{
    int flags[FLAG_COUNT], e;
    if (sim_reorder_due(s) && (e = sim_reorder(s)))
        return e;
    skin_choose(s);
    s->trace.rebuild_at = DEM_CORE(s->be)->ntrace;
    if (dem_stage_bin_bounds(s->ops, s->be))
        return sim_be_fail(s);
    if (sim_read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if (flags[FLAG_OUT_OF_DOMAIN] != DEM_NO_PARTICLE)
        return report_out_of_domain(s, flags[FLAG_OUT_OF_DOMAIN]);
    if (dem_stage_bin_cells(s->ops, s->be, flags) || dem_stage_bin(s->ops, s->be))
        return sim_be_fail(s);
    /* s->rows.maxn is the current rows' slots: it changes only once new rows are committed */
    int maxn = s->rows.maxn, need = 0;
    if (dem_stage_nbr_count(s->ops, s->be, &need))
        return sim_be_fail(s);
    if (need < 0 || need > INT_MAX / 9 * 8 - 16)
        return sim_fail(s, DEM_ERR_NOMEM, "step %ld: the neighbour rows need %d slots, more than an int counts",
                        s->run.step, need);
    if (need > maxn)
        maxn = row_capacity(need);
    if (dem_stage_nbr_reserve(s->ops, s->be, maxn) || dem_stage_nbr_build(s->ops, s->be))
        return sim_be_fail(s);
    /* checked before the commit reads the rows: a row filled short of its count would hand it stale partners */
    if (sim_read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if (flags[FLAG_ASYMMETRIC])
        return sim_fail(s, DEM_ERR_STATE, "step %ld: neighbour rows are not as counted (a library bug; please report)",
                        s->run.step);
    if (dem_stage_nbr_commit(s->ops, s->be))
        return sim_be_fail(s);
    s->rows.maxn = maxn;
    if (sim_read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if (flags[FLAG_ASYMMETRIC])
        return sim_fail(s, DEM_ERR_STATE, "step %ld: neighbour rows are not symmetric (a library bug; please report)",
                        s->run.step);
    if ((s->effects & DEM_EFFECT_PATCHES) && s->mesh.npatch && (e = patch_rows(s)))
        return e;
    if (s->order.reordered) { /* the rows are numbered in the new places: where the particles were no longer matters */
        dem_bufref r = {TABLE_ONE, BUF_OLD_SLOT};
        if (s->ops->write(s->be, r, 0, s->setup.identity, sizeof(int) * (size_t)s->n, 1))
            return sim_be_fail(s);
        s->order.reordered = 0;
    }
    s->rows.rebuilds++;
    return 0;
}

int dem_neighbor_capacity(const dem_sim *s) { return sim_stepped(s)->rows.maxn; }
double dem_neighbor_skin(const dem_sim *s) { return sim_stepped(s)->rows.skin_now; }
long dem_rebuild_count(const dem_sim *s) { return sim_stepped(s)->rows.rebuilds; }
long dem_reorder_count(const dem_sim *s) { return sim_stepped(s)->order.count; }
int dem_cell_count(const dem_sim *s)
{
    return s->be ? DEM_CORE(s->be)->ncells : s->setup.cells[0] * s->setup.cells[1] * s->setup.cells[2];
}
int dem_grid_cells(const dem_sim *s, int first[3], int count[3])
{
    if (!s->run.started)
        return DEM_ERR_STATE;
    const int *si = DEM_CORE(s->be)->si;
    first[0] = si[SI_CX0], first[1] = si[SI_CY0], first[2] = si[SI_CZ0];
    count[0] = si[SI_NCX], count[1] = si[SI_NCY], count[2] = si[SI_NCZ];
    return 0;
}
int dem_grid_get(const dem_sim *s, double lo[3], double *inv_cell, int ncell[3])
{
    if (!s->run.started)
        return DEM_ERR_STATE;
    memcpy(lo, s->setup.lo, sizeof(double) * 3);
    memcpy(ncell, s->setup.ncell, sizeof(int) * 3);
    *inv_cell = s->setup.inv_cell;
    return 0;
}
