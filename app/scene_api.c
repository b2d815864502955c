/* scene_api.c - a scene file as a built simulation, for a program that drives the library and wants the scenes of
 * `dem run` (the Python package: python/libdem/sim.py Sim.from_scene). Linked into the shared library the package
 * loads from the tree (make python-lib), not into the installed one, which keeps no YAML reader. */
#include "scene.h"
#include <stdio.h>

/* Loads and builds the scene at path (every check of `dem check`), not started: the caller starts it with *cfg, the
 * scene's configuration (backend, precision, device), and may step it *steps steps, its duration. NULL on a bad scene
 * with the message ("file:line: field: reason") in err. */
DEM_API dem_sim *dem_scene_open(const char *path, dem_config *cfg, long *steps, char *err, size_t errlen)
{
    scene *sc = scene_load(path, err, errlen);
    if (!sc)
        return NULL;
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, errlen);
    if (s) {
        *cfg = run.cfg;
        cfg->source_dir = NULL; /* the library's own (the scene's run takes it from the build) */
        *steps = run.steps;
    }
    scene_free(sc);
    return s;
}
