/* cli/cli.h: what every command of the glpgp CLI shares: the log callback
 * that prints library progress and warnings on stderr (filtered by --quiet /
 * --verbose), the one error printer ("glpgp: error: ..." on one line, the
 * trace only with --verbose), the usage-error printer and whole-string number
 * parsing. */
#ifndef GLPGP_CLI_H
#define GLPGP_CLI_H

#include <stddef.h>

#define GLPGP_EXIT_FAIL 1
#define GLPGP_EXIT_USAGE 2
#define GLPGP_EXIT_INVALID 3 /* a quad mesh is invalid: not written (README "Quad meshes") */

struct glpgp_quads_report;
struct glpgp_quads_surface_steps;

/* Verbosity: 0 = --quiet (warnings only), 1 = default (progress), 2 = --verbose. */
void glpgp_cli_set_verbosity(int v);
int glpgp_cli_verbosity(void);

/* Print the recorded library error as one line "glpgp: error: MESSAGE" (and,
 * with --verbose, its trace), clear it, return GLPGP_EXIT_FAIL. */
int glpgp_cli_fail(void);
/* Record that the run's failure (exit code `code`) has been reported on
 * stderr and return code: a SIGINT/SIGTERM after it (mpirun ending the
 * other ranks of a failed run) exits with that code and no further line.
 * glpgp_cli_fail, glpgp_cli_usage_error and glpgp_cli_invalid call it. */
int glpgp_cli_reported(int code);
/* The code recorded by glpgp_cli_reported, 0 when none (async-signal-safe). */
int glpgp_cli_reported_code(void);

/* Print "glpgp: usage error: ..." and the hint to `glpgp SUB --help` (or
 * `glpgp --help` when sub is NULL); return GLPGP_EXIT_USAGE. */
int glpgp_cli_usage_error(const char *sub, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Verdict on a quad mesh with report qq: -1 when it is valid once the
 * reasons in ignore are taken out. Otherwise, with allow (--allow-invalid),
 * prints one warning line naming the reasons and returns -1 (write it
 * anyway); without, returns GLPGP_EXIT_INVALID and leaves the reasons in why
 * (for glpgp_cli_invalid, after the other outputs are written). */
int glpgp_cli_quads_verdict(const struct glpgp_quads_report *qq, unsigned ignore, int allow, char *why,
                            size_t n);
/* Print "glpgp: error: quad mesh is invalid (WHY): not written ..." and
 * return GLPGP_EXIT_INVALID. what: "not written" or "" (quality). */
int glpgp_cli_invalid(const char *why, const char *what);

/* Print a surface quad pipeline's steps (extraction, closing, split, last
 * resort; local repair; smoothing) as the summary's lines (cmd_quads.c). */
void glpgp_cli_print_surface_steps(const struct glpgp_quads_surface_steps *s);

/* Parse all of s as a finite double into *out. Returns 1 on success, 0 on
 * empty input, trailing characters, overflow or a non-finite value. */
int glpgp_cli_double(const char *s, double *out);

/* Parse all of s as a base-10 integer in [lo, hi] into *out (1 ok, 0 not). */
int glpgp_cli_long(const char *s, long lo, long hi, long *out);

#endif
