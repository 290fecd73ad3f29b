/* glpgp/io.h: everything glpgp reads and writes: triangle meshes (OBJ, Gmsh
 * MSH 2.2/4.1), results (legacy VTK, textured OBJ; read back from VTK),
 * statistics JSON, quad meshes and their quality report, and the atomic-file
 * helper every writer uses. Layer: io.
 *
 *  - glpgp_atomic_*: write a file under a temporary name in the destination's
 *    directory, then rename() it over the destination on success; on any
 *    failure the temporary file is removed and the destination is untouched
 *    (a pre-existing file keeps its old content, a new one never appears).
 *    Reusable by every writer of the library.
 *  - glpgp_write_vtk:          legacy VTK (ASCII) unstructured grid for ParaView;
 *  - glpgp_write_obj_textured: OBJ with per-corner (theta_u, theta_v) texture
 *                              coordinates, unwrapped inside every triangle;
 *  - glpgp_write_stats_json:   run statistics as JSON;
 *  - glpgp_write_result:       picks the VTK or OBJ writer by extension.
 * Every writer is atomic and returns GLPGP_ERR_IO (with a message naming the
 * path and the system error) when the file cannot be written. */
#ifndef GLPGP_OUTPUT_H
#define GLPGP_OUTPUT_H

#include <stdio.h>

#include "glpgp/mesh.h"
#include "glpgp/quads.h"
#include "glpgp/result.h"
#include "glpgp/solve.h"
#include "glpgp/version.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- atomic file ------------------------------------------------------- */

/* An output file being written. Use:
 *     glpgp_atomic_file af;
 *     GLPGP_CHECK(glpgp_atomic_open(&af, path));
 *     fprintf(af.f, ...);                    // write through af.f freely
 *     if (something_failed) { glpgp_atomic_abort(&af); return ...; }
 *     GLPGP_CHECK(glpgp_atomic_commit(&af)); // errors of the writes surface here
 * After commit or abort the struct holds no resources (both are safe to call
 * on a struct that was already committed/aborted, or whose open failed). */
typedef struct glpgp_atomic_file {
    FILE *f;    /* open stream on the temporary file (NULL when closed) */
    char *path; /* final destination (owned copy) */
    char *tmp;  /* temporary name "<path>.tmp.<pid>.<n>" in the same directory */
} glpgp_atomic_file;

/* Create the temporary file for `path` (exclusive creation, mode 0666 & ~umask)
 * and open it for binary writing. GLPGP_ERR_IO if it cannot be created (e.g.
 * the directory does not exist or path names an existing directory),
 * GLPGP_ERR_ARG for an empty path. On failure af holds nothing. */
glpgp_status glpgp_atomic_open(glpgp_atomic_file *af, const char *path);

/* Flush and close the stream, check that every write succeeded (ferror,
 * fflush, fclose), then rename the temporary file onto the destination. On
 * any failure the temporary file is removed and GLPGP_ERR_IO returned. */
glpgp_status glpgp_atomic_commit(glpgp_atomic_file *af);

/* Close and remove the temporary file; the destination is left untouched. */
void glpgp_atomic_abort(glpgp_atomic_file *af);

/* ---- result writers ---------------------------------------------------- */

/* Legacy VTK ASCII UNSTRUCTURED_GRID (ParaView, VisIt):
 *   POINTS (x, y, 0); CELLS / CELL_TYPES (5 = triangle);
 *   POINT_DATA: z_u, z_v (SCALARS, 2 components Re, Im), theta_u, theta_v
 *   (arg(z) / 2 pi wrapped to [0, 1)), zabs_u, zabs_v (|z|), dirichlet_u,
 *   dirichlet_v (int 0/1), field_u, field_v (VECTORS U and V, z = 0);
 *   CELL_DATA: singular_u, singular_v (int winding -1 / 0 / +1).
 * Numbers are written with %.17g (lossless). result must match the mesh
 * (nv, nt), else GLPGP_ERR_ARG. */
glpgp_status glpgp_write_vtk(const glpgp_mesh *m, const glpgp_result *r, const char *path);

