/* io/msh_read.c: the one Gmsh MSH 2.2 / 4.1 ASCII parser (msh.h): one pass
 * over a text_reader, node tags in an open-addressing hash table, every
 * declared count checked before it is trusted. */
#include "msh.h"

#include "glpgp/io.h"
#include "text_reader.h"

#include <stdlib.h>
#include <string.h>

/* ---- node tag -> vertex index ------------------------------------------- */

typedef struct tag_map {
    long long *keys; /* -1: empty slot */
    int *vals;
    size_t cap;      /* power of two (0: none) */
    size_t n;
} tag_map;

static size_t hash_tag(long long t)
{
    unsigned long long x = (unsigned long long)t;
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdULL;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ULL;
    x ^= x >> 33;
    return (size_t)x;
}

static void map_free(tag_map *m)
{
    free(m->keys);
    free(m->vals);
    memset(m, 0, sizeof *m);
}

static glpgp_status map_rehash(tag_map *m, size_t cap)
{
    tag_map nm = {NULL, NULL, cap, 0};
    GLPGP_CHECK(glpgp_malloc(cap, sizeof *nm.keys, &nm.keys));
    glpgp_status st = glpgp_malloc(cap, sizeof *nm.vals, &nm.vals);
    if (st != GLPGP_OK) {
        free(nm.keys);
        GLPGP_CHECK(st);
    }
    for (size_t i = 0; i < cap; i++) nm.keys[i] = -1;
    for (size_t i = 0; i < m->cap; i++) {
        if (m->keys[i] < 0) continue;
        size_t h = hash_tag(m->keys[i]) & (cap - 1);
        while (nm.keys[h] >= 0) h = (h + 1) & (cap - 1);
        nm.keys[h] = m->keys[i];
        nm.vals[h] = m->vals[i];
    }
    nm.n = m->n;
    map_free(m);
    *m = nm;
    return GLPGP_OK;
}

/* Insert tag -> val; *dup = 1 (nothing inserted) when the tag is known. */
static glpgp_status map_insert(tag_map *m, long long tag, int val, int *dup)
{
    *dup = 0;
    if (2 * (m->n + 1) > m->cap) GLPGP_CHECK(map_rehash(m, m->cap ? 2 * m->cap : 1024));
    size_t h = hash_tag(tag) & (m->cap - 1);
    while (m->keys[h] >= 0) {
        if (m->keys[h] == tag) {
            *dup = 1;
            return GLPGP_OK;
        }
        h = (h + 1) & (m->cap - 1);
    }
    m->keys[h] = tag;
    m->vals[h] = val;
    m->n++;
    return GLPGP_OK;
}

static int map_find(const tag_map *m, long long tag)
{
    if (!m->cap || tag < 0) return -1;
    size_t h = hash_tag(tag) & (m->cap - 1);
    while (m->keys[h] >= 0) {
        if (m->keys[h] == tag) return m->vals[h];
        h = (h + 1) & (m->cap - 1);
    }
    return -1;
}

/* ---- parser ---------------------------------------------------------------- */

typedef struct parser {
    text_reader tr;
    msh_data *d;
    size_t cap_v, cap_f;
    tag_map map;
} parser;

/* Next line of a section; the end of the input is an error. */
static glpgp_status sec_line(parser *p, const char *section, char **s)
{
    GLPGP_CHECK(text_next_line(&p->tr, s));
    if (!*s) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "unexpected end of file in $%s", section);
    return GLPGP_OK;
}

static glpgp_status expect_end(parser *p, const char *section)
{
    char *s;
    GLPGP_CHECK(sec_line(p, section, &s));
    s = text_skip_ws(s);
    if (s[0] != '$' || strncmp(s + 1, "End", 3) || strcmp(s + 4, section))
        return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "expected $End%s", section);
    return GLPGP_OK;
}

/* Parse exactly n integers from line s (nothing after them). */
static int parse_lls(char *s, int n, long long *v)
{
    for (int i = 0; i < n; i++)
        if (!text_parse_ll(&s, &v[i])) return 0;
    return text_at_end(s);
}

