/* io/mesh_io.c: triangle-mesh readers (Wavefront OBJ; Gmsh MSH 2.2 / 4.1
 * ASCII through the shared parser of msh_read.c) and writers (OBJ, MSH 4.1,
 * through the output set), glpgp/io.h. Readers are one pass over a
 * text_reader, drop unused vertices, take the coordinate plane the mesh
 * lies in, weld unwelded pieces and hand the triangles to
 * glpgp_mesh_create for validation. */
#include "glpgp/io.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include "msh.h"
#include "raw_mesh.h"
#include "text_reader.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Welding of unwelded meshes. Exports from CAD and mesh tools often repeat a
 * vertex per triangle or per surface patch (STL-derived OBJ files, MSH files
 * with nodes per entity): read as they are, each triangle or patch is a
 * domain of its own, its seams boundaries (a soup of 3585 triangles was
 * refined to 610k vertices and solved for 6 minutes as 3585 domains).
 * Vertices with equal coordinates are merged when they lie in different
 * pieces (connected components, through shared vertex indices) of the mesh
 * as read; coincident vertices of one piece stay apart: the two lips of a
 * crack (a slit meshed with doubled vertices) are such a pair. In each group
 * of coincident vertices, every vertex of another piece than the group's
 * first (lowest index) is merged into the first.
 *
 * Input: xy[2 nv], tri[3 nt] (indices < nv). Output: *nmerged, and when it
 * is > 0, xy compacted in place (kept vertices in their order) and tri
 * renumbered; *nv updated; *pieces_before / *pieces_after the counts of
 * pieces. */
typedef struct xy_index {
    double x, y, z; /* z = 0 for planar coordinates: the 2D order */
    int i;
} xy_index;

static int cmp_xy_index(const void *a, const void *b)
{
    const xy_index *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    if (p->z != q->z) return p->z < q->z ? -1 : 1;
    return (p->i > q->i) - (p->i < q->i);
}

static int count_pieces(int nv, int nt, const int *tri, int *parent)
{
    for (int v = 0; v < nv; v++) parent[v] = v;
    for (int t = 0; t < nt; t++)
        for (int k = 1; k < 3; k++) {
            int a = glpgp_uf_find(parent, tri[3 * t]), b = glpgp_uf_find(parent, tri[3 * t + k]);
            if (a != b) parent[b] = a;
        }
    int n = 0;
    for (int v = 0; v < nv; v++) n += glpgp_uf_find(parent, v) == v;
    return n;
}

static glpgp_status weld(int *nv, double *xy, int dim, int nt, int *tri, int *nmerged, int *pieces_before,
                         int *pieces_after)
{
    glpgp_status st = GLPGP_OK;
    int *piece = NULL, *renum = NULL, *to = NULL;
    xy_index *srt = NULL;
    const int n = *nv;
    *nmerged = 0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof *piece, &piece), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof *renum, &renum), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof *to, &to), done);
    *pieces_before = *pieces_after = count_pieces(n, nt, tri, piece);
    if (*pieces_before == 1) goto done; /* one piece: nothing to weld */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof *srt, &srt), done);
    for (int v = 0; v < n; v++) {
        piece[v] = glpgp_uf_find(piece, v);
        srt[v] = (xy_index){xy[dim * v], xy[dim * v + 1], dim == 3 ? xy[3 * v + 2] : 0.0, v};
        to[v] = v;
    }
    qsort(srt, (size_t)n, sizeof *srt, cmp_xy_index);
    int merged = 0;
    for (int i = 0; i < n;) {
        int j = i + 1;
        while (j < n && srt[j].x == srt[i].x && srt[j].y == srt[i].y && srt[j].z == srt[i].z) j++;
        const int first = srt[i].i; /* lowest index of the group */
        for (int k = i + 1; k < j; k++)
            if (piece[srt[k].i] != piece[first]) {
                to[srt[k].i] = first;
                merged++;
            }
        i = j;
    }
    if (merged) {
        /* new numbers: kept vertices in their order; merged ones take their
         * target's */
        int m = 0;
        for (int v = 0; v < n; v++)
            if (to[v] == v) {
                for (int c = 0; c < dim; c++) xy[dim * m + c] = xy[dim * v + c];
                renum[v] = m++;
            }
        for (int v = 0; v < n; v++) renum[v] = renum[to[v]];
        for (long i = 0; i < 3L * nt; i++) tri[i] = renum[tri[i]];
        *nv = m;
        *pieces_after = count_pieces(m, nt, tri, piece);
    }
    *nmerged = merged;
done:
    free(piece);
    free(renum);
    free(to);
    free(srt);
    return st;
}

/* Largest polygon face that is ear-clipped (O(n^2), O(n^3) at worst);
 * larger faces must be convex (fanned). The corner tests of all faces
 * together are bounded too (a second at most), so that no file of
 * pathological faces runs unbounded. */
#define OBJ_EARCLIP_MAX 2000
#define OBJ_EARCLIP_WORK 2000000000LL

