/* quads/quads_surface.c: the quad pipeline on a 3D surface
 * (glpgp_quads_build_surface, glpgp/quads.h): the extraction
 * (extract_surface.c), the closing (close_surface.c), the local repair (repair_surface.c),
 * the local split of the bad faces and their quad strips (split_surface.c),
 * one Catmull-Clark split in 3D when those leave it invalid, the check
 * (check_surface.c), and the last resort that cannot fail: the input
 * triangles split into three quads each; then the smoothing and the split
 * of flat boundary corners (split_surface.c). */
#include "quads_surface.h"

#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_qs_alloc(int nv, int nf, int ncorner, glpgp_quadmesh **out)
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

void glpgp_qs_finish_from(glpgp_quadmesh *r, const glpgp_quadmesh *q)
{
    set_xy(r);
    memcpy(r->singular_tris, q->singular_tris, sizeof r->singular_tris);
    memcpy(r->inconsistent_tris, q->inconsistent_tris, sizeof r->inconsistent_tris);
}

static int cmp_ll(const void *pa, const void *pb)
{
    const long long *a = pa, *b = pb;
    return a[0] < b[0] ? -1 : a[0] > b[0] ? 1 : 0;
}

glpgp_status glpgp_qs_split_triangles(const double *xyz, int np, const int *tri, int nt, glpgp_quadmesh **out)
{
    *out = NULL;
    long long *key = NULL; /* (edge key, slot) pairs */
    int *mid = NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)6 * nt + 2, sizeof(long long), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt + 1, sizeof(int), &mid), done);
    for (int s = 0; s < 3 * nt; s++) {
        const long long a = tri[s], b = tri[s - s % 3 + (s % 3 + 1) % 3];
        key[2 * s] = a < b ? a * np + b : b * np + a;
        key[2 * s + 1] = s;
    }
    qsort(key, (size_t)3 * nt, 2 * sizeof(long long), cmp_ll);
    int nv = np;
    for (int i = 0; i < 3 * nt; i++) {
        if (i == 0 || key[2 * i] != key[2 * i - 2]) nv++;
        mid[key[2 * i + 1]] = nv - 1;
    }
    const int cen = nv;
    nv += nt;
    GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(nv, 3 * nt, 12 * nt, &q), done);
    memcpy(q->xyz, xyz, (size_t)3 * np * sizeof(double));
    for (int t = 0; t < nt; t++) {
        const int *v = tri + 3 * t;
        for (int d = 0; d < 3; d++) {
            q->xyz[3 * (cen + t) + d] = (xyz[3 * v[0] + d] + xyz[3 * v[1] + d] + xyz[3 * v[2] + d]) / 3.0;
            for (int k = 0; k < 3; k++)
                q->xyz[3 * mid[3 * t + k] + d] = 0.5 * (xyz[3 * v[k] + d] + xyz[3 * v[(k + 1) % 3] + d]);
        }
        for (int a = 0; a < 3; a++) {
            const int f = 3 * t + a;
            q->face_start[f] = 4 * f;
            q->face_vert[4 * f] = v[a];
            q->face_vert[4 * f + 1] = mid[3 * t + a];
            q->face_vert[4 * f + 2] = cen + t;
            q->face_vert[4 * f + 3] = mid[3 * t + (a + 2) % 3];
            q->face_origin[f] = GLPGP_QFACE_FALLBACK;
        }
    }
    q->face_start[q->nf] = 4 * q->nf;
    set_xy(q);
    *out = q;
done:
    free(key);
    free(mid);
    return st;
}

glpgp_status glpgp_quads_surface_fallback(const glpgp_mesh *m, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!glpgp_mesh_is_surface(m) || !m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "surface fallback: not a surface");
    const glpgp_mesh *s = m->surf->origin ? m->surf->origin : m;
    return glpgp_qs_split_triangles(s->xyz, s->nv, s->tri, s->nt, out);
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
    GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(nv, nc, 4 * nc, &r), done);
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
    glpgp_qs_finish_from(r, q);
    *out = r;
    r = NULL;
done:
    glpgp_quadmesh_destroy(&r);
    free(key);
    free(mid);
    return st;
}


/* Its Catmull-Clark split with the new points on the surface. */
static glpgp_status split_onto(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, glpgp_quadmesh **out)
{
    glpgp_status st = glpgp_quadmesh_subdivide_surface(q, out);
    if (st == GLPGP_OK) st = glpgp_qs_project(m, h, (*out)->xyz, q->nv, (*out)->nv);
    if (st == GLPGP_OK) set_xy(*out);
    else glpgp_quadmesh_destroy(out);
    return st;
}