/* OBJ with texture coordinates: `v x y 0` per vertex, one `vt tu tv` per
 * triangle corner and `f a/ta b/tb c/tc`. (tu, tv) = (theta_u, theta_v),
 * unwrapped inside each triangle: corner 0 gets theta in [0, 1); corners 1, 2
 * get theta_0 + arg(z_k conj(z_0)) / 2 pi, so no triangle contains a wrap jump
 * and a checker texture with REPEAT wrapping shows the quad layout. */
glpgp_status glpgp_write_obj_textured(const glpgp_mesh *m, const glpgp_result *r,
                                      const char *path);

/* Caller-supplied context for the JSON statistics (every member optional). */
typedef struct glpgp_stats_extra {
    const char *input;   /* input path or "shape:NAME:N" (NULL: written as null) */
    const char *output;  /* result file written alongside (NULL: null) */
    double seconds_read; /* time to read / generate the mesh (< 0: omitted) */
} glpgp_stats_extra;

/* Statistics JSON (one object; numbers written losslessly: the shortest of
 * %.15g/%.16g/%.17g that reads back exactly; NaN/Inf written as null,
 * strings escaped). Top-level keys:
 *   version, input, output, vertices, triangles, size, method ("gl"/"pgp"),
 *   energy ("p1"/"transport"), newton ("mixed"/"projected"/"paper"/"exact"), backend,
 *   field ("boundary"/"radial"/"file"), field_file, init ("naive"/"one"),
 *   options {eps0, eps_ratio, eps_min, newton_rtol, newton_max, cg_rtol,
 *            cg_max, cg_check, center},
 *   mesh {area, mean_edge, boundary_loops, bbox, orientation_fixed},
 *   singularities {u: {plus, minus}, v: {...}},
 *   zabs {u: {min, p10, median}, v: {...}},
 *   final_energy {u, v}, dirichlet {u, v},
 *   newton_iterations {total, u, v}, cg_iterations {total, u, v, field},
 *   eps_schedule {u: [{level, eps, newton, cg, grad0, grad, energy,
 *                      median_zabs, restarted, fallbacks, backtracked, rtol,
 *                      capped}, ...],
 *                 v: [...]},
 *   seconds {read, setup, field, u, v, total}.
 * opts may be NULL (the option keys are then null); extra may be NULL. */
glpgp_status glpgp_write_stats_json(const glpgp_mesh *m, const glpgp_options *opts,
                                    const glpgp_result *r, const char *path,
                                    const glpgp_stats_extra *extra);

/* Write the result with the writer chosen by the extension of path
 * (case-insensitive): ".vtk" -> glpgp_write_vtk, ".obj" ->
 * glpgp_write_obj_textured; anything else -> GLPGP_ERR_ARG (nothing written).
 * opts may be NULL (it only annotates the VTK header). */
glpgp_status glpgp_write_result(const glpgp_mesh *m, const glpgp_options *opts,
                                const glpgp_result *r, const char *path);

/* Whether path has a result extension glpgp_write_result accepts (for
 * validating command lines before a long solve). */
int glpgp_result_path_supported(const char *path);

/* Check, before a long run, that path can be created: its directory exists
 * and is writable and path itself is not a directory. GLPGP_ERR_IO naming
 * the problem otherwise. */
glpgp_status glpgp_output_path_check(const char *path);

/* ---- triangle meshes --------------------------------------------------- */

/* Read by extension: .obj or .msh (MSH 2.2 and 4.1 ASCII, 3-node triangles only).
 * Rejects: missing/unreadable file (GLPGP_ERR_IO), malformed content
 * (GLPGP_ERR_FORMAT), no triangles, non-planar input (z not constant, relative
 * tolerance 1e-9 of the bbox size) and everything glpgp_mesh_create rejects
 * (GLPGP_ERR_MESH). OBJ: `v x y [z]`, `f` with a, a/b, a//c, a/b/c forms and
 * negative (relative) indices; polygons with more than 3 corners are
 * fan-triangulated. Unused vertices are dropped silently (with renumbering). */
