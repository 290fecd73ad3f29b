/* io/names.h: the names the writers give to option values (method,
 * energy, Newton variant, field, initial guess). Private to the io layer. */
#ifndef GLPGP_IO_NAMES_H
#define GLPGP_IO_NAMES_H

#include "glpgp/solve.h"

static inline const char *method_name(int v)
{
    return v == GLPGP_METHOD_PGP ? "pgp" : v == GLPGP_METHOD_GL ? "gl" : "unknown";
}
static inline const char *energy_name(int v)
{
    return v == GLPGP_ELEM_P1 ? "p1" : v == GLPGP_ELEM_TRANSPORT ? "transport" : "unknown";
}
static inline const char *hess_name(int v)
{
    return v == GLPGP_HESS_PAPER       ? "paper"
           : v == GLPGP_HESS_PROJECTED ? "projected"
           : v == GLPGP_HESS_EXACT     ? "exact"
           : v == GLPGP_HESS_MIXED     ? "mixed"
                                       : "unknown";
}
static inline const char *field_name(int v)
{
    return v == GLPGP_FIELD_BOUNDARY ? "boundary"
           : v == GLPGP_FIELD_RADIAL ? "radial"
           : v == GLPGP_FIELD_FILE   ? "file"
           : v == GLPGP_FIELD_CROSS  ? "cross"
                                     : "unknown";
}
static inline const char *init_name(int v)
{
    return v == GLPGP_INIT_NAIVE ? "naive" : v == GLPGP_INIT_ONE ? "one" : "unknown";
}

#endif
