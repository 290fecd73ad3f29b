/* test_oscillators.c: glpgp_options.oscillators on the reference backend.
 *  - identical: a disk with vortices solved with u and v concurrently (v on
 *    a clone of the backend in a second thread) and one after the other: the
 *    same z, Dirichlet flags, energies, Newton / CG counts and device-call
 *    counts, bit for bit; r->concurrent says which ran;
 *  - worker error: v's clone fails in its quadratic assembly while u
 *    succeeds: glpgp_solve returns v's status and message in the calling
 *    thread, no result;
 *  - u fails first (its energy): u's error is returned and v stops at its next
 *    Newton step (far fewer gradient evaluations on the clone than a whole
 *    v solve makes);
 *  - clone failure: a clone that cannot be made (out of memory): v is solved
 *    after u on the backend itself, the same result, r->concurrent = 0, one
 *    warning when concurrency was asked for, none in auto;
 *  - no clone op: --oscillators concurrent warns once and solves one after
 *    the other; sequential never clones. */
#include "glpgp/solve.h"
#include "glpgp/util.h"
#include "testutil.h"

#include <stdatomic.h>
#include <string.h>

static atomic_int warnings;
static atomic_int clones;

static void count_warnings(glpgp_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level == GLPGP_LOG_WARNING) {
        atomic_fetch_add(&warnings, 1);
        printf("  (warning: %s)\n", msg);
    }
}

/* ops of the parent (clone: make_clone) and of its clones (assembly fails);
 * u_fails: the parent's energy fails, the clone counts its gradients */
static glpgp_backend_ops parent_ops, failing_ops, u_fails_ops, counting_ops;
static int clone_mode; /* 0: a working clone, 1: its assembly fails, 2: no clone (NOMEM),
                          3: a counting clone */
static atomic_int gradients;
static glpgp_status (*ref_gradient)(glpgp_backend *, const glpgp_vec *, double, glpgp_vec *);

static glpgp_status counting_gradient(glpgp_backend *b, const glpgp_vec *x, double inv4e2, glpgp_vec *g)
{
    atomic_fetch_add(&gradients, 1);
    return ref_gradient(b, x, inv4e2, g);
}

static glpgp_status failing_energy(glpgp_backend *b, const glpgp_vec *x, double inv4e2, glpgp_vec *work)
{
    (void)b;
    (void)x;
    (void)inv4e2;
    (void)work;
    return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "injected failure of the first oscillator");
}

static glpgp_status failing_assembly(glpgp_backend *b, int kind, double h)
{
    (void)b;
    (void)kind;
    (void)h;
    return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "injected failure of the second oscillator");
}

static glpgp_status make_clone(glpgp_backend *b, glpgp_backend **out)
{
    (void)b;
    atomic_fetch_add(&clones, 1);
    *out = NULL;
    if (clone_mode == 2) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "injected: no memory for a clone");
    GLPGP_CHECK(glpgp_backend_create_reference(out));
    if (clone_mode == 1) (*out)->ops = &failing_ops;
    if (clone_mode == 3) (*out)->ops = &counting_ops;
    return GLPGP_OK;
}

static glpgp_result *solve(const glpgp_mesh *m, const glpgp_backend_ops *ops, int mode, glpgp_status *st)
{
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!b) return NULL;
    if (ops) b->ops = ops;
    glpgp_options o;
    glpgp_options_default(&o);
    o.oscillators = mode;
    /* the uniform size (this coarse disk at its default size would get the
     * chord budget's smaller size and a resolution warning besides) */
    o.size_chord_area = o.size_chord_depth = 0.0;
    *st = glpgp_solve(m, b, &o, &r);
    glpgp_backend_destroy(&b);
    return r;
}

