/* io/vtu.c: VTK XML UnstructuredGrid with appended raw data (vtu.h).
 *
 * File layout written:
 *   XML header: VTKFile (header_type UInt64, byte_order of the host,
 *   compressor vtkZLibDataCompressor when compressed), FieldData, one Piece
 *   with PointData, CellData, Points, Cells; every DataArray
 *   format="appended" with offset="%020lld" (patched once known);
 *   <AppendedData encoding="raw"> newline, "_", then per array either
 *     raw:        UInt64 byte count, the bytes;
 *     compressed: UInt64 [nblocks, block size, last partial block size (0 if
 *                 none), compressed size of each block], the zlib streams;
 *   blocks hold whole tuples (block size = largest multiple of the tuple size
 *   <= 1 MiB); an array whose first block shrinks by less than 10% has its
 *   other blocks stored (zlib level 0): noisy doubles do not compress, and
 *   trying costs more than the write. */
#include "vtu.h"
#include "glpgp/util.h"

#include "glpgp/io.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef GLPGP_HAVE_ZLIB
#include <zlib.h>
#endif

#define BLOCK_BYTES (1u << 20)

int glpgp_io_have_zlib(void)
{
#ifdef GLPGP_HAVE_ZLIB
    return 1;
#else
    return 0;
#endif
}

static int host_little_endian(void)
{
    const uint16_t one = 1;
    return *(const unsigned char *)&one == 1;
}

static const char *const section_tag[VTU_NSECTIONS] = {"FieldData", "PointData", "CellData", "Points", "Cells"};

/* ---- a growing text buffer for the XML header ------------------------------- */

typedef struct sbuf {
    char *s;
    size_t n, cap;
    int oom;
} sbuf;

static void sb_printf(sbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void sb_printf(sbuf *b, const char *fmt, ...)
{
    if (b->oom) return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int k = glpgp_vsnprintf(b->s ? b->s + b->n : NULL, b->s ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (k < 0) {
            b->oom = 1;
            return;
        }
        if (b->s && b->n + (size_t)k < b->cap) {
            b->n += (size_t)k;
            return;
        }
        size_t nc = b->cap ? 2 * b->cap : 4096;
        while (nc < b->n + (size_t)k + 1) nc *= 2;
        char *p = realloc(b->s, nc);
        if (!p) {
            b->oom = 1;
            return;
        }
        b->s = p;
        b->cap = nc;
    }
}

/* ---- writer -------------------------------------------------------------------- */

typedef struct patch {
    long long pos;       /* file position */
    size_t nbytes;
    unsigned char *data; /* owned */
} patch;

typedef struct wstate {
    FILE *f;
    long long pos; /* bytes written so far */
    patch *patches;
    size_t npatch, cap_patch;
} wstate;

static void put(wstate *w, const void *p, size_t n)
{
    fwrite(p, 1, n, w->f);
    w->pos += (long long)n;
}

static glpgp_status add_patch(wstate *w, long long pos, const void *data, size_t n)
{
    GLPGP_CHECK(glpgp_grow(&w->patches, &w->cap_patch, w->npatch + 1, sizeof *w->patches));
    patch *p = &w->patches[w->npatch];
    GLPGP_CHECK(glpgp_malloc(n ? n : 1, 1, &p->data));
    memcpy(p->data, data, n);
    p->pos = pos;
    p->nbytes = n;
    w->npatch++;
    return GLPGP_OK;
}

/* One array's data (header + blocks) at the current position. */
static glpgp_status write_array(wstate *w, const vtu_array *a, int level, unsigned char *stage,
                                unsigned char *cbuf, size_t cbuf_cap)
{
    const size_t tb = (size_t)a->elsize * (size_t)a->ncomp; /* tuple bytes */
    const size_t per_block = BLOCK_BYTES / tb ? BLOCK_BYTES / tb : 1;
    const uint64_t total = (uint64_t)a->ntuples * tb;
    if (level <= 0) {
        put(w, &total, sizeof total);
        for (size_t t = 0; t < a->ntuples; t += per_block) {
            size_t k = a->ntuples - t < per_block ? a->ntuples - t : per_block;
            a->fill(a->ctx, t, k, stage);
            put(w, stage, k * tb);
        }
        return GLPGP_OK;
    }
#ifdef GLPGP_HAVE_ZLIB
    const uint64_t bs = (uint64_t)per_block * tb;
    const uint64_t nblocks = (total + bs - 1) / bs;
    uint64_t *hdr = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)(3 + nblocks), sizeof *hdr, &hdr));
    hdr[0] = nblocks;
    hdr[1] = bs;
    hdr[2] = total % bs;
    const long long hdr_pos = w->pos;
    put(w, hdr, (size_t)(3 + nblocks) * sizeof *hdr); /* placeholder */
    int lvl = level;
    for (uint64_t b = 0; b < nblocks; b++) {
        size_t t = (size_t)b * per_block;
        size_t k = a->ntuples - t < per_block ? a->ntuples - t : per_block;
        a->fill(a->ctx, t, k, stage);
        uLongf clen = (uLongf)cbuf_cap;
        int zr = compress2(cbuf, &clen, stage, (uLong)(k * tb), lvl);
        /* data that does not compress (noisy doubles): store the rest of the
         * array's blocks (zlib level 0, a copy) instead of spending time */
        if (zr == Z_OK && b == 0 && (double)clen > 0.9 * (double)(k * tb)) lvl = 0;
        if (zr != Z_OK) {
            free(hdr);
            return GLPGP_FAIL(zr == Z_MEM_ERROR ? GLPGP_ERR_NOMEM : GLPGP_ERR_IO, "zlib compression failed (%d)", zr);
        }
        put(w, cbuf, (size_t)clen);
        hdr[3 + b] = (uint64_t)clen;
    }
    glpgp_status st = add_patch(w, hdr_pos, hdr, (size_t)(3 + nblocks) * sizeof *hdr);
    free(hdr);
    return st;
