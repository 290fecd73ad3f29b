/* quads/extract_surface.c: quad-mesh extraction on a 3D surface
 * (glpgp_quads_extract_surface, quads_surface.h). The planar extraction
 * (extract.c) is untouched; this is its twin on a surface, where there is
 * no global plane: every geometric question is asked in one triangle's own
 * plane (m->surf->txy, the local chart).
 *
 * Algorithm
 * =========
 * Per triangle t and family k the corners' phases are read through t's
 * matching (glpgp_coupled_frame_value with glpgp_coupled_corner_turn, as the
 * surface renderer and the OBJ writer read them) and unwrapped relative to
 * corner 0 (glpgp_phase_chart); a family whose three principal steps do not
 * sum to zero (winding != 0: t is singular for it) draws no line in t.
 * Nodes of the graph:
 *  V  mesh vertices on a level line (a frame phase exactly 0: the Dirichlet
 *     vertices of boundaries and features) and every boundary vertex;
 *  X  the crossings of integer level lines with mesh edges, computed once
 *     per undirected edge in its owner triangle (the one holding the edge's
 *     smaller half-edge), at parameter s along the owner's half-edge, the
 *     u and v crossings at one parameter merged (a grid point on an edge).
 *     The other triangle sees the same node: its family is the owner's,
 *     swapped when the two triangles' turns at the edge's first vertex differ
 *     by an odd number of quarter turns (u <-> v through the matching), and
 *     its integer is its own chart's value at s, rounded;
 *  G  the crossing of a u chord and a v chord inside a triangle, when their
 *     end points interleave along the triangle's perimeter (combinatorial,
 *     so both sides of an edge agree), placed at the chords' intersection in
 *     the triangle's plane, in barycentric coordinates.
 * Per triangle, family and integer the perimeter points must pair up (two
 * points: a chord; one vertex: a touch; three vertices: a flat triangle),
 * else no line of that family is drawn in t. Graph edges: chord pieces
 * between consecutive nodes (each in one triangle), mesh edges on a level
 * line and the boundary edges, split at their X nodes (boundary pieces run
 * along the boundary loop, surface on their left). Dangling ends (lines
 * ending in singular triangles) are pruned back to the last grid point.
 *
 * Faces: the rotation system at a node orders its half-edges by an angle on
 * the surface: inside a triangle the angle in its plane; on an edge the
 * angle from the edge's direction, in [0, pi] in the owner triangle and
 * [pi, 2 pi] in the other (each triangle unfolded about the edge); at a
 * vertex the angle from its fan's reference edge, the corners' angles
 * accumulated around the fan (vstart order). Faces are traced with the face
 * on the left (next = the half-edge before the twin at the next node); the
 * faces with a boundary piece traversed against the loop are outside.
 * Corners: nodes of degree >= 3 and the boundary vertices where the
 * boundary turns by more than 40 degrees, both between its two edges and
 * at the scale of the constraints, the most there (glpgp_surface_rim_corners:
 * a jagged rim's teeth are no corners). Positions: barycentric
 * interpolation of the triangle's 3D corners. The result is a polygon mesh
 * with xyz set (quads_surface.c makes it all-quad and checks it). */
#include "quads_surface.h"
#include "vec3.h"

#include "glpgp/cross.h"
#include "glpgp/kinds.h"
#include "glpgp/phase.h"
#include "glpgp/surface.h"
#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_ GLPGP_PI
/* a face's side along a boundary loop strays at most this x h from the loop
 * (rim_corners; the check allows h / 4): 0.2 measured on spheres with 4, 20
 * and 120 round holes (bench/results/surface_holes.md) */
#define QX_RIM_CHORD 0.2

enum { SN_VERT = 0, SN_EDGE = 1, SN_IN = 2 };
enum { SE_BND = 1, SE_ALONG = 2, SE_DEL = 4 };

typedef struct snode {
    int kind, id;      /* vertex / owner half-edge / triangle */
    double s;          /* SN_EDGE: parameter along the owner half-edge */
    double b[3];       /* SN_IN: barycentric coordinates in triangle id */
    unsigned char fam; /* SN_EDGE: families crossing here in the owner's chart */
} snode;

typedef struct sedge {
    int a, b, t;
    unsigned char flags;
} sedge;

typedef struct sxctx {
    const glpgp_mesh *m;
    const glpgp_surface *S;
    double *ch;          /* 6 nt: chart value of family k at corner j: 6t + 3k + j */
    unsigned char *zc;   /* 6 nt: the frame phase is exactly 0 there */
    unsigned char *ok;   /* 2 nt: family k closes in t */
    unsigned char *rimc; /* nv: a boundary vertex that may be a corner (glpgp_surface_rim_corners) */
    unsigned char *turn; /* 3 nt */
    double *off;         /* 3 nt: fan angle offset of the corner */
    int *vnode;          /* nv */
    int *hstart;         /* 3 nt + 1: nodes on the owner half-edge h: hnode[hstart[h] .. hstart[h+1]) */
    int *hnode;
    snode *n;
    int nn, capn;
    sedge *e;
    int ne, cape;
    int inconsistent[2];
    double h; /* the target size: the boundary arcs' chord tolerance */
} sxctx;

