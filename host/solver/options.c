/* solver/options.c: the documented defaults and range checks of every solve
 * parameter, the default quad size and the eps schedule (glpgp/solve.h). */
#include "glpgp/solve.h"
#include "glpgp/surface.h"
#include "glpgp/internal/newton.h"

#include <math.h>
#include <string.h>

void glpgp_options_default(glpgp_options *o)
{
    memset(o, 0, sizeof *o);
    o->size = 0.0;
    o->method = GLPGP_METHOD_GL;
    o->energy = GLPGP_ELEM_P1;
    o->hess = GLPGP_HESS_MIXED;
    o->field = GLPGP_FIELD_BOUNDARY;
    o->init = GLPGP_INIT_NAIVE;
    o->vertex_order = GLPGP_ORDER_RCM;
    o->oscillators = GLPGP_OSC_AUTO;
    o->eps0 = 0.5;
    o->eps_ratio = 0.5;
    o->eps_min = 2.5;
    o->eps_merge = 1.25;
    o->collapse_zabs = 0.5;
    o->cross_eps0 = 0.05;
    o->cross_eps_min = 2.5;
    o->cross_rtol = 1e-3;
    o->cross_ftol = 1e-5;
    o->cross_coupling = GLPGP_COUPLING_AUTO;
    o->cross_mesh = GLPGP_CROSS_MESH_POLISH;
    o->cross_align = 5.0; /* the torus: 12 singularities -> 0 (bench/results/surface_align.md) */
    o->cross_size = GLPGP_CROSS_SIZE_AUTO;
    o->cross_size_quantile = 0.9;
    o->cross_size_ratio = 1.4;
    o->newton_rtol = 1e-6;
    o->intermediate_rtol = 1e-3;
    o->newton_max = 50;
    o->newton_ftol = 1e-8; /* the torus's plateau at |g| ~ 5e-6 |g0| (bench/results/newton_stall.md) */
    o->exact_switch = 0.05;
    o->exact_cooldown = 5;
    o->armijo = 1e-4;
    o->max_backtracks = 40;
    o->forcing = 0.1;
    o->forcing_max = 1e-2;
    o->globalization = GLPGP_GLOBAL_TRUST_REGION;
    o->tr_accept = 1e-4;
    o->tr_poor = 0.25;
    o->tr_shrink = 0.5;
    o->tr_shrink_min = 0.1;
    o->tr_good = 0.75;
    o->tr_grow = 2.0;
    o->tr_resolve = 3;
    o->tr_resolve_shrink = 0.7;
    o->tr_resolve_rho = 0.1;
    o->tr_lookahead = 0;
    o->tr_precond = GLPGP_PRECOND_AMG;
    o->retract_zabs = 0.8;
    o->cg_rtol = 1e-8;
    o->cg_max = 20000;
    o->cg_check = 10;
    o->precond = GLPGP_PRECOND_AMG; /* measured faster: bench/results/history.md, "Multigrid measured" */
    o->amg_coarse = 48;
    o->amg_max_levels = 20;
    o->amg_coarse_passes = 2; /* 3: bench/results/time_to_solution.md, "Coarser aggregates" */
    o->amg_cycle = GLPGP_AMG_KCYCLE;
    o->amg_kcycle_min = -1; /* by the backend: glpgp_amg_kcycle_min */
    o->amg_pre = 1;
    o->amg_post = 1;
    o->amg_weight = 1.5;
    o->amg_check = 1;
    o->amg_maxit = 1000;
    o->size_field = GLPGP_SIZE_AUTO;
    o->size_file = NULL;
    o->size_fn = NULL;
    o->size_ctx = NULL;
    o->size_grading = 0.5;
    o->size_across = 2.0;
    o->size_min = 0.05;
    o->size_chord_area = 0.005;
    o->size_chord_depth = 0.125;
    o->size_resolution = 4.0;
    o->size_curl = 1.0; /* surfaces: measured fewer irregular vertices everywhere but jagged rims (bench/results/surface_curl.md) */
    o->size_diag_div = 20.0;
    o->size_min_edges = 10.0;
    o->feature_angle = GLPGP_FEATURE_ANGLE_DEFAULT;
    o->denoise = GLPGP_DENOISE_AUTO;
}

