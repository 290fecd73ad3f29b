/* cmd_opencl.c: the OpenCL subcommands of the CLI:
 *   glpgp devices      list every OpenCL platform and device (the global device
 *                      index used by --device and GLPGP_DEVICE);
 *   glpgp crosscheck   run the reference and the OpenCL backend on the same mesh
 *                      and compare them stage by stage (assembly, gradient,
 *                      spmv, dot, CG, one Newton step, a whole GL solve), print
 *                      a table and exit 1 if any stage is out of tolerance.
 * Matrices are read back from both backends through the ops table only
 * (glpgp_probe_matrix, exact), so the comparison needs no backend internals.
 * Tolerance per entry: |a - b| <= atol + rtol |b| with atol = afac * max|b|
 * over the stage (scalars: afac * their own scale); "max rel diff" in the
 * table is the normwise max|a - b| / max|b|. */
#include "commands.h"

#include "cli.h"
#include "opts.h"
#include "glpgp/backends.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/shapes.h"
#include "glpgp/solve.h"
#include "glpgp/system.h"
#include "element.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- glpgp devices ------------------------------------------------------- */

int glpgp_cmd_devices(int argc, char **argv)
{
    int verbosity = 1;
    glpgp_opts t;
    glpgp_opts_init(&t, "devices", "glpgp devices",
                    "List the OpenCL platforms and devices: global index (for --device N and the\n"
                    "GLPGP_DEVICE environment variable), name, vendor, version, compute units,\n"
                    "global memory, double precision support and type. Exit 1 if no platform.\n");
    glpgp_opts_add_verbosity(&t, &verbosity);
    const char *none = NULL;
    int npos = 0;
    int rc = glpgp_opts_parse(&t, argc, argv, &none, 0, &npos);
    if (rc >= 0) return rc;
    glpgp_device_info *devs = NULL;
    int n = 0;
    if (glpgp_devices_list(&devs, &n) != GLPGP_OK) return glpgp_cli_fail();
    int last_plat = -1;
    if (n == 0) printf("OpenCL platforms found, but no devices\n");
    for (int i = 0; i < n; i++) {
        const glpgp_device_info *d = &devs[i];
        if (d->platform_index != last_plat) {
            last_plat = d->platform_index;
            printf("platform %d: %s | %s | %s\n", last_plat, d->platform, d->platform_vendor,
                   d->platform_version);
        }
        printf("  device %d: %s\n", i, d->name);
        printf("      vendor %s | %s | %u compute units | %.2f GiB global memory | fp64 %s | %s\n",
               d->vendor, d->version, d->compute_units,
               (double)d->global_mem / (1024.0 * 1024.0 * 1024.0), d->fp64 ? "yes" : "no", d->type);
    }
    free(devs);
    return 0;
}

#ifdef GLPGP_HAVE_OPENCL

/* ---- glpgp crosscheck ---------------------------------------------------- */

typedef struct cc_row {
    char stage[48];
    double maxabs, maxrel;
    char tol[40];
    int pass;
} cc_row;

typedef struct cc_table {
    cc_row row[48];
    int n;
    double tscale;
    int failed;
} cc_table;

/* Compare a (OpenCL) with b (reference) entrywise: |a-b| <= atol + rtol |b|,
 * atol = afac * scale (scale <= 0: max|b|). NaN anywhere fails. */
static void cc_compare(cc_table *t, const char *stage, const double *a, const double *b, size_t n,
                       double rtol, double afac, double scale)
{
    cc_row *r = &t->row[t->n < 47 ? t->n++ : 47];
    rtol *= t->tscale;
    afac *= t->tscale;
    double maxb = 0.0, maxd = 0.0;
    int pass = 1;
    for (size_t i = 0; i < n; i++) maxb = fmax(maxb, fabs(b[i]));
    if (scale <= 0.0) scale = maxb;
    const double atol = afac * scale;
    for (size_t i = 0; i < n; i++) {
        double d = fabs(a[i] - b[i]);
        if (!(d <= atol + rtol * fabs(b[i]))) pass = 0;
        if (!(d <= maxd)) maxd = d; /* keeps NaN */
    }
    snprintf(r->stage, sizeof r->stage, "%s", stage);
    r->maxabs = maxd;
    r->maxrel = maxb > 0.0 ? maxd / maxb : (maxd > 0.0 ? INFINITY : 0.0);
    snprintf(r->tol, sizeof r->tol, "rtol %.0e, atol %.0e", rtol, atol);
    r->pass = pass;
    if (!pass) t->failed = 1;
}

