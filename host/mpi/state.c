/* state.c - a run split over ranks (dem_mpi.h): its whole state gathered from each rank's own particles, and a whole
 * state cut to the particles one rank keeps. Together they move particles, their per-particle and per-wall arrays and
 * their contacts' histories between ranks when the run is split anew (migration), and make a checkpoint that does
 * not depend on the rank count. */
#include "dem_mpi.h"
#include "sim.h"
#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* the bytes of one pair's data in a state: its history, MC-strain force, force record, MC-strain displacements, law
 * state and rolling spring, as dem_state holds them */
typedef struct {
    size_t hist, mcf, rec, mcd, law, rsp, all;
} pair_bytes;
static pair_bytes pair_bytes_of(const dem_state *st)
{
    size_t rs = (size_t)st->real_size;
    pair_bytes b = {3 * rs, rs, (size_t)DEM_PAIR_RECORD_REALS * rs, 2 * rs, (size_t)st->has_law * rs,
                    st->has_rspring ? 3 * rs : 0, 0};
    b.all = b.hist + b.mcf + b.rec + b.mcd + b.law + b.rsp;
    return b;
}
/* pair p's data of st into dst, or (to = 1) dst into pair p of st */
static void pair_copy(dem_state *st, long p, unsigned char *dst, const pair_bytes *b, int to)
{
    void *part[6] = {st->pair_hist, st->pair_mc_fn, st->pair_rec, st->pair_mc_disp, st->pair_law, st->pair_rspring};
    size_t w[6] = {b->hist, b->mcf, b->rec, b->mcd, b->law, b->rsp};
    for (int q = 0; q < 6; q++) {
        if (!w[q] || !part[q])
            continue;
        unsigned char *at = (unsigned char *)part[q] + (size_t)p * w[q];
        if (to)
            memcpy(at, dst, w[q]);
        else
            memcpy(dst, at, w[q]);
        dst += w[q];
    }
}
static int pair_alloc(dem_state *st, long np)
{
    pair_bytes b = pair_bytes_of(st);
    size_t m = (size_t)(np ? np : 1);
    st->npairs = np;
    st->pair_i = malloc(sizeof(int) * m), st->pair_j = malloc(sizeof(int) * m);
    st->pair_hist = calloc(m, b.hist), st->pair_mc_fn = calloc(m, b.mcf), st->pair_rec = calloc(m, b.rec);
    st->pair_mc_disp = calloc(m, b.mcd);
    st->pair_law = b.law ? calloc(m, b.law) : NULL;
    st->pair_rspring = b.rsp ? calloc(m, b.rsp) : NULL;
    return st->pair_i && st->pair_j && st->pair_hist && st->pair_mc_fn && st->pair_rec && st->pair_mc_disp &&
                   (!b.law || st->pair_law) && (!b.rsp || st->pair_rspring)
               ? 0
               : DEM_ERR_NOMEM;
}

/* the header of st (step, walls, stages, what it holds), no arrays or pairs */
static void header_copy(dem_state *dst, const dem_state *st, int n)
{
    memset(dst, 0, sizeof *dst);
    dst->step = st->step, dst->rebuilds = st->rebuilds, dst->n = n, dst->nwalls = st->nwalls;
    dst->real_size = st->real_size;
    memcpy(dst->wall_pos, st->wall_pos, sizeof dst->wall_pos);
    dst->has_stages = st->has_stages;
    memcpy(dst->wall_stage, st->wall_stage, sizeof dst->wall_stage);
    memcpy(dst->wall_stage_first, st->wall_stage_first, sizeof dst->wall_stage_first);
    memcpy(dst->wall_stage_from, st->wall_stage_from, sizeof dst->wall_stage_from);
    dst->has_hist = st->has_hist, dst->has_mc = st->has_mc, dst->has_law = st->has_law;
    dst->has_rspring = st->has_rspring, dst->mc = st->mc;
}

static int by_pair(const void *a, const void *b)
{
    long p[2], q[2]; /* the records' ids, copied out: a record of an fp32 run is not aligned for a long */
    memcpy(p, a, sizeof p), memcpy(q, b, sizeof q);
    return p[0] != q[0] ? (p[0] < q[0] ? -1 : 1) : p[1] != q[1] ? (p[1] < q[1] ? -1 : 1) : 0;
}

/* whether a message of count items of `bytes` bytes each, and offsets up to it, fit MPI's int counts */
static int fits_int(size_t count, size_t bytes) { return bytes == 0 || count <= (size_t)INT_MAX / bytes; }

/* Every collective below is entered by every rank or by none: each local failure is agreed (dem_mpi_agreed) before
 * the next collective, and all ranks leave together. */
