/* api.c - dem_create_mpi (include/dem_mpi.h): the calls of dem.h on a run split over the ranks of a communicator.
 * The dem_sim a program holds is the whole set-up, never started itself (each part is copied from it, as `dem run`
 * under mpirun copies its parts from the scene's whole run); from dem_start on, libdem.a's calls that work on it
 * come here through its split_ops (host/core/sim.h), and the split (host/mpi/split.c) does the work. */
#include "dem_mpi.h"
#include "mpi_layer.h"
#include "sim.h"
#include "dem_layout.h"
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    MPI_Comm comm; /* the program's communicator, duplicated */
    dem_mpi_split sp;
    int failed;    /* a step failed (on every rank, agreed): the parts may stand at different steps, or be gone */
} split_run;

static split_run *of(const dem_sim *s) { return s->split_ctx; }

static int start(dem_sim *s, const dem_config *c)
{
    split_run *q = of(s);
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    char err[4096];
    memset(&q->sp, 0, sizeof q->sp);
    q->sp.comm = q->comm, q->sp.fail_step = -1;
    int e = dem_mpi_split_start(&q->sp, q->comm, s, c, NULL, 0, "dem_start", err, sizeof err); /* agreed */
    if (e) {
        dem_mpi_split_free(&q->sp);
        return sim_fail(s, e, "%s", err);
    }
    s->split_started = 1;
    return 0;
}

/* after a failed step, what reads or steps the parts is refused (the same on every rank: the failure was agreed) */
static int gone(dem_sim *s)
{
    return of(s)->failed ? sim_fail(s, DEM_ERR_STATE, "a step of this run split over MPI ranks failed at step %ld: "
                                    "it cannot go on (its parts may stand at different steps)", of(s)->sp.step)
                         : 0;
}

static int step(dem_sim *s, long nsteps, const unsigned char *want, dem_sample *rows)
{
    char err[4096];
    if (gone(s))
        return DEM_ERR_STATE;
    dem_mpi_split *sp = &of(s)->sp;
    int e = dem_mpi_split_step(sp, nsteps, want, rows, err, sizeof err); /* agreed */
    if (!e)
        return 0;
    of(s)->failed = 1;
    /* the particle a failed step names (dem_error_particle; the part's own says the whole run's id): the lowest
     * rank's that has one, on every rank */
    int mine = sp->part ? dem_error_particle(sp->part) : -1, who = mine >= 0 ? sp->rank : INT_MAX, first = INT_MAX;
    MPI_Allreduce(&who, &first, 1, MPI_INT, MPI_MIN, sp->comm);
    if (first != INT_MAX)
        MPI_Bcast(&mine, 1, MPI_INT, first, sp->comm);
    else
        mine = -1;
    sim_fail(s, e, "%s", err);
    s->report.err_particle = mine;
    return e;
}

/* the row of the state now: its energies the parts' own, merged (dem_mpi_split_sample), and its walls' sums too, as
 * after a step (the split's own row holds them merged only at the start, where `dem run` asks for it) */
static int sample(dem_sim *s, dem_sample *row)
{
    dem_mpi_split *sp = &of(s)->sp;
    char err[4096];
    exact_acc acc[SE_STRIDE + WP_STRIDE * DEM_MAX_WALLS];
    if (gone(s))
        return DEM_ERR_STATE;
    int nw, e = dem_mpi_split_sample(sp, row, err, sizeof err); /* agreed */
    if (!e && !(e = dem_mpi_split_walls(sp, acc, &nw, err, sizeof err))) /* agreed */
        dem_mpi_split_walls_row(sp, acc, nw, row);
    return e ? sim_fail(s, e, "%s", err) : 0;
}

/* the whole state gathered on every rank, its walls' sums every rank's own particles', merged */
static int state_get(dem_sim *s, dem_state *st)
{
    dem_mpi_split *sp = &of(s)->sp;
    char err[4096] = "";
    if (gone(s))
        return DEM_ERR_STATE;
    int e = dem_mpi_state_gather(&sp->h, sp->gid, sp->owner, sp->n, st), nw; /* agreed */
    if (e)
        return sim_fail(s, dem_mpi_split_shared_error(sp, e, err, sizeof err), "%s", err);
    exact_acc acc[SE_STRIDE + WP_STRIDE * DEM_MAX_WALLS];
    if ((e = dem_mpi_split_walls(sp, acc, &nw, err, sizeof err))) { /* agreed */
        dem_state_free(st);
        return sim_fail(s, e, "%s", err);
    }
    dem_mpi_split_walls_put(sp, acc, nw, st);
    return 0;
}

