/* accuracy.c - what accuracy costs in time (`make accuracy`).
 *
 * A matrix of runs, each with an error against a reference no one tuned to and the wall time its steps took, written
 * as CSV (one row per run) for tools/plot_accuracy.py, which draws error against time and writes docs/accuracy.md.
 *
 * Cases (the closed forms are typed in here from the textbooks, not taken from the library):
 *   head_on      two equal glass spheres, head on, undamped, frictionless: maximum overlap, peak force and contact
 *                time against Hertz's closed forms (Johnson, Contact Mechanics, 1985, Sec. 11.4); the error is the
 *                largest of the three relative errors. Peak values from a parabola through the three samples at the
 *                top, the contact time from the linear zero crossings of the gap: what the trajectory gives, not
 *                where the samples fell.
 *   restitution  the same pair with e = 0.5 requested: |e measured / e - 1|.
 *   oblique      an alumina sphere onto a rigid plane at 60 degrees from the normal, e = 1, mu = 0.092: gross sliding
 *                throughout (tan 60 > 3.5 mu (1 + e)), so the tangential velocity change is mu (1 + e) v_n and the
 *                rebound spin 5 mu (1 + e) v_n / (2 r) (Maw, Barber & Fawcett 1976; Chung & Ooi 2011, test 6).
 *                The error is the larger relative error of the tangential velocity change and the normal rebound
 *                speed; the spin's is reported beside it (part1), not in it: our torque's lever arm is the distance
 *                to the contact point on the wall, r - delta (common/wall_forces.h), where the closed form has r,
 *                so the spin comes out low by about the mean delta / r during the contact (1.5e-3 here) at any dt.
 *   hydrogel     seed 000's 514-hydrogel compression (scenes/hydrogel_514.yaml, settling and compression only): the
 *                stress at the end of the compression (13.4 % strain, interpolated to that piston travel) against the
 *                same model's converged run (fp64, the smallest time step, MC-strain iterated to 1e-10).
 *   rubber       the rubber sphere between two steel plates to d/r = 0.4 (scenes/validation/rubber_plates.yaml),
 *                the plate force there against the same model's converged run.
 *   membrane     seed 001's triaxial test in miniature (tests/scenes/triaxial_small.yaml): the top platen's stress at
 *                the end, MSS_patch and MSS_particle at several edge lengths, against MSS_patch on the finest mesh.
 * Settings: precision, dt as a fraction of the Rayleigh time, contact model (classical, mc_stress, mc_strain lagged,
 * mc_strain iterated with its tolerance), the membrane's model and edge and, for cost only, the neighbour skin
 * (whose results must be bit-identical: the run stops if they are not).
 *
 * The binary cases are Hertz's, so they run the classical law only (a multi-contact law is not Hertz's for one
 * contact). Timings are the steps alone (dem_start, which compiles kernels, is left out), on $ACCURACY_BACKEND
 * (opencl, the default, or reference); the errors are the same bits on either.
 *
 * usage: dem-accuracy OUT.csv      ACCURACY_QUICK=1: fewer time steps, the converged runs at 0.05 t_R;
 *                                   ACCURACY_ONLY=binary,rubber,hydrogel,membrane,skin: those groups only */
#include "dem.h"
#include "scene.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { CLASSICAL, MC_STRESS, MC_LAGGED, MC_ITERATED, NMODELS };
static const char *const model_names[NMODELS] = {"classical", "mc_stress", "mc_strain", "mc_strain_iterated"};

typedef struct {
    dem_precision prec;
    double dtf;   /* dt / Rayleigh time */
    int model;
    double tol;   /* MC-strain iteration tolerance (iterated only) */
    double skin;  /* neighbour skin as a fraction of the smallest radius (0: the default, chosen at each rebuild between 0.05 and 0.3) */
} setting;

typedef struct {
    double value;  /* the measured quantity (case-specific, in SI units) */
    double err;    /* relative error against the case's reference */
    double parts[3];
    double seconds;
    long steps;
    long unconverged, iterations;
} result;

static dem_backend_kind backend = DEM_BACKEND_OPENCL;

/* $ACCURACY_ONLY: a comma-separated list of the case groups to run (binary, rubber, hydrogel, membrane, skin) */
static int only(const char *group)
{
    const char *o = getenv("ACCURACY_ONLY");
    if (!o || !*o)
        return 1;
    size_t n = strlen(group);
    for (const char *p = o; (p = strstr(p, group)); p += n)
        if ((p == o || p[-1] == ',') && (p[n] == 0 || p[n] == ','))
            return 1;
    return 0;
}
static FILE *csv;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void die(const char *what, const char *why)
{
    fprintf(stderr, "dem-accuracy: %s: %s\n", what, why);
    exit(1);
}

