/* output.h - the run's HDF5 file (frames of particle fields, time series, provenance) and its XDMF sidecar.
 *
 * The file is written as OUT.part and renamed to OUT when the run ends well, so that OUT is never a truncated
 * file; a run that fails keeps what it wrote in OUT.part and leaves any older OUT untouched.
 * Layout (units in each dataset's "units" attribute):
 *   /            attributes libdem_version, device, precision, effects, dt, steps, scene_path; dataset scene_text
 *   /particles/  radius [n], material [n] (constant over the run)
 *   /frames/     time [F], step [F], position|velocity|angular_velocity|force|torque [F, n, 3]
 *   /series/     time, step, kinetic, elastic, potential, total [R]; contacts, wall_contacts [R];
 *                wall_position, wall_force [R, nwalls, 3]; strain, stress [R] when the scene names a sample
 */
#ifndef DEM_OUTPUT_H
#define DEM_OUTPUT_H
#include "scene.h"

typedef struct output output;

/* The XDMF sidecar of an HDF5 output: OUT.h5 -> OUT.xmf (any other name gets .xmf appended). */
void output_xmf_path(const char *h5, char *buf, size_t len);
output *output_open(const char *path, const scene *sc, const scene_run *run, dem_sim *s, char *err, size_t errlen);
int output_frame(output *o, dem_sim *s);
/* One time-series row; strain and stress are NAN without a sample. */
int output_series(output *o, dem_sim *s, double strain, double stress);
/* Closes, writes PATH.xmf, renames PATH.part to PATH. */
int output_finish(output *o, char *err, size_t errlen);
/* Closes and keeps PATH.part (after a failure). */
void output_abort(output *o);
#endif
