/* mpi_layer.h - libdem's MPI layer, in its own archive (build/libdem_mpi.a): a program that never calls it links
 * without MPI, and libdem.a is the same with or without it (docs/design.md "Runs over MPI").
 *
 * What it holds so far: the exact sums (common/exact_sum.h) merged across the ranks of a communicator, the one
 * operation the run's global sums need whatever the decomposition - each rank sums its own particles' terms exactly
 * (the walls' forces: sim_wall_sums_exact, whose tree leaves a rank's ghosts out, sim_set_ghosts; the energies:
 * sim_row_exact), the accumulators are merged, and every rank rounds the same integer to the same bits; a halo of ghost particles kept equal to their owners' after each step; and the
 * whole state gathered from the ranks' own particles and cut to a rank's part, which moves particles and their
 * contacts between ranks when the run is split anew. `mpirun -np N dem run` (app/run_mpi.c) chooses the subdomains
 * and drives these (docs/design.md "Runs over MPI"). */
#ifndef DEM_MPI_LAYER_H
#define DEM_MPI_LAYER_H
#include <mpi.h>
#include "dem.h"
#include "exact_sum.h"

/* The halo of one rank of a run split by space: its dem_sim holds its own particles and, as ghosts, copies of the
 * particles of other ranks that can touch them; after every step the owners' values of what a step reads of a
 * particle (position, velocity, spin, force, torque: a ghost's own step used its owner's values and gets them back, so
 * it holds the owner's bits while it is in the halo) are written into the ghosts (dem_mpi_halo_exchange). A particle's
 * force is its touching pairs' forces in the order of the partners' stable ids (docs/design.md "Every sum follows the
 * particle ids"), which ghosts do not change, so each own particle keeps the bits it has in one process.
 * The set of ghosts is fixed from dem_mpi_halo_init on: a run whose particles can leave it must be split anew
 * (dem_mpi_state_move, or dem_mpi_state_gather and dem_mpi_state_part; dem_state_set into a run of the new part). */
typedef struct {
    MPI_Comm comm;
    int rank, size;
    dem_sim *s;
    int n;                                  /* particles held: own and ghosts */
    int nsend, nrecv;                       /* own particles other ranks hold as ghosts (with repeats), ghosts held */
    int *send_count, *send_displ, *send_id; /* per rank, its ghosts of ours, ascending global id: our local ids */
    int *recv_count, *recv_displ, *recv_id; /* per rank, our ghosts it owns, ascending global id: our local ids */
    double *field;                          /* room for the held particles' positions (3 n): read by a split
                                               anew and the bounds, not by every step */
    void *sbuf, *rbuf;                      /* the messages: rows of HALO_W reals (common/halo.h) */
    int rs;                                 /* bytes per real of the run (and of the messages) */
    int *msg_count;                         /* [4 size]: a message's counts and displacements, sent and received */
    int steer;                              /* walls steered by their sums (a servo, an until_force stage): the
                                               ranks' sums merged after each step (dem_mpi_halo_exchange) */
    int mdr;                                /* MDR: each particle's row (mdr_particle.h) exchanged too */
    long *gid;                              /* [n]: each held particle's global id (as given to dem_mpi_halo_init) */
    int *owner;                             /* [n]: its rank */
} dem_mpi_halo;
/* Sets up h for the started run s of n particles: gid[k] each one's global id (ascending in k, the order they were
 * added, so that the local stable ids keep the global order), owner[k] the rank that owns it. Collective over comm;
 * every ghost must be owned, in the owner's run, by the rank named. Returns 0, or a dem_status, the same on every
 * rank (dem_mpi_agreed). Refused on more than one rank (DEM_ERR_ARG, dem_error(s) names it): what the halo does not
 * carry yet - membranes (springs, pressure, hinges, patches) - and an until_density stage in a run not cut with
 * sim_part_copy (it needs the whole scene's volume). A run started by sim_start_deferred (its state its
 * set-up's) gets the start's forces here, after the hook below is set, and its walls' sums merged over the ranks.
 * Ends with an exchange: the start's forces of a ghost (whose partners outside the halo it does not see) replaced by
 * its owner's before the first step; in a run whose state was set, the walls' sums are left as the state set them. Under MC-stress, MDR or MC-strain it also hooks the step (dem_sim.halo_hook, SIM_HOOK_*):
 * after MC-stress's pass 1 the owners' stress traces go into the ghosts, before pass 2 reads them at both ends of a
 * contact; after MDR's mdr_surface the owners' particle rows; after each evaluation of MC-strain's displacements the
 * owners' values of the ghosts' contacts with own particles, and its convergence test is merged over the ranks. Every
 * such point, and the step's end, is a meeting that first agrees on any rank's failure, so every step of the run is
 * collective from then on and a step that fails on one rank ends on all (dem_mpi_halo_free unhooks it). */
