/* bench_precond.c: glpgp-bench --precond jacobi|amg|both, the preconditioner
 * ladder (issue 12): for each size of the ladder (default 64k, 256k, 1M
 * vertices; 4M with --with-4m), two target sizes (h = 10 mean edges, and
 * the default size glpgp_default_size) and each backend, the same Newton
 * steps solved with 2x2-block Jacobi PCG and with flexible CG + the
 * aggregation multigrid of solver/amg.c, side by side in one run. Per Newton
 * step and preconditioner: CG iterations, setup seconds (multigrid: the
 * per-step values glpgp_amg_update; Jacobi: none, its DINV is part of the
 * assembly), solve seconds, ms per iteration and bytes moved (model below);
 * per case the hierarchy (levels, operator complexity, structure seconds)
 * and the ratio of Jacobi to multigrid time. Markdown on stdout, JSON with
 * --json (iterations vs vertices in "precond_ladder").
 *
 * Anchors (issue 12), on the reference backend's case of each size and h (the
 * OpenCL case's with --no-reference), each left out with a note when its
 * library is absent (--no-petsc, --no-cholmod leave them out): PETSc GAMG
 * (the PETSc backend, one process: KSPCG + PCGAMG with the near null space
 * [z, iz] of the current iterate, its own Newton steps from the same start,
 * the hierarchy built in the first step's solve and reused after, as the
 * solver does within an eps level: "solve s" includes PCSetUp), and CHOLMOD
 * on every Newton system of the Jacobi run (analysis, factorisation, solve;
 * its difference to the CG solution).
 *
 * The Newton steps: the bench's state (bench.c): field W = (1, 0) with its
 * Dirichlet set, z = exp(i theta), theta = 2 pi x / h + a smooth
 * perturbation, eps = 0.5 h; each step assembles NEWTON (o->hess, mixed),
 * solves NEWTON d = -g to rtol 1e-8 from 0 (cap 20000), then x <- x + alpha
 * d with alpha halved from 1 until E + P decreases (at most 10 halvings).
 * Both preconditioners start from the same x; their steps then differ only
 * by the solves' rounding.
 *
 * Bytes moved (a model, counted like bench.c's bytes_cg): Jacobi: bytes_cg
 * per iteration. Multigrid, per flexible-CG iteration: one fine SpMV and 10
 * fine vectors of the outer iteration, plus per visit of level l < L-1 three
 * SpMVs of A_l (restriction residual, post-smoothing, the K-cycle's product)
 * and 16 level vectors of 16 n_l bytes, per visit of the coarsest level the
 * dense inverse (8 m^2); the K-cycle visits level l+1 twice per visit of
 * level l (levels 1 .. L-2), V-cycle levels once. */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PC_MAX_STEPS 20
#define PC_N 3 /* 0: Jacobi, 1: multigrid, 2: PETSc GAMG (an anchor) */
static const char *const pc_name[PC_N] = {"jacobi", "amg", "gamg"};

typedef struct pc_step {
    int cg;
    double setup_s, solve_s, assemble_s, bytes, relres, alpha;
    int reason;
    long sync_setup, sync_solve; /* host round trips counted by the drivers (b->n_sync) */
    long launch_setup, launch_solve; /* OpenCL kernel launches (b->n_launch; 0 on the reference) */
} pc_step;

typedef struct pc_case {
    int nv;
    long nnzb;
    double h;
    int hdefault;        /* 1: h = the default size, 0: 10 mean edges */
    int opencl;
    int ran[PC_N];       /* [0] Jacobi, [1] multigrid, [2] PETSc GAMG */
    char note[PC_N][200];
    pc_step st[PC_N][PC_MAX_STEPS];
    int nsteps[PC_N];
    int anchors;         /* this case runs the anchors (GAMG, CHOLMOD) */
    int want_cholmod;    /* CHOLMOD on the Jacobi run's systems */
    bench_cholmod ch[PC_MAX_STEPS];
    int nch;             /* CHOLMOD runs recorded */
    char ch_note[200];   /* why CHOLMOD did not run */
    glpgp_amg_info info;
    double bytes_amg_it; /* model, per flexible-CG iteration */
    int kmin;            /* K-cycle on levels of >= kmin nodes (resolved amg_kcycle_min) */
    int passes;          /* amg_coarse_passes */
} pc_case;

