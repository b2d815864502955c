/* run_mpi.c - `mpirun -np N dem run SCENE.yaml`: the run split over N ranks by space (docs/design.md "Runs over MPI").
 * run.c drives it through run_ranks (run.h); this file alone of app/ is compiled with MPI, and only dem links it.
 *
 * The split: recursive bisection of the particles' positions (the cut across the longest side of a part's particles,
 * at the count that gives each side its share of ranks), each rank a box. A rank's run holds its own particles and,
 * as ghosts, every particle within 2 r_max + margin of its box (margin = r_max), in ascending global id; after each
 * step the owners' values go to the ghosts (host/mpi/halo.c). Before a step, when some own particle has moved by
 * half the margin since the split, the run is split anew: each rank's particles and contacts move to the ranks that
 * keep them (dem_mpi_state_move). The walls' sums and the series rows are each rank's own particles', merged exactly
 * (dem_mpi_exact_allreduce): the bits of one process at any rank count. Frames are gathered on rank 0 from the parts
 * slab by slab (frame), and so are the checkpoints (checkpoint_parts): no rank holds the whole state. */
#include "run.h"
#include "dem_mpi.h"
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
    dem_config cfg;                                   /* the parts' (the run's device, precision, backend) */
    const dem_sim *from;                              /* what each part is copied from: this rank's whole run, the
                                                         scene's set-up, never started */
    dem_sim *part;                                    /* this rank's particles and ghosts, started */
    dem_mpi_halo h;
    int have_h;
    long n;                                           /* particles of the whole run */
    int nloc, nown;                                   /* held, and own of them */
    long *gid;                                        /* [nloc]: each held particle's global id, ascending */
    int *owner;                                       /* [nloc]: its rank */
    double *x0;                                       /* [3 nloc]: positions at the split */
    double rmax, margin;
    long splits;                                      /* the splits so far (the first included) */
    long ghosts_sum;                                  /* ghosts over all ranks at the last split */
    int *last_owner;                                  /* [n]: each particle's rank after the last split */
    long moves;                                       /* particles that changed rank at the splits anew */
    int nw;
    double domain[6];                                 /* the whole run's binning domain, given to every part */
    double *xprev, last_step;                         /* [3 nloc] positions before the last step; its longest move */
    long step;                                        /* the step the parts are at (also while none is held) */
    /* this rank's time per part of the steps [s] and what it sent to other ranks' ghosts: the report's and make
     * bench's (bench/mpi.sh) account of where a split run's time goes */
    double t_step, t_halo, t_check, t_split, t_sums, sent;
    long nsteps;
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
    long fail_step;                                   /* DEM_TEST_RANK_FAIL="STEP RANK [nan|frame|checkpoint]": */
    int fail_rank, fail_nan, fail_frame, fail_ck;     /* that rank fails there, after its step, or (nan) inside it:
                                                         a particle's position made NaN before the step, or (frame,
                                                         checkpoint) answering the first frame or checkpoint from
                                                         that step on */
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

static void share(run_ranks *r, int who, char *msg, size_t len)
{
    if (who < 0 || who >= r->size || !len)
        return;
    if (who != 0 && r->rank == who) { /* said as that rank's */
        char tmp[8192];
        snprintf(tmp, sizeof tmp, "rank %d: %s", who, msg);
        snprintf(msg, len, "%s", tmp);
    }
    msg[len - 1] = 0;
    int n = r->rank == who ? (int)strlen(msg) + 1 : 0;
    MPI_Bcast(&n, 1, MPI_INT, who, of(r)->comm);
    if (n > (int)len)
        n = (int)len;
    MPI_Bcast(msg, n, MPI_CHAR, who, of(r)->comm);
    msg[len - 1] = 0;
}

/* every rank's e agreed; on failure the first failing rank's message (its dem_error, or what is in err) to all */
static int agreed_msg(rr *q, int e, dem_sim *s, char *err, size_t len)
{
    if (e && s && err != NULL && !err[0])
        snprintf(err, len, "%s", dem_error(s));
    int who, a = agree(&q->pub, e, &who);
    if (a)
        share(&q->pub, who, err, len);
    return a;
}

/* after a call that agreed on failure e itself (the halo's, the gather): the words of the first rank that has any */
static int shared_error(rr *q, int e, char *err, size_t len)
{
    snprintf(err, len, "%s", q->part ? dem_error(q->part) : "");
    int who;
    agree(&q->pub, err[0] ? -1 : 0, &who);
    if (who >= 0)
        share(&q->pub, who, err, len);
    else
        snprintf(err, len, "a collective call failed (code %d)", e);
    return e;
}

