/* quads/components_surface.c: glpgp_quads_build_surface (glpgp/quads.h).
 * A surface of several connected components is meshed one component at a
 * time: each part's sub-mesh and the result's values on it go through the
 * whole pipeline (glpgp_qs_build_one: extraction, repair, last resort,
 * smoothing) and the parts' quad meshes are joined. A part the grid cannot
 * mesh (scan debris smaller than h, one body of an assembly) falls back
 * alone; before, it sent the whole surface to the last resort. A part
 * keeps its vertices' and triangles' order, so each vertex's first corner,
 * its frame and the oscillators read in it are the whole surface's. */
#include "quads_surface.h"

#include "glpgp/result.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* comp[v]: v's component, numbered in the order of their first vertices;
 * returns how many. */
static int label(const glpgp_mesh *m, int *comp, int *parent)
{
    for (int v = 0; v < m->nv; v++) parent[v] = v;
    for (int c = 0; c < 3 * m->nt; c++) {
        const int a = glpgp_uf_find(parent, m->tri[c]), b = glpgp_uf_find(parent, m->tri[c - c % 3 + (c % 3 + 1) % 3]);
        if (a != b) parent[a > b ? a : b] = a < b ? a : b;
    }
    int n = 0;
    for (int v = 0; v < m->nv; v++) comp[v] = -1;
    for (int v = 0; v < m->nv; v++) {
        const int r = glpgp_uf_find(parent, v);
        if (comp[r] < 0) comp[r] = n++;
        comp[v] = comp[r];
    }
    return n;
}

/* The parts' vertices and triangles, each part's in their order (counting
 * sorts by part): part k has vertices vlist[vstart[k] .. vstart[k + 1]),
 * triangles tlist[tstart[k] ..); vmap[v]: v's index in its part. */
typedef struct parts {
    int n, *comp, *vmap, *vstart, *vlist, *tstart, *tlist;
} parts;

static void parts_free(parts *p)
{
    free(p->comp);
    free(p->vmap);
    free(p->vstart);
    free(p->vlist);
    free(p->tstart);
    free(p->tlist);
}

static glpgp_status parts_make(const glpgp_mesh *m, parts *p)
{
    memset(p, 0, sizeof *p);
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(int), &p->comp));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(int), &p->vmap));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(int), &p->vlist));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nt, sizeof(int), &p->tlist));
    p->n = label(m, p->comp, p->vmap); /* vmap: label's scratch until set below */
    GLPGP_CHECK(glpgp_calloc((size_t)p->n + 1, sizeof(int), &p->vstart));
    GLPGP_CHECK(glpgp_calloc((size_t)p->n + 1, sizeof(int), &p->tstart));
    for (int v = 0; v < m->nv; v++) p->vstart[p->comp[v] + 1]++;
    for (int t = 0; t < m->nt; t++) p->tstart[p->comp[m->tri[3 * t]] + 1]++;
    for (int k = 0; k < p->n; k++) {
        p->vstart[k + 1] += p->vstart[k];
        p->tstart[k + 1] += p->tstart[k];
    }
    int *fill = NULL; /* per part: the vertices, then the triangles, placed so far */
    GLPGP_CHECK(glpgp_calloc((size_t)p->n, sizeof(int), &fill));
    for (int v = 0; v < m->nv; v++) {
        const int k = p->comp[v];
        p->vmap[v] = fill[k]++;
        p->vlist[p->vstart[k] + p->vmap[v]] = v;
    }
    memset(fill, 0, (size_t)p->n * sizeof(int));
    for (int t = 0; t < m->nt; t++) {
        const int k = p->comp[m->tri[3 * t]];
        p->tlist[p->tstart[k] + fill[k]++] = t;
    }
    free(fill);
    return GLPGP_OK;
}

