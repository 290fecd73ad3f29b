/* quads/repair.c: local repair of an extracted quad mesh
 * (glpgp_quadmesh_repair, glpgp/quads.h): the regions where the
 * parametrization did not give a valid mesh are cut out and re-meshed with
 * quads, the rest of the mesh is kept as it is; when that does not end
 * valid, the whole domain is meshed again by a chain whose last step is
 * valid by construction.
 *
 * Round r (at most REPAIR_ROUNDS):
 *  0. (first round) boundary vertices of the mesh within h/4 of the domain
 *     boundary but not on it (strip midpoints on boundary chords) are moved
 *     onto it, when no face around them gets a corner with SJ <= 0.05;
 *  1. every face is checked (check.c, tolerance h/4): not a quad, inverted,
 *     degenerate or flat (SJ < 1e-3), non-manifold, pinched, overlapping,
 *     outside the domain, far from it, or over a lost part of the domain
 *     boundary (a hole, a corner, a feature); when the mesh area is off by
 *     more than 1%, also the faces along boundary pieces farther than t
 *     from the mesh boundary, t the largest of h/10, h/20, ... h/80 that
 *     flags a face (smaller in later rounds). None: done;
 *  2. B = the bad faces and every face sharing a vertex with them (r + 1
 *     rings; in the first round no ring around a face that is bad only for
 *     the boundary distance); K = the others. The regions R = domain \ K
 *     (region.c) are polygons with holes;
 *  3. each region is made even (a region boundary with an odd number of
 *     points has no quad mesh: the longest piece of domain boundary in it
 *     gets a point, or, inside the mesh, the longest interface edge, whose
 *     kept face becomes a pentagon for the closing) and meshed by the cut
 *     mesher (qcut.c: quads grown from the region's boundary, origin
 *     "repair"); where that fails, by the triangulation fill (trisplit.c,
 *     origin "fallback");
 *  4. K + the new quads; odd faces closed (close.c), the new vertices
 *     smoothed (glpgp_quadmesh_smooth), and the next round checks again.
 * A mesh still invalid after the last round is replaced by the last resort
 * (lastresort.c: the whole domain meshed, down to the input triangles split
 * into quads), kept only if that one is valid; else it is returned as it
 * is and the quality report says so. */
#include "glpgp/internal/edgekey.h"
#include "repair.h"
#include "geom.h"
#include "qcut.h"
#include "check.h"
#include "glpgp/quads.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define REPAIR_ROUNDS 4

/* ---- output builder ----------------------------------------------------------- */

glpgp_status glpgp_rbuild_face(rbuild *R, const int *v, int n, int origin)
{
    if (R->fs.n == 0) GLPGP_CHECK(ipush(&R->fs, 0));
    for (int i = 0; i < n; i++) GLPGP_CHECK(ipush(&R->fv, v[i]));
    GLPGP_CHECK(ipush(&R->fo, origin));
    return ipush(&R->fs, R->fv.n);
}

glpgp_status glpgp_rbuild_vertex(rbuild *R, double x, double y, int *id)
{
    *id = R->xy.n / 2;
    GLPGP_CHECK(dpush(&R->xy, x));
    GLPGP_CHECK(dpush(&R->xy, y));
    return ipush(&R->newv, *id);
}

void glpgp_rbuild_free(rbuild *R)
{
    dvec_free(&R->xy);
    ivec_free(&R->fs);
    ivec_free(&R->fv);
    ivec_free(&R->fo);
    ivec_free(&R->newv);
}

/* The mesh of B without unused vertices; *newmark: per vertex 1 if added
 * by the repair; diagnostics from ref. */
static glpgp_status rbuild_mesh(const rbuild *B, const glpgp_quadmesh *ref, glpgp_quadmesh **out,
                                unsigned char **newmark)
{
    const int nvo = B->xy.n / 2, nfo = B->fs.n > 0 ? B->fs.n - 1 : 0;
    int *id = NULL;
    unsigned char *isnew = NULL;
    glpgp_quadmesh *o = NULL;
    glpgp_status st = glpgp_malloc((size_t)nvo + 1, sizeof(int), &id);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nvo + 1, 1, &isnew);
    if (st == GLPGP_OK) st = glpgp_calloc(1, sizeof *o, &o);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nvo + 1, 2 * sizeof(double), &o->xy);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nfo + 1, sizeof(int), &o->face_start);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)B->fv.n + 1, sizeof(int), &o->face_vert);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nfo + 1, 1, &o->face_origin);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nvo + 1, 1, newmark);
    if (st != GLPGP_OK) goto done;
    for (int i = 0; i < B->newv.n; i++) isnew[B->newv.p[i]] = 1;
    for (int v = 0; v < nvo; v++) id[v] = -1;
    o->face_start[0] = 0;
    for (int f = 0; f < nfo; f++) {
        for (int s = B->fs.p[f]; s < B->fs.p[f + 1]; s++) {
            int v = B->fv.p[s];
            if (id[v] < 0) {
                id[v] = o->nv;
                o->xy[2 * o->nv] = B->xy.p[2 * v];
                o->xy[2 * o->nv + 1] = B->xy.p[2 * v + 1];
                (*newmark)[o->nv] = isnew[v];
                o->nv++;
            }
            o->face_vert[s] = id[v];
        }
        o->face_start[f + 1] = B->fs.p[f + 1];
        o->face_origin[f] = (unsigned char)B->fo.p[f];
    }
    o->nf = nfo;
    memcpy(o->singular_tris, ref->singular_tris, sizeof o->singular_tris);
    memcpy(o->inconsistent_tris, ref->inconsistent_tris, sizeof o->inconsistent_tris);
    o->collapsed_edges = ref->collapsed_edges;
    o->promoted_corners = ref->promoted_corners;
    o->split_pentagons = ref->split_pentagons;
    o->center_splits = ref->center_splits;
    o->closing = ref->closing;
    *out = o;
    o = NULL;
