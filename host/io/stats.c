/* io/stats.c: the statistics JSON of a run (glpgp/io.h), written with the
 * one JSON emitter (json.c); the quad-mesh report joins it as the "quads"
 * member, so the file is written once. */
#include "glpgp/io.h"
#include "glpgp/surface.h"
#include "glpgp/cross.h"

#include "names.h"

#include <stdio.h>
#include <stdlib.h>

/* mesh.surface.denoise: what glpgp_solve_prepare smoothed (null: nothing) */
static void stats_denoise(glpgp_json *w, const glpgp_stats_extra *x)
{
    const glpgp_surface_denoise_info *d = x ? x->denoise : NULL;
    if (!d) {
        glpgp_json_null(w, "denoise");
        return;
    }
    const double h = x->denoise_h > 0.0 ? x->denoise_h : 1.0;
    glpgp_json_object(w, "denoise");
    glpgp_json_int(w, "noise_edges", d->noise_edges);
    glpgp_json_int(w, "noise_edges_after", d->noise_edges_after);
    glpgp_json_int(w, "folds", d->folds);
    glpgp_json_int(w, "folds_after", d->folds_after);
    glpgp_json_int(w, "rounds", d->rounds);
    glpgp_json_int(w, "moved", d->moved);
    glpgp_json_int(w, "capped", d->capped);
    glpgp_json_num(w, "max_move", d->max_move);
    glpgp_json_num(w, "mean_move", d->mean_move);
    glpgp_json_num(w, "max_move_over_h", d->max_move / h);
    glpgp_json_num(w, "defect_rms", d->defect_rms);
    glpgp_json_num(w, "defect_rms_after", d->defect_rms_after);
    if (x->hausdorff_input >= 0.0) glpgp_json_num(w, "quads_hausdorff_to_input", x->hausdorff_input);
    else glpgp_json_null(w, "quads_hausdorff_to_input");
    glpgp_json_close(w);
}

/* A surface's members of "mesh" (glpgp/surface.h): its 3D box, topology,
 * features and what the smoothing did. */
static void stats_surface(glpgp_json *w, const glpgp_mesh *m, const glpgp_options *o, const glpgp_stats_extra *x)
{
    unsigned char *fl = malloc((size_t)3 * m->nt);
    glpgp_json_array(w, "bbox3");
    for (int i = 0; i < 6; i++) glpgp_json_num(w, NULL, m->bbox3[i]);
    glpgp_json_close(w);
    glpgp_json_object(w, "surface");
    glpgp_json_int(w, "euler_characteristic", m->surf->euler);
    glpgp_json_int(w, "genus", m->surf->genus);
    glpgp_json_int(w, "components", m->surf->ncomponents);
    glpgp_json_int(w, "edges", m->surf->nedges);
    int nfeat = 0;
    if (fl && o && glpgp_surface_features(m, o->feature_angle, fl, &nfeat) == GLPGP_OK)
        glpgp_json_int(w, "feature_edges", nfeat);
    if (o) glpgp_json_int(w, "edges_above_feature_angle", glpgp_surface_edges_above(m, o->feature_angle));
    if (o) glpgp_json_num(w, "feature_angle", o->feature_angle);
    glpgp_json_num(w, "total_holonomy", glpgp_surface_total_holonomy(m));
    stats_denoise(w, x);
    glpgp_json_close(w);
    free(fl);
}

/* "field", "field_file", "init" and "options": the solve's options (null
 * without them). */