/* Reserve room for `want` more items, but never more than a bounded guess
 * for streams of unknown size (the arrays grow with the data otherwise). */
static size_t reserve_hint(const parser *p, long long want)
{
    if (text_remaining(&p->tr) < 0 && want > 65536) return 65536;
    return (size_t)want;
}

static glpgp_status add_node(parser *p, long long tag, const double *x)
{
    msh_data *d = p->d;
    int dup;
    if (tag < 0) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "negative node tag %lld", tag);
    if (d->nv >= GLPGP_IO_MAX_ITEMS)
        return text_error(&p->tr, GLPGP_ERR_LIMIT, 0, "more than %ld nodes", (long)GLPGP_IO_MAX_ITEMS);
    GLPGP_CHECK(map_insert(&p->map, tag, (int)d->nv, &dup));
    if (dup) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "duplicate node tag %lld", tag);
    if (x) {
        GLPGP_CHECK(glpgp_grow(&d->xyz, &p->cap_v, (size_t)d->nv + 1, 3 * sizeof(double)));
        memcpy(d->xyz + 3 * d->nv, x, 3 * sizeof(double));
    }
    d->nv++;
    return GLPGP_OK;
}

static glpgp_status set_coords(parser *p, long idx, const double *x)
{
    GLPGP_CHECK(glpgp_grow(&p->d->xyz, &p->cap_v, (size_t)idx + 1, 3 * sizeof(double)));
    memcpy(p->d->xyz + 3 * idx, x, 3 * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status add_face(parser *p, int k, const long long *tags)
{
    msh_data *d = p->d;
    int c[4] = {-1, -1, -1, -1};
    for (int i = 0; i < k; i++) {
        c[i] = map_find(&p->map, tags[i]);
        if (c[i] < 0)
            return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "element references unknown node %lld", tags[i]);
    }
    if (d->nf >= GLPGP_IO_MAX_ITEMS)
        return text_error(&p->tr, GLPGP_ERR_LIMIT, 0, "more than %ld elements", (long)GLPGP_IO_MAX_ITEMS);
    GLPGP_CHECK(glpgp_grow(&d->corner, &p->cap_f, (size_t)d->nf + 1, 4 * sizeof(int)));
    memcpy(d->corner + 4 * d->nf, c, sizeof c);
    d->nf++;
    if (k == 3)
        d->ntri++;
    else
        d->nquad++;
    return GLPGP_OK;
}

/* $Nodes of MSH 2.2: "n", then n lines "tag x y z". */
static glpgp_status nodes22(parser *p)
{
    char *s;
    long long n;
    GLPGP_CHECK(sec_line(p, "Nodes", &s));
    if (!parse_lls(s, 1, &n)) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "expected the number of nodes");
    GLPGP_CHECK(text_check_count(&p->tr, n, 8, "nodes"));
    GLPGP_CHECK(glpgp_grow(&p->d->xyz, &p->cap_v, reserve_hint(p, n), 3 * sizeof(double)));
    for (long long i = 0; i < n; i++) {
        long long tag;
        double x[3];
        GLPGP_CHECK(sec_line(p, "Nodes", &s));
        if (!text_parse_ll(&s, &tag) || !text_parse_double(&s, &x[0]) || !text_parse_double(&s, &x[1]) ||
            !text_parse_double(&s, &x[2]) || !text_at_end(s))
            return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                              "malformed node line (expected: tag x y z, finite numbers)");
        GLPGP_CHECK(add_node(p, tag, x));
    }
    return expect_end(p, "Nodes");
}

/* $Nodes of MSH 4.1: "numEntityBlocks numNodes minTag maxTag", then per
 * block "entityDim entityTag parametric numNodesInBlock", its tags (one per
 * line), its coordinates "x y z [u [v [w]]]" (parametric: entityDim more). */