#else
    (void)cbuf;
    (void)cbuf_cap;
    return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "this build has no zlib");
#endif
}

glpgp_status vtu_write(FILE *f, const char *comment, size_t npoints, size_t ncells, const vtu_array *a,
                       int na, int level)
{
    glpgp_status st = GLPGP_OK;
    sbuf x = {NULL, 0, 0, 0};
    long long *offset_pos = NULL;
    unsigned char *stage = NULL, *cbuf = NULL;
    size_t cbuf_cap = 0;
    wstate w = {f, 0, NULL, 0, 0};
#ifndef GLPGP_HAVE_ZLIB
    level = 0;
#endif
    if (level > 9) level = 9;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)na + 1, sizeof *offset_pos, &offset_pos), done);

    /* XML header; offsets are placeholders patched below */
    sb_printf(&x, "<?xml version=\"1.0\"?>\n");
    if (comment) sb_printf(&x, "<!-- %s -->\n", comment);
    sb_printf(&x, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\"%s>\n",
              host_little_endian() ? "LittleEndian" : "BigEndian",
              level > 0 ? " compressor=\"vtkZLibDataCompressor\"" : "");
    sb_printf(&x, "  <UnstructuredGrid>\n");
    for (int sec = 0; sec < VTU_NSECTIONS; sec++) {
        int any = 0;
        for (int i = 0; i < na; i++) any |= a[i].section == sec;
        if (sec == VTU_POINTDATA) sb_printf(&x, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", npoints, ncells);
        if (!any) continue;
        const char *ind = sec == VTU_FIELD ? "    " : "      ";
        sb_printf(&x, "%s<%s>\n", ind, section_tag[sec]);
        for (int i = 0; i < na; i++) {
            if (a[i].section != sec) continue;
            sb_printf(&x, "%s  <DataArray type=\"%s\"", ind, a[i].type);
            if (a[i].name) sb_printf(&x, " Name=\"%s\"", a[i].name);
            if (a[i].ncomp != 1) sb_printf(&x, " NumberOfComponents=\"%d\"", a[i].ncomp);
            if (sec == VTU_FIELD) sb_printf(&x, " NumberOfTuples=\"%zu\"", a[i].ntuples);
            sb_printf(&x, " format=\"appended\" offset=\"");
            offset_pos[i] = (long long)x.n;
            sb_printf(&x, "%020d\"/>\n", 0);
        }
        sb_printf(&x, "%s</%s>\n", ind, section_tag[sec]);
    }
    sb_printf(&x, "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n_");
    if (x.oom) {
        st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory writing a .vtu header");
        goto done;
    }
    put(&w, x.s, x.n);
    const long long data_start = w.pos;

    GLPGP_CHECK_GOTO(st, glpgp_malloc(BLOCK_BYTES + 64, 1, &stage), done);
#ifdef GLPGP_HAVE_ZLIB
    if (level > 0) {
        cbuf_cap = (size_t)compressBound(BLOCK_BYTES + 64);
        GLPGP_CHECK_GOTO(st, glpgp_malloc(cbuf_cap, 1, &cbuf), done);
    }
#endif
    /* data, in the order of the header (sections, then list order) */
    for (int sec = 0; sec < VTU_NSECTIONS; sec++)
        for (int i = 0; i < na; i++) {
            if (a[i].section != sec) continue;
            char digits[32];
            snprintf(digits, sizeof digits, "%020lld", w.pos - data_start);
            GLPGP_CHECK_GOTO(st, add_patch(&w, offset_pos[i], digits, 20), done);
            GLPGP_CHECK_GOTO(st, write_array(&w, &a[i], level, stage, cbuf, cbuf_cap), done);
        }
    static const char tail[] = "\n  </AppendedData>\n</VTKFile>\n";
    put(&w, tail, sizeof tail - 1);

    /* patch offsets and compression headers */
    for (size_t i = 0; i < w.npatch; i++) {
        if (fseek(f, (long)w.patches[i].pos, SEEK_SET) != 0) {
            st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot seek in a .vtu output: %s", strerror(errno ? errno : EIO));
            goto done;
        }
        fwrite(w.patches[i].data, 1, w.patches[i].nbytes, f);
    }
    if (w.npatch && fseek(f, 0, SEEK_END) != 0) {
        st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot seek in a .vtu output: %s", strerror(errno ? errno : EIO));
        goto done;
    }
done:
    for (size_t i = 0; i < w.npatch; i++) free(w.patches[i].data);
    free(w.patches);
    free(x.s);
    free(offset_pos);
    free(stage);
    free(cbuf);
    return st;
}