/* Triangles of polygon face k (corners c[0 .. n), raw indices) in the plane
 * (cx, cy) of the coordinates: ear clipping of the simple polygon, in the
 * face's own orientation (a tip whose corner is straight is never cut:
 * CAD faces carry points along their straight edges, which a fan from such
 * a point would turn into flat triangles); above OBJ_EARCLIP_MAX corners a
 * strictly convex face is fanned. */
static glpgp_status triangulate_face(const char *path, raw_mesh *r, size_t k, int cx, int cy)
{
    const int *c = r->poly + r->pstart[k];
    const int n = (int)(r->pstart[k + 1] - r->pstart[k]);
    const long line = r->pline[k];
    const double *X = r->xyz;
#define PX(i) X[3 * (size_t)(i) + cx]
#define PY(i) X[3 * (size_t)(i) + cy]
#define CROSS(a, b, q) ((PX(b) - PX(a)) * (PY(q) - PY(a)) - (PY(b) - PY(a)) * (PX(q) - PX(a)))
    double area2 = 0.0; /* twice the signed area, about the first corner */
    for (int i = 1; i + 1 < n; i++) area2 += CROSS(c[0], c[i], c[i + 1]);
    if (!(area2 != 0.0))
        return GLPGP_FAIL(GLPGP_ERR_MESH, "%s:%ld: the face of %d corners encloses no area", path, line, n);
    const double sgn = area2 > 0 ? 1.0 : -1.0;
    if (n > OBJ_EARCLIP_MAX) {
        for (int i = 0; i < n; i++)
            if (!(sgn * CROSS(c[i], c[(i + 1) % n], c[(i + 2) % n]) > 0))
                return GLPGP_FAIL(GLPGP_ERR_LIMIT,
                                  "%s:%ld: a face of %d corners that is not strictly convex (faces above %d corners "
                                  "must be; split it into triangles)",
                                  path, line, n, OBJ_EARCLIP_MAX);
        for (int i = 1; i + 1 < n; i++) GLPGP_CHECK(raw_add_tri(r, c[0], c[i], c[i + 1]));
        return GLPGP_OK;
    }
    int *v = malloc(sizeof(int) * (size_t)n);
    if (!v) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory triangulating a face of %d corners", n);
    memcpy(v, c, sizeof(int) * (size_t)n);
    int m = n, k0 = 0, misses = 0;
    glpgp_status st = GLPGP_OK;
    while (m > 3 && st == GLPGP_OK) {
        if (misses > m) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "%s:%ld: the face of %d corners is not a simple polygon (its sides cross)",
                            path, line, n);
            break;
        }
        const int i0 = (k0 + m - 1) % m, i1 = k0 % m, i2 = (k0 + 1) % m;
        const int a = v[i0], b = v[i1], q = v[i2];
        int ear = sgn * CROSS(a, b, q) > 0; /* a convex, not straight, corner */
        /* no other corner inside or on the triangle a b q */
        r->ear_work += m;
        if (r->ear_work > OBJ_EARCLIP_WORK) {
            st = GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s:%ld: the polygon faces are too complex to triangulate (over %lld "
                            "corner tests); split them into triangles", path, line, OBJ_EARCLIP_WORK);
            break;
        }
        for (int j = 0; j < m && ear; j++) {
            const int p = v[j];
            if (j == i0 || j == i1 || j == i2 || p == a || p == b || p == q) continue;
            if (sgn * CROSS(a, b, p) >= 0 && sgn * CROSS(b, q, p) >= 0 && sgn * CROSS(q, a, p) >= 0) ear = 0;
        }
        if (!ear) {
            k0 = i2;
            misses++;
            continue;
        }
        st = raw_add_tri(r, a, b, q); /* the face's own orientation */
        memmove(v + i1, v + i1 + 1, sizeof(int) * (size_t)(m - i1 - 1));
        m--;
        k0 = i1 < m ? i1 : 0;
        misses = 0;
    }
    if (st == GLPGP_OK && m == 3) {
        if (sgn * CROSS(v[0], v[1], v[2]) > 0) st = raw_add_tri(r, v[0], v[1], v[2]);
        else st = GLPGP_FAIL(GLPGP_ERR_MESH, "%s:%ld: the face of %d corners is not a simple polygon", path, line, n);
    }
#undef PX
#undef PY
#undef CROSS
    free(v);
    return st;
}

/* A 3D triangle mesh (a CAD part's whole surface, e.g. the STL of an
 * extruded lamination): keep the triangles of its largest face in a
 * coordinate plane, those whose three corners have exactly the same z (or y,
 * or x), grouped by that value, the group of the largest area winning (ties:
 * z before y before x, then the lower value). 0 when no triangle lies in
 * such a plane. */
typedef struct face_tri {
    int axis;
    double val, area;
} face_tri;

static int cmp_face_tri(const void *a, const void *b)
{
    const face_tri *p = a, *q = b;
    if (p->axis != q->axis) return q->axis - p->axis; /* z, y, x */
    return (p->val > q->val) - (p->val < q->val);
}

