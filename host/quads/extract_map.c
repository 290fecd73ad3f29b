/* quads/extract_map.c: the planar map of the extraction's graph
 * (extract.h): node merging, pruning of dangling ends, the rotation system
 * and its faces, corners, and the clean-up rounds described at the top of
 * extract.c. */
#include "extract.h"
#include "glpgp/kinds.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_ GLPGP_PI

/* ---- graph simplification ---------------------------------------------- */

/* Node priority when merging: fixed corner > boundary > other. */
static int node_rank(const qnode *n) { return 2 * n->fixed + n->bnd; }

/* Merge node sets given by the union-find parent array: every edge is
 * re-pointed to representatives, self-loops are removed, duplicates merged
 * (flags OR-ed; a boundary direction is kept from the first boundary copy).
 * The representative takes the position of its best-ranked member. */
static int cmp_edge(const void *pa, const void *pb)
{
    const qedge *a = pa, *b = pb;
    int a0 = a->a < a->b ? a->a : a->b, a1 = a->a < a->b ? a->b : a->a;
    int b0 = b->a < b->b ? b->a : b->b, b1 = b->a < b->b ? b->b : b->a;
    if (a0 != b0) return a0 < b0 ? -1 : 1;
    if (a1 != b1) return a1 < b1 ? -1 : 1;
    /* boundary copies first */
    return (int)(b->flags & QE_BND) - (int)(a->flags & QE_BND);
}

glpgp_status glpgp_xm_merge_nodes(graph *g, int *parent)
{
    /* representative position */
    int *best = NULL;
    int *cnt = NULL;
    double *sx = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn, sizeof(int), &best), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)g->nn, sizeof(int), &cnt), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * g->nn, sizeof(double), &sx), done);
    for (int i = 0; i < g->nn; i++) best[i] = -1;
    for (int i = 0; i < g->nn; i++) {
        int rp = glpgp_uf_find(parent, i);
        int rk = node_rank(&g->node[i]);
        if (best[rp] < 0 || rk > node_rank(&g->node[best[rp]])) {
            best[rp] = i;
            cnt[rp] = 0;
            sx[2 * rp] = sx[2 * rp + 1] = 0.0;
        }
        if (rk == node_rank(&g->node[best[rp]])) {
            cnt[rp]++;
            sx[2 * rp] += g->node[i].x;
            sx[2 * rp + 1] += g->node[i].y;
        }
    }
    for (int i = 0; i < g->nn; i++) {
        if (parent[i] != i || glpgp_uf_find(parent, i) != i) continue;
        qnode nb = g->node[best[i]];
        nb.x = sx[2 * i] / cnt[i];
        nb.y = sx[2 * i + 1] / cnt[i];
        /* a mesh vertex keeps its exact position */
        if (nb.vert >= 0 || nb.fixed) {
            nb.x = g->node[best[i]].x;
            nb.y = g->node[best[i]].y;
        }
        g->node[i] = nb;
    }
    int w = 0;
    for (int e = 0; e < g->ne; e++) {
        qedge E = g->edge[e];
        if (E.flags & QE_DEL) continue;
        E.a = glpgp_uf_find(parent, E.a);
        E.b = glpgp_uf_find(parent, E.b);
        if (E.a == E.b) continue;
        g->edge[w++] = E;
    }
    g->ne = w;
    qsort(g->edge, (size_t)g->ne, sizeof *g->edge, cmp_edge);
    w = 0;
    for (int e = 0; e < g->ne; e++) {
        if (w > 0) {
            qedge *P = &g->edge[w - 1];
            int p0 = P->a < P->b ? P->a : P->b, p1 = P->a < P->b ? P->b : P->a;
            int q0 = g->edge[e].a < g->edge[e].b ? g->edge[e].a : g->edge[e].b;
            int q1 = g->edge[e].a < g->edge[e].b ? g->edge[e].b : g->edge[e].a;
            if (p0 == q0 && p1 == q1) {
                P->flags |= (unsigned char)(g->edge[e].flags & (QE_U | QE_V));
                continue;
            }
        }
        g->edge[w++] = g->edge[e];
    }
    g->ne = w;
done:
    free(best);
    free(cnt);
    free(sx);
    return st;
}

