/* h5util.c - see h5util.h. Every function returns 0 on success, -1 on an HDF5 failure. */
#include "h5util.h"
#include <stdlib.h>
#include <string.h>

int h5rows_create(h5rows *r, hid_t parent, const char *name, hid_t mem_type, int rank, hsize_t d1, hsize_t d2,
                  const char *units)
{
    memset(r, 0, sizeof *r);
    r->rank = rank;
    r->mem_type = mem_type;
    r->dims[0] = 0;
    r->dims[1] = d1;
    r->dims[2] = d2;
    hsize_t maxd[3] = {H5S_UNLIMITED, d1, d2}, chunk[3] = {1, d1, d2};
    r->row_bytes = H5Tget_size(mem_type) * (size_t)(rank > 1 ? d1 : 1) * (size_t)(rank > 2 ? d2 : 1);
    int level = 4;
    if (r->row_bytes <= 1024) {
        chunk[0] = 1024; /* many short rows (series, wall series, contact records): a chunk per row would make every
                            row a compressed write of its own (a wall series every step doubled a small run's time) */
        level = 1; /* deflate at 4 was 3 % of a 514-sphere run with a row every step, for files 2 % smaller */
    }
    /* frames: one frame per chunk, split along particles so that a chunk stays below ~4 MiB */
    while (rank > 1 && chunk[1] > 1 && chunk[1] * (rank > 2 ? d2 : 1) * 8 > ((hsize_t)4 << 20))
        chunk[1] = (chunk[1] + 1) / 2;
    r->chunk1 = rank > 1 ? chunk[1] : 1;
    hid_t space = H5Screate_simple(rank, r->dims, maxd), dcpl = H5Pcreate(H5P_DATASET_CREATE);
    int ok = space >= 0 && dcpl >= 0 && H5Pset_chunk(dcpl, rank, chunk) >= 0 && H5Pset_shuffle(dcpl) >= 0 &&
             H5Pset_deflate(dcpl, (unsigned)level) >= 0;
    hid_t file_type = mem_type == H5T_NATIVE_DOUBLE ? H5T_IEEE_F64LE
                      : mem_type == H5T_NATIVE_LLONG ? H5T_STD_I64LE
                                                     : H5T_STD_I32LE;
    r->cap = H5ROWS_BUFFER_BYTES / r->row_bytes;
    if (r->cap > 1 && !(r->buf = malloc(r->cap * r->row_bytes)))
        r->cap = 0; /* no memory for the buffer: rows go straight through */
    r->id = ok ? H5Dcreate2(parent, name, file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT) : -1;
    if (space >= 0)
        H5Sclose(space);
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (r->id < 0)
        return -1;
    if (units && h5_attr_string(r->id, "units", units))
        return -1;
    return 0;
}

/* the block at start of extent cnt of dataset d (of rank dimensions) from buf, the dataset already as large */
/* the block start + cnt of the dataset written from buf, or (rd) read into it */
static int hyperslab(hid_t d, hid_t mem_type, int rank, const hsize_t *start, const hsize_t *cnt, void *buf, int rd)
{
    hid_t fs = H5Dget_space(d), ms = H5Screate_simple(rank, cnt, NULL);
    int rc = fs >= 0 && ms >= 0 && H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, cnt, NULL) >= 0 &&
                     (rd ? H5Dread(d, mem_type, ms, fs, H5P_DEFAULT, buf)
                         : H5Dwrite(d, mem_type, ms, fs, H5P_DEFAULT, buf)) >= 0
                 ? 0
                 : -1;
    if (fs >= 0)
        H5Sclose(fs);
    if (ms >= 0)
        H5Sclose(ms);
    return rc;
}

/* rows [first, first + count) of the dataset from buf */
static int write_rows(h5rows *r, const void *buf, hsize_t count)
{
    hsize_t start[3] = {r->dims[0], 0, 0}, cnt[3] = {count, r->dims[1], r->dims[2]};
    hsize_t grown[3] = {r->dims[0] + count, r->dims[1], r->dims[2]};
    if (H5Dset_extent(r->id, grown) < 0 || hyperslab(r->id, r->mem_type, r->rank, start, cnt, (void *)buf, 0))
        return -1;
    r->dims[0] += count;
    return 0;
}

int h5rows_append(h5rows *r, const void *row)
{
    if (r->cap <= 1)
        return write_rows(r, row, 1);
    memcpy(r->buf + r->nbuf * r->row_bytes, row, r->row_bytes);
    return ++r->nbuf == r->cap ? h5rows_flush(r) : 0;
}