done:
    if (st != GLPGP_OK) {
        free(*newmark);
        *newmark = NULL;
    }
    glpgp_quadmesh_destroy(&o);
    free(id);
    free(isnew);
    return st;
}

glpgp_quadmesh *glpgp_qm_copy(const glpgp_quadmesh *q)
{
    glpgp_quadmesh *o = calloc(1, sizeof *o);
    if (!o) return NULL;
    *o = *q;
    o->face_origin = NULL;
    o->xy = malloc(sizeof(double) * 2 * ((size_t)q->nv + 1));
    o->face_start = malloc(sizeof(int) * ((size_t)q->nf + 1));
    o->face_vert = malloc(sizeof(int) * ((size_t)q->face_start[q->nf] + 1));
    if (q->face_origin) o->face_origin = malloc((size_t)q->nf + 1);
    if (!o->xy || !o->face_start || !o->face_vert || (q->face_origin && !o->face_origin)) {
        glpgp_quadmesh_destroy(&o);
        return NULL;
    }
    /* an empty mesh may have NULL arrays: copy only what is there */
    if (q->nv > 0) memcpy(o->xy, q->xy, sizeof(double) * 2 * (size_t)q->nv);
    memcpy(o->face_start, q->face_start, sizeof(int) * ((size_t)q->nf + 1));
    if (q->face_start[q->nf] > 0) memcpy(o->face_vert, q->face_vert, sizeof(int) * (size_t)q->face_start[q->nf]);
    if (q->face_origin && q->nf > 0) memcpy(o->face_origin, q->face_origin, (size_t)q->nf);
    return o;
}

void glpgp_qm_adopt_quads(glpgp_quadmesh *q, double **xy, int nv, int **fv, int **fs, unsigned char **fo, int nf)
{
    for (int f = 0; f <= nf; f++) (*fs)[f] = 4 * f;
    free(q->xy);
    free(q->face_vert);
    free(q->face_start);
    free(q->face_origin);
    q->xy = *xy;
    q->face_vert = *fv;
    q->face_start = *fs;
    q->face_origin = *fo;
    q->nv = nv;
    q->nf = nf;
    *xy = NULL;
    *fv = *fs = NULL;
    *fo = NULL;
}

/* ---- snapping ---------------------------------------------------------------------- */

/* Faces per vertex (CSR): vs[v] .. vs[v+1] in vf. */
static glpgp_status vertex_faces(const glpgp_quadmesh *q, int **vs, int **vf)
{
    int *cnt = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 2, sizeof(int), vs));
    GLPGP_CHECK(glpgp_malloc((size_t)q->face_start[q->nf] + 1, sizeof(int), vf));
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, sizeof(int), &cnt));
    for (int s = 0; s < q->face_start[q->nf]; s++) (*vs)[q->face_vert[s] + 1]++;
    for (int v = 0; v < q->nv; v++) (*vs)[v + 1] += (*vs)[v];
    for (int f = 0; f < q->nf; f++)
        for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++)
            (*vf)[(*vs)[q->face_vert[s]] + cnt[q->face_vert[s]]++] = f;
    free(cnt);
    return GLPGP_OK;
}

/* Move mesh boundary vertices within h/4 of the domain boundary onto it. */
static glpgp_status snap_boundary(glpgp_quadmesh *q, dbnd *D, double h, int *snapped)
{
    int *cand = NULL, ncap = 0, *vs = NULL, *vf = NULL, nc = q->face_start[q->nf];
    glpgp_ekv *E = NULL;
    unsigned char *bnd = NULL;
    glpgp_status st = glpgp_malloc((size_t)nc + 1, sizeof *E, &E);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 1, 1, &bnd);
    if (st == GLPGP_OK) st = vertex_faces(q, &vs, &vf);
    if (st != GLPGP_OK) goto done;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) E[s + i] = (glpgp_ekv){glpgp_edge_key(q->face_vert[s + i], q->face_vert[s + (i + 1) % k]), s + i};
    }
    qsort(E, (size_t)nc, sizeof *E, glpgp_ekv_cmp);
    for (int i = 0; i < nc;) {
        int j = i + 1;
        while (j < nc && E[j].k == E[i].k) j++;
        if (j - i == 1) bnd[(int)(E[i].k >> 32)] = bnd[(int)(E[i].k & 0xffffffffu)] = 1;
        i = j;
    }
    for (int v = 0; v < q->nv; v++) {
        if (!bnd[v]) continue;
        double t, d, pr[2];
        int s = glpgp_dbnd_nearest(D, q->xy + 2 * v, 0.25 * h, &t, &d, pr, &cand, &ncap);
        if (s < 0 || d <= 1e-9 * h) continue;
        double ox = q->xy[2 * v], oy = q->xy[2 * v + 1];
        q->xy[2 * v] = pr[0];
        q->xy[2 * v + 1] = pr[1];
        int ok = 1;
        for (int j = vs[v]; j < vs[v + 1] && ok; j++) {
            int f = vf[j];
            ok = glpgp_poly_min_sj(q->xy, q->face_vert + q->face_start[f], q->face_start[f + 1] - q->face_start[f]) > 0.05;
        }
        if (ok) {
            (*snapped)++;
        } else {
            q->xy[2 * v] = ox;
            q->xy[2 * v + 1] = oy;
        }
    }
