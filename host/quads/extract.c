/* quads/extract.c: quad-mesh extraction from the two GL-PGP oscillators
 * (glpgp/quads.h). Quality metrics: quality.c; writers and the MSH reader:
 * io/quadmesh_io.c. Phases, charts and principal steps come from the phase
 * module (glpgp/phase.h).
 *
 * Algorithm
 * =========
 * theta_k = arg(z_k) / 2 pi (k = u, v) is a per-vertex value in [0, 1), exact
 * 0 where z_k = 1 (the Dirichlet vertices). The quad edges are the integer
 * level lines of theta_u and theta_v. Everything is built as one planar
 * straight-line graph (the "arrangement") whose nodes are
 *   V  every mesh vertex (used when a line passes exactly through it, and for
 *      the domain boundary polyline),
 *   X  the crossing of an integer line of theta_k with a mesh edge: on edge
 *      (a, b), a < b, with the canonical unwrapping c_a = theta(a),
 *      c_b = c_a + step(theta(b) - theta(a)) (step: principal difference
 *      in [-1/2, 1/2]), the integer n strictly between c_a and c_b (at most
 *      one per edge and family since |c_b - c_a| <= 1/2), at parameter
 *      s = (n - c_a) / (c_b - c_a). Computed once per edge, so both
 *      triangles of the edge use the same node; u and v crossings at the
 *      same parameter are one node (a grid point on the edge);
 *   G  grid points (theta_u and theta_v both integer) inside a triangle.
 * Per triangle t (corners p0 p1 p2, CCW) and family k, the chart unwraps
 * theta relative to corner 0: c_0 = theta(p0), c_j = c_0 + step(theta(pj) -
 * theta(p0)); it is affine in the triangle. Charts of two triangles differ by
 * an integer translation on their shared edge, recovered as
 * T = round(c_t(a) - c_canonical(a)) at the edge's base vertex a; the edge's
 * crossing integer n is the chart integer n + T. For every chart integer i
 * the triangle collects the points where theta_k = i on its perimeter
 * (vertices whose theta is exactly integer, and edge crossings) and they must
 * pair up: 2 points give a chord (the segment of the level line inside t),
 * 1 vertex is a touch, 3 vertices a flat triangle (nothing drawn); anything
 * else means the chart does not close (winding != 0, i.e. t is singular for
 * k, or rounding) and no line of family k is drawn in t.
 * A u-chord and a v-chord cross inside t exactly when their end points
 * interleave along the triangle perimeter (a combinatorial test on the shared
 * per-edge parameters, so neighbouring triangles can never disagree); the
 * crossing is a G node placed at the segment intersection. Graph edges are
 * the pieces of the chords between consecutive nodes, the pieces of mesh
 * edges that lie on a level line (both ends exactly integer, e.g. along a
 * Dirichlet boundary), and the pieces of the boundary edges between their
 * nodes (so boundary parts that are not level lines close the cells cut by
 * the boundary). Duplicates are merged.
 *
 * Singular triangles are holes for their family: the lines of that family
 * entering them end on their edges; these dangling ends are pruned back to
 * the last grid point (repeated removal of degree-1 nodes), so the cells
 * around a singularity merge into one face, usually a pentagon with a
 * T-junction vertex of valence 3 (a single dislocation has odd parity and
 * cannot be closed into quads locally), or a quad with valence 3/5 corners
 * when a u and a v singularity sit in the same cell.
 *
 * Faces: edges shorter than 1e-6 h are contracted, every node sorts its
 * incident edges by angle, and the faces of the planar map are traced with
 * next(h) = the edge before twin(h) in counter-clockwise order at its origin
 * (face on the left). Faces containing a boundary edge traversed against the
 * boundary loop direction are the outside and are dropped. Face corners are
 * the nodes of degree >= 3 and the degree-2 boundary nodes where the boundary
 * turns by more than 40 degrees (domain corners); other degree-2 nodes (a
 * line crossing a mesh edge, a boundary vertex) are not corners, so a face
 * side may be a polyline that is output as its chord.
 *
 * Clean-up (repeated until nothing changes, at most 8 rounds):
 *  - corner-to-corner sides shorter than 0.2 h are contracted (boundary and
 *    corner positions win), which removes the slivers that appear where a
 *    level line meets the boundary at a grazing angle or near a corner; the
 *    whole side collapses, its intermediate nodes too, even when its two end
 *    corners were already merged through other short sides of the same small
 *    face (otherwise the side survives as a loop through the merged node and
 *    crosses the edges re-pointed to it: a zero-length edge and a face that
 *    visits one vertex several times); two domain corners are never merged,
 *    not even through a chain of short sides;
 *  - faces with <= 2 corners (thin slivers between two parallel sides) are
 *    merged into a neighbour by deleting one of their sides (never a
 *    boundary side);
 *  - a 3-corner face with a side on the boundary gets the boundary vertex
 *    farthest from that side's chord as a fourth corner (this is free: the
 *    vertex belongs to no other face).
 * Output: a 5-corner face with a side on the boundary (a dislocation or a
 * switch between u- and v-Dirichlet boundary next to the boundary) gets a
 * boundary vertex M of that side (not within 30% of the side's ends) as a
 * sixth corner (free: M belongs to no other face, so the odd parity is
 * absorbed by the boundary). The hexagon is split either into two quads
 * along one of its three diagonals or, when no diagonal reaches a scaled
 * Jacobian of 0.5 and the alternative is better, into three quads around a
 * new interior vertex X joined to every other hexagon corner (X gets
 * valence 3, one corner one more edge: the 3-5 pair of a dislocation). The
 * center split is what closes a pentagon whose boundary side is a concave
 * arc (a hole), where every diagonal gives a reflex quad. M, the pattern and
 * X are chosen to maximise the smallest scaled Jacobian of the new quads,
 * and a split is made only if that is > 0.1.
 * Interior pentagons (a dislocation away from the boundary: odd parity, so
 * no quad split exists that leaves the neighbours unchanged) are kept here;
 * glpgp_quadmesh_close_polygons (close.c, run by glpgp_quads_build and
 * the CLI unless --keep-polygons) closes them pairwise or against the
 * boundary through strips of quads cut in two, at the same element size.
 * Whatever is still invalid against the domain after that (faces across
 * features narrower than h, lost holes, wedges, coarse input triangles) is
 * cut out and re-meshed by glpgp_quadmesh_repair (repair.c).
 * glpgp_quadmesh_subdivide (--all-quads) is the other route to an all-quad
 * mesh: one Catmull-Clark step (centroid + shared edge midpoints) turns
 * every n-gon into n quads at half the size.
 */
