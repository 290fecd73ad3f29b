/* io/msh.h: the one Gmsh MSH 2.2 / 4.1 ASCII parser of the io layer, shared
 * by the triangle-mesh reader (glpgp_mesh_read) and the quad-mesh reader
 * (glpgp_quads_read_msh). Private to the io layer. */
#ifndef GLPGP_IO_MSH_H
#define GLPGP_IO_MSH_H

#include "glpgp/status.h"

typedef struct msh_data {
    long nv;      /* nodes, in file order */
    double *xyz;  /* 3 * nv */
    long nf;      /* triangles and quadrangles, in file order */
    int *corner;  /* 4 * nf node indices (0-based); corner[4f+3] = -1 for a triangle */
    long ntri, nquad;
    long nhigh;   /* of those, second- or higher-order elements (corners kept) */
} msh_data;

/* Parse path in one pass (works on pipes). Sections: $MeshFormat (first,
 * version 2.x or 4.1, ASCII), $Nodes and $Elements (each at most once, nodes
 * before elements), anything else skipped up to its $End line. Triangles and
 * quadrangles of any order are kept by their corners (higher-order ones
 * counted in nhigh); other element types are skipped. Node tags: any integer in [0, 2^63),
 * unique, looked up through a hash table. Counts are checked (overflow,
 * bytes left, GLPGP_IO_MAX_ITEMS) before anything is reserved for them.
 * Errors "PATH:LINE: ..." (GLPGP_ERR_FORMAT / _LIMIT / _IO / _NOMEM); on
 * failure *out is empty. */
glpgp_status msh_read(const char *path, msh_data *out);
void msh_free(msh_data *d);

#endif