/* Part k of m (vertices and triangles in their order) and r's values on it. */
static glpgp_status part(const glpgp_mesh *m, const glpgp_result *r, const parts *p, int k, glpgp_mesh **pm,
                         glpgp_result **pr)
{
    const int nv = p->vstart[k + 1] - p->vstart[k], nt = p->tstart[k + 1] - p->tstart[k];
    const int *vl = p->vlist + p->vstart[k], *tl = p->tlist + p->tstart[k];
    double *xyz = NULL;
    int *tri = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nv, sizeof(double), &xyz), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof(int), &tri), done);
    for (int i = 0; i < nv; i++) memcpy(xyz + 3 * i, m->xyz + 3 * vl[i], 3 * sizeof(double));
    for (int i = 0; i < nt; i++)
        for (int a = 0; a < 3; a++) tri[3 * i + a] = p->vmap[m->tri[3 * tl[i] + a]];
    GLPGP_CHECK_GOTO(st, glpgp_mesh_create_surface(nv, xyz, nt, tri, pm), done);
    GLPGP_CHECK_GOTO(st, glpgp_result_create(nv, nt, pr), done);
    glpgp_result *q = *pr;
    q->size = r->size;
    q->coupled = r->coupled;
    if (!r->field) {
        free(q->field);
        q->field = NULL;
    }
    for (int i = 0; i < nv; i++) {
        const int v = vl[i];
        if (r->field) memcpy(q->field + 2 * i, r->field + 2 * v, 2 * sizeof(double));
        for (int s = 0; s < 2; s++) {
            if (r->osc[s].z) memcpy(q->osc[s].z + 2 * i, r->osc[s].z + 2 * v, 2 * sizeof(double));
            if (r->osc[s].dirichlet) q->osc[s].dirichlet[i] = r->osc[s].dirichlet[v];
        }
    }
done:
    free(xyz);
    free(tri);
    return st;
}

/* The parts' quad meshes one after the other; their diagnostics summed. */
static glpgp_status join(glpgp_quadmesh *const *qp, int n, glpgp_quadmesh **out)
{
    int nv = 0, nf = 0, nc = 0;
    for (int k = 0; k < n; k++) {
        nv += qp[k]->nv;
        nf += qp[k]->nf;
        nc += qp[k]->face_start[qp[k]->nf];
    }
    GLPGP_CHECK(glpgp_qs_alloc(nv, nf, nc, out));
    glpgp_quadmesh *q = *out;
    int v0 = 0, f0 = 0;
    q->face_start[0] = 0;
    for (int k = 0; k < n; k++) {
        const glpgp_quadmesh *p = qp[k];
        memcpy(q->xyz + 3 * v0, p->xyz, (size_t)3 * p->nv * sizeof(double));
        memcpy(q->xy + 2 * v0, p->xy, (size_t)2 * p->nv * sizeof(double));
        for (int f = 0; f < p->nf; f++) {
            const int o = q->face_start[f0 + f];
            for (int i = p->face_start[f]; i < p->face_start[f + 1]; i++)
                q->face_vert[o + i - p->face_start[f]] = v0 + p->face_vert[i];
            q->face_start[f0 + f + 1] = o + p->face_start[f + 1] - p->face_start[f];
            q->face_origin[f0 + f] = p->face_origin ? p->face_origin[f] : GLPGP_QFACE_GRID;
        }
        for (int s = 0; s < 2; s++) {
            q->singular_tris[s] += p->singular_tris[s];
            q->inconsistent_tris[s] += p->inconsistent_tris[s];
        }
        q->collapsed_edges += p->collapsed_edges;
        q->promoted_corners += p->promoted_corners;
        q->split_pentagons += p->split_pentagons;
        q->center_splits += p->center_splits;
        q->closing.closed_polygons += p->closing.closed_polygons;
        q->closing.strips_to_boundary += p->closing.strips_to_boundary;
        q->closing.strip_quads += p->closing.strip_quads;
        q->closing.strip_turns += p->closing.strip_turns;
        q->closing.split_even += p->closing.split_even;
        q->closing.smoothed_vertices += p->closing.smoothed_vertices;
        q->repair.rounds = q->repair.rounds > p->repair.rounds ? q->repair.rounds : p->repair.rounds;
        q->repair.removed_faces += p->repair.removed_faces;
        q->repair.regions += p->repair.regions;
        q->repair.new_quads += p->repair.new_quads;
        q->repair.paved_regions += p->repair.paved_regions;
        q->repair.fallback_regions += p->repair.fallback_regions;
        for (int i = 0; i < p->repair.nlisted && q->repair.nlisted < GLPGP_QUADS_REGIONS_LISTED; i++)
            q->repair.region[q->repair.nlisted++] = p->repair.region[i];
        v0 += p->nv;
        f0 += p->nf;
    }
    return GLPGP_OK;
}

