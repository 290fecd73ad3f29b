/* quads/quads_surface.c: the quad pipeline on a 3D surface
 * (glpgp_quads_build_surface, glpgp/quads.h): the extraction
 * (extract_surface.c), one Catmull-Clark split in 3D when it left faces
 * that are not quads, the check (check_surface.c), and the last resort
 * that cannot fail: the input triangles split into three quads each. */
#include "quads_surface.h"

#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static glpgp_status qalloc(int nv, int nf, int ncorner, glpgp_quadmesh **out)
{
    glpgp_quadmesh *q = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *q, &q));
    q->nv = nv;
    q->nf = nf;
    glpgp_status st = glpgp_malloc((size_t)3 * nv + 1, sizeof(double), &q->xyz);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)2 * nv + 1, sizeof(double), &q->xy);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nf + 1, sizeof(int), &q->face_start);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)ncorner + 1, sizeof(int), &q->face_vert);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nf + 1, 1, &q->face_origin);
    if (st != GLPGP_OK) {
        glpgp_quadmesh_destroy(&q);
        return st;
    }
    *out = q;
    return GLPGP_OK;
}

static void set_xy(glpgp_quadmesh *q)
{
    for (int i = 0; i < q->nv; i++) {
        q->xy[2 * i] = q->xyz[3 * i];
        q->xy[2 * i + 1] = q->xyz[3 * i + 1];
    }
}

glpgp_status glpgp_quads_surface_fallback(const glpgp_mesh *m, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!glpgp_mesh_is_surface(m) || !m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "surface fallback: not a surface");
    const glpgp_surface *S = m->surf;
    int *emid = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * m->nt, sizeof(int), &emid));
    int nv = m->nv;
    for (int h = 0; h < 3 * m->nt; h++)
        if (S->twin[h] < 0 || h < S->twin[h]) emid[h] = nv++;
    for (int h = 0; h < 3 * m->nt; h++)
        if (!(S->twin[h] < 0 || h < S->twin[h])) emid[h] = emid[S->twin[h]];
    const int nc = nv;
    nv += m->nt;
    glpgp_quadmesh *q = NULL;
    glpgp_status st = qalloc(nv, 3 * m->nt, 12 * m->nt, &q);
    if (st != GLPGP_OK) {
        free(emid);
        return st;
    }
    memcpy(q->xyz, m->xyz, (size_t)3 * m->nv * sizeof(double));
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        for (int a = 0; a < 3; a++) {
            const int h = 3 * t + a, b = (a + 1) % 3;
            for (int d = 0; d < 3; d++) {
                q->xyz[3 * emid[h] + d] = 0.5 * (m->xyz[3 * v[a] + d] + m->xyz[3 * v[b] + d]);
                q->xyz[3 * (nc + t) + d] = (m->xyz[3 * v[0] + d] + m->xyz[3 * v[1] + d] + m->xyz[3 * v[2] + d]) / 3.0;
            }
        }
        for (int a = 0; a < 3; a++) {
            const int f = 3 * t + a;
            q->face_start[f] = 4 * f;
            q->face_vert[4 * f] = v[a];
            q->face_vert[4 * f + 1] = emid[3 * t + a];
            q->face_vert[4 * f + 2] = nc + t;
            q->face_vert[4 * f + 3] = emid[3 * t + (a + 2) % 3];
            q->face_origin[f] = GLPGP_QFACE_FALLBACK;
        }
    }
    q->face_start[q->nf] = 4 * q->nf;
    set_xy(q);
    free(emid);
    *out = q;
    return GLPGP_OK;
}

static int cmp_ll(const void *pa, const void *pb)
{
    const long long *a = pa, *b = pb;
    return a[0] < b[0] ? -1 : a[0] > b[0] ? 1 : 0;
}

