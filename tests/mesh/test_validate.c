/* test_validate.c: geometric validation of glpgp_mesh_create beyond the
 * combinatorial checks: a mesh folded over one of its edges (two triangles on
 * the same side of the shared edge) is rejected with a message that says so,
 * whatever the input winding; the same triangles unfolded are accepted, and
 * input triangles given clockwise are re-oriented (counted) and accepted. */
#include "testutil.h"

#include <string.h>

static glpgp_status make(const double *xy, int nv, const int *tri, int nt, glpgp_mesh **m)
{
    glpgp_error_clear();
    return glpgp_mesh_create(nv, xy, nt, tri, m);
}

int main(void)
{
    glpgp_mesh *m = NULL;
    /* unit square as two triangles: fine, also when one is given clockwise */
    const double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const int good[6] = {0, 1, 2, 0, 2, 3}, mixed[6] = {0, 1, 2, 0, 3, 2};
    CHECK(make(sq, 4, good, 2, &m) == GLPGP_OK && m && m->orientation_fixed == 0);
    glpgp_mesh_destroy(&m);
    CHECK(make(sq, 4, mixed, 2, &m) == GLPGP_OK && m && m->orientation_fixed == 1);
    CHECK(m && fabs(m->area - 1.0) < 1e-15);
    glpgp_mesh_destroy(&m);

    /* folded: the second triangle shares edge 1-2 and lies on the first one's side */
    const double fold[8] = {0, 0, 1, 0, 0, 1, 0.3, 0.3};
    const int ft[6] = {0, 1, 2, 1, 3, 2}, ft_rev[6] = {0, 2, 1, 1, 2, 3};
    glpgp_status st = make(fold, 4, ft, 2, &m);
    CHECK(st == GLPGP_ERR_MESH && m == NULL);
    CHECK(strstr(glpgp_error_message(), "folds") != NULL);
    st = make(fold, 4, ft_rev, 2, &m);
    CHECK(st == GLPGP_ERR_MESH && m == NULL);
    CHECK(strstr(glpgp_error_message(), "folds") != NULL);

    /* the same connectivity with the fourth vertex on the other side: valid */
    const double unfold[8] = {0, 0, 1, 0, 0, 1, 0.8, 0.8};
    CHECK(make(unfold, 4, ft, 2, &m) == GLPGP_OK && m != NULL);
    glpgp_mesh_destroy(&m);

    /* a fold inside a larger mesh (a vertex of a fan pushed over its neighbour) */
    glpgp_mesh *disk = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 200, &disk));
    if (disk) {
        double *xy = malloc(sizeof(double) * 2 * disk->nv);
        memcpy(xy, disk->xy, sizeof(double) * 2 * disk->nv);
        /* move an interior vertex far across the domain: its fan flips */
        int v = -1;
        for (int i = 0; i < disk->nv && v < 0; i++)
            if (!disk->on_boundary[i] && hypot(xy[2 * i], xy[2 * i + 1]) < 0.5) v = i;
        CHECK(v >= 0);
        if (v >= 0) {
            xy[2 * v] = 0.95 * (xy[2 * v] >= 0 ? -1 : 1);
            xy[2 * v + 1] = 0.0;
            st = make(xy, disk->nv, disk->tri, disk->nt, &m);
            CHECK(st == GLPGP_ERR_MESH && m == NULL);
            CHECK(strstr(glpgp_error_message(), "folds") || strstr(glpgp_error_message(), "overlap") ||
                  strstr(glpgp_error_message(), "degenerate"));
        }
        free(xy);
    }
    glpgp_mesh_destroy(&disk);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
