/* halo.c - ghost particles kept equal to their owners' after each step (mpi_layer.h) */
#include "mpi_layer.h"
#include "sim.h"
#include "dem_layout.h"
#include <stdlib.h>
#include <string.h>

void dem_mpi_halo_free(dem_mpi_halo *h)
{
    if (h->s && h->s->halo_ctx == h)
        h->s->halo_hook = NULL, h->s->halo_ctx = NULL;
    free(h->send_count), free(h->send_displ), free(h->send_id);
    free(h->recv_count), free(h->recv_displ), free(h->recv_id);
    free(h->field), free(h->sbuf), free(h->rbuf), free(h->msg_count);
    free(h->gid), free(h->owner);
    memset(h, 0, sizeof *h);
}

int dem_mpi_id_from(const long *ids, int n, long v) { return (int)sim_id_from(ids, n, v); }

int dem_mpi_id_at(const long *ids, int n, long v)
{
    int k = dem_mpi_id_from(ids, n, v);
    return k < n && ids[k] == v ? k : -1;
}

static int exchange(dem_mpi_halo *h, int walls);
static int mid_step(dem_sim *s, void *ctx, int event, int *value);

/* a wall stage that ends at a relative density */
static int until_density(const dem_sim *s)
{
    for (int k = 0; k < s->nwalls; k++)
        for (int st = 0; st < s->walls[k].nstages; st++)
            if (s->walls[k].stages[st].until_density > 0)
                return 1;
    return 0;
}

