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
#include <fcntl.h>
#include <stdio.h>
#include <errno.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The HDF5 type of a state array's elements */
static hid_t array_type(const dem_state_array *a, hid_t real_t)
{
    return a->elem == DEM_STATE_REAL ? real_t : a->elem == DEM_STATE_UINT ? H5T_NATIVE_UINT : H5T_NATIVE_INT;
}

/* Every array of the state, as /state/<name>: rows of `width` elements */
static int write_arrays(hid_t g, const dem_state *st, hid_t real_t)
{
    for (int k = 0; k < st->narrays; k++) {
        const dem_state_array *a = &st->arrays[k];
        hsize_t d[2] = {a->width > 1 ? a->count / (size_t)a->width : a->count, (hsize_t)a->width};
        if (a->data && h5_write(g, a->name, array_type(a, real_t), a->width > 1 ? 2 : 1, d, a->data, a->unit))
            return 1;
    }
    return 0;
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

int checkpoint_write(const char *path, dem_sim *s, const scene *sc, const scene_run *run, char *err, size_t errlen)
{
    dem_state st;
    if (dem_state_get(s, &st)) {
        snprintf(err, errlen, "checkpoint: %s", dem_error(s));
        return 1;
    }
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s" CHECKPOINT_TMP_SUFFIX, path);
    errno = 0;
    hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    int rc = f < 0;
    hid_t real_t = st.real_size == 8 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT;
    hsize_t w3[2] = {(hsize_t)st.nwalls, 3}, p3[2] = {(hsize_t)st.npairs, 3};
    hsize_t p7[2] = {(hsize_t)st.npairs, DEM_PAIR_RECORD_REALS};
    hsize_t n1[1] = {(hsize_t)st.n}, p1[1] = {(hsize_t)st.npairs}, w1[1] = {(hsize_t)st.nwalls};
    hsize_t pl[2] = {(hsize_t)st.npairs, (hsize_t)st.has_law}; /* a law's row per pair (MDR) */
    hsize_t pm[1] = {st.has_mc ? (hsize_t)st.npairs : 0}, pd[2] = {st.has_mc ? (hsize_t)st.npairs : 0, 2};
    hsize_t q1[1] = {(hsize_t)st.npatch}, q3[2] = {(hsize_t)st.npatch, 3};
    double *radius = malloc(sizeof(double) * (size_t)(st.n ? st.n : 1));
    if (!rc) {
        hid_t g = H5Gcreate2(f, "state", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        for (int i = 0; radius && i < st.n; i++)
            radius[i] = dem_particle_radius(s, i);
        rc = g < 0 || !radius || h5_attr_long(g, "step", st.step) || h5_attr_long(g, "n", st.n) ||
             h5_attr_long(g, "nwalls", st.nwalls) || h5_attr_long(g, "real_size", st.real_size) ||
             h5_attr_long(g, "has_hist", st.has_hist) || h5_attr_long(g, "rebuilds", st.rebuilds) ||
             h5_attr_double(g, "time", dem_time(s)) ||
             write_arrays(g, &st, real_t) ||
             h5_write(g, "wall_pos", H5T_NATIVE_DOUBLE, 2, w3, st.wall_pos, "m") ||
             h5_write(g, "wall_stage", H5T_NATIVE_INT, 1, w1, st.wall_stage, NULL) ||
             h5_write(g, "wall_stage_first", H5T_NATIVE_LONG, 1, w1, st.wall_stage_first, NULL) ||
             h5_write(g, "wall_stage_from", H5T_NATIVE_DOUBLE, 2, w3, st.wall_stage_from, "m") ||
             h5_write(g, "pair_i", H5T_NATIVE_INT, 1, p1, st.pair_i, NULL) ||
             h5_write(g, "pair_j", H5T_NATIVE_INT, 1, p1, st.pair_j, NULL) ||
             h5_write(g, "pair_hist", real_t, 2, p3, st.pair_hist, "N") ||
             (st.pair_rec &&
              h5_write(g, "pair_rec", real_t, 2, p7, st.pair_rec, "N (force, n x f_t), m (overlap)")) ||
             h5_write(g, "radius", H5T_NATIVE_DOUBLE, 1, n1, radius, "m") ||
             h5_attr_long(g, "has_mc", st.has_mc) || h5_attr_long(g, "mc_last", st.mc.last) ||
             h5_attr_long(g, "mc_max", st.mc.max) || h5_attr_long(g, "mc_total", st.mc.total) ||
             h5_attr_long(g, "mc_unconverged", st.mc.unconverged) ||
             h5_write(g, "pair_mc_fn", real_t, 1, pm, st.pair_mc_fn, "N") ||
             h5_attr_long(g, "has_law", st.has_law) ||
             ((dem_effects(s) & DEM_EFFECT_ADHESION) && h5_attr_string(g, "law_state", CHECKPOINT_JKR_STATE)) ||
             (st.has_law == 1 && h5_write(g, "pair_law", real_t, 1, p1, st.pair_law, "m")) ||
             (st.has_law > 1 && h5_write(g, "pair_law", real_t, 2, pl, st.pair_law, NULL)) ||
             (st.has_rspring && (h5_attr_long(g, "has_rspring", 1) ||
                                 h5_write(g, "pair_rspring", real_t, 2, p3, st.pair_rspring, "N m"))) ||
             (st.pair_mc_disp && h5_write(g, "pair_mc_disp", real_t, 2, pd, st.pair_mc_disp, "m")) ||
             h5_write(g, "patch_i", H5T_NATIVE_INT, 1, q1, st.patch_i, NULL) ||
             h5_write(g, "patch_t", H5T_NATIVE_INT, 1, q1, st.patch_t, NULL) ||
             h5_write(g, "patch_hist", real_t, 2, q3, st.patch_hist, "N") ||
             (st.patch_side && h5_write(g, "patch_side", H5T_NATIVE_INT, 1, q1, st.patch_side, NULL));
        if (g >= 0)
            H5Gclose(g);
        hid_t sg = rc ? -1 : H5Gcreate2(f, "scene", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = rc || sg < 0 || h5_write_text(sg, "text", sc->text) || h5_write_text(sg, "path", sc->path) ||
             h5_attr_string(sg, "model", run->model) || h5_attr_string(sg, "particle_order", scene_particle_order(sc)) ||
             h5_attr_string(f, "libdem_version", DEM_VERSION);
        if (sg >= 0)
            H5Gclose(sg);
    }
    free(radius);
    dem_state_free(&st);
    int e = errno; /* the first failure's reason, before close and unlink add their own */
    if (f >= 0 && H5Fclose(f) < 0)
        rc = 1, e = e ? e : errno;
    if (!rc && (sync_file(tmp) || rename(tmp, path)))
        rc = 1, e = errno;
    if (rc) {
        unlink(tmp);
        snprintf(err, errlen, "%s: cannot write the checkpoint: %s (the previous one, if any, is kept)", path,
                 h5_io_reason(e));
        return 1;
    }
    return 0;
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
            return snprintf(err, errlen, "%s: /state/%s: element %ld is %g: a checkpoint holds finite numbers only "
                            "(damaged or edited)", path, a->name, at, v), 1;
    }
    for (size_t q = 0; q < sizeof arrays / sizeof arrays[0]; q++) {
        double v = 0;
        long k = first_nonfinite(arrays[q].a, arrays[q].count, arrays[q].size, &v);
        if (k >= 0)
            return snprintf(err, errlen, "%s: /state/%s: element %ld is %g: a checkpoint holds finite numbers only "
                            "(damaged or edited)", path, arrays[q].name, k, v), 1;
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
static int read_state(hid_t g, checkpoint *ck)
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
        st->pair_i = malloc(sizeof(int) * (size_t)(npairs + 1));
        st->pair_j = malloc(sizeof(int) * (size_t)(npairs + 1));
        st->pair_hist = malloc(3 * (size_t)(npairs + 1) * rs);
        size_t want_pm = hm ? (size_t)npairs : 0;
        st->pair_mc_fn = malloc((want_pm + 1) * rs);
        st->pair_law = malloc(((size_t)hl * (size_t)npairs + 1) * rs);
        st->pair_rspring = malloc(((hr ? 3 * (size_t)npairs : 0) + 1) * rs);
        ck->radius = malloc(sizeof(double) * (size_t)n);
        rc = rc || !st->pair_i || !st->pair_j || !st->pair_hist || !ck->radius || read_arrays(g, st, real_t) ||
             h5_read(g, "wall_pos", H5T_NATIVE_DOUBLE, st->wall_pos, 3 * (size_t)nw) ||
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
        /* each wall's motion stage (absent from checkpoints of libdem before stages could end early: derived from
         * the step by dem_state_set) */
        st->has_stages = !rc && H5Lexists(g, "wall_stage", H5P_DEFAULT) > 0;
        rc = rc || (st->has_stages && (h5_read(g, "wall_stage", H5T_NATIVE_INT, st->wall_stage, (size_t)nw) ||
                                       h5_read(g, "wall_stage_first", H5T_NATIVE_LONG, st->wall_stage_first,
                                               (size_t)nw) ||
                                       h5_read(g, "wall_stage_from", H5T_NATIVE_DOUBLE, st->wall_stage_from,
                                               3 * (size_t)nw)));
        rc = rc || read_patches(g, st, real_t);
    }
    return rc;
}

int checkpoint_read(const char *path, checkpoint *ck, char *err, size_t errlen)
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
    int rc = g < 0 || read_state(g, ck);
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
    if (check_finite(ck, path, err, errlen)) {
        checkpoint_free(ck);
        return 1;
    }
    return 0;
}

void checkpoint_free(checkpoint *ck)
{
    dem_state_free(&ck->st);
    free(ck->scene_text);
    free(ck->scene_path);
    free(ck->radius);
    memset(ck, 0, sizeof *ck);
}
