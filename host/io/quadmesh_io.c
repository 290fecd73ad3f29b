/* io/quadmesh_io.c: quad meshes on disk (glpgp/io.h): the quality report as
 * JSON (through the one emitter, json.c), the OBJ / legacy VTK / VTK XML /
 * Gmsh MSH 4.1 writers (through the output set) and the MSH reader (a thin
 * wrapper of the shared parser, msh_read.c). */
#include "glpgp/io.h"
#include "glpgp/util.h"
#include "glpgp/version.h"

#include "msh.h"
#include "vtu.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- JSON -------------------------------------------------------------- */

/* Histogram as an object {"<prefix>n": count} of the non-zero bins. */
static void histogram(glpgp_json *w, const char *key, const int *h, int n, int first, int skip, int capped)
{
    glpgp_json_object(w, key);
    for (int b = 0; b < n; b++) {
        if (b == skip || !h[b]) continue;
        char name[16];
        snprintf(name, sizeof name, "%s%d", b == capped ? ">=" : "", b + first);
        glpgp_json_int(w, name, h[b]);
    }
    glpgp_json_close(w);
}

/* "origin": quads per face origin, the repaired share; "mostly_repaired". */
static void json_origin(glpgp_json *w, const glpgp_quads_report *qq)
{
    glpgp_json_object(w, "origin");
    for (int k = 0; k < GLPGP_QFACE_KINDS; k++) glpgp_json_int(w, glpgp_quads_origin_name(k), qq->quads_by_origin[k]);
    glpgp_json_num(w, "repaired_share", qq->repaired_share);
    glpgp_json_close(w);
    glpgp_json_bool(w, "mostly_repaired", qq->repaired_share > GLPGP_QUADS_MOSTLY_REPAIRED);
}

