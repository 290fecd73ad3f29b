/* cli/opts.h: the one option parser of the glpgp CLI. A command describes its
 * options as a table (name, alias, kind, destination, range or choices, help
 * text), grouped under titles; glpgp_opts_parse accepts `--opt value` and
 * `--opt=value` for every option, validates each value completely (numbers
 * must parse whole and lie in range, choices must match), reports the first
 * problem as one usage error (exit 2), and prints the help text with the
 * defaults read from the destinations before parsing (so the help can never
 * disagree with the code). Option groups shared by several commands (solver
 * parameters, backend, quad options, picture, mask image, verbosity) are built
 * by the glpgp_opts_add_* functions. */
#ifndef GLPGP_CLI_OPTS_H
#define GLPGP_CLI_OPTS_H

#include "glpgp/backends.h"
#include "glpgp/optdesc.h"
#include "glpgp/image.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"

#include <stdio.h>

typedef enum glpgp_opt_kind {
    GLPGP_OPT_FLAG,   /* int *dest <- ival (no value allowed) */
    GLPGP_OPT_INT,    /* int *dest <- integer in [lo, hi] */
    GLPGP_OPT_DOUBLE, /* double *dest <- finite number in the range (see lo_open/hi_open) */
    GLPGP_OPT_STRING, /* const char **dest <- non-empty string */
    GLPGP_OPT_CHOICE, /* int *dest <- values[k] for the k-th of names */
    GLPGP_OPT_CUSTOM  /* parse(value, dest) returns NULL or the reason it is invalid */
} glpgp_opt_kind;

typedef struct glpgp_opt {
    const char *name;          /* "--size" (or a group title when kind < 0, internal) */
    const char *alias;         /* "-o" or NULL */
    glpgp_opt_kind kind;
    void *dest;
    double lo, hi;             /* numeric range */
    int lo_open, hi_open;      /* exclusive bounds */
    int ival;                  /* FLAG: value stored */
    const char *const *names;  /* CHOICE: NULL-terminated names */
    const int *values;         /* CHOICE: stored values (NULL: the index) */
    const char *(*parse)(const char *value, void *dest); /* CUSTOM */
    const char *meta;          /* value placeholder in the help ("H"); CHOICE: the names */
    const char *help;          /* help text; '\n' starts a continuation line */
    const char *def;           /* default shown in the help: NULL = from *dest, "" = none */
    int *seen;                 /* set to 1 when the option is given (may be NULL) */
    char defbuf[128];           /* internal: the default, captured before parsing */
    const char *group;         /* internal: title of its group */
    const glpgp_optdesc *desc; /* internal: the library's descriptor (glpgp_opts_add_desc), or NULL */
    void *obj;                 /* internal: the struct desc describes */
    char namebuf[64];          /* internal: "--" + desc->name */
} glpgp_opt;

#define GLPGP_OPTS_MAX 96

typedef struct glpgp_opts {
    const char *cmd;           /* "solve" */
    const char *usage;         /* "glpgp solve INPUT [options]" */
    const char *about;         /* paragraph(s) printed under the usage line */
    const char *epilog;        /* printed after the options (may be NULL) */
    glpgp_opt opt[GLPGP_OPTS_MAX];
    int n;
    const char *group;         /* current group title */
    int help;                  /* --help seen (set by the parser) */
} glpgp_opts;

/* Start a table for command cmd. */
void glpgp_opts_init(glpgp_opts *t, const char *cmd, const char *usage, const char *about);
/* Following options belong to the group `title`. */
void glpgp_opts_group(glpgp_opts *t, const char *title);
/* Add one option (copied). Returns a pointer to the stored entry. */
glpgp_opt *glpgp_opts_add(glpgp_opts *t, glpgp_opt o);

/* Add the option of a library table (glpgp/optdesc.h) setting a member of
 * obj, and every option of a table whose group is not NULL (each under its
 * group). Values are parsed and checked by the library (glpgp_optdesc_set). */
