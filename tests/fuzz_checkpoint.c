/* fuzz_checkpoint.c - libFuzzer harness for the checkpoint reader and the restore (make fuzz-checkpoint).
 *
 * Structure-aware: random bytes are not an HDF5 file, and libhdf5's own parser is not what we test. So the input is a
 * list of edits applied, through the HDF5 API, to a real checkpoint (made once from tests/scenes/restart_box.yaml):
 * each 10-byte record is [op][target][value: 8 bytes] and sets an attribute of /state to any 64-bit value, replaces
 * a dataset with one of another length, type or rank, deletes a dataset or an attribute, writes one element of
 * the contact pair lists, replaces the scene's text, path or model with an array, a string of another kind or a
 * number, or makes one element of a real dataset nan or infinite. The result must be refused with a message or restored (checkpoint_read, the scene it
 * carries, dem_start on the reference, dem_state_set), never crash, leak or overrun (ASan, UBSan). */
#include "checkpoint.h"
#include "scene.h"
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char base[256], work[256];

static const char *const attrs[] = {"step", "n", "nwalls", "real_size", "has_hist", "has_mc", "rebuilds",
                                    "mc_last", "mc_max", "mc_total", "mc_unconverged"};
static const char *const sets[] = {"x", "v", "w", "force", "torque", "radius", "wall_force", "wall_pos",
                                   "wall_hist", "wall_mask", "pair_i", "pair_j", "pair_hist", "pair_mc_fn",
                                   "wall_mc_fn", "pair_rec", "wall_pf", "pair_mc_disp", "wall_mc_disp",
                                   "wall_normal_force", "wall_stage", "wall_stage_first", "wall_stage_from",
                                   "patch_i", "patch_t", "patch_hist"};
#define NA (sizeof attrs / sizeof attrs[0])
#define NS (sizeof sets / sizeof sets[0])

static int make_base(void)
{
    char err[8192], path[512];
    snprintf(path, sizeof path, "%s/tests/scenes/restart_box.yaml", DEM_DEFAULT_SOURCE_DIR);
    snprintf(base, sizeof base, "/tmp/fuzz-checkpoint-base-%d.h5", (int)getpid());
    snprintf(work, sizeof work, "/tmp/fuzz-checkpoint-work-%d.h5", (int)getpid());
    scene *sc = scene_load(path, err, sizeof err);
    scene_run run;
    dem_sim *s = sc ? scene_build(sc, &run, err, sizeof err) : NULL;
    if (!s)
        return fprintf(stderr, "fuzz_checkpoint: %s\n", err), -1;
    run.cfg.backend = DEM_BACKEND_REFERENCE;
    int rc = dem_start(s, &run.cfg) || dem_step(s, 60) || checkpoint_write(base, s, sc, &run, err, sizeof err);
    dem_destroy(s);
    scene_free(sc);
    return rc ? (fprintf(stderr, "fuzz_checkpoint: cannot make the base checkpoint\n"), -1) : 0;
}

static int copy_file(const char *from, const char *to)
{
    FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
    char buf[65536];
    size_t n;
    int rc = !a || !b;
    while (!rc && (n = fread(buf, 1, sizeof buf, a)) > 0)
        rc = fwrite(buf, 1, n, b) != n;
    if (a)
        fclose(a);
    if (b)
        fclose(b);
    return rc;
}

/* /scene/text or /scene/path (or the model attribute) replaced: an array of strings, a variable-length string, a
 * number, a string of another size (an array there must not be read whole into a buffer for one) */
