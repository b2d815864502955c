/* run_mpi.c - `mpirun -np N dem run SCENE.yaml`: the run split over N ranks by space (docs/design.md "Runs over MPI").
 * run.c drives it through run_ranks (run.h); this file alone of app/ is compiled with MPI, and only dem links it.
 *
 * The split, its parts and their steps are the MPI layer's (host/mpi/split.c, mpi_layer.h: recursive bisection, a
 * halo of ghosts exchanged after each step, split anew when a particle has moved half the margin, the walls' sums
 * and series rows merged exactly); what is `dem run`'s is here: a restart's part read by each rank from the
 * checkpoint, frames gathered on rank 0 from the parts slab by slab (frame), and so are the checkpoints
 * (checkpoint_parts): no rank holds the whole state. */
#include "run.h"
#include "mpi_layer.h"
#include "output.h"
#include "checkpoint.h"
#include "sim.h"
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* particles per slab of a checkpoint written from the parts: each a few tens of MB on rank 0 (about 1.5 KB a
 * particle with its contacts in a compact, fp64) */
#define RUN_MPI_CK_SLAB 32768L

typedef struct {
    run_ranks pub;
    MPI_Comm comm;
    dem_mpi_split sp;                                 /* the split, its parts and their steps (host/mpi/split.c) */
    /* a frame written from the parts (frame): what this rank read of its part for it */
    double *fval;                                     /* [nloc ncomp]: field fval_f of the held particles */
    int fval_f;                                       /* -1: none read */
    int *fcounts;                                     /* rank 0: [2 size], the gather's counts and displacements */
    dem_contact *fcs;                                 /* own contacts (the lower id own), global ids: pairs, walls */
    long fcs_n, fcs_np;
    int fcs_have;
    long ck_slab;                                     /* particles per slab of a checkpoint */
    const checkpoint *ck;                             /* a restart's first split: the checkpoint's head, and */
    const char *ck_path;                              /* its file, which each rank reads its part of */
    long fail_step;                                   /* DEM_TEST_RANK_FAIL="STEP RANK [nan|kill|frame|checkpoint]": */
    int fail_rank, fail_frame, fail_ck;               /* that rank fails there, after its step, or (nan) inside it:
                                                         a particle's position made NaN before the step (sp.fail_*),
                                                         or (kill) dies of SIGKILL after it, or (frame, checkpoint)
                                                         answering the first frame or checkpoint from that step on */
} rr;

static rr *of(run_ranks *r) { return (rr *)r->ctx; }

/* 0 when every code is 0, else the lowest of those that are not (dem_status codes are negative, exit statuses
 * positive: a rank's failure is never outvoted by another's 0), and the first rank that had it */
static int agree(run_ranks *r, int code, int *who) { return dem_mpi_agreed_who(of(r)->comm, code, who); }

static long agree_min(run_ranks *r, long v)
{
    long out = v;
    MPI_Allreduce(&v, &out, 1, MPI_LONG, MPI_MIN, of(r)->comm);
    return out;
}

static void share(run_ranks *r, int who, char *msg, size_t len) { dem_mpi_share(of(r)->comm, who, msg, len); }

static int agreed_msg(rr *q, int e, dem_sim *s, char *err, size_t len)
{
    return dem_mpi_split_agreed(&q->sp, e, s, err, len);
}

static int shared_error(rr *q, int e, char *err, size_t len) { return dem_mpi_split_shared_error(&q->sp, e, err, len); }

/* This rank's part of the checkpoint q->ck_path, its radii checked against the scene's, into ps: 0, or a dem_status
 * with the reason in err */
