/* output.h - the run's HDF5 file (frames of particle fields, time series, provenance) and its XDMF sidecar.
 *
 * The file is written as OUT.part and renamed to OUT when the run ends well, so that OUT is never a truncated
 * file; a run that fails keeps what it wrote in OUT.part and leaves any older OUT untouched.
 * Layout (units in each dataset's "units" attribute):
 *   /            attributes libdem_version, device, precision, effects, dt, steps, scene_path; dataset scene_text
 *   /particles/  radius [n], material [n] (constant over the run)
 *   /frames/     time [F], step [F], position|velocity|angular_velocity|force|torque [F, n, 3]
 *   /series/     time, step, kinetic, elastic, potential, total [R]; contacts, wall_contacts [R];
 *                wall_position, wall_force [R, nwalls, 3], wall_normal_force [R, nwalls]; strain, stress [R] when the
 *                scene names a sample;
 *                wall_radius, wall_height [nwalls] (cylinders; 0 for planes), wall_normal [nwalls, 3] (normal or axis)
 */
#ifndef DEM_OUTPUT_H
#define DEM_OUTPUT_H
#include "scene.h"

typedef struct output output;

/* The XDMF sidecar of an HDF5 output: OUT.h5 -> OUT.xmf (any other name gets .xmf appended). */
void output_xmf_path(const char *h5, char *buf, size_t len);
/* The output file OUT.part opened and its header written from s (particles, materials, walls: a run not started
 * does), the device and build from dev (s itself in one process; a run split over ranks: rank 0's part), the walls'
 * drawn planes over the scene's domain or the box lo[3], hi[3] of the particles (x +- r) at the start (NULL: s's) */
output *output_open(const char *path, const scene *sc, const scene_run *run, dem_sim *s, dem_sim *dev,
                    const double *box, char *err, size_t errlen);
int output_frame(output *o, dem_sim *s);
/* Where a frame's particle values come from when not from the run s itself: over MPI ranks, the ranks' parts,
 * gathered slab by slab (app/run_mpi.c), so that no rank holds a whole frame or the whole state. Each returns 0, or -1
 * (the reason in err, err_len bytes):
 *   field: rows [a, b) of field f (ncomp reals each) in particle id order, into rows;
 *   contacts: the contacts whose particle id i is in [a, b) - the particle pairs (walls 0: i < j) or the
 *   particle-wall pairs (walls 1) - in dem_contacts_get's order, *out malloc'd (free() it). */
typedef struct {
    void *ctx;
    int (*field)(void *ctx, dem_field f, int ncomp, long a, long b, double *rows);
    int (*contacts)(void *ctx, int walls, long a, long b, dem_contact **out, long *count);
    char *err;
    size_t err_len;
} frame_source;
/* A frame whose time, step and walls are s's and whose particle values are src's (NULL: s's, output_frame): the
 * same datasets and values. A failure of src returns -2 (its reason in src->err), of the file -1. */
int output_frame_from(output *o, dem_sim *s, const frame_source *src);

/* One time-series row: the series' columns (time, step, energies, contact counts, strain and stress - NAN without a
 * sample -, MC-strain iterations and capped steps) and every wall's position and received force. */
enum { S_TIME, S_STEP, S_KIN, S_ELA, S_POT, S_TOT, S_CON, S_WCON, S_COORD, S_STRAIN, S_STRESS, S_MCIT, S_MCCAP, S__N };
typedef struct {
    double v[S__N];
    double wall_pos[3 * DEM_MAX_WALLS], wall_force[3 * DEM_MAX_WALLS], wall_normal[DEM_MAX_WALLS];
} series_row;
/* The row of a sample (dem_sample_get, dem_step_sampled). */
void output_row_of(const dem_sample *smp, const scene_run *run, int nwalls, series_row *r);
/* The row of the current state (dem_sample_get: one synchronisation). */
int output_sample(dem_sim *s, const scene_run *run, series_row *r);
/* Accumulates a row into a sum (series_average), and turns a sum of count rows into their mean: every column is
 * averaged except time, step and the running count of capped steps, which are the last row's. */
void output_row_add(series_row *sum, const series_row *r, int nwalls);
void output_row_mean(series_row *sum, int count, int nwalls);
/* Appends a row (buffered: rows reach the file in chunks, at output_flush and at the end). */
int output_series(output *o, const series_row *r);
/* Writes the buffered rows (at checkpoints, so that OUT.part holds the series up to the last checkpoint). */
int output_flush(output *o);
/* Closes, writes PATH.xmf, renames PATH.part to PATH. */
int output_finish(output *o, char *err, size_t errlen);
/* Closes and keeps PATH.part (after a failure). */
void output_abort(output *o);
#endif