/* ---- the split ---- */

/* ids[0..m) ordered by their coordinate along axis, ties by id (the same order on every rank) */
static const double *sort_x;
static int sort_axis;
static int by_coord(const void *a, const void *b)
{
    long i = *(const long *)a, j = *(const long *)b;
    double xi = sort_x[3 * i + sort_axis], xj = sort_x[3 * j + sort_axis];
    return xi < xj ? -1 : xi > xj ? 1 : (i > j) - (i < j);
}

/* Recursive bisection: ids[0..m) shared among ranks r0 .. r0 + np - 1, inside box (lo[3], hi[3]) */
static void bisect(const double *x, long *ids, long m, int r0, int np, double box[6], int *owner, double (*boxes)[6])
{
    if (np == 1) {
        for (long k = 0; k < m; k++)
            owner[ids[k]] = r0;
        memcpy(boxes[r0], box, sizeof(double) * 6);
        return;
    }
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (long k = 0; k < m; k++)
        for (int d = 0; d < 3; d++) {
            double v = x[3 * ids[k] + d];
            lo[d] = v < lo[d] ? v : lo[d];
            hi[d] = v > hi[d] ? v : hi[d];
        }
    int axis = 0;
    for (int d = 1; d < 3; d++)
        if (hi[d] - lo[d] > hi[axis] - lo[axis])
            axis = d;
    sort_x = x, sort_axis = axis;
    qsort(ids, (size_t)m, sizeof(long), by_coord);
    int nl = np / 2;
    long cut = m * nl / np; /* the left ranks' share of the particles */
    double c = 0.5 * (x[3 * ids[cut - 1] + axis] + x[3 * ids[cut] + axis]);
    double left[6], right[6];
    memcpy(left, box, sizeof left), memcpy(right, box, sizeof right);
    left[3 + axis] = c, right[axis] = c;
    bisect(x, ids, cut, r0, nl, left, owner, boxes);
    bisect(x, ids + cut, m - cut, r0 + nl, np - nl, right, owner, boxes);
}

/* the distance from point p to box b (0 inside) */
static double box_dist(const double *p, const double b[6])
{
    double s = 0;
    for (int d = 0; d < 3; d++) {
        double o = p[d] < b[d] ? b[d] - p[d] : p[d] > b[3 + d] ? p[d] - b[3 + d] : 0;
        s += o * o;
    }
    return sqrt(s);
}

static void drop_part(rr *q)
{
    if (q->have_h)
        dem_mpi_halo_free(&q->h);
    q->have_h = 0;
    dem_destroy(q->part);
    q->part = NULL;
    free(q->gid), free(q->owner), free(q->x0), free(q->xprev);
    q->gid = NULL, q->owner = NULL, q->x0 = NULL, q->xprev = NULL;
}

/* who keeps what in a split: a particle's owner, and every rank whose box it is within the halo's width of */
typedef struct {
    const double *x;        /* [3 n] the positions the split cuts by */
    const int *owner;       /* [n] */
    double (*boxes)[6];     /* [ranks] */
    double width;
} split_keep;
static int keeps(void *arg, long id, int rank)
{
    const split_keep *k = arg;
    return k->owner[id] == rank || box_dist(k->x + 3 * id, k->boxes[rank]) <= k->width;
}

/* This rank's part of the checkpoint q->ck_path, its radii checked against the scene's, into ps: 0, or a dem_status
 * with the reason in err */
static int part_from_checkpoint(rr *q, dem_state *ps, char *err, size_t len)
{
    double *rad = malloc(sizeof(double) * ((size_t)q->nloc + 1));
    if (!rad)
        return snprintf(err, len, "out of host memory reading %s", q->ck_path), DEM_ERR_NOMEM;
    int e = checkpoint_read_part(q->ck_path, q->ck, q->part, q->nloc, q->gid, ps, rad, err, len) ? DEM_ERR_ARG : 0;
    for (int k = 0; !e && k < q->nloc; k++) /* run.c's check of the whole, on each rank's part */
        if (rad[k] != dem_particle_radius(q->from, (int)q->gid[k])) {
            snprintf(err, len, "%s: particle %ld has radius %g m in the checkpoint and %g m in the scene (did a CSV "
                     "file change?)", q->ck_path, q->gid[k], rad[k], dem_particle_radius(q->from, (int)q->gid[k]));
            e = DEM_ERR_ARG;
        }
    free(rad);
    if (e)
        dem_state_free(ps);
    return e;
}