static int part_from_checkpoint(rr *q, dem_state *ps, char *err, size_t len)
{
    double *rad = malloc(sizeof(double) * ((size_t)q->sp.nloc + 1));
    if (!rad)
        return snprintf(err, len, "out of host memory reading %s", q->ck_path), DEM_ERR_NOMEM;
    int e = checkpoint_read_part(q->ck_path, q->ck, q->sp.part, q->sp.nloc, q->sp.gid, ps, rad, err, len) ? DEM_ERR_ARG : 0;
    for (int k = 0; !e && k < q->sp.nloc; k++) /* run.c's check of the whole, on each rank's part */
        if (rad[k] != dem_particle_radius(q->sp.from, (int)q->sp.gid[k])) {
            snprintf(err, len, "%s: particle %ld has radius %g m in the checkpoint and %g m in the scene (did a CSV "
                     "file change?)", q->ck_path, q->sp.gid[k], rad[k], dem_particle_radius(q->sp.from, (int)q->sp.gid[k]));
            e = DEM_ERR_ARG;
        }
    free(rad);
    if (e)
        dem_state_free(ps);
    return e;
}

/* The parts made and started (host/mpi/split.c): split by the set-up's positions, or where the run restarts by the
 * checkpoint's, which every rank reads, each rank then reading its own particles and contacts of it
 * (part_from_checkpoint) */
static int start(run_ranks *r, dem_sim *whole, const checkpoint *ck, const char *ck_path, const dem_config *cfg,
                 const char *what, char *err, size_t len)
{
    rr *q = of(r);
    long n = dem_count(whole);
    int e = 0;
    err[0] = 0;
    double *x = ck ? malloc(sizeof(double) * 3 * (size_t)(n ? n : 1)) : NULL;
    if (ck && !x)
        e = DEM_ERR_NOMEM, snprintf(err, len, "%ld particles: out of host memory", n);
    else if (ck && checkpoint_read_x(ck_path, ck, x, err, len))
        e = DEM_ERR_ARG;
    if (!(e = agreed_msg(q, e, NULL, err, len))) {
        q->ck = ck, q->ck_path = ck_path, q->sp.load_what = ck_path;
        e = dem_mpi_split_start(&q->sp, q->comm, whole, cfg, x, ck ? ck->st.step : 0, what, err, len);
        q->ck = NULL, q->ck_path = NULL, q->sp.load_what = NULL; /* a split anew moves the parts' states */
    }
    free(x);
    return e;
}

static int load_part(void *arg, dem_mpi_split *sp, dem_state *ps, char *err, size_t len)
{
    (void)sp;
    return part_from_checkpoint(arg, ps, err, len);
}

static int step(run_ranks *r, long nsteps, const unsigned char *want, dem_sample *rows, char *err, size_t len)
{
    return dem_mpi_split_step(&of(r)->sp, nsteps, want, rows, err, len);
}

static int sample(run_ranks *r, dem_sample *row, char *err, size_t len)
{
    return dem_mpi_split_sample(&of(r)->sp, row, err, len);
}

static int bounds(run_ranks *r, double box[6]) { return dem_mpi_split_bounds(&of(r)->sp, box); }

/* ---- a frame written from the parts: rank 0 asks for each slab (output_frame_from), every rank answers with its
 * own particles' values or contacts in it, gathered on rank 0; the whole state is not gathered ---- */

enum { FR_DONE, FR_FIELD, FR_PAIRS, FR_WALLS, FR_CKSLAB };

static void frame_drop(rr *q)
{
    free(q->fval);
    free(q->fcs);
    q->fval = NULL, q->fcs = NULL;
    q->fval_f = -1, q->fcs_have = 0, q->fcs_n = q->fcs_np = 0;
}

/* first contact of cs[0..m) with i >= v (ascending i) */
static long contact_from(const dem_contact *cs, long m, long v)
{
    long lo = 0, hi = m;
    while (lo < hi) {
        long k = lo + (hi - lo) / 2;
        if (cs[k].i < v)
            lo = k + 1;
        else
            hi = k;
    }
    return lo;
}

/* this rank's own contacts of its part, in global ids and dem_contacts_get's order (a contact is its lower id's
 * owner's, whose rows hold its history: the state's rule, dem_mpi_state_gather) */
