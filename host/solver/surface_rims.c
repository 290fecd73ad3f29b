/* solver/surface_rims.c: a surface's boundary crosses at the scale of the
 * mesh to be made (glpgp_surface_constraints_rims, glpgp/surfsolve.h).
 *
 * A boundary vertex's cross is the mean of its two edges' crosses. On a rim
 * cut through triangles (a scan's hole, a mesh clipped by a curve) most
 * vertices turn by 45-135 degrees between their two edges, and that mean
 * lands 45 degrees off the curve the rim follows, tooth by tooth: the cross
 * field then follows every tooth and both oscillators are fixed at many rim
 * vertices. Here each loop is walked by arc length; a vertex's edges are
 * replaced by the chords to the rim points `scale` behind and ahead of it,
 * stopped at the corners at that scale. */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>

#define CORNER_TURN (GLPGP_PI / 3.0) /* the constraints' corners: a turn at the scale (a right angle's: 74 degrees) */

/* one boundary loop, walked along its boundary half-edges */
typedef struct {
    const glpgp_mesh *m;
    const int *v;    /* n vertices in order */
    const double *s; /* n + 1 arc lengths: s[0] = 0, s[n] = perimeter */
    int n;
} rim;

/* The vertex after v along its loop (its fan's outgoing boundary edge). */
static int rim_next(const glpgp_mesh *m, int v)
{
    const int c = m->surf->vstart[v];
    return m->tri[c - c % 3 + (c % 3 + 1) % 3];
}

static void sub3(const double *a, const double *b, double *d)
{
    for (int k = 0; k < 3; k++) d[k] = a[k] - b[k];
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double *a, const double *b, double *d)
{
    d[0] = a[1] * b[2] - a[2] * b[1];
    d[1] = a[2] * b[0] - a[0] * b[2];
    d[2] = a[0] * b[1] - a[1] * b[0];
}

/* the length of the segment from the loop's vertex a to the next */
static double seg_len(const rim *r, int a) { return r->s[a + 1] - r->s[a]; }

/* p <- the rim's point at arc length t (taken modulo the perimeter) */
static void rim_point(const rim *r, double t, double *p)
{
    const double len = r->s[r->n];
    t = fmod(t, len);
    if (t < 0.0) t += len;
    int lo = 0, hi = r->n; /* s[lo] <= t < s[hi] */
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (r->s[mid] <= t) lo = mid;
        else hi = mid;
    }
    const double *a = r->m->xyz + 3 * r->v[lo], *b = r->m->xyz + 3 * r->v[(lo + 1) % r->n];
    const double seg = r->s[lo + 1] - r->s[lo], f = seg > 0.0 ? (t - r->s[lo]) / seg : 0.0;
    for (int k = 0; k < 3; k++) p[k] = a[k] + f * (b[k] - a[k]);
}

/* p <- the rim's mean point over the arc [t - w, t + w] (w > 0, 2 w at
 * most the perimeter): the integral of its segments, clipped to the arc */
static void rim_mean(const rim *r, double t, double w, double *p)
{
    const double len = r->s[r->n];
    double a = fmod(t - w, len);
    if (a < 0.0) a += len;
    double left = 2.0 * w, base = 0.0;
    int k = 0;
    while (k + 1 < r->n && r->s[k + 1] <= a) k++;
    p[0] = p[1] = p[2] = 0.0;
    for (int step = 0; left > 0.0 && step <= r->n; step++) {
        const double *x = r->m->xyz + 3 * r->v[k], *y = r->m->xyz + 3 * r->v[(k + 1) % r->n];
        const double s0 = base + r->s[k], seg = seg_len(r, k), t0 = fmax(a, s0), t1 = fmin(a + left, s0 + seg);
        if (t1 > t0 && seg > 0.0) {
            const double f = (0.5 * (t0 + t1) - s0) / seg;
            for (int i = 0; i < 3; i++) p[i] += (t1 - t0) * (x[i] + f * (y[i] - x[i]));
            left -= t1 - t0;
            a = t1;
        }
        if (++k == r->n) {
            k = 0;
            base += len;
        }
    }
    const double got = 2.0 * w - left;
    if (got > 0.0)
        for (int i = 0; i < 3; i++) p[i] /= got;
    else
        rim_point(r, t, p);
}

/* vertex k's turn at the scale len: between the rim's mean points (over
 * len) len behind, at and len ahead of it, so that teeth finer than len
 * do not make one */
static double rim_turn(const rim *r, int k, double len)
{
    double p0[3], p1[3], p2[3], a[3], b[3], x[3];
    rim_mean(r, r->s[k] - len, 0.5 * len, p0);
    rim_mean(r, r->s[k], 0.5 * len, p1);
    rim_mean(r, r->s[k] + len, 0.5 * len, p2);
    sub3(p1, p0, a);
    sub3(p2, p1, b);
    cross3(a, b, x);
    return atan2(sqrt(dot3(x, x)), dot3(a, b));
}

