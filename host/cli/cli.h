/* cli/cli.h: what every command of the glpgp CLI shares: the log callback
 * that prints library progress and warnings on stderr (filtered by --quiet /
 * --verbose), the one error printer ("glpgp: error: ..." on one line, the
 * trace only with --verbose), the usage-error printer and whole-string number
 * parsing. */
#ifndef GLPGP_CLI_H
#define GLPGP_CLI_H

#define GLPGP_EXIT_FAIL 1
#define GLPGP_EXIT_USAGE 2

/* Verbosity: 0 = --quiet (warnings only), 1 = default (progress), 2 = --verbose. */
void glpgp_cli_set_verbosity(int v);
int glpgp_cli_verbosity(void);

/* Print the recorded library error as one line "glpgp: error: MESSAGE" (and,
 * with --verbose, its trace), clear it, return GLPGP_EXIT_FAIL. */
int glpgp_cli_fail(void);

/* Print "glpgp: usage error: ..." and the hint to `glpgp SUB --help` (or
 * `glpgp --help` when sub is NULL); return GLPGP_EXIT_USAGE. */
int glpgp_cli_usage_error(const char *sub, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Parse all of s as a finite double into *out. Returns 1 on success, 0 on
 * empty input, trailing characters, overflow or a non-finite value. */
int glpgp_cli_double(const char *s, double *out);

/* Parse all of s as a base-10 integer in [lo, hi] into *out (1 ok, 0 not). */
int glpgp_cli_long(const char *s, long lo, long hi, long *out);

#endif
