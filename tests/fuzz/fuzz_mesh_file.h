/* fuzz_mesh_file.h: the body shared by the triangle-mesh reader harnesses
 * (fuzz_obj.c, fuzz_msh.c, fuzz_stl.c, fuzz_ply.c, fuzz_off.c): the input written as a file with
 * extension ext, read by glpgp_mesh_read (reader + glpgp_mesh_create's
 * validation). Properties: a failure returns no mesh and one error line; an
 * accepted mesh (planar, or a surface: glpgp/surface.h) has >= 3 vertices
 * and >= 1 triangle, finite coordinates, indices in range, and survives a
 * write / read round trip (as back_ext: STL, PLY and OFF are read only) with
 * the same counts. */
#ifndef GLPGP_FUZZ_MESH_FILE_H
#define GLPGP_FUZZ_MESH_FILE_H

#include "fuzz_common.h"

#include "glpgp/io.h"

#include <math.h>

static int fuzz_mesh_file(const char *ext, const char *back_ext, const uint8_t *data, size_t size)
{
    glpgp_error_clear();
    const char *path = fuzz_write_file(0, ext, data, size);
    glpgp_mesh *m = (glpgp_mesh *)&m; /* must be reset to NULL on failure */
    glpgp_status st = glpgp_mesh_read(path, &m);
    if (st != GLPGP_OK) {
        FUZZ_ASSERT(m == NULL);
        fuzz_check_error(st);
        return 0;
    }
    FUZZ_ASSERT(m && m->nv >= 3 && m->nt >= 1);
    FUZZ_ASSERT((m->xy != NULL) != (m->xyz != NULL) && (m->xyz != NULL) == (m->surf != NULL));
    for (int i = 0; i < (m->xyz ? 3 : 2) * m->nv; i++) FUZZ_ASSERT(isfinite(m->xyz ? m->xyz[i] : m->xy[i]));
    for (int k = 0; k < 3 * m->nt; k++) FUZZ_ASSERT(m->tri[k] >= 0 && m->tri[k] < m->nv);
    /* round trip */
    const char *back = fuzz_write_file(1, back_ext, NULL, 0);
    glpgp_mesh *m2 = NULL;
    FUZZ_ASSERT(glpgp_mesh_write(m, back) == GLPGP_OK);
    FUZZ_ASSERT(glpgp_mesh_read(back, &m2) == GLPGP_OK);
    FUZZ_ASSERT(m2->nv == m->nv && m2->nt == m->nt);
    glpgp_mesh_destroy(&m2);
    glpgp_mesh_destroy(&m);
    return 0;
}

#endif
