/* core/numlocale.c: locale-independent number reading and writing. The
 * library's files, option values and messages use '.' as the decimal point
 * whatever locale the embedding process set (a Python notebook after
 * locale.setlocale(LC_ALL, ""), a GUI in a comma-decimal country): a scope
 * switches the calling thread alone to the "C" locale (uselocale: other
 * threads and the process's locale are untouched) around a reader or writer,
 * and glpgp_strtod / glpgp_sscanf / glpgp_snprintf do the same per call.
 * No state is kept: newlocale(LC_ALL_MASK, "C", 0) is the C library's
 * built-in C locale (no allocation in glibc or musl). */
#include "glpgp/util.h"

#include <errno.h>
#include <locale.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

void glpgp_cnum_begin(glpgp_cnum *s)
{
    s->prev = NULL;
    s->loc = NULL;
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (c == (locale_t)0) return; /* out of memory: the thread's own locale */
    locale_t prev = uselocale(c);
    if (prev == (locale_t)0) {
        freelocale(c);
        return;
    }
    s->prev = (void *)prev;
    s->loc = (void *)c;
}

void glpgp_cnum_end(glpgp_cnum *s)
{
    if (!s->loc) return;
    uselocale((locale_t)s->prev);
    freelocale((locale_t)s->loc);
    s->prev = NULL;
    s->loc = NULL;
}

double glpgp_strtod(const char *str, char **end)
{
    glpgp_cnum cn;
    glpgp_cnum_begin(&cn);
    double v = strtod(str, end);
    const int e = errno; /* strtod's ERANGE for the caller */
    glpgp_cnum_end(&cn);
    errno = e;
    return v;
}

int glpgp_sscanf(const char *str, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    glpgp_cnum cn;
    glpgp_cnum_begin(&cn);
    int n = vsscanf(str, fmt, ap);
    glpgp_cnum_end(&cn);
    va_end(ap);
    return n;
}

int glpgp_vsnprintf(char *buf, size_t n, const char *fmt, va_list ap)
{
    glpgp_cnum cn;
    glpgp_cnum_begin(&cn);
    int k = vsnprintf(buf, n, fmt, ap);
    glpgp_cnum_end(&cn);
    return k;
}

int glpgp_snprintf(char *buf, size_t n, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int k = glpgp_vsnprintf(buf, n, fmt, ap);
    va_end(ap);
    return k;
}
