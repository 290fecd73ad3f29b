/* io/result_read.c: reader of glpgp's own results (glpgp/io.h): legacy
 * ASCII VTK (one pass over a text_reader, every section and array at most
 * once, counts checked before anything is reserved, non-finite values
 * rejected) and VTK XML .vtu (vtu.c); both end in the same assembly of the
 * mesh and the result. */
#include "glpgp/io.h"
#include "glpgp/cross.h"
#include "glpgp/surface.h"

#include "text_reader.h"
#include "vtu.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* What a result file provides, before validation. */
typedef struct raw_result {
    long long nv, nt;
    double *xyz;       /* 3 * nv */
    long long *tri;    /* 3 * nt */
    double *z[2];      /* 2 * nv each */
    double *field;     /* 3 * nv (U as written: a 3D vector), may be NULL */
    double *fframe;    /* 2 * nv (a surface's U in its vertices' frames, exact), may be NULL */
    double *dir[2];    /* nv each, may be NULL */
    double *cross;     /* 2 * nv (cross field w), may be NULL */
    int coupled;       /* a cross_coupled cell array was present (coupled solve) */
    double h;
} raw_result;

static void raw_free(raw_result *w)
{
    free(w->xyz);
    free(w->tri);
    free(w->z[0]);
    free(w->z[1]);
    free(w->field);
    free(w->fframe);
    free(w->dir[0]);
    free(w->dir[1]);
    free(w->cross);
    memset(w, 0, sizeof *w);
}

/* Mesh (validated, must come back unchanged) and result from raw data. */
static glpgp_status assemble(const char *path, raw_result *w, glpgp_mesh **mout, glpgp_result **rout)
{
    glpgp_status st = GLPGP_OK;
    glpgp_mesh *m = NULL;
    glpgp_result *res = NULL;
    double *xy = NULL;
    int *tri = NULL;
    if (w->nv < 0 || w->nt < 0 || !w->xyz || !w->tri)
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no points / cells (not a glpgp result)", path);
    if (!w->z[0] || !w->z[1])
        return GLPGP_FAIL(GLPGP_ERR_FORMAT,
                          "%s: result file without oscillators (arrays z_u and z_v are missing); "
                          "write one with 'glpgp solve ... --out FILE.vtk'",
                          path);
    const int nv = (int)w->nv, nt = (int)w->nt;
    int flat = 1; /* every z 0: a planar result, else a surface's */
    for (int i = 0; i < nv; i++) flat &= w->xyz[3 * i + 2] == 0.0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof *xy, &xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof *tri, &tri), done);
    for (int i = 0; i < nv; i++) {
        xy[2 * i] = w->xyz[3 * i];
        xy[2 * i + 1] = w->xyz[3 * i + 1];
    }
    for (long long t = 0; t < 3LL * nt; t++) {
        if (w->tri[t] < 0 || w->tri[t] >= nv) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: cell %lld: vertex index %lld out of range", path, t / 3,
                            w->tri[t]);
            goto done;
        }
        tri[t] = (int)w->tri[t];
    }
    if ((st = flat ? glpgp_mesh_create(nv, xy, nt, tri, &m) : glpgp_mesh_create_surface(nv, w->xyz, nt, tri, &m)) !=
        GLPGP_OK) {
        io_name_error(path, st);
        goto done;
    }
    if (m->nv != nv || m->nt != nt || m->orientation_fixed) {
        /* our writer emits validated CCW meshes: anything else is not ours */
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: mesh changed on validation (not written by glpgp?)", path);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_result_create(nv, nt, &res), done);
    res->size = w->h;
    res->backend = "file";
    if (w->fframe && !w->field) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: field_frame without field_u", path);
        goto done;
    }
    for (int i = 0; i < nv && w->field; i++) {
        if (m->surf && w->fframe) { /* exact: as the solve held it */
            res->field[2 * i] = w->fframe[2 * i];
            res->field[2 * i + 1] = w->fframe[2 * i + 1];
        } else if (m->surf) { /* the 3D vector's angle in the vertex's frame (the writer's inverse) */
            const double a = glpgp_surface_vertex_angle(m, i, w->field + 3 * i);
            res->field[2 * i] = cos(a);
            res->field[2 * i + 1] = sin(a);
        } else {
            res->field[2 * i] = w->field[3 * i];
            res->field[2 * i + 1] = w->field[3 * i + 1];
        }
    }
    for (int k = 0; k < 2; k++) {
        glpgp_osc_result *o = &res->osc[k];
        memcpy(o->z, w->z[k], (size_t)2 * nv * sizeof(double));
        o->n_dirichlet = 0;
        for (int i = 0; i < nv; i++) {
            o->dirichlet[i] = w->dir[k] && w->dir[k][i] != 0.0;
            o->n_dirichlet += o->dirichlet[i];
        }
        GLPGP_CHECK_GOTO(st, glpgp_osc_summarize(m, o), done);
    }
    if (w->coupled && w->field) { /* coupled solve: the frame windings (glpgp/cross.h) */
        res->coupled = 1;
        for (int k = 0; k < 2; k++)
            glpgp_coupled_windings(m, res->field, res->osc[0].z, res->osc[1].z, k, res->osc[k].singular,
                                   &res->osc[k].plus, &res->osc[k].minus);
    }
    if (w->cross) { /* the cross field: singularities recomputed from w */
        for (long long i = 0; i < 2 * w->nv; i++)
            if (!isfinite(w->cross[i])) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: cross_w has a non-finite value", path);
                goto done;
            }
        GLPGP_CHECK_GOTO(st, glpgp_cross_result_create(nv, nt, &res->cross), done);
        memcpy(res->cross->w, w->cross, (size_t)2 * nv * sizeof(double));
        GLPGP_CHECK_GOTO(st, glpgp_cross_analyze(m, res->cross), done);
    }