static void stats_options(glpgp_json *w, const glpgp_options *o)
{
    if (o) {
        glpgp_json_str(w, "field", field_name(o->field));
        glpgp_json_str(w, "field_file", o->field == GLPGP_FIELD_FILE ? o->field_file : NULL);
        glpgp_json_str(w, "init", init_name(o->init));
        glpgp_json_object(w, "options");
        glpgp_json_num(w, "eps0", o->eps0);
        glpgp_json_num(w, "eps_ratio", o->eps_ratio);
        glpgp_json_num(w, "eps_min", o->eps_min);
        glpgp_json_str(w, "globalization",
                       o->globalization == GLPGP_GLOBAL_LINE_SEARCH ? "line-search" : "trust-region");
        glpgp_json_num(w, "newton_rtol", o->newton_rtol);
        glpgp_json_int(w, "newton_max", o->newton_max);
        glpgp_json_num(w, "newton_ftol", o->newton_ftol);
        glpgp_json_num(w, "cg_rtol", o->cg_rtol);
        glpgp_json_int(w, "cg_max", o->cg_max);
        glpgp_json_int(w, "cg_check", o->cg_check);
        glpgp_json_num(w, "cross_eps0", o->cross_eps0);
        glpgp_json_num(w, "cross_eps_min", o->cross_eps_min);
        glpgp_json_num(w, "cross_rtol", o->cross_rtol);
        glpgp_json_num(w, "cross_ftol", o->cross_ftol);
        glpgp_json_str(w, "cross_size", o->cross_size == GLPGP_CROSS_SIZE_AUTO ? "auto"
                                        : o->cross_size == GLPGP_CROSS_SIZE_ON ? "on"
                                                                                : "off");
        glpgp_json_num(w, "cross_size_quantile", o->cross_size_quantile);
        glpgp_json_num(w, "cross_size_ratio", o->cross_size_ratio);
        glpgp_json_str(w, "vertex_order", o->vertex_order == GLPGP_ORDER_INPUT ? "input" : "rcm");
        glpgp_json_str(w, "oscillators", o->oscillators == GLPGP_OSC_SEQUENTIAL   ? "sequential"
                                         : o->oscillators == GLPGP_OSC_CONCURRENT ? "concurrent"
                                                                                  : "auto");
        if (o->has_center) {
            glpgp_json_array(w, "center");
            glpgp_json_num(w, NULL, o->center[0]);
            glpgp_json_num(w, NULL, o->center[1]);
            glpgp_json_close(w);
        } else {
            glpgp_json_null(w, "center");
        }
        glpgp_json_close(w);
    } else {
        glpgp_json_null(w, "field");
        glpgp_json_null(w, "field_file");
        glpgp_json_null(w, "init");
        glpgp_json_null(w, "options");
    }
}

/* One eps level's row of an "eps_schedule": the cross field's (osc = 0)
 * or an oscillator's (osc = 1: also the median |z|, restarts, backtracks,
 * whether it stopped at the noise level). */
static void stats_level(glpgp_json *w, int l, const glpgp_level_stats *ls, int osc)
{
    glpgp_json_object(w, NULL);
    glpgp_json_int(w, "level", l);
    glpgp_json_num(w, "eps", ls->eps);
    glpgp_json_int(w, "newton", ls->newton);
    glpgp_json_int(w, "cg", ls->cg);
    glpgp_json_num(w, "grad0", ls->grad0);
    glpgp_json_num(w, "grad", ls->grad);
    glpgp_json_num(w, "energy", ls->energy);
    if (osc) {
        glpgp_json_num(w, "median_zabs", ls->median_zabs);
        glpgp_json_bool(w, "restarted", ls->restarted);
    }
    glpgp_json_int(w, "fallbacks", ls->fallbacks);
    if (osc) glpgp_json_int(w, "backtracked", ls->backtracked);
    glpgp_json_num(w, "rtol", ls->rtol);
    glpgp_json_bool(w, "capped", ls->capped);
    if (osc) glpgp_json_bool(w, "at_noise", ls->at_noise);
    glpgp_json_bool(w, "stalled", ls->stalled);
    glpgp_json_close(w);
}

/* "cross_field" (--field cross): singularities with index and position,
 * the levels of its continuation. */
