/* contact_forces.c - reference twin of kernels/contact_forces.cl (serial loops over common/contact_forces.h). */
#include "ref_kernels.h"
#include "contact_forces.h"

void REF(ref_contact_pairs)(unsigned fx, int n, int maxn, int nmat, real dt, const real *x, const real *v, const real *w,
                            const real *radius, const real *invmass, const int *mat, const real *pairmat,
                            const int *nbr_count, const int *nbr_list, const int *nbr_mirror, real *hist,
                            unsigned char *touch, const int *in_start, real *pair, real *force, real *torque,
                            const real *trace, const real *invvol, const real *mc_disp, real *mc_fn)
{
    for (int i = 0; i < n; i++)
        contact_pairs_item(fx, i, maxn, x, v, w, radius, invmass, mat, pairmat, nmat, nbr_count, nbr_list, nbr_mirror, hist,
                           touch, dt, in_start, pair, force, torque, trace, invvol, mc_disp, mc_fn);
}

void REF(ref_contact_forces)(unsigned fx, int n, int maxn, int nmat, real dt, const real *x, const real *v, const real *w,
                             const real *radius, const real *invmass, const int *mat, const real *pairmat,
                             const int *nbr_count, const int *nbr_list, const int *nbr_mirror,
                             const unsigned char *touch, const int *in_start, const real *pair,
                             real *force, real *torque, int nwalls, const int *wall_int, const real *wall_real,
                             real *wall_hist, real *wall_pf, unsigned *wall_mask, const real *trace,
                             const real *invvol, const real *mc_wall_disp, real *mc_wall_fn)
{
    for (int i = 0; i < n; i++)
        contact_forces_item(fx, i, maxn, x, v, w, radius, invmass, mat, pairmat, nmat, nbr_count, nbr_list, nbr_mirror,
                            touch, in_start, pair, dt, force, torque, n, nwalls, wall_int, wall_real,
                            wall_hist, wall_pf, wall_mask, trace, invvol, mc_wall_disp, mc_wall_fn);
}
