/* scene_schema.c - the scene file format as a libcyaml schema, and loading with located errors.
 * Every key is listed here once; docs/scenes.md describes them for users. libcyaml (1.3) logs an error with a
 * backtrace of keys and lines; the backtrace is turned into a field path ("walls[1].motion[0].velocity"), and the
 * line is the key's own line from scene_locate.c (libyaml events), else the backtrace's innermost line. */
#include "scene.h"
#include <cyaml/cyaml.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

static const cyaml_schema_value_t real_entry = {CYAML_VALUE_FLOAT(CYAML_FLAG_DEFAULT, double)};
static const cyaml_schema_value_t string_entry = {CYAML_VALUE_STRING(CYAML_FLAG_POINTER, char, 0, CYAML_UNLIMITED)};
#define VEC3(key, st, member) CYAML_FIELD_SEQUENCE_FIXED(key, CYAML_FLAG_OPTIONAL, st, member, &real_entry, 3)
#define REAL(key, st, member) CYAML_FIELD_FLOAT(key, CYAML_FLAG_OPTIONAL, st, member)
#define TEXT(key, st, member) CYAML_FIELD_STRING_PTR(key, CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, st, member, 0, \
                                                     CYAML_UNLIMITED)
/* names go into HDF5 attributes (scene_name, wall_names), whose size is limited: keep them short, so that `dem check`
 * refuses what the output could not hold */
#define NAME(key, st, member) CYAML_FIELD_STRING_PTR(key, CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, st, member, 0, 1000)

static const cyaml_schema_field_t material_fields[] = {
    CYAML_FIELD_STRING_PTR("name", CYAML_FLAG_POINTER, scene_material, name, 1, 64),
    REAL("density", scene_material, density), /* required for the materials particles use (scene_build.c) */
    CYAML_FIELD_FLOAT("young", CYAML_FLAG_DEFAULT, scene_material, young),
    CYAML_FIELD_FLOAT("poisson", CYAML_FLAG_DEFAULT, scene_material, poisson),
    CYAML_FIELD_FLOAT("restitution", CYAML_FLAG_DEFAULT, scene_material, restitution),
    REAL("friction", scene_material, friction),
    REAL("beta", scene_material, beta), REAL("gamma", scene_material, gamma),
    REAL("yield_stress", scene_material, yield_stress), REAL("rolling_friction", scene_material, rolling_friction),
    REAL("bond_strength", scene_material, bond_strength), REAL("rolling_damping", scene_material, rolling_damping),
    REAL("surface_energy", scene_material, surface_energy), REAL("bulk_fraction", scene_material, bulk_fraction),
    REAL("mdr_damping", scene_material, mdr_damping),
    CYAML_FIELD_END};
static const cyaml_schema_value_t material_entry = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_material, material_fields)};

static const cyaml_schema_field_t material_pair_fields[] = {
    CYAML_FIELD_SEQUENCE("materials", CYAML_FLAG_POINTER, scene_material_pair, materials, &string_entry, 2, 2),
    REAL("friction", scene_material_pair, friction), REAL("restitution", scene_material_pair, restitution),
    REAL("rolling_friction", scene_material_pair, rolling_friction),
    REAL("bond_strength", scene_material_pair, bond_strength),
    REAL("surface_energy", scene_material_pair, surface_energy),
    CYAML_FIELD_END};
static const cyaml_schema_value_t material_pair_entry = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_material_pair, material_pair_fields)};

static const cyaml_schema_field_t sphere_fields[] = {
    CYAML_FIELD_SEQUENCE_FIXED("x", CYAML_FLAG_DEFAULT, scene_sphere, x, &real_entry, 3),
    VEC3("v", scene_sphere, v), VEC3("w", scene_sphere, w),
    CYAML_FIELD_FLOAT("radius", CYAML_FLAG_DEFAULT, scene_sphere, radius),
    CYAML_FIELD_END};
static const cyaml_schema_value_t sphere_entry = {CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_sphere, sphere_fields)};

static const cyaml_schema_field_t region_fields[] = {
    VEC3("lo", scene_region, lo), VEC3("hi", scene_region, hi), VEC3("base", scene_region, base),
    VEC3("axis", scene_region, axis), REAL("radius", scene_region, radius), REAL("height", scene_region, height),
    CYAML_FIELD_END};

static const cyaml_schema_field_t lognormal_fields[] = {
    CYAML_FIELD_FLOAT("median", CYAML_FLAG_DEFAULT, scene_lognormal, median),
    CYAML_FIELD_FLOAT("sigma", CYAML_FLAG_DEFAULT, scene_lognormal, sigma), CYAML_FIELD_END};
