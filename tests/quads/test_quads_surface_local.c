/* test_quads_surface_local.c: the surface repair stays local (issue 29,
 * surfaces II), without a solve, on the grid of plane waves on the half
 * cylinder (radius 2, height 2; periods 2 pi / 27 x 2 / 9, 28 x 10 cells):
 *  - 16 dislocations (a row of three quads whose middle one is cut in two
 *    along the row: a pentagon at each end, 32 faces that are not quads,
 *    each an odd region on its own) are repaired by the local repair, all
 *    the odd regions joined in pairs (it used to join one pair per shaping
 *    pass, 12 at most, and gave up on more: "no disks"), valid, all quads,
 *    Euler 1 and one boundary loop, at least 150 of the grid's quads kept;
 *  - the local split (glpgp_qs_split_local) of one face of the grid splits
 *    it in four and the two quad strips through it in two: a conforming
 *    all-quad mesh (valid; 28 x 10 cells, the rims' half cells included:
 *    4 + 2 (27 + 9) faces in place of 28 + 10 - 1), on the cylinder;
 *  - the local 3-refinement (glpgp_qs_refine3) of one interior face: it
 *    3 x 3 and its 8 neighbours by the transition templates, nothing
 *    else, valid with the templates' corners above 0.65 before any
 *    smoothing; two diagonal faces: the closure refines the 2 x 2 block;
 *    a rim face: the boundary kept;
 *  - a flat boundary corner (two rim quads a-b-x-.., b-c-..-x redrawn as
 *    a-b-c-z and z-..-a, so that rim vertex b is in one quad whose corner
 *    there is the rim's straight angle) is found (glpgp_qs_find_flat) and
 *    split like a triangle (glpgp_qs_split_flat): valid, all quads, the
 *    topology kept, no flat corner left, the smallest scaled Jacobian from
 *    0.014 (the flat corner) to 0.23 (the split of the quad, a right
 *    triangle, before any smoothing). */
#include "testutil.h"

#include "glpgp/surface.h"
#include "../host/quads/quads_surface.h"
#include "halfcyl_waves.h"

#include <string.h>

#define NU 27
#define NV 9
#define HU (2.0 * GLPGP_PI / NU)
#define HV (2.0 / NV)

/* The half cylinder and its grid (*q NULL when one failed). */
static void grid(glpgp_mesh **m, glpgp_quadmesh **q)
{
    *q = NULL;
    CHECK_OK(glpgp_surface_generate("halfcyl", 20000, m));
    if (!*m) return;
    glpgp_result *r = halfcyl_waves(*m, HU, HV);
    if (r) CHECK_OK(glpgp_quads_extract_surface(*m, r, q));
    glpgp_result_destroy(&r);
    glpgp_quads_report qq;
    if (*q) CHECK_OK(glpgp_quads_quality_surface(*q, *m, HV, &qq));
    CHECK(*q && (*q)->nf == (NU + 1) * (NV + 1) && qq.invalid == 0); /* half cells at the rims */
}

/* r checked on the half cylinder m (*qq its report): valid, all quads,
 * Euler 1 and one boundary loop, as the grid. */
static void valid_on_cylinder(const glpgp_mesh *m, const glpgp_quadmesh *r, glpgp_quads_report *qq)
{
    CHECK_OK(glpgp_quads_quality_surface(r, m, HV, qq));
    CHECK(qq->invalid == 0 && qq->others == 0 && qq->euler == 1 && qq->boundary_loops == 1);
}

/* The face whose centroid is nearest to arc length s and height y (cells). */
static int face_at(const glpgp_quadmesh *q, double s, double y)
{
    int best = -1;
    double bd = 1e30;
    for (int f = 0; f < q->nf; f++) {
        double c[3] = {0, 0, 0};
        for (int k = q->face_start[f]; k < q->face_start[f + 1]; k++)
            for (int d = 0; d < 3; d++) c[d] += q->xyz[3 * q->face_vert[k] + d] / 4.0;
        const double ds = 2.0 * atan2(c[1], c[0]) / HU - s, dy = c[2] / HV - y, d = ds * ds + dy * dy;
        if (d < bd) bd = d, best = f;
    }
    return best;
}

/* The side of face f shared with face g (-1: none). */
static int shared_side(const glpgp_quadmesh *q, int f, int g)
{
    const int *a = q->face_vert + q->face_start[f], *b = q->face_vert + q->face_start[g];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (a[i] == b[(j + 1) % 4] && a[(i + 1) % 4] == b[j]) return i;
    return -1;
}

/* Dislocations: for each (s, y), the faces a, b, c in a row along s; b cut
 * in two through the midpoints of its sides shared with a and c, which
 * become pentagons. Rewrites q (faces and points). */
