/* solver/option_table.c: the table of the user-settable solve options
 * (glpgp_solve_option_table, glpgp/solve.h; descriptors: glpgp/optdesc.h):
 * names, ranges, choices, help texts and defaults of `glpgp solve`'s
 * "Parametrization" and "Continuation and solvers" groups, the parsers of
 * the options given as text (--field, --center, --size-field), and
 * --input-order (placed by the command). The CLI (cli/opts.c) and the
 * Python keyword arguments (python/) read this table. */
#include "glpgp/solve.h"

#include "glpgp/util.h"

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

static const char *parse_center(void *opts, const char *v)
{
    glpgp_options *o = opts;
    const char *comma = strchr(v, ',');
    char xs[128];
    size_t n = comma ? (size_t)(comma - v) : 0;
    if (!comma || n >= sizeof xs) return "is not X,Y (two numbers)";
    memcpy(xs, v, n);
    xs[n] = '\0';
    double c[2];
    if (!glpgp_parse_double(xs, &c[0]) || !glpgp_parse_double(comma + 1, &c[1])) return "is not X,Y (two numbers)";
    o->center[0] = c[0];
    o->center[1] = c[1];
    o->has_center = 1;
    return NULL;
}

/* the file name is kept (not copied): it must outlive the solve */
static const char *parse_field(void *opts, const char *v)
{
    glpgp_options *o = opts;
    if (!*v) return "is empty";
    o->field_values = NULL;
    if (!strcmp(v, "boundary")) {
        o->field = GLPGP_FIELD_BOUNDARY;
    } else if (!strcmp(v, "radial")) {
        o->field = GLPGP_FIELD_RADIAL;
    } else if (!strcmp(v, "cross")) {
        o->field = GLPGP_FIELD_CROSS;
    } else {
        o->field = GLPGP_FIELD_FILE;
        o->field_file = v;
    }
    return NULL;
}

static const char *parse_size_field(void *opts, const char *v)
{
    glpgp_options *o = opts;
    if (!*v) return "is empty";
    if (!strcmp(v, "auto")) {
        o->size_field = GLPGP_SIZE_AUTO;
    } else if (!strcmp(v, "iso")) {
        o->size_field = GLPGP_SIZE_ISO;
    } else if (!strcmp(v, "none")) {
        o->size_field = GLPGP_SIZE_NONE;
    } else if (glpgp_is_image_path(v)) {
        /* a grey-level image: the caller reads it once the domain is known
         * and sets size_fn (the CLI: glpgp_cli_size_image) */
        o->size_field = GLPGP_SIZE_FUNC;
        o->size_file = v;
        o->size_fn = NULL;
    } else {
        o->size_field = GLPGP_SIZE_FILE;
        o->size_file = v;
    }
    return NULL;
}

static const char *const k_methods[] = {"gl", "pgp", NULL};
static const int k_method_vals[] = {GLPGP_METHOD_GL, GLPGP_METHOD_PGP};
static const char *const k_energies[] = {"p1", "transport", NULL};
static const int k_energy_vals[] = {GLPGP_ELEM_P1, GLPGP_ELEM_TRANSPORT};
static const char *const k_newtons[] = {"mixed", "projected", "paper", NULL};
static const int k_newton_vals[] = {GLPGP_HESS_MIXED, GLPGP_HESS_PROJECTED, GLPGP_HESS_PAPER};
static const char *const k_globals[] = {"trust-region", "line-search", NULL};
static const int k_global_vals[] = {GLPGP_GLOBAL_TRUST_REGION, GLPGP_GLOBAL_LINE_SEARCH};
static const char *const k_preconds[] = {"jacobi", "amg", NULL};
static const int k_precond_vals[] = {GLPGP_PRECOND_JACOBI, GLPGP_PRECOND_AMG};
static const char *const k_couplings[] = {"auto", "off", "on", NULL};
static const char *const k_cross_meshes[] = {"input", "polish", "refined", NULL};
static const int k_cross_mesh_vals[] = {GLPGP_CROSS_MESH_INPUT, GLPGP_CROSS_MESH_POLISH, GLPGP_CROSS_MESH_REFINED};
static const int k_coupling_vals[] = {GLPGP_COUPLING_AUTO, GLPGP_COUPLING_OFF, GLPGP_COUPLING_ON};
static const char *const k_cross_sizes[] = {"off", "on", "auto", NULL};
static const int k_cross_size_vals[] = {GLPGP_CROSS_SIZE_OFF, GLPGP_CROSS_SIZE_ON, GLPGP_CROSS_SIZE_AUTO};
static const char *const k_denoise[] = {"auto", "off", NULL};
static const int k_denoise_vals[] = {GLPGP_DENOISE_AUTO, GLPGP_DENOISE_OFF};
static const char *const k_oscs[] = {"auto", "concurrent", "sequential", NULL};
static const int k_osc_vals[] = {GLPGP_OSC_AUTO, GLPGP_OSC_CONCURRENT, GLPGP_OSC_SEQUENTIAL};
static const char *const k_inits[] = {"naive", "one", NULL};
static const int k_init_vals[] = {GLPGP_INIT_NAIVE, GLPGP_INIT_ONE};