/* a and b the same result bit for bit */
static void check_same(const glpgp_mesh *m, const glpgp_result *a, const glpgp_result *b)
{
    const size_t n2 = (size_t)2 * m->nv;
    for (int k = 0; k < 2; k++) {
        CHECK(!memcmp(a->osc[k].z, b->osc[k].z, n2 * sizeof(double)));
        CHECK(!memcmp(a->osc[k].dirichlet, b->osc[k].dirichlet, (size_t)m->nv));
        CHECK(a->osc[k].energy == b->osc[k].energy);
        CHECK(a->osc[k].newton_iterations == b->osc[k].newton_iterations);
        CHECK(a->osc[k].cg_iterations == b->osc[k].cg_iterations);
        CHECK(a->osc[k].plus == b->osc[k].plus && a->osc[k].minus == b->osc[k].minus);
    }
    CHECK(a->host_round_trips == b->host_round_trips);
    CHECK(a->kernel_launches == b->kernel_launches);
}

static void test_identical(const glpgp_mesh *m)
{
    glpgp_status s1, s2;
    glpgp_result *c = solve(m, NULL, GLPGP_OSC_CONCURRENT, &s1);
    glpgp_result *q = solve(m, NULL, GLPGP_OSC_SEQUENTIAL, &s2);
    CHECK(s1 == GLPGP_OK && s2 == GLPGP_OK);
    if (!c || !q) return;
    printf("identical: concurrent %.3f s (u %.3f, v %.3f), sequential %.3f s; singular u +%d/-%d, v +%d/-%d; "
           "round trips %ld / %ld\n",
           c->seconds_total, c->osc[0].seconds, c->osc[1].seconds, q->seconds_total, c->osc[0].plus,
           c->osc[0].minus, c->osc[1].plus, c->osc[1].minus, c->host_round_trips, q->host_round_trips);
    CHECK(c->concurrent == 1 && q->concurrent == 0);
    CHECK(c->osc[0].plus + c->osc[1].plus > 0); /* a vortex state: a solve that could differ */
    check_same(m, c, q);
    glpgp_result *a = solve(m, NULL, GLPGP_OSC_AUTO, &s1);
    CHECK(s1 == GLPGP_OK);
    if (a) {
        printf("identical: auto ran %s\n", a->concurrent ? "concurrently" : "one after the other");
        check_same(m, a, q);
    }
    glpgp_result_destroy(&a);
    glpgp_result_destroy(&c);
    glpgp_result_destroy(&q);
}

static void test_worker_error(const glpgp_mesh *m)
{
    clone_mode = 1;
    glpgp_status st;
    glpgp_error_clear();
    glpgp_result *r = solve(m, &parent_ops, GLPGP_OSC_CONCURRENT, &st);
    printf("worker error: status %d (%s), message '%s'\n", (int)st, glpgp_status_name(st), glpgp_error_message());
    CHECK(st == GLPGP_ERR_NUMERIC && r == NULL);
    CHECK(glpgp_error_status() == GLPGP_ERR_NUMERIC);
    CHECK(strstr(glpgp_error_message(), "injected failure of the second oscillator") != NULL);
    glpgp_error_clear();
    glpgp_result_destroy(&r);
}

static void test_u_fails(const glpgp_mesh *m)
{
    /* a whole v solve on a counting clone: its gradient evaluations */
    clone_mode = 3;
    glpgp_status st;
    atomic_store(&gradients, 0);
    glpgp_result *r = solve(m, &parent_ops, GLPGP_OSC_CONCURRENT, &st);
    const int whole = atomic_load(&gradients);
    CHECK(st == GLPGP_OK && r && r->concurrent);
    glpgp_result_destroy(&r);
    /* u fails at its first energy: v stops at its next Newton step */
    atomic_store(&gradients, 0);
    glpgp_error_clear();
    r = solve(m, &u_fails_ops, GLPGP_OSC_CONCURRENT, &st);
    const int stopped = atomic_load(&gradients);
    printf("u fails first: status %d, message '%s'; v's gradients %d (a whole v solve: %d)\n", (int)st,
           glpgp_error_message(), stopped, whole);
    CHECK(st == GLPGP_ERR_NUMERIC && r == NULL);
    CHECK(strstr(glpgp_error_message(), "injected failure of the first oscillator") != NULL);
    CHECK(whole > 10 && stopped < whole / 2);
    glpgp_error_clear();
    glpgp_result_destroy(&r);
}