static int own_contacts(rr *q)
{
    dem_contact *cs;
    long count, np;
    if (dem_contacts_get(q->sp.part, &cs, &count, &np))
        return -1;
    long m = 0, mp = 0;
    for (long k = 0; k < count; k++) {
        int i = cs[k].i, j = cs[k].j;
        if (q->sp.owner[i] != q->pub.rank)
            continue;
        cs[m] = cs[k];
        cs[m].i = (int)q->sp.gid[i];
        cs[m].j = j >= 0 ? (int)q->sp.gid[j] : j;
        mp += k < np;
        m++;
    }
    q->fcs = cs, q->fcs_n = m, q->fcs_np = mp, q->fcs_have = 1;
    return 0;
}

/* This rank's answer to request rq (kind, field, ncomp, a, b), gathered on rank 0 into rows (a field: (b - a) ncomp
 * reals in id order) or *cs, *count (contacts, malloc'd). A rank that cannot answer sends -1: rank 0 then fails the
 * frame. Returns 0, or -1 where this rank failed (its words in err) or, on rank 0, any rank did. */
static int frame_answer(rr *q, const long rq[5], double *rows, dem_contact **cs, long *count, char *err, size_t len)
{
    int me = q->pub.rank, size = q->pub.size, kind = (int)rq[0], nc = (int)rq[2], mine = 0, bad = 0;
    long a = rq[3], b = rq[4];
    void *out = NULL;
    int m = 0, unit = kind == FR_FIELD ? (int)sizeof(double) * (1 + nc) : (int)sizeof(dem_contact);
    if (kind == FR_FIELD) {
        if (q->fval_f != (int)rq[1]) {
            free(q->fval);
            q->fval_f = -1;
            q->fval = malloc(sizeof(double) * (size_t)nc * (size_t)(q->sp.nloc ? q->sp.nloc : 1));
            if (!q->fval || dem_get_field(q->sp.part, (dem_field)rq[1], q->fval))
                mine = -1;
            else
                q->fval_f = (int)rq[1];
        }
        int k0 = dem_mpi_id_from(q->sp.gid, q->sp.nloc, a), k1 = dem_mpi_id_from(q->sp.gid, q->sp.nloc, b);
        double *buf = mine ? NULL : malloc((size_t)unit * (size_t)(k1 - k0 + 1));
        mine = mine || !buf;
        for (int k = k0; !mine && k < k1; k++)
            if (q->sp.owner[k] == me) {
                buf[(size_t)m * (1 + nc)] = (double)q->sp.gid[k]; /* exact: ids below 2^53 */
                memcpy(buf + (size_t)m * (1 + nc) + 1, q->fval + (size_t)k * nc, sizeof(double) * nc);
                m++;
            }
        out = buf;
    } else {
        if (!q->fcs_have && own_contacts(q))
            mine = -1;
        long lo = 0, hi = 0;
        if (!mine && kind == FR_PAIRS)
            lo = contact_from(q->fcs, q->fcs_np, a), hi = contact_from(q->fcs, q->fcs_np, b);
        else if (!mine)
            lo = q->fcs_np + contact_from(q->fcs + q->fcs_np, q->fcs_n - q->fcs_np, a),
            hi = q->fcs_np + contact_from(q->fcs + q->fcs_np, q->fcs_n - q->fcs_np, b);
        if (hi - lo > INT_MAX / unit)
            mine = -1;
        m = (int)(hi - lo);
        out = mine ? NULL : q->fcs + lo;
    }
    if (q->fail_frame && q->fail_rank == me && dem_step_index(q->sp.part) >= q->fail_step && !mine) /* test hook */
        mine = -1, snprintf(err, len, "DEM_TEST_RANK_FAIL: rank %d cannot read its part for the frame at step %ld", me,
                            dem_step_index(q->sp.part));
    if (mine && !err[0])
        snprintf(err, len, "%s", dem_error(q->sp.part)[0] ? dem_error(q->sp.part) : "out of host memory");
    /* the sizes to rank 0, its verdict to all: a rank that could not answer, a slab too large for MPI's int counts
     * or no memory for it on rank 0 fails it on every rank, and then nothing more is sent */
    int cnt = mine ? -1 : m * unit, *counts = q->fcounts, *displs = q->fcounts ? q->fcounts + size : NULL;
    MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, q->comm);
    long total = 0;
    for (int k = 0; me == 0 && k < size; k++) {
        bad |= counts[k] < 0;
        if (counts[k] < 0 && !err[0])
            snprintf(err, len, "rank %d could not read its part", k);
        total += counts[k] < 0 ? 0 : counts[k];
    }
    if (me == 0 && !bad && total > INT_MAX)
        bad = 1, snprintf(err, len, "a slab of the frame over 2 GiB");
    unsigned char *all = me == 0 && !bad ? malloc((size_t)total + 1) : NULL;
    if (me == 0 && !bad && !all)
        bad = 1, snprintf(err, len, "out of host memory");
    MPI_Bcast(&bad, 1, MPI_INT, 0, q->comm);
    for (int k = 0; me == 0 && !bad && k < size; k++)
        displs[k] = k ? displs[k - 1] + counts[k - 1] : 0;
    if (!bad)
        MPI_Gatherv(out, cnt, MPI_BYTE, all, counts, displs, MPI_BYTE, 0, q->comm);
    if (kind == FR_FIELD)
        free(out);
    if (me != 0)
        return mine;
    if (!bad && kind == FR_FIELD) { /* each row in its place; every id of the slab once */
        long got = total / unit, filled = 0;
        const double *v = (const double *)all;
        for (long r = 0; r < got; r++) {
            long id = (long)v[r * (1 + nc)];
            if (id < a || id >= b)
                continue;
            memcpy(rows + (size_t)(id - a) * nc, v + r * (1 + nc) + 1, sizeof(double) * nc);
            filled++;
        }
        if (filled != b - a || got != b - a)
            bad = 1, snprintf(err, len, "the parts hold %ld of the %ld particles %ld..%ld", got, b - a, a, b - 1);
        free(all);
    } else if (!bad) {
        *count = total / unit;
        *cs = (dem_contact *)all;
        qsort(*cs, (size_t)*count, sizeof **cs, sim_contact_order); /* as dem_contacts_get */
    } else {
        free(all);
    }
    return bad || mine ? -1 : 0;
}

