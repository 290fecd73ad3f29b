/* solver/backend.c: what the backend table needs beside its implementations:
 * destruction of any backend and the phase accounts every backend carries
 * (glpgp/backend.h, glpgp/timers.h). */
#include "glpgp/backend.h"
#include "glpgp/util.h"
#include "glpgp/internal/newton.h"

#include <stdlib.h>
#include <string.h>

void glpgp_backend_destroy(glpgp_backend **pb)
{
    if (!pb || !*pb) return;
    glpgp_backend *b = *pb;
    for (int k = 0; k < GLPGP_SCRATCH_VECTORS; k++)
        if (b->scratch[k] && b->ops && b->ops->vec_destroy) b->ops->vec_destroy(b, &b->scratch[k]);
    if ((*pb)->ops && (*pb)->ops->destroy) (*pb)->ops->destroy(*pb);
    free(*pb);
    *pb = NULL;
}

void glpgp_timer_reset(glpgp_backend *b)
{
    memset(&b->tm, 0, sizeof b->tm);
    b->tm_cur = GLPGP_TM_OTHER;
    b->tm_mark = glpgp_now();
}

/* book the time since the mark to the current phase */
static void book(glpgp_backend *b)
{
    const double t = glpgp_now();
    if (b->tm_mark > 0.0 && b->tm_cur >= 0 && b->tm_cur < GLPGP_TM_COUNT) b->tm.s[b->tm_cur] += t - b->tm_mark;
    b->tm_mark = t;
}

int glpgp_timer_enter(glpgp_backend *b, int id)
{
    const int prev = b->tm_cur;
    /* the fields' own solves stay theirs; their multigrid structure is the structure's */
    if ((prev == GLPGP_TM_FIELD || prev == GLPGP_TM_SIZE) && id != GLPGP_TM_STRUCTURE) return prev;
    book(b);
    b->tm_cur = id;
    return prev;
}

void glpgp_timer_leave(glpgp_backend *b, int prev)
{
    if (prev == b->tm_cur) return;
    book(b);
    b->tm_cur = prev;
}

void glpgp_backend_waited(glpgp_backend *b, double seconds)
{
    if (b->tm_cur >= 0 && b->tm_cur < GLPGP_TM_COUNT) b->tm.wait[b->tm_cur] += seconds;
}

void glpgp_timer_read(glpgp_backend *b, glpgp_timers *t)
{
    book(b);
    *t = b->tm;
}

int glpgp_amg_layout_same(const glpgp_amg_layout *a, const glpgp_amg_layout *b)
{
    if (!a->key || a->key != b->key || a->nlevels != b->nlevels || a->weight != b->weight || a->pre != b->pre ||
        a->post != b->post)
        return 0;
    for (int l = 0; l < a->nlevels; l++)
        if (a->lev[l].n != b->lev[l].n || a->lev[l].nnzb != b->lev[l].nnzb || a->kcycle[l] != b->kcycle[l]) return 0;
    return 1;
}

glpgp_status glpgp_backend_scratch(glpgp_backend *b, int k, size_t n, glpgp_vec **v)
{
    if (k < 0 || k >= GLPGP_SCRATCH_VECTORS) return GLPGP_FAIL(GLPGP_ERR_ARG, "scratch vector %d", k);
    if (b->scratch[k] && b->scratch_n[k] != n) b->ops->vec_destroy(b, &b->scratch[k]);
    if (!b->scratch[k]) {
        GLPGP_CHECK(b->ops->vec_create(b, n, &b->scratch[k]));
        b->scratch_n[k] = n;
    }
    *v = b->scratch[k];
    return GLPGP_OK;
}
