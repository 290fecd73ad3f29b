/* io/mesh_io.c: triangle-mesh readers (Wavefront OBJ; Gmsh MSH 2.2 / 4.1
 * ASCII through the shared parser of msh_read.c) and writers (OBJ, MSH 4.1,
 * through the output set), glpgp/io.h. Readers are one pass over a
 * text_reader, check planarity, drop unused vertices and hand the triangles
 * to glpgp_mesh_create for validation. */
#include "glpgp/io.h"
#include "glpgp/util.h"

#include "msh.h"
#include "text_reader.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- raw (unvalidated) mesh: 3D points and triangles --------------------- */

typedef struct raw_mesh {
    double *xyz;
    size_t nv, cap_v;
    int *tri;
    size_t nt, cap_t;
} raw_mesh;

static void raw_free(raw_mesh *r)
{
    free(r->xyz);
    free(r->tri);
    memset(r, 0, sizeof *r);
}

static glpgp_status raw_add_tri(raw_mesh *r, int a, int b, int c)
{
    GLPGP_CHECK(glpgp_grow(&r->tri, &r->cap_t, r->nt + 1, 3 * sizeof(int)));
    int *t = r->tri + 3 * r->nt++;
    t[0] = a;
    t[1] = b;
    t[2] = c;
    return GLPGP_OK;
}

/* Planarity check, removal of unused vertices, then glpgp_mesh_create. */
static glpgp_status finish(const char *path, raw_mesh *r, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    int *map = NULL;
    double *xy = NULL;
    if (r->nt == 0) return GLPGP_FAIL(GLPGP_ERR_MESH, "%s: no triangles", path);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(r->nv, sizeof *map, &map), done);
    for (size_t v = 0; v < r->nv; v++) map[v] = -1;
    for (size_t i = 0; i < 3 * r->nt; i++) map[r->tri[i]] = 0;
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    double zmin = HUGE_VAL, zmax = -HUGE_VAL;
    int nv = 0;
    for (size_t v = 0; v < r->nv; v++) {
        if (map[v] < 0) continue;
        map[v] = nv++;
        const double *p = r->xyz + 3 * v;
        xmin = fmin(xmin, p[0]);
        xmax = fmax(xmax, p[0]);
        ymin = fmin(ymin, p[1]);
        ymax = fmax(ymax, p[1]);
        zmin = fmin(zmin, p[2]);
        zmax = fmax(zmax, p[2]);
    }
    double size = fmax(xmax - xmin, ymax - ymin);
    if (zmax - zmin > 1e-9 * size) {
        st = GLPGP_FAIL(GLPGP_ERR_MESH, "%s: mesh is not planar: z varies from %.17g to %.17g", path,
                        zmin, zmax);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv * 2, sizeof *xy, &xy), done);
    for (size_t v = 0; v < r->nv; v++) {
        if (map[v] < 0) continue;
        xy[2 * map[v]] = r->xyz[3 * v];
        xy[2 * map[v] + 1] = r->xyz[3 * v + 1];
    }
    for (size_t i = 0; i < 3 * r->nt; i++) r->tri[i] = map[r->tri[i]];
    if ((st = glpgp_mesh_create(nv, xy, (int)r->nt, r->tri, out)) != GLPGP_OK)
        io_name_error(path, st); /* "FILE: the mesh folds over itself ..." */
done:
    free(map);
    free(xy);
    return st;
}

/* ---- OBJ ------------------------------------------------------------------ */

static int cmp_ll(const void *a, const void *b)
{
    long long x = *(const long long *)a, y = *(const long long *)b;
    return (x > y) - (x < y);
}

/* One pass: positive indices may refer to vertices defined later, so the
 * largest one is checked at the end (with the line it appeared on). */