static int dislocate(glpgp_quadmesh *q, const double (*at)[2], int n)
{
    const int nf = q->nf + n, nc = q->face_start[q->nf] + 6 * n, nv = q->nv + 2 * n;
    int *fs = malloc((size_t)(nf + 1) * sizeof(int)), *fv = malloc((size_t)nc * sizeof(int));
    double *xyz = malloc((size_t)3 * nv * sizeof(double));
    int *ins = malloc((size_t)q->nf * sizeof(int)), *insv = malloc((size_t)q->nf * sizeof(int));
    int *cut = malloc((size_t)q->nf * sizeof(int)), ok = fs && fv && xyz && ins && insv && cut;
    if (!ok) goto out;
    memcpy(xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
    for (int f = 0; f < q->nf; f++) ins[f] = cut[f] = -1;
    int v = q->nv;
    for (int k = 0; k < n && ok; k++) {
        const int a = face_at(q, at[k][0] - 1, at[k][1]), b = face_at(q, at[k][0], at[k][1]),
                  c = face_at(q, at[k][0] + 1, at[k][1]);
        const int sa = shared_side(q, a, b), sb = shared_side(q, b, a), sc = shared_side(q, c, b), sb2 = shared_side(q, b, c);
        ok = sa >= 0 && sb >= 0 && sc >= 0 && sb2 >= 0 && (sb + 2) % 4 == sb2 && ins[a] < 0 && ins[c] < 0 && cut[b] < 0;
        if (!ok) break;
        const int *vb = q->face_vert + q->face_start[b];
        for (int d = 0; d < 3; d++) {
            xyz[3 * v + d] = 0.5 * (q->xyz[3 * vb[sb] + d] + q->xyz[3 * vb[(sb + 1) % 4] + d]);
            xyz[3 * (v + 1) + d] = 0.5 * (q->xyz[3 * vb[sb2] + d] + q->xyz[3 * vb[(sb2 + 1) % 4] + d]);
        }
        ins[a] = sa, insv[a] = v, ins[c] = sc, insv[c] = v + 1, cut[b] = sb, insv[b] = v;
        v += 2;
    }
    int o = 0, w = 0;
    for (int f = 0; f < q->nf && ok; f++) {
        const int *c = q->face_vert + q->face_start[f];
        if (cut[f] >= 0) { /* sides s (midpoint m) and s + 2 (midpoint m + 1): (c[s], m, m+1, c[s+3]), (m, c[s+1], c[s+2], m+1) */
            const int s = cut[f], m = insv[f];
            const int t[8] = {c[s], m, m + 1, c[(s + 3) % 4], m, c[(s + 1) % 4], c[(s + 2) % 4], m + 1};
            for (int h = 0; h < 2; h++) {
                fs[o++] = w;
                for (int i = 0; i < 4; i++) fv[w++] = t[4 * h + i];
            }
            continue;
        }
        fs[o++] = w;
        for (int i = 0; i < 4; i++) {
            fv[w++] = c[i];
            if (ins[f] == i) fv[w++] = insv[f];
        }
    }
    if (!ok) goto out;
    fs[o] = w;
    free(q->face_start);
    free(q->face_vert);
    free(q->xyz);
    free(q->face_origin);
    q->face_start = fs, q->face_vert = fv, q->xyz = xyz, q->face_origin = NULL;
    q->nf = o, q->nv = v;
    fs = fv = NULL;
    xyz = NULL;
    double *xy = realloc(q->xy, (size_t)2 * v * sizeof(double));
    if (xy) q->xy = xy;
out:
    free(fs);
    free(fv);
    free(xyz);
    free(ins);
    free(insv);
    free(cut);
    return ok;
}

static void many_odd_regions(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL, *r = NULL;
    grid(&m, &q);
    if (!q) goto out;
    double at[16][2];
    int n = 0;
    for (int row = 1; row < NV; row += 2) /* rows 1 3 5 7, dislocations 6 cells apart */
        for (int col = 2; col + 1 < NU && n < 16; col += 6) {
            at[n][0] = col + 0.5 * (row % 4 == 3) * 2;
            at[n++][1] = row;
        }
    CHECK(n == 16);
    CHECK(dislocate(q, (const double (*)[2])at, n));
    glpgp_quads_report qq;
    CHECK_OK(glpgp_quads_quality_surface(q, m, HV, &qq));
    CHECK(qq.others == 2 * n && (qq.invalid & GLPGP_QUADS_BAD_NONQUAD));
    glpgp_quads_repair rs;
    CHECK_OK(glpgp_qs_local_repair(m, q, HV, 0, &r, &rs));
    CHECK(r != NULL);
    if (!r) goto out;
    valid_on_cylinder(m, r, &qq);
    CHECK(r->nf - rs.new_quads >= 150);
    if (qq.invalid || r->nf - rs.new_quads < 150)
        fprintf(stderr, "many odd regions: invalid 0x%x, %d kept faces of %d, %d regions\n", qq.invalid,
                r->nf - rs.new_quads, r->nf, rs.regions);
out:
    glpgp_quadmesh_destroy(&r);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* The local split of one interior face: it in four, the two strips through it in two. */
static void split_local(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL, *r = NULL;
    unsigned char *sel = NULL;
    grid(&m, &q);
    if (!q) goto out;
    const int f = face_at(q, NU / 2, NV / 2);
    CHECK_OK(glpgp_calloc((size_t)q->nf, 1, &sel));
    if (!sel) goto out;
    sel[f] = 1;
    int ns = 0;
    CHECK_OK(glpgp_qs_split_local(m, q, HV, sel, &r, &ns));
    if (!r) goto out;
    /* the strip along s: NU + 1 faces (the face's in four, NU in two); along y: NV + 1, NV in two */
    CHECK(ns == NU + NV + 1);
    CHECK(r->nf == q->nf - ns + 4 + 2 * (NU + NV));
    if (ns != NU + NV + 1) fprintf(stderr, "local split: %d faces split, %d faces\n", ns, r->nf);
    glpgp_quads_report qq;
    valid_on_cylinder(m, r, &qq);
    for (int i = 0; i < r->nv; i++) /* on the cylinder */
        CHECK(fabs(hypot(r->xyz[3 * i], r->xyz[3 * i + 1]) - 2.0) < 0.01);
out:
    free(sel);
    glpgp_quadmesh_destroy(&r);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* The smallest corner scaled Jacobian of r's faces in their own planes. */
static double sj_min(const glpgp_quadmesh *r)
{
    double s = 1.0;
    for (int f = 0; f < r->nf; f++) s = fmin(s, glpgp_quadmesh_face_sj_surface(r, f));
    return s;
}

/* The local 3-refinement (glpgp_qs_refine3) of one interior face: it 3 x 3,
 * its 4 side neighbours by the two-corner template (7 quads), its 4 corner
 * neighbours by the one-corner template (3 quads), nothing else; then of
 * two faces touching at a corner only, whose pattern in the two quads
 * beside both (two opposite corners marked) the closure turns into four. */
static void refine3(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL, *r = NULL;
    unsigned char *sel = NULL;
    grid(&m, &q);
    if (!q) goto out;
    const int f = face_at(q, NU / 2, NV / 2);
    CHECK_OK(glpgp_calloc((size_t)q->nf, 1, &sel));
    if (!sel) goto out;
    sel[f] = 1;
    int nr = 0;
    CHECK_OK(glpgp_qs_refine3(m, q, HV, sel, &r, &nr));
    if (!r) goto out;
    CHECK(nr == 9 && r->nf == q->nf - 9 + 9 + 4 * 7 + 4 * 3);
    if (nr != 9) fprintf(stderr, "refine3: %d faces refined, %d faces\n", nr, r->nf);
    glpgp_quads_report qq;
    valid_on_cylinder(m, r, &qq);
    CHECK(sj_min(r) > 0.65); /* the templates' worst corner on a square grid: 0.707 */
    for (int i = 0; i < r->nv; i++) /* on the cylinder */
        CHECK(fabs(hypot(r->xyz[3 * i], r->xyz[3 * i + 1]) - 2.0) < 0.01);
    glpgp_quadmesh_destroy(&r);
    /* two faces diagonal to each other: the two quads beside both see two opposite marked corners */
    memset(sel, 0, (size_t)q->nf);
    sel[f] = 1;
    sel[face_at(q, NU / 2 + 1, NV / 2 + 1)] = 1;
    CHECK_OK(glpgp_qs_refine3(m, q, HV, sel, &r, &nr));
    if (!r) goto out;
    /* a 2 x 2 block refined 3 x 3 (36), 8 side neighbours (7 each), 4 corner neighbours (3 each) */
    CHECK(nr == 16 && r->nf == q->nf - 16 + 36 + 8 * 7 + 4 * 3);
    if (nr != 16) fprintf(stderr, "refine3 (closure): %d faces refined, %d faces\n", nr, r->nf);
    valid_on_cylinder(m, r, &qq);
    CHECK(sj_min(r) > 0.65);
    glpgp_quadmesh_destroy(&r);
    /* a face on the rim: its boundary sides split too, the mesh still one loop */
    memset(sel, 0, (size_t)q->nf);
    sel[face_at(q, NU / 2, 0.25)] = 1;
    CHECK_OK(glpgp_qs_refine3(m, q, HV, sel, &r, &nr));
    if (!r) goto out;
    valid_on_cylinder(m, r, &qq);
    CHECK(nr == 6);
out:
    free(sel);
    glpgp_quadmesh_destroy(&r);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* Two rim quads sharing a side redrawn with a flat corner at their common
 * rim vertex b; returns the first quad's face (-1: none found). */
static int make_flat(glpgp_quadmesh *q)
{
    int *nface = calloc((size_t)q->nv, sizeof(int)), res = -1;
    if (!nface) return -1;
    for (int c = 0; c < q->face_start[q->nf]; c++) nface[q->face_vert[c]]++;
    const int f1 = face_at(q, NU / 2, 0.25), f2 = face_at(q, NU / 2 + 1, 0.25);
    const int i1 = shared_side(q, f1, f2);
    if (i1 < 0) goto out;
    int *u = q->face_vert + q->face_start[f1], *w = q->face_vert + q->face_start[f2], U[4], W[4], H[6];
    for (int k = 0; k < 4; k++) U[k] = u[(i1 + 1 + k) % 4]; /* the shared side is (U[3], U[0]) */
    int j = 0;
    while (j < 4 && w[j] != U[0]) j++;
    if (j == 4) goto out;
    for (int k = 0; k < 4; k++) W[k] = w[(j + k) % 4]; /* W[0] = U[0], W[1] = U[3] */
    const int hx[6] = {U[0], U[1], U[2], U[3], W[2], W[3]};
    memcpy(H, hx, sizeof H);
    const int b = nface[U[0]] == 2 ? 0 : nface[U[3]] == 2 ? 3 : -1;
    if (b < 0) goto out;
    for (int k = 0; k < 4; k++) {
        u[k] = H[(b + 5 + k) % 6]; /* (H[b-1], b, H[b+1], H[b+2]) */
        w[k] = H[(b + 2 + k) % 6]; /* (H[b+2], x = H[b+3], H[b+4], H[b-1]) */
    }
    /* x, above b, raised by a quarter of the row: the second quad's corner there
     * (z, x and y on one grid line) convex */
    double *x = q->xyz + 3 * H[(b + 3) % 6];
    x[2] += 0.25 * (x[2] - q->xyz[3 * H[b] + 2]);
    res = f1;
out:
    free(nface);
    return res;
}

static void flat_corner(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL, *r = NULL;
    signed char *flat = NULL;
    grid(&m, &q);
    if (!q) goto out;
    const int f = make_flat(q);
    CHECK(f >= 0);
    if (f < 0) goto out;
    glpgp_quads_report qq;
    CHECK_OK(glpgp_quads_quality_surface(q, m, HV, &qq));
    CHECK(qq.invalid == 0 && qq.sj_min < 0.05);
    CHECK_OK(glpgp_calloc((size_t)q->nf + 1, 1, &flat));
    if (!flat) goto out;
    int nflat = 0, ns = 0;
    CHECK_OK(glpgp_qs_find_flat(q, 0.3, flat, &nflat));
    CHECK(nflat == 1 && flat[f] >= 0);
    CHECK_OK(glpgp_qs_split_flat(m, q, HV, flat, &r, &ns));
    if (!r) goto out;
    valid_on_cylinder(m, r, &qq);
    CHECK(qq.sj_min > 0.2);
    /* the flat quad in three, the two strips from its sides up the cylinder and along the rim */
    CHECK(ns >= 3 && r->nf == q->nf + 2 + (ns - 1));
    if (qq.invalid || qq.sj_min <= 0.2)
        fprintf(stderr, "flat corner: invalid 0x%x, smallest scaled Jacobian %.3f, %d faces split\n", qq.invalid,
                qq.sj_min, ns);
    free(flat);
    flat = NULL;
    CHECK_OK(glpgp_calloc((size_t)r->nf + 1, 1, &flat));
    if (flat) CHECK_OK(glpgp_qs_find_flat(r, 0.3, flat, &nflat));
    CHECK(nflat == 0);
out:
    free(flat);
    glpgp_quadmesh_destroy(&r);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

static void dbg_log(glpgp_log_level l, const char *msg, void *u)
{
    (void)l;
    (void)u;
    if (getenv("XXDBG")) fprintf(stderr, "%s\n", msg);
}

int main(void)
{
    glpgp_log_set_callback(dbg_log, NULL);
    many_odd_regions();
    split_local();
    refine3();
    flat_corner();
    TEST_DONE();
}
