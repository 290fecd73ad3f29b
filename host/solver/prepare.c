/* solver/prepare.c: what `glpgp solve` (and the Python glpgp.solve) does
 * between reading a domain and glpgp_solve (glpgp_solve_prepare,
 * glpgp/solve.h): the sliver warning, the default size of a too coarse
 * input, the size checks against the mesh and --max-elements, an early read
 * of a field file, and the refinement of the triangles too coarse for the
 * local size. One copy, so that every front end solves the same mesh with
 * the same options. */
#include "glpgp/cross.h"
#include "glpgp/solve.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"
#include "glpgp/internal/newton.h"
#include "internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* one warning naming the remedy when 1% or more of the triangles are slivers */
static void warn_slivers(const glpgp_mesh *m, const char *name)
{
    double amin;
    int nsliver;
    glpgp_mesh_angles(m, GLPGP_SLIVER_DEG, &amin, &nsliver);
    if (!(nsliver > 0 && nsliver >= 0.01 * m->nt)) return;
    if (m->xyz) /* --remesh and glpgp mesh are planar (Gmsh inside the boundary points): no remedy to name here */
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d of %d triangles have an angle below %g degrees (smallest %.3g): the solution is "
                  "inaccurate on such slivers and refinement keeps them thin (an isotropic remesh of the surface "
                  "elsewhere helps)",
                  name, nsliver, m->nt, GLPGP_SLIVER_DEG, amin);
    else
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d of %d triangles have an angle below %g degrees (smallest %.3g): the solution is "
                  "inaccurate on such slivers and refinement keeps them thin; remesh the domain first "
                  "(--remesh, or glpgp mesh %s -o NEW.msh)",
                  name, nsliver, m->nt, GLPGP_SLIVER_DEG, amin, name);
}

/* The checks on the options and sizes before any work: the refinement's
 * size against max_triangles, h against the mesh. */
static glpgp_status check_sizes(const glpgp_mesh *m, const glpgp_options *o, int refine, double max_triangles)
{
    /* below 2 mean edges the mesh is refined to edges of h / R (R =
     * size_resolution) at least: 2.31 area / (h / R)^2 triangles
     * (equilateral), refused before any work above max_triangles (the
     * refinement's own limits would stop it only after seconds and
     * gigabytes) */
    const double l_ref = o->size / o->size_resolution;
    const int below = refine && o->size > 0.0 && o->size < GLPGP_SIZE_MIN_EDGES * m->mean_edge;
    if (below && max_triangles > 0 && !(2.31 * m->area / (l_ref * l_ref) <= max_triangles))
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "size h = %g is %.3g mean edge lengths of the mesh: refined for it, the mesh would "
                          "have about %.3g triangles, more than --max-elements %.0f",
                          o->size, o->size / m->mean_edge, 2.31 * m->area / (l_ref * l_ref), max_triangles);
    if (below) {
        glpgp_options big = *o;
        big.size = GLPGP_SIZE_MIN_EDGES * m->mean_edge; /* the other rules (diameter, options) */
        return glpgp_options_check_mesh(&big, m);
    }
    return glpgp_options_check_mesh(o, m);
}

/* a field file read now: a bad one fails before the backend starts (the
 * solve reads it again) */
static glpgp_status check_field(const glpgp_mesh *m, const glpgp_options *o)
{
    if (o->field != GLPGP_FIELD_FILE) return GLPGP_OK;
    double *u = NULL;
    long cg = 0;
    glpgp_status st = glpgp_malloc(2 * (size_t)m->nv, sizeof *u, &u);
    if (st == GLPGP_OK) st = glpgp_field_compute(m, NULL, o, u, &cg);
    free(u);
    return st;
}

/* A surface too coarse for its size (an edge above h(x) /
 * GLPGP_SURFACE_EDGES, h(x) the local size the solve uses: the curvature
 * cap and the feature spacing with --size-field auto / iso, else h; the
 * oscillators collapse towards z = 0 at about 4 mean edges per period) is
 * refined by longest-edge bisection (glpgp_surface_refine_local) until no
 * edge is longer, only where it is coarser (the same surface), within
 * max_triangles; *out NULL when no edge needed it. The refined mesh keeps
 * a copy of m for the cross field (--cross-mesh input, polish). */
