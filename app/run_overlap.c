/* run_overlap.c - how deep the particles went into each other during a run, and whether that is beyond what the
 * contact model is valid for (pressed compacts; docs/design.md "Lagged MC-strain rings").
 *
 * At every frame `dem run` measures, over the particle pairs of the neighbour rows, the largest overlap / the
 * smaller radius and the mean over the touching pairs, keeps the largest of each with when they happened, reports
 * them at the end, and warns where a model was used beyond its range:
 *   - classical Hertz-Mindlin beyond RUN_HERTZ_RANGE (10 %) of a radius: Hertz's law is a small-strain law (its
 *     contact radius sqrt(r* delta) small against r; at 10 % it is a third of the smaller radius between like
 *     spheres); dense compaction is what seed 000's multi-contact models are for;
 *   - MC-stress and MC-strain beyond RUN_MC_RANGE (25 %): seed 000 validates them up to d/r = 0.4 between plates (20 %
 *     at each contact) and in packings whose largest overlap reaches 19.5 % (the 514 hydrogels at 13.4 % strain);
 *   - lagged MC-strain once the mean overlap passed the overlap at which its loop gain reaches 1 for a material of
 *     the run (run_mc_lag_overlap; the smallest over the materials with gamma > 0): it rings there.
 * At the same frames, how close dt came to the explicit step's stability bound at those overlaps (dem_stability_get:
 * contacts stiffen as they go deeper), reported at the end and warned about above DEM_STABILITY_LIMIT.
 * Scenes with membranes are left out (their vertex spheres overlap each other by design, seed 001's MSS_particle). */
#include "run.h"
#include "dem_debug.h" /* the neighbour rows */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* app/run.c derives it ("Lagged MC-strain"): delta_1 / r = 2 (4 pi (1 - nu) / (2 (z - 1) gamma (3 - 2 nu)))^2 */
double run_mc_lag_overlap(double gamma, double nu)
{
    if (!(gamma > 0))
        return INFINITY;
    double c = 4 * M_PI * (1 - nu) / (2 * (MC_LAG_CONTACTS - 1) * gamma * (3 - 2 * nu));
    return 2 * c * c;
}

#define RUN_HERTZ_RANGE 0.10
#define RUN_MC_RANGE 0.25

int overlap_frame_scan(overlap_watch *w, dem_sim *s, const long *ids, const unsigned char *own, overlap_frame *f)
{
    memset(f, 0, sizeof *f);
    f->wi = f->wj = -1;
    exact_clear(&f->sum);
    int n = dem_count(s), slots = dem_neighbor_capacity(s);
    if (n < 2 || slots <= 0)
        return 0;
    size_t need = (size_t)slots; /* the rows packed: all of them together (DEM_FIELD_NBR_START) */
    if (need > w->cap) { /* each buffer grown on its own: a split run's parts change both counts */
        int *l = realloc(w->list, need * sizeof(int));
        if (!l)
            return -1; /* out of host memory: this frame is not measured */
        w->list = l, w->cap = need;
    }
    if ((size_t)n > w->ncap) {
        double *x = realloc(w->x, 3 * (size_t)n * sizeof(double));
        if (x)
            w->x = x;
        int *c = x ? realloc(w->count, (2 * (size_t)n + 1) * sizeof(int)) : NULL; /* the counts, then the starts */
        if (!c)
            return -1;
        w->count = c, w->ncap = (size_t)n;
    }
    int *start = w->count + n;
    if (dem_get_raw(s, DEM_FIELD_NBR_COUNT, w->count, (size_t)n * sizeof(int)) ||
        dem_get_raw(s, DEM_FIELD_NBR_START, start, ((size_t)n + 1) * sizeof(int)) ||
        dem_get_raw(s, DEM_FIELD_NBR_LIST, w->list, (size_t)slots * sizeof(int)) || dem_get_field(s, DEM_FIELD_X, w->x))
        return -1;
    for (int i = 0; i < n; i++) {
        if (own && !own[i])
            continue;
        double ri = dem_particle_radius(s, i);
        for (int k = 0; k < w->count[i] && start[i] + k < slots; k++) {
            int j = w->list[start[i] + k];
            if (j <= i || j >= n)
                continue;
            double rj = dem_particle_radius(s, j), d[3];
            for (int q = 0; q < 3; q++)
                d[q] = w->x[3 * j + q] - w->x[3 * i + q];
            double ov = (ri + rj - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])) / (ri < rj ? ri : rj);
            if (ov > 0) {
                exact_add_double(&f->sum, ov);
                f->touching++;
                long gi = ids ? ids[i] : i, gj = ids ? ids[j] : j;
                if (ov > f->worst || (ov == f->worst && (gi < f->wi || (gi == f->wi && gj < f->wj))))
                    f->worst = ov, f->wi = gi, f->wj = gj;
            }
        }
    }
    return 0;
}