static glpgp_status select_face(const char *path, raw_mesh *r, int *found)
{
    *found = 0;
    face_tri *ft = NULL;
    GLPGP_CHECK(glpgp_malloc(r->nt + 1, sizeof *ft, &ft));
    size_t n = 0;
    const double *X = r->xyz;
    for (size_t t = 0; t < r->nt; t++) {
        const int *v = r->tri + 3 * t;
        for (int a = 2; a >= 0; a--) {
            if (!(X[3 * v[0] + a] == X[3 * v[1] + a] && X[3 * v[0] + a] == X[3 * v[2] + a])) continue;
            const int i = (a + 1) % 3, j = (a + 2) % 3;
            const double *p = X + 3 * v[0], *q = X + 3 * v[1], *o = X + 3 * v[2];
            ft[n].axis = a;
            ft[n].val = p[a];
            ft[n].area = 0.5 * fabs((q[i] - p[i]) * (o[j] - p[j]) - (q[j] - p[j]) * (o[i] - p[i]));
            n++;
            break;
        }
    }
    qsort(ft, n, sizeof *ft, cmp_face_tri);
    int best_axis = -1;
    double best_val = 0.0, best_area = 0.0;
    for (size_t k = 0; k < n;) {
        size_t l = k;
        double sum = 0.0;
        while (l < n && ft[l].axis == ft[k].axis && ft[l].val == ft[k].val) sum += ft[l++].area;
        if (sum > best_area * (1.0 + 1e-9)) { /* equal areas up to rounding: the first wins */
            best_area = sum;
            best_axis = ft[k].axis;
            best_val = ft[k].val;
        }
        k = l;
    }
    free(ft);
    if (best_axis < 0) return GLPGP_OK;
    size_t w = 0;
    for (size_t t = 0; t < r->nt; t++) {
        const int *v = r->tri + 3 * t;
        if (X[3 * v[0] + best_axis] == best_val && X[3 * v[1] + best_axis] == best_val &&
            X[3 * v[2] + best_axis] == best_val) {
            memmove(r->tri + 3 * w, v, 3 * sizeof(int));
            w++;
        }
    }
    glpgp_log(GLPGP_LOG_WARNING,
              "%s: a 3D mesh (x, y and z vary): solving its largest face in a coordinate plane, %c = %.9g (%zu of "
              "%zu triangles, area %.6g)",
              path, "xyz"[best_axis], best_val, w, r->nt, best_area);
    r->nt = w;
    *found = 1;
    return GLPGP_OK;
}

/* map[v] <- the number of raw vertex v among those the triangles and
 * polygon faces use (-1: unused), lo / hi their coordinate ranges; returns
 * how many are used. */
static int used_vertices(const raw_mesh *r, int *map, double lo[3], double hi[3])
{
    for (size_t v = 0; v < r->nv; v++) map[v] = -1;
    for (size_t i = 0; i < 3 * r->nt; i++) map[r->tri[i]] = 0;
    for (size_t i = 0; i < r->npc; i++) map[r->poly[i]] = 0;
    for (int c = 0; c < 3; c++) {
        lo[c] = HUGE_VAL;
        hi[c] = -HUGE_VAL;
    }
    int nv = 0;
    for (size_t v = 0; v < r->nv; v++) {
        if (map[v] < 0) continue;
        map[v] = nv++;
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], r->xyz[3 * v + c]);
            hi[c] = fmax(hi[c], r->xyz[3 * v + c]);
        }
    }
    return nv;
}

/* What the welding did (nothing when merged is 0): an info line for an STL
 * soup (welding is what it needs), a warning for any other format. */
static void weld_log(const char *path, const raw_mesh *r, int merged, int nv, int before, int after)
{
    if (merged && r->soup)
        glpgp_log(GLPGP_LOG_INFO, "%s: %d STL vertices welded into %d, %d pieces -> %d", path, merged + nv, nv,
                  before, after);
    else if (merged)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d vertices repeat the coordinates of a vertex of another piece of the mesh (an "
                  "unwelded mesh): merged, %d pieces -> %d",
                  path, merged, before, after);
}

/* What glpgp_surface_fix did, one warning per repair (a file that needed
 * them is not what its writer meant to write). */
static void fix_log(const char *path, const glpgp_surface_fixes *fx, int nt)
{
    if (fx->duplicate)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d triangles repeat the three vertices of another (a face written twice): dropped", path,
                  fx->duplicate);
    if (fx->degenerate)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d triangles of zero area (a vertex inside an edge, or two vertices at one point): removed "
                  "by edge flips and collapses",
                  path, fx->degenerate);
    if (fx->thin)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d triangles with an angle below 1e-6 radians (two vertices a hair apart, or one a hair from "
                  "an edge): removed by edge flips and collapses (the surface moves by 1e-6 of their size at most)",
                  path, fx->thin);
    if (fx->flipped)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d of %d triangles were oriented against their neighbours: flipped (closed parts "
                  "outward)",
                  path, fx->flipped, nt);
    if (fx->nonmanifold)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d edges of four or more triangles (bodies touching along an edge): separated, the bodies "
                  "are meshed apart (%d vertices added)",
                  path, fx->nonmanifold, fx->nonmanifold_added);
    if (fx->pinched)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%s: %d vertices where surfaces touch at a point (more than one fan of triangles): split "
                  "into %d, the sheets are meshed apart",
                  path, fx->pinched, fx->pinched + fx->added);
}