static int owner_of(const glpgp_surface *S, int h) { return S->twin[h] < 0 || h < S->twin[h] ? h : S->twin[h]; }
static int nxt(int h) { return h - h % 3 + (h % 3 + 1) % 3; }

static glpgp_status add_node(sxctx *c, int kind, int id, double s, const double *b, unsigned char fam, int *out)
{
    if (c->nn == c->capn) {
        int nc = c->capn ? 2 * c->capn : 1024;
        snode *p = realloc(c->n, (size_t)nc * sizeof *p);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (surface quad graph)");
        c->n = p;
        c->capn = nc;
    }
    snode *n = &c->n[c->nn];
    memset(n, 0, sizeof *n);
    n->kind = kind;
    n->id = id;
    n->s = s;
    if (b) memcpy(n->b, b, sizeof n->b);
    n->fam = fam;
    *out = c->nn++;
    return GLPGP_OK;
}

static glpgp_status add_edge(sxctx *c, int a, int b, int t, int flags)
{
    if (a == b) return GLPGP_OK;
    if (c->ne == c->cape) {
        int nc = c->cape ? 2 * c->cape : 2048;
        sedge *p = realloc(c->e, (size_t)nc * sizeof *p);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (surface quad graph)");
        c->e = p;
        c->cape = nc;
    }
    c->e[c->ne].a = a;
    c->e[c->ne].b = b;
    c->e[c->ne].t = t;
    c->e[c->ne].flags = (unsigned char)flags;
    c->ne++;
    return GLPGP_OK;
}

/* Barycentric coordinates of node i in triangle t (which contains it). */
static void node_bary(const sxctx *c, int i, int t, double *b)
{
    const snode *n = &c->n[i];
    b[0] = b[1] = b[2] = 0.0;
    if (n->kind == SN_IN) {
        memcpy(b, n->b, 3 * sizeof *b);
    } else if (n->kind == SN_VERT) {
        for (int a = 0; a < 3; a++)
            if (c->m->tri[3 * t + a] == n->id) b[a] = 1.0;
    } else if (n->id / 3 == t) {
        b[n->id % 3] = 1.0 - n->s;
        b[(n->id % 3 + 1) % 3] = n->s;
    } else {
        const int tw = c->S->twin[n->id];
        b[tw % 3] = n->s;
        b[(tw % 3 + 1) % 3] = 1.0 - n->s;
    }
}

/* Node i's position in triangle t's plane. */
static void node_2d(const sxctx *c, int i, int t, double *p)
{
    double b[3];
    node_bary(c, i, t, b);
    const double *T = c->S->txy + 6 * t;
    p[0] = b[0] * T[0] + b[1] * T[2] + b[2] * T[4];
    p[1] = b[0] * T[1] + b[1] * T[3] + b[2] * T[5];
}

/* Any triangle that holds node i. */
static int node_tri(const sxctx *c, int i)
{
    const snode *n = &c->n[i];
    if (n->kind == SN_IN) return n->id;
    if (n->kind == SN_EDGE) return n->id / 3;
    return c->S->vstart[n->id] / 3;
}

/* ---- phase 1: charts --------------------------------------------------- */

static void charts(sxctx *c, const glpgp_result *r)
{
    const glpgp_mesh *m = c->m;
    for (int t = 0; t < m->nt; t++) {
        for (int j = 0; j < 3; j++)
            c->turn[3 * t + j] =
                (unsigned char)(r->coupled && r->field ? glpgp_coupled_corner_turn(m, r->field, t, j) & 3 : 0);
        for (int k = 0; k < 2; k++) {
            double th[3];
            for (int j = 0; j < 3; j++) {
                const int v = m->tri[3 * t + j];
                double f[2] = {r->osc[k].z[2 * v], r->osc[k].z[2 * v + 1]};
                if (r->coupled && r->field)
                    glpgp_coupled_frame_value(c->turn[3 * t + j], k, r->osc[0].z + 2 * v, r->osc[1].z + 2 * v, f);
                th[j] = glpgp_theta(f[0], f[1]);
                c->zc[6 * t + 3 * k + j] = th[j] == 0.0;
            }
            glpgp_phase_chart(th, c->ch + 6 * t + 3 * k);
            c->ok[2 * t + k] = glpgp_phase_winding(th) == 0;
        }
    }
}