static glpgp_status read_obj(text_reader *tr, raw_mesh *r)
{
    glpgp_status st = GLPGP_OK;
    long long *corners = NULL; /* vertex indices of the current face (0-based) */
    size_t ncap = 0;
    long long max_index = 0; /* largest positive index used, 1-based */
    long max_line = 0;
    char *s;
    for (;;) {
        GLPGP_CHECK_GOTO(st, text_next_line(tr, &s), done);
        if (!s) break;
        s = text_skip_ws(s);
        if (*s == '\0' || *s == '#') continue;
        char *kw = s;
        while (*s && !isspace((unsigned char)*s)) s++;
        size_t kl = (size_t)(s - kw);
        if (kl == 1 && kw[0] == 'v') {
            double c[7];
            int n = 0;
            while (n < 7 && text_parse_double(&s, &c[n])) n++;
            if (!text_at_end(s)) {
                st = text_error(tr, GLPGP_ERR_FORMAT, 0,
                                "malformed vertex (expected finite numbers: v x y [z [w]])");
                goto done;
            }
            if (n < 2) {
                st = text_error(tr, GLPGP_ERR_FORMAT, 0, "vertex needs at least x and y");
                goto done;
            }
            if (r->nv >= (size_t)GLPGP_IO_MAX_ITEMS) {
                st = text_error(tr, GLPGP_ERR_LIMIT, 0, "more than %ld vertices", (long)GLPGP_IO_MAX_ITEMS);
                goto done;
            }
            GLPGP_CHECK_GOTO(st, glpgp_grow(&r->xyz, &r->cap_v, r->nv + 1, 3 * sizeof(double)), done);
            double *p = r->xyz + 3 * r->nv++;
            p[0] = c[0];
            p[1] = c[1];
            p[2] = n >= 3 ? c[2] : 0.0;
        } else if (kl == 1 && kw[0] == 'f') {
            size_t n = 0;
            for (;;) {
                s = text_skip_ws(s);
                if (*s == '\0') break;
                char *tok = s, *e;
                errno = 0;
                long long idx = strtoll(tok, &e, 10);
                if (e == tok || errno == ERANGE) {
                    st = text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed face index '%.40s'", tok);
                    goto done;
                }
                /* optional /vt/vn parts: digits, signs and slashes only */
                if (*e == '/') {
                    while (*e && !isspace((unsigned char)*e)) {
                        if (!(isdigit((unsigned char)*e) || *e == '/' || *e == '-')) {
                            st = text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed face corner '%.40s'", tok);
                            goto done;
                        }
                        e++;
                    }
                } else if (*e && !isspace((unsigned char)*e)) {
                    st = text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed face index '%.40s'", tok);
                    goto done;
                }
                s = e;
                long long v;
                if (idx > 0) {
                    v = idx - 1;
                    if (idx > max_index) {
                        max_index = idx;
                        max_line = tr->line;
                    }
                } else if (idx < 0) {
                    v = (long long)r->nv + idx;
                    if (v < 0) {
                        st = text_error(tr, GLPGP_ERR_FORMAT, 0,
                                        "relative face index %lld refers before the first vertex (%zu "
                                        "defined so far)",
                                        idx, r->nv);
                        goto done;
                    }
                } else {
                    st = text_error(tr, GLPGP_ERR_FORMAT, 0, "face index 0 is invalid (OBJ indices start at 1)");
                    goto done;
                }
                GLPGP_CHECK_GOTO(st, glpgp_grow(&corners, &ncap, n + 1, sizeof *corners), done);
                corners[n++] = v;
            }
            if (n < 3) {
                st = text_error(tr, GLPGP_ERR_FORMAT, 0, "face with %zu corner%s (at least 3 needed)", n,
                                n == 1 ? "" : "s");
                goto done;
            }
            /* a face uses each vertex once (checked on a sorted copy) */
            GLPGP_CHECK_GOTO(st, glpgp_grow(&corners, &ncap, 2 * n, sizeof *corners), done);
            memcpy(corners + n, corners, n * sizeof *corners);
            qsort(corners + n, n, sizeof *corners, cmp_ll);
            for (size_t i = n + 1; i < 2 * n; i++)
                if (corners[i] == corners[i - 1]) {
                    st = text_error(tr, GLPGP_ERR_FORMAT, 0, "face uses vertex %lld more than once", corners[i] + 1);
                    goto done;
                }
            /* fan triangulation (c0, ci, ci+1) */
            for (size_t i = 1; i + 1 < n; i++) {
                long long a = corners[0], b = corners[i], c = corners[i + 1];
                if (a > GLPGP_IO_MAX_ITEMS || b > GLPGP_IO_MAX_ITEMS || c > GLPGP_IO_MAX_ITEMS) {
                    st = text_error(tr, GLPGP_ERR_FORMAT, 0, "face index out of range");
                    goto done;
                }
                if (r->nt >= (size_t)GLPGP_IO_MAX_ITEMS) {
                    st = text_error(tr, GLPGP_ERR_LIMIT, 0, "more than %ld triangles", (long)GLPGP_IO_MAX_ITEMS);
                    goto done;
                }
                GLPGP_CHECK_GOTO(st, raw_add_tri(r, (int)a, (int)b, (int)c), done);
            }
        } else if ((kl == 2 && (!strncmp(kw, "vt", 2) || !strncmp(kw, "vn", 2) || !strncmp(kw, "vp", 2))) ||
                   (kl == 1 && (kw[0] == 'o' || kw[0] == 'g' || kw[0] == 's' || kw[0] == 'l' || kw[0] == 'p')) ||
                   (kl == 6 && (!strncmp(kw, "usemtl", 6) || !strncmp(kw, "mtllib", 6)))) {
            continue; /* ignored statements */
        } else {
            st = text_error(tr, GLPGP_ERR_FORMAT, 0, "unknown OBJ statement '%.*s'", (int)(kl > 40 ? 40 : kl), kw);
            goto done;
        }
    }
    if (max_index > (long long)r->nv) {
        st = text_error(tr, GLPGP_ERR_FORMAT, max_line, "face index %lld out of range (%zu vertices)", max_index,
                        r->nv);
        goto done;
    }
done:
    free(corners);
    return st;
}

/* ---- MSH: triangles of the shared parser ------------------------------------ */

