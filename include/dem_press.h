/* dem_press.h - a press in libdem: the die and the punches a relative density is measured between, whether a punch's
 * cup lies within the bore, the relative density, and how a servo stage held its force. The stages themselves
 * (dem_stage: velocities, servo forces, ends at a force, a distance or a density) are part of a wall (dem.h).
 * Installed with dem.h, which includes it; the error rule at the top of dem.h holds here too.
 */
#ifndef DEM_PRESS_H
#define DEM_PRESS_H
#include "dem.h"

#ifdef __cplusplus
extern "C" {
#endif

/* For a punch (plane wall): the die (the first cylinder wall whose axis is parallel to its normal) and the punch facing
 * it (the nearest plane wall with the opposite normal, on the particles' side) that dem_stage.until_density measures
 * between; -1 where there is none (then DEM_ERR_ARG). Valid as soon as the walls are added. */
DEM_API int dem_density_walls(const dem_sim *s, int wall, int *die, int *other);
/* Whether punch `wall`'s cup (dem_wall.cup_radius) lies within die `die`'s bore - the offset of the punch's point from
 * the die's axis plus the cup's radius at most the bore's radius - as the relative density, which counts the cup's
 * volume as the bore's, assumes: 1 (and 1 for a flat punch), else 0; DEM_ERR_ARG for a wall or die that is not
 * there. */
DEM_API int dem_cup_in_bore(const dem_sim *s, int wall, int die);
/* The relative density punch `wall` sees now (before dem_start: where the walls were added), as until_density
 * measures it; DEM_ERR_ARG without a die and a facing punch, or when a punch's cup does not lie within the bore. */
DEM_API int dem_relative_density(const dem_sim *s, int wall, double *rho);

/* How wall k's latest servo stage went (a P controller: it settles when gain x the stiffness of the wall's contacts
 * x dt is below 1; above it the force chatters about the target, the wall touching and leaving the particles in
 * turn, and the mean force it holds is off). Counted by this process from dem_start (a restored run counts anew). */
typedef struct {
    int stage;     /* the stage's index, -1 if none has run */
    double force;  /* its target [N] */
    long steps;    /* its steps run */
    long tail;     /* of them, the steps in its last tenth */
    double held;   /* the mean normal force the wall received over those [N] (NAN: none yet) */
    long chatter;  /* steps whose force error changed sign from the step before, both beyond 10 % of the target */
} dem_servo_stats;
DEM_API int dem_servo_stats_get(const dem_sim *s, int wall, dem_servo_stats *st);

#ifdef __cplusplus
}
#endif
#endif /* DEM_PRESS_H */