static void stats_cross(glpgp_json *w, const glpgp_mesh *m, const glpgp_result *r)
{
    /* the cross field (--field cross): singularities with index and position */
    if (r->cross) {
        const glpgp_cross_result *c = r->cross;
        glpgp_json_object(w, "cross_field");
        glpgp_json_int(w, "singularities", c->nsing);
        glpgp_json_num(w, "index_sum", c->index4_sum / 4.0);
        glpgp_json_num(w, "index_expected", c->index4_expected / 4.0);
        glpgp_json_bool(w, "poincare_hopf", c->index4_sum == c->index4_expected);
        glpgp_json_num(w, "median_abs_w", c->zabs_median);
        /* the mesh it was solved on: the solve's own (solve), or a refined surface's input (carried over) */
        if (m->xyz) {
            glpgp_json_str(w, "mesh", c->solved_nv == c->nv ? "solve" : c->polished ? "input+polish" : "input");
            glpgp_json_int(w, "mesh_vertices", c->solved_nv);
        }
        /* u and v solved as one system coupled across the cuts (--cross-coupling) */
        glpgp_json_bool(w, "coupled", r->coupled != 0);
        glpgp_json_array(w, "singular");
        for (int k = 0; k < c->nsing; k++) {
            glpgp_json_object(w, NULL);
            glpgp_json_num(w, "x", c->sing[k].x);
            glpgp_json_num(w, "y", c->sing[k].y);
            if (m->xyz) glpgp_json_num(w, "z", c->sing[k].z);
            glpgp_json_num(w, "index", c->sing[k].index4 / 4.0);
            glpgp_json_int(w, "triangles", c->sing[k].ntri);
            glpgp_json_int(w, "triangle", c->sing[k].tri);
            glpgp_json_close(w);
        }
        glpgp_json_close(w);
        glpgp_json_int(w, "newton_iterations", c->newton_iterations);
        glpgp_json_int(w, "cg_iterations", c->cg_iterations);
        glpgp_json_int(w, "capped_levels", c->capped_levels);
        glpgp_json_array(w, "eps_schedule");
        for (int l = 0; l < c->nlevels && l < GLPGP_CROSS_MAX_LEVELS; l++) {
            stats_level(w, l, &c->level[l], 0);
        }
        glpgp_json_close(w);
        glpgp_json_num(w, "seconds", c->seconds);
        glpgp_json_close(w);
    }
}

/* "zabs", "final_energy", "dirichlet", iteration counts and "converged". */
static void stats_counts(glpgp_json *w, const glpgp_result *r)
{
    static const char *const oname[2] = {"u", "v"};
    const glpgp_osc_result *ou = &r->osc[0], *ov = &r->osc[1];
    glpgp_json_object(w, "zabs");
    for (int k = 0; k < 2; k++) {
        glpgp_json_object(w, oname[k]);
        glpgp_json_num(w, "min", r->osc[k].zabs_min);
        glpgp_json_num(w, "p10", r->osc[k].zabs_p10);
        glpgp_json_num(w, "median", r->osc[k].zabs_median);
        glpgp_json_close(w);
    }
    glpgp_json_close(w);

    glpgp_json_object(w, "final_energy");
    glpgp_json_num(w, "u", ou->energy);
    glpgp_json_num(w, "v", ov->energy);
    glpgp_json_close(w);

    glpgp_json_object(w, "dirichlet");
    glpgp_json_int(w, "u", ou->n_dirichlet);
    glpgp_json_int(w, "v", ov->n_dirichlet);
    glpgp_json_close(w);

    glpgp_json_object(w, "newton_iterations");
    glpgp_json_int(w, "total", (long)ou->newton_iterations + ov->newton_iterations);
    glpgp_json_int(w, "u", ou->newton_iterations);
    glpgp_json_int(w, "v", ov->newton_iterations);
    glpgp_json_close(w);

    glpgp_json_object(w, "cg_iterations");
    glpgp_json_int(w, "total", ou->cg_iterations + ov->cg_iterations + r->field_cg_iterations);
    glpgp_json_int(w, "u", ou->cg_iterations);
    glpgp_json_int(w, "v", ov->cg_iterations);
    glpgp_json_int(w, "field", r->field_cg_iterations);
    glpgp_json_close(w);

    /* a level stopped by the Newton cap is not a converged state: said here */
    glpgp_json_object(w, "converged");
    glpgp_json_bool(w, "all", ou->capped_levels + ov->capped_levels == 0);
    glpgp_json_int(w, "capped_levels_u", ou->capped_levels);
    glpgp_json_int(w, "capped_levels_v", ov->capped_levels);
    glpgp_json_close(w);
}

/* "eps_schedule": every level of both oscillators. */
static void stats_schedule(glpgp_json *w, const glpgp_result *r)
{
    static const char *const oname[2] = {"u", "v"};
    glpgp_json_object(w, "eps_schedule");
    for (int k = 0; k < 2; k++) {
        const glpgp_osc_result *os = &r->osc[k];
        int nl = os->nlevels;
        if (nl < 0) nl = 0;
        if (nl > GLPGP_MAX_LEVELS) nl = GLPGP_MAX_LEVELS;
        glpgp_json_array(w, oname[k]);
        for (int l = 0; l < nl; l++) {
            stats_level(w, l, &os->level[l], 1);
        }
        glpgp_json_close(w);
    }
    glpgp_json_close(w);
}

