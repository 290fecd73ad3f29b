/* solver/refine.c: the refinement of an input mesh for its local size
 * (glpgp_size_refine, glpgp/solve.h): rounds of longest-edge bisection of
 * the triangles whose longest edge is coarser than their local size / R
 * (R = size_resolution), the local size recomputed on each round's mesh;
 * bounded by --max-elements and a round cap. The size field itself:
 * sizefield.c. */
#include "internal.h"

#include "glpgp/util.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- refinement ------------------------------------------------------------- */

typedef struct rmesh {
    int nv, nt;
    double *xy;
    int *tri;
} rmesh;

/* Edge key (i < j) of vertices a, b. */
static uint64_t ekey(int a, int b)
{
    const uint32_t i = (uint32_t)(a < b ? a : b), j = (uint32_t)(a < b ? b : a);
    return ((uint64_t)i << 32) | j;
}

typedef struct ekey_ref {
    uint64_t key;
    int he; /* half-edge t*3 + a */
} ekey_ref;

static int cmp_ekey(const void *p, const void *q)
{
    const ekey_ref *a = p, *b = q;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return (a->he > b->he) - (a->he < b->he);
}

/* Squared length of edge a of triangle t (from corner a to a + 1). */
static double elen2(const rmesh *r, int t, int a)
{
    const int i = r->tri[3 * t + a], j = r->tri[3 * t + (a + 1) % 3];
    const double dx = r->xy[2 * j] - r->xy[2 * i], dy = r->xy[2 * j + 1] - r->xy[2 * i + 1];
    return dx * dx + dy * dy;
}

/* The longest edge of triangle t; ties broken by the edge key, a total order
 * on edges, so that every triangle of a longest-edge chain agrees. */
static int longest(const rmesh *r, int t)
{
    int best = 0;
    double lb = elen2(r, t, 0);
    uint64_t kb = ekey(r->tri[3 * t], r->tri[3 * t + 1]);
    for (int a = 1; a < 3; a++) {
        const double l = elen2(r, t, a);
        const uint64_t k = ekey(r->tri[3 * t + a], r->tri[3 * t + (a + 1) % 3]);
        if (l > lb || (l == lb && k > kb)) {
            best = a;
            lb = l;
            kb = k;
        }
    }
    return best;
}

/* One refinement round: split the triangles flagged in need[] (and the
 * closure), out-of-place into *out. Returns the number of split edges. */
