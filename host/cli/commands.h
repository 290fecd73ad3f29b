/* commands.h: CLI subcommands implemented outside main.c. Each takes the
 * subcommand's own argv (argv[0] = subcommand name) and returns the process
 * exit code (0 ok, 1 failure, 2 usage error). */
#ifndef GLPGP_COMMANDS_H
#define GLPGP_COMMANDS_H

/* `glpgp devices`: list OpenCL platforms and devices. */
int glpgp_cmd_devices(int argc, char **argv);
/* `glpgp crosscheck INPUT [--size H] ...`: compare every stage of the OpenCL
 * path with the reference path on a mesh, print a table, exit 1 on failure. */
int glpgp_cmd_crosscheck(int argc, char **argv);

/* `glpgp extract RESULT.vtk --quads OUT.{obj,vtk,msh} [--stats OUT.json]`:
 * quad mesh and its quality report from a solve result (cmd_quads.c). */
int glpgp_cmd_extract(int argc, char **argv);
/* `glpgp quality MESH.msh [--size H] [--domain D] [--stats OUT.json]`: the
 * quad quality report of a mesh made elsewhere (cmd_quads.c). */
int glpgp_cmd_quality(int argc, char **argv);

/* For `glpgp solve --quads FILE`: extract the quad mesh of result r on m and
 * add it as quads_path (.obj/.vtk/.vtu/.msh) to the output set outs (the
 * caller commits it with the run's other outputs and puts *qq into the
 * statistics); *qq receives the report (print it with glpgp_quads_print). qo: what is
 * done after the extraction (glpgp_quads_build; NULL: the defaults; with
 * all_quads the report uses h / 2). Returns -1 on success, else the exit
 * code after printing the error (cmd_quads.c). */
struct glpgp_mesh;
struct glpgp_result;
struct glpgp_quad_quality;
struct glpgp_quad_options;
struct glpgp_output_set;
int glpgp_solve_quads(const struct glpgp_mesh *m, const struct glpgp_result *r,
                      const char *quads_path, struct glpgp_output_set *outs,
                      const struct glpgp_quad_options *qo, struct glpgp_quad_quality *qq);

/* ---- pictures and image domains (cmd_image.c) ---------------------------- */

#include <stdio.h>

struct glpgp_mesh;
struct glpgp_result;

/* `glpgp render RESULT.vtk -o OUT.png [--image-size N] [--image-kind K]
 * [--background white|transparent] [--line-width W]`: picture of a result. */
int glpgp_cmd_render(int argc, char **argv);
/* `glpgp mesh MASK.png -o DOMAIN.msh [--threshold T] [--invert] [--pixel-size S]
 * [--mesh-size M] ...`: triangle mesh of the domain drawn in a mask image. */
int glpgp_cmd_mesh(int argc, char **argv);
/* `glpgp figure INPUT -o OUT.png [options]`: naive PGP and GL side by side,
 * singularity counts under each. */
int glpgp_cmd_figure(int argc, char **argv);

/* Image options of `glpgp solve` (--image, --image-size, --image-kind,
 * --background, and the mask options used when INPUT is an image). */
typedef struct glpgp_solve_image_cli {
    const char *image;  /* --image OUT.{png,exr,tif,jpg}: picture after the solve */
    int image_size;     /* --image-size N (default 1024) */
    int image_kind;     /* --image-kind grid|checker|zabs|field|theta (default grid) */
    int transparent;    /* --background white|transparent */
    double threshold;   /* --threshold T (default 0.5) */
    int invert;         /* --invert */
    double pixel_size;  /* --pixel-size S (default 1) */
    double mesh_size;   /* --mesh-size M (default: h / 8) */
} glpgp_solve_image_cli;

void glpgp_solve_image_init(glpgp_solve_image_cli *c);
/* 0: name is not an image option of solve; 1: a flag (no value); 2: takes a value. */
int glpgp_solve_image_option(const char *name);
/* Apply one image option (value NULL for flags). Returns -1 when accepted,
 * else prints a usage error and returns 2. */
int glpgp_solve_image_parse(glpgp_solve_image_cli *c, const char *name, const char *value);
/* Mesh the mask image `input` for solve (size: --size, 0 when not given).
 * Returns -1 on success, else prints the error and returns 1. */
int glpgp_solve_image_load(const glpgp_solve_image_cli *c, const char *input, double size,
                           int verbose, struct glpgp_mesh **m);
/* Write the --image picture of a finished solve (nothing when c->image is
 * NULL). Returns -1 on success, else prints the error and returns 1. */
int glpgp_solve_image_write(const glpgp_solve_image_cli *c, const struct glpgp_mesh *m,
                            const struct glpgp_result *r);
/* The image options' lines for `glpgp solve --help`. */
void glpgp_solve_image_usage(FILE *f);

#endif