/* Fan offsets of every corner (the angle from its vertex's reference edge). */
static void fan_offsets(sxctx *c)
{
    const glpgp_surface *S = c->S;
    for (int v = 0; v < c->m->nv; v++) {
        int cc = S->vstart[v];
        double acc = 0.0;
        for (int guard = 0; guard < 3 * c->m->nt; guard++) {
            c->off[cc] = acc;
            acc += S->corner[cc];
            const int in = cc - cc % 3 + (cc % 3 + 2) % 3;
            const int tw = S->twin[in];
            if (tw < 0 || tw == S->vstart[v]) break;
            cc = tw;
        }
    }
}

/* ---- phase 2: vertex and edge nodes ------------------------------------ */

static int cmp_sk(const void *pa, const void *pb)
{
    const double *a = pa, *b = pb;
    return a[0] < b[0] ? -1 : a[0] > b[0] ? 1 : 0;
}

static glpgp_status edge_nodes(sxctx *c)
{
    const glpgp_mesh *m = c->m;
    for (int v = 0; v < m->nv; v++) c->vnode[v] = -1;
    for (int t = 0; t < m->nt; t++)
        for (int j = 0; j < 3; j++) {
            const int v = m->tri[3 * t + j];
            if (c->vnode[v] < 0 && (c->zc[6 * t + j] || c->zc[6 * t + 3 + j] || m->on_boundary[v]))
                GLPGP_CHECK(add_node(c, SN_VERT, v, 0.0, NULL, 0, &c->vnode[v]));
        }
    int cap = 3 * m->nt + 16, cnt = 0;
    GLPGP_CHECK(glpgp_malloc((size_t)cap, sizeof(int), &c->hnode));
    for (int h = 0; h < 3 * m->nt; h++) {
        c->hstart[h] = cnt;
        if (owner_of(c->S, h) != h) continue;
        const int t = h / 3, a = h % 3, b = (a + 1) % 3;
        double sk[16][2];
        int ns = 0;
        for (int k = 0; k < 2; k++) {
            const double cA = c->ch[6 * t + 3 * k + a];
            const double cB = cA + glpgp_phase_step(c->ch[6 * t + 3 * k + b] - cA);
            if (cA == cB) continue;
            const double lo = fmin(cA, cB), hi = fmax(cA, cB);
            for (double n = floor(lo) + 1.0; n < hi && ns < 16; n += 1.0) {
                if (c->zc[6 * t + 3 * k + a] && fabs(n - cA) < 1e-9) continue;
                if (c->zc[6 * t + 3 * k + b] && fabs(n - cB) < 1e-9) continue;
                const double s = (n - cA) / (cB - cA);
                if (!(s > 0.0 && s < 1.0)) continue;
                sk[ns][0] = s;
                sk[ns][1] = k;
                ns++;
            }
        }
        qsort(sk, (size_t)ns, sizeof sk[0], cmp_sk);
        for (int i = 0; i < ns; i++) {
            unsigned char fam = (unsigned char)(1u << (int)sk[i][1]);
            if (cnt > c->hstart[h] && fabs(sk[i][0] - c->n[c->hnode[cnt - 1]].s) < 1e-12) {
                c->n[c->hnode[cnt - 1]].fam |= fam;
                continue;
            }
            if (cnt == cap) {
                cap *= 2;
                int *p = realloc(c->hnode, (size_t)cap * sizeof *p);
                if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (surface quad graph)");
                c->hnode = p;
            }
            GLPGP_CHECK(add_node(c, SN_EDGE, h, sk[i][0], NULL, fam, &c->hnode[cnt]));
            cnt++;
        }
    }
    c->hstart[3 * m->nt] = cnt;
    return GLPGP_OK;
}

/* The graph edges along the mesh half-edge h (first vertex, its X nodes,
 * last vertex), directed along h. */
static glpgp_status edge_run(sxctx *c, int h, int flags)
{
    const int o = owner_of(c->S, h);
    const int P = c->vnode[c->m->tri[h]], Q = c->vnode[c->m->tri[nxt(h)]];
    if (P < 0 || Q < 0) return GLPGP_OK;
    const int n0 = c->hstart[o], n1 = c->hstart[o + 1];
    int prev = P;
    for (int i = 0; i < n1 - n0; i++) {
        const int id = c->hnode[o == h ? n0 + i : n1 - 1 - i];
        GLPGP_CHECK(add_edge(c, prev, id, h / 3, flags));
        prev = id;
    }
    return add_edge(c, prev, Q, h / 3, flags);
}

/* ---- phase 3: chords and grid points ----------------------------------- */

typedef struct ppt {
    double pos;  /* perimeter coordinate: edge j + local parameter */
    int node, label;
} ppt;

typedef struct chord {
    ppt p[2];
    int k, nin;
    double tin[8];
    int in[8];
} chord;

static int cmp_ppt(const void *pa, const void *pb)
{
    const ppt *a = pa, *b = pb;
    if (a->label != b->label) return a->label < b->label ? -1 : 1;
    return a->pos < b->pos ? -1 : a->pos > b->pos ? 1 : 0;
}

