/* test_quads_property.c: every valid triangle mesh gets a valid all-quad
 * mesh (issue 27). Random polygons with holes of the kinds that broke the
 * quad layer: a star-shaped outer loop with spikes down to 0.5 degrees,
 * slits 0.005 .. 0.1 H wide cut into it, holes of radius 0.02 .. 0.8 H,
 * some of them 0.001 .. 0.5 H from the outer loop or from each other
 * (near-touching loops). Each is meshed by Gmsh at a random edge length
 * (H / 4 .. H / 12) and given a plane-wave parametrization at a random
 * period (0.5 .. 2 H) and direction, which follows no boundary: the
 * extraction is wrong near every boundary, and the closing, the repair and
 * its last resort have to make the mesh valid. glpgp_quads_build with the
 * defaults must return a valid all-quad mesh for every one (no solve: fast).
 * The count is GLPGP_PROPERTY_COUNT (default 40; long runs: 3000);
 * GLPGP_PROPERTY_SEED sets the first seed. A failure prints its
 * seed, and GLPGP_PROPERTY_KEEP=DIR keeps its triangle mesh (with
 * GLPGP_PROPERTY_KEEP_POOR=S also the valid ones whose smallest scaled
 * Jacobian over its corner bound is below S, with their quads). Skips (77)
 * without Gmsh. */
#include "testutil.h"
#include "hard_domains.h"

#include <string.h>
#include <unistd.h>

#define PI_ 3.14159265358979323846

static char g_dir[64];

/* The connected pieces of m (one per polygon of a batch), in order of
 * their lowest x (the polygons are placed left to right). */
static int split_pieces(const glpgp_mesh *m, glpgp_mesh **piece, int maxp)
{
    int *par = malloc(sizeof(int) * (size_t)m->nv), *id = malloc(sizeof(int) * (size_t)m->nv);
    int *tri = malloc(sizeof(int) * 3 * (size_t)m->nt), *root = malloc(sizeof(int) * (size_t)m->nv);
    double *xy = malloc(sizeof(double) * 2 * (size_t)m->nv), *xmin = malloc(sizeof(double) * (size_t)m->nv);
    int np = 0;
    for (int v = 0; v < m->nv; v++) par[v] = v;
    for (int t = 0; t < m->nt; t++)
        for (int j = 1; j < 3; j++) par[glpgp_uf_find(par, m->tri[3 * t + j])] = glpgp_uf_find(par, m->tri[3 * t]);
    for (int v = 0; v < m->nv; v++) xmin[v] = INFINITY;
    for (int v = 0; v < m->nv; v++) {
        int r = glpgp_uf_find(par, v);
        xmin[r] = fmin(xmin[r], m->xy[2 * v]);
    }
    int nr = 0;
    for (int v = 0; v < m->nv; v++)
        if (glpgp_uf_find(par, v) == v) root[nr++] = v;
    for (int i = 1; i < nr; i++) /* by lowest x */
        for (int j = i; j > 0 && xmin[root[j]] < xmin[root[j - 1]]; j--) {
            int t = root[j];
            root[j] = root[j - 1];
            root[j - 1] = t;
        }
    for (int k = 0; k < nr && np < maxp; k++) {
        int nv = 0, nt = 0;
        for (int v = 0; v < m->nv; v++) {
            id[v] = -1;
            if (glpgp_uf_find(par, v) != root[k]) continue;
            id[v] = nv;
            xy[2 * nv] = m->xy[2 * v];
            xy[2 * nv + 1] = m->xy[2 * v + 1];
            nv++;
        }
        for (int t = 0; t < m->nt; t++)
            if (id[m->tri[3 * t]] >= 0) {
                for (int j = 0; j < 3; j++) tri[3 * nt + j] = id[m->tri[3 * t + j]];
                nt++;
            }
        piece[np] = NULL;
        if (glpgp_mesh_create(nv, xy, nt, tri, &piece[np]) != GLPGP_OK) glpgp_error_clear();
        np++;
    }
    free(par);
    free(id);
    free(tri);
    free(root);
    free(xy);
    free(xmin);
    return np;
}