static const cyaml_schema_field_t size_fields[] = {
    CYAML_FIELD_FLOAT("radius", CYAML_FLAG_DEFAULT, scene_size, radius),
    CYAML_FIELD_FLOAT("fraction", CYAML_FLAG_DEFAULT, scene_size, fraction), CYAML_FIELD_END};
static const cyaml_schema_value_t size_entry = {CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_size, size_fields)};

static const cyaml_schema_field_t generate_fields[] = {
    CYAML_FIELD_STRING_PTR("kind", CYAML_FLAG_POINTER, scene_generate, kind, 1, 16),
    CYAML_FIELD_STRING_PTR("shape", CYAML_FLAG_POINTER, scene_generate, shape, 1, 16),
    CYAML_FIELD_MAPPING("region", CYAML_FLAG_DEFAULT, scene_generate, region, region_fields),
    CYAML_FIELD_UINT("count", CYAML_FLAG_OPTIONAL, scene_generate, count),
    REAL("radius", scene_generate, radius), REAL("radius_min", scene_generate, radius_min),
    REAL("radius_max", scene_generate, radius_max), REAL("spacing", scene_generate, spacing),
    REAL("speed", scene_generate, speed),
    CYAML_FIELD_MAPPING_PTR("lognormal", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_generate, lognormal,
                            lognormal_fields),
    CYAML_FIELD_SEQUENCE("sizes", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_generate, sizes, &size_entry, 1, 64),
    CYAML_FIELD_STRING_PTR("fractions", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_generate, fractions, 1, 16),
    CYAML_FIELD_UINT("seed", CYAML_FLAG_OPTIONAL, scene_generate, seed),
    CYAML_FIELD_END};

static const cyaml_schema_field_t particles_fields[] = {
    CYAML_FIELD_STRING_PTR("material", CYAML_FLAG_POINTER, scene_particles, material, 1, 64),
    CYAML_FIELD_SEQUENCE("spheres", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_particles, spheres, &sphere_entry,
                         1, CYAML_UNLIMITED),
    TEXT("csv", scene_particles, csv),
    TEXT("csv_density", scene_particles, csv_density),
    CYAML_FIELD_MAPPING_PTR("generate", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_particles, generate,
                            generate_fields),
    CYAML_FIELD_SEQUENCE("hold", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_particles, hold, &string_entry, 1, 3),
    CYAML_FIELD_BOOL("fixed_rotation", CYAML_FLAG_OPTIONAL, scene_particles, fixed_rotation),
    CYAML_FIELD_END};
static const cyaml_schema_value_t particles_entry = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_particles, particles_fields)};

static const cyaml_schema_field_t stage_fields[] = {
    VEC3("velocity", scene_stage, velocity), REAL("duration", scene_stage, duration),
    REAL("distance", scene_stage, distance), REAL("strain", scene_stage, strain), REAL("length", scene_stage, length),
    REAL("force", scene_stage, force), REAL("stress", scene_stage, stress), REAL("area", scene_stage, area),
    REAL("gain", scene_stage, gain), REAL("max_speed", scene_stage, max_speed),
    REAL("until_force", scene_stage, until_force), REAL("until_stress", scene_stage, until_stress),
    REAL("until_distance", scene_stage, until_distance), REAL("until_density", scene_stage, until_density),
    REAL("ramp", scene_stage, ramp), NAME("after", scene_stage, after),
    CYAML_FIELD_END};
static const cyaml_schema_value_t stage_entry = {CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_stage, stage_fields)};

static const cyaml_schema_field_t cup_fields[] = {
    CYAML_FIELD_FLOAT("radius", CYAML_FLAG_DEFAULT, scene_cup, radius),
    CYAML_FIELD_FLOAT("depth", CYAML_FLAG_DEFAULT, scene_cup, depth), CYAML_FIELD_END};

static const cyaml_schema_field_t wall_fields[] = {
    CYAML_FIELD_STRING_PTR("type", CYAML_FLAG_POINTER, scene_wall, type, 1, 16),
    NAME("name", scene_wall, name),
    CYAML_FIELD_STRING_PTR("material", CYAML_FLAG_POINTER, scene_wall, material, 1, 64),
    VEC3("point", scene_wall, point), VEC3("normal", scene_wall, normal), VEC3("axis", scene_wall, axis),
    REAL("radius", scene_wall, radius), REAL("height", scene_wall, height), VEC3("lo", scene_wall, lo),
    VEC3("hi", scene_wall, hi),
    CYAML_FIELD_BOOL("rigid", CYAML_FLAG_OPTIONAL, scene_wall, rigid),
    CYAML_FIELD_UINT("repeat", CYAML_FLAG_OPTIONAL, scene_wall, repeat),
    CYAML_FIELD_MAPPING_PTR("cup", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_wall, cup, cup_fields),
    CYAML_FIELD_SEQUENCE("motion", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_wall, motion, &stage_entry, 0,
                         DEM_MAX_STAGES - 1),
    CYAML_FIELD_END};