glpgp_status glpgp_quadmesh_subdivide_surface(const glpgp_quadmesh *q, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!q || !q->xyz || q->nf == 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "surface subdivision: an empty or planar mesh");
    const int nc = q->face_start[q->nf];
    long long *key = NULL; /* (edge key, corner) pairs */
    int *mid = NULL;
    glpgp_quadmesh *r = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nc + 2, sizeof(long long), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &mid), done);
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            key[2 * (s + i)] = a < b ? a * q->nv + b : b * q->nv + a;
            key[2 * (s + i) + 1] = s + i;
        }
    }
    qsort(key, (size_t)nc, 2 * sizeof(long long), cmp_ll);
    int nv = q->nv;
    for (int i = 0; i < nc; i++) {
        if (i == 0 || key[2 * i] != key[2 * i - 2]) nv++;
        mid[key[2 * i + 1]] = nv - 1;
    }
    const int nedge_v = nv;
    nv += q->nf;
    GLPGP_CHECK_GOTO(st, qalloc(nv, nc, 4 * nc, &r), done);
    memcpy(r->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
    for (int f = 0, o = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s, c = nedge_v + f;
        for (int d = 0; d < 3; d++) r->xyz[3 * c + d] = 0.0;
        for (int i = 0; i < n; i++) {
            const int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            for (int d = 0; d < 3; d++) {
                r->xyz[3 * mid[s + i] + d] = 0.5 * (q->xyz[3 * a + d] + q->xyz[3 * b + d]);
                r->xyz[3 * c + d] += q->xyz[3 * a + d] / n;
            }
        }
        for (int i = 0; i < n; i++, o++) {
            r->face_start[o] = 4 * o;
            r->face_vert[4 * o] = q->face_vert[s + i];
            r->face_vert[4 * o + 1] = mid[s + i];
            r->face_vert[4 * o + 2] = c;
            r->face_vert[4 * o + 3] = mid[s + (i + n - 1) % n];
            r->face_origin[o] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        }
    }
    r->face_start[nc] = 4 * nc;
    set_xy(r);
    memcpy(r->singular_tris, q->singular_tris, sizeof r->singular_tris);
    memcpy(r->inconsistent_tris, q->inconsistent_tris, sizeof r->inconsistent_tris);
    *out = r;
    r = NULL;
done:
    glpgp_quadmesh_destroy(&r);
    free(key);
    free(mid);
    return st;
}

/* ---- closing: a triangle and a pentagon sharing an edge, even faces ---- */

static double sj4(const double *xyz, const int *v)
{
    double N[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
        const double *a = xyz + 3 * v[i], *b = xyz + 3 * v[(i + 1) % 4];
        N[0] += (a[1] - b[1]) * (a[2] + b[2]);
        N[1] += (a[2] - b[2]) * (a[0] + b[0]);
        N[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double nn = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    if (!(nn > 0)) return -1.0;
    double sj = 1.0;
    for (int i = 0; i < 4; i++) {
        const double *p = xyz + 3 * v[i], *a = xyz + 3 * v[(i + 1) % 4], *b = xyz + 3 * v[(i + 3) % 4];
        const double e1[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]}, e2[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
        const double l = sqrt((e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) * (e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]));
        if (!(l > 0)) return -1.0;
        const double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        sj = fmin(sj, (x[0] * N[0] + x[1] * N[1] + x[2] * N[2]) / (nn * l));
    }
    return sj;
}

/* The best split of hexagon p (6 vertices) into two quads (q: 8 vertices); its smallest scaled Jacobian. */
static double split_hexagon(const double *xyz, const int *p, int *q)
{
    double best = -2.0;
    for (int i = 0; i < 3; i++) {
        int a[4], b[4];
        for (int k = 0; k < 4; k++) {
            a[k] = p[(i + k) % 6];
            b[k] = p[(i + 3 + k) % 6];
        }
        const double sj = fmin(sj4(xyz, a), sj4(xyz, b));
        if (sj > best) {
            best = sj;
            memcpy(q, a, sizeof a);
            memcpy(q + 4, b, sizeof b);
        }
    }
    return best;
}

typedef struct fedge {
    long long key;
    int f, i;
} fedge;

static int cmp_fedge(const void *pa, const void *pb)
{
    const fedge *a = pa, *b = pb;
    return a->key < b->key ? -1 : a->key > b->key ? 1 : a->f - b->f;
}

/* The face across side i of face f (-1: none or more than one); *j its side. */
static int across(const glpgp_quadmesh *q, const fedge *E, int nc, int f, int i, int *j)
{
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
    const long long key = a < b ? a * q->nv + b : b * q->nv + a;
    int lo = 0, hi = nc;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (E[mid].key < key) lo = mid + 1;
        else hi = mid;
    }
    if (lo + 1 >= nc || E[lo].key != key || E[lo + 1].key != key || (lo + 2 < nc && E[lo + 2].key == key)) return -1;
    const fedge *o = E[lo].f == f ? &E[lo + 1] : &E[lo];
    *j = o->i;
    return o->f;
}