/* A batch of polygons placed 20 H apart in x, meshed by one Gmsh call. */
static glpgp_mesh *mesh_batch(const hd_poly *all, double e, const char *path)
{
    if (!hd_write_poly(all, path)) return NULL;
    glpgp_polygons *P = NULL;
    glpgp_mesh *m = NULL;
    if (glpgp_polygons_read(path, &P) != GLPGP_OK || glpgp_mesh_polygons(P, e, 6, &m) != GLPGP_OK) m = NULL;
    glpgp_error_clear();
    glpgp_polygons_destroy(&P);
    return m;
}

/* Append polygon p to batch b, shifted by dx. */
static void append(hd_poly *b, const hd_poly *p, double dx)
{
    for (int l = 0; l < p->n; l++) {
        hd_begin(b);
        for (int i = p->start[l]; i < p->start[l + 1]; i++) hd_point(b, p->xy[2 * i] + dx, p->xy[2 * i + 1], p->size[i]);
        hd_end(b);
    }
}

static glpgp_result *plane_waves(const glpgp_mesh *m, double h, double turn)
{
    glpgp_result *r = NULL;
    if (glpgp_result_create(m->nv, m->nt, &r) != GLPGP_OK) return NULL;
    r->size = h;
    double cs = cos(turn), sn = sin(turn);
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < m->nv; i++) {
            double x = m->xy[2 * i], y = m->xy[2 * i + 1];
            double t = (k == 0 ? cs * x + sn * y : -sn * x + cs * y) / h;
            r->osc[k].z[2 * i] = cos(2 * PI_ * t);
            r->osc[k].z[2 * i + 1] = sin(2 * PI_ * t);
        }
    return r;
}

typedef struct tally {
    int tried, meshed, valid, quads, irregular, repaired, last;
    double sjmin;
} tally;

/* The quad pipeline on one polygon's mesh (its seed for the messages). */
static void check_one(const glpgp_mesh *m, unsigned long long seed, double h, double turn, tally *T)
{
    glpgp_result *r = plane_waves(m, h, turn);
    glpgp_quadmesh *q = NULL;
    double hq = h, t0 = glpgp_now();
    glpgp_quads_report qq;
    memset(&qq, 0, sizeof qq);
    qq.invalid = ~0u;
    T->meshed++;
    if (r && glpgp_quads_build(m, r, NULL, &q, &hq) == GLPGP_OK && q && glpgp_quads_quality(q, m, hq, &qq) == GLPGP_OK) {
        T->quads += qq.quads;
        T->irregular += qq.irregular;
        T->sjmin = fmin(T->sjmin, qq.sj_min);
        T->repaired += qq.repair.rounds > 0;
        T->last += qq.repair.whole_domain > 0;
    }
    glpgp_error_clear();
    if (getenv("GLPGP_PROPERTY_VERBOSE"))
        printf("seed %llu: %d vertices, %d loops, h %.2f: %d quads, SJ %.3f (of the corner bound %.3f), repair %d "
               "rounds, %.2f s\n", seed, m->nv, m->nloops, h, qq.quads, qq.sj_min, qq.sj_min_corner, qq.repair.rounds,
               glpgp_now() - t0);
    const char *poor = getenv("GLPGP_PROPERTY_KEEP_POOR"), *keepdir = getenv("GLPGP_PROPERTY_KEEP");
    if (poor && keepdir && q && qq.invalid == 0 && qq.sj_min_corner < atof(poor)) { /* a poorly shaped valid mesh */
        char path[512];
        snprintf(path, sizeof path, "%s/p%llu.msh", keepdir, seed);
        glpgp_mesh_write(m, path);
        snprintf(path, sizeof path, "%s/p%llu_quads.obj", keepdir, seed);
        glpgp_quads_write(q, path);
    }
    if (qq.invalid == 0) {
        T->valid++;
    } else {
        char why[512] = "(no mesh)";
        if (qq.invalid != ~0u) glpgp_quads_invalid_text(&qq, 0, why, sizeof why);
        fprintf(stderr, "seed %llu: %d vertices, %d loops, h %.3f: INVALID: %s\n", seed, m->nv, m->nloops, h, why);
        const char *keep = getenv("GLPGP_PROPERTY_KEEP");
        if (keep) {
            char path[512];
            snprintf(path, sizeof path, "%s/p%llu.msh", keep, seed);
            glpgp_mesh_write(m, path);
        }
    }
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
}

