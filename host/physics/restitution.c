/* restitution.c - the damping factor c of common/laws/hertz_mindlin.h for a requested coefficient of restitution e.
 *
 * With f_n = k d^(3/2) + c sqrt(1.5 k m*) d^(1/4) d' (clamped at zero; k = 4/3 E* sqrt(r*)), scaling
 * d = d0 x, t = t0 s with t0^2 = m* / (k d0^(1/2)) and d0 = v t0 turns the collision into
 *        x'' = -max(0, x^(3/2) + kappa x^(1/4) x'),   x(0) = 0, x'(0) = 1,   kappa = c sqrt(1.5),
 * whose rebound speed -x'(end) is e. It depends on c alone: the restitution is the same at every impact speed,
 * size and stiffness. We integrate it with RK4 and bisect on c. (LIGGGHTS' beta = ln e / sqrt(ln^2 e + pi^2) is
 * the linear-spring answer; for Hertz it misses the requested e by several per cent.)
 * Runs on the host in double precision once per material pair; the device only sees c.
 */
#include "dem.h"
#include <math.h>

static void rhs(double kappa, double x, double u, double *dx, double *du)
{
    double xp = x > 0 ? x : 0;
    double f = xp * sqrt(xp) + kappa * sqrt(sqrt(xp)) * u;
    *dx = u;
    *du = f > 0 ? -f : 0;
}

static double damping_by_bisection(double e);

/* The scaled collision lasts about 3.2 time units: RESTITUTION_STEP resolves it in some 16 000 RK4 steps (the
 * rebound speed to ~1e-12); RESTITUTION_MAX_STEPS only stops a contact that never separates (c very large). */
#define RESTITUTION_STEP 2e-4
#define RESTITUTION_MAX_STEPS 10000000L
/* Bisection halvings of [0, hi]: 60 take the interval below one ulp of c, so c is the double nearest the root. */
#define RESTITUTION_BISECTIONS 60

double dem_restitution_for_damping(double c)
{
    const double h = RESTITUTION_STEP, kappa = c * sqrt(1.5);
    double x = 0, u = 1;
    for (long step = 0; step < RESTITUTION_MAX_STEPS; step++) {
        double k1x, k1u, k2x, k2u, k3x, k3u, k4x, k4u;
        rhs(kappa, x, u, &k1x, &k1u);
        rhs(kappa, x + 0.5 * h * k1x, u + 0.5 * h * k1u, &k2x, &k2u);
        rhs(kappa, x + 0.5 * h * k2x, u + 0.5 * h * k2u, &k3x, &k3u);
        rhs(kappa, x + h * k3x, u + h * k3u, &k4x, &k4u);
        double xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
        double un = u + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
        if (step > 0 && xn <= 0) {
            double a = x / (x - xn); /* linear interpolation of the crossing */
            return -(u + a * (un - u));
        }
        x = xn;
        u = un;
    }
    return 0; /* never separated: fully damped */
}

/* The answer is a pure function of e and costs about 10 ms (60 bisections of some 16 000 RK4 steps), paid per
 * material pair at every scene build: the last few answers are remembered, per thread, and returned as the same bits. */
#define RESTITUTION_MEMO 8

double dem_damping_for_restitution(double e)
{
    if (!(e > 0 && e < 1))
        return 0; /* e = 1: no damping; invalid e is rejected by dem_add_material */
    static _Thread_local double memo_e[RESTITUTION_MEMO], memo_c[RESTITUTION_MEMO];
    static _Thread_local int memo_n, memo_next;
    for (int k = 0; k < memo_n; k++)
        if (memo_e[k] == e)
            return memo_c[k];
    double c = damping_by_bisection(e);
    memo_e[memo_next] = e, memo_c[memo_next] = c;
    memo_next = (memo_next + 1) % RESTITUTION_MEMO;
    memo_n += memo_n < RESTITUTION_MEMO;
    return c;
}

static double damping_by_bisection(double e)
{
    double lo = 0, hi = 1;
    while (dem_restitution_for_damping(hi) > e && hi < 1e6)
        hi *= 2;
    for (int it = 0; it < RESTITUTION_BISECTIONS; it++) {
        double mid = 0.5 * (lo + hi);
        if (dem_restitution_for_damping(mid) > e)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}
