/* test_quads_surface.c: quad meshes of 3D surfaces (issue 29), without a
 * solve:
 *  - the extraction on the half cylinder (radius 2, height 2, its vertex
 *    columns on generators) from plane waves in its arc length s and height
 *    y, theta_u = s / (2 pi / 9) + 1/2, theta_v = y / (2/3) + 1/2: the grid
 *    is 10 x 4 cells, all quads, every corner on the surface, valid (SJ in
 *    the faces' planes, orientation, Euler 1, one boundary loop, Hausdorff,
 *    area) and the same through glpgp_quads_build_surface;
 *  - the last resort (3 quads per triangle) on a sphere and a hemisphere is
 *    valid with the input's Euler characteristic and loops, and its
 *    Catmull-Clark split too;
 *  - the smoothing on the surface: an interior vertex of that grid slid
 *    along the cylinder (smallest scaled Jacobian about 0.3) comes back
 *    (above 0.9), every vertex stays on the cylinder, the boundary on the
 *    boundary (rim on rim, sides on sides), the loop's four corners in place;
 *  - the boundary slide: a rim vertex moved along the rim 0.35 of a period
 *    slides back along the input's rim (SJ min up by more than 0.15), the
 *    rim's ends stay;
 *  - the local repair: that grid with an octagon in place of the four
 *    quads at an interior vertex and a face turned over elsewhere comes back
 *    valid, all quads, on the cylinder, with its Euler characteristic and
 *    boundary loop, in two regions (the turned face with the 8 around its
 *    pinched corners), at least 27 of the grid's 40 quads kept; the grid
 *    with one face twice (an overlapping copy) comes back valid too;
 *  - the coarse last resort on genus 2, the cube (sharp features) and the
 *    hemisphere: valid, all quads, the input's Euler characteristic and
 *    loops, under a tenth of the fine last resort's quads, and smoothing
 *    it keeps it valid without lowering its smallest scaled Jacobian (also
 *    on the torus); with arguments MESH H EULER LOOPS the same on a file
 *    (a sphere with 20 round holes: its rim sides' midpoints stay on their
 *    chords, moved onto the concave rims they left inverted quads; a
 *    marching-tetrahedra plate with a hole, `implicit part 24`: coarse
 *    triangles across its staircase creases keep their new points on their
 *    chords where the move onto the surface folded 4-11 quads); its
 *    tolerant rules (the relaxation) against the strict ones: fewer
 *    triangles on the sphere, a higher smallest scaled Jacobian on genus 2;
 *  - two components (the half cylinder and a speck beside it) are meshed
 *    apart: the grid's 40 quads and the speck's 12 from the last resort;
 *  - the check fails where it must: a face turned over (non-manifold and
 *    inverted), a face removed (a new boundary loop, Euler 1 of 2), a vertex
 *    moved h/2 off the surface (Hausdorff), a planar mesh or h <= 0
 *    refused. */
#include "testutil.h"

#include "glpgp/io.h"
#include "glpgp/surface.h"
#include "../host/quads/quads_surface.h"
#include "halfcyl_waves.h"

#include <stdlib.h>
#include <string.h>

#define HU (2.0 * GLPGP_PI / 9.0)
#define HV (2.0 / 3.0)

/* The half cylinder (5000 vertices), its plane waves (HU, HV; *r may be
 * NULL: freed) and their extraction *q: 0 when one of them failed. */
static int halfcyl_grid(glpgp_mesh **m, glpgp_result **r, glpgp_quadmesh **q)
{
    glpgp_result *rr = NULL;
    *q = NULL;
    CHECK_OK(glpgp_surface_generate("halfcyl", 5000, m));
    if (!*m) return 0;
    rr = halfcyl_waves(*m, HU, HV);
    if (rr) CHECK_OK(glpgp_quads_extract_surface(*m, rr, q));
    if (r) *r = rr;
    else glpgp_result_destroy(&rr);
    if (*q) return 1;
    glpgp_result_destroy(&rr);
    if (r) *r = NULL;
    glpgp_mesh_destroy(m);
    return 0;
}

