/* mesh_io.c: mesh readers (Wavefront OBJ, Gmsh MSH 2.2 and 4.1 ASCII) and
 * writers (OBJ, MSH 4.1 ASCII, written atomically via temp file + rename).
 * Readers check planarity, drop unused vertices and hand the triangles to
 * glpgp_mesh_create for validation. */
#include "glpgp/mesh.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ------------------------------------------------------------------------ */
/* Shared helpers                                                            */

/* Raw (unvalidated) mesh as read from a file: 3D points and triangles. */
typedef struct raw_mesh {
    double *xyz;
    long nv, cap_v;
    int *tri;
    long nt, cap_t;
} raw_mesh;

static void raw_free(raw_mesh *r)
{
    free(r->xyz);
    free(r->tri);
    memset(r, 0, sizeof *r);
}

static glpgp_status raw_add_vertex(raw_mesh *r, double x, double y, double z)
{
    if (r->nv == r->cap_v) {
        long cap = r->cap_v ? 2 * r->cap_v : 1024;
        if (cap > INT32_MAX) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "too many vertices");
        double *p = realloc(r->xyz, (size_t)cap * 3 * sizeof *p);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading vertices");
        r->xyz = p;
        r->cap_v = cap;
    }
    r->xyz[3 * r->nv] = x;
    r->xyz[3 * r->nv + 1] = y;
    r->xyz[3 * r->nv + 2] = z;
    r->nv++;
    return GLPGP_OK;
}

static glpgp_status raw_add_tri(raw_mesh *r, int a, int b, int c)
{
    if (r->nt == r->cap_t) {
        long cap = r->cap_t ? 2 * r->cap_t : 2048;
        if (cap > INT32_MAX / 3) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "too many triangles");
        int *p = realloc(r->tri, (size_t)cap * 3 * sizeof *p);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading triangles");
        r->tri = p;
        r->cap_t = cap;
    }
    r->tri[3 * r->nt] = a;
    r->tri[3 * r->nt + 1] = b;
    r->tri[3 * r->nt + 2] = c;
    r->nt++;
    return GLPGP_OK;
}

/* Reader context: file name and the buffer split into lines. */
typedef struct reader {
    const char *path;
    char *buf;
    size_t len;
    char *cur;  /* start of the next line */
    int line;   /* number of the line last returned (1-based) */
} reader;

