/* fuzz_h5.c - libFuzzer harness for every HDF5 text and array reader of app/h5util.c (make fuzz-h5): h5_read_text,
 * h5_read_attr_string, h5_count, h5_read, h5_read_attr_long, h5_read_attr_double - what checkpoint_read builds on.
 *
 * Input: 6 bytes of shape, then the data. [type][rank][dim 0][dim 1][string size or array length][flags]: a dataset
 * "d" and an attribute "a" of that type and shape are made in a file held in memory (the core driver: no disk),
 * filled from the rest of the input. Types: fixed-length string (ASCII or UTF-8, null- or space-padded), variable-
 * length string, int, long long, float, double, a compound, an array of doubles, an enum, opaque bytes. Every reader
 * is then called on them with a buffer of exactly the size it is told (so ASan sees any write past it, e.g. a
 * checkpoint's /scene/text as an array of strings read whole into a buffer for one). Oracles: h5_read_text and
 * h5_read_attr_string return a string only for one fixed-length string, and no longer than its size; h5_read fills
 * what it is asked for only when the count is the dataset's; the number readers read one value or refuse. */
#include "h5util.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static hid_t make_type(uint8_t which, size_t size, uint8_t flags)
{
    switch (which % 10) {
    case 0: {
        hid_t t = H5Tcopy(H5T_C_S1);
        H5Tset_size(t, size ? size : 1);
        H5Tset_cset(t, flags & 1 ? H5T_CSET_UTF8 : H5T_CSET_ASCII);
        H5Tset_strpad(t, flags & 2 ? H5T_STR_SPACEPAD : H5T_STR_NULLTERM);
        return t;
    }
    case 1: {
        hid_t t = H5Tcopy(H5T_C_S1);
        H5Tset_size(t, H5T_VARIABLE);
        return t;
    }
    case 2: return H5Tcopy(H5T_NATIVE_INT);
    case 3: return H5Tcopy(H5T_NATIVE_LLONG);
    case 4: return H5Tcopy(H5T_NATIVE_FLOAT);
    case 5: return H5Tcopy(H5T_NATIVE_DOUBLE);
    case 6: {
        hid_t t = H5Tcreate(H5T_COMPOUND, 16);
        H5Tinsert(t, "a", 0, H5T_NATIVE_DOUBLE);
        H5Tinsert(t, "b", 8, H5T_NATIVE_INT);
        return t;
    }
    case 7: {
        hsize_t n = size ? size : 1;
        return H5Tarray_create2(H5T_NATIVE_DOUBLE, 1, &n);
    }
    case 8: {
        hid_t t = H5Tenum_create(H5T_NATIVE_INT);
        int v0 = 0, v1 = 1;
        H5Tenum_insert(t, "zero", &v0);
        H5Tenum_insert(t, "one", &v1);
        return t;
    }
    default: {
        hid_t t = H5Tcreate(H5T_OPAQUE, size ? size : 1);
        H5Tset_tag(t, "fuzz");
        return t;
    }
    }
}

/* Fills a buffer for n elements of type t from the input (variable-length strings point at NUL-terminated copies). */
static void *fill(hid_t t, size_t n, const uint8_t *data, size_t size, char ***vl)
{
    size_t es = H5Tget_size(t);
    uint8_t *buf = calloc(n * es + 1, 1);
    if (!buf)
        return NULL;
    if (H5Tis_variable_str(t) > 0) {
        *vl = calloc(n + 1, sizeof(char *));
        for (size_t k = 0; *vl && k < n; k++) {
            size_t from = size ? (k * 7) % size : 0, len = size - from < 24 ? size - from : 24;
            (*vl)[k] = calloc(len + 1, 1);
            if ((*vl)[k] && len)
                memcpy((*vl)[k], data + from, len);
            memcpy(buf + k * sizeof(char *), &(*vl)[k], sizeof(char *));
        }
        return buf;
    }
    for (size_t k = 0; k < n * es && size; k++)
        buf[k] = data[k % size];
    return buf;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int quiet;
    if (!quiet)
        H5Eset_auto2(H5E_DEFAULT, NULL, NULL), quiet = 1;
    if (size < 6)
        return 0;
    uint8_t which = data[0], rank = data[1] % 3, flags = data[5];
    hsize_t dims[2] = {data[2] % 65, data[3] % 65};
    size_t ssize = data[4] % 80;
    data += 6, size -= 6;
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_core(fapl, 1 << 16, 0); /* in memory, never written */
    char name[64];
    snprintf(name, sizeof name, "fuzz-h5-%p", (void *)&quiet);
    hid_t f = H5Fcreate(name, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    if (f < 0)
        __builtin_trap(); /* the harness itself is broken */
    hid_t t = make_type(which, ssize, flags);
    hid_t sp = rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, NULL);
    size_t n = rank == 0 ? 1 : (size_t)dims[0] * (rank == 2 ? (size_t)dims[1] : 1);
    char **vl = NULL;
    void *buf = t >= 0 && sp >= 0 ? fill(t, n, data, size, &vl) : NULL;
    hid_t d = buf ? H5Dcreate2(f, "d", t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
    if (d >= 0)
        H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf), H5Dclose(d);
    hid_t a = buf && !(flags & 4) ? H5Acreate2(f, "a", t, sp, H5P_DEFAULT, H5P_DEFAULT) : -1;
    if (a >= 0)
        H5Awrite(a, t, buf), H5Aclose(a);
    int one_fixed_string = which % 10 == 0 && n == 1;
    /* the text readers: one fixed-length string, at most its size, or nothing */
    char *s = h5_read_text(f, "d");
    if (s && (!one_fixed_string || strlen(s) > (ssize ? ssize : 1)))
        __builtin_trap();
    free(s);
    s = h5_read_attr_string(f, "a");
    if (s && (!one_fixed_string || strlen(s) > (ssize ? ssize : 1)))
        __builtin_trap();
    free(s);
    /* the array reader, into buffers of exactly the size asked for: the dataset's count, one less and one more */
    long count = h5_count(f, "d");
    if (d >= 0 && count != (long)n)
        __builtin_trap();
    for (long c = count - 1; count >= 0 && c <= count + 1; c++) {
        if (c < 0)
            continue;
        double *dv = malloc(sizeof(double) * (size_t)(c ? c : 1));
        int *iv = malloc(sizeof(int) * (size_t)(c ? c : 1));
        int rd = dv ? h5_read(f, "d", H5T_NATIVE_DOUBLE, dv, (size_t)c) : -1;
        int ri = iv ? h5_read(f, "d", H5T_NATIVE_INT, iv, (size_t)c) : -1;
        if ((rd == 0 || ri == 0) && c != count) /* another count than the dataset's is refused */
            __builtin_trap();
        free(dv), free(iv);
    }
    long lv;
    double dv;
    h5_read_attr_long(f, "a", &lv);
    h5_read_attr_double(f, "a", &dv);
    if (vl)
        for (size_t k = 0; k < n; k++)
            free(vl[k]);
    free(vl), free(buf);
    if (t >= 0)
        H5Tclose(t);
    if (sp >= 0)
        H5Sclose(sp);
    H5Fclose(f);
    return 0;
}