/* "seconds", "phases" (glpgp/timers.h), "solve_split", "device_calls",
 * "oscillators". */
static void stats_time(glpgp_json *w, const glpgp_result *r, const glpgp_stats_extra *x)
{
    const glpgp_osc_result *ou = &r->osc[0], *ov = &r->osc[1];
    glpgp_json_object(w, "seconds");
    if (x && x->seconds_read >= 0)
        glpgp_json_num(w, "read", x->seconds_read);
    else
        glpgp_json_null(w, "read");
    glpgp_json_num(w, "setup", r->seconds_setup);
    glpgp_json_num(w, "field", r->seconds_field);
    glpgp_json_num(w, "u", ou->seconds);
    glpgp_json_num(w, "v", ov->seconds);
    glpgp_json_num(w, "total", r->seconds_total);
    glpgp_json_close(w);
    /* where the time went, per phase (glpgp/timers.h): wall seconds (exclusive)
     * and of them the host's wait on the device; program_build ran in the
     * background while the input was read (its wait: what the run waited) */
    {
        const glpgp_timers *t = &r->timers;
        double solve_wait = 0.0, solve_s = 0.0;
        glpgp_json_object(w, "phases");
        for (int i = 0; i < GLPGP_TM_COUNT; i++) {
            glpgp_json_object(w, glpgp_timer_key(i));
            glpgp_json_num(w, "seconds", t->s[i]);
            glpgp_json_num(w, "wait", t->wait[i]);
            glpgp_json_close(w);
            if (glpgp_timer_in_solve(i)) {
                solve_wait += t->wait[i];
                solve_s += t->s[i];
            }
        }
        glpgp_json_close(w);
        /* the solve's phases summed (both threads with concurrent oscillators),
         * split into host work and waiting on the device */
        glpgp_json_object(w, "solve_split");
        glpgp_json_num(w, "seconds", solve_s);
        glpgp_json_num(w, "wait", solve_wait);
        glpgp_json_num(w, "host", solve_s - solve_wait);
        glpgp_json_num(w, "host_share", solve_s > 0.0 ? (solve_s - solve_wait) / solve_s : 0.0);
        glpgp_json_close(w);
    }
    /* what a GPU pays per call whatever the work (bench/results/gpu_h200) */
    glpgp_json_object(w, "device_calls");
    glpgp_json_int(w, "host_round_trips", r->host_round_trips);
    glpgp_json_int(w, "kernel_launches", r->kernel_launches);
    glpgp_json_close(w);
    /* u and v: one after the other, at the same time (glpgp_options.oscillators) or
     * one coupled system */
    glpgp_json_str(w, "oscillators", r->coupled ? "coupled" : r->concurrent ? "concurrent" : "sequential");
}

/* "ranks" and "per_rank" of a distributed run. */
static void stats_ranks(glpgp_json *w, const glpgp_stats_extra *x)
{
    if (x && x->ranks > 0 && x->rank_info) {
        glpgp_json_int(w, "ranks", x->ranks);
        glpgp_json_array(w, "per_rank");
        for (int k = 0; k < x->ranks; k++) {
            const double *ri = x->rank_info + (size_t)k * GLPGP_RANK_INFO_N;
            glpgp_json_object(w, NULL);
            glpgp_json_int(w, "rank", k);
            glpgp_json_int(w, "owned", (long)ri[0]);
            glpgp_json_int(w, "ghosts", (long)ri[1]);
            glpgp_json_num(w, "seconds", ri[2]);
            glpgp_json_num(w, "max_rss_mib", ri[3] / (1024.0 * 1024.0));
            glpgp_json_close(w);
        }
        glpgp_json_close(w);
    }
}

