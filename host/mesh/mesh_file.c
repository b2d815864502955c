/* mesh_file.c - dem_mesh_read: a triangle mesh from a Wavefront OBJ or an STL (ASCII or binary) file, strictly.
 *
 * No library: Debian's candidates are Assimp (a large C++ importer whose OBJ errors name no line, and which
 * repairs what it reads) and ADMesh (STL only); a membrane needs neither materials nor normals, only vertices and
 * triangles, and a wrong file must be refused with its line, not repaired. What is read:
 *   OBJ: `v x y z [w]` and `f a b c` (triangles only; a/t/n, a//n forms; negative indices count back), `#` comments;
 *        vt, vn, vp, o, g, s, usemtl, mtllib, l are ignored; anything else, a polygon of more than three corners, an
 *        index out of range, a number that is not one, is refused with its line.
 *   STL: ASCII (`solid ... facet normal ... outer loop, vertex x y z x3, endloop, endfacet ... endsolid`, refused with
 *        its line) or binary (80-byte header, count, 50 bytes a triangle; the size must match the count). STL repeats
 *        a vertex in every facet: equal coordinates (bit for bit) become one vertex, numbered in order of first use.
 * Triangles keep the file's order and orientation; degenerate ones (a repeated corner) are refused. */
#include "dem.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#define MESH_FILE_MAX 2000000 /* vertices and triangles, as host/mesh/mesh.c's generated meshes */

typedef struct {
    double *x;
    int *tri;
    int nv, nt, capv, capt;
} grow_mesh;

static int add_vertex(grow_mesh *g, const double p[3])
{
    if (g->nv == g->capv) {
        int c = g->capv ? 2 * g->capv : 1024;
        double *x = realloc(g->x, sizeof(double) * 3 * (size_t)c);
        if (!x)
            return -1;
        g->x = x, g->capv = c;
    }
    memcpy(g->x + 3 * g->nv, p, sizeof(double) * 3);
    return g->nv++;
}

static int add_tri(grow_mesh *g, const int t[3])
{
    if (g->nt == g->capt) {
        int c = g->capt ? 2 * g->capt : 1024;
        int *tri = realloc(g->tri, sizeof(int) * 3 * (size_t)c);
        if (!tri)
            return -1;
        g->tri = tri, g->capt = c;
    }
    memcpy(g->tri + 3 * g->nt, t, sizeof(int) * 3);
    return g->nt++;
}

/* a whole number token as a double, or 0 */
static int number(const char *tok, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(tok, &end);
    return tok[0] && !*end && errno != ERANGE && isfinite(*v);
}

