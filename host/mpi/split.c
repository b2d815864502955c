/* split.c - a run split by space over the ranks of a communicator (mpi_layer.h "a run split by space"): the split
 * by recursive bisection, each rank's part started with its halo, the steps with the ghosts' exchange and the splits
 * anew, the merged series rows and walls' sums. `mpirun -np N dem run` (app/run_mpi.c) and dem_create_mpi
 * (host/mpi/api.c) drive it. */
#include "mpi_layer.h"
#include "sim.h"
#include "dem_layout.h"
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void dem_mpi_share(MPI_Comm comm, int who, char *msg, size_t len)
{
    int rank, size;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    if (who < 0 || who >= size || !len)
        return;
    if (who != 0 && rank == who) { /* said as that rank's */
        char tmp[8192];
        snprintf(tmp, sizeof tmp, "rank %d: %s", who, msg);
        snprintf(msg, len, "%s", tmp);
    }
    msg[len - 1] = 0;
    int n = rank == who ? (int)strlen(msg) + 1 : 0;
    MPI_Bcast(&n, 1, MPI_INT, who, comm);
    if (n > (int)len)
        n = (int)len;
    MPI_Bcast(msg, n, MPI_CHAR, who, comm);
    msg[len - 1] = 0;
}

int dem_mpi_split_agreed(dem_mpi_split *q, int e, dem_sim *s, char *err, size_t len)
{
    if (e && s && err != NULL && !err[0])
        snprintf(err, len, "%s", dem_error(s));
    int who, a = dem_mpi_agreed_who(q->comm, e, &who);
    if (a)
        dem_mpi_share(q->comm, who, err, len);
    return a;
}