/* Remove dangling edges: repeatedly delete the edges of degree-1 nodes. */
glpgp_status glpgp_xm_prune(graph *g)
{
    int *deg = NULL, *adj_start = NULL, *adj = NULL, *stack = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)g->nn + 1, sizeof(int), &deg), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)g->nn + 1, sizeof(int), &adj_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * g->ne + 1, sizeof(int), &adj), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn + 1, sizeof(int), &stack), done);
    for (int e = 0; e < g->ne; e++) {
        if (g->edge[e].flags & QE_DEL) continue;
        deg[g->edge[e].a]++;
        deg[g->edge[e].b]++;
    }
    for (int i = 0; i < g->nn; i++) adj_start[i + 1] = adj_start[i] + deg[i];
    {
        int *fill = stack; /* reuse as cursor */
        for (int i = 0; i < g->nn; i++) fill[i] = adj_start[i];
        for (int e = 0; e < g->ne; e++) {
            if (g->edge[e].flags & QE_DEL) continue;
            adj[fill[g->edge[e].a]++] = e;
            adj[fill[g->edge[e].b]++] = e;
        }
    }
    int sp = 0;
    for (int i = 0; i < g->nn; i++)
        if (deg[i] == 1) stack[sp++] = i;
    while (sp > 0) {
        int v = stack[--sp];
        if (deg[v] != 1) continue;
        for (int q = adj_start[v]; q < adj_start[v + 1]; q++) {
            qedge *E = &g->edge[adj[q]];
            if (E->flags & QE_DEL) continue;
            E->flags |= QE_DEL;
            int o = E->a == v ? E->b : E->a;
            deg[v]--;
            deg[o]--;
            if (deg[o] == 1) stack[sp++] = o;
            break;
        }
    }
    int w = 0;
    for (int e = 0; e < g->ne; e++)
        if (!(g->edge[e].flags & QE_DEL)) g->edge[w++] = g->edge[e];
    g->ne = w;
done:
    free(deg);
    free(adj_start);
    free(adj);
    free(stack);
    return st;
}

/* ---- planar map and faces ---------------------------------------------- */



void glpgp_xm_pmap_free(pmap *p)
{
    free(p->rot_start);
    free(p->rot);
    free(p->rot_pos);
    free(p->face);
    free(p->face_he);
    free(p->outer);
    free(p->deg);
    memset(p, 0, sizeof *p);
}

/* A half-edge with its angle at its origin: the rotation system is sorted as
 * such records (no qsort context in a static: two extractions may run in
 * parallel threads). Ties (coincident directions) keep the half-edge order. */
typedef struct he_ang {
    double ang;
    int h;
} he_ang;
static int cmp_he_angle(const void *pa, const void *pb)
{
    const he_ang *a = pa, *b = pb;
    if (a->ang != b->ang) return (a->ang > b->ang) - (a->ang < b->ang);
    return (a->h > b->h) - (a->h < b->h);
}


/* glpgp_xm_face_next(h) = the half-edge before twin(h) in counter-clockwise order
 * around the origin of twin(h) (= destination of h). */
int glpgp_xm_face_next(const graph *g, const pmap *p, int h)
{
    int t = h ^ 1;
    int v = he_orig(g, t);
    int i = p->rot_pos[t];
    int s = p->rot_start[v], n = p->rot_start[v + 1] - s;
    return p->rot[s + (i - s + n - 1) % n];
}

glpgp_status glpgp_xm_pmap_build(const graph *g, pmap *p)
{
    memset(p, 0, sizeof *p);
    glpgp_status st = GLPGP_OK;
    double *ang = NULL;
    int *fill = NULL;
    he_ang *rec = NULL;
    int nh = 2 * g->ne;
    p->nh = nh;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)g->nn + 1, sizeof(int), &p->rot_start), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)g->nn + 1, sizeof(int), &p->deg), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof(int), &p->rot), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof(int), &p->rot_pos), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof(int), &p->face), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof(double), &ang), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn + 1, sizeof(int), &fill), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof *rec, &rec), fail);
    for (int h = 0; h < nh; h++) {
        int o = he_orig(g, h), d = he_dest(g, h);
        p->deg[o]++;
        ang[h] = atan2(g->node[d].y - g->node[o].y, g->node[d].x - g->node[o].x);
    }
    for (int i = 0; i < g->nn; i++) p->rot_start[i + 1] = p->rot_start[i] + p->deg[i];
    for (int i = 0; i < g->nn; i++) fill[i] = p->rot_start[i];
    for (int h = 0; h < nh; h++) p->rot[fill[he_orig(g, h)]++] = h;
    for (int i = 0; i < g->nn; i++) {
        int s = p->rot_start[i], n = p->rot_start[i + 1] - s;
        if (n < 2) continue;
        for (int k = 0; k < n; k++) rec[k] = (he_ang){ang[p->rot[s + k]], p->rot[s + k]};
        qsort(rec, (size_t)n, sizeof *rec, cmp_he_angle);
        for (int k = 0; k < n; k++) p->rot[s + k] = rec[k].h;
    }
    for (int q = 0; q < nh; q++) p->rot_pos[p->rot[q]] = q;
    for (int h = 0; h < nh; h++) p->face[h] = -1;
    int nf = 0, capf = 0;
    for (int h = 0; h < nh; h++) {
        if (p->face[h] >= 0) continue;
        if (nf == capf) {
            capf = capf ? 2 * capf : 1024;
            int *nfh = realloc(p->face_he, (size_t)capf * sizeof(int));
            if (!nfh) {
                st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (quad faces)");
                goto fail;
            }
            p->face_he = nfh;
        }
        p->face_he[nf] = h;
        int c = h, guard = 0;
        do {
            p->face[c] = nf;
            c = glpgp_xm_face_next(g, p, c);
        } while (c != h && ++guard <= nh);
        nf++;
    }
    p->nf = nf;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nf + 1, 1, &p->outer), fail);
    for (int e = 0; e < g->ne; e++)
        if (g->edge[e].flags & QE_BND) p->outer[p->face[2 * e + 1]] = 1; /* b -> a: outside */
    free(ang);
    free(fill);
    free(rec);
    return GLPGP_OK;
