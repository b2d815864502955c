/* fuzz_scene.c - libFuzzer harness for the scene loader and checker (make fuzz).
 * Any input must give either a scene or a located error, never a crash, leak or undefined behaviour (ASan, UBSan).
 * Generated packings are capped lower here (Makefile: DEM_SCENE_MAX_*) so that one input cannot take minutes or
 * gigabytes; the caps themselves are the loader's code, exercised either way. */
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
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s && !strstr(err, "fuzz.yaml:"))
        __builtin_trap();
    dem_destroy(s);
    scene_free(sc);
    return 0;
}
