/* checkpoint.c - see checkpoint.h. Layout: /state/<name> for each array of the state (dem_state_arrays: the library's
 * saved buffers, common/dem_buffers.h's checkpoint column: x, v, w, force, torque, wall_force, wall_normal_force,
 * wall_hist, wall_pf, wall_mask, wall_mc_fn, wall_mc_disp), /state/{wall_pos,wall_stage,wall_stage_first,
 * wall_stage_from,pair_i,pair_j,pair_hist,pair_rec,radius,pair_mc_fn,pair_mc_disp,pair_law,pair_rspring,patch_i,
 * patch_t,patch_hist,patch_side} with attributes step, n, nwalls, real_size (4 or 8: the arrays hold the run's own
 * bits), has_hist, has_mc, has_law, has_rspring, mc_* (MC-strain iteration counts), and /scene/text, /scene/path. */
#include "checkpoint.h"
/* a checkpoint claiming more is damaged (or not ours): far above any run this library makes */
#define CHECKPOINT_MAX_PARTICLES 100000000L
#define CHECKPOINT_MAX_STEP 1000000000000L
#include "h5util.h"
#include "sim.h"
#include <fcntl.h>
#include <stdio.h>
#include <errno.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The HDF5 type of a state array's elements, and their bytes */
static hid_t array_type(const dem_state_array *a, hid_t real_t)
{
    return a->elem == DEM_STATE_REAL ? real_t : a->elem == DEM_STATE_UINT ? H5T_NATIVE_UINT : H5T_NATIVE_INT;
}
static size_t array_elem(const dem_state_array *a, int real_size)
{
    return a->elem == DEM_STATE_REAL ? (size_t)real_size : sizeof(int);
}

static int sync_file(const char *path)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0)
        return -1;
    int rc = fsync(fd);
    close(fd);
    return rc;
}

/* The datasets of a checkpoint's particles and contacts, made at the whole run's size and written slab by slab */
enum { D_RADIUS, D_PI, D_PJ, D_HIST, D_REC, D_MCF, D_LAW, D_RSP, D_MCD, D__N };
typedef struct {
    hid_t arr[DEM_STATE_MAX_ARRAYS]; /* each array's dataset where it is a particle's (0: the walls', written whole) */
    int kind[DEM_STATE_MAX_ARRAYS];  /* its layout (sim_state_array_layout: DEM_MOVE_P or DEM_MOVE_G) */
    int per[DEM_STATE_MAX_ARRAYS];   /* and its elements per particle (DEM_MOVE_G: per particle in a group) */
    hid_t d[D__N];                   /* radius and the pairs' (0: not in this run) */
    long at;                         /* contacts written so far */
} slab_sets;

/* slab p of particles [a, b) of the n of the run into the datasets: each array's rows (groups of n rows: every
 * group's rows of the slab), the radii, and the contacts after those written so far; -1 where a write failed, -2
 * where p does not fit them */
static int write_slab(slab_sets *w, const dem_state *h, const dem_state *p, const double *radius, long a, long b,
                      long n, long npairs, hid_t real_t)
{
    long m = b - a;
    if (p->narrays != h->narrays || p->n != m || w->at + p->npairs > npairs)
        return -2;
    for (int k = 0; k < h->narrays; k++) {
        const dem_state_array *ha = &h->arrays[k], *pa = &p->arrays[k];
        if (!w->arr[k])
            continue;
        /* a particle's rows one after the other (DEM_MOVE_P), or groups of n items, one item of `each` rows of
         * each particle in each group (DEM_MOVE_G: one group per wall): the slab's m items at each of groups places */
        size_t wd = (size_t)(ha->width > 1 ? ha->width : 1), rows = pa->count / wd, whole = ha->count / wd;
        size_t times = whole / (size_t)(n ? n : 1), row = wd * array_elem(ha, h->real_size);
        size_t each = w->kind[k] == DEM_MOVE_G ? (size_t)w->per[k] / wd : times, groups = each ? times / each : 0;
        if (strcmp(pa->name, ha->name) || pa->count % wd || rows != times * (size_t)m || (rows && !pa->data) ||
            groups * each != times)
            return -2;
        for (size_t g = 0; g < groups; g++)
            if (h5_write_rows(w->arr[k], array_type(ha, real_t), (g * (size_t)n + (size_t)a) * each, (hsize_t)m * each,
                              (const unsigned char *)pa->data + g * (size_t)m * each * row))
                return -1;
    }
    long q = p->npairs, at = w->at;
    const void *src[D__N] = {radius, p->pair_i, p->pair_j, p->pair_hist, p->pair_rec, p->pair_mc_fn, p->pair_law,
                             p->pair_rspring, p->pair_mc_disp};
    for (int k = 0; k < D__N; k++) {
        hid_t t = k == D_RADIUS ? H5T_NATIVE_DOUBLE : k == D_PI || k == D_PJ ? H5T_NATIVE_INT : real_t;
        long first = k == D_RADIUS ? a : at, count = k == D_RADIUS ? m : q;
        if (w->d[k] > 0 && count && (!src[k] || h5_write_rows(w->d[k], t, (hsize_t)first, (hsize_t)count, src[k])))
            return -1;
    }
    w->at += q;
    return 0;
}

/* /state of the checkpoint: the header's attributes, walls and patch contacts from h, the particles and contacts from
 * src; 1 where a write failed, 2 where src did, 3 where what it gave does not fit h */