/* The names of the GLPGP_QUADS_BAD_* bits in bad, comma-separated. */
static void bad_names(unsigned bad, char *why, size_t n)
{
    size_t w = 0;
    why[0] = 0;
    for (int b = 0; b < GLPGP_QUADS_BAD_COUNT && w < n; b++)
        if (bad & (1u << b)) {
            int k = snprintf(why + w, n - w, "%s%s", w ? ", " : "", glpgp_quads_bad_name(1u << b));
            if (k > 0) w += (size_t)k;
        }
}

/* The invalidity bits of q (less non-quads with keep_polygons). */
static glpgp_status verdict_of(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int keep_polygons,
                               unsigned *bad)
{
    glpgp_quads_report qq;
    GLPGP_CHECK(glpgp_quads_quality_surface(q, m, h, &qq));
    *bad = qq.invalid & ~(keep_polygons ? (unsigned)GLPGP_QUADS_BAD_NONQUAD : 0u);
    if (*bad) { /* which checks failed, by name */
        char why[256];
        bad_names(*bad, why, sizeof why);
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: surface candidate of %d faces not valid: %s (Hausdorff %.3f h, area ratio %.4f, %d inverted, "
                  "%d not quads)",
                  q->nf, why, qq.hausdorff, qq.area_ratio, qq.inverted, qq.others);
    }
    return GLPGP_OK;
}

/* The regions of a local repair pass b added to those of the passes before (a). */
static void add_regions(glpgp_quads_repair *a, const glpgp_quads_repair *b, int pass)
{
    a->rounds += b->rounds;
    a->regions += b->regions;
    a->paved_regions += b->paved_regions;
    a->removed_faces += b->removed_faces;
    a->new_quads += b->new_quads;
    for (int i = 0; i < b->nlisted && a->nlisted < GLPGP_QUADS_REGIONS_LISTED; i++) {
        a->region[a->nlisted] = b->region[i];
        a->region[a->nlisted++].round = pass;
    }
}

/* The local repair of q (glpgp_qs_local_repair; far: faces far from the
 * surface repaired too), run again on what a pass left bad (3 passes):
 * *out the last pass's mesh (NULL: no region repaired), *bad its
 * invalidity bits, *rs the regions of every pass. */
static glpgp_status local_repair(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int far, glpgp_quadmesh **out,
                                 unsigned *bad, glpgp_quads_repair *rs)
{
    glpgp_quads_repair one;
    glpgp_quads_report qq;
    memset(rs, 0, sizeof *rs);
    *out = NULL;
    *bad = 0;
    for (int pass = 0; pass < 3; pass++) {
        glpgp_quadmesh *r = NULL;
        GLPGP_CHECK(glpgp_qs_local_repair(m, *out ? *out : q, h, far, &r, &one));
        if (!r) break;
        glpgp_quadmesh_destroy(out);
        *out = r;
        add_regions(rs, &one, pass);
        GLPGP_CHECK(glpgp_quads_quality_surface(*out, m, h, &qq));
        *bad = qq.invalid;
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: surface local repair (pass %d%s): %d regions, %d faces -> %d quads; %s (0x%x: %d inverted, "
                  "Hausdorff %.3f h (quads->surface %.3f, surface->quads %.3f), area ratio %.4f)",
                  pass, far ? ", far faces too" : "", one.regions, one.removed_faces, one.new_quads,
                  *bad ? "not valid" : "valid", *bad, qq.inverted, qq.hausdorff, qq.dist_quad_to_domain,
                  qq.dist_domain_to_quad, qq.area_ratio);
        if (!*bad) break;
    }
    if (*out) {
        memset(&(*out)->closing, 0, sizeof (*out)->closing);
        (*out)->repair = *rs;
    }
    return GLPGP_OK;
}

/* The local repair's regions into stp. */
static void note_local(glpgp_quads_surface_steps *stp, const glpgp_quads_repair *rs)
{
    stp->local_regions = rs->regions;
    stp->local_faces_in = rs->removed_faces;
    stp->local_quads_out = rs->new_quads;
    stp->local_sj_min = 1.0;
    for (int i = 0; i < rs->nlisted; i++) stp->local_sj_min = fmin(stp->local_sj_min, rs->region[i].sj_min);
}

