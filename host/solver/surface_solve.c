/* solver/surface_solve.c: glpgp_solve on a surface (glpgp/surfsolve.h):
 * constraints, the guiding cross field and its representatives, the local
 * size, and the two oscillators coupled across each triangle's matching in
 * the triangle's own plane (glpgp_solve_coupled with the surface's
 * Dirichlet nodes); without Dirichlet nodes (a closed surface without sharp
 * features) naive PGP is the quadratic form's smallest eigenvector (inverse
 * iteration), which also starts the GL continuation. */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* init_free of the surface's coupled oscillators: x <- the smallest
 * eigenvector of QUAD against the lumped mass, from z = 1 (both families of
 * every vertex in its own frame): 12 steps at most for naive PGP (the
 * baseline), 4 as GL's start (measured: as many or fewer singular triangles
 * and CG iterations than 12 on 4 of 5 surfaces, host/README.md). ctx: the
 * nodes' mass. */
static glpgp_status eigen_oscillators(osc_work *w, int k, glpgp_osc_result *r)
{
    glpgp_backend *b = w->b;
    const glpgp_backend_ops *op = b->ops;
    const double *mass = w->init_ctx;
    const int n = b->sys->nv;
    for (int i = 0; i < n; i++) {
        w->host[2 * i] = 1.0;
        w->host[2 * i + 1] = 0.0;
    }
    GLPGP_CHECK(op->vec_write(b, w->x, w->host));
    GLPGP_CHECK(op->assemble_newton(b, w->x, 0.0, w->o->hess));
    long cg = 0;
    int steps = 0;
    const int maxsteps = w->o->method == GLPGP_METHOD_PGP ? 12 : 4;
    GLPGP_CHECK(glpgp_inverse_iteration(b, w->o, &w->amg, w->x, w->d, w->xt, w->work, mass, n, w->host, maxsteps, &cg,
                                        &steps));
    r->cg_iterations += cg;
    glpgp_log(GLPGP_LOG_INFO, "%s: no Dirichlet node: naive PGP is the smallest eigenvector, %d steps of inverse "
                              "iteration, %ld CG", glpgp_osc_name(k), steps, cg);
    return GLPGP_OK;
}

/* What a surface cannot be solved with: one line each. */
static glpgp_status check_surface(const glpgp_mesh *m, const glpgp_backend *b, const glpgp_options *o)
{
    if (m->part) return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "a surface cannot be distributed over MPI ranks yet");
    if (!b->ops->coupled_systems)
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "the %s backend cannot solve surfaces (its rows are planar): use "
                                                 "--backend opencl or reference", b->ops->name);
    if (o->field == GLPGP_FIELD_RADIAL || o->field == GLPGP_FIELD_FILE)
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "--field %s is for planar domains; a surface takes --field cross "
                                                 "(default) or boundary",
                          o->field == GLPGP_FIELD_RADIAL ? "radial" : "FILE");
    if (o->size_field == GLPGP_SIZE_FUNC)
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "--size-field IMAGE is for planar domains (a surface: auto, iso, "
                                                 "none or FILE)");
    return GLPGP_OK;
}

/* The guiding field: the cross field (or the harmonic boundary-aligned one)
 * into r->cross, its representatives into r->field. A refined surface that
 * kept its input (glpgp_solve_prepare) gets the cross field solved there and
 * carried over unless --cross-mesh refined. */
static glpgp_status guiding_field(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                  const glpgp_surface_constraints *con, glpgp_result *r)
{
    const double t1 = glpgp_now();
    /* a refined surface's cross field on its input (--cross-mesh input, polish) */
    const int on_input = o->field == GLPGP_FIELD_CROSS && o->cross_mesh != GLPGP_CROSS_MESH_REFINED && m->surf->origin &&
                         m->surf->origin_cross;
    if (on_input)
        GLPGP_CHECK(glpgp_surface_cross_on_input(m, b, o, con, o->cross_mesh == GLPGP_CROSS_MESH_POLISH, &r->cross));
    else if (o->field == GLPGP_FIELD_CROSS)
        GLPGP_CHECK(glpgp_surface_cross_solve(m, b, o, con, &r->cross));
    else
        GLPGP_CHECK(glpgp_surface_boundary_field(m, b, o, con, &r->cross));
    r->field_cg_iterations += r->cross->cg_iterations;
    const int cuts = glpgp_surface_cross_to_vector(m, r->cross->w, r->field);
    if (cuts < 0) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "cross field: no memory for its representatives");
    glpgp_log(GLPGP_LOG_INFO, "surface: %d cross-field singularities (index sum %g, Poincare-Hopf %g); U turns "
                              "across %d edges, the oscillators are coupled across every triangle's matching",
              r->cross->nsing, r->cross->index4_sum / 4.0, r->cross->index4_expected / 4.0, cuts);
    r->seconds_field = glpgp_now() - t1;
    return GLPGP_OK;
}

/* The local size divided by the curl correction's factors (--size-curl;
 * the curl within 2 h of the boundary not counted), enlarged at most to
 * what the surface allows at the same chord depth (glpgp_surface_size_local
 * at 2 h with half the relative depth: the sagitta cap and the feature
 * spacing; the quads' Hausdorff check is against h). */
