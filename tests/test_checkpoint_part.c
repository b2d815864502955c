/* test_checkpoint_part.c - a rank's part of a checkpoint (app/checkpoint.c checkpoint_read_part: what each rank of a
 * restart split over MPI ranks reads, app/run_mpi.c) against the whole read of the same file (checkpoint_read): for
 * sets of kept ids - every third, a run of ids, scattered ids, all of them - each array's rows of each kept particle
 * (a wall array group by group), the contacts with both ends kept (renumbered to their places, in order), the radii
 * and the header are the whole state's; in slabs of the reader's own size and across them (2000 particles, over the
 * 32 768 of a slab only in the count of its reads). A velocity made NaN in the file is refused with the element the
 * whole read names. Scenes: tests/scenes/restart_box.yaml (walls, friction) and restart_box_mc.yaml (MC-strain). */
#include "test_util.h"
#include "checkpoint.h"
#include "h5util.h"
#include "sim.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static size_t esize(const dem_state_array *a, int rs) { return a->elem == DEM_STATE_REAL ? (size_t)rs : sizeof(int); }

/* part (of the m ids keep) against the whole state w: arrays, contacts, header; radii against rad_w */
static void same_part(dem_sim *s, const dem_state *w, const double *rad_w, const dem_state *p, const double *rad,
                      const long *keep, long m, const char *what)
{
    long n = w->n;
    assert_int_equal(p->n, m);
    assert_int_equal(p->step, w->step);
    assert_int_equal(p->nwalls, w->nwalls);
    assert_memory_equal(p->wall_pos, w->wall_pos, sizeof w->wall_pos);
    assert_int_equal(p->narrays, w->narrays);
    for (int k = 0; k < w->narrays; k++) {
        const dem_state_array *a = &w->arrays[k], *b = &p->arrays[k];
        assert_string_equal(a->name, b->name);
        int per = 0, kind = sim_state_array_layout(s, a->name, &per);
        size_t es = esize(a, w->real_size);
        if (kind == DEM_MOVE_STAY || !a->count) {
            assert_int_equal(b->count, a->count);
            if (a->count)
                assert_memory_equal(b->data, a->data, a->count * es);
            continue;
        }
        size_t wd = (size_t)(a->width > 1 ? a->width : 1), times = a->count / wd / (size_t)n;
        size_t each = kind == DEM_MOVE_G ? (size_t)per / wd : times, groups = times / each, row = each * wd * es;
        assert_int_equal(b->count, a->count / (size_t)n * (size_t)m);
        for (size_t g = 0; g < groups; g++)
            for (long q = 0; q < m; q++)
                if (memcmp((const char *)b->data + (g * (size_t)m + (size_t)q) * row,
                           (const char *)a->data + (g * (size_t)n + (size_t)keep[q]) * row, row))
                    fail_msg("%s: %s: particle %ld (group %zu) differs from the whole read", what, a->name, keep[q], g);
    }
    for (long q = 0; q < m; q++)
        if (rad[q] != rad_w[keep[q]])
            fail_msg("%s: radius of particle %ld", what, keep[q]);
    long at = 0, rs = w->real_size;
    for (long c = 0; c < w->npairs; c++) {
        long i = -1, j = -1;
        for (long q = 0; q < m; q++)
            i = keep[q] == w->pair_i[c] ? q : i, j = keep[q] == w->pair_j[c] ? q : j;
        if (i < 0 || j < 0)
            continue;
        if (at >= p->npairs || p->pair_i[at] != i || p->pair_j[at] != j)
            fail_msg("%s: contact %ld (%d, %d) of the whole is not the part's contact %ld", what, c, w->pair_i[c],
                     w->pair_j[c], at);
        assert_memory_equal((char *)p->pair_hist + 3 * at * rs, (char *)w->pair_hist + 3 * c * rs, 3 * (size_t)rs);
        if (w->has_mc)
            assert_memory_equal((char *)p->pair_mc_fn + at * rs, (char *)w->pair_mc_fn + c * rs, (size_t)rs);
        if (w->pair_mc_disp)
            assert_memory_equal((char *)p->pair_mc_disp + 2 * at * rs, (char *)w->pair_mc_disp + 2 * c * rs,
                                2 * (size_t)rs);
        if (w->pair_rec)
            assert_memory_equal((char *)p->pair_rec + DEM_PAIR_RECORD_REALS * at * rs,
                                (char *)w->pair_rec + DEM_PAIR_RECORD_REALS * c * rs, DEM_PAIR_RECORD_REALS * (size_t)rs);
        at++;
    }
    assert_int_equal(p->npairs, at);
}