/* Record a GLPGP_ERR_FORMAT error "path:line: message". */
static glpgp_status ferr(const reader *rd, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static glpgp_status ferr(const reader *rd, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: %s", rd->path, line, msg);
}

static glpgp_status read_all(const char *path, char **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open %s: %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *b = malloc(cap + 1);
    if (!b) {
        fclose(f);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading %s", path);
    }
    for (;;) {
        if (n == cap) {
            char *nb = realloc(b, 2 * cap + 1);
            if (!nb) {
                free(b);
                fclose(f);
                return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading %s", path);
            }
            b = nb;
            cap *= 2;
        }
        size_t got = fread(b + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        int e = errno;
        free(b);
        fclose(f);
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read %s: %s", path, strerror(e ? e : EIO));
    }
    fclose(f);
    b[n] = '\0';
    *buf = b;
    *len = n;
    return GLPGP_OK;
}

/* Next line (NUL-terminated in place, trailing CR and blanks removed), or NULL at EOF. */
static char *next_line(reader *rd)
{
    char *end = rd->buf + rd->len;
    if (rd->cur >= end) return NULL;
    char *s = rd->cur;
    char *nl = memchr(s, '\n', (size_t)(end - s));
    char *e = nl ? nl : end;
    rd->cur = nl ? nl + 1 : end;
    *e = '\0';
    while (e > s && isspace((unsigned char)e[-1])) *--e = '\0';
    rd->line++;
    return s;
}

static char *skip_ws(char *p)
{
    while (*p && isspace((unsigned char)*p)) p++;
    return p;
}

/* Parse a whitespace-delimited integer / double at *p; advance *p. */
static int parse_long(char **p, long *out)
{
    char *s = skip_ws(*p), *e;
    errno = 0;
    long v = strtol(s, &e, 10);
    if (e == s || errno == ERANGE || (*e && !isspace((unsigned char)*e))) return 0;
    *out = v;
    *p = e;
    return 1;
}

static int parse_double(char **p, double *out)
{
    char *s = skip_ws(*p), *e;
    double v = strtod(s, &e);
    if (e == s || (*e && !isspace((unsigned char)*e)) || !isfinite(v)) return 0;
    *out = v;
    *p = e;
    return 1;
}

static int at_end(char *p) { return *skip_ws(p) == '\0'; }

/* Planarity check, removal of unused vertices, then glpgp_mesh_create. */
static glpgp_status finish(const char *path, raw_mesh *r, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    int *map = NULL;
    double *xy = NULL;
    if (r->nt == 0) return GLPGP_FAIL(GLPGP_ERR_MESH, "%s: no triangles", path);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)r->nv, sizeof *map, &map), done);
    for (long v = 0; v < r->nv; v++) map[v] = -1;
    for (long i = 0; i < 3 * r->nt; i++) map[r->tri[i]] = 0;
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    double zmin = HUGE_VAL, zmax = -HUGE_VAL;
    int nv = 0;
    for (long v = 0; v < r->nv; v++) {
        if (map[v] < 0) continue;
        map[v] = nv++;
        const double *p = r->xyz + 3 * v;
        if (p[0] < xmin) xmin = p[0];
        if (p[0] > xmax) xmax = p[0];
        if (p[1] < ymin) ymin = p[1];
        if (p[1] > ymax) ymax = p[1];
        if (p[2] < zmin) zmin = p[2];
        if (p[2] > zmax) zmax = p[2];
    }
    double size = fmax(xmax - xmin, ymax - ymin);
    if (zmax - zmin > 1e-9 * size) {
        st = GLPGP_FAIL(GLPGP_ERR_MESH, "%s: mesh is not planar: z varies from %.17g to %.17g", path,
                        zmin, zmax);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv * 2, sizeof *xy, &xy), done);
    for (long v = 0; v < r->nv; v++) {
        if (map[v] < 0) continue;
        xy[2 * map[v]] = r->xyz[3 * v];
        xy[2 * map[v] + 1] = r->xyz[3 * v + 1];
    }
    for (long i = 0; i < 3 * r->nt; i++) r->tri[i] = map[r->tri[i]];
    GLPGP_CHECK_GOTO(st, glpgp_mesh_create(nv, xy, (int)r->nt, r->tri, out), done);
done:
    free(map);
    free(xy);
    return st;
}

/* ------------------------------------------------------------------------ */
/* OBJ                                                                        */

static int obj_is_vertex_line(const char *s) { return s[0] == 'v' && (s[1] == ' ' || s[1] == '\t'); }