#define OFF(m) offsetof(glpgp_options, m)
#define DBL(nm, grp, m, l, lopen, h, hopen, mt, hlp)                                                         \
    {.name = nm, .group = grp, .kind = GLPGP_OPTK_DOUBLE, .offset = OFF(m), .lo = l, .hi = h, .lo_open = lopen, \
     .hi_open = hopen, .meta = mt, .help = hlp}
#define INT(nm, grp, m, l, h, mt, hlp)                                                                        \
    {.name = nm, .group = grp, .kind = GLPGP_OPTK_INT, .offset = OFF(m), .lo = l, .hi = h, .meta = mt, .help = hlp}
#define CHO(nm, grp, m, nms, vals, hlp)                                                                       \
    {.name = nm, .group = grp, .kind = GLPGP_OPTK_CHOICE, .offset = OFF(m), .names = nms, .values = vals,       \
     .help = hlp}
#define TXT(nm, grp, fn, mt, dflt, hlp)                                                                       \
    {.name = nm, .group = grp, .kind = GLPGP_OPTK_TEXT, .parse = fn, .meta = mt, .def = dflt, .help = hlp}

#define G1 "Parametrization"
#define G2 "Continuation and solvers"

static const glpgp_optdesc k_table[] = {
    {.name = "size", .group = G1, .kind = GLPGP_OPTK_DOUBLE, .offset = OFF(size), .lo = 0.0, .lo_open = 1,
     .hi = HUGE_VAL, .meta = "H", .help = "target quad size h, the period of the oscillators",
     .def = "bounding-box diagonal / 20, at least 10 mean edges"},
    CHO("method", G1, method, k_methods, k_method_vals, "Ginzburg-Landau continuation or naive PGP (one linear solve)"),
    CHO("energy", G1, energy, k_energies, k_energy_vals,
        "discretisation of the quadratic energy: P1 finite elements or\n"
        "the edge-transport (cotan) form of the original PGP"),
    CHO("newton", G1, hess, k_newtons, k_newton_vals,
        "penalty Hessian used by Newton: exact where |z|^2 >= 1/2 and\n"
        "projected in vortex cores (the trust region uses the exact one\n"
        "everywhere), projected (PSD) everywhere, or the paper's eq. 8"),
    CHO("globalization", G1, globalization, k_globals, k_global_vals,
        "Newton step: trust region on the exact Hessian (Steihaug CG,\n"
        "polar trial points), or the line search of the modified Newton"),
    CHO("tr-precond", G1, tr_precond, k_preconds, k_precond_vals,
        "with --precond amg: preconditioner and norm of the trust region's\n"
        "Steihaug CG: 2x2-block Jacobi, or a symmetric multigrid W-cycle\n"
        "built on the projected Hessian"),
    TXT("field", G1, parse_field, "boundary|radial|cross|FILE", "boundary; cross with --quads and on surfaces",
        "guiding field U: smooth field aligned with the boundary, radial\n"
        "about --center, from the Ginzburg-Landau cross field (see\n"
        "--cross-eps0), or one \"ux uy\" line per vertex from FILE;\n"
        "a surface: cross (default) or boundary (harmonic, aligned with\n"
        "its boundary and sharp features)"),
    TXT("center", G1, parse_center, "X,Y", "area centroid", "center of the radial field"),
    CHO("init", G1, init, k_inits, k_init_vals,
        "initial guess of the GL continuation: the normalised naive PGP\n"
        "solution, or z = 1"),
    TXT("size-field", G1, parse_size_field, "auto|iso|none|FILE|IMAGE", "auto",
        "local size h(x) <= h: auto shrinks it where the domain (a wall,\n"
        "strip, web) is thinner than --size-across periods, per\n"
        "oscillator along its direction, and refines the input there;\n"
        "iso: the same for both; none: h everywhere (the input as it\n"
        "is); FILE: one \"h\" or \"h_u h_v\" line per vertex; IMAGE (.png,\n"
        ".tif, .exr, ...): auto, further limited to the grey level times\n"
        "h (black: --size-min h, white: h) over --size-image-box"),
    DBL("size-grading", G1, size_grading, 0.0, 1, HUGE_VAL, 0, "G",
        "local size grows at most G per unit length:\n"
        "h(x) <= h(y) + G |x - y| along mesh edges"),
    DBL("size-across", G1, size_across, 1.0, 0, HUGE_VAL, 0, "N", "periods (quads) across the thinnest features"),
    DBL("size-min", G1, size_min, 0.0, 1, 1.0, 0, "F",
        "smallest local size, as a fraction of h (cusps and wedge tips\n"
        "stop there; black in a --size-field IMAGE)"),
    DBL("size-chord-area", G1, size_chord_area, 0.0, 0, 1.0, 1, "F",
        "curved boundaries: when the boundary quads' chords would cut\n"
        "(convex arcs) net of what they add (holes) more than F of the\n"
        "domain's area (arcs of few chords per turn not netted), the\n"
        "size near those parts is capped at c x the radius of curvature\n"
        "(c the largest that brings them within F); 0: off"),
    DBL("size-chord-depth", G1, size_chord_depth, 0.0, 0, 1.0, 1, "F",
        "curved boundaries: a chord's depth (sagitta) stays below F h\n"
        "(the size is capped where it would not); 0: off (on a surface: its\n"
        "curvature the same way)"),
    DBL("feature-angle", G1, feature_angle, 0.0, 0, 180.0, 0, "DEG",
        "a surface: interior edges whose triangles' normals differ by more\n"
        "than DEG degrees are sharp features, which the field and the\n"
        "quads follow like the boundary (180: none); a scan's noise is\n"
        "not: an edge counts only where it separates its sides locally,\n"
        "keeps its angle over a few edges and is part of a crease"),
    CHO("denoise", G1, denoise, k_denoise, k_denoise_vals,
        "a surface: where it shows a scan's noise (edges above\n"
        "--feature-angle that are not creases, folded slivers), its\n"
        "vertices there are smoothed before the solve (bilateral normal\n"
        "filtering: creases and corners stay sharp; the boundary kept,\n"
        "each vertex moved at most h / 10); the quads lie on the smoothed\n"
        "surface (the summary gives the largest move and their distance\n"
        "to the input); off: the input as it is"),
    DBL("size-curl", G1, size_curl, 0.0, 0, 1.0, 0, "F",
        "a surface: the local size scaled so that the guiding frame over\n"
        "h(x) is curl-free (least squares; Ray et al.'s curl correction),\n"
        "F the strength: fewer dislocations (T-junctions, 3-5 pairs) where\n"
        "the surface curves (with --size-field auto or iso); 0: off"),
    DBL("rim-scale", G1, rim_scale, 0.0, 0, 4.0, 0, "F",
        "a surface's boundary: its crosses from the rim seen over F h (at\n"
        "least 3 of its mean edges) on either side of each vertex, stopped\n"
        "at its corners there: a jagged rim (a scan's hole, triangles cut\n"
        "along a curve) aligns the field with the curve it follows, not\n"
        "with each tooth; 0: each vertex's own two edges"),

    DBL("eps0", G2, eps0, 0.0, 1, HUGE_VAL, 0, "F", "first eps, as a multiple of h"),
    DBL("cross-eps0", G2, cross_eps0, 0.0, 1, HUGE_VAL, 0, "F",
        "--field cross: first eps, as a multiple of the bounding-box diagonal"),
    DBL("cross-eps-min", G2, cross_eps_min, 0.0, 1, HUGE_VAL, 0, "F",
        "--field cross: last eps, as a multiple of the mean edge length"),
    DBL("cross-rtol", G2, cross_rtol, 0.0, 1, 1.0, 1, "F", "--field cross: each eps level stops when |g| <= F |g0|"),
    DBL("cross-ftol", G2, cross_ftol, 0.0, 0, 1.0, 1, "F",
        "--field cross: ... or, from its 20th Newton step on, when E + P\n"
        "fell by at most F of itself over the last 3 (the singularities'\n"
        "drift stalls; 0: off)"),
    CHO("cross-size", G2, cross_size, k_cross_sizes, k_cross_size_vals,
        "--field cross: local size from the cross field (its conformal\n"
        "scale, which makes the quads' grid integrable away from the\n"
        "singularities: fewer dislocations), the smaller of it and\n"
        "--size-field's; on: fully conformal (largest size h); auto: h at\n"
        "the --cross-size-quantile of the conformal scale, at least\n"
        "h / --cross-size-ratio"),
    DBL("cross-size-quantile", G2, cross_size_quantile, 0.0, 1, 1.0, 0, "F",
        "--cross-size auto: the conformal scale's quantile over the vertices\n"
        "that gets size h (larger scales are capped at h)"),
    DBL("cross-size-ratio", G2, cross_size_ratio, 1.0, 0, HUGE_VAL, 1, "C",
        "--cross-size auto: the size stays at least h / C"),
    CHO("cross-coupling", G2, cross_coupling, k_couplings, k_coupling_vals,
        "--field cross with singularities: solve u and v coupled across the\n"
        "cross field's cuts (auto: when it has cuts and the backend can,\n"
        "on: an error where the backend cannot), or apart (off)"),
    CHO("cross-mesh", G2, cross_mesh, k_cross_meshes, k_cross_mesh_vals,
        "--field cross on a surface refined for its size: solve the cross\n"
        "field on the input mesh (5-6x fewer vertices) and carry it onto\n"
        "the refined one, then its last eps level on the refined mesh from\n"
        "it (polish) or not (input), or solve it on the refined mesh\n"
        "(refined)"),
    DBL("cross-align", G2, cross_align, 0.0, 0, HUGE_VAL, 1, "F",
        "--field cross on a surface: weight of the principal-curvature term\n"
        "(the field pulled towards the principal directions where the\n"
        "surface bends more one way than the other: a torus, a cylinder);\n"
        "0: the smoothest field only"),
    DBL("eps-ratio", G2, eps_ratio, 0.0, 1, 1.0, 1, "F", "eps_{k+1} = F eps_k"),
    DBL("eps-min", G2, eps_min, 0.0, 1, HUGE_VAL, 0, "F", "last eps, as a multiple of the mean edge length"),
    DBL("newton-rtol", G2, newton_rtol, 0.0, 1, 1.0, 1, "F", "the last level stops when |g| <= F |g0|"),
    INT("newton-max", G2, newton_max, 1, INT_MAX, "N", "Newton iterations per eps level"),
    DBL("newton-ftol", G2, newton_ftol, 0.0, 0, 1.0, 1, "F",
        "a level also stops, from its 20th Newton step on, when E + P\n"
        "fell by at most F of itself over the last 3 (a plateau: nothing\n"
        "left to gain; 0: off)"),
    DBL("cg-rtol", G2, cg_rtol, 0.0, 1, 1.0, 1, "F", "CG stops when |r| <= F |b|"),
    INT("cg-max", G2, cg_max, 1, INT_MAX, "N", "CG iteration cap"),
    INT("cg-check", G2, cg_check, 1, INT_MAX, "N", "read the CG residual back every N iterations"),
    CHO("precond", G2, precond, k_preconds, k_precond_vals,
        "preconditioner of the linear solves: 2x2-block Jacobi CG, or\n"
        "aggregation multigrid (K-cycle, flexible CG; falls back to\n"
        "Jacobi with one warning on a backend without it)"),
    CHO("oscillators", G2, oscillators, k_oscs, k_osc_vals,
        "u and v at the same time (v on a second copy of the backend\n"
        "in a second thread; the same result bit for bit) or one after\n"
        "the other; auto: concurrent where measured to pay (reference\n"
        "backend; multigrid on an OpenCL CPU device up to 500k vertices;\n"
        "a GPU) with two or more processors and memory for the copy"),
    {.name = "phase-sync", .group = G2, .kind = GLPGP_OPTK_FLAG, .offset = OFF(phase_sync), .ival = 1, .def = "",
     .help = "wait for the device at the end of every timed phase, so that\n"
             "each phase's time in the summary and the statistics includes\n"
             "its device work (one more host round trip per phase)"},

    /* placed by the command (glpgp solve: after --remesh) */
    {.name = "input-order", .kind = GLPGP_OPTK_FLAG, .offset = OFF(vertex_order), .ival = GLPGP_ORDER_INPUT,
     .def = "",
     .help = "solve in the input's vertex numbering (default: renumbered in\n"
             "reverse Cuthill-McKee order for memory locality, the result\n"
             "written back in the input's order; not with per-vertex input\n"
             "files, whose lines follow the input's numbering)"},
    {.name = NULL}};

const glpgp_optdesc *glpgp_solve_option_table(void) { return k_table; }