done:
    free(xy);
    free(tri);
    if (st != GLPGP_OK) {
        glpgp_mesh_destroy(&m);
        glpgp_result_destroy(&res);
    }
    *mout = m;
    *rout = res;
    return st;
}

/* ---- legacy VTK -------------------------------------------------------------- */

typedef struct lex {
    text_reader *tr;
    char *p; /* cursor in the current line (NULL: need a line) */
} lex;

/* Next whitespace-delimited token (across lines), NULL at the end. */
static glpgp_status next_tok(lex *lx, char **tok)
{
    for (;;) {
        if (lx->p) {
            char *s = text_skip_ws(lx->p);
            if (*s) {
                char *e = s;
                while (*e && *e != ' ' && *e != '\t' && *e != '\r' && *e != '\f' && *e != '\v') e++;
                lx->p = *e ? e + 1 : e;
                *e = '\0';
                *tok = s;
                return GLPGP_OK;
            }
        }
        GLPGP_CHECK(text_next_line(lx->tr, &lx->p));
        if (!lx->p) {
            *tok = NULL;
            return GLPGP_OK;
        }
    }
}

/* The rest of the current line (and move to the next). */
static char *rest_of_line(lex *lx)
{
    char *s = lx->p ? text_skip_ws(lx->p) : (char *)"";
    lx->p = NULL;
    return s;
}

static glpgp_status tok_ll(lex *lx, const char *what, long long *out)
{
    char *t;
    GLPGP_CHECK(next_tok(lx, &t));
    if (!t || !text_parse_ll(&t, out))
        return text_error(lx->tr, GLPGP_ERR_FORMAT, 0, "expected an integer (%s)", what);
    return GLPGP_OK;
}

/* Read n numbers into a buffer grown as they arrive (*out NULL: discard). */
static glpgp_status read_numbers(lex *lx, long long n, const char *what, double **out)
{
    size_t cap = 0;
    double *v = NULL;
    for (long long i = 0; i < n; i++) {
        char *t;
        double x;
        glpgp_status st = next_tok(lx, &t);
        if (st == GLPGP_OK && (!t || !text_parse_double(&t, &x)))
            st = text_error(lx->tr, GLPGP_ERR_FORMAT, 0, "%s: value %lld %s", what, i,
                            !t ? "missing (truncated file)" : "is not a finite number");
        if (st == GLPGP_OK && out) st = glpgp_grow(&v, &cap, (size_t)i + 1, sizeof *v);
        if (st != GLPGP_OK) {
            free(v);
            glpgp_error_push_trace(__FILE__, __LINE__);
            return st;
        }
        if (out) v[i] = x;
    }
    if (out) *out = v;
    return GLPGP_OK;
}