static const cyaml_schema_value_t wall_entry = {CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_wall, wall_fields)};

static const cyaml_schema_field_t mesh_fields[] = {
    CYAML_FIELD_STRING_PTR("kind", CYAML_FLAG_POINTER, scene_mesh, kind, 1, 16),
    VEC3("center", scene_mesh, center), REAL("radius", scene_mesh, radius), REAL("height", scene_mesh, height),
    CYAML_FIELD_SEQUENCE_FIXED("size", CYAML_FLAG_OPTIONAL, scene_mesh, size, &real_entry, 2),
    REAL("edge", scene_mesh, edge), TEXT("path", scene_mesh, path), REAL("scale", scene_mesh, scale),
    VEC3("translate", scene_mesh, translate), CYAML_FIELD_BOOL("flip", CYAML_FLAG_OPTIONAL, scene_mesh, flip),
    CYAML_FIELD_END};

static const cyaml_schema_field_t membrane_material_fields[] = {
    CYAML_FIELD_FLOAT("young", CYAML_FLAG_DEFAULT, scene_membrane_material, young),
    CYAML_FIELD_FLOAT("poisson", CYAML_FLAG_DEFAULT, scene_membrane_material, poisson),
    CYAML_FIELD_FLOAT("thickness", CYAML_FLAG_DEFAULT, scene_membrane_material, thickness),
    CYAML_FIELD_FLOAT("density", CYAML_FLAG_DEFAULT, scene_membrane_material, density),
    CYAML_FIELD_FLOAT("restitution", CYAML_FLAG_DEFAULT, scene_membrane_material, restitution),
    REAL("friction", scene_membrane_material, friction), REAL("damping", scene_membrane_material, damping),
    REAL("kel", scene_membrane_material, kel), REAL("kdiss", scene_membrane_material, kdiss),
    REAL("vertex_radius", scene_membrane_material, vertex_radius), CYAML_FIELD_END};

static const cyaml_schema_field_t attach_fields[] = {
    CYAML_FIELD_STRING_PTR("wall", CYAML_FLAG_POINTER, scene_attach, wall, 1, 1000),
    CYAML_FIELD_FLOAT("within", CYAML_FLAG_DEFAULT, scene_attach, within), CYAML_FIELD_END};
static const cyaml_schema_value_t attach_entry = {CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_attach, attach_fields)};

static const cyaml_schema_field_t pressure_stage_fields[] = {
    CYAML_FIELD_FLOAT("duration", CYAML_FLAG_DEFAULT, scene_pressure_stage, duration),
    CYAML_FIELD_FLOAT("pressure", CYAML_FLAG_DEFAULT, scene_pressure_stage, pressure), CYAML_FIELD_END};
static const cyaml_schema_value_t pressure_stage_entry = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_pressure_stage, pressure_stage_fields)};

static const cyaml_schema_field_t membrane_fields[] = {
    NAME("name", scene_membrane, name),
    CYAML_FIELD_MAPPING("mesh", CYAML_FLAG_DEFAULT, scene_membrane, mesh, mesh_fields),
    CYAML_FIELD_MAPPING("material", CYAML_FLAG_DEFAULT, scene_membrane, material, membrane_material_fields),
    TEXT("model", scene_membrane, model),
    REAL("pressure", scene_membrane, pressure),
    CYAML_FIELD_SEQUENCE("pressure_stages", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_membrane, pressure_stages,
                         &pressure_stage_entry, 1, DEM_MAX_STAGES),
    CYAML_FIELD_SEQUENCE("attach", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_membrane, attach, &attach_entry, 1,
                         DEM_MAX_WALLS),
    CYAML_FIELD_BOOL("fixed", CYAML_FLAG_OPTIONAL, scene_membrane, fixed),
    CYAML_FIELD_END};
static const cyaml_schema_value_t membrane_entry = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, scene_membrane, membrane_fields)};

static const cyaml_schema_field_t time_fields[] = {
    REAL("dt", scene_time, dt), REAL("dt_rayleigh", scene_time, dt_rayleigh),
    CYAML_FIELD_FLOAT("duration", CYAML_FLAG_DEFAULT, scene_time, duration), REAL("settle", scene_time, settle),
    REAL("mass_scale", scene_time, mass_scale), TEXT("mass_scale_keeps", scene_time, mass_scale_keeps), CYAML_FIELD_END};

