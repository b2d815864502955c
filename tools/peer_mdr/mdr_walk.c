/* mdr_walk.c - the C law's core (common/laws/mdr_core.h, through the reference's dem_mdr_walk_f64) on the cases that
 * `tools/peer_mdr/mdr_reference.py --walk` prints on its standard input, for `make peer-mdr`'s comparison with LAMMPS:
 * writes DIR/c_<case>.csv (step, force_N, radius_m, psi) per case. Built by make as build/dem-mdr-walk.
 *
 * usage: mdr_reference.py --walk | dem-mdr-walk DIR */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "ref_kernels.h" /* dem_mdr_walk_f64 */

static int run_case(const char *dir, const char *name, const char *kind, int n, const double *h, const double *u)
{
    size_t m = (size_t)n + 1;
    double *out = malloc(4 * m * sizeof(double));
    if (!out)
        return 1;
    int k = !strcmp(kind, "pair") ? 0 : !strcmp(kind, "wall") ? 1 : 2; /* mdr_core.h's MDR_WALK_* */
    double mat[8] = {h[5], h[6], h[7], h[8], h[9], h[10], h[11], h[12]};
    dem_mdr_walk_f64(k, n, u, mat, h[0], h[1], h[2], h[3], h[4], out, out + m, out + 2 * m, out + 3 * m);
    char path[4096];
    snprintf(path, sizeof path, "%s/c_%s.csv", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        free(out);
        return 1;
    }
    fprintf(f, "# MDR single contact, the C law's core (common/laws/mdr_core.h, fp64 reference); case %s\n"
               "step,force_N,radius_m,psi\n", name);
    for (size_t s = 0; s < m; s++)
        fprintf(f, "%zu,%.17g,%.17g,%.17g\n", s, out[3 * m + s], out[m + s], out[2 * m + s]);
    free(out);
    return fclose(f) != 0;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: mdr_reference.py --walk | %s DIR\n", argv[0]);
        return 2;
    }
    char line[1024], name[64] = "", kind[16] = "";
    double h[13], *u = NULL;
    int n = 0, row = 0, cases = 0;
    while (fgets(line, sizeof line, stdin)) {
        if (!strncmp(line, "case ", 5)) {
            if (u && (row != n + 1 || run_case(argv[1], name, kind, n, h, u)))
                return 1;
            free(u);
            if (sscanf(line, "case %63s %15s %d %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", name, kind, &n,
                       h, h + 1, h + 2, h + 3, h + 4, h + 5, h + 6, h + 7, h + 8, h + 9, h + 10, h + 11, h + 12) != 16 ||
                n < 0 || !(u = malloc(((size_t)n + 1) * sizeof(double)))) {
                fprintf(stderr, "dem-mdr-walk: cannot read the case line: %s", line);
                return 1;
            }
            row = 0, cases++;
        } else if (!u || row > n || sscanf(line, "%lf", &u[row++]) != 1) {
            fprintf(stderr, "dem-mdr-walk: a row outside a case, or unreadable: %s", line);
            return 1;
        }
    }
    if (!u || row != n + 1 || run_case(argv[1], name, kind, n, h, u))
        return 1;
    free(u);
    fprintf(stderr, "dem-mdr-walk: %d cases written to %s/c_*.csv\n", cases, argv[1]);
    return 0;
}