/* The perimeter points of family k in triangle t. */
static int perimeter_points(const sxctx *c, int t, int k, ppt *pt, int cap)
{
    const glpgp_surface *S = c->S;
    const double *ch = c->ch + 6 * t + 3 * k;
    int np = 0;
    for (int j = 0; j < 3 && np < cap; j++) {
        if (c->zc[6 * t + 3 * k + j]) pt[np++] = (ppt){(double)j, c->vnode[c->m->tri[3 * t + j]], (int)lround(ch[j])};
        const int h = 3 * t + j, o = owner_of(S, h);
        int kk = k;
        if (o != h) {
            const int ot = o / 3, oc = (o % 3 + 1) % 3; /* the owner's corner of vertex tri[h] */
            if ((c->turn[3 * t + j] - c->turn[3 * ot + oc]) & 1) kk = 1 - k;
        }
        for (int i = c->hstart[o]; i < c->hstart[o + 1] && np < cap; i++) {
            const snode *n = &c->n[c->hnode[i]];
            if (!(n->fam & (1u << kk))) continue;
            const double sl = o == h ? n->s : 1.0 - n->s;
            const double val = ch[j] + sl * (ch[(j + 1) % 3] - ch[j]);
            pt[np++] = (ppt){j + sl, c->hnode[i], (int)lround(val)};
        }
    }
    return np;
}

/* Chords of family k in t; returns their number (0 when the chart does not close). */
static int tri_chords(sxctx *c, int t, int k, chord *out, int cap)
{
    ppt pt[48];
    const int np = perimeter_points(c, t, k, pt, 48);
    qsort(pt, (size_t)np, sizeof pt[0], cmp_ppt);
    int nc = 0;
    for (int i = 0; i < np;) {
        int j = i;
        while (j < np && pt[j].label == pt[i].label) j++;
        const int n = j - i;
        int nv = 0;
        for (int q = i; q < j; q++) nv += pt[q].pos == floor(pt[q].pos) && c->n[pt[q].node].kind == SN_VERT;
        if (n == 2 && nc < cap) {
            out[nc].p[0] = pt[i];
            out[nc].p[1] = pt[i + 1];
            out[nc].k = k;
            out[nc].nin = 0;
            nc++;
        } else if (!(n == 1 || (n == 3 && nv == 3))) {
            c->inconsistent[k]++;
            return 0;
        }
        i = j;
    }
    return nc;
}

/* Is chord a a piece of a mesh edge (both ends vertices of one edge)? */
static int along_edge(const sxctx *c, const chord *a, int *h, int t)
{
    if (c->n[a->p[0].node].kind != SN_VERT || c->n[a->p[1].node].kind != SN_VERT) return 0;
    const int j0 = (int)a->p[0].pos, j1 = (int)a->p[1].pos;
    if ((j0 + 1) % 3 == j1) *h = 3 * t + j0;
    else if ((j1 + 1) % 3 == j0) *h = 3 * t + j1;
    else return 0;
    return 1;
}

static int inside(double x, double lo, double hi) { return x > lo && x < hi; }

/* The grid point of chords a (u) and b (v) in t, if their ends interleave. */
static glpgp_status cross_chords(sxctx *c, int t, chord *a, chord *b)
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            if (a->p[i].node == b->p[j].node) return GLPGP_OK;
    const double lo = fmin(a->p[0].pos, a->p[1].pos), hi = fmax(a->p[0].pos, a->p[1].pos);
    if (inside(b->p[0].pos, lo, hi) == inside(b->p[1].pos, lo, hi)) return GLPGP_OK;
    if (a->nin >= 8 || b->nin >= 8) return GLPGP_OK;
    double A0[2], A1[2], B0[2], B1[2];
    node_2d(c, a->p[0].node, t, A0);
    node_2d(c, a->p[1].node, t, A1);
    node_2d(c, b->p[0].node, t, B0);
    node_2d(c, b->p[1].node, t, B1);
    const double dx = A1[0] - A0[0], dy = A1[1] - A0[1], ex = B1[0] - B0[0], ey = B1[1] - B0[1];
    const double den = dx * ey - dy * ex;
    double ta = 0.5, tb = 0.5;
    if (fabs(den) > 1e-300) {
        ta = ((B0[0] - A0[0]) * ey - (B0[1] - A0[1]) * ex) / den;
        tb = ((B0[0] - A0[0]) * dy - (B0[1] - A0[1]) * dx) / den;
    }
    ta = fmin(fmax(ta, 1e-9), 1.0 - 1e-9);
    tb = fmin(fmax(tb, 1e-9), 1.0 - 1e-9);
    double ba[3], bb[3], bc[3];
    node_bary(c, a->p[0].node, t, ba);
    node_bary(c, a->p[1].node, t, bb);
    for (int q = 0; q < 3; q++) bc[q] = (1.0 - ta) * ba[q] + ta * bb[q];
    int id = -1;
    GLPGP_CHECK(add_node(c, SN_IN, t, 0.0, bc, 0, &id));
    a->tin[a->nin] = ta;
    a->in[a->nin++] = id;
    b->tin[b->nin] = tb;
    b->in[b->nin++] = id;
    return GLPGP_OK;
}