/* The hexagon of triangle f and pentagon g across f's side i (g's side j). */
static void merged(const glpgp_quadmesh *q, int f, int i, int g, int j, int *p)
{
    const int sf = q->face_start[f], sg = q->face_start[g];
    int n = 0;
    for (int k = 0; k < 2; k++) p[n++] = q->face_vert[sf + (i + 1 + k) % 3]; /* b, c (f runs a -> b on side i) */
    for (int k = 0; k < 4; k++) p[n++] = q->face_vert[sg + (j + 1 + k) % 5];   /* a, x, y, z */
}

/* Triangles paired with a pentagon across a side, and the hexagons, split
 * into two quads each where both have a scaled Jacobian above 0.05;
 * *closed: faces made quads. */
static glpgp_status close_pairs(const glpgp_quadmesh *q, glpgp_quadmesh **out, int *closed)
{
    *out = NULL;
    *closed = 0;
    const int nc = q->face_start[q->nf];
    fedge *E = NULL;
    unsigned char *used = NULL;
    int *newq = NULL, nnew = 0;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof *E, &E), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nf + 1, 1, &used), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nc + 8, sizeof(int), &newq), done);
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            E[s + i] = (fedge){a < b ? a * q->nv + b : b * q->nv + a, f, i};
        }
    }
    qsort(E, (size_t)nc, sizeof *E, cmp_fedge);
    for (int f = 0; f < q->nf; f++) {
        const int n = q->face_start[f + 1] - q->face_start[f];
        int p[6], qd[8];
        double best = 0.05;
        int bg = -1;
        if (n == 6) {
            memcpy(p, q->face_vert + q->face_start[f], sizeof p);
            if (split_hexagon(q->xyz, p, qd) > best) {
                memcpy(newq + 4 * nnew, qd, sizeof qd);
                nnew += 2;
                used[f] = 1;
                (*closed)++;
            }
            continue;
        }
        if (n != 3 || used[f]) continue;
        for (int i = 0; i < 3; i++) {
            int j, g = across(q, E, nc, f, i, &j);
            if (g < 0 || used[g] || q->face_start[g + 1] - q->face_start[g] != 5) continue;
            merged(q, f, i, g, j, p);
            const double sj = split_hexagon(q->xyz, p, qd);
            if (sj > best) {
                best = sj;
                bg = g;
                memcpy(newq + 4 * nnew, qd, sizeof qd);
            }
        }
        if (bg >= 0) {
            used[f] = used[bg] = 1;
            nnew += 2;
            *closed += 2;
        }
    }
    if (nnew) {
        glpgp_quadmesh *r = NULL;
        int nf = nnew, ncr = 4 * nnew;
        for (int f = 0; f < q->nf; f++)
            if (!used[f]) {
                nf++;
                ncr += q->face_start[f + 1] - q->face_start[f];
            }
        GLPGP_CHECK_GOTO(st, qalloc(q->nv, nf, ncr, &r), done);
        memcpy(r->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
        int o = 0, w = 0;
        for (int f = 0; f < q->nf; f++) {
            if (used[f]) continue;
            r->face_start[o] = w;
            r->face_origin[o++] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
            for (int k = q->face_start[f]; k < q->face_start[f + 1]; k++) r->face_vert[w++] = q->face_vert[k];
        }
        for (int k = 0; k < nnew; k++) {
            r->face_start[o] = w;
            r->face_origin[o++] = GLPGP_QFACE_CLOSED;
            for (int c = 0; c < 4; c++) r->face_vert[w++] = newq[4 * k + c];
        }
        r->face_start[o] = w;
        set_xy(r);
        memcpy(r->singular_tris, q->singular_tris, sizeof r->singular_tris);
        memcpy(r->inconsistent_tris, q->inconsistent_tris, sizeof r->inconsistent_tris);
        r->closing.closed_polygons = *closed;
        *out = r;
    }
done:
    free(E);
    free(used);
    free(newq);
    return st;
}