static dem_config config_of(const setting *st)
{
    dem_config c;
    dem_config_default(&c);
    c.backend = backend;
    c.precision = st->prec;
    return c;
}

static double rayleigh(dem_sim *s)
{
    dem_time_scales ts;
    if (dem_time_scales_get(s, 1.0, &ts))
        die("time scales", dem_error(s));
    return ts.rayleigh_time;
}

/* dt at the setting's fraction of the Rayleigh time, then dem_start; returns dt */
static double start_at(dem_sim *s, const setting *st, const char *what)
{
    double dt = st->dtf * rayleigh(s);
    dem_set_dt(s, dt);
    dem_config c = config_of(st);
    if (dem_start(s, &c))
        die(what, dem_error(s));
    return dt;
}

static void step(dem_sim *s, long n, double *secs)
{
    double t0 = now();
    if (dem_step(s, n))
        die("step", dem_error(s));
    *secs += now() - t0;
}

/* parabola through (-1, a), (0, b), (1, c): its extreme value */
static double parabola_peak(double a, double b, double c)
{
    double den = a - 2 * b + c;
    if (den == 0)
        return b;
    double u = 0.5 * (a - c) / den;
    return b - 0.25 * (a - c) * u;
}

/* ---- binary collisions ---- */

/* Two equal spheres (Chung & Ooi's test 1 glass: E 48 GPa, nu 0.2, rho 2800, r 10 mm, each at 10 m/s) just touching
 * at t = 0. restitution < 1 turns on damping. Returns the pair's trajectory measures. */
static result head_on(const setting *st, double e)
{
    const double r = 0.01, v = 10, E = 4.8e10, nu = 0.2, rho = 2800;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){rho, E, nu, e, 0.0});
    dem_add_particle(s, (double[3]){-r, 0, 0}, (double[3]){v, 0, 0}, r, m);
    dem_add_particle(s, (double[3]){r, 0, 0}, (double[3]){-v, 0, 0}, r, m);
    dem_set_domain(s, (double[3]){-8 * r, -8 * r, -8 * r}, (double[3]){8 * r, 8 * r, 8 * r});
    dem_set_effects(s, e < 1 ? DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING : DEM_EFFECT_HERTZ);
    double dt = start_at(s, st, "head_on start");
    result res = {0};
    double hist_d[3] = {0}, hist_f[3] = {0}, dmax = 0, fmax_ = 0, gap_prev = 0, tc = NAN;
    long k;
    for (k = 1; k < 100000; k++) {
        step(s, 1, &res.seconds);
        double x[6], f[6];
        dem_get_field(s, DEM_FIELD_X, x);
        dem_get_field(s, DEM_FIELD_FORCE, f);
        double gap = (x[3] - x[0]) - 2 * r, d = -gap, fx = fabs(f[0]);
        /* a new top: the parabola through it and its neighbours, once the next sample is in */
        if (hist_d[1] >= hist_d[0] && hist_d[1] > d && hist_d[1] > 0)
            dmax = fmax(dmax, parabola_peak(hist_d[0], hist_d[1], d));
        if (hist_f[1] >= hist_f[0] && hist_f[1] > fx && hist_f[1] > 0)
            fmax_ = fmax(fmax_, parabola_peak(hist_f[0], hist_f[1], fx));
        hist_d[0] = hist_d[1], hist_d[1] = d, hist_f[0] = hist_f[1], hist_f[1] = fx;
        if (gap >= 0 && k > 1) { /* separated: the zero crossing between the last two samples */
            tc = dt * (k - 1 + (-gap_prev) / (gap - gap_prev));
            break;
        }
        gap_prev = gap;
    }
    res.steps = k;
    double vel[6];
    dem_get_field(s, DEM_FIELD_V, vel);
    dem_destroy(s);
    if (e < 1) {
        res.value = (vel[3] - vel[0]) / (2 * v);
        res.err = fabs(res.value / e - 1);
        return res;
    }
    /* Hertz: m* = m/2, r* = r/2, E* = E / (2 (1 - nu^2)), relative speed 2v */
    double mass = rho * 4.0 / 3.0 * M_PI * r * r * r, ms = mass / 2, rs = r / 2, es = E / (2 * (1 - nu * nu)),
           vr = 2 * v;
    double tc0 = 2.868 * pow(ms * ms / (rs * es * es * vr), 0.2);
    double d0 = pow(15 * ms * vr * vr / (16 * es * sqrt(rs)), 0.4);
    double f0 = 4.0 / 3.0 * es * sqrt(rs) * d0 * sqrt(d0);
    if (!isfinite(tc))
        die("head_on", "the spheres did not separate");
    res.parts[0] = fabs(dmax / d0 - 1), res.parts[1] = fabs(fmax_ / f0 - 1), res.parts[2] = fabs(tc / tc0 - 1);
    res.err = fmax(res.parts[0], fmax(res.parts[1], res.parts[2]));
    res.value = tc;
    return res;
}