static glpgp_status read_obj(reader *rd, raw_mesh *r)
{
    glpgp_status st = GLPGP_OK;
    int *corners = NULL;
    long ncap = 0;
    /* Pass 1: total number of vertices (for range checks of positive indices). */
    long total = 0;
    {
        const char *p = rd->buf, *end = rd->buf + rd->len;
        while (p < end) {
            while (p < end && (*p == ' ' || *p == '\t')) p++;
            if (p + 1 < end && obj_is_vertex_line(p)) total++;
            const char *nl = memchr(p, '\n', (size_t)(end - p));
            p = nl ? nl + 1 : end;
        }
    }
    if (total > INT32_MAX) return ferr(rd, 1, "too many vertices (%ld)", total);
    char *s;
    while ((s = next_line(rd)) != NULL) {
        s = skip_ws(s);
        if (*s == '\0' || *s == '#') continue;
        char *kw = s;
        while (*s && !isspace((unsigned char)*s)) s++;
        size_t kl = (size_t)(s - kw);
        if (kl == 1 && kw[0] == 'v') {
            double c[7];
            int n = 0;
            while (n < 7 && parse_double(&s, &c[n])) n++;
            if (!at_end(s)) {
                st = ferr(rd, rd->line, "malformed vertex (expected numbers: v x y [z [w]])");
                goto done;
            }
            if (n < 2) {
                st = ferr(rd, rd->line, "vertex needs at least x and y");
                goto done;
            }
            GLPGP_CHECK_GOTO(st, raw_add_vertex(r, c[0], c[1], n >= 3 ? c[2] : 0.0), done);
        } else if (kl == 1 && kw[0] == 'f') {
            long n = 0;
            for (;;) {
                s = skip_ws(s);
                if (*s == '\0') break;
                char *tok = s, *e;
                errno = 0;
                long idx = strtol(tok, &e, 10);
                if (e == tok || errno == ERANGE) {
                    st = ferr(rd, rd->line, "malformed face index '%.40s'", tok);
                    goto done;
                }
                /* Optional /vt/vn parts: digits, signs and slashes only. */
                if (*e == '/') {
                    while (*e && !isspace((unsigned char)*e)) {
                        if (!(isdigit((unsigned char)*e) || *e == '/' || *e == '-')) {
                            st = ferr(rd, rd->line, "malformed face corner '%.40s'", tok);
                            goto done;
                        }
                        e++;
                    }
                } else if (*e && !isspace((unsigned char)*e)) {
                    st = ferr(rd, rd->line, "malformed face index '%.40s'", tok);
                    goto done;
                }
                s = e;
                long v;
                if (idx > 0) {
                    v = idx - 1;
                    if (v >= total) {
                        st = ferr(rd, rd->line, "face index %ld out of range (%ld vertices)", idx, total);
                        goto done;
                    }
                } else if (idx < 0) {
                    v = r->nv + idx;
                    if (v < 0) {
                        st = ferr(rd, rd->line, "relative face index %ld refers before the first vertex (%ld defined so far)",
                                  idx, r->nv);
                        goto done;
                    }
                } else {
                    st = ferr(rd, rd->line, "face index 0 is invalid (OBJ indices start at 1)");
                    goto done;
                }
                if (n == ncap) {
                    long cap = ncap ? 2 * ncap : 16;
                    int *p = realloc(corners, (size_t)cap * sizeof *p);
                    if (!p) {
                        st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading faces");
                        goto done;
                    }
                    corners = p;
                    ncap = cap;
                }
                corners[n++] = (int)v;
            }
            if (n < 3) {
                st = ferr(rd, rd->line, "face with %ld corner%s (at least 3 needed)", n, n == 1 ? "" : "s");
                goto done;
            }
            for (long i = 1; i + 1 < n; i++)
                GLPGP_CHECK_GOTO(st, raw_add_tri(r, corners[0], corners[i], corners[i + 1]), done);
        } else if ((kl == 2 && (!strncmp(kw, "vt", 2) || !strncmp(kw, "vn", 2) || !strncmp(kw, "vp", 2))) ||
                   (kl == 1 && (kw[0] == 'o' || kw[0] == 'g' || kw[0] == 's' || kw[0] == 'l' || kw[0] == 'p')) ||
                   (kl == 6 && (!strncmp(kw, "usemtl", 6) || !strncmp(kw, "mtllib", 6)))) {
            continue; /* ignored statements */
        } else {
            st = ferr(rd, rd->line, "unknown OBJ statement '%.*s'", (int)(kl > 40 ? 40 : kl), kw);
            goto done;
        }
    }
done:
    free(corners);
    return st;
}

/* ------------------------------------------------------------------------ */
/* Gmsh MSH                                                                   */

/* Node tag -> vertex index map: dense array when tags are compact, sorted
 * (tag, index) pairs otherwise. */
typedef struct tag_pair {
    long tag;
    int idx;
} tag_pair;

typedef struct msh_state {
    long *tags;  /* node tag of every vertex read so far */
    long ntags_cap;
    int *dense;  /* tag -> index (or -1), size dense_n */
    long dense_n;
    tag_pair *pairs; /* sorted, when not dense */
    long npairs;
    int have_map;
} msh_state;

static void msh_free(msh_state *s)
{
    free(s->tags);
    free(s->dense);
    free(s->pairs);
    memset(s, 0, sizeof *s);
}

static int cmp_pair(const void *a, const void *b)
{
    long x = ((const tag_pair *)a)->tag, y = ((const tag_pair *)b)->tag;
    return x < y ? -1 : x > y;
}