#define BATCH 40

int main(void)
{
    (void)hd_build;
    if (!glpgp_have_gmsh()) {
        printf("skipped: this build has no Gmsh (or its module is missing)\n");
        return 77;
    }
    const char *ev = getenv("GLPGP_PROPERTY_COUNT"), *sv = getenv("GLPGP_PROPERTY_SEED");
    int count = ev ? atoi(ev) : 40;
    unsigned long long seed0 = sv ? strtoull(sv, NULL, 10) : 1;
    snprintf(g_dir, sizeof g_dir, "/tmp/glpgp_prop_XXXXXX");
    if (!mkdtemp(g_dir)) return 1;
    tally T = {0, 0, 0, 0, 0, 0, 0, 1.0};
    char path[128];
    snprintf(path, sizeof path, "%s/batch.poly", g_dir);
    for (int b0 = 0; b0 < count; b0 += BATCH) {
        /* one edge length per batch (Gmsh's size), the polygons side by side */
        unsigned long long bseed = seed0 + (unsigned long long)b0;
        tu_rng = 0x9e3779b97f4a7c15ULL * (bseed + 1);
        double e = 1.0 / (4 + 8 * tu_rand());
        hd_poly all;
        memset(&all, 0, sizeof all);
        unsigned long long seeds[BATCH];
        double hs[BATCH], turns[BATCH];
        int n = 0;
        for (int it = b0; it < count && it < b0 + BATCH; it++) {
            unsigned long long seed = seed0 + (unsigned long long)it;
            tu_rng = 0x9e3779b97f4a7c15ULL * (seed + 1);
            hd_poly p;
            T.tried++;
            if (!hd_random(tu_rand, &p, e)) continue; /* crossing sides: not a polygon */
            seeds[n] = seed;
            hs[n] = 0.5 + 1.5 * tu_rand();
            turns[n] = 2 * PI_ * tu_rand();
            append(&all, &p, 20.0 * n);
            hd_free(&p);
            n++;
        }
        glpgp_mesh *m = n ? mesh_batch(&all, e, path) : NULL;
        hd_free(&all);
        unlink(path);
        if (!m) continue;
        glpgp_mesh *piece[BATCH];
        int np = split_pieces(m, piece, BATCH);
        if (np != n) fprintf(stderr, "batch at seed %llu: %d polygons, %d meshed pieces\n", bseed, n, np);
        for (int k = 0; k < np && np == n; k++)
            if (piece[k]) check_one(piece[k], seeds[k], hs[k], turns[k], &T);
        for (int k = 0; k < np; k++) glpgp_mesh_destroy(&piece[k]);
        glpgp_mesh_destroy(&m);
    }
    rmdir(g_dir);
    printf("%d polygons, %d meshed by Gmsh, %d valid all-quad meshes (%d repaired, %d whole domain again); "
           "%d quads, %.1f irregular per 100, smallest scaled Jacobian %.3f\n",
           T.tried, T.meshed, T.valid, T.repaired, T.last, T.quads, T.quads ? 100.0 * T.irregular / T.quads : 0.0,
           T.sjmin);
    CHECK(T.meshed > 0);
    CHECK(T.valid == T.meshed);
    TEST_DONE();
}
