/* damping.c - make bench-peer's damping match: the coefficientRestitution to give LIGGGHTS so that its Hertz
 * damping equals ours.
 *
 * Both codes damp a Hertz contact as f_d = -c sqrt(S m*) v (S = 2 E* sqrt(r* d), normal; k_t, tangential). LIGGGHTS
 * takes c = 2 sqrt(5/6) |beta| with beta = ln e / sqrt(ln^2 e + pi^2), the linear-spring formula; libdem solves the
 * Hertz collision for the c that rebounds at e (host/physics/restitution.c, docs/design.md). Handed the same e the two codes
 * damp differently; handed e_liggghts below, LIGGGHTS computes our c and both integrate the same equations.
 *
 * usage: damping E   prints one line of key=value pairs:
 *   c_dem            our c for e = E
 *   e_liggghts       the coefficientRestitution for which LIGGGHTS' c equals c_dem
 *   c_liggghts       LIGGGHTS' own c for e = E
 *   e_hertz_liggghts the restitution a Hertz collision really has under c_liggghts (what LIGGGHTS' e = E gives)
 */
#include "dem.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: damping RESTITUTION\n");
        return 2;
    }
    double e = strtod(argv[1], NULL);
    if (!(e > 0 && e < 1)) {
        fprintf(stderr, "damping: restitution must lie in (0, 1), got %s\n", argv[1]);
        return 2;
    }
    const double pi = 3.14159265358979323846, k = 2 * sqrt(5.0 / 6.0);
    double c_dem = dem_damping_for_restitution(e);
    double beta = c_dem / k;          /* |beta| that LIGGGHTS must compute */
    if (!(beta < 1)) {
        fprintf(stderr, "damping: c = %g needs |beta| = %g >= 1: no restitution gives it in LIGGGHTS\n", c_dem, beta);
        return 1;
    }
    double e_l = exp(-beta * pi / sqrt(1 - beta * beta));
    double le = log(e), c_l = k * -le / sqrt(le * le + pi * pi);
    printf("c_dem=%.17g e_liggghts=%.17g c_liggghts=%.17g e_hertz_liggghts=%.6g\n", c_dem, e_l, c_l,
           dem_restitution_for_damping(c_l));
    return 0;
}