static glpgp_status refine_round(const rmesh *r, const unsigned char *need, rmesh *out, long *nsplit)
{
    glpgp_status st = GLPGP_OK;
    const int nt = r->nt;
    ekey_ref *ref = NULL;
    int *edge = NULL, *mid = NULL, *etri = NULL, *work = NULL;
    unsigned char *mark = NULL;
    int ne = 0;
    out->xy = NULL;
    out->tri = NULL;
    /* edges: sort the 3 nt half-edges by key; edge[he] = edge index */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof *ref, &ref), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof(int), &edge), done);
    for (int t = 0; t < nt; t++)
        for (int a = 0; a < 3; a++) {
            ref[3 * t + a].key = ekey(r->tri[3 * t + a], r->tri[3 * t + (a + 1) % 3]);
            ref[3 * t + a].he = 3 * t + a;
        }
    qsort(ref, (size_t)3 * nt, sizeof *ref, cmp_ekey);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)6 * nt + 2, sizeof(int), &etri), done);
    for (int k = 0; k < 3 * nt; k++) {
        if (k == 0 || ref[k].key != ref[k - 1].key) {
            etri[2 * ne] = ref[k].he / 3;
            etri[2 * ne + 1] = -1;
            ne++;
        } else {
            etri[2 * (ne - 1) + 1] = ref[k].he / 3;
        }
        edge[ref[k].he] = ne - 1;
    }
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)ne + 1, 1, &mark), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt + 2 * (size_t)ne + 1, sizeof(int), &work), done);
    /* mark the longest edge of every triangle that needs it, then close: a
     * triangle with a marked edge gets its longest edge marked (worklist) */
    size_t nw = 0;
    for (int t = 0; t < nt; t++)
        if (need[t]) work[nw++] = t;
    while (nw > 0) {
        const int t = work[--nw];
        const int e = edge[3 * t + longest(r, t)];
        if (mark[e]) continue;
        mark[e] = 1;
        for (int s = 0; s < 2; s++) {
            const int u = etri[2 * e + s];
            if (u >= 0 && u != t) work[nw++] = u;
        }
    }
    /* new vertices: one midpoint per marked edge */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)ne + 1, sizeof(int), &mid), done);
    int nv2 = r->nv;
    for (int e = 0; e < ne; e++) mid[e] = mark[e] ? nv2++ : -1;
    long ntri2 = 0;
    for (int t = 0; t < nt; t++) {
        int c = 0;
        for (int a = 0; a < 3; a++) c += mark[edge[3 * t + a]];
        ntri2 += 1 + c;
    }
    if (ntri2 > GLPGP_MESH_MAX_TRIANGLES) {
        st = GLPGP_FAIL(GLPGP_ERR_LIMIT, "refinement: %ld triangles is too many", ntri2);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv2, sizeof(double), &out->xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * ntri2, sizeof(int), &out->tri), done);
    memcpy(out->xy, r->xy, (size_t)2 * r->nv * sizeof(double));
    for (int t = 0; t < nt; t++)
        for (int a = 0; a < 3; a++) {
            const int e = edge[3 * t + a];
            if (mid[e] < 0) continue;
            const int i = r->tri[3 * t + a], j = r->tri[3 * t + (a + 1) % 3];
            out->xy[2 * mid[e]] = 0.5 * (r->xy[2 * i] + r->xy[2 * j]);
            out->xy[2 * mid[e] + 1] = 0.5 * (r->xy[2 * i + 1] + r->xy[2 * j + 1]);
        }
    int k = 0;
#define EMIT(p, q, s)                                                                                        \
    do {                                                                                                     \
        out->tri[3 * k] = (p);                                                                               \
        out->tri[3 * k + 1] = (q);                                                                           \
        out->tri[3 * k + 2] = (s);                                                                           \
        k++;                                                                                                 \
    } while (0)
    for (int t = 0; t < nt; t++) {
        const int L = longest(r, t);
        const int a = r->tri[3 * t + L], b = r->tri[3 * t + (L + 1) % 3], c = r->tri[3 * t + (L + 2) % 3];
        const int mab = mid[edge[3 * t + L]];
        if (mab < 0) { /* the closure marks the longest edge first: no marked edge at all */
            EMIT(a, b, c);
            continue;
        }
        /* (a, b, c) -> (a, mab, c) + (mab, b, c); then the halves at their other marked edge:
         * (p0, p1, p2) split at the midpoint q of (p2, p0) -> (p0, p1, q), (p1, p2, q) */
        const int mca = mid[edge[3 * t + (L + 2) % 3]], mbc = mid[edge[3 * t + (L + 1) % 3]];
        if (mca >= 0) {
            EMIT(a, mab, mca);
            EMIT(mab, c, mca);
        } else {
            EMIT(a, mab, c);
        }
        if (mbc >= 0) { /* (mab, b, c) at the midpoint of (b, c) */
            EMIT(mab, b, mbc);
            EMIT(mab, mbc, c);
        } else {
            EMIT(mab, b, c);
        }
    }
#undef EMIT
    out->nv = nv2;
    out->nt = k;
    *nsplit = nv2 - r->nv;
done:
    if (st != GLPGP_OK) {
        glpgp_free(&out->xy);
        glpgp_free(&out->tri);
    }
    free(ref);
    free(edge);
    free(mid);
    free(etri);
    free(work);
    free(mark);
    return st;
}

