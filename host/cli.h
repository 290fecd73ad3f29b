/* cli.h: small command-line helpers shared by the CLI commands (main.c,
 * cmd_*.c) and the writers: whole-string number parsing, case-insensitive
 * extension tests and the early output-directory check. */
#ifndef GLPGP_CLI_H
#define GLPGP_CLI_H

/* Parse all of s as a finite double into *out. Returns 1 on success, 0 on
 * empty input, trailing characters, overflow or a non-finite value. */
int glpgp_cli_double(const char *s, double *out);

/* Parse all of s as a base-10 integer in [lo, hi] into *out (1 ok, 0 not). */
int glpgp_cli_long(const char *s, long lo, long hi, long *out);

/* Whether path ends with ext (lower-case, with the dot: ".png"), ignoring
 * the case of path. */
int glpgp_has_ext(const char *path, const char *ext);

/* Check, before a long run, that path can be created: its directory exists
 * and is writable and path itself is not a directory. Returns 1 when fine,
 * else 0 with a GLPGP_ERR_IO message recorded (glpgp_error_message). */
int glpgp_output_dir_ok(const char *path);

#endif