/* The legacy reader's state between sections. */
typedef struct legacy {
    text_reader *tr;
    lex lx;
    raw_result *w;
    long long ncell_types;                    /* -1: no CELL_TYPES yet */
    enum { NONE, POINT_DATA, CELL_DATA } where; /* the data section being read */
    char seen[32][64];                        /* names of the arrays seen (each at most once) */
    int nseen;
} legacy;

/* Line 2 (the title, "... h VALUE ..."), "ASCII", "DATASET UNSTRUCTURED_GRID". */
static glpgp_status legacy_header(legacy *L)
{
    text_reader *tr = L->tr;
    char *s, *t;
    GLPGP_CHECK(text_next_line(tr, &s));
    if (s) {
        const char *p = strstr(s, " h ");
        if (p) {
            char *q = (char *)p + 3;
            double h;
            if (text_parse_double(&q, &h) && h >= 0) L->w->h = h;
        }
    }
    GLPGP_CHECK(next_tok(&L->lx, &t));
    if (!t || strcmp(t, "ASCII"))
        return text_error(tr, GLPGP_ERR_FORMAT, 0, "%s VTK is not supported (only ASCII)", t ? t : "(empty)");
    GLPGP_CHECK(next_tok(&L->lx, &t));
    if (!t || strcmp(t, "DATASET")) return text_error(tr, GLPGP_ERR_FORMAT, 0, "expected DATASET UNSTRUCTURED_GRID");
    GLPGP_CHECK(next_tok(&L->lx, &t));
    if (!t || strcmp(t, "UNSTRUCTURED_GRID"))
        return text_error(tr, GLPGP_ERR_FORMAT, 0, "dataset %s is not supported (UNSTRUCTURED_GRID only)",
                          t ? t : "(none)");
    return GLPGP_OK;
}

static glpgp_status legacy_points(legacy *L)
{
    text_reader *tr = L->tr;
    raw_result *w = L->w;
    long long n;
    if (w->xyz) return text_error(tr, GLPGP_ERR_FORMAT, 0, "second POINTS section");
    GLPGP_CHECK(tok_ll(&L->lx, "number of points", &n));
    rest_of_line(&L->lx); /* data type */
    GLPGP_CHECK(text_check_count(tr, n, 6, "points"));
    if (n < 3) return text_error(tr, GLPGP_ERR_FORMAT, 0, "%lld points (at least 3 needed)", n);
    w->nv = n;
    return read_numbers(&L->lx, 3 * n, "POINTS", &w->xyz);
}

/* CELLS: triangles only, "3 a b c" each, integer indices. */
static glpgp_status legacy_cells(legacy *L)
{
    text_reader *tr = L->tr;
    raw_result *w = L->w;
    long long n, size;
    if (w->tri) return text_error(tr, GLPGP_ERR_FORMAT, 0, "second CELLS section");
    GLPGP_CHECK(tok_ll(&L->lx, "number of cells", &n));
    GLPGP_CHECK(tok_ll(&L->lx, "size of the cell list", &size));
    GLPGP_CHECK(text_check_count(tr, n, 8, "cells"));
    if (n < 1 || size != 4 * n) /* n <= GLPGP_IO_MAX_ITEMS: no overflow */
        return text_error(tr, GLPGP_ERR_FORMAT, 0, "CELLS must hold triangles only (%lld cells, size %lld)", n, size);
    w->nt = n;
    double *tmp = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, read_numbers(&L->lx, 4 * n, "CELLS", &tmp), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)(3 * n), sizeof *w->tri, &w->tri), done);
    for (long long c = 0; c < n; c++) {
        const double *q = tmp + 4 * c;
        for (int k = 0; k < 4; k++)
            if (q[k] != floor(q[k]) || fabs(q[k]) > 2147483647.0) {
                st = text_error(tr, GLPGP_ERR_FORMAT, 0, "cell %lld: not an integer index", c);
                goto done;
            }
        if (q[0] != 3) {
            st = text_error(tr, GLPGP_ERR_FORMAT, 0, "cell %lld is not a triangle", c);
            goto done;
        }
        for (int k = 0; k < 3; k++) w->tri[3 * c + k] = (long long)q[k + 1];
    }
