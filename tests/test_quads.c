/* test_quads.c: quad extraction and its quality report.
 *  - plane waves z_u = exp(2 pi i x / h), z_v = exp(2 pi i y / h) on the unit
 *    square with 1/h = 5 (no solve): exactly 25 quads, every interior vertex
 *    valence 4, scaled Jacobian > 0.99, exact boundary;
 *  - the same from a real GL solve (square, h = 0.2);
 *  - annulus with the radial and the default guiding field: no inverted or
 *    degenerate face, conforming, covers the domain, non-quad faces and
 *    irregular vertices only where the solve reports singularities;
 *  - data/annulus.msh (a domain with a hole; GLPGP_DATA): conforming, no
 *    inverted face, boundary Hausdorff distance < 0.25 h;
 *  - data/plate_holes.msh (the default domain: holes, a small ellipse, a
 *    v dipole): no degenerate or inverted face (a level-line loop left by
 *    the short-side contraction once gave a zero-length edge and a 10-gon),
 *    every face a quad (boundary pentagons closed by a diagonal or a centre
 *    vertex);
 *  - glpgp_quadmesh_subdivide (--all-quads) on the radial annulus: only
 *    quads, n quads per n-gon, conforming, same area, nothing inverted;
 *  - writers (OBJ / VTK / MSH, MSH read back), JSON report appended to an
 *    existing object;
 *  - a result without oscillators is rejected with GLPGP_ERR_FORMAT. */
#include "output.h"
#include "quads.h"
#include "result_io.h"
#include "testutil.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI_ 3.14159265358979323846

static void print_q(const char *what, const glpgp_quad_quality *qq)
{
    if (*what) printf("%s:\n", what);
    glpgp_quads_print(stdout, qq, "  ");
}

/* Common invariants of every extracted mesh. */
static void check_valid(const glpgp_quad_quality *qq, const glpgp_mesh *m)
{
    CHECK(qq->inverted == 0);
    CHECK(qq->degenerate == 0);
    CHECK(qq->nonmanifold_edges == 0);
    CHECK(qq->gap_edges == 0); /* every one-face edge lies on the domain boundary */
    /* the faces cover the domain: area within 2% (curved boundaries are chords) */
    CHECK_CLOSE(qq->area, m->area, 0, 0.02);
}

static glpgp_result *plane_waves(const glpgp_mesh *m, double h)
{
    glpgp_result *r = calloc(1, sizeof *r);
    r->nv = m->nv;
    r->nt = m->nt;
    r->size = h;
    for (int k = 0; k < 2; k++) {
        r->osc[k].z = malloc(sizeof(double) * 2 * m->nv);
        r->osc[k].dirichlet = calloc((size_t)m->nv, 1);
        r->osc[k].singular = calloc((size_t)m->nt, 1);
        for (int i = 0; i < m->nv; i++) {
            double t = m->xy[2 * i + k] / h; /* theta_u = x / h, theta_v = y / h */
            double fr = t - floor(t + 0.5);
            if (fabs(fr) < 1e-12) { /* exactly on a level line: z = 1 as a Dirichlet vertex */
                r->osc[k].z[2 * i] = 1.0;
                r->osc[k].z[2 * i + 1] = 0.0;
            } else {
                r->osc[k].z[2 * i] = cos(2 * PI_ * t);
                r->osc[k].z[2 * i + 1] = sin(2 * PI_ * t);
            }
        }
    }
    return r;
}

static glpgp_result *solve(const glpgp_mesh *m, double h, int field)
{
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    glpgp_options o;
    glpgp_options_default(&o);
    o.verbose = 0;
    o.size = h;
    o.field = field;
    o.newton_max = 20;
    CHECK_OK(glpgp_solve(m, b, &o, &r));
    glpgp_backend_destroy(&b);
    return r;
}