/* "repair": what it did, with the regions listed (the worst first). */
static void json_repair(glpgp_json *w, const glpgp_quads_repair *r)
{
    glpgp_json_object(w, "repair");
    glpgp_json_int(w, "rounds", r->rounds);
    glpgp_json_int(w, "removed_faces", r->removed_faces);
    glpgp_json_int(w, "regions", r->regions);
    glpgp_json_int(w, "new_quads", r->new_quads);
    glpgp_json_int(w, "snapped_vertices", r->snapped);
    glpgp_json_int(w, "chord_strips", r->chord_strips);
    glpgp_json_int(w, "paved_regions", r->paved_regions);
    glpgp_json_int(w, "fallback_regions", r->fallback_regions);
    glpgp_json_int(w, "flat_corners", r->flat_corners);
    glpgp_json_int(w, "sharp_tips", r->sharp_tips);
    glpgp_json_int(w, "shaped_vertices", r->shaped_vertices);
    glpgp_json_str(w, "whole_domain", r->whole_domain == 2 ? "input-triangles" : r->whole_domain == 1 ? "meshed-again" : "no");
    int order[GLPGP_QUADS_REGIONS_LISTED], n = r->nlisted;
    for (int i = 0; i < n; i++) order[i] = i;
    for (int i = 1; i < n; i++) /* by sj_min, the worst first */
        for (int j = i; j > 0 && r->region[order[j]].sj_min < r->region[order[j - 1]].sj_min; j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    glpgp_json_array(w, "regions_listed");
    for (int i = 0; i < n; i++) {
        const glpgp_quads_region *g = &r->region[order[i]];
        glpgp_json_object(w, NULL);
        glpgp_json_int(w, "faces_in", g->faces_in);
        glpgp_json_int(w, "quads_out", g->quads_out);
        glpgp_json_num(w, "sj_min", g->sj_min);
        glpgp_json_num(w, "x", g->x);
        glpgp_json_num(w, "y", g->y);
        glpgp_json_str(w, "mesher", glpgp_quads_origin_name(g->origin));
        glpgp_json_int(w, "round", g->round);
        glpgp_json_close(w);
    }
    glpgp_json_close(w);
    glpgp_json_close(w);
}

/* "steps": what the surface pipeline did (glpgp_quads_surface_steps), and
 * "path": the step the mesh came from, as the summary names it. */
static void json_steps(glpgp_json *w, const glpgp_quads_surface_steps *s)
{
    const char *path = s->fallback ? (s->coarse_triangles ? "coarse last resort" : "input triangles split")
                       : s->subdivided      ? "split h/2"
                       : s->split_faces     ? "local split"
                       : s->refined_faces   ? "local refinement"
                       : s->local_regions   ? "local repair"
                                            : "grid";
    glpgp_json_object(w, "steps");
    glpgp_json_str(w, "path", path);
    glpgp_json_int(w, "extracted_faces", s->extracted_faces);
    glpgp_json_int(w, "extracted_quads", s->extracted_quads);
    glpgp_json_int(w, "closed", s->closed);
    glpgp_json_int(w, "strips", s->strips);
    glpgp_json_int(w, "local_regions", s->local_regions);
    glpgp_json_int(w, "local_faces_in", s->local_faces_in);
    glpgp_json_int(w, "local_quads_out", s->local_quads_out);
    glpgp_json_int(w, "split_faces", s->split_faces);
    glpgp_json_int(w, "refined_faces", s->refined_faces);
    glpgp_json_bool(w, "split_h2", s->subdivided);
    glpgp_json_bool(w, "last_resort", s->fallback);
    glpgp_json_int(w, "coarse_triangles", s->coarse_triangles);
    glpgp_json_int(w, "smoothed_vertices", s->smoothed);
    glpgp_json_num(w, "sj_before_smoothing", s->sj_before);
    glpgp_json_num(w, "sj_after_smoothing", s->sj_after);
    glpgp_json_int(w, "flat_corners", s->flat_corners);
    glpgp_json_int(w, "flat_faces", s->flat_faces);
    glpgp_json_int(w, "parts", s->parts > 1 ? s->parts : 1);
    glpgp_json_int(w, "parts_last_resort", s->parts > 1 ? s->parts_last_resort : s->fallback);
    glpgp_json_close(w);
}

void glpgp_quads_json(glpgp_json *w, const char *key, const glpgp_quads_report *qq)
{
    glpgp_json_object(w, key);
    glpgp_json_int(w, "vertices", qq->vertices);
    glpgp_json_int(w, "faces", qq->faces);
    glpgp_json_int(w, "quads", qq->quads);
    glpgp_json_int(w, "other_faces", qq->others);
    histogram(w, "other_faces_by_corners", qq->others_by_size, 8, 3, 1, 7);
    glpgp_json_object(w, "valence");
    histogram(w, "interior", qq->valence_interior, GLPGP_QUADS_MAXVAL + 1, 0, -1, GLPGP_QUADS_MAXVAL);
    histogram(w, "boundary", qq->valence_boundary, GLPGP_QUADS_MAXVAL + 1, 0, -1, GLPGP_QUADS_MAXVAL);
    glpgp_json_close(w);
    glpgp_json_object(w, "irregular_vertices");
    glpgp_json_int(w, "interior", qq->irregular_interior);
    glpgp_json_int(w, "boundary", qq->irregular_boundary);
    glpgp_json_int(w, "total", qq->irregular);
    if (qq->cross_singularities >= 0) { /* a --field cross solve: interior = near + far */
        glpgp_json_int(w, "interior_near_cross", qq->irregular_near_cross);
        glpgp_json_int(w, "interior_far_cross", qq->irregular_far_cross);
    }
    glpgp_json_close(w);
    if (qq->cross_singularities >= 0) {
        glpgp_json_object(w, "cross_singularities");
        glpgp_json_int(w, "count", qq->cross_singularities);
        glpgp_json_num(w, "radius", qq->cross_radius);
        glpgp_json_int(w, "with_irregular_vertex", qq->cross_matched);
        glpgp_json_close(w);
    }
    glpgp_json_object(w, "scaled_jacobian");
    glpgp_json_num(w, "min", qq->sj_min);
    glpgp_json_num(w, "mean", qq->sj_mean);
    glpgp_json_num(w, "p01", qq->sj_p01);
    glpgp_json_num(w, "min_of_corner_bound", qq->sj_min_corner);
    glpgp_json_int(w, "below_goal", qq->below_sj_goal);
    glpgp_json_close(w);
    glpgp_json_int(w, "inverted", qq->inverted);
    glpgp_json_int(w, "degenerate", qq->degenerate);
    glpgp_json_object(w, "edges");
    glpgp_json_int(w, "count", qq->edges);
    glpgp_json_int(w, "boundary", qq->boundary_edges);
    glpgp_json_int(w, "nonmanifold", qq->nonmanifold_edges);
    glpgp_json_close(w);
    glpgp_json_object(w, "edge_length_over_h");
    glpgp_json_num(w, "mean", qq->len_mean);
    glpgp_json_num(w, "min", qq->len_min);
    glpgp_json_num(w, "max", qq->len_max);
    glpgp_json_close(w);
    glpgp_json_num(w, "h", qq->h);
    glpgp_json_num(w, "area", qq->area);
    const int domain = qq->hausdorff >= 0;
    if (domain)
        glpgp_json_num(w, "domain_area", qq->domain_area);
    else
        glpgp_json_null(w, "domain_area");
    if (domain) {
        glpgp_json_object(w, "boundary_distance_over_h");
        glpgp_json_num(w, "hausdorff", qq->hausdorff);
        glpgp_json_num(w, "quads_to_domain", qq->dist_quad_to_domain);
        glpgp_json_num(w, "domain_to_quads", qq->dist_domain_to_quad);
        glpgp_json_close(w);
        glpgp_json_num(w, "gap_edges", qq->gap_edges);
    } else {
        glpgp_json_null(w, "boundary_distance_over_h");
        glpgp_json_null(w, "gap_edges");
    }
    if (qq->singular[0] >= 0) {
        glpgp_json_object(w, "singular_triangles");
        glpgp_json_int(w, "u", qq->singular[0]);
        glpgp_json_int(w, "v", qq->singular[1]);
        glpgp_json_close(w);
    } else {
        glpgp_json_null(w, "singular_triangles");
    }
    glpgp_json_bool(w, "valid", qq->invalid == 0);
    glpgp_json_array(w, "invalid_reasons");
    for (int b = 0; b < GLPGP_QUADS_BAD_COUNT; b++)
        if (qq->invalid & (1u << b)) glpgp_json_str(w, NULL, glpgp_quads_bad_name(1u << b));
    glpgp_json_close(w);
    glpgp_json_int(w, "orientation", qq->orientation);
    glpgp_json_int(w, "overlapping_faces", qq->overlaps);
    glpgp_json_int(w, "pinched_vertices", qq->pinched);
    glpgp_json_int(w, "non_quad_faces", qq->others);
    glpgp_json_object(w, "boundary_loops");
    glpgp_json_int(w, "mesh", qq->boundary_loops);
    if (qq->domain_loops >= 0)
        glpgp_json_int(w, "domain", qq->domain_loops);
    else
        glpgp_json_null(w, "domain");
    glpgp_json_close(w);
    if (domain) {
        glpgp_json_num(w, "area_ratio", qq->area_ratio);
        glpgp_json_int(w, "outside_faces", qq->outside);
        glpgp_json_int(w, "far_faces", qq->far_faces);
        glpgp_json_int(w, "corners_lost", qq->corners_lost);
        glpgp_json_num(w, "boundary_vertex_distance_over_h", qq->bnd_vertex_dist);
    } else {
        glpgp_json_null(w, "area_ratio");
        glpgp_json_null(w, "outside_faces");
        glpgp_json_null(w, "far_faces");
        glpgp_json_null(w, "corners_lost");
        glpgp_json_null(w, "boundary_vertex_distance_over_h");
    }
    glpgp_json_num(w, "max_edge_over_h", qq->len_max);
    if (qq->surface) { /* a surface's mesh: distances to the surface, topology against the input's */
        glpgp_json_object(w, "surface");
        glpgp_json_num(w, "hausdorff_over_h", qq->hausdorff);
        glpgp_json_num(w, "quads_to_surface_over_h", qq->dist_quad_to_domain);
        glpgp_json_num(w, "surface_to_quads_over_h", qq->dist_domain_to_quad);
        glpgp_json_int(w, "euler", qq->euler);
        glpgp_json_int(w, "input_euler", qq->domain_euler);
        glpgp_json_int(w, "boundary_loops", qq->boundary_loops);
        glpgp_json_int(w, "input_boundary_loops", qq->domain_loops);
        glpgp_json_num(w, "area_ratio", qq->area_ratio);
        glpgp_json_num(w, "area_tolerance", glpgp_quads_surface_area_tolerance(qq));
        if (qq->has_steps) json_steps(w, &qq->steps);
        glpgp_json_close(w);
    }
    json_origin(w, qq);
    json_repair(w, &qq->repair);
    glpgp_json_object(w, "cleanup");
    glpgp_json_int(w, "doublets", qq->cleanup.doublets);
    glpgp_json_int(w, "collapses", qq->cleanup.collapses);
    glpgp_json_int(w, "rotations", qq->cleanup.rotations);
    glpgp_json_int(w, "cost_before", qq->cleanup.cost_before);
    glpgp_json_int(w, "cost_after", qq->cleanup.cost_after);
    glpgp_json_close(w);
    glpgp_json_object(w, "closing");
    glpgp_json_int(w, "odd_faces_closed", qq->closing.closed_polygons);
    glpgp_json_int(w, "strips_to_boundary", qq->closing.strips_to_boundary);
    glpgp_json_int(w, "quads_cut", qq->closing.strip_quads);
    glpgp_json_int(w, "turns", qq->closing.strip_turns);
    glpgp_json_int(w, "even_faces_split", qq->closing.split_even);
    glpgp_json_int(w, "smoothed_vertices", qq->closing.smoothed_vertices);
    glpgp_json_close(w);
    glpgp_json_close(w);
}

glpgp_status glpgp_output_set_quads_json(glpgp_output_set *s, const glpgp_quads_report *qq, const char *path)
{
    FILE *f;
    if (!qq) return GLPGP_FAIL(GLPGP_ERR_ARG, "no quad report to write");
    GLPGP_CHECK(glpgp_output_set_open(s, path, &f));
    glpgp_json w;
    glpgp_json_init(&w, f);
    glpgp_json_object(&w, NULL);
    glpgp_quads_json(&w, "quads", qq);
    glpgp_json_finish(&w);
    return GLPGP_OK;
}

glpgp_status glpgp_quads_write_json_file(const glpgp_quads_report *qq, const char *path)
{
    glpgp_output_set *s = NULL;
    GLPGP_CHECK(glpgp_output_set_create(&s));
    glpgp_status st = glpgp_output_set_quads_json(s, qq, path);
    if (st == GLPGP_OK) st = glpgp_output_set_commit(s);
    glpgp_output_set_destroy(&s);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

/* ---- writers ----------------------------------------------------------- */

enum { QF_NONE = 0, QF_OBJ, QF_VTK, QF_VTU, QF_MSH, QF_PLY };

static int quads_format(const char *path)
{
    if (!path) return QF_NONE;
    return glpgp_has_ext(path, ".obj")   ? QF_OBJ
           : glpgp_has_ext(path, ".vtk") ? QF_VTK
           : glpgp_has_ext(path, ".vtu") ? QF_VTU
           : glpgp_has_ext(path, ".msh") ? QF_MSH
           : glpgp_has_ext(path, ".ply") ? QF_PLY
                                         : QF_NONE;
}

int glpgp_quads_path_supported(const char *path) { return quads_format(path) != QF_NONE; }

/* ASCII PLY: the vertices (z 0 for a planar mesh) and the faces as
 * vertex index lists, counter-clockwise (seen from the surface's front). */
static void write_ply(FILE *f, const glpgp_quadmesh *q)
{
    fprintf(f, "ply\nformat ascii 1.0\ncomment glpgp %s quad mesh\nelement vertex %d\n", GLPGP_VERSION, q->nv);
    fprintf(f, "property double x\nproperty double y\nproperty double z\nelement face %d\n", q->nf);
    fprintf(f, "property list uchar int vertex_indices\nend_header\n");
    for (int i = 0; i < q->nv; i++) {
        if (q->xyz) fprintf(f, "%.17g %.17g %.17g\n", q->xyz[3 * i], q->xyz[3 * i + 1], q->xyz[3 * i + 2]);
        else fprintf(f, "%.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    }
    for (int fa = 0; fa < q->nf; fa++) {
        const int b = q->face_start[fa], n = q->face_start[fa + 1] - b;
        fprintf(f, "%d", n > 255 ? 255 : n);
        for (int i = 0; i < n && i < 255; i++) fprintf(f, " %d", q->face_vert[b + i]);
        fputc('\n', f);
    }
}

static void write_obj(FILE *f, const glpgp_quadmesh *q)
{
    fprintf(f, "# glpgp %s quad mesh: %d vertices, %d faces\n", GLPGP_VERSION, q->nv, q->nf);
    for (int i = 0; i < q->nv; i++) {
        if (q->xyz) fprintf(f, "v %.17g %.17g %.17g\n", q->xyz[3 * i], q->xyz[3 * i + 1], q->xyz[3 * i + 2]);
        else fprintf(f, "v %.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    }
    int group = -1;
    for (int fa = 0; fa < q->nf; fa++) {
        int o = q->face_origin ? q->face_origin[fa] : -1;
        if (o != group && o >= 0) fprintf(f, "g %s\n", glpgp_quads_origin_name(o));
        group = o;
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
    for (int i = 0; i < q->nv; i++) {
        if (q->xyz) fprintf(f, "%.17g %.17g %.17g\n", q->xyz[3 * i], q->xyz[3 * i + 1], q->xyz[3 * i + 2]);
        else fprintf(f, "%.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    }
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
    for (int fa = 0; fa < q->nf; fa++) fprintf(f, "%.6g\n", q->xyz ? glpgp_quadmesh_face_sj_surface(q, fa) : glpgp_quadmesh_face_sj(q, fa));
    fprintf(f, "SCALARS origin int 1\nLOOKUP_TABLE default\n");
    for (int fa = 0; fa < q->nf; fa++) fprintf(f, "%d\n", q->face_origin ? q->face_origin[fa] : 0);
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
    for (int i = 0; i < q->nv; i++) {
        if (q->xyz) fprintf(f, "%.17g %.17g %.17g\n", q->xyz[3 * i], q->xyz[3 * i + 1], q->xyz[3 * i + 2]);
        else fprintf(f, "%.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    }
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

/* VTK XML: the arrays of the legacy writer, scaled Jacobian exact. */
typedef struct q_ctx {
    const glpgp_quadmesh *q;
    const int *valence;
} q_ctx;

static void qfill_points(const void *c, size_t first, size_t n, void *out)
{
    const glpgp_quadmesh *q = ((const q_ctx *)c)->q;
    double *o = out;
    for (size_t i = 0; i < n; i++) {
        o[3 * i] = q->xy[2 * (first + i)];
        o[3 * i + 1] = q->xy[2 * (first + i) + 1];
        o[3 * i + 2] = q->xyz ? q->xyz[3 * (first + i) + 2] : 0.0;
        if (q->xyz) {
            o[3 * i] = q->xyz[3 * (first + i)];
            o[3 * i + 1] = q->xyz[3 * (first + i) + 1];
        }
    }
}
static void qfill_conn(const void *c, size_t first, size_t n, void *out)
{
    memcpy(out, ((const q_ctx *)c)->q->face_vert + first, n * sizeof(int));
}
static void qfill_offsets(const void *c, size_t first, size_t n, void *out)
{
    memcpy(out, ((const q_ctx *)c)->q->face_start + first + 1, n * sizeof(int));
}
static void qfill_types(const void *c, size_t first, size_t n, void *out)
{
    const glpgp_quadmesh *q = ((const q_ctx *)c)->q;
    unsigned char *o = out;
    for (size_t i = 0; i < n; i++) {
        size_t f = first + i;
        o[i] = q->face_start[f + 1] - q->face_start[f] == 4 ? 9 : 7; /* VTK_QUAD, VTK_POLYGON */
    }
}
static void qfill_corners(const void *c, size_t first, size_t n, void *out)
{
    const glpgp_quadmesh *q = ((const q_ctx *)c)->q;
    int *o = out;
    for (size_t i = 0; i < n; i++) o[i] = q->face_start[first + i + 1] - q->face_start[first + i];
}
static void qfill_sj(const void *c, size_t first, size_t n, void *out)
{
    const glpgp_quadmesh *q = ((const q_ctx *)c)->q;
    double *o = out;
    for (size_t i = 0; i < n; i++) o[i] = q->xyz ? glpgp_quadmesh_face_sj_surface(q, (int)(first + i)) : glpgp_quadmesh_face_sj(q, (int)(first + i));
}
static void qfill_origin(const void *c, size_t first, size_t n, void *out)
{
    const glpgp_quadmesh *q = ((const q_ctx *)c)->q;
    int *o = out;
    for (size_t i = 0; i < n; i++) o[i] = q->face_origin ? q->face_origin[first + i] : 0;
}
static void qfill_valence(const void *c, size_t first, size_t n, void *out)
{
    memcpy(out, ((const q_ctx *)c)->valence + first, n * sizeof(int));
}

static glpgp_status write_vtu(FILE *f, const glpgp_quadmesh *q)
{
    int *val = NULL;
    GLPGP_CHECK(glpgp_quadmesh_valences(q, &val));
    q_ctx ctx = {q, val};
    const size_t nv = (size_t)q->nv, nf = (size_t)q->nf;
    const vtu_array a[] = {
        {VTU_POINTDATA, "valence", "Int32", 4, 1, nv, qfill_valence, &ctx},
        {VTU_CELLDATA, "corners", "Int32", 4, 1, nf, qfill_corners, &ctx},
        {VTU_CELLDATA, "scaled_jacobian", "Float64", 8, 1, nf, qfill_sj, &ctx},
        {VTU_CELLDATA, "origin", "Int32", 4, 1, nf, qfill_origin, &ctx},
        {VTU_POINTS, "Points", "Float64", 8, 3, nv, qfill_points, &ctx},
        {VTU_CELLS, "connectivity", "Int32", 4, 1, (size_t)q->face_start[q->nf], qfill_conn, &ctx},
        {VTU_CELLS, "offsets", "Int32", 4, 1, nf, qfill_offsets, &ctx},
        {VTU_CELLS, "types", "UInt8", 1, 1, nf, qfill_types, &ctx},
    };
    char comment[128];
    snprintf(comment, sizeof comment, "glpgp %s quad mesh", GLPGP_VERSION);
    glpgp_status st = vtu_write(f, comment, nv, nf, a, (int)(sizeof a / sizeof a[0]),
                                glpgp_io_have_zlib() ? GLPGP_VTU_DEFAULT_LEVEL : 0);
    free(val);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

glpgp_status glpgp_output_set_quads(glpgp_output_set *s, const glpgp_quadmesh *q, const char *path)
{
    if (!q || !path) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad writer: no mesh or path");
    int kind = quads_format(path);
    if (!kind)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "quad mesh output '%s': extension must be .obj, .vtk, .vtu, .msh or .ply", path);
    FILE *f;
    GLPGP_CHECK(glpgp_output_set_open(s, path, &f));
    glpgp_status st = GLPGP_OK;
    glpgp_cnum cn; /* '.' whatever the locale */
    glpgp_cnum_begin(&cn);
    if (kind == QF_OBJ) {
        write_obj(f, q);
    } else if (kind == QF_VTK) {
        write_vtk(f, q);
        st = write_vtk_valence(f, q);
    } else if (kind == QF_VTU) {
        st = write_vtu(f, q);
    } else if (kind == QF_PLY) {
        write_ply(f, q);
    } else {
        write_msh(f, q);
    }
    glpgp_cnum_end(&cn);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

glpgp_status glpgp_quads_write(const glpgp_quadmesh *q, const char *path)
{
    glpgp_output_set *s = NULL;
    GLPGP_CHECK(glpgp_output_set_create(&s));
    glpgp_status st = glpgp_output_set_quads(s, q, path);
    if (st == GLPGP_OK) st = glpgp_output_set_commit(s);
    glpgp_output_set_destroy(&s);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

/* ---- MSH reader: faces of the shared parser ------------------------------ */

glpgp_status glpgp_quads_read_msh(const char *path, glpgp_quadmesh **out)
{
    glpgp_status st = GLPGP_OK;
    msh_data d;
    int *used = NULL;
    glpgp_quadmesh *q = NULL;
    *out = NULL;
    GLPGP_CHECK(msh_read(path, &d));
    if (d.nf == 0) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no triangles or quadrangles", path);
        goto done;
    }
    /* renumber the used nodes in order of first use */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)d.nv, sizeof(int), &used), done);
    for (long i = 0; i < d.nv; i++) used[i] = -1;
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *q, &q), done);
    const long ncorner = 3 * d.ntri + 4 * d.nquad;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)d.nf + 1, sizeof(int), &q->face_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)ncorner, sizeof(int), &q->face_vert), done);
    int nv = 0, nc = 0;
    q->face_start[0] = 0;
    for (long f = 0; f < d.nf; f++) {
        const int *c = d.corner + 4 * f;
        for (int k = 0; k < 4 && c[k] >= 0; k++) {
            if (used[c[k]] < 0) used[c[k]] = nv++;
            q->face_vert[nc++] = used[c[k]];
        }
        q->face_start[f + 1] = nc;
    }
    q->nv = nv;
    q->nf = (int)d.nf;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &q->xy), done);
    for (long i = 0; i < d.nv; i++)
        if (used[i] >= 0) {
            q->xy[2 * used[i]] = d.xyz[3 * i];
            q->xy[2 * used[i] + 1] = d.xyz[3 * i + 1];
        }
    /* faces are kept in the file's orientation: the quality report takes
     * one orientation for the whole mesh (the sign of its total area), so a
     * folded face reads back as inverted */
    *out = q;
    q = NULL;
done:
    msh_free(&d);
    free(used);
    glpgp_quadmesh_destroy(&q);
    return st;
}
