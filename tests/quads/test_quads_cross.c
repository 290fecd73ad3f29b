/* test_quads_cross.c: the quality report's count of irregular interior
 * vertices near cross-field singularities (glpgp_quads_quality_cross) on a
 * hand-made mesh whose irregular vertices are known:
 *  - a 6 x 6 grid of unit cells on [0,6]^2 in which the cells with lower-left
 *    corners (1,1) and (4,3) are cut into two triangles along their diagonal,
 *    refined into quads by glpgp_quadmesh_subdivide: the irregular interior
 *    vertices are exactly the diagonals' ends (valence 5) and the triangles'
 *    centroids (valence 3), 8 in all;
 *  - singularities at (1.5,1.5), (5,4) and (0.2,5.5) give the near / far
 *    counts and matched singularities computed by hand for two radii;
 *  - near + far = irregular_interior; no singularity: all far; without a
 *    call the fields are -1 (absent); bad arguments are refused. */
#include "testutil.h"

#include <string.h>

/* 6 x 6 unit grid, cells (1,1) and (4,3) split along their diagonal. */
static glpgp_quadmesh *coarse(void)
{
    const int n = 6, nv = (n + 1) * (n + 1);
    glpgp_quadmesh *q = calloc(1, sizeof *q);
    q->nv = nv;
    q->xy = malloc(sizeof(double) * 2 * (size_t)nv);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            q->xy[2 * (j * (n + 1) + i)] = i;
            q->xy[2 * (j * (n + 1) + i) + 1] = j;
        }
    q->face_start = malloc(sizeof(int) * (n * n + 3));
    q->face_vert = malloc(sizeof(int) * 4 * (n * n + 2));
    int nf = 0, k = 0;
    q->face_start[0] = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            if ((i == 1 && j == 1) || (i == 4 && j == 3)) { /* two triangles a b c, a c d (CCW) */
                int t[6] = {a, b, c, a, c, d};
                for (int s = 0; s < 2; s++) {
                    memcpy(q->face_vert + k, t + 3 * s, 3 * sizeof(int));
                    k += 3;
                    q->face_start[++nf] = k;
                }
            } else {
                int f[4] = {a, b, c, d};
                memcpy(q->face_vert + k, f, 4 * sizeof(int));
                k += 4;
                q->face_start[++nf] = k;
            }
        }
    q->nf = nf;
    return q;
}

static glpgp_cross_sing sing_at(double x, double y, int index4)
{
    glpgp_cross_sing s;
    memset(&s, 0, sizeof s);
    s.x = x;
    s.y = y;
    s.index4 = index4;
    s.ntri = 1;
    return s;
}

int main(void)
{
    glpgp_quadmesh *c = coarse(), *q = NULL;
    CHECK_OK(glpgp_quadmesh_subdivide(c, &q));
    CHECK(q != NULL);
    if (!q) TEST_DONE();
    glpgp_quads_report qq;
    CHECK_OK(glpgp_quads_quality(q, NULL, 0.5, &qq));
    CHECK(qq.quads == q->nf && qq.others == 0);
    CHECK(qq.irregular_interior == 8);
    CHECK(qq.valence_interior[3] == 4 && qq.valence_interior[5] == 4);
    /* without a cross field: absent */
    CHECK(qq.cross_singularities == -1 && qq.irregular_near_cross == -1 && qq.irregular_far_cross == -1 &&
          qq.cross_matched == -1);

    glpgp_cross_sing s[3] = {sing_at(1.5, 1.5, 1), sing_at(5.0, 4.0, -1), sing_at(0.2, 5.5, 1)};
    /* radius 0.3: (1.5,1.5) has the two centroids (4/3,5/3), (5/3,4/3) at
     * 0.236 (the diagonal's ends at 0.707); (5,4) has the diagonal end (5,4)
     * at 0 (the centroids at 0.745); (0.2,5.5) none */
    CHECK_OK(glpgp_quads_quality_cross(q, s, 3, 0.3, &qq));
    CHECK(qq.cross_singularities == 3);
    CHECK(qq.cross_radius == 0.3);
    CHECK(qq.irregular_near_cross == 3);
    CHECK(qq.irregular_far_cross == 5);
    CHECK(qq.cross_matched == 2);
    CHECK(qq.irregular_near_cross + qq.irregular_far_cross == qq.irregular_interior);
    /* radius 0.8: the first cell's four, and (5,4) and both centroids of the second (0.745); (4,3) at 1.41 */
    CHECK_OK(glpgp_quads_quality_cross(q, s, 3, 0.8, &qq));
    CHECK(qq.irregular_near_cross == 7);
    CHECK(qq.irregular_far_cross == 1);
    CHECK(qq.cross_matched == 2);
    /* a vertex within reach of two singularities counts once */
    glpgp_cross_sing two[2] = {sing_at(1.4, 1.6, 1), sing_at(1.3, 1.7, 1)};
    CHECK_OK(glpgp_quads_quality_cross(q, two, 2, 0.1, &qq));
    CHECK(qq.irregular_near_cross == 1 && qq.irregular_far_cross == 7 && qq.cross_matched == 2);
    /* boundary vertices never count: a singularity at a boundary corner */
    glpgp_cross_sing corner = sing_at(0.0, 0.0, 1);
    CHECK_OK(glpgp_quads_quality_cross(q, &corner, 1, 0.9, &qq));
    CHECK(qq.irregular_near_cross == 0 && qq.irregular_far_cross == 8 && qq.cross_matched == 0);
    /* a cross field without singularities: every irregular vertex is far */
    CHECK_OK(glpgp_quads_quality_cross(q, NULL, 0, 0.5, &qq));
    CHECK(qq.cross_singularities == 0 && qq.irregular_near_cross == 0 && qq.irregular_far_cross == 8 &&
          qq.cross_matched == 0);
    /* bad arguments */
    CHECK(glpgp_quads_quality_cross(q, s, 3, 0.0, &qq) == GLPGP_ERR_ARG);
    CHECK(glpgp_quads_quality_cross(q, s, 3, NAN, &qq) == GLPGP_ERR_ARG);
    CHECK(glpgp_quads_quality_cross(q, NULL, 2, 0.5, &qq) == GLPGP_ERR_ARG);
    CHECK(glpgp_quads_quality_cross(q, s, -1, 0.5, &qq) == GLPGP_ERR_ARG);
    glpgp_error_clear();

    glpgp_quadmesh_destroy(&q);
    glpgp_quadmesh_destroy(&c);
    TEST_DONE();
}