static glpgp_status nodes41(parser *p)
{
    char *s;
    long long h[4];
    GLPGP_CHECK(sec_line(p, "Nodes", &s));
    if (!parse_lls(s, 4, h))
        return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                          "malformed $Nodes header (expected: numEntityBlocks numNodes minNodeTag maxNodeTag)");
    const long long nblocks = h[0], nnodes = h[1];
    GLPGP_CHECK(text_check_count(&p->tr, nblocks, 8, "node blocks"));
    GLPGP_CHECK(text_check_count(&p->tr, nnodes, 8, "nodes"));
    GLPGP_CHECK(glpgp_grow(&p->d->xyz, &p->cap_v, reserve_hint(p, nnodes), 3 * sizeof(double)));
    long long seen = 0;
    for (long long b = 0; b < nblocks; b++) {
        long long bh[4];
        GLPGP_CHECK(sec_line(p, "Nodes", &s));
        if (!parse_lls(s, 4, bh) || bh[0] < 0 || bh[0] > 3 || bh[2] < 0 || bh[2] > 1 || bh[3] < 0)
            return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                              "malformed node block header (expected: entityDim entityTag parametric "
                              "numNodesInBlock)");
        const long long n = bh[3];
        if (n > nnodes - seen)
            return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                              "node blocks hold more nodes than the $Nodes header says (%lld)", nnodes);
        const int extra = bh[2] ? (int)bh[0] : 0; /* parametric coordinates */
        const long first = p->d->nv;
        for (long long i = 0; i < n; i++) {
            long long tag;
            GLPGP_CHECK(sec_line(p, "Nodes", &s));
            if (!parse_lls(s, 1, &tag)) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "malformed node tag");
            GLPGP_CHECK(add_node(p, tag, NULL));
        }
        for (long long i = 0; i < n; i++) {
            double x[6];
            GLPGP_CHECK(sec_line(p, "Nodes", &s));
            int ok = 1;
            for (int k = 0; k < 3 + extra && ok; k++) ok = text_parse_double(&s, &x[k]);
            if (!ok || !text_at_end(s))
                return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                                  "malformed node coordinates (expected: x y z%s, finite numbers)",
                                  extra == 0 ? "" : extra == 1 ? " u" : extra == 2 ? " u v" : " u v w");
            GLPGP_CHECK(set_coords(p, first + (long)i, x));
        }
        seen += n;
    }
    if (seen != nnodes)
        return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "node blocks hold %lld nodes, the header says %lld",
                          seen, nnodes);
    return expect_end(p, "Nodes");
}

/* The element types kept: triangles and quadrangles of any order Gmsh
 * writes (2: 3-node triangle; 9, 20-25: 6- to 21-node; 3: 4-node quadrangle;
 * 10, 16, 36, 37: 9-, 8-, 16-, 25-node). Returns the corner count (3, 4;
 * 0 for a type not kept) and in *nodes the element's node count. Gmsh lists
 * an element's corners first: glpgp (P1, straight edges) keeps them and reads
 * past the edge and face nodes of curved elements. */
static int kept_corners(long long type, int *nodes)
{
    static const struct {
        int type, corners, nodes;
    } kept[] = {{2, 3, 3},   {9, 3, 6},   {20, 3, 9},  {21, 3, 10}, {22, 3, 12}, {23, 3, 15}, {24, 3, 15},
                {25, 3, 21}, {3, 4, 4},   {10, 4, 9},  {16, 4, 8},  {36, 4, 16}, {37, 4, 25}};
    for (size_t i = 0; i < sizeof kept / sizeof kept[0]; i++)
        if (kept[i].type == type) {
            *nodes = kept[i].nodes;
            return kept[i].corners;
        }
    *nodes = 0;
    return 0;
}

/* Read the element's nn node tags from s (corners into v[0 .. k)), then the
 * line's end; 0 when malformed. */
static int parse_nodes(char *s, int k, int nn, long long *v)
{
    long long tmp;
    for (int i = 0; i < nn; i++)
        if (!text_parse_ll(&s, i < k ? &v[i] : &tmp)) return 0;
    return text_at_end(s);
}