#define OPEN01(v) ((v) > 0.0 && (v) < 1.0)

glpgp_status glpgp_options_check(const glpgp_options *o)
{
    if (!isfinite(o->size) || o->size < 0.0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size must be > 0 (or 0 for the default), got %g", o->size);
    if (o->method != GLPGP_METHOD_GL && o->method != GLPGP_METHOD_PGP)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown method %d", o->method);
    if (o->energy != GLPGP_ELEM_P1 && o->energy != GLPGP_ELEM_TRANSPORT)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown energy %d", o->energy);
    if (o->hess < GLPGP_HESS_PAPER || o->hess > GLPGP_HESS_MIXED)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown Newton Hessian %d", o->hess);
    if (o->field == GLPGP_FIELD_FILE && !o->field_values && (!o->field_file || !*o->field_file))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "field from a file needs a file name");
    if (!(o->eps0 > 0.0) || !(o->eps_min > 0.0) || !isfinite(o->eps0) || !isfinite(o->eps_min))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "eps0 and eps-min must be positive");
    if (!(o->cross_eps0 > 0.0) || !(o->cross_eps_min > 0.0) || !isfinite(o->cross_eps0) ||
        !isfinite(o->cross_eps_min))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross-eps0 and cross-eps-min must be positive");
    if (!OPEN01(o->cross_rtol)) return GLPGP_FAIL(GLPGP_ERR_ARG, "cross-rtol must be in (0,1)");
    if (!(o->cross_ftol >= 0.0 && o->cross_ftol < 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross-ftol must be in [0,1), got %g", o->cross_ftol);
    if (o->cross_mesh < GLPGP_CROSS_MESH_INPUT || o->cross_mesh > GLPGP_CROSS_MESH_POLISH)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross_mesh must be input, polish or refined, got %d", o->cross_mesh);
    if (!(o->cross_align >= 0.0) || !isfinite(o->cross_align))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross-align must be finite and >= 0, got %g", o->cross_align);
    if (o->cross_coupling < GLPGP_COUPLING_AUTO || o->cross_coupling > GLPGP_COUPLING_ON)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross_coupling must be auto, off or on, got %d", o->cross_coupling);
    if (o->cross_size < GLPGP_CROSS_SIZE_OFF || o->cross_size > GLPGP_CROSS_SIZE_AUTO)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross_size must be off, on or auto, got %d", o->cross_size);
    if (o->vertex_order != GLPGP_ORDER_RCM && o->vertex_order != GLPGP_ORDER_INPUT)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown vertex order %d", o->vertex_order);
    if (o->oscillators != GLPGP_OSC_AUTO && o->oscillators != GLPGP_OSC_SEQUENTIAL &&
        o->oscillators != GLPGP_OSC_CONCURRENT)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown oscillators mode %d", o->oscillators);
    if (!(o->cross_size_quantile > 0.0 && o->cross_size_quantile <= 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross-size-quantile must be in (0,1], got %g", o->cross_size_quantile);
    if (!(o->cross_size_ratio >= 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross-size-ratio must be >= 1, got %g", o->cross_size_ratio);
    if (!OPEN01(o->eps_ratio))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "eps ratio must be in (0,1), got %g", o->eps_ratio);
    if (!(o->eps_merge >= 1.0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "eps_merge must be >= 1");
    if (!(o->collapse_zabs >= 0.0 && o->collapse_zabs < 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "collapse_zabs must be in [0,1)");
    if (!OPEN01(o->newton_rtol) || !OPEN01(o->intermediate_rtol))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "Newton tolerances must be in (0,1)");
    if (!(o->newton_ftol >= 0.0 && o->newton_ftol < 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "newton-ftol must be in [0,1), got %g", o->newton_ftol);
    if (o->newton_max < 1 || o->cg_max < 1 || o->cg_check < 1 || o->max_backtracks < 1 ||
        o->exact_cooldown < 0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "iteration counts must be >= 1");
    if (!OPEN01(o->cg_rtol)) return GLPGP_FAIL(GLPGP_ERR_ARG, "cg-rtol must be in (0,1)");
    if (!(o->exact_switch >= 0.0) || !OPEN01(o->armijo) || !(o->forcing > 0.0) ||
        !OPEN01(o->forcing_max))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "Newton step parameters out of range");
    if (o->tr_lookahead != 0 && o->tr_lookahead != 1)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "tr_lookahead must be 0 or 1, got %d", o->tr_lookahead);
    if (o->tr_precond != GLPGP_PRECOND_JACOBI && o->tr_precond != GLPGP_PRECOND_AMG)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown trust-region preconditioner %d", o->tr_precond);
    if (o->globalization != GLPGP_GLOBAL_TRUST_REGION && o->globalization != GLPGP_GLOBAL_LINE_SEARCH)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown Newton globalization %d", o->globalization);
    if (!(o->tr_accept >= 0.0 && o->tr_accept < o->tr_poor) || !(o->tr_poor < o->tr_good) ||
        !(o->tr_good < 1.0) || !OPEN01(o->tr_shrink) ||
        !(o->tr_shrink_min > 0.0 && o->tr_shrink_min <= o->tr_shrink) ||
        !(o->retract_zabs >= 0.0 && o->retract_zabs <= 2.0) || !(o->tr_grow > 1.0 && isfinite(o->tr_grow)))
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "trust-region parameters out of range (need 0 <= accept < poor < good < 1, "
                          "0 < shrink < 1 < grow)");
    if (o->tr_resolve < 0 || !OPEN01(o->tr_resolve_shrink) ||
        !(o->tr_resolve_rho >= o->tr_accept && o->tr_resolve_rho <= o->tr_poor))
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "trust-region re-solve parameters out of range (need resolve >= 0, "
                          "0 < resolve_shrink < 1, accept <= resolve_rho <= poor)");
    if (o->precond != GLPGP_PRECOND_JACOBI && o->precond != GLPGP_PRECOND_AMG)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown preconditioner %d", o->precond);
    if (o->amg_coarse < 2 || o->amg_coarse > 1024)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_coarse must be in [2, 1024], got %d", o->amg_coarse);
    if (o->amg_coarse_passes < 2 || o->amg_coarse_passes > 3)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_coarse_passes must be 2 or 3, got %d", o->amg_coarse_passes);
    if (o->amg_max_levels < 2 || o->amg_max_levels > GLPGP_AMG_MAX_LEVELS)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_max_levels must be in [2, %d], got %d",
                          GLPGP_AMG_MAX_LEVELS, o->amg_max_levels);
    if (o->amg_kcycle_min < -1)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_kcycle_min must be >= 0 or -1 (by the backend), got %d",
                          o->amg_kcycle_min);
    if (o->amg_cycle != GLPGP_AMG_KCYCLE && o->amg_cycle != GLPGP_AMG_VCYCLE)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown multigrid cycle %d", o->amg_cycle);
    if (o->amg_pre < 0 || o->amg_pre > 8 || o->amg_post < 1 || o->amg_post > 8)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_pre must be in [0, 8] and amg_post in [1, 8], got %d, %d",
                          o->amg_pre, o->amg_post);
    if (!(o->amg_weight > 0.0 && o->amg_weight < 2.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_weight must be in (0, 2), got %g", o->amg_weight);
    if (o->amg_check < 1 || o->amg_maxit < 1)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_check and amg_maxit must be >= 1");
    if (o->size_field < GLPGP_SIZE_NONE || o->size_field > GLPGP_SIZE_FUNC)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown size field %d", o->size_field);
    if (o->size_field == GLPGP_SIZE_FILE && (!o->size_file || !*o->size_file))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size field from a file needs a file name");
    if (o->size_field == GLPGP_SIZE_FUNC && !o->size_fn)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size field from a function needs the function (size_fn)");
    if (!(o->size_grading > 0.0) || !isfinite(o->size_grading))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size grading must be a positive number, got %g", o->size_grading);
    if (!(o->size_across >= 1.0) || !isfinite(o->size_across))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size_across must be >= 1, got %g", o->size_across);
    if (!(o->size_min > 0.0 && o->size_min <= 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size_min must be in (0, 1], got %g", o->size_min);
    if (!(o->size_chord_area >= 0.0 && o->size_chord_area < 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size_chord_area must be in [0, 1), got %g", o->size_chord_area);
    if (!(o->size_chord_depth >= 0.0 && o->size_chord_depth < 1.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size_chord_depth must be in [0, 1), got %g", o->size_chord_depth);
    if (!(o->size_resolution >= GLPGP_SIZE_MIN_EDGES) || !isfinite(o->size_resolution))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size_resolution must be >= %g, got %g", GLPGP_SIZE_MIN_EDGES,
                          o->size_resolution);
    if (!(o->size_diag_div > 0.0) || !(o->size_min_edges >= 0.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "default-size parameters out of range");
    if (!(o->feature_angle >= 0.0 && o->feature_angle <= 180.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "feature_angle must be in [0, 180] degrees, got %g", o->feature_angle);
    return GLPGP_OK;
}

glpgp_status glpgp_options_check_mesh(const glpgp_options *o, const glpgp_mesh *m)
{
    GLPGP_CHECK(glpgp_options_check(o));
    double h = o->size > 0.0 ? o->size : glpgp_default_size(m, o);
    double dx = m->bbox[2] - m->bbox[0], dy = m->bbox[3] - m->bbox[1], diag = sqrt(dx * dx + dy * dy);
    if (m->xyz) diag = glpgp_mesh_diagonal(m); /* a surface: the 3D box */
    if (!(h >= GLPGP_SIZE_MIN_EDGES * m->mean_edge))
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "size h = %g is %.3g mean edge lengths of the mesh: at least %g are needed "
                          "(P1 needs about 10 per period)",
                          h, h / m->mean_edge, GLPGP_SIZE_MIN_EDGES);
    if (!(h <= GLPGP_SIZE_MAX_DIAG * diag))
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "size h = %g is %.3g times the domain's diameter: at most %g (no quad would "
                          "fit in the domain)",
                          h, h / diag, GLPGP_SIZE_MAX_DIAG);
    return GLPGP_OK;
}

double glpgp_default_size(const glpgp_mesh *m, const glpgp_options *o)
{
    glpgp_options d;
    if (!o) {
        glpgp_options_default(&d);
        o = &d;
    }
    /* diameter / 20, raised to 10 mean edges when the mesh is too coarse for it
     * (P1 needs about 10 vertices per period, see docs/numerics.md) */
    double dx = m->bbox[2] - m->bbox[0], dy = m->bbox[3] - m->bbox[1];
    const double diag = m->xyz ? glpgp_mesh_diagonal(m) : sqrt(dx * dx + dy * dy); /* a surface: the 3D box */
    return fmax(diag / o->size_diag_div, o->size_min_edges * m->mean_edge);
}

int glpgp_eps_schedule(const glpgp_mesh *m, const glpgp_options *o, double h,
                       double eps[GLPGP_MAX_LEVELS])
{
    /* eps_0 = eps0 h;  eps_{k+1} = max(ratio eps_k, emin) while eps_k > emin,
     * except that a level within merge of emin becomes the last one, lowered
     * to emin (the level after it would be within merge of it); eps0 h <=
     * emin: one level at eps0 h */
    int n = 0;
    double e = o->eps0 * h, emin = o->eps_min * m->mean_edge;
    eps[n++] = e;
    while (e > emin && n < GLPGP_MAX_LEVELS) {
        if (e <= emin * o->eps_merge) {
            eps[n - 1] = emin;
            break;
        }
        e = fmax(e * o->eps_ratio, emin);
        eps[n++] = e;
    }
    return n;
}