glpgp_status glpgp_mesh_read(const char *path, glpgp_mesh **out);

/* Write the triangles as OBJ or MSH 4.1 (by extension), atomically
 * (temporary file + rename). */
glpgp_status glpgp_mesh_write(const glpgp_mesh *m, const char *path);

/* ---- results read back ---------------------------------------------------- */

/* Read path (ASCII legacy VTK from glpgp_write_vtk). On success *m is the
 * mesh (validated by glpgp_mesh_create) and *r a result with nv, nt, size
 * (from the header; 0 if absent), field (U, zeros if absent), osc[k].z,
 * dirichlet (if present), and singularities and |z| statistics recomputed
 * from z. A file without the z_u and z_v arrays -> GLPGP_ERR_FORMAT;
 * unreadable -> GLPGP_ERR_IO. */
glpgp_status glpgp_read_result_vtk(const char *path, glpgp_mesh **m, glpgp_result **r);

/* ---- quad meshes and their quality report ---------------------------------- */

/* Write the report as one JSON object (no trailing newline) to f:
 * {"vertices", "faces", "quads", "other_faces", "other_faces_by_corners": {"3":..,"5":..},
 *  "valence": {"interior": {"2": n, ...}, "boundary": {...}},
 *  "irregular_vertices": {"interior", "boundary", "total"},
 *  "scaled_jacobian": {"min", "mean", "p01"}, "inverted", "degenerate",
 *  "edges": {"count", "boundary", "nonmanifold"},
 *  "edge_length_over_h": {"mean", "min", "max"}, "h", "area", "domain_area",
 *  "boundary_distance_over_h": {"hausdorff", "quads_to_domain", "domain_to_quads"}
 *  (null without a domain), "gap_edges", "singular_triangles": {"u", "v"},
 *  "closing": {"odd_faces_closed", "strips_to_boundary", "quads_cut", "turns",
 *  "even_faces_split", "smoothed_vertices"}}.
 * Non-finite numbers are written as null. */
void glpgp_quads_write_json(FILE *f, const glpgp_quad_quality *qq);

/* Write a standalone JSON file {"quads": REPORT} atomically. */
glpgp_status glpgp_quads_write_json_file(const glpgp_quad_quality *qq, const char *path);

/* Insert "quads": REPORT as the last member of the JSON object stored in
 * path (e.g. the statistics written by glpgp_write_stats_json), atomically.
 * GLPGP_ERR_FORMAT when the file does not end with a JSON object. */
glpgp_status glpgp_quads_append_json(const char *path, const glpgp_quad_quality *qq);

/* Write q by extension (case-insensitive), atomically:
 *  .obj  `v x y 0` and one `f` line per face (quads: 4 indices, other faces
 *        as n-gons);
 *  .vtk  legacy ASCII UNSTRUCTURED_GRID, VTK_QUAD (9) for quads and
 *        VTK_POLYGON (7) for every other face; CELL_DATA corners (int) and
 *        scaled_jacobian (quads; min corner value for polygons); POINT_DATA
 *        valence;
 *  .msh  Gmsh MSH 4.1 ASCII, one surface entity; quads are element type 3;
 *        a face with n != 4 corners is split into a fan of quads
 *        (0,2i+1,2i+2,2i+3) plus, for odd n, one triangle (type 2), so the
 *        file holds only quads and triangles and stays conforming.
 * Other extensions -> GLPGP_ERR_ARG. */
glpgp_status glpgp_quads_write(const glpgp_quadmesh *q, const char *path);

/* Whether path ends in .obj, .vtk or .msh (case-insensitive). */
int glpgp_quads_path_supported(const char *path);

/* Read a 2D quad/triangle mesh from Gmsh MSH 4.1 or 2.2 ASCII (element types
 * 2 = triangle and 3 = quadrangle; other element types are ignored; z
 * ignored). Faces are made counter-clockwise. GLPGP_ERR_IO / _FORMAT. */
glpgp_status glpgp_quads_read_msh(const char *path, glpgp_quadmesh **out);


#ifdef __cplusplus
}
#endif

#endif