done:
    free(cand);
    free(E);
    free(bnd);
    free(vs);
    free(vf);
    return st;
}

/* ---- bad faces -------------------------------------------------------------------- */

/* The flags of every face of q (ck), with the chord faces when the area is
 * off by more than 1%. */
static glpgp_status check_faces(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, int round, qcheck *ck)
{
    GLPGP_CHECK(glpgp_qcheck_run(q, m, h, 0.25 * h, ck));
    double area = 0.0;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            const double *a = q->xy + 2 * q->face_vert[s + i], *b = q->xy + 2 * q->face_vert[s + (i + 1) % k];
            area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
        }
    }
    if (!(m->area > 0 && fabs(area / m->area - 1.0) > 0.01)) return GLPGP_OK;
    /* the boundary chords cut too much: the largest tolerance (h/10, h/20, ... h/80) that flags something */
    for (double t = ldexp(0.1, -round); t >= 0.012; t *= 0.5) {
        qcheck c2;
        int hit = 0;
        GLPGP_CHECK(glpgp_qcheck_run(q, m, h, t * h, &c2));
        for (int f = 0; f < q->nf; f++)
            if (c2.flags[f] & (QF_FAR | QF_LOST)) {
                ck->flags[f] |= c2.flags[f] & (QF_FAR | QF_LOST);
                hit = 1;
            }
        glpgp_qcheck_free(&c2);
        if (hit) break;
    }
    return GLPGP_OK;
}

/* Kept faces in small islands (edge-connected sets of at most ISLAND faces
 * with fewer faces than the removed ones around them) go too: a thin
 * kept island inside a region leaves slivers between it and the domain. */
#define ISLAND 12
static glpgp_status drop_islands(const glpgp_quadmesh *q, unsigned char *inB)
{
    int nc = q->face_start[q->nf], *comp = NULL, *size = NULL, *stack = NULL;
    glpgp_ekv *E = NULL;
    glpgp_status st = glpgp_malloc((size_t)nc + 1, sizeof *E, &E);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)q->nf + 1, sizeof(int), &comp);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nf + 1, sizeof(int), &size);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)q->nf + 1, sizeof(int), &stack);
    if (st != GLPGP_OK) goto done;
    int sf = 0, removed = 0;
    for (int f = 0; f < q->nf; f++) {
        removed += inB[f];
        for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) {
            int k = q->face_start[f + 1] - q->face_start[f], i = s - q->face_start[f];
            E[sf++] = (glpgp_ekv){glpgp_edge_key(q->face_vert[s], q->face_vert[q->face_start[f] + (i + 1) % k]), f};
        }
    }
    qsort(E, (size_t)nc, sizeof *E, glpgp_ekv_cmp);
    int *nbr = NULL; /* adjacency through shared edges, CSR over E */
    for (int f = 0; f < q->nf; f++) comp[f] = -1;
    int ncomp = 0;
    for (int f0 = 0; f0 < q->nf; f0++) {
        if (inB[f0] || comp[f0] >= 0) continue;
        int sp = 0;
        stack[sp++] = f0;
        comp[f0] = ncomp;
        while (sp > 0) {
            int f = stack[--sp];
            size[ncomp]++;
            int k = q->face_start[f + 1] - q->face_start[f];
            for (int i = 0; i < k; i++) {
                unsigned long long key = glpgp_edge_key(q->face_vert[q->face_start[f] + i], q->face_vert[q->face_start[f] + (i + 1) % k]);
                int lo = 0, hi = nc;
                while (lo < hi) {
                    int mid = (lo + hi) / 2;
                    if (E[mid].k < key) lo = mid + 1;
                    else hi = mid;
                }
                for (int j = lo; j < nc && E[j].k == key; j++) {
                    int g = E[j].slot;
                    if (inB[g] || comp[g] >= 0) continue;
                    comp[g] = ncomp;
                    stack[sp++] = g;
                }
            }
        }
        ncomp++;
    }
    (void)nbr;
    for (int f = 0; f < q->nf; f++)
        if (!inB[f] && size[comp[f]] <= ISLAND && size[comp[f]] < removed) inB[f] = 1;