int dem_mpi_halo_init(dem_mpi_halo *h, MPI_Comm comm, dem_sim *s, int n, const long *gid, const int *owner)
{
    memset(h, 0, sizeof *h);
    h->comm = comm, h->s = s, h->n = n;
    MPI_Comm_rank(comm, &h->rank);
    MPI_Comm_size(comm, &h->size);
    int P = h->size, e = 0;
    /* what the halo does not carry yet: membranes */
    unsigned not_yet = DEM_EFFECT_SPRINGS |
                       DEM_EFFECT_PRESSURE | DEM_EFFECT_BENDING | DEM_EFFECT_PATCHES;
    unsigned bad = s->effects & not_yet;
    if (!s->run.started)
        e = sim_fail(s, DEM_ERR_STATE, "dem_mpi_halo_init: dem_start first");
    else if (P > 1 && bad)
        e = sim_fail(s, DEM_ERR_ARG, "a run over %d ranks does not take the effect %s yet (docs/design.md \"Runs over MPI\")",
                     P, dem_effect_name(__builtin_ctz(bad)));
    else if (P > 1 && until_density(s) && !(s->whole_volume > 0)) /* each rank would count its own spheres */
        e = sim_fail(s, DEM_ERR_ARG, "a run over %d ranks takes an until_density stage only in a run cut with "
                     "sim_part_copy (the whole scene's volume)", P);
    if ((e = dem_mpi_agreed(comm, e)))
        return e;
    h->send_count = calloc((size_t)P, sizeof(int)), h->send_displ = calloc((size_t)P, sizeof(int));
    h->recv_count = calloc((size_t)P, sizeof(int)), h->recv_displ = calloc((size_t)P, sizeof(int));
    h->recv_id = malloc(sizeof(int) * ((size_t)n + 1));
    long *want = malloc(sizeof(long) * ((size_t)n + 1)), *asked = NULL;
    if (!h->send_count || !h->send_displ || !h->recv_count || !h->recv_displ || !h->recv_id || !want)
        e = DEM_ERR_NOMEM;
    for (int k = 0; !e && k < n; k++) {
        if ((k && gid[k] <= gid[k - 1]) || owner[k] < 0 || owner[k] >= P)
            e = DEM_ERR_ARG; /* global ids not ascending, or an owner that is no rank */
        else if (owner[k] != h->rank)
            h->recv_count[owner[k]]++;
    }
    if ((e = dem_mpi_agreed(comm, e))) {
        free(want);
        dem_mpi_halo_free(h);
        return e;
    }
    for (int q = 1; q < P; q++)
        h->recv_displ[q] = h->recv_displ[q - 1] + h->recv_count[q - 1];
    h->nrecv = P ? h->recv_displ[P - 1] + h->recv_count[P - 1] : 0;
    int *fill = calloc((size_t)P, sizeof(int));
    for (int k = 0; fill && k < n; k++) /* ghosts by owner, ascending global id within each */
        if (owner[k] != h->rank) {
            int at = h->recv_displ[owner[k]] + fill[owner[k]]++;
            h->recv_id[at] = k, want[at] = gid[k];
        }
    e = dem_mpi_agreed(comm, fill ? 0 : DEM_ERR_NOMEM);
    free(fill);
    /* each rank learns which of its particles the others hold (their ghost lists), and finds them */
    if (!e && (e = MPI_Alltoall(h->recv_count, 1, MPI_INT, h->send_count, 1, MPI_INT, comm)) == MPI_SUCCESS) {
        for (int q = 1; q < P; q++)
            h->send_displ[q] = h->send_displ[q - 1] + h->send_count[q - 1];
        h->nsend = h->send_displ[P - 1] + h->send_count[P - 1];
        asked = malloc(sizeof(long) * ((size_t)h->nsend + 1));
        h->send_id = malloc(sizeof(int) * ((size_t)h->nsend + 1));
        e = asked && h->send_id ? 0 : DEM_ERR_NOMEM;
        if (!dem_mpi_agreed(comm, e))
            e = MPI_Alltoallv(want, h->recv_count, h->recv_displ, MPI_LONG, asked, h->send_count, h->send_displ,
                              MPI_LONG, comm);
        else
            e = e ? e : DEM_ERR_NOMEM;
    }
    for (int k = 0; !e && k < h->nsend; k++) {
        int i = dem_mpi_id_at(gid, n, asked[k]);
        if (i < 0 || owner[i] != h->rank)
            e = DEM_ERR_ARG; /* a rank holds as a ghost of ours a particle we do not own */
        else
            h->send_id[k] = i;
    }
    free(want), free(asked);
    if (!e) {
        h->gid = malloc(sizeof(long) * ((size_t)n + 1)), h->owner = malloc(sizeof(int) * ((size_t)n + 1));
        if (h->gid && h->owner)
            memcpy(h->gid, gid, sizeof(long) * (size_t)n), memcpy(h->owner, owner, sizeof(int) * (size_t)n);
        h->rs = s->setup.real_size;
        h->field = malloc(sizeof(double) * 3 * ((size_t)n + 1));
        h->sbuf = malloc((size_t)h->rs * HALO_W * ((size_t)h->nsend + 1));
        h->rbuf = malloc((size_t)h->rs * HALO_W * ((size_t)h->nrecv + 1));
        h->msg_count = malloc(sizeof(int) * 4 * (size_t)P);
        e = h->field && h->sbuf && h->rbuf && h->gid && h->owner && h->msg_count ? 0 : DEM_ERR_NOMEM;
    }
    if (!dem_mpi_agreed(comm, e)) /* the device's message rows: the particles sent, then the ghosts, in the
                                   * messages' order */
        e = sim_halo_set(s, h->nsend, h->send_id, h->nrecv, h->recv_id);
    if ((e = dem_mpi_agreed(comm, e)))
        dem_mpi_halo_free(h);
    else {
        h->steer = P > 1 && sim_has_servo(s) && (s->effects & DEM_EFFECT_WALLS) && s->nwalls > 0;
        h->mdr = P > 1 && (s->effects & DEM_EFFECT_MDR);
        if (P > 1 && (s->effects & (DEM_EFFECT_MC_STRESS | DEM_EFFECT_MDR | DEM_EFFECT_MC_STRAIN)))
            s->halo_hook = mid_step, s->halo_ctx = h;
        /* a run started by sim_start_deferred (its state its set-up's): the start's forces now, with the meetings
         * of a step, then every rank's own walls' sums merged (one process's, in every rank's run: what a servo's
         * first step and the first series row read) */
        int fresh = s->run.forces_due;
        if (fresh)
            e = dem_mpi_agreed(comm, sim_start_forces(s));
        /* the start's forces of a ghost miss its partners outside the halo: its owner's, before the first step;
         * in a run whose state was set, the walls' sums are the state's (no step has made a rank's own since) */
        if (!e)
            e = exchange(h, fresh && (s->effects & DEM_EFFECT_WALLS) && s->nwalls > 0);
    }
    return e;
}

