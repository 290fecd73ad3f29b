/* glpgp/surfsolve.h: the GL-PGP pipeline on a triangulated surface (issue
 * 28; the mesh: glpgp/surface.h): sharp features and boundary constraints,
 * the Ginzburg-Landau cross field with the discrete connection and its
 * indices, the representatives U in the vertices' frames, the oscillator
 * system coupled across each triangle's matching in the triangle's own
 * plane, and the local size from curvature and feature spacing. glpgp_solve
 * (glpgp/solve.h) takes this path for a surface. Derivations and
 * measurements: host/README.md "Surfaces". Layer: solver.
 *
 * Every per-vertex angle and complex number is in that vertex's frame
 * (glpgp/surface.h): the cross w_i = exp(4 i alpha_i), the representative
 * U_i = (cos, sin) of a direction. A vertex quantity enters triangle t
 * turned by the corner's rotation phi_{t,a}: a cross by exp(4 i phi), a
 * direction by exp(i phi) (kernels/coupled_rows.h: crot, cfield). */
#ifndef GLPGP_SURFSOLVE_H
#define GLPGP_SURFSOLVE_H

#include "glpgp/cross.h"
#include "glpgp/solve.h"
#include "glpgp/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Alignment constraints of a surface: its boundary edges and its sharp
 * features (interior edges whose dihedral angle exceeds feature_angle).
 * A vertex's cross is fixed (Dirichlet) where the constraint edges give it
 * one: on the boundary from its two boundary edges, inside where exactly
 * two feature edges meet (a crease passing through), as the mean of the two
 * edges' crosses along the shorter arc, w = exp(i (4 a1 + d / 2)), d =
 * principal(4 (a2 - a1)) (glpgp_cross_boundary's rule: exact where the
 * edges turn by a multiple of 90 degrees). Vertices where one or three and
 * more feature edges meet (a crease's end, a cube's corner) stay free: the
 * cross field places the singularity a corner needs near them. */
typedef struct glpgp_surface_constraints {
    int nv, nt;
    unsigned char *feature; /* 3 nt: half-edge on a sharp feature (both of an edge) */
    int nfeatures;          /* undirected feature edges */
    unsigned char *fixed;   /* nv: the cross is fixed */
    int nfixed;
    double *w0;             /* 2 nv: the fixed crosses (0 where free) */
    int *cptr;              /* nv + 1: vertex i's constraint edges are */
    double *cangle;         /*   cangle[cptr[i] .. cptr[i+1]): their angles in i's frame */
    double rim_scale;       /* the boundary's crosses are at this scale (0: its edges'; glpgp_surface_constraints_rims) */
} glpgp_surface_constraints;

glpgp_status glpgp_surface_constraints_create(const glpgp_mesh *m, double feature_deg,
                                              glpgp_surface_constraints **out);
void glpgp_surface_constraints_destroy(glpgp_surface_constraints **c);

/* The boundary's crosses seen at the scale of the mesh to be made. A plain
 * boundary vertex's two constraint edges become the chords from the rim
 * point an arc length `scale` behind it and to the one `scale` ahead (its
 * cross their mean by the rule above): a rim whose teeth are finer than the
 * scale (a scan's hole, triangles cut along a curve) gets the crosses of the
 * curve it follows, where its edges' crosses alternate tooth by tooth. The
 * chords stop at the rim's corners at that scale (a turn of 60 degrees or
 * more, glpgp_surface_rim_turns, the largest within `scale` of it), so
 * the sides next to a corner keep their own direction; a vertex where a
 * feature edge meets the rim is a corner and keeps its edges. Both chords
 * are at most a quarter of the loop. scale 0 changes nothing. Sets
 * c->rim_scale. */
glpgp_status glpgp_surface_constraints_rims(const glpgp_mesh *m, double scale, glpgp_surface_constraints *c);

/* The scale of the boundary's crosses for the target size h and the
 * option's fraction f (glpgp_options.rim_scale): f h, and at least
 * GLPGP_RIM_EDGES of the rim's mean edges (those of the mesh m was refined
 * from, m->surf->origin, where it kept it): a rim is read no finer than its
 * own sampling. 0 for f = 0 or without a boundary. The extraction reads the
 * rim's corners at GLPGP_RIM_SCALE h. */
#define GLPGP_RIM_SCALE 0.5
#define GLPGP_RIM_EDGES 3.0
double glpgp_surface_rim_scale(const glpgp_mesh *m, double f, double h);

/* turn (nv) <- each boundary vertex's turn at the scale (radians): the angle
 * between the rim's mean points (each over an arc of length `scale`) an arc
 * length `scale` behind it, at it and ahead of it; teeth finer than the
 * scale do not turn it. HUGE_VAL on a loop too short for the scale (or
 * with scale 0), 0 inside. */
glpgp_status glpgp_surface_rim_turns(const glpgp_mesh *m, double scale, double *turn);

/* corner (nv) <- the boundary's corners at the scale: the vertices whose
 * turn there (glpgp_surface_rim_turns) is min_turn (radians) or more, the
 * most within `scale` of them along the loop; every vertex of a loop too
 * short for the scale (or with scale 0); 0 inside. */