done:
    free(E);
    free(comp);
    free(size);
    free(stack);
    return st;
}

/* inB: the bad faces and round + 1 vertex rings around them (in the first
 * round none around a face that is bad only for its boundary distance). */
static glpgp_status grow_bad(const glpgp_quadmesh *q, const qcheck *ck, int round, unsigned char *inB)
{
    int *vs = NULL, *vf = NULL;
    unsigned char *vb = NULL;
    glpgp_status st = vertex_faces(q, &vs, &vf);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 1, 1, &vb);
    if (st == GLPGP_OK) {
        for (int f = 0; f < q->nf; f++) inB[f] = ck->flags[f] != 0;
        for (int ring = 0; ring <= round; ring++) {
            memset(vb, 0, (size_t)q->nv + 1);
            for (int f = 0; f < q->nf; f++)
                if (inB[f] && (round > 0 || ring > 0 || (ck->flags[f] & ~(unsigned)(QF_FAR | QF_LOST))))
                    for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) vb[q->face_vert[s]] = 1;
            for (int v = 0; v < q->nv; v++)
                if (vb[v])
                    for (int j = vs[v]; j < vs[v + 1]; j++) inB[vf[j]] = 1;
        }
    }
    free(vs);
    free(vf);
    free(vb);
    if (st == GLPGP_OK) st = drop_islands(q, inB);
    return st;
}

/* ---- one round --------------------------------------------------------------------- */

/* Record a region in rs (the GLPGP_QUADS_REGIONS_LISTED with the lowest sj_min kept). */
static void note_region(glpgp_quads_repair *rs, const glpgp_quads_region *g)
{
    rs->regions++;
    rs->new_quads += g->quads_out;
    if (g->origin == GLPGP_QFACE_PAVED) rs->paved_regions++;
    else rs->fallback_regions++;
    if (rs->nlisted < GLPGP_QUADS_REGIONS_LISTED) {
        rs->region[rs->nlisted++] = *g;
        return;
    }
    int w = 0;
    for (int i = 1; i < rs->nlisted; i++)
        if (rs->region[i].sj_min > rs->region[w].sj_min) w = i;
    if (g->sj_min < rs->region[w].sj_min) rs->region[w] = *g;
}

/* Centroid, box and smallest scaled Jacobian of the faces of B from f0 on. */
static void face_box(const rbuild *B, int f0, glpgp_quads_region *g)
{
    g->sj_min = INFINITY;
    g->box[0] = g->box[1] = INFINITY;
    g->box[2] = g->box[3] = -INFINITY;
    double cx = 0.0, cy = 0.0;
    int n = 0;
    for (int f = f0; f + 1 < B->fs.n; f++) {
        g->sj_min = fmin(g->sj_min, glpgp_poly_min_sj(B->xy.p, B->fv.p + B->fs.p[f], B->fs.p[f + 1] - B->fs.p[f]));
        for (int s = B->fs.p[f]; s < B->fs.p[f + 1]; s++) {
            const double *p = B->xy.p + 2 * B->fv.p[s];
            cx += p[0];
            cy += p[1];
            n++;
            g->box[0] = fmin(g->box[0], p[0]);
            g->box[1] = fmin(g->box[1], p[1]);
            g->box[2] = fmax(g->box[2], p[0]);
            g->box[3] = fmax(g->box[3], p[1]);
        }
    }
    g->x = n ? cx / n : 0.0;
    g->y = n ? cy / n : 0.0;
}

/* The listed regions' sj_min from the repaired quads of q in their boxes. */
static void final_region_sj(const glpgp_quadmesh *q, glpgp_quads_repair *rs)
{
    for (int i = 0; i < rs->nlisted; i++) {
        glpgp_quads_region *g = &rs->region[i];
        double m = INFINITY;
        for (int f = 0; f < q->nf; f++) {
            if (!q->face_origin || q->face_origin[f] < GLPGP_QFACE_PAVED) continue;
            int s = q->face_start[f], k = q->face_start[f + 1] - s;
            double cx = 0.0, cy = 0.0;
            for (int t = 0; t < k; t++) {
                cx += q->xy[2 * q->face_vert[s + t]] / k;
                cy += q->xy[2 * q->face_vert[s + t] + 1] / k;
            }
            if (cx >= g->box[0] && cx <= g->box[2] && cy >= g->box[1] && cy <= g->box[3])
                m = fmin(m, glpgp_poly_min_sj(q->xy, q->face_vert + s, k));
        }
        if (m < INFINITY) g->sj_min = m;
    }
}

/* Mesh outer loop O of R (and its holes) with the cut mesher: its quads
 * into B (region point v is output vertex gid[v]). *ok: 0 when it failed
 * (nothing added). */