static double b_spmv(double nv, double nnzb) { return 36.0 * nnzb + 4.0 * (nv + 1) + 32.0 * nv; }
static double b_cg(double nv, double nnzb) { return b_spmv(nv, nnzb) + 144.0 * nv + 48.0 * nv; }

/* the multigrid byte model above */
static double amg_bytes_per_it(const glpgp_amg_info *in, const glpgp_options *o)
{
    const int L = in->nlevels;
    double visits = 1.0, bytes = b_spmv(in->n[0], (double)in->nnzb[0]) + 10.0 * 16.0 * in->n[0];
    for (int l = 0; l < L; l++) {
        if (l == L - 1) {
            const double m = 2.0 * in->n[l];
            bytes += visits * (8.0 * m * m + 32.0 * m);
            break;
        }
        bytes += visits * (3.0 * b_spmv(in->n[l], (double)in->nnzb[l]) + 16.0 * 16.0 * in->n[l]);
        const int next = l + 1;
        const int k = o->amg_cycle == GLPGP_AMG_KCYCLE && next < L - 1 && in->n[next] >= o->amg_kcycle_min;
        visits *= k ? 2.0 : 1.0;
    }
    return bytes;
}

static glpgp_status make_backend(int opencl, int pc, int device, glpgp_backend **b)
{
    if (pc == 2) return glpgp_backend_create_petsc(GLPGP_PETSC_PRECOND_GAMG, b); /* the GAMG anchor */
    if (!opencl) return glpgp_backend_create_reference(b);
    glpgp_cl_options co = {device, 0, NULL};
    return glpgp_backend_create_opencl(&co, b);
}

static glpgp_status sync_be(glpgp_backend *b)
{
    double s[1];
    return b->ops->get_scalars(b, s, 1);
}

/* E + P at x into *F (work: scratch vector) */
static glpgp_status energy_at(glpgp_backend *b, const glpgp_vec *x, double inv4e2, glpgp_vec *work, double *F)
{
    double s[GLPGP_NSLOTS];
    GLPGP_CHECK(b->ops->energy(b, x, inv4e2, work));
    GLPGP_CHECK(b->ops->get_scalars(b, s, GLPGP_NSLOTS));
    *F = s[GLPGP_S_E] + s[GLPGP_S_P];
    return GLPGP_OK;
}

/* The Newton steps of one case with one preconditioner (pc 0: Jacobi, 1:
 * multigrid, 2: PETSc GAMG on the PETSc backend); with cs->want_cholmod and
 * pc 0, CHOLMOD on each step's system too. */