static int read_obj(FILE *fp, const char *path, grow_mesh *g, char *err, size_t errlen)
{
    char line[4096];
    int ln = 0;
    while (fgets(line, sizeof line, fp)) {
        ln++;
        if (!strchr(line, '\n') && !feof(fp))
            return snprintf(err, errlen, "%s:%d: line longer than %zu characters", path, ln, sizeof line - 2), -1;
        char *save, *tok = strtok_r(line, " \t\r\n", &save);
        if (!tok || tok[0] == '#')
            continue;
        if (!strcmp(tok, "v")) {
            double p[3];
            int k = 0;
            char *t;
            while ((t = strtok_r(NULL, " \t\r\n", &save))) {
                double v;
                if (!number(t, &v))
                    return snprintf(err, errlen, "%s:%d: vertex: '%s' is not a finite number", path, ln, t), -1;
                if (k < 3)
                    p[k] = v;
                k++;
            }
            if (k != 3 && k != 4)
                return snprintf(err, errlen, "%s:%d: vertex: %d numbers (want x y z, or x y z w)", path, ln, k), -1;
            if (g->nv >= MESH_FILE_MAX)
                return snprintf(err, errlen, "%s:%d: more than %d vertices", path, ln, MESH_FILE_MAX), -1;
            if (add_vertex(g, p) < 0)
                return snprintf(err, errlen, "%s:%d: out of host memory", path, ln), DEM_ERR_NOMEM;
        } else if (!strcmp(tok, "f")) {
            int t[3], k = 0;
            char *c;
            while ((c = strtok_r(NULL, " \t\r\n", &save))) {
                char *end;
                errno = 0;
                long i = strtol(c, &end, 10);
                if (end == c || (*end && *end != '/') || errno == ERANGE)
                    return snprintf(err, errlen, "%s:%d: face: '%s' is not a vertex index", path, ln, c), -1;
                long idx = i > 0 ? i - 1 : i < 0 ? g->nv + i : -1;
                if (idx < 0 || idx >= g->nv)
                    return snprintf(err, errlen, "%s:%d: face: vertex %ld does not exist (%d so far)", path, ln, i,
                                    g->nv), -1;
                if (k < 3)
                    t[k] = (int)idx;
                k++;
            }
            if (k != 3)
                return snprintf(err, errlen, "%s:%d: face: %d corners (only triangles)", path, ln, k), -1;
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                return snprintf(err, errlen, "%s:%d: face: a corner is repeated", path, ln), -1;
            if (g->nt >= MESH_FILE_MAX)
                return snprintf(err, errlen, "%s:%d: more than %d triangles", path, ln, MESH_FILE_MAX), -1;
            if (add_tri(g, t) < 0)
                return snprintf(err, errlen, "%s:%d: out of host memory", path, ln), DEM_ERR_NOMEM;
        } else if (strcmp(tok, "vt") && strcmp(tok, "vn") && strcmp(tok, "vp") && strcmp(tok, "o") &&
                   strcmp(tok, "g") && strcmp(tok, "s") && strcmp(tok, "usemtl") && strcmp(tok, "mtllib") &&
                   strcmp(tok, "l"))
            return snprintf(err, errlen, "%s:%d: unknown statement '%.40s'", path, ln, tok), -1;
    }
    return 0;
}

/* STL: vertices merged where their coordinates are equal bit for bit (sorted copy, then binary search) */
typedef struct {
    double p[3];
    int first; /* index of the corner that used it first */
} corner;

static int cmp_corner(const void *a, const void *b)
{
    const corner *u = a, *v = b;
    int c = memcmp(u->p, v->p, sizeof u->p);
    return c ? c : (u->first > v->first) - (u->first < v->first);
}

static int stl_finish(const double *c, int ncorners, grow_mesh *g, const char *path, char *err, size_t errlen)
{
    corner *s = malloc(sizeof(corner) * (size_t)(ncorners ? ncorners : 1));
    int *id = malloc(sizeof(int) * (size_t)(ncorners ? ncorners : 1));
    if (!s || !id)
        return free(s), free(id), snprintf(err, errlen, "%s: out of memory", path), DEM_ERR_NOMEM;
    for (int k = 0; k < ncorners; k++) {
        memcpy(s[k].p, c + 3 * k, sizeof s[k].p);
        s[k].p[0] += 0.0, s[k].p[1] += 0.0, s[k].p[2] += 0.0; /* -0 and +0 alike */
        s[k].first = k;
    }
    qsort(s, (size_t)ncorners, sizeof *s, cmp_corner);
    /* each run of equal coordinates: the corner that comes first in the file names the vertex */
    int *owner = malloc(sizeof(int) * (size_t)(ncorners ? ncorners : 1));
    for (int a = 0, z; owner && a < ncorners; a = z) {
        for (z = a; z < ncorners && !memcmp(s[z].p, s[a].p, sizeof s[a].p); z++)
            owner[s[z].first] = s[a].first;
    }
    int rc = owner ? 0 : -1;
    for (int k = 0; !rc && k < ncorners; k++) { /* vertices numbered in order of first use (owner[k] <= k) */
        id[k] = owner[k] == k ? add_vertex(g, c + 3 * k) : id[owner[k]];
        if (id[k] < 0)
            rc = -1;
    }
    for (int f = 0; !rc && f < ncorners / 3; f++) {
        int t[3] = {id[3 * f], id[3 * f + 1], id[3 * f + 2]};
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
            snprintf(err, errlen, "%s: facet %d: two of its corners are the same point", path, f + 1);
            rc = -2;
        } else if (add_tri(g, t) < 0)
            rc = -1;
    }
    if (rc == -1)
        snprintf(err, errlen, "%s: out of memory", path);
    free(s), free(id), free(owner);
    return rc == -1 ? DEM_ERR_NOMEM : rc ? -1 : 0;
}