#include "glpgp/quads.h"
#include "glpgp/cross.h"
#include "glpgp/phase.h"
#include "glpgp/solve.h"
#include "glpgp/util.h"
#include "extract.h"
#include "geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_ GLPGP_PI

/* ---- small growable arrays --------------------------------------------- */

glpgp_status glpgp_xg_add_node(graph *g, double x, double y, int vert, int bnd, int *id)
{
    if (g->nn == g->capn) {
        int nc = g->capn ? 2 * g->capn : 1024;
        qnode *p = realloc(g->node, (size_t)nc * sizeof *p);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (quad graph nodes)");
        g->node = p;
        g->capn = nc;
    }
    qnode *n = &g->node[g->nn];
    n->x = x;
    n->y = y;
    n->vert = vert;
    n->bnd = (unsigned char)bnd;
    n->fixed = 0;
    *id = g->nn++;
    return GLPGP_OK;
}

glpgp_status glpgp_xg_add_edge(graph *g, int a, int b, int flags)
{
    if (a == b) return GLPGP_OK;
    if (g->ne == g->cape) {
        int nc = g->cape ? 2 * g->cape : 2048;
        qedge *p = realloc(g->edge, (size_t)nc * sizeof *p);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (quad graph edges)");
        g->edge = p;
        g->cape = nc;
    }
    g->edge[g->ne].a = a;
    g->edge[g->ne].b = b;
    g->edge[g->ne].flags = (unsigned char)flags;
    g->ne++;
    return GLPGP_OK;
}

/* ---- mesh edges -------------------------------------------------------- */

typedef struct medges {
    int ne;
    int *ev;       /* 2*ne: a < b */
    int *nbt;      /* 2*ne: adjacent triangles (second -1 on the boundary) */
    int *tri_edge; /* 3*nt: edge of triangle side j = (p_j, p_{j+1}) */
} medges;

static int cmp_key3(const void *pa, const void *pb)
{
    const long long *a = pa, *b = pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

static glpgp_status build_edges(const glpgp_mesh *m, medges *E)
{
    long long *k = NULL;
    size_t n3 = (size_t)3 * m->nt;
    GLPGP_CHECK(glpgp_malloc(n3 * 2, sizeof *k, &k));
    for (int t = 0; t < m->nt; t++)
        for (int j = 0; j < 3; j++) {
            int a = m->tri[3 * t + j], b = m->tri[3 * t + (j + 1) % 3];
            int lo = a < b ? a : b, hi = a < b ? b : a;
            k[2 * (3 * t + j)] = (long long)lo * m->nv + hi;
            k[2 * (3 * t + j) + 1] = 3 * t + j;
        }
    qsort(k, n3, 2 * sizeof *k, cmp_key3);
    glpgp_status st = GLPGP_OK;
    E->ev = E->nbt = E->tri_edge = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n3 * 2, sizeof(int), &E->ev), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n3 * 2, sizeof(int), &E->nbt), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n3, sizeof(int), &E->tri_edge), fail);
    int ne = 0;
    for (size_t i = 0; i < n3;) {
        size_t j = i + 1;
        while (j < n3 && k[2 * j] == k[2 * i]) j++;
        long long key = k[2 * i];
        E->ev[2 * ne] = (int)(key / m->nv);
        E->ev[2 * ne + 1] = (int)(key % m->nv);
        E->nbt[2 * ne] = (int)(k[2 * i + 1] / 3);
        E->nbt[2 * ne + 1] = j > i + 1 ? (int)(k[2 * i + 3] / 3) : -1;
        for (size_t q = i; q < j; q++) E->tri_edge[k[2 * q + 1]] = ne;
        ne++;
        i = j;
    }
    E->ne = ne;
    free(k);
    return GLPGP_OK;