/* This rank's part, started, with its halo, split by the positions x[3 n] (the same on every rank). Fresh (a run's
 * start): its state its set-up's, the start's forces made with the halo's meetings (dem_mpi_halo_init). At a
 * restart's first split (q->ck): its state its part of the checkpoint, which it reads itself. Else its state moved
 * from each rank's state loc (held particles of global ids lgid, ranks lowner: dem_mpi_state_move): the ranks' last
 * parts. Collective; agreed; frees nothing it is given. */
static int split_from(rr *q, int fresh, long n, const double *x, const dem_state *loc, const long *lgid,
                      const int *lowner, char *err, size_t len)
{
    int P = q->pub.size, me = q->pub.rank, e = 0;
    err[0] = 0;
    long *ids = malloc(sizeof(long) * (size_t)(n ? n : 1));
    int *owner = malloc(sizeof(int) * (size_t)(n ? n : 1));
    unsigned char *keep = calloc((size_t)(n ? n : 1), 1), *ghost = NULL;
    double(*boxes)[6] = malloc(sizeof(double[6]) * (size_t)P);
    if (!ids || !owner || !keep || !boxes)
        e = DEM_ERR_NOMEM, snprintf(err, len, "out of host memory splitting %ld particles", n);
    else if (n < P)
        e = DEM_ERR_ARG, snprintf(err, len, "%ld particles cannot be split over %d ranks: run it on %ld or fewer", n,
                                  P, n);
    split_keep sk = {x, owner, boxes, 2 * q->rmax + q->margin};
    if (!e) {
        for (long k = 0; k < n; k++)
            ids[k] = k;
        double all[6] = {-INFINITY, -INFINITY, -INFINITY, INFINITY, INFINITY, INFINITY};
        bisect(x, ids, n, 0, P, all, owner, boxes);
        if (!q->last_owner)
            q->last_owner = malloc(sizeof(int) * (size_t)(n ? n : 1));
        else
            for (long k = 0; k < n; k++)
                q->moves += owner[k] != q->last_owner[k];
        if (q->last_owner)
            memcpy(q->last_owner, owner, sizeof(int) * (size_t)n);
        q->nloc = q->nown = 0;
        for (long k = 0; k < n; k++) {
            keep[k] = (unsigned char)keeps(&sk, k, me);
            q->nloc += keep[k];
            q->nown += owner[k] == me;
        }
        q->gid = malloc(sizeof(long) * (size_t)(q->nloc ? q->nloc : 1));
        q->owner = malloc(sizeof(int) * (size_t)(q->nloc ? q->nloc : 1));
        q->x0 = malloc(sizeof(double) * 3 * (size_t)(q->nloc ? q->nloc : 1));
        q->xprev = malloc(sizeof(double) * 3 * (size_t)(q->nloc ? q->nloc : 1));
        ghost = malloc((size_t)(q->nloc ? q->nloc : 1));
        if (!q->gid || !q->owner || !q->x0 || !q->xprev || !ghost)
            e = DEM_ERR_NOMEM, snprintf(err, len, "out of host memory");
        for (long k = 0, m = 0; !e && k < n; k++)
            if (keep[k]) {
                q->gid[m] = k, q->owner[m] = owner[k], ghost[m] = owner[k] != me;
                memcpy(q->x0 + 3 * m, x + 3 * k, sizeof(double) * 3);
                memcpy(q->xprev + 3 * m, x + 3 * k, sizeof(double) * 3);
                m++;
            }
    }
    if (!e && !(q->part = sim_part_copy(q->from, keep, err, len))) /* no scene file read again */
        e = DEM_ERR_NOMEM;
    if (!e && sim_set_ghosts(q->part, ghost))
        e = DEM_ERR_NOMEM;
    if (!e) /* the whole run's domain: wherever its particles go, the part's go too */
        e = dem_set_domain(q->part, q->domain, q->domain + 3);
    if (!e)
        e = fresh ? sim_start_deferred(q->part, &q->cfg) : dem_start(q->part, &q->cfg);
    dem_state ps;
    memset(&ps, 0, sizeof ps);
    if (!(e = agreed_msg(q, e, q->part, err, len)) && !fresh && q->ck) { /* each rank's part of the checkpoint */
        e = part_from_checkpoint(q, &ps, err, len);
        if (!e && (e = dem_state_set(q->part, &ps)))
            snprintf(err, len, "%s: %s", q->ck_path, dem_error(q->part));
    } else if (!e && !fresh) { /* the states moved where they are kept */
        e = dem_mpi_state_move(q->comm, q->part, loc, lgid, lowner, keeps, &sk, q->nloc, q->gid, &ps); /* agreed */
        if (e)
            snprintf(err, len, "the particles could not be moved to their new ranks (code %d: out of host memory, "
                     "or a message past MPI's int counts)", e);
        else
            e = dem_state_set(q->part, &ps);
    }
    dem_state_free(&ps);
    free(ids), free(owner), free(keep), free(ghost), free(boxes);
    if ((e = agreed_msg(q, e, q->part, err, len)))
        return e;
    e = dem_mpi_halo_init(&q->h, q->comm, q->part, q->nloc, q->gid, q->owner); /* agreed; fresh: the forces */
    q->have_h = e == 0;
    if (e) {
        dem_mpi_halo_free(&q->h);
        return shared_error(q, e, err, len);
    }
    long gh = q->nloc - q->nown;
    MPI_Allreduce(&gh, &q->ghosts_sum, 1, MPI_LONG, MPI_SUM, q->comm);
    q->splits++;
    return 0;
}