static int frame_ask(rr *q, long kind, long f, long nc, long a, long b, double *rows, dem_contact **cs, long *count,
                     char *err, size_t len)
{
    long rq[5] = {kind, f, nc, a, b};
    MPI_Bcast(rq, 5, MPI_LONG, 0, q->comm);
    return frame_answer(q, rq, rows, cs, count, err, len);
}

typedef struct {
    rr *q;
    char *err;
    size_t len;
} frame_ctx;

static int src_field(void *ctx, dem_field f, int ncomp, long a, long b, double *rows)
{
    frame_ctx *c = ctx;
    return frame_ask(c->q, FR_FIELD, (long)f, ncomp, a, b, rows, NULL, NULL, c->err, c->len);
}

static int src_contacts(void *ctx, int walls, long a, long b, dem_contact **out, long *count)
{
    frame_ctx *c = ctx;
    *out = NULL, *count = 0;
    return frame_ask(c->q, walls ? FR_WALLS : FR_PAIRS, 0, 0, a, b, NULL, out, count, c->err, c->len);
}

/* the frame of the parts' state: rank 0 writes it to o slab by slab (time, step and walls its part's), the others
 * answer until it is done. 0, -1 where rank 0's file failed, -2 where a part could not be read (the words of the
 * rank that could not in err); the same on every rank */
