/* output.c - see output.h. */
#include "output.h"
#include "h5util.h"
#include "dem_debug.h" /* dem_build_info */
#include <math.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const struct {
    unsigned bit;
    dem_field field;
    const char *name, *units;
    int ncomp;          /* components per particle */
    const char *xdmf;   /* XDMF attribute type */
} frame_fields[] = {{OUT_POSITION, DEM_FIELD_X, "position", "m", 3, "Vector"},
                    {OUT_VELOCITY, DEM_FIELD_V, "velocity", "m/s", 3, "Vector"},
                    {OUT_ANGULAR_VELOCITY, DEM_FIELD_W, "angular_velocity", "rad/s", 3, "Vector"},
                    {OUT_FORCE, DEM_FIELD_FORCE, "force", "N", 3, "Vector"},
                    {OUT_TORQUE, DEM_FIELD_TORQUE, "torque", "N m", 3, "Vector"},
                    /* xx, yy, zz, xy, xz, yz (dem_layout.h ST_*), seed 000 Eq. 9, negative in compression */
                    {OUT_STRESS, DEM_FIELD_STRESS, "stress", "Pa", 6, "Tensor6"},
                    /* mdr: each sphere's apparent radius, which grows as it is pressed (docs/laws/mdr.md M34); frames
                     * [F, n]. /particles/radius stays the radius as created: the solid volume a relative density
                     * counts (MDR's growth stands for the material its flattened caps push aside) */
                    {OUT_APPARENT_RADIUS, DEM_FIELD_RADIUS, "apparent_radius", "m", 1, "Scalar"}};
#define NFF (sizeof frame_fields / sizeof frame_fields[0])

/* coordination: the mean number of particle contacts per particle, 2 contacts / particles (every particle counted,
 * rattlers too; walls not): python/libdem's coordination_number gives it without rattlers or with the walls */
static const char *series_names[S__N] = {"time", "step", "kinetic", "elastic", "potential", "total",
                                         "contacts", "wall_contacts", "coordination", "strain", "stress",
                                         "mc_iterations", "mc_capped"};
static const char *series_units[S__N] = {"s", NULL, "J", "J", "J", "J", NULL, NULL, NULL, "1", "Pa", NULL, NULL};

struct output {
    char path[4096], part[4200];
    hid_t file, frames, series;
    int n, nwalls, sample, mc; /* mc: MC-strain iterations are recorded */
    int ntri;                  /* membrane triangles (/membranes/triangles), drawn as a second XDMF grid */
    unsigned fields;
    h5rows ftime, fstep, fdata[NFF];
    h5rows s[S__N], wall_pos, wall_force, wall_normal;
    long nframes;
    long slab; /* > 0: particles per slab of a frame from a source (DEM_TEST_FRAME_SLAB); 0: a chunk's */
    double *buf;
    /* the contact network per frame (field "contacts"): rows of ids and data, where each frame starts */
    hid_t contacts;
    h5rows c_start, c_pairs, c_ids, c_data, c_fn;
    long long c_total;
    long long *c_frame; /* per frame: first row, pair rows (for the XDMF) */
    long c_cap;
    /* the walls as surfaces (wall_mesh): each vertex an offset from its wall's point as added, moved per frame by
     * the wall's position; /walls/points holds the frames' vertices, /walls/triangles the shared connectivity */
    hid_t walls;
    h5rows wpoints;
    int wnv, wnt;   /* wall-mesh vertices, triangles */
    double *wlocal; /* wnv x 3: offset from the wall's point */
    int *wvert;     /* wnv: the wall of each vertex */
    double *wbuf;   /* wnv x 3: one frame's vertices */
};

/* One name per library wall, newline-separated, in the order of the wall_position / wall_force columns
 * (scene_wall_label) */
static char *wall_names(const scene *sc, int nw)
{
    size_t cap = 1, len = 0;
    for (unsigned k = 0; k < sc->f->walls_count; k++)
        cap += 6 * (strlen(sc->f->walls[k].name ? sc->f->walls[k].name : "") + 32);
    char *t = malloc(cap);
    if (!t)
        return NULL;
    t[0] = 0;
    for (int k = 0; k < nw; k++) {
        char one[1100];
        scene_wall_label(sc, k, one, sizeof one);
        len += (size_t)snprintf(t + len, cap - len, "%s%s", len ? "\n" : "", one);
    }
    return t;
}

void output_xmf_path(const char *h5, char *buf, size_t len)
{
    size_t l = strlen(h5);
    snprintf(buf, len, "%.*s.xmf", (int)(l > 3 && !strcmp(h5 + l - 3, ".h5") ? l - 3 : l), h5);
}

/* The walls as triangle surfaces for ParaView (/walls in the HDF5 file, the "walls" grid of the XDMF). Walls are
 * endless or have no visible edge in the library, so the drawing needs a size: the extent is the binning domain the
 * scene gives (domain:), else the particles' bounding box (centres +- radii) when the output opens, stretched to
 * hold every plane's point (so that an endless die reaches its punches). A plane is a
 * rectangle centred on its point, reaching every corner of that box projected onto it (and at least 1.25 cup radii);
 * a plane with a cup (a punch) is the same rectangle with the spherical cap recessed in it, the cup drawn as
 * WM_CUP_RINGS rings; a cylinder is an open tube of its radius from its point along its height, or over the box's
 * extent along its axis when endless (height 0). Every mesh moves rigidly with its wall's position (walls translate:
 * dem_stage has no rotation). Triangles face the particles: (x1 - x0) x (x2 - x0) along a plane's normal, towards a
 * cylinder's axis. */
#define WM_SIDE 12                 /* points per side of a plane's rectangle */
#define WM_AROUND (4 * WM_SIDE)    /* points around a plane's rectangle, a cup's rings and a cylinder's rims */
#define WM_CUP_RINGS 8