/* The parts made and started, each rank's cut from its own whole run (the scene's set-up, never started: no rank
 * holds a whole run's buffers or state), split by the positions at the start: the set-up's, which every rank holds,
 * or where the run restarts the checkpoint's, which every rank reads. A fresh part's state is its set-up's, the
 * start's forces made with the halo; a restarted part's is its own particles' and contacts' of the checkpoint, which
 * each rank reads itself (checkpoint_read_part). */
static int start(run_ranks *r, dem_sim *whole, const checkpoint *ck, const char *ck_path, const dem_config *cfg,
                 const char *what, char *err, size_t len)
{
    rr *q = of(r);
    q->cfg = *cfg;
    q->n = dem_count(whole), q->nw = dem_wall_count(whole);
    q->rmax = 0;
    for (int i = 0; i < q->n; i++)
        q->rmax = dem_particle_radius(whole, i) > q->rmax ? dem_particle_radius(whole, i) : q->rmax;
    q->margin = q->rmax; /* a split anew when a particle has moved r_max / 2 */
    const char *tm = getenv("DEM_TEST_HALO_MARGIN"); /* tests/mpi_run_check.sh: a thin halo (f r_max), whose ghosts
                                                      * touching own particles miss partners of theirs */
    if (tm && atof(tm) > 0)
        q->margin = atof(tm) * q->rmax;
    err[0] = 0;
    /* what dem_start would refuse of the whole scene (a time step past its bound, a sphere wider than its die), said
     * as one process says it; the part's own start checks only its particles */
    whole->cfg = *cfg;
    int e = sim_validate(whole);
    if (e)
        snprintf(err, len, "%s: %s", what, dem_error(whole));
    if ((e = agreed_msg(q, e, NULL, err, len)))
        return e;
    /* the whole scene's volume once (an exact sum over every particle), not at each split's copy */
    whole->whole_volume = sim_particle_volume(whole);
    q->from = whole;
    /* the binning domain of the whole run at its start (given, or its set-up's padded bounding box: what dem_start
     * of the whole run makes, a restart's too), every part's: wherever the particles go, the parts' go too */
    double pmin[3], pmax[3];
    sim_domain_bounds(whole, q->rmax, q->domain, q->domain + 3, pmin, pmax);
    q->step = ck ? ck->st.step : dem_step_index(whole);
    long n = q->n;
    /* the positions the split cuts by, on every rank the same: the set-up's, or the checkpoint's */
    double *x = ck ? malloc(sizeof(double) * 3 * (size_t)(n ? n : 1)) : NULL;
    if (ck && !x)
        e = DEM_ERR_NOMEM, snprintf(err, len, "%ld particles: out of host memory", n);
    else if (ck && checkpoint_read_x(ck_path, ck, x, err, len))
        e = DEM_ERR_ARG;
    if (!(e = agreed_msg(q, e, NULL, err, len))) {
        q->ck = ck, q->ck_path = ck_path;
        e = split_from(q, !ck, n, ck ? x : whole->x, NULL, NULL, NULL, err, len);
        q->ck = NULL, q->ck_path = NULL; /* a split anew moves the parts' states */
    }
    free(x);
    return e;
}

/* Every rank's own particles' positions, by global id, into x[3 n] on every rank (the split cuts by them): 3 reals
 * a particle, where a gather of the whole state moved every array and contact of every particle to every rank */
