/* glpgp/kinds.h: the numeric constants shared by the host and the OpenCL
 * kernels: pi, the element kinds of the quadratic form and the penalty
 * Hessian variants. Plain #defines only: this header is also compiled as
 * OpenCL C (kernels/embed.cmake puts it in front of kernels/element.h).
 * Layer: core. */
#ifndef GLPGP_KINDS_H
#define GLPGP_KINDS_H

#define GLPGP_PI 3.14159265358979323846

/* Element kinds of the quadratic form. */
#define GLPGP_ELEM_P1 0        /* P1 finite elements of E */
#define GLPGP_ELEM_TRANSPORT 1 /* edge-transport form (cotan weights) */
#define GLPGP_ELEM_LAPLACE 2   /* plain cotan Laplacian (S only), for harmonic fields */

/* Penalty Hessian variants. */
#define GLPGP_HESS_PAPER 0
#define GLPGP_HESS_PROJECTED 1
#define GLPGP_HESS_EXACT 2
#define GLPGP_HESS_MIXED 3 /* exact where |z|^2 >= 1/2, projected in vortex cores */

#endif