/* Exact comparison of integer counts. */
static void cc_counts(cc_table *t, const char *stage, int a1, int a2, int b1, int b2)
{
    cc_row *r = &t->row[t->n < 47 ? t->n++ : 47];
    snprintf(r->stage, sizeof r->stage, "%s", stage);
    r->maxabs = fmax(fabs((double)a1 - b1), fabs((double)a2 - b2));
    r->maxrel = r->maxabs / fmax(1.0, fmax(fabs((double)b1), fabs((double)b2)));
    snprintf(r->tol, sizeof r->tol, "exact (%d+/%d- vs %d+/%d-)", a1, a2, b1, b2);
    r->pass = r->maxabs == 0.0;
    if (!r->pass) t->failed = 1;
}

static void cc_print(const cc_table *t)
{
    printf("%-34s | %-12s | %-12s | %-30s | %s\n", "stage", "max abs diff", "max rel diff", "tolerance",
           "result");
    printf("-----------------------------------+--------------+--------------+--------------------------------+-------\n");
    for (int i = 0; i < t->n; i++) {
        const cc_row *r = &t->row[i];
        printf("%-34s | %12.3e | %12.3e | %-30s | %s\n", r->stage, r->maxabs, r->maxrel, r->tol,
               r->pass ? "PASS" : "FAIL");
    }
}