static glpgp_status cut_region(const region *R, int O, int *gid, rbuild *B, glpgp_quads_region *g, int *ok)
{
    *ok = 0;
    ivec ls = {0}, lv = {0}, ow = {0}, quads = {0}, map = {0};
    dvec xy = {0};
    glpgp_status st = ipush(&ls, 0);
    /* local points: the loops' points in order (qcut's xy), region ids in map */
    for (int L = 0; L < R->nloops && st == GLPGP_OK; L++) {
        if (L != O && R->owner[L] != O) continue;
        for (int i = R->loop_start[L]; i < R->loop_start[L + 1] && st == GLPGP_OK; i++) {
            int v = R->he[R->loopv.p[i]].a;
            st = ipush(&lv, map.n);
            if (st == GLPGP_OK) st = ipush(&map, v);
            if (st == GLPGP_OK) st = dpush(&xy, glpgp_region_xy(R, v)[0]);
            if (st == GLPGP_OK) st = dpush(&xy, glpgp_region_xy(R, v)[1]);
        }
        if (st == GLPGP_OK) st = ipush(&ls, lv.n);
        if (st == GLPGP_OK) st = ipush(&ow, L == O ? -1 : 0);
    }
    /* the same region point twice in the loops (touching parts): one id */
    for (int i = 0; i < map.n && st == GLPGP_OK; i++)
        for (int j = 0; j < i; j++)
            if (map.p[j] == map.p[i]) {
                lv.p[i] = j;
                break;
            }
    const int nfixed = map.n;
    qcut_stats qs;
    qcut_region QR = {ls.n - 1, ls.p, lv.p, ow.p, 0.0};
    if (st == GLPGP_OK) {
        st = glpgp_qcut_mesh(&xy, &QR, R->h, &quads, &qs);
        if (st == GLPGP_ERR_NUMERIC) { /* the fallback fill takes it */
            glpgp_log(GLPGP_LOG_DEBUG, "quad repair: %s", glpgp_error_message());
            glpgp_error_clear();
            st = GLPGP_OK;
            goto done;
        }
    }
    if (st != GLPGP_OK) goto done;
    double sjmin = INFINITY;
    for (int q = 0; q < quads.n / 4; q++) {
        int id4[4] = {quads.p[4 * q], quads.p[4 * q + 1], quads.p[4 * q + 2], quads.p[4 * q + 3]};
        sjmin = fmin(sjmin, glpgp_poly_min_sj(xy.p, id4, 4));
    }
    if (!(sjmin > 0.0) || quads.n == 0) goto done; /* should not happen: the fallback takes it */
    int *lid = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)xy.n / 2 + 1, sizeof(int), &lid), done);
    for (int i = 0; i < xy.n / 2 && st == GLPGP_OK; i++) {
        if (i < nfixed) {
            int v = map.p[i];
            if (gid[v] < 0) st = glpgp_rbuild_vertex(B, xy.p[2 * i], xy.p[2 * i + 1], &gid[v]);
            lid[i] = gid[v];
        } else {
            st = glpgp_rbuild_vertex(B, xy.p[2 * i], xy.p[2 * i + 1], &lid[i]);
        }
    }
    double cx = 0.0, cy = 0.0;
    g->box[0] = g->box[1] = INFINITY;
    g->box[2] = g->box[3] = -INFINITY;
    for (int q = 0; q < quads.n / 4 && st == GLPGP_OK; q++) {
        int f[4];
        for (int t = 0; t < 4; t++) {
            const double *p = xy.p + 2 * quads.p[4 * q + t];
            f[t] = lid[quads.p[4 * q + t]];
            cx += 0.25 * p[0];
            cy += 0.25 * p[1];
            g->box[0] = fmin(g->box[0], p[0]);
            g->box[1] = fmin(g->box[1], p[1]);
            g->box[2] = fmax(g->box[2], p[0]);
            g->box[3] = fmax(g->box[3], p[1]);
        }
        st = glpgp_rbuild_face(B, f, 4, GLPGP_QFACE_PAVED);
    }
    free(lid);
    g->quads_out = quads.n / 4;
    g->sj_min = sjmin;
    g->x = cx / g->quads_out;
    g->y = cy / g->quads_out;
    g->origin = GLPGP_QFACE_PAVED;
    *ok = st == GLPGP_OK;
done:
    ivec_free(&ls);
    ivec_free(&lv);
    ivec_free(&ow);
    ivec_free(&quads);
    ivec_free(&map);
    dvec_free(&xy);
    return st;
}

/* The kept faces into B (K vertices are output ids 0 .. nv-1); a kept face
 * whose edge b -> a was split at point mid (region id) gets it. */
static glpgp_status emit_kept(const glpgp_quadmesh *q, const unsigned char *inB, const ivec *ksplit, int *gid,
                              const region *R, rbuild *B)
{
    for (int v = 0; v < q->nv; v++) {
        GLPGP_CHECK(dpush(&B->xy, q->xy[2 * v]));
        GLPGP_CHECK(dpush(&B->xy, q->xy[2 * v + 1]));
        gid[v] = v;
    }
    int buf[64];
    for (int f = 0; f < q->nf; f++) {
        if (inB[f]) continue;
        int s = q->face_start[f], k = q->face_start[f + 1] - s, n = 0;
        for (int i = 0; i < k && n < 60; i++) {
            int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
            buf[n++] = a;
            for (int t = 0; t + 2 < ksplit->n; t += 3) /* region edge (b, a) of kept edge a -> b */
                if (ksplit->p[t] == b && ksplit->p[t + 1] == a) {
                    int mid = ksplit->p[t + 2];
                    if (gid[mid] < 0)
                        GLPGP_CHECK(glpgp_rbuild_vertex(B, glpgp_region_xy(R, mid)[0], glpgp_region_xy(R, mid)[1], &gid[mid]));
                    buf[n++] = gid[mid];
                }
        }
        GLPGP_CHECK(glpgp_rbuild_face(B, buf, n, q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID));
    }
    return GLPGP_OK;
}

