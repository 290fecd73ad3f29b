/* glpgp/internal/probe.h: the cross-check engine's exact read-back of a
 * backend's matrices through its ops table (backends/probe.c), for
 * crosscheck and the benchmark. Internal: not installed. Layer: backends. */
#ifndef GLPGP_INTERNAL_PROBE_H
#define GLPGP_INTERNAL_PROBE_H

#include "glpgp/backend.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which matrix glpgp_probe_matrix reads: GLPGP_MAT_QUAD, GLPGP_MAT_NEWTON
 * (4*nnzb values, block-CSR order) or GLPGP_PROBE_DINV (4*nv values). */
#define GLPGP_PROBE_DINV 2
/* Recover every value of a matrix of backend b (setup done) exactly, using
 * only its ops: vertices get a distance-2 colouring (no two vertices of one
 * colour share a row), so spmv of the indicator vector of colour c and
 * component d returns column d of every block whose column has colour c
 * (2 spmvs per colour). DINV comes from cg_precond on the two unit fields
 * (it overwrites s[GLPGP_S_DOT] and s[GLPGP_S_RR]). Products with 0 and 1
 * are exact, so the values are bit-exact. */
glpgp_status glpgp_probe_matrix(glpgp_backend *b, int which, double *vals);

#ifdef __cplusplus
}
#endif

#endif