/* The chord's pieces between its end points and grid points, in order. */
static glpgp_status chord_edges(sxctx *c, int t, chord *a)
{
    for (int i = 1; i < a->nin; i++) /* insertion sort by the parameter */
        for (int j = i; j > 0 && a->tin[j] < a->tin[j - 1]; j--) {
            double x = a->tin[j];
            a->tin[j] = a->tin[j - 1];
            a->tin[j - 1] = x;
            int y = a->in[j];
            a->in[j] = a->in[j - 1];
            a->in[j - 1] = y;
        }
    int prev = a->p[0].node;
    for (int i = 0; i < a->nin; i++) {
        GLPGP_CHECK(add_edge(c, prev, a->in[i], t, 0));
        prev = a->in[i];
    }
    return add_edge(c, prev, a->p[1].node, t, 0);
}

static glpgp_status triangle_lines(sxctx *c, int t)
{
    chord ch[2][16];
    int n[2] = {0, 0};
    for (int k = 0; k < 2; k++)
        if (c->ok[2 * t + k]) n[k] = tri_chords(c, t, k, ch[k], 16);
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < n[k]; i++) {
            int h;
            if (along_edge(c, &ch[k][i], &h, t)) {
                GLPGP_CHECK(edge_run(c, h, SE_ALONG));
                ch[k][i].k = -1;
            }
        }
    for (int i = 0; i < n[0]; i++)
        for (int j = 0; j < n[1]; j++)
            if (ch[0][i].k >= 0 && ch[1][j].k >= 0) GLPGP_CHECK(cross_chords(c, t, &ch[0][i], &ch[1][j]));
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < n[k]; i++)
            if (ch[k][i].k >= 0) GLPGP_CHECK(chord_edges(c, t, &ch[k][i]));
    return GLPGP_OK;
}

/* ---- phase 4: duplicates, pruning -------------------------------------- */

static int cmp_sedge(const void *pa, const void *pb)
{
    const sedge *a = pa, *b = pb;
    int a0 = a->a < a->b ? a->a : a->b, a1 = a->a ^ a->b ^ a0;
    int b0 = b->a < b->b ? b->a : b->b, b1 = b->a ^ b->b ^ b0;
    if (a0 != b0) return a0 < b0 ? -1 : 1;
    if (a1 != b1) return a1 < b1 ? -1 : 1;
    return (int)(b->flags & SE_BND) - (int)(a->flags & SE_BND);
}

static void dedupe(sxctx *c)
{
    if (c->ne > 1) qsort(c->e, (size_t)c->ne, sizeof *c->e, cmp_sedge);
    int w = 0;
    for (int i = 0; i < c->ne; i++) {
        if (w > 0 && cmp_sedge(&c->e[w - 1], &c->e[i]) <= 0 &&
            ((c->e[w - 1].a == c->e[i].a && c->e[w - 1].b == c->e[i].b) ||
             (c->e[w - 1].a == c->e[i].b && c->e[w - 1].b == c->e[i].a))) {
            c->e[w - 1].flags |= c->e[i].flags & SE_ALONG;
            continue;
        }
        c->e[w++] = c->e[i];
    }
    c->ne = w;
}

static glpgp_status prune(sxctx *c, int *deg)
{
    for (int i = 0; i < c->nn; i++) deg[i] = 0;
    for (int e = 0; e < c->ne; e++) {
        deg[c->e[e].a]++;
        deg[c->e[e].b]++;
    }
    for (int changed = 1; changed;) { /* few rounds: dangling lines are short */
        changed = 0;
        for (int e = 0; e < c->ne; e++) {
            sedge *E = &c->e[e];
            if (E->flags & SE_DEL || E->flags & SE_BND) continue;
            if (deg[E->a] == 1 || deg[E->b] == 1) {
                E->flags |= SE_DEL;
                deg[E->a]--;
                deg[E->b]--;
                changed = 1;
            }
        }
    }
    int w = 0;
    for (int e = 0; e < c->ne; e++)
        if (!(c->e[e].flags & SE_DEL)) c->e[w++] = c->e[e];
    c->ne = w;
    return GLPGP_OK;
}

/* ---- phase 5: rotation system and faces -------------------------------- */

static double angle_from(const double *E, const double *D)
{
    return atan2(E[0] * D[1] - E[1] * D[0], E[0] * D[0] + E[1] * D[1]);
}