fail:
    free(k);
    free(E->ev);
    free(E->nbt);
    free(E->tri_edge);
    return st;
}

/* ---- the arrangement --------------------------------------------------- */

typedef struct chord {
    double pos[2]; /* perimeter positions in [0, 3): corner j -> j, side j -> j + s */
    int node[2];
    int edge_side; /* >= 0: the chord is triangle side j (both ends exactly integer) */
    int ng;        /* grid points on it */
    int gnode[16];
    double gpar[16];
} chord;

typedef struct builder {
    const glpgp_mesh *m;
    const glpgp_result *r;
    medges E;
    double *theta[2];
    unsigned char *exact[2];
    const double *rep; /* coupled result: the representatives U (2*nv), else NULL */
    int *xint;      /* 2*ne: canonical crossing integer of family k, or INT_MIN-ish sentinel */
    double *xs;     /* 2*ne: its parameter along a -> b */
    int *xnode;     /* 2*ne: its node */
    graph g;
    int singular[2], inconsistent[2];
} builder;

#define NOX (-2147483647)

/* Append the graph edges along mesh edge e (a -> b in the given direction),
 * through its crossing nodes in order. */
static glpgp_status add_mesh_edge_path(builder *B, int e, int from, int flags)
{
    int a = B->E.ev[2 * e], b = B->E.ev[2 * e + 1];
    int seq[4], n = 0;
    seq[n++] = a;
    int x0 = B->xint[2 * e] != NOX ? B->xnode[2 * e] : -1;
    int x1 = B->xint[2 * e + 1] != NOX ? B->xnode[2 * e + 1] : -1;
    if (x0 >= 0 && x1 >= 0 && x0 != x1) {
        if (B->xs[2 * e] <= B->xs[2 * e + 1]) {
            seq[n++] = x0;
            seq[n++] = x1;
        } else {
            seq[n++] = x1;
            seq[n++] = x0;
        }
    } else if (x0 >= 0) {
        seq[n++] = x0;
    } else if (x1 >= 0) {
        seq[n++] = x1;
    }
    seq[n++] = b;
    if (from == a) {
        for (int i = 0; i + 1 < n; i++) GLPGP_CHECK(glpgp_xg_add_edge(&B->g, seq[i], seq[i + 1], flags));
    } else {
        for (int i = n - 1; i > 0; i--) GLPGP_CHECK(glpgp_xg_add_edge(&B->g, seq[i], seq[i - 1], flags));
    }
    return GLPGP_OK;
}

/* Chords of family k in triangle t. Returns the number of chords (<= 3) or
 * -1 when the chart does not close. */