static int positions_all(rr *q, double *x)
{
    int P = q->pub.size, no = 0, e = 0;
    int *cnt = malloc(sizeof(int) * 2 * (size_t)P);
    long *ids = malloc(sizeof(long) * ((size_t)q->nown + 1)), *allid = malloc(sizeof(long) * ((size_t)q->n + 1));
    double *mine = malloc(sizeof(double) * 3 * ((size_t)q->nown + 1)),
           *all = malloc(sizeof(double) * 3 * ((size_t)q->n + 1));
    e = cnt && ids && allid && mine && all ? 0 : DEM_ERR_NOMEM;
    for (int k = 0; !e && k < q->nloc; k++)
        if (q->owner[k] == q->pub.rank) {
            ids[no] = q->gid[k];
            memcpy(mine + 3 * no, q->h.field + 3 * k, sizeof(double) * 3); /* the last exchange's (moved) */
            no++;
        }
    long total = 0;
    if (!(e = dem_mpi_agreed(q->comm, e))) {
        MPI_Allgather(&no, 1, MPI_INT, cnt, 1, MPI_INT, q->comm);
        for (int r = 0; r < P; r++)
            cnt[P + r] = (int)total, total += cnt[r];
        e = total == q->n && 3 * total <= INT_MAX ? 0 : DEM_ERR_ARG; /* the same verdict on every rank */
    }
    if (!e) {
        MPI_Allgatherv(ids, no, MPI_LONG, allid, cnt, cnt + P, MPI_LONG, q->comm);
        for (int r = 0; r < P; r++)
            cnt[r] *= 3, cnt[P + r] *= 3;
        MPI_Allgatherv(mine, 3 * no, MPI_DOUBLE, all, cnt, cnt + P, MPI_DOUBLE, q->comm);
        for (long k = 0; k < total; k++)
            memcpy(x + 3 * allid[k], all + 3 * k, sizeof(double) * 3);
    }
    free(cnt), free(ids), free(allid), free(mine), free(all);
    return e;
}

/* The run split anew by the positions now: each rank's state moved to the ranks that keep it in the new split (no
 * rank holds the whole state). Collective; agreed. */
static int split_anew(rr *q, char *err, size_t len)
{
    long n = q->n;
    double *x = malloc(sizeof(double) * 3 * (size_t)(n ? n : 1));
    int e = dem_mpi_agreed(q->comm, x ? 0 : DEM_ERR_NOMEM);
    e = e ? e : positions_all(q, x); /* agreed */
    dem_state loc;
    memset(&loc, 0, sizeof loc);
    if (!e)
        e = dem_mpi_agreed(q->comm, dem_state_get(q->part, &loc));
    if (e) {
        free(x);
        dem_state_free(&loc);
        return shared_error(q, e, err, len);
    }
    sim_run_record rec; /* the servo stages' records and the stage ends go on in the next part */
    sim_run_record_get(q->part, &rec);
    long *lgid = q->gid; /* the last part's, kept past its end for the move */
    int *lowner = q->owner;
    q->gid = NULL, q->owner = NULL;
    drop_part(q);
    e = split_from(q, 0, n, x, &loc, lgid, lowner, err, len);
    if (!e)
        sim_run_record_set(q->part, &rec);
    free(x), free(lgid), free(lowner);
    dem_state_free(&loc);
    return e;
}