static int frame(run_ranks *r, output *o, char *err, size_t len)
{
    rr *q = of(r);
    int rc = 0, mine = 0, saved_errno = 0;
    err[0] = 0;
    if (r->rank == 0) {
        frame_ctx c = {q, err, len};
        frame_source src = {&c, src_field, src_contacts, err, len};
        if (!(q->fcounts = malloc(sizeof(int) * 2 * (size_t)r->size)))
            rc = -2, snprintf(err, len, "out of host memory");
        else
            rc = output_frame_from(o, q->sp.part, &src);
        saved_errno = errno; /* the file's reason, for run.c's message: MPI's calls below may set errno */
        long done[5] = {FR_DONE, 0, 0, 0, 0};
        MPI_Bcast(done, 5, MPI_LONG, 0, q->comm);
    } else {
        for (;;) {
            long rq[5];
            MPI_Bcast(rq, 5, MPI_LONG, 0, q->comm);
            if (rq[0] == FR_DONE)
                break;
            mine |= frame_answer(q, rq, NULL, NULL, NULL, err, len) != 0; /* keeps answering: -1 */
        }
    }
    frame_drop(q);
    free(q->fcounts);
    q->fcounts = NULL;
    /* a rank's own failure (-3) before rank 0's account of it (-2), so that its words are the ones shared */
    int who, a = agree(r, mine ? -3 : rc == -2 && r->rank == 0 && strncmp(err, "rank ", 5) ? -3 : rc, &who);
    if (a == -3) {
        share(r, who, err, len);
        return -2;
    }
    errno = saved_errno;
    return a;
}

/* the overlaps and stability of a frame: each rank's own pairs (the lower id its own) and own particles, merged so
 * that rank 0's watch takes what one process's would (the largest overlap with the lowest ids on ties, the mean from
 * the exact sum, the least stable particle with the lowest id on ties); a frame that cannot be read on some rank is
 * not measured, as in one process */
static void overlaps(run_ranks *r, overlap_watch *w)
{
    rr *q = of(r);
    overlap_frame f;
    dem_stability st;
    memset(&st, 0, sizeof st);
    st.particle = -1;
    /* as one process: no frame measured while no particle has a neighbour slot */
    long slots = dem_neighbor_capacity(q->sp.part) > 0, any = 0;
    MPI_Allreduce(&slots, &any, 1, MPI_LONG, MPI_MAX, q->comm);
    if (!any)
        return;
    unsigned char *own = malloc((size_t)(q->sp.nloc ? q->sp.nloc : 1));
    int e = !own;
    for (int k = 0; own && k < q->sp.nloc; k++)
        own[k] = q->sp.owner[k] == r->rank;
    e = e || overlap_frame_scan(w, q->sp.part, q->sp.gid, own, &f);
    free(own);
    int se = e || dem_stability_get(q->sp.part, &st);
    if (!se && st.particle >= 0)
        st.particle = (int)q->sp.gid[st.particle];
    if (dem_mpi_agreed(q->comm, e ? DEM_ERR_NOMEM : 0))
        return;
    int bad_st = dem_mpi_agreed(q->comm, se ? DEM_ERR_NOMEM : 0) != 0;
    struct {
        double worst;
        long wi, wj;
    } mine = {f.worst, f.wi, f.wj}, *all = malloc(sizeof mine * (size_t)r->size);
    dem_stability *sts = malloc(sizeof st * (size_t)r->size);
    long touching = 0;
    int ok = all && sts;
    if (dem_mpi_agreed(q->comm, ok ? 0 : DEM_ERR_NOMEM)) {
        free(all), free(sts);
        return;
    }
    MPI_Allgather(&mine, (int)sizeof mine, MPI_BYTE, all, (int)sizeof mine, MPI_BYTE, q->comm);
    MPI_Allgather(&st, (int)sizeof st, MPI_BYTE, sts, (int)sizeof st, MPI_BYTE, q->comm);
    MPI_Allreduce(&f.touching, &touching, 1, MPI_LONG, MPI_SUM, q->comm);
    dem_mpi_exact_allreduce(q->comm, &f.sum, 1);
    f.touching = touching;
    for (int k = 0; k < r->size; k++) {
        if (all[k].worst > f.worst ||
            (all[k].worst == f.worst && all[k].worst > 0 &&
             (all[k].wi < f.wi || (all[k].wi == f.wi && all[k].wj < f.wj))))
            f.worst = all[k].worst, f.wi = all[k].wi, f.wj = all[k].wj;
        if (!bad_st && (sts[k].ratio > st.ratio ||
                        (sts[k].ratio == st.ratio && st.ratio > 0 && sts[k].particle < st.particle)))
            st = sts[k];
    }
    if (r->rank == 0)
        overlap_watch_add(w, &f, bad_st ? NULL : &st, dem_time(q->sp.part));
    free(all), free(sts);
}