static int tri_chords(builder *B, int t, int k, chord *ch)
{
    const glpgp_mesh *m = B->m;
    int p[3];
    double c[3], tp[3];
    unsigned char exv[3];
    int fam[3] = {k, k, k}, cj[3] = {0, 0, 0};
    for (int j = 0; j < 3; j++) p[j] = m->tri[3 * t + j];
    for (int j = 0; j < 3; j++) {
        /* coupled: the frame (corner 0's representative) family k at corner j
         * is family fam[j] of vertex p[j], conjugated (theta -> -theta) when cj[j] */
        if (B->rep) glpgp_cross_frame_map(glpgp_cross_turn(B->rep + 2 * p[0], B->rep + 2 * p[j]), k, &fam[j], &cj[j]);
        const double v = B->theta[fam[j]][p[j]];
        tp[j] = cj[j] ? -v : v;
        exv[j] = B->exact[fam[j]][p[j]];
    }
    glpgp_phase_chart(tp, c);
    /* perimeter points: (chart integer, position, node) */
    long ii[6];
    double pos[6];
    int nd[6], isv[6], np = 0;
    for (int j = 0; j < 3; j++) {
        if (exv[j]) {
            ii[np] = lround(c[j]);
            pos[np] = j;
            nd[np] = p[j];
            isv[np] = 1;
            np++;
        }
        int e = B->E.tri_edge[3 * t + j];
        int a = B->E.ev[2 * e];
        int ja = p[0] == a ? 0 : p[1] == a ? 1 : 2;
        /* the edge's crossings are stored in a's own families: the frame's
         * family k is a's family fam[ja], with the sign sg */
        const int ka = fam[ja];
        const long sg = cj[ja] ? -1 : 1;
        if (B->xint[2 * e + ka] == NOX) continue;
        long T = lround(c[ja] - (double)sg * B->theta[ka][a]); /* chart = sg canonical + T */
        double s = B->xs[2 * e + ka];    /* from a */
        double sl = (a == p[j]) ? s : 1.0 - s;
        ii[np] = sg * B->xint[2 * e + ka] + T;
        pos[np] = j + sl;
        nd[np] = B->xnode[2 * e + ka];
        isv[np] = 0;
        np++;
    }
    int nch = 0;
    unsigned char used[6] = {0};
    for (int q = 0; q < np; q++) {
        if (used[q]) continue;
        int grp[6], ng = 0, nv = 0;
        for (int w = q; w < np; w++)
            if (!used[w] && ii[w] == ii[q]) {
                grp[ng++] = w;
                used[w] = 1;
                nv += isv[w];
            }
        if (ng == 1 && nv == 1) continue; /* touches a corner */
        if (ng == 3 && nv == 3) continue; /* flat triangle */
        if (ng != 2) return -1;
        chord *C = &ch[nch++];
        int w0 = grp[0], w1 = grp[1];
        if (pos[w0] > pos[w1]) {
            int tmp = w0;
            w0 = w1;
            w1 = tmp;
        }
        C->pos[0] = pos[w0];
        C->pos[1] = pos[w1];
        C->node[0] = nd[w0];
        C->node[1] = nd[w1];
        C->ng = 0;
        C->edge_side = -1;
        if (isv[w0] && isv[w1]) {
            int j0 = (int)pos[w0], j1 = (int)pos[w1];
            C->edge_side = (j1 == j0 + 1) ? j0 : 2; /* (0,1)->0, (1,2)->1, (0,2)->2 */
        }
        if (nch > 3) return -1;
    }
    return nch;
}

static int in_arc(double x, double a0, double a1) { return x > a0 && x < a1; }

static void node_xy(const graph *g, int n, double *x, double *y)
{
    *x = g->node[n].x;
    *y = g->node[n].y;
}

/* Intersection parameters of segments P0P1 and Q0Q1 (clamped to [0, 1]). */
static void seg_intersect(double px0, double py0, double px1, double py1, double qx0, double qy0,
                          double qx1, double qy1, double *tp, double *tq)
{
    double rx = px1 - px0, ry = py1 - py0, sx = qx1 - qx0, sy = qy1 - qy0;
    double den = rx * sy - ry * sx;
    double wx = qx0 - px0, wy = qy0 - py0;
    double a = 0.5, b = 0.5;
    if (fabs(den) > 1e-300) {
        a = (wx * sy - wy * sx) / den;
        b = (wx * ry - wy * rx) / den;
    }
    *tp = fmin(1.0, fmax(0.0, a));
    *tq = fmin(1.0, fmax(0.0, b));
}

static glpgp_status add_chord_edges(builder *B, chord *C, int flags)
{
    /* insertion sort of the grid points by parameter */
    for (int i = 1; i < C->ng; i++) {
        double pv = C->gpar[i];
        int nv = C->gnode[i], j = i - 1;
        while (j >= 0 && C->gpar[j] > pv) {
            C->gpar[j + 1] = C->gpar[j];
            C->gnode[j + 1] = C->gnode[j];
            j--;
        }
        C->gpar[j + 1] = pv;
        C->gnode[j + 1] = nv;
    }
    int prev = C->node[0];
    for (int i = 0; i < C->ng; i++) {
        GLPGP_CHECK(glpgp_xg_add_edge(&B->g, prev, C->gnode[i], flags));
        prev = C->gnode[i];
    }
    return glpgp_xg_add_edge(&B->g, prev, C->node[1], flags);
}