/* Chung & Ooi's test 6 sphere (alumina: E 380 GPa, nu 0.23, rho 4000, r 2.5 mm, 3.9 m/s, mu 0.092) onto a rigid
 * plane at 60 degrees from its normal, undamped. */
static result oblique(const setting *st)
{
    const double r = 0.0025, E = 3.8e11, nu = 0.23, rho = 4000, mu = 0.092, speed = 3.9, th = M_PI / 3;
    const double vn = speed * cos(th), vt = speed * sin(th);
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){rho, E, nu, 1.0, mu});
    int rigid = dem_add_material(s, &(dem_material){1, INFINITY, 0.3, 1.0, mu});
    dem_add_particle(s, (double[3]){0, 0, r}, (double[3]){vt, 0, -vn}, r, m);
    dem_wall w = {DEM_WALL_PLANE, rigid, {0, 0, 0}, {0, 0, 1}};
    dem_add_wall(s, &w);
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.01}, (double[3]){0.05, 0.05, 0.05});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_FRICTION | DEM_EFFECT_WALLS);
    start_at(s, st, "oblique start");
    result res = {0};
    long k;
    for (k = 1; k < 100000; k++) {
        step(s, 1, &res.seconds);
        double x[3];
        dem_get_field(s, DEM_FIELD_X, x);
        if (k > 1 && x[2] > r)
            break;
    }
    res.steps = k;
    double v[3], w3[3];
    dem_get_field(s, DEM_FIELD_V, v);
    dem_get_field(s, DEM_FIELD_W, w3);
    dem_destroy(s);
    double dvt0 = mu * 2 * vn, w0 = 5 * mu * 2 * vn / (2 * r);
    res.parts[0] = fabs((vt - v[0]) / dvt0 - 1);
    res.parts[1] = fabs(fabs(w3[1]) / w0 - 1);
    res.parts[2] = fabs(v[2] / vn - 1);
    res.err = fmax(res.parts[0], res.parts[2]); /* the spin apart: its lever arm is r - delta, not r (below) */
    res.value = w3[1];
    return res;
}

/* ---- scenes: the piston force where its first moving stage ends ---- */