static void parts_of(const char *scene_path, long steps)
{
    char err[4096], path[] = "/tmp/test_checkpoint_part_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    scene *sc = scene_load(scene_path, err, sizeof err);
    if (!sc)
        fail_msg("%s", err);
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    run.cfg.backend = DEM_BACKEND_REFERENCE;
    start_or_fail(s, &run.cfg);
    step_or_fail(s, steps);
    assert_int_equal(checkpoint_write(path, s, sc, &run, err, sizeof err), 0);
    checkpoint whole, head;
    if (checkpoint_read(path, &whole, err, sizeof err) || checkpoint_read_head(path, &head, err, sizeof err))
        fail_msg("%s", err);
    long n = whole.st.n;
    assert_true(whole.st.npairs >= 10); /* contacts to pick from */
    long *keep = malloc(sizeof(long) * (size_t)n);
    double *x = malloc(sizeof(double) * 3 * (size_t)n), *rad = malloc(sizeof(double) * (size_t)n);
    assert_true(keep && x && rad);
    /* the positions every rank reads: the whole read's, widened */
    assert_int_equal(checkpoint_read_x(path, &head, x, err, sizeof err), 0);
    const dem_state_array *xa = dem_state_find(&whole.st, "x");
    for (long k = 0; k < 3 * n; k++)
        assert_true(x[k] == sim_real_at(xa->data, (size_t)k, whole.st.real_size));
    for (int set = 0; set < 8; set++) {
        if (set == 4) /* the same sets again, read in slabs of 5 particles and 5 contacts */
            setenv("DEM_TEST_FRAME_SLAB", "5", 1);
        long m = 0;
        unsigned rng = 7;
        for (long i = 0; i < n; i++)
            if (set % 4 == 0   ? i % 3 == 1
                : set % 4 == 1 ? i >= n / 4 && i < n / 2
                : set % 4 == 2 ? uniform01(&rng) < 0.3
                               : 1)
                keep[m++] = i;
        dem_state part;
        if (checkpoint_read_part(path, &head, s, m, keep, &part, rad, err, sizeof err))
            fail_msg("set %d: %s", set, err);
        char what[128];
        snprintf(what, sizeof what, "%s, set %d (%ld of %ld particles)", scene_path, set, m, n);
        same_part(s, &whole.st, whole.radius, &part, rad, keep, m, what);
        print_message("  %s: %ld contacts of %ld, equal to the whole read\n", what, part.npairs, whole.st.npairs);
        dem_state_free(&part);
    }
    unsetenv("DEM_TEST_FRAME_SLAB");
    /* a velocity not a number: refused, the whole file's element named as the whole read names it */
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    assert_true(f >= 0);
    hid_t d = H5Dopen2(f, "state/v", H5P_DEFAULT);
    double *v = malloc(sizeof(double) * 3 * (size_t)n);
    assert_true(d >= 0 && v);
    assert_true(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    v[3 * (n - 2) + 1] = NAN;
    assert_true(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    H5Dclose(d), H5Fclose(f);
    char want[64];
    snprintf(want, sizeof want, "/state/v: element %ld is nan", 3 * (n - 2) + 1);
    keep[0] = n - 2, keep[1] = n - 1;
    dem_state part;
    assert_int_not_equal(checkpoint_read_part(path, &head, s, 2, keep, &part, rad, err, sizeof err), 0);
    if (!strstr(err, want))
        fail_msg("the damaged part said \"%s\", not %s", err, want);
    keep[0] = 0, keep[1] = 1; /* a part without it reads */
    assert_int_equal(checkpoint_read_part(path, &head, s, 2, keep, &part, rad, err, sizeof err), 0);
    dem_state_free(&part);
    checkpoint_free(&whole), checkpoint_free(&head);
    free(keep), free(x), free(rad), free(v);
    dem_destroy(s);
    scene_free(sc);
    unlink(path);
}

static void test_part_box(void **st)
{
    (void)st;
    parts_of("tests/scenes/restart_box.yaml", 500);
}

static void test_part_mc(void **st)
{
    (void)st;
    parts_of("tests/scenes/restart_box_mc.yaml", 500);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_part_box),
        cmocka_unit_test(test_part_mc),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
