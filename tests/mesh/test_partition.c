/* test_partition.c: glpgp_mesh_partition (recursive coordinate bisection into
 * parts of prescribed sizes) and glpgp_mesh_renumber: exact part sizes, the
 * same parts on a second call, compact parts (few cut edges against a
 * partition by vertex index on a mesh numbered in random order), and a
 * renumbered mesh that is the same mesh (area, boundary loops, the
 * coordinates of every triangle's corners); glpgp_mesh_rcm_order: a
 * deterministic permutation with small index gaps along the edges; the parts of a distributed solve
 * (glpgp_mesh_extract_part): owned vertices first with consecutive global
 * ids, increasing ghosts outside the owned range, every triangle touching
 * an owned vertex and no other, each triangle counted by exactly one part,
 * the whole mesh's coordinates, boundary data, sizes and scalars. */
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

    /* reverse Cuthill-McKee order of the random numbering: a permutation,
     * deterministic, and the edges' index gaps far smaller (median over the
     * triangle sides, against the random numbering's) */
    {
        int *rcm = malloc(sizeof(int) * nv), *rcm2 = malloc(sizeof(int) * nv), *seen = calloc((size_t)nv, sizeof(int));
        CHECK_OK(glpgp_mesh_rcm_order(shuf, rcm));
        CHECK_OK(glpgp_mesh_rcm_order(shuf, rcm2));
        CHECK(!memcmp(rcm, rcm2, sizeof(int) * nv));
        int okperm = 1;
        for (int i = 0; i < nv; i++) {
            if (rcm[i] < 0 || rcm[i] >= nv || seen[rcm[i]]) okperm = 0;
            else seen[rcm[i]] = 1;
        }
        CHECK(okperm);
        long far_rcm = 0, far_rand = 0; /* sides with |i - j| > nv / 20 */
        for (int t = 0; t < shuf->nt && okperm; t++)
            for (int a = 0; a < 3; a++) {
                const int i = shuf->tri[3 * t + a], j = shuf->tri[3 * t + (a + 1) % 3];
                far_rand += abs(i - j) > nv / 20;
                far_rcm += abs(rcm[i] - rcm[j]) > nv / 20;
            }
        printf("triangle sides with |i - j| > nv/20: random numbering %ld, reverse Cuthill-McKee %ld\n", far_rand,
               far_rcm);
        CHECK(far_rcm * 100 < far_rand);
        free(rcm);
        free(rcm2);
        free(seen);
    }

    /* the parts of 3 ranks of the renumbered mesh shuf */
    double *sz = malloc(sizeof(double) * 2 * nv);
    for (int i = 0; i < 2 * nv; i++) sz[i] = 1.0 + i;
    const double cen[2] = {0.25, -0.5};
    long counted = 0;
    int *touch = calloc((size_t)m->nt, sizeof(int));
    for (int q = 0; q < P; q++) {
        glpgp_mesh *pq = NULL;
        CHECK_OK(glpgp_mesh_extract_part(shuf, P, q, sz, cen, 0.5, &pq));
        if (!pq) continue;
        const glpgp_mesh_part *pt = pq->part;
        const int lo = (int)((long long)nv * q / P), hi = (int)((long long)nv * (q + 1) / P);
        CHECK(pt->nv_owned == hi - lo && pt->first == lo && pt->nv_global == nv && pt->nt_global == m->nt);
        CHECK(pt->center[0] == 0.25 && pt->center[1] == -0.5 && pt->size_opt == 0.5);
        CHECK(pq->area == shuf->area && pq->mean_edge == shuf->mean_edge && pq->nloops == 0);
        for (int i = 0; i < pq->nv; i++) {
            const int g = pt->gid[i];
            if (i < pt->nv_owned) CHECK(g == lo + i);
            else CHECK((g < lo || g >= hi) && (i == pt->nv_owned || g > pt->gid[i - 1]));
            CHECK(pq->xy[2 * i] == shuf->xy[2 * g] && pq->xy[2 * i + 1] == shuf->xy[2 * g + 1]);
            CHECK(pq->on_boundary[i] == shuf->on_boundary[g] && pq->normal_next[2 * i] == shuf->normal_next[2 * g]);
            CHECK(pt->size[i] == sz[g] && pt->size[pq->nv + i] == sz[nv + g]);
        }
        /* the triangles touching [lo, hi), in the whole mesh's order */
        int k = 0;
        for (int t = 0; t < shuf->nt; t++) {
            const int *v = shuf->tri + 3 * t;
            int own = 0;
            for (int a = 0; a < 3; a++) own |= v[a] >= lo && v[a] < hi;
            if (!own) continue;
            touch[t]++;
            CHECK(k < pq->nt);
            if (k >= pq->nt) break;
            for (int a = 0; a < 3; a++) CHECK(pt->gid[pq->tri[3 * k + a]] == v[a]);
            counted += glpgp_part_counts_tri(pt, pq->tri, k);
            k++;
        }
        CHECK(k == pq->nt);
        printf("part %d: %d owned + %d ghosts, %d triangles\n", q, pt->nv_owned, pq->nv - pt->nv_owned, pq->nt);
        glpgp_mesh_destroy(&pq);
    }
    CHECK(counted == shuf->nt);
    for (int t = 0; t < m->nt; t++) CHECK(touch[t] >= 1);
    free(touch);
    free(sz);
    glpgp_mesh *bad_part = NULL;
    CHECK(glpgp_mesh_extract_part(shuf, P, P, NULL, NULL, 0.0, &bad_part) == GLPGP_ERR_ARG && !bad_part);
    glpgp_error_clear();

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