static double dist3(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Over every rank: the largest distance an own particle has moved since the split, plus twice the longest move of
 * the last step (the step to come drifts the particles before their forces: by about that much). A NaN counts as
 * far. */
static double moved(rr *q)
{
    /* the positions as the last exchange left them (dem_mpi_halo: its field holds x first; a halo set up has them):
     * no read of the device, and nothing that can fail */
    const double *x = q->h.field;
    double m[2] = {0, 0}, out[2];
    for (int k = 0; k < q->nloc; k++)
        if (q->owner[k] == q->pub.rank) {
            double d = dist3(x + 3 * k, q->x0 + 3 * k), st = dist3(x + 3 * k, q->xprev + 3 * k);
            m[0] = d > m[0] || d != d ? d : m[0];
            m[1] = st > m[1] || st != st ? st : m[1];
        }
    memcpy(q->xprev, x, sizeof(double) * 3 * (size_t)q->nloc);
    for (int k = 0; k < 2; k++)
        m[k] = m[k] != m[k] ? INFINITY : m[k];
    MPI_Allreduce(m, out, 2, MPI_DOUBLE, MPI_MAX, q->comm);
    return out[0] + 2 * out[1];
}

/* The exact sums of the last step merged over the ranks: the series row's (SE_*) and each wall's (WP_*), rounded
 * as one process rounds them (common/series.h, host/physics/energy.c) */
static int merged_sums(rr *q, int nw, exact_acc *acc)
{
    int e = 0;
    sim_row_exact(q->part, acc);
    for (int w = 0; !e && w < nw; w++)
        e = sim_wall_sums_exact(q->part, w, acc + SE_STRIDE + WP_STRIDE * w);
    int m = dem_mpi_exact_allreduce(q->comm, acc, SE_STRIDE + WP_STRIDE * nw);
    return e ? e : m ? DEM_ERR_DEVICE : 0;
}

static double rounded(const rr *q, const exact_acc *a)
{
    return q->cfg.precision == DEM_FP64 ? exact_to_double(a) : (double)exact_to_float(a);
}

/* a series row's energies and contact counts from the merged exact sums (SE_*), each rounded once to double as one
 * process rounds them (host/physics/energy.c) */
static void energies_of(const exact_acc *acc, dem_energy_t *en)
{
    en->kinetic = exact_to_double(&acc[SE_KIN]);
    en->potential = exact_to_double(&acc[SE_POT]);
    en->elastic = exact_to_double(&acc[SE_ELA]);
    en->contacts = (long)exact_to_double(&acc[SE_CON]);
    en->wall_contacts = (long)exact_to_double(&acc[SE_WCON]);
    en->total = en->kinetic + en->elastic + en->potential;
}

static int step(run_ranks *r, long nsteps, const unsigned char *want, dem_sample *rows, char *err, size_t len)
{
    rr *q = of(r);
    int walls = (q->part->effects & DEM_EFFECT_WALLS) && q->nw > 0;
    exact_acc acc[SE_STRIDE + WP_STRIDE * DEM_MAX_WALLS];
    dem_sample *o = rows;
    err[0] = 0;
    for (long k = 0; k < nsteps; k++) {
        double t0 = MPI_Wtime(), most = moved(q), t1 = MPI_Wtime();
        int e;
        q->t_check += t1 - t0;
        if (most > 0.5 * q->margin && (e = split_anew(q, err, len))) /* cut by the positions now */
            return e;
        double t2 = MPI_Wtime();
        q->t_split += t2 - t1;
        int wk = want && want[k];
        dem_sample one;
        if (q->fail_nan && q->fail_step == q->step + 1 && q->fail_rank == r->rank && q->nown > 0) { /* test hook */
            double *x = malloc(sizeof(double) * 3 * (size_t)q->nloc);
            int own = 0;
            while (own < q->nloc && q->owner[own] != r->rank)
                own++;
            if (x && !dem_get_field(q->part, DEM_FIELD_X, x)) {
                x[3 * own] = NAN;
                sim_set_field(q->part, DEM_FIELD_X, x);
            }
            free(x);
        }
        long before = q->step;
        e = dem_step_sampled(q->part, 1, wk ? (const unsigned char[1]){1} : NULL, &one);
        if (!e && !q->fail_nan && !q->fail_frame && !q->fail_ck && q->fail_step == dem_step_index(q->part) &&
            q->fail_rank == r->rank) { /* the test hook */
            snprintf(err, len, "DEM_TEST_RANK_FAIL: this rank's step %ld fails as a lost device's would",
                     q->fail_step);
            e = DEM_ERR_DEVICE;
        }
        q->step = dem_step_index(q->part);
        double t3 = MPI_Wtime();
        q->t_step += t3 - t2;
        /* a step that failed here only because another rank's did (a meeting inside the step, host/mpi/halo.c):
         * that rank's code and words are the ones to agree on */
        int mine = e && q->part->run.halo_learned ? 0 : e, a = agreed_msg(q, mine, q->part, err, len);
        if ((e = a ? a : e)) { /* a == 0 with e set cannot be: some rank's own step failed */
            /* the run stopped where this step began, as one process's failed step counts nothing: a rank whose own
             * step went through and learned of another's failure after it has counted it, one that learned at a
             * meeting inside the step has not */
            q->step = before;
            return e;
        }
        if ((e = dem_mpi_halo_exchange(&q->h)))
            return shared_error(q, e, err, len);
        double t4 = MPI_Wtime();
        q->t_halo += t4 - t3;
        q->sent += (double)HALO_W * q->h.rs * (double)q->h.nsend; /* a row of HALO_W reals per ghost (halo.h) */
        q->nsteps++;
        if (!wk)
            continue;
        int nw = walls ? q->nw : 0;
        for (int a = 0; a < SE_STRIDE + WP_STRIDE * nw; a++)
            exact_clear(&acc[a]);
        e = merged_sums(q, nw, acc);
        if ((e = agreed_msg(q, e, q->part, err, len)))
            return e;
        energies_of(acc, &one.energy);
        for (int w = 0; w < nw; w++) {
            const exact_acc *a = acc + SE_STRIDE + WP_STRIDE * w;
            for (int d = 0; d < 3; d++)
                one.wall_force[3 * w + d] = rounded(q, &a[WP_FX + d]);
            one.wall_normal[w] = rounded(q, &a[WP_FN]);
        }
        *o++ = one;
        q->t_sums += MPI_Wtime() - t4;
    }
    return 0;
}

/* The series row of the state now (the run's first): each part's own particles' energies and contacts, exact,
 * merged; its walls' sums are the run's (merged at a fresh start, the checkpoint's at a restart) */
static int sample(run_ranks *r, dem_sample *row, char *err, size_t len)
{
    rr *q = of(r);
    exact_acc acc[SE_STRIDE];
    err[0] = 0;
    int e = sim_sample_own(q->part, row, acc);
    if ((e = agreed_msg(q, e, q->part, err, len)))
        return e;
    if ((e = agreed_msg(q, dem_mpi_exact_allreduce(q->comm, acc, SE_STRIDE) ? DEM_ERR_DEVICE : 0, NULL, err, len))) {
        if (!err[0])
            snprintf(err, len, "the ranks' energies could not be merged (MPI)");
        return e;
    }
    energies_of(acc, &row->energy);
    return 0;
}

static void bounds(run_ranks *r, double box[6])
{
    rr *q = of(r);
    double mine[6] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY}; /* lo, then -hi */
    const double *x = q->h.field; /* the positions as the last exchange left them */
    for (int k = 0; k < q->nloc; k++)
        if (q->owner[k] == r->rank) {
            double rad = dem_particle_radius(q->part, k);
            for (int d = 0; d < 3; d++)
                mine[d] = fmin(mine[d], x[3 * k + d] - rad), mine[3 + d] = fmin(mine[3 + d], -(x[3 * k + d] + rad));
        }
    MPI_Allreduce(mine, box, 6, MPI_DOUBLE, MPI_MIN, q->comm);
    for (int d = 0; d < 3; d++)
        box[3 + d] = -box[3 + d];
}

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
    if (dem_contacts_get(q->part, &cs, &count, &np))
        return -1;
    long m = 0, mp = 0;
    for (long k = 0; k < count; k++) {
        int i = cs[k].i, j = cs[k].j;
        if (q->owner[i] != q->pub.rank)
            continue;
        cs[m] = cs[k];
        cs[m].i = (int)q->gid[i];
        cs[m].j = j >= 0 ? (int)q->gid[j] : j;
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
            q->fval = malloc(sizeof(double) * (size_t)nc * (size_t)(q->nloc ? q->nloc : 1));
            if (!q->fval || dem_get_field(q->part, (dem_field)rq[1], q->fval))
                mine = -1;
            else
                q->fval_f = (int)rq[1];
        }
        int k0 = dem_mpi_id_from(q->gid, q->nloc, a), k1 = dem_mpi_id_from(q->gid, q->nloc, b);
        double *buf = mine ? NULL : malloc((size_t)unit * (size_t)(k1 - k0 + 1));
        mine = mine || !buf;
        for (int k = k0; !mine && k < k1; k++)
            if (q->owner[k] == me) {
                buf[(size_t)m * (1 + nc)] = (double)q->gid[k]; /* exact: ids below 2^53 */
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
    if (q->fail_frame && q->fail_rank == me && dem_step_index(q->part) >= q->fail_step && !mine) /* test hook */
        mine = -1, snprintf(err, len, "DEM_TEST_RANK_FAIL: rank %d cannot read its part for the frame at step %ld", me,
                            dem_step_index(q->part));
    if (mine && !err[0])
        snprintf(err, len, "%s", dem_error(q->part)[0] ? dem_error(q->part) : "out of host memory");
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
            rc = output_frame_from(o, q->part, &src);
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
    long slots = dem_neighbor_capacity(q->part) > 0, any = 0;
    MPI_Allreduce(&slots, &any, 1, MPI_LONG, MPI_MAX, q->comm);
    if (!any)
        return;
    unsigned char *own = malloc((size_t)(q->nloc ? q->nloc : 1));
    int e = !own;
    for (int k = 0; own && k < q->nloc; k++)
        own[k] = q->owner[k] == r->rank;
    e = e || overlap_frame_scan(w, q->part, q->gid, own, &f);
    free(own);
    int se = e || dem_stability_get(q->part, &st);
    if (!se && st.particle >= 0)
        st.particle = (int)q->gid[st.particle];
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
        overlap_watch_add(w, &f, bad_st ? NULL : &st, dem_time(q->part));
    free(all), free(sts);
}