static void wm_basis(const double n[3], double u[3], double v[3])
{
    int a = fabs(n[0]) <= fabs(n[1]) && fabs(n[0]) <= fabs(n[2]) ? 0 : fabs(n[1]) <= fabs(n[2]) ? 1 : 2;
    double e[3] = {0, 0, 0};
    e[a] = 1;
    u[0] = n[1] * e[2] - n[2] * e[1], u[1] = n[2] * e[0] - n[0] * e[2], u[2] = n[0] * e[1] - n[1] * e[0];
    double l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    u[0] /= l, u[1] /= l, u[2] /= l;
    v[0] = n[1] * u[2] - n[2] * u[1], v[1] = n[2] * u[0] - n[0] * u[2], v[2] = n[0] * u[1] - n[1] * u[0];
}

/* The largest |(corner - p).d| and the range of (corner - p).d over the box's corners */
static void wm_extent(const double lo[3], const double hi[3], const double p[3], const double d[3], double *amax,
                      double *mn, double *mx)
{
    *amax = 0, *mn = INFINITY, *mx = -INFINITY;
    for (int c = 0; c < 8; c++) {
        double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
        double t = (x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1] + (x[2] - p[2]) * d[2];
        *amax = fmax(*amax, fabs(t)), *mn = fmin(*mn, t), *mx = fmax(*mx, t);
    }
}

/* Vertices and triangles of wall w (its index k), appended at *nv and *nt; with NULL arrays, counts them only */
static void wall_mesh(const dem_wall *w, int k, const double lo[3], const double hi[3], double *loc, int *vw, int *tri,
                      int *nv, int *nt)
{
    const double *n = w->normal;
    double u[3], v[3];
    wm_basis(n, u, v);
    int v0 = *nv;
#define WM_VERT(a, b, h)                                                                                               \
    do {                                                                                                               \
        if (loc) {                                                                                                     \
            for (int d_ = 0; d_ < 3; d_++)                                                                             \
                loc[3 * *nv + d_] = (a) * u[d_] + (b) * v[d_] + (h) * n[d_];                                           \
            vw[*nv] = k;                                                                                               \
        }                                                                                                              \
        ++*nv;                                                                                                         \
    } while (0)
#define WM_TRI(a, b, c)                                                                                                \
    do {                                                                                                               \
        if (tri)                                                                                                       \
            tri[3 * *nt] = (a), tri[3 * *nt + 1] = (b), tri[3 * *nt + 2] = (c);                                        \
        ++*nt;                                                                                                         \
    } while (0)
    if (w->kind == DEM_WALL_CYLINDER) { /* two rims, WM_AROUND quads between them */
        double z0 = 0, z1 = w->height, amax;
        if (!(w->height > 0))
            wm_extent(lo, hi, w->point, n, &amax, &z0, &z1);
        for (int r = 0; r < 2; r++)
            for (int j = 0; j < WM_AROUND; j++) {
                double th = 2 * M_PI * j / WM_AROUND;
                WM_VERT(w->radius * cos(th), w->radius * sin(th), r ? z1 : z0);
            }
        for (int j = 0; j < WM_AROUND; j++) {
            int a0 = v0 + j, a1 = v0 + (j + 1) % WM_AROUND, b0 = a0 + WM_AROUND, b1 = a1 + WM_AROUND;
            WM_TRI(a0, b0, a1);
            WM_TRI(a1, b0, b1);
        }
    } else { /* the centre, the cup's rings (if any), the rectangle's edge: fans and bands around the centre */
        double a, b, mn, mx, c = w->cup_radius, depth = w->cup_depth;
        wm_extent(lo, hi, w->point, u, &a, &mn, &mx);
        wm_extent(lo, hi, w->point, v, &b, &mn, &mx);
        a = fmax(a, 1.25 * c), b = fmax(b, 1.25 * c);
        if (!(a > 0))
            a = b = 1;
        double ex[WM_AROUND], ey[WM_AROUND]; /* the edge, anticlockwise about n from the corner (a, -b) */
        for (int j = 0; j < WM_SIDE; j++) {
            double t = 2.0 * j / WM_SIDE - 1;
            ex[j] = a, ey[j] = t * b;
            ex[j + WM_SIDE] = -t * a, ey[j + WM_SIDE] = b;
            ex[j + 2 * WM_SIDE] = -a, ey[j + 2 * WM_SIDE] = -t * b;
            ex[j + 3 * WM_SIDE] = t * a, ey[j + 3 * WM_SIDE] = -b;
        }
        int rings = c > 0 && depth > 0 ? WM_CUP_RINGS : 0;
        double R = rings ? (c * c + depth * depth) / (2 * depth) : 0; /* the cup's sphere, its centre R - depth
                                                                       * along n from the point */
        WM_VERT(0, 0, rings ? -depth : 0);
        for (int r = 1; r <= rings; r++) {
            double rho = c * r / rings, h = r == rings ? 0 : (R - depth) - sqrt(R * R - rho * rho);
            for (int j = 0; j < WM_AROUND; j++) {
                double l = sqrt(ex[j] * ex[j] + ey[j] * ey[j]);
                WM_VERT(rho * ex[j] / l, rho * ey[j] / l, h);
            }
        }
        for (int j = 0; j < WM_AROUND; j++)
            WM_VERT(ex[j], ey[j], 0);
        for (int j = 0; j < WM_AROUND; j++)
            WM_TRI(v0, v0 + 1 + j, v0 + 1 + (j + 1) % WM_AROUND);
        for (int r = 0; r < rings; r++)
            for (int j = 0; j < WM_AROUND; j++) {
                int a0 = v0 + 1 + r * WM_AROUND + j, a1 = v0 + 1 + r * WM_AROUND + (j + 1) % WM_AROUND;
                WM_TRI(a0, a0 + WM_AROUND, a1);
                WM_TRI(a1, a0 + WM_AROUND, a1 + WM_AROUND);
            }
    }
#undef WM_VERT
#undef WM_TRI
}

/* Builds the walls' meshes and creates /walls (triangles, wall of each triangle, points per frame); box: the
 * particles' bounding box at the start (NULL: s's) */
