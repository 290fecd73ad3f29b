/* hard_domains.c: glpgp-domains, writes the CAD-like hard test domains of
 * tests/quads/hard_domains.h as Triangle .poly files (with per-point mesh
 * sizes), for `glpgp mesh` / `glpgp solve` and bench/gmsh_compare.sh.
 *
 *   glpgp-domains H EDGES DIR [NAME ...]
 *
 * writes DIR/NAME.poly for each NAME (default: all of HD_NAMES; the issue-27
 * failure classes HD_NAMES_27 by name, or all of them with the name "27") scaled to
 * quad size H with point size e = H / EDGES (the wanted triangle edge), and
 * prints the names written.
 *
 *   glpgp-domains H EDGES DIR random SEED COUNT
 *
 * writes COUNT random polygons with holes (hd_random: spikes, slits,
 * near-touching holes) as DIR/randomN.poly, N = SEED .. SEED + COUNT - 1. */
#include "../tests/quads/hard_domains.h"

static unsigned long long g_rng;
static double rnd(void)
{
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return (double)((g_rng * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* random SEED COUNT: the polygons (crossing ones skipped, their number kept). */
static int write_random(double H, double edges, const char *dir, long seed, int count)
{
    for (int i = 0; i < count; i++) {
        hd_poly p;
        g_rng = 0x9e3779b97f4a7c15ULL * (unsigned long long)(seed + i + 1);
        if (!hd_random(rnd, &p, 1.0 / edges)) continue;
        for (int k = 0; k < 2 * p.np; k++) p.xy[k] *= H;
        for (int k = 0; k < p.np; k++) p.size[k] *= H;
        char path[4096];
        snprintf(path, sizeof path, "%s/random%ld.poly", dir, seed + i);
        int ok = hd_write_poly(&p, path);
        hd_free(&p);
        if (!ok) {
            fprintf(stderr, "glpgp-domains: cannot write %s\n", path);
            return 1;
        }
        printf("random%ld\n", seed + i);
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: glpgp-domains H EDGES DIR [NAME ...]\n  names: %s\n  and %s (\"27\": all of these)\n",
                HD_NAMES, HD_NAMES_27);
        return 2;
    }
    double H = atof(argv[1]), edges = atof(argv[2]);
    if (!(H > 0) || !(edges > 0)) {
        fprintf(stderr, "glpgp-domains: H and EDGES must be > 0\n");
        return 2;
    }
    if (argc == 7 && !strcmp(argv[4], "random")) return write_random(H, edges, argv[3], atol(argv[5]), atoi(argv[6]));
    char all[] = HD_NAMES, set27[] = HD_NAMES_27;
    char *names[64];
    int n = 0;
    if (argc > 4 && !(argc == 5 && !strcmp(argv[4], "27")))
        for (int i = 4; i < argc && n < 64; i++) names[n++] = argv[i];
    else
        for (char *t = strtok(argc > 4 ? set27 : all, " "); t && n < 64; t = strtok(NULL, " ")) names[n++] = t;
    for (int i = 0; i < n; i++) {
        hd_poly p;
        if (!hd_build(names[i], 1.0 / edges, &p)) {
            fprintf(stderr, "glpgp-domains: unknown domain '%s' (%s %s)\n", names[i], HD_NAMES, HD_NAMES_27);
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