static glpgp_status split_local_repair(const glpgp_mesh *m, const glpgp_quadmesh *base, double h,
                                       glpgp_quads_surface_steps *stp, glpgp_quadmesh **out);

/* Whether invalidity bits bad name only the distance or the area (a grid
 * too coarse for the surface somewhere), or nothing. */
static int only_far(unsigned bad)
{
    return !(bad & ~(unsigned)(GLPGP_QUADS_BAD_HAUSDORFF | GLPGP_QUADS_BAD_AREA));
}

/* The local 3-refinement (glpgp_qs_refine3) of base's far faces (all quads,
 * valid but for the distance or the area), twice at most while only those
 * fail; a refinement with other bad faces gets their local repair (no
 * split) first. Far: a face sample over R3_FAR h from the surface, or the
 * face nearest to a surface point that far from the mesh. A refinement to
 * over R3_GROWTH x base's faces is left to the global split (4 x, and no
 * transition templates: each leaves irregular vertices). *out NULL: none
 * is valid. */
#define R3_GROWTH 2 /* the refinement's faces at most this many times the mesh's */
#define R3_FAR 0.22 /* a surface point farther from the mesh (in h): its nearest face refined (as the repair's far faces) */

static glpgp_status refine3_repair(const glpgp_mesh *m, const glpgp_quadmesh *base, double h,
                                   glpgp_quads_surface_steps *stp, glpgp_quadmesh **out)
{
    glpgp_quadmesh *own = NULL, *s = NULL;
    unsigned char *sel = NULL;
    const glpgp_quadmesh *b = base;
    int refined = 0;
    glpgp_status st = GLPGP_OK;
    *out = NULL;
    for (int level = 0; level < 2 && st == GLPGP_OK && !*out; level++) {
        int nbad = 0, nref = 0;
        unsigned bad = 0;
        free(sel);
        sel = NULL;
        st = glpgp_malloc((size_t)b->nf + 1, 1, &sel);
        if (st == GLPGP_OK) st = glpgp_qs_bad_faces(m, b, h, 1, sel, &nbad);
        int nunc = 0; /* and the faces nearest to the surface's points far from the mesh */
        if (st == GLPGP_OK) st = glpgp_qs_mark_uncovered(m, b, h, R3_FAR * h, sel, &nunc);
        nbad += nunc;
        if (st == GLPGP_OK && nbad) st = glpgp_qs_refine3(m, b, h, sel, &s, &nref);
        if (st != GLPGP_OK || !s) break;
        if (s->nf > R3_GROWTH * base->nf) { /* as many quads as the global split's: its job (no transitions) */
            glpgp_log(GLPGP_LOG_DEBUG, "quads: 3-refinement %d: %d of %d faces refined -> %d quads, not local", level,
                      nref, b->nf, s->nf);
            break;
        }
        refined += nref;
        st = verdict_of(m, s, h, 0, &bad);
        glpgp_log(GLPGP_LOG_DEBUG, "quads: 3-refinement %d: %d far faces of %d, %d faces refined -> %d quads; %s", level,
                  nbad, b->nf, nref, s->nf, bad ? "not valid" : "valid");
        if (st != GLPGP_OK) break;
        if (!bad) {
            *out = s;
            s = NULL;
            break;
        }
        if (!only_far(bad)) { /* its bad faces repaired */
            glpgp_quads_repair rs;
            glpgp_quadmesh *t = NULL;
            st = local_repair(m, s, h, 0, &t, &bad, &rs);
            if (st != GLPGP_OK || !t || !only_far(bad)) {
                glpgp_quadmesh_destroy(&t);
                break;
            }
            glpgp_quadmesh_destroy(&s);
            s = t;
            if (!bad) {
                *out = s;
                s = NULL;
                break;
            }
        }
        glpgp_quadmesh_destroy(&own); /* still too far somewhere: refined again */
        own = s;
        s = NULL;
        b = own;
    }
    if (*out) stp->refined_faces = refined;
    glpgp_quadmesh_destroy(&own);
    glpgp_quadmesh_destroy(&s);
    free(sel);
    return st;
}

/* The local repair's candidates: the repaired mesh (bad faces but the far
 * ones); with split, when only the distance or the area fails (a grid too
 * coarse for the surface somewhere): the local split of its far faces,
 * their local 3-refinement, the repair with the far faces too, then its
 * whole split; last (or without
 * split) the repair with the far faces too. *out NULL: none is valid. */