glpgp_opt *glpgp_opts_add_desc(glpgp_opts *t, const glpgp_optdesc *d, void *obj);
void glpgp_opts_add_table(glpgp_opts *t, const glpgp_optdesc *table, void *obj);

/* Shorthands. */
glpgp_opt *glpgp_opt_flag(glpgp_opts *t, const char *name, int *dest, int value, const char *help);
glpgp_opt *glpgp_opt_int(glpgp_opts *t, const char *name, int *dest, long lo, long hi,
                         const char *meta, const char *help);
glpgp_opt *glpgp_opt_double(glpgp_opts *t, const char *name, double *dest, double lo, int lo_open,
                            double hi, int hi_open, const char *meta, const char *help);
glpgp_opt *glpgp_opt_string(glpgp_opts *t, const char *name, const char **dest, const char *meta,
                            const char *help);
glpgp_opt *glpgp_opt_choice(glpgp_opts *t, const char *name, int *dest, const char *const *names,
                            const int *values, const char *help);

/* Parse argv[1..argc) (argv[0] is the command name). Positional arguments
 * (anything not starting with '-', and "-" itself) go to pos[0..maxpos);
 * *npos receives their count. Returns -1 when parsing succeeded, 0 after
 * printing the help (--help/-h), else the usage-error exit code (2) after
 * printing one "glpgp: usage error: ..." message. */
int glpgp_opts_parse(glpgp_opts *t, int argc, char **argv, const char **pos, int maxpos, int *npos);

/* The usual start of a command with one positional INPUT: parse into *in,
 * set the verbosity (glpgp_cli_set_verbosity of *verbosity as the options,
 * --verbose / --quiet among them, left it), and when missing is not
 * NULL a usage error "missing ..." without an input. Returns -1 to go on,
 * else the exit code as glpgp_opts_parse. */
int glpgp_opts_parse_input(glpgp_opts *t, int argc, char **argv, const char **in, const int *verbosity,
                           const char *missing);

/* Print the help text of the table (usage, about, grouped options with their
 * defaults, epilog). */
void glpgp_opts_usage(glpgp_opts *t, FILE *f);

/* ---- shared option groups ---------------------------------------------------- */

/* Verbosity: --quiet (0), --verbose (2); *v starts at 1. */
void glpgp_opts_add_verbosity(glpgp_opts *t, int *v);
/* The solver parameters of glpgp_options (every documented member a user may
 * set): parametrization, continuation and solvers. */
void glpgp_opts_add_solver(glpgp_opts *t, glpgp_options *o);
/* --size-image-box X0,Y0,X1,Y1 into box[4] (NaN until given: the domain's
 * bounding box), for --size-field IMAGE (glpgp_cli_size_image). */
void glpgp_opts_add_size_image(glpgp_opts *t, double box[4]);
/* --backend auto|opencl|reference, --device N (-1: none given). */
void glpgp_opts_add_backend(glpgp_opts *t, int *kind, int *device);
/* --keep-polygons, --smooth N, --all-quads, --no-repair, --allow-invalid;
 * *given set when one is used. */
void glpgp_opts_add_quads(glpgp_opts *t, glpgp_quads_options *q, int *given, int *allow_invalid);
/* --image-size, --image-kind, --background[, --line-width]. */
void glpgp_opts_add_picture(glpgp_opts *t, glpgp_render_options *r, int line_width);
/* --threshold, --invert, --pixel-size, --mesh-size, --min-area, --simplify, --algorithm,
 * --mesh-timeout. */
void glpgp_opts_add_mask(glpgp_opts *t, glpgp_mask_options *m);
/* Limits (group "Limits"): --max-elements N into *max_elements (the
 * triangles / faces of any mesh the command reads, generates or meshes,
 * 1 .. GLPGP_IO_MAX_ITEMS) and, when max_pixels is not NULL, --max-pixels N
 * (width x height of a mask image read or a picture written, >= 1). */
void glpgp_opts_add_limits(glpgp_opts *t, long *max_elements, long long *max_pixels);

#endif