static void edit_scene(hid_t f, uint8_t target, int64_t value)
{
    hid_t sg = H5Lexists(f, "scene", H5P_DEFAULT) > 0 ? H5Gopen2(f, "scene", H5P_DEFAULT) : -1;
    if (sg < 0)
        return;
    const char *name = target % 3 == 0 ? "text" : target % 3 == 1 ? "path" : "model";
    hsize_t n = (hsize_t)((uint64_t)value % 2000) + 1;
    size_t len = (size_t)((uint64_t)value >> 16) % 300 + 1;
    hid_t t = H5Tcopy(H5T_C_S1);
    int kind = (target / 3) % 4; /* 0: n fixed strings, 1: one of another size, 2: variable-length, 3: a double */
    if (kind == 2)
        H5Tset_size(t, H5T_VARIABLE);
    else
        H5Tset_size(t, len);
    hid_t sp = kind == 0 ? H5Screate_simple(1, &n, NULL) : H5Screate(H5S_SCALAR);
    char *buf = calloc((kind == 0 ? n : 1) * (len + 8) + 16, 1);
    const char *vl = "varlen";
    for (size_t k = 0; buf && k < (kind == 0 ? n : 1) * len; k++)
        buf[k] = (char)('a' + k % 26);
    if (!strcmp(name, "model")) {
        if (H5Aexists(sg, name) > 0)
            H5Adelete(sg, name);
        hid_t a = buf ? H5Acreate2(sg, name, kind == 3 ? H5T_NATIVE_DOUBLE : t, sp, H5P_DEFAULT, H5P_DEFAULT) : -1;
        if (a >= 0)
            H5Awrite(a, kind == 3 ? H5T_NATIVE_DOUBLE : t, kind == 2 ? (const void *)&vl : buf), H5Aclose(a);
    } else {
        if (H5Lexists(sg, name, H5P_DEFAULT) > 0)
            H5Ldelete(sg, name, H5P_DEFAULT);
        hid_t d = buf ? H5Dcreate2(sg, name, kind == 3 ? H5T_NATIVE_DOUBLE : t, sp, H5P_DEFAULT, H5P_DEFAULT,
                                   H5P_DEFAULT) : -1;
        if (d >= 0)
            H5Dwrite(d, kind == 3 ? H5T_NATIVE_DOUBLE : t, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                     kind == 2 ? (const void *)&vl : buf), H5Dclose(d);
    }
    free(buf);
    H5Sclose(sp), H5Tclose(t), H5Gclose(sg);
}

/* One element of a real dataset made nan, inf or -inf (a nan wall position must be refused, not restored and acted on)
 */
static void edit_nonfinite(hid_t st, uint8_t target, int64_t value)
{
    const char *name = sets[target % NS];
    if (H5Lexists(st, name, H5P_DEFAULT) <= 0)
        return;
    hid_t d = H5Dopen2(st, name, H5P_DEFAULT), sp = H5Dget_space(d), t = H5Dget_type(d);
    hssize_t n = H5Sget_simple_extent_npoints(sp);
    if (n > 0 && H5Tget_class(t) == H5T_FLOAT) {
        hsize_t at[2] = {(hsize_t)((uint64_t)value >> 8) % (hsize_t)n, 0}, one = 1;
        int rank = H5Sget_simple_extent_ndims(sp);
        hsize_t dims[2] = {1, 1};
        H5Sget_simple_extent_dims(sp, dims, NULL);
        if (rank == 2)
            at[1] = at[0] % dims[1], at[0] = at[0] / dims[1] % dims[0];
        double v = value & 1 ? NAN : value & 2 ? INFINITY : -INFINITY;
        hid_t ms = H5Screate_simple(1, &one, NULL);
        H5Sselect_elements(sp, H5S_SELECT_SET, 1, at);
        H5Dwrite(d, H5T_NATIVE_DOUBLE, ms, sp, H5P_DEFAULT, &v);
        H5Sclose(ms);
    }
    H5Tclose(t), H5Sclose(sp), H5Dclose(d);
}