static glpgp_status build_arrangement(builder *B)
{
    const glpgp_mesh *m = B->m;
    const glpgp_result *r = B->r;
    const int nv = m->nv, ne = B->E.ne;
    graph *g = &B->g;
    /* theta per family */
    for (int k = 0; k < 2; k++) {
        GLPGP_CHECK(glpgp_malloc((size_t)nv, sizeof(double), &B->theta[k]));
        GLPGP_CHECK(glpgp_malloc((size_t)nv, 1, &B->exact[k]));
        for (int i = 0; i < nv; i++) {
            double t = glpgp_theta(r->osc[k].z[2 * i], r->osc[k].z[2 * i + 1]);
            B->theta[k][i] = t;
            B->exact[k][i] = (t == 0.0);
        }
    }
    /* V nodes: one per mesh vertex, id = vertex index */
    for (int i = 0; i < nv; i++) {
        int id;
        GLPGP_CHECK(glpgp_xg_add_node(g, m->xy[2 * i], m->xy[2 * i + 1], i, m->on_boundary[i], &id));
    }
    /* X nodes: crossings per edge and family, computed once per edge */
    GLPGP_CHECK(glpgp_malloc((size_t)2 * ne, sizeof(int), &B->xint));
    GLPGP_CHECK(glpgp_malloc((size_t)2 * ne, sizeof(double), &B->xs));
    GLPGP_CHECK(glpgp_malloc((size_t)2 * ne, sizeof(int), &B->xnode));
    for (int e = 0; e < ne; e++) {
        int a = B->E.ev[2 * e], b = B->E.ev[2 * e + 1];
        int bnd = B->E.nbt[2 * e + 1] < 0;
        for (int k = 0; k < 2; k++) {
            const double *th = B->theta[k];
            /* b's value in a's family k (coupled: through the matching of the edge) */
            int fb = k, cb_conj = 0;
            if (B->rep) glpgp_cross_frame_map(glpgp_cross_turn(B->rep + 2 * a, B->rep + 2 * b), k, &fb, &cb_conj);
            const double tb = cb_conj ? -B->theta[fb][b] : B->theta[fb][b];
            double ca = th[a], cb = ca + glpgp_phase_step(tb - th[a]);
            if (B->exact[fb][b]) cb = (double)lround(cb);
            B->xint[2 * e + k] = NOX;
            double lo = fmin(ca, cb), hi = fmax(ca, cb);
            double n = floor(lo) + 1.0; /* smallest integer > lo */
            if (n < hi) {
                B->xint[2 * e + k] = (int)n;
                B->xs[2 * e + k] = (n - ca) / (cb - ca);
            }
        }
        int have0 = B->xint[2 * e] != NOX, have1 = B->xint[2 * e + 1] != NOX;
        double ax = m->xy[2 * a], ay = m->xy[2 * a + 1], bx = m->xy[2 * b], by = m->xy[2 * b + 1];
        for (int k = 0; k < 2; k++) {
            if (B->xint[2 * e + k] == NOX) continue;
            if (k == 1 && have0 && fabs(B->xs[2 * e] - B->xs[2 * e + 1]) < 1e-12) {
                B->xnode[2 * e + 1] = B->xnode[2 * e]; /* grid point on the edge */
                continue;
            }
            double s = B->xs[2 * e + k];
            int id = -1;
            GLPGP_CHECK(glpgp_xg_add_node(g, ax + s * (bx - ax), ay + s * (by - ay), -1, bnd, &id));
            B->xnode[2 * e + k] = id;
        }
        (void)have1;
    }
    /* boundary edges, in loop direction (the domain on the left) */
    for (int t = 0; t < m->nt; t++)
        for (int j = 0; j < 3; j++) {
            int e = B->E.tri_edge[3 * t + j];
            if (B->E.nbt[2 * e + 1] >= 0) continue;
            GLPGP_CHECK(add_mesh_edge_path(B, e, m->tri[3 * t + j], QE_BND));
        }
    /* chords and grid points, triangle by triangle */
    for (int t = 0; t < m->nt; t++) {
        if ((t & 16383) == 0) glpgp_progress_poll();
        chord ch[2][3];
        int nch[2];
        for (int k = 0; k < 2; k++) {
            int sing = r->osc[k].singular && r->osc[k].singular[t] != 0;
            if (B->rep) { /* coupled: a cross-field singular triangle (matching around it not the
                             identity) has no consistent frame: no quad corner there */
                const int *v = m->tri + 3 * t;
                const int q = glpgp_cross_turn(B->rep + 2 * v[0], B->rep + 2 * v[1]) +
                              glpgp_cross_turn(B->rep + 2 * v[1], B->rep + 2 * v[2]) +
                              glpgp_cross_turn(B->rep + 2 * v[2], B->rep + 2 * v[0]);
                if (q % 4 != 0) sing = 1;
            }
            nch[k] = tri_chords(B, t, k, ch[k]);
            if (sing) {
                B->singular[k]++;
                nch[k] = -1;
            } else if (nch[k] < 0) {
                B->inconsistent[k]++;
            }
        }
        if (nch[0] > 0 && nch[1] > 0) {
            for (int a = 0; a < nch[0]; a++) {
                chord *U = &ch[0][a];
                if (U->edge_side >= 0) continue;
                for (int b = 0; b < nch[1]; b++) {
                    chord *V = &ch[1][b];
                    if (V->edge_side >= 0) continue;
                    if (V->node[0] == U->node[0] || V->node[0] == U->node[1] ||
                        V->node[1] == U->node[0] || V->node[1] == U->node[1])
                        continue; /* they meet at a shared end point */
                    int in0 = in_arc(V->pos[0], U->pos[0], U->pos[1]);
                    int in1 = in_arc(V->pos[1], U->pos[0], U->pos[1]);
                    if (in0 == in1) continue;
                    if (U->ng >= 16 || V->ng >= 16) continue;
                    double p0x, p0y, p1x, p1y, q0x, q0y, q1x, q1y, tu, tv;
                    node_xy(g, U->node[0], &p0x, &p0y);
                    node_xy(g, U->node[1], &p1x, &p1y);
                    node_xy(g, V->node[0], &q0x, &q0y);
                    node_xy(g, V->node[1], &q1x, &q1y);
                    seg_intersect(p0x, p0y, p1x, p1y, q0x, q0y, q1x, q1y, &tu, &tv);
                    int id = -1;
                    GLPGP_CHECK(glpgp_xg_add_node(g, p0x + tu * (p1x - p0x), p0y + tu * (p1y - p0y), -1, 0,
                                         &id));
                    U->gnode[U->ng] = id;
                    U->gpar[U->ng++] = tu;
                    V->gnode[V->ng] = id;
                    V->gpar[V->ng++] = tv;
                }
            }
        }
        for (int k = 0; k < 2; k++) {
            for (int a = 0; a < nch[k]; a++) {
                chord *C = &ch[k][a];
                int fl = k == 0 ? QE_U : QE_V;
                if (C->edge_side >= 0) {
                    int e = B->E.tri_edge[3 * t + C->edge_side];
                    GLPGP_CHECK(add_mesh_edge_path(B, e, B->E.ev[2 * e], fl));
                } else {
                    GLPGP_CHECK(add_chord_edges(B, C, fl));
                }
            }
        }
    }
    return GLPGP_OK;
}

