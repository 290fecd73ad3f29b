/* quads/soup.h: the growable polygon soup the closing works on (soup.c):
 * faces with their origins, edits in place (deleted faces have no corners),
 * its face adjacency, and the conversions from and to a quad mesh. Shared
 * by close.c (the strips) and smooth.c (the smoothing). Internal. */
#ifndef GLPGP_QUADS_SOUP_H
#define GLPGP_QUADS_SOUP_H

#include "glpgp/internal/vec.h"
#include "glpgp/quads.h"

typedef struct psoup {
    int nv, cap_v;
    double *xy;
    int nf, cap_f;
    int *fs, *fn; /* face start in fv, corner count; fn = 0: deleted */
    int nfv, cap_fv;
    int *fv;
    unsigned char *fo;  /* per face: origin (GLPGP_QFACE_*) */
    unsigned char cur;  /* origin given to the faces soup_face adds */
} psoup;

/* Origin of a face made from face f by the closing (at least "strips"). */
unsigned char glpgp_soup_closed_origin(const psoup *s, int f);
glpgp_status glpgp_soup_vertex(psoup *s, double x, double y, int *id);
/* Append a face (n corners v[], origin s->cur); *id (may be NULL) receives its index. */
glpgp_status glpgp_soup_face(psoup *s, const int *v, int n, int *id);
void glpgp_soup_free(psoup *s);
/* The soup of q (the same vertices and corner slots: slot fs[f] + i is
 * q->face_vert[q->face_start[f] + i]). */
glpgp_status glpgp_soup_from_mesh(const glpgp_quadmesh *q, psoup *s);
/* The live faces of s as a new quad mesh (unused vertices dropped; *omark:
 * mark[] of the kept vertices); the extraction diagnostics from ref. */
glpgp_status glpgp_soup_to_mesh(const psoup *s, const glpgp_quadmesh *ref, const unsigned char *mark,
                                unsigned char **omark, glpgp_quadmesh **out);

typedef struct hedge {
    int a, b, f, i; /* key (min, max), face, local edge index */
} hedge;

typedef struct adjacency {
    int *adj, *adji, *val;
    int nv;  /* vertices when built (val, bnd cover 0 .. nv) */
    int *sf; /* face of each corner slot fs[f] + i */
    unsigned char *bnd;
} adjacency;

void glpgp_adj_free(adjacency *A);
/* Edge adjacency of the soup's live faces: per corner slot the face and
 * side across (-1 boundary, -2 non-manifold), valences, boundary vertices. */
glpgp_status glpgp_adj_build(const psoup *s, adjacency *A);

#endif
