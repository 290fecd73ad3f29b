/* cli/commands.h: the commands of the glpgp CLI and the helpers they share.
 * Each command takes its own argv (argv[0] = the command name) and returns
 * the process exit code: 0 success, 1 failure ("glpgp: error: ..."), 2 usage
 * error. */
#ifndef GLPGP_COMMANDS_H
#define GLPGP_COMMANDS_H

#include "glpgp/image.h"
#include "glpgp/mesh.h"
#include "glpgp/solve.h"

int glpgp_cmd_solve(int argc, char **argv);
int glpgp_cmd_generate(int argc, char **argv);
int glpgp_cmd_devices(int argc, char **argv);
int glpgp_cmd_crosscheck(int argc, char **argv);
int glpgp_cmd_extract(int argc, char **argv);
int glpgp_cmd_quality(int argc, char **argv);
int glpgp_cmd_render(int argc, char **argv);
int glpgp_cmd_mesh(int argc, char **argv);
int glpgp_cmd_figure(int argc, char **argv);

/* glpgp render QUADS.obj|QUADS.msh (cli/cmd_render_quads.c): read the quad
 * mesh (and the domain, may be NULL), draw it (glpgp_render_quadmesh with
 * the caption) into out, print one line with the counts. Returns the exit
 * code. */
int glpgp_cli_render_quads(const char *in, const char *out, const char *domain, double sj_below,
                           const glpgp_render_options *ro, long max_elements, int verbosity);

/* --size-field IMAGE (o->size_field GLPGP_SIZE_FUNC with o->size_file the
 * image and no size_fn yet): read the image (limit mo->max_pixels) over box
 * (--size-image-box; NaN: m's bounding box), black = o->size_min, white = 1,
 * and attach it (o->size_fn, o->size_ctx = *out, freed by the caller with
 * glpgp_size_image_destroy after the solve). Nothing to do otherwise.
 * Returns -1 on success, else the exit code after printing the error. */
int glpgp_cli_size_image(glpgp_options *o, const glpgp_mesh *m, const double box[4],
                         const glpgp_mask_options *mo, glpgp_size_image **out);

/* Load INPUT: shape:NAME[:N], a mask image (meshed with mo) or a mesh file.
 * mo->max_triangles (--max-elements) limits every kind: the estimate of
 * shape:NAME:N (2 N) and of a mask (before Gmsh), the triangles of a file
 * (after reading: the readers' memory is bounded by the file size).
 * *is_mask (may be NULL) tells whether it was an image. Returns -1 on
 * success, else the exit code after printing the error (2 for a malformed
 * shape:..., 1 otherwise). */
int glpgp_cli_load_input(const char *cmd, const char *input, const glpgp_mask_options *mo,
                         glpgp_mesh **m, int *is_mask);
/* glpgp_cli_load_input with glpgp_mesh_read_ex's flags for mesh files
 * (GLPGP_READ_PLANAR_FACE). */
int glpgp_cli_load_input_ex(const char *cmd, const char *input, const glpgp_mask_options *mo, int read_flags,
                            glpgp_mesh **m, int *is_mask);

/* --max-elements: -1 when count <= max (max <= 0: the default), else print
 * "glpgp: error: WHAT: [about ]COUNT ITEMS: more than the limit of MAX
 * (--max-elements)" and return 1. */
int glpgp_cli_check_elements(const char *what, long count, const char *items, int approx, long max);

/* --image-size vs --max-pixels: -1 when panels pictures of size x size
 * pixels fit in max_pixels (<= 0: the default), else a usage error (2). */
int glpgp_cli_check_picture_size(const char *cmd, int size, int panels, long long max_pixels);

/* Whether the image modules a command needs are built in (prints the error
 * and returns 0 when not). */
int glpgp_cli_need_images(int oiio, int gmsh);

/* Validate an output path given to option opt before any work: its extension
 * is one of exts (NULL-terminated, lower case with the dot; NULL: any), its
 * directory exists and is writable. Returns -1 when fine, else the exit code
 * after printing the error (2 for a wrong extension, 1 otherwise). */
int glpgp_cli_check_output(const char *cmd, const char *opt, const char *path,
                           const char *const *exts);

#endif