/* $Elements of MSH 2.2: "n", then "id type ntags tag... node..." lines. */
static glpgp_status elements22(parser *p)
{
    char *s;
    long long n;
    GLPGP_CHECK(sec_line(p, "Elements", &s));
    if (!parse_lls(s, 1, &n)) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "expected the number of elements");
    GLPGP_CHECK(text_check_count(&p->tr, n, 8, "elements"));
    GLPGP_CHECK(glpgp_grow(&p->d->corner, &p->cap_f, reserve_hint(p, n), 4 * sizeof(int)));
    for (long long i = 0; i < n; i++) {
        long long id, type, ntags, tmp, nodes[4];
        GLPGP_CHECK(sec_line(p, "Elements", &s));
        if (!text_parse_ll(&s, &id) || !text_parse_ll(&s, &type) || !text_parse_ll(&s, &ntags) || ntags < 0)
            return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                              "malformed element line (expected: id type ntags tags... nodes...)");
        int nn, k = kept_corners(type, &nn);
        if (!k) continue;
        for (long long t = 0; t < ntags; t++)
            if (!text_parse_ll(&s, &tmp)) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "malformed element tags");
        for (int c = 0; c < nn; c++)
            if (!text_parse_ll(&s, c < k ? &nodes[c] : &tmp))
                return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "element type %lld needs %d node tags", type, nn);
        if (!text_at_end(s)) return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "extra data after the element's nodes");
        GLPGP_CHECK(add_face(p, k, nodes));
        if (nn > k) p->d->nhigh++;
    }
    return expect_end(p, "Elements");
}

/* $Elements of MSH 4.1: "numEntityBlocks numElements minTag maxTag", then per
 * block "entityDim entityTag elementType numElementsInBlock" and its lines
 * "tag node...". */
static glpgp_status elements41(parser *p)
{
    char *s;
    long long h[4];
    GLPGP_CHECK(sec_line(p, "Elements", &s));
    if (!parse_lls(s, 4, h))
        return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                          "malformed $Elements header (expected: numEntityBlocks numElements minElementTag "
                          "maxElementTag)");
    const long long nblocks = h[0], nelem = h[1];
    GLPGP_CHECK(text_check_count(&p->tr, nblocks, 8, "element blocks"));
    GLPGP_CHECK(text_check_count(&p->tr, nelem, 4, "elements"));
    long long seen = 0;
    for (long long b = 0; b < nblocks; b++) {
        long long bh[4];
        GLPGP_CHECK(sec_line(p, "Elements", &s));
        if (!parse_lls(s, 4, bh) || bh[3] < 0)
            return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                              "malformed element block header (expected: entityDim entityTag elementType "
                              "numElementsInBlock)");
        const long long n = bh[3];
        if (n > nelem - seen)
            return text_error(&p->tr, GLPGP_ERR_FORMAT, 0,
                              "element blocks hold more elements than the $Elements header says (%lld)", nelem);
        int nn;
        const int k = kept_corners(bh[2], &nn);
        if (k) GLPGP_CHECK(glpgp_grow(&p->d->corner, &p->cap_f, (size_t)p->d->nf + reserve_hint(p, n), 4 * sizeof(int)));
        for (long long i = 0; i < n; i++) {
            long long v[5];
            GLPGP_CHECK(sec_line(p, "Elements", &s));
            if (!k) continue;
            if (!text_parse_ll(&s, &v[0]) || !parse_nodes(s, k, nn, v + 1))
                return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "malformed element of type %lld (expected: tag and %d nodes)",
                                  bh[2], nn);
            GLPGP_CHECK(add_face(p, k, v + 1));
            if (nn > k) p->d->nhigh++;
        }
        seen += n;
    }
    if (seen != nelem)
        return text_error(&p->tr, GLPGP_ERR_FORMAT, 0, "element blocks hold %lld elements, the header says %lld",
                          seen, nelem);
    return expect_end(p, "Elements");
}

