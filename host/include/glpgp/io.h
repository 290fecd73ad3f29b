/* glpgp/io.h: everything glpgp reads and writes: triangle meshes (OBJ, Gmsh
 * MSH 2.2/4.1), results (legacy VTK, VTK XML .vtu, textured OBJ; read back
 * from .vtk and .vtu), statistics JSON, quad meshes and their quality report;
 * the output set (atomic multi-file commit) every writer goes through, and
 * the JSON emitter every JSON file is written with. Layer: io.
 *
 * Writing. Every output is written under a temporary name in its
 * destination's directory ("DIR/STEM.tmp.PID.N.EXT": the extension stays
 * last) and renamed over the destination only when the whole output set it
 * belongs to was written completely (streams flushed, fsync'ed and closed
 * without error). If any write, sync or rename fails, no destination is left
 * modified: files already renamed are restored from hard-link backups
 * (DIR/STEM.tmp.PID.N.old, removed on success) or removed when they did not
 * exist before, and every temporary is removed. Errors are GLPGP_ERR_IO with
 * one line naming the file and the system error ("No space left on device").
 * A process-wide list of the live temporaries lets a signal handler clean up
 * (glpgp_output_signal_cleanup).
 *
 * Reading: limits and errors (every reader).
 *  - Errors are one line, GLPGP_ERR_FORMAT "FILE:LINE: what" for text formats
 *    (the section / array for binary .vtu data), GLPGP_ERR_IO for missing or
 *    unreadable files, GLPGP_ERR_LIMIT above a limit below, GLPGP_ERR_MESH
 *    when glpgp_mesh_create rejects the mesh.
 *  - Inputs are read in one pass (pipes and FIFOs work; nothing seeks).
 *  - Memory grows with the data actually read, never with a count a file
 *    declares: a count is checked for overflow, against GLPGP_IO_MAX_ITEMS
 *    and, for regular files, against the bytes left in the file before
 *    anything is reserved for it (a 163-byte file cannot ask for 537 MiB).
 *    Text formats need a small multiple (< 32x) of the input size; raw .vtu
 *    data about twice its size; a compressed .vtu block may inflate to at
 *    most 1100 times its compressed size.
 *  - Lines longer than GLPGP_IO_MAX_LINE bytes, NUL bytes in text formats,
 *    non-finite numbers (nan, inf, overflowing literals), repeated sections
 *    or arrays, counts that disagree with the data that follows are errors.
 *  - MSH node tags are mapped through a hash table (any tag in [0, 2^63)),
 *    never through an array sized by the largest tag. */
#ifndef GLPGP_IO_H
#define GLPGP_IO_H

#include <stdio.h>

#include "glpgp/json.h"
#include "glpgp/mesh.h"
#include "glpgp/util.h"
#include "glpgp/quads.h"
#include "glpgp/result.h"
#include "glpgp/solve.h"
#include "glpgp/version.h"

