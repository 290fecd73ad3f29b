/* core/timers.c: the names and sums of the per-phase time accounts
 * (glpgp/timers.h). */
#include "glpgp/timers.h"

#include <stddef.h>

static const char *const keys[GLPGP_TM_COUNT] = {
    "other",       "read",           "refine",        "program_build",  "renumber",    "pattern",
    "upload",      "size_field",     "guiding_field", "structure",      "numeric_setup", "assembly",
    "linear_solves", "energies",     "summary",       "extraction",     "image",       "out_result",
    "out_quads",   "out_image"};

static const char *const labels[GLPGP_TM_COUNT] = {
    "other",       "read",           "refine",        "program build",  "renumber",    "pattern",
    "upload",      "size field",     "guiding field", "multigrid structure", "numeric setup", "assembly",
    "linear solves", "energies",     "summary",       "extraction",     "picture",     "write result",
    "write quads", "write picture"};

const char *glpgp_timer_key(int id) { return id >= 0 && id < GLPGP_TM_COUNT ? keys[id] : "?"; }

const char *glpgp_timer_label(int id) { return id >= 0 && id < GLPGP_TM_COUNT ? labels[id] : "?"; }

int glpgp_timer_in_solve(int id)
{
    return id == GLPGP_TM_OTHER || (id >= GLPGP_TM_RENUMBER && id <= GLPGP_TM_SUMMARY);
}

void glpgp_timers_add(glpgp_timers *a, const glpgp_timers *b)
{
    for (int i = 0; i < GLPGP_TM_COUNT; i++) {
        a->s[i] += b->s[i];
        a->wait[i] += b->wait[i];
    }
}

void glpgp_timers_sub(glpgp_timers *a, const glpgp_timers *b)
{
    for (int i = 0; i < GLPGP_TM_COUNT; i++) {
        a->s[i] -= b->s[i];
        a->wait[i] -= b->wait[i];
    }
}

double glpgp_timers_total(const glpgp_timers *t, double *wait)
{
    double s = 0.0, w = 0.0;
    for (int i = 0; i < GLPGP_TM_COUNT; i++) {
        s += t->s[i];
        w += t->wait[i];
    }
    if (wait) *wait = w;
    return s;
}