static void edit(hid_t f, hid_t st, uint8_t op, uint8_t target, int64_t value)
{
    switch (op % 7) {
    case 5:
        edit_scene(f, target, value);
        return;
    case 6:
        edit_nonfinite(st, target, value);
        return;
    }
    switch (op % 7) {
    case 0: { /* an attribute of /state to any value */
        const char *name = attrs[target % NA];
        if (H5Aexists(st, name) > 0)
            H5Adelete(st, name);
        hid_t sp = H5Screate(H5S_SCALAR), a = H5Acreate2(st, name, H5T_NATIVE_INT64, sp, H5P_DEFAULT, H5P_DEFAULT);
        if (a >= 0)
            H5Awrite(a, H5T_NATIVE_INT64, &value), H5Aclose(a);
        H5Sclose(sp);
        break;
    }
    case 1:   /* a dataset replaced: another length (up to 4096), element type and rank */
    case 2: {
        const char *name = sets[target % NS];
        if (H5Lexists(st, name, H5P_DEFAULT) > 0)
            H5Ldelete(st, name, H5P_DEFAULT);
        hsize_t len = (hsize_t)((uint64_t)value % 4097), dims[2] = {len, 3};
        int rank = (op / 7) % 2 ? 2 : 1;
        if (rank == 2)
            dims[0] = len / 3;
        hid_t type = (value >> 20) & 1 ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE;
        size_t count = (size_t)dims[0] * (rank == 2 ? 3 : 1);
        double *buf = calloc(count + 1, sizeof(double));
        for (size_t k = 0; k < count && buf; k++)
            buf[k] = (double)((value >> (k % 40)) & 0xffff) - 100;
        int *ibuf = calloc(count + 1, sizeof(int));
        for (size_t k = 0; k < count && ibuf; k++)
            ibuf[k] = (int)((value >> (k % 33)) & 0x3f) - 2;
        hid_t sp = H5Screate_simple(rank, dims, NULL);
        hid_t d = H5Dcreate2(st, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        if (d >= 0 && buf && ibuf)
            H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, type == H5T_NATIVE_INT ? (void *)ibuf : (void *)buf);
        if (d >= 0)
            H5Dclose(d);
        H5Sclose(sp);
        free(buf), free(ibuf);
        break;
    }
    case 3: { /* something deleted */
        if (target & 1) {
            const char *name = sets[(target >> 1) % NS];
            if (H5Lexists(st, name, H5P_DEFAULT) > 0)
                H5Ldelete(st, name, H5P_DEFAULT);
        } else if (H5Aexists(st, attrs[(target >> 1) % NA]) > 0) {
            H5Adelete(st, attrs[(target >> 1) % NA]);
        }
        break;
    }
    default: { /* one element of a contact pair list */
        const char *name = target & 1 ? "pair_j" : "pair_i";
        if (H5Lexists(st, name, H5P_DEFAULT) <= 0)
            break;
        hid_t d = H5Dopen2(st, name, H5P_DEFAULT), sp = H5Dget_space(d);
        hssize_t n = H5Sget_simple_extent_npoints(sp);
        if (n > 0 && H5Sget_simple_extent_ndims(sp) == 1) {
            hsize_t at = (hsize_t)((uint64_t)value >> 32) % (hsize_t)n, one = 1;
            int v = (int)(value & 0xffffffff);
            hid_t ms = H5Screate_simple(1, &one, NULL);
            H5Sselect_elements(sp, H5S_SELECT_SET, 1, &at);
            H5Dwrite(d, H5T_NATIVE_INT, ms, sp, H5P_DEFAULT, &v);
            H5Sclose(ms);
        }
        H5Sclose(sp), H5Dclose(d);
    }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int ready = -2;
    if (ready == -2) {
        H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
        ready = make_base();
    }
    if (ready || copy_file(base, work))
        __builtin_trap(); /* the harness itself is broken */
    hid_t f = H5Fopen(work, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t st = f >= 0 ? H5Gopen2(f, "state", H5P_DEFAULT) : -1;
    for (size_t k = 0; st >= 0 && k + 10 <= size && k < 400; k += 10) {
        int64_t v;
        memcpy(&v, data + k + 2, sizeof v);
        edit(f, st, data[k], data[k + 1], v);
    }
    if (st >= 0)
        H5Gclose(st);
    if (f >= 0)
        H5Fclose(f);
    checkpoint ck;
    char err[8192];
    if (checkpoint_read(work, &ck, err, sizeof err)) {
        if (!strstr(err, work)) /* a refusal names the file */
            __builtin_trap();
        return 0;
    }
    /* what is restored is finite (checkpoint_read refuses the rest with the dataset's name) */
    const void *cx = dem_state_find(&ck.st, "x")->data, *cw = dem_state_find(&ck.st, "w")->data;
    for (size_t k = 0; k < 3 * (size_t)ck.st.n; k++) {
        double x = ck.st.real_size == 8 ? ((const double *)cx)[k] : ((const float *)cx)[k];
        double w = ck.st.real_size == 8 ? ((const double *)cw)[k] : ((const float *)cw)[k];
        if (!isfinite(x) || !isfinite(w))
            __builtin_trap();
    }
    for (int k = 0; k < ck.st.nwalls; k++)
        if (!isfinite(ck.st.wall_pos[k][0] + ck.st.wall_pos[k][1] + ck.st.wall_pos[k][2]))
            __builtin_trap();
    scene *sc = scene_load_text(ck.scene_path, ck.scene_text, strlen(ck.scene_text), err, sizeof err);
    scene_run run;
    dem_sim *s = sc ? scene_build(sc, &run, err, sizeof err) : NULL;
    if (s) {
        run.cfg.backend = DEM_BACKEND_REFERENCE;
        run.cfg.precision = (dem_precision)ck.st.real_size;
        if (!dem_start(s, &run.cfg) && ck.st.step <= run.steps && !dem_state_set(s, &ck.st))
            dem_step(s, 2); /* a restored state must also run */
    }
    dem_destroy(s);
    scene_free(sc);
    checkpoint_free(&ck);
    return 0;
}
