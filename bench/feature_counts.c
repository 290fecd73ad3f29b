/* bench/feature_counts.c: glpgp-features MESH...: per surface mesh one JSON
 * line with its triangles, the interior edges above the feature angle
 * (glpgp_surface_edges_above) and those of them that are creases
 * (glpgp_surface_features). GLPGP_FEATURE_ANGLE sets the angle (default
 * 35). Used by bench/surface_features.sh. */
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/surface.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    const char *env = getenv("GLPGP_FEATURE_ANGLE");
    const double deg = env ? atof(env) : GLPGP_FEATURE_ANGLE_DEFAULT;
    int rc = 0;
    for (int i = 1; i < argc; i++) {
        glpgp_mesh *m = NULL;
        unsigned char *fl = NULL;
        int n = 0;
        if (glpgp_mesh_read(argv[i], &m) != GLPGP_OK || !m->surf || !(fl = malloc((size_t)3 * m->nt)) ||
            glpgp_surface_features(m, deg, fl, &n) != GLPGP_OK) {
            fprintf(stderr, "glpgp-features: %s: %s\n", argv[i], glpgp_error_message());
            rc = 1;
        } else {
            printf("{\"model\": \"%s\", \"triangles\": %d, \"feature_angle\": %g, \"edges_above\": %d, "
                   "\"features\": %d}\n", argv[i], m->nt, deg, glpgp_surface_edges_above(m, deg), n);
        }
        free(fl);
        glpgp_mesh_destroy(&m);
    }
    return rc;
}