static long step_index(run_ranks *r) { return of(r)->sp.step; }
static dem_sim *stepped(run_ranks *r) { return of(r)->sp.part; }

/* ---- a checkpoint written from the parts: rank 0 asks for each slab of particle ids, and the ranks' own particles'
 * rows and contacts in it are gathered to it (dem_mpi_state_slab); no rank holds the whole state ---- */

typedef struct {
    rr *q;
    dem_state *loc; /* this rank's state */
    dem_state slab; /* rank 0: the last slab gathered */
    int have;
    double *radius; /* its radii */
    char *err;
    size_t len;
} ck_ctx;

/* this rank's part of slab [a, b), gathered into g on rank 0; 0, or -1 on every rank with the reason in err */
static int ck_answer(rr *q, dem_state *loc, long a, long b, dem_state *g, char *err, size_t len)
{
    int me = q->pub.rank, mine = 0, who;
    if (q->fail_ck && q->fail_rank == me && q->sp.step >= q->fail_step) /* test hook */
        mine = DEM_ERR_DEVICE, snprintf(err, len, "DEM_TEST_RANK_FAIL: rank %d cannot read its part for the "
                                                  "checkpoint at step %ld", me, q->sp.step);
    if (q->fail_ck && agree(&q->pub, mine, &who)) { /* (the hook's setting is every rank's: mpirun's environment) */
        share(&q->pub, who, err, len);
        return -1;
    }
    int e = dem_mpi_state_slab(&q->sp.h, q->sp.gid, q->sp.owner, q->sp.n, loc, a, b, 0, g); /* agreed */
    if (e)
        snprintf(err, len, "the particles %ld..%ld of the checkpoint could not be gathered: %s", a, b - 1,
                 e == DEM_ERR_NOMEM ? "out of host memory"
                                    : "the parts do not hold each of them once, or a message past MPI's int counts");
    return e ? -1 : 0;
}

static int ck_slab(void *ctx, long a, long b, const dem_state **part, const double **radius)
{
    ck_ctx *c = ctx;
    rr *q = c->q;
    if (c->have)
        dem_state_free(&c->slab);
    c->have = 0;
    long rq[5] = {FR_CKSLAB, 0, 0, a, b};
    MPI_Bcast(rq, 5, MPI_LONG, 0, q->comm);
    if (ck_answer(q, c->loc, a, b, &c->slab, c->err, c->len))
        return -1;
    c->have = 1;
    double *r = realloc(c->radius, sizeof(double) * (size_t)(b - a + 1));
    if (!r) {
        snprintf(c->err, c->len, "out of host memory");
        return -1;
    }
    c->radius = r;
    for (long k = a; k < b; k++) /* the radii as set up (the scene's, which every rank holds) */
        r[k - a] = dem_particle_radius(q->sp.from, (int)k);
    *part = &c->slab, *radius = r;
    return 0;
}

/* The checkpoint of the parts' state, written by rank 0 slab by slab: its header is rank 0's part's (step, walls,
 * stages, counts: every rank's; the rebuild and iteration counts rank 0's, as a gather takes them) with the walls'
 * sums merged exactly from every rank's own particles, its particles and contacts the ranks' own (the contacts each
 * from its lower id's owner). The file of one process (tests/mpi_run_check.sh). */
