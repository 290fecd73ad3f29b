/* io/quadmesh_obj.c: reading quad meshes back (glpgp_quads_read, glpgp/io.h):
 * the OBJ polygon reader here (faces of any corner count, in the file's
 * orientation, the face origins from the groups glpgp's writer puts them in),
 * .msh through glpgp_quads_read_msh. An OBJ whose z are not all 0 is a
 * surface's mesh: q->xyz is set too (q->xy its x and y). */
#include "glpgp/io.h"
#include "glpgp/util.h"

#include "text_reader.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* The group names of the face origins (glpgp_quads_write's OBJ groups). */
static const char *const k_origin_group[GLPGP_QFACE_KINDS] = {"grid", "strips", "repair", "fallback"};

const char *glpgp_quads_origin_name(int origin)
{
    return origin >= 0 && origin < GLPGP_QFACE_KINDS ? k_origin_group[origin] : "?";
}

typedef struct qobj {
    double *xy, *z;
    size_t nv, cap_v, cap_z;
    int any_z; /* a z other than 0: a surface's mesh (q->xyz) */
    int *fs, *fv;
    size_t nf, cap_fs, nfv, cap_fv;
    unsigned char *origin;
    size_t cap_o;
    int any_origin;
} qobj;

/* One face line (after "f"): corners appended to o. */
static glpgp_status obj_face(text_reader *tr, char *s, qobj *o, int origin)
{
    size_t n = 0;
    for (;;) {
        long long idx;
        GLPGP_CHECK(obj_corner(tr, &s, &idx));
        if (idx == 0) break;
        long long v = idx > 0 ? idx - 1 : (long long)o->nv + idx;
        if (v < 0 || v >= (long long)o->nv)
            return text_error(tr, GLPGP_ERR_FORMAT, 0, "face index %lld out of range (%zu vertices defined so far)",
                              idx, o->nv);
        if (o->nfv >= (size_t)GLPGP_IO_MAX_ITEMS)
            return text_error(tr, GLPGP_ERR_LIMIT, 0, "more than %ld face corners", (long)GLPGP_IO_MAX_ITEMS);
        GLPGP_CHECK(glpgp_grow(&o->fv, &o->cap_fv, o->nfv + 1, sizeof(int)));
        o->fv[o->nfv++] = (int)v;
        n++;
    }
    if (n < 3) return text_error(tr, GLPGP_ERR_FORMAT, 0, "face with %zu corner%s (at least 3 needed)", n, n == 1 ? "" : "s");
    GLPGP_CHECK(glpgp_grow(&o->fs, &o->cap_fs, o->nf + 2, sizeof(int)));
    GLPGP_CHECK(glpgp_grow(&o->origin, &o->cap_o, o->nf + 1, 1));
    o->origin[o->nf] = (unsigned char)origin;
    o->fs[++o->nf] = (int)o->nfv;
    return GLPGP_OK;
}

static glpgp_status read_qobj(text_reader *tr, qobj *o)
{
    int origin = GLPGP_QFACE_GRID;
    GLPGP_CHECK(glpgp_grow(&o->fs, &o->cap_fs, 1, sizeof(int)));
    o->fs[0] = 0;
    for (;;) {
        char *kw, *s;
        size_t kl;
        GLPGP_CHECK(text_next_keyword(tr, &kw, &kl, &s));
        if (!kw) break;
        if (kl == 1 && kw[0] == 'v') {
            double c[4];
            int n = 0;
            while (n < 4 && text_parse_double(&s, &c[n])) n++;
            if (!text_at_end(s) || n < 2)
                return text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed vertex (expected finite numbers: v x y [z])");
            if (o->nv >= (size_t)GLPGP_IO_MAX_ITEMS)
                return text_error(tr, GLPGP_ERR_LIMIT, 0, "more than %ld vertices", (long)GLPGP_IO_MAX_ITEMS);
            GLPGP_CHECK(glpgp_grow(&o->xy, &o->cap_v, o->nv + 1, 2 * sizeof(double)));
            GLPGP_CHECK(glpgp_grow(&o->z, &o->cap_z, o->nv + 1, sizeof(double)));
            o->xy[2 * o->nv] = c[0];
            o->xy[2 * o->nv + 1] = c[1];
            o->z[o->nv] = n > 2 ? c[2] : 0.0;
            if (o->z[o->nv] != 0.0) o->any_z = 1;
            o->nv++;
        } else if (kl == 1 && kw[0] == 'f') {
            GLPGP_CHECK(obj_face(tr, s, o, origin));
        } else if (kl == 1 && kw[0] == 'g') {
            char *name = text_skip_ws(s);
            origin = GLPGP_QFACE_GRID;
            for (int k = 0; k < GLPGP_QFACE_KINDS; k++)
                if (!strcmp(name, k_origin_group[k])) {
                    origin = k;
                    o->any_origin = 1;
                }
        } /* anything else (vt, vn, o, s, usemtl, mtllib, ...) is not needed */
    }
    if (o->nf == 0) return text_error(tr, GLPGP_ERR_FORMAT, 0, "no faces");
    return GLPGP_OK;
}

glpgp_status glpgp_quads_read(const char *path, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_quads_read: no path");
    if (glpgp_has_ext(path, ".msh")) return glpgp_quads_read_msh(path, out);
    if (!glpgp_has_ext(path, ".obj"))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: quad meshes are read from .obj or .msh files", path);
    text_reader tr;
    qobj o;
    memset(&o, 0, sizeof o);
    GLPGP_CHECK(text_open(&tr, path));
    glpgp_status st = read_qobj(&tr, &o);
    text_close(&tr);
    glpgp_quadmesh *q = NULL;
    if (st == GLPGP_OK) st = glpgp_calloc(1, sizeof *q, &q);
    if (st == GLPGP_OK) {
        /* vertices used by no face are kept (the faces index them as written) */
        q->nv = (int)o.nv;
        q->nf = (int)o.nf;
        q->xy = o.xy;
        q->face_start = o.fs;
        q->face_vert = o.fv;
        q->face_origin = o.any_origin ? o.origin : NULL;
        if (!o.any_origin) free(o.origin);
        if (o.any_z) st = glpgp_malloc(3 * o.nv + 1, sizeof(double), &q->xyz);
        for (size_t i = 0; o.any_z && st == GLPGP_OK && i < o.nv; i++) {
            q->xyz[3 * i] = o.xy[2 * i];
            q->xyz[3 * i + 1] = o.xy[2 * i + 1];
            q->xyz[3 * i + 2] = o.z[i];
        }
        free(o.z);
        if (st != GLPGP_OK) glpgp_quadmesh_destroy(&q);
        *out = q;
        return st;
    }
    free(o.z);
    free(o.xy);
    free(o.fs);
    free(o.fv);
    free(o.origin);
    return st;
}