static glpgp_status msh_add_node(msh_state *ms, raw_mesh *r, reader *rd, long tag, double x, double y, double z)
{
    if (tag < 0) return ferr(rd, rd->line, "negative node tag %ld", tag);
    if (r->nv == ms->ntags_cap) {
        long cap = ms->ntags_cap ? 2 * ms->ntags_cap : 1024;
        long *p = realloc(ms->tags, (size_t)cap * sizeof *p);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading nodes");
        ms->tags = p;
        ms->ntags_cap = cap;
    }
    ms->tags[r->nv] = tag;
    ms->have_map = 0;
    return raw_add_vertex(r, x, y, z);
}

static glpgp_status msh_build_map(msh_state *ms, const raw_mesh *r, reader *rd)
{
    free(ms->dense);
    free(ms->pairs);
    ms->dense = NULL;
    ms->pairs = NULL;
    long maxtag = -1;
    for (long v = 0; v < r->nv; v++)
        if (ms->tags[v] > maxtag) maxtag = ms->tags[v];
    if (maxtag < 8 * r->nv + 1024) {
        ms->dense_n = maxtag + 1;
        GLPGP_CHECK(glpgp_malloc((size_t)ms->dense_n, sizeof *ms->dense, &ms->dense));
        for (long t = 0; t < ms->dense_n; t++) ms->dense[t] = -1;
        for (long v = 0; v < r->nv; v++) {
            if (ms->dense[ms->tags[v]] >= 0) return ferr(rd, rd->line, "duplicate node tag %ld", ms->tags[v]);
            ms->dense[ms->tags[v]] = (int)v;
        }
    } else {
        GLPGP_CHECK(glpgp_malloc((size_t)r->nv, sizeof *ms->pairs, &ms->pairs));
        for (long v = 0; v < r->nv; v++) {
            ms->pairs[v].tag = ms->tags[v];
            ms->pairs[v].idx = (int)v;
        }
        qsort(ms->pairs, (size_t)r->nv, sizeof *ms->pairs, cmp_pair);
        ms->npairs = r->nv;
        for (long v = 1; v < r->nv; v++)
            if (ms->pairs[v].tag == ms->pairs[v - 1].tag)
                return ferr(rd, rd->line, "duplicate node tag %ld", ms->pairs[v].tag);
    }
    ms->have_map = 1;
    return GLPGP_OK;
}

/* Vertex index of node tag, or -1. */
static int msh_lookup(const msh_state *ms, long tag)
{
    if (ms->dense) return (tag >= 0 && tag < ms->dense_n) ? ms->dense[tag] : -1;
    long lo = 0, hi = ms->npairs - 1;
    while (lo <= hi) {
        long mid = lo + (hi - lo) / 2;
        if (ms->pairs[mid].tag == tag) return ms->pairs[mid].idx;
        if (ms->pairs[mid].tag < tag) lo = mid + 1;
        else hi = mid - 1;
    }
    return -1;
}

/* Next line inside a section; error if the file ends. */
static glpgp_status msh_line(reader *rd, const char *section, char **out)
{
    *out = next_line(rd);
    if (!*out) return ferr(rd, rd->line, "unexpected end of file in $%s", section);
    return GLPGP_OK;
}

static glpgp_status msh_expect_end(reader *rd, const char *section)
{
    char *s;
    GLPGP_CHECK(msh_line(rd, section, &s));
    s = skip_ws(s);
    if (s[0] != '$' || strncmp(s + 1, "End", 3) || strcmp(s + 4, section))
        return ferr(rd, rd->line, "expected $End%s", section);
    return GLPGP_OK;
}

static glpgp_status msh_triangle(msh_state *ms, raw_mesh *r, reader *rd, const long n[3])
{
    int v[3];
    if (!ms->have_map) {
        if (r->nv == 0) return ferr(rd, rd->line, "$Elements before $Nodes");
        GLPGP_CHECK(msh_build_map(ms, r, rd));
    }
    for (int k = 0; k < 3; k++) {
        v[k] = msh_lookup(ms, n[k]);
        if (v[k] < 0) return ferr(rd, rd->line, "triangle references unknown node %ld", n[k]);
    }
    return raw_add_tri(r, v[0], v[1], v[2]);
}