/* One repair round on q (faces in inB removed). *out: the new mesh,
 * *newmark: per output vertex 1 if made here. */
static glpgp_status repair_round(const glpgp_quadmesh *q, const glpgp_mesh *m, dbnd *D, double h,
                                 const unsigned char *inB, int round, glpgp_quads_repair *rs, glpgp_quadmesh **out,
                                 unsigned char **newmark)
{
    region R;
    rbuild B;
    memset(&B, 0, sizeof B);
    ivec ksplit = {0};
    int *gid = NULL, removed = 0;
    for (int f = 0; f < q->nf; f++) removed += inB[f];
    glpgp_status st = glpgp_region_build(&R, q, m, D, h, inB);
    /* parity of every region first (a split interface edge changes a kept face) */
    for (int O = 0; O < R.nloops && st == GLPGP_OK; O++) {
        if (R.area[O] <= 0) continue;
        int ke[2], kmid;
        st = glpgp_region_make_even(&R, O, ke, &kmid);
        if (st == GLPGP_OK && kmid >= 0) {
            st = ipush(&ksplit, ke[0]);
            if (st == GLPGP_OK) st = ipush(&ksplit, ke[1]);
            if (st == GLPGP_OK) st = ipush(&ksplit, kmid);
        }
    }
    const int nrv = q->nv + R.vxy.n / 2;
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nrv + 1, sizeof(int), &gid);
    if (st == GLPGP_OK) {
        for (int v = 0; v <= nrv; v++) gid[v] = -1;
        st = emit_kept(q, inB, &ksplit, gid, &R, &B);
    }
    int nreg = 0;
    for (int O = 0; O < R.nloops; O++) nreg += R.area[O] > 0;
    for (int O = 0; O < R.nloops && st == GLPGP_OK; O++) {
        if (R.area[O] <= 0) continue;
        glpgp_quads_region g = {removed / (nreg > 0 ? nreg : 1), 0, INFINITY, 0.0, 0.0, {0, 0, 0, 0}, GLPGP_QFACE_PAVED, round};
        int ok = 0, f0 = B.fs.n;
        glpgp_progress_poll();
        st = cut_region(&R, O, gid, &B, &g, &ok);
        if (st == GLPGP_OK && !ok) {
            int nq = 0;
            st = glpgp_trisplit_fill(&R, O, gid, &B, GLPGP_QFACE_FALLBACK, &nq);
            g.origin = GLPGP_QFACE_FALLBACK;
            g.quads_out = nq;
            face_box(&B, f0 > 0 ? f0 - 1 : 0, &g);
        }
        if (st == GLPGP_OK) note_region(rs, &g);
    }
    if (st == GLPGP_OK) st = rbuild_mesh(&B, q, out, newmark);
    glpgp_region_free(&R);
    glpgp_rbuild_free(&B);
    ivec_free(&ksplit);
    free(gid);
    return st;
}

/* ---- driver ------------------------------------------------------------------------ */

/* Whether q is valid against m (the quality report's verdict; keep_polygons:
 * non-quad faces allowed). */
static glpgp_status is_valid(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, int keep_polygons, int *valid)
{
    glpgp_quads_report qq;
    *valid = 0;
    if (q->nf == 0) return GLPGP_OK;
    GLPGP_CHECK(glpgp_quads_quality(q, m, h, &qq));
    *valid = (qq.invalid & ~(keep_polygons ? (unsigned)GLPGP_QUADS_BAD_NONQUAD : 0u)) == 0;
    return GLPGP_OK;
}

/* The new mesh of a round: odd faces closed, new vertices smoothed. */
static glpgp_status finish_round(glpgp_quadmesh **n, unsigned char *mark, int smooth, int keep_polygons)
{
    if (smooth > 0) GLPGP_CHECK(glpgp_quadmesh_smooth(*n, mark, smooth, 0.5, NULL));
    int odd = 0;
    for (int f = 0; f < (*n)->nf; f++) odd += ((*n)->face_start[f + 1] - (*n)->face_start[f]) != 4;
    if (!odd || keep_polygons) return GLPGP_OK;
    glpgp_quadmesh *c = NULL;
    unsigned char *mark2 = NULL;
    glpgp_quads_closing keep = (*n)->closing;
    GLPGP_CHECK(glpgp_quadmesh_close_polygons(*n, &c, &mark2));
    c->closing = keep;
    glpgp_status st = smooth > 0 ? glpgp_quadmesh_smooth(c, mark2, smooth, 0.5, NULL) : GLPGP_OK;
    free(mark2);
    glpgp_quadmesh_destroy(n);
    *n = c;
    return st;
}

