/* bench.c: glpgp-bench, the benchmark harness (issue 4): host memory
 * bandwidth (STREAM copy/triad, all cores), then for a ladder of generated
 * domains the per-operation and whole-solve times of both backends (scalar C
 * reference and OpenCL) through the backend ops table, effective GB/s of SpMV
 * and CG iterations against the measured triad, the optional CHOLMOD
 * comparison, memory figures, OpenCL program build time cold vs cached; a
 * Markdown report on stdout, JSON (--json), comparison with an older JSON
 * (--compare) and a log-log plot via gnuplot (--plot). bench/README.md
 * documents every figure and the byte-count formulas. */
#define _XOPEN_SOURCE 700 /* nftw */

#include "bench.h"
#include "glpgp/backends.h"
#include "glpgp/backends.h"
#include "glpgp/mesh.h"
#include "glpgp/solve.h"
#include "glpgp/status.h"
#include "glpgp/system.h"
#include "glpgp/internal/newton.h"

#include <errno.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef GLPGP_SOURCE_DIR
#define GLPGP_SOURCE_DIR "."
#endif

#define MAX_SIZES 32
#define CG_BLOCK 10 /* CG iterations per timed block = the driver's residual-check interval */

/* ---- options ----------------------------------------------------------------- */

typedef struct bopts {
    long sizes[MAX_SIZES];
    int nsizes;
    const char *shape;
    int repeat;
    double min_time;       /* keep repeating cheap operations until this much time is spent */
    size_t stream_n;       /* doubles per STREAM array */
    int stream_reps;
    long max_solve_ref;    /* whole GL solve on the reference path up to this many vertices (0: no limit) */
    long max_solve_cl;     /* same for OpenCL (0: no limit) */
    long max_cholmod;      /* CHOLMOD up to this many vertices (0: no limit) */
    int solve_repeat;      /* whole GL solve repeats */
    int smoke;
    int no_opencl, no_reference, no_cholmod, no_petsc;
    int device;
    int keep_cache;        /* do not point POCL_CACHE_DIR at a fresh directory */
    const char *json, *compare, *against, *plot;
    int precond;           /* --precond: -1 not given, else 0 jacobi, 1 amg, 2 both */
    int sizes_given, with_4m, steps;
    int hcases; /* --precond-h: bit 0 10 mean edges, bit 1 default (0: both) */
    int kcycle_min;        /* --amg-kcycle-min (-1: auto) */
    int amg_pre, amg_post; /* --amg-pre / --amg-post (-1: the default) */
    int amg_passes;        /* --amg-coarse-passes (-1: the default) */
    int oscillators;       /* --oscillators: GLPGP_OSC_* of the whole GL solves */
} bopts;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: glpgp-bench [options]\n"
            "  --sizes N,N,...          vertex counts of the ladder (default 16000,64000,256000,1000000)\n"
            "  --shape NAME             disk (default), square, annulus, lshape\n"
            "  --repeat N               timed repeats per figure, median and min reported (default 3)\n"
            "  --min-time S             repeat cheap operations for at least S seconds (default 0.3)\n"
            "  --stream-mb M            MiB per STREAM array (default 256, three arrays)\n"
            "  --stream-reps N          STREAM repetitions, best reported (default 10)\n"
            "  --max-solve-vertices N   whole GL solve on the reference path only up to N vertices\n"
            "                           (default 300000; 0 = no limit)\n"
            "  --max-solve-vertices-opencl N  same for OpenCL (default 0 = no limit)\n"
            "  --full-solve             whole GL solve at every size on both paths (both limits 0)\n"
            "  --solve-repeat N         whole GL solve repeats (default 1)\n"
            "  --oscillators M          whole GL solves: sequential (default: each backend's own figure,\n"
            "                           comparable with earlier JSON), concurrent or auto (glpgp solve's\n"
            "                           default: u and v at the same time, v on a clone of the backend)\n"
            "  --max-cholmod-vertices N CHOLMOD only up to N vertices (default 2000000; 0 = no limit)\n"
            "  --no-opencl, --no-reference, --no-cholmod   leave a column out\n"
            "  --no-petsc               with --precond: leave the PETSc GAMG anchor out (it runs when\n"
            "                           glpgp has its PETSc module; CHOLMOD, the other anchor, when built\n"
            "                           with it, up to --max-cholmod-vertices)\n"
            "  --device N               OpenCL device index (as `glpgp devices`; default: GLPGP_DEVICE, first fp64 GPU, first fp64)\n"
            "  --keep-pocl-cache        keep POCL_CACHE_DIR (default: a fresh temporary directory, so the\n"
            "                           first program build is cold and the later ones are cached)\n"
            "  --smoke                  tiny run (2000,4000 vertices, 1 repeat, 8 MiB STREAM) that still\n"
            "                           writes JSON (glpgp-bench-smoke.json unless --json is given)\n"
            "  --json FILE              write every figure as JSON\n"
            "  --compare OLD.json       print new/old ratio per figure (of this run, or of --against)\n"
            "  --against NEW.json       with --compare: compare two files, run nothing\n"
            "  --plot FILE.png          log-log plot of time vs vertices (needs gnuplot)\n"
            "  --precond jacobi|amg|both  instead of the above: the preconditioner ladder (bench_precond.c):\n"
            "                           per Newton step Jacobi-PCG and flexible CG + multigrid side by side\n"
            "                           (CG iterations, setup / solve seconds, ms per iteration, bytes moved)\n"
            "                           at 64k, 256k, 1M vertices (or --sizes), h = 10 mean edges and the\n"
            "                           default size, on both backends (--no-opencl / --no-reference)\n"
            "  --with-4m                with --precond: add 4M vertices to the ladder (slow)\n"
            "  --precond-h edges|default|both  with --precond: h = 10 mean edges, the default size, or both [both]\n"
            "  --newton-steps N         with --precond: Newton steps per case (default 3)\n"
            "  --amg-kcycle-min N|auto  with --precond: K-cycle on levels of >= N nodes, a plain visit below\n"
            "                           (0: every level; auto: 0, or 2000 on a launch-bound GPU; default auto)\n"
            "  --amg-pre N, --amg-post N  with --precond: l1-Jacobi sweeps before (0..8) / after (1..8)\n"
            "                           the coarse correction (default: glpgp's, 1 and 1)\n"
            "  --amg-coarse-passes N    with --precond: pairing passes per coarse level, 2 (aggregates of\n"
            "                           ~4 nodes, the default) or 3 (~8: fewer levels and launches)\n"
            "  -h, --help               this text\n");
}

static int parse_long(const char *s, long *v)
{
    char *end = NULL;
    errno = 0;
    double d = strtod(s, &end);
    if (errno || end == s) return 0;
    if (*end == 'k' || *end == 'K') {
        d *= 1e3;
        end++;
    } else if (*end == 'm' || *end == 'M') {
        d *= 1e6;
        end++;
    }
    if (*end != '\0' || d < 0 || d > 1e12) return 0;
    *v = (long)(d + 0.5);
    return 1;
}