glpgp_status glpgp_surface_rim_corners(const glpgp_mesh *m, double scale, double min_turn, unsigned char *corner);

/* mass (nv) <- each vertex's third of its triangles' areas (the lumped mass). */
void glpgp_surface_lumped_mass(const glpgp_mesh *m, double *mass);

/* Cross-field windings with the connection: index4 of triangle t = (sum over
 * its half-edges h = (a -> b) of principal arg(w_b / (exp(4 i rho_h) w_a))
 * + 4 Omega_t) / (2 pi), an integer by construction; each interior edge's
 * two terms are exact negatives, so the sum over all triangles is the
 * boundary's share plus 4 sum Omega_t / (2 pi): 4 chi on a closed surface
 * (host/README.md "Surfaces"). wind (nt, may be NULL) <- -1, 0, +1 (a
 * larger |index4| is clamped there but counted in full in *plus / *minus). */
void glpgp_surface_cross_windings(const glpgp_mesh *m, const double *w, signed char *wind, int *plus, int *minus);

/* Poincare-Hopf on a surface, in quarters: 4 chi - sum over the boundary
 * vertices of k_v = round(tau_v / (pi/2)), tau_v = principal(pi - Theta_v)
 * the boundary's turn at v (the planar corner terms; 4 chi on a closed
 * surface whatever its features). */
int glpgp_surface_expected_index4(const glpgp_mesh *m);

/* The index sum, in quarters, that the crosses w on the boundary imply
 * (their terms along the boundary edges and 4 sum Omega_t over 2 pi: the
 * interior edges' terms cancel whatever the field inside).
 * glpgp_surface_expected_index4 where they are the boundary edges' own
 * crosses; with crosses at a scale (glpgp_surface_constraints_rims) the one
 * to compare the field's sum with. */
int glpgp_surface_boundary_index4(const glpgp_mesh *m, const double *w);

/* A unit field transported along a breadth-first tree from each
 * component's first vertex: z_j = z_i exp(i mult rho_{i->j}) (mult 4:
 * crosses, 1: directions), z = 1 at the roots. Locally parallel; the
 * holonomy collects where the tree's branches meet. z: 2 nv. */
void glpgp_surface_transport(const glpgp_mesh *m, int mult, double *z);

/* The cross field's system on the surface: the mesh's layout with, per
 * corner, the triangle's own plane (ctxy) and the turn exp(4 i phi) of the
 * vertex's cross into the triangle's frame (crot); no conjugation, zero
 * frame field (the P1 element is then the connection Laplacian). */
glpgp_status glpgp_surface_cross_system(const glpgp_mesh *m, glpgp_system **out);

/* The Ginzburg-Landau cross field of a surface on backend b (set up here
 * with glpgp_surface_cross_system; the caller sets b up again afterwards):
 * the constraints' fixed crosses, harmonic inside (one linear solve), or
 * without any fixed vertex (a closed surface without features) a few steps
 * of inverse iteration towards the smallest eigenvector of the connection
 * Laplacian from the transported field (the "globally optimal" field of
 * Knoeppel et al.); |w| = 1; then the eps levels of the planar cross field
 * (glpgp_cross_solve: cross_eps0 x the 3D diagonal down to cross_eps_min mean
 * edges) and glpgp_cross_analyze (windings with the connection, the
 * singularities' 3D positions, the expected sum). */
glpgp_status glpgp_surface_cross_solve(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                       const glpgp_surface_constraints *con, glpgp_cross_result **out);

/* The cross field w (2 fine->nv) of surface fine, refined by bisection
 * from coarse (fine->surf->otri and obary relative to coarse's triangles:
 * glpgp_mesh_refine_surface), from coarse's cross field wc (2 coarse->nv):
 * at a refined vertex the P1 interpolant of its input triangle's corner
 * crosses in that triangle's plane (as 4-RoSy values, |w| interpolated),
 * in the vertex's own frame; an input vertex keeps its cross (in the
 * refined fan's frame). GLPGP_ERR_ARG where fine has no origin in coarse
 * (solver/surface_transfer.c). */
glpgp_status glpgp_surface_cross_transfer(const glpgp_mesh *coarse, const double *wc, const glpgp_mesh *fine,
                                          double *wf);

/* The Ginzburg-Landau cross field of a refined surface m (m->surf->origin
 * kept by glpgp_surface_keep_origin) solved on that input (its own
 * constraints and eps levels) and carried onto m
 * (glpgp_surface_cross_transfer; the fixed crosses set to con's), analysed
 * on m; with polish, then the last eps level on m from it
 * (glpgp_surface_cross_polish). c->solved_nv, solved_nt: the input's. */
glpgp_status glpgp_surface_cross_on_input(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                          const glpgp_surface_constraints *con, int polish,
                                          glpgp_cross_result **out);

/* glpgp_surface_cross_solve's last eps level only (cross_eps_min mean
 * edges of m), Newton from the crosses w (2 nv; the fixed ones con's). */
