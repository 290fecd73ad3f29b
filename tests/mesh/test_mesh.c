/* test_mesh.c: tests for glpgp_mesh_create (validation, orientation repair,
 * boundary loops and normals) and the mesh readers/writers (OBJ, MSH 2.2/4.1,
 * error cases, the meshes in data/, write/read round trips, a part far from
 * the origin). */
#include "testutil.h"

#include <dirent.h>
#include <string.h>
#include <unistd.h>

static char g_tmp[256];

static double tri_area(const glpgp_mesh *m, int t)
{
    const int *v = m->tri + 3 * t;
    const double *a = m->xy + 2 * v[0], *b = m->xy + 2 * v[1], *c = m->xy + 2 * v[2];
    return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

static int all_ccw(const glpgp_mesh *m)
{
    for (int t = 0; t < m->nt; t++)
        if (!(tri_area(m, t) > 0.0)) return 0;
    return 1;
}

/* Signed area of boundary loop l. */
static double loop_area(const glpgp_mesh *m, int l)
{
    int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
    double a = 0.0;
    const double *o = m->xy + 2 * m->loop_vertices[s]; /* about the first vertex: no cancellation */
    for (int i = 0; i < n; i++) {
        const double *p = m->xy + 2 * m->loop_vertices[s + i], *q = m->xy + 2 * m->loop_vertices[s + (i + 1) % n];
        a += (p[0] - o[0]) * (q[1] - o[1]) - (q[0] - o[0]) * (p[1] - o[1]);
    }
    return 0.5 * a;
}

/* Structural checks every valid mesh must pass. */
static void check_invariants(const glpgp_mesh *m)
{
    CHECK(all_ccw(m));
    CHECK(m->nloops >= 1);
    double sum = 0.0;
    for (int t = 0; t < m->nt; t++) sum += tri_area(m, t);
    CHECK(fabs(sum - m->area) <= 1e-12 * fabs(m->area));
    /* Outer loop CCW and largest; holes CW; loop areas add up to the mesh area. */
    double la = 0.0;
    for (int l = 0; l < m->nloops; l++) {
        double a = loop_area(m, l);
        la += a;
        if (l == 0) CHECK(a > 0.0);
        else CHECK(a < 0.0 && fabs(a) <= loop_area(m, 0));
    }
    CHECK(fabs(la - m->area) <= 1e-9 * m->area);
    int nb = 0;
    for (int v = 0; v < m->nv; v++) nb += m->on_boundary[v] != 0;
    CHECK(nb == m->loop_start[m->nloops]);
    /* Normals: unit length, perpendicular to the edge, pointing to the right. */
    int bad = 0;
    for (int l = 0; l < m->nloops; l++) {
        int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
        for (int i = 0; i < n; i++) {
            int p = m->loop_vertices[s + i], q = m->loop_vertices[s + (i + 1) % n];
            double dx = m->xy[2 * q] - m->xy[2 * p], dy = m->xy[2 * q + 1] - m->xy[2 * p + 1];
            const double *nn = m->normal_next + 2 * p, *np = m->normal_prev + 2 * q;
            if (fabs(hypot(nn[0], nn[1]) - 1.0) > 1e-12) bad++;
            if (fabs(nn[0] * dx + nn[1] * dy) > 1e-12 * hypot(dx, dy)) bad++;
            if (!(nn[0] * dy - nn[1] * dx > 0.0)) bad++;
            if (nn[0] != np[0] || nn[1] != np[1]) bad++;
        }
    }
    CHECK(bad == 0);
}

static void test_square2(void)
{
    const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
    const int tri[] = {0, 1, 2, 0, 2, 3};
    glpgp_mesh *m = NULL;
    CHECK(glpgp_mesh_create(4, xy, 2, tri, &m) == GLPGP_OK);
    if (!m) return;
    CHECK(m->nv == 4 && m->nt == 2);
    CHECK(fabs(m->area - 1.0) < 1e-15);
    CHECK(m->orientation_fixed == 0);
    CHECK(m->nloops == 1);
    CHECK(m->loop_start[0] == 0 && m->loop_start[1] == 4);
    CHECK(m->bbox[0] == 0 && m->bbox[1] == 0 && m->bbox[2] == 1 && m->bbox[3] == 1);
    CHECK(fabs(m->mean_edge - (4.0 + sqrt(2.0)) / 5.0) < 1e-15);
    for (int v = 0; v < 4; v++) CHECK(m->on_boundary[v]);
    /* Loop order follows the CCW boundary 0 -> 1 -> 2 -> 3. */
    int s = -1;
    for (int i = 0; i < 4; i++)
        if (m->loop_vertices[i] == 0) s = i;
    CHECK(s >= 0);
    if (s >= 0)
        for (int i = 0; i < 4; i++) CHECK(m->loop_vertices[(s + i) % 4] == i);
    /* Vertex 0 = (0,0): edge 3->0 enters (outward -x), edge 0->1 leaves (outward -y). */
    CHECK(m->normal_prev[0] == -1.0 && m->normal_prev[1] == 0.0);
    CHECK(m->normal_next[0] == 0.0 && m->normal_next[1] == -1.0);
    /* Vertex 2 = (1,1): 1->2 enters (+x), 2->3 leaves (+y). */
    CHECK(m->normal_prev[4] == 1.0 && m->normal_prev[5] == 0.0);
    CHECK(m->normal_next[4] == 0.0 && m->normal_next[5] == 1.0);
    check_invariants(m);
    glpgp_mesh_destroy(&m);
    CHECK(m == NULL);
    glpgp_mesh_destroy(&m); /* NULL is fine */
    glpgp_mesh_destroy(NULL);
}

static void test_orientation(void)
{
    const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
    glpgp_mesh *m = NULL;
    const int one_flipped[] = {0, 1, 2, 0, 3, 2};
    CHECK(glpgp_mesh_create(4, xy, 2, one_flipped, &m) == GLPGP_OK);
    if (m) {
        CHECK(m->orientation_fixed == 1);
        CHECK(fabs(m->area - 1.0) < 1e-15);
        check_invariants(m);
        glpgp_mesh_destroy(&m);
    }
    const int all_cw[] = {0, 2, 1, 0, 3, 2};
    CHECK(glpgp_mesh_create(4, xy, 2, all_cw, &m) == GLPGP_OK);
    if (m) {
        CHECK(m->orientation_fixed == 2);
        CHECK(fabs(m->area - 1.0) < 1e-15);
        check_invariants(m);
        glpgp_mesh_destroy(&m);
    }
    /* Two components: one CW, one CCW with a flipped triangle. */
    const double xy2[] = {0, 0, 1, 0, 1, 1, 0, 1, 3, 0, 4, 0, 4, 1, 3, 1};
    const int tri2[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 7, 6};
    CHECK(glpgp_mesh_create(8, xy2, 4, tri2, &m) == GLPGP_OK);
    if (m) {
        CHECK(m->orientation_fixed == 3);
        CHECK(m->nloops == 2);
        CHECK(fabs(m->area - 2.0) < 1e-15);
        CHECK(all_ccw(m));
        glpgp_mesh_destroy(&m);
    }
    /* Moebius strip (5 vertices on a pentagon, triangles (i, i+1, i+2)). */
    double pent[10];
    for (int i = 0; i < 5; i++) {
        pent[2 * i] = cos(2 * 3.14159265358979 * i / 5);
        pent[2 * i + 1] = sin(2 * 3.14159265358979 * i / 5);
    }
    int mob[15];
    for (int i = 0; i < 5; i++) {
        mob[3 * i] = i;
        mob[3 * i + 1] = (i + 1) % 5;
        mob[3 * i + 2] = (i + 2) % 5;
    }
    glpgp_error_clear();
    CHECK(glpgp_mesh_create(5, pent, 5, mob, &m) == GLPGP_ERR_MESH);
    CHECK(m == NULL);
    CHECK(strstr(glpgp_error_message(), "non-orientable") != NULL);
    glpgp_error_clear();
}

static void expect_reject(int nv, const double *xy, int nt, const int *tri, const char *needle, int line)
{
    glpgp_mesh *m = (glpgp_mesh *)&m; /* must be reset to NULL */
    glpgp_error_clear();
    glpgp_status st = glpgp_mesh_create(nv, xy, nt, tri, &m);
    if (st != GLPGP_ERR_MESH || m != NULL || !strstr(glpgp_error_message(), needle)) {
        fprintf(stderr, "%s:%d: expected GLPGP_ERR_MESH containing '%s', got %d: %s\n", __FILE__, line, needle,
                (int)st, glpgp_error_message());
        tu_failures++;
    }
    if (st == GLPGP_OK) glpgp_mesh_destroy(&m);
    glpgp_error_clear();
}

static void test_rejects(void)
{
    const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
    const int out_of_range[] = {0, 1, 2, 0, 2, 4};
    expect_reject(4, xy, 2, out_of_range, "triangle 1", __LINE__);
    const int negative[] = {0, 1, 2, -1, 2, 3};
    expect_reject(4, xy, 2, negative, "triangle 1", __LINE__);
    const int repeated[] = {0, 1, 2, 0, 2, 2};
    expect_reject(4, xy, 2, repeated, "triangle 1", __LINE__);
    const int unused[] = {0, 1, 2};
    expect_reject(4, xy, 1, unused, "vertex 3", __LINE__);
    expect_reject(2, xy, 1, unused, "at least 3", __LINE__);
    expect_reject(4, xy, 0, unused, "at least 1", __LINE__);

    const double col[] = {0, 0, 1, 0, 2, 0, 0, 1};
    const int degen[] = {0, 1, 3, 0, 1, 2};
    expect_reject(4, col, 2, degen, "triangle 1", __LINE__);
    expect_reject(4, col, 2, degen, "degenerate", __LINE__);
    /* Nearly degenerate (area ~ 1e-16 of bbox^2) is rejected too. */
    const double thin[] = {0, 0, 1, 0, 0.5, 1e-17, 0, 1};
    const int thin_t[] = {0, 1, 3, 0, 1, 2};
    expect_reject(4, thin, 2, thin_t, "triangle 1", __LINE__);

    const double nm[] = {0, 0, 1, 0, 0.5, 1, 0.5, -1, 0.5, 2};
    const int nm_t[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    expect_reject(5, nm, 3, nm_t, "non-manifold", __LINE__);
    expect_reject(5, nm, 3, nm_t, "(0, 1)", __LINE__);

    /* Bow tie: two triangles touching at vertex 0 only. */
    const double bow[] = {0, 0, 1, 0, 1, 1, -1, 0, -1, -1};
    const int bow_t[] = {0, 1, 2, 0, 3, 4};
    expect_reject(5, bow, 2, bow_t, "vertex 0", __LINE__);
    /* One component, hole touching the outer boundary: square [0,2]^2 minus
     * the triangle (1,0) (0.8,1) (1.2,1) whose apex lies on the bottom edge.
     * Vertices 0..3 corners, 4 = apex, 5, 6 = hole top corners, 7 = (1,1.5). */
    const double ph[] = {0, 0, 2, 0, 2, 2, 0, 2, 1, 0, 0.8, 1, 1.2, 1, 1, 1.5};
    const int ph_t[] = {0, 4, 5, 0, 5, 3, 5, 7, 3, 5, 6, 7, 6, 2, 7, 7, 2, 3, 4, 1, 6, 6, 1, 2};
    expect_reject(8, ph, 8, ph_t, "vertex 4", __LINE__);
    /* The same without the pinch (apex lifted to (1,0.5), bottom edge split
     * at (1,0) by vertex 8) is accepted and has a hole. */
    const double ok[] = {0, 0, 2, 0, 2, 2, 0, 2, 1, 0.5, 0.8, 1, 1.2, 1, 1, 1.5, 1, 0};
    const int ok_t[] = {0, 8, 4, 0, 4, 5, 0, 5, 3, 5, 7, 3, 5, 6, 7, 6, 2, 7, 7, 2, 3,
                        8, 1, 4, 4, 1, 6, 6, 1, 2};
    glpgp_mesh *m = NULL;
    glpgp_error_clear();
    CHECK(glpgp_mesh_create(9, ok, 10, ok_t, &m) == GLPGP_OK);
    if (m) {
        CHECK(m->nloops == 2);
        CHECK(m->loop_start[1] == 5 && m->loop_start[2] == 8);
        CHECK(fabs(m->area - 3.9) < 1e-14);
        check_invariants(m);
        glpgp_mesh_destroy(&m);
    }
}

/* ------------------------------------------------------------------------ */

static const char *tmp_path(const char *name)
{
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", g_tmp, name);
    return buf[k];
}

static const char *write_file(const char *name, const char *text, size_t len)
{
    const char *p = tmp_path(name);
    FILE *f = fopen(p, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", p);
        tu_failures++;
        return p;
    }
    fwrite(text, 1, len ? len : strlen(text), f);
    fclose(f);
    return p;
}

/* Read `path`; expect status st and (if needle) the message to contain it. */
static glpgp_mesh *read_expect(const char *path, glpgp_status st, const char *needle, int line)
{
    glpgp_mesh *m = NULL;
    glpgp_error_clear();
    glpgp_status got = glpgp_mesh_read(path, &m);
    if (got != st || (needle && !strstr(glpgp_error_message(), needle)) || (st != GLPGP_OK && m)) {
        fprintf(stderr, "%s:%d: reading %s: expected status %d%s%s, got %d: %s\n", __FILE__, line, path, (int)st,
                needle ? " containing " : "", needle ? needle : "", (int)got, glpgp_error_message());
        tu_failures++;
    }
    glpgp_error_clear();
    return m;
}

static void test_obj(void)
{
    /* 3x3 grid on [0,1]^2 in the plane z = 2.5, 4 quads written in every
     * index form, negative indices, an unused vertex, ignored statements. */
    const char *obj = "# test\r\n"
                      "mtllib x.mtl\n"
                      "o grid\n"
                      "v 0 0 2.5\n"
                      "v 0.5 0 2.5\n"
                      "v 1 0 2.5\n"
                      "v 0 0.5 2.5\n"
                      "v 0.5 0.5 2.5\n"
                      "v 1 0.5 2.5 1.0\n"
                      "v 7 7 2.5\n"
                      "v 0 1 2.5\n"
                      "v 0.5 1 2.5\n"
                      "v 1 1 2.5\n"
                      "vt 0 0\n"
                      "vn 0 0 1\n"
                      "g g1\n"
                      "usemtl m\n"
                      "s off\n"
                      "f 1 2 5 4\n"
                      "f 2/1 3/1 6/1 5/1\n"
                      "  f 4//1 5//1 9//1 8//1  \n"
                      "f -6/1/1 -5/1/1 -1/1/1 -2/1/1\n";
    const char *p = write_file("grid.obj", obj, 0);
    glpgp_mesh *m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    if (m) {
        CHECK(m->nv == 9); /* (7,7) dropped */
        CHECK(m->nt == 8);
        CHECK(fabs(m->area - 1.0) < 1e-14);
        CHECK(m->nloops == 1 && m->loop_start[1] == 8);
        CHECK(m->bbox[2] == 1.0 && m->bbox[3] == 1.0);
        CHECK(m->orientation_fixed == 0);
        check_invariants(m);
        glpgp_mesh_destroy(&m);
    }
    /* Upper-case extension, 2D vertices, clockwise faces (fixed). */
    p = write_file("cw.OBJ", "v 0 0\nv 1 0\nv 1 1\nv 0 1\nf 1 3 2\nf 1 4 3\n", 0);
    m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    if (m) {
        CHECK(m->orientation_fixed == 2 && all_ccw(m));
        glpgp_mesh_destroy(&m);
    }

    /* x, y and z vary: a surface (glpgp/surface.h), not a planar mesh */
    p = write_file("bumpy.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0.001\nv 0 1 0\nf 1 2 3 4\n", 0);
    m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    if (m) {
        CHECK(m->xyz && !m->xy && m->nt == 2 && m->nloops == 1);
        glpgp_mesh_destroy(&m);
    }
    /* A part drawn in a side view (y = 5, or x = -2): solved in (x, z) or
     * (y, z), the same unit square. */
    p = write_file("xz.obj", "v 0 5 0\nv 1 5 0\nv 1 5 1\nv 0 5 1\nf 1 2 3 4\n", 0);
    m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    if (m) {
        CHECK(m->nv == 4 && m->nt == 2 && fabs(m->area - 1.0) < 1e-15 && m->bbox[0] == 0 && m->bbox[3] == 1);
        glpgp_mesh_destroy(&m);
    }
    p = write_file("yz.obj", "v -2 0 0\nv -2 1 0\nv -2 1 1\nv -2 0 1\nf 1 2 3 4\n", 0);
    m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    if (m) {
        CHECK(m->nv == 4 && fabs(m->area - 1.0) < 1e-15);
        glpgp_mesh_destroy(&m);
    }
    /* Tiny z noise (below 1e-9 of the size) is accepted. */
    p = write_file("flatish.obj", "v 0 0 0\nv 1 0 1e-12\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", 0);
    m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    glpgp_mesh_destroy(&m);

    p = write_file("garbage.obj", "v 0 0 0\nv 1 0 0\nhello world\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "garbage.obj:3:", __LINE__);
    p = write_file("badv.obj", "v 0 0 0\nv 1 zero 0\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "badv.obj:2:", __LINE__);
    p = write_file("badf.obj", "v 0 0\nv 1 0\nv 0 1\nf 1 2 x\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "badf.obj:4:", __LINE__);
    p = write_file("zero.obj", "v 0 0\nv 1 0\nv 0 1\nf 0 1 2\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "zero.obj:4:", __LINE__);
    p = write_file("range.obj", "v 0 0\nv 1 0\nv 0 1\nf 1 2 4\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "range.obj:4:", __LINE__);
    p = write_file("neg.obj", "v 0 0\nv 1 0\nf -1 -2 -3\nv 0 1\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "neg.obj:3:", __LINE__);
    p = write_file("two.obj", "v 0 0\nv 1 0\nv 0 1\nf 1 2\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "two.obj:4:", __LINE__);
    p = write_file("binary.obj", "v 0 0\n\0\1\2\3", 10);
    m = read_expect(p, GLPGP_ERR_FORMAT, NULL, __LINE__);
    p = write_file("empty.obj", "v 0 0\nv 1 0\nv 0 1\n", 0);
    m = read_expect(p, GLPGP_ERR_MESH, "no triangles", __LINE__);
    p = write_file("nm.obj", "v 0 0\nv 1 0\nv 0.5 1\nv 0.5 -1\nv 0.5 2\nf 1 2 3\nf 2 1 4\nf 1 2 5\n", 0);
    m = read_expect(p, GLPGP_ERR_MESH, "non-manifold", __LINE__);

    m = read_expect(tmp_path("does_not_exist.obj"), GLPGP_ERR_IO, "No such file", __LINE__);
    m = read_expect(tmp_path("mesh.xyz"), GLPGP_ERR_ARG, ".ply", __LINE__);
    m = read_expect(tmp_path("mesh"), GLPGP_ERR_ARG, ".msh", __LINE__);
    (void)m;
}

static void test_msh(void)
{
    /* MSH 2.2: unit square split in 4 around a center node, tags
     * non-contiguous, a physical-names section, points and lines ignored. */
    const char *m22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                      "$PhysicalNames\n1\n2 1 \"domain $Nodes\"\n$EndPhysicalNames\n"
                      "$Nodes\n6\n10 0 0 0\n20 1 0 0\n30 1 1 0\n40 0 1 0\n55 0.5 0.5 0\n99 5 5 0\n$EndNodes\n"
                      "$Elements\n8\n1 15 2 0 1 10\n2 1 2 0 1 10 20\n3 2 2 1 1 10 20 55\n"
                      "4 2 2 1 1 20 30 55\n5 2 2 1 1 30 40 55\n6 2 0 40 10 55\n7 1 2 0 1 20 30\n"
                      "8 15 2 0 1 99\n$EndElements\n";
    const char *p = write_file("sq22.msh", m22, 0);
    glpgp_mesh *m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    if (m) {
        CHECK(m->nv == 5 && m->nt == 4);
        CHECK(fabs(m->area - 1.0) < 1e-15);
        CHECK(m->nloops == 1 && m->loop_start[1] == 4);
        check_invariants(m);
        glpgp_mesh_destroy(&m);
    }
    /* MSH 4.1: same square, two node blocks, sparse tags (sorted lookup),
     * parametric block, element blocks of several types, $Entities skipped. */
    const char *m41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                      "$Entities\n1 0 1 0\n1 0 0 0 0\n1 0 0 0 1 1 0 0 0\n$EndEntities\n"
                      "$Nodes\n2 5 7 9000000\n"
                      "0 1 0 2\n7\n1000000\n0 0 3\n1 0 3\n"
                      "2 1 1 3\n9000000\n12\n8000\n1 1 3 0.1 0.2\n0 1 3 0.3 0.4\n0.5 0.5 3 0 0\n"
                      "$EndNodes\n"
                      "$Elements\n3 6 1 6\n"
                      "0 1 15 1\n1 7\n"
                      "2 1 2 4\n2 7 1000000 8000\n3 1000000 9000000 8000\n4 9000000 12 8000\n5 12 7 8000\n"
                      "1 1 1 1\n6 7 1000000\n"
                      "$EndElements\n";
    p = write_file("sq41.msh", m41, 0);
    m = read_expect(p, GLPGP_OK, NULL, __LINE__);
    if (m) {
        CHECK(m->nv == 5 && m->nt == 4);
        CHECK(fabs(m->area - 1.0) < 1e-15);
        CHECK(m->nloops == 1);
        check_invariants(m);
        glpgp_mesh_destroy(&m);
    }
    p = write_file("bin.MSH", "$MeshFormat\n4.1 1 8\n\1\0\0\0\n$EndMeshFormat\n", 40);
    m = read_expect(p, GLPGP_ERR_FORMAT, "binary MSH not supported", __LINE__);
    p = write_file("v3.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "not supported", __LINE__);
    p = write_file("garbage.msh", "hello\nworld\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "garbage.msh:1:", __LINE__);
    p = write_file("unknown.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                                  "$Elements\n1\n1 2 0 1 2 4\n$EndElements\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "unknown.msh:12:", __LINE__);
    p = write_file("trunc.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n0 1 0 3\n1\n2\n", 0);
    m = read_expect(p, GLPGP_ERR_FORMAT, "trunc.msh:", __LINE__);
    p = write_file("bumpy.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 1\n$EndNodes\n"
                                "$Elements\n1\n1 2 0 1 2 3\n$EndElements\n", 0);
    m = read_expect(p, GLPGP_OK, NULL, __LINE__); /* a surface of one triangle */
    if (m) {
        CHECK(m->xyz && m->nt == 1 && m->nloops == 1);
        glpgp_mesh_destroy(&m);
    }
    p = write_file("notri.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n"
                                "$Elements\n1\n1 1 0 1 2\n$EndElements\n", 0);
    m = read_expect(p, GLPGP_ERR_MESH, "no triangles", __LINE__);
    m = read_expect(tmp_path("missing.msh"), GLPGP_ERR_IO, NULL, __LINE__);
    (void)m;
}

/* ------------------------------------------------------------------------ */

static void test_data(void)
{
    const char *dir = getenv("GLPGP_DATA");
    if (!dir || !*dir) {
        printf("GLPGP_DATA not set: data/ meshes not tested\n");
        return;
    }
    static const struct {
        const char *name;
        int loops_min, loops_max;
        double area_lo, area_hi;
        int nv_lo, nv_hi;
    } files[] = {
        {"square.obj", 1, 1, 0.999999, 1.000001, 1500, 3000},
        {"annulus.msh", 2, 2, 2.80, 2.86, 4000, 7000},
        {"plate_holes.msh", 3, 10, 1.0, 1e9, 10000, 20000},
        {"lshape.msh", 1, 1, 0.749999, 0.750001, 500, 20000},
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, files[i].name);
        glpgp_mesh *m = read_expect(path, GLPGP_OK, NULL, __LINE__);
        if (!m) continue;
        printf("%-16s nv=%d nt=%d loops=%d area=%.6f mean_edge=%.4g flipped=%d\n", files[i].name, m->nv, m->nt,
               m->nloops, m->area, m->mean_edge, m->orientation_fixed);
        CHECK(m->nloops >= files[i].loops_min && m->nloops <= files[i].loops_max);
        CHECK(m->area >= files[i].area_lo && m->area <= files[i].area_hi);
        CHECK(m->nv >= files[i].nv_lo && m->nv <= files[i].nv_hi);
        check_invariants(m);
        if (!strcmp(files[i].name, "plate_holes.msh")) {
            /* Holes are smaller than the plate and the area is below the bbox. */
            double bb = (m->bbox[2] - m->bbox[0]) * (m->bbox[3] - m->bbox[1]);
            CHECK(m->area < 0.98 * bb && m->area > 0.5 * bb);
        }
        glpgp_mesh_destroy(&m);
    }
}

static int dir_has_tmp_files(void)
{
    DIR *d = opendir(g_tmp);
    if (!d) return 1;
    struct dirent *e;
    int found = 0;
    while ((e = readdir(d)) != NULL)
        if (strstr(e->d_name, ".tmp.")) found = 1;
    closedir(d);
    return found;
}

static void test_roundtrip(void)
{
    glpgp_mesh *m = NULL;
    CHECK(glpgp_mesh_generate("annulus", 600, &m) == GLPGP_OK);
    if (!m) return;
    const char *names[] = {"rt.obj", "rt.msh", "RT2.Msh"};
    for (int k = 0; k < 3; k++) {
        const char *p = tmp_path(names[k]);
        glpgp_error_clear();
        CHECK(glpgp_mesh_write(m, p) == GLPGP_OK);
        /* Writing again replaces the file atomically. */
        CHECK(glpgp_mesh_write(m, p) == GLPGP_OK);
        glpgp_mesh *r = read_expect(p, GLPGP_OK, NULL, __LINE__);
        if (!r) continue;
        CHECK(r->nv == m->nv && r->nt == m->nt && r->nloops == m->nloops);
        if (r->nv == m->nv) CHECK(memcmp(r->xy, m->xy, sizeof(double) * 2 * (size_t)m->nv) == 0);
        if (r->nt == m->nt) CHECK(memcmp(r->tri, m->tri, sizeof(int) * 3 * (size_t)m->nt) == 0);
        CHECK(r->orientation_fixed == 0);
        CHECK(r->area == m->area);
        glpgp_mesh_destroy(&r);
    }
    CHECK(!dir_has_tmp_files());
    glpgp_error_clear();
    CHECK(glpgp_mesh_write(m, tmp_path("no/such/dir/x.obj")) == GLPGP_ERR_IO);
    glpgp_error_clear();
    CHECK(glpgp_mesh_write(m, tmp_path("x.vtk")) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    CHECK(!dir_has_tmp_files());
    glpgp_mesh_destroy(&m);
}

/* A part drawn far from the origin (CAD coordinates): the annulus moved by
 * offsets up to 2e6 is accepted with the same area and loops. The boundary's
 * shoelace sum over absolute coordinates cancelled to errors far above the
 * overlap test's tolerance ("the mesh overlaps itself: its triangles cover
 * 34.9125 but its boundary encloses 34.9125" at (1e5, -5e4)). */
static void test_far_from_origin(void)
{
    glpgp_mesh *m0 = NULL;
    CHECK(glpgp_mesh_generate("annulus", 4000, &m0) == GLPGP_OK);
    if (!m0) return;
    const double off[][2] = {{1e5, -5e4}, {3e5, 7e5}, {-1e6, 2e6}, {12345.678, -98765.4321}};
    double *xy = malloc(2 * (size_t)m0->nv * sizeof *xy);
    CHECK(xy != NULL);
    for (size_t k = 0; xy && k < sizeof off / sizeof off[0]; k++) {
        for (int v = 0; v < m0->nv; v++) {
            xy[2 * v] = m0->xy[2 * v] + off[k][0];
            xy[2 * v + 1] = m0->xy[2 * v + 1] + off[k][1];
        }
        glpgp_mesh *m = NULL;
        glpgp_status st = glpgp_mesh_create(m0->nv, xy, m0->nt, m0->tri, &m);
        if (st != GLPGP_OK) fprintf(stderr, "offset (%g, %g): %s\n", off[k][0], off[k][1], glpgp_error_message());
        CHECK(st == GLPGP_OK && m);
        if (!m) continue;
        CHECK(m->nloops == m0->nloops);
        CHECK(fabs(m->area - m0->area) <= 1e-9 * m0->area);
        check_invariants(m);
        glpgp_mesh_destroy(&m);
    }
    free(xy);
    glpgp_mesh_destroy(&m0);
}

/* The size limit holds every int product of the counts (9 * nt element
 * entries, 12 * nt corners, 6 * nv): a count one over it is refused with
 * GLPGP_ERR_LIMIT before anything is read or allocated (the arrays here are
 * far too short to be read), and the limits keep those products in an int. */
static void test_size_limits(void)
{
    const double xy[6] = {0, 0, 1, 0, 0, 1};
    const int tri[3] = {0, 1, 2};
    glpgp_mesh *m = NULL;
    CHECK((long long)GLPGP_MESH_MAX_TRIANGLES * 12 <= INT_MAX && (long long)GLPGP_MESH_MAX_VERTICES * 6 <= INT_MAX);
    CHECK(glpgp_mesh_create(3, xy, GLPGP_MESH_MAX_TRIANGLES + 1, tri, &m) == GLPGP_ERR_LIMIT && !m);
    CHECK(strstr(glpgp_error_message(), "too many triangles") != NULL);
    glpgp_error_clear();
    CHECK(glpgp_mesh_create(GLPGP_MESH_MAX_VERTICES + 1, xy, 1, tri, &m) == GLPGP_ERR_LIMIT && !m);
    glpgp_error_clear();
    const double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    CHECK(glpgp_mesh_create_surface(3, xyz, GLPGP_MESH_MAX_TRIANGLES + 1, tri, &m) == GLPGP_ERR_LIMIT && !m);
    glpgp_error_clear();
    CHECK(glpgp_mesh_check_size(GLPGP_MESH_MAX_VERTICES, GLPGP_MESH_MAX_TRIANGLES) == GLPGP_OK);
    CHECK(glpgp_mesh_check_size(1LL << 40, 1) == GLPGP_ERR_LIMIT);
    glpgp_error_clear();
}

static void remove_tmp_dir(void)
{
    DIR *d = opendir(g_tmp);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.') continue;
        char p[1024];
        snprintf(p, sizeof p, "%s/%s", g_tmp, e->d_name);
        remove(p);
    }
    closedir(d);
    rmdir(g_tmp);
}

/* glpgp_mesh_vertex_triangles: every vertex lists exactly the triangles
 * that have it as a corner, by increasing index */
static void test_vertex_triangles(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 500, &m));
    if (!m) return;
    int *ptr = NULL, *list = NULL;
    CHECK_OK(glpgp_mesh_vertex_triangles(m, &ptr, &list));
    if (ptr && list) {
        CHECK(ptr[0] == 0 && ptr[m->nv] == 3 * m->nt);
        int bad = 0;
        for (int i = 0; i < m->nv; i++)
            for (int k = ptr[i]; k < ptr[i + 1]; k++) {
                const int *t = m->tri + 3 * list[k];
                bad += !(t[0] == i || t[1] == i || t[2] == i) || (k > ptr[i] && list[k] <= list[k - 1]);
            }
        CHECK(bad == 0);
    }
    free(ptr);
    free(list);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    const char *base = getenv("TMPDIR");
    snprintf(g_tmp, sizeof g_tmp, "%s/glpgp_test_mesh_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(g_tmp)) {
        perror("mkdtemp");
        return 1;
    }
    test_square2();
    test_orientation();
    test_rejects();
    test_obj();
    test_msh();
    test_data();
    test_roundtrip();
    test_far_from_origin();
    test_vertex_triangles();
    remove_tmp_dir();
    test_size_limits();
    TEST_DONE();
}
