/* io/raw_mesh.h: the raw (unvalidated) triangle mesh the mesh readers fill
 * (mesh_io.c: OBJ, STL, MSH; mesh_read3d.c: PLY, OFF) before mesh_io.c's
 * finish() drops unused vertices, picks the plane or the surface path,
 * triangulates polygon faces, welds and validates. Private to the io layer. */
#ifndef GLPGP_IO_RAW_MESH_H
#define GLPGP_IO_RAW_MESH_H

#include "glpgp/io.h"
#include "glpgp/util.h"

#include "text_reader.h"

#include <stdlib.h>
#include <string.h>

typedef struct raw_mesh {
    double *xyz;
    size_t nv, cap_v;
    int *tri;
    size_t nt, cap_t;
    /* faces of more than 3 corners, triangulated once the plane is known
     * (finish): corners poly[pstart[k] .. pstart[k + 1]), the file line */
    int *poly;
    size_t npc, cap_pc;
    long *pstart, *pline;
    size_t npoly, cap_ps, cap_pl;
    long long ear_work; /* corner tests of the ear clipping so far (bounded) */
    int soup;           /* STL: no shared vertices by design (welding is not news) */
} raw_mesh;

static inline void raw_free(raw_mesh *r)
{
    free(r->xyz);
    free(r->tri);
    free(r->poly);
    free(r->pstart);
    free(r->pline);
    memset(r, 0, sizeof *r);
}

static inline glpgp_status raw_add_tri(raw_mesh *r, int a, int b, int c)
{
    GLPGP_CHECK(glpgp_grow(&r->tri, &r->cap_t, r->nt + 1, 3 * sizeof(int)));
    int *t = r->tri + 3 * r->nt++;
    t[0] = a;
    t[1] = b;
    t[2] = c;
    return GLPGP_OK;
}

/* A face of n > 3 corners c[0 .. n) read on line `line`, kept for finish. */
static inline glpgp_status raw_add_poly(raw_mesh *r, const int *c, size_t n, long line)
{
    GLPGP_CHECK(glpgp_grow(&r->poly, &r->cap_pc, r->npc + n, sizeof(int)));
    for (size_t i = 0; i < n; i++) r->poly[r->npc + i] = c[i];
    GLPGP_CHECK(glpgp_grow(&r->pstart, &r->cap_ps, r->npoly + 2, sizeof(long)));
    GLPGP_CHECK(glpgp_grow(&r->pline, &r->cap_pl, r->npoly + 1, sizeof(long)));
    r->pstart[r->npoly] = (long)r->npc;
    r->pline[r->npoly] = line;
    r->npc += n;
    r->pstart[++r->npoly] = (long)r->npc;
    return GLPGP_OK;
}

/* Stanford PLY (ASCII, binary little- and big-endian) and Object File
 * Format (OFF) into r (mesh_read3d.c). Errors: "PATH:LINE: what" for text,
 * the element and its index for binary data; counts are checked against the
 * bytes left before anything is reserved. */
glpgp_status glpgp_read_ply(const char *path, raw_mesh *r);
glpgp_status glpgp_read_off(const char *path, raw_mesh *r);

#endif