/* ---- reader ---------------------------------------------------------------------- */

static glpgp_status verr(const vtu_reader *v, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static glpgp_status verr(const vtu_reader *v, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    glpgp_vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: %s", v->tr->path, msg);
}

/* Value of attribute name in the tag text (up to '>'), copied into out. */
static int attr(const char *tag, const char *name, char *out, size_t n)
{
    size_t ln = strlen(name);
    for (const char *p = tag; (p = strstr(p, name)) != NULL; p += ln) {
        if (p > tag && !isspace((unsigned char)p[-1])) continue;
        const char *q = p + ln;
        if (q[0] != '=' || q[1] != '"') continue;
        q += 2;
        const char *e = strchr(q, '"');
        if (!e || (size_t)(e - q) >= n) return 0;
        memcpy(out, q, (size_t)(e - q));
        out[e - q] = '\0';
        return 1;
    }
    return 0;
}

static int attr_ll(const char *tag, const char *name, long long *out)
{
    char buf[32], *e;
    if (!attr(tag, name, buf, sizeof buf)) return 0;
    errno = 0;
    long long v = strtoll(buf, &e, 10);
    if (e == buf || *e || errno == ERANGE) return 0;
    *out = v;
    return 1;
}

static int type_size(const char *t)
{
    static const struct {
        const char *name;
        int size;
    } types[] = {{"Int8", 1},  {"UInt8", 1},  {"Int16", 2},  {"UInt16", 2},  {"Int32", 4},
                 {"UInt32", 4}, {"Int64", 8}, {"UInt64", 8}, {"Float32", 4}, {"Float64", 8}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (!strcmp(t, types[i].name)) return types[i].size;
    return 0;
}

/* One tag "<Name attrs...>" of the header; updates the current section. */
static glpgp_status header_tag(vtu_reader *v, const char *tag, int *section, int *piece, int *appended)
{
    char name[32];
    size_t k = 0;
    const char *p = tag + 1;
    int closing = *p == '/';
    if (closing) p++;
    while (*p && !isspace((unsigned char)*p) && *p != '>' && *p != '/' && k + 1 < sizeof name) name[k++] = *p++;
    name[k] = '\0';
    if (tag[1] == '?' || tag[1] == '!') return GLPGP_OK; /* declaration, comment */
    for (int s = 0; s < VTU_NSECTIONS; s++)
        if (!strcmp(name, section_tag[s])) {
            *section = closing ? -1 : s;
            return GLPGP_OK;
        }
    if (closing) return GLPGP_OK;
    char buf[64];
    if (!strcmp(name, "VTKFile")) {
        if (!attr(tag, "type", buf, sizeof buf) || strcmp(buf, "UnstructuredGrid"))
            return verr(v, "not a VTK UnstructuredGrid file");
        if (!attr(tag, "byte_order", buf, sizeof buf)) strcpy(buf, "LittleEndian");
        if (strcmp(buf, "LittleEndian") && strcmp(buf, "BigEndian")) return verr(v, "unknown byte_order '%s'", buf);
        v->swap = (!strcmp(buf, "LittleEndian")) != host_little_endian();
        if (!attr(tag, "header_type", buf, sizeof buf)) strcpy(buf, "UInt32");
        if (strcmp(buf, "UInt32") && strcmp(buf, "UInt64")) return verr(v, "unknown header_type '%s'", buf);
        v->header64 = !strcmp(buf, "UInt64");
        if (attr(tag, "compressor", buf, sizeof buf)) {
            if (strcmp(buf, "vtkZLibDataCompressor")) return verr(v, "compressor '%s' not supported", buf);
#ifndef GLPGP_HAVE_ZLIB
            return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "%s: compressed .vtu, but this build has no zlib", v->tr->path);
#endif
            v->compressed = 1;
        }
    } else if (!strcmp(name, "Piece")) {
        if (*piece) return verr(v, "more than one Piece (not written by glpgp)");
        *piece = 1;
        if (!attr_ll(tag, "NumberOfPoints", &v->npoints) || !attr_ll(tag, "NumberOfCells", &v->ncells) ||
            v->npoints < 0 || v->ncells < 0)
            return verr(v, "Piece without valid NumberOfPoints / NumberOfCells");
        if (v->npoints > GLPGP_IO_MAX_ITEMS || v->ncells > GLPGP_IO_MAX_ITEMS)
            return GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: %lld points / %lld cells: more than the limit of %ld",
                              v->tr->path, v->npoints, v->ncells, (long)GLPGP_IO_MAX_ITEMS);
    } else if (!strcmp(name, "DataArray")) {
        if (*section < 0) return verr(v, "DataArray outside a data section");
        if (v->narrays >= VTU_MAX_ARRAYS) return verr(v, "more than %d data arrays", VTU_MAX_ARRAYS);
        vtu_in_array *a = &v->arrays[v->narrays];
        memset(a, 0, sizeof *a);
        a->section = *section;
        if (!attr(tag, "Name", a->name, sizeof a->name)) a->name[0] = '\0';
        if (!attr(tag, "type", a->type, sizeof a->type) || !(a->elsize = type_size(a->type)))
            return verr(v, "DataArray '%s' has no known type", a->name);
        long long nc = 1;
        if (attr(tag, "NumberOfComponents", buf, sizeof buf) && (!attr_ll(tag, "NumberOfComponents", &nc) || nc < 1 || nc > 16))
            return verr(v, "DataArray '%s': bad NumberOfComponents", a->name);
        a->ncomp = (int)nc;
        a->ntuples = -1;
        if (a->section == VTU_FIELD && (!attr_ll(tag, "NumberOfTuples", &a->ntuples) || a->ntuples < 0 ||
                                        a->ntuples > GLPGP_IO_MAX_ITEMS))
            return verr(v, "field array '%s' without a valid NumberOfTuples", a->name);
        if (!attr(tag, "format", buf, sizeof buf) || strcmp(buf, "appended"))
            return verr(v, "DataArray '%s' is not in the appended section (only appended raw data is read)", a->name);
        if (!attr_ll(tag, "offset", &a->offset) || a->offset < 0)
            return verr(v, "DataArray '%s' without a valid offset", a->name);
        for (int i = 0; i < v->narrays; i++)
            if (v->arrays[i].section == a->section && !strcmp(v->arrays[i].name, a->name))
                return verr(v, "repeated array '%s' in %s", a->name, section_tag[a->section]);
        v->narrays++;
    } else if (!strcmp(name, "AppendedData")) {
        if (!attr(tag, "encoding", buf, sizeof buf) || strcmp(buf, "raw"))
            return verr(v, "AppendedData is not raw (only encoding=\"raw\" is read)");
        *appended = 1;
    }
    return GLPGP_OK;
}