static void stats_body(FILE *f, const glpgp_mesh *m, const glpgp_options *o, const glpgp_result *r,
                       const glpgp_stats_extra *x)
{
    static const char *const oname[2] = {"u", "v"};
    glpgp_json w0, *w = &w0;
    glpgp_json_init(w, f);

    glpgp_json_object(w, NULL);
    glpgp_json_str(w, "version", GLPGP_VERSION);
    glpgp_json_str(w, "input", x ? x->input : NULL);
    glpgp_json_str(w, "output", x ? x->output : NULL);
    glpgp_json_int(w, "vertices", m->nv);
    glpgp_json_int(w, "triangles", m->nt);
    glpgp_json_num(w, "size", r->size);
    if (o) {
        glpgp_json_str(w, "method", method_name(o->method));
        glpgp_json_str(w, "energy", energy_name(o->energy));
        glpgp_json_str(w, "newton", hess_name(o->hess));
    } else {
        glpgp_json_null(w, "method");
        glpgp_json_null(w, "energy");
        glpgp_json_null(w, "newton");
    }
    glpgp_json_str(w, "backend", r->backend);
    glpgp_json_str(w, "device", x ? x->device : NULL);
    stats_options(w, o);

    glpgp_json_object(w, "mesh");
    glpgp_json_num(w, "area", m->area);
    glpgp_json_num(w, "mean_edge", m->mean_edge);
    glpgp_json_int(w, "boundary_loops", m->nloops);
    glpgp_json_array(w, "bbox");
    for (int i = 0; i < 4; i++) glpgp_json_num(w, NULL, m->bbox[i]);
    glpgp_json_close(w);
    glpgp_json_int(w, "orientation_fixed", m->orientation_fixed);
    if (m->surf) stats_surface(w, m, o, x);
    glpgp_json_close(w);

    glpgp_json_object(w, "singularities");
    for (int k = 0; k < 2; k++) {
        glpgp_json_object(w, oname[k]);
        glpgp_json_int(w, "plus", r->osc[k].plus);
        glpgp_json_int(w, "minus", r->osc[k].minus);
        glpgp_json_close(w);
    }
    glpgp_json_close(w);

    stats_cross(w, m, r);
    stats_counts(w, r);
    stats_schedule(w, r);
    stats_time(w, r, x);
    stats_ranks(w, x);
    if (x && x->quads) glpgp_quads_json(w, "quads", x->quads);
    glpgp_json_finish(w);
}

glpgp_status glpgp_output_set_stats(glpgp_output_set *s, const glpgp_mesh *m, const glpgp_options *opts,
                                    const glpgp_result *r, const char *path, const glpgp_stats_extra *extra)
{
    FILE *f;
    if (!m || !r) return GLPGP_FAIL(GLPGP_ERR_ARG, "no mesh or no result to write");
    GLPGP_CHECK(glpgp_output_set_open(s, path, &f));
    stats_body(f, m, opts, r, extra);
    return GLPGP_OK;
}

glpgp_status glpgp_write_stats_json(const glpgp_mesh *m, const glpgp_options *opts,
                                    const glpgp_result *r, const char *path,
                                    const glpgp_stats_extra *extra)
{
    glpgp_output_set *s = NULL;
    GLPGP_CHECK(glpgp_output_set_create(&s));
    glpgp_status st = glpgp_output_set_stats(s, m, opts, r, path, extra);
    if (st == GLPGP_OK) st = glpgp_output_set_commit(s);
    glpgp_output_set_destroy(&s);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

/* the statistics as a string: the same writer on a memory stream */
glpgp_status glpgp_stats_json_text(const glpgp_mesh *m, const glpgp_options *opts, const glpgp_result *r,
                                   const glpgp_stats_extra *extra, char **out)
{
    *out = NULL;
    if (!m || !r) return GLPGP_FAIL(GLPGP_ERR_ARG, "no mesh or no result to write");
    size_t len = 0;
    FILE *f = open_memstream(out, &len);
    if (!f) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (statistics text)");
    stats_body(f, m, opts, r, extra);
    if (fclose(f) != 0 || !*out) {
        free(*out);
        *out = NULL;
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (statistics text)");
    }
    return GLPGP_OK;
}

glpgp_status glpgp_quads_json_text(const glpgp_quads_report *qq, char **out)
{
    *out = NULL;
    size_t len = 0;
    FILE *f = open_memstream(out, &len);
    if (!f) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (quality report text)");
    glpgp_json w;
    glpgp_json_init(&w, f);
    glpgp_quads_json(&w, NULL, qq);
    glpgp_json_finish(&w);
    if (fclose(f) != 0 || !*out) {
        free(*out);
        *out = NULL;
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (quality report text)");
    }
    return GLPGP_OK;
}
