/* result_io.h: reading a glpgp result back from the legacy VTK file that
 * glpgp_write_vtk writes (mesh + oscillators + field), for the commands that
 * post-process a finished solve (render, extract). */
#ifndef GLPGP_RESULT_IO_H
#define GLPGP_RESULT_IO_H

#include "solve.h"

/* Read path (ASCII legacy VTK from glpgp_write_vtk). On success *m is the
 * mesh (validated by glpgp_mesh_create) and *r a result with nv, nt, size
 * (from the header; 0 if absent), field (U, zeros if absent), osc[k].z,
 * dirichlet (if present), and singularities and |z| statistics recomputed
 * from z. A file without the z_u and z_v arrays -> GLPGP_ERR_FORMAT;
 * unreadable -> GLPGP_ERR_IO. */
glpgp_status glpgp_read_result_vtk(const char *path, glpgp_mesh **m, glpgp_result **r);

#endif