/* A meeting of the ranks (every agreement in and after a step goes through it): every rank's code e agreed; a rank
 * that had none but learns of another's failure marks it (dem_sim.run.halo_learned), so that the step's caller
 * reports the words of the rank that failed (app/run_mpi.c) */
static int in_step(dem_mpi_halo *h, int e)
{
    int a = dem_mpi_agreed(h->comm, e);
    if (a && !e)
        h->s->run.halo_learned = 1;
    return a;
}

/* The packed rows of width reals each (h->sbuf, the particles sent in the halo's order) to the ranks that hold them
 * as ghosts, theirs into h->rbuf: one MPI_Alltoallv in the run's precision. Returns MPI's code. Collective. */
static int send_rows(dem_mpi_halo *h, int width)
{
    int P = h->size, *sc = h->msg_count, *sd = sc + P, *rc = sd + P, *rd = rc + P;
    for (int q = 0; q < P; q++)
        sc[q] = width * h->send_count[q], sd[q] = width * h->send_displ[q], rc[q] = width * h->recv_count[q],
        rd[q] = width * h->recv_displ[q];
    MPI_Datatype real = h->rs == 8 ? MPI_DOUBLE : MPI_FLOAT;
    return MPI_Alltoallv(h->sbuf, sc, sd, real, h->rbuf, rc, rd, real, h->comm);
}

/* The owners' values of the per-particle registry buffer `buf` of `width` <= HALO_W reals per particle into the
 * ghosts: packed and unpacked on the device (common/halo.h: halo_pack_rows, halo_unpack_rows), width reals per
 * particle through MPI. Collective. */
static int exchange_rows(dem_mpi_halo *h, int buf, int width)
{
    int e = sim_halo_pack_rows(h->s, buf, width, h->sbuf); /* sbuf and rbuf hold HALO_W reals a row: room for these */
    if (!(e = in_step(h, e))) {
        if ((e = send_rows(h, width)))
            e = sim_fail(h->s, DEM_ERR_DEVICE, "MPI_Alltoallv of the ghosts' values failed (%d)", e);
        if (!e)
            e = sim_halo_unpack_rows(h->s, buf, width, h->rbuf);
        e = in_step(h, e);
    }
    return e;
}

/* this rank's entries (i own here, a ghost on rank q; j owned by q) of the list (pi, pj) of m row slots: counted
 * (out NULL) or packed as (global i, global j, D) into out; mark: scratch of h->n bytes */
static long mc_disp_pick(const dem_mpi_halo *h, int q, const int *pi, const int *pj, const double *d, long m,
                         unsigned char *mark, double *out)
{
    long c = 0;
    memset(mark, 0, (size_t)h->n);
    for (int k = h->send_displ[q]; k < h->send_displ[q] + h->send_count[q]; k++)
        mark[h->send_id[k]] = 1;
    for (long k = 0; k < m; k++)
        if (mark[pi[k]] && h->owner[pj[k]] == q) {
            if (out)
                out[3 * c] = (double)h->gid[pi[k]], out[3 * c + 1] = (double)h->gid[pj[k]], out[3 * c + 2] = d[k];
            c++;
        }
    return c;
}

/* MC-strain's displacements of the ghosts' contacts with our own particles, from their owners. A rank sends, for
 * each of its own particles i that another rank q holds as a ghost, D_i,c of i's contacts c with q's own particles
 * (each touching one is in i's row here: it is in our halo), as (global i, global j, D); q writes them into its
 * ghost i's row slots (sim_mc_disp_set). A contact of two ghosts is left as it is: no own particle reads it.
 * Collective. */
