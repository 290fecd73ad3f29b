/* glpgp/cross.h: Ginzburg-Landau cross fields (the paper's reference [1],
 * Beaufort et al. 2017) and their singularities.
 *
 * A cross (four directions alpha + k pi/2) is stored as w = exp(4 i alpha)
 * per vertex. The field minimises
 *     F_eps(w) = 1/2 int |grad w|^2 + 1/(4 eps^2) int (|w|^2 - 1)^2
 * with w fixed on every boundary vertex to the boundary-aligned cross
 * (glpgp_cross_boundary), eps decreasing: this is the oscillators' energy with
 * W = 0 (omega = 0) and another Dirichlet set, solved by the same Newton / CG /
 * continuation engine and kernels (solver/crossfield.c).
 *
 * Singularities: a triangle where w winds by +-1 (sum of the principal
 * arg(w_b / w_a) over its edges / 2 pi) carries a cross-field index of +-1/4;
 * adjacent singular triangles of one sign are merged into one singularity
 * whose index is their sum (+-1/2 ...). Indices are stored as integers in
 * quarter units (index4 = 4 * index).
 *
 * Poincare-Hopf with corners (glpgp_cross_expected_index4, derived in
 * docs/numerics.md "Cross fields"): for a planar domain whose boundary loops
 * turn by +-2 pi,
 *     sum of interior indices = chi - sum over corners c of (2 - n_c) / 4,
 *     chi = (outer loops) - (holes),  n_c = round(interior angle / (pi/2)),
 * a smooth boundary point having n_c = 2 (no share). Layer: solver. */
#ifndef GLPGP_CROSS_H
#define GLPGP_CROSS_H

#include "glpgp/backend.h"
#include "glpgp/mesh.h"
#include "glpgp/result.h"