/* ---- driver ------------------------------------------------------------ */

/* Minimum corner scaled Jacobian of the quad (a, b, c, d) of graph nodes. */
static double quad_sj(const graph *g, const int *v)
{
    double xy[8];
    int id[4] = {0, 1, 2, 3};
    for (int i = 0; i < 4; i++) {
        xy[2 * i] = g->node[v[i]].x;
        xy[2 * i + 1] = g->node[v[i]].y;
    }
    return glpgp_poly_min_sj(xy, id, 4);
}

/* glpgp_hex_center_split for the hexagon hx[0..5] of graph nodes. */
static double hex_center_split(const graph *g, const int *hx, int *o_best, double *xb, double *yb)
{
    double xy[12];
    int id[6] = {0, 1, 2, 3, 4, 5};
    for (int i = 0; i < 6; i++) {
        xy[2 * i] = g->node[hx[i]].x;
        xy[2 * i + 1] = g->node[hx[i]].y;
    }
    return glpgp_hex_center_split(xy, id, o_best, xb, yb);
}

/* Output index of graph node v (appended on first use). */
static int out_vertex(const graph *g, glpgp_quadmesh *q, int *newid, int v)
{
    if (newid[v] < 0) {
        newid[v] = q->nv;
        q->xy[2 * q->nv] = g->node[v].x;
        q->xy[2 * q->nv + 1] = g->node[v].y;
        q->nv++;
    }
    return newid[v];
}

/* The graph simplified: domain corners fixed (the boundary turns by more
 * than 40 degrees), coincident nodes (edges below 1e-6 h) merged, dangling
 * ends pruned, the clean-up rounds; its final map in *P. */
static glpgp_status simplify(builder *B, double h, pmap *P, int *collapsed, int *promoted)
{
    const glpgp_mesh *m = B->m;
    graph *g = &B->g;
    for (int i = 0; i < m->nv; i++) {
        if (!m->on_boundary[i]) continue;
        const double *a = m->normal_prev + 2 * i, *b = m->normal_next + 2 * i;
        if (a[0] * b[0] + a[1] * b[1] < cos(GLPGP_CORNER_DEG * PI_ / 180.0)) g->node[i].fixed = 1;
    }
    int *parent = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)g->nn, sizeof(int), &parent));
    for (int i = 0; i < g->nn; i++) parent[i] = i;
    for (int e = 0; e < g->ne; e++) {
        const qnode *a = &g->node[g->edge[e].a], *b = &g->node[g->edge[e].b];
        if (hypot(a->x - b->x, a->y - b->y) < 1e-6 * h) {
            int ra = glpgp_uf_find(parent, g->edge[e].a), rb = glpgp_uf_find(parent, g->edge[e].b);
            if (ra != rb) parent[rb] = ra;
        }
    }
    glpgp_status st = glpgp_xm_merge_nodes(g, parent);
    free(parent);
    GLPGP_CHECK(st);
    GLPGP_CHECK(glpgp_xm_prune(g));
    for (int round = 0; round < 8; round++) {
        GLPGP_CHECK(glpgp_xm_pmap_build(g, P));
        int changes = 0;
        GLPGP_CHECK(glpgp_xm_cleanup_round(g, P, h, &changes, collapsed, promoted));
        if (changes == 0) break;
        glpgp_xm_pmap_free(P);
        GLPGP_CHECK(glpgp_xm_prune(g));
    }
    if (!P->rot_start) GLPGP_CHECK(glpgp_xm_pmap_build(g, P));
    return GLPGP_OK;
}