static glpgp_status parse_args(int argc, char **argv, bopts *o, int *help)
{
    memset(o, 0, sizeof *o);
    o->shape = "disk";
    o->repeat = 3;
    o->min_time = 0.3;
    o->stream_n = (size_t)256 * 1024 * 1024 / sizeof(double);
    o->stream_reps = 10;
    o->max_solve_ref = 300000;
    o->max_solve_cl = 0;
    o->max_cholmod = 2000000;
    o->solve_repeat = 1;
    o->oscillators = GLPGP_OSC_SEQUENTIAL;
    o->device = -1;
    o->precond = -1;
    o->steps = 3;
    o->kcycle_min = -1;
    o->amg_pre = o->amg_post = o->amg_passes = -1;
    const long defsizes[] = {16000, 64000, 256000, 1000000};
    int sizes_given = 0, repeat_given = 0, stream_given = 0, reps_given = 0, mt_given = 0;
    *help = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
#define NEEDV()                                                                          \
    do {                                                                                 \
        if (!v) return GLPGP_FAIL(GLPGP_ERR_ARG, "option %s needs a value", a);          \
        i++;                                                                             \
    } while (0)
        long lv = 0;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            *help = 1;
            return GLPGP_OK;
        } else if (!strcmp(a, "--sizes")) {
            NEEDV();
            char buf[1024];
            snprintf(buf, sizeof buf, "%s", v);
            o->nsizes = 0;
            for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
                if (o->nsizes == MAX_SIZES) return GLPGP_FAIL(GLPGP_ERR_ARG, "--sizes: at most %d sizes", MAX_SIZES);
                if (!parse_long(t, &lv) || lv < 16)
                    return GLPGP_FAIL(GLPGP_ERR_ARG, "--sizes: '%s' is not a vertex count >= 16", t);
                o->sizes[o->nsizes++] = lv;
            }
            if (o->nsizes == 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "--sizes: empty list");
            sizes_given = 1;
        } else if (!strcmp(a, "--shape")) {
            NEEDV();
            const char *const *sh = glpgp_mesh_shapes();
            int ok = 0;
            for (int k = 0; sh[k]; k++) ok |= !strcmp(sh[k], v);
            if (!ok) return GLPGP_FAIL(GLPGP_ERR_ARG, "--shape: unknown shape '%s' (disk, square, annulus, lshape)", v);
            o->shape = v;
        } else if (!strcmp(a, "--repeat")) {
            NEEDV();
            if (!parse_long(v, &lv) || lv < 1 || lv > 1000) return GLPGP_FAIL(GLPGP_ERR_ARG, "--repeat: expected 1..1000");
            o->repeat = (int)lv;
            repeat_given = 1;
        } else if (!strcmp(a, "--min-time")) {
            NEEDV();
            char *end = NULL;
            o->min_time = strtod(v, &end);
            if (*end || !(o->min_time >= 0.0) || o->min_time > 60.0)
                return GLPGP_FAIL(GLPGP_ERR_ARG, "--min-time: expected seconds in [0, 60]");
            mt_given = 1;
        } else if (!strcmp(a, "--stream-mb")) {
            NEEDV();
            if (!parse_long(v, &lv) || lv < 1 || lv > 65536) return GLPGP_FAIL(GLPGP_ERR_ARG, "--stream-mb: expected 1..65536");
            o->stream_n = (size_t)lv * 1024 * 1024 / sizeof(double);
            stream_given = 1;
        } else if (!strcmp(a, "--stream-reps")) {
            NEEDV();
            if (!parse_long(v, &lv) || lv < 1 || lv > 1000) return GLPGP_FAIL(GLPGP_ERR_ARG, "--stream-reps: expected 1..1000");
            o->stream_reps = (int)lv;
            reps_given = 1;
        } else if (!strcmp(a, "--max-solve-vertices")) {
            NEEDV();
            if (!parse_long(v, &lv)) return GLPGP_FAIL(GLPGP_ERR_ARG, "--max-solve-vertices: expected a count");
            o->max_solve_ref = lv;
        } else if (!strcmp(a, "--max-solve-vertices-opencl")) {
            NEEDV();
            if (!parse_long(v, &lv)) return GLPGP_FAIL(GLPGP_ERR_ARG, "--max-solve-vertices-opencl: expected a count");
            o->max_solve_cl = lv;
        } else if (!strcmp(a, "--full-solve")) {
            o->max_solve_ref = 0;
            o->max_solve_cl = 0;
        } else if (!strcmp(a, "--solve-repeat")) {
            NEEDV();
            if (!parse_long(v, &lv) || lv < 1 || lv > 100) return GLPGP_FAIL(GLPGP_ERR_ARG, "--solve-repeat: expected 1..100");
            o->solve_repeat = (int)lv;
        } else if (!strcmp(a, "--max-cholmod-vertices")) {
            NEEDV();
            if (!parse_long(v, &lv)) return GLPGP_FAIL(GLPGP_ERR_ARG, "--max-cholmod-vertices: expected a count");
            o->max_cholmod = lv;
        } else if (!strcmp(a, "--no-opencl")) {
            o->no_opencl = 1;
        } else if (!strcmp(a, "--no-reference")) {
            o->no_reference = 1;
        } else if (!strcmp(a, "--no-cholmod")) {
            o->no_cholmod = 1;
        } else if (!strcmp(a, "--no-petsc")) {
            o->no_petsc = 1;
        } else if (!strcmp(a, "--device")) {
            NEEDV();
            if (!parse_long(v, &lv) || lv > 1000) return GLPGP_FAIL(GLPGP_ERR_ARG, "--device: expected an index");
            o->device = (int)lv;
        } else if (!strcmp(a, "--keep-pocl-cache")) {
            o->keep_cache = 1;
        } else if (!strcmp(a, "--precond")) {
            NEEDV();
            if (!strcmp(v, "jacobi")) o->precond = 0;
            else if (!strcmp(v, "amg")) o->precond = 1;
            else if (!strcmp(v, "both")) o->precond = 2;
            else return GLPGP_FAIL(GLPGP_ERR_ARG, "--precond: '%s' is not jacobi, amg or both", v);
        } else if (!strcmp(a, "--with-4m")) {
            o->with_4m = 1;
        } else if (!strcmp(a, "--precond-h")) {
            NEEDV();
            if (!strcmp(v, "edges")) o->hcases = 1;
            else if (!strcmp(v, "default")) o->hcases = 2;
            else if (!strcmp(v, "both")) o->hcases = 3;
            else return GLPGP_FAIL(GLPGP_ERR_ARG, "--precond-h: '%s' is not edges, default or both", v);
        } else if (!strcmp(a, "--newton-steps")) {
            NEEDV();
            if (!parse_long(v, &lv) || lv < 1 || lv > 20) return GLPGP_FAIL(GLPGP_ERR_ARG, "--newton-steps: expected 1..20");
            o->steps = (int)lv;
        } else if (!strcmp(a, "--oscillators")) {
            NEEDV();
            if (!strcmp(v, "sequential")) o->oscillators = GLPGP_OSC_SEQUENTIAL;
            else if (!strcmp(v, "concurrent")) o->oscillators = GLPGP_OSC_CONCURRENT;
            else if (!strcmp(v, "auto")) o->oscillators = GLPGP_OSC_AUTO;
            else return GLPGP_FAIL(GLPGP_ERR_ARG, "--oscillators: '%s' is not sequential, concurrent or auto", v);
        } else if (!strcmp(a, "--amg-kcycle-min")) {
            NEEDV();
            if (!strcmp(v, "auto")) o->kcycle_min = -1;
            else if (!parse_long(v, &lv) || lv < 0 || lv > 100000000)
                return GLPGP_FAIL(GLPGP_ERR_ARG, "--amg-kcycle-min: expected a node count or auto");
            else o->kcycle_min = (int)lv;
        } else if (!strcmp(a, "--amg-pre") || !strcmp(a, "--amg-post")) {
            NEEDV();
            const int pre = !strcmp(a, "--amg-pre");
            if (!parse_long(v, &lv) || lv < (pre ? 0 : 1) || lv > 8)
                return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: expected %d..8 sweeps", a, pre ? 0 : 1);
            if (pre) o->amg_pre = (int)lv;
            else o->amg_post = (int)lv;
        } else if (!strcmp(a, "--amg-coarse-passes")) {
            NEEDV();
            if (!parse_long(v, &lv) || lv < 2 || lv > 3)
                return GLPGP_FAIL(GLPGP_ERR_ARG, "--amg-coarse-passes: expected 2 or 3");
            o->amg_passes = (int)lv;
        } else if (!strcmp(a, "--smoke")) {
            o->smoke = 1;
        } else if (!strcmp(a, "--json")) {
            NEEDV();
            o->json = v;
        } else if (!strcmp(a, "--compare")) {
            NEEDV();
            o->compare = v;
        } else if (!strcmp(a, "--against")) {
            NEEDV();
            o->against = v;
        } else if (!strcmp(a, "--plot")) {
            NEEDV();
            o->plot = v;
        } else {
            return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown option '%s' (see --help)", a);
        }
#undef NEEDV
    }
    if (o->against && !o->compare) return GLPGP_FAIL(GLPGP_ERR_ARG, "--against needs --compare OLD.json");
    o->sizes_given = sizes_given;
    if (o->smoke) {
        if (!sizes_given) {
            o->sizes[0] = 2000;
            o->sizes[1] = 4000;
            o->nsizes = 2;
        }
        if (!repeat_given) o->repeat = 1;
        if (!mt_given) o->min_time = 0.0;
        if (!stream_given) o->stream_n = (size_t)8 * 1024 * 1024 / sizeof(double);
        if (!reps_given) o->stream_reps = 3;
        if (!o->json) o->json = "glpgp-bench-smoke.json";
    } else if (!sizes_given) {
        for (int k = 0; k < 4; k++) o->sizes[k] = defsizes[k];
        o->nsizes = 4;
    }
    return GLPGP_OK;
}

/* ---- small helpers -------------------------------------------------------------- */

typedef struct tstat {
    double med, min;
    int n;
} tstat;