fail:
    free(ang);
    free(fill);
    free(rec);
    glpgp_xm_pmap_free(p);
    return st;
}

/* Turning angle at a degree-2 node between its two edges (0: straight). */
static double turn_angle(const graph *g, const pmap *p, int v)
{
    int s = p->rot_start[v];
    int h0 = p->rot[s], h1 = p->rot[s + 1];
    int d0 = he_dest(g, h0), d1 = he_dest(g, h1);
    double ax = g->node[d0].x - g->node[v].x, ay = g->node[d0].y - g->node[v].y;
    double bx = g->node[d1].x - g->node[v].x, by = g->node[d1].y - g->node[v].y;
    double c = (ax * bx + ay * by) / (hypot(ax, ay) * hypot(bx, by) + 1e-300);
    c = fmax(-1.0, fmin(1.0, c));
    return PI_ - acos(c);
}

/* Corner flags of all nodes for the current map. */
void glpgp_xm_corners(const graph *g, const pmap *p, unsigned char *corner)
{
    for (int v = 0; v < g->nn; v++) {
        int d = p->deg[v];
        corner[v] = 0;
        if (d >= 3 || (d >= 1 && g->node[v].fixed))
            corner[v] = 1;
        else if (d == 2 && g->node[v].bnd && turn_angle(g, p, v) > GLPGP_CORNER_DEG * PI_ / 180.0)
            corner[v] = 1;
    }
}

/* ---- clean-up ---------------------------------------------------------- */

/* One round of clean-up on the current map. Returns the number of changes
 * (0: the map is final). */
/* 1. Short sides: walk every side (corner to corner) once, from the
 * half-edge leaving a corner; contract those shorter than 0.2 h unless that
 * would merge two domain corners. */
static int short_sides(const graph *g, const pmap *p, const unsigned char *corner, double h, int *parent,
                       unsigned char *fx, int *collapsed)
{
    int nchg = 0;
    for (int h0 = 0; h0 < p->nh; h0++) {
        int a = he_orig(g, h0);
        if (!corner[a]) continue;
        if (p->outer[p->face[h0]] && p->outer[p->face[h0 ^ 1]]) continue;
        double len = 0.0;
        int c = h0, n = 0;
        for (;;) {
            int d = he_dest(g, c);
            len += hypot(g->node[d].x - g->node[he_orig(g, c)].x, g->node[d].y - g->node[he_orig(g, c)].y);
            if (corner[d] || ++n > 10000) break;
            /* continue through the degree-2 node */
            int s = p->rot_start[d];
            c = (p->rot[s] == (c ^ 1)) ? p->rot[s + 1] : p->rot[s];
        }
        int b = he_dest(g, c);
        /* each side once; a loop side (a == b: a closed level line through
         * one corner, or a side whose two ends were merged) is seen twice,
         * which is harmless since merging is idempotent */
        if (a > b || len >= 0.2 * h) continue;
        int ra = glpgp_uf_find(parent, a), rb = glpgp_uf_find(parent, b);
        if (ra != rb && fx[ra] && fx[rb]) continue; /* would merge two domain corners */
        /* merge the whole chain, interior nodes included: when a and b are
         * already in one set (merged through other short sides of the same
         * small face), the chain must collapse too, or it would be left as a
         * loop that crosses the edges re-pointed to the merged node */
        int changed = 0;
        c = h0;
        n = 0;
        for (;;) {
            int d = he_dest(g, c);
            int rd = glpgp_uf_find(parent, d), r = glpgp_uf_find(parent, a);
            if (rd != r) {
                parent[rd] = r;
                fx[r] = (unsigned char)(fx[r] | fx[rd]);
                changed = 1;
            }
            if (corner[d] || ++n > 10000) break;
            int s = p->rot_start[d];
            c = (p->rot[s] == (c ^ 1)) ? p->rot[s + 1] : p->rot[s];
        }
        if (!changed) continue;
        nchg++;
        (*collapsed)++;
    }
    return nchg;
}