static int write_state(hid_t g, dem_sim *s, const dem_state *h, const checkpoint_source *src)
{
    hid_t real_t = h->real_size == 8 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT;
    long n = src->n, np = src->npairs;
    hsize_t w3[2] = {(hsize_t)h->nwalls, 3}, w1[1] = {(hsize_t)h->nwalls};
    hsize_t q1[1] = {(hsize_t)h->npatch}, q3[2] = {(hsize_t)h->npatch, 3};
    int rc = h5_attr_long(g, "step", h->step) || h5_attr_long(g, "n", n) || h5_attr_long(g, "nwalls", h->nwalls) ||
             h5_attr_long(g, "real_size", h->real_size) || h5_attr_long(g, "has_hist", h->has_hist) ||
             h5_attr_long(g, "rebuilds", h->rebuilds) || h5_attr_double(g, "time", dem_time(s));
    slab_sets w;
    memset(&w, 0, sizeof w);
    /* the arrays: the walls' (DEM_MOVE_STAY) whole from h, the particles' made whole for the slabs */
    for (int k = 0; !rc && k < h->narrays; k++) {
        const dem_state_array *a = &h->arrays[k];
        size_t wd = (size_t)(a->width > 1 ? a->width : 1);
        hsize_t d[2] = {a->count / wd, wd};
        if ((w.kind[k] = sim_state_array_layout(s, a->name, &w.per[k])) == DEM_MOVE_STAY)
            rc = a->data && h5_write(g, a->name, array_type(a, real_t), a->width > 1 ? 2 : 1, d, a->data, a->unit);
        else if (a->data || a->count) /* (an empty array with data: an empty dataset, as before) */
            rc = (w.arr[k] = h5_create(g, a->name, array_type(a, real_t), a->width > 1 ? 2 : 1, d, a->unit)) < 0;
    }
    rc = rc || h5_write(g, "wall_pos", H5T_NATIVE_DOUBLE, 2, w3, h->wall_pos, "m") ||
         h5_write(g, "wall_stage", H5T_NATIVE_INT, 1, w1, h->wall_stage, NULL) ||
         h5_write(g, "wall_stage_first", H5T_NATIVE_LONG, 1, w1, h->wall_stage_first, NULL) ||
         h5_write(g, "wall_stage_from", H5T_NATIVE_DOUBLE, 2, w3, h->wall_stage_from, "m");
    /* the contacts' datasets, in the order h5_write made them before they were written in slabs */
    struct {
        int k, rank, on;
        const char *name, *unit;
        hsize_t d1;
    } ds[] = {
        {D_PI, 1, 1, "pair_i", NULL, 0},
        {D_PJ, 1, 1, "pair_j", NULL, 0},
        {D_HIST, 2, 1, "pair_hist", "N", 3},
        {D_REC, 2, h->pair_rec != NULL, "pair_rec", "N (force, n x f_t), m (overlap)", DEM_PAIR_RECORD_REALS},
        {D_RADIUS, 1, 1, "radius", "m", 0},
        {D_MCF, 1, 1, "pair_mc_fn", "N", 0},
        {D_LAW, h->has_law > 1 ? 2 : 1, h->has_law > 0, "pair_law", h->has_law == 1 ? "m" : NULL,
         (hsize_t)h->has_law},
        {D_RSP, 2, h->has_rspring, "pair_rspring", "N m", 3},
        {D_MCD, 2, h->pair_mc_disp != NULL, "pair_mc_disp", "m", 2},
    };
    for (size_t k = 0; !rc && k < sizeof ds / sizeof ds[0]; k++) {
        hsize_t d[2] = {ds[k].k == D_RADIUS ? (hsize_t)n : (hsize_t)np, ds[k].d1};
        if (ds[k].k == D_MCF || ds[k].k == D_MCD) /* MC-strain's: empty without it */
            d[0] = h->has_mc ? d[0] : 0;
        if (ds[k].k == D_MCF)
            rc = h5_attr_long(g, "has_mc", h->has_mc) || h5_attr_long(g, "mc_last", h->mc.last) ||
                 h5_attr_long(g, "mc_max", h->mc.max) || h5_attr_long(g, "mc_total", h->mc.total) ||
                 h5_attr_long(g, "mc_unconverged", h->mc.unconverged);
        if (!rc && ds[k].k == D_LAW)
            rc = h5_attr_long(g, "has_law", h->has_law) ||
                 ((dem_effects(s) & DEM_EFFECT_ADHESION) && h5_attr_string(g, "law_state", CHECKPOINT_JKR_STATE));
        if (!rc && ds[k].k == D_RSP && h->has_rspring)
            rc = h5_attr_long(g, "has_rspring", 1);
        if (!rc && ds[k].on)
            rc = (w.d[ds[k].k] = h5_create(g, ds[k].name, ds[k].k == D_PI || ds[k].k == D_PJ ? H5T_NATIVE_INT
                                                          : ds[k].k == D_RADIUS ? H5T_NATIVE_DOUBLE
                                                                                 : real_t,
                                           ds[k].rank, d, ds[k].unit)) < 0;
        if (!rc && d[0] == 0) /* nothing to write: closed now */
            H5Dclose(w.d[ds[k].k]), w.d[ds[k].k] = 0;
    }
    rc = rc || h5_write(g, "patch_i", H5T_NATIVE_INT, 1, q1, h->patch_i, NULL) ||
         h5_write(g, "patch_t", H5T_NATIVE_INT, 1, q1, h->patch_t, NULL) ||
         h5_write(g, "patch_hist", real_t, 2, q3, h->patch_hist, "N") ||
         (h->patch_side && h5_write(g, "patch_side", H5T_NATIVE_INT, 1, q1, h->patch_side, NULL));
    /* the particles and their contacts, slab by slab */
    for (long a = 0; !rc && a < n; a += src->slab) {
        long b = n - a > src->slab ? a + src->slab : n;
        const dem_state *p;
        const double *radius;
        int e = src->slab_get(src->ctx, a, b, &p, &radius) ? -3 : (errno = 0, write_slab(&w, h, p, radius, a, b, n,
                                                                                         np, real_t));
        rc = e == -3 ? 2 : e == -2 ? 3 : e ? 1 : 0;
    }
    if (!rc && w.at != np)
        rc = 3;
    for (int k = 0; k < DEM_STATE_MAX_ARRAYS; k++)
        if (w.arr[k] > 0 && H5Dclose(w.arr[k]) < 0)
            rc = rc ? rc : 1;
    for (int k = 0; k < D__N; k++)
        if (w.d[k] > 0 && H5Dclose(w.d[k]) < 0)
            rc = rc ? rc : 1;
    return rc;
}

