/* glpgp/json.h: the one JSON emitter of glpgp (core/json.c): pretty printed,
 * lossless numbers, escaped strings; the statistics file, the quad-mesh
 * quality report and the benchmarks' reports are written with it.
 * Layer: core. */
#ifndef GLPGP_JSON_H
#define GLPGP_JSON_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GLPGP_JSON_MAX_DEPTH 32

/* Pretty-printed JSON (two-space indentation) to a stream. key is the member
 * name inside an object, NULL inside an array and for the top-level value.
 * Numbers are lossless: the shortest of %.15g/%.16g/%.17g that strtod reads
 * back exactly; non-finite numbers are written as null. Strings are escaped
 * (", \, control characters; invalid UTF-8 bytes become U+FFFD); a NULL
 * string is null. At most GLPGP_JSON_MAX_DEPTH - 1 levels of nesting. */
typedef struct glpgp_json {
    FILE *f;
    int depth;
    unsigned char used[GLPGP_JSON_MAX_DEPTH];  /* container has a member already */
    char closer[GLPGP_JSON_MAX_DEPTH];         /* '}' or ']' */
} glpgp_json;

void glpgp_json_init(glpgp_json *w, FILE *f);
void glpgp_json_object(glpgp_json *w, const char *key); /* opens { */
void glpgp_json_array(glpgp_json *w, const char *key);  /* opens [ */
void glpgp_json_close(glpgp_json *w);                   /* closes the innermost */
void glpgp_json_num(glpgp_json *w, const char *key, double v);
void glpgp_json_int(glpgp_json *w, const char *key, long long v);
void glpgp_json_str(glpgp_json *w, const char *key, const char *v);
void glpgp_json_bool(glpgp_json *w, const char *key, int v);
void glpgp_json_null(glpgp_json *w, const char *key);
/* After the top-level value: closes what is open and ends the line. */
void glpgp_json_finish(glpgp_json *w);

/* The number as glpgp_json_num writes it ("null" if not finite) into buf
 * (at least 32 bytes). Returns buf. */
char *glpgp_json_format_number(double v, char *buf);

#ifdef __cplusplus
}
#endif

#endif
