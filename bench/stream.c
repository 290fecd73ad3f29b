/* stream.c: STREAM-style host memory bandwidth probe (copy and triad) on
 * all cores with pthreads, for glpgp-bench: the physical limit a
 * memory-bound CG iteration is compared against. */
#include "bench.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct stream_shared {
    double *a, *b, *c;
    size_t n;
    int threads, reps;
    pthread_barrier_t bar;
    double *tcopy, *ttriad; /* reps + 1 (index 0: warm-up) */
} stream_shared;

typedef struct stream_arg {
    stream_shared *sh;
    int id;
} stream_arg;

static void *stream_worker(void *p)
{
    stream_arg *arg = p;
    stream_shared *sh = arg->sh;
    const size_t lo = sh->n * (size_t)arg->id / (size_t)sh->threads;
    const size_t hi = sh->n * (size_t)(arg->id + 1) / (size_t)sh->threads;
    double *restrict a = sh->a, *restrict b = sh->b, *restrict c = sh->c;
    const double s = 3.0;
    /* first touch: each thread's pages live near it */
    for (size_t i = lo; i < hi; i++) {
        a[i] = 1.0;
        b[i] = 2.0;
        c[i] = 0.5;
    }
    for (int r = 0; r <= sh->reps; r++) {
        double t0 = 0.0;
        pthread_barrier_wait(&sh->bar);
        if (arg->id == 0) t0 = bench_now();
        for (size_t i = lo; i < hi; i++) c[i] = a[i];
        pthread_barrier_wait(&sh->bar);
        if (arg->id == 0) sh->tcopy[r] = bench_now() - t0;
        pthread_barrier_wait(&sh->bar);
        if (arg->id == 0) t0 = bench_now();
        for (size_t i = lo; i < hi; i++) a[i] = b[i] + s * c[i];
        pthread_barrier_wait(&sh->bar);
        if (arg->id == 0) sh->ttriad[r] = bench_now() - t0;
    }
    return NULL;
}

static int cmp_d(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

glpgp_status bench_stream_run(int threads, size_t n, int reps, bench_stream *out)
{
    glpgp_status st = GLPGP_OK;
    stream_shared sh;
    pthread_t *tid = NULL;
    stream_arg *args = NULL;
    int started = 0, barrier = 0;
    memset(&sh, 0, sizeof sh);
    memset(out, 0, sizeof *out);
    if (threads < 1) threads = 1;
    if (reps < 1) reps = 1;
    sh.n = n;
    sh.threads = threads;
    sh.reps = reps;
    /* malloc, not calloc: the pages are first touched by the worker threads */
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n, sizeof(double), &sh.a), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n, sizeof(double), &sh.b), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n, sizeof(double), &sh.c), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)reps + 1, sizeof(double), &sh.tcopy), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)reps + 1, sizeof(double), &sh.ttriad), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)threads, sizeof *tid, &tid), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)threads, sizeof *args, &args), done);
    if (pthread_barrier_init(&sh.bar, NULL, (unsigned)threads) != 0) {
        st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "STREAM: pthread_barrier_init failed");
        goto done;
    }
    barrier = 1;
    for (int t = 0; t < threads; t++) {
        args[t].sh = &sh;
        args[t].id = t;
        if (pthread_create(&tid[t], NULL, stream_worker, &args[t]) != 0) {
            /* cannot continue with fewer threads than the barrier expects */
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "STREAM: pthread_create failed for thread %d", t);
            for (int u = 0; u < t; u++) pthread_cancel(tid[u]);
            for (int u = 0; u < t; u++) pthread_join(tid[u], NULL);
            goto done;
        }
        started++;
    }
    for (int t = 0; t < started; t++) pthread_join(tid[t], NULL);
    /* skip the warm-up (index 0) */
    qsort(sh.tcopy + 1, (size_t)reps, sizeof(double), cmp_d);
    qsort(sh.ttriad + 1, (size_t)reps, sizeof(double), cmp_d);
    const double bytes = (double)n * sizeof(double);
    out->threads = threads;
    out->array_bytes = n * sizeof(double);
    out->reps = reps;
    out->copy_gbs = 2.0 * bytes / sh.tcopy[1] * 1e-9;
    out->triad_gbs = 3.0 * bytes / sh.ttriad[1] * 1e-9;
    out->copy_gbs_med = 2.0 * bytes / sh.tcopy[1 + reps / 2] * 1e-9;
    out->triad_gbs_med = 3.0 * bytes / sh.ttriad[1 + reps / 2] * 1e-9;
done:
    if (barrier) pthread_barrier_destroy(&sh.bar);
    free(sh.a);
    free(sh.b);
    free(sh.c);
    free(sh.tcopy);
    free(sh.ttriad);
    free(tid);
    free(args);
    return st;
}