glpgp_status vtu_read_header(vtu_reader *v, text_reader *tr, const char *first_line)
{
    memset(v, 0, sizeof *v);
    v->tr = tr;
    v->npoints = v->ncells = -1;
    int section = -1, piece = 0, appended = 0, vtkfile = 0;
    const char *line = first_line;
    char *s = NULL;
    long lines = 0;
    while (!appended) {
        if (!line) {
            GLPGP_CHECK(text_next_line(tr, &s));
            if (!s) return verr(v, "no AppendedData section (truncated file?)");
            line = s;
        }
        if (++lines > 100000) return verr(v, "XML header too long");
        for (const char *p = strchr(line, '<'); p && !appended; p = strchr(p + 1, '<')) {
            const char *e = strchr(p, '>');
            char tag[1024];
            if (!e) return verr(v, "line %ld: XML tag spans lines (not written by glpgp)", tr->line);
            if ((size_t)(e - p) >= sizeof tag) return verr(v, "line %ld: XML tag too long", tr->line);
            memcpy(tag, p, (size_t)(e - p));
            tag[e - p] = '\0';
            if (!strncmp(tag, "<VTKFile", 8)) vtkfile = 1;
            GLPGP_CHECK(header_tag(v, tag, &section, &piece, &appended));
        }
        line = NULL;
    }
    if (!vtkfile || !piece) return verr(v, "no VTKFile / Piece element before the data");
    /* the data starts after '_' */
    int c;
    while ((c = text_getc_raw(tr)) >= 0 && isspace(c)) {
    }
    if (c != '_') return verr(v, "appended data does not start with '_'");
    return GLPGP_OK;
}