done:
    free(tmp);
    return st;
}

/* CELL_TYPES: after CELLS, as many, every one a triangle (5). */
static glpgp_status legacy_cell_types(legacy *L)
{
    text_reader *tr = L->tr;
    long long n;
    if (L->ncell_types >= 0 || !L->w->tri)
        return text_error(tr, GLPGP_ERR_FORMAT, 0, "%s CELL_TYPES section",
                          L->ncell_types >= 0 ? "second" : "CELLS must come before the");
    GLPGP_CHECK(tok_ll(&L->lx, "number of cell types", &n));
    if (n != L->w->nt) return text_error(tr, GLPGP_ERR_FORMAT, 0, "CELL_TYPES %lld does not match CELLS %lld", n, L->w->nt);
    L->ncell_types = n;
    double *tmp = NULL;
    glpgp_status st = read_numbers(&L->lx, n, "CELL_TYPES", &tmp);
    for (long long c = 0; st == GLPGP_OK && c < n; c++)
        if (tmp[c] != 5) st = text_error(tr, GLPGP_ERR_FORMAT, 0, "cell %lld has type %g, not a triangle (5)", c, tmp[c]);
    free(tmp);
    return st;
}

/* POINT_DATA n / CELL_DATA n: the section that the arrays after it are in. */
static glpgp_status legacy_data_section(legacy *L, const char *t)
{
    const raw_result *w = L->w;
    long long n;
    const int cells = t[0] == 'C';
    GLPGP_CHECK(tok_ll(&L->lx, t, &n));
    if ((cells && (!w->tri || n != w->nt)) || (!cells && (!w->xyz || n != w->nv)))
        return text_error(L->tr, GLPGP_ERR_FORMAT, 0, "%s %lld does not match the %s",
                          cells ? "CELL_DATA" : "POINT_DATA", n, cells ? "cells" : "points");
    L->where = cells ? CELL_DATA : POINT_DATA;
    return GLPGP_OK;
}

/* The header of a SCALARS / VECTORS array: its name (name[64]) and
 * component count; each name at most once. */
static glpgp_status legacy_array_header(legacy *L, int vectors, char *name, long long *ncomp)
{
    text_reader *tr = L->tr;
    char *t;
    *ncomp = 3;
    GLPGP_CHECK(next_tok(&L->lx, &t));
    if (!t || strlen(t) >= 64) return text_error(tr, GLPGP_ERR_FORMAT, 0, "bad data array header");
    strcpy(name, t);
    GLPGP_CHECK(next_tok(&L->lx, &t)); /* data type */
    if (!t) return text_error(tr, GLPGP_ERR_FORMAT, 0, "bad data array header for %s", name);
    if (!vectors) { /* optional component count, then LOOKUP_TABLE name */
        char *rest = rest_of_line(&L->lx);
        *ncomp = 1;
        if (*rest && (!text_parse_ll(&rest, ncomp) || !text_at_end(rest) || *ncomp < 1 || *ncomp > 4))
            return text_error(tr, GLPGP_ERR_FORMAT, 0, "bad component count for %s", name);
        GLPGP_CHECK(next_tok(&L->lx, &t));
        if (!t || strcmp(t, "LOOKUP_TABLE")) return text_error(tr, GLPGP_ERR_FORMAT, 0, "missing LOOKUP_TABLE for %s", name);
        rest_of_line(&L->lx);
    }
    if (L->where == NONE)
        return text_error(tr, GLPGP_ERR_FORMAT, 0, "data array %s before POINT_DATA / CELL_DATA", name);
    for (int i = 0; i < L->nseen; i++)
        if (!strcmp(L->seen[i], name)) return text_error(tr, GLPGP_ERR_FORMAT, 0, "repeated data array %s", name);
    if (L->nseen == 32) return text_error(tr, GLPGP_ERR_FORMAT, 0, "more than 32 data arrays");
    strcpy(L->seen[L->nseen++], name);
    return GLPGP_OK;
}

/* A SCALARS / VECTORS array: the ones a result needs kept (z_u, z_v,
 * field_u, dirichlet_*, cross_w), the others read past. */