static int cmp_d(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

static void tstat_of(double *t, int n, tstat *s)
{
    s->n = n;
    if (n <= 0) {
        s->med = s->min = NAN;
        return;
    }
    qsort(t, (size_t)n, sizeof *t, cmp_d);
    s->min = t[0];
    s->med = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

static long peak_rss_kb(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return -1;
    return ru.ru_maxrss;
}

static long cur_rss_bytes(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    long pages = -1, rss = -1;
    if (!f) return -1;
    if (fscanf(f, "%ld %ld", &pages, &rss) != 2) rss = -1;
    fclose(f);
    return rss < 0 ? -1 : rss * sysconf(_SC_PAGESIZE);
}

/* "1.23 ms" / "4.56 s" into buf. */
static const char *ftime(char *buf, size_t len, double s)
{
    if (!isfinite(s)) snprintf(buf, len, "-");
    else if (s < 1e-3) snprintf(buf, len, "%.3g us", s * 1e6);
    else if (s < 1.0) snprintf(buf, len, "%.3g ms", s * 1e3);
    else snprintf(buf, len, "%.3g s", s);
    return buf;
}

static int on_path(const char *prog)
{
    const char *path = getenv("PATH");
    if (!path) return 0;
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *d = strtok(buf, ":"); d; d = strtok(NULL, ":")) {
        char full[4352];
        snprintf(full, sizeof full, "%s/%s", *d ? d : ".", prog);
        if (access(full, X_OK) == 0) return 1;
    }
    return 0;
}

static int rm_entry(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    remove(p);
    return 0;
}

/* ---- per-size, per-backend results ---------------------------------------------- */

typedef struct bres {
    int ran;
    char note[256];
    double create_s, setup_s;
    tstat quad, newton, spmv, cg_iter, lin, nstep;
    int lin_iters;
    int nstep_cg;      /* CG iterations of the timed Newton step */
    double nstep_alpha; /* its accepted step length */
    double lin_relres;
    int gl_ran;
    char gl_note[160];
    tstat gl;
    int gl_newton;
    long gl_cg;
    double gl_setup_s, gl_field_s;
    double spmv_gbs, spmv_gbs_best, cg_gbs, cg_gbs_best;
    double backend_bytes; /* model of the backend's allocations, see bench/README.md */
    long rss_delta;       /* resident set growth over create + setup + vectors + assembly */
} bres;

typedef struct sres {
    long requested;
    int nv, nt;
    long nnzb;
    double mean_edge, h, eps;
    double bytes_spmv, bytes_cg;
    double mesh_s, system_s;
    bres ref, cl;
    bench_cholmod chol;
    long peak_rss_kb;
} sres;

typedef struct clbuild {
    int tried, ok;
    char note[512];
    char device[512];
    double create_cold_s, first_ops_cold_s, create_warm_s, first_ops_warm_s;
    char cache_dir[256];
    /* the OpenCL device's own bandwidth through the backend's ops (best of
     * stream_reps on two vectors of stream_n doubles): copy moves 16 bytes per
     * double, axpby (y <- a x + c y) 24 like STREAM's triad; NAN if not run */
    double dev_copy_gbs, dev_axpby_gbs;
    size_t dev_bytes;
    int dev_reps;
} clbuild;

/* Bytes one SpMV / one CG iteration must move (see bench/README.md). */
static double bytes_spmv(long nv, long nnzb) { return 36.0 * nnzb + 4.0 * (nv + 1) + 32.0 * nv; }
static double bytes_cg(long nv, long nnzb) { return bytes_spmv(nv, nnzb) + 144.0 * nv + 48.0 * nv; }

/* Allocation model of a backend after setup with nvec vectors of 2 nv doubles. */
static double backend_bytes(int opencl, const glpgp_system *s, int nvec)
{
    const double nv = s->nv, nt = s->nt, nb = (double)s->nnzb;
    double b = 64.0 * nb + 32.0 * nv + 16.0 * nv + nv + nvec * 16.0 * nv; /* QUAD, NEWTON, DINV, W, dir, vectors */
    if (opencl) /* the mesh, pattern and maps live on the device too */
        b += 16.0 * nv + 12.0 * nt + 4.0 * (nv + 1) + 4.0 * nb + 4.0 * nv + 4.0 * (nb + 1) + 36.0 * nt +
             4.0 * (nv + 1) + 12.0 * nt + 8.0 * GLPGP_NSLOTS;
    return b;
}

/* ---- timing through the ops table ----------------------------------------------- */

typedef struct bctx {
    glpgp_backend *b;
    glpgp_vec *x, *g, *y, *rhs, *d, *r, *z, *p, *q, *x0;
    double h, inv4e2;
    int hess;
    int lin_iters;
    double lin_rel;
    glpgp_options so;
    glpgp_newton_step_info nsi;
} bctx;

typedef glpgp_status (*opfn)(bctx *c);

static glpgp_status sync_b(glpgp_backend *b)
{
    double s[1];
    return b->ops->get_scalars(b, s, 1); /* blocking: waits for the in-order queue */
}

/* Warm-up once, then time prep-less calls of fn (each followed by a sync)
 * until at least `reps` runs and `min_time` seconds; per = work units per
 * call (the stat is per unit). */
static glpgp_status time_op(bctx *c, opfn prep, opfn fn, int reps, double min_time, int per, tstat *out)
{
    enum { CAP = 2000 };
    static double t[CAP];
    if (prep) GLPGP_CHECK(prep(c));
    GLPGP_CHECK(fn(c));
    GLPGP_CHECK(sync_b(c->b));
    int n = 0;
    double total = 0.0;
    while (n < CAP && (n < reps || total < min_time)) {
        if (prep) {
            GLPGP_CHECK(prep(c));
            GLPGP_CHECK(sync_b(c->b));
        }
        double t0 = bench_now();
        GLPGP_CHECK(fn(c));
        GLPGP_CHECK(sync_b(c->b));
        double dt = bench_now() - t0;
        total += dt;
        t[n++] = dt / per;
    }
    tstat_of(t, n, out);
    return GLPGP_OK;
}

static glpgp_status op_quad(bctx *c) { return c->b->ops->assemble_quadratic(c->b, GLPGP_ELEM_P1, c->h); }
static glpgp_status op_newton(bctx *c) { return c->b->ops->assemble_newton(c->b, c->x, c->inv4e2, c->hess); }
static glpgp_status op_spmv(bctx *c) { return c->b->ops->spmv(c->b, GLPGP_MAT_NEWTON, c->x, c->y); }

/* CG restart: x = 0, r = rhs, z = DINV r, p = z (fresh start, so a block never
 * runs into converged, denormal-valued vectors). */
static glpgp_status op_cg_prep(bctx *c)
{
    const glpgp_backend_ops *o = c->b->ops;
    GLPGP_CHECK(o->axpby(c->b, 0.0, c->d, 0.0, c->d));
    GLPGP_CHECK(o->copy(c->b, c->r, c->rhs));
    GLPGP_CHECK(o->cg_precond(c->b, c->r, c->z, GLPGP_S_RZ0));
    GLPGP_CHECK(o->copy(c->b, c->p, c->z));
    return GLPGP_OK;
}

/* CG_BLOCK iterations exactly as glpgp_cg runs them (its residual read-back
 * every 10 iterations is the sync time_op adds). */
static glpgp_status op_cg_block(bctx *c)
{
    const glpgp_backend_ops *o = c->b->ops;
    int rz = GLPGP_S_RZ0, rzn = GLPGP_S_RZ1;
    for (int k = 0; k < CG_BLOCK; k++) {
        GLPGP_CHECK(o->cg_spmv_dot(c->b, c->p, c->q));
        GLPGP_CHECK(o->cg_update(c->b, c->d, c->r, c->p, c->q, c->z, rz, rzn));
        GLPGP_CHECK(o->cg_direction(c->b, c->p, c->z, rzn, rz));
        int t = rz;
        rz = rzn;
        rzn = t;
    }
    return GLPGP_OK;
}

static glpgp_status op_linsolve(bctx *c)
{
    glpgp_cg_info ci;
    glpgp_status st = glpgp_cg(c->b, c->rhs, c->d, c->so.cg_rtol, c->so.cg_max, c->so.cg_check, &ci);
    c->lin_iters = ci.iterations;
    c->lin_rel = ci.relres;
    return st;
}

/* One whole Newton step of the GL driver from x0, as glpgp_solve runs it at
 * the first eps level: gradient, then glpgp_newton_step (assembly, inexact
 * PCG, line search, update) with the default options (mixed Hessian). */
static glpgp_status op_newton_step(bctx *c)
{
    const glpgp_backend_ops *o = c->b->ops;
    double s[GLPGP_NSLOTS];
    GLPGP_CHECK(o->copy(c->b, c->x, c->x0));
    GLPGP_CHECK(o->gradient(c->b, c->x, c->inv4e2, c->g));
    GLPGP_CHECK(o->dot(c->b, c->g, c->g, GLPGP_S_DOT));
    GLPGP_CHECK(o->get_scalars(c->b, s, GLPGP_NSLOTS));
    glpgp_newton_state ns;
    memset(&ns, 0, sizeof ns);
    ns.x = c->x;
    ns.g = c->g;
    ns.d = c->d;
    ns.xt = c->y;
    ns.work = c->r;
    ns.grad0 = sqrt(s[GLPGP_S_DOT]);
    GLPGP_CHECK(glpgp_newton_step(c->b, &c->so, &ns, c->inv4e2, s[GLPGP_S_E] + s[GLPGP_S_P], ns.grad0, &c->nsi));
    return o->copy(c->b, c->x, c->x0); /* leave x as it was */
}

static glpgp_status create_backend(int opencl, const bopts *o, glpgp_backend **b)
{
    if (!opencl) return glpgp_backend_create_reference(b);
    glpgp_cl_options co = {o->device, 0, NULL};
    return glpgp_backend_create_opencl(&co, b);
}

/* Host data shared by both backends for one size. */
typedef struct sdata {
    glpgp_mesh *mesh;
    glpgp_system *sys;
    double *w;           /* 2 nv unit field (1, 0) */
    unsigned char *dir;  /* Dirichlet flags of w */
    double *x0;          /* 2 nv perturbed plane wave */
    double *rhs;         /* 2 nv: -gradient at x0 (from the reference path) */
    double *xcg;         /* 2 nv: reference CG solution */
    double *newton;      /* 4 nnzb: NEWTON values (for CHOLMOD) */
} sdata;

/* Time every op on one backend. want_matrix: read NEWTON, rhs and the CG
 * solution back for CHOLMOD. */
static glpgp_status bench_backend(int opencl, const bopts *o, sdata *sd, sres *sr, bres *br, int want_matrix)
{
    glpgp_status st = GLPGP_OK;
    bctx c;
    memset(&c, 0, sizeof c);
    const size_t n2 = (size_t)2 * sd->sys->nv;
    long rss0 = cur_rss_bytes();
    double t0 = bench_now();
    GLPGP_CHECK(create_backend(opencl, o, &c.b));
    br->create_s = bench_now() - t0;
    glpgp_backend *b = c.b;
    const glpgp_backend_ops *op = b->ops;
    t0 = bench_now();
    GLPGP_CHECK_GOTO(st, op->setup(b, sd->sys), done);
    br->setup_s = bench_now() - t0;
    glpgp_vec **vecs[] = {&c.x, &c.g, &c.y, &c.rhs, &c.d, &c.r, &c.z, &c.p, &c.q, &c.x0};
    const int nvec = (int)(sizeof vecs / sizeof vecs[0]);
    for (int k = 0; k < nvec; k++) GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, vecs[k]), done);
    c.h = sr->h;
    c.inv4e2 = 1.0 / (4.0 * sr->eps * sr->eps);
    c.hess = GLPGP_HESS_PROJECTED;
    glpgp_options_default(&c.so);
    GLPGP_CHECK_GOTO(st, op->set_field(b, sd->w, sd->dir), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, c.x, sd->x0), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, c.x0, sd->x0), done);

    GLPGP_CHECK_GOTO(st, time_op(&c, NULL, op_quad, o->repeat, o->min_time, 1, &br->quad), done);
    GLPGP_CHECK_GOTO(st, time_op(&c, NULL, op_newton, o->repeat, o->min_time, 1, &br->newton), done);
    br->rss_delta = rss0 >= 0 ? cur_rss_bytes() - rss0 : -1;
    /* rhs = -grad(x0): the right-hand side of a Newton step at x0 */
    GLPGP_CHECK_GOTO(st, op->gradient(b, c.x, c.inv4e2, c.g), done);
    GLPGP_CHECK_GOTO(st, op->axpby(b, -1.0, c.g, 0.0, c.rhs), done);
    GLPGP_CHECK_GOTO(st, time_op(&c, NULL, op_spmv, o->repeat, o->min_time, 1, &br->spmv), done);
    GLPGP_CHECK_GOTO(st, time_op(&c, op_cg_prep, op_cg_block, o->repeat, o->min_time, CG_BLOCK, &br->cg_iter), done);
    GLPGP_CHECK_GOTO(st, time_op(&c, NULL, op_linsolve, o->repeat, 0.0, 1, &br->lin), done);
    br->lin_iters = c.lin_iters;
    br->lin_relres = c.lin_rel;
    GLPGP_CHECK_GOTO(st, time_op(&c, NULL, op_newton_step, o->repeat, 0.0, 1, &br->nstep), done);
    br->nstep_cg = c.nsi.cg;
    br->nstep_alpha = c.nsi.alpha;
    br->spmv_gbs = sr->bytes_spmv / br->spmv.med * 1e-9;
    br->spmv_gbs_best = sr->bytes_spmv / br->spmv.min * 1e-9;
    br->cg_gbs = sr->bytes_cg / br->cg_iter.med * 1e-9;
    br->cg_gbs_best = sr->bytes_cg / br->cg_iter.min * 1e-9;
    br->backend_bytes = backend_bytes(opencl, sd->sys, nvec + 4 /* glpgp_cg's work vectors */);
    br->ran = 1;
    if (want_matrix) {
        GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &sd->rhs), done);
        GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &sd->xcg), done);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * sd->sys->nnzb, sizeof(double), &sd->newton), done);
        GLPGP_CHECK_GOTO(st, op->vec_read(b, c.rhs, sd->rhs), done);
        GLPGP_CHECK_GOTO(st, op->vec_read(b, c.d, sd->xcg), done);
        GLPGP_CHECK_GOTO(st, glpgp_probe_matrix(b, GLPGP_MAT_NEWTON, sd->newton), done);
    }
