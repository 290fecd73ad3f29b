/* json_flat.c: a small recursive-descent JSON reader for glpgp-bench
 * --compare: it flattens a document into numeric (and string) leaves keyed
 * by dotted paths ("sizes.2.opencl.cg_iter_s.median"; array elements by
 * index). Enough for the files glpgp-bench writes; not a general library. */
#include "bench.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct jp {
    const char *s;
    bench_flat *f;
    char path[1024];
    int depth;
} jp;

static void ws(jp *p)
{
    while (*p->s && isspace((unsigned char)*p->s)) p->s++;
}

static glpgp_status bad(jp *p, const char *what)
{
    return GLPGP_FAIL(GLPGP_ERR_FORMAT, "JSON: %s near '%.20s'", what, p->s);
}

static char *dupstr(const char *a)
{
    size_t n = strlen(a);
    char *d = malloc(n + 1);
    if (d) memcpy(d, a, n + 1);
    return d;
}

static glpgp_status add_num(jp *p, double v)
{
    bench_flat *f = p->f;
    if (f->n == f->cap) {
        size_t nc = f->cap ? 2 * f->cap : 256;
        char **np = realloc(f->path, nc * sizeof *np);
        if (!np) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "JSON: out of memory");
        f->path = np;
        double *nv = realloc(f->value, nc * sizeof *nv);
        if (!nv) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "JSON: out of memory");
        f->value = nv;
        f->cap = nc;
    }
    char *d = dupstr(p->path);
    if (!d) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "JSON: out of memory");
    f->path[f->n] = d;
    f->value[f->n] = v;
    f->n++;
    return GLPGP_OK;
}

static glpgp_status add_str(jp *p, const char *v)
{
    bench_flat *f = p->f;
    if (f->ns == f->scap) {
        size_t nc = f->scap ? 2 * f->scap : 64;
        char **np = realloc(f->spath, nc * sizeof *np);
        if (!np) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "JSON: out of memory");
        f->spath = np;
        char **nv = realloc(f->svalue, nc * sizeof *nv);
        if (!nv) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "JSON: out of memory");
        f->svalue = nv;
        f->scap = nc;
    }
    char *d = dupstr(p->path), *e = dupstr(v);
    if (!d || !e) {
        free(d);
        free(e);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "JSON: out of memory");
    }
    f->spath[f->ns] = d;
    f->svalue[f->ns] = e;
    f->ns++;
    return GLPGP_OK;
}

/* Parse a string at p->s (opening quote) into buf (escapes simplified:
 * \uXXXX becomes '?'). */
static glpgp_status str(jp *p, char *buf, size_t len)
{
    size_t k = 0;
    if (*p->s != '"') return bad(p, "expected a string");
    p->s++;
    while (*p->s && *p->s != '"') {
        char ch = *p->s++;
        if (ch == '\\') {
            char e = *p->s++;
            switch (e) {
            case 'n': ch = '\n'; break;
            case 't': ch = '\t'; break;
            case 'r': ch = '\r'; break;
            case 'b': ch = '\b'; break;
            case 'f': ch = '\f'; break;
            case 'u':
                for (int i = 0; i < 4; i++)
                    if (!isxdigit((unsigned char)*p->s++)) return bad(p, "bad \\u escape");
                ch = '?';
                break;
            case '\0': return bad(p, "unterminated string");
            default: ch = e; break;
            }
        }
        if (k + 1 < len) buf[k++] = ch;
    }
    if (*p->s != '"') return bad(p, "unterminated string");
    p->s++;
    buf[k] = '\0';
    return GLPGP_OK;
}

static glpgp_status value(jp *p);

/* Append ".key" (or "key" at the root) to the path; returns the old length. */
static size_t push(jp *p, const char *key)
{
    size_t old = strlen(p->path);
    snprintf(p->path + old, sizeof p->path - old, "%s%s", old ? "." : "", key);
    return old;
}

static glpgp_status value(jp *p)
{
    ws(p);
    if (++p->depth > 64) return bad(p, "nested too deeply");
    glpgp_status st = GLPGP_OK;
    if (*p->s == '{') {
        p->s++;
        ws(p);
        if (*p->s == '}') {
            p->s++;
        } else {
            for (;;) {
                char key[256];
                ws(p);
                GLPGP_CHECK(str(p, key, sizeof key));
                ws(p);
                if (*p->s != ':') return bad(p, "expected ':'");
                p->s++;
                size_t old = push(p, key);
                GLPGP_CHECK(value(p));
                p->path[old] = '\0';
                ws(p);
                if (*p->s == ',') {
                    p->s++;
                    continue;
                }
                if (*p->s == '}') {
                    p->s++;
                    break;
                }
                return bad(p, "expected ',' or '}'");
            }
        }
    } else if (*p->s == '[') {
        p->s++;
        ws(p);
        if (*p->s == ']') {
            p->s++;
        } else {
            for (int i = 0;; i++) {
                char key[32];
                snprintf(key, sizeof key, "%d", i);
                size_t old = push(p, key);
                GLPGP_CHECK(value(p));
                p->path[old] = '\0';
                ws(p);
                if (*p->s == ',') {
                    p->s++;
                    continue;
                }
                if (*p->s == ']') {
                    p->s++;
                    break;
                }
                return bad(p, "expected ',' or ']'");
            }
        }
    } else if (*p->s == '"') {
        char buf[1024];
        GLPGP_CHECK(str(p, buf, sizeof buf));
        st = add_str(p, buf);
    } else if (strncmp(p->s, "true", 4) == 0) {
        p->s += 4;
    } else if (strncmp(p->s, "false", 5) == 0) {
        p->s += 5;
    } else if (strncmp(p->s, "null", 4) == 0) {
        p->s += 4;
    } else {
        char *end = NULL;
        double v = strtod(p->s, &end);
        if (end == p->s) return bad(p, "unexpected character");
        p->s = end;
        st = add_num(p, v);
    }
    p->depth--;
    return st;
}

glpgp_status bench_json_flatten(const char *text, bench_flat *out)
{
    jp p;
    memset(out, 0, sizeof *out);
    memset(&p, 0, sizeof p);
    p.s = text;
    p.f = out;
    glpgp_status st = value(&p);
    if (st == GLPGP_OK) {
        ws(&p);
        if (*p.s) st = bad(&p, "trailing characters");
    }
    if (st != GLPGP_OK) bench_flat_free(out);
    return st;
}

void bench_flat_free(bench_flat *f)
{
    for (size_t i = 0; i < f->n; i++) free(f->path[i]);
    for (size_t i = 0; i < f->ns; i++) {
        free(f->spath[i]);
        free(f->svalue[i]);
    }
    free(f->path);
    free(f->value);
    free(f->spath);
    free(f->svalue);
    memset(f, 0, sizeof *f);
}

const double *bench_flat_get(const bench_flat *f, const char *path)
{
    for (size_t i = 0; i < f->n; i++)
        if (strcmp(f->path[i], path) == 0) return &f->value[i];
    return NULL;
}