static const cyaml_schema_field_t output_fields[] = {
    REAL("frame_every", scene_output, frame_every), REAL("series_every", scene_output, series_every),
    CYAML_FIELD_UINT("series_average", CYAML_FLAG_OPTIONAL, scene_output, series_average),
    REAL("checkpoint_every", scene_output, checkpoint_every),
    CYAML_FIELD_SEQUENCE("fields", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_output, fields, &string_entry, 0,
                         16),
    CYAML_FIELD_END};

static const cyaml_schema_field_t sample_fields[] = {
    CYAML_FIELD_STRING_PTR("piston", CYAML_FLAG_POINTER, scene_sample, piston, 1, 64),
    REAL("height", scene_sample, height), REAL("area", scene_sample, area),
    REAL("contact_travel", scene_sample, contact_travel), CYAML_FIELD_END};

static const cyaml_schema_field_t mcs_convention_fields[] = {
    TEXT("own_contact", scene_mcs_convention, own_contact), TEXT("lever", scene_mcs_convention, lever),
    TEXT("scale", scene_mcs_convention, scale), CYAML_FIELD_END};

static const cyaml_schema_field_t domain_fields[] = {
    CYAML_FIELD_SEQUENCE_FIXED("lo", CYAML_FLAG_DEFAULT, scene_file, domain_lo, &real_entry, 3),
    CYAML_FIELD_SEQUENCE_FIXED("hi", CYAML_FLAG_DEFAULT, scene_file, domain_hi, &real_entry, 3), CYAML_FIELD_END};

/* "domain" maps onto two members of scene_file itself: a mapping field at offset 0 whose fields carry their own
 * offsets into scene_file. */
static const cyaml_schema_field_t scene_fields[] = {
    NAME("name", scene_file, name),
    TEXT("description", scene_file, description),
    TEXT("precision", scene_file, precision),
    CYAML_FIELD_INT("device", CYAML_FLAG_OPTIONAL, scene_file, device),
    TEXT("backend", scene_file, backend),
    TEXT("particle_order", scene_file, particle_order),
    CYAML_FIELD_SEQUENCE("effects", CYAML_FLAG_POINTER, scene_file, effects, &string_entry, 1, 16),
    CYAML_FIELD_SEQUENCE("materials", CYAML_FLAG_POINTER, scene_file, materials, &material_entry, 1, 64),
    CYAML_FIELD_SEQUENCE("material_pairs", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_file, material_pairs,
                         &material_pair_entry, 0, 256),
    CYAML_FIELD_SEQUENCE("particles", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_file, particles, &particles_entry, 0, 64),
    CYAML_FIELD_SEQUENCE("walls", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_file, walls, &wall_entry, 0, DEM_MAX_WALLS),
    CYAML_FIELD_SEQUENCE("membranes", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_file, membranes,
                         &membrane_entry, 0, 16),
    VEC3("gravity", scene_file, gravity),
    {.key = "domain", .data_offset = 0,
     .value = {.type = CYAML_MAPPING, .flags = CYAML_FLAG_OPTIONAL, .data_size = sizeof(scene_file),
               .mapping = {.fields = domain_fields}}},
    REAL("overlap_tolerance", scene_file, overlap_tolerance),
    CYAML_FIELD_MAPPING("time", CYAML_FLAG_DEFAULT, scene_file, time, time_fields),
    CYAML_FIELD_MAPPING("output", CYAML_FLAG_OPTIONAL, scene_file, output, output_fields),
    CYAML_FIELD_MAPPING_PTR("sample", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_file, sample, sample_fields),
    CYAML_FIELD_INT("mc_iterations", CYAML_FLAG_OPTIONAL, scene_file, mc_iterations),
    REAL("mc_tolerance", scene_file, mc_tolerance),
    REAL("mc_contact_distance", scene_file, mc_contact_distance),
    CYAML_FIELD_MAPPING_PTR("mc_stress_convention", CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER, scene_file,
                            mc_stress_convention, mcs_convention_fields),
    CYAML_FIELD_END};

static const cyaml_schema_value_t scene_schema = {CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, scene_file, scene_fields)};