void overlap_watch_add(overlap_watch *w, const overlap_frame *f, const dem_stability *st, double t)
{
    double mean = f->touching ? exact_to_double(&f->sum) / (double)f->touching : 0;
    w->sampled = 1;
    if (f->worst > w->largest)
        w->largest = f->worst, w->largest_t = t, w->largest_i = (int)f->wi, w->largest_j = (int)f->wj;
    if (mean > w->mean)
        w->mean = mean, w->mean_t = t;
    if (st && st->ratio > w->stab.ratio)
        w->stab = *st, w->stab_t = t;
}

void overlap_watch_sample(overlap_watch *w, dem_sim *s)
{
    overlap_frame f;
    dem_stability st;
    if (dem_count(s) < 2 || dem_neighbor_capacity(s) <= 0 || overlap_frame_scan(w, s, NULL, NULL, &f))
        return;
    overlap_watch_add(w, &f, dem_stability_get(s, &st) ? NULL : &st, dem_time(s));
}

void overlap_watch_report(const overlap_watch *w, const scene *sc, const scene_run *run, int info)
{
    if (!w->sampled)
        return;
    if (info && w->largest_i < 0)
        fprintf(stderr, "dem: overlaps at the frames: no two particles overlapped\n");
    else if (info)
        fprintf(stderr, "dem: overlaps at the frames: largest %.3g %% of the smaller radius (t = %.6g s, particles %d "
                        "and %d), largest mean over the touching pairs %.3g %% (t = %.6g s)\n", 100 * w->largest,
                w->largest_t, w->largest_i, w->largest_j, 100 * w->mean, w->mean_t);
    const dem_stability *st = &w->stab;
    if (info && st->ratio > 0) /* a frame with contacts (the watch starts zeroed) */
        fprintf(stderr, "dem: time step at the frames' overlaps: at most %.3g of the estimated stability bound "
                        "(t = %.6g s, particle %d, %d contacts, its %s mode: omega dt %.3g, damping ratio %.3g)\n",
                st->ratio, w->stab_t, st->particle, st->contacts, st->tangential ? "tangential-rotational" : "normal",
                st->omega_dt, st->zeta);
    if (st->ratio > DEM_STABILITY_LIMIT)
        fprintf(stderr, "dem: warning: %s: at t = %.6g s the contacts had stiffened to %.3g of the estimated stability "
                        "bound of the step, above %.3g, beyond which pressed packings were measured to stay stirred "
                        "instead of coming to rest: the results there may carry numerical heat (see the kinetic energy "
                        "in the series); dt = %.3g s (%.2g of this one) keeps it at %.2g (docs/design.md \"The time "
                        "step under compaction\")\n",
                sc->path, w->stab_t, st->ratio, DEM_STABILITY_LIMIT, st->dt_advice, DEM_STABILITY_TARGET / st->ratio,
                DEM_STABILITY_TARGET);
    int mc = (run->effects & (DEM_EFFECT_MC_STRESS | DEM_EFFECT_MC_STRAIN)) != 0;
    double range = mc ? RUN_MC_RANGE : RUN_HERTZ_RANGE;
    /* MDR is written for large apparent overlaps (each sphere pressed on a flat, Part II's confined bulk; its flats'
     * own limit is 95 % of a radius a side, docs/laws/mdr.md (M3)): no small-strain range to warn of */
    if (w->largest > range && !(run->effects & DEM_EFFECT_MDR))
        fprintf(stderr, "dem: warning: %s: particles overlapped by up to %.3g %% of the smaller radius (t = %.6g s), "
                        "beyond the %.0f %% %s\n", sc->path, 100 * w->largest, w->largest_t, 100 * range,
                mc ? "up to which seed 000 validates the multi-contact models (d/r = 0.4 between plates, 20 % at each "
                     "contact): the results beyond are the model's extrapolation"
                   : "within which Hertz's small-strain law holds (its contact radius small against the radius): "
                     "for dense compaction use a multi-contact model (--model mc_stress or mc_strain_iterated). "
                     "Expected where a compression is run classically to be set against those models: make run's "
                     "scenes/hydrogel_514.yaml reaches 19 %, and that gap is seed 000's point");
    if ((run->effects & DEM_EFFECT_MC_STRAIN) && run->mc_cap == 0) {
        double d1 = INFINITY;
        for (unsigned q = 0; q < sc->f->materials_count; q++) {
            double d = run_mc_lag_overlap(sc->f->materials[q].gamma, sc->f->materials[q].poisson);
            d1 = d < d1 ? d : d1;
        }
        if (w->mean > d1)
            fprintf(stderr, "dem: warning: %s: the contacts' mean overlap reached %.3g %% of a radius (t = %.6g s), "
                            "past the %.3g %% at which lagged MC-strain's loop gain reaches 1: it rings there "
                            "(docs/multicontact.md); iterate it (--model mc_strain_iterated)\n", sc->path,
                    100 * w->mean, w->mean_t, 100 * d1);
    }
}

void overlap_watch_free(overlap_watch *w)
{
    free(w->list);
    free(w->x);
    free(w->count);
}
