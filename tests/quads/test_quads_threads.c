/* test_quads_threads.c: glpgp_quads_extract called from two threads at once
 * (the Python binding runs two extractions in parallel). Each thread
 * extracts its own input (a disk and a square with plane waves at different
 * periods, so the two extractions' graphs differ) many times, and every
 * result must equal the one extracted alone, vertex coordinates and faces
 * bit for bit. With a qsort context kept in a static (the rotation system
 * sorted through a static angle array) the threads sort with each other's
 * angles: different faces, or reads past the array. */
#include "testutil.h"

#include <pthread.h>
#include <string.h>

#define PI_ 3.14159265358979323846
#define REPEAT 200

static glpgp_result *plane_waves(const glpgp_mesh *m, double h, double turn)
{
    glpgp_result *r = calloc(1, sizeof *r);
    r->nv = m->nv;
    r->nt = m->nt;
    r->size = h;
    double c = cos(turn), s = sin(turn);
    for (int k = 0; k < 2; k++) {
        r->osc[k].z = malloc(sizeof(double) * 2 * (size_t)m->nv);
        r->osc[k].dirichlet = calloc((size_t)m->nv, 1);
        r->osc[k].singular = calloc((size_t)m->nt, 1);
        for (int i = 0; i < m->nv; i++) {
            double x = m->xy[2 * i], y = m->xy[2 * i + 1];
            double t = (k == 0 ? c * x + s * y : -s * x + c * y) / h;
            r->osc[k].z[2 * i] = cos(2 * PI_ * t);
            r->osc[k].z[2 * i + 1] = sin(2 * PI_ * t);
        }
    }
    return r;
}

static int same(const glpgp_quadmesh *a, const glpgp_quadmesh *b)
{
    if (!a || !b || a->nv != b->nv || a->nf != b->nf) return 0;
    if (memcmp(a->xy, b->xy, sizeof(double) * 2 * (size_t)a->nv)) return 0;
    if (memcmp(a->face_start, b->face_start, sizeof(int) * ((size_t)a->nf + 1))) return 0;
    return !memcmp(a->face_vert, b->face_vert, sizeof(int) * (size_t)a->face_start[a->nf]);
}

typedef struct job {
    const glpgp_mesh *m;
    const glpgp_result *r;
    const glpgp_quadmesh *ref;
    int mismatches, failures;
} job;

static void *run(void *arg)
{
    job *j = arg;
    for (int i = 0; i < REPEAT; i++) {
        glpgp_quadmesh *q = NULL;
        if (glpgp_quads_extract(j->m, j->r, &q) != GLPGP_OK) {
            j->failures++;
            glpgp_error_clear();
        } else if (!same(q, j->ref)) {
            j->mismatches++;
        }
        glpgp_quadmesh_destroy(&q);
    }
    return NULL;
}

int main(void)
{
    glpgp_mesh *m[2] = {NULL, NULL};
    glpgp_result *r[2] = {NULL, NULL};
    glpgp_quadmesh *ref[2] = {NULL, NULL};
    CHECK_OK(glpgp_mesh_generate("disk", 3000, &m[0]));
    CHECK_OK(glpgp_mesh_generate("square", 2500, &m[1]));
    if (!m[0] || !m[1]) TEST_DONE();
    r[0] = plane_waves(m[0], 0.12, 0.3);
    r[1] = plane_waves(m[1], 0.07, -0.2);
    for (int k = 0; k < 2; k++) CHECK_OK(glpgp_quads_extract(m[k], r[k], &ref[k]));
    if (ref[0] && ref[1]) {
        printf("alone: disk %d faces, square %d faces\n", ref[0]->nf, ref[1]->nf);
        CHECK(ref[0]->nf > 100 && ref[1]->nf > 150);
        job j[2];
        pthread_t th[2];
        for (int k = 0; k < 2; k++) j[k] = (job){m[k], r[k], ref[k], 0, 0};
        for (int k = 0; k < 2; k++) CHECK(pthread_create(&th[k], NULL, run, &j[k]) == 0);
        for (int k = 0; k < 2; k++) pthread_join(th[k], NULL);
        for (int k = 0; k < 2; k++) {
            printf("thread %d: %d extractions, %d differ from the one alone, %d failed\n", k, REPEAT,
                   j[k].mismatches, j[k].failures);
            CHECK(j[k].mismatches == 0 && j[k].failures == 0);
        }
    }
    for (int k = 0; k < 2; k++) {
        glpgp_quadmesh_destroy(&ref[k]);
        glpgp_result_destroy(&r[k]);
        glpgp_mesh_destroy(&m[k]);
    }
    TEST_DONE();
}