/* The libcyaml type of the value at a located path such as "particles[0].spheres[1].x[2]", or -1. */
static int schema_type_at(const char *path)
{
    const cyaml_schema_field_t *fields = scene_fields;
    const cyaml_schema_value_t *v = NULL;
    const char *p = path;
    while (*p) {
        size_t n = strcspn(p, ".[");
        if (n == 0 || !fields)
            return -1;
        const cyaml_schema_field_t *f = fields;
        while (f->key && (strlen(f->key) != n || strncmp(f->key, p, n)))
            f++;
        if (!f->key)
            return -1;
        v = &f->value;
        p += n;
        while (*p == '[') {
            const char *e = strchr(p, ']');
            if (!e || (v->type != CYAML_SEQUENCE && v->type != CYAML_SEQUENCE_FIXED))
                return -1;
            v = v->sequence.entry;
            p = e + 1;
        }
        fields = v->type == CYAML_MAPPING ? v->mapping.fields : NULL;
        if (*p == '.')
            p++;
    }
    return v ? (int)v->type : -1;
}

/* libcyaml reads a number from its front and drops the rest ("0.004 mm" is 0.004, "2_500" is 2, "1e12" for an int
 * is 1): every scalar of a numeric field must be one number, whole, before libcyaml sees it. 0 when all are. */
static int check_numbers(const scene *sc, const char *path, char *err, size_t errlen)
{
    const char *fp, *val;
    int line;
    for (size_t k = 0; scene_scalar(sc->loc, k, &fp, &val, &line); k++) {
        if (!val)
            continue;
        int t = schema_type_at(fp);
        if (t != CYAML_INT && t != CYAML_UINT && t != CYAML_FLOAT)
            continue;
        char *end;
        errno = 0;
        int range = 0;
        if (t == CYAML_FLOAT) {
            double d = strtod(val, &end);
            range = errno == ERANGE && (d == HUGE_VAL || d == -HUGE_VAL); /* underflow is left to the field checks */
        } else {
            (void)strtoll(val, &end, 10);
            range = errno == ERANGE;
        }
        if (range) {
            snprintf(err, errlen, "%s:%d: %s: '%s' is out of range", path, line, fp, val);
            return 1;
        }
        const char *digits = val + (*val == '-' || *val == '+');
        if (end == val || *end || (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X'))) { /* strtod reads hex */
            snprintf(err, errlen, "%s:%d: %s: '%s' is not %s%s", path, line, fp, val,
                     t == CYAML_FLOAT ? "a number" : "a whole number",
                     t == CYAML_FLOAT ? " (values are plain SI numbers: write 0.004 for 4 mm, no units or '_')" : "");
            return 1;
        }
    }
    return 0;
}

/* libcyaml's messages, collected: the first error line and the backtrace of keys under it. */
typedef struct {
    char msg[512];
    char path[512];
    int in_backtrace;
    int line;      /* line of the innermost backtrace entry */
    int last_seq;  /* the path so far starts with a sequence entry */
} cyaml_log_capture;

static void trim_newline(char *s)
{
    size_t n = strlen(s);
    while (n && (s[n - 1] == '\n' || s[n - 1] == ' '))
        s[--n] = 0;
}

/* Backtrace lines come innermost first: "  in mapping field 'x' (line: 11, column: 13)", "  in sequence entry '2'
 * (line: ...)" (entries counted from 1), "  in mapping (line: ...)". They are prepended to the path being built. */
static void capture_log(cyaml_log_t level, void *ctx, const char *fmt, va_list args)
{
    cyaml_log_capture *c = ctx;
    char line[512];
    vsnprintf(line, sizeof line, fmt, args);
    trim_newline(line);
    if (getenv("DEM_DEBUG_CYAML"))
        fprintf(stderr, "[libcyaml] %s\n", line);
    if (level < CYAML_LOG_ERROR)
        return;
    const char *body = strncmp(line, "Load: ", 6) == 0 ? line + 6 : line;
    if (strstr(body, "Backtrace:")) {
        c->in_backtrace = 1;
        return;
    }
    if (c->in_backtrace) {
        const char *ln = strstr(body, "(line: ");
        if (ln && !c->line)
            c->line = atoi(ln + 7);
        const char *f = strstr(body, "in mapping field '"), *e = strstr(body, "in sequence entry '");
        if (!f && !e)
            return;
        const char *start = f ? f + 18 : e + 19, *q = strchr(start, '\'');
        if (!q)
            return;
        char part[256], tmp[800];
        if (f)
            snprintf(part, sizeof part, "%.*s", (int)(q - start), start);
        else
            snprintf(part, sizeof part, "[%d]", atoi(start) - 1);
        snprintf(tmp, sizeof tmp, "%s%s%s", part, (c->path[0] && c->path[0] != '[') ? "." : "", c->path);
        snprintf(c->path, sizeof c->path, "%s", tmp);
        return;
    }
    if (!c->msg[0])
        snprintf(c->msg, sizeof c->msg, "%s", body);
}

/* The key written on line `line` of text ("  - key: value" or "key:"), into buf; "" when the line has none */
static void key_on_line(const char *text, size_t len, int line, char *buf, size_t blen)
{
    size_t at = 0;
    for (int l = 1; l < line && at < len; at++)
        l += text[at] == '\n';
    while (at < len && (text[at] == ' ' || text[at] == '-'))
        at++;
    size_t k = 0;
    while (at + k < len && k + 1 < blen && (isalnum((unsigned char)text[at + k]) || text[at + k] == '_'))
        k++;
    int is_key = k > 0 && at + k < len && text[at + k] == ':';
    snprintf(buf, blen, "%.*s", is_key ? (int)k : 0, text + at);
}

static char *dup_str(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = 0;
    }
    return d;
}