static int mc_disp_exchange(dem_mpi_halo *h)
{
    int P = h->size, e = 0, *pi = NULL, *pj = NULL, *ri = NULL, *rj = NULL;
    long m = 0, nsend = 0, nrecv = 0;
    double *d = NULL, *sb = NULL, *rb = NULL;
    int *cnt = calloc((size_t)(4 * P), sizeof(int));
    unsigned char *mark = calloc((size_t)h->n + 1, 1);
    if (!cnt || !mark)
        e = sim_fail(h->s, DEM_ERR_NOMEM, "out of host memory for MC-strain's exchange");
    if (!e)
        e = sim_mc_disp_get(h->s, &m, &pi, &pj, &d);
    for (int q = 0; !e && q < P; q++)
        nsend += cnt[q] = (int)mc_disp_pick(h, q, pi, pj, d, m, mark, NULL);
    if (!e && !(sb = malloc(sizeof(double) * 3 * (size_t)(nsend + 1))))
        e = sim_fail(h->s, DEM_ERR_NOMEM, "out of host memory for MC-strain's exchange");
    for (int q = 0, at = 0; !e && q < P; at += cnt[q], q++)
        mc_disp_pick(h, q, pi, pj, d, m, mark, sb + 3 * (size_t)at);
    free(pi), free(pj), free(d), free(mark);
    pi = pj = NULL, d = NULL;
    int *dsp = cnt + P, *rcnt = cnt + 2 * P, *rdsp = cnt + 3 * P;
    if (!(e = in_step(h, e))) { /* every agreement below is entered by every rank */
        if ((e = MPI_Alltoall(cnt, 1, MPI_INT, rcnt, 1, MPI_INT, h->comm)))
            e = sim_fail(h->s, DEM_ERR_DEVICE, "MPI_Alltoall of MC-strain's counts failed (%d)", e);
        e = in_step(h, e);
    }
    if (!e) {
        for (int q = 0, at = 0; q < P; q++) { /* in reals: 3 per entry */
            dsp[q] = 3 * at, at += cnt[q], cnt[q] *= 3;
            rdsp[q] = (int)(3 * nrecv), nrecv += rcnt[q], rcnt[q] *= 3;
        }
        rb = malloc(sizeof(double) * 3 * (size_t)(nrecv + 1));
        ri = malloc(sizeof(int) * (size_t)(nrecv + 1)), rj = malloc(sizeof(int) * (size_t)(nrecv + 1));
        d = malloc(sizeof(double) * (size_t)(nrecv + 1));
        if (!rb || !ri || !rj || !d)
            e = sim_fail(h->s, DEM_ERR_NOMEM, "out of host memory for MC-strain's exchange");
        if (!(e = in_step(h, e)) && (e = MPI_Alltoallv(sb, cnt, dsp, MPI_DOUBLE, rb, rcnt, rdsp, MPI_DOUBLE, h->comm)))
            e = sim_fail(h->s, DEM_ERR_DEVICE, "MPI_Alltoallv of MC-strain's displacements failed (%d)", e);
        for (long k = 0; !e && k < nrecv; k++) {
            ri[k] = dem_mpi_id_at(h->gid, h->n, (long)rb[3 * k]), rj[k] = dem_mpi_id_at(h->gid, h->n, (long)rb[3 * k + 1]);
            d[k] = rb[3 * k + 2];
            if (ri[k] < 0 || rj[k] < 0)
                e = sim_fail(h->s, DEM_ERR_ARG, "MC-strain's exchange: a contact of particle %ld or %ld, which this rank "
                             "does not hold", (long)rb[3 * k], (long)rb[3 * k + 1]);
        }
        if (!e)
            e = sim_mc_disp_set(h->s, nrecv, ri, rj, d);
        e = in_step(h, e);
    }
    free(cnt), free(sb), free(rb), free(ri), free(rj), free(d);
    return e;
}

