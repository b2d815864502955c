/* h5util.h - small helpers over the HDF5 C API: extendible, chunked, compressed datasets that grow by rows. */
#ifndef DEM_H5UTIL_H
#define DEM_H5UTIL_H
#include <hdf5.h>
#include <stddef.h>

/* A dataset of shape [rows, d1, d2] (rank 1..3) whose first dimension grows; double, int or long long elements. Small rows
 * (a time series) are gathered in memory and written in chunks of up to H5ROWS_BUFFER_BYTES: one HDF5 write per
 * chunk instead of per row (a series every step made a run 3x slower). Large rows (frames) go straight through. */
#define H5ROWS_BUFFER_BYTES (256 * 1024)
typedef struct {
    hid_t id;
    int rank;
    hsize_t dims[3];  /* rows in the file, d1, d2 */
    hid_t mem_type;
    size_t row_bytes;
    unsigned char *buf; /* rows not yet written */
    size_t nbuf, cap;
    hsize_t chunk1;     /* the chunk's extent along d1 (frames: particles per chunk) */
} h5rows;

int h5rows_create(h5rows *r, hid_t parent, const char *name, hid_t mem_type, int rank, hsize_t d1, hsize_t d2,
                  const char *units);
int h5rows_append(h5rows *r, const void *row);
/* One row given in parts: elements [a, b) of its first dimension after the row (d1; a rank-1 dataset's row is one
 * element), in order, the first from a = 0 and the last to b = d1 (a frame written from the ranks' parts slab by slab,
 * app/run_mpi.c: best in slabs of chunk1, which a write covers whole). */
int h5rows_append_part(h5rows *r, hsize_t a, hsize_t b, const void *part);
int h5rows_flush(h5rows *r); /* writes the gathered rows */
void h5rows_close(h5rows *r); /* without flushing: flush first to keep the rows */

int h5_attr_string(hid_t obj, const char *name, const char *value);
int h5_attr_double(hid_t obj, const char *name, double value);
int h5_attr_long(hid_t obj, const char *name, long value);
/* Whole dataset of a native type; units as an attribute when given. */
int h5_write(hid_t parent, const char *name, hid_t mem_type, int rank, const hsize_t *dims, const void *data,
             const char *units);
/* The same dataset created, contiguous as h5_write's, and written a block of whole rows at a time: rows [first, first
 * + count) of its first dimension from data (a checkpoint written slab by slab, app/checkpoint.c) */
hid_t h5_create(hid_t parent, const char *name, hid_t mem_type, int rank, const hsize_t *dims, const char *units);
int h5_write_rows(hid_t d, hid_t mem_type, hsize_t first, hsize_t count, const void *data);
/* the same rows read into data (a restart split over ranks reads its part of a checkpoint so, app/checkpoint.c) */
int h5_read_rows(hid_t d, hid_t mem_type, hsize_t first, hsize_t count, void *data);
/* Reads a whole dataset (or fails when its element count is not count). */
int h5_read(hid_t parent, const char *name, hid_t mem_type, void *data, size_t count);
long h5_count(hid_t parent, const char *name); /* elements of a dataset, -1 if absent */
char *h5_read_attr_string(hid_t obj, const char *name); /* malloc'd, NULL if absent */
int h5_read_attr_double(hid_t obj, const char *name, double *v);
int h5_read_attr_long(hid_t obj, const char *name, long *v);

/* A text of any length as a scalar string dataset (attributes are limited to 64 KiB). */
int h5_write_text(hid_t parent, const char *name, const char *text);
char *h5_read_text(hid_t parent, const char *name); /* malloc'd, NULL if absent */

/* Why a write failed, for a one-line message: the operating system's reason when the failing call left one in errno
 * (callers set errno = 0 before the write), else that HDF5 refused it without one. */
const char *h5_io_reason(int saved_errno);
#endif
