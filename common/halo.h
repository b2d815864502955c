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

/* The split's check of the moves (host/mpi/split.c; host/core/part.c sim_move_check), on the device so that a step
 * reads back 2 reals per block of particles instead of every position. move_mark: the positions now into MOVE_X0
 * (where the particles were at the split) and MOVE_PREV (before the next step). move_check: item b takes the
 * particles stored at [b B, (b + 1) B), B = DEM_REDUCE_BLOCK, as wall_reduce_block does, leaves the ghosts out
 * (their owners check them), and writes the largest distance one has moved since the mark and the largest move
 * since the last check into MOVE_MAX[2b] and [2b + 1] (a NaN stays a NaN: the host counts it as far); then MOVE_PREV
 * holds the positions now. A largest value is the same in any order: no sum is involved. (Taking the particles b,
 * b + nblocks, ... instead, a GPU's coalesced order, ran 10.4 ms a step on PoCL at 5e5 particles a rank, against
 * 3.2-3.9 ms.) */
DEM_ITEM(move_mark)
{
    for (int q = 0; q < 3; q++) {
        move_x0[3 * i + q] = x[3 * i + q];
        move_prev[3 * i + q] = x[3 * i + q];
    }
}

DEM_ITEM(move_check)
{
    real far = (real)0, last = (real)0;
    int end = (i + 1) * DEM_REDUCE_BLOCK < n ? (i + 1) * DEM_REDUCE_BLOCK : n;
    for (int p = i * DEM_REDUCE_BLOCK; p < end; p++) {
        real dx = x[3 * p] - move_x0[3 * p], dy = x[3 * p + 1] - move_x0[3 * p + 1],
             dz = x[3 * p + 2] - move_x0[3 * p + 2];
        real sx = x[3 * p] - move_prev[3 * p], sy = x[3 * p + 1] - move_prev[3 * p + 1],
             sz = x[3 * p + 2] - move_prev[3 * p + 2];
        real d = sqrt(dx * dx + dy * dy + dz * dz), st = sqrt(sx * sx + sy * sy + sz * sz);
        if (!ghost[p]) {
            far = d > far || d != d ? d : far;
            last = st > last || st != st ? st : last;
        }
        for (int q = 0; q < 3; q++)
            move_prev[3 * p + q] = x[3 * p + q];
    }
    move_max[2 * i] = far;
    move_max[2 * i + 1] = last;
}
#endif /* DEM_HALO_H */
