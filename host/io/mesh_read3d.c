/* io/mesh_read3d.c: the readers of the common 3D surface formats into a raw
 * mesh (raw_mesh.h), finished by mesh_io.c like every other mesh:
 *  - Stanford PLY: ASCII, binary little- and big-endian; the vertex
 *    element's x, y, z and the face element's vertex_indices (or
 *    vertex_index) list; every other element and property is skipped;
 *  - OFF (with the C / N / ST prefixes of colours, normals, texture
 *    coordinates: their extra numbers are ignored).
 * One pass, no seeking; counts checked against the bytes left before they
 * are used; errors name the file and the line (or the element and item for
 * binary data). */
#include "raw_mesh.h"
#include "glpgp/util.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- a token stream over the lines (ASCII PLY bodies, OFF) ---------------- */

typedef struct tok_stream {
    text_reader *tr;
    char *p;   /* rest of the current line */
    int hash;  /* '#' starts a comment to the end of the line (OFF) */
} tok_stream;

/* Next whitespace-delimited token into *tok (NUL-terminated in the line
 * buffer), NULL at the end of the input. */
static glpgp_status tok_next(tok_stream *ts, char **tok)
{
    for (;;) {
        if (ts->p) {
            char *q = text_skip_ws(ts->p);
            if (*q && !(ts->hash && *q == '#')) {
                char *e = q;
                while (*e && !isspace((unsigned char)*e)) e++;
                if (*e) *e++ = '\0';
                ts->p = e;
                *tok = q;
                return GLPGP_OK;
            }
        }
        GLPGP_CHECK(text_next_line(ts->tr, &ts->p));
        if (!ts->p) {
            *tok = NULL;
            return GLPGP_OK;
        }
    }
}

static glpgp_status tok_double(tok_stream *ts, double *out, const char *what)
{
    char *t;
    GLPGP_CHECK(tok_next(ts, &t));
    if (!t) return text_error(ts->tr, GLPGP_ERR_FORMAT, 0, "the file ends before %s", what);
    char *e;
    errno = 0;
    *out = glpgp_strtod(t, &e);
    if (e == t || *e || !isfinite(*out) || errno == ERANGE)
        return text_error(ts->tr, GLPGP_ERR_FORMAT, 0, "malformed number '%.40s' (%s)", t, what);
    return GLPGP_OK;
}

static glpgp_status tok_ll(tok_stream *ts, long long *out, const char *what)
{
    char *t;
    GLPGP_CHECK(tok_next(ts, &t));
    if (!t) return text_error(ts->tr, GLPGP_ERR_FORMAT, 0, "the file ends before %s", what);
    char *e;
    errno = 0;
    *out = strtoll(t, &e, 10);
    if (e == t || *e || errno == ERANGE)
        return text_error(ts->tr, GLPGP_ERR_FORMAT, 0, "malformed integer '%.40s' (%s)", t, what);
    return GLPGP_OK;
}

/* A face of n corners: a triangle, or a polygon for finish (line: for its
 * messages). 1 (nothing added) when it uses a vertex twice; 2 above the
 * triangle limit; 0 added; -1 out of memory (recorded). */
static int add_face(raw_mesh *r, const int *c, size_t n, long line)
{
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            if (c[i] == c[j]) return 1;
    if (r->nt + r->npc >= (size_t)GLPGP_IO_MAX_ITEMS) return 2;
    if ((n == 3 ? raw_add_tri(r, c[0], c[1], c[2]) : raw_add_poly(r, c, n, line)) != GLPGP_OK) return -1;
    return 0;
}

static glpgp_status add_vertex(raw_mesh *r, const double *x)
{
    if (r->nv >= (size_t)GLPGP_IO_MAX_ITEMS)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "more than %ld vertices", (long)GLPGP_IO_MAX_ITEMS);
    GLPGP_CHECK(glpgp_grow(&r->xyz, &r->cap_v, r->nv + 1, 3 * sizeof(double)));
    memcpy(r->xyz + 3 * r->nv++, x, 3 * sizeof(double));
    return GLPGP_OK;
}