glpgp_status glpgp_surface_cross_polish(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                        const glpgp_surface_constraints *con, const double *w,
                                        glpgp_cross_result **out);

/* The harmonic boundary-aligned cross field of a surface (--field
 * boundary): the first part of glpgp_surface_cross_solve only (the fixed
 * crosses extended harmonically, normalised; no Ginzburg-Landau levels).
 * GLPGP_ERR_ARG when nothing is fixed (a closed surface without sharp
 * features: use the cross field). */
glpgp_status glpgp_surface_boundary_field(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                          const glpgp_surface_constraints *con, glpgp_cross_result **out);

/* Representatives u (2 nv) of the crosses w: alpha_i = arg(w_i) / 4 + k pi/2,
 * k chosen along a breadth-first walk closest to the neighbour's alpha
 * transported (alpha_j + rho). Any choice is valid (the coupled solve is
 * invariant); this one has few cuts. Returns the edges across which U
 * turns (the matching is not the identity), -1 without memory. */
int glpgp_surface_cross_to_vector(const glpgp_mesh *m, const double *w, double *u);

/* Quarter turns r_a of corner a of triangle t of mesh m (planar or surface)
 * with representatives u: rot^{r_a}(U_a) closest to U_{corner 0}, both in
 * t's frame on a surface (turned by the corners' rotations), in the plane's
 * on a planar mesh (glpgp_cross_turn). The coupled solve's matching. */
int glpgp_coupled_corner_turn(const glpgp_mesh *m, const double *u, int t, int a);

/* The Dirichlet nodes of the coupled oscillators on a surface: node
 * (i, s) (dir[2i + s]) where its direction (U_i, or V_i for s = 1) is at
 * least as normal as tangent to one of i's constraint edges
 * (glpgp_dirichlet_set's rule, in i's frame). Returns their count. */
int glpgp_surface_dirichlet(const glpgp_mesh *m, const glpgp_surface_constraints *con, const double *u,
                            unsigned char *dir);

/* Local size on a surface (size: 2 nv, u then v; *uniform set when every
 * value is h): GLPGP_SIZE_NONE h; GLPGP_SIZE_FILE one "h" or "h_u h_v" line
 * per vertex; GLPGP_SIZE_AUTO / ISO the smaller of (1) the curvature cap,
 * 2 rho with rho the largest patch radius (up to h / 2) whose patch around
 * the vertex, not crossing sharp features, stays within d = size_chord_depth
 * h of its plane (on a sphere of radius R the chord 2 sqrt(2 R d - d^2);
 * noise under d / 2 caps nothing) and (2) the feature spacing, the geodesic gap between
 * two different constraint curves (boundary loops, creases) over
 * size_across, then at least size_min h, graded by Dijkstra along the edges
 * with slope size_grading. GLPGP_SIZE_FUNC: GLPGP_ERR_UNSUPPORTED. */
glpgp_status glpgp_surface_size(const glpgp_mesh *m, const glpgp_options *o, const glpgp_surface_constraints *con,
                                double h, double *size, int *uniform);

/* The curl correction of the local size (surface_curl.c): per vertex the
 * factor f_i by which the frame (U, V) of representatives u (2 nv) is
 * scaled so that it is curl-free in the least-squares sense (Ray et al.),
 * f = e^(strength phi) normalised to keep the area in periods, within
 * [1/2, 2]; the oscillators' local size is h(x) / f. Triangles with a
 * vertex within rim_gap of the boundary (along the edges) do not count
 * (0: all count). range: the smallest and largest factor. GLPGP_ERR_ARG on
 * a planar mesh or strength < 0. */
glpgp_status glpgp_surface_size_curl(const glpgp_mesh *m, const double *u, double strength, double rim_gap,
                                     double *factor, double *range);

/* The principal-curvature term of the cross field (surface_align.c):
 * b (2 nv) <- lambda times each vertex's share of int Re(conj(w) q) (the
 * energy's term is -b . w), zero where fixed (nv flags, or NULL); q per
 * vertex the cross of the principal directions times ((k1 - k2) / 2)^2, a
 * refined surface's from its input's (surf->origin). stats (2, or NULL):
 * the largest |q| and the share of the area where q is not 0 (the
 * anisotropy gate). GLPGP_ERR_ARG on a planar mesh or lambda < 0. */
glpgp_status glpgp_surface_align_source(const glpgp_mesh *m, double lambda, const unsigned char *fixed, double *b,
                                        double *stats);

/* The pipeline on a surface (glpgp_solve's, which calls it): constraints,
 * the guiding field (cross, or the boundary-aligned harmonic one), its
 * representatives, the local size, the coupled oscillators (naive PGP: the
 * quadratic form's minimiser with the Dirichlet nodes, or without any its
 * smallest eigenvector by inverse iteration; GL: the eps continuation from
 * it), per-vertex results in each vertex's frame (r->coupled = 1). */
glpgp_status glpgp_solve_surface(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                 glpgp_result **out);

#ifdef __cplusplus
}
#endif

#endif