const vtu_in_array *vtu_find(const vtu_reader *v, int section, const char *name)
{
    for (int i = 0; i < v->narrays; i++)
        if (v->arrays[i].section == section && (!name || !strcmp(v->arrays[i].name, name))) return &v->arrays[i];
    return NULL;
}

static void swap_bytes(unsigned char *p, size_t n, int size)
{
    if (size == 1) return;
    for (size_t i = 0; i < n; i++, p += size)
        for (int a = 0, b = size - 1; a < b; a++, b--) {
            unsigned char t = p[a];
            p[a] = p[b];
            p[b] = t;
        }
}

/* Integer of elsize bytes at p (host order), unsigned 64-bit values clamped. */
static long long get_int(const unsigned char *p, int elsize, int is_unsigned)
{
    switch (elsize) {
    case 1: {
        int8_t i8;
        uint8_t u8;
        memcpy(&i8, p, 1);
        memcpy(&u8, p, 1);
        return is_unsigned ? (long long)u8 : (long long)i8;
    }
    case 2: {
        int16_t i16;
        uint16_t u16;
        memcpy(&i16, p, 2);
        memcpy(&u16, p, 2);
        return is_unsigned ? (long long)u16 : (long long)i16;
    }
    case 4: {
        int32_t i32;
        uint32_t u32;
        memcpy(&i32, p, 4);
        memcpy(&u32, p, 4);
        return is_unsigned ? (long long)u32 : (long long)i32;
    }
    default: {
        int64_t i64;
        uint64_t u64;
        memcpy(&i64, p, 8);
        memcpy(&u64, p, 8);
        return is_unsigned ? (long long)(u64 > INT64_MAX ? INT64_MAX : u64) : (long long)i64;
    }
    }
}

