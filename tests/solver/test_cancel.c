/* test_cancel.c: the cancellation hook of glpgp_options (cancel,
 * cancel_ctx): polled before every Newton step, a non-zero return ends the
 * solve with GLPGP_ERR_CANCELLED and no result, on one thread and with the
 * oscillators in two threads; a hook that never cancels changes nothing
 * (the same z bit for bit) and is called at least once per Newton step. */
#include "testutil.h"

#include <string.h>

typedef struct counter {
    int calls;
    int cancel_at; /* return 1 from this call on (0: never) */
} counter;

static int hook(void *ctx)
{
    counter *c = ctx;
    int n = __atomic_add_fetch(&c->calls, 1, __ATOMIC_RELAXED);
    return c->cancel_at > 0 && n >= c->cancel_at;
}

static glpgp_status run(const glpgp_mesh *m, int osc, counter *c, glpgp_result **r)
{
    glpgp_backend *b = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    o.oscillators = osc;
    if (c) {
        o.cancel = hook;
        o.cancel_ctx = c;
    }
    *r = NULL;
    glpgp_status st = glpgp_backend_create_reference(&b);
    if (st == GLPGP_OK) st = glpgp_solve(m, b, &o, r);
    glpgp_backend_destroy(&b);
    return st;
}

int main(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 1500, &m));
    if (!m) TEST_DONE();
    glpgp_result *r0 = NULL, *r1 = NULL, *r2 = NULL;
    CHECK_OK(run(m, GLPGP_OSC_SEQUENTIAL, NULL, &r0));
    counter never = {0, 0};
    CHECK_OK(run(m, GLPGP_OSC_SEQUENTIAL, &never, &r1));
    if (r0 && r1) {
        const int steps = r0->osc[0].newton_iterations + r0->osc[1].newton_iterations;
        CHECK(steps > 4);
        CHECK(never.calls >= steps);
        for (int k = 0; k < 2; k++)
            CHECK(!memcmp(r0->osc[k].z, r1->osc[k].z, 2 * sizeof(double) * (size_t)m->nv));
    }
    for (int osc = GLPGP_OSC_SEQUENTIAL; osc <= GLPGP_OSC_CONCURRENT; osc++) {
        counter stop = {0, 3};
        glpgp_error_clear();
        glpgp_status st = run(m, osc, &stop, &r2);
        CHECK(st == GLPGP_ERR_CANCELLED);
        CHECK(glpgp_error_status() == GLPGP_ERR_CANCELLED);
        CHECK(strstr(glpgp_error_message(), "cancelled") != NULL);
        CHECK(r2 == NULL);
        CHECK(stop.calls >= 3 && stop.calls <= 6); /* stopped at once (each thread polls once more at most) */
        glpgp_result_destroy(&r2);
        glpgp_error_clear();
    }
    CHECK(!strcmp(glpgp_status_name(GLPGP_ERR_CANCELLED), "cancelled"));
    glpgp_result_destroy(&r0);
    glpgp_result_destroy(&r1);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