/* A field of the whole run on every rank: a per-particle one from each rank's own particles (their rows in the
 * part: an own particle's contacts are all in it, so its stress is one process's), the walls' merged */
static int get_field(dem_sim *s, dem_field f, double *dst)
{
    dem_mpi_split *sp = &of(s)->sp;
    char err[4096] = "";
    int nc = sim_field_per_particle(f), e;
    if (gone(s))
        return DEM_ERR_STATE;
    if (f == DEM_FIELD_WALL_FORCE || f == DEM_FIELD_WALL_NORMAL_FORCE) {
        exact_acc acc[SE_STRIDE + WP_STRIDE * DEM_MAX_WALLS];
        dem_sample row;
        memset(&row, 0, sizeof row);
        int nw;
        if ((e = dem_mpi_split_walls(sp, acc, &nw, err, sizeof err))) /* agreed */
            return sim_fail(s, e, "%s", err);
        dem_mpi_split_walls_row(sp, acc, nw, &row);
        size_t m = dem_field_bytes(sp->part, f) / (size_t)sp->part->setup.real_size; /* one process's count */
        memcpy(dst, f == DEM_FIELD_WALL_FORCE ? row.wall_force : row.wall_normal, sizeof(double) * m);
        return 0;
    }
    if (!nc) /* the same answer on every rank: f is every rank's */
        return sim_fail(s, DEM_ERR_ARG, "field %d: not on a run split over MPI ranks (dem_create_mpi), whose "
                        "per-particle fields and walls' forces are", (int)f);
    if (!dem_field_bytes(sp->part, f)) /* a field the run does not keep (a stress trace without MC-stress) */
        return 0;
    double *v = malloc(sizeof(double) * (size_t)nc * ((size_t)sp->nloc + 1));
    e = v ? dem_get_field(sp->part, f, v) : DEM_ERR_NOMEM;
    if (e && !v)
        snprintf(err, sizeof err, "out of host memory");
    if (!(e = dem_mpi_split_agreed(sp, e, sp->part, err, sizeof err)) && (e = dem_mpi_split_rows(sp, v, nc, dst)))
        snprintf(err, sizeof err, "field %d: the ranks' rows could not be gathered (out of host memory, or past "
                 "MPI's int counts)", (int)f);
    free(v);
    return e ? sim_fail(s, e, "%s", err) : 0;
}

static dem_sim *part(const dem_sim *s) { return of(s)->failed ? NULL : of(s)->sp.part; }
static long step_index(const dem_sim *s) { return of(s)->sp.step; }

static void destroy(dem_sim *s)
{
    split_run *q = of(s);
    dem_mpi_split_free(&q->sp);
    int done = 0;
    MPI_Finalized(&done);
    if (!done)
        MPI_Comm_free(&q->comm);
    free(q);
    s->split_ops = NULL, s->split_ctx = NULL, s->split_started = 0;
}

static const sim_split_ops ops = {start, step, sample, state_get, part, step_index, get_field, destroy};

dem_sim *dem_create_mpi(MPI_Comm comm)
{
    int init = 0, fin = 0;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    MPI_Comm dup;
    if (!init || fin || MPI_Comm_dup(comm, &dup) != MPI_SUCCESS)
        return NULL;
    dem_sim *s = dem_create();
    split_run *q = s ? calloc(1, sizeof *q) : NULL;
    int ok = q != NULL, all = 0; /* every rank's verdict: none left alone with a run the others lack */
    if (MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, dup) != MPI_SUCCESS || !all) {
        free(q);
        dem_destroy(s);
        MPI_Comm_free(&dup);
        return NULL;
    }
    q->comm = dup;
    s->split_ops = &ops, s->split_ctx = q;
    return s;
}