static glpgp_status curl_size(const glpgp_mesh *m, const glpgp_options *o, const glpgp_surface_constraints *con,
                              const double *u, double h, double *size, int *uniform)
{
    const int nv = m->nv;
    double *f = NULL, *cap = NULL, range[2];
    glpgp_options o2 = *o;
    o2.size_chord_depth = 0.5 * o->size_chord_depth;
    glpgp_status st = glpgp_malloc((size_t)nv + 1, sizeof(double), &f);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nv + 1, sizeof(double), &cap);
    if (st == GLPGP_OK) st = glpgp_surface_size_curl(m, u, o->size_curl, 2.0 * h, f, range);
    if (st == GLPGP_OK) st = glpgp_surface_size_local(m, &o2, con, 2.0 * h, 1, cap);
    if (st == GLPGP_OK) {
        double lo = HUGE_VAL, hi = 0.0;
        for (int i = 0; i < nv; i++)
            for (int k = 0; k < 2; k++) {
                double *sz = size + k * nv + i;
                *sz = fmin(*sz / f[i], fmax(*sz, cap[i]));
                lo = fmin(lo, *sz);
                hi = fmax(hi, *sz);
            }
        *uniform = 0;
        glpgp_log(GLPGP_LOG_INFO, "surface: curl correction (--size-curl %g): frame scale %.3f .. %.3f, local size "
                                  "%.3f .. %.3f h", o->size_curl, range[0], range[1], lo / h, hi / h);
    }
    free(f);
    free(cap);
    return st;
}

glpgp_status glpgp_solve_surface(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o, glpgp_result **out)
{
    glpgp_status st = GLPGP_OK;
    glpgp_result *r = NULL;
    glpgp_surface_constraints *con = NULL;
    double *size = NULL, *mass = NULL;
    unsigned char *dn = NULL;
    glpgp_options ojac;
    const double t0 = glpgp_now();
    const int nv = m->nv;
    *out = NULL;
    GLPGP_CHECK(check_surface(m, b, o));
    GLPGP_CHECK(glpgp_options_check_mesh(o, m));
    if (o->precond == GLPGP_PRECOND_AMG && !glpgp_amg_supported(b)) {
        glpgp_log(GLPGP_LOG_WARNING, "the %s backend has no multigrid preconditioner; using Jacobi-PCG", b->ops->name);
        ojac = *o;
        ojac.precond = GLPGP_PRECOND_JACOBI;
        o = &ojac;
    }
    const double h = o->size > 0.0 ? o->size : glpgp_default_size(m, o);
    const glpgp_surface *s = m->surf;
    glpgp_log(GLPGP_LOG_INFO,
              "surface: %d vertices, %d triangles, chi %d, genus %d, %d boundary loop(s), %d component(s); h = %g "
              "(%.1f edges per period), backend %s",
              nv, m->nt, s->euler, s->genus, m->nloops, s->ncomponents, h, h / m->mean_edge, b->ops->name);
    GLPGP_CHECK(glpgp_result_create(nv, m->nt, &r));
    r->size = h;
    r->backend = b->ops->name;
    GLPGP_CHECK_GOTO(st, glpgp_surface_constraints_create(m, o->feature_angle, &con), fail);
    GLPGP_CHECK_GOTO(st, glpgp_surface_constraints_rims(m, glpgp_surface_rim_scale(m, o->rim_scale, h), con), fail);
    if (con->rim_scale > 0.0)
        glpgp_log(GLPGP_LOG_INFO, "surface: the boundary's crosses read over %g (%.2f h) either side (--rim-scale)",
                  con->rim_scale, con->rim_scale / h);
    const int above = glpgp_surface_edges_above(m, o->feature_angle);
    if (above)
        glpgp_log(GLPGP_LOG_INFO,
                  "surface: %d sharp feature edges (creases with a dihedral angle above %g degrees; %d more edges above "
                  "it are not creases: a scan's noise)",
                  con->nfeatures, o->feature_angle, above - con->nfeatures);
    r->seconds_setup = glpgp_now() - t0;
    GLPGP_CHECK_GOTO(st, guiding_field(m, b, o, con, r), fail);
    /* local size (uniform: NULL, the plain element arithmetic) */
    int uniform = 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &size), fail);
    double eps[GLPGP_MAX_LEVELS];
    const int nlev = glpgp_eps_schedule(m, o, h, eps);
    /* Dirichlet nodes; without any, the eigenvector starts (or is) the solve */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, 1, &dn), fail);
    const int ndir = glpgp_surface_dirichlet(m, con, r->field, dn);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &mass), fail);
    glpgp_surface_lumped_mass(m, size); /* scratch: the vertices' mass, then each node's */
    for (int i = 0; i < nv; i++) mass[2 * i] = mass[2 * i + 1] = size[i];
    GLPGP_CHECK_GOTO(st, glpgp_surface_size(m, o, con, h, size, &uniform), fail);
    /* the curl correction adapts the auto / iso sizes; none and FILE are the user's as given */
    if (o->size_curl > 0.0 && (o->size_field == GLPGP_SIZE_AUTO || o->size_field == GLPGP_SIZE_ISO))
        GLPGP_CHECK_GOTO(st, curl_size(m, o, con, r->field, h, size, &uniform), fail);
    if (!uniform) glpgp_size_log(m, size, h);
    glpgp_log(GLPGP_LOG_INFO, "surface: %d Dirichlet nodes of %d", ndir, 2 * nv);
    GLPGP_CHECK_GOTO(st, glpgp_solve_coupled(m, b, o, r, uniform ? NULL : size, h, eps, nlev, dn, eigen_oscillators,
                                             mass),
                     fail);
    r->seconds_total = glpgp_now() - t0;
    goto done;
fail:
    glpgp_result_destroy(&r);
done:
    glpgp_surface_constraints_destroy(&con);
    free(size);
    free(mass);
    free(dn);
    *out = r;
    return st;
}
