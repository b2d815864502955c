/* energy.c - energy bookkeeping on the host, in double precision, from the backend's current state.
 * Elastic: Hertz normal energy 8/15 E* sqrt(r*) d^(5/2) per contact (the integral of Eq. 3's elastic part), walls
 * included, and k e^2 / 2 per spring (e its extension); the Mindlin tangential spring's energy is not counted (zero
 * when mu = 0). */
#include "sim.h"
#include "dem_layout.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>


static double pair_estar(const dem_sim *s, int a, int b)
{
    const dem_material *p = &s->mats[a], *q = &s->mats[b];
    return 1 / ((1 - p->poisson * p->poisson) / p->young + (1 - q->poisson * q->poisson) / q->young);
}

/* raw reals of the run's precision to double */
/* whether particle i rides on wall k (the packed table the kernels get) */
static int rides_on(const dem_sim *s, int i, int k)
{
    return (s->setup.effects & DEM_EFFECT_RIDERS) && s->setup.ride && ((s->setup.ride[i] >> k) & 1u);
}

static void widen(const void *raw, double *dst, size_t count, int rs)
{
    for (size_t k = 0; k < count; k++)
        dst[k] = rs == 8 ? ((const double *)raw)[k] : (double)((const float *)raw)[k];
}

/* Everything a series row needs in one device synchronisation (positions, velocities, spins, rows, wall forces):
 * each blocking read costs a wake-up of the device's threads, and a series every step made thirteen of them. */
static int energy_of(dem_sim *s, dem_energy_t *en, double *wall_force);

/* the closest point of a triangle, as the kernels compute it (common/patch.h through reference/patch.c, in double) */
void dem_patch_probe_f64(int n, const double *p, const double *tri_x, int *kind, int *index, double *w, double *point);

/* Sphere-patch contacts: each touching slot of the patch rows (common/patch_contacts.h), its overlap from the
 * positions x, 8/15 E* sqrt(r) d^(5/2) as for a wall (r* = the sphere's radius) */
static int patch_energy(dem_sim *s, const double *x, dem_energy_t *en)
{
    int n = s->n, maxp = DEM_CORE(s->be)->maxp, e = 0;
    int *cnt = sim_buffer_get(s, BUF_PCOUNT, &e), *list = sim_buffer_get(s, BUF_PLIST, &e);
    unsigned char *touch = sim_buffer_get(s, BUF_PTOUCH, &e);
    for (int i = 0; !e && i < n; i++)
        for (int k = 0; k < cnt[i]; k++) {
            if (!touch[(size_t)i * maxp + k])
                continue;
            int t = list[(size_t)i * maxp + k], kind, index;
            double tx[9], wgt[3], q[3];
            for (int v = 0; v < 3; v++)
                memcpy(tx + 3 * v, x + 3 * s->tri[3 * t + v], sizeof(double) * 3);
            dem_patch_probe_f64(1, x + 3 * i, tx, &kind, &index, wgt, q);
            double d = s->radius[i] - sqrt((x[3 * i] - q[0]) * (x[3 * i] - q[0]) + (x[3 * i + 1] - q[1]) *
                                           (x[3 * i + 1] - q[1]) + (x[3 * i + 2] - q[2]) * (x[3 * i + 2] - q[2]));
            if (d > 0)
                en->elastic += 8.0 / 15.0 * pair_estar(s, s->mat[i], s->mat[s->tri[3 * t]]) * sqrt(s->radius[i]) *
                               (d * d * sqrt(d));
            en->patch_contacts++;
        }
    free(cnt), free(list), free(touch);
    return e;
}

int dem_energy(dem_sim *s, dem_energy_t *en) { return energy_of(s, en, NULL); }

int dem_sample_get(dem_sim *s, dem_sample *out)
{
    memset(out, 0, sizeof *out);
    return energy_of(s, &out->energy, out->wall_force);
}