done:
    for (int k = 0; k < (int)(sizeof vecs / sizeof vecs[0]); k++) op->vec_destroy(b, vecs[k]);
    glpgp_backend_destroy(&c.b);
    return st;
}

/* Whole GL solve (glpgp_solve with defaults, h = 10 mean edges, verbose 0),
 * solve_repeat times on fresh backends. */
static glpgp_status bench_gl(int opencl, const bopts *o, const sdata *sd, const sres *sr, bres *br)
{
    enum { MAXR = 100 };
    double t[MAXR];
    int n = 0;
    for (int r = 0; r < o->solve_repeat && r < MAXR; r++) {
        glpgp_backend *b = NULL;
        glpgp_result *res = NULL;
        GLPGP_CHECK(create_backend(opencl, o, &b));
        glpgp_options so;
        glpgp_options_default(&so);
        so.size = sr->h;
        so.oscillators = o->oscillators;
        double t0 = bench_now();
        glpgp_status st = glpgp_solve(sd->mesh, b, &so, &res);
        double dt = bench_now() - t0;
        glpgp_backend_destroy(&b);
        if (st != GLPGP_OK) {
            glpgp_result_destroy(&res);
            glpgp_error_push_trace(__FILE__, __LINE__);
            return st;
        }
        t[n++] = dt;
        br->gl_newton = res->osc[0].newton_iterations + res->osc[1].newton_iterations;
        br->gl_cg = res->field_cg_iterations + res->osc[0].cg_iterations + res->osc[1].cg_iterations;
        br->gl_setup_s = res->seconds_setup;
        br->gl_field_s = res->seconds_field;
        glpgp_result_destroy(&res);
    }
    tstat_of(t, n, &br->gl);
    br->gl_ran = 1;
    return GLPGP_OK;
}

/* Cold vs cached OpenCL program build on a small disk: create (clBuildProgram)
 * and first launch of every kernel the CG path uses (PoCL compiles a kernel
 * again at its first launch per local size). */
static glpgp_status cl_first_ops(const bopts *o, glpgp_mesh *m, glpgp_system *sys, double *create_s, double *first_s,
                                 char *devname, size_t dlen)
{
    glpgp_status st = GLPGP_OK;
    glpgp_backend *b = NULL;
    glpgp_vec *x = NULL, *y = NULL, *z = NULL;
    double *w = NULL;
    unsigned char *dir = NULL;
    double t0 = bench_now();
    GLPGP_CHECK(create_backend(1, o, &b));
    *create_s = bench_now() - t0;
    if (devname) glpgp_cl_backend_info(b, devname, dlen);
    const glpgp_backend_ops *op = b->ops;
    const size_t n2 = (size_t)2 * m->nv;
    GLPGP_CHECK_GOTO(st, glpgp_calloc(n2, sizeof(double), &w), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)m->nv, 1, &dir), done);
    for (int i = 0; i < m->nv; i++) w[2 * i] = 1.0;
    glpgp_dirichlet_set(m, w, dir);
    t0 = bench_now();
    GLPGP_CHECK_GOTO(st, op->setup(b, sys), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &x), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &y), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &z), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, w), done);
    GLPGP_CHECK_GOTO(st, op->set_field(b, w, dir), done);
    GLPGP_CHECK_GOTO(st, op->assemble_quadratic(b, GLPGP_ELEM_P1, 10.0 * m->mean_edge), done);
    GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, 1.0, GLPGP_HESS_PROJECTED), done);
    GLPGP_CHECK_GOTO(st, op->gradient(b, x, 1.0, y), done);
    GLPGP_CHECK_GOTO(st, op->spmv(b, GLPGP_MAT_NEWTON, x, y), done);
    GLPGP_CHECK_GOTO(st, op->cg_precond(b, y, z, GLPGP_S_RZ0), done);
    GLPGP_CHECK_GOTO(st, op->cg_spmv_dot(b, z, y), done);
    GLPGP_CHECK_GOTO(st, op->cg_update(b, x, y, z, y, z, GLPGP_S_RZ0, GLPGP_S_RZ1), done);
    GLPGP_CHECK_GOTO(st, op->cg_direction(b, z, y, GLPGP_S_RZ1, GLPGP_S_RZ0), done);
    GLPGP_CHECK_GOTO(st, sync_b(b), done);
    *first_s = bench_now() - t0;
done:
    if (b) {
        op->vec_destroy(b, &x);
        op->vec_destroy(b, &y);
        op->vec_destroy(b, &z);
    }
    glpgp_backend_destroy(&b);
    free(w);
    free(dir);
    return st;
}

/* The device's bandwidth through the ops table: y <- x (clEnqueueCopyBuffer)
 * and y <- a x + c y (the backend's axpby kernel) on two vectors of
 * o->stream_n doubles, best of o->stream_reps. On PoCL this is the host's
 * memory again (compare STREAM); on a GPU it is the card's, the figure the
 * CG iteration's GB/s is measured against. A tiny system is set up first
 * because the scalar slots live in the backend's setup. */
static glpgp_status cl_device_bw(const bopts *o, glpgp_system *sys, clbuild *cb)
{
    glpgp_status st = GLPGP_OK;
    glpgp_backend *b = NULL;
    glpgp_vec *x = NULL, *y = NULL;
    double *w = NULL;
    const size_t n = o->stream_n;
    GLPGP_CHECK(create_backend(1, o, &b));
    const glpgp_backend_ops *op = b->ops;
    GLPGP_CHECK_GOTO(st, op->setup(b, sys), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(n, sizeof(double), &w), done);
    for (size_t i = 0; i < n; i++) w[i] = 1.0 + 1e-9 * (double)(i % 1000);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n, &x), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n, &y), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, w), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, y, w), done);
    double best_copy = INFINITY, best_axpby = INFINITY;
    for (int r = 0; r <= o->stream_reps; r++) { /* r = 0 warms up */
        GLPGP_CHECK_GOTO(st, sync_b(b), done);
        double t0 = bench_now();
        GLPGP_CHECK_GOTO(st, op->copy(b, y, x), done); /* y <- x */
        GLPGP_CHECK_GOTO(st, sync_b(b), done);
        double t1 = bench_now();
        GLPGP_CHECK_GOTO(st, op->axpby(b, 0.5, x, 0.5, y), done); /* y <- x/2 + y/2 (y stays bounded) */
        GLPGP_CHECK_GOTO(st, sync_b(b), done);
        double t2 = bench_now();
        if (r > 0) {
            if (t1 - t0 < best_copy) best_copy = t1 - t0;
            if (t2 - t1 < best_axpby) best_axpby = t2 - t1;
        }
    }
    cb->dev_copy_gbs = 16.0 * (double)n / best_copy * 1e-9;
    cb->dev_axpby_gbs = 24.0 * (double)n / best_axpby * 1e-9;
    cb->dev_bytes = n * sizeof(double);
    cb->dev_reps = o->stream_reps;
done:
    if (b) {
        op->vec_destroy(b, &x);
        op->vec_destroy(b, &y);
    }
    glpgp_backend_destroy(&b);
    free(w);
    return st;
}

static void cl_build_probe(const bopts *o, clbuild *cb)
{
    glpgp_mesh *m = NULL;
    glpgp_system *sys = NULL;
    cb->tried = 1;
    glpgp_error_clear();
    glpgp_status st = glpgp_mesh_generate("disk", 2000, &m);
    if (st == GLPGP_OK) st = glpgp_system_create(m, &sys);
    if (st == GLPGP_OK)
        st = cl_first_ops(o, m, sys, &cb->create_cold_s, &cb->first_ops_cold_s, cb->device, sizeof cb->device);
    if (st == GLPGP_OK) st = cl_first_ops(o, m, sys, &cb->create_warm_s, &cb->first_ops_warm_s, NULL, 0);
    cb->dev_copy_gbs = cb->dev_axpby_gbs = NAN;
    if (st == GLPGP_OK && cl_device_bw(o, sys, cb) != GLPGP_OK) { /* a figure missing, not a failure */
        fprintf(stderr, "glpgp-bench: OpenCL device bandwidth skipped: %s\n", glpgp_error_message());
        cb->dev_copy_gbs = cb->dev_axpby_gbs = NAN;
        glpgp_error_clear();
    }
    if (st == GLPGP_OK) {
        cb->ok = 1;
    } else {
        snprintf(cb->note, sizeof cb->note, "%s", glpgp_error_message());
        for (char *p = cb->note; *p; p++)
            if (*p == '\n') *p = ' ';
    }
    glpgp_error_clear();
    glpgp_system_destroy(&sys);
    glpgp_mesh_destroy(&m);
}

/* ---- one size ---------------------------------------------------------------------- */

static void one_line(char *dst, size_t len, const char *src)
{
    snprintf(dst, len, "%s", src);
    for (char *p = dst; *p; p++)
        if (*p == '\n') *p = ' ';
}