/* The half-edge of face f's first corner (from h). */
static int first_corner(const graph *g, const pmap *p, const unsigned char *corner, int h)
{
    int start = h, guard = 0;
    while (!corner[he_orig(g, start)] && ++guard < p->nh) start = glpgp_xm_face_next(g, p, start);
    return start;
}

/* 2. A face with <= 2 corners: delete one of its sides without boundary edges. */
static int drop_side(graph *g, const pmap *p, const unsigned char *corner, int h)
{
    int start = first_corner(g, p, corner, h), c = start, guard = 0;
    do {
        int s0 = c, isb = 0, d = c;
        do {
            if (g->edge[d >> 1].flags & QE_BND) isb = 1;
            d = glpgp_xm_face_next(g, p, d);
        } while (!corner[he_orig(g, d)] && ++guard < p->nh);
        if (!isb) {
            int q = s0;
            do {
                g->edge[q >> 1].flags |= QE_DEL;
                q = glpgp_xm_face_next(g, p, q);
            } while (q != d);
            return 1;
        }
        c = d;
    } while (c != start && guard < p->nh);
    return 0;
}

/* 3. A 3-corner face with a boundary side through degree-2 boundary nodes:
 * the node farthest from the side's chord (-1: none). */
static int farthest_boundary_node(const graph *g, const pmap *p, const unsigned char *corner, int h)
{
    int best = -1, start = first_corner(g, p, corner, h), c = start, guard = 0;
    double bestd = 0.0;
    do {
        int a = he_orig(g, c), d = c, allb = 1, cnt = 0;
        do {
            if (!(g->edge[d >> 1].flags & QE_BND)) allb = 0;
            d = glpgp_xm_face_next(g, p, d);
            cnt++;
        } while (!corner[he_orig(g, d)] && ++guard < p->nh);
        int b = he_orig(g, d);
        if (allb && cnt >= 2) {
            double ax = g->node[a].x, ay = g->node[a].y, bx = g->node[b].x, by = g->node[b].y;
            double L = hypot(bx - ax, by - ay) + 1e-300;
            for (int q = glpgp_xm_face_next(g, p, c); q != d; q = glpgp_xm_face_next(g, p, q)) {
                int v = he_orig(g, q);
                double dist = fabs((bx - ax) * (g->node[v].y - ay) - (by - ay) * (g->node[v].x - ax)) / L;
                if (dist > bestd) {
                    bestd = dist;
                    best = v;
                }
            }
        }
        c = d;
    } while (c != start && guard < p->nh);
    return best;
}

glpgp_status glpgp_xm_cleanup_round(graph *g, const pmap *p, double h, int *changes, int *collapsed, int *promoted)
{
    glpgp_status st = GLPGP_OK;
    unsigned char *corner = NULL;
    int *parent = NULL;
    unsigned char *fx = NULL; /* per union-find root: the set holds a domain corner */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn + 1, 1, &corner), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn + 1, 1, &fx), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn + 1, sizeof(int), &parent), done);
    glpgp_xm_corners(g, p, corner);
    for (int i = 0; i < g->nn; i++) {
        parent[i] = i;
        fx[i] = g->node[i].fixed;
    }
    int nchg = short_sides(g, p, corner, h, parent, fx, collapsed);
    /* 2. faces with <= 2 corners: delete one of their non-boundary sides.
     * 3. 3-corner faces with a boundary side through degree-2 boundary
     *    nodes: promote the node farthest from the side's chord. */
    const int short_changes = nchg;
    for (int f = 0; f < p->nf && short_changes == 0; f++) {
        if (p->outer[f]) continue;
        int hf = p->face_he[f], nc = 0, guard = 0, c = hf;
        do {
            if (corner[he_orig(g, c)]) nc++;
            c = glpgp_xm_face_next(g, p, c);
        } while (c != hf && ++guard < p->nh);
        if (nc <= 2) {
            nchg += drop_side(g, p, corner, hf);
        } else if (nc == 3) {
            int best = farthest_boundary_node(g, p, corner, hf);
            if (best >= 0) {
                g->node[best].fixed = 1;
                (*promoted)++;
                nchg++;
            }
        }
    }
    if (nchg > 0) GLPGP_CHECK_GOTO(st, glpgp_xm_merge_nodes(g, parent), done);
    *changes = nchg;
done:
    free(corner);
    free(parent);
    free(fx);
    return st;
}