void msh_free(msh_data *d)
{
    free(d->xyz);
    free(d->corner);
    memset(d, 0, sizeof *d);
}

glpgp_status msh_read(const char *path, msh_data *out)
{
    glpgp_status st = GLPGP_OK;
    parser p;
    memset(&p, 0, sizeof p);
    memset(out, 0, sizeof *out);
    p.d = out;
    GLPGP_CHECK(text_open(&p.tr, path));
    text_reader *tr = &p.tr;
    char *s;
    do {
        GLPGP_CHECK_GOTO(st, text_next_line(tr, &s), done);
    } while (s && *text_skip_ws(s) == '\0');
    if (!s || strcmp(text_skip_ws(s), "$MeshFormat") != 0) {
        st = text_error(tr, GLPGP_ERR_FORMAT, 0, "not a Gmsh MSH file (expected $MeshFormat)");
        goto done;
    }
    GLPGP_CHECK_GOTO(st, sec_line(&p, "MeshFormat", &s), done);
    double version;
    long long ftype, dsize;
    if (!text_parse_double(&s, &version) || !text_parse_ll(&s, &ftype) || !text_parse_ll(&s, &dsize)) {
        st = text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed $MeshFormat line (expected: version file-type data-size)");
        goto done;
    }
    if (ftype != 0) {
        st = text_error(tr, GLPGP_ERR_FORMAT, 0, "binary MSH not supported, save as ASCII");
        goto done;
    }
    const int v2 = version >= 2.0 && version < 3.0;
    const int v41 = version >= 4.1 && version < 5.0;
    if (!v2 && !v41) {
        st = text_error(tr, GLPGP_ERR_FORMAT, 0, "MSH version %g not supported (supported: 2.2 and 4.1 ASCII)",
                        version);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, expect_end(&p, "MeshFormat"), done);
    int have_nodes = 0, have_elements = 0;
    for (;;) {
        GLPGP_CHECK_GOTO(st, text_next_line(tr, &s), done);
        if (!s) break;
        s = text_skip_ws(s);
        if (*s == '\0') continue;
        if (s[0] != '$') {
            st = text_error(tr, GLPGP_ERR_FORMAT, 0, "expected a section header ($Name)");
            goto done;
        }
        char name[64];
        snprintf(name, sizeof name, "%s", s + 1);
        if (!strcmp(name, "Nodes") || !strcmp(name, "Elements") || !strcmp(name, "MeshFormat")) {
            int nodes = name[0] == 'N', elements = name[0] == 'E';
            if ((nodes && have_nodes) || (elements && have_elements) || (!nodes && !elements)) {
                st = text_error(tr, GLPGP_ERR_FORMAT, 0, "repeated section $%s", name);
                goto done;
            }
            if (elements && !have_nodes) {
                st = text_error(tr, GLPGP_ERR_FORMAT, 0, "$Elements before $Nodes");
                goto done;
            }
            if (nodes) {
                GLPGP_CHECK_GOTO(st, v2 ? nodes22(&p) : nodes41(&p), done);
                have_nodes = 1;
            } else {
                GLPGP_CHECK_GOTO(st, v2 ? elements22(&p) : elements41(&p), done);
                have_elements = 1;
            }
        } else if (!strncmp(name, "End", 3)) {
            st = text_error(tr, GLPGP_ERR_FORMAT, 0, "$%s without its section", name);
            goto done;
        } else { /* any other section: skipped up to its end */
            long start = tr->line;
            for (;;) {
                GLPGP_CHECK_GOTO(st, text_next_line(tr, &s), done);
                if (!s) {
                    st = text_error(tr, GLPGP_ERR_FORMAT, start, "section $%s is not closed by $End%s", name, name);
                    goto done;
                }
                s = text_skip_ws(s);
                if (s[0] == '$' && !strncmp(s + 1, "End", 3) && !strcmp(s + 4, name)) break;
            }
        }
    }
done:
    map_free(&p.map);
    text_close(&p.tr);
    if (st != GLPGP_OK) msh_free(out);
    return st;
}