static double wall(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Deterministic pseudo-random numbers in [0, 1). */
static double cc_rand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/* Read or generate the input mesh. */
static glpgp_status cc_load(const char *input, glpgp_mesh **m)
{
    if (strncmp(input, "shape:", 6) == 0) {
        char name[64];
        long nv;
        GLPGP_CHECK(glpgp_shape_parse(input, 0, name, sizeof name, &nv));
        return glpgp_mesh_generate(name, nv, m);
    }
    return glpgp_mesh_read(input, m);
}

/* The two backends under comparison, each with its own state. */
typedef struct cc_side {
    glpgp_backend *b;
    glpgp_vec *x, *y, *g, *d, *w;
} cc_side;

static void cc_side_free(cc_side *s)
{
    if (s->b) {
        const glpgp_backend_ops *o = s->b->ops;
        o->vec_destroy(s->b, &s->x);
        o->vec_destroy(s->b, &s->y);
        o->vec_destroy(s->b, &s->g);
        o->vec_destroy(s->b, &s->d);
        o->vec_destroy(s->b, &s->w);
    }
    glpgp_backend_destroy(&s->b);
}

static glpgp_status cc_side_init(cc_side *s, const glpgp_system *sys)
{
    const glpgp_backend_ops *o = s->b->ops;
    const size_t n2 = (size_t)2 * sys->nv;
    GLPGP_CHECK(o->setup(s->b, sys));
    GLPGP_CHECK(o->vec_create(s->b, n2, &s->x));
    GLPGP_CHECK(o->vec_create(s->b, n2, &s->y));
    GLPGP_CHECK(o->vec_create(s->b, n2, &s->g));
    GLPGP_CHECK(o->vec_create(s->b, n2, &s->d));
    GLPGP_CHECK(o->vec_create(s->b, n2, &s->w));
    return GLPGP_OK;
}

typedef struct cc_args {
    const char *input;
    double size;
    int kind;
    int device;
    double tscale;
    int solve;
} cc_args;

/* Run the stages; rows go to t. */
static glpgp_status cc_run(const cc_args *a, cc_table *t)
{
    glpgp_status st = GLPGP_OK;
    glpgp_mesh *m = NULL;
    glpgp_system *sys = NULL;
    cc_side S[2]; /* 0: OpenCL, 1: reference */
    double *field = NULL, *z = NULL, *h0 = NULL, *h1 = NULL, *m0 = NULL, *m1 = NULL;
    unsigned char *dir = NULL;
    glpgp_result *res[2] = {NULL, NULL};
    glpgp_backend *sb[2] = {NULL, NULL};
    memset(S, 0, sizeof S);
    glpgp_cl_options clo = {a->device, 0};

    GLPGP_CHECK_GOTO(st, cc_load(a->input, &m), done);
    GLPGP_CHECK_GOTO(st, glpgp_system_create(m, &sys), done);
    const int nv = m->nv;
    const size_t n2 = (size_t)2 * nv, nm = (size_t)4 * sys->nnzb;
    const double h = a->size > 0.0 ? a->size : glpgp_default_size(m, NULL);
    GLPGP_CHECK_GOTO(st, glpgp_backend_create_opencl(&clo, &S[0].b), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_create_reference(&S[1].b), done);
    char info[512];
    glpgp_cl_backend_info(S[0].b, info, sizeof info);
    printf("glpgp crosscheck: %s: %d vertices, %d triangles, %ld blocks, h = %.6g, energy %s\n", a->input, nv,
           m->nt, sys->nnzb, h, a->kind == GLPGP_ELEM_TRANSPORT ? "transport" : "p1");
    printf("OpenCL %s\n\n", info);
    for (int s = 0; s < 2; s++) GLPGP_CHECK_GOTO(st, cc_side_init(&S[s], sys), done);

    GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &field), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &z), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(nm > n2 ? nm : n2, sizeof(double), &h0), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(nm > n2 ? nm : n2, sizeof(double), &h1), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(nm, sizeof(double), &m0), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(nm, sizeof(double), &m1), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, 1, &dir), done);

    /* guiding field (boundary-aligned, from the reference path) and its Dirichlet set */
    glpgp_options opt;
    glpgp_options_default(&opt);
    opt.size = h;
    opt.energy = a->kind;
    long fit = 0;
    GLPGP_CHECK_GOTO(st, glpgp_field_compute(m, S[1].b, &opt, field, &fit), done);
    int ndir = glpgp_dirichlet_set(m, field, dir);
    unsigned long long seed = 12345;
    for (int i = 0; i < nv; i++) {
        /* z = r exp(i phi), r in [0.3, 1.3] */
        double r = 0.3 + cc_rand(&seed), ph = 2.0 * GLPGP_PI * cc_rand(&seed);
        z[2 * i] = r * cos(ph);
        z[2 * i + 1] = r * sin(ph);
    }
    const double eps = opt.eps0 * h, inv4e2 = 1.0 / (4.0 * eps * eps);
    printf("field: boundary (%ld CG iterations), %d Dirichlet vertices; eps = %.4g\n\n", fit, ndir, eps);

    /* QUAD assembly */
    for (int s = 0; s < 2; s++) {
        GLPGP_CHECK_GOTO(st, S[s].b->ops->set_field(S[s].b, field, dir), done);
        GLPGP_CHECK_GOTO(st, S[s].b->ops->assemble_quadratic(S[s].b, a->kind, h), done);
        GLPGP_CHECK_GOTO(st, glpgp_probe_matrix(S[s].b, GLPGP_MAT_QUAD, s ? m1 : m0), done);
    }
    cc_compare(t, "QUAD assembly", m0, m1, nm, 1e-12, 1e-14, 0.0);

    /* NEWTON assembly + DINV for the Hessian variants */
    static const struct { int hess; const char *name; } hv[] = {
        {GLPGP_HESS_PAPER, "paper"}, {GLPGP_HESS_PROJECTED, "projected"}, {GLPGP_HESS_MIXED, "mixed"}};
    for (size_t v = 0; v < sizeof hv / sizeof hv[0]; v++) {
        char name[48];
        for (int s = 0; s < 2; s++) {
            GLPGP_CHECK_GOTO(st, S[s].b->ops->vec_write(S[s].b, S[s].x, z), done);
            GLPGP_CHECK_GOTO(st, S[s].b->ops->assemble_newton(S[s].b, S[s].x, inv4e2, hv[v].hess), done);
            GLPGP_CHECK_GOTO(st, glpgp_probe_matrix(S[s].b, GLPGP_MAT_NEWTON, s ? m1 : m0), done);
        }
        snprintf(name, sizeof name, "NEWTON assembly (%s)", hv[v].name);
        cc_compare(t, name, m0, m1, nm, 1e-12, 1e-14, 0.0);
        for (int s = 0; s < 2; s++)
            GLPGP_CHECK_GOTO(st, glpgp_probe_matrix(S[s].b, GLPGP_PROBE_DINV, s ? h1 : h0), done);
        snprintf(name, sizeof name, "DINV (%s)", hv[v].name);
        cc_compare(t, name, h0, h1, (size_t)4 * nv, 1e-12, 1e-14, 0.0);
    }

    /* gradient and energies at z (NEWTON stays the mixed variant) */
    double sc[2][GLPGP_NSLOTS];
    for (int s = 0; s < 2; s++) {
        GLPGP_CHECK_GOTO(st, S[s].b->ops->gradient(S[s].b, S[s].x, inv4e2, S[s].g), done);
        GLPGP_CHECK_GOTO(st, S[s].b->ops->vec_read(S[s].b, S[s].g, s ? h1 : h0), done);
        GLPGP_CHECK_GOTO(st, S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS), done);
    }
    cc_compare(t, "gradient g", h0, h1, n2, 1e-12, 1e-14, 0.0);
    cc_compare(t, "gradient: E = 1/2 x.QUAD x", &sc[0][GLPGP_S_E], &sc[1][GLPGP_S_E], 1, 1e-12, 1e-14, 0.0);
    cc_compare(t, "gradient: P (penalty)", &sc[0][GLPGP_S_P], &sc[1][GLPGP_S_P], 1, 1e-12, 1e-14, 0.0);
    for (int s = 0; s < 2; s++) {
        GLPGP_CHECK_GOTO(st, S[s].b->ops->energy(S[s].b, S[s].x, inv4e2, S[s].w), done);
        GLPGP_CHECK_GOTO(st, S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS), done);
    }
    cc_compare(t, "energy: E", &sc[0][GLPGP_S_E], &sc[1][GLPGP_S_E], 1, 1e-12, 1e-14, 0.0);
    cc_compare(t, "energy: P", &sc[0][GLPGP_S_P], &sc[1][GLPGP_S_P], 1, 1e-12, 1e-14, 0.0);

    /* spmv on both matrices, dot */
    for (int mat = 0; mat < 2; mat++) {
        for (int s = 0; s < 2; s++) {
            GLPGP_CHECK_GOTO(st, S[s].b->ops->spmv(S[s].b, mat, S[s].x, S[s].y), done);
            GLPGP_CHECK_GOTO(st, S[s].b->ops->vec_read(S[s].b, S[s].y, s ? h1 : h0), done);
        }
        cc_compare(t, mat == GLPGP_MAT_QUAD ? "spmv QUAD" : "spmv NEWTON", h0, h1, n2, 1e-12, 1e-14, 0.0);
    }
    double dscale = 0.0;
    for (size_t i = 0; i < n2; i++) dscale += fabs(z[i] * h1[i]);
    for (int s = 0; s < 2; s++) {
        GLPGP_CHECK_GOTO(st, S[s].b->ops->dot(S[s].b, S[s].x, S[s].y, GLPGP_S_DOT), done);
        GLPGP_CHECK_GOTO(st, S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS), done);
    }
    cc_compare(t, "dot x.(NEWTON x)", &sc[0][GLPGP_S_DOT], &sc[1][GLPGP_S_DOT], 1, 1e-12, 1e-14, dscale);

    /* one CG solve: NEWTON d = -g (projected Hessian: SPD) */
    int it[2] = {0, 0};
    for (int s = 0; s < 2; s++) {
        const glpgp_backend_ops *o = S[s].b->ops;
        GLPGP_CHECK_GOTO(st, o->assemble_newton(S[s].b, S[s].x, inv4e2, GLPGP_HESS_PROJECTED), done);
        GLPGP_CHECK_GOTO(st, o->gradient(S[s].b, S[s].x, inv4e2, S[s].g), done);
        GLPGP_CHECK_GOTO(st, o->axpby(S[s].b, -1.0, S[s].g, 0.0, S[s].y), done);
        glpgp_cg_info ci;
        GLPGP_CHECK_GOTO(st, glpgp_cg(S[s].b, S[s].y, S[s].d, 1e-10, 20000, 10, &ci), done);
        it[s] = ci.iterations;
        GLPGP_CHECK_GOTO(st, o->vec_read(S[s].b, S[s].d, s ? h1 : h0), done);
    }
    char name[48];
    snprintf(name, sizeof name, "CG solve (%d vs %d it)", it[0], it[1]);
    cc_compare(t, name, h0, h1, n2, 1e-6, 1e-6, 0.0);
    /* one Newton step: z <- z + d */
    for (int s = 0; s < 2; s++) {
        GLPGP_CHECK_GOTO(st, S[s].b->ops->axpby(S[s].b, 1.0, S[s].d, 1.0, S[s].x), done);
        GLPGP_CHECK_GOTO(st, S[s].b->ops->vec_read(S[s].b, S[s].x, s ? h1 : h0), done);
    }
    cc_compare(t, "Newton step z + d", h0, h1, n2, 1e-6, 1e-6, 0.0);
    for (int s = 0; s < 2; s++) cc_side_free(&S[s]);

    /* the whole GL solve on fresh backends (glpgp_solve does its own setup),
     * converged tightly so both paths reach the same minimiser (at the default
     * 1e-6 they may stop one iteration apart, ~1e-6 apart in z) */
    opt.newton_rtol = 1e-8;
    opt.cg_rtol = 1e-10;
    if (a->solve) {
        double secs[2];
        GLPGP_CHECK_GOTO(st, glpgp_backend_create_opencl(&clo, &sb[0]), done);
        GLPGP_CHECK_GOTO(st, glpgp_backend_create_reference(&sb[1]), done);
        for (int s = 0; s < 2; s++) {
            double t0 = wall();
            GLPGP_CHECK_GOTO(st, glpgp_solve(m, sb[s], &opt, &res[s]), done);
            secs[s] = wall() - t0;
        }
        for (int k = 0; k < 2; k++) {
            /* a level stopped by the Newton cap (drifting vortices) is not converged:
             * reduction-order rounding is amplified along the drift, so 1e-4 there */
            int capped = 0;
            for (int l = 0; l < res[1]->osc[k].nlevels; l++)
                capped |= res[1]->osc[k].level[l].newton >= opt.newton_max;
            const double gtol = capped ? 1e-4 : 1e-6;
            snprintf(name, sizeof name, "GL solve z_%s (newton %d vs %d%s)", k ? "v" : "u",
                     res[0]->osc[k].newton_iterations, res[1]->osc[k].newton_iterations, capped ? ", capped" : "");
            cc_compare(t, name, res[0]->osc[k].z, res[1]->osc[k].z, n2, gtol, gtol, 0.0);
            snprintf(name, sizeof name, "GL singularities %s", k ? "v" : "u");
            cc_counts(t, name, res[0]->osc[k].plus, res[0]->osc[k].minus, res[1]->osc[k].plus,
                      res[1]->osc[k].minus);
        }
        printf("GL solve: OpenCL %.2f s, reference %.2f s (CG iterations %ld+%ld vs %ld+%ld)\n\n", secs[0],
               secs[1], res[0]->osc[0].cg_iterations, res[0]->osc[1].cg_iterations, res[1]->osc[0].cg_iterations,
               res[1]->osc[1].cg_iterations);
    }
