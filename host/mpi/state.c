/* state.c - a run split over ranks (mpi_layer.h): its whole state gathered from each rank's own particles, and a whole
 * state cut to the particles one rank keeps. Together they move particles, their per-particle and per-wall arrays and
 * their contacts' histories between ranks when the run is split anew (migration), and make a checkpoint that does
 * not depend on the rank count. */
#include "mpi_layer.h"
#include "sim.h"
#include <limits.h>
#include <stdio.h>
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
/* the first of st's contacts (ascending pair_i) with pair_i >= v */
static long pair_from(const dem_state *st, int v)
{
    long lo = 0, hi = st->npairs;
    while (lo < hi) {
        long k = lo + (hi - lo) / 2;
        if (st->pair_i[k] < v)
            lo = k + 1;
        else
            hi = k;
    }
    return lo;
}

/* root < 0: on every rank; else on rank root alone (the others' g: the header, no arrays or contacts). The particles
 * of global ids [a, b) of the nglobal (a state of b - a particles: the whole state, or a slab of it) and the
 * contacts whose lower id is among them. */
static int gather_state(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, long a, long b,
                        dem_state *loc, dem_state *g, int root)
{
    int here = root < 0 || h->rank == root; /* this rank receives the whole state */
    MPI_Comm comm = h->comm;
    int P = h->size, n = h->n, rs = loc->real_size, no = 0;
    /* patch contacts do not travel yet; every rank holds a particle. MC-strain's force and displacements travel with
     * their pair: the owner of its lower id holds both ends' (the ghost end's from its owner, halo.c) */
    int e = loc->npatch || n == 0 || a < 0 || b < a || b > nglobal ? DEM_ERR_ARG : 0;
    long m = e ? 0 : b - a; /* the particles gathered */
    /* the held ones among them: local ids k0..k1 (gid ascends), and their contacts p0..p1 (pair_i ascends, as a
     * state lists its contacts): a checkpoint's slabs do not each scan the whole part */
    int k0 = e ? 0 : dem_mpi_id_from(gid, n, a), k1 = e ? 0 : dem_mpi_id_from(gid, n, b);
    long p0 = pair_from(loc, k0), p1 = pair_from(loc, k1);
    int *own = malloc(sizeof(int) * ((size_t)(k1 - k0) + 1)), *cnt = malloc(sizeof(int) * 4 * (size_t)P);
    int *dsp = cnt ? cnt + P : NULL, *bc = cnt ? cnt + 2 * P : NULL, *bd = cnt ? cnt + 3 * P : NULL;
    long *allgid = malloc(sizeof(long) * ((size_t)m + 1)), *mine = malloc(sizeof(long) * ((size_t)(k1 - k0) + 1));
    unsigned char *send = NULL, *recv = NULL;
    e = e ? e : own && cnt && allgid && mine ? 0 : DEM_ERR_NOMEM;
    for (int i = k0; !e && i < k1; i++)
        if (owner[i] == h->rank)
            mine[no] = gid[i] - a, own[no++] = i;
    long total = 0;
    if (!(e = dem_mpi_agreed(comm, e))) {
        MPI_Allgather(&no, 1, MPI_INT, cnt, 1, MPI_INT, comm);
        for (int q = 0; q < P; q++)
            dsp[q] = (int)total, total += cnt[q];
        e = total == m ? 0 : DEM_ERR_ARG; /* every particle owned once: the same verdict on every rank */
    }
    if (!e && root < 0)
        MPI_Allgatherv(mine, no, MPI_LONG, allgid, cnt, dsp, MPI_LONG, comm);
    else if (!e)
        MPI_Gatherv(mine, no, MPI_LONG, allgid, cnt, dsp, MPI_LONG, root, comm);
    if (!e) { /* the header: rank 0's (the step and the walls are every rank's; the rebuild and iteration counts not) */
        header_copy(g, loc, (int)m);
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
            ga->data = here ? malloc(la->count * es) : NULL;
            if (ga->data)
                memcpy(ga->data, la->data, la->count * es);
            if (!(e = dem_mpi_agreed(comm, ga->data || !here ? 0 : DEM_ERR_NOMEM)) && root != 0)
                MPI_Bcast(ga->data ? ga->data : la->data, (int)(la->count * es), MPI_BYTE, 0, comm);
            continue;
        }
        if (kind < 0 || per <= 0 || la->count % ((size_t)n * per))
            e = DEM_ERR_ARG;
        else {
            groups = la->count / ((size_t)n * per), row = (size_t)per * es; /* groups: 1 for a per-particle array */
            ga->count = groups * (size_t)m * per;
            send = malloc(groups * (size_t)no * row + 1);
            recv = here ? malloc(groups * (size_t)m * row + 1) : NULL;
            ga->data = here ? malloc(ga->count * es + 1) : NULL;
            e = !send || (here && (!recv || !ga->data)) ? DEM_ERR_NOMEM
                : fits_int(groups * (size_t)m, row) ? 0 : DEM_ERR_ARG;
        }
        if (!(e = dem_mpi_agreed(comm, e))) {
            for (size_t gr = 0; gr < groups; gr++)
                for (int k = 0; k < no; k++)
                    memcpy(send + (gr * no + k) * row, (unsigned char *)la->data + (gr * n + own[k]) * row, row);
            for (int q = 0; q < P; q++)
                bc[q] = (int)(groups * cnt[q] * row), bd[q] = (int)(groups * dsp[q] * row);
            if (root < 0)
                MPI_Allgatherv(send, (int)(groups * no * row), MPI_BYTE, recv, bc, bd, MPI_BYTE, comm);
            else
                MPI_Gatherv(send, (int)(groups * no * row), MPI_BYTE, recv, bc, bd, MPI_BYTE, root, comm);
            for (int q = 0; here && q < P; q++) /* rank q's block: its groups, each of its cnt[q] rows */
                for (size_t gr = 0; gr < groups; gr++)
                    for (int k = 0; k < cnt[q]; k++)
                        memcpy((unsigned char *)ga->data + (gr * m + allgid[dsp[q] + k]) * row,
                               recv + (size_t)bd[q] + (gr * cnt[q] + k) * row, row);
        }
        free(send), free(recv);
        send = recv = NULL;
    }
    /* the contacts: each from the rank that owns its lower id, whose copy is right */
    pair_bytes pb = pair_bytes_of(loc);
    size_t rec = 2 * sizeof(long) + pb.all;
    long npo = 0, all = 0;
    for (long p = p0; !e && p < p1; p++)
        npo += owner[loc->pair_i[p]] == h->rank;
    if (!e) {
        send = malloc((size_t)npo * rec + 1);
        e = send ? 0 : DEM_ERR_NOMEM;
    }
    for (long p = p0, k = 0; !e && p < p1; p++)
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
        recv = here ? malloc((size_t)all * rec + 1) : NULL;
        e = dem_mpi_agreed(comm, !here || (recv && !pair_alloc(g, all)) ? 0 : DEM_ERR_NOMEM);
    }
    if (!e) {
        if (root < 0)
            MPI_Allgatherv(send, (int)((size_t)npo * rec), MPI_BYTE, recv, bc, bd, MPI_BYTE, comm);
        else
            MPI_Gatherv(send, (int)((size_t)npo * rec), MPI_BYTE, recv, bc, bd, MPI_BYTE, root, comm);
        if (here) /* ascending i, then j: as a run's state lists them */
            qsort(recv, (size_t)all, rec, by_pair);
        for (long p = 0; here && p < all; p++) {
            long ij[2];
            memcpy(ij, recv + (size_t)p * rec, sizeof ij);
            g->pair_i[p] = (int)ij[0], g->pair_j[p] = (int)ij[1];
            pair_copy(g, p, recv + (size_t)p * rec + sizeof ij, &pb, 1);
        }
    }
    free(send), free(recv), free(own), free(cnt), free(allgid), free(mine);
    return e;
}