/* Optimal string alignment distance (Levenshtein with swaps of two neighbours), for "did you mean" */
static int edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 64 || lb > 64) /* names are short; a long one is no typo of a key */
        return 99;
    int d[65][65];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int c = a[i - 1] != b[j - 1], v = d[i - 1][j - 1] + c;
            v = d[i - 1][j] + 1 < v ? d[i - 1][j] + 1 : v;
            v = d[i][j - 1] + 1 < v ? d[i][j - 1] + 1 : v;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < v)
                v = d[i - 2][j - 2] + 1;
            d[i][j] = v;
        }
    return d[la][lb];
}

const char *scene_did_you_mean(const char *word, const char *const *cands, int n, char *buf, size_t len)
{
    size_t lw = strlen(word);
    int limit = lw <= 4 ? 1 : lw <= 8 ? 2 : 3, best = limit + 1;
    const char *pick = NULL;
    for (int k = 0; k < n; k++) {
        if (!cands[k] || !strcmp(cands[k], word))
            continue;
        int d = edit_distance(word, cands[k]);
        if (d < best)
            best = d, pick = cands[k];
    }
    if (len)
        buf[0] = 0;
    if (pick)
        snprintf(buf, len, " (did you mean '%.200s'?)", pick);
    return buf;
}

const char *scene_wall_hint(const scene *sc, const char *word, int planes_only, char *buf, size_t len)
{
    const char *names[DEM_MAX_WALLS];
    int n = 0;
    for (unsigned w = 0; w < sc->f->walls_count && n < DEM_MAX_WALLS; w++)
        if (sc->f->walls[w].name && (!planes_only || (sc->f->walls[w].type && !strcmp(sc->f->walls[w].type, "plane"))))
            names[n++] = sc->f->walls[w].name;
    return scene_did_you_mean(word, names, n, buf, len);
}

const char *scene_material_hint(const scene *sc, const char *word, char *buf, size_t len)
{
    const char *names[64];
    int n = 0;
    for (unsigned m = 0; m < sc->f->materials_count && n < 64; m++)
        names[n++] = sc->f->materials[m].name;
    return scene_did_you_mean(word, names, n, buf, len);
}

/* The keys the schema knows in the mapping at path ("particles[0].generate"; "" the top level): follows the path's
 * keys through the schema's mappings and sequences. Returns their count (0 when the path leads to no mapping). */
static int schema_keys_at(const char *path, const char **keys, int max)
{
    const cyaml_schema_value_t *v = &scene_schema;
    char seg[128];
    const char *p = path;
    while (*p) {
        size_t l = strcspn(p, ".[");
        if (l) { /* a key: the field of that name in the current mapping */
            snprintf(seg, sizeof seg, "%.*s", (int)(l < sizeof seg - 1 ? l : sizeof seg - 1), p);
            if (v->type != CYAML_MAPPING)
                return 0;
            const cyaml_schema_field_t *f = v->mapping.fields;
            while (f->key && strcmp(f->key, seg))
                f++;
            if (!f->key)
                return 0;
            v = &f->value;
            p += l;
        } else if (*p == '[') { /* an index: the sequence's entry */
            if (v->type != CYAML_SEQUENCE && v->type != CYAML_SEQUENCE_FIXED)
                return 0;
            v = v->sequence.entry;
            p = strchr(p, ']') ? strchr(p, ']') + 1 : p + strlen(p);
        } else {
            p++; /* the '.' between keys */
        }
    }
    if (v->type != CYAML_MAPPING)
        return 0;
    int n = 0;
    for (const cyaml_schema_field_t *f = v->mapping.fields; f->key && n < max; f++)
        keys[n++] = f->key;
    return n;
}