glpgp_status glpgp_size_refine(const glpgp_mesh *m, const glpgp_options *o, double h, glpgp_mesh **out,
                               glpgp_refine_info *info)
{
    glpgp_status st = GLPGP_OK;
    glpgp_options oi = *o;
    glpgp_mesh *cur = NULL;
    if (m->xyz) { /* a surface: not refined (yet): solved as it is */
        *out = NULL;
        if (info) memset(info, 0, sizeof *info);
        return GLPGP_OK;
    }
    double *size = NULL;
    unsigned char *need = NULL;
    *out = NULL;
    if (info) {
        memset(info, 0, sizeof *info);
        info->nv0 = m->nv;
        info->nt0 = m->nt;
        info->nv = m->nv;
        info->nt = m->nt;
    }
    /* none: the input as it is (today's pipeline); a file's values belong to
     * the input's vertices: no refinement */
    if (o->size_field == GLPGP_SIZE_FILE || o->size_field == GLPGP_SIZE_NONE) return GLPGP_OK;
    if (oi.size_field == GLPGP_SIZE_AUTO) oi.size_field = GLPGP_SIZE_ISO;
    const glpgp_mesh *mm = m;
    glpgp_progress pr;
    glpgp_progress_start(&pr, "refinement for the local size");
    for (int round = 0;; round++) {
        glpgp_size_res res;
        glpgp_progress_tick(&pr, "round %d: %d vertices, %d triangles", round + 1, mm->nv, mm->nt);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * mm->nv, sizeof(double), &size), done);
        GLPGP_CHECK_GOTO(st, glpgp_size_compute_field(mm, &oi, h, NULL, size, NULL, 0, NULL), done);
        GLPGP_CHECK_GOTO(st, glpgp_size_resolution(mm, size, o->size_resolution, &res), done);
        if (res.coarse == 0) break;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)mm->nt + 1, 1, &need), done);
        for (int t = 0; t < mm->nt; t++) need[t] = glpgp_size_tri_resolution(mm, size, t, NULL) < o->size_resolution;
        rmesh r = {mm->nv, mm->nt, mm->xy, mm->tri}, r2 = {0, 0, NULL, NULL};
        long nsplit = 0;
        if (round < GLPGP_REFINE_MAX_ROUNDS) GLPGP_CHECK_GOTO(st, refine_round(&r, need, &r2, &nsplit), done);
        if (round >= GLPGP_REFINE_MAX_ROUNDS || r2.nv > GLPGP_REFINE_MAX_VERTICES) {
            free(r2.xy);
            free(r2.tri);
            st = GLPGP_FAIL(GLPGP_ERR_LIMIT,
                            "refinement stopped after %d rounds at %d vertices (limits: %d rounds, %d vertices): "
                            "%d triangles are still coarser than h / %g, worst near (%.6g, %.6g) (edge %.3g for "
                            "h = %.3g)",
                            round, mm->nv, GLPGP_REFINE_MAX_ROUNDS, GLPGP_REFINE_MAX_VERTICES, res.coarse,
                            o->size_resolution, res.x, res.y, res.lmax, res.h);
            goto done;
        }
        glpgp_mesh *next = NULL;
        st = glpgp_mesh_create(r2.nv, r2.xy, r2.nt, r2.tri, &next);
        free(r2.xy);
        free(r2.tri);
        GLPGP_CHECK_GOTO(st, st, done);
        glpgp_mesh_destroy(&cur);
        cur = next;
        mm = cur;
        glpgp_free(&size);
        glpgp_free(&need);
        if (info) {
            info->rounds = round + 1;
            info->split_edges += nsplit;
            info->nv = mm->nv;
            info->nt = mm->nt;
        }
    }
done:
    glpgp_progress_done(&pr, "%d -> %d vertices", m->nv, mm->nv);
    free(size);
    free(need);
    if (st != GLPGP_OK) {
        glpgp_mesh_destroy(&cur);
        return st;
    }
    *out = cur;
    return GLPGP_OK;
}