static glpgp_status refine_surface(const glpgp_mesh *m, const glpgp_options *o, const char *name, double max_triangles,
                                   glpgp_mesh **out, glpgp_prepare_info *info)
{
    *out = NULL;
    const double h = o->size, t0 = glpgp_now();
    if (!(h > 0.0)) return GLPGP_OK;
    const int local = o->size_field == GLPGP_SIZE_AUTO || o->size_field == GLPGP_SIZE_ISO;
    glpgp_surface_refine_info ri;
    GLPGP_CHECK(glpgp_surface_refine_local(m, o, h, max_triangles, out, &ri));
    if (ri.stopped)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: h = %.4g is %.2g longest edges of the surface (%g per local size h(x) are needed, smallest "
                  "h(x) = h / %.2g; P1 needs about 10 mean edges per period); refined further it would have more "
                  "than %.0f triangles (--max-elements): solved with %d triangles, longest edge %.2g x h(x) / %g "
                  "(the oscillators may collapse: a larger --size, fewer --faces)",
                  name, h, h / ri.max_edge0, GLPGP_SURFACE_EDGES, h / (GLPGP_SURFACE_EDGES * ri.min_target),
                  max_triangles > 0 ? max_triangles : (double)GLPGP_MESH_MAX_TRIANGLES, ri.nt, ri.ratio,
                  GLPGP_SURFACE_EDGES);
    if (!*out) return GLPGP_OK;
    /* the input kept for the cross field: its curvature term reads the
     * input's normals (glpgp_surface_align_source), and with --cross-mesh
     * input or polish the field is solved there and carried over
     * (glpgp_surface_cross_on_input) where the input carries a continuation
     * (two eps levels or more; else the polish on the refined mesh starts
     * far from its eps: docs/surfaces.md) */
    if (o->field == GLPGP_FIELD_CROSS) {
        const glpgp_status st = glpgp_surface_keep_origin(*out, m);
        if (st != GLPGP_OK) {
            glpgp_mesh_destroy(out);
            return st;
        }
        double eps[GLPGP_CROSS_MAX_LEVELS];
        const int on_input = o->cross_mesh != GLPGP_CROSS_MESH_REFINED;
        (*out)->surf->origin_cross = on_input && glpgp_cross_eps_schedule(m, o, eps) >= 2;
        if (on_input && !(*out)->surf->origin_cross)
            glpgp_log(GLPGP_LOG_INFO, "cross: the input (%d vertices) is too coarse for the continuation (one eps "
                                      "level): solved on the refined mesh", m->nv);
    }
    info->refined.split_edges = ri.splits;
    info->refined.target_edge = ri.min_target;
    info->refined.local = local;
    info->refined.nv0 = m->nv;
    info->refined.nt0 = m->nt;
    info->refined.nv = ri.nv;
    info->refined.nt = ri.nt;
    info->refined.edge_ratio = ri.ratio; /* local: against the size recomputed on the refined mesh */
    info->seconds_refine = glpgp_now() - t0;
    char what[96] = "";
    if (local)
        snprintf(what, sizeof what, " and its local size h(x) (down to h / %.3g; %d pass%s)",
                 h / (GLPGP_SURFACE_EDGES * ri.min_target), ri.passes, ri.passes == 1 ? "" : "es");
    glpgp_log(GLPGP_LOG_INFO,
              "%s: refined for h = %.4g%s by longest-edge bisection: %d -> %d vertices (%ld edges bisected; longest "
              "edge h / %.3g, mean edge h / %.3g; the longest edge / (h(x) / %g) %.3g on the refined mesh)",
              name, h, what, m->nv, ri.nv, ri.splits, h / ri.max_edge, h / (*out)->mean_edge, GLPGP_SURFACE_EDGES,
              info->refined.edge_ratio);
    return GLPGP_OK;
}

