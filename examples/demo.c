/* demo.c - `make demo`: a 2000-particle polydisperse packing compressed by a lid, run on the first OpenCL device
 * (PoCL on a CPU machine) and on the plain C reference, fp64; prints what happened and whether the bits agree. */
#include "dem.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static dem_sim *build(int n, unsigned seed)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.6, 0.4});
    int wm = dem_add_material(s, &(dem_material){7800, 2e8, 0.3, 0.6, 0.4});
    int side = (int)ceil(cbrt((double)n));
    double rmax = 1e-3, a = 1.9 * rmax, L = side * a;
    for (int i = 0; i < n; i++) {
        double x[3] = {(i % side + 0.5) * a, (i / side % side + 0.5) * a, (i / (side * side) + 0.5) * a}, v[3];
        for (int d = 0; d < 3; d++) {
            seed = seed * 1664525u + 1013904223u;
            v[d] = 0.5 * ((seed >> 8) / 8388608.0 - 1);
        }
        seed = seed * 1664525u + 1013904223u;
        dem_add_particle(s, x, v, rmax * (0.5 + 0.5 * (seed >> 8) / 16777216.0), m);
    }
    int lid = dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, wm) + 5;
    dem_set_wall_motion(s, lid, 2, (dem_stage[2]){{0.01, {0, 0, -0.3}}, {0.01, {0, 0, 0.3}}});
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    dem_set_domain(s, (double[3]){-L, -L, -L}, (double[3]){2 * L, 2 * L, 2 * L});
    dem_time_scales ts;
    dem_time_scales_get(s, 1.0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

int main(void)
{
    const int n = 2000;
    const long steps = 2000;
    dem_sim *sims[2] = {build(n, 7), build(n, 7)};
    dem_backend_kind kinds[2] = {DEM_BACKEND_OPENCL, DEM_BACKEND_REFERENCE};
    dem_time_scales ts;
    dem_time_scales_get(sims[0], 1.0, &ts);
    printf("libdem %s demo: %d polydisperse spheres (r 0.5-1 mm, E 10 MPa), box with a lid moving down then up\n",
           DEM_VERSION, n);
    printf("Rayleigh time %.3g s, Hertz contact time at 1 m/s %.3g s, dt %.3g s (0.2 x Rayleigh), %ld steps\n",
           ts.rayleigh_time, ts.hertz_time, dem_dt(sims[0]), steps);
    double secs[2];
    for (int k = 0; k < 2; k++) {
        dem_config c;
        dem_config_default(&c);
        c.backend = kinds[k];
        c.precision = DEM_FP64;
        double t0 = now(), peak = 0, f[3];
        if (dem_start(sims[k], &c)) {
            fprintf(stderr, "demo: %s\n", dem_error(sims[k]));
            return 1;
        }
        for (long done = 0; done < steps; done += 100) { /* the lid force, sampled every 100 steps */
            if (dem_step(sims[k], 100) || dem_wall_force(sims[k], 5, f)) {
                fprintf(stderr, "demo: %s\n", dem_error(sims[k]));
                return 1;
            }
            peak = fmax(peak, f[2]);
        }
        dem_energy_t e;
        dem_energy(sims[k], &e);
        secs[k] = now() - t0;
        printf("%-48.48s %6.2f s  %9.3g particle-steps/s  E_kin %.4g J  %ld contacts  peak lid force %.4g N  "
               "rebuilds %ld\n", dem_describe(sims[k]), secs[k], (double)n * steps / secs[k], e.kinetic, e.contacts,
               peak, dem_rebuild_count(sims[k]));
    }
    size_t bytes = dem_field_bytes(sims[0], DEM_FIELD_X);
    unsigned char *a = malloc(bytes), *b = malloc(bytes);
    int same = a && b;
    for (dem_field f = DEM_FIELD_X; same && f <= DEM_FIELD_TORQUE; f++)
        same = !dem_get_raw(sims[0], f, a, bytes) && !dem_get_raw(sims[1], f, b, bytes) && !memcmp(a, b, bytes);
    printf("OpenCL and reference state after %ld steps: %s\n", steps, same ? "bitwise identical" : "DIFFERENT");
    free(a);
    free(b);
    dem_destroy(sims[0]);
    dem_destroy(sims[1]);
    return same ? 0 : 1;
}