scene *scene_load_text(const char *path, const char *text, size_t len, char *err, size_t errlen)
{
    scene *sc = calloc(1, sizeof *sc);
    if (!sc) {
        snprintf(err, errlen, "%s: out of memory", path);
        return NULL;
    }
    sc->path = dup_str(path, strlen(path));
    const char *slash = strrchr(path, '/');
    sc->dir = slash ? dup_str(path, (size_t)(slash - path)) : dup_str(".", 1);
    sc->text = dup_str(text, len);
    sc->text_len = len;
    if (!sc->path || !sc->dir || !sc->text) {
        snprintf(err, errlen, "%s: out of memory", path);
        scene_free(sc);
        return NULL;
    }
    sc->loc = scene_locate(text, len);
    int sline;
    const char *syntax = scene_syntax_error(sc->loc, &sline);
    if (syntax) {
        /* a syntax error first, from libyaml's own reason and line, named by the key written on that line (the
         * path libcyaml was in is the key before it when an indent is wrong, and the values it met before the error
         * are half-read) */
        char key[128];
        key_on_line(text, len, sline, key, sizeof key);
        snprintf(err, errlen, "%s:%d: %s%sYAML syntax error: %s (check this line's indentation, brackets and quotes, "
                              "and the line before)", path, sline, key, key[0] ? ": " : "", syntax);
        scene_free(sc);
        return NULL;
    }
    const char *dpath;
    int dfirst, dline = scene_duplicate(sc->loc, &dpath, &dfirst);
    if (dline > 0 && scene_line(sc->loc, "#error") == 0) {
        snprintf(err, errlen, "%s:%d: %s: the key is given twice (first at line %d); keep one", path, dline, dpath,
                 dfirst);
        scene_free(sc);
        return NULL;
    }
    if (check_numbers(sc, path, err, errlen)) {
        scene_free(sc);
        return NULL;
    }
    int second = scene_line(sc->loc, "#second_document");
    if (second > 0) { /* libcyaml would read the first document and drop the rest without a word */
        snprintf(err, errlen, "%s:%d: a second YAML document starts here: a scene is one document (remove the '---' "
                              "and merge the keys, or split it into two scene files)", path, second);
        scene_free(sc);
        return NULL;
    }
    cyaml_log_capture cap = {{0}, {0}, 0, 0, 0};
    cyaml_config_t cfg = {.log_fn = capture_log, .log_ctx = &cap, .mem_fn = cyaml_mem, .log_level = CYAML_LOG_ERROR,
                          .flags = CYAML_CFG_NO_ALIAS};
    cyaml_err_t e = cyaml_load_data((const uint8_t *)text, len, &cfg, &scene_schema, (cyaml_data_t **)&sc->f, NULL);
    if (e != CYAML_OK) {
        char full[800];
        snprintf(full, sizeof full, "%s", cap.path);
        /* a sequence with too few or too many entries: the error is the sequence's, not its last entry's */
        if (strstr(cap.msg, "entries") && full[0] && full[strlen(full) - 1] == ']')
            *strrchr(full, '[') = 0;
        /* a missing key: the backtrace ends at the mapping's last key read; the error belongs to the mapping */
        const char *mk = strstr(cap.msg, "Missing required mapping field: ");
        if (mk && full[0] && full[strlen(full) - 1] != ']') {
            char *cut = strrchr(full, '.');
            if (cut)
                *cut = 0;
            else
                full[0] = 0;
        }
        /* an unknown key is reported as "Unexpected key: k" inside its mapping */
        const char *uk = strstr(cap.msg, "Unexpected key: ");
        char hint[300] = "";
        if (uk) {
            const char *keys[64];
            char word[128];
            snprintf(word, sizeof word, "%.*s", (int)strcspn(uk + 16, " \n"), uk + 16);
            scene_did_you_mean(word, keys, schema_keys_at(full, keys, 64), hint, sizeof hint); /* before full grows */
            size_t l = strlen(full);
            snprintf(full + l, sizeof full - l, "%s%s", l ? "." : "", uk + 16);
        }
        int line = scene_line(sc->loc, full);
        if (strstr(cap.msg, "libyaml") && scene_line(sc->loc, "#error")) /* a syntax error: where libyaml stopped */
            line = scene_line(sc->loc, "#error");
        if (mk) { /* name the missing key in the path; the line is its mapping's */
            size_t l = strlen(full);
            snprintf(full + l, sizeof full - l, "%s%s", l ? "." : "", mk + 32);
            if (!line)
                line = 1;
            cap.line = 0;
        }
        if (!line)
            line = cap.line;
        if (!line)
            line = scene_line(sc->loc, "#error"); /* a YAML syntax error: where libyaml stopped */
        snprintf(err, errlen, "%s:%d: %s%s%s (%s)%s", path, line, full[0] ? full : "", full[0] ? ": " : "",
                 cap.msg[0] ? cap.msg : "invalid scene", cyaml_strerror(e), hint);
        sc->f = NULL;
        scene_free(sc);
        return NULL;
    }
    if (!sc->f) { /* an empty document loads as nothing */
        snprintf(err, errlen, "%s:1: effects: missing: the scene is empty (it needs effects, materials, particles and "
                              "time)", path);
        scene_free(sc);
        return NULL;
    }
    return sc;
}