int dem_mpi_state_gather_at(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, int root,
                            dem_state *g)
{
    dem_state loc;
    memset(g, 0, sizeof *g);
    int e = dem_mpi_agreed(h->comm, dem_state_get(h->s, &loc));
    if (!e) /* (its verdict is every rank's already) */
        e = dem_mpi_state_slab(h, gid, owner, nglobal, &loc, 0, nglobal, root, g);
    dem_state_free(&loc);
    return e;
}

int dem_mpi_state_gather(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, dem_state *g)
{
    return dem_mpi_state_gather_at(h, gid, owner, nglobal, -1, g);
}

int dem_mpi_state_slab(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, dem_state *loc, long a,
                       long b, int root, dem_state *g)
{
    memset(g, 0, sizeof *g);
    int e = gather_state(h, gid, owner, nglobal, a, b, loc, g, root);
    if (!e && root >= 0 && h->rank != root) { /* the header alone: no arrays or contacts were received here */
        for (int k = 0; k < g->narrays; k++)
            free(g->arrays[k].data);
        g->narrays = 0;
    }
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

/* ---- a split anew without the whole state: each rank's own particles and contacts go to the ranks that keep them ---- */

static int by_id(const void *a, const void *b)
{
    long p, q; /* copied out: a record is not aligned for a long */
    memcpy(&p, a, sizeof p), memcpy(&q, b, sizeof q);
    return (p > q) - (p < q);
}

/* counts per rank to byte counts and displacements (of rec bytes each); 0, or DEM_ERR_ARG past MPI's int counts */
static int byte_counts(int P, const int *cnt, size_t rec, int *bc, int *bd, size_t *total)
{
    size_t at = 0;
    for (int q = 0; q < P; q++) {
        if (!fits_int(at + (size_t)cnt[q], rec))
            return DEM_ERR_ARG;
        bd[q] = (int)(at * rec), bc[q] = (int)((size_t)cnt[q] * rec), at += (size_t)cnt[q];
    }
    *total = at;
    return 0;
}

/* one array of a state as rank 0 holds it: what every rank needs to send and receive its rows alike */
typedef struct {
    char name[64];
    int kind, present; /* sim_state_array_layout's kind; whether rank 0 holds data for it */
    size_t es, groups, row, count;
} move_array;

int dem_mpi_state_move(MPI_Comm comm, const dem_sim *s, const dem_state *loc, const long *gid, const int *owner,
                       int (*keeps)(void *arg, long id, int rank), void *arg, int nkeep, const long *keep_id,
                       dem_state *part)
{
    int P, me;
    MPI_Comm_size(comm, &P), MPI_Comm_rank(comm, &me);
    memset(part, 0, sizeof *part);
    int n = loc ? loc->n : 0, e = (loc && loc->npatch) || (me == 0 && !loc) ? DEM_ERR_ARG : 0; /* no patch contacts */
    /* the layout, rank 0's for every rank: its header (the step, the walls, what the run keeps; the rebuild and
     * iteration counts, as a gather takes them) and its arrays. A rank that holds nothing (loc NULL) takes it whole. */
    dem_state hdr;
    static move_array lay[DEM_STATE_MAX_ARRAYS]; /* (1 rank per process: no second caller at a time) */
    memset(&hdr, 0, sizeof hdr), memset(lay, 0, sizeof lay);
    if (me == 0 && loc) {
        hdr = *loc;
        for (int a = 0; !e && a < loc->narrays; a++) {
            const dem_state_array *la = &loc->arrays[a];
            move_array *m = &lay[a];
            int per;
            snprintf(m->name, sizeof m->name, "%s", la->name);
            m->kind = sim_state_array_layout(s, la->name, &per);
            m->es = la->elem == DEM_STATE_REAL ? (size_t)loc->real_size : sizeof(int), m->count = la->count;
            m->present = la->data && la->count;
            if (!m->present || m->kind == DEM_MOVE_STAY) /* the walls' sums travel whole, from rank 0 */
                continue;
            if (m->kind < 0 || per <= 0 || n <= 0 || la->count % ((size_t)n * per))
                e = DEM_ERR_ARG;
            else
                m->groups = la->count / ((size_t)n * per), m->row = (size_t)per * m->es;
        }
    }
    if ((e = dem_mpi_agreed(comm, e)))
        return e;
    MPI_Bcast(&hdr, (int)sizeof hdr, MPI_BYTE, 0, comm); /* its pointers are rank 0's: never read here */
    MPI_Bcast(lay, (int)sizeof lay, MPI_BYTE, 0, comm);
    /* each array's description in this process (its name's and unit's addresses): loc's, or the library's list */
    dem_state names;
    memset(&names, 0, sizeof names);
    names.n = nkeep, names.nwalls = hdr.nwalls, names.real_size = hdr.real_size, names.has_hist = hdr.has_hist;
    names.has_mc = hdr.has_mc, names.has_law = hdr.has_law, names.has_rspring = hdr.has_rspring;
    dem_state_arrays(&names);
    const dem_state_array *desc[DEM_STATE_MAX_ARRAYS] = {0};
    for (int a = 0; !e && a < hdr.narrays; a++) {
        const dem_state *from = loc ? loc : &names;
        for (int b = 0; b < from->narrays && !desc[a]; b++)
            if (!strcmp(from->arrays[b].name, lay[a].name))
                desc[a] = &from->arrays[b];
        e = desc[a] && (!loc || (loc->narrays == hdr.narrays && desc[a] == &loc->arrays[a])) ? 0 : DEM_ERR_ARG;
    }
    size_t prec = sizeof(long); /* a particle's record: its global id, then its rows of every array that moves */
    for (int a = 0; a < hdr.narrays; a++)
        prec += lay[a].groups * lay[a].row;
    pair_bytes pb = pair_bytes_of(&hdr);
    size_t qrec = 2 * sizeof(long) + pb.all;
    long npairs = loc ? loc->npairs : 0;
    int *cnt = calloc(8 * (size_t)P, sizeof(int)); /* particles and pairs per rank, sent and received, bytes, displs */
    int *pc = cnt, *qc = cnt ? cnt + P : NULL, *pr = cnt ? cnt + 2 * P : NULL, *qr = cnt ? cnt + 3 * P : NULL;
    int *bc = cnt ? cnt + 4 * P : NULL, *bd = cnt ? cnt + 5 * P : NULL, *rc = cnt ? cnt + 6 * P : NULL,
        *rd = cnt ? cnt + 7 * P : NULL;
    long *at = malloc(sizeof(long) * (size_t)P); /* per rank: the next record's place in the send buffer */
    unsigned char *send = NULL, *recv = NULL;
    e = e ? e : cnt && at ? 0 : DEM_ERR_NOMEM;
    /* who keeps what: every own particle to each rank that keeps it, each contact whose lower id is ours to each rank
     * that keeps both its ends (our copy of it is right: our rows held it since the last split) */
    for (int k = 0; !e && k < n; k++)
        for (int r = 0; owner[k] == me && r < P; r++)
            pc[r] += keeps(arg, gid[k], r) != 0;
    for (long p = 0; !e && p < npairs; p++)
        for (int r = 0; owner[loc->pair_i[p]] == me && r < P; r++)
            qc[r] += keeps(arg, gid[loc->pair_i[p]], r) && keeps(arg, gid[loc->pair_j[p]], r);
    size_t ptot = 0, qtot = 0, prtot = 0, qrtot = 0;
    if (!(e = dem_mpi_agreed(comm, e))) {
        MPI_Alltoall(pc, 1, MPI_INT, pr, 1, MPI_INT, comm);
        MPI_Alltoall(qc, 1, MPI_INT, qr, 1, MPI_INT, comm);
        e = byte_counts(P, pc, prec, bc, bd, &ptot) || byte_counts(P, pr, prec, rc, rd, &prtot) ? DEM_ERR_ARG : 0;
        e = e ? e : prtot == (size_t)nkeep ? 0 : DEM_ERR_ARG; /* every kept particle came, once */
        send = e ? NULL : malloc(ptot * prec + 1), recv = e ? NULL : malloc(prtot * prec + 1);
        e = e ? e : send && recv ? 0 : DEM_ERR_NOMEM;
    }
    for (int r = 0; !e && r < P; r++)
        at[r] = bd[r];
    for (int k = 0; !e && k < n; k++)
        for (int r = 0; owner[k] == me && r < P; r++)
            if (keeps(arg, gid[k], r)) {
                unsigned char *o = send + at[r];
                memcpy(o, &gid[k], sizeof(long)), o += sizeof(long);
                for (int a = 0; a < hdr.narrays; a++)
                    for (size_t g = 0; g < lay[a].groups; g++, o += lay[a].row)
                        memcpy(o, (const unsigned char *)loc->arrays[a].data +
                                      (g * (size_t)n + (size_t)k) * lay[a].row, lay[a].row);
                at[r] += (long)prec;
            }
    if (!(e = dem_mpi_agreed(comm, e))) {
        MPI_Alltoallv(send, bc, bd, MPI_BYTE, recv, rc, rd, MPI_BYTE, comm);
        qsort(recv, prtot, prec, by_id); /* ascending global id: the part's order */
        for (int k = 0; k < nkeep; k++) {
            long v;
            memcpy(&v, recv + (size_t)k * prec, sizeof v);
            e = e ? e : v == keep_id[k] ? 0 : DEM_ERR_ARG;
        }
    }
    /* the part: rank 0's header, its arrays */
    if (!(e = dem_mpi_agreed(comm, e)))
        header_copy(part, &hdr, nkeep);
    size_t off = sizeof(long);
    for (int a = 0; !e && a < hdr.narrays; a++) {
        const move_array *m = &lay[a];
        dem_state_array *pa = &part->arrays[part->narrays++];
        *pa = *desc[a], pa->count = m->count, pa->data = NULL;
        if (!m->present)
            continue;
        if (m->kind == DEM_MOVE_STAY) { /* the walls' sums: rank 0's, as a gather takes them */
            pa->data = malloc(m->count * m->es + 1);
            if (pa->data && me == 0)
                memcpy(pa->data, loc->arrays[a].data, m->count * m->es);
            if (!(e = dem_mpi_agreed(comm, pa->data ? 0 : DEM_ERR_NOMEM)))
                MPI_Bcast(pa->data, (int)(m->count * m->es), MPI_BYTE, 0, comm);
            continue;
        }
        pa->count = m->groups * (m->row / m->es) * (size_t)nkeep;
        pa->data = malloc(pa->count * m->es + 1);
        e = dem_mpi_agreed(comm, pa->data ? 0 : DEM_ERR_NOMEM); /* every rank at every meeting of this loop */
        for (int k = 0; !e && k < nkeep; k++)
            for (size_t g = 0; g < m->groups; g++)
                memcpy((unsigned char *)pa->data + (g * (size_t)nkeep + (size_t)k) * m->row,
                       recv + (size_t)k * prec + off + g * m->row, m->row);
        off += m->groups * m->row;
    }
    e = dem_mpi_agreed(comm, e);
    free(send), free(recv);
    send = recv = NULL;
    /* the contacts */
    if (!e) {
        e = byte_counts(P, qc, qrec, bc, bd, &qtot) || byte_counts(P, qr, qrec, rc, rd, &qrtot) ? DEM_ERR_ARG : 0;
        send = e ? NULL : malloc(qtot * qrec + 1), recv = e ? NULL : malloc(qrtot * qrec + 1);
        e = e ? e : send && recv && !pair_alloc(part, (long)qrtot) ? 0 : DEM_ERR_NOMEM;
    }
    for (int r = 0; !e && r < P; r++)
        at[r] = bd[r];
    for (long p = 0; !e && p < npairs; p++) {
        long ij[2] = {gid[loc->pair_i[p]], gid[loc->pair_j[p]]};
        for (int r = 0; owner[loc->pair_i[p]] == me && r < P; r++)
            if (keeps(arg, ij[0], r) && keeps(arg, ij[1], r)) {
                memcpy(send + at[r], ij, sizeof ij);
                pair_copy((dem_state *)loc, p, send + at[r] + sizeof ij, &pb, 0);
                at[r] += (long)qrec;
            }
    }
    if (!(e = dem_mpi_agreed(comm, e))) {
        MPI_Alltoallv(send, bc, bd, MPI_BYTE, recv, rc, rd, MPI_BYTE, comm);
        qsort(recv, qrtot, qrec, by_pair); /* ascending i, then j: as a run's state lists them */
        for (size_t p = 0; !e && p < qrtot; p++) {
            long ij[2];
            memcpy(ij, recv + p * qrec, sizeof ij);
            int i = dem_mpi_id_at(keep_id, nkeep, ij[0]), j = dem_mpi_id_at(keep_id, nkeep, ij[1]);
            if (i < 0 || j < 0) {
                e = DEM_ERR_ARG;
                break;
            }
            part->pair_i[p] = i, part->pair_j[p] = j;
            pair_copy(part, (long)p, recv + p * qrec + sizeof ij, &pb, 1);
        }
        e = dem_mpi_agreed(comm, e);
    }
    free(send), free(recv), free(cnt), free(at);
    if (e)
        dem_state_free(part);
    return e;
}
