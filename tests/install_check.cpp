// install_check.cpp - a C++ program built against an installed libdem by tests/install_check.sh, once with the shared
// library and once with the static one: the public headers must compile as C++ (with -Wall -Wextra -pedantic
// -Werror) and link without an extern "C" of the program's own, and the calls must behave as dem.h says. It uses a
// function of each public header (dem.h, dem_effects.h, dem_membrane.h, dem_press.h) and the error rule: two spheres
// dropped in a box on the reference backend, a particle refused after the start, a mesh, a press query. Prints one
// line; exits non-zero, saying why, on any failure.
#include <dem.h>

#include <cmath>
#include <cstdio>

static int fail(const char *what, dem_sim *s)
{
    std::fprintf(stderr, "install_check.cpp: %s%s%s\n", what, s ? ": " : "", s ? dem_error(s) : "");
    if (s)
        dem_destroy(s);
    return 1;
}

int main()
{
    dem_sim *s = dem_create();
    if (!s)
        return fail("dem_create", nullptr);
    const dem_material glass = {2500, 65e9, 0.24, 0.98, 0.2, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    int m = dem_add_material(s, &glass);
    const double lo[3] = {0, 0, 0}, hi[3] = {0.02, 0.02, 0.02}, g[3] = {0, 0, -9.81};
    const double a[3] = {0.01, 0.01, 0.004}, b[3] = {0.0105, 0.01, 0.009};
    if (m != 0 || dem_add_box(s, lo, hi, m) != 0 || dem_add_particle(s, a, nullptr, 0.002, m) != 0 ||
        dem_add_particle(s, b, nullptr, 0.002, m) != 1)
        return fail("set-up", s);
    if (dem_add_particle(s, a, nullptr, -1, m) != DEM_ERR_ARG) // ids and errors share one return: negative = error
        return fail("a negative radius was not refused with DEM_ERR_ARG", s);
    if (dem_set_gravity(s, g) != DEM_OK || dem_set_effects(s, DEM_EFFECT_CLASSICAL) != DEM_OK)
        return fail("gravity, effects", s);
    dem_time_scales ts;
    if (dem_time_scales_get(s, 1.0, &ts) != DEM_OK || dem_set_dt(s, ts.recommended_dt) != DEM_OK)
        return fail("time step", s);
    dem_config c;
    dem_config_default(&c);
    c.backend = DEM_BACKEND_REFERENCE;
    if (dem_start(s, &c) != DEM_OK || dem_step(s, 300) != DEM_OK)
        return fail("run", s);
    if (dem_add_particle(s, a, nullptr, 0.001, m) != DEM_ERR_STATE)
        return fail("a particle added after dem_start was not refused with DEM_ERR_STATE", s);
    dem_energy_t e;
    if (dem_energy(s, &e) != DEM_OK || !std::isfinite(e.total) || !(e.kinetic > 0))
        return fail("energy", s);

    // dem_membrane.h
    dem_mesh mesh;
    char err[256];
    const dem_mesh_spec sphere = {DEM_MESH_SPHERE, {0, 0, 0}, 0.01, 0, 0.004};
    if (dem_mesh_make(&sphere, &mesh, err, sizeof err) != DEM_OK || mesh.nv < 12)
        return fail(err, s);
    int nv = mesh.nv;
    dem_mesh_free(&mesh);
    // dem_press.h: a box has no die
    int die = 0, other = 0;
    if (dem_density_walls(s, 0, &die, &other) != DEM_ERR_ARG || die != -1)
        return fail("dem_density_walls found a die in a box", s);

    std::printf("install_check.cpp: %s; %d particles at step %ld, energy %.6g J; a sphere mesh of %d vertices\n",
                dem_describe(s), dem_count(s), dem_step_index(s), e.total, nv);
    dem_destroy(s);
    return 0;
}
