/* halo.h - a run split over MPI ranks (host/mpi/halo.c): after each step the owners' values of what a step reads of a
 * particle go into the other ranks' copies of it (their ghosts). halo_pack copies each particle this rank sends into
 * one message row of HALO_W reals; halo_unpack copies each received row into its ghost. Plain copies of the run's
 * reals, so the values are the owners' bits on every device. HALO_IDX holds the particles' stable ids (the order of
 * dem_start), the first NSEND those sent, the next NRECV the ghosts, so that a rebuild that stores the particles
 * anew (ORDER) needs no new list; HALO_BUF holds the rows in the same order. */
#ifndef DEM_HALO_H
#define DEM_HALO_H
#include "dem_kernels.h"
#include "dem_layout.h"

DEM_ITEM(halo_pack)
{
    int p = order[halo_idx[i]];
    DEM_GLOBAL real *row = halo_buf + HALO_W * i;
    for (int q = 0; q < 3; q++) {
        row[HALO_X + q] = x[3 * p + q];
        row[HALO_V + q] = v[3 * p + q];
        row[HALO_WV + q] = w[3 * p + q];
        row[HALO_F + q] = force[3 * p + q];
        row[HALO_T + q] = torque[3 * p + q];
    }
}

DEM_ITEM(halo_unpack)
{
    int k = nsend + i, p = order[halo_idx[k]];
    DEM_CONST_GLOBAL real *row = halo_buf + HALO_W * k;
    for (int q = 0; q < 3; q++) {
        x[3 * p + q] = row[HALO_X + q];
        v[3 * p + q] = row[HALO_V + q];
        w[3 * p + q] = row[HALO_WV + q];
        force[3 * p + q] = row[HALO_F + q];
        torque[3 * p + q] = row[HALO_T + q];
    }
}
/* The same for one per-particle buffer of `width` <= HALO_W reals per particle, named by the alias HALO_ROWS, in
 * message rows of `width` reals: what a step reads of a ghost within the step (MC-stress's stress trace after its
 * pass 1, MDR's particle row after mdr_surface and after the step) */
DEM_ITEM(halo_pack_rows)
{
    int p = order[halo_idx[i]];
    for (int q = 0; q < width; q++)
        halo_buf[width * i + q] = rows[width * p + q];
}

DEM_ITEM(halo_unpack_rows)
{
    int k = nsend + i, p = order[halo_idx[k]];
    for (int q = 0; q < width; q++)
        rows[width * p + q] = halo_buf[width * k + q];
}
#endif /* DEM_HALO_H */