static glpgp_status legacy_array(legacy *L, int vectors)
{
    text_reader *tr = L->tr;
    raw_result *w = L->w;
    char name[64];
    long long ncomp;
    GLPGP_CHECK(legacy_array_header(L, vectors, name, &ncomp));
    const int pts = L->where == POINT_DATA;
    const long long n = pts ? w->nv : w->nt;
    const int is_z = pts && (!strcmp(name, "z_u") || !strcmp(name, "z_v"));
    const int is_field = pts && vectors && !strcmp(name, "field_u");
    const int is_dir = pts && (!strcmp(name, "dirichlet_u") || !strcmp(name, "dirichlet_v"));
    const int is_cross = pts && !strcmp(name, "cross_w");
    const int is_frame = pts && !strcmp(name, "field_frame");
    if (!pts && !strcmp(name, "cross_coupled")) w->coupled = 1;
    if ((is_z || is_cross || is_frame) && ncomp != 2) return text_error(tr, GLPGP_ERR_FORMAT, 0, "%s must have 2 components", name);
    if (is_dir && ncomp != 1) return text_error(tr, GLPGP_ERR_FORMAT, 0, "%s must have 1 component", name);
    double *tmp = NULL;
    GLPGP_CHECK(read_numbers(&L->lx, n * ncomp, name, (is_z || is_field || is_dir || is_cross || is_frame) ? &tmp : NULL));
    if (is_frame) {
        free(w->fframe);
        w->fframe = tmp;
    } else if (is_cross)
        w->cross = tmp;
    else if (is_z)
        w->z[name[2] == 'v'] = tmp;
    else if (is_dir)
        w->dir[name[10] == 'v'] = tmp;
    else if (is_field)
        w->field = tmp; /* 3D vectors: to the plane or the vertices' frames in assemble */
    return GLPGP_OK;
}

static glpgp_status read_legacy(text_reader *tr, raw_result *w)
{
    legacy L;
    memset(&L, 0, sizeof L);
    L.tr = tr;
    L.lx.tr = tr;
    L.w = w;
    L.ncell_types = -1;
    L.where = NONE;
    GLPGP_CHECK(legacy_header(&L));
    for (;;) {
        char *t;
        GLPGP_CHECK(next_tok(&L.lx, &t));
        if (!t) break;
        if (!strcmp(t, "POINTS"))
            GLPGP_CHECK(legacy_points(&L));
        else if (!strcmp(t, "CELLS"))
            GLPGP_CHECK(legacy_cells(&L));
        else if (!strcmp(t, "CELL_TYPES"))
            GLPGP_CHECK(legacy_cell_types(&L));
        else if (!strcmp(t, "POINT_DATA") || !strcmp(t, "CELL_DATA"))
            GLPGP_CHECK(legacy_data_section(&L, t));
        else if (!strcmp(t, "SCALARS") || !strcmp(t, "VECTORS"))
            GLPGP_CHECK(legacy_array(&L, t[0] == 'V'));
        else
            return text_error(tr, GLPGP_ERR_FORMAT, 0, "unexpected '%.40s' (not a glpgp result)", t);
    }
    return GLPGP_OK;
}

/* ---- VTK XML (.vtu) ----------------------------------------------------------------- */