static long step_index(run_ranks *r) { return of(r)->step; }
static dem_sim *stepped(run_ranks *r) { return of(r)->part; }

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
    if (q->fail_ck && q->fail_rank == me && q->step >= q->fail_step) /* test hook */
        mine = DEM_ERR_DEVICE, snprintf(err, len, "DEM_TEST_RANK_FAIL: rank %d cannot read its part for the "
                                                  "checkpoint at step %ld", me, q->step);
    if (q->fail_ck && agree(&q->pub, mine, &who)) { /* (the hook's setting is every rank's: mpirun's environment) */
        share(&q->pub, who, err, len);
        return -1;
    }
    int e = dem_mpi_state_slab(&q->h, q->gid, q->owner, q->n, loc, a, b, 0, g); /* agreed */
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
        r[k - a] = dem_particle_radius(q->from, (int)k);
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
    int e = dem_mpi_agreed(q->comm, dem_state_get(q->part, &loc));
    if (e) {
        shared_error(q, e, err, len);
        return -2;
    }
    long mine = 0, np = 0; /* the whole run's contacts: each rank's own */
    for (long p = 0; p < loc.npairs; p++)
        mine += q->owner[loc.pair_i[p]] == r->rank;
    MPI_Allreduce(&mine, &np, 1, MPI_LONG, MPI_SUM, q->comm);
    int nw = (q->part->effects & DEM_EFFECT_WALLS) ? q->nw : 0;
    exact_acc acc[SE_STRIDE + WP_STRIDE * DEM_MAX_WALLS];
    for (int a = 0; a < SE_STRIDE + WP_STRIDE * nw; a++)
        exact_clear(&acc[a]);
    if (agreed_msg(q, merged_sums(q, nw, acc), q->part, err, len)) {
        dem_state_free(&loc);
        return -2;
    }
    int rc = 0, failed = 0;
    if (r->rank == 0) {
        dem_state head = loc; /* its arrays' pointers loc's: not freed through head */
        for (int k = 0; k < head.narrays; k++) {
            dem_state_array *ha = &head.arrays[k];
            int per;
            if (sim_state_array_layout(q->part, ha->name, &per) != DEM_MOVE_STAY) /* the whole run's count */
                ha->count = loc.n ? ha->count / (size_t)loc.n * (size_t)q->n : 0,
                ha->data = ha->count ? NULL : ha->data; /* (the data of an empty one: an empty dataset) */
        }
        dem_state_array *wf = dem_state_find(&head, "wall_force"), *wn = dem_state_find(&head, "wall_normal_force");
        for (int w = 0; w < nw; w++) { /* the walls' sums: every rank's own particles', as one process rounds them */
            const exact_acc *a = acc + SE_STRIDE + WP_STRIDE * w;
            for (int d = 0; wf && wf->data && d < 3; d++)
                sim_real_put(wf->data, (size_t)(3 * w + d), head.real_size, rounded(q, &a[WP_FX + d]));
            if (wn && wn->data)
                sim_real_put(wn->data, (size_t)w, head.real_size, rounded(q, &a[WP_FN]));
        }
        ck_ctx c = {q, &loc, {0}, 0, NULL, err, len};
        checkpoint_source src = {&c, q->n, np, q->ck_slab, ck_slab};
        rc = checkpoint_write_from(path, q->part, &head, &src, sc, run, err, len);
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
             r->size, q->n, q->ghosts_sum, 100.0 * (double)q->ghosts_sum / (double)(q->n ? q->n : 1), q->margin,
             0.5 * q->margin, q->splits, q->splits == 1 ? "" : "s", q->moves);
    if (q->nsteps > 0) {
        double k = 1e3 / (double)q->nsteps;
        size_t at = strlen(buf);
        snprintf(buf + at, len - at, "; rank 0 per step: its part's step %.3g ms, ghost exchange %.3g ms (%.4g kB "
                 "sent), check of the moves %.3g ms, merged sums %.3g ms, splits anew %.3g ms", k * q->t_step,
                 k * q->t_halo, q->sent / (double)q->nsteps / 1e3, k * q->t_check, k * q->t_sums, k * q->t_split);
    }
}

static void finish(run_ranks *r)
{
    rr *q = of(r);
    if (q) {
        drop_part(q);
        free(q->last_owner);
        q->last_owner = NULL;
    }
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
    q.fail_nan = !strcmp(mode, "nan");
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
