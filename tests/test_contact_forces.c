/* test_contact_forces.c - the kernels contact_pairs, contact_forces and their reference twins, on every
 * backend x precision (tests/test_util.h: FOR_EACH_BACKEND): static contacts at a known overlap give the Hertz
 * force of seed 000 Eq. 3, F = 4/3 E* sqrt(r*) delta^(3/2) with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, computed
 * here: between two spheres (equal, and unequal along a diagonal), a sphere on a plane, a sphere inside a cylinder
 * (a wall: r* = r), and a sphere on a rigid plane (young = inf: E* = E / (1 - nu^2) of the particle alone). At rest there is no damping and no tangential force, so the force is along the normal, the
 * partner's is its exact negation, and there is no torque. Tolerance: the overlap is a difference of coordinates,
 * so its relative rounding is about eps (r_a + r_b) / delta: the force is checked to 16 times that. OpenCL = the
 * reference bit for bit in each precision. Collisions in time: tests/test_hertz_collision.c, friction:
 * tests/test_friction.c, restitution: tests/test_restitution.c. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const dem_material grain = {2500, 1e7, 0.3, 0.5, 0.4}, steel = {7800, 2e8, 0.28, 0.5, 0.3};

static double estar(const dem_material *a, const dem_material *b)
{
    return 1 / ((1 - a->poisson * a->poisson) / a->young + (1 - b->poisson * b->poisson) / b->young);
}

static double hertz(double es, double rs, double delta) { return 4.0 / 3.0 * es * sqrt(rs) * delta * sqrt(delta); }

typedef struct {
    int kind;           /* 0 pair, 1 plane, 2 cylinder, 3 rigid plane */
    double r1, r2, delta, dir[3];
} scene;

static dem_sim *build(void *ctx)
{
    const scene *sc = ctx;
    dem_sim *s = dem_create();
    int g = dem_add_material(s, &grain), st = dem_add_material(s, &steel);
    if (sc->kind == 3) { /* a rigid wall material: no density, infinite stiffness */
        dem_material rigid = steel;
        rigid.young = INFINITY, rigid.density = 0;
        st = dem_add_material(s, &rigid);
        assert_true(st >= 0);
    }
    if (sc->kind == 0) { /* sphere 1 at the origin, sphere 2 along dir at r1 + r2 - delta */
        double d = sc->r1 + sc->r2 - sc->delta, x2[3];
        for (int k = 0; k < 3; k++)
            x2[k] = d * sc->dir[k];
        dem_add_particle(s, (double[3]){0, 0, 0}, NULL, sc->r1, g);
        dem_add_particle(s, x2, NULL, sc->r2, g);
    } else if (sc->kind == 1 || sc->kind == 3) { /* on the floor z = 0 */
        dem_add_particle(s, (double[3]){0.001, -0.002, sc->r1 - sc->delta}, NULL, sc->r1, g);
        dem_add_wall(s, &(dem_wall){.kind = DEM_WALL_PLANE, .material = st, .normal = {0, 0, 1}});
    } else { /* inside a cylinder of radius 0.02 m along z, pressed against it along +x */
        dem_add_particle(s, (double[3]){0.02 - sc->r1 + sc->delta, 0, 0.003}, NULL, sc->r1, g);
        dem_add_wall(s, &(dem_wall){.kind = DEM_WALL_CYLINDER, .material = st, .normal = {0, 0, 1}, .radius = 0.02});
    }
    dem_set_domain(s, (double[3]){-0.03, -0.03, -0.03}, (double[3]){0.03, 0.03, 0.03});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION | DEM_EFFECT_WALLS);
    dem_set_dt(s, 1e-7);
    return s;
}

