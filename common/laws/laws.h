/* laws.h - the contact laws, one header each (law.h says what a law gives), and the one entry point per quantity
 * that every caller uses: law_force (particle pairs, walls, patches), law_elastic (the stress), law_energy and
 * law_energy_kept (the series rows, the host's energies), law_stiffness (the host's stability estimate).
 *
 * DEM_LAW_LIST is the registry: X(law, effect bit), the first law whose bit is in the effect mask applies. In a
 * kernel the mask is the constant DEM_EFFECTS, so the chain folds to the one law of the run; the reference and the
 * host take the same chain at run time. Hertz-Mindlin (DEM_EFFECT_HERTZ, in every mask: dem_set_effects) is last.
 * MC-stress and MC-strain exclude each other (dem_set_effects).
 *
 * Adding a law: its header here (#include) and its line in DEM_LAW_LIST; a law compiled only into a test build goes
 * under DEM_TEST_LAWS, with its effect bit (dem_effects.h).
 */
#ifndef DEM_LAWS_H
#define DEM_LAWS_H
#include "law.h"
#include "hertz_mindlin.h"
#include "mc_stress.h"
#include "mc_strain.h"
#include "thornton_ning.h"
#include "mdr.h"
#ifdef DEM_TEST_LAWS
#include "linear_spring.h"
#define DEM_TEST_LAW_LIST(X) X(linear_spring, DEM_EFFECT_TEST_SPRING)
#else
#define DEM_TEST_LAW_LIST(X)
#endif

#define DEM_LAW_LIST(X)                                                                                              \
    DEM_TEST_LAW_LIST(X)                                                                                             \
    X(mc_stress, DEM_EFFECT_MC_STRESS)                                                                               \
    X(mc_strain, DEM_EFFECT_MC_STRAIN)                                                                               \
    X(thornton_ning, DEM_EFFECT_THORNTON_NING)                                                                       \
    X(mdr, DEM_EFFECT_MDR)                                                                                           \
    X(hertz_mindlin, DEM_EFFECT_HERTZ)

/* every column a law names is one of the pair table's */
#ifndef __OPENCL_C_VERSION__
#define DEM_LAW_COLUMN_CHECK(col) _Static_assert((col) >= 0 && (col) < PM_STRIDE, "a law's column is off the pair table");
#define DEM_LAW_COLUMNS_CHECK(law, bit) LAW_COLUMNS_##law(DEM_LAW_COLUMN_CHECK)
DEM_LAW_LIST(DEM_LAW_COLUMNS_CHECK)
#undef DEM_LAW_COLUMNS_CHECK
#undef DEM_LAW_COLUMN_CHECK
#endif

/* The contact force on a (law.h: law_in, law_ctx) */
DEM_INLINE law_result law_force(unsigned fx, law_in c, law_ctx ctx)
{
#define DEM_LAW_CASE(law, bit)                                                                                       \
    if (fx & (bit))                                                                                                  \
        return law##_force(fx, c, ctx);
    DEM_LAW_LIST(DEM_LAW_CASE)
#undef DEM_LAW_CASE
    return hertz_mindlin_force(fx, c, ctx);
}

/* The elastic normal force at overlap delta (pm: the pair-table row), given the contact's law state st (law.h; 0 for a
 * law without) */
DEM_INLINE real law_elastic(unsigned fx, DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
#define DEM_LAW_CASE(law, bit)                                                                                       \
    if (fx & (bit))                                                                                                  \
        return law##_elastic(pm, rstar, delta, st);
    DEM_LAW_LIST(DEM_LAW_CASE)
#undef DEM_LAW_CASE
    return hertz_mindlin_elastic(pm, rstar, delta, st);
}

/* The elastic energy stored at overlap delta, given the contact's law state st (law.h; 0 for a law without) */
DEM_INLINE real law_energy(unsigned fx, DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
#define DEM_LAW_CASE(law, bit)                                                                                       \
    if (fx & (bit))                                                                                                  \
        return law##_energy(pm, rstar, delta, st);
    DEM_LAW_LIST(DEM_LAW_CASE)
#undef DEM_LAW_CASE
    return hertz_mindlin_energy(pm, rstar, delta, st);
}

/* The same, given the elastic force fel that law_force returned for this contact (law_result.fel) */
DEM_INLINE real law_energy_kept(unsigned fx, DEM_CONST_GLOBAL real *pm, real rstar, real delta, real fel, real st)
{
#define DEM_LAW_CASE(law, bit)                                                                                       \
    if (fx & (bit))                                                                                                  \
        return law##_energy_kept(pm, rstar, delta, fel, st);
    DEM_LAW_LIST(DEM_LAW_CASE)
#undef DEM_LAW_CASE
    return hertz_mindlin_energy_kept(pm, rstar, delta, fel, st);
}

/* Normal and tangential stiffness at overlap delta */
DEM_INLINE void law_stiffness(unsigned fx, DEM_CONST_GLOBAL real *pm, real rstar, real delta, real *kn, real *kt)
{
#define DEM_LAW_CASE(law, bit)                                                                                       \
    if (fx & (bit)) {                                                                                                \
        law##_stiffness(pm, rstar, delta, kn, kt);                                                                   \
        return;                                                                                                      \
    }
    DEM_LAW_LIST(DEM_LAW_CASE)
#undef DEM_LAW_CASE
    hertz_mindlin_stiffness(pm, rstar, delta, kn, kt);
}
#endif /* DEM_LAWS_H */