done:
    for (int s = 0; s < 2; s++) {
        cc_side_free(&S[s]);
        glpgp_result_destroy(&res[s]);
        glpgp_backend_destroy(&sb[s]);
    }
    free(field);
    free(z);
    free(h0);
    free(h1);
    free(m0);
    free(m1);
    free(dir);
    glpgp_system_destroy(&sys);
    glpgp_mesh_destroy(&m);
    return st;
}

#else /* no OpenCL */

typedef struct cc_args {
    const char *input;
    double size;
    int kind, device;
    double tscale;
    int solve;
} cc_args;
typedef struct cc_table {
    int n, failed;
    double tscale;
} cc_table;
static void cc_print(const cc_table *t) { (void)t; }
static glpgp_status cc_run(const cc_args *a, cc_table *t)
{
    (void)a;
    (void)t;
    return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "this glpgp was built without OpenCL support");
}

#endif /* GLPGP_HAVE_OPENCL */

int glpgp_cmd_crosscheck(int argc, char **argv)
{
    cc_args a = {NULL, 0.0, GLPGP_ELEM_P1, -1, 1.0, 1};
    static const char *const energies[] = {"p1", "transport", NULL};
    static const int energy_vals[] = {GLPGP_ELEM_P1, GLPGP_ELEM_TRANSPORT};
    int no_solve = 0, verbosity = 1;
    glpgp_opts t;
    glpgp_opts_init(&t, "crosscheck", "glpgp crosscheck INPUT [options]",
                    "Compare the OpenCL backend with the reference backend on one mesh (a .obj/.msh\n"
                    "file or shape:NAME[:N]), stage by stage, and print a table; exit 1 if any\n"
                    "stage exceeds its tolerance.\n");
    glpgp_opt *o = glpgp_opt_double(&t, "--size", &a.size, 0.0, 1, HUGE_VAL, 0, "H", "target quad size");
    o->def = "bounding-box diagonal / 20";
    glpgp_opt_choice(&t, "--energy", &a.kind, energies, energy_vals, "discretisation of the quadratic energy");
    o = glpgp_opt_int(&t, "--device", &a.device, 0, INT_MAX, "N", "OpenCL device index as listed by 'glpgp devices'");
    o->def = "$GLPGP_DEVICE or the first fp64 device";
    glpgp_opt_double(&t, "--tol-scale", &a.tscale, 0.0, 1, HUGE_VAL, 0, "F", "multiply every tolerance by F");
    glpgp_opt_flag(&t, "--no-solve", &no_solve, 1, "skip the whole GL solve stage");
    glpgp_opts_add_verbosity(&t, &verbosity);
    t.epilog = "Tolerances (|a-b| <= atol + rtol |b|): assembly, gradient, spmv, dot rtol 1e-12;\n"
               "CG, Newton step and GL solve rtol 1e-6 on z (1e-4 for an oscillator whose GL\n"
               "levels stopped at the Newton cap: unconverged vortex drift amplifies rounding).\n"
               "The environment variable GLPGP_CL_CORRUPT=1 corrupts the OpenCL QUAD assembly\n"
               "(the check must fail).\n";
    int npos = 0;
    int rc = glpgp_opts_parse(&t, argc, argv, &a.input, 1, &npos);
    if (rc >= 0) return rc;
    glpgp_cli_set_verbosity(verbosity);
    a.solve = !no_solve;
    if (!a.input) return glpgp_cli_usage_error("crosscheck", "missing INPUT (a .obj/.msh file or shape:NAME[:N])");
    cc_table tab;
    memset(&tab, 0, sizeof tab);
    tab.tscale = a.tscale;
    glpgp_status st = cc_run(&a, &tab);
    if (tab.n > 0) cc_print(&tab);
    if (st != GLPGP_OK) return glpgp_cli_fail();
    printf("\ncrosscheck: %s\n", tab.failed ? "FAILED" : "all stages PASS");
    return tab.failed ? 1 : 0;
}