int dem_mpi_halo_init(dem_mpi_halo *h, MPI_Comm comm, dem_sim *s, int n, const long *gid, const int *owner);
/* After a step: the owners' position, velocity, spin, force and torque into every ghost, as rows of HALO_W reals
 * packed and unpacked on the device (common/halo.h: only the rows sent and received cross to the host and MPI, in
 * the run's precision; under MDR also each particle's row, packed the same way: the sums the step's contacts left,
 * which the next step's mdr_begin reads); and where walls are
 * steered by their sums (h->steer: a servo, an until_force stage), every rank's sums of that step merged exactly
 * and set in every rank's run (sim_wall_sums_set), so that the next step's servo and stage ends read the force one
 * process reads. Collective. */
int dem_mpi_halo_exchange(dem_mpi_halo *h);
void dem_mpi_halo_free(dem_mpi_halo *h);

/* In the ascending global ids ids[0..n): the first place k with ids[k] >= v (n where none), and the place of v (-1
 * where it is not there) - a held particle's local id from its global id (host/mpi/halo.c) */
int dem_mpi_id_from(const long *ids, int n, long v);
int dem_mpi_id_at(const long *ids, int n, long v);

/* One verdict from every rank's code e (0 or a negative dem_status; an MPI error code counts as DEM_ERR_DEVICE): 0
 * when all are 0, else the lowest, on every rank, so that all ranks take the same branch. Collective. */
int dem_mpi_agreed(MPI_Comm comm, int e);
/* The same for codes of any sign (a dem_status, or `dem run`'s exit status): 0 when all are 0, else the lowest of
 * those that are not, and *who (when not NULL) the lowest rank that had it, -1 when none failed. Collective. */
int dem_mpi_agreed_who(MPI_Comm comm, int e, int *who);

/* The whole state of a run split over the ranks of h, on every rank: what dem_state_get gives in one process whose
 * particles are those of global ids 0..nglobal-1 in that order (gid, owner: as given to dem_mpi_halo_init). Each
 * particle's arrays come from its owner, each contact from the owner of its lower id (whose rows held it since the
 * split: its history is right); the walls' sums (wall_force, wall_normal_force) are rank 0's (its own particles' where
 * its ghosts are marked: the caller merges the ranks' and sets them, app/run_mpi.c). Not yet for patch contacts (DEM_ERR_ARG). Collective; frees nothing of h. */
int dem_mpi_state_gather(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, dem_state *g);
/* The same on rank root alone (root < 0: on every rank, dem_mpi_state_gather): the others receive nothing and their
 * g holds the header only (no arrays, no contacts), so only one rank's memory holds the whole state (what the
 * output and checkpoints of a split run are written from, app/run_mpi.c). Collective. */
int dem_mpi_state_gather_at(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, int root,
                            dem_state *g);
/* A slab of the whole state on rank root alone (root < 0: on every rank): the particles of global ids [a, b) of the nglobal (a state of
 * b - a particles, in ascending id, with every array's rows of them) and the contacts whose lower id is among them,
 * with their global ids, in ascending (i, j); taken from loc, this rank's state (dem_state_get of h's run), as
 * dem_state_gather takes the whole (the walls' sums are rank 0's). The others' g holds the header only. What a
 * checkpoint of a split run is written from, slab by slab, so that no rank holds the whole state (app/run_mpi.c).
 * Collective; returns 0 or a dem_status, the same on every rank. */
int dem_mpi_state_slab(dem_mpi_halo *h, const long *gid, const int *owner, long nglobal, dem_state *loc, long a,
                       long b, int root, dem_state *g);
