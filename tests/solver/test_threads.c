/* test_threads.c: the library from two threads at once (what the Python
 * binding does with the GIL released): solves, quad extractions and
 * coordinate partitions of different meshes run concurrently give the same
 * results bit for bit as one after the other (no shared mutable state: the
 * extraction's rotation sort and the partition's axis sort once kept their
 * qsort context in statics), and each thread keeps its own error record. */
#include "testutil.h"

#include <pthread.h>
#include <string.h>

#define REPEAT 40

typedef struct job {
    const glpgp_mesh *m;
    const glpgp_result *r;
    int nf, nv;             /* the sequential quad mesh */
    double sum;             /* sum of its coordinates, in order */
    int *part, *part_ref;   /* partition into 7 parts */
    int bad;
    glpgp_status err_st;    /* the error record seen by this thread */
} job;

static double coord_sum(const glpgp_quadmesh *q)
{
    double s = 0.0;
    for (int i = 0; i < 2 * q->nv; i++) s += q->xy[i] * (double)(i % 7 + 1);
    for (int i = 0; i < q->face_start[q->nf]; i++) s += q->face_vert[i];
    return s;
}

static int sizes7(const glpgp_mesh *m, int size[7])
{
    for (int p = 0; p < 7; p++) size[p] = (int)((long long)m->nv * (p + 1) / 7) - (int)((long long)m->nv * p / 7);
    return 7;
}

static void *work(void *arg)
{
    job *j = arg;
    glpgp_error_clear();
    int size[7];
    sizes7(j->m, size);
    for (int it = 0; it < REPEAT; it++) {
        glpgp_quadmesh *q = NULL;
        if (glpgp_quads_extract(j->m, j->r, &q) != GLPGP_OK || !q || q->nf != j->nf || q->nv != j->nv ||
            coord_sum(q) != j->sum)
            j->bad++;
        glpgp_quadmesh_destroy(&q);
        if (glpgp_mesh_partition(j->m, 7, size, j->part) != GLPGP_OK ||
            memcmp(j->part, j->part_ref, sizeof(int) * (size_t)j->m->nv))
            j->bad++;
    }
    /* an error recorded here stays in this thread's record */
    glpgp_mesh *none = NULL;
    j->err_st = glpgp_mesh_generate("no-such-shape", 100, &none);
    return NULL;
}

static glpgp_result *solve(const glpgp_mesh *m)
{
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    o.oscillators = GLPGP_OSC_SEQUENTIAL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (b) CHECK_OK(glpgp_solve(m, b, &o, &r));
    glpgp_backend_destroy(&b);
    return r;
}

int main(void)
{
    const char *shapes[2] = {"disk", "annulus"};
    glpgp_mesh *m[2] = {NULL, NULL};
    glpgp_result *r[2] = {NULL, NULL};
    job jobs[2];
    memset(jobs, 0, sizeof jobs);
    for (int k = 0; k < 2; k++) {
        CHECK_OK(glpgp_mesh_generate(shapes[k], 3000 + 1000 * k, &m[k]));
        if (!m[k]) TEST_DONE();
        r[k] = solve(m[k]);
        if (!r[k]) TEST_DONE();
        glpgp_quadmesh *q = NULL;
        CHECK_OK(glpgp_quads_extract(m[k], r[k], &q));
        if (!q) TEST_DONE();
        int size[7];
        sizes7(m[k], size);
        jobs[k] = (job){.m = m[k], .r = r[k], .nf = q->nf, .nv = q->nv, .sum = coord_sum(q)};
        glpgp_quadmesh_destroy(&q);
        jobs[k].part = malloc(sizeof(int) * (size_t)m[k]->nv);
        jobs[k].part_ref = malloc(sizeof(int) * (size_t)m[k]->nv);
        CHECK_OK(glpgp_mesh_partition(m[k], 7, size, jobs[k].part_ref));
    }
    /* two solves at once: the same z as one after the other */
    pthread_t th[2];
    glpgp_result *rc[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) CHECK(pthread_create(&th[k], NULL, (void *(*)(void *))solve, m[k]) == 0);
    for (int k = 0; k < 2; k++) {
        void *out = NULL;
        pthread_join(th[k], &out);
        rc[k] = out;
        CHECK(rc[k] && !memcmp(rc[k]->osc[0].z, r[k]->osc[0].z, 2 * sizeof(double) * (size_t)m[k]->nv) &&
              !memcmp(rc[k]->osc[1].z, r[k]->osc[1].z, 2 * sizeof(double) * (size_t)m[k]->nv));
        glpgp_result_destroy(&rc[k]);
    }
    /* extractions and partitions at once */
    glpgp_error_clear();
    for (int k = 0; k < 2; k++) CHECK(pthread_create(&th[k], NULL, work, &jobs[k]) == 0);
    for (int k = 0; k < 2; k++) pthread_join(th[k], NULL);
    for (int k = 0; k < 2; k++) {
        if (jobs[k].bad) fprintf(stderr, "%s: %d of %d runs differ from the sequential ones\n", shapes[k], jobs[k].bad,
                                 2 * REPEAT);
        CHECK(jobs[k].bad == 0);
        CHECK(jobs[k].err_st == GLPGP_ERR_ARG);
        free(jobs[k].part);
        free(jobs[k].part_ref);
        glpgp_result_destroy(&r[k]);
        glpgp_mesh_destroy(&m[k]);
    }
    CHECK(glpgp_error_status() == GLPGP_OK); /* the threads' errors are theirs */
    TEST_DONE();
}