static int gather_state(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, dem_state *loc, dem_state *g)
{
    MPI_Comm comm = h->comm;
    int P = h->size, n = h->n, rs = loc->real_size, no = 0;
    /* patch contacts do not travel yet; every rank holds a particle. MC-strain's force and displacements travel with
     * their pair: the owner of its lower id holds both ends' (the ghost end's from its owner, halo.c) */
    int e = loc->npatch || n == 0 ? DEM_ERR_ARG : 0;
    int *own = malloc(sizeof(int) * ((size_t)n + 1)), *cnt = malloc(sizeof(int) * 4 * (size_t)P);
    int *dsp = cnt ? cnt + P : NULL, *bc = cnt ? cnt + 2 * P : NULL, *bd = cnt ? cnt + 3 * P : NULL;
    long *allgid = malloc(sizeof(long) * ((size_t)nglobal + 1)), *mine = malloc(sizeof(long) * ((size_t)n + 1));
    unsigned char *send = NULL, *recv = NULL;
    e = e ? e : own && cnt && allgid && mine ? 0 : DEM_ERR_NOMEM;
    for (int i = 0; !e && i < n; i++)
        if (owner[i] == h->rank)
            mine[no] = gid[i], own[no++] = i;
    long total = 0;
    if (!(e = dem_mpi_agreed(comm, e))) {
        MPI_Allgather(&no, 1, MPI_INT, cnt, 1, MPI_INT, comm);
        for (int q = 0; q < P; q++)
            dsp[q] = (int)total, total += cnt[q];
        e = total == nglobal ? 0 : DEM_ERR_ARG; /* every particle owned once: the same verdict on every rank */
    }
    if (!e)
        MPI_Allgatherv(mine, no, MPI_LONG, allgid, cnt, dsp, MPI_LONG, comm);
    if (!e) { /* the header: rank 0's (the step and the walls are every rank's; the rebuild and iteration counts not) */
        header_copy(g, loc, (int)nglobal);
        MPI_Bcast(&g->rebuilds, 1, MPI_LONG, 0, comm);
        MPI_Bcast(&g->mc, (int)sizeof g->mc, MPI_BYTE, 0, comm);
    }
    /* the arrays: each rank's own rows (of every group), gathered, put at their global ids */
    for (int a = 0; !e && a < loc->narrays; a++) {
        const dem_state_array *la = &loc->arrays[a];
        dem_state_array *ga = &g->arrays[g->narrays++];
        *ga = *la, ga->data = NULL;
        int per, kind = sim_state_array_layout(h->s, la->name, &per);
        size_t es = la->elem == DEM_STATE_REAL ? (size_t)rs : sizeof(int), groups = 0, row = 0;
        if (!la->data || !la->count) /* the same on every rank: the run's set-up decides it */
            continue;
        if (kind == DEM_MOVE_STAY) { /* the walls' sums: rank 0's (docs/design.md "Runs over MPI") */
            ga->data = malloc(la->count * es);
            if (ga->data)
                memcpy(ga->data, la->data, la->count * es);
            if (!(e = dem_mpi_agreed(comm, ga->data ? 0 : DEM_ERR_NOMEM)))
                MPI_Bcast(ga->data, (int)(la->count * es), MPI_BYTE, 0, comm);
            continue;
        }
        if (kind < 0 || per <= 0 || la->count % ((size_t)n * per))
            e = DEM_ERR_ARG;
        else {
            groups = la->count / ((size_t)n * per), row = (size_t)per * es; /* groups: 1 for a per-particle array */
            ga->count = groups * (size_t)nglobal * per;
            send = malloc(groups * (size_t)no * row + 1), recv = malloc(groups * (size_t)nglobal * row + 1);
            ga->data = malloc(ga->count * es + 1);
            e = !send || !recv || !ga->data ? DEM_ERR_NOMEM : fits_int(groups * (size_t)nglobal, row) ? 0 : DEM_ERR_ARG;
        }
        if (!(e = dem_mpi_agreed(comm, e))) {
            for (size_t gr = 0; gr < groups; gr++)
                for (int k = 0; k < no; k++)
                    memcpy(send + (gr * no + k) * row, (unsigned char *)la->data + (gr * n + own[k]) * row, row);
            for (int q = 0; q < P; q++)
                bc[q] = (int)(groups * cnt[q] * row), bd[q] = (int)(groups * dsp[q] * row);
            MPI_Allgatherv(send, (int)(groups * no * row), MPI_BYTE, recv, bc, bd, MPI_BYTE, comm);
            for (int q = 0; q < P; q++) /* rank q's block: its groups, each of its cnt[q] rows */
                for (size_t gr = 0; gr < groups; gr++)
                    for (int k = 0; k < cnt[q]; k++)
                        memcpy((unsigned char *)ga->data + (gr * nglobal + allgid[dsp[q] + k]) * row,
                               recv + (size_t)bd[q] + (gr * cnt[q] + k) * row, row);
        }
        free(send), free(recv);
        send = recv = NULL;
    }
    /* the contacts: each from the rank that owns its lower id, whose copy is right */
    pair_bytes pb = pair_bytes_of(loc);
    size_t rec = 2 * sizeof(long) + pb.all;
    long npo = 0, all = 0;
    for (long p = 0; !e && p < loc->npairs; p++)
        npo += owner[loc->pair_i[p]] == h->rank;
    if (!e) {
        send = malloc((size_t)npo * rec + 1);
        e = send ? 0 : DEM_ERR_NOMEM;
    }
    for (long p = 0, k = 0; !e && p < loc->npairs; p++)
        if (owner[loc->pair_i[p]] == h->rank) {
            long ij[2] = {gid[loc->pair_i[p]], gid[loc->pair_j[p]]};
            memcpy(send + (size_t)k * rec, ij, sizeof ij);
            pair_copy(loc, p, send + (size_t)k * rec + sizeof ij, &pb, 0);
            k++;
        }
    int np_me = (int)npo;
    if (!(e = dem_mpi_agreed(comm, e))) {
        MPI_Allgather(&np_me, 1, MPI_INT, bc, 1, MPI_INT, comm);
        for (int q = 0; q < P; q++)
            all += bc[q];
        e = fits_int((size_t)all, rec) ? 0 : DEM_ERR_ARG; /* the same on every rank */
    }
    if (!e) {
        for (int q = 0, at = 0; q < P; q++)
            bd[q] = (int)((size_t)at * rec), at += bc[q], bc[q] = (int)((size_t)bc[q] * rec);
        recv = malloc((size_t)all * rec + 1);
        e = dem_mpi_agreed(comm, recv && !pair_alloc(g, all) ? 0 : DEM_ERR_NOMEM);
    }
    if (!e) {
        MPI_Allgatherv(send, (int)((size_t)npo * rec), MPI_BYTE, recv, bc, bd, MPI_BYTE, comm);
        qsort(recv, (size_t)all, rec, by_pair); /* ascending i, then j: as a run's state lists them */
        for (long p = 0; p < all; p++) {
            long ij[2];
            memcpy(ij, recv + (size_t)p * rec, sizeof ij);
            g->pair_i[p] = (int)ij[0], g->pair_j[p] = (int)ij[1];
            pair_copy(g, p, recv + (size_t)p * rec + sizeof ij, &pb, 1);
        }
    }
    free(send), free(recv), free(own), free(cnt), free(allgid), free(mine);
    return e;
}

