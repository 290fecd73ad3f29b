/* bench/feature_counts.c: glpgp-features MESH...: per surface mesh one JSON
 * line with its triangles, the interior edges above the feature angle
 * (glpgp_surface_edges_above), those of them that are creases
 * (glpgp_surface_features), the root mean square angle defect (the Gauss
 * curvature the cross field integrates) and what --denoise auto makes of
 * it (glpgp_surface_denoise with the solve's cap of h / 10 taken as 10
 * mean edges: the noise edges before and after, the vertices moved, the
 * largest move in mean edges, the creases and the defect afterwards).
 * GLPGP_FEATURE_ANGLE sets the angle (default 35). Used by
 * bench/surface_features.sh. */
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/surface.h"

#include <stdio.h>
#include <stdlib.h>

static int one(const char *path, double deg)
{
    glpgp_mesh *m = NULL, *d = NULL;
    unsigned char *fl = NULL;
    glpgp_surface_denoise_info in;
    int n = 0, nd = 0, rc = 1;
    if (glpgp_mesh_read(path, &m) != GLPGP_OK || !m->surf || !(fl = malloc((size_t)3 * m->nt)) ||
        glpgp_surface_features(m, deg, fl, &n) != GLPGP_OK ||
        glpgp_surface_denoise(m, deg, 10.0 * m->mean_edge, &d, &in) != GLPGP_OK ||
        (d && glpgp_surface_features(d, deg, fl, &nd) != GLPGP_OK)) {
        fprintf(stderr, "glpgp-features: %s: %s\n", path, glpgp_error_message());
    } else {
        printf("{\"model\": \"%s\", \"triangles\": %d, \"feature_angle\": %g, \"edges_above\": %d, "
               "\"features\": %d, \"defect_rms\": %.6g, \"denoise\": {\"noise_edges\": %d, \"noise_edges_after\": "
               "%d, \"folds\": %d, \"folds_after\": %d, \"rounds\": %d, \"moved\": %d, \"max_move_edges\": %.4g, \"features\": %d, \"defect_rms\": %.6g}}\n",
               path, m->nt, deg, glpgp_surface_edges_above(m, deg), n, glpgp_surface_defect_rms(m), in.noise_edges,
               in.noise_edges_after, in.folds, in.folds_after, in.rounds, in.moved, in.max_move / m->mean_edge, d ? nd : n,
               glpgp_surface_defect_rms(d ? d : m));
        rc = 0;
    }
    free(fl);
    glpgp_mesh_destroy(&d);
    glpgp_mesh_destroy(&m);
    return rc;
}

int main(int argc, char **argv)
{
    const char *env = getenv("GLPGP_FEATURE_ANGLE");
    const double deg = env ? atof(env) : GLPGP_FEATURE_ANGLE_DEFAULT;
    int rc = 0;
    for (int i = 1; i < argc; i++) rc |= one(argv[i], deg);
    return rc;
}