/* ---- PLY ------------------------------------------------------------------ */

enum { PLY_ASCII = 0, PLY_LE = 1, PLY_BE = 2 };
enum { T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64, T_BAD };
#define PLY_MAX_ELEM 16
#define PLY_MAX_PROP 64

typedef struct ply_prop {
    int type, list, count_type; /* list: count_type counts, then items of type */
    int role;                   /* 0 none, 1..3: x, y, z; 4: the face's corner list */
} ply_prop;

typedef struct ply_elem {
    char name[32];
    long long n;
    int np;
    ply_prop p[PLY_MAX_PROP];
} ply_elem;

static int ply_type(const char *s)
{
    static const char *const names[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                        "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
    for (int k = 0; k < 16; k++)
        if (!strcmp(s, names[k])) return k % 8;
    return T_BAD;
}

static int ply_size(int t) { return t <= T_U8 ? 1 : t <= T_U16 ? 2 : t <= T_F32 ? 4 : 8; }

/* The header up to end_header: format, elements, properties and roles. */
static glpgp_status ply_header(text_reader *tr, int *format, ply_elem *el, int *nel)
{
    char *s;
    int magic = 0, fmt = -1;
    *nel = 0;
    for (;;) {
        GLPGP_CHECK(text_next_line(tr, &s));
        if (!s) return text_error(tr, GLPGP_ERR_FORMAT, 0, "the file ends inside the PLY header");
        char w[4][64];
        const int nw = sscanf(s, "%63s %63s %63s %63s", w[0], w[1], w[2], w[3]);
        if (!magic) {
            if (nw != 1 || strcmp(w[0], "ply")) return text_error(tr, GLPGP_ERR_FORMAT, 0, "not a PLY file (no 'ply' line)");
            magic = 1;
        } else if (nw <= 0 || !strcmp(w[0], "comment") || !strcmp(w[0], "obj_info")) {
            continue;
        } else if (!strcmp(w[0], "format") && nw >= 2) {
            fmt = !strcmp(w[1], "ascii") ? PLY_ASCII : !strcmp(w[1], "binary_little_endian") ? PLY_LE
                  : !strcmp(w[1], "binary_big_endian")                                   ? PLY_BE
                                                                                          : -2;
            if (fmt == -2) return text_error(tr, GLPGP_ERR_FORMAT, 0, "unknown PLY format '%.40s'", w[1]);
        } else if (!strcmp(w[0], "element") && nw == 3) {
            if (*nel == PLY_MAX_ELEM) return text_error(tr, GLPGP_ERR_LIMIT, 0, "more than %d PLY elements", PLY_MAX_ELEM);
            ply_elem *e = &el[(*nel)++];
            memset(e, 0, sizeof *e);
            snprintf(e->name, sizeof e->name, "%.31s", w[1]);
            char *end;
            errno = 0;
            e->n = strtoll(w[2], &end, 10);
            if (*end || errno || e->n < 0 || e->n > GLPGP_IO_MAX_ITEMS)
                return text_error(tr, GLPGP_ERR_FORMAT, 0, "bad element count '%.40s'", w[2]);
        } else if (!strcmp(w[0], "property") && *nel > 0 && nw >= 3) {
            ply_elem *e = &el[*nel - 1];
            if (e->np == PLY_MAX_PROP) return text_error(tr, GLPGP_ERR_LIMIT, 0, "more than %d properties", PLY_MAX_PROP);
            ply_prop *p = &e->p[e->np++];
            memset(p, 0, sizeof *p);
            if (!strcmp(w[1], "list")) { /* property list COUNT ITEM NAME */
                char nm[64];
                if (nw != 4 || sscanf(s, "%*s %*s %*s %*s %63s", nm) != 1)
                    return text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed list property (property list COUNT ITEM NAME)");
                p->list = 1;
                p->count_type = ply_type(w[2]);
                p->type = ply_type(w[3]);
                if (p->count_type == T_BAD || p->type == T_BAD || p->count_type >= T_F32)
                    return text_error(tr, GLPGP_ERR_FORMAT, 0, "bad list property types '%.20s %.20s'", w[2], w[3]);
                if (!strcmp(e->name, "face") && (!strcmp(nm, "vertex_indices") || !strcmp(nm, "vertex_index")))
                    p->role = 4;
            } else {
                p->type = ply_type(w[1]);
                if (p->type == T_BAD) return text_error(tr, GLPGP_ERR_FORMAT, 0, "unknown PLY type '%.40s'", w[1]);
                const char *name = w[2];
                if (!strcmp(e->name, "vertex") && name[0] >= 'x' && name[0] <= 'z' && !name[1]) p->role = 1 + name[0] - 'x';
            }
        } else if (!strcmp(w[0], "end_header")) {
            break;
        } else {
            return text_error(tr, GLPGP_ERR_FORMAT, 0, "unexpected PLY header line '%.40s'", s);
        }
    }
    if (fmt < 0) return text_error(tr, GLPGP_ERR_FORMAT, 0, "PLY header without a format line");
    *format = fmt;
    return GLPGP_OK;
}

/* One binary value of type t (byte order fmt) as a double. 0: the input ended. */
static int ply_read_bin(text_reader *tr, int t, int fmt, double *out)
{
    unsigned char b[8];
    const int n = ply_size(t);
    if (!text_read_raw(tr, b, (size_t)n)) return 0;
    uint64_t u = 0;
    for (int k = 0; k < n; k++) u |= (uint64_t)b[fmt == PLY_LE ? k : n - 1 - k] << (8 * k);
    switch (t) {
    case T_I8: *out = (int8_t)u; break;
    case T_U8: *out = (uint8_t)u; break;
    case T_I16: *out = (int16_t)u; break;
    case T_U16: *out = (uint16_t)u; break;
    case T_I32: *out = (int32_t)u; break;
    case T_U32: *out = (uint32_t)u; break;
    case T_F32: {
        const uint32_t v = (uint32_t)u;
        float f;
        memcpy(&f, &v, sizeof f);
        *out = f;
        break;
    }
    default: memcpy(out, &u, sizeof *out); break;
    }
    return 1;
}

/* Next value of an element: ASCII token or binary value. */
static glpgp_status ply_value(tok_stream *ts, int fmt, int t, const ply_elem *e, long long i, double *v)
{
    if (fmt == PLY_ASCII) return tok_double(ts, v, e->name);
    if (!ply_read_bin(ts->tr, t, fmt, v))
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: the file ends inside %s %lld of %lld", ts->tr->path, e->name, i, e->n);
    if (!isfinite(*v))
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: %s %lld has a non-finite value", ts->tr->path, e->name, i);
    return GLPGP_OK;
}

/* The instances of one element: vertices, faces, or skipped. */
static glpgp_status ply_element(tok_stream *ts, int fmt, const ply_elem *e, raw_mesh *r, int **corners, size_t *cap)
{
    long long minb = 0;
    for (int k = 0; k < e->np; k++) minb += fmt == PLY_ASCII ? 2 : ply_size(e->p[k].list ? e->p[k].count_type : e->p[k].type);
    GLPGP_CHECK(text_check_count(ts->tr, e->n, minb, e->name));
    for (long long i = 0; i < e->n; i++) {
        double x[3] = {0.0, 0.0, 0.0};
        size_t nc = 0;
        for (int k = 0; k < e->np; k++) {
            const ply_prop *p = &e->p[k];
            double v;
            if (!p->list) {
                GLPGP_CHECK(ply_value(ts, fmt, p->type, e, i, &v));
                if (p->role >= 1 && p->role <= 3) x[p->role - 1] = v;
                continue;
            }
            GLPGP_CHECK(ply_value(ts, fmt, p->count_type, e, i, &v));
            if (v < 0 || v != floor(v) || v > (double)GLPGP_IO_MAX_ITEMS)
                return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: %s %lld: bad list length %g", ts->tr->path, e->name, i, v);
            const long long n = (long long)v;
            for (long long j = 0; j < n; j++) {
                double c;
                GLPGP_CHECK(ply_value(ts, fmt, p->type, e, i, &c));
                if (p->role != 4) continue;
                if (c < 0 || c != floor(c) || c >= (double)GLPGP_IO_MAX_ITEMS)
                    return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: face %lld: bad vertex index %g", ts->tr->path, i, c);
                GLPGP_CHECK(glpgp_grow(corners, cap, nc + 1, sizeof(int)));
                (*corners)[nc++] = (int)c;
            }
            if (p->role == 4 && nc < 3)
                return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: face %lld has %zu corners (at least 3)", ts->tr->path, i, nc);
        }
        if (!strcmp(e->name, "vertex")) GLPGP_CHECK(add_vertex(r, x));
        const int fr = nc ? add_face(r, *corners, nc, (long)i) : 0;
        if (fr == 1) return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: face %lld uses a vertex more than once", ts->tr->path, i);
        if (fr == 2) return GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: more than %ld triangles", ts->tr->path, (long)GLPGP_IO_MAX_ITEMS);
        if (fr < 0) return GLPGP_ERR_NOMEM;
    }
    return GLPGP_OK;
}

glpgp_status glpgp_read_ply(const char *path, raw_mesh *r)
{
    text_reader tr;
    ply_elem *el = NULL;
    int *corners = NULL;
    size_t cap = 0;
    int fmt = 0, nel = 0;
    GLPGP_CHECK(text_open(&tr, path));
    glpgp_status st = glpgp_malloc(PLY_MAX_ELEM, sizeof *el, &el);
    if (st == GLPGP_OK) st = ply_header(&tr, &fmt, el, &nel);
    int have_xyz = 0, have_faces = 0;
    for (int k = 0; k < nel && st == GLPGP_OK; k++)
        for (int j = 0; j < el[k].np; j++) {
            if (!strcmp(el[k].name, "vertex") && el[k].p[j].role >= 1) have_xyz |= 1 << (el[k].p[j].role - 1);
            if (el[k].p[j].role == 4) have_faces = 1;
        }
    if (st == GLPGP_OK && have_xyz != 7)
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: the PLY vertex element has no x, y and z properties", path);
    if (st == GLPGP_OK && !have_faces)
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: the PLY face element has no vertex_indices list", path);
    tok_stream ts = {&tr, NULL, 0};
    for (int k = 0; k < nel && st == GLPGP_OK; k++) st = ply_element(&ts, fmt, &el[k], r, &corners, &cap);
    /* indices against the vertices (the face element may come first) */
    for (size_t i = 0; i < 3 * r->nt && st == GLPGP_OK; i++)
        if ((size_t)r->tri[i] >= r->nv)
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: face %zu: vertex index %d out of range (%zu vertices)", path, i / 3,
                            r->tri[i], r->nv);
    for (size_t i = 0; i < r->npc && st == GLPGP_OK; i++)
        if ((size_t)r->poly[i] >= r->nv)
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: a polygon face's vertex index %d is out of range (%zu vertices)",
                            path, r->poly[i], r->nv);
    free(el);
    free(corners);
    text_close(&tr);
    return st;
}