static glpgp_status bench_size(const bopts *o, long nreq, int use_cl, sres *sr)
{
    glpgp_status st = GLPGP_OK;
    sdata sd;
    memset(&sd, 0, sizeof sd);
    sr->requested = nreq;
    double t0 = bench_now();
    GLPGP_CHECK(glpgp_mesh_generate(o->shape, nreq, &sd.mesh));
    sr->mesh_s = bench_now() - t0;
    t0 = bench_now();
    GLPGP_CHECK_GOTO(st, glpgp_system_create(sd.mesh, &sd.sys), done);
    sr->system_s = bench_now() - t0;
    const glpgp_mesh *m = sd.mesh;
    sr->nv = m->nv;
    sr->nt = m->nt;
    sr->nnzb = sd.sys->nnzb;
    sr->mean_edge = m->mean_edge;
    sr->h = 10.0 * m->mean_edge;
    sr->eps = 0.5 * sr->h;
    sr->bytes_spmv = bytes_spmv(m->nv, sd.sys->nnzb);
    sr->bytes_cg = bytes_cg(m->nv, sd.sys->nnzb);
    const size_t n2 = (size_t)2 * m->nv;
    GLPGP_CHECK_GOTO(st, glpgp_calloc(n2, sizeof(double), &sd.w), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)m->nv, 1, &sd.dir), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &sd.x0), done);
    /* field W = (1, 0); z = exp(i theta), theta = 2 pi x / h + a smooth
     * large-scale perturbation (so the gradient is not ~0) */
    const double L = fmax(m->bbox[2] - m->bbox[0], m->bbox[3] - m->bbox[1]);
    for (int i = 0; i < m->nv; i++) {
        const double x = m->xy[2 * i], y = m->xy[2 * i + 1];
        sd.w[2 * i] = 1.0;
        const double th = 2.0 * GLPGP_PI * x / sr->h + 0.5 * sin(2.0 * GLPGP_PI * x / L) * cos(2.0 * GLPGP_PI * y / L);
        sd.x0[2 * i] = cos(th);
        sd.x0[2 * i + 1] = sin(th);
    }
    glpgp_dirichlet_set(m, sd.w, sd.dir);

    const int want_chol = !o->no_cholmod && bench_have_cholmod() && (o->max_cholmod == 0 || m->nv <= o->max_cholmod);
    if (!o->no_reference) {
        fprintf(stderr, "glpgp-bench: %d vertices: reference ops\n", m->nv);
        GLPGP_CHECK_GOTO(st, bench_backend(0, o, &sd, sr, &sr->ref, want_chol), done);
    } else {
        snprintf(sr->ref.note, sizeof sr->ref.note, "skipped (--no-reference)");
    }
    if (use_cl) {
        fprintf(stderr, "glpgp-bench: %d vertices: OpenCL ops\n", m->nv);
        glpgp_error_clear();
        glpgp_status s2 = bench_backend(1, o, &sd, sr, &sr->cl, 0);
        if (s2 != GLPGP_OK) {
            /* report and go on: the reference column is still worth having */
            sr->cl.ran = 0;
            one_line(sr->cl.note, sizeof sr->cl.note, glpgp_error_message());
            fprintf(stderr, "glpgp-bench: OpenCL failed at %d vertices: %s\n", m->nv, glpgp_error_message());
            glpgp_error_clear();
        }
    } else {
        snprintf(sr->cl.note, sizeof sr->cl.note, "skipped (OpenCL unavailable)");
    }

    /* CHOLMOD on the reference NEWTON matrix */
    if (want_chol && sd.newton) {
        fprintf(stderr, "glpgp-bench: %d vertices: CHOLMOD\n", m->nv);
        GLPGP_CHECK_GOTO(st, bench_cholmod_run(sd.sys, sd.newton, sd.rhs, sd.xcg, &sr->chol), done);
    } else if (!bench_have_cholmod()) {
        bench_cholmod_run(sd.sys, NULL, NULL, NULL, &sr->chol);
    } else {
        sr->chol.available = 1;
        snprintf(sr->chol.note, sizeof sr->chol.note, "skipped (%s)",
                 o->no_cholmod ? "--no-cholmod" : o->no_reference ? "needs the reference path" : "above --max-cholmod-vertices");
    }
    glpgp_free(&sd.newton);

    /* whole GL solves */
    for (int k = 0; k < 2; k++) {
        bres *br = k == 0 ? &sr->ref : &sr->cl;
        long lim = k == 0 ? o->max_solve_ref : o->max_solve_cl;
        if (!br->ran) {
            snprintf(br->gl_note, sizeof br->gl_note, "skipped (path did not run)");
            continue;
        }
        if (lim > 0 && m->nv > lim) {
            snprintf(br->gl_note, sizeof br->gl_note, "skipped (%d vertices > %s %ld)", m->nv,
                     k == 0 ? "--max-solve-vertices" : "--max-solve-vertices-opencl", lim);
            continue;
        }
        fprintf(stderr, "glpgp-bench: %d vertices: whole GL solve, %s\n", m->nv, k == 0 ? "reference" : "OpenCL");
        glpgp_error_clear();
        glpgp_status s2 = bench_gl(k == 1, o, &sd, sr, br);
        if (s2 != GLPGP_OK) {
            one_line(br->gl_note, sizeof br->gl_note, glpgp_error_message());
            fprintf(stderr, "glpgp-bench: GL solve failed (%s): %s\n", k == 0 ? "reference" : "OpenCL",
                    glpgp_error_message());
            glpgp_error_clear();
        }
    }
    sr->peak_rss_kb = peak_rss_kb();
done:
    free(sd.w);
    free(sd.dir);
    free(sd.x0);
    free(sd.rhs);
    free(sd.xcg);
    free(sd.newton);
    glpgp_system_destroy(&sd.sys);
    glpgp_mesh_destroy(&sd.mesh);
    return st;
}

/* ---- machine ------------------------------------------------------------------------- */

typedef struct machine {
    char cpu[256];
    int cores;
    double mem_bytes;
    char commit[64];
    int have_commit, dirty;
} machine;

static void machine_info(machine *mc)
{
    memset(mc, 0, sizeof *mc);
    snprintf(mc->cpu, sizeof mc->cpu, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (strncmp(line, "model name", 10) == 0) {
                char *c = strchr(line, ':');
                if (c) {
                    c++;
                    while (*c == ' ' || *c == '\t') c++;
                    one_line(mc->cpu, sizeof mc->cpu, c);
                    size_t l = strlen(mc->cpu);
                    while (l && (mc->cpu[l - 1] == ' ' || mc->cpu[l - 1] == '\n')) mc->cpu[--l] = '\0';
                }
                break;
            }
        }
        fclose(f);
    }
    mc->cores = (int)sysconf(_SC_NPROCESSORS_ONLN);
    f = fopen("/proc/meminfo", "r");
    if (f) {
        unsigned long long kb = 0;
        while (fgets(line, sizeof line, f))
            if (sscanf(line, "MemTotal: %llu kB", &kb) == 1) break;
        mc->mem_bytes = 1024.0 * (double)kb;
        fclose(f);
    }
    f = popen("git -C '" GLPGP_SOURCE_DIR "' rev-parse HEAD 2>/dev/null", "r");
    if (f) {
        if (fgets(line, sizeof line, f) && strlen(line) >= 40) {
            line[40] = '\0';
            snprintf(mc->commit, sizeof mc->commit, "%s", line);
            mc->have_commit = 1;
        }
        pclose(f);
    }
    if (mc->have_commit) {
        f = popen("git -C '" GLPGP_SOURCE_DIR "' status --porcelain --untracked-files=no 2>/dev/null", "r");
        if (f) {
            mc->dirty = fgets(line, sizeof line, f) != NULL;
            while (fgets(line, sizeof line, f)) {
            }
            pclose(f);
        }
    }
}

/* ---- JSON (the library's emitter, glpgp/json.h) -------------------------------------- */

static void jstat(glpgp_json *w, const char *key, const tstat *t)
{
    glpgp_json_object(w, key);
    glpgp_json_num(w, "median", t->med);
    glpgp_json_num(w, "min", t->min);
    glpgp_json_int(w, "n", t->n);
    glpgp_json_close(w);
}

static double ratio(double a, double b) { return (isfinite(a) && isfinite(b) && b != 0.0) ? a / b : NAN; }

static void json_bres(glpgp_json *w, const char *key, const bres *b, double triad)
{
    glpgp_json_object(w, key);
    glpgp_json_bool(w, "ran", b->ran);
    glpgp_json_str(w, "note", b->note);
    if (b->ran) {
        glpgp_json_num(w, "create_s", b->create_s);
        glpgp_json_num(w, "setup_s", b->setup_s);
        jstat(w, "quad_assembly_s", &b->quad);
        jstat(w, "newton_assembly_s", &b->newton);
        jstat(w, "spmv_s", &b->spmv);
        glpgp_json_num(w, "spmv_gbs", b->spmv_gbs);
        glpgp_json_num(w, "spmv_gbs_best", b->spmv_gbs_best);
        glpgp_json_num(w, "spmv_triad_ratio", ratio(b->spmv_gbs, triad));
        jstat(w, "cg_iter_s", &b->cg_iter);
        glpgp_json_num(w, "cg_iter_gbs", b->cg_gbs);
        glpgp_json_num(w, "cg_iter_gbs_best", b->cg_gbs_best);
        glpgp_json_num(w, "cg_triad_ratio", ratio(b->cg_gbs, triad));
        jstat(w, "linear_solve_s", &b->lin);
        glpgp_json_int(w, "linear_solve_iterations", b->lin_iters);
        glpgp_json_num(w, "linear_solve_relres", b->lin_relres);
        jstat(w, "newton_step_s", &b->nstep);
        glpgp_json_int(w, "newton_step_cg_iterations", b->nstep_cg);
        glpgp_json_num(w, "newton_step_alpha", b->nstep_alpha);
        glpgp_json_num(w, "backend_bytes", b->backend_bytes);
        glpgp_json_int(w, "rss_delta_bytes", b->rss_delta);
    }
    glpgp_json_object(w, "gl_solve");
    glpgp_json_bool(w, "ran", b->gl_ran);
    glpgp_json_str(w, "note", b->gl_note);
    if (b->gl_ran) {
        jstat(w, "s", &b->gl);
        glpgp_json_int(w, "newton_iterations", b->gl_newton);
        glpgp_json_int(w, "cg_iterations", b->gl_cg);
        glpgp_json_num(w, "setup_s", b->gl_setup_s);
        glpgp_json_num(w, "field_s", b->gl_field_s);
    }
    glpgp_json_close(w);
    glpgp_json_close(w);
}

static void json_cholmod(glpgp_json *w, const sres *s)
{
    const bench_cholmod *c = &s->chol;
    glpgp_json_object(w, "cholmod");
    glpgp_json_bool(w, "ran", c->ran);
    glpgp_json_bool(w, "ok", c->ok);
    glpgp_json_str(w, "note", c->note);
    if (c->ok) {
        const double fs = c->factorize_s + c->solve_s, afs = c->analyze_s + fs;
        glpgp_json_num(w, "analyze_s", c->analyze_s);
        glpgp_json_num(w, "factorize_s", c->factorize_s);
        glpgp_json_num(w, "solve_s", c->solve_s);
        glpgp_json_num(w, "factor_nnz", c->factor_nnz);
        glpgp_json_num(w, "peak_bytes", c->peak_bytes);
        glpgp_json_num(w, "rel_diff_vs_cg", c->rel_diff_vs_cg);
        glpgp_json_num(w, "pcg_reference_over_factor_solve", s->ref.ran ? ratio(s->ref.lin.med, fs) : NAN);
        glpgp_json_num(w, "pcg_opencl_over_factor_solve", s->cl.ran ? ratio(s->cl.lin.med, fs) : NAN);
        glpgp_json_num(w, "pcg_reference_over_analyze_factor_solve", s->ref.ran ? ratio(s->ref.lin.med, afs) : NAN);
        glpgp_json_num(w, "pcg_opencl_over_analyze_factor_solve", s->cl.ran ? ratio(s->cl.lin.med, afs) : NAN);
    }
    glpgp_json_close(w);
}

