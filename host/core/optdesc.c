/* core/optdesc.c: setting, describing and naming options through their
 * descriptors (glpgp/optdesc.h), and whole-string number parsing: the one
 * place where option values are parsed and range-checked, for the CLI and
 * the Python binding alike. */
#include "glpgp/optdesc.h"
#include "glpgp/util.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int glpgp_parse_double(const char *s, double *out)
{
    if (!s || !*s) return 0;
    char *end = NULL;
    errno = 0;
    double v = glpgp_strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

int glpgp_parse_long(const char *s, long lo, long hi, long *out)
{
    if (!s || !*s) return 0;
    char *end = NULL;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

static int choice_value(const glpgp_optdesc *d, int k) { return d->values ? d->values[k] : k; }

static int is_negated(const glpgp_optdesc *d)
{
    return d->kind == GLPGP_OPTK_FLAG && !strncmp(d->name, "no-", 3);
}

void glpgp_optdesc_choices(const glpgp_optdesc *d, const char *sep, char *buf, size_t n)
{
    size_t used = 0;
    if (n) buf[0] = '\0';
    for (int k = 0; d->names && d->names[k]; k++) {
        int w = snprintf(buf + used, n - used, "%s%s", k ? sep : "", d->names[k]);
        if (w < 0 || (size_t)w >= n - used) break;
        used += (size_t)w;
    }
}

void glpgp_optdesc_range(const glpgp_optdesc *d, char *buf, size_t n)
{
    const char *what = d->kind == GLPGP_OPTK_INT ? "an integer" : "a number";
    int lo_inf = d->lo == -HUGE_VAL, hi_inf = d->hi == HUGE_VAL;
    if (d->kind == GLPGP_OPTK_INT) {
        lo_inf = d->lo <= (double)INT_MIN;
        hi_inf = d->hi >= (double)INT_MAX;
    }
    if (lo_inf && hi_inf)
        snprintf(buf, n, "%s", what);
    else if (hi_inf && d->lo == 0.0 && d->lo_open && d->kind == GLPGP_OPTK_DOUBLE)
        snprintf(buf, n, "a positive number");
    else if (hi_inf)
        glpgp_snprintf(buf, n, "%s %s %g", what, d->lo_open ? ">" : ">=", d->lo);
    else if (lo_inf)
        glpgp_snprintf(buf, n, "%s %s %g", what, d->hi_open ? "<" : "<=", d->hi);
    else
        glpgp_snprintf(buf, n, "%s in %c%g, %g%c", what, d->lo_open ? '(' : '[', d->lo, d->hi, d->hi_open ? ')' : ']');
}

static const char *not_in_range(const glpgp_optdesc *d, char *why, size_t n)
{
    char range[96];
    glpgp_optdesc_range(d, range, sizeof range);
    snprintf(why, n, "is not %s", range);
    return why;
}

const char *glpgp_optdesc_set(const glpgp_optdesc *d, void *opts, const char *text, char *why, size_t n)
{
    char *member = (char *)opts + d->offset;
    switch (d->kind) {
    case GLPGP_OPTK_FLAG: *(int *)member = d->ival; return NULL;
    case GLPGP_OPTK_INT: {
        long l;
        long lo = d->lo <= (double)LONG_MIN ? LONG_MIN : (long)d->lo;
        long hi = d->hi >= (double)LONG_MAX ? LONG_MAX : (long)d->hi;
        if (!glpgp_parse_long(text, lo, hi, &l)) return not_in_range(d, why, n);
        *(int *)member = (int)l;
        return NULL;
    }
    case GLPGP_OPTK_DOUBLE: {
        double v;
        int ok = glpgp_parse_double(text, &v);
        if (ok) ok = d->lo_open ? v > d->lo : v >= d->lo;
        if (ok) ok = d->hi_open ? v < d->hi : v <= d->hi;
        if (!ok) return not_in_range(d, why, n);
        *(double *)member = v;
        return NULL;
    }
    case GLPGP_OPTK_CHOICE: {
        for (int k = 0; d->names[k]; k++)
            if (text && !strcmp(text, d->names[k])) {
                *(int *)member = choice_value(d, k);
                return NULL;
            }
        char names[256];
        glpgp_optdesc_choices(d, ", ", names, sizeof names);
        snprintf(why, n, "is not one of %s", names);
        return why;
    }
    case GLPGP_OPTK_TEXT: {
        const char *r = d->parse(opts, text ? text : "");
        if (!r) return NULL;
        snprintf(why, n, "%s", r);
        return why;
    }
    }
    snprintf(why, n, "cannot be set");
    return why;
}

void glpgp_optdesc_set_flag(const glpgp_optdesc *d, void *opts, int on)
{
    *(int *)((char *)opts + d->offset) = (!!on != is_negated(d)) ? d->ival : !d->ival;
}

void glpgp_optdesc_pyname(const glpgp_optdesc *d, char *buf, size_t n)
{
    const char *s = d->pyname ? d->pyname : is_negated(d) ? d->name + 3 : d->name;
    snprintf(buf, n, "%s", s);
    for (char *p = buf; *p; p++)
        if (*p == '-') *p = '_';
}

const glpgp_optdesc *glpgp_optdesc_find(const glpgp_optdesc *table, const char *name)
{
    char py[64];
    for (const glpgp_optdesc *d = table; d && d->name; d++) {
        glpgp_optdesc_pyname(d, py, sizeof py);
        if (!strcmp(py, name) || !strcmp(d->name, name)) return d;
    }
    return NULL;
}

void glpgp_optdesc_default(const glpgp_optdesc *d, const void *opts, char *buf, size_t n)
{
    if (d->def) {
        snprintf(buf, n, "%s", d->def);
        return;
    }
    if (d->kind == GLPGP_OPTK_FLAG || d->kind == GLPGP_OPTK_TEXT) {
        if (n) buf[0] = '\0';
        return;
    }
    if (d->kind == GLPGP_OPTK_DOUBLE)
        glpgp_snprintf(buf, n, "%g", *(const double *)((const char *)opts + d->offset));
    else
        glpgp_optdesc_value(d, opts, buf, n);
}

void glpgp_optdesc_value(const glpgp_optdesc *d, const void *opts, char *buf, size_t n)
{
    const char *member = (const char *)opts + d->offset;
    if (n) buf[0] = '\0';
    switch (d->kind) {
    case GLPGP_OPTK_INT: snprintf(buf, n, "%d", *(const int *)member); break;
    case GLPGP_OPTK_DOUBLE: glpgp_snprintf(buf, n, "%.17g", *(const double *)member); break;
    case GLPGP_OPTK_CHOICE:
        for (int k = 0; d->names[k]; k++)
            if (choice_value(d, k) == *(const int *)member) snprintf(buf, n, "%s", d->names[k]);
        break;
    case GLPGP_OPTK_FLAG:
        snprintf(buf, n, "%s", (*(const int *)member == d->ival) != is_negated(d) ? "true" : "false");
        break;
    case GLPGP_OPTK_TEXT: break;
    }
}