/* A split anew without the whole state on any rank: loc, this rank's state (dem_state_get of its run, whose held
 * particles have the ascending global ids gid[0..loc->n) and ranks owner[]), goes where the new split keeps it:
 * each own particle's arrays to every rank r with keeps(arg, id, r), each contact whose lower id this rank owns to
 * every rank that keeps both its ends; the walls' sums and the rebuild and iteration counts are rank 0's, as a
 * gather takes them. part: this rank's new part, the nkeep particles of the ascending ids keep_id (those keeps
 * names for this rank), what dem_mpi_state_part of the gathered whole state would give, bit for bit (tests/
 * test_mpi_halo.c). keeps must answer the same on every rank; s: any started run of the scene (the arrays'
 * layout). Not for patch contacts (DEM_ERR_ARG). Collective; returns 0 or a dem_status, the same on every rank. */
int dem_mpi_state_move(MPI_Comm comm, const dem_sim *s, const dem_state *loc, const long *gid, const int *owner,
                       int (*keeps)(void *arg, long id, int rank), void *arg, int nkeep, const long *keep_id,
                       dem_state *part);
/* The part of a whole state g that keep[0..g->n) selects, its particles renumbered in ascending global id, with the
 * contacts of two kept particles: the state to dem_state_set into a rank's new run after a split (s: any started run
 * of the scene, for the arrays' layout). */
int dem_mpi_state_part(const dem_sim *s, const dem_state *g, const unsigned char *keep, dem_state *part);

/* acc[0..count) replaced on every rank of comm by the merge of all ranks' acc[0..count): exact, so the result does
 * not depend on the number of ranks, their order or the reduction tree MPI chooses (the operation is commutative
 * and associative: integer addition, and an OR of the flags). The accumulators travel as bytes: the ranks must share
 * the byte order (every machine a run of ours meets: x86-64 and AArch64, little-endian). Returns MPI's error code
 * (MPI_SUCCESS: 0). Collective: every rank of comm calls it with the same count. */
int dem_mpi_exact_allreduce(MPI_Comm comm, exact_acc *acc, int count);

/* ---- a run split by space over the ranks of a communicator (host/mpi/split.c): what `mpirun -np N dem run`
 * (app/run_mpi.c) and a library program's dem_create_mpi (host/mpi/api.c) both drive ----
 * The split: recursive bisection of the particles' positions (the cut across the longest side of a part's
 * particles, at the count that gives each side its share of ranks), each rank a box. A rank's run (part) holds its
 * own particles and, as ghosts, every particle within 2 r_max + margin of its box, in ascending global id; after each
 * step the owners' values go to the ghosts (dem_mpi_halo_exchange). Before a step, when some own particle has moved
 * by half the margin since the split, the run is split anew: each rank's particles and contacts move to the ranks
 * that keep them (dem_mpi_state_move). The walls' sums and the series rows are each rank's own particles', merged
 * exactly (dem_mpi_exact_allreduce): the bits of one process at any rank count (docs/design.md "Runs over MPI"). */
typedef struct dem_mpi_split dem_mpi_split;
struct dem_mpi_split {
    MPI_Comm comm;
    int rank, size;
    dem_config cfg;       /* the parts' (the run's device, precision, backend) */
    const dem_sim *from;  /* what each part is copied from: this rank's whole run, the set-up, never started */
    dem_sim *part;        /* this rank's particles and ghosts, started */
    dem_mpi_halo h;
    int have_h;
    long n;               /* particles of the whole run */
    int nloc, nown;       /* held, and own of them */
    long *gid;            /* [nloc]: each held particle's global id, ascending */
    int *owner;           /* [nloc]: its rank */
    double rmax, margin;  /* margin: r_max times margin_f (0: 1), the halo's width beyond 2 r_max */
    double margin_f;
    long splits;          /* the splits so far (the first included) */
    long ghosts_sum;      /* ghosts over all ranks at the last split */
    int *last_owner;      /* [n]: each particle's rank after the last split */
    long moves;           /* particles that changed rank at the splits anew */
    int nw;
    double domain[6];     /* the whole run's binning domain, given to every part */
    long step;            /* the step the parts are at (also while none is held) */
    /* this rank's time per part of the steps [s] and what it sent to other ranks' ghosts: `dem run`'s report's and
     * make bench's (bench/mpi.sh) account of where a split run's time goes */
    double t_step, t_halo, t_check, t_split, t_sums, sent;
    long nsteps;
    /* a restart's first split (dem_mpi_split_start with positions x): this rank's part of the state, read by the
     * caller (app/run_mpi.c: its part of a checkpoint) into ps once the part's particles are chosen (sp->gid); 0, or
     * a dem_status with the reason in err. NULL: a fresh start (the set-up's state, the start's forces made). */
    int (*load)(void *arg, dem_mpi_split *sp, dem_state *ps, char *err, size_t len);
    void *load_arg;
    const char *load_what; /* what it reads (a file: the words of a state the part refuses begin with it) */
    /* tests (DEM_TEST_RANK_FAIL, app/run_mpi.c): rank fail_rank fails after its step fail_step (fail_mode 1, as a
     * lost device would) or inside it (2: a particle's position made NaN before it), or dies after it (3: it sends
     * itself SIGKILL, as the kernel's out-of-memory killer or a lost node would end it: no word, nothing closed);
     * fail_step -1: never */
    long fail_step;
    int fail_rank, fail_mode;
};
/* The parts made and started from whole (this rank's whole run, the scene's set-up, which no rank starts and each
 * part is copied from; every rank's the same), split by the positions x[3 n] (NULL: the set-up's; given: a
 * restart's, with sp->load reading this rank's part of its state, at step step0). Fresh: each part's state its
 * set-up's, the start's forces made with the halo's meetings. What dem_start would refuse of the whole scene is said
 * with `what` (its file) first. sp: zeroed but for margin_f, load, load_arg and the fail_ hooks. Collective; 0, or a
 * dem_status, the same on every rank, with the words of the first rank that failed in err on every rank. */