/* The splits of a boundary pentagon considered (see the header). */
typedef struct pent_split {
    int split, csplit, co; /* diagonal split found (-1: none); center split; its offset */
    int cs[8], chx[6];     /* the two quads of the diagonal; the hexagon of the center split */
    double best_diag, cbest, cx, cy;
} pent_split;

/* Boundary pentagon (cycle cyc of len nodes, half-edges cych): make the best
 * intermediate boundary node of a boundary side a sixth corner and split the
 * hexagon by the diagonal from it to an opposite corner (of the three
 * diagonals, the one whose worse quad has the best scaled Jacobian, if that
 * is > 0.1), or, when no diagonal gives a quad as good as 0.5, into three
 * quads around a new center vertex if that is better: the usual case when
 * the new corner sits on a concave boundary arc, where every diagonal makes
 * a reflex quad. */
static void pentagon_split(const graph *g, const int *cyc, const int *cych, int len, const unsigned char *corner,
                           pent_split *ps)
{
    double best = 0.1;
    int pos5[5], np5 = 0;
    ps->split = ps->csplit = -1;
    ps->best_diag = ps->cbest = -INFINITY;
    for (int i = 0; i < len && np5 < 5; i++)
        if (corner[cyc[i]]) pos5[np5++] = i;
    for (int sd = 0; sd < 5; sd++) {
        int i0 = pos5[sd], i1 = sd < 4 ? pos5[sd + 1] : len, allb = 1;
        for (int i = i0; i < i1; i++)
            if (!(g->edge[cych[i] >> 1].flags & QE_BND)) allb = 0;
        if (!allb || i1 - i0 < 2) continue;
        int ca = cyc[i0], cb = cyc[i1 % len];
        double Lab = hypot(g->node[cb].x - g->node[ca].x, g->node[cb].y - g->node[ca].y);
        for (int i = i0 + 1; i < i1; i++) {
            int hx[6];
            hx[0] = cyc[i];
            /* keep the new corner away from the side's ends */
            double da = hypot(g->node[hx[0]].x - g->node[ca].x, g->node[hx[0]].y - g->node[ca].y);
            double db = hypot(g->node[hx[0]].x - g->node[cb].x, g->node[hx[0]].y - g->node[cb].y);
            if (da < 0.3 * Lab || db < 0.3 * Lab) continue;
            for (int k = 1; k < 6; k++) hx[k] = cyc[pos5[(sd + k) % 5]];
            int o = 0;
            double x = 0.0, y = 0.0, sj = hex_center_split(g, hx, &o, &x, &y);
            if (sj > ps->cbest) {
                ps->cbest = sj;
                ps->csplit = i;
                ps->co = o;
                ps->cx = x;
                ps->cy = y;
                memcpy(ps->chx, hx, sizeof ps->chx);
            }
            for (int d = 0; d < 3; d++) { /* the three diagonals (d, d + 3) of the hexagon */
                int qa[4], qb[4];
                for (int k = 0; k < 4; k++) {
                    qa[k] = hx[(d + k) % 6];
                    qb[k] = hx[(d + 3 + k) % 6];
                }
                double v = fmin(quad_sj(g, qa), quad_sj(g, qb));
                if (v > best) {
                    best = ps->best_diag = v;
                    ps->split = i;
                    memcpy(ps->cs, qa, sizeof qa);
                    memcpy(ps->cs + 4, qb, sizeof qb);
                }
            }
        }
    }
}

/* The output and its counters. */
typedef struct xout {
    glpgp_quadmesh *q;
    int *newid, w;
    int split_pentagons, center_splits;
} xout;

/* Inner face f of the map into the output: its corners, a boundary
 * pentagon split into two or three quads. */
static glpgp_status emit_face(graph *g, const pmap *P, const unsigned char *corner, int f, int *cyc, int *cych, xout *X)
{
    glpgp_quadmesh *q = X->q;
    int h0 = P->face_he[f], guard = 0;
    while (!corner[he_orig(g, h0)] && ++guard < P->nh) h0 = glpgp_xm_face_next(g, P, h0); /* start at a corner */
    int nc = 0, len = 0, c = h0;
    guard = 0;
    do {
        cych[len] = c;
        cyc[len++] = he_orig(g, c);
        nc += corner[he_orig(g, c)];
        c = glpgp_xm_face_next(g, P, c);
    } while (c != h0 && ++guard < P->nh);
    if (nc < 3) return GLPGP_OK;
    pent_split ps = {-1, -1, 0, {0}, {0}, -INFINITY, -INFINITY, 0.0, 0.0};
    if (nc == 5) pentagon_split(g, cyc, cych, len, corner, &ps);
    if (ps.csplit >= 0 && ps.cbest > 0.1 && (ps.split < 0 || (ps.best_diag < 0.5 && ps.cbest > ps.best_diag))) {
        int C = -1;
        GLPGP_CHECK(glpgp_xg_add_node(g, ps.cx, ps.cy, -1, 0, &C));
        X->newid[C] = -1;
        for (int i = 0; i < 3; i++) {
            for (int k = 0; k < 3; k++) q->face_vert[X->w++] = out_vertex(g, q, X->newid, ps.chx[(ps.co + 2 * i + k) % 6]);
            q->face_vert[X->w++] = out_vertex(g, q, X->newid, C);
            q->face_start[++q->nf] = X->w;
        }
        X->split_pentagons++;
        X->center_splits++;
        return GLPGP_OK;
    }
    if (ps.split >= 0) {
        for (int k = 0; k < 8; k++) {
            q->face_vert[X->w++] = out_vertex(g, q, X->newid, ps.cs[k]);
            if (k == 3 || k == 7) q->face_start[++q->nf] = X->w;
        }
        X->split_pentagons++;
        return GLPGP_OK;
    }
    for (int i = 0; i < len; i++)
        if (corner[cyc[i]]) q->face_vert[X->w++] = out_vertex(g, q, X->newid, cyc[i]);
    q->face_start[++q->nf] = X->w;
    return GLPGP_OK;
}