/* The angle key of the half-edge from node i to node j along graph edge e. */
static double he_key(const sxctx *c, int i, int j, const sedge *e)
{
    const int t = e->t;
    const snode *n = &c->n[i];
    double P[2], Q[2], D[2];
    node_2d(c, i, t, P);
    node_2d(c, j, t, Q);
    D[0] = Q[0] - P[0];
    D[1] = Q[1] - P[1];
    const double *T = c->S->txy + 6 * t;
    if (n->kind == SN_IN) return atan2(D[1], D[0]);
    if (n->kind == SN_EDGE) {
        const int o = n->id;
        int a, b; /* t's corners of the owner half-edge's two vertices */
        if (o / 3 == t) {
            a = o % 3;
            b = (a + 1) % 3;
        } else {
            b = c->S->twin[o] % 3;
            a = (b + 1) % 3;
        }
        const double E[2] = {T[2 * b] - T[2 * a], T[2 * b + 1] - T[2 * a + 1]};
        if (e->flags & (SE_BND | SE_ALONG)) return E[0] * D[0] + E[1] * D[1] > 0 ? 0.0 : PI_;
        double ang = angle_from(E, D);
        if (o / 3 == t) return fmin(fmax(ang, 1e-12), PI_ - 1e-12);
        ang = fmin(fmax(ang, -PI_ + 1e-12), -1e-12);
        return 2.0 * PI_ + ang;
    }
    int a = 0;
    while (a < 3 && c->m->tri[3 * t + a] != n->id) a++;
    const int cc = 3 * t + a, a1 = (a + 1) % 3;
    if (e->flags & (SE_BND | SE_ALONG)) {
        double bq[3];
        node_bary(c, j, t, bq);
        return bq[a1] > 0.0 && bq[(a + 2) % 3] == 0.0 ? c->off[cc] : c->off[cc] + c->S->corner[cc];
    }
    const double O[2] = {T[2 * a1] - T[2 * a], T[2 * a1 + 1] - T[2 * a + 1]};
    const double ang = fmin(fmax(angle_from(O, D), 1e-12), c->S->corner[cc] - 1e-12);
    return c->off[cc] + ang;
}

typedef struct hkey {
    int orig, h;
    double key;
} hkey;

static int cmp_hkey(const void *pa, const void *pb)
{
    const hkey *a = pa, *b = pb;
    if (a->orig != b->orig) return a->orig < b->orig ? -1 : 1;
    return a->key < b->key ? -1 : a->key > b->key ? 1 : 0;
}

/* Node i's 3D position (barycentric in a triangle that holds it). */
static void node_xyz(const sxctx *c, int i, double *X)
{
    const int t = node_tri(c, i);
    double b[3];
    node_bary(c, i, t, b);
    for (int d = 0; d < 3; d++) {
        X[d] = 0.0;
        for (int a = 0; a < 3; a++) X[d] += b[a] * c->m->xyz[3 * c->m->tri[3 * t + a] + d];
    }
}

/* Distance from p to the segment ab in 3D. */
static double seg_dist(const double *p, const double *a, const double *b)
{
    double ab[3], ap[3];
    sub3(b, a, ab);
    sub3(p, a, ap);
    const double l2 = dot3(ab, ab), t = l2 > 0.0 ? fmin(fmax(dot3(ab, ap) / l2, 0.0), 1.0) : 0.0;
    for (int d = 0; d < 3; d++) ap[d] -= t * ab[d];
    return sqrt(dot3(ap, ap));
}

/* Corners on the boundary arc loop[i0 .. i1] (indices into the loop's n
 * nodes, cyclic; xyz their positions): the node farthest from the chord
 * when it is over tol away, then both halves the same way
 * (Douglas-Peucker). */
static void arc_corners(const int *loop, const double *xyz, int n, int i0, int i1, double tol, unsigned char *corner)
{
    int far = -1;
    double dmax = tol;
    for (int k = (i0 + 1) % n; k != i1; k = (k + 1) % n) {
        const double d = seg_dist(xyz + 3 * k, xyz + 3 * i0, xyz + 3 * i1);
        if (d > dmax) {
            dmax = d;
            far = k;
        }
    }
    if (far < 0) return;
    corner[loop[far]] = 1;
    arc_corners(loop, xyz, n, i0, far, tol, corner);
    arc_corners(loop, xyz, n, far, i1, tol, corner);
}

/* A face's side along a boundary loop is drawn as the chord between its
 * corners: where the loop curves tightly (a hole about h across: a few
 * faces around it, each with a long arc), the chord crosses the hole, and
 * the face is far from the surface (the check's Hausdorff distance, which
 * no repair of the grid's faces can fix: they are all valid quads). Here
 * the boundary nodes between two corners become corners where the arc
 * strays over QX_RIM_CHORD h from the chord (Douglas-Peucker), so the sides follow
 * the loop; the faces gain corners (odd or even faces: the closing makes
 * them quads). A loop that no grid line reaches (no corner) is left. */
