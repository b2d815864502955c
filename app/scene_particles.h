/* scene_particles.h - the particles of a scene: explicit lists, CSV files, generated packings, and the check of
 * initial overlaps (scene_particles.c, scene_overlaps.c). */
#ifndef DEM_SCENE_PARTICLES_H
#define DEM_SCENE_PARTICLES_H
#include "scene.h"

/* Where particle i came from, for error messages, and its initial position and radius. */
typedef struct {
    int group;    /* index in the scene's particles list */
    int index;    /* index in its group */
    int csv_line; /* line in the CSV file, 0 if not from a file */
    double x[3], r;
} scene_origin;

int scene_fail(const scene *sc, char *err, size_t errlen, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
int scene_material_id(const scene *sc, const char *name);
/* Adds every particle group to s; *origin (malloc'd) gets one entry per particle. */
/* fill: a line per random group (count, volume share, time taken), for dem check */
int scene_add_particles(const scene *sc, dem_sim *s, scene_origin **origin, char *fill, size_t fill_len, char *err,
                        size_t errlen);
/* Rejects initial particle-particle and particle-wall overlaps above the scene's tolerance. */
int scene_check_overlaps(const scene *sc, dem_sim *s, const scene_origin *origin, int n, char *err, size_t errlen);
/* The scene's membranes (scene_membranes.c), after the walls (first_wall: each scene wall's first library wall) */
int scene_add_membranes(const scene *sc, dem_sim *s, scene_run *run, const int *first_wall, char *err, size_t errlen);
#endif
