/* test_mc_strain.c - mc_strain_disp's two code paths give the same bits. mc_strain_disp keeps the geometry of up to
 * MC_CACHE contacts in private memory (fast path) and recomputes it for particles with more (slow path). This file
 * compiles common/mc_strain.h with MC_CACHE 2, so every particle with more than two contacts takes the slow path,
 * and compares its induced displacements with libdem's reference twin (MC_CACHE 16: the fast path) on the same
 * input: a sphere with six particle contacts and two wall contacts, and its neighbours. */
#define DEM_REAL_SIZE 8
#define MC_CACHE 2
#include "mc_strain.h"
#include "ref_kernels.h"
#include "test_util.h"
#include <string.h>

enum { N = 7, MAXN = 8, NW = 2 };

static void test_slow_path_equals_fast_path(void **st)
{
    (void)st;
    /* particle 0 at the origin (r 1 cm) pressed by six neighbours along +-x, +-y, +-z (and off-axis a little) and by
     * two planes below and beside it */
    double xs[3 * N] = {0, 0, 0, 0.0195, 0.001, 0, -0.0196, 0, 0.0005, 0.0012, 0.0194, 0, 0, -0.0193, 0.0009,
                        0.0004, 0.0011, 0.0197, -0.001, 0, -0.0192};
    real x[3 * N], radius[N];
    for (int k = 0; k < 3 * N; k++)
        x[k] = (real)xs[k];
    for (int i = 0; i < N; i++)
        radius[i] = (real)0.01;
    int mat[N] = {0, 0, 0, 0, 0, 0, 0};
    real pairmat[2 * 2 * PM_STRIDE];
    memset(pairmat, 0, sizeof pairmat);
    for (int k = 0; k < 4; k++) { /* material 0: nu 0.3, E 1e6, gamma 1; material 1 the walls */
        pairmat[k * PM_STRIDE + PM_ESTAR] = 1e6 / (2 * (1 - 0.09));
        pairmat[k * PM_STRIDE + PM_MCS_K] = 1.0 * 1.3 / (2 * M_PI * 1e6);
        pairmat[k * PM_STRIDE + PM_MCS_C1] = 3 - 4 * 0.3;
        pairmat[k * PM_STRIDE + PM_MCS_C2] = 1 - 2 * 0.3;
    }
    int count[N], list[N * MAXN];
    memset(list, 0, sizeof list);
    count[0] = 6;
    for (int k = 0; k < 6; k++)
        list[k] = k + 1;
    for (int i = 1; i < N; i++) {
        count[i] = 1;
        list[i * MAXN] = 0;
    }
    int wall_int[NW * WI_STRIDE] = {WALL_PLANE, 1, WALL_PLANE, 1};
    real wall_real[NW * W_STRIDE];
    memset(wall_real, 0, sizeof wall_real);
    wall_real[W_PZ] = (real)-0.0098; /* floor z = -9.8 mm, normal +z */
    wall_real[W_NZ] = 1;
    wall_real[W_STRIDE + W_PY] = (real)0.0099; /* side y = 9.9 mm, normal -y */
    wall_real[W_STRIDE + W_NY] = -1;
    /* the six pairs, numbered by their host, particle 0 (neighbor.h pair_index): pair p joins 0 and p + 1; each
     * other particle finds its one pair, stored before it, through in_pair */
    real fn[6], wall_fn[N * NW];
    for (int k = 0; k < 6; k++)
        fn[k] = (real)(0.05 + 0.01 * k);
    int own_start[N + 1], in_start[N + 1], in_pair[6];
    for (int i = 0; i <= N; i++) {
        own_start[i] = i == 0 ? 0 : 6;
        in_start[i] = i == 0 ? 0 : i - 1;
    }
    for (int k = 0; k < 6; k++)
        in_pair[k] = k;
    for (int k = 0; k < N * NW; k++)
        wall_fn[k] = (real)(0.03 + 0.02 * (k % 3));
    real slow[N * MAXN], fast[N * MAXN], wslow[N * NW], wfast[N * NW];
    unsigned ride[N] = {0}; /* no riders (read only with DEM_EFFECT_RIDERS) */
    int in_count[N]; /* partners of lower stable id: none for particle 0, particle 0 for the others */
    for (int i = 0; i < N; i++)
        in_count[i] = i > 0;
    int start[N + 1]; /* each row at i * MAXN: the kernels read a row from its start, wherever it lies */
    for (int i = 0; i <= N; i++)
        start[i] = i * MAXN;
    memset(slow, 0xff, sizeof slow);
    memset(fast, 0xff, sizeof fast);
    for (int i = 0; i < N; i++)
        mc_strain_disp_item(DEM_EFFECT_CLASSICAL | DEM_EFFECT_MC_STRAIN, i, N, start, 2, x, radius, mat, pairmat, count,
                            list, NW, wall_int, wall_real, fn, wall_fn, slow, wslow, ride, in_count, own_start,
                            in_start, in_pair);
    ref_mc_strain_disp_f64(DEM_EFFECT_CLASSICAL | DEM_EFFECT_MC_STRAIN, N, start, 2, x, radius, mat, pairmat, count,
                           list, NW, wall_int, wall_real, fn, wall_fn, fast, wfast, ride, in_count, own_start, in_start,
                           in_pair);
    int touching = 0;
    for (int k = 0; k < 6; k++) {
        assert_memory_equal(&slow[k], &fast[k], sizeof(real));
        touching += slow[k] != 0;
    }
    assert_int_equal(touching, 6); /* all six contacts of particle 0 touch and feel the others */
    assert_memory_equal(wslow, wfast, 2 * sizeof(real));
    assert_true(wslow[0] != 0 && wslow[1] != 0); /* both walls touch particle 0 */
    for (int i = 1; i < N; i++) /* a neighbour: one particle contact (and maybe a wall) */
        assert_memory_equal(&slow[i * MAXN], &fast[i * MAXN], sizeof(real));
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_slow_path_equals_fast_path)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