static glpgp_status rim_corners(const sxctx *c, const int *deg, unsigned char *corner)
{
    if (!(c->h > 0.0)) return GLPGP_OK;
    int *next = NULL, *loop = NULL;
    unsigned char *seen = NULL;
    double *xyz = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)c->nn + 1, sizeof(int), &next), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)c->nn + 1, sizeof(int), &loop), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)c->nn + 1, 1, &seen), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * c->nn + 3, sizeof(double), &xyz), done);
    for (int i = 0; i < c->nn; i++) next[i] = -1;
    for (int e = 0; e < c->ne; e++)
        if (c->e[e].flags & SE_BND) next[c->e[e].a] = c->e[e].b; /* along the loop */
    for (int s0 = 0; s0 < c->nn; s0++) {
        if (next[s0] < 0 || seen[s0]) continue;
        int n = 0, first = -1;
        for (int i = s0; i >= 0 && !seen[i] && n < c->nn; i = next[i]) {
            seen[i] = 1;
            loop[n] = i;
            node_xyz(c, i, xyz + 3 * n);
            if (first < 0 && (corner[i] || deg[i] >= 3)) first = n;
            n++;
        }
        if (first < 0 || n < 3) continue;
        int prev = first;
        for (int k = 1; k <= n; k++) {
            const int j = (first + k) % n;
            if (!corner[loop[j]] && k < n) continue;
            arc_corners(loop, xyz, n, prev, j, QX_RIM_CHORD * c->h, corner);
            prev = j;
        }
    }
done:
    free(next);
    free(loop);
    free(seen);
    free(xyz);
    return st;
}

/* Output: the faces of the map (inner ones), their corner nodes. */
static glpgp_status trace_faces(sxctx *c, const int *deg, glpgp_quadmesh *q)
{
    const int nh = 2 * c->ne;
    hkey *hk = NULL;
    int *rot_pos = NULL, *rstart = NULL, *face = NULL, *vmap = NULL, *poly = NULL;
    unsigned char *corner = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof *hk, &hk), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof(int), &rot_pos), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)c->nn + 1, sizeof(int), &rstart), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof(int), &face), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)c->nn + 1, sizeof(int), &vmap), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh + 1, sizeof(int), &poly), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)c->nn + 1, 1, &corner), done);
    for (int h = 0; h < nh; h++) {
        const sedge *e = &c->e[h >> 1];
        const int o = h & 1 ? e->b : e->a, d = h & 1 ? e->a : e->b;
        hk[h] = (hkey){o, h, he_key(c, o, d, e)};
        rstart[o + 1]++;
    }
    for (int i = 0; i < c->nn; i++) rstart[i + 1] += rstart[i];
    qsort(hk, (size_t)nh, sizeof *hk, cmp_hkey);
    for (int i = 0; i < nh; i++) rot_pos[hk[i].h] = i;
    for (int i = 0; i < c->nn; i++) {
        const snode *n = &c->n[i];
        corner[i] = deg[i] >= 3;
        if (deg[i] == 2 && n->kind == SN_VERT && c->rimc[n->id] && /* rimc: on the boundary */
            fabs(c->S->angle_sum[n->id] - PI_) > GLPGP_CORNER_DEG * PI_ / 180.0)
            corner[i] = 1;
    }
    GLPGP_CHECK_GOTO(st, rim_corners(c, deg, corner), done);
    for (int h = 0; h < nh; h++) face[h] = -1;
    for (int i = 0; i < c->nn; i++) vmap[i] = -1;
    int nf = 0, nfv = 0, nvout = 0, capf = 1024, capv = 4096;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)capf + 1, sizeof(int), &q->face_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)capv, sizeof(int), &q->face_vert), done);
    q->face_start[0] = 0;
    for (int h0 = 0; h0 < nh; h0++) {
        if (face[h0] >= 0) continue;
        int np = 0, outer = 0, h = h0, guard = 0;
        do {
            face[h] = nf;
            const sedge *e = &c->e[h >> 1];
            if ((e->flags & SE_BND) && (h & 1)) outer = 1;
            const int d = h & 1 ? e->a : e->b;
            if (corner[d]) poly[np++] = d;
            const int tw = h ^ 1, p = rot_pos[tw], o = hk[p].orig;
            const int prev = p == rstart[o] ? rstart[o + 1] - 1 : p - 1;
            h = hk[prev].h;
        } while (h != h0 && ++guard < nh);
        if (outer || np < 3) continue;
        if (nf + 1 >= capf) {
            capf *= 2;
            int *p = realloc(q->face_start, (size_t)(capf + 1) * sizeof *p);
            if (!p) GLPGP_CHECK_GOTO(st, GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (surface quads)"), done);
            q->face_start = p;
        }
        if (nfv + np > capv) {
            while (nfv + np > capv) capv *= 2;
            int *p = realloc(q->face_vert, (size_t)capv * sizeof *p);
            if (!p) GLPGP_CHECK_GOTO(st, GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (surface quads)"), done);
            q->face_vert = p;
        }
        for (int i = 0; i < np; i++) {
            if (vmap[poly[i]] < 0) vmap[poly[i]] = nvout++;
            q->face_vert[nfv++] = vmap[poly[i]];
        }
        q->face_start[++nf] = nfv;
    }
    q->nf = nf;
    q->nv = nvout;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nvout + 1, sizeof(double), &q->xyz), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nvout + 1, sizeof(double), &q->xy), done);
    for (int i = 0; i < c->nn; i++) {
        if (vmap[i] < 0) continue;
        double *X = q->xyz + 3 * vmap[i];
        node_xyz(c, i, X);
        q->xy[2 * vmap[i]] = X[0];
        q->xy[2 * vmap[i] + 1] = X[1];
    }