static glpgp_status read_msh(const char *path, raw_mesh *r)
{
    msh_data d;
    GLPGP_CHECK(msh_read(path, &d));
    /* take the nodes as they are; keep the triangles */
    r->xyz = d.xyz;
    r->nv = r->cap_v = (size_t)d.nv;
    d.xyz = NULL;
    glpgp_status st = GLPGP_OK;
    if (d.ntri > 0) GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)d.ntri * 3, sizeof(int), &r->tri), done);
    r->cap_t = (size_t)d.ntri;
    for (long f = 0; f < d.nf; f++) {
        const int *c = d.corner + 4 * f;
        if (c[3] >= 0) continue;
        int *t = r->tri + 3 * r->nt++;
        t[0] = c[0];
        t[1] = c[1];
        t[2] = c[2];
    }
done:
    msh_free(&d);
    return st;
}

/* ---- entry points -------------------------------------------------------------- */

static int mesh_kind(const char *path)
{
    return glpgp_has_ext(path, ".obj") ? 1 : glpgp_has_ext(path, ".msh") ? 2 : 0;
}

/* Lower-case extension of path (without the dot) into ext; "" when none. */
static void path_ext(const char *path, char *ext, size_t n)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(path, '.');
    ext[0] = '\0';
    if (!dot || (slash && dot < slash)) return;
    size_t i = 0;
    for (const char *p = dot + 1; *p && i + 1 < n; p++) ext[i++] = (char)tolower((unsigned char)*p);
    ext[i] = '\0';
}

glpgp_status glpgp_mesh_read(const char *path, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    raw_mesh r;
    memset(&r, 0, sizeof r);
    if (!out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_read: out is NULL");
    *out = NULL;
    if (!path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_read: path is NULL");
    int kind = mesh_kind(path);
    if (!kind) {
        char ext[16];
        path_ext(path, ext, sizeof ext);
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: unknown mesh file extension '%s' (supported: .obj, .msh)", path, ext);
    }
    if (kind == 1) {
        text_reader tr;
        GLPGP_CHECK(text_open(&tr, path));
        st = read_obj(&tr, &r);
        text_close(&tr);
        if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    } else {
        st = read_msh(path, &r);
    }
    if (st == GLPGP_OK) GLPGP_CHECK_GOTO(st, finish(path, &r, out), done);
done:
    raw_free(&r);
    return st;
}

static void write_obj(FILE *f, const glpgp_mesh *m)
{
    fprintf(f, "# glpgp mesh: %d vertices, %d triangles\n", m->nv, m->nt);
    for (int v = 0; v < m->nv; v++) fprintf(f, "v %.17g %.17g 0\n", m->xy[2 * v], m->xy[2 * v + 1]);
    for (int t = 0; t < m->nt; t++)
        fprintf(f, "f %d %d %d\n", m->tri[3 * t] + 1, m->tri[3 * t + 1] + 1, m->tri[3 * t + 2] + 1);
}

static void write_msh(FILE *f, const glpgp_mesh *m)
{
    fprintf(f, "$MeshFormat\n4.1 0 %d\n$EndMeshFormat\n", (int)sizeof(size_t));
    fprintf(f, "$Entities\n0 0 1 0\n1 %.17g %.17g 0 %.17g %.17g 0 0 0\n$EndEntities\n", m->bbox[0], m->bbox[1],
            m->bbox[2], m->bbox[3]);
    fprintf(f, "$Nodes\n1 %d 1 %d\n2 1 0 %d\n", m->nv, m->nv, m->nv);
    for (int v = 0; v < m->nv; v++) fprintf(f, "%d\n", v + 1);
    for (int v = 0; v < m->nv; v++) fprintf(f, "%.17g %.17g 0\n", m->xy[2 * v], m->xy[2 * v + 1]);
    fprintf(f, "$EndNodes\n$Elements\n1 %d 1 %d\n2 1 2 %d\n", m->nt, m->nt, m->nt);
    for (int t = 0; t < m->nt; t++)
        fprintf(f, "%d %d %d %d\n", t + 1, m->tri[3 * t] + 1, m->tri[3 * t + 1] + 1, m->tri[3 * t + 2] + 1);
    fprintf(f, "$EndElements\n");
}

glpgp_status glpgp_output_set_mesh(glpgp_output_set *s, const glpgp_mesh *m, const char *path)
{
    if (!m || !path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_write: NULL argument");
    int kind = mesh_kind(path);
    if (!kind) {
        char ext[16];
        path_ext(path, ext, sizeof ext);
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: unknown mesh file extension '%s' (supported: .obj, .msh)", path, ext);
    }
    FILE *f;
    GLPGP_CHECK(glpgp_output_set_open(s, path, &f));
    if (kind == 1)
        write_obj(f, m);
    else
        write_msh(f, m);
    return GLPGP_OK;
}

glpgp_status glpgp_mesh_write(const glpgp_mesh *m, const char *path)
{
    glpgp_output_set *s = NULL;
    GLPGP_CHECK(glpgp_output_set_create(&s));
    glpgp_status st = glpgp_output_set_mesh(s, m, path);
    if (st == GLPGP_OK) st = glpgp_output_set_commit(s);
    glpgp_output_set_destroy(&s);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}