static glpgp_status repaired(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int split,
                             glpgp_quads_surface_steps *stp, glpgp_quadmesh **out)
{
    glpgp_quadmesh *r = NULL, *s = NULL;
    glpgp_quads_repair rs;
    unsigned bad = 0;
    int tried_far = 0;
    *out = NULL;
    glpgp_status st = local_repair(m, q, h, 0, &r, &bad, &rs);
    if (st == GLPGP_OK && r && !bad) goto keep_r;
    if (st == GLPGP_OK && r && split && only_far(bad)) {
        st = split_local_repair(m, r, h, stp, &s); /* the far faces split with their strips */
        if (st == GLPGP_OK && s) {
            glpgp_quadmesh_destroy(&r);
            *out = s;
            return GLPGP_OK;
        }
    }
    if (st == GLPGP_OK && r && split && only_far(bad)) {
        /* the strips ran through most of the mesh: the far faces refined 3 x 3, templates around
         * (more irregular vertices than the strips' split where that closes soon) */
        st = refine3_repair(m, r, h, stp, &s);
        if (st == GLPGP_OK && s) {
            s->repair = rs;
            note_local(stp, &rs);
            glpgp_quadmesh_destroy(&r);
            *out = s;
            return GLPGP_OK;
        }
    }
    if (st == GLPGP_OK && r && split && only_far(bad)) {
        /* the far faces repaired too, before the whole mesh is split (4x the quads) */
        glpgp_quadmesh *f = NULL;
        glpgp_quads_repair fs;
        unsigned fbad = 0;
        tried_far = 1;
        st = local_repair(m, q, h, 1, &f, &fbad, &fs);
        if (st == GLPGP_OK && f && !fbad) {
            glpgp_quadmesh_destroy(&r);
            r = f;
            rs = fs;
            goto keep_r;
        }
        glpgp_quadmesh_destroy(&f);
    }
    if (st == GLPGP_OK && r && split && only_far(bad)) {
        st = split_onto(m, r, h, &s);
        if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
        if (st == GLPGP_OK && bad) { /* the split's own bad faces repaired locally */
            glpgp_quadmesh *t = NULL;
            glpgp_quads_surface_steps st2;
            memset(&st2, 0, sizeof st2);
            st = repaired(m, s, h, 0, &st2, &t);
            if (st == GLPGP_OK && t) {
                glpgp_quadmesh_destroy(&s);
                s = t;
                bad = 0;
                add_regions(&rs, &s->repair, 1);
            }
        }
        if (st == GLPGP_OK && !bad) {
            s->repair = rs;
            stp->subdivided = 1;
            note_local(stp, &rs);
            glpgp_quadmesh_destroy(&r);
            *out = s;
            return GLPGP_OK;
        }
        glpgp_quadmesh_destroy(&s);
    }
    glpgp_quadmesh_destroy(&r);
    if (st == GLPGP_OK && !tried_far) st = local_repair(m, q, h, 1, &r, &bad, &rs);
    if (st == GLPGP_OK && r && !bad) goto keep_r;
    glpgp_quadmesh_destroy(&r);
    return st;
keep_r:
    note_local(stp, &rs);
    *out = r;
    return GLPGP_OK;
}

/* The local split (glpgp_qs_split_local) of base's bad faces (the far ones
 * too) and the quad strips through them, then the local repair of what it
 * leaves bad; again (twice at most) on the partial repair of the split.
 * A split of over half the faces is left to the global split. *out NULL:
 * none is valid. */