done:
    free(hk);
    free(rot_pos);
    free(rstart);
    free(face);
    free(vmap);
    free(poly);
    free(corner);
    return st;
}

/* ---- entry ------------------------------------------------------------- */

static void ctx_free(sxctx *c)
{
    free(c->ch);
    free(c->zc);
    free(c->ok);
    free(c->turn);
    free(c->rimc);
    free(c->off);
    free(c->vnode);
    free(c->hstart);
    free(c->hnode);
    free(c->n);
    free(c->e);
}

static glpgp_status build_graph(sxctx *c, const glpgp_result *r)
{
    const glpgp_mesh *m = c->m;
    const size_t nt = (size_t)m->nt;
    GLPGP_CHECK(glpgp_malloc(6 * nt, sizeof(double), &c->ch));
    GLPGP_CHECK(glpgp_calloc(6 * nt, 1, &c->zc));
    GLPGP_CHECK(glpgp_calloc(2 * nt, 1, &c->ok));
    GLPGP_CHECK(glpgp_calloc(3 * nt, 1, &c->turn));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, 1, &c->rimc));
    /* h / 2 on whatever mesh: solve --quads (a refined mesh that kept its
     * input) and extract (the refined mesh alone) read the same corners */
    GLPGP_CHECK(glpgp_surface_rim_corners(m, GLPGP_RIM_SCALE * fmax(c->h, 0.0), GLPGP_CORNER_DEG * PI_ / 180.0,
                                          c->rimc));
    GLPGP_CHECK(glpgp_calloc(3 * nt, sizeof(double), &c->off));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(int), &c->vnode));
    GLPGP_CHECK(glpgp_malloc(3 * nt + 1, sizeof(int), &c->hstart));
    charts(c, r);
    fan_offsets(c);
    GLPGP_CHECK(edge_nodes(c));
    for (int h = 0; h < 3 * m->nt; h++)
        if (c->S->twin[h] < 0) GLPGP_CHECK(edge_run(c, h, SE_BND));
    for (int t = 0; t < m->nt; t++) GLPGP_CHECK(triangle_lines(c, t));
    dedupe(c);
    return GLPGP_OK;
}

glpgp_status glpgp_quads_extract_surface(const glpgp_mesh *m, const glpgp_result *r, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!glpgp_mesh_is_surface(m) || !m->surf)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "surface quad extraction: the mesh is not a surface");
    if (!r || r->nv != m->nv || r->nt != m->nt)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "surface quad extraction: the result does not match the mesh");
    if (!r->osc[0].z || !r->osc[1].z) return GLPGP_FAIL(GLPGP_ERR_FORMAT, "surface quad extraction: no oscillators");
    sxctx c;
    memset(&c, 0, sizeof c);
    c.m = m;
    c.S = m->surf;
    c.h = r->size;
    glpgp_quadmesh *q = NULL;
    int *deg = NULL;
    glpgp_status st = build_graph(&c, r);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)c.nn + 1, sizeof(int), &deg);
    if (st == GLPGP_OK) st = prune(&c, deg);
    if (st == GLPGP_OK) st = glpgp_calloc(1, sizeof *q, &q);
    if (st == GLPGP_OK) st = trace_faces(&c, deg, q);
    if (st == GLPGP_OK && q->nf == 0) st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "surface quad extraction: no face");
    if (st == GLPGP_OK) {
        for (int k = 0; k < 2; k++) {
            q->inconsistent_tris[k] = c.inconsistent[k];
            for (int t = 0; t < m->nt; t++) q->singular_tris[k] += !c.ok[2 * t + k];
        }
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: surface extraction: %d nodes, %d graph edges, %d faces; singular triangles u %d v %d, "
                  "charts not closing u %d v %d",
                  c.nn, c.ne, q->nf, q->singular_tris[0], q->singular_tris[1], c.inconsistent[0], c.inconsistent[1]);
        *out = q;
        q = NULL;
    }
    glpgp_quadmesh_destroy(&q);
    free(deg);
    ctx_free(&c);
    return st;
}
