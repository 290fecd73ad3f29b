/* glpgp/optdesc.h: option descriptors. Each options struct a user sets
 * (glpgp_options: glpgp_solve_option_table, glpgp/solve.h;
 * glpgp_quads_options: glpgp_quads_option_table, glpgp/quads.h;
 * glpgp_render_options: glpgp_render_option_table, glpgp/image.h) has one
 * table naming every user-settable member once, with its type, range or
 * choices, help text and default: the CLI's parser and help (cli/opts.c)
 * and the Python keyword arguments (python/) read the same table and set
 * values through the same functions below, so names, defaults, ranges and
 * their messages exist once. Layer: core. */
#ifndef GLPGP_OPTDESC_H
#define GLPGP_OPTDESC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum glpgp_optkind {
    GLPGP_OPTK_FLAG,   /* int member <- ival when given (CLI: no value; Python: a bool) */
    GLPGP_OPTK_INT,    /* int member <- an integer in [lo, hi] */
    GLPGP_OPTK_DOUBLE, /* double member <- a finite number in the range (lo_open / hi_open: exclusive) */
    GLPGP_OPTK_CHOICE, /* int member <- values[k] for names[k] (values NULL: k) */
    GLPGP_OPTK_TEXT    /* parse(opts, text) sets whatever members it needs */
} glpgp_optkind;

typedef struct glpgp_optdesc {
    const char *name;    /* "size-field": the CLI's --size-field; NULL ends a table */
    const char *pyname;  /* Python keyword when it is not derived from name (NULL: name with '-'
                            as '_', a leading "no-" of a flag dropped: --no-repair is repair=False) */
    const char *group;   /* help group title (NULL: the command places the option itself) */
    glpgp_optkind kind;
    size_t offset;       /* offsetof the member (FLAG, INT, DOUBLE, CHOICE) */
    double lo, hi;       /* INT, DOUBLE: the range (+-HUGE_VAL: none) */
    int lo_open, hi_open;
    int ival;            /* FLAG: the value stored (0 or 1) */
    const char *const *names; /* CHOICE: NULL-terminated names */
    const int *values;   /* CHOICE: the stored values (NULL: the index) */
    const char *(*parse)(void *opts, const char *text); /* TEXT: NULL, or why text is invalid */
    const char *meta;    /* value placeholder in the help ("H"; CHOICE: NULL = names joined by '|') */
    const char *help;    /* help text; '\n' starts a continuation line */
    const char *def;     /* default shown in the help; NULL: read from the member */
} glpgp_optdesc;

/* Whole-string number parsing (no trailing characters, no overflow, finite):
 * 1 on success, 0 otherwise. */
int glpgp_parse_double(const char *s, double *out);
int glpgp_parse_long(const char *s, long lo, long hi, long *out);

/* Set d's member of opts from text (FLAG: text ignored, ival stored).
 * Returns NULL on success, else why the value is invalid ("is not a
 * positive number", "is not one of gl, pgp", the parser's reason), written
 * into why[0 .. n) (opts unchanged). Callers prefix the option and value:
 * "--size: '0' is not a positive number". */
const char *glpgp_optdesc_set(const glpgp_optdesc *d, void *opts, const char *text, char *why, size_t n);

/* FLAG: set it from the boolean of its Python name (repair=False stores 0
 * for --no-repair, keep_polygons=True stores 1). */
void glpgp_optdesc_set_flag(const glpgp_optdesc *d, void *opts, int on);

/* The Python keyword of d into buf ("size_field", "repair"). */
void glpgp_optdesc_pyname(const glpgp_optdesc *d, char *buf, size_t n);

/* The entry of table whose Python keyword or CLI name (without "--") is
 * name; NULL when none. */
const glpgp_optdesc *glpgp_optdesc_find(const glpgp_optdesc *table, const char *name);

/* The accepted range of an INT or DOUBLE as text ("a positive number", "an
 * integer >= 1", "a number in (0, 1)"). */
void glpgp_optdesc_range(const glpgp_optdesc *d, char *buf, size_t n);

/* The choices of a CHOICE joined by sep ("gl|pgp"). */
void glpgp_optdesc_choices(const glpgp_optdesc *d, const char *sep, char *buf, size_t n);

/* The default as the help shows it: d->def, else the member's value in opts
 * (INT %d, DOUBLE %g, CHOICE its name; "" for a FLAG or TEXT without def). */
void glpgp_optdesc_default(const glpgp_optdesc *d, const void *opts, char *buf, size_t n);

/* The member's current value in opts as text (INT %d, DOUBLE %.17g, CHOICE its
 * name, FLAG "true"/"false" of its Python name; TEXT: "" ). */
void glpgp_optdesc_value(const glpgp_optdesc *d, const void *opts, char *buf, size_t n);

#ifdef __cplusplus
}
#endif

#endif