static glpgp_status msh22_nodes(msh_state *ms, raw_mesh *r, reader *rd)
{
    char *s;
    long n;
    GLPGP_CHECK(msh_line(rd, "Nodes", &s));
    if (!parse_long(&s, &n) || n < 0 || !at_end(s)) return ferr(rd, rd->line, "expected the number of nodes");
    for (long i = 0; i < n; i++) {
        long tag;
        double x, y, z;
        GLPGP_CHECK(msh_line(rd, "Nodes", &s));
        if (!parse_long(&s, &tag) || !parse_double(&s, &x) || !parse_double(&s, &y) || !parse_double(&s, &z))
            return ferr(rd, rd->line, "malformed node line (expected: tag x y z)");
        GLPGP_CHECK(msh_add_node(ms, r, rd, tag, x, y, z));
    }
    return msh_expect_end(rd, "Nodes");
}

static glpgp_status msh22_elements(msh_state *ms, raw_mesh *r, reader *rd)
{
    char *s;
    long n;
    GLPGP_CHECK(msh_line(rd, "Elements", &s));
    if (!parse_long(&s, &n) || n < 0 || !at_end(s)) return ferr(rd, rd->line, "expected the number of elements");
    for (long i = 0; i < n; i++) {
        long id, type, ntags, tmp, nodes[3];
        GLPGP_CHECK(msh_line(rd, "Elements", &s));
        if (!parse_long(&s, &id) || !parse_long(&s, &type) || !parse_long(&s, &ntags) || ntags < 0)
            return ferr(rd, rd->line, "malformed element line (expected: id type ntags tags... nodes...)");
        if (type != 2) continue;
        for (long k = 0; k < ntags; k++)
            if (!parse_long(&s, &tmp)) return ferr(rd, rd->line, "malformed element tags");
        for (int k = 0; k < 3; k++)
            if (!parse_long(&s, &nodes[k])) return ferr(rd, rd->line, "triangle needs 3 node tags");
        if (!at_end(s)) return ferr(rd, rd->line, "extra data after triangle nodes");
        GLPGP_CHECK(msh_triangle(ms, r, rd, nodes));
    }
    return msh_expect_end(rd, "Elements");
}

static glpgp_status msh41_nodes(msh_state *ms, raw_mesh *r, reader *rd)
{
    glpgp_status st = GLPGP_OK;
    char *s;
    long nblocks, nnodes, mintag, maxtag;
    long *btags = NULL;
    GLPGP_CHECK(msh_line(rd, "Nodes", &s));
    if (!parse_long(&s, &nblocks) || !parse_long(&s, &nnodes) || !parse_long(&s, &mintag) ||
        !parse_long(&s, &maxtag) || nblocks < 0 || nnodes < 0)
        return ferr(rd, rd->line, "malformed $Nodes header (expected: numEntityBlocks numNodes minNodeTag maxNodeTag)");
    long seen = 0;
    for (long b = 0; b < nblocks; b++) {
        long dim, etag, param, n;
        GLPGP_CHECK_GOTO(st, msh_line(rd, "Nodes", &s), done);
        if (!parse_long(&s, &dim) || !parse_long(&s, &etag) || !parse_long(&s, &param) || !parse_long(&s, &n) ||
            n < 0 || !at_end(s)) {
            st = ferr(rd, rd->line, "malformed node block header (expected: entityDim entityTag parametric numNodesInBlock)");
            goto done;
        }
        if (seen + n > nnodes) {
            st = ferr(rd, rd->line, "node blocks hold more nodes than the $Nodes header says (%ld)", nnodes);
            goto done;
        }
        seen += n;
        free(btags);
        btags = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof *btags, &btags), done);
        for (long i = 0; i < n; i++) {
            GLPGP_CHECK_GOTO(st, msh_line(rd, "Nodes", &s), done);
            if (!parse_long(&s, &btags[i]) || !at_end(s)) {
                st = ferr(rd, rd->line, "malformed node tag");
                goto done;
            }
        }
        for (long i = 0; i < n; i++) {
            double x, y, z;
            GLPGP_CHECK_GOTO(st, msh_line(rd, "Nodes", &s), done);
            if (!parse_double(&s, &x) || !parse_double(&s, &y) || !parse_double(&s, &z)) {
                st = ferr(rd, rd->line, "malformed node coordinates (expected: x y z)");
                goto done;
            }
            GLPGP_CHECK_GOTO(st, msh_add_node(ms, r, rd, btags[i], x, y, z), done);
        }
    }
    if (seen != nnodes) {
        st = ferr(rd, rd->line, "node blocks hold %ld nodes, header says %ld", seen, nnodes);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, msh_expect_end(rd, "Nodes"), done);