/* limit > 0: a warm-up of that many steps (the first launches of a set-up), nothing measured */
static result compression(const char *path, const setting *st, int cap, long limit)
{
    char err[1024];
    scene *sc = scene_load(path, err, sizeof err);
    if (!sc)
        die(path, err);
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s)
        die(path, err);
    if (scene_apply_model(sc, s, &run, model_names[st->model], err, sizeof err))
        die(path, err);
    if (st->model == MC_ITERATED && dem_set_mc_strain(s, cap, st->tol))
        die(path, dem_error(s));
    double dt = st->dtf * run.ts.rayleigh_time;
    dem_set_dt(s, dt);
    dem_config c = run.cfg;
    c.backend = backend;
    c.precision = st->prec;
    if (st->skin > 0) {
        double rmin = INFINITY;
        for (int i = 0; i < dem_count(s); i++)
            rmin = fmin(rmin, dem_particle_radius(s, i));
        c.skin = st->skin * rmin;
    }
    int p = run.piston;
    dem_wall w;
    if (p < 0 || dem_wall_get(s, p, &w))
        die(path, "the scene names no piston (sample.piston)");
    long end = 0;
    double travel = 0;
    for (int k = 0; k < w.nstages; k++) {
        end += lround(w.stages[k].duration / dt);
        double sp = sqrt(w.stages[k].velocity[0] * w.stages[k].velocity[0] +
                         w.stages[k].velocity[1] * w.stages[k].velocity[1] +
                         w.stages[k].velocity[2] * w.stages[k].velocity[2]);
        if (sp > 0) {
            travel = sp * w.stages[k].duration;
            break;
        }
    }
    if (dem_start(s, &c))
        die(path, dem_error(s));
    result res = {0};
    if (limit > 0) {
        step(s, limit, &res.seconds);
        dem_destroy(s);
        scene_free(sc);
        return res;
    }
    step(s, end - 4, &res.seconds);
    double d[9], f[9], p0[3] = {w.point[0], w.point[1], w.point[2]};
    int nd = 0;
    for (long k = end - 3; k <= end + 2 && nd < 9; k++) { /* the steps around the stage's end, one at a time */
        step(s, 1, &res.seconds);
        double x[3];
        dem_wall_position(s, p, x);
        d[nd] = (x[0] - p0[0]) * w.normal[0] + (x[1] - p0[1]) * w.normal[1] + (x[2] - p0[2]) * w.normal[2];
        dem_wall_normal_force(s, p, &f[nd]);
        nd++;
    }
    /* the last two samples in which the piston still moved: F interpolated (or extrapolated by < 1 step) to travel */
    int b = nd - 1;
    while (b > 1 && d[b] == d[b - 1])
        b--;
    double u = (travel - d[b - 1]) / (d[b] - d[b - 1]);
    res.value = (f[b - 1] + u * (f[b] - f[b - 1])) / run.sample_area;
    res.steps = dem_step_index(s);
    dem_mc_stats ms;
    dem_mc_stats_get(s, &ms);
    res.unconverged = ms.unconverged;
    res.iterations = ms.total;
    dem_destroy(s);
    scene_free(sc);
    return res;
}

/* ---- the membrane: seed 001's triaxial test in miniature (tests/scenes/triaxial_small.yaml) ---- */

/* The scene's text with the membrane's model ("patch" or "particle") and edge [m]: MSS_particle's vertex spheres are
 * 0.624 edges in radius on a tube that much wider (the proportions of scenes/seed001/triaxial_case1_particle.yaml,
 * 0.83 mm spheres on 1.33 mm edges), so that their inner side starts at the packing's 12 mm. The time step: dtf
 * Rayleigh times, or 0.9 of the library's bound where the hinges' damping sets a lower one. Measured: the top
 * platen's normal stress at the end (8 ms: the 100 kPa confinement, then 4 ms of axial compression). */
static result membrane(const char *model, double edge, double dtf)
{
    const char *path = DEM_DEFAULT_SOURCE_DIR "/tests/scenes/triaxial_small.yaml";
    FILE *f = fopen(path, "rb");
    if (!f)
        die(path, "cannot open");
    static char text[16384], out[20000];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    if (n == sizeof text - 1)
        die(path, "longer than this driver reads");
    text[n] = 0;
    int particle = !strcmp(model, "particle");
    double vr = 0.624 * edge;
    struct { const char *from; char to[160]; int hits; } subs[4] = {{0}};
    snprintf(subs[0].to, sizeof subs[0].to, "radius: %.6g, height: 0.0518044, edge: %.6g}", particle ? 0.012 + vr : 0.012,
             edge);
    subs[0].from = "radius: 0.012, height: 0.0518044, edge: 0.004}";
    subs[1].from = "model: patch";
    snprintf(subs[1].to, sizeof subs[1].to, "model: %s", model);
    subs[2].from = "kdiss: 1.0e-4}";
    if (particle)
        snprintf(subs[2].to, sizeof subs[2].to, "kdiss: 1.0e-4, vertex_radius: %.6g}", vr);
    else
        snprintf(subs[2].to, sizeof subs[2].to, "kdiss: 1.0e-4}");
    subs[3].from = "time: {dt_rayleigh: 0.2,";
    snprintf(subs[3].to, sizeof subs[3].to, "time: {dt_rayleigh: 0.01,"); /* the step is set below */
    size_t o = 0;
    for (const char *p = text; *p;) {
        int k;
        for (k = 0; k < 4; k++)
            if (!strncmp(p, subs[k].from, strlen(subs[k].from)))
                break;
        const char *piece = k < 4 ? subs[k].to : p;
        size_t len = k < 4 ? strlen(subs[k].to) : 1;
        if (o + len >= sizeof out)
            die(path, "the edited scene does not fit this driver's buffer");
        memcpy(out + o, piece, len);
        o += len;
        if (k < 4)
            p += strlen(subs[k].from), subs[k].hits++;
        else
            p++;
    }
    out[o] = 0;
    for (int k = 0; k < 4; k++) /* the scene must still read as this driver expects, or every run would be one */
        if (subs[k].hits != 1)
            die(path, "the scene changed: a setting this driver edits is not there exactly once");
    char err[2048];
    scene *sc = scene_load_text(path, out, o, err, sizeof err);
    if (!sc)
        die("membrane scene", err);
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s)
        die("membrane scene", err);
    double dt = fmin(dtf * run.ts.rayleigh_time, 0.9 * run.ts.max_dt);
    dem_set_dt(s, dt);
    dem_config c = run.cfg;
    c.backend = backend;
    c.precision = DEM_FP64;
    if (dem_start(s, &c))
        die("membrane start", dem_error(s));
    result res = {0};
    res.steps = lround(sc->f->time.duration / dt);
    step(s, res.steps, &res.seconds);
    double fn;
    dem_wall_normal_force(s, run.piston >= 0 ? run.piston : 1, &fn);
    res.value = fn / 0.00045239;
    res.parts[0] = edge, res.parts[1] = dt / run.ts.rayleigh_time;
    dem_destroy(s);
    scene_free(sc);
    return res;
}