static int read_stl_binary(FILE *fp, long size, const char *path, grow_mesh *g, char *err, size_t errlen)
{
    unsigned char head[84];
    if (fseek(fp, 0, SEEK_SET) || fread(head, 1, 84, fp) != 84)
        return snprintf(err, errlen, "%s: binary STL shorter than its 84-byte header", path), -1;
    unsigned long n = head[80] | head[81] << 8 | (unsigned long)head[82] << 16 | (unsigned long)head[83] << 24;
    if (n > MESH_FILE_MAX || (unsigned long)size != 84 + 50 * n)
        return snprintf(err, errlen, "%s: binary STL of %ld bytes says %lu triangles (%lu bytes; at most %d "
                        "triangles)", path, size, n, 84 + 50 * n, MESH_FILE_MAX), -1;
    double *c = malloc(sizeof(double) * 9 * (n ? n : 1));
    if (!c)
        return snprintf(err, errlen, "%s: out of memory", path), DEM_ERR_NOMEM;
    for (unsigned long f = 0; f < n; f++) {
        unsigned char rec[50];
        if (fread(rec, 1, 50, fp) != 50)
            return free(c), snprintf(err, errlen, "%s: facet %lu: cut short", path, f + 1), -1;
        for (int k = 0; k < 9; k++) {
            unsigned char *b = rec + 12 + 4 * k;
            unsigned u = b[0] | b[1] << 8 | (unsigned)b[2] << 16 | (unsigned)b[3] << 24;
            float v;
            memcpy(&v, &u, 4);
            if (!isfinite(v))
                return free(c), snprintf(err, errlen, "%s: facet %lu: a coordinate is not finite", path, f + 1), -1;
            c[9 * f + k] = v;
        }
    }
    int rc = stl_finish(c, 3 * (int)n, g, path, err, errlen);
    free(c);
    return rc;
}

static int read_stl_ascii(FILE *fp, const char *path, grow_mesh *g, char *err, size_t errlen)
{
    static const char *const want[] = {"facet", "outer", "vertex", "vertex", "vertex", "endloop", "endfacet"};
    char line[4096];
    int ln = 0, state = -1, n = 0, cap = 0, done = 0; /* state: -1 before solid, 0..6 the word expected next */
    double *c = NULL;
    while (fgets(line, sizeof line, fp)) {
        ln++;
        char *save, *tok = strtok_r(line, " \t\r\n", &save);
        if (!tok)
            continue;
        if (done)
            return free(c), snprintf(err, errlen, "%s:%d: '%.40s' after endsolid", path, ln, tok), -1;
        if (state < 0) {
            if (strcmp(tok, "solid"))
                return free(c), snprintf(err, errlen, "%s:%d: an ASCII STL starts with 'solid'", path, ln), -1;
            state = 0;
            continue;
        }
        if (state == 0 && !strcmp(tok, "endsolid")) {
            done = 1;
            continue;
        }
        if (strcmp(tok, want[state]))
            return free(c), snprintf(err, errlen, "%s:%d: '%.40s' where '%s' was due", path, ln, tok, want[state]), -1;
        if (state >= 2 && state <= 4) {
            if (n == cap) {
                cap = cap ? 2 * cap : 3072;
                if (cap / 3 > MESH_FILE_MAX)
                    return free(c), snprintf(err, errlen, "%s:%d: more than %d triangles", path, ln, MESH_FILE_MAX),
                           -1;
                double *nc = realloc(c, sizeof(double) * 3 * (size_t)cap);
                if (!nc)
                    return free(c), snprintf(err, errlen, "%s:%d: out of host memory", path, ln), DEM_ERR_NOMEM;
                c = nc;
            }
            for (int k = 0; k < 3; k++) {
                char *t = strtok_r(NULL, " \t\r\n", &save);
                if (!t || !number(t, c + 3 * n + k))
                    return free(c), snprintf(err, errlen, "%s:%d: vertex: want three finite numbers", path, ln), -1;
            }
            n++;
        }
        state = (state + 1) % 7;
    }
    if (!done || state != 0)
        return free(c), snprintf(err, errlen, "%s:%d: the file ends inside a %s", path, ln, state ? "facet" : "solid"),
               -1;
    int rc = stl_finish(c, n, g, path, err, errlen);
    free(c);
    return rc;
}