/* A surface's scan noise smoothed away (o->denoise; glpgp_surface_denoise):
 * *out the smoothed copy, or NULL where m shows none or a size file gives
 * values per input vertex (kept on the input as it is). */
static glpgp_status denoise_surface(const glpgp_mesh *m, const glpgp_options *o, const char *name, glpgp_mesh **out,
                                    glpgp_prepare_info *info)
{
    *out = NULL;
    if (o->denoise != GLPGP_DENOISE_AUTO || o->size_field == GLPGP_SIZE_FILE || o->field == GLPGP_FIELD_FILE)
        return GLPGP_OK;
    const double h = o->size > 0.0 ? o->size : glpgp_default_size(m, o);
    glpgp_surface_denoise_info *d = &info->denoise;
    GLPGP_CHECK(glpgp_surface_denoise(m, o->feature_angle, h / GLPGP_DENOISE_MAX_MOVE, out, d));
    info->denoise_h = h;
    if (*out && (d->noise_edges_after > d->noise_edges || d->folds_after > d->folds)) {
        /* by its own measure the smoothing made it worse (the faceting of marching-cubes output,
         * which the filter sharpens where it takes kinks for creases): the input as it is */
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: a scan's noise (%d edges above %g degrees that are not creases, %d folded triangles) not "
                  "smoothed: the smoothing made it worse (%d -> %d such edges, %d -> %d folds); solved as it is",
                  name, d->noise_edges, o->feature_angle, d->folds, d->noise_edges, d->noise_edges_after, d->folds,
                  d->folds_after);
        glpgp_mesh_destroy(out);
        d->rounds = 0;
        return GLPGP_OK;
    }
    if (*out)
        glpgp_log(GLPGP_LOG_INFO,
                  "%s: a scan's noise (%d edges above %g degrees that are not creases, %d folded triangles) smoothed: "
                  "%d vertices moved, largest move %.3g h (mean %.3g h)%s; %d such edges and %d folds left (--denoise "
                  "off: the input as it is)",
                  name, d->noise_edges, o->feature_angle, d->folds, d->moved, d->max_move / h, d->mean_move / h,
                  d->capped ? " (held at h / 10)" : "", d->noise_edges_after, d->folds_after);
    else if (d->noise_edges || d->folds)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: a scan's noise (%d edges above %g degrees that are not creases, %d folded triangles) not "
                  "smoothed: the smoothing would make a triangle degenerate; solved as it is",
                  name, d->noise_edges, o->feature_angle, d->folds);
    return GLPGP_OK;
}

/* glpgp_solve_prepare on a surface: slivers, the scan noise, the refinement,
 * the size and field checks on the mesh that is solved. */
static glpgp_status prepare_surface(const glpgp_mesh *m0, glpgp_options *o, const char *name, double max_triangles,
                                    int refine_ok, glpgp_mesh **refined, glpgp_prepare_info *info)
{
    warn_slivers(m0, name);
    glpgp_mesh *md = NULL, *mr = NULL;
    GLPGP_CHECK(denoise_surface(m0, o, name, &md, info));
    const glpgp_mesh *m = md ? md : m0;
    const int refine = refine_ok && o->field != GLPGP_FIELD_FILE;
    const double lmax = refine && o->size_field == GLPGP_SIZE_FILE ? glpgp_mesh_longest_edge(m) : 0.0;
    /* a size file's values belong to the input's vertices: not refined (the
     * file could not be read on the refined mesh) */
    if (o->size > 0.0 && lmax > o->size / GLPGP_SURFACE_EDGES)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: edges up to h / %.2g, not refined for h = %.4g (%g edges per period are needed): the size file "
                  "%s gives one value per input vertex (the oscillators may collapse: a finer input)",
                  name, o->size / lmax, o->size, GLPGP_SURFACE_EDGES, o->size_file ? o->size_file : "");
    glpgp_status st = GLPGP_OK;
    if (refine && o->size_field != GLPGP_SIZE_FILE) st = refine_surface(m, o, name, max_triangles, &mr, info);
    if (mr) glpgp_mesh_destroy(&md); /* mr keeps what it needs of it (origin) */
    const glpgp_mesh *ms = mr ? mr : m;
    if (st == GLPGP_OK) {
        st = check_sizes(ms, o, 0, max_triangles);
        if (st != GLPGP_OK) info->usage = 1;
    }
    if (st == GLPGP_OK) st = check_field(ms, o);
    if (st != GLPGP_OK) {
        glpgp_mesh_destroy(&mr);
        glpgp_mesh_destroy(&md);
        return st;
    }
    *refined = mr ? mr : md;
    return GLPGP_OK;
}

