/* core/json.c: the one JSON emitter of the library (glpgp/json.h): pretty
 * printed, lossless numbers (shortest of %.15g/%.16g/%.17g that reads back
 * exactly), non-finite numbers as null, escaped strings. Used by the
 * statistics file and the quad-mesh quality report. */
#include "glpgp/json.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

char *glpgp_json_format_number(double v, char *buf)
{
    if (!isfinite(v)) {
        strcpy(buf, "null");
        return buf;
    }
    glpgp_cnum cn; /* '.' whatever the locale */
    glpgp_cnum_begin(&cn);
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, 32, "%.*g", prec, v);
        if (strtod(buf, NULL) == v) break; /* %.17g always reads back */
    }
    glpgp_cnum_end(&cn);
    return buf;
}

void glpgp_json_init(glpgp_json *w, FILE *f)
{
    memset(w, 0, sizeof *w);
    w->f = f;
}

static void indent(glpgp_json *w)
{
    fputc('\n', w->f);
    for (int i = 0; i < w->depth; i++) fputs("  ", w->f);
}

/* Escaped string literal. */
static void put_string(FILE *f, const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    fputc('"', f);
    while (*p) {
        unsigned char c = *p;
        if (c == '"' || c == '\\') {
            fputc('\\', f);
            fputc(c, f);
            p++;
        } else if (c == '\n') {
            fputs("\\n", f);
            p++;
        } else if (c == '\t') {
            fputs("\\t", f);
            p++;
        } else if (c == '\r') {
            fputs("\\r", f);
            p++;
        } else if (c < 0x20 || c == 0x7f) {
            fprintf(f, "\\u%04x", c);
            p++;
        } else if (c < 0x80) {
            fputc(c, f);
            p++;
        } else {
            /* a well-formed UTF-8 sequence is copied, anything else is U+FFFD */
            int len = (c & 0xe0) == 0xc0 ? 2 : (c & 0xf0) == 0xe0 ? 3 : (c & 0xf8) == 0xf0 ? 4 : 0;
            int ok = len > 0 && c != 0xc0 && c != 0xc1 && c < 0xf5;
            for (int k = 1; ok && k < len; k++)
                if ((p[k] & 0xc0) != 0x80) ok = 0;
            if (ok) {
                fwrite(p, 1, (size_t)len, f);
                p += len;
            } else {
                fputs("\\ufffd", f);
                p++;
            }
        }
    }
    fputc('"', f);
}

/* Separator, indentation and key before a new member / element. */
static void begin_value(glpgp_json *w, const char *key)
{
    if (w->depth > 0) {
        if (w->used[w->depth]) fputc(',', w->f);
        w->used[w->depth] = 1;
        indent(w);
    }
    if (key && w->depth > 0 && w->closer[w->depth] == '}') {
        put_string(w->f, key);
        fputs(": ", w->f);
    }
}

static void open_container(glpgp_json *w, const char *key, char open, char close)
{
    begin_value(w, key);
    fputc(open, w->f);
    if (w->depth < GLPGP_JSON_MAX_DEPTH - 1) w->depth++;
    w->used[w->depth] = 0;
    w->closer[w->depth] = close;
}

void glpgp_json_object(glpgp_json *w, const char *key) { open_container(w, key, '{', '}'); }

void glpgp_json_array(glpgp_json *w, const char *key) { open_container(w, key, '[', ']'); }

void glpgp_json_close(glpgp_json *w)
{
    if (w->depth == 0) return;
    int had = w->used[w->depth];
    char c = w->closer[w->depth];
    w->depth--;
    if (had) indent(w);
    fputc(c, w->f);
}

void glpgp_json_num(glpgp_json *w, const char *key, double v)
{
    char buf[32];
    begin_value(w, key);
    fputs(glpgp_json_format_number(v, buf), w->f);
}

void glpgp_json_int(glpgp_json *w, const char *key, long long v)
{
    begin_value(w, key);
    fprintf(w->f, "%lld", v);
}

void glpgp_json_str(glpgp_json *w, const char *key, const char *v)
{
    begin_value(w, key);
    if (v)
        put_string(w->f, v);
    else
        fputs("null", w->f);
}

void glpgp_json_bool(glpgp_json *w, const char *key, int v)
{
    begin_value(w, key);
    fputs(v ? "true" : "false", w->f);
}

void glpgp_json_null(glpgp_json *w, const char *key)
{
    begin_value(w, key);
    fputs("null", w->f);
}

void glpgp_json_finish(glpgp_json *w)
{
    while (w->depth > 0) glpgp_json_close(w);
    fputc('\n', w->f);
}