#ifdef __cplusplus
extern "C" {
#endif

struct glpgp_options;

#define GLPGP_CROSS_MAX_LEVELS GLPGP_MAX_LEVELS

/* One singularity (a connected group of same-sign singular triangles). */
typedef struct glpgp_cross_sing {
    double x, y;  /* position: area-weighted mean of the triangles' zeros of the
                     linear interpolant of w (its centroid when it has none inside) */
    double z;     /* a surface's: the point is (x, y, z) (glpgp/surfsolve.h); 0 in the plane */
    int index4;   /* index times 4: +1 = +1/4, -2 = -1/2 ... */
    int ntri;     /* singular triangles merged into it */
    int tri;      /* one of them (the first in triangle order) */
} glpgp_cross_sing;

typedef struct glpgp_cross_result {
    int nv, nt;
    double *w;              /* 2*nv: w = exp(4 i alpha) (|w| ~ 1 away from singularities) */
    signed char *winding;   /* nt: winding of w around each triangle, -1, 0, +1 */
    int nsing;
    glpgp_cross_sing *sing; /* nsing singularities, ordered by first triangle */
    int index4_sum;         /* sum of the singularities' index4 (= sum of windings) */
    int index4_expected;    /* Poincare-Hopf with corners, from the boundary geometry */
    double zabs_median;     /* median |w| */
    int nlevels;
    glpgp_level_stats level[GLPGP_CROSS_MAX_LEVELS]; /* eps, newton, cg, grad0, grad, energy,
                                                        median_zabs, fallbacks, capped, rtol */
    int newton_iterations, capped_levels;
    long cg_iterations;     /* including the initial harmonic solve */
    double seconds;
    int solved_nv, solved_nt; /* the mesh it was solved on: nv, nt, or a refined surface's input
                                 (--cross-mesh input: carried over, glpgp_surface_cross_transfer) */
    int polished;           /* --cross-mesh polish: the last level (level[nlevels - 1]) was on nv */
} glpgp_cross_result;

/* A zeroed cross result for nv vertices, nt triangles (w, winding allocated). */
glpgp_status glpgp_cross_result_create(int nv, int nt, glpgp_cross_result **out);
void glpgp_cross_result_destroy(glpgp_cross_result **c);

/* Boundary-aligned crosses: for each boundary vertex, each adjacent boundary
 * edge with tangent angle theta gives exp(4 i theta) (the same for the normal:
 * a cross contains both); the vertex gets the mean of its two edges' values
 * along the shorter arc, w = exp(4 i theta_prev + i d / 2) with
 * d = principal arg(exp(4 i (theta_next - theta_prev))) in (-pi, pi]. At a
 * corner whose turn is a multiple of pi/2 (right angles, reentrant right
 * angles) both edges agree and w is exact; at other (sharp or obtuse) corners
 * w is the bisecting cross; at a turn of exactly 45 degrees mod 90 (the two
 * crosses opposite) the +pi/2 side is taken. Interior vertices get 0.
 * w: 2*nv. */
void glpgp_cross_boundary(const glpgp_mesh *m, double *w);

/* Poincare-Hopf with corners, in quarter units: sum over boundary loops of
 * 4 * turn_l / (2 pi) - sum over the loop's vertices of k_v, where k_v =
 * round(tau_v / (pi/2)) for the turning angle tau_v in (-pi, pi] at v
 * (k_v = 2 - n_v). Equals the sum of the triangle windings of any w that
 * holds glpgp_cross_boundary's values (discrete Stokes), and 4 chi - sum of
 * (2 - n_c) over the corners. */
int glpgp_cross_expected_index4(const glpgp_mesh *m);

/* Windings per triangle of c->w, the singularities (merged, with positions)
 * and their index sum, the expected sum and the median |w|. */
glpgp_status glpgp_cross_analyze(const glpgp_mesh *m, glpgp_cross_result *c);

/* Unit vector field U (2*nv) from the crosses: alpha = arg(w) / 4, the branch
 * (alpha + k pi/2) at each vertex chosen by a breadth-first walk over the
 * mesh edges from the vertex nearest the area centroid, closest to the
 * neighbour it was reached from. Without singularities (and with index sums
 * that are multiples of 4 around holes) U is smooth; otherwise U turns by
 * 90 degrees across cuts. Returns the number of mesh edges across which U
 * turns by more than 45 degrees (the cuts; 0 for a smooth field). */
int glpgp_cross_to_vector(const glpgp_mesh *m, const double *w, double *u);

/* Solve the cross field on mesh m with backend b (set up for m; its field,
 * Dirichlet set and matrices are overwritten): harmonic initial guess from
 * the boundary crosses (one linear solve, then |w| normalised to 1), then
 * Newton levels at eps = cross_eps0 * D, times eps_ratio, down to
 * cross_eps_min mean edges (D = bounding-box diagonal), each to cross_rtol,
 * then glpgp_cross_analyze. */
glpgp_status glpgp_cross_solve(const glpgp_mesh *m, glpgp_backend *b, const struct glpgp_options *o,
                               glpgp_cross_result **out);

/* The guiding field of --field cross: glpgp_cross_solve, then U =
 * glpgp_cross_to_vector (a warning line when the field has singularities or
 * U has cuts: the oscillators then see U turn by 90 degrees across them).
 * *keep (may be NULL) receives the cross result (else it is freed);
 * *cg_iterations is increased by its CG iterations. */
glpgp_status glpgp_cross_guiding_field(const glpgp_mesh *m, glpgp_backend *b,
                                       const struct glpgp_options *o, glpgp_cross_result **keep,
                                       double *u, long *cg_iterations);

/* The eps levels of the cross field (<= GLPGP_CROSS_MAX_LEVELS), as
 * glpgp_eps_schedule but from cross_eps0 * diagonal to cross_eps_min mean edges. */
int glpgp_cross_eps_schedule(const glpgp_mesh *m, const struct glpgp_options *o,
                             double eps[GLPGP_CROSS_MAX_LEVELS]);

/* ---- coupled oscillators across the branch cuts (issue 14, item 3;
 * solver/coupled.c, docs/numerics.md "Coupled oscillators") -----------------
 * Vertex i has the representative U_i (glpgp_cross_to_vector) and two nodes,
 * 2i (z_u, along U_i) and 2i + 1 (z_v, along V_i = U_i rotated by +90 deg).
 * Triangle t's frame is its corner 0's representative; corner a has the
 * quarter-turn count r_a = glpgp_cross_turn(U_{corner 0}, U_a). */

/* Quarter turns r in 0..3 with rot^r(U_b) closest to U_a (rot: +90 degrees). */
int glpgp_cross_turn(const double *ua, const double *ub);

/* The frame oscillator k (0: u, 1: v) at a corner with quarter-turn count r
 * is the node family *family (0: z_u, 1: z_v) of that vertex, conjugated when
 * *conj:  r = 0: (z_u, z_v), 1: (z_v, conj z_u), 2: (conj z_u, conj z_v),
 * 3: (conj z_v, z_u). */
void glpgp_cross_frame_map(int r, int k, int *family, int *conj);

/* out (2 doubles) <- the frame oscillator k at a corner with count r, from
 * that vertex's own (z_u, z_v) (2 doubles each). */
void glpgp_coupled_frame_value(int r, int k, const double *zu, const double *zv, double *out);

/* The coupled system of mesh m and representatives u (2*nv): a virtual mesh
 * of 2 nv nodes (node 2i + s at x_i) and 2 nt triangles (2t + s: the frame
 * oscillator s of triangle t, on the nodes that carry it), its block layout
 * with the matching attached (sys->cconj, sys->cfield), and match[3t + a] =
 * r_a. Vectors of the coupled solve hold 4 nv doubles: (Re, Im) of node
 * 2i + s at 4i + 2s. */
typedef struct glpgp_coupled {
    int nv, nt;               /* of the real mesh */
    glpgp_mesh vm;            /* virtual mesh: nv, nt, xy, tri set (no boundary data) */
    glpgp_system *sys;        /* layout of vm with cconj, cfield */
    unsigned char *match;     /* 3 * nt: r_a per corner */
} glpgp_coupled;

glpgp_status glpgp_coupled_create(const glpgp_mesh *m, const double *u, glpgp_coupled **out);
void glpgp_coupled_destroy(glpgp_coupled **c);

/* Per-node unit fields of the coupled system (4 nv): U_i at node 2i, V_i at
 * node 2i + 1 (each node's own frame; used for Dirichlet sets and the
 * multigrid's plane-wave frames). */
void glpgp_coupled_node_field(const double *u, int nv, double *w);

/* Windings of the frame oscillator k per triangle (sing: nt, -1, 0, +1) from
 * the per-vertex own-frame values zu, zv (2*nv each) and representatives u;
 * counts into *plus, *minus. */
void glpgp_coupled_windings(const glpgp_mesh *m, const double *u, const double *zu, const double *zv, int k,
                            signed char *sing, int *plus, int *minus);

/* Conformal size field of the cross field w (2*nv) for target size h
 * (--cross-size, docs/numerics.md "Coupled oscillators"): phi minimising
 * int |grad phi - R grad theta|^2, theta = arg(w)/4 per triangle, R the turn
 * by -90 degrees (so that U / s and V / s are curl-free where theta is
 * harmonic), by one linear solve on backend b (set up for m; its field,
 * Dirichlet set and matrices are overwritten); size (nv) <- h clamp(exp(phi
 * - phi_q), 1/c, 1), phi_q the q-quantile of phi over the vertices: q = 1,
 * c = inf unless o->cross_size is GLPGP_CROSS_SIZE_AUTO (then q =
 * o->cross_size_quantile, c = o->cross_size_ratio); at least size_min h and
 * min(h, size_resolution x the longest edge at the vertex). *cg_iterations is
 * increased by its CG iterations. */
glpgp_status glpgp_cross_conformal_size(const glpgp_mesh *m, glpgp_backend *b, const struct glpgp_options *o,
                                        const double *w, double h, double *size, long *cg_iterations);

#ifdef __cplusplus
}
#endif

#endif