/* the chords into vertex k (from the point `back` behind it) and out of it
 * (to the point `ahead` ahead) */
static void rim_chords(const rim *r, int k, double back, double ahead, double *cin, double *cout)
{
    double p[3];
    const double *q = r->m->xyz + 3 * r->v[k];
    rim_point(r, r->s[k] - back, p);
    sub3(q, p, cin);
    rim_point(r, r->s[k] + ahead, p);
    sub3(p, q, cout);
}

/* The angle in vertex v's frame of direction d (3D): its turn from v's
 * outgoing boundary edge about the vertex normal, added to that edge's angle. */
static double frame_angle(const glpgp_mesh *m, int v, const double *d)
{
    const glpgp_surface *s = m->surf;
    const double *n = s->vnormal + 3 * v;
    double e[3], x[3];
    sub3(m->xyz + 3 * rim_next(m, v), m->xyz + 3 * v, e);
    cross3(e, d, x);
    return s->eangle[s->vstart[v]] + atan2(dot3(n, x), dot3(e, d) - dot3(e, n) * dot3(d, n));
}

/* the loop's length scale: `scale`, at most a quarter of the loop (0: too
 * short a loop to smooth) */
static double rim_len(const rim *r, double scale)
{
    const double len = fmin(scale, 0.25 * r->s[r->n]);
    return len > 0.0 && r->n >= 4 ? len : 0.0;
}

/* Corners at the scale: a vertex whose turn is min_turn or more, the most
 * within `len` of it (ties: the first). turn: the loop's turns (rim_turn;
 * HUGE_VAL: a corner whatever the scale). */
static void rim_corners(const rim *r, double len, double min_turn, const double *turn, unsigned char *corner)
{
    for (int k = 0; k < r->n; k++) {
        int keep = turn[k] >= min_turn;
        for (int dir = -1; dir <= 1 && keep; dir += 2) {
            double arc = 0.0;
            for (int j = k, step = 1; step < r->n; step++) {
                const int i = (j + dir + r->n) % r->n;
                arc += seg_len(r, dir > 0 ? j : i);
                if (arc >= len) break;
                if (turn[i] > turn[k] || (turn[i] == turn[k] && i < k)) keep = 0;
                j = i;
            }
        }
        corner[k] = (unsigned char)keep;
    }
}

/* the arc length from vertex k to the nearest corner in direction dir
 * (+1 ahead, -1 behind), at most len */
static double rim_reach(const rim *r, const unsigned char *corner, int k, int dir, double len)
{
    double arc = 0.0;
    for (int j = k, step = 1; step < r->n; step++) {
        const int i = (j + dir + r->n) % r->n;
        arc += seg_len(r, dir > 0 ? j : i);
        if (arc >= len) return len;
        if (corner[i]) return arc;
        j = i;
    }
    return len;
}

/* one loop's plain vertices: their crosses from the clipped chords */
static void rim_apply(const rim *r, glpgp_surface_constraints *c, double len, double *turn, unsigned char *corner)
{
    for (int k = 0; k < r->n; k++) {
        const int v = r->v[k];
        turn[k] = c->cptr[v + 1] - c->cptr[v] != 2 ? HUGE_VAL : rim_turn(r, k, len);
    }
    rim_corners(r, len, CORNER_TURN, turn, corner); /* a feature edge meeting the rim: one */
    for (int k = 0; k < r->n; k++) {
        const int v = r->v[k];
        if (c->cptr[v + 1] - c->cptr[v] != 2) continue;
        double cin[3], cout[3];
        rim_chords(r, k, rim_reach(r, corner, k, -1, len), rim_reach(r, corner, k, 1, len), cin, cout);
        if (!(dot3(cin, cin) > 0.0) || !(dot3(cout, cout) > 0.0)) continue;
        if (!corner[k]) /* the curve's tangent: the chord from the point behind to the one ahead */
            for (int i = 0; i < 3; i++) cin[i] = cout[i] = cin[i] + cout[i];
        const double a1 = frame_angle(r->m, v, cin), a2 = frame_angle(r->m, v, cout);
        glpgp_surface_fix_cross(c, v, a1, a2);
        c->cangle[c->cptr[v]] = a2;                /* as the edges': the outgoing one's direction */
        c->cangle[c->cptr[v] + 1] = a1 + GLPGP_PI; /* and the incoming one's, pointing back */
    }
}

/* The boundary loops of m one by one (their vertices and arc lengths), with
 * the loop's length scale, into fn(r, len, ctx); loops too short skipped. */
typedef void (*rim_fn)(const rim *r, double len, void *ctx);