static void test_square_exact(const char *dir)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("square", 2000, &m));
    glpgp_result *r = plane_waves(m, 0.2);
    glpgp_quadmesh *q = NULL;
    CHECK_OK(glpgp_quads_extract(m, r, &q));
    if (!q) goto out;
    glpgp_quad_quality qq;
    CHECK_OK(glpgp_quads_quality(q, m, 0.2, &qq));
    print_q("square, plane waves, h = 0.2", &qq);
    CHECK(qq.quads == 25 && qq.others == 0);
    CHECK(qq.vertices == 36);
    CHECK(qq.valence_interior[4] == 16 && qq.irregular == 0);
    CHECK(qq.sj_min > 0.99);
    CHECK(qq.hausdorff >= 0 && qq.hausdorff < 1e-6);
    CHECK_CLOSE(qq.len_mean, 1.0, 1e-6, 0);
    check_valid(&qq, m);

    /* writers: OBJ (4-vertex faces), VTK (VTK_QUAD), MSH read back */
    char p[512];
    snprintf(p, sizeof p, "%s/q.obj", dir);
    CHECK_OK(glpgp_quads_write(q, p));
    FILE *f = fopen(p, "r");
    int nfl = 0, nv4 = 0;
    char line[256];
    while (f && fgets(line, sizeof line, f)) {
        if (line[0] == 'f') {
            int a, b, c, d, e;
            nfl++;
            if (sscanf(line + 1, "%d %d %d %d %d", &a, &b, &c, &d, &e) == 4) nv4++;
        }
    }
    if (f) fclose(f);
    CHECK(nfl == 25 && nv4 == 25);
    snprintf(p, sizeof p, "%s/q.vtk", dir);
    CHECK_OK(glpgp_quads_write(q, p));
    f = fopen(p, "r");
    int n9 = 0, in_types = 0;
    while (f && fgets(line, sizeof line, f)) {
        if (!strncmp(line, "CELL_TYPES", 10)) in_types = 1;
        else if (!strncmp(line, "CELL_DATA", 9)) in_types = 0;
        else if (in_types && atoi(line) == 9) n9++;
    }
    if (f) fclose(f);
    CHECK(n9 == 25);
    snprintf(p, sizeof p, "%s/q.msh", dir);
    CHECK_OK(glpgp_quads_write(q, p));
    glpgp_quadmesh *q2 = NULL;
    CHECK_OK(glpgp_quads_read_msh(p, &q2));
    if (q2) {
        glpgp_quad_quality q2q;
        CHECK_OK(glpgp_quads_quality(q2, m, 0.2, &q2q));
        CHECK(q2q.quads == 25 && q2q.vertices == 36 && q2q.sj_min > 0.99);
        glpgp_quadmesh_destroy(&q2);
    }
    snprintf(p, sizeof p, "%s/q.txt", dir);
    CHECK(glpgp_quads_write(q, p) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    CHECK(access(p, F_OK) != 0);

    /* JSON report appended to an existing object */
    snprintf(p, sizeof p, "%s/s.json", dir);
    f = fopen(p, "w");
    fputs("{\n  \"vertices\": 3\n}\n", f);
    fclose(f);
    CHECK_OK(glpgp_quads_append_json(p, &qq));
    f = fopen(p, "r");
    char buf[8192] = {0};
    size_t nr = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f) fclose(f);
    CHECK(nr > 0 && strstr(buf, "\"vertices\": 3,") && strstr(buf, "\"quads\": {\"vertices\": 36"));
    CHECK(strstr(buf, "\"scaled_jacobian\"") && strstr(buf, "\"irregular_vertices\""));

    /* a result without oscillators */
    free(r->osc[0].z);
    r->osc[0].z = NULL;
    glpgp_quadmesh *q3 = NULL;
    CHECK(glpgp_quads_extract(m, r, &q3) == GLPGP_ERR_FORMAT && q3 == NULL);
    CHECK(strstr(glpgp_error_message(), "no oscillators") != NULL);
    glpgp_error_clear();
out:
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
}