int dem_mpi_split_shared_error(dem_mpi_split *q, int e, char *err, size_t len)
{
    snprintf(err, len, "%s", q->part ? dem_error(q->part) : "");
    int who;
    dem_mpi_agreed_who(q->comm, err[0] ? -1 : 0, &who);
    if (who >= 0)
        dem_mpi_share(q->comm, who, err, len);
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

static void drop_part(dem_mpi_split *q)
{
    if (q->have_h)
        dem_mpi_halo_free(&q->h);
    q->have_h = 0;
    dem_destroy(q->part);
    q->part = NULL;
    free(q->gid), free(q->owner);
    q->gid = NULL, q->owner = NULL;
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


/* This rank's part, started, with its halo, split by the positions x[3 n] (the same on every rank). Fresh (a run's
 * start): its state its set-up's, the start's forces made with the halo's meetings (dem_mpi_halo_init). At a
 * restart's first split (loc NULL): its state its part of the restart's, which q->load reads. Else its state moved
 * from each rank's state loc (held particles of global ids lgid, ranks lowner: dem_mpi_state_move): the ranks' last
 * parts. Collective; agreed; frees nothing it is given. */
static int split_from(dem_mpi_split *q, int fresh, long n, const double *x, const dem_state *loc, const long *lgid,
                      const int *lowner, char *err, size_t len)
{
    int P = q->size, me = q->rank, e = 0;
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
        ghost = malloc((size_t)(q->nloc ? q->nloc : 1));
        if (!q->gid || !q->owner || !ghost)
            e = DEM_ERR_NOMEM, snprintf(err, len, "out of host memory");
        for (long k = 0, m = 0; !e && k < n; k++)
            if (keep[k]) {
                q->gid[m] = k, q->owner[m] = owner[k], ghost[m] = owner[k] != me;
                m++;
            }
    }
    if (!e && !(q->part = sim_part_copy(q->from, keep, err, len))) /* no scene file read again */
        e = DEM_ERR_NOMEM;
    if (!e && sim_set_ghosts(q->part, ghost))
        e = DEM_ERR_NOMEM;
    if (!e) /* its messages name the whole run's particles */
        q->part->said_ids = q->gid;
    if (!e) /* the whole run's domain: wherever its particles go, the part's go too */
        e = dem_set_domain(q->part, q->domain, q->domain + 3);
    if (!e)
        e = fresh ? sim_start_deferred(q->part, &q->cfg) : dem_start(q->part, &q->cfg);
    dem_state ps;
    memset(&ps, 0, sizeof ps);
    if (!(e = dem_mpi_split_agreed(q, e, q->part, err, len)) && !fresh && !loc) { /* the caller's part of it */
        e = q->load(q->load_arg, q, &ps, err, len);
        if (!e && (e = dem_state_set(q->part, &ps)))
            snprintf(err, len, "%s%s%s", q->load_what ? q->load_what : "", q->load_what ? ": " : "",
                     dem_error(q->part));
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
    if ((e = dem_mpi_split_agreed(q, e, q->part, err, len)))
        return e;
    e = dem_mpi_halo_init(&q->h, q->comm, q->part, q->nloc, q->gid, q->owner); /* agreed; fresh: the forces */
    q->have_h = e == 0;
    if (e) {
        dem_mpi_halo_free(&q->h);
        return dem_mpi_split_shared_error(q, e, err, len);
    }
    double none[2]; /* the positions now, where the check of the moves measures from (on the device) */
    if ((e = dem_mpi_agreed(q->comm, sim_move_check(q->part, 1, none))))
        return dem_mpi_split_shared_error(q, e, err, len);
    long gh = q->nloc - q->nown;
    MPI_Allreduce(&gh, &q->ghosts_sum, 1, MPI_LONG, MPI_SUM, q->comm);
    q->splits++;
    return 0;
}


/* The parts made and started, each rank's cut from its own whole run (the set-up, never started: no rank holds a
 * whole run's buffers or state), split by the positions at the start: the set-up's, which every rank holds, or where
 * the run restarts the caller's (a checkpoint's, which every rank reads). A fresh part's state is its set-up's, the
 * start's forces made with the halo; a restarted part's is what q->load reads of its own particles and contacts. */
int dem_mpi_split_start(dem_mpi_split *q, MPI_Comm comm, dem_sim *whole, const dem_config *cfg, const double *x,
                        long step0, const char *what, char *err, size_t len)
{
    q->comm = comm;
    MPI_Comm_rank(comm, &q->rank);
    MPI_Comm_size(comm, &q->size);
    q->cfg = *cfg;
    q->n = dem_count(whole), q->nw = dem_wall_count(whole);
    q->rmax = 0;
    for (int i = 0; i < q->n; i++)
        q->rmax = dem_particle_radius(whole, i) > q->rmax ? dem_particle_radius(whole, i) : q->rmax;
    q->margin = (q->margin_f > 0 ? q->margin_f : 1) * q->rmax; /* a split anew when a particle has moved margin / 2 */
    err[0] = 0;
    int e = x && !q->load ? DEM_ERR_ARG : 0;
    if (e)
        snprintf(err, len, "dem_mpi_split_start: a restart's positions without the reader of its state");
    /* what dem_start would refuse of the whole scene (a time step past its bound, a sphere wider than its die), said
     * as one process says it; the part's own start checks only its particles */
    whole->cfg = *cfg;
    if (!e && (e = sim_validate(whole)))
        snprintf(err, len, "%s: %s", what, dem_error(whole));
    if ((e = dem_mpi_split_agreed(q, e, NULL, err, len)))
        return e;
    /* the whole scene's volume once (an exact sum over every particle), not at each split's copy */
    whole->whole_volume = sim_particle_volume(whole);
    q->from = whole;
    /* the binning domain of the whole run at its start (given, or its set-up's padded bounding box: what dem_start
     * of the whole run makes, a restart's too), every part's: wherever the particles go, the parts' go too */
    double pmin[3], pmax[3];
    sim_domain_bounds(whole, q->rmax, q->domain, q->domain + 3, pmin, pmax);
    q->step = x ? step0 : dem_step_index(whole);
    return split_from(q, !x, q->n, x ? x : whole->x, NULL, NULL, NULL, err, len);
}

int dem_mpi_split_rows(dem_mpi_split *q, const double *vals, int nc, double *out)
{
    int P = q->size, no = 0, e = 0;
    int *cnt = malloc(sizeof(int) * 2 * (size_t)P);
    long *ids = malloc(sizeof(long) * ((size_t)q->nown + 1)), *allid = malloc(sizeof(long) * ((size_t)q->n + 1));
    double *mine = malloc(sizeof(double) * (size_t)nc * ((size_t)q->nown + 1)),
           *all = malloc(sizeof(double) * (size_t)nc * ((size_t)q->n + 1));
    e = cnt && ids && allid && mine && all ? 0 : DEM_ERR_NOMEM;
    for (int k = 0; !e && k < q->nloc; k++)
        if (q->owner[k] == q->rank) {
            ids[no] = q->gid[k];
            memcpy(mine + (size_t)nc * no, vals + (size_t)nc * k, sizeof(double) * nc);
            no++;
        }
    long total = 0;
    if (!(e = dem_mpi_agreed(q->comm, e))) {
        MPI_Allgather(&no, 1, MPI_INT, cnt, 1, MPI_INT, q->comm);
        for (int r = 0; r < P; r++)
            cnt[P + r] = (int)total, total += cnt[r];
        e = total == q->n && (long)nc * total <= INT_MAX ? 0 : DEM_ERR_ARG; /* the same verdict on every rank */
    }
    if (!e) {
        MPI_Allgatherv(ids, no, MPI_LONG, allid, cnt, cnt + P, MPI_LONG, q->comm);
        for (int r = 0; r < P; r++)
            cnt[r] *= nc, cnt[P + r] *= nc;
        MPI_Allgatherv(mine, nc * no, MPI_DOUBLE, all, cnt, cnt + P, MPI_DOUBLE, q->comm);
        for (long k = 0; k < total; k++)
            memcpy(out + (size_t)nc * allid[k], all + (size_t)nc * k, sizeof(double) * nc);
    }
    free(cnt), free(ids), free(allid), free(mine), free(all);
    return e;
}

/* The run split anew by the positions now: each rank's state moved to the ranks that keep it in the new split (no
 * rank holds the whole state). Collective; agreed. */
static int split_anew(dem_mpi_split *q, char *err, size_t len)
{
    long n = q->n;
    double *x = malloc(sizeof(double) * 3 * (size_t)(n ? n : 1));
    int e = dem_mpi_agreed(q->comm, x ? 0 : DEM_ERR_NOMEM);
    if (!e) /* the positions now (the last exchange's: the own particles' are their owners') */
        e = dem_mpi_agreed(q->comm, dem_get_field(q->part, DEM_FIELD_X, q->h.field));
    e = e ? e : dem_mpi_split_rows(q, q->h.field, 3, x); /* agreed */
    dem_state loc;
    memset(&loc, 0, sizeof loc);
    if (!e)
        e = dem_mpi_agreed(q->comm, dem_state_get(q->part, &loc));
    if (e) {
        free(x);
        dem_state_free(&loc);
        return dem_mpi_split_shared_error(q, e, err, len);
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

/* Over every rank: the largest distance an own particle has moved since the split, plus twice the longest move of
 * the last step (the step to come drifts the particles before their forces: by about that much), into *most.
 * Measured on the device (sim_move_check: 2 reals a block of particles read, not the positions). A NaN counts as
 * far. Collective; agreed: a rank whose check failed makes every rank return its code, its words in err. */
static int moved(dem_mpi_split *q, double *most, char *err, size_t len)
{
    double m[3], out[3];
    int e = sim_move_check(q->part, 0, m);
    for (int k = 0; k < 2; k++)
        m[k] = e || m[k] != m[k] ? INFINITY : m[k];
    m[2] = e ? 1 : 0;
    MPI_Allreduce(m, out, 3, MPI_DOUBLE, MPI_MAX, q->comm);
    *most = out[0] + 2 * out[1];
    return out[2] > 0 ? dem_mpi_split_agreed(q, e, q->part, err, len) : 0;
}

/* The exact sums of the last step merged over the ranks: the series row's (SE_*) and each wall's (WP_*), rounded
 * as one process rounds them (common/series.h, host/physics/energy.c) */
static int merged_sums(dem_mpi_split *q, int nw, exact_acc *acc)
{
    int e = 0;
    sim_row_exact(q->part, acc);
    for (int w = 0; !e && w < nw; w++)
        e = sim_wall_sums_exact(q->part, w, acc + SE_STRIDE + WP_STRIDE * w);
    int m = dem_mpi_exact_allreduce(q->comm, acc, SE_STRIDE + WP_STRIDE * nw);
    return e ? e : m ? DEM_ERR_DEVICE : 0;
}

static double rounded(const dem_mpi_split *q, const exact_acc *a)
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

int dem_mpi_split_step(dem_mpi_split *q, long nsteps, const unsigned char *want, dem_sample *rows, char *err,
                       size_t len)
{
    int walls = (q->part->effects & DEM_EFFECT_WALLS) && q->nw > 0;
    exact_acc acc[SE_STRIDE + WP_STRIDE * DEM_MAX_WALLS];
    dem_sample *o = rows;
    err[0] = 0;
    for (long k = 0; k < nsteps; k++) {
        double t0 = MPI_Wtime(), most;
        int e = moved(q, &most, err, len);
        double t1 = MPI_Wtime();
        q->t_check += t1 - t0;
        if (e)
            return e;
        if (most > 0.5 * q->margin && (e = split_anew(q, err, len))) /* cut by the positions now */
            return e;
        double t2 = MPI_Wtime();
        q->t_split += t2 - t1;
        int wk = want && want[k];
        dem_sample one;
        if (q->fail_mode == 2 && q->fail_step == q->step + 1 && q->fail_rank == q->rank && q->nown > 0) { /* test hook */
            double *x = malloc(sizeof(double) * 3 * (size_t)q->nloc);
            int own = 0;
            while (own < q->nloc && q->owner[own] != q->rank)
                own++;
            if (x && !dem_get_field(q->part, DEM_FIELD_X, x)) {
                x[3 * own] = NAN;
                sim_set_field(q->part, DEM_FIELD_X, x);
            }
            free(x);
        }
        long before = q->step;
        e = dem_step_sampled(q->part, 1, wk ? (const unsigned char[1]){1} : NULL, &one);
        if (!e && (q->fail_mode == 1 || q->fail_mode == 3) && q->fail_step == dem_step_index(q->part) &&
            q->fail_rank == q->rank) { /* the test hooks: a rank killed mid-run (3), or whose step fails (1) */
            if (q->fail_mode == 3)
                raise(SIGKILL);
            snprintf(err, len, "DEM_TEST_RANK_FAIL: this rank's step %ld fails as a lost device's would",
                     q->fail_step);
            e = DEM_ERR_DEVICE;
        }
        q->step = dem_step_index(q->part);
        double t3 = MPI_Wtime();
        q->t_step += t3 - t2;
        /* a step that failed here only because another rank's did (a meeting inside the step, host/mpi/halo.c):
         * that rank's code and words are the ones to agree on */
        int mine = e && q->part->run.halo_learned ? 0 : e, a = dem_mpi_split_agreed(q, mine, q->part, err, len);
        if ((e = a ? a : e)) { /* a == 0 with e set cannot be: some rank's own step failed */
            /* the run stopped where this step began, as one process's failed step counts nothing: a rank whose own
             * step went through and learned of another's failure after it has counted it, one that learned at a
             * meeting inside the step has not */
            q->step = before;
            return e;
        }
        if ((e = dem_mpi_halo_exchange(&q->h)))
            return dem_mpi_split_shared_error(q, e, err, len);
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
        if ((e = dem_mpi_split_agreed(q, e, q->part, err, len)))
            return e;
        energies_of(acc, &one.energy);
        dem_mpi_split_walls_row(q, acc, nw, &one);
        *o++ = one;
        q->t_sums += MPI_Wtime() - t4;
    }
    return 0;
}

/* The series row of the state now (the run's first): each part's own particles' energies and contacts, exact,
 * merged; its walls' sums are the run's (merged at a fresh start, the checkpoint's at a restart) */
int dem_mpi_split_sample(dem_mpi_split *q, dem_sample *row, char *err, size_t len)
{
    exact_acc acc[SE_STRIDE];
    err[0] = 0;
    int e = sim_sample_own(q->part, row, acc);
    if ((e = dem_mpi_split_agreed(q, e, q->part, err, len)))
        return e;
    if ((e = dem_mpi_split_agreed(q, dem_mpi_exact_allreduce(q->comm, acc, SE_STRIDE) ? DEM_ERR_DEVICE : 0, NULL, err, len))) {
        if (!err[0])
            snprintf(err, len, "the ranks' energies could not be merged (MPI)");
        return e;
    }
    energies_of(acc, &row->energy);
    return 0;
}

int dem_mpi_split_bounds(dem_mpi_split *q, double box[6])
{
    /* lo, then -hi, then -1 where this rank could not read its positions (the smallest over the ranks: any rank's) */
    double mine[7] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, 0}, all[7];
    const double *x = q->h.field; /* the positions now */
    int e = dem_get_field(q->part, DEM_FIELD_X, q->h.field);
    mine[6] = e ? -1 : 0;
    for (int k = 0; !e && k < q->nloc; k++)
        if (q->owner[k] == q->rank) {
            double rad = dem_particle_radius(q->part, k);
            for (int d = 0; d < 3; d++)
                mine[d] = fmin(mine[d], x[3 * k + d] - rad), mine[3 + d] = fmin(mine[3 + d], -(x[3 * k + d] + rad));
        }
    MPI_Allreduce(mine, all, 7, MPI_DOUBLE, MPI_MIN, q->comm);
    for (int d = 0; d < 3; d++)
        box[d] = all[d], box[3 + d] = -all[3 + d];
    return all[6] < 0 ? DEM_ERR_DEVICE : 0;
}

int dem_mpi_split_walls(dem_mpi_split *q, exact_acc *acc, int *nw, char *err, size_t len)
{
    *nw = (q->part->effects & DEM_EFFECT_WALLS) ? q->nw : 0;
    for (int a = 0; a < SE_STRIDE + WP_STRIDE * *nw; a++)
        exact_clear(&acc[a]);
    return dem_mpi_split_agreed(q, merged_sums(q, *nw, acc), q->part, err, len);
}

void dem_mpi_split_walls_row(const dem_mpi_split *q, const exact_acc *acc, int nw, dem_sample *row)
{
    for (int w = 0; w < nw; w++) { /* every rank's own particles' sums, each rounded once as one process rounds it */
        const exact_acc *a = acc + SE_STRIDE + WP_STRIDE * w;
        for (int d = 0; d < 3; d++)
            row->wall_force[3 * w + d] = rounded(q, &a[WP_FX + d]);
        row->wall_normal[w] = rounded(q, &a[WP_FN]);
    }
}

void dem_mpi_split_walls_put(const dem_mpi_split *q, const exact_acc *acc, int nw, dem_state *st)
{
    dem_state_array *wf = st ? dem_state_find(st, "wall_force") : NULL;
    dem_state_array *wn = st ? dem_state_find(st, "wall_normal_force") : NULL;
    dem_sample row;
    dem_mpi_split_walls_row(q, acc, nw, &row);
    for (int k = 0; wf && wf->data && k < 3 * nw; k++) /* (a run's real: the rounded value is one exactly) */
        sim_real_put(wf->data, (size_t)k, st->real_size, row.wall_force[k]);
    for (int w = 0; wn && wn->data && w < nw; w++)
        sim_real_put(wn->data, (size_t)w, st->real_size, row.wall_normal[w]);
}

void dem_mpi_split_free(dem_mpi_split *q)
{
    drop_part(q);
    free(q->last_owner);
    q->last_owner = NULL;
}