done:
    free(btags);
    return st;
}

static glpgp_status msh41_elements(msh_state *ms, raw_mesh *r, reader *rd)
{
    char *s;
    long nblocks, nelem, mintag, maxtag;
    GLPGP_CHECK(msh_line(rd, "Elements", &s));
    if (!parse_long(&s, &nblocks) || !parse_long(&s, &nelem) || !parse_long(&s, &mintag) ||
        !parse_long(&s, &maxtag) || nblocks < 0 || nelem < 0)
        return ferr(rd, rd->line,
                    "malformed $Elements header (expected: numEntityBlocks numElements minElementTag maxElementTag)");
    for (long b = 0; b < nblocks; b++) {
        long dim, etag, type, n;
        GLPGP_CHECK(msh_line(rd, "Elements", &s));
        if (!parse_long(&s, &dim) || !parse_long(&s, &etag) || !parse_long(&s, &type) || !parse_long(&s, &n) ||
            n < 0 || !at_end(s))
            return ferr(rd, rd->line,
                        "malformed element block header (expected: entityDim entityTag elementType numElementsInBlock)");
        for (long i = 0; i < n; i++) {
            long id, nodes[3];
            GLPGP_CHECK(msh_line(rd, "Elements", &s));
            if (type != 2) continue;
            if (!parse_long(&s, &id) || !parse_long(&s, &nodes[0]) || !parse_long(&s, &nodes[1]) ||
                !parse_long(&s, &nodes[2]) || !at_end(s))
                return ferr(rd, rd->line, "malformed triangle (expected: tag n1 n2 n3)");
            GLPGP_CHECK(msh_triangle(ms, r, rd, nodes));
        }
    }
    return msh_expect_end(rd, "Elements");
}

static glpgp_status read_msh(reader *rd, raw_mesh *r)
{
    glpgp_status st = GLPGP_OK;
    msh_state ms;
    memset(&ms, 0, sizeof ms);
    char *s;
    do {
        s = next_line(rd);
    } while (s && *skip_ws(s) == '\0');
    if (!s || strcmp(skip_ws(s), "$MeshFormat") != 0)
        return ferr(rd, rd->line, "not a Gmsh MSH file (expected $MeshFormat)");
    GLPGP_CHECK(msh_line(rd, "MeshFormat", &s));
    double version;
    long ftype, dsize;
    if (!parse_double(&s, &version) || !parse_long(&s, &ftype) || !parse_long(&s, &dsize))
        return ferr(rd, rd->line, "malformed $MeshFormat line (expected: version file-type data-size)");
    if (ftype != 0) return ferr(rd, rd->line, "binary MSH not supported, save as ASCII");
    int v2 = version >= 2.0 && version < 3.0;
    int v41 = version >= 4.1 && version < 5.0;
    if (!v2 && !v41)
        return ferr(rd, rd->line, "MSH version %g not supported (supported: 2.2 and 4.1 ASCII)", version);
    GLPGP_CHECK(msh_expect_end(rd, "MeshFormat"));
    while ((s = next_line(rd)) != NULL) {
        s = skip_ws(s);
        if (*s == '\0') continue;
        if (s[0] != '$') {
            st = ferr(rd, rd->line, "expected a section header ($Name)");
            goto done;
        }
        char name[64];
        snprintf(name, sizeof name, "%s", s + 1);
        if (!strcmp(name, "Nodes")) {
            GLPGP_CHECK_GOTO(st, v2 ? msh22_nodes(&ms, r, rd) : msh41_nodes(&ms, r, rd), done);
        } else if (!strcmp(name, "Elements")) {
            GLPGP_CHECK_GOTO(st, v2 ? msh22_elements(&ms, r, rd) : msh41_elements(&ms, r, rd), done);
        } else {
            int start = rd->line;
            for (;;) {
                s = next_line(rd);
                if (!s) {
                    st = ferr(rd, start, "section $%s is not closed by $End%s", name, name);
                    goto done;
                }
                s = skip_ws(s);
                if (s[0] == '$' && !strncmp(s + 1, "End", 3) && !strcmp(s + 4, name)) break;
            }
        }
    }
done:
    msh_free(&ms);
    return st;
}