static int checkpoint_parts(run_ranks *r, const char *path, const scene *sc, const scene_run *run, char *err, size_t len)
{
    rr *q = of(r);
    dem_state loc;
    err[0] = 0;
    int e = dem_mpi_agreed(q->comm, dem_state_get(q->sp.part, &loc));
    if (e) {
        shared_error(q, e, err, len);
        return -2;
    }
    long mine = 0, np = 0; /* the whole run's contacts: each rank's own */
    for (long p = 0; p < loc.npairs; p++)
        mine += q->sp.owner[loc.pair_i[p]] == r->rank;
    MPI_Allreduce(&mine, &np, 1, MPI_LONG, MPI_SUM, q->comm);
    int nw;
    exact_acc acc[SE_STRIDE + WP_STRIDE * DEM_MAX_WALLS];
    if (dem_mpi_split_walls(&q->sp, acc, &nw, err, len)) {
        dem_state_free(&loc);
        return -2;
    }
    int rc = 0, failed = 0;
    if (r->rank == 0) {
        dem_state head = loc; /* its arrays' pointers loc's: not freed through head */
        for (int k = 0; k < head.narrays; k++) {
            dem_state_array *ha = &head.arrays[k];
            int per;
            if (sim_state_array_layout(q->sp.part, ha->name, &per) != DEM_MOVE_STAY) /* the whole run's count */
                ha->count = loc.n ? ha->count / (size_t)loc.n * (size_t)q->sp.n : 0,
                ha->data = ha->count ? NULL : ha->data; /* (the data of an empty one: an empty dataset) */
        }
        dem_mpi_split_walls_put(&q->sp, acc, nw, &head); /* every rank's own particles' sums */
        ck_ctx c = {q, &loc, {0}, 0, NULL, err, len};
        checkpoint_source src = {&c, q->sp.n, np, q->ck_slab, ck_slab};
        rc = checkpoint_write_from(path, q->sp.part, &head, &src, sc, run, err, len);
        long done[5] = {FR_DONE, 0, 0, 0, 0};
        MPI_Bcast(done, 5, MPI_LONG, 0, q->comm);
        if (c.have)
            dem_state_free(&c.slab);
        free(c.radius);
    } else {
        for (;;) {
            long rq[5];
            MPI_Bcast(rq, 5, MPI_LONG, 0, q->comm);
            if (rq[0] != FR_CKSLAB)
                break;
            dem_state g;
            failed |= ck_answer(q, &loc, rq[3], rq[4], &g, err, len) != 0; /* -1 on every rank: rank 0 stops */
            if (!failed)
                dem_state_free(&g);
        }
    }
    dem_state_free(&loc);
    int who, a = agree(r, failed ? -2 : rc, &who); /* -2 where a part failed (its words on every rank), -1 the file */
    return a;
}

static void describe(run_ranks *r, char *buf, size_t len)
{
    rr *q = of(r);
    snprintf(buf, len, "split over %d MPI ranks by recursive bisection: %ld particles, %ld ghosts (%.1f %% more held), "
                       "halo 2 r_max + %.3g m, split anew when a particle has moved %.3g m (%ld split%s so far, %ld changes of rank)",
             r->size, q->sp.n, q->sp.ghosts_sum, 100.0 * (double)q->sp.ghosts_sum / (double)(q->sp.n ? q->sp.n : 1), q->sp.margin,
             0.5 * q->sp.margin, q->sp.splits, q->sp.splits == 1 ? "" : "s", q->sp.moves);
    if (q->sp.nsteps > 0) {
        double k = 1e3 / (double)q->sp.nsteps;
        size_t at = strlen(buf);
        snprintf(buf + at, len - at, "; rank 0 per step: its part's step %.3g ms, ghost exchange %.3g ms (%.4g kB "
                 "sent), check of the moves %.3g ms, merged sums %.3g ms, splits anew %.3g ms", k * q->sp.t_step,
                 k * q->sp.t_halo, q->sp.sent / (double)q->sp.nsteps / 1e3, k * q->sp.t_check, k * q->sp.t_sums, k * q->sp.t_split);
    }
}

