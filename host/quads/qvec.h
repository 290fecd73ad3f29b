/* quads/qvec.h: the quad layer's short names for the core's growable int
 * and double arrays (glpgp/internal/vec.h), used by its builders (repair,
 * region loops, the cut mesher). Internal. */
#ifndef GLPGP_QUADS_QVEC_H
#define GLPGP_QUADS_QVEC_H

#include "glpgp/internal/vec.h"

typedef glpgp_dvec dvec;
typedef glpgp_ivec ivec;
#define dpush glpgp_dvec_push
#define ipush glpgp_ivec_push
#define ivec_free glpgp_ivec_free
#define dvec_free glpgp_dvec_free

#endif
