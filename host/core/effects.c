/* effects.c - which physics a run has: the effect mask (dem_effects.h) and its bits' names, and the settings of the
 * multi-contact laws (MC-stress's convention, MC-strain's iteration and reach, and its statistics). */
#include "sim.h"
#include "dem_layout.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

int dem_set_effects(dem_sim *s, unsigned effects)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (effects & ~(unsigned)(DEM_EFFECT_ALL | DEM_EFFECT_TEST_LAWS))
        return sim_fail(s, DEM_ERR_ARG, "effect mask 0x%x has bits of effects this version does not have", effects);
    if ((effects & DEM_EFFECT_MC_STRESS) && (effects & DEM_EFFECT_MC_STRAIN))
        return sim_fail(s, DEM_ERR_ARG, "mc_stress and mc_strain are two alternative normal laws: choose one");
    if ((effects & DEM_EFFECT_THORNTON_NING) && (effects & (DEM_EFFECT_MC_STRESS | DEM_EFFECT_MC_STRAIN)))
        return sim_fail(s, DEM_ERR_ARG, "thornton_ning and the multi-contact laws are alternative normal laws: choose one");
    if ((effects & DEM_EFFECT_THORNTON_NING) && (effects & DEM_EFFECT_PATCHES))
        return sim_fail(s, DEM_ERR_ARG, "thornton_ning does not act at membrane patches yet (their contacts keep no "
                                        "normal history): use hertz there");
    if ((effects & DEM_EFFECT_MDR) && (effects & (DEM_EFFECT_MC_STRESS | DEM_EFFECT_MC_STRAIN | DEM_EFFECT_THORNTON_NING)))
        return sim_fail(s, DEM_ERR_ARG, "mdr, thornton_ning and the multi-contact laws are alternative normal laws: choose one");
    if ((effects & DEM_EFFECT_MDR) && (effects & DEM_EFFECT_PATCHES))
        return sim_fail(s, DEM_ERR_ARG, "mdr does not act at membrane patches (its contacts are spheres pressed on "
                                        "flats: pairs and walls)");
    if ((effects & DEM_EFFECT_ADHESION) && !(effects & DEM_EFFECT_THORNTON_NING))
        return sim_fail(s, DEM_ERR_ARG, "adhesion is thornton_ning's JKR adhesion: list thornton_ning too (mdr has its "
                                        "own, from surface_energy)");
    if ((effects & DEM_EFFECT_ROLLING) && !(effects & DEM_EFFECT_FRICTION))
        return sim_fail(s, DEM_ERR_ARG, "rolling resistance acts on spins, which only friction gives: list friction too");
    if ((effects & DEM_EFFECT_ROLLING) && (effects & DEM_EFFECT_PATCHES))
        return sim_fail(s, DEM_ERR_ARG, "rolling resistance does not act at membrane patches yet");
    if ((effects & DEM_EFFECT_ROLLING_SPRING) && !(effects & DEM_EFFECT_ROLLING))
        return sim_fail(s, DEM_ERR_ARG, "rolling_spring is a model of rolling resistance: list rolling too");
    if (!(effects & DEM_EFFECT_HERTZ))
        return sim_fail(s, DEM_ERR_ARG, "the effect mask must contain DEM_EFFECT_HERTZ (the contact law itself)");
    s->effects = effects;
    return 0;
}

unsigned dem_effects(const dem_sim *s) { return s->effects; }

int dem_set_mc_stress_convention(dem_sim *s, unsigned convention)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (convention & ~(unsigned)DEM_MCS_MASK)
        return sim_fail(s, DEM_ERR_ARG, "MC-stress convention 0x%x has bits other than DEM_MCS_*", convention);
    if ((convention & DEM_MCS_SCALE_TEXT) && (convention & DEM_MCS_SCALE_TRACE))
        return sim_fail(s, DEM_ERR_ARG, "MC-stress convention: choose one scale (text or trace), not both");
    s->mc.stress_conv = convention;
    return 0;
}

unsigned dem_mc_stress_convention(const dem_sim *s) { return s->mc.stress_conv; }

void dem_mc_stress_convention_string(unsigned c, char *buf, size_t len)
{
    snprintf(buf, len, "own_contact %s, lever %s, scale %s", (c & DEM_MCS_OWN_IN) ? "in" : "out",
             (c & DEM_MCS_LEVER_CENTRES) ? "centres" : "contact_point",
             (c & DEM_MCS_SCALE_TRACE) ? "mean_trace" : (c & DEM_MCS_SCALE_TEXT) ? "text" : "mean_pressure");
}

int dem_set_mc_strain(dem_sim *s, int max_iterations, double tolerance)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (max_iterations < 0 || max_iterations > 10000 || !(tolerance > 0) || !isfinite(tolerance))
        return sim_fail(s, DEM_ERR_ARG, "MC-strain: iterations in 0..10000 (0 = lagged) and tolerance > 0 (got %d, %g)",
                        max_iterations, tolerance);
    s->mc.max_iter = max_iterations;
    s->mc.tol = tolerance;
    return 0;
}

int dem_set_mc_strain_reach(dem_sim *s, double factor)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (!(factor >= 1 && factor <= 2))
        return sim_fail(s, DEM_ERR_ARG, "MC-strain contact distance factor must be in [1, 2] (got %g)", factor);
    s->mc.reach = factor;
    return 0;
}

void dem_mc_stats_get(const dem_sim *s, dem_mc_stats *st) { *st = sim_stepped(s)->mc.stats; }

/* by bit position; the convention bits (7..11, dem_effects.h) and the host's bits (18..20, 25) have no name */
static const char *const effect_names[DEM_EFFECT_COUNT] = {"hertz", "damping", "friction", "gravity", "walls",
                                                           "mc_stress", "mc_strain", NULL, NULL, NULL, NULL, NULL,
                                                           "springs", "pressure", "bending", "patches", "riders", "constraints",
                                                           NULL, NULL, NULL, "thornton_ning", "rolling",
                                                           "rolling_spring", "mdr", NULL, "adhesion"};

const char *dem_effect_name(int bit) { return bit >= 0 && bit < DEM_EFFECT_COUNT ? effect_names[bit] : NULL; }

void dem_effects_string(unsigned effects, char *buf, size_t len)
{
    size_t at = 0;
    buf[0] = 0;
    for (int k = 0; k < DEM_EFFECT_COUNT && at < len; k++)
        if (effect_names[k] && (effects & (1u << k)))
            at += (size_t)snprintf(buf + at, len - at, "%s%s", at ? "+" : "", effect_names[k]);
}

int dem_effect_bit(const char *name)
{
    for (int k = 0; k < DEM_EFFECT_COUNT; k++)
        if (effect_names[k] && !strcmp(name, effect_names[k]))
            return k;
    return DEM_ERR_ARG;
}