static void test_clone_failure(const glpgp_mesh *m, const glpgp_result *ref)
{
    clone_mode = 2;
    for (int mode = GLPGP_OSC_AUTO; mode <= GLPGP_OSC_CONCURRENT; mode += GLPGP_OSC_CONCURRENT) {
        glpgp_status st;
        atomic_store(&warnings, 0);
        atomic_store(&clones, 0);
        glpgp_result *r = solve(m, &parent_ops, mode, &st);
        printf("clone failure (%s): status %d, concurrent %d, %d clone attempt(s), %d warning(s)\n",
               mode == GLPGP_OSC_AUTO ? "auto" : "concurrent", (int)st, r ? r->concurrent : -1,
               atomic_load(&clones), atomic_load(&warnings));
        CHECK(st == GLPGP_OK && r != NULL);
        /* auto clones with two processors or more */
        CHECK(atomic_load(&clones) == (mode == GLPGP_OSC_AUTO && glpgp_cpu_count() < 2 ? 0 : 1));
        CHECK(atomic_load(&warnings) == (mode == GLPGP_OSC_CONCURRENT ? 1 : 0));
        if (r) {
            CHECK(r->concurrent == 0);
            check_same(m, r, ref);
        }
        glpgp_result_destroy(&r);
    }
}

static void test_no_clone(const glpgp_mesh *m, const glpgp_result *ref)
{
    glpgp_backend_ops noclone = parent_ops;
    noclone.clone = NULL;
    glpgp_status st;
    atomic_store(&warnings, 0);
    glpgp_result *r = solve(m, &noclone, GLPGP_OSC_CONCURRENT, &st);
    printf("no clone op: %d warning(s)\n", atomic_load(&warnings));
    CHECK(st == GLPGP_OK && r && r->concurrent == 0);
    CHECK(atomic_load(&warnings) == 1);
    if (r) check_same(m, r, ref);
    glpgp_result_destroy(&r);
    /* sequential: no clone attempted */
    clone_mode = 0;
    atomic_store(&clones, 0);
    r = solve(m, &parent_ops, GLPGP_OSC_SEQUENTIAL, &st);
    CHECK(st == GLPGP_OK && atomic_load(&clones) == 0);
    glpgp_result_destroy(&r);
}

int main(int argc, char **argv)
{
    const char *only = argc > 1 ? argv[1] : "";
    glpgp_log_set_callback(count_warnings, NULL);
    glpgp_backend *b = NULL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!b) TEST_DONE();
    parent_ops = *b->ops;
    parent_ops.clone = make_clone;
    failing_ops = *b->ops;
    failing_ops.assemble_quadratic = failing_assembly;
    u_fails_ops = parent_ops;
    u_fails_ops.energy = failing_energy;
    counting_ops = *b->ops;
    ref_gradient = b->ops->gradient;
    counting_ops.gradient = counting_gradient;
    glpgp_backend_destroy(&b);
    /* a disk at 10 mean edges per period: vortices in u and v */
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 3000, &m));
    if (!m) TEST_DONE();
    glpgp_status st;
    glpgp_result *ref = solve(m, NULL, GLPGP_OSC_SEQUENTIAL, &st);
    CHECK(st == GLPGP_OK && ref);
    if (!*only || !strcmp(only, "identical")) test_identical(m);
    if (!*only || !strcmp(only, "worker")) test_worker_error(m);
    if (!*only || !strcmp(only, "ufails")) test_u_fails(m);
    if (ref && (!*only || !strcmp(only, "clone"))) test_clone_failure(m, ref);
    if (ref && (!*only || !strcmp(only, "noclone"))) test_no_clone(m, ref);
    glpgp_result_destroy(&ref);
    glpgp_mesh_destroy(&m);
    glpgp_log_set_callback(NULL, NULL);
    TEST_DONE();
}