static void builder_free(builder *B)
{
    for (int k = 0; k < 2; k++) {
        free(B->theta[k]);
        free(B->exact[k]);
    }
    free(B->xint);
    free(B->xs);
    free(B->xnode);
    free(B->E.ev);
    free(B->E.nbt);
    free(B->E.tri_edge);
    free(B->g.node);
    free(B->g.edge);
}

glpgp_status glpgp_quads_extract(const glpgp_mesh *m, const glpgp_result *r, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!m || !r) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad extraction: no mesh or result");
    if (m->xyz) /* a surface: glpgp_quads_extract_surface */
        return GLPGP_FAIL(GLPGP_ERR_ARG, "quad extraction: a 3D surface (glpgp_quads_extract_surface extracts it)");
    if (r->nv != m->nv || r->nt != m->nt)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "quad extraction: result has %d vertices / %d triangles, mesh %d / %d", r->nv,
                          r->nt, m->nv, m->nt);
    if (!r->osc[0].z || !r->osc[1].z)
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "quad extraction: the result has no oscillators z_u, z_v");
    double h = r->size > 0.0 ? r->size : glpgp_default_size(m, NULL);
    glpgp_status st = GLPGP_OK;
    builder B;
    memset(&B, 0, sizeof B);
    B.m = m;
    B.r = r;
    B.rep = r->coupled && r->field ? r->field : NULL;
    pmap P;
    memset(&P, 0, sizeof P);
    unsigned char *corner = NULL;
    xout X;
    memset(&X, 0, sizeof X);
    int collapsed = 0, promoted = 0, *cyc = NULL, *cych = NULL;
    GLPGP_CHECK_GOTO(st, build_edges(m, &B.E), done);
    GLPGP_CHECK_GOTO(st, build_arrangement(&B), done);
    GLPGP_CHECK_GOTO(st, simplify(&B, h, &P, &collapsed, &promoted), done);
    graph *g = &B.g;
    /* output: corner nodes of inner faces, renumbered (room for one center vertex per face) */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn + 1, 1, &corner), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->nn + P.nf + 1, sizeof(int), &X.newid), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)P.nh + 1, sizeof(int), &cyc), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)P.nh + 1, sizeof(int), &cych), done);
    glpgp_xm_corners(g, &P, corner);
    for (int i = 0; i < g->nn + P.nf + 1; i++) X.newid[i] = -1;
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *X.q, &X.q), done);
    /* a face becomes at most 3 quads (12 corners; it has >= 6 half-edges then) */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)P.nf + 2, 3 * sizeof(int), &X.q->face_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)P.nh + 1, 2 * sizeof(int), &X.q->face_vert), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)P.nh + P.nf + 1, 2 * sizeof(double), &X.q->xy), done);
    X.q->face_start[0] = 0;
    for (int f = 0; f < P.nf; f++)
        if (!P.outer[f]) GLPGP_CHECK_GOTO(st, emit_face(g, &P, corner, f, cyc, cych, &X), done);
    glpgp_quadmesh *q = X.q;
    if (q->nf == 0) {
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad extraction: no face found (is h = %g too large for the domain?)", h);
        goto done;
    }
    for (int k = 0; k < 2; k++) {
        q->singular_tris[k] = B.singular[k];
        q->inconsistent_tris[k] = B.inconsistent[k];
    }
    q->collapsed_edges = collapsed;
    q->promoted_corners = promoted;
    q->split_pentagons = X.split_pentagons;
    q->center_splits = X.center_splits;
    *out = q;
    X.q = NULL;
done:
    glpgp_quadmesh_destroy(&X.q);
    glpgp_xm_pmap_free(&P);
    free(X.newid);
    free(corner);
    free(cyc);
    free(cych);
    builder_free(&B);
    return st;
}