static void extraction(void)
{
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    glpgp_quadmesh *q = NULL;
    const double hv = HV;
    if (!halfcyl_grid(&m, &r, &q)) return;
    {
        CHECK(q->nf == 40);
        for (int f = 0; f < q->nf; f++) CHECK(q->face_start[f + 1] - q->face_start[f] == 4);
        for (int i = 0; i < q->nv; i++) {
            const double *p = q->xyz + 3 * i;
            CHECK(fabs(hypot(p[0], p[1]) - 2.0) < 0.01); /* on the cylinder (chords of 1/70 of it) */
        }
        glpgp_quads_report qq;
        CHECK_OK(glpgp_quads_quality_surface(q, m, hv, &qq));
        CHECK(qq.invalid == 0);
        CHECK(qq.quads == 40 && qq.euler == 1 && qq.boundary_loops == 1);
        CHECK(qq.sj_min > 0.9);
        CHECK(qq.hausdorff < 0.05);
        CHECK(qq.valence_interior[4] == 27);
    }
    glpgp_quadmesh_destroy(&q);
    double h = hv;
    glpgp_quads_surface_steps steps;
    CHECK_OK(glpgp_quads_build_surface(m, r, NULL, &q, &h, &steps));
    CHECK(q && q->nf == 40 && !steps.fallback && !steps.subdivided && h == hv);
    glpgp_quadmesh_destroy(&q);
    /* a planar mesh is refused */
    glpgp_mesh *flat = NULL;
    CHECK_OK(glpgp_surface_generate("halfcyl_flat", 500, &flat));
    CHECK(glpgp_quads_extract_surface(flat, r, &q) == GLPGP_ERR_ARG && !q);
    glpgp_error_clear();
    glpgp_mesh_destroy(&flat);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
}

