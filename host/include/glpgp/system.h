/* glpgp/system.h: the 2x2-block CSR layout of a mesh's vertex adjacency and the
 * atomic-free, deterministic assembly maps shared by every backend:
 *  - block CSR: row i lists its neighbours j (sorted, diagonal included);
 *    each block holds 4 doubles, row-major [[a00,a01],[a10,a11]];
 *  - slot map (gather form): for block slot k, the element entries that sum
 *    into it are contrib[cptr[k] .. cptr[k+1]), each encoded as t*9 + a*3 + b
 *    (triangle t, local row a, local column b), in increasing t, so every
 *    backend adds them in the same order;
 *  - vertex -> triangle map: vtri[vptr[i] .. vptr[i+1]) = t*3 + a (corner a
 *    of triangle t is vertex i), for per-vertex gradient gathers. Layer: mesh. */
#ifndef GLPGP_SYSTEM_H
#define GLPGP_SYSTEM_H

#include "glpgp/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct glpgp_system {
    int nv, nt;
    long nnzb;     /* number of 2x2 blocks */
    int *rowptr;   /* nv + 1 */
    int *col;      /* nnzb */
    int *diag;     /* nv: block index of (i,i) */
    int *cptr;     /* nnzb + 1 */
    int *contrib;  /* 9 * nt */
    int *vptr;     /* nv + 1 */
    int *vtri;     /* 3 * nt */
    const glpgp_mesh *mesh; /* borrowed, must outlive the system */
    /* Matching of the coupled cross-field solve (solver/coupled.c, NULL for
     * every other system; owned, freed by glpgp_system_destroy): per corner
     * (t, a) of the mesh's triangles, cconj[3t+a] = 1 when the node's values
     * enter triangle t's frame conjugated (real transform diag(1, -1)) and
     * cfield[2(3t+a) .. +1] the unit field of the frame at that corner; the
     * backends then assemble with kernels/coupled_rows.h. */
    unsigned char *cconj; /* 3 * nt or NULL */
    double *cfield;       /* 6 * nt or NULL */
    /* A surface's system (solver/surface_solve.c; NULL otherwise, owned like
     * cconj): ctxy[6t + 2a] the corner a of triangle t in the triangle's own
     * plane (replacing the mesh's xy), crot[2(3t+a)] a unit complex that
     * turns the node's (conjugated) value into the triangle's frame
     * (kernels/coupled_rows.h); both only with cconj set. */
    double *ctxy;         /* 6 * nt or NULL */
    double *crot;         /* 6 * nt or NULL */
} glpgp_system;

/* Build the layout and maps for mesh m (borrowed). */
glpgp_status glpgp_system_create(const glpgp_mesh *m, glpgp_system **out);
void glpgp_system_destroy(glpgp_system **s);

#ifdef __cplusplus
}
#endif

#endif
