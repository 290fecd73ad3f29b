/* core/text_reader.c: streaming line reader and token helpers shared by the
 * text-format readers and the per-vertex files (glpgp/internal/text.h). */
#include "glpgp/internal/text.h"
#include "glpgp/util.h"


#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define CHUNK (256 * 1024)

glpgp_status text_open(text_reader *tr, const char *path)
{
    memset(tr, 0, sizeof *tr);
    tr->path = path;
    tr->size = -1;
    tr->f = fopen(path, "rb");
    if (!tr->f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open %s: %s", path, strerror(errno));
    struct stat sb;
    if (fstat(fileno(tr->f), &sb) == 0) {
        if (S_ISDIR(sb.st_mode)) {
            fclose(tr->f);
            tr->f = NULL;
            return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read %s: %s", path, strerror(EISDIR));
        }
        if (S_ISREG(sb.st_mode)) tr->size = (long long)sb.st_size;
    }
    setvbuf(tr->f, NULL, _IONBF, 0); /* we buffer ourselves */
    tr->cap = CHUNK;
    tr->buf = malloc(tr->cap + 1);
    if (!tr->buf) {
        fclose(tr->f);
        tr->f = NULL;
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading %s", path);
    }
    return GLPGP_OK;
}

void text_close(text_reader *tr)
{
    if (tr->f) fclose(tr->f);
    free(tr->buf);
    tr->f = NULL;
    tr->buf = NULL;
}

glpgp_status text_error(const text_reader *tr, glpgp_status st, long line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    glpgp_vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return GLPGP_FAIL(st, "%s:%ld: %s", tr->path, line > 0 ? line : tr->line, msg);
}

glpgp_status text_next_line(text_reader *tr, char **line)
{
    *line = NULL;
    for (;;) {
        char *s = tr->buf + tr->pos;
        size_t avail = tr->len - tr->pos;
        char *nl = memchr(s, '\n', avail);
        if (nl || (tr->eof && avail > 0)) {
            size_t n = nl ? (size_t)(nl - s) : avail;
            if (memchr(s, '\0', n))
                return text_error(tr, GLPGP_ERR_FORMAT, tr->line + 1, "binary data (NUL byte) in a text file");
            s[n] = '\0'; /* buf has one spare byte past cap */
            size_t used = n + (nl ? 1 : 0);
            tr->pos += used;
            tr->consumed += (long long)used;
            tr->line++;
            while (n > 0 && isspace((unsigned char)s[n - 1])) s[--n] = '\0';
            *line = s;
            return GLPGP_OK;
        }
        if (tr->eof) return GLPGP_OK;
        /* need more input: keep the partial line at the start of buf */
        if (tr->pos > 0) {
            memmove(tr->buf, s, avail);
            tr->len = avail;
            tr->pos = 0;
        }
        if (tr->len == tr->cap) {
            if (tr->len >= (size_t)GLPGP_IO_MAX_LINE)
                return text_error(tr, GLPGP_ERR_LIMIT, tr->line + 1, "line longer than %ld bytes",
                                  (long)GLPGP_IO_MAX_LINE);
            size_t nc = 2 * tr->cap;
            char *nb = realloc(tr->buf, nc + 1);
            if (!nb) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading %s", tr->path);
            tr->buf = nb;
            tr->cap = nc;
        }
        size_t got = fread(tr->buf + tr->len, 1, tr->cap - tr->len, tr->f);
        tr->len += got;
        if (got == 0) {
            if (ferror(tr->f))
                return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read %s: %s", tr->path, strerror(errno ? errno : EIO));
            tr->eof = 1;
        }
    }
}

glpgp_status text_next_keyword(text_reader *tr, char **kw, size_t *kl, char **rest)
{
    *kw = *rest = NULL;
    *kl = 0;
    for (;;) {
        char *s;
        GLPGP_CHECK(text_next_line(tr, &s));
        if (!s) return GLPGP_OK;
        s = text_skip_ws(s);
        if (*s == '\0' || *s == '#') continue;
        *kw = s;
        while (*s && !isspace((unsigned char)*s)) s++;
        *kl = (size_t)(s - *kw);
        *rest = s;
        return GLPGP_OK;
    }
}

int text_read_raw(text_reader *tr, void *dst, size_t n)
{
    unsigned char *d = dst;
    size_t avail = tr->len - tr->pos;
    size_t k = avail < n ? avail : n;
    if (d) memcpy(d, tr->buf + tr->pos, k);
    tr->pos += k;
    tr->consumed += (long long)k;
    n -= k;
    if (d) d += k;
    while (n > 0) {
        size_t want = n, got;
        if (d) {
            got = fread(d, 1, want, tr->f);
            d += got;
        } else {
            if (want > tr->cap) want = tr->cap; /* skip through the (now empty) buffer */
            got = fread(tr->buf, 1, want, tr->f);
            tr->pos = tr->len = 0;
        }
        tr->consumed += (long long)got;
        n -= got;
        if (got == 0) {
            tr->eof = 1;
            return 0;
        }
    }
    return 1;
}

int text_getc_raw(text_reader *tr)
{
    unsigned char c;
    return text_read_raw(tr, &c, 1) ? c : -1;
}

long long text_remaining(const text_reader *tr)
{
    if (tr->size < 0) return -1;
    long long r = tr->size - tr->consumed;
    return r < 0 ? 0 : r;
}

char *text_skip_ws(char *p)
{
    while (*p && isspace((unsigned char)*p)) p++;
    return p;
}

int text_at_end(const char *p) { return *text_skip_ws((char *)p) == '\0'; }

int text_parse_ll(char **p, long long *out)
{
    char *s = text_skip_ws(*p), *e;
    errno = 0;
    long long v = strtoll(s, &e, 10);
    if (e == s || errno == ERANGE || (*e && !isspace((unsigned char)*e))) return 0;
    *out = v;
    *p = e;
    return 1;
}

int text_parse_double(char **p, double *out)
{
    char *s = text_skip_ws(*p), *e;
    double v = glpgp_strtod(s, &e);
    if (e == s || (*e && !isspace((unsigned char)*e)) || !isfinite(v)) return 0;
    *out = v;
    *p = e;
    return 1;
}

glpgp_status text_check_count(const text_reader *tr, long long n, long long min_bytes, const char *what)
{
    if (n < 0) return text_error(tr, GLPGP_ERR_FORMAT, 0, "negative number of %s (%lld)", what, n);
    long long rem = text_remaining(tr);
    if (rem >= 0 && min_bytes > 0 && n > rem / min_bytes)
        return text_error(tr, GLPGP_ERR_FORMAT, 0,
                          "%lld %s declared but only %lld bytes follow (truncated or corrupt file)", n, what,
                          rem);
    if (n > GLPGP_IO_MAX_ITEMS)
        return text_error(tr, GLPGP_ERR_LIMIT, 0, "%lld %s: more than the limit of %ld", n, what,
                          (long)GLPGP_IO_MAX_ITEMS);
    return GLPGP_OK;
}

glpgp_status text_read_rows(const char *path, const char *what, int nrows, int max_cols, long max_line,
                            text_row_fn fn, void *ctx)
{
    if (max_cols < 1 || max_cols > 8) return GLPGP_FAIL(GLPGP_ERR_ARG, "text_read_rows: max_cols %d", max_cols);
    text_reader tr;
    GLPGP_CHECK(text_open(&tr, path));
    glpgp_status st = GLPGP_OK;
    int i = 0;
    for (;;) {
        char *line;
        GLPGP_CHECK_GOTO(st, text_next_line(&tr, &line), done);
        if (!line) break;
        if ((long)strlen(line) > max_line) {
            st = text_error(&tr, GLPGP_ERR_FORMAT, 0, "line longer than %ld characters", max_line);
            goto done;
        }
        char *p = text_skip_ws(line);
        if (*p == '#' || *p == '\0') continue;
        double v[9];
        int nv = 0;
        while (nv <= max_cols && !text_at_end(p) && text_parse_double(&p, &v[nv])) nv++;
        if (nv > max_cols || !text_at_end(p)) nv = -1;
        if (i >= nrows) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: more than %d %s lines (one per vertex expected)", path, nrows,
                            what);
            goto done;
        }
        GLPGP_CHECK_GOTO(st, fn(ctx, &tr, i, v, nv), done);
        i++;
    }
    if (i != nrows) st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: %d %s lines for %d vertices", path, i, what, nrows);
done:
    text_close(&tr);
    return st;
}