static int energy_of(dem_sim *s, dem_energy_t *en, double *wall_force)
{
    memset(en, 0, sizeof *en);
    if (!s->started)
        return sim_fail(s, DEM_ERR_STATE, "dem_start first");
    int n = s->n, rs = s->setup.real_size;
    size_t n3 = 3 * (size_t)n, lb = dem_field_bytes(s, DEM_FIELD_NBR_LIST);
    /* one scratch block kept in the simulation (a series every step allocated and freed it every step) */
    size_t need = 3 * n3 * sizeof(double) + sizeof(int) * (size_t)n + lb + 3 * n3 * (size_t)rs +
                  3 * DEM_MAX_WALLS * (size_t)rs + 64;
    if (need > s->scratch_bytes) {
        free(s->scratch);
        s->scratch = malloc(need);
        s->scratch_bytes = s->scratch ? need : 0;
    }
    if (!s->scratch)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    double *x = (double *)s->scratch, *v = x + n3, *w = v + n3;
    int *cnt = (int *)(w + n3), *list = cnt + n;
    unsigned char *raw = (unsigned char *)list + lb;
    int e = 0;
    if (!e) {
        dem_field f[6] = {DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W, DEM_FIELD_NBR_COUNT, DEM_FIELD_NBR_LIST,
                          DEM_FIELD_WALL_FORCE};
        void *dst[6] = {raw, raw + n3 * rs, raw + 2 * n3 * rs, cnt, list, raw + 3 * n3 * rs};
        size_t bytes[6] = {n3 * rs, n3 * rs, n3 * rs, sizeof(int) * n, dem_field_bytes(s, DEM_FIELD_NBR_LIST),
                           3 * (size_t)s->nwalls * rs};
        if (dem_stage_read_fields(s->ops, s->be, wall_force && s->nwalls ? 6 : 5, f, dst, bytes))
            e = sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
    }
    if (!e) {
        widen(raw, x, n3, rs);
        widen(raw + n3 * rs, v, n3, rs);
        widen(raw + 2 * n3 * rs, w, n3, rs);
        if (wall_force)
            widen(raw + 3 * n3 * rs, wall_force, 3 * (size_t)s->nwalls, rs);
    }

    for (int i = 0; !e && i < n; i++) {
        double m = sim_mass(s, i), r = s->radius[i], I = sim_inertia(s, i);
        unsigned fl = s->pflags[i];
        double v2 = v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2];
        double w2 = w[3 * i] * w[3 * i] + w[3 * i + 1] * w[3 * i + 1] + w[3 * i + 2] * w[3 * i + 2];
        if (!(fl & DEM_PARTICLE_FIXED)) {
            en->kinetic += 0.5 * m * v2;
            if (s->effects & DEM_EFFECT_GRAVITY)
                en->potential -= m * (s->gravity[0] * x[3 * i] + s->gravity[1] * x[3 * i + 1] + s->gravity[2] * x[3 * i + 2]);
        }
        if (!(fl & (DEM_PARTICLE_FIXED | DEM_PARTICLE_NO_ROTATION)))
            en->kinetic += 0.5 * I * w2;
        for (int k = 0; k < cnt[i]; k++) {
            int j = list[i * s->maxn + k];
            if (j <= i)
                continue;
            double d[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
            double delta = r + s->radius[j] - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (delta > 0) {
                double rs = r * s->radius[j] / (r + s->radius[j]);
                en->elastic += 8.0 / 15.0 * pair_estar(s, s->mat[i], s->mat[j]) * sqrt(rs) * (delta * delta * sqrt(delta));
                en->contacts++;
            }
        }
        for (int k = 0; k < s->nwalls; k++) {
            if (rides_on(s, i, k)) /* a rider does not touch its wall (contact_geometry.h, wall_met) */
                continue;
            const dem_wall *wl = &s->walls[k];
            double delta = dem_wall_overlap(wl, s->wall_pos[k], x + 3 * i, r, NULL); /* the kernels' geometry */
            if (delta > 0) {
                en->elastic += 8.0 / 15.0 * pair_estar(s, s->mat[i], wl->material) * sqrt(r) * (delta * delta * sqrt(delta));
                en->wall_contacts++;
            }
        }
    }
    for (int k = 0; !e && k < s->nsprings; k++) { /* springs: k (|rho| - rho0)^2 / 2 */
        int a = s->spring_ij[2 * k], b = s->spring_ij[2 * k + 1];
        double d2 = 0, r2 = 0, rest = s->spring_kr[3 * k + 1];
        for (int q = 0; q < 3; q++) {
            d2 += (x[3 * a + q] - x[3 * b + q]) * (x[3 * a + q] - x[3 * b + q]);
            r2 += (s->x[3 * a + q] - s->x[3 * b + q]) * (s->x[3 * a + q] - s->x[3 * b + q]);
        }
        double ext = sqrt(d2) - (rest < 0 ? sqrt(r2) : rest);
        en->elastic += 0.5 * s->spring_kr[3 * k] * ext * ext;
    }
    if (!e && (s->setup.effects & DEM_EFFECT_PATCHES) && s->npatch)
        e = patch_energy(s, x, en);
    en->total = en->kinetic + en->elastic + en->potential;
    return e;
}