/* In the step (dem_sim.halo_hook, SIM_HOOK_*), each call a meeting of the ranks that first agrees on any rank's
 * failure (SIM_HOOK_FAILED: this rank's; SIM_HOOK_STEP_END: nothing else to do), then what the contacts read of a
 * ghost that its own evaluation got wrong (its partners outside the halo missing): its owner's. After MC-stress's pass 1, each particle's stress
 * trace; after MDR's mdr_surface, each particle's row with its mean surface displacement (mdr_particle.h); after each
 * evaluation of MC-strain's displacements, those of the ghosts' contacts with own particles. And MC-strain's
 * convergence test: another iteration when any rank's own contacts still moved. */
static int mid_step(dem_sim *s, void *ctx, int event, int *value)
{
    (void)s;
    dem_mpi_halo *h = ctx;
    if (event == SIM_HOOK_FAILED) /* this rank's step failed: the others meet it at their next point */
        return in_step(h, *value);
    int e = in_step(h, 0); /* the meeting: did any rank's step fail since the last one */
    if (e || event == SIM_HOOK_STEP_END)
        return e;
    if (event == SIM_HOOK_STAGE && *value == (int)DEM_EFFECT_MC_STRESS)
        return exchange_rows(h, BUF_TRACE, 1);
    if (event == SIM_HOOK_STAGE && *value == (int)DEM_EFFECT_MDR)
        return exchange_rows(h, BUF_MDR_PART, MDR_P_STRIDE);
    if (event == SIM_HOOK_MC_DISP)
        return mc_disp_exchange(h);
    if (event == SIM_HOOK_MC_PENDING) {
        int mine = *value != 0, any = mine;
        e = MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, h->comm);
        *value = any;
        return in_step(h, e ? sim_fail(h->s, DEM_ERR_DEVICE, "MPI_Allreduce failed (%d)", e) : 0);
    }
    return 0;
}

/* Walls steered by their sums (a servo, a stage that ends at a force): each rank's exact sums of the step just taken
 * (its own particles') merged, and the one-process force set in every rank's run before the next step reads it */
static int walls_merged(dem_mpi_halo *h)
{
    dem_sim *s = h->s;
    int nw = s->nwalls, e = 0;
    exact_acc acc[WP_STRIDE * DEM_MAX_WALLS];
    for (int k = 0; k < WP_STRIDE * nw; k++)
        exact_clear(&acc[k]);
    for (int k = 0; !e && k < nw; k++)
        e = sim_wall_sums_exact(s, k, acc + WP_STRIDE * k);
    if ((e = dem_mpi_agreed(h->comm, e)))
        return e;
    if (dem_mpi_exact_allreduce(h->comm, acc, WP_STRIDE * nw))
        return dem_mpi_agreed(h->comm, DEM_ERR_DEVICE);
    return dem_mpi_agreed(h->comm, sim_wall_sums_set(s, acc));
}

int dem_mpi_halo_exchange(dem_mpi_halo *h) { return exchange(h, h->steer); }

static int exchange(dem_mpi_halo *h, int walls)
{
    /* the rows of the particles sent, packed on the device in the run's precision */
    int e = dem_mpi_agreed(h->comm, sim_halo_pack(h->s, h->sbuf));
    if (e)
        return e;
    e = send_rows(h, HALO_W);
    /* the owners' rows into the ghosts (the split's check of the moves reads no positions: sim_move_check) */
    if (!e)
        e = sim_halo_unpack(h->s, h->rbuf);
    if ((e = dem_mpi_agreed(h->comm, e)))
        return e;
    /* MDR: the row's sums the contacts left, which the next step's mdr_begin turns into volumes and a radius */
    if (h->mdr && (e = exchange_rows(h, BUF_MDR_PART, MDR_P_STRIDE)))
        return e;
    return walls ? walls_merged(h) : 0;
}
