/* cli/cmd_render_quads.c: `glpgp render QUADS.obj|QUADS.msh -o OUT.png
 * [--domain MESH] [--sj-below S]`, the quad-mesh branch of glpgp render
 * (cmd_image.c parses the command line and calls it): the picture of
 * glpgp_render_quadmesh (a 3D surface's OBJ: glpgp_render3d_quadmesh, from
 * --view) and one line of counts. */
#include "commands.h"

#include "cli.h"

#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/quads.h"

#include <math.h>
#include <stdio.h>

int glpgp_cli_render_quads(const char *in, const char *out, const char *domain, double sj_below,
                           const glpgp_render_options *ro, long max_elements, int verbosity)
{
    glpgp_quadmesh *q = NULL;
    glpgp_mesh *dm = NULL;
    glpgp_image *im = NULL;
    int rc = -1;
    if (glpgp_quads_read(in, &q) != GLPGP_OK) rc = glpgp_cli_fail();
    if (rc < 0) rc = glpgp_cli_check_elements(in, q->nf, "faces", 0, max_elements);
    if (rc < 0 && domain && glpgp_mesh_read(domain, &dm) != GLPGP_OK) rc = glpgp_cli_fail();
    if (rc < 0 && dm) rc = glpgp_cli_check_elements(domain, dm->nt, "triangles", 0, max_elements);
    if (rc < 0 && (q->xyz ? glpgp_render3d_quadmesh(q, ro, sj_below, 1, &im)
                          : glpgp_render_quadmesh(q, dm, ro, sj_below, 1, &im)) != GLPGP_OK)
        rc = glpgp_cli_fail();
    if (rc < 0 && glpgp_image_write(out, im) != GLPGP_OK)
        rc = glpgp_cli_fail();
    if (rc < 0) {
        rc = 0;
        if (verbosity > 0) {
            int n[GLPGP_QFACE_KINDS] = {0}, quads = 0, low = 0;
            double sjmin = INFINITY;
            for (int f = 0; f < q->nf; f++) {
                if (q->face_start[f + 1] - q->face_start[f] != 4) continue;
                double sj = q->xyz ? glpgp_quadmesh_face_sj_surface(q, f) : glpgp_quadmesh_face_sj(q, f);
                quads++;
                low += sj < sj_below;
                sjmin = fmin(sjmin, sj);
                n[q->face_origin ? q->face_origin[f] % GLPGP_QFACE_KINDS : 0]++;
            }
            printf("glpgp: %s: %d x %d picture -> %s (%d faces, %d quads: grid %d, strips %d, repair %d, "
                   "fallback %d; smallest scaled Jacobian %.3f, %d below %g)\n",
                   in, im->w, im->h, out, q->nf, quads, n[0], n[1], n[2], n[3], quads ? sjmin : 0.0, low, sj_below);
        }
    }
    glpgp_image_destroy(&im);
    glpgp_mesh_destroy(&dm);
    glpgp_quadmesh_destroy(&q);
    return rc;
}