static void json_size(glpgp_json *w, const sres *s, const bench_stream *bs, const clbuild *cb)
{
    const double triad = bs->triad_gbs;
    const int both = s->cl.ran && s->ref.ran;
    glpgp_json_object(w, NULL);
    glpgp_json_int(w, "requested", s->requested);
    glpgp_json_int(w, "vertices", s->nv);
    glpgp_json_int(w, "triangles", s->nt);
    glpgp_json_int(w, "blocks", s->nnzb);
    glpgp_json_num(w, "mean_edge", s->mean_edge);
    glpgp_json_num(w, "h", s->h);
    glpgp_json_num(w, "eps", s->eps);
    glpgp_json_num(w, "bytes_spmv", s->bytes_spmv);
    glpgp_json_num(w, "bytes_cg_iter", s->bytes_cg);
    glpgp_json_num(w, "mesh_s", s->mesh_s);
    glpgp_json_num(w, "system_s", s->system_s);
    glpgp_json_num(w, "cg_bandwidth_ratio", s->cl.ran ? ratio(s->cl.cg_gbs, triad) : NAN);
    glpgp_json_num(w, "cg_device_bandwidth_ratio", s->cl.ran && cb->ok ? ratio(s->cl.cg_gbs, cb->dev_axpby_gbs) : NAN);
    glpgp_json_num(w, "cg_speedup_vs_reference", both ? ratio(s->ref.cg_iter.med, s->cl.cg_iter.med) : NAN);
    glpgp_json_num(w, "spmv_speedup_vs_reference", both ? ratio(s->ref.spmv.med, s->cl.spmv.med) : NAN);
    glpgp_json_num(w, "linear_solve_speedup_vs_reference", both ? ratio(s->ref.lin.med, s->cl.lin.med) : NAN);
    glpgp_json_num(w, "newton_step_speedup_vs_reference", both ? ratio(s->ref.nstep.med, s->cl.nstep.med) : NAN);
    glpgp_json_num(w, "gl_speedup_vs_reference",
                   (s->cl.gl_ran && s->ref.gl_ran) ? ratio(s->ref.gl.med, s->cl.gl.med) : NAN);
    glpgp_json_num(w, "peak_rss_bytes", s->peak_rss_kb >= 0 ? 1024.0 * s->peak_rss_kb : NAN);
    glpgp_json_num(w, "device_bytes", s->cl.ran ? s->cl.backend_bytes : NAN);
    json_bres(w, "reference", &s->ref, triad);
    json_bres(w, "opencl", &s->cl, triad);
    json_cholmod(w, s);
    glpgp_json_close(w);
}

static void write_json(FILE *f, const bopts *o, const machine *mc, const bench_stream *bs, const clbuild *cb,
                       const sres *sr, int ns, double total_s)
{
    glpgp_json w;
    glpgp_json_init(&w, f);
    glpgp_json_object(&w, NULL);
    glpgp_json_str(&w, "schema", "glpgp-bench/1");
    glpgp_json_object(&w, "machine");
    glpgp_json_str(&w, "cpu", mc->cpu);
    glpgp_json_int(&w, "cores", mc->cores);
    glpgp_json_num(&w, "memory_bytes", mc->mem_bytes);
    glpgp_json_close(&w);
    glpgp_json_str(&w, "device", cb->ok ? cb->device : NULL);
    glpgp_json_str(&w, "commit", mc->have_commit ? mc->commit : NULL);
    glpgp_json_bool(&w, "worktree_dirty", mc->dirty);
    glpgp_json_object(&w, "options");
    glpgp_json_str(&w, "shape", o->shape);
    glpgp_json_int(&w, "repeat", o->repeat);
    glpgp_json_num(&w, "min_time_s", o->min_time);
    glpgp_json_bool(&w, "smoke", o->smoke);
    glpgp_json_int(&w, "h_mean_edges", 10);
    glpgp_json_num(&w, "eps_h", 0.5);
    glpgp_json_str(&w, "hessian", "projected");
    glpgp_json_int(&w, "cg_block", CG_BLOCK);
    glpgp_json_int(&w, "max_solve_vertices", o->max_solve_ref);
    glpgp_json_int(&w, "max_solve_vertices_opencl", o->max_solve_cl);
    glpgp_json_int(&w, "solve_repeat", o->solve_repeat);
    glpgp_json_str(&w, "oscillators", o->oscillators == GLPGP_OSC_SEQUENTIAL   ? "sequential"
                                      : o->oscillators == GLPGP_OSC_CONCURRENT ? "concurrent"
                                                                               : "auto");
    glpgp_json_close(&w);
    glpgp_json_object(&w, "stream");
    glpgp_json_int(&w, "threads", bs->threads);
    glpgp_json_int(&w, "array_bytes", (long long)bs->array_bytes);
    glpgp_json_int(&w, "reps", bs->reps);
    glpgp_json_num(&w, "copy_gbs", bs->copy_gbs);
    glpgp_json_num(&w, "triad_gbs", bs->triad_gbs);
    glpgp_json_num(&w, "copy_gbs_median", bs->copy_gbs_med);
    glpgp_json_num(&w, "triad_gbs_median", bs->triad_gbs_med);
    glpgp_json_close(&w);
    glpgp_json_object(&w, "opencl");
    glpgp_json_bool(&w, "available", cb->ok);
    glpgp_json_str(&w, "note", cb->ok ? "" : cb->note);
    glpgp_json_bool(&w, "profiling_events", 0);
    glpgp_json_str(&w, "timing", "wall clock (the backend exposes no profiling events)");
    if (cb->ok) {
        glpgp_json_str(&w, "pocl_cache_dir", cb->cache_dir[0] ? cb->cache_dir : NULL);
        glpgp_json_num(&w, "build_cold_s", cb->create_cold_s);
        glpgp_json_num(&w, "first_launch_cold_s", cb->first_ops_cold_s);
        glpgp_json_num(&w, "build_cached_s", cb->create_warm_s);
        glpgp_json_num(&w, "first_launch_cached_s", cb->first_ops_warm_s);
        glpgp_json_int(&w, "device_array_bytes", (long long)cb->dev_bytes);
        glpgp_json_int(&w, "device_reps", cb->dev_reps);
        glpgp_json_num(&w, "device_copy_gbs", cb->dev_copy_gbs);
        glpgp_json_num(&w, "device_axpby_gbs", cb->dev_axpby_gbs);
    }
    glpgp_json_close(&w);
    glpgp_json_object(&w, "cholmod");
    glpgp_json_bool(&w, "built", bench_have_cholmod());
    glpgp_json_close(&w);
    glpgp_json_array(&w, "sizes");
    for (int i = 0; i < ns; i++) json_size(&w, &sr[i], bs, cb);
    glpgp_json_close(&w);
    glpgp_json_num(&w, "total_s", total_s);
    glpgp_json_finish(&w);
}

/* ---- Markdown -------------------------------------------------------------------------- */

static void md_cell_time(FILE *f, const bres *b, const tstat *t)
{
    char x[32], y[32];
    if (!b->ran) fprintf(f, " - |");
    else fprintf(f, " %s / %s |", ftime(x, sizeof x, t->med), ftime(y, sizeof y, t->min));
}

static void md_row(FILE *f, const char *label, const char *op, const sres *s, const tstat *tr, const tstat *tc,
                   double gr, double gc, double triad)
{
    fprintf(f, "| %s | %s |", label, op);
    md_cell_time(f, &s->ref, tr);
    md_cell_time(f, &s->cl, tc);
    double sp = (s->ref.ran && s->cl.ran) ? ratio(tr->med, tc->med) : NAN;
    if (isfinite(sp)) fprintf(f, " %.2fx |", sp);
    else fprintf(f, " - |");
    if (isfinite(gr) && s->ref.ran) fprintf(f, " %.1f |", gr);
    else fprintf(f, " |");
    if (isfinite(gc) && s->cl.ran) fprintf(f, " %.1f | %.2f |\n", gc, gc / triad);
    else fprintf(f, " | |\n");
}