/* Read one header integer (UInt32 or UInt64). */
static int read_hdr(vtu_reader *v, uint64_t *out)
{
    unsigned char b[8];
    int n = v->header64 ? 8 : 4;
    if (!text_read_raw(v->tr, b, (size_t)n)) return 0;
    v->pos += n;
    if (v->swap) swap_bytes(b, 1, n);
    if (n == 8) {
        memcpy(out, b, 8);
    } else {
        uint32_t u;
        memcpy(&u, b, 4);
        *out = u;
    }
    return 1;
}

/* Read exactly n raw bytes into a buffer grown as the data arrives. */
static glpgp_status read_grow(vtu_reader *v, unsigned char **buf, size_t *cap, size_t at, size_t n, const char *name)
{
    size_t done = 0;
    while (done < n) {
        size_t step = n - done < (64u << 20) ? n - done : (64u << 20);
        GLPGP_CHECK(glpgp_grow(buf, cap, at + done + step, 1));
        if (!text_read_raw(v->tr, *buf + at + done, step))
            return verr(v, "array '%s': data ends early (truncated file)", name);
        done += step;
        v->pos += (long long)step;
    }
    return GLPGP_OK;
}

glpgp_status vtu_read_array(vtu_reader *v, const vtu_in_array *a, size_t count, double **out_d, long long **out_ll)
{
    glpgp_status st = GLPGP_OK;
    unsigned char *raw = NULL, *cbuf = NULL;
    uint64_t *csize = NULL;
    size_t cap = 0, ccap = 0;
    const char *name = a->name[0] ? a->name : section_tag[a->section];
    if (out_d) *out_d = NULL;
    if (out_ll) *out_ll = NULL;
    if (count % (size_t)a->ncomp) return verr(v, "array '%s': wrong number of components", name);
    if (a->offset < v->pos) return verr(v, "array '%s': offsets out of order or overlapping", name);
    /* pass over the arrays before it */
    for (long long skip = a->offset - v->pos; skip > 0;) {
        size_t k = skip > (1 << 20) ? (1 << 20) : (size_t)skip;
        if (!text_read_raw(v->tr, NULL, k)) return verr(v, "array '%s': offset past the end of the file", name);
        skip -= (long long)k;
        v->pos += (long long)k;
    }
    const uint64_t nbytes = (uint64_t)count * (uint64_t)a->elsize;
    const long long left = text_remaining(v->tr);
    if (!v->compressed) {
        uint64_t n;
        if (!read_hdr(v, &n)) return verr(v, "array '%s': data ends early (truncated file)", name);
        if (n != nbytes)
            return verr(v, "array '%s' holds %llu bytes, %llu expected", name, (unsigned long long)n,
                        (unsigned long long)nbytes);
        if (left >= 0 && n > (uint64_t)left) return verr(v, "array '%s': data ends early (truncated file)", name);
        GLPGP_CHECK_GOTO(st, read_grow(v, &raw, &cap, 0, (size_t)n, name), done);
    } else {
#ifdef GLPGP_HAVE_ZLIB
        uint64_t nb, bs, last;
        if (!read_hdr(v, &nb) || !read_hdr(v, &bs) || !read_hdr(v, &last))
            return verr(v, "array '%s': data ends early (truncated file)", name);
        /* nb blocks of bs bytes, the last one `last` bytes when last != 0 */
        int ok = (nb == 0 && nbytes == 0) ||
                 (nb > 0 && bs > 0 && last < bs && (bs >= 4096 || nb == 1) && nb <= nbytes / bs + 1 &&
                  (nb - 1) * bs + (last ? last : bs) == nbytes);
        if (!ok) return verr(v, "array '%s': compression header does not match %llu bytes", name, (unsigned long long)nbytes);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nb + 1, sizeof *csize, &csize), done);
        uint64_t csum = 0;
        for (uint64_t b = 0; b < nb; b++) {
            if (!read_hdr(v, &csize[b])) {
                st = verr(v, "array '%s': data ends early (truncated file)", name);
                goto done;
            }
            uint64_t ub = (b + 1 == nb && last) ? last : bs;
            if (csize[b] == 0 || csize[b] > compressBound((uLong)ub) || ub > 1100 * csize[b] + 1024) {
                st = verr(v, "array '%s': block %llu has an impossible compressed size", name, (unsigned long long)b);
                goto done;
            }
            csum += csize[b];
        }
        if (left >= 0 && csum > (uint64_t)left) {
            st = verr(v, "array '%s': data ends early (truncated file)", name);
            goto done;
        }
        size_t at = 0;
        for (uint64_t b = 0; b < nb; b++) {
            uint64_t ub = (b + 1 == nb && last) ? last : bs;
            GLPGP_CHECK_GOTO(st, glpgp_grow(&cbuf, &ccap, (size_t)csize[b], 1), done);
            if (!text_read_raw(v->tr, cbuf, (size_t)csize[b])) {
                st = verr(v, "array '%s': data ends early (truncated file)", name);
                goto done;
            }
            v->pos += (long long)csize[b];
            GLPGP_CHECK_GOTO(st, glpgp_grow(&raw, &cap, at + (size_t)ub, 1), done);
            uLongf got = (uLongf)ub;
            int zr = uncompress(raw + at, &got, cbuf, (uLong)csize[b]);
            if (zr != Z_OK || got != ub) {
                st = verr(v, "array '%s': block %llu does not decompress (%s)", name, (unsigned long long)b,
                          zr == Z_OK ? "short" : zError(zr));
                goto done;
            }
            at += (size_t)ub;
        }
