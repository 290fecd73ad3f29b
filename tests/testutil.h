/* testutil.h: the one header of the C tests: every public glpgp header, the
 * check macros (a failed check prints file:line and the expression, the test
 * exits 1 at TEST_DONE), a deterministic random generator and the solve ->
 * quads -> quality pipeline of the quad tests. */
#ifndef GLPGP_TESTUTIL_H
#define GLPGP_TESTUTIL_H

#include "glpgp/backends.h"
#include "glpgp/cross.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/phase.h"
#include "glpgp/quads.h"
#include "glpgp/result.h"
#include "glpgp/shapes.h"
#include "glpgp/solve.h"
#include "glpgp/status.h"
#include "glpgp/surface.h"
#include "glpgp/surfsolve.h"
#include "glpgp/system.h"
#include "glpgp/util.h"
#include "glpgp/version.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int tu_failures = 0;

#define CHECK(cond)                                                            \
    do {                                                                       \
        if (!(cond)) {                                                         \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            tu_failures++;                                                     \
        }                                                                      \
    } while (0)

/* |a - b| <= atol + rtol |b| */
#define CHECK_CLOSE(a, b, atol, rtol)                                          \
    do {                                                                       \
        double ca_ = (a), cb_ = (b);                                           \
        if (!(fabs(ca_ - cb_) <= (atol) + (rtol)*fabs(cb_))) {                 \
            fprintf(stderr, "%s:%d: CHECK_CLOSE failed: %s = %.17g vs %s = %.17g\n", \
                    __FILE__, __LINE__, #a, ca_, #b, cb_);                     \
            tu_failures++;                                                     \
        }                                                                      \
    } while (0)

#define CHECK_OK(call)                                                         \
    do {                                                                       \
        glpgp_status st_ = (call);                                             \
        if (st_ != GLPGP_OK) {                                                 \
            fprintf(stderr, "%s:%d: %s failed: %s\n", __FILE__, __LINE__, #call,  \
                    glpgp_error_message());                                    \
            glpgp_error_clear();                                               \
            tu_failures++;                                                     \
        }                                                                      \
    } while (0)

#define TEST_DONE()                                                            \
    do {                                                                       \
        if (tu_failures) {                                                     \
            fprintf(stderr, "%d check(s) failed\n", tu_failures);             \
            return 1;                                                          \
        }                                                                      \
        printf("all checks passed\n");                                         \
        return 0;                                                              \
    } while (0)

/* Deterministic uniform random in [0,1) (xorshift64*). */
static unsigned long long tu_rng = 88172645463325252ULL;
static inline double tu_rand(void)
{
    tu_rng ^= tu_rng >> 12;
    tu_rng ^= tu_rng << 25;
    tu_rng ^= tu_rng >> 27;
    return (double)((tu_rng * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* The quad tests' pipeline on the reference backend: m solved with o, its
 * quads extracted at the period h and measured into *qq. Returns 1 when a
 * quad mesh came out (then *qq is set), 0 otherwise (a failed step is a
 * failed check). */
static inline int tu_solve_quads(const glpgp_mesh *m, const glpgp_options *o, double h, glpgp_quad_quality *qq)
{
    glpgp_backend *be = NULL;
    glpgp_result *r = NULL;
    glpgp_quadmesh *q = NULL;
    CHECK_OK(glpgp_backend_create_reference(&be));
    if (be) CHECK_OK(glpgp_solve(m, be, o, &r));
    if (r) CHECK_OK(glpgp_quads_build(m, r, NULL, &q, &h));
    if (q) CHECK_OK(glpgp_quads_quality(q, m, h, qq));
    const int made = q != NULL;
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&be);
    return made;
}

#endif