FILE *scene_open_regular(const char *path, char *why, size_t len)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC); /* O_NONBLOCK: a pipe with no writer does not block */
    struct stat sb;
    if (fd < 0 || fstat(fd, &sb) != 0) {
        snprintf(why, len, "%s", strerror(errno));
        if (fd >= 0)
            close(fd);
        return NULL;
    }
    if (!S_ISREG(sb.st_mode)) {
        snprintf(why, len, "not a regular file (%s)", S_ISDIR(sb.st_mode) ? "a folder" : S_ISFIFO(sb.st_mode) ? "a pipe"
                           : S_ISSOCK(sb.st_mode) ? "a socket" : "a device");
        close(fd);
        return NULL;
    }
    FILE *fp = fcntl(fd, F_SETFL, 0) == 0 ? fdopen(fd, "rb") : NULL;
    if (!fp) {
        snprintf(why, len, "%s", strerror(errno));
        close(fd);
    }
    return fp;
}

scene *scene_load(const char *path, char *err, size_t errlen)
{
    char why[256];
    FILE *fp = scene_open_regular(path, why, sizeof why);
    if (!fp) {
        snprintf(err, errlen, "%s:0: cannot open the scene file: %s", path, why);
        return NULL;
    }
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + len, 1, cap - len, fp)) > 0;) {
        len += got;
        if (len == cap) {
            char *nb = len < ((size_t)1 << 30) ? realloc(buf, cap *= 2) : NULL;
            if (!nb)
                free(buf);
            buf = nb;
        }
    }
    int bad = ferror(fp);
    fclose(fp);
    if (!buf || bad) {
        free(buf);
        snprintf(err, errlen, "%s:0: cannot read the scene file%s", path, buf ? "" : " (too large or out of memory)");
        return NULL;
    }
    scene *sc = scene_load_text(path, buf, len, err, errlen);
    free(buf);
    return sc;
}

void scene_file_path(const scene *sc, const char *name, char *buf, size_t len)
{
    if (name[0] == '/')
        snprintf(buf, len, "%s", name);
    else
        snprintf(buf, len, "%s/%s", sc->dir, name);
}

void scene_free(scene *sc)
{
    if (!sc)
        return;
    if (sc->f) {
        cyaml_config_t cfg = {.log_fn = cyaml_log, .mem_fn = cyaml_mem, .log_level = CYAML_LOG_ERROR};
        cyaml_free(&cfg, &scene_schema, sc->f, 0);
    }
    scene_locator_free(sc->loc);
    free(sc->path);
    free(sc->dir);
    free(sc->text);
    free(sc);
}

/* the library walls a scene wall adds: a box its six planes, any other wall one */
static int walls_of(const scene_wall *w) { return w->type && !strcmp(w->type, "box") ? 6 : 1; }

int scene_first_wall(const scene *sc, unsigned k)
{
    int at = 0;
    for (unsigned i = 0; i < k && i < sc->f->walls_count; i++)
        at += walls_of(&sc->f->walls[i]);
    return at;
}

/* Library wall k's name: the scene's (or walls[i]); a box's six faces "NAME x-", "NAME x+", ... (dem_add_box's
 * order); "?" past the last */
void scene_wall_label(const scene *sc, int k, char *buf, size_t len)
{
    static const char *face[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
    int at = 0;
    snprintf(buf, len, "?");
    for (unsigned i = 0; i < sc->f->walls_count; i++) {
        const scene_wall *w = &sc->f->walls[i];
        int nw = walls_of(w), box = nw == 6;
        if (k < at + nw) {
            char own[32];
            snprintf(own, sizeof own, "walls[%u]", i);
            const char *nm = w->name ? w->name : own;
            if (box)
                snprintf(buf, len, "%s %s", nm, face[k - at]);
            else
                snprintf(buf, len, "%s", nm);
            return;
        }
        at += nw;
    }
}