static glpgp_status split_local_repair(const glpgp_mesh *m, const glpgp_quadmesh *base, double h,
                                       glpgp_quads_surface_steps *stp, glpgp_quadmesh **out)
{
    glpgp_quadmesh *own = NULL, *s = NULL, *t = NULL;
    unsigned char *sel = NULL;
    const glpgp_quadmesh *b = base;
    int split = 0;
    *out = NULL;
    glpgp_status st = glpgp_malloc((size_t)base->nf + 1, 1, &sel);
    for (int level = 0; level < 2 && st == GLPGP_OK && !*out; level++) {
        int nbad = 0, ns = 0;
        unsigned bad = 0;
        unsigned char *grown = realloc(sel, (size_t)b->nf + 1);
        if (!grown) st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (local split)");
        else sel = grown;
        if (st == GLPGP_OK) st = glpgp_qs_bad_faces(m, b, h, 1, sel, &nbad);
        if (st != GLPGP_OK || nbad == 0) break;
        if (st == GLPGP_OK) st = glpgp_qs_split_local(m, b, h, sel, &s, &ns);
        if (st == GLPGP_OK && 2 * ns > b->nf) { /* the strips ran through most of the mesh: the global split's job */
            glpgp_log(GLPGP_LOG_DEBUG, "quads: local split %d: %d of %d faces split, not local", level, ns, b->nf);
            break;
        }
        if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
        if (st != GLPGP_OK) break;
        split += ns;
        glpgp_log(GLPGP_LOG_DEBUG, "quads: local split %d: %d bad faces of %d, %d faces split -> %d quads; %s", level,
                  nbad, b->nf, ns, s->nf, bad ? "not valid" : "valid");
        if (!bad) {
            *out = s;
            s = NULL;
            break;
        }
        glpgp_quads_surface_steps st2;
        memset(&st2, 0, sizeof st2);
        st = repaired(m, s, h, 0, &st2, &t);
        if (st == GLPGP_OK && t) {
            stp->local_regions = st2.local_regions;
            stp->local_faces_in = st2.local_faces_in;
            stp->local_quads_out = st2.local_quads_out;
            stp->local_sj_min = st2.local_sj_min;
            *out = t;
            t = NULL;
            break;
        }
        glpgp_quads_repair rs; /* the next level on the split's partial repair */
        glpgp_quadmesh *r = NULL;
        if (st == GLPGP_OK) st = local_repair(m, s, h, 1, &r, &bad, &rs);
        glpgp_quadmesh_destroy(&own);
        if (r) {
            own = r;
            glpgp_quadmesh_destroy(&s);
        } else {
            own = s;
            s = NULL;
        }
        b = own;
    }
    if (*out) stp->split_faces = split;
    glpgp_quadmesh_destroy(&own);
    glpgp_quadmesh_destroy(&s);
    glpgp_quadmesh_destroy(&t);
    free(sel);
    return st;
}

/* The strips' all-quad mesh *t of closed mesh c against the local repair
 * of c: when *t is valid and the repair (which re-meshes the odd faces'
 * regions instead) is valid with fewer irregular interior vertices (a
 * strip that turns leaves a 3-5 pair), *s the repair (stp its steps) and
 * *t NULL; an invalid *t is left as it is (its bad faces are the caller's
 * repair's). */
static glpgp_status strips_or_repair(const glpgp_mesh *m, double h, const glpgp_quadmesh *c, glpgp_quadmesh **t,
                                     glpgp_quads_surface_steps *stp, glpgp_quadmesh **s)
{
    unsigned bad = 0;
    glpgp_quads_surface_steps st2 = *stp;
    *s = NULL;
    GLPGP_CHECK(verdict_of(m, *t, h, 0, &bad));
    if (bad) return GLPGP_OK; /* the caller repairs *t's bad faces */
    GLPGP_CHECK(repaired(m, c, h, 1, &st2, s));
    const int it = glpgp_qs_irregular_interior(*t), is = *s ? glpgp_qs_irregular_interior(*s) : INT_MAX;
    glpgp_log(GLPGP_LOG_DEBUG, "quads: surface strips: %d irregular interior vertices, the local repair %d", it,
              *s ? is : -1);
    if (*s && is >= 0 && it >= 0 && is < it) {
        glpgp_quadmesh_destroy(t);
        *stp = st2;
        return GLPGP_OK;
    }
    glpgp_quadmesh_destroy(s);
    return GLPGP_OK;
}

/* The candidates in order, the first valid one kept: the extraction (all
 * quads, or polygons with keep_polygons), the closed mesh when all quads,
 * the split of the closed mesh, the split of the extraction. *out NULL:
 * none is valid (*bad: the extraction's reasons). */