static void write_markdown(FILE *f, const bopts *o, const machine *mc, const bench_stream *bs, const clbuild *cb,
                           const sres *sr, int ns, double total_s)
{
    char a[64], b2[64], c3[64], d4[64];
    fprintf(f, "## glpgp-bench\n\n");
    fprintf(f, "- machine: %s, %d cores, %.1f GiB; commit %s%s\n", mc->cpu, mc->cores, mc->mem_bytes / 1073741824.0,
            mc->have_commit ? mc->commit : "unknown", mc->dirty ? " (work tree modified)" : "");
    fprintf(f, "- STREAM (%d threads, 3 x %.0f MiB, best of %d): copy %.1f GB/s, triad %.1f GB/s (median %.1f)\n",
            bs->threads, bs->array_bytes / 1048576.0, bs->reps, bs->copy_gbs, bs->triad_gbs, bs->triad_gbs_med);
    if (cb->ok)
        fprintf(f, "- OpenCL: %s; program build cold %s + first launch %s, cached %s + %s%s\n", cb->device,
                ftime(a, sizeof a, cb->create_cold_s), ftime(b2, sizeof b2, cb->first_ops_cold_s),
                ftime(c3, sizeof c3, cb->create_warm_s), ftime(d4, sizeof d4, cb->first_ops_warm_s),
                cb->cache_dir[0] ? " (fresh POCL_CACHE_DIR)" : " (existing PoCL cache: cold figure may be cached)");
    if (cb->ok && isfinite(cb->dev_axpby_gbs))
        fprintf(f, "- OpenCL device bandwidth (2 x %.0f MiB, best of %d): copy %.1f GB/s, axpby (y <- a x + c y) "
                   "%.1f GB/s\n",
                cb->dev_bytes / 1048576.0, cb->dev_reps, cb->dev_copy_gbs, cb->dev_axpby_gbs);
    if (!cb->ok)
        fprintf(f, "- OpenCL: skipped (%s)\n", cb->note[0] ? cb->note : "not available");
    fprintf(f, "- kernel times: wall clock only (the OpenCL backend exposes no profiling events); every timed "
               "call ends with a blocking scalar read\n");
    fprintf(f, "- %s domains, h = 10 mean edges, Newton matrix at a perturbed plane wave, eps = h/2, projected "
               "Hessian; median / min of >= %d runs%s\n",
            o->shape, o->repeat, o->min_time > 0 ? " (cheap ops repeated for >= min-time)" : "");
    fprintf(f, "- GB/s: SpMV moves 36 nnzb + 36 nv bytes, a CG iteration 36 nnzb + 228 nv (bench/README.md)\n\n");

    fprintf(f, "| vertices | operation | reference (median / min) | OpenCL (median / min) | ref / OpenCL | ref GB/s | "
               "OpenCL GB/s | OpenCL / triad |\n|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < ns; i++) {
        const sres *s = &sr[i];
        char lab[32], op[96];
        snprintf(lab, sizeof lab, "%d", s->nv);
        md_row(f, lab, "QUAD assembly", s, &s->ref.quad, &s->cl.quad, NAN, NAN, bs->triad_gbs);
        md_row(f, "", "Newton assembly", s, &s->ref.newton, &s->cl.newton, NAN, NAN, bs->triad_gbs);
        md_row(f, "", "SpMV (NEWTON)", s, &s->ref.spmv, &s->cl.spmv, s->ref.spmv_gbs, s->cl.spmv_gbs, bs->triad_gbs);
        md_row(f, "", "CG iteration", s, &s->ref.cg_iter, &s->cl.cg_iter, s->ref.cg_gbs, s->cl.cg_gbs, bs->triad_gbs);
        if (s->ref.ran && s->cl.ran && s->ref.lin_iters != s->cl.lin_iters)
            snprintf(op, sizeof op, "linear solve (%d / %d CG it)", s->ref.lin_iters, s->cl.lin_iters);
        else
            snprintf(op, sizeof op, "linear solve (%d CG it)", s->ref.ran ? s->ref.lin_iters : s->cl.lin_iters);
        md_row(f, "", op, s, &s->ref.lin, &s->cl.lin, NAN, NAN, bs->triad_gbs);
        if (s->ref.ran && s->cl.ran && s->ref.nstep_cg != s->cl.nstep_cg)
            snprintf(op, sizeof op, "Newton step (%d / %d CG it)", s->ref.nstep_cg, s->cl.nstep_cg);
        else
            snprintf(op, sizeof op, "Newton step (%d CG it)", s->ref.ran ? s->ref.nstep_cg : s->cl.nstep_cg);
        md_row(f, "", op, s, &s->ref.nstep, &s->cl.nstep, NAN, NAN, bs->triad_gbs);
        /* whole GL solve: its own row with counts */
        fprintf(f, "| | GL solve (Newton / CG it) |");
        for (int k = 0; k < 2; k++) {
            const bres *b = k ? &s->cl : &s->ref;
            if (b->gl_ran)
                fprintf(f, " %s (%d / %ld) |", ftime(a, sizeof a, b->gl.med), b->gl_newton, b->gl_cg);
            else
                fprintf(f, " %s |", b->ran ? "skipped" : "-");
        }
        if (s->ref.gl_ran && s->cl.gl_ran) fprintf(f, " %.2fx | | | |\n", ratio(s->ref.gl.med, s->cl.gl.med));
        else fprintf(f, " - | | | |\n");
    }
    int skipped = 0;
    for (int i = 0; i < ns; i++)
        for (int k = 0; k < 2; k++) {
            const bres *b = k ? &sr[i].cl : &sr[i].ref;
            if (b->ran && !b->gl_ran) {
                if (!skipped++) fprintf(f, "\n");
                fprintf(f, "- GL solve, %d vertices, %s: %s\n", sr[i].nv, k ? "OpenCL" : "reference", b->gl_note);
            }
        }
    for (int i = 0; i < ns; i++)
        if (!sr[i].cl.ran && sr[i].cl.note[0] && cb->ok)
            fprintf(f, "- OpenCL, %d vertices: %s\n", sr[i].nv, sr[i].cl.note);

    fprintf(f, "\n| vertices | blocks | cg_bandwidth_ratio | CG / device axpby | cg_speedup_vs_reference | GL speedup "
               "| peak RSS | OpenCL device bytes | CHOLMOD analyse / factor / solve | PCG / Cholesky (ref, OpenCL) |\n"
               "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < ns; i++) {
        const sres *s = &sr[i];
        fprintf(f, "| %d | %ld |", s->nv, s->nnzb);
        if (s->cl.ran) fprintf(f, " %.2f |", s->cl.cg_gbs / bs->triad_gbs);
        else fprintf(f, " - |");
        if (s->cl.ran && isfinite(cb->dev_axpby_gbs)) fprintf(f, " %.2f |", s->cl.cg_gbs / cb->dev_axpby_gbs);
        else fprintf(f, " - |");
        if (s->cl.ran && s->ref.ran) fprintf(f, " %.2f |", ratio(s->ref.cg_iter.med, s->cl.cg_iter.med));
        else fprintf(f, " - |");
        if (s->cl.gl_ran && s->ref.gl_ran) fprintf(f, " %.2f |", ratio(s->ref.gl.med, s->cl.gl.med));
        else fprintf(f, " - |");
        fprintf(f, " %.0f MiB |", s->peak_rss_kb / 1024.0);
        if (s->cl.ran) fprintf(f, " %.0f MiB |", s->cl.backend_bytes / 1048576.0);
        else fprintf(f, " - |");
        const bench_cholmod *c = &s->chol;
        if (c->ok) {
            char x[32], y[32], z[32];
            const double fs = c->factorize_s + c->solve_s;
            fprintf(f, " %s / %s / %s |", ftime(x, sizeof x, c->analyze_s), ftime(y, sizeof y, c->factorize_s),
                    ftime(z, sizeof z, c->solve_s));
            fprintf(f, " %s, %s |\n", s->ref.ran ? (snprintf(x, sizeof x, "%.3f", s->ref.lin.med / fs), x) : "-",
                    s->cl.ran ? (snprintf(y, sizeof y, "%.3f", s->cl.lin.med / fs), y) : "-");
        } else {
            fprintf(f, " %s | - |\n", c->note[0] ? c->note : "-");
        }
    }
    if (!bench_have_cholmod()) fprintf(f, "\nCHOLMOD: skipped (not built with it)\n");
    else
        fprintf(f, "\nPCG / Cholesky = PCG linear-solve time / (CHOLMOD numeric factorisation + solve); the symbolic "
                   "analysis is re-used across Newton steps, so it is shown but not counted.\n");
    fprintf(f, "\nTotal bench time %.1f s.\n", total_s);
}

/* ---- --compare ----------------------------------------------------------------------- */

static glpgp_status read_all(const char *path, char **out)
{
    FILE *f = fopen(path, "rb");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    size_t cap = 65536, n = 0;
    char *buf = malloc(cap);
    if (!buf) {
        fclose(f);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
    }
    size_t r;
    while ((r = fread(buf + n, 1, cap - n - 1, f)) > 0) {
        n += r;
        if (n + 1 == cap) {
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                free(buf);
                fclose(f);
                return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
            }
            buf = nb;
            cap *= 2;
        }
    }
    int err = ferror(f);
    fclose(f);
    if (err) {
        free(buf);
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read '%s'", path);
    }
    buf[n] = '\0';
    *out = buf;
    return GLPGP_OK;
}

/* Whether a leaf is a figure worth comparing (times, rates, ratios, counts). */
static int is_figure(const char *p)
{
    static const char *const skip[] = {".n", ".requested", ".vertices", ".triangles", ".blocks", ".mean_edge", ".h",
                                       ".eps", ".bytes_spmv", ".bytes_cg_iter", "cores", "memory_bytes", ".threads",
                                       ".array_bytes", ".reps", NULL};
    if (strncmp(p, "options.", 8) == 0 || strncmp(p, "machine.", 8) == 0) return 0;
    size_t lp = strlen(p);
    for (int k = 0; skip[k]; k++) {
        size_t l = strlen(skip[k]);
        if (lp >= l && strcmp(p + lp - l, skip[k]) == 0) return 0;
    }
    return 1;
}