static glpgp_status run_case(const glpgp_mesh *m, const glpgp_system *sys, const double *w,
                             const unsigned char *dir, const double *x0, pc_case *cs, int pc, int steps,
                             const bench_precond_opts *po)
{
    glpgp_status st = GLPGP_OK;
    glpgp_backend *b = NULL;
    glpgp_amg *a = NULL;
    glpgp_vec *x = NULL, *g = NULL, *rhs = NULL, *d = NULL, *xt = NULL, *wk = NULL;
    double *hv = NULL, *hr = NULL, *hd = NULL; /* CHOLMOD: NEWTON values, rhs, CG solution */
    const size_t n2 = (size_t)2 * m->nv;
    glpgp_options o;
    glpgp_options_default(&o);
    o.precond = pc ? GLPGP_PRECOND_AMG : GLPGP_PRECOND_JACOBI;
    o.amg_kcycle_min = po->kcycle_min;
    if (po->amg_pre >= 0) o.amg_pre = po->amg_pre;
    if (po->amg_post >= 0) o.amg_post = po->amg_post;
    if (po->amg_passes >= 0) o.amg_coarse_passes = po->amg_passes;
    const double eps = 0.5 * cs->h, inv4e2 = 1.0 / (4.0 * eps * eps);
    const int chol = pc == 0 && cs->want_cholmod;
    GLPGP_CHECK(make_backend(cs->opencl, pc, po->device, &b));
    o.amg_kcycle_min = glpgp_amg_kcycle_min(b, &o); /* resolved: the byte model reads it */
    if (pc == 1) {
        cs->kmin = o.amg_kcycle_min;
        cs->passes = o.amg_coarse_passes;
    }
    const glpgp_backend_ops *op = b->ops;
    glpgp_vec **vs[] = {&x, &g, &rhs, &d, &xt, &wk};
    GLPGP_CHECK_GOTO(st, op->setup(b, sys), done);
    for (size_t k = 0; k < sizeof vs / sizeof vs[0]; k++) GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, vs[k]), done);
    if (chol) {
        cs->nch = 0;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * sys->nnzb, sizeof(double), &hv), done);
        GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &hr), done);
        GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &hd), done);
    }
    GLPGP_CHECK_GOTO(st, op->set_field(b, w, dir), done);
    GLPGP_CHECK_GOTO(st, op->assemble_quadratic(b, GLPGP_ELEM_P1, cs->h), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, x0), done);
    if (pc == 1) {
        GLPGP_CHECK_GOTO(st, glpgp_amg_create(b, &o, dir, w, cs->h, &a), done);
        glpgp_amg_get_info(a, &cs->info);
        cs->bytes_amg_it = amg_bytes_per_it(&cs->info, &o);
    }
    double F = 0.0;
    GLPGP_CHECK_GOTO(st, energy_at(b, x, inv4e2, wk, &F), done);
    for (int k = 0; k < steps; k++) {
        pc_step *s = &cs->st[pc][k];
        /* NEWTON at x (DINV included) */
        double t0 = bench_now();
        GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, inv4e2, o.hess), done);
        GLPGP_CHECK_GOTO(st, op->gradient(b, x, inv4e2, g), done);
        GLPGP_CHECK_GOTO(st, op->axpby(b, -1.0, g, 0.0, rhs), done);
        GLPGP_CHECK_GOTO(st, sync_be(b), done);
        double t1 = bench_now();
        s->assemble_s = t1 - t0;
        /* setup: the multigrid values of this step */
        long ns0 = b->n_sync, nl0 = b->n_launch;
        if (a) GLPGP_CHECK_GOTO(st, glpgp_amg_update(a, x), done);
        s->sync_setup = b->n_sync - ns0;
        s->launch_setup = b->n_launch - nl0;
        ns0 = b->n_sync;
        nl0 = b->n_launch;
        GLPGP_CHECK_GOTO(st, sync_be(b), done);
        double t2 = bench_now();
        s->setup_s = t2 - t1;
        /* NEWTON d = -g */
        glpgp_cg_info ci;
        GLPGP_CHECK_GOTO(st, glpgp_linear_solve(b, a, rhs, d, 1e-8, 20000, o.cg_check, &ci), done);
        GLPGP_CHECK_GOTO(st, sync_be(b), done);
        s->solve_s = bench_now() - t2;
        s->sync_solve = b->n_sync - ns0;
        s->launch_solve = b->n_launch - nl0;
        s->cg = ci.iterations;
        s->relres = ci.relres;
        s->reason = (int)ci.reason;
        s->bytes = pc == 2 ? 0.0 : ci.iterations * (a ? cs->bytes_amg_it : b_cg(m->nv, (double)sys->nnzb));
        if (chol && k < PC_MAX_STEPS) {
            /* the same system by CHOLMOD (NEWTON read back; its time is not the step's) */
            GLPGP_CHECK_GOTO(st, glpgp_probe_matrix(b, GLPGP_MAT_NEWTON, hv), done);
            GLPGP_CHECK_GOTO(st, op->vec_read(b, rhs, hr), done);
            GLPGP_CHECK_GOTO(st, op->vec_read(b, d, hd), done);
            GLPGP_CHECK_GOTO(st, bench_cholmod_run(sys, hv, hr, hd, &cs->ch[k]), done);
            cs->nch = k + 1;
        }
        /* x <- x + alpha d, alpha halved until E + P decreases */
        double alpha = 1.0, Ft = F;
        int ok = 0;
        for (int h = 0; h <= 10; h++, alpha *= 0.5) {
            GLPGP_CHECK_GOTO(st, op->copy(b, xt, x), done);
            GLPGP_CHECK_GOTO(st, op->axpby(b, alpha, d, 1.0, xt), done);
            GLPGP_CHECK_GOTO(st, energy_at(b, xt, inv4e2, wk, &Ft), done);
            if (Ft < F) {
                ok = 1;
                break;
            }
        }
        s->alpha = ok ? alpha : 0.0;
        cs->nsteps[pc] = k + 1;
        if (!ok) break;
        GLPGP_CHECK_GOTO(st, op->copy(b, x, xt), done);
        F = Ft;
    }
    cs->ran[pc] = 1;