static glpgp_status candidates(const glpgp_mesh *m, glpgp_quadmesh **pq, const glpgp_quads_options *o, double h,
                               glpgp_quads_surface_steps *stp, glpgp_quadmesh **out, unsigned *bad0)
{
    glpgp_quadmesh *q = *pq, *c = NULL, *s = NULL;
    unsigned bad;
    *out = NULL;
    GLPGP_CHECK(verdict_of(m, q, h, o->keep_polygons, bad0));
    if (!*bad0 || o->keep_polygons || !o->repair) {
        *out = q;
        *pq = NULL;
        return GLPGP_OK;
    }
    glpgp_status st = glpgp_qs_close_pairs(m, h, q, &c, &stp->closed);
    if (st == GLPGP_OK)
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface closing: %d faces made quads, %d of %d faces not quads left",
                  stp->closed, c ? glpgp_qs_count_nonquads(c) : glpgp_qs_count_nonquads(q), c ? c->nf : q->nf);
    if (st == GLPGP_OK && glpgp_qs_count_nonquads(c ? c : q)) { /* strips between the odd faces left */
        glpgp_quadmesh *t = NULL;
        int ns = 0, cl = 0;
        st = glpgp_qs_strips_closed(m, h, c ? c : q, &t, &ns, &cl);
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface strips: %d, %d faces not quads left", ns,
                  t ? 0 : glpgp_qs_count_nonquads(c ? c : q));
        if (st == GLPGP_OK && t) st = strips_or_repair(m, h, c ? c : q, &t, stp, &s);
        if (st == GLPGP_OK && s) {
            glpgp_quadmesh_destroy(&c);
            goto keep_r;
        }
        if (st == GLPGP_OK && t) {
            glpgp_quadmesh_destroy(&c);
            c = t;
            stp->strips = ns;
            stp->closed += cl;
        }
    }
    if (st == GLPGP_OK && c && !glpgp_qs_count_nonquads(c)) {
        st = verdict_of(m, c, h, 0, &bad);
        if (st == GLPGP_OK && !bad) goto keep_c;
    }
    if (st == GLPGP_OK) {
        st = repaired(m, c ? c : q, h, 1, stp, &s);
        if (st == GLPGP_OK && s) goto keep_r;
    }
    if (st == GLPGP_OK) { /* the bad regions split with their quad strips, then repaired */
        st = split_local_repair(m, c ? c : q, h, stp, &s);
        if (st == GLPGP_OK && s) goto keep_r;
    }
    if (st == GLPGP_OK && c && glpgp_qs_count_nonquads(c) < glpgp_qs_count_nonquads(q)) {
        st = split_onto(m, c, h, &s);
        if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
        if (st == GLPGP_OK && !bad) goto keep_s;
        glpgp_log(GLPGP_LOG_DEBUG, "quads: the closed mesh's split is not valid (0x%x)", bad);
        if (st == GLPGP_OK) { /* its bad faces repaired locally */
            glpgp_quadmesh *r = NULL;
            st = repaired(m, s, h, 0, stp, &r);
            if (st == GLPGP_OK && r) {
                glpgp_quadmesh_destroy(&s);
                s = r;
                goto keep_s;
            }
        }
        glpgp_quadmesh_destroy(&s);
    }
    stp->closed = 0;
    if (st == GLPGP_OK) st = split_onto(m, q, h, &s);
    if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
    if (st == GLPGP_OK && !bad) goto keep_s;
    glpgp_quadmesh_destroy(&s);
    glpgp_quadmesh_destroy(&c);
    return st;
keep_c:
    memset(&c->closing, 0, sizeof c->closing); /* the surface's steps are in stp */
    *out = c;
    return GLPGP_OK;
keep_r:
    *out = s;
    glpgp_quadmesh_destroy(&c);
    return GLPGP_OK;
keep_s:
    stp->subdivided = 1;
    *out = s;
    glpgp_quadmesh_destroy(&c);
    return GLPGP_OK;
}

/* The smoothing on the surface (o->smooth sweeps, glpgp_quads_smooth_surface) of a
 * valid mesh, undone when the smoothed mesh is not valid (the check's
 * Hausdorff distance or area). */
static glpgp_status smooth_valid(const glpgp_mesh *m, double h, const glpgp_quads_options *o, glpgp_quadmesh *q,
                                 glpgp_quads_surface_steps *stp)
{
    glpgp_quads_report qq;
    GLPGP_CHECK(glpgp_quads_quality_surface(q, m, h, &qq));
    stp->sj_before = stp->sj_after = qq.sj_min;
    if (o->smooth <= 0 || o->keep_polygons || !o->repair || qq.invalid) return GLPGP_OK;
    double *keep = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * q->nv + 1, sizeof(double), &keep));
    memcpy(keep, q->xyz, (size_t)3 * q->nv * sizeof(double));
    int moved = 0;
    glpgp_status st = glpgp_quads_smooth_surface(m, h, o->feature_angle, o->smooth, q, &moved);
    if (st == GLPGP_OK && moved) st = glpgp_quads_quality_surface(q, m, h, &qq);
    if (st == GLPGP_OK && moved && !qq.invalid) {
        stp->smoothed = moved;
        stp->sj_after = qq.sj_min;
        q->closing.smoothed_vertices = moved; /* the report's closing.smoothed_vertices */
    } else if (moved) {
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: the surface smoothing undone: the smoothed mesh is not valid (0x%x, Hausdorff %.3f h: quads "
                  "to surface %.3f h, surface to quads %.3f h; area ratio %.4f)",
                  qq.invalid, qq.hausdorff, qq.dist_quad_to_domain, qq.dist_domain_to_quad, qq.area_ratio);
        memcpy(q->xyz, keep, (size_t)3 * q->nv * sizeof(double));
        set_xy(q);
    }
    free(keep);
    glpgp_log(GLPGP_LOG_DEBUG, "quads: surface smoothing: %d vertices moved, smallest scaled Jacobian %.3f -> %.3f",
              stp->smoothed, stp->sj_before, stp->sj_after);
    return st;
}