int dem_mpi_state_gather(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, dem_state *g)
{
    dem_state loc;
    memset(g, 0, sizeof *g);
    int e = dem_mpi_agreed(h->comm, dem_state_get(h->s, &loc));
    if (!e) /* (its verdict is every rank's already) */
        e = gather_state(h, gid, owner, nglobal, &loc, g);
    dem_state_free(&loc);
    if (e)
        dem_state_free(g);
    return e;
}

int dem_mpi_state_part(const dem_sim *s, const dem_state *g, const unsigned char *keep, dem_state *part)
{
    int n = 0, N = g->n, e = 0;
    int *local = malloc(sizeof(int) * ((size_t)N + 1)); /* global id -> the part's id, -1 where not kept */
    if (!local)
        return DEM_ERR_NOMEM;
    for (int k = 0; k < N; k++)
        local[k] = keep[k] ? n++ : -1;
    header_copy(part, g, n);
    for (int a = 0; !e && a < g->narrays; a++) {
        const dem_state_array *ga = &g->arrays[a];
        dem_state_array *pa = &part->arrays[part->narrays++];
        *pa = *ga, pa->data = NULL;
        int per, kind = sim_state_array_layout(s, ga->name, &per);
        size_t es = ga->elem == DEM_STATE_REAL ? (size_t)g->real_size : sizeof(int);
        if (!ga->data || !ga->count)
            continue;
        if (kind == DEM_MOVE_STAY) {
            if ((pa->data = malloc(ga->count * es)))
                memcpy(pa->data, ga->data, ga->count * es);
            e = pa->data ? 0 : DEM_ERR_NOMEM;
            continue;
        }
        if (kind < 0 || per <= 0 || ga->count % ((size_t)N * per)) {
            e = DEM_ERR_ARG;
            break;
        }
        size_t groups = ga->count / ((size_t)N * per), row = (size_t)per * es;
        pa->count = groups * (size_t)n * per;
        if (!(pa->data = malloc(pa->count * es + 1)))
            e = DEM_ERR_NOMEM;
        for (size_t gr = 0; !e && gr < groups; gr++)
            for (int k = 0; k < N; k++)
                if (local[k] >= 0)
                    memcpy((unsigned char *)pa->data + (gr * n + local[k]) * row,
                           (const unsigned char *)ga->data + (gr * N + k) * row, row);
    }
    long np = 0;
    for (long p = 0; p < g->npairs; p++)
        np += local[g->pair_i[p]] >= 0 && local[g->pair_j[p]] >= 0;
    if (!e)
        e = pair_alloc(part, np);
    pair_bytes pb = pair_bytes_of(g);
    unsigned char *one = malloc(pb.all + 1);
    e = e ? e : one ? 0 : DEM_ERR_NOMEM;
    for (long p = 0, q = 0; !e && p < g->npairs; p++)
        if (local[g->pair_i[p]] >= 0 && local[g->pair_j[p]] >= 0) {
            part->pair_i[q] = local[g->pair_i[p]], part->pair_j[q] = local[g->pair_j[p]];
            pair_copy((dem_state *)g, p, one, &pb, 0);
            pair_copy(part, q, one, &pb, 1);
            q++;
        }
    free(one), free(local);
    if (e)
        dem_state_free(part);
    return e;
}