/* The parts' steps: counts summed, smallest scaled Jacobians the least, the
 * path (split, last resort) the largest part's. */
static void add_steps(glpgp_quads_surface_steps *a, const glpgp_quads_surface_steps *b, int largest)
{
    a->extracted_faces += b->extracted_faces;
    a->extracted_quads += b->extracted_quads;
    a->closed += b->closed;
    a->strips += b->strips;
    a->split_faces += b->split_faces;
    a->refined_faces += b->refined_faces;
    a->invalid_before |= b->invalid_before;
    if (b->local_regions) a->local_sj_min = a->local_regions ? fmin(a->local_sj_min, b->local_sj_min) : b->local_sj_min;
    a->local_regions += b->local_regions;
    a->local_faces_in += b->local_faces_in;
    a->local_quads_out += b->local_quads_out;
    if (b->smoothed) {
        a->sj_before = a->smoothed ? fmin(a->sj_before, b->sj_before) : b->sj_before;
        a->sj_after = a->smoothed ? fmin(a->sj_after, b->sj_after) : b->sj_after;
    }
    a->smoothed += b->smoothed;
    if (b->flat_corners) {
        a->flat_sj_before = a->flat_corners ? fmin(a->flat_sj_before, b->flat_sj_before) : b->flat_sj_before;
        a->flat_sj_after = a->flat_corners ? fmin(a->flat_sj_after, b->flat_sj_after) : b->flat_sj_after;
    }
    a->flat_corners += b->flat_corners;
    a->flat_faces += b->flat_faces;
    a->parts_last_resort += b->fallback;
    if (largest) {
        a->subdivided = b->subdivided;
        a->fallback = b->fallback;
        a->coarse_triangles = b->coarse_triangles;
    }
}

static glpgp_status build_parts(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                                glpgp_quadmesh **out, double *h, glpgp_quads_surface_steps *steps, const parts *p)
{
    const int n = p->n;
    glpgp_quadmesh **qp = NULL;
    glpgp_quads_surface_steps stp;
    memset(&stp, 0, sizeof stp);
    stp.parts = n;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK(glpgp_calloc((size_t)n, sizeof *qp, &qp));
    int best_nt = 0;
    for (int k = 0; k < n && st == GLPGP_OK; k++) {
        glpgp_mesh *pm = NULL;
        glpgp_result *pr = NULL;
        glpgp_quads_surface_steps ps;
        memset(&ps, 0, sizeof ps);
        st = part(m, r, p, k, &pm, &pr);
        if (st == GLPGP_OK) st = glpgp_qs_build_one(pm, pr, o, &qp[k], h, &ps);
        if (st == GLPGP_OK) {
            const int largest = pm->nt > best_nt;
            if (largest) best_nt = pm->nt;
            add_steps(&stp, &ps, largest);
            glpgp_log(n <= 10 ? GLPGP_LOG_INFO : GLPGP_LOG_DEBUG,
                      "quads: part %d of %d (%d triangles): %d faces%s", k + 1, n, pm->nt, qp[k]->nf,
                      ps.fallback ? ", by the last resort" : "");
        }
        glpgp_mesh_destroy(&pm);
        glpgp_result_destroy(&pr);
    }
    if (st == GLPGP_OK && n > 10)
        glpgp_log(GLPGP_LOG_INFO, "quads: %d parts meshed apart, %d of them by the last resort", n,
                  stp.parts_last_resort);
    if (st == GLPGP_OK) st = join(qp, n, out);
    for (int k = 0; k < n; k++) glpgp_quadmesh_destroy(&qp[k]);
    free(qp);
    if (st == GLPGP_OK && steps) *steps = stp;
    return st;
}

glpgp_status glpgp_quads_build_surface(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                                       glpgp_quadmesh **out, double *h, glpgp_quads_surface_steps *steps)
{
    *out = NULL;
    if (!m || !m->surf || !r || r->nv != m->nv || r->nt != m->nt || m->surf->ncomponents <= 1)
        return glpgp_qs_build_one(m, r, o, out, h, steps);
    parts p;
    glpgp_status st = parts_make(m, &p);
    if (st == GLPGP_OK)
        st = p.n > 1 ? build_parts(m, r, o, out, h, steps, &p) : glpgp_qs_build_one(m, r, o, out, h, steps);
    parts_free(&p);
    return st;
}
