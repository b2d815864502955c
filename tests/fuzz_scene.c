/* fuzz_scene.c - libFuzzer harness for the scene loader and checker (make fuzz).
 * Any input must give either a scene or a located error, never a crash, leak or undefined behaviour (ASan, UBSan).
 * Generated packings are capped at 2000 spheres here so that one input cannot take minutes (the loader's own cap
 * is 200000). */
#include "scene.h"
#include "scene_particles.h"
#include <stdint.h>
#include <stdio.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[8192];
    scene *sc = scene_load_text("fuzz.yaml", (const char *)data, size, err, sizeof err);
    if (!sc) {
        if (!strstr(err, "fuzz.yaml:")) /* every error names the file */
            __builtin_trap();
        return 0;
    }
    for (unsigned g = 0; g < sc->f->particles_count; g++)
        if (sc->f->particles[g].generate && sc->f->particles[g].generate->count > 2000) {
            scene_free(sc);
            return 0;
        }
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s && !strstr(err, "fuzz.yaml:"))
        __builtin_trap();
    dem_destroy(s);
    scene_free(sc);
    return 0;
}