#else
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "%s: compressed .vtu, but this build has no zlib", v->tr->path);
#endif
    }
    if (count == 0) goto done;
    if (v->swap) swap_bytes(raw, count, a->elsize);
    /* convert */
    const char *t = a->type;
    if (out_d) {
        double *d = NULL;
        if (!strcmp(t, "Float64")) {
            d = (double *)(void *)raw; /* malloc'd: aligned */
            raw = NULL;
        } else {
            GLPGP_CHECK_GOTO(st, glpgp_malloc(count, sizeof *d, &d), done);
            for (size_t i = 0; i < count; i++) {
                const unsigned char *p = raw + i * (size_t)a->elsize;
                if (!strcmp(t, "Float32")) {
                    float x;
                    memcpy(&x, p, 4);
                    d[i] = x;
                } else {
                    d[i] = (double)get_int(p, a->elsize, t[0] == 'U');
                }
            }
        }
        for (size_t i = 0; i < count; i++)
            if (!isfinite(d[i])) {
                free(d);
                st = verr(v, "array '%s': value %zu is not finite", name, i);
                goto done;
            }
        *out_d = d;
    } else {
        if (!strncmp(t, "Float", 5)) {
            st = verr(v, "array '%s' must hold integers, not %s", name, t);
            goto done;
        }
        long long *l = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_malloc(count, sizeof *l, &l), done);
        for (size_t i = 0; i < count; i++) {
            l[i] = get_int(raw + i * (size_t)a->elsize, a->elsize, t[0] == 'U');
        }
        *out_ll = l;
    }
done:
    free(raw);
    free(cbuf);
    free(csize);
    return st;
}
