/* test_partition.c: glpgp_mesh_partition (recursive coordinate bisection into
 * parts of prescribed sizes) and glpgp_mesh_renumber: exact part sizes, the
 * same parts on a second call, compact parts (few cut edges against a
 * partition by vertex index on a mesh numbered in random order), and a
 * renumbered mesh that is the same mesh (area, boundary loops, the
 * coordinates of every triangle's corners). */
#include "testutil.h"

#include "glpgp/mesh.h"
#include "glpgp/shapes.h"

#include <stdlib.h>
#include <string.h>

/* edges (a, b) of the triangles with part[a] != part[b] (each edge counted per triangle side) */
static long cut_edges(const glpgp_mesh *m, const int *part)
{
    long cut = 0;
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) cut += part[m->tri[3 * t + a]] != part[m->tri[3 * t + (a + 1) % 3]];
    return cut;
}

int main(void)
{
    glpgp_mesh *m = NULL, *shuf = NULL, *back = NULL;
    CHECK_OK(glpgp_mesh_generate("annulus", 4000, &m));
    if (!m) TEST_DONE();
    const int nv = m->nv, P = 3;
    int size[3] = {nv / 3, nv / 3, nv - 2 * (nv / 3)};
    int *part = malloc(sizeof(int) * nv), *part2 = malloc(sizeof(int) * nv), *perm = malloc(sizeof(int) * nv);
    int *inv = malloc(sizeof(int) * nv);

    /* a random numbering: a partition by index range is then a scatter */
    for (int i = 0; i < nv; i++) perm[i] = i;
    for (int i = nv - 1; i > 0; i--) {
        int j = (int)(tu_rand() * (i + 1)), t = perm[i];
        perm[i] = perm[j];
        perm[j] = t;
    }
    CHECK_OK(glpgp_mesh_renumber(m, perm, &shuf));
    if (!shuf) TEST_DONE();
    CHECK_CLOSE(shuf->area, m->area, 0.0, 1e-12);
    CHECK(shuf->nloops == m->nloops);
    CHECK(shuf->orientation_fixed == 0);
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) {
            const int i = m->tri[3 * t + a], j = shuf->tri[3 * t + a];
            CHECK(j == perm[i] && shuf->xy[2 * j] == m->xy[2 * i] && shuf->xy[2 * j + 1] == m->xy[2 * i + 1]);
        }

    CHECK_OK(glpgp_mesh_partition(shuf, P, size, part));
    CHECK_OK(glpgp_mesh_partition(shuf, P, size, part2));
    CHECK(!memcmp(part, part2, sizeof(int) * nv)); /* deterministic */
    int count[3] = {0, 0, 0};
    for (int i = 0; i < nv; i++) {
        CHECK(part[i] >= 0 && part[i] < P);
        if (part[i] >= 0 && part[i] < P) count[part[i]]++;
    }
    for (int p = 0; p < P; p++) CHECK(count[p] == size[p]);
    /* compact: far fewer cut edges than index ranges of the random numbering */
    for (int i = 0; i < nv; i++) part2[i] = i < size[0] ? 0 : i < size[0] + size[1] ? 1 : 2;
    const long cut = cut_edges(shuf, part), cut_index = cut_edges(shuf, part2);
    printf("cut edges: bisection %ld, index ranges of a random numbering %ld\n", cut, cut_index);
    CHECK(cut * 10 < cut_index);

    /* renumbering back restores the mesh */
    for (int i = 0; i < nv; i++) inv[perm[i]] = i;
    CHECK_OK(glpgp_mesh_renumber(shuf, inv, &back));
    if (back) {
        CHECK(!memcmp(back->xy, m->xy, sizeof(double) * 2 * nv));
        CHECK(!memcmp(back->tri, m->tri, sizeof(int) * 3 * m->nt));
    }

    /* bad sizes: an error, not a crash */
    int bad[3] = {1, 1, 1};
    CHECK(glpgp_mesh_partition(m, P, bad, part) == GLPGP_ERR_ARG);
    glpgp_error_clear();

    free(part);
    free(part2);
    free(perm);
    free(inv);
    glpgp_mesh_destroy(&m);
    glpgp_mesh_destroy(&shuf);
    glpgp_mesh_destroy(&back);
    TEST_DONE();
}