static int walls_open(output *o, const scene *sc, dem_sim *s, const double *box)
{
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    if (scene_has(sc->loc, "domain")) {
        memcpy(lo, sc->f->domain_lo, sizeof lo);
        memcpy(hi, sc->f->domain_hi, sizeof hi);
    } else if (o->n > 0 && box) {
        memcpy(lo, box, sizeof lo);
        memcpy(hi, box + 3, sizeof hi);
    } else if (o->n > 0) {
        if (dem_get_field(s, DEM_FIELD_X, o->buf))
            return -1;
        for (int d = 0; d < 3; d++)
            lo[d] = INFINITY, hi[d] = -INFINITY;
        for (int i = 0; i < o->n; i++) {
            double r = dem_particle_radius(s, i);
            for (int d = 0; d < 3; d++)
                lo[d] = fmin(lo[d], o->buf[3 * i + d] - r), hi[d] = fmax(hi[d], o->buf[3 * i + d] + r);
        }
    }
    dem_wall w[DEM_MAX_WALLS];
    int nv = 0, nt = 0;
    for (int k = 0; k < o->nwalls; k++) {
        dem_wall_get(s, k, &w[k]);
        for (int d = 0; !scene_has(sc->loc, "domain") && w[k].kind == DEM_WALL_PLANE && d < 3; d++)
            lo[d] = fmin(lo[d], w[k].point[d]), hi[d] = fmax(hi[d], w[k].point[d]); /* a tube reaches the punches */
    }
    for (int k = 0; k < o->nwalls; k++)
        wall_mesh(&w[k], k, lo, hi, NULL, NULL, NULL, &nv, &nt);
    int *tri = malloc(sizeof(int) * 3 * (size_t)nt), *twall = malloc(sizeof(int) * (size_t)nt);
    o->wlocal = malloc(sizeof(double) * 3 * (size_t)nv);
    o->wbuf = malloc(sizeof(double) * 3 * (size_t)nv);
    o->wvert = malloc(sizeof(int) * (size_t)nv);
    int rc = !tri || !twall || !o->wlocal || !o->wbuf || !o->wvert;
    o->wnv = o->wnt = 0;
    for (int k = 0; !rc && k < o->nwalls; k++) {
        int t0 = o->wnt;
        wall_mesh(&w[k], k, lo, hi, o->wlocal, o->wvert, tri, &o->wnv, &o->wnt);
        for (int t = t0; t < o->wnt; t++)
            twall[t] = k;
    }
    if (!rc) {
        o->walls = H5Gcreate2(o->file, "walls", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        hsize_t dt[2] = {(hsize_t)nt, 3}, d1[1] = {(hsize_t)nt};
        rc = o->walls < 0 || h5_write(o->walls, "triangles", H5T_NATIVE_INT, 2, dt, tri, NULL) ||
             h5_write(o->walls, "wall", H5T_NATIVE_INT, 1, d1, twall, NULL) ||
             h5rows_create(&o->wpoints, o->walls, "points", H5T_NATIVE_DOUBLE, 3, (hsize_t)nv, 3, "m") ||
             h5_attr_string(o->walls, "layout",
                            "the walls drawn as triangle surfaces, per frame of /frames: points[f] the vertices at "
                            "frame f (each wall's mesh moved by its position), triangles the vertex ids of each "
                            "triangle (facing the particles), wall the wall of each triangle (a column of "
                            "/series/wall_position, named in /series wall_names). Planes are rectangles over the "
                            "scene's domain (or the particles' first bounding box and the planes' points), cups "
                            "recessed in them; cylinders "
                            "open tubes of their height (endless: over that box)");
    }
    free(tri);
    free(twall);
    return rc ? -1 : 0;
}

static int walls_frame(output *o, dem_sim *s)
{
    double p[DEM_MAX_WALLS][3];
    for (int k = 0; k < o->nwalls; k++)
        if (dem_wall_position(s, k, p[k]))
            return -1;
    for (int i = 0; i < o->wnv; i++)
        for (int d = 0; d < 3; d++)
            o->wbuf[3 * i + d] = p[o->wvert[i]][d] + o->wlocal[3 * i + d];
    return h5rows_append(&o->wpoints, o->wbuf);
}

output *output_open(const char *path, const scene *sc, const scene_run *run, dem_sim *s, dem_sim *dev,
                    const double *box, char *err, size_t errlen)
{
    output *o = calloc(1, sizeof *o);
    int n = dem_count(s), nw = dem_wall_count(s);
    if (!o || strlen(path) > 4000) {
        free(o);
        snprintf(err, errlen, "%s: output path too long or out of memory", path);
        return NULL;
    }
    snprintf(o->path, sizeof o->path, "%s", path);
    snprintf(o->part, sizeof o->part, "%s.part", path);
    o->n = n;
    o->nwalls = nw;
    const char *ts = getenv("DEM_TEST_FRAME_SLAB"); /* tests/mpi_run_check.sh: frames from the parts in small slabs */
    o->slab = ts ? atol(ts) : 0;
    o->fields = run->fields;
    if ((run->fields & OUT_RADIUS) && (run->effects & DEM_EFFECT_MDR))
        o->fields |= OUT_APPARENT_RADIUS;
    o->sample = run->piston >= 0;
    o->mc = (run->effects & DEM_EFFECT_MC_STRAIN) != 0;
    o->buf = malloc(sizeof(double) * 6 * (size_t)(n > DEM_MAX_WALLS ? n : DEM_MAX_WALLS)); /* frames, and wall rows */
    errno = 0;
    o->file = H5Fcreate(o->part, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    int create_errno = o->file < 0 ? errno : 0;
    int rc = !o->buf || o->file < 0;
    char fx[128], conv[128];
    dem_effects_string(run->effects, fx, sizeof fx);
    dem_mc_stress_convention_string(run->mcs_conv, conv, sizeof conv);
    if (!rc)
        rc = h5_attr_string(o->file, "libdem_version", DEM_VERSION) ||
             h5_attr_string(o->file, "device", dem_describe(dev)) ||
             h5_attr_string(o->file, "build", dem_build_info(dev)) ||
             h5_attr_string(o->file, "precision", run->cfg.precision == DEM_FP64 ? "fp64" : "fp32") ||
             h5_attr_string(o->file, "effects", fx) || h5_attr_double(o->file, "dt", run->dt) ||
             h5_attr_double(o->file, "mass_scale", scene_mass_scale(sc)) ||
             h5_attr_string(o->file, "mass_scale_keeps", scene_keeps_acceleration(sc) ? "acceleration" : "weight") ||
             h5_attr_string(o->file, "model", run->model[0] ? run->model : "as in the scene") ||
             h5_attr_long(o->file, "steps", run->steps) || h5_attr_string(o->file, "scene_path", sc->path) ||
             h5_attr_string(o->file, "units", "SI: m, kg, s, N, Pa, J") ||
             h5_attr_string(o->file, "scene_name", sc->f->name ? sc->f->name : sc->path) ||
             ((run->effects & DEM_EFFECT_MC_STRESS) && h5_attr_string(o->file, "mc_stress_convention", conv)) ||
             h5_write_text(o->file, "scene_text", sc->text);
    if (!rc) {
        hid_t g = H5Gcreate2(o->file, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        int *mat = malloc(sizeof(int) * (size_t)n);
        for (int i = 0; i < n; i++)
            o->buf[i] = dem_particle_radius(s, i);
        for (int i = 0; mat && i < n; i++)
            mat[i] = dem_particle_material(s, i);
        hsize_t dn[1] = {(hsize_t)n};
        rc = g < 0 || !mat || h5_write(g, "radius", H5T_NATIVE_DOUBLE, 1, dn, o->buf, "m") ||
             h5_write(g, "material", H5T_NATIVE_INT, 1, dn, mat, NULL);
        int moved = 0; /* particle_order: spatial - each particle's place in the scene's own order */
        for (int i = 0; mat && i < n; i++)
            moved |= (mat[i] = dem_particle_source(s, i)) != i;
        rc = rc || (moved && (h5_write(g, "input_index", H5T_NATIVE_INT, 1, dn, mat, NULL) ||
                              h5_attr_string(g, "input_index", "particle_order: spatial - particle i is the scene's "
                                                               "particle input_index[i] (its groups in order)")));
        free(mat);
        if (g >= 0)
            H5Gclose(g);
    }
    o->ntri = dem_triangle_count(s);
    if (!rc && o->ntri) { /* the membranes' connectivity: rows of the frames' particle arrays */
        hid_t g = H5Gcreate2(o->file, "membranes", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        int *tri = malloc(sizeof(int) * 3 * (size_t)o->ntri);
        if (tri)
            dem_triangles_get(s, tri);
        hsize_t dt[2] = {(hsize_t)o->ntri, 3};
        rc = g < 0 || !tri || h5_write(g, "triangles", H5T_NATIVE_INT, 2, dt, tri, NULL) ||
             h5_attr_string(g, "layout", "triangles: the particle ids (rows of /frames/position ...) of each membrane "
                                         "triangle, ordered so that (x1 - x0) x (x2 - x0) points where the confining "
                                         "pressure pushes; the vertices are particles too, with their radius");
        free(tri);
        if (g >= 0)
            H5Gclose(g);
    }
    if (!rc) {
        o->frames = H5Gcreate2(o->file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = o->frames < 0 || h5rows_create(&o->ftime, o->frames, "time", H5T_NATIVE_DOUBLE, 1, 0, 0, "s") ||
             h5rows_create(&o->fstep, o->frames, "step", H5T_NATIVE_DOUBLE, 1, 0, 0, NULL);
        for (size_t k = 0; !rc && k < NFF; k++)
            if (o->fields & frame_fields[k].bit)
                rc = h5rows_create(&o->fdata[k], o->frames, frame_fields[k].name, H5T_NATIVE_DOUBLE,
                                   frame_fields[k].ncomp > 1 ? 3 : 2, (hsize_t)n, (hsize_t)frame_fields[k].ncomp,
                                   frame_fields[k].units);
    }
    if (!rc && (o->fields & OUT_CONTACTS)) { /* the contact network, ragged: each frame's rows from start[f] */
        o->contacts = H5Gcreate2(o->file, "contacts", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = o->contacts < 0 ||
             h5rows_create(&o->c_start, o->contacts, "frame_start", H5T_NATIVE_LLONG, 1, 0, 0, NULL) ||
             h5rows_create(&o->c_pairs, o->contacts, "frame_pairs", H5T_NATIVE_LLONG, 1, 0, 0, NULL) ||
             h5rows_create(&o->c_ids, o->contacts, "ids", H5T_NATIVE_INT, 2, 2, 0, NULL) ||
             h5rows_create(&o->c_data, o->contacts, "data", H5T_NATIVE_DOUBLE, 2, 12, 0, NULL) ||
             h5rows_create(&o->c_fn, o->contacts, "normal_force", H5T_NATIVE_DOUBLE, 1, 0, 0, "N") ||
             h5_attr_string(o->contacts, "layout",
                            "frame f holds rows frame_start[f] .. frame_start[f+1] (or the end): first frame_pairs[f] "
                            "particle pairs (ids i < j, ascending), then particle-wall pairs (ids i, -1 - wall). data: "
                            "overlap [m], normal force on i [N] (3), tangential force on i [N] (3), contact point [m] "
                            "(3), the law's terms (2: MC-stress traces T_i, T_j [Pa]; MC-strain induced displacements "
                            "at i and j [m]; else 0). normal_force: |normal force| [N].");
    }
    if (!rc) {
        o->series = H5Gcreate2(o->file, "series", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = o->series < 0;
        for (int k = 0; !rc && k < S__N; k++)
            if (k < S_STRAIN || (k < S_MCIT && o->sample) || (k >= S_MCIT && o->mc))
                rc = h5rows_create(&o->s[k], o->series, series_names[k], H5T_NATIVE_DOUBLE, 1, 0, 0, series_units[k]);
        if (!rc && nw)
            rc = h5rows_create(&o->wall_pos, o->series, "wall_position", H5T_NATIVE_DOUBLE, 3, (hsize_t)nw, 3, "m") ||
                 h5rows_create(&o->wall_force, o->series, "wall_force", H5T_NATIVE_DOUBLE, 3, (hsize_t)nw, 3, "N") ||
                 h5rows_create(&o->wall_normal, o->series, "wall_normal_force", H5T_NATIVE_DOUBLE, 2, (hsize_t)nw, 0,
                               "N");
        if (!rc && nw) {
            char *names = wall_names(sc, nw);
            rc = !names || h5_attr_string(o->series, "wall_names", names);
            free(names);
            /* each wall's shape, for tools that need it (tools/plot_tablet.py: the die's bore) */
            double rad[DEM_MAX_WALLS], nrm[3 * DEM_MAX_WALLS], hgt[DEM_MAX_WALLS], cupr[DEM_MAX_WALLS],
                cupd[DEM_MAX_WALLS];
            for (int k = 0; k < nw; k++) {
                dem_wall w;
                dem_wall_get(s, k, &w);
                rad[k] = w.kind == DEM_WALL_CYLINDER ? w.radius : 0;
                hgt[k] = w.kind == DEM_WALL_CYLINDER ? w.height : 0;
                cupr[k] = w.cup_radius;
                cupd[k] = w.cup_depth;
                memcpy(nrm + 3 * k, w.normal, sizeof(double) * 3);
            }
            hsize_t d1[1] = {(hsize_t)nw}, d3[2] = {(hsize_t)nw, 3};
            rc = rc || h5_write(o->series, "wall_radius", H5T_NATIVE_DOUBLE, 1, d1, rad, "m") ||
                 h5_write(o->series, "wall_height", H5T_NATIVE_DOUBLE, 1, d1, hgt, "m") ||
                 h5_write(o->series, "wall_cup_radius", H5T_NATIVE_DOUBLE, 1, d1, cupr, "m") ||
                 h5_write(o->series, "wall_cup_depth", H5T_NATIVE_DOUBLE, 1, d1, cupd, "m") ||
                 h5_write(o->series, "wall_normal", H5T_NATIVE_DOUBLE, 2, d3, nrm, NULL);
        }
        if (!rc && o->sample)
            rc = h5_attr_long(o->series, "piston_wall", run->piston) ||
                 h5_attr_double(o->series, "sample_height", run->sample_height) ||
                 h5_attr_double(o->series, "sample_area", run->sample_area) ||
                 h5_attr_double(o->series, "contact_travel", run->contact_travel) ||
                 h5_attr_string(o->series, "convention", "strain = (piston travel - contact_travel) / height; stress = "
                                                         "force the piston receives against its normal / area "
                                                         "(compression positive)");
    }
    if (!rc && nw)
        rc = walls_open(o, sc, s, box);
    if (rc) {
        if (create_errno)
            snprintf(err, errlen, "%s: cannot create the output file: %s", o->part, strerror(create_errno));
        else
            snprintf(err, errlen, "%s: cannot write the output file's header (HDF5 refused a value; names longer than "
                                  "1000 characters are refused by `dem check`)", o->part);
        output_abort(o);
        unlink(o->part);
        return NULL;
    }
    return o;
}

/* the frame's contacts written: the rows, then where they start and how many are pairs */
static int contacts_rows(output *o, const dem_contact *cs, long count)
{
    int rc = 0;
    for (long k = 0; !rc && k < count; k++) {
        const dem_contact *e = &cs[k];
        int ids[2] = {e->i, e->j};
        double row[12] = {e->overlap, e->fn[0], e->fn[1], e->fn[2], e->ft[0], e->ft[1], e->ft[2],
                          e->point[0], e->point[1], e->point[2], e->extra[0], e->extra[1]};
        double fn = sqrt(e->fn[0] * e->fn[0] + e->fn[1] * e->fn[1] + e->fn[2] * e->fn[2]);
        rc = h5rows_append(&o->c_ids, ids) || h5rows_append(&o->c_data, row) || h5rows_append(&o->c_fn, &fn);
    }
    return rc;
}

/* Particles per slab of a frame's contacts gathered from a source: its contacts, a few per particle, in one buffer */
#define OUTPUT_CONTACT_SLAB 65536L

static int output_contacts(output *o, dem_sim *s, const frame_source *src)
{
    long long start = o->c_total, np = 0, total = 0;
    if (!src) {
        dem_contact *cs;
        long count, npairs;
        if (dem_contacts_get(s, &cs, &count, &npairs))
            return -1;
        int rc = contacts_rows(o, cs, count);
        free(cs);
        if (rc)
            return -1;
        np = npairs, total = count;
    } else {
        for (int walls = 0; walls < 2; walls++)
            for (long a = 0, slab = o->slab > 0 ? o->slab : OUTPUT_CONTACT_SLAB; a < o->n; a += slab) {
                long b = a + slab < o->n ? a + slab : o->n, count;
                dem_contact *cs;
                if (src->contacts(src->ctx, walls, a, b, &cs, &count))
                    return -2;
                int rc = contacts_rows(o, cs, count);
                free(cs);
                if (rc)
                    return -1;
                total += count;
                np += walls ? 0 : count;
            }
    }
    if (h5rows_append(&o->c_start, &start) || h5rows_append(&o->c_pairs, &np))
        return -1;
    if (o->nframes >= o->c_cap) {
        long cap = o->c_cap ? 2 * o->c_cap : 64;
        long long *g = realloc(o->c_frame, sizeof(long long) * 2 * (size_t)cap);
        if (!g)
            return -1;
        o->c_frame = g, o->c_cap = cap;
    }
    o->c_frame[2 * o->nframes] = start, o->c_frame[2 * o->nframes + 1] = np;
    o->c_total += total;
    return 0;
}

/* field k of the frame from src, slab by slab: a slab of the dataset's chunks (its writes cover whole chunks) */
static int field_slabs(output *o, size_t k, const frame_source *src)
{
    h5rows *r = &o->fdata[k];
    int nc = frame_fields[k].ncomp;
    long slab = o->slab > 0 ? o->slab : (long)r->chunk1;
    for (long a = 0; a < o->n; a += slab) {
        long b = a + slab < o->n ? a + slab : o->n;
        if (src->field(src->ctx, frame_fields[k].field, nc, a, b, o->buf))
            return -2;
        if (h5rows_append_part(r, (hsize_t)a, (hsize_t)b, o->buf))
            return -1;
    }
    return 0;
}

int output_frame_from(output *o, dem_sim *s, const frame_source *src)
{
    double t = dem_time(s), st = (double)dem_step_index(s);
    int rc;
    if (h5rows_append(&o->ftime, &t) || h5rows_append(&o->fstep, &st))
        return -1;
    if ((o->fields & OUT_CONTACTS) && (rc = output_contacts(o, s, src)))
        return rc;
    for (size_t k = 0; k < NFF; k++)
        if (o->fields & frame_fields[k].bit) {
            if (src && (rc = field_slabs(o, k, src)))
                return rc;
            if (!src && (dem_get_field(s, frame_fields[k].field, o->buf) || h5rows_append(&o->fdata[k], o->buf)))
                return -1;
        }
    if (o->nwalls && walls_frame(o, s))
        return -1;
    o->nframes++;
    return 0;
}

int output_frame(output *o, dem_sim *s) { return output_frame_from(o, s, NULL); }

void output_row_of(const dem_sample *smp, const scene_run *run, int nwalls, series_row *r)
{
    const dem_energy_t *e = &smp->energy;
    double strain = NAN, stress = NAN;
    memcpy(r->wall_pos, smp->wall_pos, sizeof(double) * 3 * nwalls);
    memcpy(r->wall_force, smp->wall_force, sizeof(double) * 3 * nwalls);
    memcpy(r->wall_normal, smp->wall_normal, sizeof(double) * nwalls);
    if (run->piston >= 0) { /* engineering strain and stress of the sample (scene.h: sample) */
        const double *n = run->piston_normal, *p0 = run->piston_point, *p = r->wall_pos + 3 * run->piston,
                     *f = r->wall_force + 3 * run->piston;
        /* n points from the piston into the sample: travel into it is (p - p0).n */
        double travel = (p[0] - p0[0]) * n[0] + (p[1] - p0[1]) * n[1] + (p[2] - p0[2]) * n[2];
        strain = (travel - run->contact_travel) / run->sample_height;
        stress = -(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]) / run->sample_area;
    }
    double v[S__N] = {smp->time, (double)smp->step, e->kinetic, e->elastic, e->potential, e->total,
                      (double)e->contacts, (double)e->wall_contacts,
                      run->particles > 0 ? 2.0 * (double)e->contacts / (double)run->particles : 0.0, strain, stress,
                      (double)smp->mc.last, (double)smp->mc.unconverged};
    memcpy(r->v, v, sizeof v);
}

int output_sample(dem_sim *s, const scene_run *run, series_row *r)
{
    dem_sample smp;
    if (dem_sample_get(s, &smp))
        return -1;
    output_row_of(&smp, run, dem_wall_count(s), r);
    return 0;
}

void output_row_add(series_row *sum, const series_row *r, int nwalls)
{
    for (int k = 0; k < S__N; k++)
        sum->v[k] = (k == S_TIME || k == S_STEP || k == S_MCCAP) ? r->v[k] : sum->v[k] + r->v[k];
    for (int k = 0; k < 3 * nwalls; k++) {
        sum->wall_pos[k] += r->wall_pos[k];
        sum->wall_force[k] += r->wall_force[k];
    }
    for (int k = 0; k < nwalls; k++)
        sum->wall_normal[k] += r->wall_normal[k];
}

void output_row_mean(series_row *sum, int count, int nwalls)
{
    for (int k = 0; k < S__N; k++)
        if (k != S_TIME && k != S_STEP && k != S_MCCAP)
            sum->v[k] /= count;
    for (int k = 0; k < 3 * nwalls; k++) {
        sum->wall_pos[k] /= count;
        sum->wall_force[k] /= count;
    }
    for (int k = 0; k < nwalls; k++)
        sum->wall_normal[k] /= count;
}

int output_series(output *o, const series_row *r)
{
    for (int k = 0; k < S__N; k++)
        if ((k < S_STRAIN || (k < S_MCIT && o->sample) || (k >= S_MCIT && o->mc)) && h5rows_append(&o->s[k], &r->v[k]))
            return -1;
    if (o->nwalls && (h5rows_append(&o->wall_pos, r->wall_pos) || h5rows_append(&o->wall_force, r->wall_force) ||
                      h5rows_append(&o->wall_normal, r->wall_normal)))
        return -1;
    return 0;
}

int output_flush(output *o)
{
    int rc = 0;
    for (int k = 0; k < S__N; k++)
        rc |= h5rows_flush(&o->s[k]);
    for (size_t k = 0; k < NFF; k++)
        rc |= h5rows_flush(&o->fdata[k]);
    rc |= h5rows_flush(&o->c_start) | h5rows_flush(&o->c_pairs) | h5rows_flush(&o->c_ids) | h5rows_flush(&o->c_data) |
          h5rows_flush(&o->c_fn);
    rc |= h5rows_flush(&o->wall_pos) | h5rows_flush(&o->wall_force) | h5rows_flush(&o->wall_normal) |
          h5rows_flush(&o->ftime) | h5rows_flush(&o->fstep) | h5rows_flush(&o->wpoints);
    return rc ? -1 : 0;
}

static void close_all(output *o)
{
    h5rows_close(&o->ftime);
    h5rows_close(&o->fstep);
    for (size_t k = 0; k < NFF; k++)
        h5rows_close(&o->fdata[k]);
    for (int k = 0; k < S__N; k++)
        h5rows_close(&o->s[k]);
    h5rows_close(&o->wall_pos);
    h5rows_close(&o->wall_force);
    h5rows_close(&o->wall_normal);
    h5rows_close(&o->c_start);
    h5rows_close(&o->c_pairs);
    h5rows_close(&o->c_ids);
    h5rows_close(&o->c_data);
    h5rows_close(&o->c_fn);
    h5rows_close(&o->wpoints);
    if (o->walls > 0)
        H5Gclose(o->walls);
    if (o->frames > 0)
        H5Gclose(o->frames);
    if (o->series > 0)
        H5Gclose(o->series);
    if (o->contacts > 0)
        H5Gclose(o->contacts);
    o->frames = o->series = o->contacts = o->walls = 0;
}

/* s with XML's five special characters as entities (&amp; &lt; &gt; &quot; &apos;), malloc'd: the HDF5 file's name
 * goes into the XDMF sidecar as element text, and -o '<&"x>.h5' made it invalid XML. (Control characters and invalid
 * UTF-8, which XML cannot hold at all, are refused with the output path: run_output_paths.) */
static char *xml_escaped(const char *s)
{
    char *e = malloc(6 * strlen(s) + 1), *q = e;
    for (; e && *s; s++) {
        const char *ent = *s == '&' ? "&amp;" : *s == '<' ? "&lt;" : *s == '>' ? "&gt;" : *s == '"' ? "&quot;"
                          : *s == '\'' ? "&apos;" : NULL;
        if (ent)
            q += sprintf(q, "%s", ent);
        else
            *q++ = *s;
    }
    if (e)
        *q = 0;
    return e;
}

/* A triangle topology of nt triangles from dataset (nt x 3 ints) of the HDF5 file h5name, as a whole-array
 * hyperslab: ParaView's XDMF reader otherwise tries to cache the geometry with it, finds a hyperslab there and logs
 * an error (the surface was right either way). Shared by the membranes and the walls. */
static void xdmf_triangles(FILE *fp, int nt, const char *h5name, const char *dataset)
{
    fprintf(fp, "<Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\">\n"
                "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d 3\" Type=\"HyperSlab\">\n"
                "<DataItem Dimensions=\"3 2\" Format=\"XML\">0 0 1 1 %d 3</DataItem>\n"
                "<DataItem Dimensions=\"%d 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
                "%s:%s</DataItem>\n</DataItem>\n</Topology>\n",
            nt, nt, nt, nt, h5name, dataset);
}

/* XDMF 2: a temporal collection of point sets; every attribute is a hyperslab of the frame arrays. */
static int write_xdmf(const output *o, const char *xmf_path, const double *times)
{
    char *h5name = xml_escaped(strrchr(o->path, '/') ? strrchr(o->path, '/') + 1 : o->path);
    FILE *fp = h5name ? fopen(xmf_path, "w") : NULL;
    if (!fp)
        return free(h5name), -1;
    long F = o->nframes;
    fprintf(fp, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n<Domain>\n"
                "<Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    for (long f = 0; f < F; f++) {
        fprintf(fp, "<Grid Name=\"frame %ld\" GridType=\"Uniform\">\n<Time Value=\"%.17g\"/>\n", f, times[f]);
        fprintf(fp, "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" NodesPerElement=\"1\"/>\n", o->n);
        fprintf(fp, "<Geometry GeometryType=\"XYZ\">\n");
        for (size_t k = 0; k < NFF; k++) {
            if (!(o->fields & frame_fields[k].bit))
                continue;
            int c = frame_fields[k].ncomp;
            if (k > 0)
                fprintf(fp, "<Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n",
                        frame_fields[k].name, frame_fields[k].xdmf);
            if (c == 1) /* a scalar per particle: frames [F, n] */
                fprintf(fp,
                        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d\" Type=\"HyperSlab\">\n"
                        "<DataItem Dimensions=\"3 2\" Format=\"XML\">%ld 0 1 1 1 %d</DataItem>\n"
                        "<DataItem Dimensions=\"%ld %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                        "%s:/frames/%s</DataItem>\n</DataItem>\n",
                        o->n, f, o->n, F, o->n, h5name, frame_fields[k].name);
            else
                fprintf(fp,
                        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d %d\" Type=\"HyperSlab\">\n"
                        "<DataItem Dimensions=\"3 3\" Format=\"XML\">%ld 0 0 1 1 1 1 %d %d</DataItem>\n"
                        "<DataItem Dimensions=\"%ld %d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                        "%s:/frames/%s</DataItem>\n</DataItem>\n",
                        o->n, c, f, o->n, c, F, o->n, c, h5name, frame_fields[k].name);
            fprintf(fp, k > 0 ? "</Attribute>\n" : "</Geometry>\n");
        }
        fprintf(fp, "<Attribute Name=\"radius\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                    "<DataItem Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                    "%s:/particles/radius</DataItem>\n</Attribute>\n", o->n, h5name);
        fprintf(fp, "<Attribute Name=\"material\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                    "<DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
                    "%s:/particles/material</DataItem>\n</Attribute>\n</Grid>\n", o->n, h5name);
    }
    fprintf(fp, "</Grid>\n");
    if (o->ntri && (o->fields & OUT_POSITION)) { /* the membranes as surfaces over the same positions */
        fprintf(fp, "<Grid Name=\"membranes\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
        for (long f = 0; f < F; f++) {
            fprintf(fp, "<Grid Name=\"membranes %ld\" GridType=\"Uniform\">\n<Time Value=\"%.17g\"/>\n", f, times[f]);
            xdmf_triangles(fp, o->ntri, h5name, "/membranes/triangles");
            for (size_t k = 0; k < NFF; k++) {
                if (!(o->fields & frame_fields[k].bit) || frame_fields[k].ncomp != 3)
                    continue;
                if (k > 0)
                    fprintf(fp, "<Attribute Name=\"%s\" AttributeType=\"Vector\" Center=\"Node\">\n",
                            frame_fields[k].name);
                else
                    fprintf(fp, "<Geometry GeometryType=\"XYZ\">\n");
                fprintf(fp,
                        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d 3\" Type=\"HyperSlab\">\n"
                        "<DataItem Dimensions=\"3 3\" Format=\"XML\">%ld 0 0 1 1 1 1 %d 3</DataItem>\n"
                        "<DataItem Dimensions=\"%ld %d 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                        "%s:/frames/%s</DataItem>\n</DataItem>\n",
                        o->n, f, o->n, F, o->n, h5name, frame_fields[k].name);
                fprintf(fp, k > 0 ? "</Attribute>\n" : "</Geometry>\n");
            }
            fprintf(fp, "</Grid>\n");
        }
        fprintf(fp, "</Grid>\n");
    }
    if (o->nwalls && o->wnt) {
        /* the walls (/walls): a temporal collection of its own, as the membranes and the contact network - ParaView's
         * XDMF reader makes each top-level grid a block of one multiblock, named, with a time series each (a spatial
         * collection per frame would nest the particles one level deeper, and readers and scripts that open the
         * particles' grid by name as the first block would change) */
        fprintf(fp, "<Grid Name=\"walls\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
        for (long f = 0; f < F; f++) {
            fprintf(fp, "<Grid Name=\"walls %ld\" GridType=\"Uniform\">\n<Time Value=\"%.17g\"/>\n", f, times[f]);
            xdmf_triangles(fp, o->wnt, h5name, "/walls/triangles");
            fprintf(fp, "<Geometry GeometryType=\"XYZ\">\n"
                        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d 3\" Type=\"HyperSlab\">\n"
                        "<DataItem Dimensions=\"3 3\" Format=\"XML\">%ld 0 0 1 1 1 1 %d 3</DataItem>\n"
                        "<DataItem Dimensions=\"%ld %d 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                        "%s:/walls/points</DataItem>\n</DataItem>\n</Geometry>\n",
                    o->wnv, f, o->wnv, F, o->wnv, h5name);
            fprintf(fp, "<Attribute Name=\"wall\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
                        "<DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
                        "%s:/walls/wall</DataItem>\n</Attribute>\n</Grid>\n", o->wnt, h5name);
        }
        fprintf(fp, "</Grid>\n");
    }
    if ((o->fields & OUT_CONTACTS) && (o->fields & OUT_POSITION) && o->c_total > 0) {
        /* the contact network: per frame, a line between the centres of each touching pair, coloured by the normal
         * force (frames without a pair are left out: XDMF has no empty polyline) */
        fprintf(fp, "<Grid Name=\"contacts\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
        for (long f = 0; f < F; f++) {
            long long s0 = o->c_frame[2 * f], np = o->c_frame[2 * f + 1];
            if (np < 1)
                continue;
            fprintf(fp, "<Grid Name=\"network %ld\" GridType=\"Uniform\">\n<Time Value=\"%.17g\"/>\n", f, times[f]);
            fprintf(fp, "<Topology TopologyType=\"Polyline\" NumberOfElements=\"%lld\" NodesPerElement=\"2\">\n"
                        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%lld 2\" Type=\"HyperSlab\">\n"
                        "<DataItem Dimensions=\"3 2\" Format=\"XML\">%lld 0 1 1 %lld 2</DataItem>\n"
                        "<DataItem Dimensions=\"%lld 2\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
                        "%s:/contacts/ids</DataItem>\n</DataItem>\n</Topology>\n",
                    np, np, s0, np, o->c_total, h5name);
            fprintf(fp, "<Geometry GeometryType=\"XYZ\">\n"
                        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d 3\" Type=\"HyperSlab\">\n"
                        "<DataItem Dimensions=\"3 3\" Format=\"XML\">%ld 0 0 1 1 1 1 %d 3</DataItem>\n"
                        "<DataItem Dimensions=\"%ld %d 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                        "%s:/frames/position</DataItem>\n</DataItem>\n</Geometry>\n",
                    o->n, f, o->n, F, o->n, h5name);
            fprintf(fp, "<Attribute Name=\"normal_force\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
                        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%lld\" Type=\"HyperSlab\">\n"
                        "<DataItem Dimensions=\"3 1\" Format=\"XML\">%lld 1 %lld</DataItem>\n"
                        "<DataItem Dimensions=\"%lld\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                        "%s:/contacts/normal_force</DataItem>\n</DataItem>\n</Attribute>\n</Grid>\n",
                    np, s0, np, o->c_total, h5name);
        }
        fprintf(fp, "</Grid>\n");
    }
    fprintf(fp, "</Domain>\n</Xdmf>\n");
    free(h5name);
    return fclose(fp) ? -1 : 0;
}

int output_finish(output *o, char *err, size_t errlen)
{
    errno = 0;
    double *times = malloc(sizeof(double) * (size_t)(o->nframes + 1));
    int rc = !times || output_flush(o) ||
             (o->nframes && H5Dread(o->ftime.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, times) < 0);
    int e = errno;
    close_all(o);
    if (H5Fclose(o->file) < 0)
        rc = 1, e = e ? e : errno;
    o->file = -1;
    char xmf[4200], xmf_part[4300];
    output_xmf_path(o->path, xmf, sizeof xmf);
    snprintf(xmf_part, sizeof xmf_part, "%s.part", xmf);
    if (!rc && (write_xdmf(o, xmf_part, times) || rename(o->part, o->path) || rename(xmf_part, xmf)))
        rc = 1, e = errno;
    free(times);
    if (rc)
        snprintf(err, errlen, "%s: cannot finish the output file: %s (what was written is in %s)", o->path,
                 h5_io_reason(e), o->part);
    free(o->buf);
    free(o->c_frame);
    free(o->wlocal);
    free(o->wvert);
    free(o->wbuf);
    free(o);
    return rc;
}

void output_abort(output *o)
{
    if (!o)
        return;
    output_flush(o); /* keep in OUT.part what can still be written (a full disk may refuse it) */
    close_all(o);
    if (o->file > 0)
        H5Fclose(o->file);
    free(o->buf);
    free(o->c_frame);
    free(o->wlocal);
    free(o->wvert);
    free(o->wbuf);
    free(o);
}