static glpgp_status rim_walk(const glpgp_mesh *m, double scale, rim_fn fn, void *ctx)
{
    int nb = 0;
    for (int v = 0; v < m->nv; v++) nb += m->on_boundary[v] != 0;
    if (!(scale > 0.0) || nb == 0) return GLPGP_OK;
    glpgp_status st = GLPGP_OK;
    int *order = NULL;
    double *s = NULL;
    unsigned char *seen = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nb, sizeof(int), &order), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nb + 1, sizeof(double), &s), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)m->nv, 1, &seen), done);
    for (int v0 = 0; v0 < m->nv; v0++) {
        if (!m->on_boundary[v0] || seen[v0]) continue;
        int n = 0;
        s[0] = 0.0;
        for (int v = v0; !seen[v] && n < nb; v = rim_next(m, v)) {
            double e[3];
            seen[v] = 1;
            order[n] = v;
            sub3(m->xyz + 3 * rim_next(m, v), m->xyz + 3 * v, e);
            s[n + 1] = s[n] + sqrt(dot3(e, e));
            n++;
        }
        const rim r = {m, order, s, n};
        const double len = rim_len(&r, scale);
        if (len > 0.0) fn(&r, len, ctx);
    }
done:
    free(order);
    free(s);
    free(seen);
    return st;
}

typedef struct {
    glpgp_surface_constraints *c;
    double *turn;
    unsigned char *corner;
} apply_ctx;

static void apply_loop(const rim *r, double len, void *ctx)
{
    apply_ctx *a = ctx;
    rim_apply(r, a->c, len, a->turn, a->corner);
}

glpgp_status glpgp_surface_constraints_rims(const glpgp_mesh *m, double scale, glpgp_surface_constraints *c)
{
    if (!m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "rim constraints of a planar mesh");
    if (!(scale >= 0.0) || !isfinite(scale)) return GLPGP_FAIL(GLPGP_ERR_ARG, "rim scale %g", scale);
    c->rim_scale = scale;
    if (scale == 0.0) return GLPGP_OK;
    apply_ctx a = {c, NULL, NULL};
    glpgp_status st = glpgp_malloc((size_t)m->nv, sizeof(double), &a.turn);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)m->nv, 1, &a.corner);
    if (st == GLPGP_OK) st = rim_walk(m, scale, apply_loop, &a);
    free(a.turn);
    free(a.corner);
    return st;
}

static void turn_loop(const rim *r, double len, void *ctx)
{
    double *turn = ctx;
    for (int k = 0; k < r->n; k++) turn[r->v[k]] = rim_turn(r, k, len);
}

glpgp_status glpgp_surface_rim_turns(const glpgp_mesh *m, double scale, double *turn)
{
    if (!m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "rim turns of a planar mesh");
    for (int v = 0; v < m->nv; v++) turn[v] = m->on_boundary[v] ? HUGE_VAL : 0.0;
    return rim_walk(m, scale, turn_loop, turn);
}

typedef struct {
    double min_turn, *turn;
    unsigned char *corner, *out;
} corner_ctx;

static void corner_loop(const rim *r, double len, void *ctx)
{
    corner_ctx *a = ctx;
    for (int k = 0; k < r->n; k++) a->turn[k] = rim_turn(r, k, len);
    rim_corners(r, len, a->min_turn, a->turn, a->corner);
    for (int k = 0; k < r->n; k++) a->out[r->v[k]] = a->corner[k];
}

glpgp_status glpgp_surface_rim_corners(const glpgp_mesh *m, double scale, double min_turn, unsigned char *corner)
{
    if (!m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "rim corners of a planar mesh");
    for (int v = 0; v < m->nv; v++) corner[v] = m->on_boundary[v] != 0;
    corner_ctx a = {min_turn, NULL, NULL, corner};
    glpgp_status st = glpgp_malloc((size_t)m->nv, sizeof(double), &a.turn);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)m->nv, 1, &a.corner);
    if (st == GLPGP_OK) st = rim_walk(m, scale, corner_loop, &a);
    free(a.turn);
    free(a.corner);
    return st;
}

double glpgp_surface_rim_scale(const glpgp_mesh *m, double f, double h)
{
    if (!(f > 0.0)) return 0.0;
    const glpgp_mesh *mi = m->surf && m->surf->origin ? m->surf->origin : m;
    double len = 0.0;
    int n = 0;
    if (!mi->xyz) return 0.0;
    for (int v = 0; v < mi->nv; v++) {
        if (!mi->on_boundary[v] || !mi->surf) continue;
        double e[3];
        sub3(mi->xyz + 3 * rim_next(mi, v), mi->xyz + 3 * v, e);
        len += sqrt(dot3(e, e));
        n++;
    }
    return n ? fmax(f * h, GLPGP_RIM_EDGES * len / n) : 0.0;
}
