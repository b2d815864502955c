/* energy.c - energy bookkeeping on the host, in double precision, from the backend's current state.
 * Elastic: Hertz normal energy 8/15 E* sqrt(r*) d^(5/2) per contact (the integral of Eq. 3's elastic part),
 * walls included; tangential spring energy is not counted (zero when mu = 0). */
#include "sim.h"
#include "dem_layout.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static double mass_of(const dem_sim *s, int i)
{
    double r = s->radius[i];
    return s->mats[s->mat[i]].density * 4.0 / 3.0 * M_PI * r * r * r;
}

static double pair_estar(const dem_sim *s, int a, int b)
{
    const dem_material *p = &s->mats[a], *q = &s->mats[b];
    return 1 / ((1 - p->poisson * p->poisson) / p->young + (1 - q->poisson * q->poisson) / q->young);
}

int dem_energy(dem_sim *s, dem_energy_t *en)
{
    memset(en, 0, sizeof *en);
    int n = s->n;
    double *x = malloc(sizeof(double) * 3 * n), *v = malloc(sizeof(double) * 3 * n),
           *w = malloc(sizeof(double) * 3 * n);
    int *cnt = malloc(sizeof(int) * n), *list = malloc(dem_field_bytes(s, DEM_FIELD_NBR_LIST) + 1);
    int e = (!x || !v || !w || !cnt || !list) ? sim_fail(s, DEM_ERR_NOMEM, "out of host memory") : 0;
    if (!e)
        e = dem_get_field(s, DEM_FIELD_X, x) || dem_get_field(s, DEM_FIELD_V, v) || dem_get_field(s, DEM_FIELD_W, w) ||
            dem_get_raw(s, DEM_FIELD_NBR_COUNT, cnt, sizeof(int) * n) ||
            dem_get_raw(s, DEM_FIELD_NBR_LIST, list, dem_field_bytes(s, DEM_FIELD_NBR_LIST));
    for (int i = 0; !e && i < n; i++) {
        double m = mass_of(s, i), r = s->radius[i], I = 0.4 * m * r * r;
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
                en->elastic += 8.0 / 15.0 * pair_estar(s, s->mat[i], s->mat[j]) * sqrt(rs) * pow(delta, 2.5);
                en->contacts++;
            }
        }
        for (int k = 0; k < s->nwalls; k++) {
            const dem_wall *wl = &s->walls[k];
            const double *p = s->wall_pos[k], *nn = wl->normal;
            double d[3] = {x[3 * i] - p[0], x[3 * i + 1] - p[1], x[3 * i + 2] - p[2]};
            double dn = d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2], delta;
            if (wl->kind == DEM_WALL_PLANE) {
                delta = r - dn;
            } else {
                double rad[3] = {d[0] - dn * nn[0], d[1] - dn * nn[1], d[2] - dn * nn[2]};
                delta = r + sqrt(rad[0] * rad[0] + rad[1] * rad[1] + rad[2] * rad[2]) - wl->radius;
            }
            if (delta > 0) {
                en->elastic += 8.0 / 15.0 * pair_estar(s, s->mat[i], wl->material) * sqrt(r) * pow(delta, 2.5);
                en->wall_contacts++;
            }
        }
    }
    en->total = en->kinetic + en->elastic + en->potential;
    free(x);
    free(v);
    free(w);
    free(cnt);
    free(list);
    return e;
}
