/* install_check_mpi.c - a program against the installed libdem_mpi (tests/install_check.sh builds it with nothing
 * but `pkg-config --cflags --libs libdem-mpi` and runs it under mpirun on 2 ranks): 64 spheres dropped into a box,
 * 300 steps on the reference, made once by dem_create and once by dem_create_mpi, split over the ranks; the whole
 * state of the split run (positions, velocities, spins) must have the one-process run's bits on every rank. */
#include <dem_mpi.h>
#include <stdio.h>
#include <string.h>

static dem_sim *build(dem_sim *s)
{
    if (!s)
        return NULL;
    dem_material mat = {0};
    mat.density = 2500, mat.young = 1e7, mat.poisson = 0.3, mat.restitution = 0.5, mat.friction = 0.5;
    int m = dem_add_material(s, &mat);
    for (int k = 0; k < 64; k++) {
        double x[3] = {0.0015 + 0.0022 * (k % 4), 0.0015 + 0.0022 * (k / 4 % 4), 0.0015 + 0.0022 * (k / 16)};
        double v[3] = {0.05 * (k % 3 - 1), 0.05 * (k % 5 - 2) / 2, -0.1};
        dem_add_particle(s, x, v, 0.001 * (0.9 + 0.1 * (k % 7) / 6.0), m);
    }
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){0.01, 0.01, 0.012}, m);
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION | DEM_EFFECT_GRAVITY |
                           DEM_EFFECT_WALLS);
    dem_set_dt(s, 2e-6);
    return s;
}

/* the array called name of a and b, equal bit for bit */
static int same(const dem_state *a, const dem_state *b, const char *name)
{
    const dem_state_array *x = dem_state_find(a, name), *y = dem_state_find(b, name);
    return x && y && x->count == y->count && !memcmp(x->data, y->data, x->count * (size_t)a->real_size);
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    dem_config c;
    dem_config_default(&c);
    c.backend = DEM_BACKEND_REFERENCE;
    dem_sim *one = build(dem_create()), *par = build(dem_create_mpi(MPI_COMM_WORLD));
    dem_state a, b;
    int ok = one && par && !dem_start(one, &c) && !dem_step(one, 300) && !dem_state_get(one, &a);
    if (!ok && rank == 0)
        fprintf(stderr, "one process: %s\n", one ? dem_error(one) : "no run");
    int e = par ? dem_start(par, &c) : -1; /* collective: every rank makes each call whatever happened before */
    e = e ? e : dem_step(par, 300);
    e = e ? e : dem_state_get(par, &b);
    if (e && rank == 0)
        fprintf(stderr, "split run: %s\n", par ? dem_error(par) : "no run");
    ok = ok && !e && same(&a, &b, "x") && same(&a, &b, "v") && same(&a, &b, "w");
    int all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (rank == 0)
        printf("install_check_mpi: %d ranks, 64 spheres, 300 steps: %s\n", size,
               all ? "the split run's state has the one-process bits" : "FAILED");
    dem_destroy(one);
    dem_destroy(par);
    MPI_Finalize();
    return all ? 0 : 1;
}
