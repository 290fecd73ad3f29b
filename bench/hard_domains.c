/* hard_domains.c: glpgp-domains, writes the CAD-like hard test domains of
 * tests/quads/hard_domains.h as Triangle .poly files (with per-point mesh
 * sizes), for `glpgp mesh` / `glpgp solve` and bench/gmsh_compare.sh.
 *
 *   glpgp-domains H EDGES DIR [NAME ...]
 *
 * writes DIR/NAME.poly for each NAME (default: all, see HD_NAMES) scaled to
 * quad size H with point size e = H / EDGES (the wanted triangle edge), and
 * prints the names written. */
#include "../tests/quads/hard_domains.h"

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: glpgp-domains H EDGES DIR [NAME ...]\n  names: %s\n", HD_NAMES);
        return 2;
    }
    double H = atof(argv[1]), edges = atof(argv[2]);
    if (!(H > 0) || !(edges > 0)) {
        fprintf(stderr, "glpgp-domains: H and EDGES must be > 0\n");
        return 2;
    }
    char all[] = HD_NAMES;
    char *names[32];
    int n = 0;
    if (argc > 4)
        for (int i = 4; i < argc && n < 32; i++) names[n++] = argv[i];
    else
        for (char *t = strtok(all, " "); t && n < 32; t = strtok(NULL, " ")) names[n++] = t;
    for (int i = 0; i < n; i++) {
        hd_poly p;
        if (!hd_build(names[i], 1.0 / edges, &p)) {
            fprintf(stderr, "glpgp-domains: unknown domain '%s' (%s)\n", names[i], HD_NAMES);
            return 2;
        }
        for (int k = 0; k < 2 * p.np; k++) p.xy[k] *= H;
        for (int k = 0; k < p.np; k++) p.size[k] *= H;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s.poly", argv[3], names[i]);
        if (!hd_write_poly(&p, path)) {
            fprintf(stderr, "glpgp-domains: cannot write %s\n", path);
            hd_free(&p);
            return 1;
        }
        printf("%s\n", names[i]);
        hd_free(&p);
    }
    return 0;
}