/* Flat boundary corners (glpgp_qs_find_flat, split_surface.c) of a valid
 * mesh below FLAT_GOAL, split like triangles and smoothed; the result kept
 * when it is valid and its smallest scaled Jacobian higher. */
#define FLAT_GOAL 0.3

static glpgp_status flat_corners(const glpgp_mesh *m, double h, const glpgp_quads_options *o, glpgp_quadmesh **pq,
                                 glpgp_quads_surface_steps *stp)
{
    glpgp_quadmesh *q = *pq, *r = NULL;
    if (o->keep_polygons || !o->repair) return GLPGP_OK;
    signed char *flat = NULL;
    int nflat = 0, nsplit = 0, moved = 0;
    glpgp_quads_report before, after;
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, 1, &flat));
    glpgp_status st = glpgp_qs_find_flat(q, FLAT_GOAL, flat, &nflat);
    if (st == GLPGP_OK && nflat) st = glpgp_quads_quality_surface(q, m, h, &before);
    if (st == GLPGP_OK && nflat && !before.invalid) st = glpgp_qs_split_flat(m, q, h, flat, &r, &nsplit);
    double *keep = NULL; /* the split before its smoothing: tried again when the smoothed one is not valid */
    if (st == GLPGP_OK && r && o->smooth > 0) st = glpgp_malloc((size_t)3 * r->nv + 1, sizeof(double), &keep);
    if (st == GLPGP_OK && keep) {
        memcpy(keep, r->xyz, (size_t)3 * r->nv * sizeof(double));
        st = glpgp_quads_smooth_surface(m, h, o->feature_angle, o->smooth, r, &moved);
    }
    if (st == GLPGP_OK && r) st = glpgp_quads_quality_surface(r, m, h, &after);
    if (st == GLPGP_OK && r && keep && after.invalid) {
        memcpy(r->xyz, keep, (size_t)3 * r->nv * sizeof(double));
        set_xy(r);
        st = glpgp_quads_quality_surface(r, m, h, &after);
    }
    free(keep);
    if (st == GLPGP_OK && r && !after.invalid && after.sj_min > before.sj_min) {
        glpgp_log(GLPGP_LOG_INFO,
                  "quads: %d flat boundary corners split (%d faces split, %d -> %d quads): smallest scaled "
                  "Jacobian %.3f -> %.3f",
                  nflat, nsplit, q->nf, r->nf, before.sj_min, after.sj_min);
        r->collapsed_edges = q->collapsed_edges;
        r->promoted_corners = q->promoted_corners;
        r->split_pentagons = q->split_pentagons;
        r->center_splits = q->center_splits;
        r->closing = q->closing;
        r->repair = q->repair;
        r->cleanup = q->cleanup;
        stp->flat_corners = nflat;
        stp->flat_faces = nsplit;
        stp->flat_sj_before = before.sj_min;
        stp->flat_sj_after = after.sj_min;
        glpgp_quadmesh_destroy(pq);
        *pq = r;
        r = NULL;
    } else if (st == GLPGP_OK && r) {
        char why[160] = "";
        bad_names(after.invalid, why, sizeof why);
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: %d flat boundary corners: the split is %s%s (smallest scaled Jacobian %.3f -> %.3f, "
                  "Hausdorff %.3f h, area ratio %.4f)",
                  nflat, after.invalid ? "not valid: " : "no better", why, before.sj_min, after.sj_min,
                  after.hausdorff, after.area_ratio);
    }
    glpgp_quadmesh_destroy(&r);
    free(flat);
    return st;
}