static glpgp_status read_vtu(text_reader *tr, const char *first_line, raw_result *w)
{
    glpgp_status st = GLPGP_OK;
    vtu_reader v;
    GLPGP_CHECK(vtu_read_header(&v, tr, first_line));
    const char *path = tr->path;
    w->nv = v.npoints;
    w->nt = v.ncells;
    if (w->nv < 3 || w->nt < 1)
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: %lld points, %lld cells (not a triangle mesh)", path, w->nv, w->nt);
    /* the arrays this reader uses, in offset order */
    const vtu_in_array *want[12];
    int nw = 0;
    const vtu_in_array *pts = vtu_find(&v, VTU_POINTS, NULL), *conn = vtu_find(&v, VTU_CELLS, "connectivity"),
                       *offs = vtu_find(&v, VTU_CELLS, "offsets"), *types = vtu_find(&v, VTU_CELLS, "types"),
                       *h = vtu_find(&v, VTU_FIELD, "h"), *zu = vtu_find(&v, VTU_POINTDATA, "z_u"),
                       *zv = vtu_find(&v, VTU_POINTDATA, "z_v"), *fu = vtu_find(&v, VTU_POINTDATA, "field_u"),
                       *du = vtu_find(&v, VTU_POINTDATA, "dirichlet_u"),
                       *dv = vtu_find(&v, VTU_POINTDATA, "dirichlet_v"),
                       *cw = vtu_find(&v, VTU_POINTDATA, "cross_w"),
                       *ff = vtu_find(&v, VTU_POINTDATA, "field_frame");
    w->coupled = vtu_find(&v, VTU_CELLDATA, "cross_coupled") != NULL;
    if (!pts || !conn || !offs || !types)
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: Points or Cells arrays missing", path);
    if (pts->ncomp != 3 || (zu && zu->ncomp != 2) || (zv && zv->ncomp != 2) || (fu && fu->ncomp != 3) ||
        (du && du->ncomp != 1) || (dv && dv->ncomp != 1) || (cw && cw->ncomp != 2) || (ff && ff->ncomp != 2) || (h && (h->ncomp != 1 || h->ntuples != 1)))
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: an array has the wrong number of components", path);
    const vtu_in_array *all[12] = {pts, conn, offs, types, h, zu, zv, fu, du, dv, cw, ff};
    for (int i = 0; i < 12; i++)
        if (all[i]) want[nw++] = all[i];
    for (int i = 1; i < nw; i++) /* insertion sort by offset */
        for (int j = i; j > 0 && want[j]->offset < want[j - 1]->offset; j--) {
            const vtu_in_array *x = want[j];
            want[j] = want[j - 1];
            want[j - 1] = x;
        }
    for (int i = 0; i < nw; i++) {
        const vtu_in_array *a = want[i];
        if (a == pts) {
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)(3 * w->nv), &w->xyz, NULL));
        } else if (a == conn) {
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)(3 * w->nt), NULL, &w->tri));
        } else if (a == offs || a == types) {
            long long *l = NULL;
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)w->nt, NULL, &l));
            for (long long c = 0; c < w->nt; c++)
                if (a == offs ? l[c] != 3 * (c + 1) : l[c] != 5) {
                    free(l);
                    return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: cell %lld is not a triangle", path, c);
                }
            free(l);
        } else if (a == h) {
            double *x = NULL;
            GLPGP_CHECK(vtu_read_array(&v, a, 1, &x, NULL));
            w->h = x[0] >= 0 ? x[0] : 0.0;
            free(x);
        } else if (a == cw) {
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)(2 * w->nv), &w->cross, NULL));
        } else if (a == ff) {
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)(2 * w->nv), &w->fframe, NULL));
        } else if (a == zu || a == zv) {
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)(2 * w->nv), &w->z[a == zv], NULL));
        } else if (a == fu) {
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)(3 * w->nv), &w->field, NULL));
        } else {
            GLPGP_CHECK(vtu_read_array(&v, a, (size_t)w->nv, &w->dir[a == dv], NULL));
        }
    }
    return st;
}

/* ---- entry ---------------------------------------------------------------------------- */

glpgp_status glpgp_read_result(const char *path, glpgp_mesh **mout, glpgp_result **rout)
{
    glpgp_status st = GLPGP_OK;
    text_reader tr;
    raw_result w;
    memset(&w, 0, sizeof w);
    w.nv = w.nt = -1;
    *mout = NULL;
    *rout = NULL;
    GLPGP_CHECK(text_open(&tr, path));
    char *s;
    GLPGP_CHECK_GOTO(st, text_next_line(&tr, &s), done);
    if (s && !strncmp(s, "# vtk DataFile", 14)) {
        GLPGP_CHECK_GOTO(st, read_legacy(&tr, &w), done);
    } else if (s && (!strncmp(s, "<?xml", 5) || !strncmp(s, "<VTKFile", 8))) {
        GLPGP_CHECK_GOTO(st, read_vtu(&tr, s, &w), done);
    } else {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: not a VTK file (legacy .vtk or XML .vtu)", path);
        goto done;
    }
    text_close(&tr);
    GLPGP_CHECK_GOTO(st, assemble(path, &w, mout, rout), done);
done:
    text_close(&tr);
    raw_free(&w);
    return st;
}

glpgp_status glpgp_read_result_vtk(const char *path, glpgp_mesh **m, glpgp_result **r)
{
    return glpgp_read_result(path, m, r);
}