/* ------------------------------------------------------------------------ */
/* Entry points                                                               */

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
    reader rd;
    char ext[16];
    memset(&r, 0, sizeof r);
    memset(&rd, 0, sizeof rd);
    if (!out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_read: out is NULL");
    *out = NULL;
    if (!path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_read: path is NULL");
    path_ext(path, ext, sizeof ext);
    int is_obj = !strcmp(ext, "obj"), is_msh = !strcmp(ext, "msh");
    if (!is_obj && !is_msh)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: unknown mesh file extension '%s' (supported: .obj, .msh)", path, ext);
    rd.path = path;
    GLPGP_CHECK(read_all(path, &rd.buf, &rd.len));
    rd.cur = rd.buf;
    if (is_obj) {
        char *nul = memchr(rd.buf, '\0', rd.len);
        if (nul) {
            int line = 1;
            for (char *p = rd.buf; p < nul; p++) line += *p == '\n';
            st = ferr(&rd, line, "binary data (NUL byte) in OBJ file");
            goto done;
        }
        GLPGP_CHECK_GOTO(st, read_obj(&rd, &r), done);
    } else {
        GLPGP_CHECK_GOTO(st, read_msh(&rd, &r), done);
    }
    free(rd.buf);
    rd.buf = NULL;
    GLPGP_CHECK_GOTO(st, finish(path, &r, out), done);
done:
    free(rd.buf);
    raw_free(&r);
    return st;
}

static int write_obj(FILE *f, const glpgp_mesh *m)
{
    fprintf(f, "# glpgp mesh: %d vertices, %d triangles\n", m->nv, m->nt);
    for (int v = 0; v < m->nv; v++) fprintf(f, "v %.17g %.17g 0\n", m->xy[2 * v], m->xy[2 * v + 1]);
    for (int t = 0; t < m->nt; t++)
        fprintf(f, "f %d %d %d\n", m->tri[3 * t] + 1, m->tri[3 * t + 1] + 1, m->tri[3 * t + 2] + 1);
    return !ferror(f);
}

static int write_msh(FILE *f, const glpgp_mesh *m)
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
    return !ferror(f);
}

glpgp_status glpgp_mesh_write(const glpgp_mesh *m, const char *path)
{
    char ext[16];
    if (!m || !path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_write: NULL argument");
    path_ext(path, ext, sizeof ext);
    int is_obj = !strcmp(ext, "obj"), is_msh = !strcmp(ext, "msh");
    if (!is_obj && !is_msh)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: unknown mesh file extension '%s' (supported: .obj, .msh)", path, ext);
    size_t n = strlen(path) + 32;
    char *tmp = malloc(n);
    if (!tmp) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory");
    snprintf(tmp, n, "%s.tmp.%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f) {
        glpgp_status st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot create %s: %s", tmp, strerror(errno));
        free(tmp);
        return st;
    }
    int ok = is_obj ? write_obj(f, m) : write_msh(f, m);
    int e = errno;
    if (fclose(f) != 0) {
        if (ok) e = errno;
        ok = 0;
    }
    if (!ok) {
        remove(tmp);
        free(tmp);
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write %s: %s", path, strerror(e ? e : EIO));
    }
    if (rename(tmp, path) != 0) {
        e = errno;
        remove(tmp);
        free(tmp);
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot rename to %s: %s", path, strerror(e));
    }
    free(tmp);
    return GLPGP_OK;
}