int h5rows_append_part(h5rows *r, hsize_t a, hsize_t b, const void *part)
{
    hsize_t d1 = r->rank > 1 ? r->dims[1] : 1, d2 = r->rank > 2 ? r->dims[2] : 1;
    size_t el = r->row_bytes / (size_t)(d1 * d2) * (size_t)d2; /* bytes per element of the first dimension */
    if (a >= b || b > d1)
        return -1;
    if (r->cap > 1) { /* into the gathered rows: the row counts once whole */
        memcpy(r->buf + r->nbuf * r->row_bytes + a * el, part, (size_t)(b - a) * el);
        return b < d1 ? 0 : ++r->nbuf == r->cap ? h5rows_flush(r) : 0;
    }
    hsize_t grown[3] = {r->dims[0] + 1, r->dims[1], r->dims[2]};
    if (a == 0 && H5Dset_extent(r->id, grown) < 0)
        return -1;
    hsize_t start[3] = {r->dims[0], a, 0}, cnt[3] = {1, b - a, r->dims[2]}; /* a rank-1 row: a = 0, b = 1 */
    if (hyperslab(r->id, r->mem_type, r->rank, start, cnt, (void *)part, 0))
        return -1;
    if (b == d1)
        r->dims[0]++;
    return 0;
}

int h5rows_flush(h5rows *r)
{
    if (r->id <= 0 || r->nbuf == 0)
        return 0;
    int rc = write_rows(r, r->buf, r->nbuf);
    r->nbuf = 0;
    return rc;
}

void h5rows_close(h5rows *r)
{
    if (r->id > 0)
        H5Dclose(r->id);
    r->id = 0;
    free(r->buf);
    r->buf = NULL;
    r->nbuf = r->cap = 0;
}

static int attr_write(hid_t obj, const char *name, hid_t type, const void *v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = sp >= 0 ? H5Acreate2(obj, name, type, sp, H5P_DEFAULT, H5P_DEFAULT) : -1;
    int rc = a >= 0 && H5Awrite(a, type, v) >= 0 ? 0 : -1;
    if (a >= 0)
        H5Aclose(a);
    if (sp >= 0)
        H5Sclose(sp);
    return rc;
}

int h5_attr_string(hid_t obj, const char *name, const char *value)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    if (t < 0 || H5Tset_size(t, strlen(value) + 1) < 0 || H5Tset_cset(t, H5T_CSET_UTF8) < 0)
        return -1;
    int rc = attr_write(obj, name, t, value);
    H5Tclose(t);
    return rc;
}

int h5_attr_double(hid_t obj, const char *name, double value) { return attr_write(obj, name, H5T_NATIVE_DOUBLE, &value); }
int h5_attr_long(hid_t obj, const char *name, long value) { return attr_write(obj, name, H5T_NATIVE_LONG, &value); }