static void fallback(const char *shape, int euler, int loops)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_surface_generate(shape, 800, &m));
    if (!m) return;
    glpgp_quadmesh *q = NULL, *s = NULL;
    glpgp_quads_report qq;
    const double h = 0.3;
    CHECK_OK(glpgp_quads_surface_fallback(m, &q));
    if (!q) {
        glpgp_mesh_destroy(&m);
        return;
    }
    CHECK(q->nf == 3 * m->nt);
    CHECK_OK(glpgp_quads_quality_surface(q, m, h, &qq));
    CHECK(qq.invalid == 0 && qq.euler == euler && qq.boundary_loops == loops && qq.hausdorff < 1e-9);
    CHECK(qq.quads_by_origin[GLPGP_QFACE_FALLBACK] == q->nf);
    CHECK_OK(glpgp_quadmesh_subdivide_surface(q, &s));
    if (s) {
        CHECK(s->nf == 4 * q->nf);
        CHECK_OK(glpgp_quads_quality_surface(s, m, h, &qq));
        CHECK(qq.invalid == 0 && qq.euler == euler);
    }
    glpgp_quadmesh_destroy(&s);
    /* one face turned over */
    int *fv = q->face_vert + q->face_start[7];
    int t = fv[1];
    fv[1] = fv[3];
    fv[3] = t;
    CHECK_OK(glpgp_quads_quality_surface(q, m, h, &qq));
    CHECK(qq.invalid & GLPGP_QUADS_BAD_NONMANIFOLD);
    CHECK(qq.invalid & GLPGP_QUADS_BAD_INVERTED);
    fv[3] = fv[1];
    fv[1] = t;
    /* one face removed: a hole */
    q->nf--;
    CHECK_OK(glpgp_quads_quality_surface(q, m, h, &qq));
    CHECK((qq.invalid & GLPGP_QUADS_BAD_LOOPS) && (qq.invalid & GLPGP_QUADS_BAD_TOPOLOGY));
    CHECK(qq.euler == euler - 1 && qq.boundary_loops == loops + 1);
    q->nf++;
    /* a centroid moved h/2 along its triangle's normal */
    double *p = q->xyz + 3 * (q->nv - 1);
    const double *n = m->surf->tframe + 9 * (m->nt - 1) + 6;
    for (int d = 0; d < 3; d++) p[d] += 0.5 * h * n[d];
    CHECK_OK(glpgp_quads_quality_surface(q, m, h, &qq));
    CHECK(qq.invalid & GLPGP_QUADS_BAD_HAUSDORFF);
    CHECK(qq.hausdorff > 0.25);
    CHECK(glpgp_quads_quality_surface(q, m, 0.0, &qq) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

static void smoothing(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL;
    const double hu = HU, hv = HV;
    if (!halfcyl_grid(&m, NULL, &q)) return;
    glpgp_quads_report qq;
    int *val = NULL, v = -1;
    CHECK_OK(glpgp_quadmesh_valences(q, &val));
    for (int i = 0; i < q->nv && v < 0; i++) { /* an interior vertex (valence 4, off the rim) */
        const double *p = q->xyz + 3 * i;
        if (val[i] == 4 && fabs(p[2] - 1.0) < 0.5 && fabs(atan2(p[1], p[0]) - 0.5 * GLPGP_PI) < 1.0) v = i;
    }
    free(val);
    CHECK(v >= 0);
    double zlo = HUGE_VAL, zhi = -HUGE_VAL;
    for (int i = 0; i < m->nv; i++) {
        zlo = fmin(zlo, m->xyz[3 * i + 2]);
        zhi = fmax(zhi, m->xyz[3 * i + 2]);
    }
    double *keep = malloc((size_t)3 * q->nv * sizeof(double));
    memcpy(keep, q->xyz, (size_t)3 * q->nv * sizeof(double));
    double *p = q->xyz + 3 * v; /* slid 0.6 of a period along the arc and 0.3 along z */
    const double a = atan2(p[1], p[0]) + 0.6 * hu / 2.0;
    p[0] = 2.0 * cos(a);
    p[1] = 2.0 * sin(a);
    p[2] += 0.3 * hv;
    CHECK_OK(glpgp_quads_quality_surface(q, m, hv, &qq));
    const double before = qq.sj_min;
    CHECK(before < 0.5 && qq.invalid == 0);
    int moved = 0;
    CHECK_OK(glpgp_quads_smooth_surface(m, hv, GLPGP_FEATURE_ANGLE_DEFAULT, 20, q, &moved));
    CHECK_OK(glpgp_quads_quality_surface(q, m, hv, &qq));
    CHECK(moved >= 1 && qq.invalid == 0);
    CHECK(qq.sj_min > 0.9);
    if (!(qq.sj_min > 0.9)) fprintf(stderr, "smoothing: SJ min %.3f -> %.3f (%d moved)\n", before, qq.sj_min, moved);
    for (int i = 0; i < q->nv; i++) {
        const double *x = q->xyz + 3 * i;
        CHECK(fabs(hypot(x[0], x[1]) - 2.0) < 0.01);
        if (fabs(keep[3 * i + 2] - zlo) < 1e-9 || fabs(keep[3 * i + 2] - zhi) < 1e-9) /* on the rim: stays there */
            CHECK(fabs(x[2] - keep[3 * i + 2]) < 1e-12);
        if (fabs(keep[3 * i + 1]) < 1e-9) /* on the straight sides (y = 0): stays there */
            CHECK(fabs(x[0] - keep[3 * i]) + fabs(x[1] - keep[3 * i + 1]) < 1e-12);
        if (fabs(keep[3 * i + 1]) < 1e-9 && (fabs(keep[3 * i + 2] - zlo) < 1e-9 || fabs(keep[3 * i + 2] - zhi) < 1e-9))
            CHECK(fabs(x[2] - keep[3 * i + 2]) < 1e-12); /* the loop's corners stay */
    }
    free(keep);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* A vertex of the grid's rim moved along the rim to the input's rim vertex
 * 0.35 of a period away: the smoothing slides it back along the rim (it
 * stays on the input's boundary polyline, the rim's corners stay), and the
 * smallest scaled Jacobian rises; before the boundary slide it stayed. */
static void slide(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL;
    const double hu = HU, hv = HV;
    if (!halfcyl_grid(&m, NULL, &q)) return;
    double zlo = HUGE_VAL;
    for (int i = 0; i < m->nv; i++) zlo = fmin(zlo, m->xyz[3 * i + 2]);
    int v = -1;
    for (int i = 0; i < q->nv && v < 0; i++) { /* on the lower rim, near the middle of the arc */
        const double *p = q->xyz + 3 * i;
        if (fabs(p[2] - zlo) < 1e-9 && fabs(atan2(p[1], p[0]) - 0.5 * GLPGP_PI) < 0.5) v = i;
    }
    CHECK(v >= 0);
    if (v < 0) return;
    double *p = q->xyz + 3 * v;
    const double home = atan2(p[1], p[0]), target = home + 0.35 * hu;
    int w = -1;
    for (int i = 0; i < m->nv; i++) { /* the input's rim vertex nearest to that angle */
        const double *x = m->xyz + 3 * i;
        if (fabs(x[2] - zlo) < 1e-9 &&
            (w < 0 || fabs(atan2(x[1], x[0]) - target) < fabs(atan2(m->xyz[3 * w + 1], m->xyz[3 * w]) - target)))
            w = i;
    }
    memcpy(p, m->xyz + 3 * w, 3 * sizeof(double));
    double corners[4][3];
    int nc = 0;
    for (int i = 0; i < q->nv && nc < 4; i++)
        if (fabs(q->xyz[3 * i + 1]) < 1e-9 && fabs(fabs(q->xyz[3 * i + 2] - zlo) - 0.0) < 1e-9)
            memcpy(corners[nc++], q->xyz + 3 * i, sizeof corners[0]);
    glpgp_quads_report qq;
    CHECK_OK(glpgp_quads_quality_surface(q, m, hv, &qq));
    const double before = qq.sj_min;
    int moved = 0;
    CHECK_OK(glpgp_quads_smooth_surface(m, hv, GLPGP_FEATURE_ANGLE_DEFAULT, 20, q, &moved));
    CHECK_OK(glpgp_quads_quality_surface(q, m, hv, &qq));
    CHECK(qq.invalid == 0 && moved >= 1);
    CHECK(qq.sj_min > before + 0.15);
    if (!(qq.sj_min > before + 0.15)) fprintf(stderr, "slide: SJ min %.3f -> %.3f (%d moved)\n", before, qq.sj_min, moved);
    CHECK(fabs(p[2] - zlo) < 1e-12 && fabs(hypot(p[0], p[1]) - 2.0) < 0.01);
    CHECK(fabs(atan2(p[1], p[0]) - home) < 0.5 * fabs(target - home)); /* at least half way back */
    for (int k = 0; k < nc; k++) { /* the rim's ends (y = 0) stay */
        int found = 0;
        for (int i = 0; i < q->nv; i++)
            if (fabs(q->xyz[3 * i] - corners[k][0]) + fabs(q->xyz[3 * i + 1] - corners[k][1]) +
                    fabs(q->xyz[3 * i + 2] - corners[k][2]) < 1e-12)
                found = 1;
        CHECK(found);
    }
    CHECK(nc == 2);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* The faces of the 4 x 10 grid at interior vertex v (valence 4) replaced
 * by their outline, an octagon (v left unused); face g turned over. */
static void damage(glpgp_quadmesh *q, int v, int g)
{
    int ring[4][3], nr = 0, keep = 0, w = 0;
    int *fs = malloc((size_t)(q->nf + 1) * sizeof(int)), *fv = malloc((size_t)q->face_start[q->nf] * sizeof(int));
    if (!fs || !fv) goto out;
    for (int f = 0; f < q->nf; f++) {
        const int *c = q->face_vert + q->face_start[f];
        int at = -1;
        for (int i = 0; i < 4; i++)
            if (c[i] == v) at = i;
        if (at >= 0 && nr < 4) { /* the corners after v: a, b, c */
            for (int i = 0; i < 3; i++) ring[nr][i] = c[(at + 1 + i) % 4];
            nr++;
            continue;
        }
        fs[keep++] = w;
        for (int i = 0; i < 4; i++) fv[w++] = f == g ? c[(4 - i) % 4] : c[i];
    }
    CHECK(nr == 4);
    fs[keep++] = w;
    for (int k = 0, cur = 0; k < 4; k++) { /* the octagon: a, b of each face in fan order */
        fv[w++] = ring[cur][0];
        fv[w++] = ring[cur][1];
        for (int j = 0; j < 4; j++)
            if (ring[j][0] == ring[cur][2]) {
                cur = j;
                break;
            }
    }
    fs[keep] = w;
    memcpy(q->face_start, fs, (size_t)(keep + 1) * sizeof(int));
    memcpy(q->face_vert, fv, (size_t)w * sizeof(int));
    q->nf = keep;
out:
    free(fs);
    free(fv);
}

/* The local repair: the grid with an octagon in place of four quads and a
 * face turned over (not valid) comes back valid, all quads, with its Euler
 * characteristic and boundary loop, and keeps the grid's faces outside the
 * two regions (at least 27 of the 40). */
static void local_repair(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL, *r = NULL;
    if (!halfcyl_grid(&m, NULL, &q)) return;
    int *val = NULL, v = -1, g = -1;
    CHECK_OK(glpgp_quadmesh_valences(q, &val));
    for (int i = 0; i < q->nv && v < 0; i++) /* an interior vertex near the middle */
        if (val[i] == 4 && fabs(q->xyz[3 * i + 2] - 1.0) < 0.4 && fabs(atan2(q->xyz[3 * i + 1], q->xyz[3 * i]) - 0.8) < 0.4)
            v = i;
    for (int f = 0; f < q->nf && g < 0 && v >= 0; f++) { /* a face away from v's, off the rim */
        int far = 1, rim = 0;
        for (int i = q->face_start[f]; i < q->face_start[f + 1]; i++) {
            const double *p = q->xyz + 3 * q->face_vert[i], *x = q->xyz + 3 * v;
            far &= hypot(hypot(p[0] - x[0], p[1] - x[1]), p[2] - x[2]) > 1.5;
            rim |= val[q->face_vert[i]] < 4;
        }
        if (far && !rim) g = f;
    }
    free(val);
    CHECK(v >= 0 && g >= 0);
    if (v < 0 || g < 0) goto out;
    damage(q, v, g);
    glpgp_quads_report qq;
    CHECK_OK(glpgp_quads_quality_surface(q, m, HV, &qq));
    CHECK(qq.invalid & GLPGP_QUADS_BAD_NONMANIFOLD);
    CHECK(qq.others == 1);
    glpgp_quads_repair rs;
    CHECK_OK(glpgp_qs_local_repair(m, q, HV, 0, &r, &rs));
    CHECK(r != NULL);
    if (!r) goto out;
    CHECK_OK(glpgp_quads_quality_surface(r, m, HV, &qq));
    CHECK(qq.invalid == 0 && qq.others == 0 && qq.euler == 1 && qq.boundary_loops == 1);
    CHECK(qq.sj_min > 0.1);
    CHECK(rs.regions == 2 && rs.paved_regions == 2);
    CHECK(qq.quads_by_origin[GLPGP_QFACE_GRID] >= 27 && qq.quads_by_origin[GLPGP_QFACE_GRID] == r->nf - rs.new_quads);
    if (qq.invalid || qq.quads_by_origin[GLPGP_QFACE_GRID] < 27)
        fprintf(stderr, "local repair: invalid 0x%x, %d grid quads of %d, %d regions\n", qq.invalid,
                qq.quads_by_origin[GLPGP_QFACE_GRID], r->nf, rs.regions);
    for (int i = 0; i < r->nv; i++) /* on the cylinder */
        CHECK(fabs(hypot(r->xyz[3 * i], r->xyz[3 * i + 1]) - 2.0) < 0.01);
    glpgp_quadmesh *again = NULL; /* nothing left to repair */
    CHECK_OK(glpgp_qs_local_repair(m, r, HV, 0, &again, &rs));
    CHECK(again == NULL && rs.regions == 0);
    glpgp_quadmesh_destroy(&again);
out:
    glpgp_quadmesh_destroy(&r);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* The local repair of the grid with one face twice (an overlapping copy:
 * four non-manifold edges): valid again, all quads, Euler 1, one loop. */
static void overlap_repair(void)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q = NULL, *r = NULL;
    if (!halfcyl_grid(&m, NULL, &q)) return;
    int *val = NULL, g = -1;
    CHECK_OK(glpgp_quadmesh_valences(q, &val));
    for (int f = 0; f < q->nf && g < 0; f++) { /* a face off the rim */
        int rim = 0;
        for (int i = q->face_start[f]; i < q->face_start[f + 1]; i++) rim |= val[q->face_vert[i]] < 4;
        if (!rim) g = f;
    }
    free(val);
    CHECK(g >= 0);
    glpgp_quadmesh *d = NULL;
    if (g >= 0) CHECK_OK(glpgp_qs_alloc(q->nv, q->nf + 1, q->face_start[q->nf] + 4, &d));
    if (!d) goto out;
    memcpy(d->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
    memcpy(d->face_start, q->face_start, (size_t)(q->nf + 1) * sizeof(int));
    memcpy(d->face_vert, q->face_vert, (size_t)q->face_start[q->nf] * sizeof(int));
    d->face_start[q->nf + 1] = q->face_start[q->nf] + 4;
    memcpy(d->face_vert + q->face_start[q->nf], q->face_vert + q->face_start[g], 4 * sizeof(int));
    glpgp_qs_finish_from(d, q);
    glpgp_quads_report qq;
    CHECK_OK(glpgp_quads_quality_surface(d, m, HV, &qq));
    CHECK(qq.invalid & GLPGP_QUADS_BAD_NONMANIFOLD);
    glpgp_quads_repair rs;
    CHECK_OK(glpgp_qs_local_repair(m, d, HV, 0, &r, &rs));
    CHECK(r != NULL);
    if (r) {
        CHECK_OK(glpgp_quads_quality_surface(r, m, HV, &qq));
        CHECK(qq.invalid == 0 && qq.others == 0 && qq.euler == 1 && qq.boundary_loops == 1);
        if (qq.invalid) fprintf(stderr, "overlap repair: invalid 0x%x, %d regions\n", qq.invalid, rs.regions);
    }
    glpgp_quadmesh_destroy(&d);
out:
    glpgp_quadmesh_destroy(&r);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

static void coarse_mesh(const char *shape, glpgp_mesh *m, double h, int euler, int loops, int fewer);

static void coarse(const char *shape, long nv, double h, int euler, int loops)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_surface_generate(shape, nv, &m));
    if (m) coarse_mesh(shape, m, h, euler, loops, 1);
}

/* The coarse last resort on m (destroyed): valid with its Euler
 * characteristic and loops, 10x fewer quads than m's triangles (fewer: a
 * fine m), valid after the smoothing too. */
static void coarse_mesh(const char *shape, glpgp_mesh *m, double h, int euler, int loops, int fewer)
{
    glpgp_quadmesh *q = NULL;
    glpgp_quads_report qq;
    int nt = 0;
    CHECK_OK(glpgp_quads_surface_fallback_coarse(m, h, &q, &nt));
    if (q) {
        CHECK_OK(glpgp_quads_quality_surface(q, m, h, &qq));
        CHECK(qq.invalid == 0 && qq.others == 0 && qq.euler == euler && qq.boundary_loops == loops);
        CHECK(q->nf == 3 * nt && (!fewer || 10 * q->nf < 3 * m->nt));
        if (qq.invalid || (fewer && 10 * q->nf >= 3 * m->nt))
            fprintf(stderr, "coarse %s: %d quads of %d triangles, invalid 0x%x\n", shape, q->nf, m->nt, qq.invalid);
        const double before = qq.sj_min;
        CHECK_OK(glpgp_quads_smooth_surface(m, h, GLPGP_FEATURE_ANGLE_DEFAULT, 20, q, NULL));
        CHECK_OK(glpgp_quads_quality_surface(q, m, h, &qq));
        CHECK(qq.sj_min >= before && qq.euler == euler);
        CHECK(qq.invalid == 0); /* the moves keep the check's Hausdorff and orientation */
        if (qq.invalid) fprintf(stderr, "coarse %s smoothed: invalid 0x%x, Hausdorff %.3f h\n", shape, qq.invalid, qq.hausdorff);
    }
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* The coarse last resort's tolerant rules (the relaxation between the
 * passes) against the strict ones on a built-in shape at h: both valid,
 * the tolerant at most max_ratio of the strict's triangles and its smallest
 * scaled Jacobian at least min_gain higher (measured: sphere at 0.3, 190
 * -> 126 triangles, 0.244 -> 0.350; genus 2 at 0.3, 422 -> 414, 0.161 ->
 * 0.410). */
static void coarse_tolerant(const char *shape, double h, double max_ratio, double min_gain)
{
    glpgp_mesh *m = NULL;
    glpgp_quadmesh *q[2] = {NULL, NULL};
    glpgp_quads_report qq[2];
    int nt[2] = {0, 0};
    CHECK_OK(glpgp_surface_generate(shape, 5000, &m));
    for (int k = 0; k < 2 && m; k++) {
        CHECK_OK(glpgp_qs_coarse(m, h, GLPGP_FEATURE_ANGLE_DEFAULT, 17.0, k, &q[k], &nt[k]));
        if (q[k]) CHECK_OK(glpgp_quads_quality_surface(q[k], m, h, &qq[k]));
    }
    if (q[0] && q[1]) {
        CHECK(qq[0].invalid == 0 && qq[1].invalid == 0);
        CHECK(nt[1] <= max_ratio * nt[0]);
        CHECK(qq[1].sj_min >= qq[0].sj_min + min_gain);
        if (nt[1] > max_ratio * nt[0] || qq[1].sj_min < qq[0].sj_min + min_gain)
            fprintf(stderr, "coarse %s: strict %d triangles SJ %.3f, tolerant %d SJ %.3f\n", shape, nt[0],
                    qq[0].sj_min, nt[1], qq[1].sj_min);
    }
    glpgp_quadmesh_destroy(&q[0]);
    glpgp_quadmesh_destroy(&q[1]);
    glpgp_mesh_destroy(&m);
}

/* Two components, the half cylinder and a speck (a tetrahedron 0.01
 * across beside it), with the cylinder's plane waves: meshed apart, the
 * grid's 40 quads kept and the speck alone split by the last resort (its
 * 4 triangles into 12 quads); the whole went to the last resort before. */
static void parts(void)
{
    glpgp_mesh *hc = NULL, *m = NULL;
    CHECK_OK(glpgp_surface_generate("halfcyl", 5000, &hc));
    if (!hc) return;
    const int nv = hc->nv + 4, nt = hc->nt + 4;
    double *xyz = malloc((size_t)3 * nv * sizeof(double));
    int *tri = malloc((size_t)3 * nt * sizeof(int));
    if (xyz && tri) {
        const double sp = 0.01, P[12] = {5, 0, 0, 5 + sp, 0, 0, 5, sp, 0, 5, 0, sp};
        const int T[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
        memcpy(xyz, hc->xyz, (size_t)3 * hc->nv * sizeof(double));
        memcpy(xyz + 3 * hc->nv, P, sizeof P);
        memcpy(tri, hc->tri, (size_t)3 * hc->nt * sizeof(int));
        for (int k = 0; k < 12; k++) tri[3 * hc->nt + k] = hc->nv + T[k];
        CHECK_OK(glpgp_mesh_create_surface(nv, xyz, nt, tri, &m));
    }
    glpgp_result *r = m ? halfcyl_waves(m, HU, HV) : NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_quads_surface_steps st;
    double h = HV;
    if (r) CHECK_OK(glpgp_quads_build_surface(m, r, NULL, &q, &h, &st));
    CHECK(q != NULL);
    if (q) {
        CHECK(st.parts == 2 && st.parts_last_resort == 1 && !st.fallback && !st.subdivided);
        CHECK(q->nf == 40 + 12 && h == HV);
        glpgp_quads_report qq;
        CHECK_OK(glpgp_quads_quality_surface(q, m, HV, &qq));
        CHECK(qq.invalid == 0 && qq.quads == 52 && qq.euler == 3 && qq.boundary_loops == 1);
    }
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    glpgp_mesh_destroy(&hc);
    free(xyz);
    free(tri);
}

static void dbg_log(glpgp_log_level l, const char *msg, void *u)
{
    (void)l;
    (void)u;
    if (getenv("XXDBG")) fprintf(stderr, "%s\n", msg);
}

int main(int argc, char **argv)
{
    glpgp_log_set_callback(dbg_log, NULL);
    if (argc == 5) { /* MESH H EULER LOOPS: the coarse last resort on a file (tests/CMakeLists.txt) */
        glpgp_mesh *m = NULL;
        CHECK_OK(glpgp_mesh_read(argv[1], &m));
        if (m) coarse_mesh(argv[1], m, atof(argv[2]), atoi(argv[3]), atoi(argv[4]), 0);
        TEST_DONE();
    }
    extraction();
    smoothing();
    slide();
    local_repair();
    overlap_repair();
    parts();
    coarse("genus2", 5000, 0.55, -2, 0);
    coarse("cube", 5000, 0.3, 2, 0);
    coarse("hemisphere", 5000, 0.25, 1, 1);
    coarse("torus", 5000, 0.23, 0, 0);
    coarse_tolerant("sphere", 0.3, 0.8, 0.05);
    coarse_tolerant("genus2", 0.3, 1.0, 0.15);
    fallback("sphere", 2, 0);
    fallback("hemisphere", 1, 1);
    TEST_DONE();
}
