/* restart_scene.c - what a continuation may change. `dem run SCENE --restart CK` continues the checkpoint's run under
 * SCENE as the file is now. SCENE must be the scene the checkpoint was run with (its text, /scene/text), field for
 * field, except:
 *   - time.duration (a run taken on past its end);
 *   - the output section (frames, series, fields, checkpoints);
 *   - a wall's stages from the one it is in: that stage lengthened or changed, later ones changed, added or removed,
 *     while the wall has a stage to run (walls[k].motion[j], j >= its stage in the checkpoint).
 * Anything else - a material, dt, a particle group, a wall, an effect, a finished wall's stages - would not continue
 * the same run: the state, the clock (step x dt) and each wall's schedule come from the checkpoint. Such a scene is
 * refused, naming the first field that differs and its line.
 * Decided 2026-12-06, after an outside review of the first version, which took any scene: a stage added after a wall's
 * last ran short (its start counted from the end of the last one), a changed dt moved the clock, a dropped effect
 * read the contacts' state as another quantity. Values are compared as written ("0.04" and "4e-2" differ). */
#include "checkpoint.h"
#include <stdio.h>
#include <string.h>

/* The number of stages wall k has in scene l */
static int stages_of(const scene_locator *l, int k)
{
    const char *path, *value;
    int line, n = 0, w, j;
    for (size_t e = 0; scene_scalar(l, e, &path, &value, &line); e++)
        if (sscanf(path, "walls[%d].motion[%d]", &w, &j) == 2 && w == k && j + 1 > n)
            n = j + 1;
    return n;
}

/* Whether the field at path may differ between the checkpoint's scene (old) and the continuation's (now) */
static int may_change(const char *path, const scene_locator *old, const scene *now, const dem_state *st)
{
    int k, j;
    if (!strcmp(path, "time.duration") || !strcmp(path, "output") || !strncmp(path, "output.", 7))
        return 1;
    if (sscanf(path, "walls[%d].motion[%d]", &k, &j) != 2 || k < 0 || j < 0)
        return 0;
    if ((unsigned)k >= now->f->walls_count)
        return 0;
    int d = scene_first_wall(now, (unsigned)k);
    if (d >= st->nwalls)
        return 0;
    int cur = st->wall_stage[d];
    return j >= cur && cur < stages_of(old, k);
}

/* The entry of l at path (from a hint: the scenes are mostly the same, in the same order), or -1 */
static long find(const scene_locator *l, const char *path, size_t *hint)
{
    const char *p, *value;
    int line;
    for (size_t e = *hint; scene_scalar(l, e, &p, &value, &line); e++)
        if (!strcmp(p, path))
            return *hint = e + 1, (long)e;
    for (size_t e = 0; e < *hint && scene_scalar(l, e, &p, &value, &line); e++)
        if (!strcmp(p, path))
            return *hint = e + 1, (long)e;
    return -1;
}

int restart_scene_check(const scene *now, const checkpoint *ck, const char *ck_path, char *err, size_t errlen)
{
    scene_locator *old = scene_locate(ck->scene_text, strlen(ck->scene_text));
    if (!old) {
        snprintf(err, errlen, "%s: out of memory", now->path);
        return 1;
    }
    const char *why = NULL, *path = NULL, *value, *p2, *v2;
    int line = 0, l2;
    size_t hint = 0;
    for (size_t e = 0; !why && scene_scalar(now->loc, e, &path, &value, &line); e++) {
        long o = find(old, path, &hint);
        if (o < 0 || (scene_scalar(old, (size_t)o, &p2, &v2, &l2) && (!value != !v2 || (value && strcmp(value, v2)))))
            if (!may_change(path, old, now, &ck->st))
                why = o < 0 ? "not in" : "not as in";
    }
    hint = 0;
    for (size_t e = 0; !why && scene_scalar(old, e, &path, &value, &line); e++)
        if (find(now->loc, path, &hint) < 0 && !may_change(path, old, now, &ck->st))
            why = "missing, but in", line = 0;
    if (why) {
        char at[32] = "";
        if (line > 0)
            snprintf(at, sizeof at, ":%d", line);
        snprintf(err, errlen, "%s%s: %s: %s the scene %s was run with; a continuation (dem run SCENE --restart) may "
                 "change only time.duration, the output section and the stages a wall has not finished (from the one "
                 "it is in); a scene that differs otherwise is a new run, from its start", now->path, at, path, why,
                 ck_path);
    }
    scene_locator_free(old);
    return why != NULL;
}