int dem_mpi_split_start(dem_mpi_split *sp, MPI_Comm comm, dem_sim *whole, const dem_config *cfg, const double *x,
                        long step0, const char *what, char *err, size_t len);
/* nsteps steps like dem_step_sampled(want, rows) of one process, the rows merged over the ranks (every rank gets
 * them); split anew before a step where a particle has moved far enough. Collective; agreed as above. */
int dem_mpi_split_step(dem_mpi_split *sp, long nsteps, const unsigned char *want, dem_sample *rows, char *err,
                       size_t len);
/* the series row of the state now (dem_sample_get of one process), from the parts' own particles' exact sums,
 * merged (every rank gets it). Collective; agreed. */
int dem_mpi_split_sample(dem_mpi_split *sp, dem_sample *row, char *err, size_t len);
/* the box lo[3], hi[3] of every particle (x +- r) now, over the parts' own (every rank gets it). Collective; 0, or
 * DEM_ERR_DEVICE on every rank where any rank could not read its positions (box then not every particle's). */
int dem_mpi_split_bounds(dem_mpi_split *sp, double box[6]);
/* Every rank's own particles' rows vals[nc k .. nc k + nc) (k: a held particle, its local id), by global id, into
 * out[nc n] on every rank: what the split cuts by (the positions: 3 reals a particle), and a split run's fields
 * (dem_get_field of dem_create_mpi's run). Collective; 0 or a dem_status, the same on every rank. */
int dem_mpi_split_rows(dem_mpi_split *sp, const double *vals, int nc, double *out);
/* the walls' sums of the state now, each rank's own particles', merged exactly (acc[SE_STRIDE + WP_STRIDE w + WP_*]
 * of nw walls: the walls of a run with the walls effect, else 0), and put as one process rounds them into the
 * arrays wall_force and wall_normal_force of st (NULL, or a state without them: not put). Collective; agreed. */
int dem_mpi_split_walls(dem_mpi_split *sp, exact_acc *acc, int *nw, char *err, size_t len);
void dem_mpi_split_walls_put(const dem_mpi_split *sp, const exact_acc *acc, int nw, dem_state *st);
/* the same into a series row's wall_force and wall_normal */
void dem_mpi_split_walls_row(const dem_mpi_split *sp, const exact_acc *acc, int nw, dem_sample *row);
/* every rank's e agreed (dem_mpi_agreed_who); on failure the first failing rank's words (dem_error(s) where err is
 * empty) in err on every rank */
int dem_mpi_split_agreed(dem_mpi_split *sp, int e, dem_sim *s, char *err, size_t len);
/* after a call that agreed on failure e itself (the halo's, the gather): the words of the first rank that has any */
int dem_mpi_split_shared_error(dem_mpi_split *sp, int e, char *err, size_t len);
/* msg of rank who to every rank (said as "rank WHO: ..." where who is not 0). Collective. */
void dem_mpi_share(MPI_Comm comm, int who, char *msg, size_t len);
void dem_mpi_split_free(dem_mpi_split *sp);
#endif /* DEM_MPI_LAYER_H */