/* The last resort: the coarse triangulation split into quads when it is
 * valid: tolerant at a 17 degree angle floor from the mesh before the
 * solve's refinement where it was kept (the same surface, a refinement's
 * factor fewer triangles to coarsen), then with the strict rules at 17 and
 * 20 from m
 * (glpgp_qs_coarse; measured on genus 2, the torus and a 20-hole sphere,
 * 17 gives 2-4x fewer quads with a higher smallest scaled Jacobian, but 16
 * already failed once), else the input's own triangles split (valid by
 * construction). */
static glpgp_status last_resort(const glpgp_mesh *m, double h, double feature_deg, glpgp_quadmesh **out,
                                glpgp_quads_surface_steps *stp)
{
    static const double amin[3] = {17.0, 17.0, 20.0};
    static const int tolerant[3] = {1, 0, 0};
    int nt = 0;
    unsigned bad = 0;
    for (int k = 0; k < 3; k++) {
        const glpgp_mesh *mc = tolerant[k] && m->surf->origin ? m->surf->origin : m;
        glpgp_status st = glpgp_qs_coarse(mc, h, feature_deg, amin[k], tolerant[k], out, &nt);
        if (st == GLPGP_OK) st = verdict_of(m, *out, h, 0, &bad);
        if (st == GLPGP_OK && !bad) {
            stp->coarse_triangles = nt;
            glpgp_log(GLPGP_LOG_INFO, "quads: the last resort: %d triangles of the %d input ones, split into quads",
                      nt, mc->nt);
            return GLPGP_OK;
        }
        glpgp_quadmesh_destroy(out);
        if (st != GLPGP_OK) return st;
        glpgp_log(GLPGP_LOG_INFO, "quads: the coarse last resort (%g degrees%s, %d triangles) is not valid (0x%x)",
                  amin[k], tolerant[k] ? ", tolerant" : "", nt, bad);
    }
    return glpgp_quads_surface_fallback(m, out);
}

glpgp_status glpgp_qs_build_one(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                                glpgp_quadmesh **out, double *h, glpgp_quads_surface_steps *steps)
{
    glpgp_quads_options def;
    glpgp_quads_surface_steps stp;
    if (!o) {
        glpgp_quads_options_default(&def);
        o = &def;
    }
    memset(&stp, 0, sizeof stp);
    *out = NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_status st = glpgp_quads_extract_surface(m, r, &q);
    if (st == GLPGP_ERR_NUMERIC && o->repair) {
        glpgp_log(GLPGP_LOG_DEBUG, "quads: %s; the last resort follows", glpgp_error_message());
        glpgp_error_clear();
        st = GLPGP_OK;
    }
    if (st != GLPGP_OK) return st;
    if (q) {
        stp.extracted_faces = q->nf;
        stp.extracted_quads = q->nf - glpgp_qs_count_nonquads(q);
        unsigned bad = 0;
        st = candidates(m, &q, o, *h, &stp, out, &bad);
        if (st == GLPGP_OK && *out) st = smooth_valid(m, *h, o, *out, &stp);
        if (st == GLPGP_OK && *out) st = flat_corners(m, *h, o, out, &stp);
        if (st != GLPGP_OK) glpgp_quadmesh_destroy(out);
        if (st != GLPGP_OK || *out) {
            glpgp_quadmesh_destroy(&q);
            if (st == GLPGP_OK && steps) *steps = stp;
            return st;
        }
        char why[256]; /* the reasons by name (the counts are in the report) */
        bad_names(bad & ~(unsigned)GLPGP_QUADS_BAD_NONQUAD, why, sizeof why);
        glpgp_log(GLPGP_LOG_WARNING,
                  "quads: the extracted mesh is not valid%s%s%s: the last resort follows (a coarsened "
                  "triangulation split into quads, else the input's triangles)",
                  why[0] ? " (" : "", why, why[0] ? ")" : "");
        stp.invalid_before = bad;
        glpgp_quadmesh_destroy(&q);
    }
    stp.fallback = 1;
    st = last_resort(m, *h, o->feature_angle, out, &stp);
    if (st == GLPGP_OK) st = smooth_valid(m, *h, o, *out, &stp);
    if (st == GLPGP_OK) st = flat_corners(m, *h, o, out, &stp);
    if (st != GLPGP_OK) glpgp_quadmesh_destroy(out);
    if (st == GLPGP_OK && steps) *steps = stp;
    return st;
}