static void test_square_solved(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("square", 10000, &m));
    glpgp_result *r = solve(m, 0.2, GLPGP_FIELD_BOUNDARY);
    glpgp_quadmesh *q = NULL;
    if (r) CHECK_OK(glpgp_quads_extract(m, r, &q));
    if (q) {
        glpgp_quad_quality qq;
        CHECK_OK(glpgp_quads_quality(q, m, 0.2, &qq));
        print_q("square, GL solve, h = 0.2", &qq);
        CHECK(qq.quads == 25 && qq.others == 0);
        CHECK(qq.irregular_interior == 0 && qq.valence_interior[4] == 16);
        CHECK(qq.sj_min > 0.99);
        check_valid(&qq, m);
    }
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
}

static void test_annulus(int field, const char *name)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("annulus", 20000, &m));
    glpgp_result *r = solve(m, 0.1, field);
    glpgp_quadmesh *q = NULL;
    if (r) CHECK_OK(glpgp_quads_extract(m, r, &q));
    if (q) {
        glpgp_quad_quality qq;
        CHECK_OK(glpgp_quads_quality(q, m, 0.1, &qq));
        int ns = r->osc[0].plus + r->osc[0].minus + r->osc[1].plus + r->osc[1].minus;
        printf("annulus, %s field, h = 0.1: %d singular triangles (u +%d -%d, v +%d -%d)\n", name,
               ns, r->osc[0].plus, r->osc[0].minus, r->osc[1].plus, r->osc[1].minus);
        print_q("", &qq);
        check_valid(&qq, m);
        CHECK(qq.hausdorff < 0.25);
        CHECK(qq.sj_min > 0.0);
        /* a clean solve: most faces are quads */
        CHECK(qq.quads >= 0.85 * qq.faces);
        /* non-quad faces and interior irregular vertices come from the
         * singularities (each closes into one T / 3-5 configuration) and from
         * the 4 + 4 places where the boundary switches from a u line to a v
         * line (default field) */
        int extra = field == GLPGP_FIELD_RADIAL ? 0 : 8;
        CHECK(qq.others <= ns + extra);
        CHECK(qq.irregular_interior <= 2 * ns + extra);
        if (ns == 0) CHECK(qq.irregular_interior == 0);
        if (field == GLPGP_FIELD_RADIAL) {
            /* the radial lines end at the v singularities: one valence-3
             * vertex per singular triangle, none on the boundary */
            CHECK(qq.irregular_interior >= ns / 2 && qq.irregular_boundary == 0);
            /* --all-quads: every n-gon -> n quads, the interior pentagons too */
            glpgp_quadmesh *fine = NULL;
            CHECK_OK(glpgp_quadmesh_subdivide(q, &fine));
            if (fine) {
                glpgp_quad_quality fq;
                CHECK_OK(glpgp_quads_quality(fine, m, 0.05, &fq));
                print_q("  refined (--all-quads), h = 0.05", &fq);
                CHECK(fq.others == 0 && fq.quads == q->face_start[q->nf]);
                check_valid(&fq, m);
                CHECK_CLOSE(fq.area, qq.area, 1e-9, 1e-9);
                CHECK(fq.sj_min > 0.0);
                CHECK(fq.hausdorff < 0.25);
                CHECK_CLOSE(fq.len_mean, 1.0, 0, 0.3);
                glpgp_quadmesh_destroy(&fine);
            }
        }
    }
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
}

