/* glpgp/internal/text.h: the streaming line reader under every text format
 * (core/text_reader.c): the io layer's readers (OBJ, MSH, legacy VTK) and the
 * solver's per-vertex files (text_read_rows): one pass, no seeking (pipes
 * work), lines up to GLPGP_IO_MAX_LINE bytes, NUL bytes rejected, the size
 * of regular files known so that declared counts can be checked against the
 * bytes left; numbers read with '.' whatever the locale.
 * Internal: not installed. Layer: core. */
#ifndef GLPGP_INTERNAL_TEXT_H
#define GLPGP_INTERNAL_TEXT_H

#include "glpgp/status.h"
#include "glpgp/util.h"

#include <stdio.h>

typedef struct text_reader {
    FILE *f;
    const char *path;
    char *buf;          /* buf[pos .. len) not yet returned */
    size_t cap, pos, len;
    long line;          /* number of the line last returned (1-based) */
    long long size;     /* file size for regular files, -1 otherwise */
    long long consumed; /* bytes before buf[pos] */
    int eof;
} text_reader;

/* Open path for reading. GLPGP_ERR_IO (naming the file and the system error)
 * when it cannot be opened or is a directory. */
glpgp_status text_open(text_reader *tr, const char *path);
void text_close(text_reader *tr);

/* Next line in *line (NUL-terminated, trailing blanks and CR removed; valid
 * until the next call), *line = NULL at the end of the input.
 * GLPGP_ERR_FORMAT: NUL byte; GLPGP_ERR_LIMIT: line too long; GLPGP_ERR_IO:
 * read error. */
glpgp_status text_next_line(text_reader *tr, char **line);

/* Next line that is neither blank nor a '#' comment, split after its first
 * word: *kw (NULL at the end of the input) and its length *kl, *rest what
 * follows (keyword formats: OBJ). Errors as text_next_line. */
glpgp_status text_next_keyword(text_reader *tr, char **kw, size_t *kl, char **rest);

/* Bytes not yet returned (after the last line), or -1 for streams of
 * unknown size. */
long long text_remaining(const text_reader *tr);

/* Record "PATH:LINE: message" as GLPGP_ERR_FORMAT (or st) and return it;
 * line <= 0 uses the current line. */
glpgp_status text_error(const text_reader *tr, glpgp_status st, long line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Token parsing on a line: skip blanks, parse one whitespace-delimited
 * number, advance *p. 0 when there is no such token (or it is not entirely
 * a number). parse_double also fails on non-finite values. */
int text_parse_ll(char **p, long long *out);
int text_parse_double(char **p, double *out);
/* Whether only blanks are left. */
int text_at_end(const char *p);
char *text_skip_ws(char *p);

/* Raw bytes after the last line returned (binary data following a text
 * header): read exactly n bytes into dst (dst NULL: skip them). 0 when the
 * input ends first (or on a read error: see ferror(tr->f)). */
int text_read_raw(text_reader *tr, void *dst, size_t n);
/* Next raw byte, or -1 at the end of the input. */
int text_getc_raw(text_reader *tr);

/* Check a declared count: 0 <= n <= GLPGP_IO_MAX_ITEMS and n * min_bytes
 * <= the bytes left (when known). what names the items ("nodes"). */
glpgp_status text_check_count(const text_reader *tr, long long n, long long min_bytes,
                              const char *what);

/* ---- per-vertex files: one row of numbers per vertex ------------------- */

/* Called for each row (row index i, its line tr->line) with its numbers
 * v[0 .. nv), or nv = -1 when the line holds more than max_cols numbers or a
 * token that is not a finite number. Returns GLPGP_OK or a recorded error
 * (text_error names the file and line). */
typedef glpgp_status (*text_row_fn)(void *ctx, const text_reader *tr, int i, const double *v, int nv);

/* Read path as nrows rows (lines of up to max_cols <= 8 numbers; blank
 * lines and lines starting with '#' skipped; lines longer than max_line
 * characters rejected), calling fn for each. Errors name the file: "PATH:
 * more than NROWS WHAT lines (one per vertex expected)", "PATH: N WHAT lines
 * for NROWS vertices". Used by the solver's per-vertex inputs (a guiding
 * field, a size field on a mesh or a surface). */
glpgp_status text_read_rows(const char *path, const char *what, int nrows, int max_cols, long max_line,
                            text_row_fn fn, void *ctx);

#endif
