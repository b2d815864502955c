/* test_particle_stress.c - the kernel stress_tensor (stress_trace is the same sum's trace, used by
 * MC-stress and checked in tests/test_multicontact.c) and its reference twin, on every backend x precision: the
 * particle stress of seed 000 Eq. 9, sigma_p = -(1/V_p) sum_c (r_p - a_c) f_H,c n_c (x) n_c (a_c = delta/2 for a
 * particle, delta for a wall; common/particle_stress.h), computed here for static contacts of known overlap: a
 * sphere pressed by a partner along a diagonal, and a sphere between the floor and a partner above it (two terms).
 * Tolerance as in tests/test_contact_forces.c (16 eps times the overlap's condition). OpenCL = the reference. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>

static const dem_material grain = {2500, 1e7, 0.3, 0.5, 0.4};

typedef struct {
    int floor;      /* 0: two spheres along dir; 1: sphere 0 on the floor, sphere 1 on top of it */
    double r0, r1, d01, dfloor, dir[3];
} scene;

static double es(void) { return 1 / (2 * (1 - grain.poisson * grain.poisson) / grain.young); }
static double hertz(double rs, double d) { return 4.0 / 3.0 * es() * sqrt(rs) * d * sqrt(d); }

static dem_sim *build(void *ctx)
{
    const scene *sc = ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &grain);
    double z0 = sc->floor ? sc->r0 - sc->dfloor : 0, c = sc->r0 + sc->r1 - sc->d01;
    dem_add_particle(s, (double[3]){0, 0, z0}, NULL, sc->r0, m);
    dem_add_particle(s, (double[3]){c * sc->dir[0], c * sc->dir[1], z0 + c * sc->dir[2]}, NULL, sc->r1, m);
    if (sc->floor)
        dem_add_wall(s, &(dem_wall){.kind = DEM_WALL_PLANE, .material = m, .normal = {0, 0, 1}});
    dem_set_domain(s, (double[3]){-0.03, -0.03, -0.03}, (double[3]){0.03, 0.03, 0.03});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_WALLS);
    dem_set_dt(s, 1e-7);
    return s;
}

/* adds -(1/V) arm F n (x) n to st[6] (xx yy zz xy xz yz) */
static void term(double *st, double r, double arm, double F, const double *n)
{
    double c = -arm * F / (4.0 / 3.0 * M_PI * r * r * r);
    st[0] += c * n[0] * n[0], st[1] += c * n[1] * n[1], st[2] += c * n[2] * n[2];
    st[3] += c * n[0] * n[1], st[4] += c * n[0] * n[2], st[5] += c * n[1] * n[2];
}

static void check(dem_sim *s, const backend_case *bc, void *ctx)
{
    const scene *sc = ctx;
    double got[12], want[12] = {0}, rs = sc->r0 * sc->r1 / (sc->r0 + sc->r1), F = hertz(rs, sc->d01);
    assert_int_equal(dem_get_field(s, DEM_FIELD_STRESS, got), 0);
    term(want, sc->r0, sc->r0 - 0.5 * sc->d01, F, sc->dir); /* n (x) n is the same for n and -n */
    term(want + 6, sc->r1, sc->r1 - 0.5 * sc->d01, F, sc->dir);
    double cond = (sc->r0 + sc->r1) / sc->d01;
    if (sc->floor) {
        term(want, sc->r0, sc->r0 - sc->dfloor, hertz(sc->r0, sc->dfloor), (double[3]){0, 0, 1});
        cond = fmax(cond, sc->r0 / sc->dfloor);
    }
    double scale = 0, worst = 0;
    for (int k = 0; k < 12; k++)
        scale = fmax(scale, fabs(want[k]));
    double tol = 16 * bc->eps * cond;
    for (int k = 0; k < 12; k++) {
        if (!(fabs(got[k] - want[k]) <= tol * scale))
            fail_msg("%s: stress component %d of particle %d: %.17g Pa, closed form %.17g Pa", bc->name, k % 6, k / 6,
                     got[k], want[k]);
        worst = fmax(worst, fabs(got[k] - want[k]) / scale);
    }
    assert_true(want[2] < 0 && got[2] < 0); /* compressive */
    printf("  %s, %s: sigma_zz of particle 0 %.9g Pa (closed form %.9g), worst relative error %.2g (bound %.2g)\n",
           bc->name, sc->floor ? "floor + partner" : "pair", got[2], want[2], worst, tol);
}

static void test_pair_diagonal(void **st)
{
    (void)st;
    double a = 1 / sqrt(3.0);
    scene sc = {0, 0.005, 0.003, 4e-5, 0, {a, a, -a}};
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build, 0, check, &sc);
}

static void test_floor_and_partner(void **st)
{
    (void)st;
    double a = 0.6, b = 0.8; /* partner above, off the vertical */
    scene sc = {1, 0.004, 0.004, 3e-5, 2e-5, {a, 0, b}};
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build, 0, check, &sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_diagonal),
        cmocka_unit_test(test_floor_and_partner),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