int checkpoint_write_from(const char *path, dem_sim *s, const dem_state *head, const checkpoint_source *src,
                          const scene *sc, const scene_run *run, char *err, size_t errlen)
{
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s" CHECKPOINT_TMP_SUFFIX, path);
    errno = 0;
    hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    int rc = f < 0;
    if (!rc) {
        hid_t g = H5Gcreate2(f, "state", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = g < 0 ? 1 : write_state(g, s, head, src);
        if (g >= 0)
            H5Gclose(g);
        hid_t sg = rc ? -1 : H5Gcreate2(f, "scene", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = rc ? rc
                : sg < 0 || h5_write_text(sg, "text", sc->text) || h5_write_text(sg, "path", sc->path) ||
                  h5_attr_string(sg, "model", run->model) ||
                  h5_attr_string(sg, "particle_order", scene_particle_order(sc)) ||
                  h5_attr_string(f, "libdem_version", DEM_VERSION);
        if (sg >= 0)
            H5Gclose(sg);
    }
    int e = errno; /* the first failure's reason, before close and unlink add their own */
    if (f >= 0 && H5Fclose(f) < 0)
        rc = rc ? rc : 1, e = e ? e : errno;
    if (!rc && (sync_file(tmp) || rename(tmp, path)))
        rc = 1, e = errno;
    if (rc) {
        unlink(tmp);
        if (rc == 2) /* the source's words are in err */
            return -2;
        if (rc == 3) {
            snprintf(err, errlen, "%s: cannot write the checkpoint: the particles or contacts given do not fit the run's "
                     "state (a bug; the previous one, if any, is kept)", path);
            return -1;
        }
        snprintf(err, errlen, "%s: cannot write the checkpoint: %s (the previous one, if any, is kept)", path,
                 h5_io_reason(e));
        return -1;
    }
    return 0;
}

/* one process: the whole state is the one slab */
typedef struct {
    const dem_state *st;
    const double *radius;
} whole_source;
static int whole_slab(void *ctx, long a, long b, const dem_state **part, const double **radius)
{
    const whole_source *w = ctx;
    (void)a, (void)b;
    *part = w->st, *radius = w->radius;
    return 0;
}

int checkpoint_write(const char *path, dem_sim *s, const scene *sc, const scene_run *run, char *err, size_t errlen)
{
    dem_state st;
    if (dem_state_get(s, &st)) {
        snprintf(err, errlen, "checkpoint: %s", dem_error(s));
        return 1;
    }
    double *radius = malloc(sizeof(double) * (size_t)(st.n ? st.n : 1));
    for (int i = 0; radius && i < st.n; i++)
        radius[i] = dem_particle_radius(s, i);
    whole_source w = {&st, radius};
    checkpoint_source src = {&w, st.n, st.npairs, st.n > 0 ? st.n : 1, whole_slab};
    int rc = radius ? checkpoint_write_from(path, s, &st, &src, sc, run, err, errlen) : -1;
    if (!radius)
        snprintf(err, errlen, "%s: cannot write the checkpoint: out of host memory (the previous one, if any, is kept)",
                 path);
    free(radius);
    dem_state_free(&st);
    return rc ? 1 : 0;
}

/* An optional dataset of `want` reals of rs bytes into *out: absent or empty, *out stays NULL; any other count than
 * want is a damaged checkpoint (1), checked before anything is allocated */
static int read_optional(hid_t g, const char *name, hid_t real_t, size_t want, long rs, void **out)
{
    long have = H5Lexists(g, name, H5P_DEFAULT) > 0 ? h5_count(g, name) : 0;
    if (have <= 0)
        return have < 0;
    if ((size_t)have != want || !(*out = malloc((want + 1) * (size_t)rs)))
        return 1;
    return h5_read(g, name, real_t, *out, want);
}

/* The state's arrays (dem_state_arrays: those of st's header) from /state/<name>: one a state must hold is there at
 * its count; another is missing, empty (NULL: zero until computed) or at its count; any other count is a damaged
 * checkpoint (1), checked before anything is allocated */
static int read_arrays(hid_t g, dem_state *st, hid_t real_t)
{
    dem_state_arrays(st);
    for (int k = 0; k < st->narrays; k++) {
        dem_state_array *a = &st->arrays[k];
        long have = a->count && H5Lexists(g, a->name, H5P_DEFAULT) > 0 ? h5_count(g, a->name) : 0;
        size_t size = a->elem == DEM_STATE_REAL ? (size_t)st->real_size : sizeof(int);
        if (have < 0 || (have == 0 && a->required && a->count) || (have > 0 && (size_t)have != a->count))
            return 1;
        if (have == 0) {
            a->count = 0;
            continue;
        }
        if (!(a->data = malloc(a->count * size + 1)) || h5_read(g, a->name, array_type(a, real_t), a->data, a->count))
            return 1;
    }
    return 0;
}

/* The first element of a[count] (reals of rs bytes) that is not finite, or -1 */
static long first_nonfinite(const void *a, size_t count, int rs, double *value)
{
    for (size_t k = 0; a && k < count; k++) {
        double v = rs == 8 ? ((const double *)a)[k] : (double)((const float *)a)[k];
        if (!isfinite(v))
            return *value = v, (long)k;
    }
    return -1;
}

/* err: /state/name's element at is v, not finite (checkpoint_read's words); returns 2 */
static int not_finite(char *err, size_t errlen, const char *path, const char *name, long at, double v)
{
    snprintf(err, errlen, "%s: /state/%s: element %ld is %g: a checkpoint holds finite numbers only (damaged or "
             "edited)", path, name, at, v);
    return 2;
}

/* Every number restored is finite and every radius > 0: a nan wall position would silently stop the wall acting (and
 * be written to the next checkpoint), a nan velocity fail the run steps later, an infinite spin run on. Refused here
 * with the dataset's name (exit 65), before anything reaches the device. */
static int check_finite(const checkpoint *ck, const char *path, char *err, size_t errlen)
{
    const dem_state *st = &ck->st;
    size_t n = (size_t)st->n, nw = (size_t)st->nwalls, np = (size_t)st->npairs;
    const struct {
        const char *name;
        const void *a;
        size_t count;
        int size; /* 8 for the doubles the file holds whatever the run's precision */
    } arrays[] = {
        {"wall_pos", st->wall_pos, 3 * nw, 8},
        {"wall_stage_from", st->has_stages ? st->wall_stage_from : NULL, 3 * nw, 8},
        {"pair_hist", st->pair_hist, 3 * np, st->real_size},
        {"pair_rec", st->pair_rec, DEM_PAIR_RECORD_REALS * np, st->real_size},
        {"pair_mc_fn", st->has_mc ? st->pair_mc_fn : NULL, np, st->real_size},
        {"pair_mc_disp", st->pair_mc_disp, 2 * np, st->real_size},
        {"pair_law", st->has_law ? st->pair_law : NULL, (size_t)st->has_law * np, st->real_size},
        {"pair_rspring", st->has_rspring ? st->pair_rspring : NULL, 3 * np, st->real_size},
        {"patch_hist", st->patch_hist, 3 * (size_t)st->npatch, st->real_size}, {"radius", ck->radius, n, 8},
    };
    for (int k = 0; k < st->narrays; k++) { /* the arrays of reals */
        const dem_state_array *a = &st->arrays[k];
        double v = 0;
        long at = a->elem == DEM_STATE_REAL ? first_nonfinite(a->data, a->count, st->real_size, &v) : -1;
        if (at >= 0)
            return not_finite(err, errlen, path, a->name, at, v);
    }
    for (size_t q = 0; q < sizeof arrays / sizeof arrays[0]; q++) {
        double v = 0;
        long k = first_nonfinite(arrays[q].a, arrays[q].count, arrays[q].size, &v);
        if (k >= 0)
            return not_finite(err, errlen, path, arrays[q].name, k, v);
    }
    for (size_t i = 0; i < n; i++)
        if (!(ck->radius[i] > 0))
            return snprintf(err, errlen, "%s: /state/radius: element %zu is %g: radii are > 0 (damaged or edited)",
                            path, i, ck->radius[i]), 1;
    return 0;
}

/* The sphere-patch contacts (membranes; absent from older checkpoints: none) */
static int read_patches(hid_t g, dem_state *st, hid_t real_t)
{
    int rc = 0;
    long n = st->n, rs = st->real_size;
    long npatch = H5Lexists(g, "patch_i", H5P_DEFAULT) > 0 ? h5_count(g, "patch_i") : 0;
    if (!rc && (npatch < 0 || npatch > 64 * n || (npatch && (h5_count(g, "patch_t") != npatch ||
                                                             h5_count(g, "patch_hist") != 3 * npatch))))
        rc = 1;
    if (!rc && npatch) {
        st->patch_i = malloc(sizeof(int) * (size_t)npatch), st->patch_t = malloc(sizeof(int) * (size_t)npatch);
        st->patch_hist = malloc(3 * (size_t)npatch * rs);
        st->npatch = npatch;
        rc = !st->patch_i || !st->patch_t || !st->patch_hist ||
             h5_read(g, "patch_i", H5T_NATIVE_INT, st->patch_i, (size_t)npatch) ||
             h5_read(g, "patch_t", H5T_NATIVE_INT, st->patch_t, (size_t)npatch) ||
             h5_read(g, "patch_hist", real_t, st->patch_hist, 3 * (size_t)npatch);
        if (!rc && H5Lexists(g, "patch_side", H5P_DEFAULT) > 0) { /* absent from older ones: not known */
            st->patch_side = malloc(sizeof(int) * (size_t)npatch);
            rc = !st->patch_side || h5_count(g, "patch_side") != npatch ||
                 h5_read(g, "patch_side", H5T_NATIVE_INT, st->patch_side, (size_t)npatch);
        }
    }
    return rc;
}

/* /state: its attributes, arrays and contacts into ck (1: missing or damaged) */
/* the walls' positions, and each wall's motion stage (absent from checkpoints of libdem before stages could end
 * early: derived from the step by dem_state_set) */
static int read_walls(hid_t g, dem_state *st, long nw)
{
    st->has_stages = H5Lexists(g, "wall_stage", H5P_DEFAULT) > 0;
    return h5_read(g, "wall_pos", H5T_NATIVE_DOUBLE, st->wall_pos, 3 * (size_t)nw) ||
           (st->has_stages &&
            (h5_read(g, "wall_stage", H5T_NATIVE_INT, st->wall_stage, (size_t)nw) ||
             h5_read(g, "wall_stage_first", H5T_NATIVE_LONG, st->wall_stage_first, (size_t)nw) ||
             h5_read(g, "wall_stage_from", H5T_NATIVE_DOUBLE, st->wall_stage_from, 3 * (size_t)nw)));
}

/* /state into ck; head: its attributes, contact count, walls and stages alone (no particle arrays, radii, contacts or
 * patch contacts: nothing of a size that grows with the run) */
static int read_state(hid_t g, checkpoint *ck, int head)
{
    dem_state *st = &ck->st;
    long n = 0, nw = 0, rs = 0, hh = 0, hm = 0, hl = 0, hr = 0;
    int rc = g < 0 || h5_read_attr_long(g, "step", &st->step) || h5_read_attr_long(g, "n", &n) ||
             h5_read_attr_long(g, "nwalls", &nw) || h5_read_attr_long(g, "real_size", &rs) ||
             h5_read_attr_long(g, "has_hist", &hh) || (rs != 4 && rs != 8) || n < 1 || nw < 0 || nw > DEM_MAX_WALLS;
    /* nothing is allocated on a size the file merely claims: the counts must agree with the datasets actually
     * there, within the library's limits, before any memory is asked for */
    if (!rc && (n > CHECKPOINT_MAX_PARTICLES || h5_count(g, "x") != 3 * n || h5_count(g, "radius") != n ||
                st->step < 0 || st->step > CHECKPOINT_MAX_STEP || (hh != 0 && hh != 1)))
        rc = 1;
    if (!rc) {
        h5_read_attr_long(g, "rebuilds", &st->rebuilds);
        h5_read_attr_long(g, "has_mc", &hm);
        h5_read_attr_long(g, "has_law", &hl); /* absent from checkpoints of runs before plastic laws: 0; the reals
                                                   per contact: 1 thornton_ning, 24 mdr */
        st->has_law = hl == 1 || hl == DEM_MDR_LAW_REALS ? (int)hl : 0;
        /* written only by runs with JKR adhesion since their state is the largest contact radius */
        char *ls = H5Aexists(g, "law_state") > 0 ? h5_read_attr_string(g, "law_state") : NULL;
        snprintf(ck->law_state, sizeof ck->law_state, "%s", ls ? ls : "");
        free(ls);
        h5_read_attr_long(g, "has_rspring", &hr); /* written only by runs with rolling springs */
        st->has_rspring = hr == 1;
        h5_read_attr_long(g, "mc_last", &st->mc.last);
        h5_read_attr_long(g, "mc_max", &st->mc.max);
        h5_read_attr_long(g, "mc_total", &st->mc.total);
        h5_read_attr_long(g, "mc_unconverged", &st->mc.unconverged);
        st->has_mc = (int)hm;
        st->n = (int)n, st->nwalls = (int)nw, st->real_size = (int)rs, st->has_hist = (int)hh;
        hid_t real_t = rs == 8 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT;
        long npairs = h5_count(g, "pair_i"); /* every other size follows from n, nwalls, has_hist, has_mc */
        if (npairs > 64 * n || h5_count(g, "pair_j") != npairs || (hm != 0 && hm != 1) || (hl != 0 && hl != 1 && hl != DEM_MDR_LAW_REALS) ||
            (hr != 0 && hr != 1))
            rc = 1, npairs = 0;
        if (npairs < 0)
            rc = 1, npairs = 0;
        if (head) {
            st->npairs = npairs;
            return rc || read_walls(g, st, nw);
        }
        st->pair_i = malloc(sizeof(int) * (size_t)(npairs + 1));
        st->pair_j = malloc(sizeof(int) * (size_t)(npairs + 1));
        st->pair_hist = malloc(3 * (size_t)(npairs + 1) * rs);
        size_t want_pm = hm ? (size_t)npairs : 0;
        st->pair_mc_fn = malloc((want_pm + 1) * rs);
        st->pair_law = malloc(((size_t)hl * (size_t)npairs + 1) * rs);
        st->pair_rspring = malloc(((hr ? 3 * (size_t)npairs : 0) + 1) * rs);
        ck->radius = malloc(sizeof(double) * (size_t)n);
        rc = rc || !st->pair_i || !st->pair_j || !st->pair_hist || !ck->radius || read_arrays(g, st, real_t) ||
             h5_read(g, "radius", H5T_NATIVE_DOUBLE, ck->radius, (size_t)n);
        st->npairs = npairs;
        rc = rc || h5_read(g, "pair_i", H5T_NATIVE_INT, st->pair_i, (size_t)npairs) ||
             h5_read(g, "pair_j", H5T_NATIVE_INT, st->pair_j, (size_t)npairs) ||
             h5_read(g, "pair_hist", real_t, st->pair_hist, 3 * (size_t)npairs) || !st->pair_mc_fn ||
             (hm && h5_read(g, "pair_mc_fn", real_t, st->pair_mc_fn, (size_t)npairs)) || !st->pair_law ||
             (hl && h5_read(g, "pair_law", real_t, st->pair_law, (size_t)hl * (size_t)npairs)) || !st->pair_rspring ||
             (hr && h5_read(g, "pair_rspring", real_t, st->pair_rspring, 3 * (size_t)npairs));
        /* what the contact network reads right after a restore (absent from older checkpoints, empty in runs that
         * keep none of it: those values zero until the next step): each touching pair's force record of the last
         * step (common/dem_layout.h PR_*) and MC-strain's induced displacements at both ends of each pair (the
         * per-particle ones are arrays of the state, read above) */
        rc = rc || read_optional(g, "pair_rec", real_t, DEM_PAIR_RECORD_REALS * (size_t)npairs, rs, &st->pair_rec) ||
             read_optional(g, "pair_mc_disp", real_t, 2 * (size_t)npairs, rs, &st->pair_mc_disp);
        rc = rc || read_walls(g, st, nw) || read_patches(g, st, real_t);
    }
    return rc;
}

static int read_file(const char *path, checkpoint *ck, int head, char *err, size_t errlen)
{
    memset(ck, 0, sizeof *ck);
    if (access(path, R_OK) != 0) { /* missing or unreadable: exit 66, unlike a damaged file (65) */
        snprintf(err, errlen, "%s: cannot open the checkpoint: %s", path, strerror(errno));
        return 1;
    }
    struct stat sb; /* a pipe would block the open forever, a device be read without end: regular files only */
    int found = stat(path, &sb) == 0;
    if (!found || !S_ISREG(sb.st_mode)) {
        snprintf(err, errlen, "%s: cannot open the checkpoint: %s", path,
                 found ? "not a regular file (a folder, pipe, socket or device)" : strerror(errno));
        return 1;
    }
    H5E_auto2_t old;
    void *old_data;
    H5Eget_auto2(H5E_DEFAULT, &old, &old_data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    H5Eset_auto2(H5E_DEFAULT, old, old_data);
    if (f < 0) {
        snprintf(err, errlen, "%s: not a readable HDF5 checkpoint", path);
        return 1;
    }
    hid_t g = H5Lexists(f, "state", H5P_DEFAULT) > 0 ? H5Gopen2(f, "state", H5P_DEFAULT) : -1;
    int rc = g < 0 || read_state(g, ck, head);
    if (g >= 0)
        H5Gclose(g);
    const char *what = NULL;
    if (!rc) {
        hid_t sg = H5Lexists(f, "scene", H5P_DEFAULT) > 0 ? H5Gopen2(f, "scene", H5P_DEFAULT) : -1;
        ck->scene_text = sg >= 0 ? h5_read_text(sg, "text") : NULL;
        ck->scene_path = sg >= 0 ? h5_read_text(sg, "path") : NULL;
        int has_model = sg >= 0 && H5Aexists(sg, "model") > 0;
        char *model = has_model ? h5_read_attr_string(sg, "model") : NULL;
        int model_ok = !has_model || model;
        snprintf(ck->model, sizeof ck->model, "%s", model ? model : "");
        free(model);
        int has_order = sg >= 0 && H5Aexists(sg, "particle_order") > 0;
        char *order = has_order ? h5_read_attr_string(sg, "particle_order") : NULL;
        int order_ok = !has_order || (order && (!strcmp(order, "input") || !strcmp(order, "spatial")));
        snprintf(ck->order, sizeof ck->order, "%s", order ? order : "");
        free(order);
        if (sg >= 0)
            H5Gclose(sg);
        rc = !ck->scene_text || !ck->scene_path || !model_ok; /* a model that cannot be read: damaged */
        rc = rc || !order_ok;
        what = !ck->scene_text ? "/scene/text" : !ck->scene_path ? "/scene/path" : !model_ok ? "/scene model"
                                                : !order_ok ? "/scene particle_order (input or spatial)" : NULL;
    }
    H5Fclose(f);
    if (rc) {
        if (what) /* the scene's text, path or model: not one fixed-length string */
            snprintf(err, errlen, "%s: incomplete or damaged checkpoint: %s is missing or not one fixed-length string",
                     path, what);
        else
            snprintf(err, errlen, "%s: incomplete or damaged checkpoint", path);
        checkpoint_free(ck);
        return 1;
    }
    if (!head && check_finite(ck, path, err, errlen)) {
        checkpoint_free(ck);
        return 1;
    }
    return 0;
}

int checkpoint_read(const char *path, checkpoint *ck, char *err, size_t errlen)
{
    return read_file(path, ck, 0, err, errlen);
}

int checkpoint_read_head(const char *path, checkpoint *ck, char *err, size_t errlen)
{
    return read_file(path, ck, 1, err, errlen);
}

void checkpoint_free(checkpoint *ck)
{
    dem_state_free(&ck->st);
    free(ck->scene_text);
    free(ck->scene_path);
    free(ck->radius);
    memset(ck, 0, sizeof *ck);
}

/* ---- a rank's part of a checkpoint (a restart split over ranks): nothing of the whole run's size but its positions
 * ---- */

/* kept ids per slab of the file's ids: no read holds more than this many particles' rows; contacts per read of the
 * pairs' datasets. DEM_TEST_FRAME_SLAB sets both (the tests: slabs of a few particles, as the writer's), read once
 * per part */
static long part_slab(long fallback)
{
    const char *t = getenv("DEM_TEST_FRAME_SLAB");
    return t && atol(t) > 0 ? atol(t) : fallback;
}

/* dataset d holds rows of wd elements (2-D, wd wide; 1-D where wd is 1): what the part's reads take it for (a
 * checkpoint of an older libdem kept some arrays flat, which the whole read takes by their count) */
static int rows_of(hid_t d, size_t wd)
{
    hid_t s = H5Dget_space(d);
    hsize_t dims[H5S_MAX_RANK];
    int r = s >= 0 ? H5Sget_simple_extent_dims(s, dims, NULL) : -1;
    if (s >= 0)
        H5Sclose(s);
    return wd == 1 ? r == 1 || (r == 2 && dims[1] == 1) : r == 2 && dims[1] == wd;
}

/* where v is in the ascending keep[0..m), or -1 */
static long keep_at(const long *keep, long m, long v)
{
    long k = sim_id_from(keep, m, v);
    return k < m && keep[k] == v ? k : -1;
}


/* A dataset of the whole run's rows read for the kept particles: n particles of `each` rows of `row` bytes in each
 * of `groups` groups (row (g n + id) each + r of the file) into out (group g's kept particles' rows one after the
 * other, in keep's order), slab by slab of ids; the reals checked finite as read (elements of `wd` per row: the
 * file's element index said). 0; 1 a read failed; 2 a real is not finite (err says which). */
static int read_kept(hid_t d, hid_t mem_t, long n, size_t groups, size_t each, size_t row, size_t wd, int real,
                     int rs, const long *keep, long m, void *out, const char *path, const char *name, char *err,
                     size_t errlen)
{
    if (!rows_of(d, wd))
        return snprintf(err, errlen, "%s: /state/%s is not in rows of %zu: a checkpoint of an older libdem, which a "
                        "split run cannot read in parts (continue it in one process)", path, name, wd), 1;
    long slab = part_slab(32768L);
    unsigned char *buf = malloc(row * each * (size_t)slab + 1);
    int rc = buf ? 0 : 1;
    for (size_t g = 0; !rc && g < groups; g++)
        for (long k0 = 0; !rc && k0 < m;) {
            long a = keep[k0], k1 = k0; /* the kept ids within [a, a + slab) */
            while (k1 < m && keep[k1] < a + slab)
                k1++;
            long span = keep[k1 - 1] - a + 1;
            rc = h5_read_rows(d, mem_t, (hsize_t)(g * (size_t)n + (size_t)a) * each, (hsize_t)span * each, buf) ? 1 : 0;
            for (long k = k0; !rc && k < k1; k++) {
                const unsigned char *src = buf + (size_t)(keep[k] - a) * each * row;
                double v = 0;
                long at = real ? first_nonfinite(src, each * wd, rs, &v) : -1;
                if (at >= 0)
                    rc = not_finite(err, errlen, path, name, (long)((g * (size_t)n + (size_t)keep[k]) * each * wd) + at,
                                    v);
                memcpy((unsigned char *)out + (g * (size_t)m + (size_t)k) * each * row, src, each * row);
            }
            k0 = k1;
        }
    free(buf);
    return rc;
}

/* The contacts of the file with both ends kept, renumbered to their places in keep (ascending i, then j, as the file
 * holds them): counted (part->npairs) when part->pair_i is NULL, else filled with every per-pair array the file has.
 * 0; 1 a read failed or the file is damaged; 2 a real is not finite (err) */
static int read_kept_pairs(hid_t g, const checkpoint *head, const long *keep, long m, dem_state *part,
                           const char *path, char *err, size_t errlen)
{
    const dem_state *h = &head->st;
    long np = h->npairs, rs = h->real_size, got = 0;
    hid_t real_t = rs == 8 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT;
    int fill = part->pair_i != NULL;
    struct {
        const char *name;
        size_t width;
        void **to;
    } per[] = {{"pair_hist", 3, &part->pair_hist},
               {"pair_rec", DEM_PAIR_RECORD_REALS, &part->pair_rec},
               {"pair_mc_fn", 1, &part->pair_mc_fn},
               {"pair_law", (size_t)h->has_law, &part->pair_law},
               {"pair_rspring", 3, &part->pair_rspring},
               {"pair_mc_disp", 2, &part->pair_mc_disp}};
    enum { NPER = sizeof per / sizeof per[0] };
    hid_t ds[NPER + 2] = {0};
    long chunk = part_slab(65536L);
    size_t widest = 3; /* the widest row of a contact's arrays: the record, or MDR's state (25 reals) */
    for (int k = 0; k < NPER; k++)
        widest = per[k].width > widest ? per[k].width : widest;
    int *pij = malloc(sizeof(int) * 2 * (size_t)chunk);
    long *at = malloc(sizeof(long) * (size_t)chunk);
    unsigned char *buf = malloc((size_t)chunk * widest * (size_t)rs + 1);
    int rc = pij && at && buf ? 0 : 1;
    if (!rc && np) {
        ds[0] = H5Dopen2(g, "pair_i", H5P_DEFAULT), ds[1] = H5Dopen2(g, "pair_j", H5P_DEFAULT);
        rc = ds[0] < 0 || ds[1] < 0;
    }
    for (int k = 0; fill && !rc && k < NPER; k++) /* those this part holds (allocated by the caller: the file has it) */
        if (*per[k].to && per[k].width) {
            rc = (ds[k + 2] = H5Dopen2(g, per[k].name, H5P_DEFAULT)) < 0;
            if (!rc && !rows_of(ds[k + 2], per[k].width))
                rc = 1, snprintf(err, errlen, "%s: /state/%s is not in rows of %zu: a checkpoint of an older libdem, "
                                 "which a split run cannot read in parts (continue it in one process)", path,
                                 per[k].name, per[k].width);
        }
    for (long c0 = 0; !rc && c0 < np; c0 += chunk) {
        long cn = np - c0 < chunk ? np - c0 : chunk, picked = 0;
        rc = h5_read_rows(ds[0], H5T_NATIVE_INT, (hsize_t)c0, (hsize_t)cn, pij) ||
             h5_read_rows(ds[1], H5T_NATIVE_INT, (hsize_t)c0, (hsize_t)cn, pij + chunk);
        for (long p = 0; !rc && p < cn; p++) {
            long i = keep_at(keep, m, pij[p]), j = keep_at(keep, m, pij[chunk + p]);
            if (pij[p] < 0 || pij[p] >= h->n || pij[chunk + p] < 0 || pij[chunk + p] >= h->n ||
                pij[p] == pij[chunk + p])
                rc = 1; /* not a pair of two of the run's particles */
            else if (i >= 0 && j >= 0) {
                if (fill)
                    part->pair_i[got + picked] = (int)i, part->pair_j[got + picked] = (int)j;
                at[picked++] = p;
            }
        }
        for (int k = 0; fill && !rc && picked && k < NPER; k++) {
            if (ds[k + 2] <= 0)
                continue;
            size_t row = per[k].width * (size_t)rs;
            rc = h5_read_rows(ds[k + 2], real_t, (hsize_t)c0, (hsize_t)cn, buf) ? 1 : 0;
            for (long q = 0; !rc && q < picked; q++) {
                const unsigned char *src = buf + (size_t)at[q] * row;
                double v = 0;
                long bad = first_nonfinite(src, per[k].width, (int)rs, &v);
                if (bad >= 0)
                    rc = not_finite(err, errlen, path, per[k].name, (c0 + at[q]) * (long)per[k].width + bad, v);
                memcpy((unsigned char *)*per[k].to + (size_t)(got + q) * row, src, row);
            }
        }
        got += picked;
    }
    for (int k = 0; k < NPER + 2; k++)
        if (ds[k] > 0)
            H5Dclose(ds[k]);
    free(pij), free(at), free(buf);
    part->npairs = got;
    return rc;
}

/* HDF5's own error stack off while a part is read (what went wrong is said once, in err), and back */
static void h5_quiet(int on)
{
    static H5E_auto2_t old;
    static void *old_data;
    if (on) {
        H5Eget_auto2(H5E_DEFAULT, &old, &old_data);
        H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    } else
        H5Eset_auto2(H5E_DEFAULT, old, old_data);
}

int checkpoint_read_x(const char *path, const checkpoint *head, double *x, char *err, size_t errlen)
{
    long n = head->st.n;
    h5_quiet(1);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t g = f >= 0 ? H5Gopen2(f, "state", H5P_DEFAULT) : -1;
    int rc = g < 0 || h5_read(g, "x", H5T_NATIVE_DOUBLE, x, 3 * (size_t)n); /* an fp32 run's floats, widened */
    if (g >= 0)
        H5Gclose(g);
    if (f >= 0)
        H5Fclose(f);
    h5_quiet(0);
    if (rc)
        return snprintf(err, errlen, "%s: incomplete or damaged checkpoint", path), 1;
    for (long k = 0; k < 3 * n; k++)
        if (!isfinite(x[k]))
            return not_finite(err, errlen, path, "x", k, x[k]);
    return 0;
}

int checkpoint_read_part(const char *path, const checkpoint *head, dem_sim *s, long m, const long *keep,
                         dem_state *part, double *radius, char *err, size_t errlen)
{
    const dem_state *h = &head->st;
    long n = h->n, rs = h->real_size;
    hid_t real_t = rs == 8 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT;
    err[0] = 0;
    *part = *h; /* the header: step, counts, walls and their stages, what the run keeps (no arrays, no contacts) */
    part->n = (int)m, part->narrays = 0, part->npairs = 0;
    part->pair_i = part->pair_j = NULL;
    part->pair_hist = part->pair_rec = part->pair_mc_fn = part->pair_mc_disp = part->pair_law = NULL;
    part->pair_rspring = NULL;
    part->npatch = 0, part->patch_i = part->patch_t = part->patch_side = NULL, part->patch_hist = NULL;
    dem_state_arrays(part);
    h5_quiet(1);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t g = f >= 0 ? H5Gopen2(f, "state", H5P_DEFAULT) : -1;
    int rc = g < 0 || m < 1;
    for (int w = 0; !rc && w < h->nwalls; w++) /* what checkpoint_read checks of the header, which the head reads */
        for (int d = 0; d < 3; d++)
            if (!isfinite(h->wall_pos[w][d]))
                rc = not_finite(err, errlen, path, "wall_pos", 3 * w + d, h->wall_pos[w][d]);
            else if (h->has_stages && !isfinite(h->wall_stage_from[w][d]))
                rc = not_finite(err, errlen, path, "wall_stage_from", 3 * w + d, h->wall_stage_from[w][d]);
    for (int k = 0; !rc && k < part->narrays; k++) {
        dem_state_array *a = &part->arrays[k];
        int per = 0, kind = sim_state_array_layout(s, a->name, &per);
        size_t wd = (size_t)(a->width > 1 ? a->width : 1), es = array_elem(a, (int)rs);
        size_t whole = kind == DEM_MOVE_STAY ? a->count : a->count / (size_t)m * (size_t)n;
        long have = a->count && H5Lexists(g, a->name, H5P_DEFAULT) > 0 ? h5_count(g, a->name) : 0;
        if (kind < 0 || have < 0 || (have == 0 && a->required && a->count) || (have > 0 && (size_t)have != whole)) {
            rc = 1;
            break;
        }
        if (have == 0) {
            a->count = 0;
            continue;
        }
        if (!(a->data = malloc(a->count * es + 1))) {
            rc = 1;
            break;
        }
        if (kind == DEM_MOVE_STAY) { /* the walls' sums: whole */
            double v = 0;
            long bad = -1;
            rc = h5_read(g, a->name, array_type(a, real_t), a->data, a->count) ? 1 : 0;
            if (!rc && a->elem == DEM_STATE_REAL && (bad = first_nonfinite(a->data, a->count, (int)rs, &v)) >= 0)
                rc = not_finite(err, errlen, path, a->name, bad, v);
            continue;
        }
        size_t times = a->count / wd / (size_t)m, each = kind == DEM_MOVE_G ? (size_t)per / wd : times;
        size_t groups = each ? times / each : 0;
        hid_t d = H5Dopen2(g, a->name, H5P_DEFAULT);
        rc = d < 0 || groups * each != times ? 1
                                             : read_kept(d, array_type(a, real_t), n, groups, each, wd * es, wd,
                                                         a->elem == DEM_STATE_REAL, (int)rs, keep, m, a->data, path,
                                                         a->name, err, errlen);
        if (d >= 0)
            H5Dclose(d);
    }
    hid_t dr = rc ? -1 : H5Dopen2(g, "radius", H5P_DEFAULT);
    rc = rc ? rc : dr < 0 ? 1 : read_kept(dr, H5T_NATIVE_DOUBLE, n, 1, 1, sizeof(double), 1, 1, 8, keep, m, radius,
                                          path, "radius", err, errlen);
    if (dr >= 0)
        H5Dclose(dr);
    for (long k = 0; !rc && k < m; k++)
        if (!(radius[k] > 0))
            snprintf(err, errlen, "%s: /state/radius: element %ld is %g: radii are > 0 (damaged or edited)", path,
                     keep[k], radius[k]), rc = 2;
    if (!rc) /* the contacts: counted, then read */
        rc = read_kept_pairs(g, head, keep, m, part, path, err, errlen);
    long np = part->npairs;
    if (!rc) {
        part->pair_i = malloc(sizeof(int) * (size_t)(np + 1)), part->pair_j = malloc(sizeof(int) * (size_t)(np + 1));
        part->pair_hist = malloc(3 * (size_t)(np + 1) * (size_t)rs);
        part->pair_mc_fn = malloc(((h->has_mc ? (size_t)np : 0) + 1) * (size_t)rs);
        part->pair_law = malloc(((size_t)h->has_law * (size_t)np + 1) * (size_t)rs);
        part->pair_rspring = malloc(((h->has_rspring ? 3 * (size_t)np : 0) + 1) * (size_t)rs);
        /* the optional ones where the file has them at their whole count (read_optional's rule) */
        long rec = H5Lexists(g, "pair_rec", H5P_DEFAULT) > 0 ? h5_count(g, "pair_rec") : 0;
        long mcd = H5Lexists(g, "pair_mc_disp", H5P_DEFAULT) > 0 ? h5_count(g, "pair_mc_disp") : 0;
        rc = rec < 0 || mcd < 0 || (rec > 0 && rec != DEM_PAIR_RECORD_REALS * h->npairs) ||
             (mcd > 0 && mcd != 2 * h->npairs) || h5_count(g, "pair_hist") != 3 * h->npairs ||
             (h->has_mc && h5_count(g, "pair_mc_fn") != h->npairs) ||
             (h->has_law && h5_count(g, "pair_law") != h->has_law * h->npairs) ||
             (h->has_rspring && h5_count(g, "pair_rspring") != 3 * h->npairs);
        part->pair_rec = rec > 0 ? malloc((size_t)(DEM_PAIR_RECORD_REALS * np + 1) * (size_t)rs) : NULL;
        part->pair_mc_disp = mcd > 0 ? malloc((size_t)(2 * np + 1) * (size_t)rs) : NULL;
        if (!part->pair_i || !part->pair_j || !part->pair_hist || !part->pair_mc_fn || !part->pair_law ||
            !part->pair_rspring || (rec > 0 && !part->pair_rec) || (mcd > 0 && !part->pair_mc_disp))
            rc = 1;
        void *mcf = part->pair_mc_fn, *law = part->pair_law, *rsp = part->pair_rspring;
        if (!h->has_mc) /* (not read: their datasets empty) */
            part->pair_mc_fn = NULL;
        if (!h->has_law)
            part->pair_law = NULL;
        if (!h->has_rspring)
            part->pair_rspring = NULL;
        rc = rc ? rc : read_kept_pairs(g, head, keep, m, part, path, err, errlen);
        part->pair_mc_fn = mcf, part->pair_law = law, part->pair_rspring = rsp;
        rc = rc ? rc : part->npairs == np ? 0 : 1;
    }
    if (g >= 0)
        H5Gclose(g);
    if (f >= 0)
        H5Fclose(f);
    h5_quiet(0);
    if (rc && !err[0])
        snprintf(err, errlen, "%s: incomplete or damaged checkpoint", path);
    if (rc)
        dem_state_free(part);
    return rc;
}
