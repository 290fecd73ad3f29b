/* io/quadmesh_io.c: quad meshes on disk (glpgp/io.h): the JSON form of the
 * quality report, the OBJ / legacy VTK / Gmsh MSH 4.1 writers and the MSH
 * 4.1/2.2 quad/triangle reader. */
#include "glpgp/io.h"
#include "glpgp/util.h"
#include "glpgp/version.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- JSON -------------------------------------------------------------- */

static void jnum(FILE *f, double v)
{
    if (!isfinite(v))
        fputs("null", f);
    else
        fprintf(f, "%.10g", v);
}

void glpgp_quads_write_json(FILE *f, const glpgp_quad_quality *qq)
{
    fprintf(f, "{\"vertices\": %d, \"faces\": %d, \"quads\": %d, \"other_faces\": %d, ",
            qq->vertices, qq->faces, qq->quads, qq->others);
    fputs("\"other_faces_by_corners\": {", f);
    int first = 1;
    for (int b = 0; b < 8; b++) {
        if (b == 1 || !qq->others_by_size[b]) continue;
        fprintf(f, "%s\"%s%d\": %d", first ? "" : ", ", b == 7 ? ">=" : "", b + 3,
                qq->others_by_size[b]);
        first = 0;
    }
    fputs("}, \"valence\": {", f);
    for (int s = 0; s < 2; s++) {
        const int *h = s ? qq->valence_boundary : qq->valence_interior;
        fprintf(f, "%s\"%s\": {", s ? ", " : "", s ? "boundary" : "interior");
        first = 1;
        for (int v = 0; v <= GLPGP_QUAD_MAXVAL; v++) {
            if (!h[v]) continue;
            fprintf(f, "%s\"%s%d\": %d", first ? "" : ", ", v == GLPGP_QUAD_MAXVAL ? ">=" : "", v,
                    h[v]);
            first = 0;
        }
        fputs("}", f);
    }
    fprintf(f, "}, \"irregular_vertices\": {\"interior\": %d, \"boundary\": %d, \"total\": %d}, ",
            qq->irregular_interior, qq->irregular_boundary, qq->irregular);
    fputs("\"scaled_jacobian\": {\"min\": ", f);
    jnum(f, qq->sj_min);
    fputs(", \"mean\": ", f);
    jnum(f, qq->sj_mean);
    fputs(", \"p01\": ", f);
    jnum(f, qq->sj_p01);
    fprintf(f, "}, \"inverted\": %d, \"degenerate\": %d, ", qq->inverted, qq->degenerate);
    fprintf(f, "\"edges\": {\"count\": %d, \"boundary\": %d, \"nonmanifold\": %d}, ", qq->edges,
            qq->boundary_edges, qq->nonmanifold_edges);
    fputs("\"edge_length_over_h\": {\"mean\": ", f);
    jnum(f, qq->len_mean);
    fputs(", \"min\": ", f);
    jnum(f, qq->len_min);
    fputs(", \"max\": ", f);
    jnum(f, qq->len_max);
    fputs("}, \"h\": ", f);
    jnum(f, qq->h);
    fputs(", \"area\": ", f);
    jnum(f, qq->area);
    fputs(", \"domain_area\": ", f);
    if (qq->hausdorff >= 0)
        jnum(f, qq->domain_area);
    else
        fputs("null", f);
    fputs(", \"boundary_distance_over_h\": ", f);
    if (qq->hausdorff >= 0) {
        fputs("{\"hausdorff\": ", f);
        jnum(f, qq->hausdorff);
        fputs(", \"quads_to_domain\": ", f);
        jnum(f, qq->dist_quad_to_domain);
        fputs(", \"domain_to_quads\": ", f);
        jnum(f, qq->dist_domain_to_quad);
        fputs("}, \"gap_edges\": ", f);
        jnum(f, qq->gap_edges);
    } else {
        fputs("null, \"gap_edges\": null", f);
    }
    fputs(", \"singular_triangles\": ", f);
    if (qq->singular[0] >= 0)
        fprintf(f, "{\"u\": %d, \"v\": %d}", qq->singular[0], qq->singular[1]);
    else
        fputs("null", f);
    fprintf(f,
            ", \"closing\": {\"odd_faces_closed\": %d, \"strips_to_boundary\": %d, \"quads_cut\": %d, "
            "\"turns\": %d, \"even_faces_split\": %d, \"smoothed_vertices\": %d}",
            qq->closing.closed_polygons, qq->closing.strips_to_boundary, qq->closing.strip_quads, qq->closing.strip_turns, qq->closing.split_even,
            qq->closing.smoothed_vertices);
    fputs("}", f);
}

