/* quads/pipeline.c: the quad pipeline as the CLI runs it (glpgp_quads_build,
 * glpgp/quads.h): extraction, closing of the odd faces, smoothing, repair,
 * clean-up (kept only when no worse), all-quad refinement; with progress
 * lines on long meshes. */
#include "glpgp/quads.h"
#include "glpgp/surface.h"
#include "glpgp/status.h"
#include "glpgp/util.h"
#include "repair.h"

#include <stdlib.h>
/* ---- pipeline --------------------------------------------------------- */

/* The last shape pass (shape.c) on a copy of *q, kept when the mesh is as
 * valid as before, its worst quad (relative to what the domain's corners
 * allow) no worse and the irregular vertices not more than the split flat
 * corners and the re-meshed tips add. */
static glpgp_status shape_pass(glpgp_quadmesh **q, const glpgp_mesh *m, double h)
{
    glpgp_quadmesh *t = glpgp_qm_copy(*q);
    if (!t) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quads: no memory for the shape pass");
    int tips = 0, flat = 0, moved = 0;
    glpgp_quads_report q0, q1;
    glpgp_status st = glpgp_quadmesh_shape_pass(t, m, h, &tips, &flat, &moved);
    if (st == GLPGP_OK && (tips || flat || moved)) {
        st = glpgp_quads_quality(*q, m, h, &q0);
        if (st == GLPGP_OK) st = glpgp_quads_quality(t, m, h, &q1);
        if (st == GLPGP_OK && (q1.invalid & ~q0.invalid) == 0 && q1.sj_min_corner >= q0.sj_min_corner - 1e-12 &&
            q1.below_sj_goal <= q0.below_sj_goal && q1.irregular <= q0.irregular + flat + tips) {
            t->repair.sharp_tips = tips;
            t->repair.flat_corners = flat;
            t->repair.shaped_vertices = moved;
            glpgp_quadmesh_destroy(q);
            *q = t;
            t = NULL;
        } else if (st == GLPGP_OK) {
            glpgp_log(GLPGP_LOG_DEBUG, "quads: shape pass not kept (invalid 0x%x, worst %.3f -> %.3f, irregular %d -> %d)",
                      q1.invalid & ~q0.invalid, q0.sj_min_corner, q1.sj_min_corner, q0.irregular, q1.irregular);
        }
    }
    glpgp_quadmesh_destroy(&t);
    return st;
}

void glpgp_quads_options_default(glpgp_quads_options *o)
{
    o->keep_polygons = 0;
    o->smooth = 20;
    o->smooth_below = 0.5;
    o->all_quads = 0;
    o->repair = 1;
    o->cleanup = 1;
    o->feature_angle = GLPGP_FEATURE_ANGLE_DEFAULT;
}

glpgp_status glpgp_quads_build(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                               glpgp_quadmesh **out, double *h)
{
    glpgp_quads_options def;
    if (!o) {
        glpgp_quads_options_default(&def);
        o = &def;
    }
    *out = NULL;
    if (m && m->xyz) return glpgp_quads_build_surface(m, r, o, out, h, NULL); /* a 3D surface: its own pipeline */
    glpgp_quadmesh *q = NULL, *c = NULL;
    unsigned char *mark = NULL;
    glpgp_progress pr;
    glpgp_progress_start(&pr, "quads");
    glpgp_progress_set(&pr, "extracting the grid of %d triangles", m->nt);
    glpgp_status st = glpgp_quads_extract(m, r, &q);
    if (st == GLPGP_ERR_NUMERIC && o->repair) { /* no face: the repair meshes everything */
        glpgp_log(GLPGP_LOG_INFO, "quads: %s; the repair meshes the whole domain", glpgp_error_message());
        glpgp_error_clear();
        st = glpgp_calloc(1, sizeof *q, &q);
        if (st == GLPGP_OK) st = glpgp_calloc(1, sizeof(int), &q->face_start);
        if (st != GLPGP_OK) {
            glpgp_quadmesh_destroy(&q);
            return st;
        }
    }
    if (st != GLPGP_OK) {
        glpgp_progress_done(&pr, "no mesh");
        return st;
    }
    glpgp_progress_tick(&pr, "%d faces extracted; closing the odd ones", q->nf);
    if (!o->keep_polygons && q->nf > 0) {
        st = glpgp_quadmesh_close_polygons(q, &c, &mark);
        if (st != GLPGP_OK) goto done;
        glpgp_quadmesh_destroy(&q);
        q = c;
        c = NULL;
    }
    if (o->smooth > 0 && q->nf > 0) {
        int moved = 0;
        st = glpgp_quadmesh_smooth(q, mark, o->smooth, o->smooth_below, &moved);
        if (st != GLPGP_OK) goto done;
        q->closing.smoothed_vertices = moved;
    }
    if (o->repair) {
        glpgp_progress_tick(&pr, "%d faces; checking and repairing", q->nf);
        st = glpgp_quadmesh_repair(q, m, *h, o->smooth, o->keep_polygons, &c);
        if (st != GLPGP_OK) goto done;
        glpgp_quadmesh_destroy(&q);
        q = c;
        c = NULL;
    }
    if (o->cleanup && !o->keep_polygons) {
        glpgp_progress_tick(&pr, "%d faces; clean-up", q->nf);
        st = glpgp_quadmesh_cleanup(q, &c);
        if (st != GLPGP_OK) goto done;
        if (c) {
            /* kept only if it is as valid as before (by construction it
             * should be: the report's own checks make sure) */
            glpgp_quads_report q0, q1;
            st = glpgp_quads_quality(q, m, *h, &q0);
            if (st == GLPGP_OK) st = glpgp_quads_quality(c, m, *h, &q1);
            if (st != GLPGP_OK) goto done;
            /* kept only if as valid as before and with no more irregular
             * vertices (the operations lower the squared valence defect, which
             * may trade one valence-6 vertex for two irregular ones: the
             * strip of the hard domains, 61.9 -> 66.7 per 100 quads) */
            if ((q1.invalid & ~q0.invalid) == 0 && q1.irregular <= q0.irregular) {
                glpgp_quadmesh_destroy(&q);
                q = c;
                c = NULL;
            } else {
                if (q1.invalid & ~q0.invalid)
                    glpgp_log(GLPGP_LOG_WARNING, "quads: the clean-up made the mesh invalid (0x%x): not used",
                              q1.invalid & ~q0.invalid);
                glpgp_quadmesh_destroy(&c);
            }
        }
    }
    if (o->repair && !o->keep_polygons && q->nf > 0) {
        glpgp_progress_tick(&pr, "%d faces; shape pass", q->nf);
        st = shape_pass(&q, m, *h);
        if (st != GLPGP_OK) goto done;
    }
    if (o->all_quads) {
        st = glpgp_quadmesh_subdivide(q, &c);
        if (st != GLPGP_OK) goto done;
        glpgp_quadmesh_destroy(&q);
        q = c;
        c = NULL;
        *h *= 0.5;
    }
    *out = q;
    glpgp_progress_done(&pr, "%d faces", q->nf);
    q = NULL;
done:
    if (q) glpgp_progress_done(&pr, "stopped");
    free(mark);
    glpgp_quadmesh_destroy(&q);
    glpgp_quadmesh_destroy(&c);
    return st;
}