static void finish(run_ranks *r)
{
    rr *q = of(r);
    if (q)
        dem_mpi_split_free(&q->sp);
}

int run_mpi_wanted(void)
{
    const char *n = getenv("OMPI_COMM_WORLD_SIZE"); /* Open MPI's mpirun sets it in every rank */
    return n && atoi(n) > 1;
}

int run_mpi(const run_opts *o)
{
    int provided;
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        fprintf(stderr, "dem: MPI does not start\n");
        return EXIT_DEVICE;
    }
    rr q;
    memset(&q, 0, sizeof q);
    q.comm = MPI_COMM_WORLD;
    MPI_Comm_rank(q.comm, &q.pub.rank);
    MPI_Comm_size(q.comm, &q.pub.size);
    q.pub.ctx = &q;
    q.pub.agree = agree, q.pub.agree_min = agree_min, q.pub.share = share, q.pub.start = start, q.pub.step = step;
    q.pub.step_index = step_index, q.pub.stepped = stepped, q.pub.checkpoint = checkpoint_parts, q.pub.describe = describe, q.pub.finish = finish;
    q.pub.frame = frame, q.pub.overlaps = overlaps, q.pub.sample = sample, q.pub.bounds = bounds;
    q.fval_f = -1;
    q.fail_step = -1;
    const char *tf = getenv("DEM_TEST_RANK_FAIL"); /* tests/mpi_check.sh: a rank that fails mid-run */
    char mode[16] = "";
    if (tf && sscanf(tf, "%ld %d %15s", &q.fail_step, &q.fail_rank, mode) < 2)
        q.fail_step = -1;
    q.sp.fail_step = q.fail_step, q.sp.fail_rank = q.fail_rank;
    q.sp.fail_mode = !strcmp(mode, "nan")    ? 2
                     : !strcmp(mode, "kill") ? 3
                     : strcmp(mode, "frame") && strcmp(mode, "checkpoint") ? 1
                                                                            : 0;
    q.sp.load = load_part, q.sp.load_arg = &q;
    q.sp.comm = q.comm; /* (its calls before the split's start: the messages' sharing) */
    const char *tm = getenv("DEM_TEST_HALO_MARGIN"); /* tests/mpi_run_check.sh: a thin halo (f r_max), whose ghosts
                                                      * touching own particles miss partners of theirs */
    q.sp.margin_f = tm && atof(tm) > 0 ? atof(tm) : 0;
    q.fail_frame = !strcmp(mode, "frame");
    q.fail_ck = !strcmp(mode, "checkpoint");
    const char *ts = getenv("DEM_TEST_FRAME_SLAB"); /* tests/mpi_run_check.sh: a checkpoint in small slabs too */
    q.ck_slab = ts && atol(ts) > 0 ? atol(ts) : RUN_MPI_CK_SLAB;
    run_opts mine = *o;
    const char *lr = getenv("OMPI_COMM_WORLD_LOCAL_RANK");
    int ndev = dem_device_count();
    if (mine.device < 0 && !getenv("DEM_DEVICE") && lr && ndev > 0) /* node-local rank k: device k modulo those seen */
        mine.device = atoi(lr) % ndev;
    int code = run_scene_ranks(&mine, &q.pub);
    /* every rank here before any leaves: mpirun ends the whole job as soon as one rank exits non-zero, which would
     * cut rank 0 short while it still prints the error or closes the output */
    fflush(NULL);
    MPI_Barrier(q.comm);
    MPI_Finalize();
    if (code == 128 + SIGINT) { /* everything written: die of it, as one process does (run.c) */
        signal(SIGINT, SIG_DFL);
        raise(SIGINT);
    }
    return code;
}