/* Still invalid after the rounds: the whole domain again (lastresort.c). */
static glpgp_status last_resort(glpgp_quadmesh **q, const glpgp_mesh *m, double h, glpgp_quads_repair *rs)
{
    glpgp_quadmesh *w = NULL;
    int level = 0;
    GLPGP_CHECK(glpgp_quads_last_resort(m, h, &w, &level));
    if (!w) return GLPGP_OK; /* nothing valid: the mesh stays, reported invalid */
    glpgp_log(GLPGP_LOG_WARNING, "quads: the local repair did not end valid; the whole domain was meshed %s",
              level == 1 ? "by the region mesher" : level == 2 ? "by the triangulation fill"
                                                  : "from the input triangles, split into quads");
    rs->whole_domain = level >= 3 ? 2 : 1;
    rs->removed_faces += (*q)->nf;
    glpgp_quads_region g = {(*q)->nf, w->nf, INFINITY, 0.0, 0.0, {0, 0, 0, 0}, level == 1 ? GLPGP_QFACE_PAVED : GLPGP_QFACE_FALLBACK, -1};
    for (int f = 0; f < w->nf; f++) g.sj_min = fmin(g.sj_min, glpgp_quadmesh_face_sj(w, f));
    memcpy(g.box, m->bbox, sizeof g.box);
    g.x = 0.5 * (m->bbox[0] + m->bbox[2]);
    g.y = 0.5 * (m->bbox[1] + m->bbox[3]);
    note_region(rs, &g);
    w->closing = (*q)->closing;
    glpgp_quadmesh_destroy(q);
    *q = w;
    return GLPGP_OK;
}

/* The rounds on a copy of qin: *q the result (owned), rs filled. */
static glpgp_status run_rounds(const glpgp_quadmesh *qin, const glpgp_mesh *m, double h, int smooth, int keep_polygons,
                               int rounds, glpgp_quadmesh **qout, glpgp_quads_repair *rs)
{
    glpgp_status st = GLPGP_OK;
    dbnd D;
    memset(&D, 0, sizeof D);
    glpgp_quadmesh *q = glpgp_qm_copy(qin), *n = NULL;
    unsigned char *inB = NULL, *mark = NULL;
    qcheck ck;
    memset(&ck, 0, sizeof ck);
    if (!q) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
    GLPGP_CHECK_GOTO(st, glpgp_dbnd_build(&D, m, h), done);
    GLPGP_CHECK_GOTO(st, snap_boundary(q, &D, h, &rs->snapped), done);
    if (!keep_polygons) GLPGP_CHECK_GOTO(st, glpgp_quadmesh_chord_strips(q, m, h, &rs->chord_strips), done);
    for (int round = 0; round < rounds; round++) {
        glpgp_progress_poll();
        glpgp_qcheck_free(&ck);
        GLPGP_CHECK_GOTO(st, check_faces(q, m, h, round, &ck), done);
        if (keep_polygons)
            for (int f = 0; f < q->nf; f++) ck.flags[f] &= ~(unsigned)QF_NONQUAD;
        int nbad = 0;
        for (int f = 0; f < q->nf; f++) nbad += ck.flags[f] != 0;
        if (nbad == 0 && q->nf > 0) break; /* an empty mesh: the whole domain is re-meshed */
        rs->rounds++;
        free(inB);
        inB = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nf + 1, 1, &inB), done);
        GLPGP_CHECK_GOTO(st, grow_bad(q, &ck, round, inB), done);
        for (int f = 0; f < q->nf; f++) rs->removed_faces += inB[f];
        free(mark);
        mark = NULL;
        st = repair_round(q, m, &D, h, inB, round, rs, &n, &mark);
        if (st == GLPGP_ERR_NUMERIC) { /* the regions could not be built: the last resort takes it */
            glpgp_log(GLPGP_LOG_DEBUG, "quad repair: %s", glpgp_error_message());
            glpgp_error_clear();
            st = GLPGP_OK;
            break;
        }
        if (st != GLPGP_OK) goto done;
        n->closing = q->closing;
        GLPGP_CHECK_GOTO(st, finish_round(&n, mark, smooth, keep_polygons), done);
        glpgp_quadmesh_destroy(&q);
        q = n;
        n = NULL;
    }
    *qout = q;
    q = NULL;
done:
    glpgp_dbnd_free(&D);
    glpgp_qcheck_free(&ck);
    glpgp_quadmesh_destroy(&q);
    glpgp_quadmesh_destroy(&n);
    free(inB);
    free(mark);
    return st;
}

/* ---- shape rounds --------------------------------------------------------------- */

#define SHAPE_ROUNDS 2

/* Quads below GLPGP_QUADS_SJ_GOAL and below 0.9 of what their sharp domain corners
 * allow (glpgp_qcheck_corner_bound) into flags (QF_FLAT); *npoor, and the
 * smallest scaled Jacobian relative to that bound over all quads. */