done:
    glpgp_amg_destroy(&a);
    if (b)
        for (size_t k = 0; k < sizeof vs / sizeof vs[0]; k++) op->vec_destroy(b, vs[k]);
    glpgp_backend_destroy(&b);
    free(hv);
    free(hr);
    free(hd);
    return st;
}

static double sum_field(const pc_case *c, int pc, int which)
{
    double s = 0.0;
    for (int k = 0; k < c->nsteps[pc]; k++) {
        const pc_step *t = &c->st[pc][k];
        s += which == 0 ? t->cg : which == 1 ? t->setup_s : which == 2 ? t->solve_s : t->bytes;
    }
    return s;
}

static void print_case(const pc_case *c, const int want[PC_N])
{
    printf("\n### %d vertices, h = %.4g (%s), %s\n\n", c->nv, c->h, c->hdefault ? "default size" : "10 mean edges",
           c->opencl ? "OpenCL" : "reference");
    if (c->ran[1])
        printf("multigrid: %d levels (%d -> %d nodes), operator complexity %.3f, structure %.3f s, "
               "K-cycle on levels of >= %d nodes\n\n",
               c->info.nlevels, c->info.n[0], c->info.n[c->info.nlevels - 1], c->info.operator_complexity,
               c->info.seconds_structure, c->kmin);
    printf("| step | precond | CG it | setup s | solve s | ms/it | GB moved | step length | host round trips setup / solve "
           "| kernel launches setup / per it |\n"
           "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < PC_MAX_STEPS; k++)
        for (int pc = 0; pc < PC_N; pc++) {
            if (!want[pc] || !c->ran[pc] || k >= c->nsteps[pc]) continue;
            const pc_step *s = &c->st[pc][k];
            if (pc == 2) { /* PETSc's own: no byte model, no counted round trips or launches */
                printf("| %d | PETSc GAMG (anchor) | %d | - | %.3f | %.3f | - | %g | - | - |\n", k + 1, s->cg,
                       s->solve_s, s->cg ? 1e3 * s->solve_s / s->cg : 0.0, s->alpha);
                continue;
            }
            printf("| %d | %s | %d | %.3f | %.3f | %.3f | %.2f | %g | %ld / %ld | %ld / %.1f |\n", k + 1,
                   pc_name[pc], s->cg, s->setup_s, s->solve_s, s->cg ? 1e3 * s->solve_s / s->cg : 0.0,
                   s->bytes * 1e-9, s->alpha, s->sync_setup, s->sync_solve, s->launch_setup,
                   s->cg ? (double)s->launch_solve / s->cg : 0.0);
        }
    for (int pc = 0; pc < PC_N; pc++)
        if (want[pc] && !c->ran[pc] && (pc < 2 || c->anchors))
            printf("| - | %s | %s | | | | | | | |\n", pc == 2 ? "PETSc GAMG (anchor)" : pc_name[pc], c->note[pc]);
    if (c->ran[0] && c->ran[1] && c->nsteps[0] && c->nsteps[1]) {
        const double tj = (sum_field(c, 0, 1) + sum_field(c, 0, 2)) / c->nsteps[0];
        const double ta = (sum_field(c, 1, 1) + sum_field(c, 1, 2)) / c->nsteps[1];
        printf("\nper Newton step: Jacobi %.1f CG it, %.3f s; multigrid %.1f CG it, %.3f s (setup %.3f s); "
               "Jacobi / multigrid time %.2f\n",
               sum_field(c, 0, 0) / c->nsteps[0], tj, sum_field(c, 1, 0) / c->nsteps[1], ta,
               sum_field(c, 1, 1) / c->nsteps[1], ta > 0 ? tj / ta : 0.0);
    }
    if (c->ran[2] && c->nsteps[2])
        printf("PETSc GAMG (anchor, [z, iz], its own steps from the same start; the first solve includes PCSetUp): "
               "%.1f CG it, %.3f s per Newton step\n",
               sum_field(c, 2, 0) / c->nsteps[2], (sum_field(c, 2, 1) + sum_field(c, 2, 2)) / c->nsteps[2]);
    if (c->anchors && c->want_cholmod && c->nch > 0) {
        printf("CHOLMOD (anchor, on the Jacobi run's systems):");
        for (int k = 0; k < c->nch; k++) {
            const bench_cholmod *h = &c->ch[k];
            if (h->ok)
                printf(" step %d: analyze %.3f + factorize %.3f + solve %.3f s, |x - x_cg| / |x| %.1e%s", k + 1,
                       h->analyze_s, h->factorize_s, h->solve_s, h->rel_diff_vs_cg, k + 1 < c->nch ? ";" : "\n");
            else
                printf(" step %d: %s%s", k + 1, h->note, k + 1 < c->nch ? ";" : "\n");
        }
    } else if (c->anchors && c->ch_note[0]) {
        printf("CHOLMOD (anchor): %s\n", c->ch_note);
    }
}

static void json_case(glpgp_json *w, const pc_case *c)
{
    glpgp_json_object(w, NULL);
    glpgp_json_int(w, "vertices", c->nv);
    glpgp_json_int(w, "blocks", c->nnzb);
    glpgp_json_num(w, "h", c->h);
    glpgp_json_str(w, "h_case", c->hdefault ? "default" : "10_mean_edges");
    glpgp_json_str(w, "backend", c->opencl ? "opencl" : "reference");
    if (c->ran[1]) {
        glpgp_json_int(w, "amg_levels", c->info.nlevels);
        glpgp_json_num(w, "amg_operator_complexity", c->info.operator_complexity);
        glpgp_json_num(w, "amg_structure_s", c->info.seconds_structure);
        glpgp_json_num(w, "amg_bytes_per_iteration", c->bytes_amg_it);
        glpgp_json_int(w, "amg_kcycle_min", c->kmin);
        glpgp_json_int(w, "amg_coarse_passes", c->passes);
    }
    for (int pc = 0; pc < PC_N; pc++) {
        const char *name = pc_name[pc];
        if (pc == 2 && !c->anchors) continue;
        if (!c->ran[pc]) {
            glpgp_json_null(w, name);
            continue;
        }
        const int n = c->nsteps[pc];
        glpgp_json_object(w, name);
        glpgp_json_int(w, "steps", n);
        glpgp_json_num(w, "mean_cg", n ? sum_field(c, pc, 0) / n : 0.0);
        glpgp_json_num(w, "mean_setup_s", n ? sum_field(c, pc, 1) / n : 0.0);
        glpgp_json_num(w, "mean_solve_s", n ? sum_field(c, pc, 2) / n : 0.0);
        glpgp_json_array(w, "per_step");
        for (int k = 0; k < n; k++) {
            const pc_step *s = &c->st[pc][k];
            glpgp_json_object(w, NULL);
            glpgp_json_int(w, "cg", s->cg);
            glpgp_json_num(w, "setup_s", s->setup_s);
            glpgp_json_num(w, "solve_s", s->solve_s);
            glpgp_json_num(w, "ms_per_it", s->cg ? 1e3 * s->solve_s / s->cg : 0.0);
            glpgp_json_num(w, "bytes", s->bytes);
            glpgp_json_num(w, "assemble_s", s->assemble_s);
            glpgp_json_num(w, "relres", s->relres);
            glpgp_json_num(w, "alpha", s->alpha);
            glpgp_json_int(w, "syncs_setup", s->sync_setup);
            glpgp_json_int(w, "syncs_solve", s->sync_solve);
            glpgp_json_int(w, "launches_setup", s->launch_setup);
            glpgp_json_int(w, "launches_solve", s->launch_solve);
            glpgp_json_close(w);
        }
        glpgp_json_close(w);
        glpgp_json_close(w);
    }
    if (c->anchors) {
        if (!c->want_cholmod || c->nch == 0) {
            glpgp_json_null(w, "cholmod");
        } else {
            glpgp_json_array(w, "cholmod");
            for (int k = 0; k < c->nch; k++) {
                const bench_cholmod *h = &c->ch[k];
                glpgp_json_object(w, NULL);
                glpgp_json_bool(w, "ok", h->ok);
                glpgp_json_num(w, "analyze_s", h->analyze_s);
                glpgp_json_num(w, "factorize_s", h->factorize_s);
                glpgp_json_num(w, "solve_s", h->solve_s);
                glpgp_json_num(w, "factor_nnz", h->factor_nnz);
                glpgp_json_num(w, "rel_diff_vs_cg", h->rel_diff_vs_cg);
                glpgp_json_num(w, "peak_bytes", h->peak_bytes);
                glpgp_json_close(w);
            }
            glpgp_json_close(w);
        }
    }
    glpgp_json_close(w);
}

int bench_precond_run(const bench_precond_opts *po)
{
    /* which: 0 jacobi, 1 amg, 2 both; the GAMG anchor when PETSc is there */
    int want[PC_N] = {po->which != 1, po->which != 0, !po->no_petsc};
    char gamg_note[200] = "";
    if (po->no_petsc)
        snprintf(gamg_note, sizeof gamg_note, "left out (--no-petsc)");
    else if (!glpgp_have_petsc())
        snprintf(gamg_note, sizeof gamg_note, "skipped: this glpgp has no PETSc module (Debian petsc-dev)");
    else if (glpgp_petsc_init() != GLPGP_OK) {
        snprintf(gamg_note, sizeof gamg_note, "skipped: %s", glpgp_error_message());
        glpgp_error_clear();
    }
    if (gamg_note[0]) {
        want[2] = 0;
        fprintf(stderr, "glpgp-bench: PETSc GAMG anchor %s\n", gamg_note);
    }
    if (!po->no_cholmod && !bench_have_cholmod())
        fprintf(stderr, "glpgp-bench: CHOLMOD anchor skipped: not built with it (Debian libsuitesparse-dev)\n");
    long sizes[16];
    int ns = 0;
    if (po->nsizes > 0) {
        for (int i = 0; i < po->nsizes && ns < 16; i++) sizes[ns++] = po->sizes[i];
    } else {
        sizes[ns++] = 64000;
        sizes[ns++] = 256000;
        sizes[ns++] = 1000000;
        if (po->with_4m) sizes[ns++] = 4000000;
    }
    const int nb = (!po->no_reference) + (!po->no_opencl);
    pc_case *cases = calloc((size_t)ns * 2 * (nb ? nb : 1), sizeof(pc_case));
    if (!cases) {
        fprintf(stderr, "glpgp-bench: out of memory\n");
        return 1;
    }
    int nc = 0, rc = 0;
    /* warm-up: the first launches of every kernel (PoCL compiles or loads
     * each at its first use in a process) on a small disk, not reported */
    {
        glpgp_mesh *m = NULL;
        glpgp_system *sys = NULL;
        double *w = NULL, *x0 = NULL;
        unsigned char *dir = NULL;
        pc_case *wc = calloc(1, sizeof *wc);
        if (wc && glpgp_mesh_generate("disk", 2000, &m) == GLPGP_OK && glpgp_system_create(m, &sys) == GLPGP_OK &&
            (w = calloc((size_t)2 * m->nv, sizeof(double))) && (x0 = calloc((size_t)2 * m->nv, sizeof(double))) &&
            (dir = calloc((size_t)m->nv, 1))) {
            for (int i = 0; i < m->nv; i++) w[2 * i] = x0[2 * i] = 1.0;
            glpgp_dirichlet_set(m, w, dir);
            wc->h = 10.0 * m->mean_edge;
            for (int be = 0; be < 2; be++) {
                if (be == 0 ? po->no_opencl : po->no_reference) continue;
                wc->opencl = be == 0;
                for (int pc = 0; pc < 2; pc++) /* not the anchors */
                    if (want[pc]) (void)run_case(m, sys, w, dir, x0, wc, pc, 1, po);
            }
        }
        glpgp_error_clear();
        free(wc);
        free(w);
        free(x0);
        free(dir);
        glpgp_system_destroy(&sys);
        glpgp_mesh_destroy(&m);
    }
    printf("# glpgp-bench --precond: Jacobi-PCG vs flexible CG + multigrid, %d Newton steps per case, shape %s\n",
           po->steps, po->shape);
    for (int si = 0; si < ns; si++) {
        glpgp_mesh *m = NULL;
        glpgp_system *sys = NULL;
        double *w = NULL, *x0 = NULL;
        unsigned char *dir = NULL;
        if (glpgp_mesh_generate(po->shape, sizes[si], &m) != GLPGP_OK || glpgp_system_create(m, &sys) != GLPGP_OK) {
            fprintf(stderr, "glpgp-bench: %ld vertices: %s\n", sizes[si], glpgp_error_message());
            glpgp_error_clear();
            glpgp_system_destroy(&sys);
            glpgp_mesh_destroy(&m);
            rc = 1;
            continue;
        }
        const size_t n2 = (size_t)2 * m->nv;
        w = calloc(n2, sizeof(double));
        x0 = calloc(n2, sizeof(double));
        dir = calloc((size_t)m->nv, 1);
        if (!w || !x0 || !dir) {
            rc = 1;
            goto next;
        }
        for (int i = 0; i < m->nv; i++) w[2 * i] = 1.0;
        glpgp_dirichlet_set(m, w, dir);
        for (int hc = 0; hc < 2; hc++) {
            if (po->hcases && !(po->hcases & (1 << hc))) continue;
            const double h = hc ? glpgp_default_size(m, NULL) : 10.0 * m->mean_edge;
            /* z = exp(i theta), theta = 2 pi x / h + a smooth perturbation (bench.c's state) */
            const double L = fmax(m->bbox[2] - m->bbox[0], m->bbox[3] - m->bbox[1]);
            for (int i = 0; i < m->nv; i++) {
                const double x = m->xy[2 * i], y = m->xy[2 * i + 1];
                const double th = 2.0 * GLPGP_PI * x / h + 0.5 * sin(2.0 * GLPGP_PI * x / L) * cos(2.0 * GLPGP_PI * y / L);
                x0[2 * i] = cos(th);
                x0[2 * i + 1] = sin(th);
            }
            for (int be = 0; be < 2; be++) {
                if (be == 0 ? po->no_opencl : po->no_reference) continue;
                pc_case *cs = &cases[nc++];
                cs->nv = m->nv;
                cs->nnzb = sys->nnzb;
                cs->h = h;
                cs->hdefault = hc;
                cs->opencl = be == 0;
                /* the anchors once per size and h: with the reference case (the
                 * OpenCL one with --no-reference) */
                cs->anchors = be == 1 || po->no_reference;
                cs->want_cholmod = cs->anchors && !po->no_cholmod && bench_have_cholmod() &&
                                   (po->max_cholmod <= 0 || m->nv <= po->max_cholmod) && want[0];
                if (cs->anchors && !cs->want_cholmod)
                    snprintf(cs->ch_note, sizeof cs->ch_note, "%s",
                             po->no_cholmod            ? "left out (--no-cholmod)"
                             : !bench_have_cholmod()   ? "skipped: not built with it (Debian libsuitesparse-dev)"
                             : !want[0]                ? "runs on the Jacobi run's systems (--precond both or jacobi)"
                                                       : "skipped: above --max-cholmod-vertices");
                if (cs->anchors && !want[2]) snprintf(cs->note[2], sizeof cs->note[2], "%s", gamg_note);
                for (int pc = 0; pc < PC_N; pc++) {
                    if (!want[pc] || (pc == 2 && !cs->anchors)) continue;
                    fprintf(stderr, "glpgp-bench: %d vertices, h = %.4g, %s, %s\n", m->nv, h,
                            pc == 2 ? "PETSc" : cs->opencl ? "OpenCL" : "reference",
                            pc == 2 ? "GAMG (anchor)" : pc ? "multigrid" : "Jacobi");
                    if (run_case(m, sys, w, dir, x0, cs, pc, po->steps, po) != GLPGP_OK) {
                        snprintf(cs->note[pc], sizeof cs->note[pc], "failed: %s", glpgp_error_message());
                        for (char *p = cs->note[pc]; *p; p++)
                            if (*p == '\n' || *p == '|') *p = ' ';
                        fprintf(stderr, "glpgp-bench: %s\n", cs->note[pc]);
                        glpgp_error_clear();
                        cs->ran[pc] = 0;
                    }
                }
                {
                    int shown[PC_N] = {want[0], want[1], 1};
                    print_case(cs, shown);
                }
                fflush(stdout);
            }
        }
    next:
        free(w);
        free(x0);
        free(dir);
        glpgp_system_destroy(&sys);
        glpgp_mesh_destroy(&m);
    }
    /* iterations vs vertices */
    printf("\n## CG iterations per Newton step vs vertices\n\n| vertices | h case | backend | Jacobi | multigrid | "
           "Jacobi s/step | multigrid s/step | ratio | PETSc GAMG it (s/step) | CHOLMOD s/step |\n"
           "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < nc; i++) {
        const pc_case *c = &cases[i];
        double it[PC_N] = {0, 0, 0}, t[PC_N] = {0, 0, 0};
        for (int pc = 0; pc < PC_N; pc++)
            if (c->ran[pc] && c->nsteps[pc]) {
                it[pc] = sum_field(c, pc, 0) / c->nsteps[pc];
                t[pc] = (sum_field(c, pc, 1) + sum_field(c, pc, 2)) / c->nsteps[pc];
            }
        char ga[64] = "", ch[64] = "";
        if (c->anchors && c->ran[2]) snprintf(ga, sizeof ga, "%.1f (%.3f)", it[2], t[2]);
        else if (c->anchors) snprintf(ga, sizeof ga, "-");
        if (c->anchors && c->nch > 0) {
            double sum = 0.0;
            int ok = 0;
            for (int k = 0; k < c->nch; k++)
                if (c->ch[k].ok) {
                    sum += c->ch[k].analyze_s + c->ch[k].factorize_s + c->ch[k].solve_s;
                    ok++;
                }
            if (ok) snprintf(ch, sizeof ch, "%.3f", sum / ok);
            else snprintf(ch, sizeof ch, "failed");
        } else if (c->anchors) {
            snprintf(ch, sizeof ch, "-");
        }
        printf("| %d | %s | %s | %.1f | %.1f | %.3f | %.3f | %.2f | %s | %s |\n", c->nv,
               c->hdefault ? "default" : "10 edges", c->opencl ? "OpenCL" : "reference", it[0], it[1], t[0], t[1],
               t[1] > 0 && t[0] > 0 ? t[0] / t[1] : 0.0, ga, ch);
    }
    if (po->json) {
        FILE *f = fopen(po->json, "w");
        if (!f) {
            fprintf(stderr, "glpgp-bench: cannot write %s\n", po->json);
            rc = 1;
        } else {
            glpgp_json w;
            glpgp_json_init(&w, f);
            glpgp_json_object(&w, NULL);
            glpgp_json_str(&w, "bench", "glpgp-bench --precond");
            glpgp_json_str(&w, "shape", po->shape);
            glpgp_json_int(&w, "newton_steps", po->steps);
            glpgp_json_num(&w, "cg_rtol", 1e-8);
            glpgp_json_array(&w, "precond_ladder");
            for (int i = 0; i < nc; i++) json_case(&w, &cases[i]);
            glpgp_json_close(&w);
            glpgp_json_finish(&w);
            if (fclose(f) != 0) rc = 1;
            else fprintf(stderr, "glpgp-bench: wrote %s\n", po->json);
        }
    }
    free(cases);
    glpgp_petsc_finalize(); /* when the GAMG anchor initialised it */
    return rc;
}