static void check(dem_sim *s, const backend_case *bc, void *ctx)
{
    const scene *sc = ctx;
    int n = dem_count(s);
    double f[6], t[6], want[3];
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0); /* dem_start evaluates the forces once */
    assert_int_equal(dem_get_field(s, DEM_FIELD_TORQUE, t), 0);
    double es, rs, cond;
    if (sc->kind == 0) {
        es = estar(&grain, &grain), rs = sc->r1 * sc->r2 / (sc->r1 + sc->r2), cond = (sc->r1 + sc->r2) / sc->delta;
        for (int k = 0; k < 3; k++)
            want[k] = -hertz(es, rs, sc->delta) * sc->dir[k]; /* sphere 1 is pushed away from sphere 2 */
    } else {
        es = sc->kind == 3 ? grain.young / (1 - grain.poisson * grain.poisson) : estar(&grain, &steel);
        rs = sc->r1, cond = (sc->kind == 2 ? 0.02 : sc->r1) / sc->delta;
        double F = hertz(es, rs, sc->delta);
        want[0] = sc->kind == 2 ? -F : 0, want[1] = 0, want[2] = sc->kind == 2 ? 0 : F;
    }
    double F = sqrt(want[0] * want[0] + want[1] * want[1] + want[2] * want[2]), tol = 16 * bc->eps * cond;
    printf("  %s, %s: |F| %.9g N (closed form %.9g N), relative error %.2g (bound %.2g)\n", bc->name,
           sc->kind == 0 ? "pair" : sc->kind == 1 ? "plane" : sc->kind == 2 ? "cylinder" : "rigid plane",
           sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]), F,
           sqrt(pow(f[0] - want[0], 2) + pow(f[1] - want[1], 2) + pow(f[2] - want[2], 2)) / F, tol);
    for (int k = 0; k < 3; k++) {
        if (!(fabs(f[k] - want[k]) <= tol * F))
            fail_msg("%s: force component %d %.17g N, closed form %.17g N", bc->name, k, f[k], want[k]);
        assert_true(t[k] == 0); /* no tangential force at rest, hence no torque */
        if (n == 2) {
            assert_true(f[3 + k] == -f[k]); /* the partner's force is the exact negation */
            assert_true(t[3 + k] == 0);
        }
    }
    if (n == 1) { /* and the wall receives the opposite */
        double w[3];
        assert_int_equal(dem_wall_force(s, 0, w), 0);
        for (int k = 0; k < 3; k++)
            assert_true(w[k] == -f[k]);
    }
}

static void run_all(scene sc)
{
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build, 0, check, &sc);
}

static void test_equal_pair(void **st)
{
    (void)st;
    run_all((scene){0, 0.005, 0.005, 5e-5, {1, 0, 0}});
}

static void test_unequal_pair_diagonal(void **st)
{
    (void)st;
    double a = 1 / sqrt(3.0);
    run_all((scene){0, 0.005, 0.002, 3e-5, {a, -a, a}});
}

static void test_sphere_on_plane(void **st)
{
    (void)st;
    run_all((scene){1, 0.004, 0, 2e-5, {0, 0, 1}});
}

static void test_sphere_in_cylinder(void **st)
{
    (void)st;
    run_all((scene){2, 0.004, 0, 2e-5, {1, 0, 0}});
}

static void test_sphere_on_rigid_plane(void **st)
{
    (void)st;
    run_all((scene){3, 0.004, 0, 2e-5, {0, 0, 1}});
}

/* A rigid material is for walls: a particle of it is refused. */
static void test_rigid_is_for_walls(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    dem_material rigid = steel;
    rigid.young = INFINITY, rigid.density = 0;
    int m = dem_add_material(s, &rigid);
    assert_true(m >= 0);
    assert_int_equal(dem_add_particle(s, (double[3]){0, 0, 0}, NULL, 0.001, m), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "rigid"));
    rigid.young = -INFINITY;
    assert_int_equal(dem_add_material(s, &rigid), DEM_ERR_ARG);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_equal_pair),
        cmocka_unit_test(test_unequal_pair_diagonal),
        cmocka_unit_test(test_sphere_on_plane),
        cmocka_unit_test(test_sphere_in_cylinder),
        cmocka_unit_test(test_sphere_on_rigid_plane),
        cmocka_unit_test(test_rigid_is_for_walls),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