glpgp_status glpgp_solve_prepare(const glpgp_mesh *m, glpgp_options *o, const char *name, double max_triangles,
                                 int refine_ok, glpgp_mesh **refined, glpgp_prepare_info *info)
{
    *refined = NULL;
    memset(info, 0, sizeof *info);
    if (!name) name = "mesh";
    if (m->xyz) return prepare_surface(m, o, name, max_triangles, refine_ok, refined, info);
    /* the input is refined for the local size (auto / iso / function,
     * refinement on, no per-vertex field): h may be below 2 mean edges here
     * (a graded input whose far field is coarser than h, a CAD export's fan
     * of slivers; the refinement's own limits bound the work); the refined
     * mesh is checked against the full rule below */
    const int refine = refine_ok && o->field != GLPGP_FIELD_FILE && !m->xyz &&
                       (o->size_field == GLPGP_SIZE_AUTO || o->size_field == GLPGP_SIZE_ISO ||
                        o->size_field == GLPGP_SIZE_FUNC);
    warn_slivers(m, name);
    /* a mesh too coarse for the default size (diameter / 20): the default
     * raised to 10 mean edges would leave a handful of quads (an STL-style
     * fan of a disk: h = 6.8 for a diameter of 2); refined for diameter / 20
     * instead */
    if (refine && !(o->size > 0.0)) {
        const double dx = m->bbox[2] - m->bbox[0], dy = m->bbox[3] - m->bbox[1], diag = sqrt(dx * dx + dy * dy);
        if (glpgp_default_size(m, o) > diag / GLPGP_SIZE_DEFAULT_MIN_QUADS) {
            o->size = diag / o->size_diag_div;
            glpgp_log(GLPGP_LOG_INFO,
                      "the input is too coarse for the default size (mean edge %.3g): h = diameter / %g = %.4g, "
                      "the mesh refined for it",
                      m->mean_edge, o->size_diag_div, o->size);
        }
    }
    if (check_sizes(m, o, refine, max_triangles) != GLPGP_OK) {
        info->usage = 1;
        return glpgp_error_status();
    }
    GLPGP_CHECK(check_field(m, o));
    if (!refine) return GLPGP_OK;
    /* triangles coarser than the local size: refined (longest-edge
     * bisection), the size h fixed from the input mesh first */
    const double h = o->size > 0.0 ? o->size : glpgp_default_size(m, o);
    glpgp_mesh *mr = NULL;
    const double t0 = glpgp_now();
    const glpgp_status rst = glpgp_size_refine(m, o, h, &mr, &info->refined);
    info->seconds_refine = glpgp_now() - t0;
    GLPGP_CHECK(rst);
    glpgp_status st = GLPGP_OK;
    if (mr) {
        glpgp_log(GLPGP_LOG_INFO, "refined the input for the local size: %d -> %d vertices in %d rounds",
                  info->refined.nv0, info->refined.nv, info->refined.rounds);
        o->size = h;
        if (max_triangles > 0 && mr->nt > max_triangles)
            st = GLPGP_FAIL(GLPGP_ERR_LIMIT, "the refined mesh has %d triangles, above --max-elements %ld", mr->nt,
                            (long)max_triangles);
    }
    /* the full rule (h >= 2 mean edges) on the mesh that is solved */
    if (st == GLPGP_OK) st = glpgp_options_check_mesh(o, mr ? mr : m);
    if (st != GLPGP_OK) {
        glpgp_mesh_destroy(&mr);
        return st;
    }
    *refined = mr;
    return GLPGP_OK;
}
