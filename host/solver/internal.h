/* solver/internal.h: what the solver's files share and nobody else sees:
 * one Newton level at fixed eps (newton.c), used by the continuation. */
#ifndef GLPGP_SOLVER_INTERNAL_H
#define GLPGP_SOLVER_INTERNAL_H

#include "glpgp/solve.h"

/* Name of oscillator k ("u" or "v") for messages. */
const char *glpgp_osc_name(int k);

/* One Newton level: x <- argmin E + P_eps from the state's x, modified Newton
 * steps until |g| <= rtol |g_0|, the cap o->newton_max (ls->capped), or no
 * descent. ls receives eps, counts, gradient norms and the energy. */
glpgp_status glpgp_newton_level(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                                int k, double eps, double rtol, glpgp_level_stats *ls);

#endif
