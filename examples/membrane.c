/* membrane.c - `build/dem-membrane`: the library's membrane (seed 001, MSS_particle model) around a granulate.
 * A closed rubber membrane of radius 26.5 mm (642 vertices with springs and hinges) holds 57 soft beads of 4 mm on a
 * lattice; a confining pressure ramps to 2 kPa over 50 ms and holds for 50 ms. Every 10 ms it prints the pressure,
 * the vertices' mean and largest distance from the centre and the beads' outermost reach [mm]: the membrane closes
 * onto the beads, wraps into the valleys between them (its mean radius drops below the beads' reach) and folds
 * where it has area to spare (its largest radius stays above), and squeezes the beads inward (about 0.9 mm).
 * Runs on the first OpenCL device (PoCL on a CPU machine), fp64, in about two seconds. */
#include "dem.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define R_MEMBRANE 0.0265
#define R_BEAD 0.004

int main(void)
{
    dem_sim *s = dem_create();
    dem_mesh m;
    char err[256];
    dem_mesh_spec sphere = {DEM_MESH_SPHERE, {0, 0, 0}, R_MEMBRANE, 0, 0.004};
    if (dem_mesh_make(&sphere, &m, err, sizeof err))
        return fprintf(stderr, "dem-membrane: %s\n", err), 1;
    /* E, nu, thickness, density, restitution, friction, damping ratio, k_el [N m], k_diss [N s], vertex radius */
    dem_membrane rubber = {1.25e6, 1.0 / 3, 3e-4, 1000, 0.5, 1.2, 0.3, 1e-4, 1e-7, 0.0012};
    dem_membrane_info info;
    if (dem_add_membrane(s, &m, &rubber, &info))
        return fprintf(stderr, "dem-membrane: %s\n", dem_error(s)), 1;
    dem_mesh_free(&m);
    int beads = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.3});
    int nbeads = 0;
    double a = 2.1 * R_BEAD;
    for (int i = -3; i <= 3; i++) /* a cubic lattice inside the membrane, clear of its vertex spheres */
        for (int j = -3; j <= 3; j++)
            for (int k = -3; k <= 3; k++) {
                double x[3] = {i * a, j * a, k * a};
                if (sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) + R_BEAD < R_MEMBRANE - 0.002 &&
                    dem_add_particle(s, x, NULL, R_BEAD, beads) >= 0)
                    nbeads++;
            }
    dem_pressure_stage ramp[2] = {{0.05, 2000}, {0.05, 2000}};
    dem_set_pressure_stages(s, 2, ramp);
    dem_set_domain(s, (double[3]){-0.04, -0.04, -0.04}, (double[3]){0.04, 0.04, 0.04});
    dem_time_scales ts;
    dem_time_scales_get(s, 0.5, &ts);
    dem_set_dt(s, ts.recommended_dt);
    dem_config c;
    dem_config_default(&c);
    if (dem_start(s, &c))
        return fprintf(stderr, "dem-membrane: %s\n", dem_error(s)), 1;
    printf("membrane: %d vertices, %d springs, %d hinges, %d triangles, %.4g g; %d beads of %g mm; dt %.3g s\n",
           info.nvertices, info.nsprings, info.nhinges, info.ntriangles, 1e3 * info.mass, nbeads, 1e3 * R_BEAD,
           dem_dt(s));
    printf("%8s %10s %14s %14s %14s\n", "t [ms]", "p [Pa]", "membrane mean", "membrane max", "beads' reach");
    int n = dem_count(s);
    double *x = malloc(sizeof(double) * 3 * (size_t)n);
    long every = lround(0.01 / dem_dt(s));
    for (int row = 0; row <= 10; row++) {
        if (row && dem_step(s, every))
            return fprintf(stderr, "dem-membrane: %s\n", dem_error(s)), 1;
        dem_get_field(s, DEM_FIELD_X, x);
        double rm = 0, rb = 0, rmax = 0;
        for (int i = 0; i < n; i++) {
            double r = sqrt(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] + x[3 * i + 2] * x[3 * i + 2]);
            if (i < info.nvertices)
                rm += r / info.nvertices, rmax = fmax(rmax, r);
            else
                rb = fmax(rb, r + R_BEAD);
        }
        printf("%8.1f %10.1f %14.3f %14.3f %14.3f\n", 1e3 * dem_time(s), dem_pressure(s), 1e3 * rm, 1e3 * rmax,
               1e3 * rb);
    }
    free(x);
    dem_destroy(s);
    return 0;
}