static glpgp_status compare(const char *oldpath, const char *newtext, const char *newname)
{
    char *oldtext = NULL;
    bench_flat fo, fn;
    GLPGP_CHECK(read_all(oldpath, &oldtext));
    glpgp_status st = bench_json_flatten(oldtext, &fo);
    free(oldtext);
    if (st != GLPGP_OK) {
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    st = bench_json_flatten(newtext, &fn);
    if (st != GLPGP_OK) {
        bench_flat_free(&fo);
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    printf("\n## Comparison: %s / %s (new / old; < 1 is faster for times, > 1 better for GB/s)\n\n", newname, oldpath);
    printf("| figure | old | new | new / old |\n|---|---|---|---|\n");
    int shown = 0, missing = 0;
    for (size_t i = 0; i < fn.n; i++) {
        const char *p = fn.path[i];
        if (!is_figure(p)) continue;
        char oldp[1024], label[1024];
        snprintf(oldp, sizeof oldp, "%s", p);
        snprintf(label, sizeof label, "%s", p);
        int idx = -1, off = 0;
        if (sscanf(p, "sizes.%d.%n", &idx, &off) == 1 && off > 0) {
            /* match sizes by requested vertex count, not by position */
            char key[64];
            snprintf(key, sizeof key, "sizes.%d.requested", idx);
            const double *req = bench_flat_get(&fn, key);
            int j = -1;
            for (int k = 0; req && k < MAX_SIZES; k++) {
                snprintf(key, sizeof key, "sizes.%d.requested", k);
                const double *r2 = bench_flat_get(&fo, key);
                if (r2 && *r2 == *req) {
                    j = k;
                    break;
                }
            }
            if (j < 0) {
                missing++;
                continue;
            }
            snprintf(oldp, sizeof oldp, "sizes.%d.%s", j, p + off);
            snprintf(label, sizeof label, "%.0f: %s", *req, p + off);
        }
        const double *ov = bench_flat_get(&fo, oldp);
        if (!ov) {
            missing++;
            continue;
        }
        const double nv = fn.value[i];
        if (*ov != 0.0) printf("| %s | %.4g | %.4g | %.3f |\n", label, *ov, nv, nv / *ov);
        else printf("| %s | %.4g | %.4g | - |\n", label, *ov, nv);
        shown++;
    }
    printf("\n%d figures compared, %d only in the new file.\n", shown, missing);
    bench_flat_free(&fo);
    bench_flat_free(&fn);
    return GLPGP_OK;
}

/* ---- plot ------------------------------------------------------------------------------ */

static void plot(const char *png, const sres *sr, int ns)
{
    if (!on_path("gnuplot")) {
        printf("\nplot skipped: gnuplot not found\n");
        return;
    }
    char dir[] = "/tmp/glpgp-bench-plot-XXXXXX";
    if (!mkdtemp(dir)) {
        printf("\nplot skipped: cannot create a temporary directory\n");
        return;
    }
    char dat[128], gp[128];
    snprintf(dat, sizeof dat, "%s/data.txt", dir);
    snprintf(gp, sizeof gp, "%s/plot.gp", dir);
    FILE *f = fopen(dat, "w");
    if (!f) {
        printf("\nplot skipped: cannot write %s\n", dat);
        return;
    }
    /* columns: nv, then ref/cl pairs: cg iter, spmv, linear solve, newton assembly, GL solve; cholmod f+s */
    for (int i = 0; i < ns; i++) {
        const sres *s = &sr[i];
        const double v[] = {
            s->ref.ran ? s->ref.cg_iter.med : NAN, s->cl.ran ? s->cl.cg_iter.med : NAN,
            s->ref.ran ? s->ref.spmv.med : NAN,    s->cl.ran ? s->cl.spmv.med : NAN,
            s->ref.ran ? s->ref.lin.med : NAN,     s->cl.ran ? s->cl.lin.med : NAN,
            s->ref.ran ? s->ref.newton.med : NAN,  s->cl.ran ? s->cl.newton.med : NAN,
            s->ref.gl_ran ? s->ref.gl.med : NAN,   s->cl.gl_ran ? s->cl.gl.med : NAN,
            s->chol.ok ? s->chol.factorize_s + s->chol.solve_s : NAN};
        fprintf(f, "%d", s->nv);
        for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
            if (isfinite(v[k])) fprintf(f, " %.6g", v[k]);
            else fprintf(f, " NaN");
        }
        fprintf(f, "\n");
    }
    fclose(f);
    f = fopen(gp, "w");
    if (!f) {
        printf("\nplot skipped: cannot write %s\n", gp);
        return;
    }
    fprintf(f,
            "set terminal pngcairo size 1000,700\nset output '%s'\nset logscale xy\nset grid\n"
            "set key outside right\nset xlabel 'vertices'\nset ylabel 'seconds'\n"
            "set title 'glpgp-bench: time vs vertices (solid: OpenCL, dashed: reference)'\n"
            "set datafile missing 'NaN'\n"
            "plot '%s' u 1:3 w lp lw 2 lc 1 t 'CG iteration, OpenCL', '' u 1:2 w lp dt 2 lc 1 t 'CG iteration, reference', \\\n"
            " '' u 1:5 w lp lw 2 lc 2 t 'SpMV, OpenCL', '' u 1:4 w lp dt 2 lc 2 t 'SpMV, reference', \\\n"
            " '' u 1:7 w lp lw 2 lc 3 t 'linear solve, OpenCL', '' u 1:6 w lp dt 2 lc 3 t 'linear solve, reference', \\\n"
            " '' u 1:9 w lp lw 2 lc 4 t 'Newton assembly, OpenCL', '' u 1:8 w lp dt 2 lc 4 t 'Newton assembly, reference', \\\n"
            " '' u 1:11 w lp lw 2 lc 7 t 'GL solve, OpenCL', '' u 1:10 w lp dt 2 lc 7 t 'GL solve, reference', \\\n"
            " '' u 1:12 w lp lw 2 lc 8 dt 3 t 'CHOLMOD factor+solve'\n",
            png, dat);
    fclose(f);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", gp);
    int rc = system(cmd);
    if (rc == 0) printf("\nplot written: %s\n", png);
    else printf("\nplot failed: gnuplot exited with status %d\n", rc);
    remove(dat);
    remove(gp);
    rmdir(dir);
}

/* STREAM in a forked child, so its arrays do not count in this process's
 * peak RSS (reported per size). Called before any OpenCL call (no threads yet). */
static glpgp_status stream_isolated(int threads, size_t n, int reps, bench_stream *out)
{
    int fd[2];
    if (pipe(fd) != 0) return GLPGP_FAIL(GLPGP_ERR_IO, "pipe: %s", strerror(errno));
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "fork: %s", strerror(errno));
    }
    if (pid == 0) {
        close(fd[0]);
        bench_stream bs;
        int ok = bench_stream_run(threads, n, reps, &bs) == GLPGP_OK;
        if (ok) ok = write(fd[1], &bs, sizeof bs) == (ssize_t)sizeof bs;
        else fprintf(stderr, "glpgp-bench: STREAM: %s\n", glpgp_error_message());
        close(fd[1]);
        _exit(ok ? 0 : 1);
    }
    close(fd[1]);
    size_t got = 0;
    while (got < sizeof *out) {
        ssize_t r = read(fd[0], (char *)out + got, sizeof *out - got);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        got += (size_t)r;
    }
    close(fd[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (got != sizeof *out || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "STREAM child failed (%zu MiB arrays)", n * sizeof(double) >> 20);
    return GLPGP_OK;
}

/* ---- main -------------------------------------------------------------------------------- */

/* the library's log lines on stderr: with GLPGP_CL_PROFILE=1 the OpenCL
 * backend's per-kernel device times (logged when a backend is destroyed) */
static void profile_log(glpgp_log_level level, const char *msg, void *user)
{
    (void)level;
    (void)user;
    if (strncmp(msg, "OpenCL profile", 14) == 0 || strncmp(msg, "  glpgp_", 8) == 0 || strncmp(msg, "    n >= ", 9) == 0)
        fprintf(stderr, "%s\n", msg);
}

int main(int argc, char **argv)
{
    bopts o;
    int help = 0;
    const char *prof = getenv("GLPGP_CL_PROFILE");
    if (prof && !strcmp(prof, "1")) glpgp_log_set_callback(profile_log, NULL);
    if (parse_args(argc, argv, &o, &help) != GLPGP_OK) {
        fprintf(stderr, "glpgp-bench: %s\n", glpgp_error_message());
        usage(stderr);
        return 2;
    }
    if (help) {
        usage(stdout);
        return 0;
    }
    if (o.precond >= 0) {
        bench_precond_opts po;
        memset(&po, 0, sizeof po);
        po.which = o.precond;
        po.nsizes = o.sizes_given ? o.nsizes : 0;
        for (int k = 0; k < po.nsizes && k < 16; k++) po.sizes[k] = o.sizes[k];
        if (po.nsizes > 16) po.nsizes = 16;
        po.with_4m = o.with_4m;
        po.hcases = o.hcases;
        po.steps = o.steps;
        po.kcycle_min = o.kcycle_min;
        po.amg_pre = o.amg_pre;
        po.amg_post = o.amg_post;
        po.amg_passes = o.amg_passes;
        po.no_petsc = o.no_petsc;
        po.no_cholmod = o.no_cholmod;
        po.max_cholmod = o.max_cholmod;
        po.shape = o.shape;
        po.no_opencl = o.no_opencl;
        po.no_reference = o.no_reference;
        po.device = o.device;
        po.json = o.json;
        return bench_precond_run(&po);
    }
    if (o.against) {
        char *text = NULL;
        if (read_all(o.against, &text) != GLPGP_OK || compare(o.compare, text, o.against) != GLPGP_OK) {
            fprintf(stderr, "glpgp-bench: %s\n", glpgp_error_message());
            free(text);
            return 1;
        }
        free(text);
        return 0;
    }
    const double tstart = bench_now();
    machine mc;
    clbuild cb;
    memset(&cb, 0, sizeof cb);
    /* a fresh PoCL kernel cache, before any OpenCL call, so the first build is cold */
    if (!o.no_opencl && glpgp_have_opencl() && !o.keep_cache) {
        char tmpl[] = "/tmp/glpgp-bench-pocl-XXXXXX";
        if (mkdtemp(tmpl)) {
            snprintf(cb.cache_dir, sizeof cb.cache_dir, "%s", tmpl);
            setenv("POCL_CACHE_DIR", cb.cache_dir, 1);
        }
    }
    machine_info(&mc);

    fprintf(stderr, "glpgp-bench: STREAM on %d threads, 3 x %.0f MiB\n", mc.cores,
            o.stream_n * sizeof(double) / 1048576.0);
    bench_stream bs;
    if (stream_isolated(mc.cores, o.stream_n, o.stream_reps, &bs) != GLPGP_OK) {
        fprintf(stderr, "glpgp-bench: %s\n", glpgp_error_message());
        return 1;
    }

    int use_cl = 0;
    if (o.no_opencl) {
        snprintf(cb.note, sizeof cb.note, "--no-opencl");
    } else if (!glpgp_have_opencl()) {
        snprintf(cb.note, sizeof cb.note, "this build has no OpenCL support");
    } else {
        fprintf(stderr, "glpgp-bench: OpenCL program build, cold and cached\n");
        cl_build_probe(&o, &cb);
        use_cl = cb.ok;
        if (!cb.ok) fprintf(stderr, "glpgp-bench: OpenCL column skipped: %s\n", cb.note);
    }

    sres *sr = calloc((size_t)o.nsizes, sizeof *sr);
    if (!sr) {
        fprintf(stderr, "glpgp-bench: out of memory\n");
        return 1;
    }
    int rc = 0, ns = 0;
    for (int i = 0; i < o.nsizes; i++) {
        glpgp_error_clear();
        if (bench_size(&o, o.sizes[i], use_cl, &sr[i]) != GLPGP_OK) {
            fprintf(stderr, "glpgp-bench: size %ld: %s\n", o.sizes[i], glpgp_error_message());
            rc = 1;
            break;
        }
        ns++;
    }
    const double total = bench_now() - tstart;

    write_markdown(stdout, &o, &mc, &bs, &cb, sr, ns, total);

    char *jtext = NULL;
    size_t jlen = 0;
    FILE *mf = open_memstream(&jtext, &jlen);
    if (!mf) {
        fprintf(stderr, "glpgp-bench: cannot create the JSON buffer\n");
        rc = 1;
    } else {
        write_json(mf, &o, &mc, &bs, &cb, sr, ns, total);
        fclose(mf);
        if (o.json) {
            FILE *f = fopen(o.json, "w");
            if (!f || fwrite(jtext, 1, jlen, f) != jlen) {
                fprintf(stderr, "glpgp-bench: cannot write '%s': %s\n", o.json, strerror(errno));
                rc = 1;
            } else {
                printf("\nJSON written: %s\n", o.json);
            }
            if (f && fclose(f) != 0) rc = 1;
        }
        if (o.compare && compare(o.compare, jtext, "this run") != GLPGP_OK) {
            fprintf(stderr, "glpgp-bench: --compare: %s\n", glpgp_error_message());
            rc = 1;
        }
        free(jtext);
    }
    if (o.plot) plot(o.plot, sr, ns);
    free(sr);
    if (cb.cache_dir[0]) nftw(cb.cache_dir, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    return rc;
}