glpgp_status glpgp_quads_write_json_file(const glpgp_quad_quality *qq, const char *path)
{
    glpgp_atomic_file af;
    GLPGP_CHECK(glpgp_atomic_open(&af, path));
    fputs("{\"quads\": ", af.f);
    glpgp_quads_write_json(af.f, qq);
    fputs("}\n", af.f);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

glpgp_status glpgp_quads_append_json(const char *path, const glpgp_quad_quality *qq)
{
    FILE *f = fopen(path, "rb");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    if (!buf) {
        fclose(f);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
    }
    size_t k;
    while ((k = fread(buf + n, 1, cap - n, f)) > 0) {
        n += k;
        if (n == cap) {
            char *nb = realloc(buf, cap *= 2);
            if (!nb) {
                free(buf);
                fclose(f);
                return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
            }
            buf = nb;
        }
    }
    fclose(f);
    /* last non-space character must be the object's closing brace */
    size_t end = n;
    while (end > 0 && isspace((unsigned char)buf[end - 1])) end--;
    size_t open = 0;
    while (open < n && isspace((unsigned char)buf[open])) open++;
    if (end == 0 || buf[end - 1] != '}' || open >= n || buf[open] != '{') {
        free(buf);
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "'%s' does not hold a JSON object", path);
    }
    size_t close = end - 1;
    size_t before = close;
    while (before > 0 && isspace((unsigned char)buf[before - 1])) before--;
    int empty = buf[before - 1] == '{';
    glpgp_atomic_file af;
    glpgp_status st = glpgp_atomic_open(&af, path);
    if (st != GLPGP_OK) {
        free(buf);
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    fwrite(buf, 1, before, af.f);
    fputs(empty ? "\"quads\": " : ",\n  \"quads\": ", af.f);
    glpgp_quads_write_json(af.f, qq);
    fputs("\n}\n", af.f);
    free(buf);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

/* ---- writers ----------------------------------------------------------- */

int glpgp_quads_path_supported(const char *path)
{
    return path && (glpgp_has_ext(path, ".obj") || glpgp_has_ext(path, ".vtk") || glpgp_has_ext(path, ".msh"));
}

static void write_obj(FILE *f, const glpgp_quadmesh *q)
{
    fprintf(f, "# glpgp %s quad mesh: %d vertices, %d faces\n", GLPGP_VERSION, q->nv, q->nf);
    for (int i = 0; i < q->nv; i++) fprintf(f, "v %.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    for (int fa = 0; fa < q->nf; fa++) {
        fputc('f', f);
        for (int j = q->face_start[fa]; j < q->face_start[fa + 1]; j++)
            fprintf(f, " %d", q->face_vert[j] + 1);
        fputc('\n', f);
    }
}

static void write_vtk(FILE *f, const glpgp_quadmesh *q)
{
    fprintf(f, "# vtk DataFile Version 3.0\nglpgp %s quad mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n",
            GLPGP_VERSION);
    fprintf(f, "POINTS %d double\n", q->nv);
    for (int i = 0; i < q->nv; i++) fprintf(f, "%.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    int nfv = q->face_start[q->nf];
    fprintf(f, "CELLS %d %d\n", q->nf, q->nf + nfv);
    for (int fa = 0; fa < q->nf; fa++) {
        fprintf(f, "%d", q->face_start[fa + 1] - q->face_start[fa]);
        for (int j = q->face_start[fa]; j < q->face_start[fa + 1]; j++)
            fprintf(f, " %d", q->face_vert[j]);
        fputc('\n', f);
    }
    fprintf(f, "CELL_TYPES %d\n", q->nf);
    for (int fa = 0; fa < q->nf; fa++)
        fprintf(f, "%d\n", q->face_start[fa + 1] - q->face_start[fa] == 4 ? 9 : 7);
    fprintf(f, "CELL_DATA %d\nSCALARS corners int 1\nLOOKUP_TABLE default\n", q->nf);
    for (int fa = 0; fa < q->nf; fa++) fprintf(f, "%d\n", q->face_start[fa + 1] - q->face_start[fa]);
    fprintf(f, "SCALARS scaled_jacobian double 1\nLOOKUP_TABLE default\n");
    for (int fa = 0; fa < q->nf; fa++) fprintf(f, "%.6g\n", glpgp_quad_face_sj(q, fa));
}

static glpgp_status write_vtk_valence(FILE *f, const glpgp_quadmesh *q)
{
    int *val = NULL;
    GLPGP_CHECK(glpgp_quadmesh_valences(q, &val));
    fprintf(f, "POINT_DATA %d\nSCALARS valence int 1\nLOOKUP_TABLE default\n", q->nv);
    for (int i = 0; i < q->nv; i++) fprintf(f, "%d\n", val[i]);
    free(val);
    return GLPGP_OK;
}

static void write_msh(FILE *f, const glpgp_quadmesh *q)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < q->nv; i++) {
        x0 = fmin(x0, q->xy[2 * i]);
        x1 = fmax(x1, q->xy[2 * i]);
        y0 = fmin(y0, q->xy[2 * i + 1]);
        y1 = fmax(y1, q->xy[2 * i + 1]);
    }
    /* split every face into quads (0, 2i+1, 2i+2, 2i+3) plus one triangle
     * (0, n-2, n-1) when the corner count n is odd */
    long nquad = 0, ntri = 0;
    for (int fa = 0; fa < q->nf; fa++) {
        int k = q->face_start[fa + 1] - q->face_start[fa];
        nquad += (k - 2) / 2;
        ntri += (k % 2);
    }
    int nblocks = (nquad > 0) + (ntri > 0);
    fprintf(f, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    fprintf(f, "$Entities\n0 0 1 0\n1 %.17g %.17g 0 %.17g %.17g 0 0 0\n$EndEntities\n", x0, y0, x1,
            y1);
    fprintf(f, "$Nodes\n1 %d 1 %d\n2 1 0 %d\n", q->nv, q->nv, q->nv);
    for (int i = 0; i < q->nv; i++) fprintf(f, "%d\n", i + 1);
    for (int i = 0; i < q->nv; i++) fprintf(f, "%.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    fprintf(f, "$EndNodes\n$Elements\n%d %ld 1 %ld\n", nblocks, nquad + ntri, nquad + ntri);
    long tag = 1;
    if (nquad > 0) {
        fprintf(f, "2 1 3 %ld\n", nquad);
        for (int fa = 0; fa < q->nf; fa++) {
            const int *v = q->face_vert + q->face_start[fa];
            int k = q->face_start[fa + 1] - q->face_start[fa];
            for (int i = 0; 2 * i + 3 < k; i++)
                fprintf(f, "%ld %d %d %d %d\n", tag++, v[0] + 1, v[2 * i + 1] + 1, v[2 * i + 2] + 1,
                        v[2 * i + 3] + 1);
        }
    }
    if (ntri > 0) {
        fprintf(f, "2 1 2 %ld\n", ntri);
        for (int fa = 0; fa < q->nf; fa++) {
            const int *v = q->face_vert + q->face_start[fa];
            int k = q->face_start[fa + 1] - q->face_start[fa];
            if (k % 2) fprintf(f, "%ld %d %d %d\n", tag++, v[0] + 1, v[k - 2] + 1, v[k - 1] + 1);
        }
    }
    fprintf(f, "$EndElements\n");
}

glpgp_status glpgp_quads_write(const glpgp_quadmesh *q, const char *path)
{
    if (!q || !path) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad writer: no mesh or path");
    int kind = glpgp_has_ext(path, ".obj") ? 1 : glpgp_has_ext(path, ".vtk") ? 2 : glpgp_has_ext(path, ".msh") ? 3 : 0;
    if (!kind)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "quad mesh output '%s': extension must be .obj, .vtk or .msh",
                          path);
    glpgp_atomic_file af;
    GLPGP_CHECK(glpgp_atomic_open(&af, path));
    if (kind == 1)
        write_obj(af.f, q);
    else if (kind == 2) {
        write_vtk(af.f, q);
        glpgp_status st = write_vtk_valence(af.f, q);
        if (st != GLPGP_OK) {
            glpgp_atomic_abort(&af);
            return st;
        }
    } else
        write_msh(af.f, q);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

/* ---- MSH reader -------------------------------------------------------- */

typedef struct growi {
    int *v;
    size_t n, cap;
} growi;

static int growi_push(growi *g, int x)
{
    if (g->n == g->cap) {
        size_t nc = g->cap ? 2 * g->cap : 4096;
        int *p = realloc(g->v, nc * sizeof *p);
        if (!p) return 0;
        g->v = p;
        g->cap = nc;
    }
    g->v[g->n++] = x;
    return 1;
}

static int find_section(FILE *f, const char *name)
{
    char line[512];
    while (fgets(line, sizeof line, f)) {
        size_t n = strcspn(line, "\r\n");
        line[n] = '\0';
        if (!strcmp(line, name)) return 1;
    }
    return 0;
}

glpgp_status glpgp_quads_read_msh(const char *path, glpgp_quadmesh **out)
{
    *out = NULL;
    FILE *f = fopen(path, "r");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    glpgp_status st = GLPGP_OK;
    double ver = 0;
    int filetype = 0, dsize = 0;
    long maxtag = 0;
    double *nxy = NULL;  /* by tag */
    growi fs = {0}, fv = {0};
    int *used = NULL;
    glpgp_quadmesh *q = NULL;
    if (!find_section(f, "$MeshFormat") || fscanf(f, "%lf %d %d", &ver, &filetype, &dsize) != 3) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: not a Gmsh MSH file (no $MeshFormat)", path);
        goto done;
    }
    if (filetype != 0) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: binary MSH not supported, save as ASCII", path);
        goto done;
    }
    int v4 = ver >= 4.0;
    if (!find_section(f, "$Nodes")) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no $Nodes section", path);
        goto done;
    }
    if (v4) {
        long nblk, nnodes, mintag;
        if (fscanf(f, "%ld %ld %ld %ld", &nblk, &nnodes, &mintag, &maxtag) != 4 || maxtag < 1 ||
            maxtag > 100000000L) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Nodes header", path);
            goto done;
        }
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)maxtag + 1, 2 * sizeof(double), &nxy), done);
        long *tags = NULL;
        for (long b = 0; b < nblk; b++) {
            int edim, etag, par;
            long nin;
            if (fscanf(f, "%d %d %d %ld", &edim, &etag, &par, &nin) != 4 || nin < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node block", path);
                goto done;
            }
            long *nt = realloc(tags, (size_t)(nin + 1) * sizeof *nt);
            if (!nt) {
                free(tags);
                st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory");
                goto done;
            }
            tags = nt;
            for (long i = 0; i < nin; i++)
                if (fscanf(f, "%ld", &tags[i]) != 1 || tags[i] < 1 || tags[i] > maxtag) {
                    free(tags);
                    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node tag", path);
                    goto done;
                }
            int npar = par ? edim : 0;
            for (long i = 0; i < nin; i++) {
                double x, y, z, u;
                if (fscanf(f, "%lf %lf %lf", &x, &y, &z) != 3) {
                    free(tags);
                    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node coordinates", path);
                    goto done;
                }
                for (int k = 0; k < npar; k++)
                    if (fscanf(f, "%lf", &u) != 1) break;
                nxy[2 * tags[i]] = x;
                nxy[2 * tags[i] + 1] = y;
            }
        }
        free(tags);
    } else {
        long nnodes;
        if (fscanf(f, "%ld", &nnodes) != 1 || nnodes < 1 || nnodes > 100000000L) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Nodes header", path);
            goto done;
        }
        long pos = ftell(f);
        maxtag = 0;
        for (long i = 0; i < nnodes; i++) {
            long t;
            double x, y, z;
            if (fscanf(f, "%ld %lf %lf %lf", &t, &x, &y, &z) != 4 || t < 1) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node line", path);
                goto done;
            }
            if (t > maxtag) maxtag = t;
        }
        if (maxtag > 100000000L) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: node tag too large", path);
            goto done;
        }
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)maxtag + 1, 2 * sizeof(double), &nxy), done);
        fseek(f, pos, SEEK_SET);
        for (long i = 0; i < nnodes; i++) {
            long t;
            double x, y, z;
            if (fscanf(f, "%ld %lf %lf %lf", &t, &x, &y, &z) != 4) break;
            nxy[2 * t] = x;
            nxy[2 * t + 1] = y;
        }
    }
    if (!find_section(f, "$Elements")) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no $Elements section", path);
        goto done;
    }
    if (!growi_push(&fs, 0)) goto nomem;
    if (v4) {
        long nblk, nel, a, b;
        if (fscanf(f, "%ld %ld %ld %ld", &nblk, &nel, &a, &b) != 4) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Elements header", path);
            goto done;
        }
        for (long bl = 0; bl < nblk; bl++) {
            int edim, etag, type;
            long nin;
            if (fscanf(f, "%d %d %d %ld", &edim, &etag, &type, &nin) != 4) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad element block", path);
                goto done;
            }
            int nper = type == 15 ? 1 : type == 1 ? 2 : type == 2 ? 3 : type == 3 ? 4 : -1;
            if (nper < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: element type %d not supported (only points, "
                                                  "lines, triangles, quadrangles)", path, type);
                goto done;
            }
            for (long i = 0; i < nin; i++) {
                long t, nd[4];
                if (fscanf(f, "%ld", &t) != 1) goto badel;
                for (int k = 0; k < nper; k++)
                    if (fscanf(f, "%ld", &nd[k]) != 1 || nd[k] < 1 || nd[k] > maxtag) goto badel;
                if (type == 2 || type == 3) {
                    for (int k = 0; k < nper; k++)
                        if (!growi_push(&fv, (int)nd[k])) goto nomem;
                    if (!growi_push(&fs, (int)fv.n)) goto nomem;
                }
            }
        }
    } else {
        long nel;
        if (fscanf(f, "%ld", &nel) != 1) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Elements header", path);
            goto done;
        }
        for (long i = 0; i < nel; i++) {
            long t, type, ntag, tg, nd[4];
            if (fscanf(f, "%ld %ld %ld", &t, &type, &ntag) != 3) goto badel;
            for (long k = 0; k < ntag; k++)
                if (fscanf(f, "%ld", &tg) != 1) goto badel;
            int nper = type == 15 ? 1 : type == 1 ? 2 : type == 2 ? 3 : type == 3 ? 4 : -1;
            if (nper < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: element type %ld not supported", path, type);
                goto done;
            }
            for (int k = 0; k < nper; k++)
                if (fscanf(f, "%ld", &nd[k]) != 1 || nd[k] < 1 || nd[k] > maxtag) goto badel;
            if (type == 2 || type == 3) {
                for (int k = 0; k < nper; k++)
                    if (!growi_push(&fv, (int)nd[k])) goto nomem;
                if (!growi_push(&fs, (int)fv.n)) goto nomem;
            }
        }
    }
    if (fs.n < 2) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no triangles or quadrangles", path);
        goto done;
    }
    /* renumber the used nodes, orient faces counter-clockwise */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)maxtag + 1, sizeof(int), &used), done);
    for (long i = 0; i <= maxtag; i++) used[i] = -1;
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *q, &q), done);
    int nv = 0;
    for (size_t i = 0; i < fv.n; i++)
        if (used[fv.v[i]] < 0) used[fv.v[i]] = nv++;
    q->nv = nv;
    q->nf = (int)fs.n - 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &q->xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(fs.n, sizeof(int), &q->face_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(fv.n, sizeof(int), &q->face_vert), done);
    for (long t = 1; t <= maxtag; t++)
        if (used[t] >= 0) {
            q->xy[2 * used[t]] = nxy[2 * t];
            q->xy[2 * used[t] + 1] = nxy[2 * t + 1];
        }
    memcpy(q->face_start, fs.v, fs.n * sizeof(int));
    for (size_t i = 0; i < fv.n; i++) q->face_vert[i] = used[fv.v[i]];
    for (int fa = 0; fa < q->nf; fa++) {
        int s = q->face_start[fa], k = q->face_start[fa + 1] - s;
        int *v = q->face_vert + s;
        double a = 0.0;
        for (int i = 0; i < k; i++) {
            int p = v[i], r = v[(i + 1) % k];
            a += q->xy[2 * p] * q->xy[2 * r + 1] - q->xy[2 * r] * q->xy[2 * p + 1];
        }
        if (a < 0)
            for (int i = 0; i < k / 2; i++) {
                int tmp = v[i];
                v[i] = v[k - 1 - i];
                v[k - 1 - i] = tmp;
            }
    }
    *out = q;
    q = NULL;
    goto done;
badel:
    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad element line", path);
    goto done;
nomem:
    st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
done:
    fclose(f);
    free(nxy);
    free(fs.v);
    free(fv.v);
    free(used);
    glpgp_quadmesh_destroy(&q);
    return st;
}

