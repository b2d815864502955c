/* tools/mdr_held_bulk/continue.c - continues a run's checkpoint in the reference backend and prints, every EVERY
 * steps, one line: time [s], kinetic and elastic energy [J], the fastest sphere's speed [m/s], how many spheres move
 * faster than 1 m/s, the normal force on wall WALL [N] (default 0) and, given a particle id P, that sphere's speed.
 * run.sh links it twice: against build/'s libdem (the law) and against a copy of the tree whose MDR law holds (M10)'s
 * bulk increments (docs/laws/mdr.md "Energy").
 * usage: continue SCENE.yaml CHECKPOINT.h5 STEPS EVERY [WALL [P]] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "checkpoint.h"
#include "dem.h"
#include "scene.h"

static double speed(const double *v, int i)
{
    return sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
}

int main(int argc, char **argv)
{
    char err[2048];
    if (argc < 5) {
        fprintf(stderr, "usage: continue SCENE.yaml CHECKPOINT.h5 STEPS EVERY [WALL [P]]\n");
        return 2;
    }
    long steps = atol(argv[3]), every = atol(argv[4]);
    int wall = argc > 5 ? atoi(argv[5]) : 0, P = argc > 6 ? atoi(argv[6]) : -1;
    checkpoint ck;
    memset(&ck, 0, sizeof ck);
    if (checkpoint_read(argv[2], &ck, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    scene *sc = scene_load(argv[1], err, sizeof err);
    if (!sc) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    sc->order_default = "spatial"; /* as dem run stores the particles */
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    run.cfg.backend = DEM_BACKEND_REFERENCE;
    run.cfg.precision = (dem_precision)ck.st.real_size;
    if (dem_start(s, &run.cfg) || dem_state_set(s, &ck.st)) {
        fprintf(stderr, "%s\n", dem_error(s));
        return 1;
    }
    int n = dem_count(s);
    if (every < 1 || steps < every || wall < 0 || wall >= DEM_MAX_WALLS || P >= n) {
        fprintf(stderr, "continue: STEPS >= EVERY >= 1, WALL a wall, P a particle id below %d\n", n);
        return 2;
    }
    double *v = malloc(sizeof(double) * 3 * (size_t)n);
    if (!v)
        return 1;
    setvbuf(stdout, NULL, _IOLBF, 0);
    printf("# time [s], kinetic [J], elastic [J], fastest [m/s], spheres above 1 m/s, wall %d normal force [N]%s\n",
           wall, P >= 0 ? ", particle P's speed [m/s]" : "");
    for (long k = 0; k < steps; k += every) {
        dem_sample sm;
        if (dem_step(s, every) || dem_get_field(s, DEM_FIELD_V, v) || dem_sample_get(s, &sm)) {
            fprintf(stderr, "%s\n", dem_error(s));
            return 1;
        }
        double vmax = 0;
        int fast = 0;
        for (int i = 0; i < n; i++) {
            vmax = fmax(vmax, speed(v, i));
            fast += speed(v, i) > 1;
        }
        printf("%.6e %.4e %.4e %.4e %d %.4e", dem_time(s), sm.energy.kinetic, sm.energy.elastic, vmax, fast,
               sm.wall_normal[wall]);
        if (P >= 0)
            printf(" %.4e", speed(v, P));
        printf("\n");
    }
    free(v);
    dem_destroy(s);
    return 0;
}