/* ---- OFF ------------------------------------------------------------------ */

glpgp_status glpgp_read_off(const char *path, raw_mesh *r)
{
    text_reader tr;
    int *corners = NULL;
    size_t cap = 0;
    GLPGP_CHECK(text_open(&tr, path));
    tok_stream ts = {&tr, NULL, 1};
    glpgp_status st = GLPGP_OK;
    char *t;
    long long nv = 0, nf = 0, ne = 0;
    GLPGP_CHECK_GOTO(st, tok_next(&ts, &t), done);
    /* [ST][C][N]OFF; 4OFF, nOFF (other dimensions) and binary OFF are not surfaces we read */
    const size_t lt = t ? strlen(t) : 0;
    if (!t || lt < 3 || strcmp(t + lt - 3, "OFF") || strspn(t, "STCN") != lt - 3) {
        st = text_error(&tr, GLPGP_ERR_FORMAT, 0, "not an OFF file (expected OFF, COFF, NOFF, STOFF ... first)");
        goto done;
    }
    GLPGP_CHECK_GOTO(st, tok_next(&ts, &t), done);
    if (t && !strcmp(t, "BINARY")) {
        st = text_error(&tr, GLPGP_ERR_FORMAT, 0, "binary OFF is not supported (convert it to ASCII OFF or PLY)");
        goto done;
    }
    if (!t) {
        st = text_error(&tr, GLPGP_ERR_FORMAT, 0, "the file ends before the counts");
        goto done;
    }
    { /* t is the vertex count (on the OFF line or the next) */
        char *e;
        errno = 0;
        nv = strtoll(t, &e, 10);
        if (e == t || *e || errno) {
            st = text_error(&tr, GLPGP_ERR_FORMAT, 0, "malformed vertex count '%.40s'", t);
            goto done;
        }
    }
    GLPGP_CHECK_GOTO(st, tok_ll(&ts, &nf, "the face count"), done);
    GLPGP_CHECK_GOTO(st, tok_ll(&ts, &ne, "the edge count"), done);
    GLPGP_CHECK_GOTO(st, text_check_count(&tr, nv, 6, "vertices"), done);
    GLPGP_CHECK_GOTO(st, text_check_count(&tr, nf, 8, "faces"), done);
    for (long long i = 0; i < nv; i++) {
        double x[3];
        for (int c = 0; c < 3; c++) GLPGP_CHECK_GOTO(st, tok_double(&ts, &x[c], "a vertex coordinate"), done);
        GLPGP_CHECK_GOTO(st, add_vertex(r, x), done);
        ts.p = NULL; /* colours, normals, texture coordinates: the rest of the line */
    }
    for (long long i = 0; i < nf; i++) {
        long long n;
        GLPGP_CHECK_GOTO(st, tok_ll(&ts, &n, "a face's corner count"), done);
        if (n < 3 || n > 1000000) {
            st = text_error(&tr, GLPGP_ERR_FORMAT, 0, "face %lld has %lld corners (3 to 1000000)", i, n);
            goto done;
        }
        GLPGP_CHECK_GOTO(st, glpgp_grow(&corners, &cap, (size_t)n, sizeof(int)), done);
        for (long long j = 0; j < n; j++) {
            long long c;
            GLPGP_CHECK_GOTO(st, tok_ll(&ts, &c, "a face's corner"), done);
            if (c < 0 || c >= nv) {
                st = text_error(&tr, GLPGP_ERR_FORMAT, 0, "face %lld: vertex index %lld out of range (%lld vertices)", i,
                                c, nv);
                goto done;
            }
            corners[j] = (int)c;
        }
        const int fr = add_face(r, corners, (size_t)n, tr.line);
        if (fr) {
            st = fr < 0 ? GLPGP_ERR_NOMEM
                 : fr == 1 ? text_error(&tr, GLPGP_ERR_FORMAT, 0, "face %lld uses a vertex more than once", i)
                           : text_error(&tr, GLPGP_ERR_LIMIT, 0, "more than %ld triangles", (long)GLPGP_IO_MAX_ITEMS);
            goto done;
        }
        ts.p = NULL; /* a colour may follow */
    }
done:
    free(corners);
    text_close(&tr);
    return st;
}