static void test_data_hole(void)
{
    const char *dd = getenv("GLPGP_DATA");
    char p[1024];
    snprintf(p, sizeof p, "%s/annulus.msh", dd ? dd : "data");
    if (access(p, R_OK) != 0) {
        printf("data/annulus.msh not found (GLPGP_DATA), skipped\n");
        return;
    }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_read(p, &m));
    if (!m) return;
    double h = glpgp_default_size(m);
    glpgp_result *r = solve(m, h, GLPGP_FIELD_BOUNDARY);
    glpgp_quadmesh *q = NULL;
    if (r) CHECK_OK(glpgp_quads_extract(m, r, &q));
    if (q) {
        glpgp_quad_quality qq;
        CHECK_OK(glpgp_quads_quality(q, m, h, &qq));
        printf("data/annulus.msh, h = %g:\n", h);
        print_q("", &qq);
        check_valid(&qq, m);
        CHECK(qq.hausdorff < 0.25);
        CHECK(qq.boundary_edges > 0);
        /* conforming: every edge in at most two faces, and the edges used by
         * one face form closed boundary loops (each boundary vertex on exactly
         * two boundary edges) */
        int *bdeg = calloc((size_t)q->nv, sizeof(int));
        int n = q->face_start[q->nf];
        int *pr = malloc(sizeof(int) * 2 * n);
        for (int f = 0; f < q->nf; f++) {
            int s = q->face_start[f], k = q->face_start[f + 1] - s;
            for (int i = 0; i < k; i++) {
                int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
                pr[2 * (s + i)] = a < b ? a : b;
                pr[2 * (s + i) + 1] = a < b ? b : a;
            }
        }
        int bad = 0;
        for (int i = 0; i < n; i++) {
            int cnt = 0;
            for (int j = 0; j < n; j++)
                if (pr[2 * j] == pr[2 * i] && pr[2 * j + 1] == pr[2 * i + 1]) cnt++;
            if (cnt > 2) bad++;
            if (cnt == 1) {
                bdeg[pr[2 * i]]++;
                bdeg[pr[2 * i + 1]]++;
            }
        }
        CHECK(bad == 0);
        int oddb = 0;
        for (int i = 0; i < q->nv; i++)
            if (bdeg[i] != 0 && bdeg[i] != 2) oddb++;
        CHECK(oddb == 0);
        free(bdeg);
        free(pr);
    }
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
}

/* Whether some face of q lists a vertex twice (a loop side or a bridge). */
static int repeated_corner(const glpgp_quadmesh *q)
{
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++)
            for (int j = i + 1; j < k; j++)
                if (q->face_vert[s + i] == q->face_vert[s + j]) return 1;
    }
    return 0;
}

static void test_data_plate(void)
{
    const char *dd = getenv("GLPGP_DATA");
    char p[1024];
    snprintf(p, sizeof p, "%s/plate_holes.msh", dd ? dd : "data");
    if (access(p, R_OK) != 0) {
        printf("data/plate_holes.msh not found (GLPGP_DATA), skipped\n");
        return;
    }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_read(p, &m));
    if (!m) return;
    double h = glpgp_default_size(m);
    glpgp_result *r = solve(m, h, GLPGP_FIELD_BOUNDARY);
    glpgp_quadmesh *q = NULL;
    if (r) CHECK_OK(glpgp_quads_extract(m, r, &q));
    if (q) {
        glpgp_quad_quality qq;
        CHECK_OK(glpgp_quads_quality(q, m, h, &qq));
        printf("data/plate_holes.msh, h = %g: singular u +%d -%d, v +%d -%d\n", h,
               r->osc[0].plus, r->osc[0].minus, r->osc[1].plus, r->osc[1].minus);
        print_q("", &qq);
        CHECK(qq.degenerate == 0);
        CHECK(qq.inverted == 0);
        CHECK(!repeated_corner(q));
        CHECK(qq.len_min > 0.05);
        check_valid(&qq, m);
        CHECK(qq.hausdorff < 0.25);
        CHECK(qq.others == 0);
        CHECK(qq.sj_min > 0.3);
    }
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    char dir[] = "/tmp/glpgp_quads_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    test_square_exact(dir);
    test_square_solved();
    test_annulus(GLPGP_FIELD_RADIAL, "radial");
    test_annulus(GLPGP_FIELD_BOUNDARY, "default");
    test_data_hole();
    test_data_plate();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "note: could not remove %s\n", dir);
    TEST_DONE();
}
