/* dem_mpi.h - one run of dem.h split over the ranks of an MPI communicator: the same calls, each rank's part on its
 * own device (docs/design.md "Runs over MPI"; tests/test_mpi_api.c).
 *
 *   MPI_Init(&argc, &argv);
 *   dem_sim *s = dem_create_mpi(MPI_COMM_WORLD);  // instead of dem_create(), on every rank
 *   ... the whole scene's set-up, the same calls with the same values on every rank ...
 *   if (dem_start(s, &c) || dem_step(s, 1000)) fprintf(stderr, "%s\n", dem_error(s));  // the same code everywhere
 *   dem_state st; dem_state_get(s, &st);  // the whole state, on every rank
 *   dem_destroy(s);
 *   MPI_Finalize();
 *
 * Link build/libdem_mpi.a before libdem.a, with MPI's flags (mpicc). A program that never calls dem_create_mpi needs
 * neither: libdem.a is built without MPI and calls the split's code only through the run it is given.
 *
 * The split is `mpirun -np N dem run`'s (host/mpi/split.c): dem_start cuts the set-up into one box of space per rank
 * by recursive bisection of the particles' positions, and each rank starts its part - its own particles and, as
 * ghosts, copies of every particle near enough to touch them - on the device its dem_config names (a rank may name
 * its own: e.g. its node-local rank modulo dem_device_count()). Each step exchanges the ghosts' values; the run is
 * split anew, particles and their contact histories moving between ranks, when a particle has moved far enough. Every
 * particle's state and every global sum (walls' forces, servo and stage decisions, energies, sample rows) has the
 * bits of the same run made by dem_create() in one process, at any number of ranks.
 *
 * What works on such a run, each call collective over the communicator (every rank calls it, in the same order) and
 * returning the same code on every rank, with dem_error(s) the words of the first rank that failed:
 *   - before dem_start: every set-up call, on every rank alike (each rank holds the whole set-up);
 *   - dem_start, dem_step, dem_step_sampled (rows merged over the ranks), dem_sample_get;
 *   - dem_state_get: the whole state gathered on every rank (its rebuild and iteration counts rank 0's part's; for
 *     runs whose state fits each rank's memory: `dem run` under mpirun writes output and checkpoints slab by slab);
 *   - dem_get_field of the public fields (positions, velocities, spins, forces, torques, stresses, stress traces,
 *     radii: each rank's own particles' rows gathered on every rank; the walls' forces merged), and dem_field_bytes
 *     (the whole run's sizes, not collective);
 *   - not collective: dem_step_index, dem_time, dem_wall_position, dem_stage_ends, dem_servo_stats_get and
 *     dem_mc_stats_get (every rank's part has the run's); dem_device_bytes, dem_device_bytes_part,
 *     dem_rebuild_count, dem_reorder_count, dem_neighbor_skin, dem_neighbor_capacity and dem_describe (this rank's
 *     part's, on its device); dem_count, dem_particle_radius and the set-up's other getters (the set-up's);
 *   - dem_destroy (before MPI_Finalize: it frees the run's duplicate of the communicator).
 * Every other call that reads the started run (dem_get_raw, dem_contacts_get, dem_energy, dem_state_set ...)
 * returns DEM_ERR_STATE and says so, and so does dem_memory_estimate (each part is sized at dem_start). A step that
 * fails fails on every rank with the same code and words (those of the lowest rank that failed, "rank R: ..."),
 * dem_error_particle naming the whole run's particle; dem_step_index then says where the run stopped, and nothing
 * more of it can be stepped or read (DEM_ERR_STATE). Refused at dem_start on more than one rank, by name: membranes
 * (springs, pressure, hinges, patches), which the split does not carry yet. */
#ifndef DEM_MPI_H
#define DEM_MPI_H
#include <mpi.h>
#include "dem.h"
#ifdef __cplusplus
extern "C" {
#endif

/* A run, as dem_create(), to be split over the ranks of comm (which it duplicates: its messages never meet the
 * program's). Collective. NULL when MPI is not initialised or out of memory. */
DEM_API dem_sim *dem_create_mpi(MPI_Comm comm);

#ifdef __cplusplus
}
#endif
#endif