static void emit_membrane(const char *model, const result *r, const char *role)
{
    fprintf(csv, "membrane,fp64,%.4g,%s,0,0,%s,%ld,%.6e,%.17g,%.6e,%.6e,%.6e,%.6e,0,0\n", r->parts[1], model, role,
            r->steps, r->seconds, r->value, r->err, r->parts[0], r->parts[1], r->parts[2]);
    fflush(csv);
    fprintf(stderr, "membrane    fp64 dt %.2f t_R %-9s edge %.2f mm %-9s %7ld steps %8.3f s  value %-12.6g err %.3e\n",
            r->parts[1], model, 1e3 * r->parts[0], role, r->steps, r->seconds, r->value, r->err);
}

static void emit(const char *cas, const setting *st, const result *r, const char *role)
{
    fprintf(csv, "%s,%s,%g,%s,%g,%g,%s,%ld,%.6e,%.17g,%.6e,%.6e,%.6e,%.6e,%ld,%ld\n", cas,
            st->prec == DEM_FP64 ? "fp64" : "fp32", st->dtf, model_names[st->model],
            st->model == MC_ITERATED ? st->tol : 0, st->skin, role, r->steps, r->seconds, r->value, r->err,
            r->parts[0], r->parts[1], r->parts[2], r->unconverged, r->iterations);
    fflush(csv);
    fprintf(stderr, "%-11s %s dt %.2f t_R %-18s tol %-6g skin %-4g %-9s %7ld steps %8.3f s  value %-12.6g err %.3e\n",
            cas, st->prec == DEM_FP64 ? "fp64" : "fp32", st->dtf, model_names[st->model],
            st->model == MC_ITERATED ? st->tol : 0, st->skin, role, r->steps, r->seconds, r->value, r->err);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: dem-accuracy OUT.csv   (ACCURACY_QUICK=1: the short matrix; ACCURACY_ONLY=binary,rubber,"
                        "hydrogel,membrane,skin: those groups; ACCURACY_BACKEND=opencl|reference)\n");
        return 2;
    }
    const char *b = getenv("ACCURACY_BACKEND");
    if (b && !strcmp(b, "reference"))
        backend = DEM_BACKEND_REFERENCE;
    else if (b && strcmp(b, "opencl"))
        die("ACCURACY_BACKEND", "opencl or reference");
    int quick = getenv("ACCURACY_QUICK") && atoi(getenv("ACCURACY_QUICK"));
    csv = fopen(argv[1], "w");
    if (!csv)
        die(argv[1], "cannot write");
    fprintf(csv, "case,precision,dt_rayleigh,model,tolerance,skin,role,steps,seconds,value,error,part0,part1,part2,"
                 "unconverged,iterations\n");
    const double dts_full[] = {0.02, 0.05, 0.1, 0.2, 0.35, 0.5}, dts_quick[] = {0.1, 0.2, 0.35, 0.5};
    const double *dts = quick ? dts_quick : dts_full;
    int ndt = quick ? 4 : 6;
    const dem_precision precs[2] = {DEM_FP64, DEM_FP32};

    /* binary collisions: closed forms */
    for (int pi = 0; pi < 2 && only("binary"); pi++)
        for (int k = 0; k < ndt; k++) {
            setting st = {precs[pi], dts[k], CLASSICAL, 0, 0};
            result r = head_on(&st, 1.0);
            r = head_on(&st, 1.0); /* twice each, the second timed: the first pays a set-up's first launches */
            emit("head_on", &st, &r, "run");
            r = head_on(&st, 0.5);
            r = head_on(&st, 0.5);
            emit("restitution", &st, &r, "run");
            r = oblique(&st);
            r = oblique(&st);
            emit("oblique", &st, &r, "run");
        }

    /* the two compressions: each model against its own converged run */
    struct { const char *name, *path; } scenes[2] = {
        {"rubber", DEM_DEFAULT_SOURCE_DIR "/scenes/validation/rubber_plates.yaml"},
        {"hydrogel", DEM_DEFAULT_SOURCE_DIR "/scenes/hydrogel_514.yaml"}};
    const double conv_dt = quick ? 0.05 : 0.02;
    for (int sc = 0; sc < 2; sc++) {
        if (!only(scenes[sc].name))
            continue;
        for (int m = 0; m < NMODELS; m++) {
            if (m == MC_LAGGED)
                continue; /* shares the iterated scheme's converged run */
            setting cs = {DEM_FP64, conv_dt, m, 1e-10, 0}, w32 = {DEM_FP32, 0.2, m, 1e-6, 0};
            compression(scenes[sc].path, &cs, 1000, 20);
            compression(scenes[sc].path, &w32, 20, 20);
            result conv = compression(scenes[sc].path, &cs, 1000, 0);
            emit(scenes[sc].name, &cs, &conv, "converged");
            int models[2] = {m, MC_LAGGED};
            for (int mm = 0; mm < (m == MC_ITERATED ? 2 : 1); mm++)
                for (int pi = 0; pi < 2; pi++)
                    for (int k = 0; k < ndt; k++) {
                        setting st = {precs[pi], dts[k], models[mm], 1e-6, 0};
                        if (st.prec == DEM_FP32 && sc == 1 && quick && k != 1)
                            continue;
                        if (st.prec == DEM_FP64 && st.dtf == conv_dt && m != MC_ITERATED)
                            continue; /* the converged run itself */
                        result r = compression(scenes[sc].path, &st, 20, 0);
                        r.err = fabs(r.value / conv.value - 1);
                        emit(scenes[sc].name, &st, &r, "run");
                    }
            if (m == MC_ITERATED) { /* the iteration tolerance at 0.2 t_R */
                const double tols[] = {1e-2, 1e-4, 1e-8};
                for (int t = 0; t < 3; t++) {
                    setting st = {DEM_FP64, 0.2, MC_ITERATED, tols[t], 0};
                    result r = compression(scenes[sc].path, &st, 1000, 0);
                    r.err = fabs(r.value / conv.value - 1);
                    emit(scenes[sc].name, &st, &r, "tolerance");
                }
            }
        }
    }
    /* the membrane: MSS_patch and MSS_particle against the edge length, both against MSS_patch on the finest mesh */
    if (only("membrane")) {
        const double edges_full[] = {0.004, 0.003, 0.002}, edges_quick[] = {0.004, 0.003};
        const double *edges = quick ? edges_quick : edges_full, fine = quick ? 0.002 : 0.0015;
        int nedge = quick ? 2 : 3;
        membrane("patch", 0.004, 0.2); /* warm-up */
        result conv = membrane("patch", fine, 0.1);
        emit_membrane("patch", &conv, "converged");
        for (int m = 0; m < 2; m++)
            for (int k = 0; k < nedge; k++) {
                result r = membrane(m ? "particle" : "patch", edges[k], 0.2);
                r.err = fabs(r.value / conv.value - 1);
                emit_membrane(m ? "particle" : "patch", &r, "run");
            }
    }

    /* the neighbour skin: cost only, the stress must come out in the same bits */
    double same = NAN;
    const double skins[] = {0.3, 0.1, 1.0};
    for (int k = 0; k < 3 && only("skin"); k++) {
        setting st = {DEM_FP64, 0.2, CLASSICAL, 0, skins[k]};
        result r = compression(scenes[1].path, &st, 20, 0);
        emit("hydrogel", &st, &r, "skin");
        if (k == 0)
            same = r.value;
        else if (memcmp(&same, &r.value, sizeof same))
            die("skin", "the stress depends on the neighbour skin: the bitwise contract is broken");
    }
    fclose(csv);
    return 0;
}
