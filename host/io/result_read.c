/* result_io.c: reader for glpgp's own legacy VTK results (see result_io.h). */
#include "glpgp/io.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct rd {
    FILE *f;
    const char *path;
    char tok[256];
} rd;

/* next whitespace-separated token; 0 at end of file */
static int next(rd *r)
{
    return fscanf(r->f, "%255s", r->tok) == 1;
}

static glpgp_status read_doubles(rd *r, double *out, long n)
{
    for (long i = 0; i < n; i++)
        if (fscanf(r->f, "%lf", &out[i]) != 1)
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: truncated or malformed data array", r->path);
    return GLPGP_OK;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

glpgp_status glpgp_read_result_vtk(const char *path, glpgp_mesh **mout, glpgp_result **rout)
{
    glpgp_status st = GLPGP_OK;
    rd r = {NULL, path, {0}};
    double *xyz = NULL, *xy = NULL, *zs[2] = {NULL, NULL}, *field = NULL, *tmp = NULL;
    int *tri = NULL, *dir[2] = {NULL, NULL};
    long nv = -1, nt = -1;
    double h = 0.0;
    glpgp_mesh *m = NULL;
    glpgp_result *res = NULL;
    *mout = NULL;
    *rout = NULL;
    r.f = fopen(path, "r");
    if (!r.f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open result '%s': %s", path, strerror(errno));
    char line[1024];
    if (!fgets(line, sizeof line, r.f) || strncmp(line, "# vtk DataFile", 14) != 0) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: not a legacy VTK file", path);
        goto done;
    }
    if (fgets(line, sizeof line, r.f)) {
        const char *p = strstr(line, " h ");
        if (p) h = atof(p + 3);
    }
    int in_cells = 0;
    while (next(&r)) {
        if (!strcmp(r.tok, "BINARY")) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: binary VTK is not supported", path);
            goto done;
        } else if (!strcmp(r.tok, "POINTS")) {
            if (fscanf(r.f, "%ld %*s", &nv) != 1 || nv < 3 || nv > 1L << 30) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad POINTS header", path);
                goto done;
            }
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv * 3, sizeof(double), &xyz), done);
            GLPGP_CHECK_GOTO(st, read_doubles(&r, xyz, 3 * nv), done);
        } else if (!strcmp(r.tok, "CELLS")) {
            long size;
            if (fscanf(r.f, "%ld %ld", &nt, &size) != 2 || nt < 1 || size != 4 * nt) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: CELLS must hold triangles only", path);
                goto done;
            }
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt * 3, sizeof(int), &tri), done);
            for (long t = 0; t < nt; t++) {
                int k;
                if (fscanf(r.f, "%d %d %d %d", &k, &tri[3 * t], &tri[3 * t + 1], &tri[3 * t + 2]) != 4 || k != 3) {
                    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: cell %ld is not a triangle", path, t);
                    goto done;
                }
            }
        } else if (!strcmp(r.tok, "CELL_DATA")) {
            in_cells = 1;
        } else if (!strcmp(r.tok, "POINT_DATA")) {
            in_cells = 0;
        } else if (!strcmp(r.tok, "SCALARS") || !strcmp(r.tok, "VECTORS")) {
            int vectors = r.tok[0] == 'V';
            char name[256], type[64];
            int ncomp = 1;
            if (fscanf(r.f, "%255s %63s", name, type) != 2) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad data array header", path);
                goto done;
            }
            if (vectors) ncomp = 3;
            else {
                /* optional component count, then LOOKUP_TABLE name */
                if (fscanf(r.f, " %d", &ncomp) != 1) ncomp = 1;
                if (!next(&r) || strcmp(r.tok, "LOOKUP_TABLE") || !next(&r)) {
                    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: missing LOOKUP_TABLE for %s", path, name);
                    goto done;
                }
            }
            long n = in_cells ? nt : nv;
            if (n < 0 || ncomp < 1 || ncomp > 4) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: data array %s before the geometry", path, name);
                goto done;
            }
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n * ncomp, sizeof(double), &tmp), done);
            GLPGP_CHECK_GOTO(st, read_doubles(&r, tmp, n * ncomp), done);
            if (!in_cells && ncomp == 2 && (!strcmp(name, "z_u") || !strcmp(name, "z_v"))) {
                int k = name[2] == 'v';
                free(zs[k]);
                zs[k] = tmp;
                tmp = NULL;
            } else if (!in_cells && vectors && !strcmp(name, "field_u")) {
                GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &field), done);
                for (long i = 0; i < nv; i++) {
                    field[2 * i] = tmp[3 * i];
                    field[2 * i + 1] = tmp[3 * i + 1];
                }
            } else if (!in_cells && ncomp == 1 && (!strcmp(name, "dirichlet_u") || !strcmp(name, "dirichlet_v"))) {
                int k = name[10] == 'v';
                free(dir[k]);
                GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &dir[k]), done);
                for (long i = 0; i < nv; i++) dir[k][i] = tmp[i] != 0.0;
            }
            free(tmp);
            tmp = NULL;
        }
    }
    if (nv < 0 || nt < 0) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no POINTS/CELLS (not a glpgp result)", path);
        goto done;
    }
    if (!zs[0] || !zs[1]) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT,
                        "%s: result file without oscillators (arrays z_u and z_v are missing); "
                        "write one with 'glpgp solve ... --out FILE.vtk'", path);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &xy), done);
    for (long i = 0; i < nv; i++) {
        xy[2 * i] = xyz[3 * i];
        xy[2 * i + 1] = xyz[3 * i + 1];
    }
    for (long t = 0; t < 3 * nt; t++)
        if (tri[t] < 0 || tri[t] >= nv) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: vertex index %d out of range", path, tri[t]);
            goto done;
        }
    GLPGP_CHECK_GOTO(st, glpgp_mesh_create((int)nv, xy, (int)nt, tri, &m), done);
    if (m->nv != nv || m->nt != nt || m->orientation_fixed) {
        /* our writer emits validated CCW meshes: anything else is not ours */
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: mesh changed on validation (not written by glpgp?)", path);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *res, &res), done);
    res->nv = (int)nv;
    res->nt = (int)nt;
    res->size = h;
    res->backend = "file";
    res->field = field;
    field = NULL;
    if (!res->field) GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &res->field), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(double), &tmp), done);
    for (int k = 0; k < 2; k++) {
        glpgp_osc_result *o = &res->osc[k];
        o->z = zs[k];
        zs[k] = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, 1, &o->dirichlet), done);
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nt, 1, &o->singular), done);
        for (long i = 0; i < nv; i++) {
            o->dirichlet[i] = dir[k] ? (unsigned char)dir[k][i] : 0;
            o->n_dirichlet += o->dirichlet[i];
            tmp[i] = hypot(o->z[2 * i], o->z[2 * i + 1]);
        }
        glpgp_singularities(m, o->z, o->singular, &o->plus, &o->minus);
        qsort(tmp, (size_t)nv, sizeof(double), cmp_d);
        o->zabs_min = tmp[0];
        o->zabs_p10 = tmp[(size_t)((nv - 1) * 0.1)];
        o->zabs_median = nv % 2 ? tmp[nv / 2] : 0.5 * (tmp[nv / 2 - 1] + tmp[nv / 2]);
    }
done:
    if (r.f) fclose(r.f);
    free(xyz);
    free(xy);
    free(tri);
    free(zs[0]);
    free(zs[1]);
    free(dir[0]);
    free(dir[1]);
    free(field);
    free(tmp);
    if (st != GLPGP_OK) {
        glpgp_mesh_destroy(&m);
        glpgp_result_destroy(&res);
    }
    *mout = m;
    *rout = res;
    return st;
}
