/* solver/internal.h: what the solver's files share and nobody else sees:
 * one Newton level at fixed eps (newton.c), used by the continuation. */
#ifndef GLPGP_SOLVER_INTERNAL_H
#define GLPGP_SOLVER_INTERNAL_H

#include "glpgp/solve.h"

/* Name of oscillator k ("u", "v", or "cross" for k = 2: the cross field) for messages. */
const char *glpgp_osc_name(int k);

/* One Newton level: x <- argmin E + P_eps from the state's x, modified Newton
 * steps until |g| <= rtol |g_0|, the cap o->newton_max (ls->capped), or no
 * descent. ls receives eps, counts, gradient norms and the energy. */
glpgp_status glpgp_newton_level(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                                int k, double eps, double rtol, glpgp_level_stats *ls);

/* The multigrid preconditioner for one system when o->precond asks for it:
 * glpgp_amg_create, or NULL after one warning line naming `what` and the
 * reason (the caller then uses Jacobi-PCG). NULL without a message when
 * o->precond is Jacobi. */
glpgp_amg *glpgp_amg_try_create(glpgp_backend *b, const glpgp_options *o, const unsigned char *dir,
                                const double *w, double h, const char *what);

/* glpgp_amg_update; on failure one warning line naming `what` and 0 (the
 * caller stops using a), else 1. */
int glpgp_amg_try_update(glpgp_amg *a, const glpgp_vec *x, const char *what);

/* One INFO line about a non-uniform size field (solver/sizefield.c). */
void glpgp_size_log(const glpgp_mesh *m, const double *size, double h);

#endif