#ifdef __cplusplus
extern "C" {
#endif

/* GLPGP_IO_MAX_ITEMS, the largest count a reader accepts, and
 * GLPGP_IO_MAX_LINE, the longest line of a text format: glpgp/util.h. */
/* Default limit on the triangles (faces, cells) of a mesh the glpgp CLI
 * reads, generates or meshes (option --max-elements; the readers' own hard
 * limit is GLPGP_IO_MAX_ITEMS), and of glpgp_mask_options.max_triangles. */
#define GLPGP_DEFAULT_MAX_ELEMENTS 20000000L
/* Most files one output set (and the whole process) may have open at once. */
#define GLPGP_IO_MAX_OPEN 256

/* ---- output set: several files committed together ---------------------- */

/* Files being written that appear together or not at all. Use:
 *     glpgp_output_set *s = NULL;
 *     GLPGP_CHECK(glpgp_output_set_create(&s));
 *     FILE *f;
 *     st = glpgp_output_set_open(s, "out/r.vtk", &f);   // write through f
 *     st = glpgp_output_set_stats(s, ...);               // or a writer below
 *     st = glpgp_output_set_commit(s);                   // all or nothing
 *     glpgp_output_set_destroy(&s);                      // aborts if not committed
 * A set is used by one thread at a time. */
typedef struct glpgp_output_set glpgp_output_set;

glpgp_status glpgp_output_set_create(glpgp_output_set **out);

/* Create the temporary file of `path` (exclusive creation, mode 0666 &
 * ~umask; at commit a replaced regular file's permission bits are kept) and
 * return a binary stream on it in *f (owned by the set: do not fclose it).
 * Write errors are remembered with their errno and reported by the commit.
 * GLPGP_ERR_ARG: empty path, or a path the set already holds;
 * GLPGP_ERR_IO: path is a directory or the temporary cannot be created
 * (missing directory, permissions); GLPGP_ERR_LIMIT: GLPGP_IO_MAX_OPEN. */
glpgp_status glpgp_output_set_open(glpgp_output_set *s, const char *path, FILE **f);

/* Like _open for a writer that writes by file name (e.g. an image library):
 * creates the empty temporary and returns its name in *tmp_path (owned by the
 * set, valid until destroy). The writer must (re)create exactly that file;
 * it keeps the extension of path. */
glpgp_status glpgp_output_set_reserve(glpgp_output_set *s, const char *path,
                                      const char **tmp_path);

/* Flush, fsync and close every stream; then, if all succeeded, replace the
 * destinations in the order they were added (hard-link backups of existing
 * ones first). On any failure nothing is left modified (see the top of this
 * header) and GLPGP_ERR_IO names the file and the system error. A set can be
 * committed once; later calls return GLPGP_ERR_ARG. */
glpgp_status glpgp_output_set_commit(glpgp_output_set *s);

/* The first half of a commit, for files committed together across
 * processes (MPI ranks: every rank prepares, they agree, every rank
 * commits): flush, fsync and close every stream and report write errors
 * (GLPGP_ERR_IO, the set then undone like a failed commit). The commit that
 * follows only replaces the destinations. At most once, before the commit. */
glpgp_status glpgp_output_set_prepare(glpgp_output_set *s);

/* Remove every uncommitted temporary, free the set, *s = NULL (NULL ok). */
void glpgp_output_set_destroy(glpgp_output_set **s);

/* For a SIGINT/SIGTERM handler: remove the temporaries of every live output
 * set of the process (and undo a commit that is half done). Only unlink()
 * and rename(): async-signal-safe. The process should exit afterwards. */
void glpgp_output_signal_cleanup(void);

/* Check, before a long run, that path can be created: its directory exists
 * and is writable and path itself is not a directory. GLPGP_ERR_IO naming
 * the problem otherwise. */
glpgp_status glpgp_output_path_check(const char *path);

/* ---- one atomic file (an output set of one) ------------------------------ */

/* An output file being written. Use:
 *     glpgp_atomic_file af;
 *     GLPGP_CHECK(glpgp_atomic_open(&af, path));
 *     fprintf(af.f, ...);                    // write through af.f freely
 *     if (something_failed) { glpgp_atomic_abort(&af); return ...; }
 *     GLPGP_CHECK(glpgp_atomic_commit(&af)); // errors of the writes surface here
 * After commit or abort the struct holds no resources (both are safe to call
 * on a struct that was already committed/aborted, or whose open failed). */
typedef struct glpgp_atomic_file {
    FILE *f;               /* open stream on the temporary file (NULL when closed) */
    const char *path;      /* final destination (owned by set) */
    const char *tmp;       /* temporary name (owned by set) */
    glpgp_output_set *set; /* the set of one */
} glpgp_atomic_file;

glpgp_status glpgp_atomic_open(glpgp_atomic_file *af, const char *path);
glpgp_status glpgp_atomic_commit(glpgp_atomic_file *af);
void glpgp_atomic_abort(glpgp_atomic_file *af);

/* The JSON emitter (glpgp_json_*): glpgp/json.h. */

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

/* VTK XML UnstructuredGrid (.vtu), binary: every array in one appended raw
 * section (header_type UInt64, the host's byte order), zlib-compressed
 * (vtkZLibDataCompressor, blocks of at most 1 MiB; an array whose first
 * block does not shrink by 10% is stored at zlib level 0) when level > 0
 * and the build has zlib. Arrays as in glpgp_write_vtk: Points Float64 x3,
 * connectivity / offsets Int32, types UInt8 (5); PointData z_u, z_v (Float64
 * x2), theta_u, theta_v, zabs_u, zabs_v (Float64), dirichlet_u, dirichlet_v
 * (Int8), field_u, field_v (Float64 x3); CellData singular_u, singular_v
 * (Int8); FieldData h (Float64, 1 tuple). Values are stored exactly.
 * level: -1 default (GLPGP_VTU_DEFAULT_LEVEL with zlib, else 0), 0 raw,
 * 1..9 zlib levels (raw when the build has no zlib). opts may be NULL (it
 * only annotates the file). */
#define GLPGP_VTU_DEFAULT_LEVEL 1
glpgp_status glpgp_write_vtu(const glpgp_mesh *m, const glpgp_options *opts,
                             const glpgp_result *r, const char *path, int level);

/* Whether this build compresses .vtu data (zlib found at build time). */
int glpgp_io_have_zlib(void);

/* OBJ with texture coordinates: `v x y 0` per vertex, one `vt tu tv` per
 * triangle corner and `f a/ta b/tb c/tc`. (tu, tv) = (theta_u, theta_v),
 * unwrapped inside each triangle: corner 0 gets theta in [0, 1); corners 1, 2
 * get theta_0 + arg(z_k conj(z_0)) / 2 pi, so no triangle contains a wrap jump
 * and a checker texture with REPEAT wrapping shows the quad layout. */
glpgp_status glpgp_write_obj_textured(const glpgp_mesh *m, const glpgp_result *r,
                                      const char *path);

/* Caller-supplied context for the JSON statistics (every member optional;
 * zero-initialise the struct). */
typedef struct glpgp_stats_extra {
    const char *input;   /* input path or "shape:NAME:N" (NULL: written as null) */
    const char *output;  /* result file written alongside (NULL: null) */
    double seconds_read; /* time to read / generate the mesh (< 0: omitted) */
    const glpgp_quads_report *quads; /* quad mesh report: "quads" member (NULL: none) */
    /* MPI runs (--backend petsc): ranks > 0 writes "ranks" and "per_rank", an
     * array of {rank, owned, ghosts, seconds, max_rss_mib} from rank_info
     * (ranks x GLPGP_RANK_INFO_N doubles, in that order; seconds: the
     * rank's solve, max_rss in bytes) */
    int ranks;
    const double *rank_info;
    const char *device;  /* the OpenCL device and launch shape (glpgp_cl_backend_info; NULL: null) */
    /* a surface's noise smoothed before the solve (glpgp_solve_prepare):
     * mesh.surface.denoise, moves also over h = denoise_h (NULL: null),
     * and the quads' Hausdorff distance / h to the input as read (< 0: not
     * measured) */
    const glpgp_surface_denoise_info *denoise;
    double denoise_h, hausdorff_input;
} glpgp_stats_extra;
#define GLPGP_RANK_INFO_N 4

/* Statistics JSON (one object, glpgp_json). Top-level keys:
 *   version, input, output, vertices, triangles, size, method ("gl"/"pgp"),
 *   energy ("p1"/"transport"), newton ("mixed"/"projected"/"paper"/"exact"), backend,
 *   field ("boundary"/"radial"/"file"), field_file, init ("naive"/"one"),
 *   options {eps0, eps_ratio, eps_min, newton_rtol, newton_max, newton_ftol, cg_rtol,
 *            cg_max, cg_check, cross_eps0, cross_eps_min, cross_rtol, cross_ftol,
 *            cross_size ("off"/"on"/"auto"), cross_size_quantile,
 *            cross_size_ratio, center},
 *   mesh {area, mean_edge, boundary_loops, bbox, orientation_fixed},
 *   singularities {u: {plus, minus}, v: {...}},
 *   zabs {u: {min, p10, median}, v: {...}},
 *   final_energy {u, v}, dirichlet {u, v},
 *   newton_iterations {total, u, v}, cg_iterations {total, u, v, field},
 *   converged {all (false when any eps level stopped at the Newton cap),
 *              capped_levels_u, capped_levels_v},
 *   eps_schedule {u: [{level, eps, newton, cg, grad0, grad, energy,
 *                      median_zabs, restarted, fallbacks, backtracked, rtol,
 *                      capped}, ...],
 *                 v: [...]},
 *   seconds {read, setup, field, u, v, total},
 *   ranks, per_rank [{rank, owned, ghosts, seconds, max_rss_mib}, ...]
 *     (only when extra->ranks > 0: MPI runs),
 *   quads (the report of glpgp_quads_json; only when extra->quads is set).
 * opts may be NULL (the option keys are then null); extra may be NULL. */
glpgp_status glpgp_write_stats_json(const glpgp_mesh *m, const glpgp_options *opts,
                                    const glpgp_result *r, const char *path,
                                    const glpgp_stats_extra *extra);

/* The same statistics (and, below, the quad report) as a malloc'ed
 * NUL-terminated JSON string in *out (free() it): what the Python binding
 * returns as Result.stats / QuadMesh.report. */
glpgp_status glpgp_stats_json_text(const glpgp_mesh *m, const glpgp_options *opts, const glpgp_result *r,
                                   const glpgp_stats_extra *extra, char **out);
glpgp_status glpgp_quads_json_text(const glpgp_quads_report *qq, char **out);

/* Write the result with the writer chosen by the extension of path
 * (case-insensitive): ".vtk" -> legacy VTK, ".vtu" -> glpgp_write_vtu
 * (default level), ".obj" -> glpgp_write_obj_textured; anything else ->
 * GLPGP_ERR_ARG (nothing written). opts may be NULL (it only annotates). */
glpgp_status glpgp_write_result(const glpgp_mesh *m, const glpgp_options *opts,
                                const glpgp_result *r, const char *path);

/* Whether path has a result extension glpgp_write_result accepts (for
 * validating command lines before a long solve). */
int glpgp_result_path_supported(const char *path);

/* The same writers, adding the file to an output set (committed by the
 * caller together with the set's other files). */
glpgp_status glpgp_output_set_result(glpgp_output_set *s, const glpgp_mesh *m,
                                     const glpgp_options *opts, const glpgp_result *r,
                                     const char *path);
glpgp_status glpgp_output_set_stats(glpgp_output_set *s, const glpgp_mesh *m,
                                    const glpgp_options *opts, const glpgp_result *r,
                                    const char *path, const glpgp_stats_extra *extra);

/* ---- parallel result: .vtu pieces and the .pvtu index (MPI runs) -------- */

/* The name of piece k of a parallel result: "OUT.pvtu" -> "OUT_pk.vtu" into
 * buf (n bytes). GLPGP_ERR_ARG: pvtu does not end in .pvtu; GLPGP_ERR_LIMIT:
 * buf too small. */
glpgp_status glpgp_pvtu_piece_path(const char *pvtu, int k, char *buf, size_t n);

/* Add this rank's piece of the parallel result pvtu (piece `rank`, named by
 * glpgp_pvtu_piece_path) to s: a .vtu with the arrays of glpgp_write_vtu
 * (default compression) plus the point arrays global_id (Int64, the vertex
 * of the renumbered whole mesh) and vtkGhostType (UInt8: 0 owned, 1 a ghost
 * point). m is a part (m->part set, result r of its local vertices and
 * triangles): points = its owned vertices, then the ghosts its triangles
 * touch; cells = the triangles whose lowest global vertex it owns
 * (glpgp_part_counts_tri), so that the pieces of all ranks hold every
 * vertex owned exactly once and every triangle once. m without a part: the
 * whole mesh as one piece (global id = index, all owned). A cross-field
 * result (r->cross) of a part: GLPGP_ERR_ARG. */
glpgp_status glpgp_output_set_result_piece(glpgp_output_set *s, const glpgp_mesh *m,
                                           const glpgp_options *opts, const glpgp_result *r,
                                           const char *pvtu, int rank);

/* Add the .pvtu index of npieces pieces (pieces 0 .. npieces-1, referenced
 * by their names relative to the index's directory) to s. r: a result with
 * the same arrays as the pieces (any rank's: only which arrays exist and h
 * are read). GLPGP_ERR_ARG: a name holding " & < > ' or not ending in .pvtu. */
glpgp_status glpgp_output_set_pvtu(glpgp_output_set *s, const glpgp_result *r, const char *pvtu,
                                   int npieces);

/* ---- triangle meshes --------------------------------------------------- */

/* Read by extension: .obj, .msh (MSH 2.2 and 4.1 ASCII), .stl (ASCII or
 * binary), .ply (Stanford PLY: ASCII, binary little- or big-endian; the
 * vertex element's x, y, z and the face element's vertex_indices (or
 * vertex_index) list, other elements and properties skipped) or .off
 * (Object File Format, OFF / COFF / NOFF headers). A mesh in a coordinate
 * plane (z, else y or x constant, relative tolerance 1e-9 of the bbox
 * size) is a planar mesh (glpgp_mesh_create); one whose x, y and z all vary
 * is a surface (glpgp_mesh_create_surface, glpgp/surface.h), or with
 * GLPGP_READ_PLANAR_FACE (glpgp_mesh_read_ex) its largest face in a
 * coordinate plane (a warning names it; none: GLPGP_ERR_MESH).
 * Rejects: missing/unreadable file (GLPGP_ERR_IO), malformed content
 * (GLPGP_ERR_FORMAT), no triangles and everything the mesh constructors
 * reject (GLPGP_ERR_MESH). OBJ: `v x y [z]`, `f` with a, a/b, a//c, a/b/c forms and
 * negative (relative) indices; polygons with more than 3 corners are
 * fan-triangulated; a face using a vertex twice is an error. MSH: element
 * types other than 2 are skipped. Unused vertices are dropped silently (with
 * renumbering). Limits: see the top of this header. */
glpgp_status glpgp_mesh_read(const char *path, glpgp_mesh **out);
/* glpgp_mesh_read with flags: GLPGP_READ_PLANAR_FACE (a 3D mesh: its
 * largest face in a coordinate plane, the behaviour for planar commands:
 * remeshing, the domain of a quad mesh's quality report). */
#define GLPGP_READ_PLANAR_FACE 1
glpgp_status glpgp_mesh_read_ex(const char *path, int flags, glpgp_mesh **out);

/* A mesh from arrays, as a reader would make it of a file with these
 * vertices and triangles (the Python binding's glpgp.Mesh): x holds nv
 * points of dim = 2 or 3 coordinates, tri 3 nt vertex indices. Unused
 * vertices are dropped, 3D points take the readers' coordinate plane (z,
 * y or x = const; of a 3D surface its largest face in one, with a
 * warning), unwelded pieces are welded, then glpgp_mesh_create validates.
 * name names it in messages. Non-finite coordinates, indices outside
 * [0, nv): GLPGP_ERR_MESH. */
glpgp_status glpgp_mesh_from_arrays(const char *name, int nv, const double *x, int dim, int nt, const int *tri,
                                    glpgp_mesh **out);

/* Write the triangles as OBJ or MSH 4.1 (by extension), atomically. */
glpgp_status glpgp_mesh_write(const glpgp_mesh *m, const char *path);
glpgp_status glpgp_output_set_mesh(glpgp_output_set *s, const glpgp_mesh *m, const char *path);

/* ---- results read back ---------------------------------------------------- */

/* Read a result written by glpgp_write_vtk (legacy ASCII VTK) or
 * glpgp_write_vtu (VTK XML, appended raw data, compressed or not); the format
 * is recognised by the content. On success *m is the mesh (validated by
 * glpgp_mesh_create) and *r a result with nv, nt, size (from the header or
 * the h field; 0 if absent), field (U, zeros if absent), osc[k].z, dirichlet
 * (if present), and singularities and |z| statistics recomputed from z.
 * Each section / array may appear once; every value must be finite.
 * A file without the z_u and z_v arrays -> GLPGP_ERR_FORMAT; unreadable ->
 * GLPGP_ERR_IO. On failure *m and *r are NULL. */
glpgp_status glpgp_read_result_vtk(const char *path, glpgp_mesh **m, glpgp_result **r);
/* The same (name for new code). */
glpgp_status glpgp_read_result(const char *path, glpgp_mesh **m, glpgp_result **r);

/* ---- quad meshes and their quality report ---------------------------------- */

/* The report as a JSON object member `key` (NULL inside arrays / at top):
 * {"vertices", "faces", "quads", "other_faces", "other_faces_by_corners": {"3":..,"5":..},
 *  "valence": {"interior": {"2": n, ...}, "boundary": {...}},
 *  "irregular_vertices": {"interior", "boundary", "total"; with a cross field
 *  (qq->cross_singularities >= 0) also "interior_near_cross", "interior_far_cross"},
 *  "cross_singularities": {"count", "radius", "with_irregular_vertex"} (only
 *  with a cross field: glpgp_quads_quality_cross),
 *  "scaled_jacobian": {"min", "mean", "p01"}, "inverted", "degenerate",
 *  "edges": {"count", "boundary", "nonmanifold"},
 *  "edge_length_over_h": {"mean", "min", "max"}, "h", "area", "domain_area",
 *  "boundary_distance_over_h": {"hausdorff", "quads_to_domain", "domain_to_quads"}
 *  (null without a domain), "gap_edges", "singular_triangles": {"u", "v"},
 *  "valid" (true / false), "invalid_reasons": ["inverted", "non-quad", ...]
 *  (glpgp_quads_bad_name), "orientation" (+1 / -1), "overlapping_faces",
 *  "pinched_vertices", "non_quad_faces", "boundary_loops": {"mesh", "domain"},
 *  on a surface "surface": {"hausdorff_over_h", ..., "steps": {"path", ...}
 *  (with qq->has_steps: glpgp_quads_surface_steps, docs/surfaces.md)},
 *  "area_ratio", "outside_faces", "far_faces", "corners_lost",
 *  "boundary_vertex_distance_over_h" (the last five null without a domain),
 *  "max_edge_over_h", "repair": {"rounds", "removed_faces", "regions",
 *  "new_quads", "snapped_vertices"},
 *  "closing": {"odd_faces_closed", "strips_to_boundary", "quads_cut", "turns",
 *  "even_faces_split", "smoothed_vertices"}}.
 * Numbers lossless, non-finite ones null (glpgp_json). */
void glpgp_quads_json(glpgp_json *w, const char *key, const glpgp_quads_report *qq);

/* Write a standalone JSON file {"quads": REPORT} atomically. */
glpgp_status glpgp_quads_write_json_file(const glpgp_quads_report *qq, const char *path);
glpgp_status glpgp_output_set_quads_json(glpgp_output_set *s, const glpgp_quads_report *qq,
                                         const char *path);

/* Write q by extension (case-insensitive), atomically:
 *  .obj  `v x y 0` and one `f` line per face (quads: 4 indices, other faces
 *        as n-gons); with face origins (q->face_origin) each run of faces
 *        of one origin is put in the group `g grid|strips|repair|fallback`;
 *  .vtk  legacy ASCII UNSTRUCTURED_GRID, VTK_QUAD (9) for quads and
 *        VTK_POLYGON (7) for every other face; CELL_DATA corners (int),
 *        scaled_jacobian (quads; min corner value for polygons) and origin
 *        (GLPGP_QFACE_*, 0 without face origins); POINT_DATA valence;
 *  .vtu  the same arrays as VTK XML (appended raw, zlib as glpgp_write_vtu;
 *        scaled_jacobian stored exactly);
 *  .msh  Gmsh MSH 4.1 ASCII, one surface entity; quads are element type 3;
 *        a face with n != 4 corners is split into a fan of quads
 *        (0,2i+1,2i+2,2i+3) plus, for odd n, one triangle (type 2), so the
 *        file holds only quads and triangles and stays conforming;
 *  .ply  ASCII PLY, x y z doubles (z 0 in the plane) and each face's
 *        vertex_indices list.
 * Other extensions -> GLPGP_ERR_ARG. */
glpgp_status glpgp_quads_write(const glpgp_quadmesh *q, const char *path);
glpgp_status glpgp_output_set_quads(glpgp_output_set *s, const glpgp_quadmesh *q,
                                    const char *path);

/* Whether path ends in .obj, .vtk, .vtu, .msh or .ply (case-insensitive). */
int glpgp_quads_path_supported(const char *path);

/* Read a 2D quad/triangle mesh from Gmsh MSH 4.1 or 2.2 ASCII (faces keep the
 * file's vertex order, so the report can find folds; element types
 * 2 = triangle and 3 = quadrangle, in file order; other element types are
 * ignored; z ignored). Same parser and
 * limits as glpgp_mesh_read. GLPGP_ERR_IO / _FORMAT / _LIMIT. */
glpgp_status glpgp_quads_read_msh(const char *path, glpgp_quadmesh **out);

/* Read a quad mesh written by glpgp_quads_write (or any polygon mesh):
 * .msh as glpgp_quads_read_msh; .obj: `v x y [z]` (q->xyz set too when a z is not 0: a surface's mesh) and `f` lines
 * of 3 or more corners (OBJ indices, negative ones relative, /vt/vn parts
 * ignored), faces in the file's orientation, vertices in file order; the
 * faces after a `g grid|strips|repair|fallback` line get that origin
 * (face_origin; NULL when the file has none of these groups). Errors name
 * the file and line (GLPGP_ERR_FORMAT / _LIMIT / _IO); another extension is
 * GLPGP_ERR_ARG. */
glpgp_status glpgp_quads_read(const char *path, glpgp_quadmesh **out);

/* Name of a face origin GLPGP_QFACE_* ("grid", "strips", "repair",
 * "fallback"): the OBJ group and the JSON key. */
const char *glpgp_quads_origin_name(int origin);


#ifdef __cplusplus
}
#endif

#endif
