/* quads/qcut_impl.h: what the cut mesher's files share (qcut.c: cuts, holes,
 * the driver; qcut_small.c: the small loops' splits, kites and rings): the
 * mesher's state, a piece, and the functions each calls in the other. Not
 * installed. */
#ifndef GLPGP_QCUT_IMPL_H
#define GLPGP_QCUT_IMPL_H

#include "qcut.h"
#include "check.h"
#include "geom.h"

#define QC_PI 3.14159265358979323846

typedef struct qc_piece {
    ivec outer;
    int nh;
    ivec *holes;
} qc_piece;

typedef struct qc {
    dvec *xy;
    ivec *quads;
    qcut_stats *stats;
    double h;
    int ns;
    double *src; /* size sources: x, y, s */
    bgrid G;
    int *cand, ncap;
    long budget; /* cuts left */
    double work, max_work; /* the cut searches' points squared so far, and their bound (0: none) */
    qc_piece *stack;
    int nstack, capstack;
} qc;

/* A small loop's best split: of the loop L (n <= GLPGP_POLY_SPLIT_MAX) and its
 * scaled Jacobian; *how: 0 diagonals (out, nq), 1 a center (o, x, y). */
typedef struct split {
    double sj;
    int how, nq, o;
    double x, y;
    int out[4 * GLPGP_POLY_SPLIT_MAX];
} split;

static inline const double *P(const qc *c, int id) { return c->xy->p + 2 * id; }

double glpgp_qc_center_split(const double *xy, const int *p, int n, int *ob, double *xb, double *yb);
double glpgp_qc_loop_angle(const qc *c, const ivec *L, int i);
int glpgp_qc_visible(const qc *c, const qc_piece *pc, int ia, int ib);
void glpgp_qc_best_split(const qc *c, const ivec *L, split *s);
glpgp_status glpgp_qc_emit(qc *c, const int *q);
glpgp_status glpgp_qc_emit_split(qc *c, const ivec *L, const split *s);
glpgp_status glpgp_qc_kite_cut(qc *c, qc_piece *pc, int *done);
glpgp_status glpgp_qc_ring_quad(qc *c, const ivec *L, int *done);

#endif