hid_t h5_create(hid_t parent, const char *name, hid_t mem_type, int rank, const hsize_t *dims, const char *units)
{
    hid_t sp = H5Screate_simple(rank, dims, NULL); /* zero-sized dimensions are allowed (HDF5 >= 1.8.7) */
    hid_t ftype = H5Tget_native_type(mem_type, H5T_DIR_DEFAULT);
    hid_t d = sp >= 0 && ftype >= 0 ? H5Dcreate2(parent, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
    if (d >= 0 && units && h5_attr_string(d, "units", units)) {
        H5Dclose(d);
        d = -1;
    }
    if (sp >= 0)
        H5Sclose(sp);
    if (ftype >= 0)
        H5Tclose(ftype);
    return d;
}

/* rows [first, first + count) of dataset d written from data, or (rd) read into it */
static int rows_io(hid_t d, hid_t mem_type, hsize_t first, hsize_t count, void *data, int rd)
{
    if (count == 0)
        return 0;
    hid_t fs = H5Dget_space(d);
    int rank = fs >= 0 ? H5Sget_simple_extent_ndims(fs) : -1, empty = 0;
    hsize_t dims[H5S_MAX_RANK], start[H5S_MAX_RANK] = {first}, cnt[H5S_MAX_RANK];
    int ok = rank >= 1 && H5Sget_simple_extent_dims(fs, dims, NULL) >= 0 && first + count <= dims[0];
    if (fs >= 0)
        H5Sclose(fs);
    for (int k = 0; ok && k < rank; k++)
        empty |= !(cnt[k] = k ? dims[k] : count); /* an empty row: nothing to write */
    return !ok ? -1 : empty ? 0 : hyperslab(d, mem_type, rank, start, cnt, data, rd);
}

int h5_write_rows(hid_t d, hid_t mem_type, hsize_t first, hsize_t count, const void *data)
{
    return rows_io(d, mem_type, first, count, (void *)data, 0);
}

int h5_read_rows(hid_t d, hid_t mem_type, hsize_t first, hsize_t count, void *data)
{
    return rows_io(d, mem_type, first, count, data, 1);
}

int h5_write(hid_t parent, const char *name, hid_t mem_type, int rank, const hsize_t *dims, const void *data,
             const char *units)
{
    hid_t d = h5_create(parent, name, mem_type, rank, dims, units);
    int rc = d >= 0 && !h5_write_rows(d, mem_type, 0, rank ? dims[0] : 1, data) ? 0 : -1;
    if (d >= 0 && H5Dclose(d) < 0)
        rc = -1;
    return rc;
}

long h5_count(hid_t parent, const char *name)
{
    if (H5Lexists(parent, name, H5P_DEFAULT) <= 0)
        return -1;
    hid_t d = H5Dopen2(parent, name, H5P_DEFAULT), sp = d >= 0 ? H5Dget_space(d) : -1;
    long n = sp >= 0 ? (long)H5Sget_simple_extent_npoints(sp) : -1;
    if (sp >= 0)
        H5Sclose(sp);
    if (d >= 0)
        H5Dclose(d);
    return n;
}

int h5_read(hid_t parent, const char *name, hid_t mem_type, void *data, size_t count)
{
    long npts = h5_count(parent, name);
    if (npts < 0 || (size_t)npts != count)
        return -1;
    if (count == 0)
        return 0;
    hid_t d = H5Dopen2(parent, name, H5P_DEFAULT);
    int rc = d >= 0 && H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0 ? 0 : -1;
    if (d >= 0)
        H5Dclose(d);
    return rc;
}

/* Number of elements of an attribute (1 for a scalar), -1 on error. */
static long attr_points(hid_t a)
{
    hid_t sp = a >= 0 ? H5Aget_space(a) : -1;
    long n = sp >= 0 ? (long)H5Sget_simple_extent_npoints(sp) : -1;
    if (sp >= 0)
        H5Sclose(sp);
    return n;
}

char *h5_read_attr_string(hid_t obj, const char *name)
{
    if (H5Aexists(obj, name) <= 0)
        return NULL;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = a >= 0 ? H5Aget_type(a) : -1;
    /* one fixed-length string only: an array would be read past the buffer, a variable-length one as a pointer */
    size_t n = t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) == 0 && attr_points(a) == 1
                   ? H5Tget_size(t)
                   : 0;
    char *buf = n ? calloc(n + 1, 1) : NULL;
    if (buf && H5Aread(a, t, buf) < 0) {
        free(buf);
        buf = NULL;
    }
    if (t >= 0)
        H5Tclose(t);
    if (a >= 0)
        H5Aclose(a);
    return buf;
}

static int attr_read(hid_t obj, const char *name, hid_t type, void *v)
{
    if (H5Aexists(obj, name) <= 0)
        return -1;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    int rc = a >= 0 && attr_points(a) == 1 && H5Aread(a, type, v) >= 0 ? 0 : -1; /* one value, never an array */
    if (a >= 0)
        H5Aclose(a);
    return rc;
}
int h5_read_attr_double(hid_t obj, const char *name, double *v) { return attr_read(obj, name, H5T_NATIVE_DOUBLE, v); }
int h5_read_attr_long(hid_t obj, const char *name, long *v) { return attr_read(obj, name, H5T_NATIVE_LONG, v); }

int h5_write_text(hid_t parent, const char *name, const char *text)
{
    hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR);
    int rc = -1;
    if (t >= 0 && sp >= 0 && H5Tset_size(t, strlen(text) + 1) >= 0 && H5Tset_cset(t, H5T_CSET_UTF8) >= 0) {
        hid_t d = H5Dcreate2(parent, name, t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = d >= 0 && H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, text) >= 0 ? 0 : -1;
        if (d >= 0)
            H5Dclose(d);
    }
    if (t >= 0)
        H5Tclose(t);
    if (sp >= 0)
        H5Sclose(sp);
    return rc;
}

char *h5_read_text(hid_t parent, const char *name)
{
    if (H5Lexists(parent, name, H5P_DEFAULT) <= 0)
        return NULL;
    hid_t d = H5Dopen2(parent, name, H5P_DEFAULT), t = d >= 0 ? H5Dget_type(d) : -1;
    /* one fixed-length string, as h5_write_text writes it: a variable-length one would read as a pointer, and an
     * array of them would be read whole into the buffer sized for one (a crafted /scene/text overwrote the heap) */
    size_t n = t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) == 0 && h5_count(parent, name) == 1
                   ? H5Tget_size(t)
                   : 0;
    char *buf = n ? calloc(n + 1, 1) : NULL;
    if (buf && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
        free(buf);
        buf = NULL;
    }
    if (t >= 0)
        H5Tclose(t);
    if (d >= 0)
        H5Dclose(d);
    return buf;
}

const char *h5_io_reason(int saved_errno)
{
    return saved_errno ? strerror(saved_errno) : "the HDF5 library refused it without an operating-system error";
}