/* path for reading when it is a regular file (as app/scene_schema.c's scene_open_regular): a named pipe would block
 * the open forever, a device be read without end. NULL with errno set, or with *odd = 1 for another kind of file. */
static FILE *open_regular(const char *path, int *odd)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    struct stat sb;
    *odd = 0;
    if (fd >= 0 && fstat(fd, &sb) == 0 && !S_ISREG(sb.st_mode))
        *odd = 1;
    FILE *fp = fd >= 0 && !*odd && fcntl(fd, F_SETFL, 0) == 0 ? fdopen(fd, "rb") : NULL;
    if (!fp && fd >= 0) {
        int e = errno;
        close(fd);
        errno = e;
    }
    return fp;
}

int dem_mesh_read(const char *path, dem_mesh *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    int odd;
    FILE *fp = open_regular(path, &odd); /* "cannot open": the dem command's exit status 66 */
    if (!fp)
        return snprintf(err, errlen, "%s: cannot open the mesh file: %s", path,
                        odd ? "not a regular file (a folder, pipe, socket or device)" : strerror(errno)), -1;
    grow_mesh g = {0};
    size_t len = strlen(path);
    int rc;
    if (len > 4 && !strcasecmp(path + len - 4, ".obj")) {
        rc = read_obj(fp, path, &g, err, errlen);
    } else if (len > 4 && !strcasecmp(path + len - 4, ".stl")) {
        char start[6] = {0};
        long size = fseek(fp, 0, SEEK_END) ? -1 : ftell(fp);
        rewind(fp);
        size_t got = fread(start, 1, 5, fp);
        rewind(fp);
        /* "solid" may also open a binary header: a binary file is the one whose size its count explains */
        unsigned char cnt[4];
        int binary = size >= 84 && fseek(fp, 80, SEEK_SET) == 0 && fread(cnt, 1, 4, fp) == 4 &&
                     (unsigned long)size == 84 + 50 * (cnt[0] | cnt[1] << 8 | (unsigned long)cnt[2] << 16 |
                                                       (unsigned long)cnt[3] << 24);
        rewind(fp);
        if (binary || !(got == 5 && !memcmp(start, "solid", 5)))
            rc = read_stl_binary(fp, size, path, &g, err, errlen);
        else
            rc = read_stl_ascii(fp, path, &g, err, errlen);
    } else {
        rc = -1;
        snprintf(err, errlen, "%s: a mesh file is .obj (Wavefront) or .stl", path);
    }
    fclose(fp);
    if (!rc && (g.nv < 3 || g.nt < 1))
        rc = -1, snprintf(err, errlen, "%s: %d vertices and %d triangles (a mesh needs a triangle)", path, g.nv, g.nt);
    if (rc) { /* the readers' -1: the file refused; DEM_ERR_NOMEM: out of memory */
        free(g.x), free(g.tri);
        return rc == DEM_ERR_NOMEM ? DEM_ERR_NOMEM : DEM_ERR_ARG;
    }
    m->nv = g.nv, m->nt = g.nt, m->x = g.x, m->tri = g.tri;
    return 0;
}