/* Newell normal of polygon face k: the axis (0, 1, 2) of its largest
 * component, the face's plane is projected along it for the ear clipping. */
static int face_axis(const raw_mesh *r, size_t k)
{
    const int *c = r->poly + r->pstart[k];
    const int n = (int)(r->pstart[k + 1] - r->pstart[k]);
    double nn[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < n; i++) {
        const double *p = r->xyz + 3 * (size_t)c[i], *q = r->xyz + 3 * (size_t)c[(i + 1) % n];
        nn[0] += (p[1] - q[1]) * (p[2] + q[2]);
        nn[1] += (p[2] - q[2]) * (p[0] + q[0]);
        nn[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    const double a0 = fabs(nn[0]), a1 = fabs(nn[1]), a2 = fabs(nn[2]);
    return a2 >= a1 && a2 >= a0 ? 2 : a1 >= a0 ? 1 : 0;
}

/* A 3D surface (glpgp/surface.h): polygon faces ear-clipped in the plane
 * their normal is closest to (cyclic axes, so the face keeps its
 * orientation), unused vertices dropped, pieces welded in 3D, then
 * glpgp_mesh_create_surface. map[] from used_vertices. */
static glpgp_status finish_surface(const char *path, raw_mesh *r, int *map, int nv, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    double *xyz = NULL;
    for (size_t k = 0; k < r->npoly; k++) {
        const int ax = face_axis(r, k);
        GLPGP_CHECK(triangulate_face(path, r, k, (ax + 1) % 3, (ax + 2) % 3));
    }
    if (r->nt > (size_t)GLPGP_IO_MAX_ITEMS)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: more than %ld triangles", path, (long)GLPGP_IO_MAX_ITEMS);
    GLPGP_CHECK(glpgp_malloc((size_t)nv * 3, sizeof *xyz, &xyz));
    for (size_t v = 0; v < r->nv; v++)
        if (map[v] >= 0) memcpy(xyz + 3 * map[v], r->xyz + 3 * v, 3 * sizeof(double));
    for (size_t i = 0; i < 3 * r->nt; i++) r->tri[i] = map[r->tri[i]];
    int merged = 0, before = 0, after = 0;
    GLPGP_CHECK_GOTO(st, weld(&nv, xyz, 3, (int)r->nt, r->tri, &merged, &before, &after), done);
    weld_log(path, r, merged, nv, before, after);
    glpgp_surface_fixes fx;
    int nt = (int)r->nt;
    GLPGP_CHECK_GOTO(st, glpgp_surface_fix(&nv, &xyz, &nt, r->tri, &fx), done);
    fix_log(path, &fx, (int)r->nt - fx.duplicate);
    r->nt = (size_t)nt;
    if ((st = glpgp_mesh_create_surface(nv, xyz, (int)r->nt, r->tri, out)) != GLPGP_OK) io_name_error(path, st);
done:
    free(xyz);
    return st;
}

/* Removal of unused vertices, the plane (z = const, or y or x = const) or,
 * when x, y and z vary, the surface (finish_surface; with
 * GLPGP_READ_PLANAR_FACE its largest face in a coordinate plane instead),
 * triangulation of polygon faces, welding, then glpgp_mesh_create. */
static glpgp_status finish(const char *path, raw_mesh *r, int flags, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    int *map = NULL;
    double *xy = NULL;
    if (r->nt == 0 && r->npoly == 0) return GLPGP_FAIL(GLPGP_ERR_MESH, "%s: no triangles", path);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(r->nv, sizeof *map, &map), done);
    double lo[3], hi[3], d[3];
    int nv = used_vertices(r, map, lo, hi);
    for (int c = 0; c < 3; c++) d[c] = hi[c] - lo[c];
    /* the plane: z = const, else y = const or x = const (a part drawn in a
     * side view), solved in its two varying coordinates; a 3D surface: the
     * surface path, or (GLPGP_READ_PLANAR_FACE, triangles only) its largest
     * face in one of them */
    double size = fmax(d[0], fmax(d[1], d[2]));
    const int three_d = d[0] > 1e-9 * size && d[1] > 1e-9 * size && d[2] > 1e-9 * size;
    if (three_d && !(flags & GLPGP_READ_PLANAR_FACE)) {
        st = finish_surface(path, r, map, nv, out);
        goto done;
    }
    if (three_d && r->npoly == 0) {
        int found = 0;
        GLPGP_CHECK_GOTO(st, select_face(path, r, &found), done);
        if (found) {
            nv = used_vertices(r, map, lo, hi);
            for (int c = 0; c < 3; c++) d[c] = hi[c] - lo[c];
            size = fmax(d[0], fmax(d[1], d[2]));
        }
    }
    int cx = 0, cy = 1; /* the coordinates taken as x and y */
    if (d[2] > 1e-9 * size) {
        if (d[1] <= 1e-9 * size)
            cy = 2;
        else if (d[0] <= 1e-9 * size) {
            cx = 1;
            cy = 2;
        } else {
            st = GLPGP_FAIL(GLPGP_ERR_MESH,
                            "%s: mesh is not planar in a coordinate plane: x, y and z vary (by %.6g, %.6g, "
                            "%.6g), and no face of it lies in one; a tilted plane must be rotated into z = const "
                            "first",
                            path, d[0], d[1], d[2]);
            goto done;
        }
        glpgp_log(GLPGP_LOG_INFO, "%s: the mesh lies in the plane %c = %.9g: solved in its (%c, %c) coordinates", path,
                  "xyz"[3 - cx - cy], lo[3 - cx - cy], "xyz"[cx], "xyz"[cy]);
    }
    for (size_t k = 0; k < r->npoly; k++) GLPGP_CHECK_GOTO(st, triangulate_face(path, r, k, cx, cy), done);
    if (r->nt > (size_t)GLPGP_IO_MAX_ITEMS) {
        st = GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: more than %ld triangles", path, (long)GLPGP_IO_MAX_ITEMS);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv * 2, sizeof *xy, &xy), done);
    for (size_t v = 0; v < r->nv; v++) {
        if (map[v] < 0) continue;
        xy[2 * map[v]] = r->xyz[3 * v + cx];
        xy[2 * map[v] + 1] = r->xyz[3 * v + cy];
    }
    for (size_t i = 0; i < 3 * r->nt; i++) r->tri[i] = map[r->tri[i]];
    int merged = 0, before = 0, after = 0;
    GLPGP_CHECK_GOTO(st, weld(&nv, xy, 2, (int)r->nt, r->tri, &merged, &before, &after), done);
    weld_log(path, r, merged, nv, before, after);
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
    for (;;) {
        char *kw, *s;
        size_t kl;
        GLPGP_CHECK_GOTO(st, text_next_keyword(tr, &kw, &kl, &s), done);
        if (!kw) break;
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
                long long idx;
                GLPGP_CHECK_GOTO(st, obj_corner(tr, &s, &idx), done);
                if (idx == 0) break;
                long long v;
                if (idx > 0) {
                    v = idx - 1;
                    if (idx > max_index) {
                        max_index = idx;
                        max_line = tr->line;
                    }
                } else {
                    v = (long long)r->nv + idx;
                    if (v < 0) {
                        st = text_error(tr, GLPGP_ERR_FORMAT, 0,
                                        "relative face index %lld refers before the first vertex (%zu "
                                        "defined so far)",
                                        idx, r->nv);
                        goto done;
                    }
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
            for (size_t i = 0; i < n; i++)
                if (corners[i] > GLPGP_IO_MAX_ITEMS) {
                    st = text_error(tr, GLPGP_ERR_FORMAT, 0, "face index out of range");
                    goto done;
                }
            if (r->nt + r->npc >= (size_t)GLPGP_IO_MAX_ITEMS) {
                st = text_error(tr, GLPGP_ERR_LIMIT, 0, "more than %ld triangles", (long)GLPGP_IO_MAX_ITEMS);
                goto done;
            }
            if (n == 3) {
                GLPGP_CHECK_GOTO(st, raw_add_tri(r, (int)corners[0], (int)corners[1], (int)corners[2]), done);
            } else { /* a polygon: triangulated in finish, in the mesh's plane */
                GLPGP_CHECK_GOTO(st, glpgp_grow(&r->poly, &r->cap_pc, r->npc + n, sizeof(int)), done);
                for (size_t i = 0; i < n; i++) r->poly[r->npc + i] = (int)corners[i];
                GLPGP_CHECK_GOTO(st, glpgp_grow(&r->pstart, &r->cap_ps, r->npoly + 2, sizeof(long)), done);
                GLPGP_CHECK_GOTO(st, glpgp_grow(&r->pline, &r->cap_pl, r->npoly + 1, sizeof(long)), done);
                r->pstart[r->npoly] = (long)r->npc;
                r->pline[r->npoly] = tr->line;
                r->npc += n;
                r->pstart[++r->npoly] = (long)r->npc;
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

/* ---- STL: triangle soups, ASCII or binary ------------------------------------ */

/* A vertex of an STL triangle (each triangle brings its own three; finish
 * welds them). */
static glpgp_status stl_vertex(raw_mesh *r, const double *x)
{
    if (r->nv >= (size_t)GLPGP_IO_MAX_ITEMS)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "more than %ld STL vertices", (long)GLPGP_IO_MAX_ITEMS);
    GLPGP_CHECK(glpgp_grow(&r->xyz, &r->cap_v, r->nv + 1, 3 * sizeof(double)));
    memcpy(r->xyz + 3 * r->nv++, x, 3 * sizeof(double));
    return GLPGP_OK;
}

/* Binary STL after its 80-byte header: a uint32 count (little-endian) and
 * 50 bytes per triangle (normal, three float32 vertices, uint16); the count
 * must match the file's size when it is known (a regular file). */
static glpgp_status read_stl_binary(const char *path, FILE *f, long long size, raw_mesh *r)
{
    unsigned char b[50];
    if (fread(b, 1, 4, f) != 4) return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: binary STL without a triangle count", path);
    const unsigned long long n = b[0] | (unsigned long long)b[1] << 8 | (unsigned long long)b[2] << 16 |
                                 (unsigned long long)b[3] << 24;
    if (size >= 0 && (unsigned long long)(size - 84) != 50ULL * n)
        return GLPGP_FAIL(GLPGP_ERR_FORMAT,
                          "%s: binary STL of %lld bytes says %llu triangles (%llu bytes expected)", path, size, n,
                          84ULL + 50ULL * n);
    if (n > (unsigned long long)GLPGP_IO_MAX_ITEMS / 3)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: %llu triangles, more than %ld", path, n, (long)GLPGP_IO_MAX_ITEMS / 3);
    for (unsigned long long t = 0; t < n; t++) {
        if (fread(b, 1, 50, f) != 50)
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: binary STL ends after %llu of %llu triangles", path, t, n);
        for (int k = 0; k < 3; k++) {
            double x[3];
            for (int c = 0; c < 3; c++) {
                const unsigned char *q = b + 12 + 12 * k + 4 * c;
                const uint32_t u = q[0] | (uint32_t)q[1] << 8 | (uint32_t)q[2] << 16 | (uint32_t)q[3] << 24;
                float v;
                memcpy(&v, &u, sizeof v);
                if (!isfinite(v))
                    return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: triangle %llu has a non-finite coordinate", path, t + 1);
                x[c] = v;
            }
            GLPGP_CHECK(stl_vertex(r, x));
        }
        GLPGP_CHECK(raw_add_tri(r, (int)(r->nv - 3), (int)(r->nv - 2), (int)(r->nv - 1)));
    }
    return GLPGP_OK;
}

/* ASCII STL: solid, then facets (facet normal, outer loop, three vertex
 * lines, endloop, endfacet), endsolid; several solids are read one after
 * the other. */
static glpgp_status read_stl_ascii(text_reader *tr, raw_mesh *r)
{
    char *s;
    int in_loop = 0, nvl = 0;
    for (;;) {
        GLPGP_CHECK(text_next_line(tr, &s));
        if (!s) break;
        s = text_skip_ws(s);
        if (*s == '\0') continue;
        char *kw = s;
        while (*s && !isspace((unsigned char)*s)) s++;
        const size_t kl = (size_t)(s - kw);
#define KW(w) (kl == sizeof(w) - 1 && !strncmp(kw, w, kl))
        if (KW("vertex")) {
            double x[3];
            if (!in_loop) return text_error(tr, GLPGP_ERR_FORMAT, 0, "vertex outside an 'outer loop'");
            if (!text_parse_double(&s, &x[0]) || !text_parse_double(&s, &x[1]) || !text_parse_double(&s, &x[2]) ||
                !text_at_end(s))
                return text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed vertex line (expected: vertex x y z, finite)");
            if (++nvl > 3) return text_error(tr, GLPGP_ERR_FORMAT, 0, "a facet with more than 3 vertices");
            GLPGP_CHECK(stl_vertex(r, x));
        } else if (KW("outer")) {
            if (in_loop) return text_error(tr, GLPGP_ERR_FORMAT, 0, "'outer loop' inside a loop");
            in_loop = 1;
            nvl = 0;
        } else if (KW("endloop")) {
            if (!in_loop || nvl != 3)
                return text_error(tr, GLPGP_ERR_FORMAT, 0, "a facet with %d vertices (3 expected)", nvl);
            in_loop = 0;
            GLPGP_CHECK(raw_add_tri(r, (int)(r->nv - 3), (int)(r->nv - 2), (int)(r->nv - 1)));
        } else if (KW("solid") || KW("endsolid") || KW("facet") || KW("endfacet")) {
            continue; /* names and normals are not needed */
        } else {
            return text_error(tr, GLPGP_ERR_FORMAT, 0, "unknown STL keyword '%.*s'", (int)(kl > 40 ? 40 : kl), kw);
        }
#undef KW
    }
    if (in_loop) return text_error(tr, GLPGP_ERR_FORMAT, 0, "the file ends inside a facet");
    return GLPGP_OK;
}

/* STL: binary when the size is 84 + 50 n for the count n of its header, or
 * when it does not start with "solid"; ASCII otherwise. */
static glpgp_status read_stl(const char *path, raw_mesh *r)
{
    FILE *f = fopen(path, "rb");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    struct stat sb;
    const int known = fstat(fileno(f), &sb) == 0;
    const long long size = known && S_ISREG(sb.st_mode) ? (long long)sb.st_size : -1;
    if (known && S_ISDIR(sb.st_mode)) {
        fclose(f);
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read '%s': is a directory", path);
    }
    unsigned char head[84];
    size_t got = fread(head, 1, sizeof head, f);
    int ascii = 0;
    size_t i = 0;
    while (i < got && isspace(head[i])) i++;
    if (got - i >= 5 && !memcmp(head + i, "solid", 5)) {
        ascii = 1;
        if (got == sizeof head && size >= 84) {
            const unsigned long long n = head[80] | (unsigned long long)head[81] << 8 |
                                         (unsigned long long)head[82] << 16 | (unsigned long long)head[83] << 24;
            if ((unsigned long long)(size - 84) == 50ULL * n) ascii = 0; /* a binary file named "solid ..." */
        }
    }
    glpgp_status st;
    if (!ascii) {
        if (got < 80) {
            fclose(f);
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: neither an ASCII STL (\"solid\") nor a binary one (%zu bytes)",
                              path, got);
        }
        /* back to the count after the 80-byte header */
        st = fseek(f, 80, SEEK_SET) == 0 ? read_stl_binary(path, f, size, r)
                                          : GLPGP_FAIL(GLPGP_ERR_IO, "%s: cannot seek in a binary STL", path);
        fclose(f);
        return st;
    }
    fclose(f);
    text_reader tr;
    GLPGP_CHECK(text_open(&tr, path));
    st = read_stl_ascii(&tr, r);
    text_close(&tr);
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
    const size_t ntri = (size_t)d.ntri + 2 * (size_t)d.nquad;
    if (ntri > (size_t)GLPGP_IO_MAX_ITEMS) {
        st = GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: more than %ld triangles", path, (long)GLPGP_IO_MAX_ITEMS);
        goto done;
    }
    if (ntri > 0) GLPGP_CHECK_GOTO(st, glpgp_malloc(ntri * 3, sizeof(int), &r->tri), done);
    r->cap_t = ntri;
    for (long f = 0; f < d.nf; f++) {
        const int *c = d.corner + 4 * f;
        int *t = r->tri + 3 * r->nt;
        if (c[3] < 0) {
            t[0] = c[0];
            t[1] = c[1];
            t[2] = c[2];
            r->nt++;
            continue;
        }
        /* a quadrangle: two triangles over the diagonal whose two halves
         * turn the way the quadrangle does (a non-convex one has one such
         * diagonal): (c0 c1 c2)(c0 c2 c3) or (c0 c1 c3)(c1 c2 c3) */
        const double *x = r->xyz;
#define CR(a, b, q) ((x[3 * (b)] - x[3 * (a)]) * (x[3 * (q) + 1] - x[3 * (a) + 1]) - \
                     (x[3 * (b) + 1] - x[3 * (a) + 1]) * (x[3 * (q)] - x[3 * (a)]))
        const double area = CR(c[0], c[1], c[2]) + CR(c[0], c[2], c[3]); /* twice the signed area */
        const int d02 = CR(c[0], c[1], c[2]) * area > 0 && CR(c[0], c[2], c[3]) * area > 0;
#undef CR
        const int split[2][6] = {{0, 1, 2, 0, 2, 3}, {0, 1, 3, 1, 2, 3}};
        for (int k = 0; k < 6; k++) t[k] = c[split[!d02][k]];
        r->nt += 2;
    }
    if (d.nquad > 0) glpgp_log(GLPGP_LOG_INFO, "%s: %ld quadrangles, each split in two triangles", path, d.nquad);
    if (d.nhigh > 0)
        glpgp_log(GLPGP_LOG_INFO, "%s: %ld second- or higher-order elements: their corner nodes are used (straight edges)",
                  path, d.nhigh);
done:
    msh_free(&d);
    return st;
}

/* ---- entry points -------------------------------------------------------------- */

static int mesh_kind(const char *path)
{
    return glpgp_has_ext(path, ".obj")   ? 1
           : glpgp_has_ext(path, ".msh") ? 2
           : glpgp_has_ext(path, ".stl") ? 3
           : glpgp_has_ext(path, ".ply") ? 4
           : glpgp_has_ext(path, ".off") ? 5
                                         : 0;
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

glpgp_status glpgp_mesh_read(const char *path, glpgp_mesh **out) { return glpgp_mesh_read_ex(path, 0, out); }

glpgp_status glpgp_mesh_read_ex(const char *path, int flags, glpgp_mesh **out)
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
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "%s: unknown mesh file extension '%s' (supported: .obj, .msh, .stl, .ply, .off)", path, ext);
    }
    if (kind == 1) {
        text_reader tr;
        GLPGP_CHECK(text_open(&tr, path));
        st = read_obj(&tr, &r);
        text_close(&tr);
        if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    } else if (kind == 2) {
        st = read_msh(path, &r);
    } else if (kind == 4) {
        st = glpgp_read_ply(path, &r);
    } else if (kind == 5) {
        st = glpgp_read_off(path, &r);
    } else {
        st = read_stl(path, &r);
        r.soup = 1;
    }
    if (st == GLPGP_OK) GLPGP_CHECK_GOTO(st, finish(path, &r, flags, out), done);
done:
    raw_free(&r);
    return st;
}

glpgp_status glpgp_mesh_from_arrays(const char *name, int nv, const double *x, int dim, int nt, const int *tri,
                                    glpgp_mesh **out)
{
    *out = NULL;
    if (!name) name = "mesh";
    if (dim != 2 && dim != 3) return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: vertices must have 2 or 3 coordinates, not %d", name, dim);
    if (nv < 0 || nt < 0 || nv > GLPGP_IO_MAX_ITEMS || nt > GLPGP_IO_MAX_ITEMS)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: %d vertices, %d triangles: more than %ld", name, nv, nt,
                          (long)GLPGP_IO_MAX_ITEMS);
    for (long i = 0; i < (long)dim * nv; i++)
        if (!isfinite(x[i]))
            return GLPGP_FAIL(GLPGP_ERR_MESH, "%s: vertex %ld has a coordinate that is not finite", name, i / dim);
    for (long i = 0; i < 3L * nt; i++)
        if (tri[i] < 0 || tri[i] >= nv)
            return GLPGP_FAIL(GLPGP_ERR_MESH, "%s: triangle %ld uses vertex %d, not in [0, %d)", name, i / 3, tri[i],
                              nv);
    raw_mesh r;
    memset(&r, 0, sizeof r);
    glpgp_status st = glpgp_malloc((size_t)nv * 3 + 1, sizeof(double), &r.xyz);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nt * 3 + 1, sizeof(int), &r.tri);
    if (st == GLPGP_OK) {
        for (int v = 0; v < nv; v++)
            for (int c = 0; c < 3; c++) r.xyz[3 * v + c] = c < dim ? x[(size_t)dim * v + c] : 0.0;
        memcpy(r.tri, tri, sizeof(int) * 3 * (size_t)nt);
        r.nv = r.cap_v = (size_t)nv;
        r.nt = r.cap_t = (size_t)nt;
        st = finish(name, &r, 0, out);
    }
    raw_free(&r);
    return st;
}