glpgp_status glpgp_quads_build_surface(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quad_options *o,
                                       glpgp_quadmesh **out, double *h, glpgp_quad_surface_steps *steps)
{
    glpgp_quad_options def;
    glpgp_quad_surface_steps stp;
    if (!o) {
        glpgp_quad_options_default(&def);
        o = &def;
    }
    memset(&stp, 0, sizeof stp);
    *out = NULL;
    glpgp_quadmesh *q = NULL, *s = NULL;
    glpgp_status st = glpgp_quads_extract_surface(m, r, &q);
    if (st == GLPGP_ERR_NUMERIC && o->repair) {
        glpgp_log(GLPGP_LOG_INFO, "quads: %s; the input triangles are split into quads", glpgp_error_message());
        glpgp_error_clear();
        st = GLPGP_OK;
    }
    if (st != GLPGP_OK) return st;
    if (q) {
        stp.extracted_faces = q->nf;
        for (int f = 0; f < q->nf; f++) stp.extracted_quads += q->face_start[f + 1] - q->face_start[f] == 4;
        int nonquad = stp.extracted_quads < q->nf;
        if (nonquad && !o->keep_polygons) {
            st = close_pairs(q, &s, &stp.closed);
            if (st != GLPGP_OK) goto fail;
            if (s) {
                glpgp_quadmesh_destroy(&q);
                q = s;
                s = NULL;
                nonquad = 0;
                for (int f = 0; f < q->nf; f++) nonquad |= q->face_start[f + 1] - q->face_start[f] != 4;
            }
        }
        if (nonquad && !o->keep_polygons) {
            st = glpgp_quadmesh_subdivide_surface(q, &s);
            if (st == GLPGP_OK) st = glpgp_qs_project(m, *h, s->xyz, q->nv, s->nv); /* the new points onto the surface */
            if (st != GLPGP_OK) goto fail;
            set_xy(s);
            glpgp_quadmesh_destroy(&q);
            q = s;
            s = NULL;
            stp.subdivided = 1;
        }
        glpgp_quad_quality qq;
        st = glpgp_quads_quality_surface(q, m, *h, &qq);
        if (st != GLPGP_OK) goto fail;
        unsigned bad = qq.invalid & ~(o->keep_polygons ? (unsigned)GLPGP_QUAD_BAD_NONQUAD : 0u);
        if (!bad || !o->repair) {
            *out = q;
            if (steps) *steps = stp;
            return GLPGP_OK;
        }
        char why[256];
        glpgp_quads_invalid_text(&qq, 0, why, sizeof why);
        glpgp_log(GLPGP_LOG_WARNING, "quads: the extracted mesh is not valid (%s): the input triangles are split into quads",
                  why);
        stp.invalid_before = qq.invalid;
        stp.subdivided = 0;
        glpgp_quadmesh_destroy(&q);
    }
    stp.fallback = 1;
    st = glpgp_quads_surface_fallback(m, out);
    if (st == GLPGP_OK && steps) *steps = stp;
    return st;
fail:
    glpgp_quadmesh_destroy(&q);
    glpgp_quadmesh_destroy(&s);
    return st;
}