static glpgp_status poor_faces(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, unsigned *flags, int *npoor,
                               double *worst)
{
    double *bound = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, sizeof(double), &bound));
    glpgp_status st = glpgp_qcheck_corner_bound(q, m, h, bound);
    *npoor = 0;
    *worst = INFINITY;
    for (int f = 0; f < q->nf && st == GLPGP_OK; f++) {
        double sj = glpgp_quadmesh_face_sj(q, f);
        flags[f] = 0;
        *worst = fmin(*worst, sj / bound[f]);
        if (glpgp_qcheck_unforced_below(sj, bound[f], GLPGP_QUADS_SJ_GOAL)) {
            flags[f] = QF_FLAT;
            (*npoor)++;
        }
    }
    free(bound);
    return st;
}

/* Valid mesh, poorly shaped quads: they and a ring around them are meshed
 * again, kept when the result is valid, has fewer poor quads and no worse
 * a smallest relative scaled Jacobian. */
static glpgp_status shape_rounds(glpgp_quadmesh **q, const glpgp_mesh *m, double h, int smooth, glpgp_quads_repair *rs)
{
    dbnd D;
    qcheck ck;
    memset(&ck, 0, sizeof ck);
    unsigned char *inB = NULL, *mark = NULL;
    glpgp_quadmesh *n = NULL;
    glpgp_status st = glpgp_dbnd_build(&D, m, h);
    for (int round = 0; round < SHAPE_ROUNDS && st == GLPGP_OK; round++) {
        int np0 = 0, np1 = 0, valid = 0;
        double w0 = 0.0, w1 = 0.0;
        free(ck.flags);
        ck.flags = NULL;
        free(inB);
        inB = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)(*q)->nf + 1, sizeof(unsigned), &ck.flags), done);
        GLPGP_CHECK_GOTO(st, poor_faces(*q, m, h, ck.flags, &np0, &w0), done);
        if (np0 == 0) break;
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)(*q)->nf + 1, 1, &inB), done);
        GLPGP_CHECK_GOTO(st, grow_bad(*q, &ck, round, inB), done); /* round + 1 rings */
        glpgp_quads_repair trial = *rs;
        free(mark);
        mark = NULL;
        st = repair_round(*q, m, &D, h, inB, REPAIR_ROUNDS + round, &trial, &n, &mark);
        if (st == GLPGP_ERR_NUMERIC) {
            glpgp_error_clear();
            st = GLPGP_OK;
            break;
        }
        if (st != GLPGP_OK) goto done;
        n->closing = (*q)->closing;
        GLPGP_CHECK_GOTO(st, finish_round(&n, mark, smooth, 0), done);
        GLPGP_CHECK_GOTO(st, is_valid(n, m, h, 0, &valid), done);
        if (valid) {
            unsigned *f1 = NULL;
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)n->nf + 1, sizeof(unsigned), &f1), done);
            st = poor_faces(n, m, h, f1, &np1, &w1);
            free(f1);
            if (st != GLPGP_OK) goto done;
        }
        glpgp_log(GLPGP_LOG_DEBUG, "quad repair: shape round %d: %d poor quads (worst %.3f of its bound) -> %s%d (%.3f)",
                  round, np0, w0, valid ? "" : "invalid, ", np1, w1);
        if (!valid || np1 >= np0 || w1 < w0 - 1e-9) { /* not better: the next round takes a wider ring */
            glpgp_quadmesh_destroy(&n);
            continue;
        }
        for (int f = 0; f < (*q)->nf; f++) trial.removed_faces += inB[f];
        trial.rounds++;
        *rs = trial;
        glpgp_quadmesh_destroy(q);
        *q = n;
        n = NULL;
    }
done:
    glpgp_dbnd_free(&D);
    free(ck.flags);
    free(inB);
    free(mark);
    glpgp_quadmesh_destroy(&n);
    return st;
}

glpgp_status glpgp_repair_rounds(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, int smooth, int rounds,
                                 glpgp_quadmesh **out)
{
    glpgp_quads_repair rs;
    memset(&rs, 0, sizeof rs);
    *out = NULL;
    GLPGP_CHECK(run_rounds(q, m, h, smooth, 0, rounds, out, &rs));
    (*out)->repair = rs;
    return GLPGP_OK;
}

glpgp_status glpgp_quadmesh_repair(const glpgp_quadmesh *qin, const glpgp_mesh *m, double h, int smooth,
                                   int keep_polygons, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!qin || !m || qin->nf < 0 || !(h > 0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad repair: bad arguments");
    glpgp_quads_repair rs;
    memset(&rs, 0, sizeof rs);
    glpgp_quadmesh *q = NULL;
    GLPGP_CHECK(run_rounds(qin, m, h, smooth, keep_polygons, REPAIR_ROUNDS, &q, &rs));
    int valid = 0;
    glpgp_status st = is_valid(q, m, h, keep_polygons, &valid);
    if (st == GLPGP_OK && !valid) st = last_resort(&q, m, h, &rs);
    if (st == GLPGP_OK && !keep_polygons) st = shape_rounds(&q, m, h, smooth, &rs);
    if (st == GLPGP_OK) final_region_sj(q, &rs);
    if (st == GLPGP_OK) {
        q->repair = rs;
        *out = q;
        q = NULL;
    }
    glpgp_quadmesh_destroy(&q);
    return st;
}