static void write_obj(FILE *f, const glpgp_mesh *m)
{
    fprintf(f, "# glpgp mesh: %d vertices, %d triangles\n", m->nv, m->nt);
    for (int v = 0; v < m->nv; v++) {
        if (m->xyz)
            fprintf(f, "v %.17g %.17g %.17g\n", m->xyz[3 * v], m->xyz[3 * v + 1], m->xyz[3 * v + 2]);
        else
            fprintf(f, "v %.17g %.17g 0\n", m->xy[2 * v], m->xy[2 * v + 1]);
    }
    for (int t = 0; t < m->nt; t++)
        fprintf(f, "f %d %d %d\n", m->tri[3 * t] + 1, m->tri[3 * t + 1] + 1, m->tri[3 * t + 2] + 1);
}

static void write_msh(FILE *f, const glpgp_mesh *m)
{
    fprintf(f, "$MeshFormat\n4.1 0 %d\n$EndMeshFormat\n", (int)sizeof(size_t));
    if (m->xyz)
        fprintf(f, "$Entities\n0 0 1 0\n1 %.17g %.17g %.17g %.17g %.17g %.17g 0 0\n$EndEntities\n", m->bbox3[0],
                m->bbox3[1], m->bbox3[2], m->bbox3[3], m->bbox3[4], m->bbox3[5]);
    else
        fprintf(f, "$Entities\n0 0 1 0\n1 %.17g %.17g 0 %.17g %.17g 0 0 0\n$EndEntities\n", m->bbox[0], m->bbox[1],
                m->bbox[2], m->bbox[3]);
    fprintf(f, "$Nodes\n1 %d 1 %d\n2 1 0 %d\n", m->nv, m->nv, m->nv);
    for (int v = 0; v < m->nv; v++) fprintf(f, "%d\n", v + 1);
    for (int v = 0; v < m->nv; v++) {
        if (m->xyz)
            fprintf(f, "%.17g %.17g %.17g\n", m->xyz[3 * v], m->xyz[3 * v + 1], m->xyz[3 * v + 2]);
        else
            fprintf(f, "%.17g %.17g 0\n", m->xy[2 * v], m->xy[2 * v + 1]);
    }
    fprintf(f, "$EndNodes\n$Elements\n1 %d 1 %d\n2 1 2 %d\n", m->nt, m->nt, m->nt);
    for (int t = 0; t < m->nt; t++)
        fprintf(f, "%d %d %d %d\n", t + 1, m->tri[3 * t] + 1, m->tri[3 * t + 1] + 1, m->tri[3 * t + 2] + 1);
    fprintf(f, "$EndElements\n");
}

glpgp_status glpgp_output_set_mesh(glpgp_output_set *s, const glpgp_mesh *m, const char *path)
{
    if (!m || !path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_write: NULL argument");
    int kind = mesh_kind(path);
    if (!kind || kind >= 4) {
        char ext[16];
        path_ext(path, ext, sizeof ext);
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: cannot write meshes as '%s' (supported: .obj, .msh)", path, ext);
    }
    FILE *f;
    GLPGP_CHECK(glpgp_output_set_open(s, path, &f));
    glpgp_cnum cn; /* '.' whatever the locale */
    glpgp_cnum_begin(&cn);
    if (kind == 1)
        write_obj(f, m);
    else
        write_msh(f, m);
    glpgp_cnum_end(&cn);
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
