/* cli/cmd_generate.c: `glpgp generate SHAPE [--vertices N] -o FILE`: write a
 * built-in domain mesh as .obj or .msh. */
#include "commands.h"

#include "cli.h"
#include "opts.h"

#include "glpgp/io.h"
#include "glpgp/shapes.h"

#include <stdio.h>

int glpgp_cmd_generate(int argc, char **argv)
{
    static const char *const exts[] = {".obj", ".msh", NULL};
    int nverts = (int)GLPGP_SHAPE_DEFAULT_VERTICES, verbosity = 1;
    long max_elements = GLPGP_DEFAULT_MAX_ELEMENTS;
    const char *out = NULL, *shape = NULL;
    glpgp_opts t;
    glpgp_opts_init(&t, "generate", "glpgp generate SHAPE [--vertices N] -o FILE",
                    "Write a built-in domain meshed with about N vertices, deterministic and with\n"
                    "well-shaped triangles. SHAPE: square, disk, annulus, lshape (or shape:NAME).\n");
    glpgp_opt *o = glpgp_opt_int(&t, "--vertices", &nverts, GLPGP_SHAPE_MIN_VERTICES, GLPGP_SHAPE_MAX_VERTICES,
                                 "N", "approximate vertex count");
    o->alias = "-n";
    o = glpgp_opt_string(&t, "--out", &out, "FILE", "output mesh, .obj or .msh (Gmsh 4.1 ASCII)");
    o->alias = "-o";
    glpgp_opts_add_limits(&t, &max_elements, NULL);
    glpgp_opts_add_verbosity(&t, &verbosity);
    int rc = glpgp_opts_parse_input(&t, argc, argv, &shape, &verbosity, "SHAPE");
    if (rc >= 0) return rc;
    if (!out) return glpgp_cli_usage_error("generate", "missing -o FILE");
    char name[64];
    long n;
    if (glpgp_shape_parse(shape, 1, name, sizeof name, &n) != GLPGP_OK) {
        rc = glpgp_cli_usage_error("generate", "%s", glpgp_error_message());
        glpgp_error_clear();
        return rc;
    }
    if ((rc = glpgp_cli_check_output("generate", "--out", out, exts)) >= 0) return rc;
    /* about 2 triangles per vertex */
    if ((rc = glpgp_cli_check_elements(name, 2L * nverts, "triangles", 1, max_elements)) >= 0) return rc;
    glpgp_mesh *m = NULL;
    if (glpgp_mesh_generate(name, nverts, &m) != GLPGP_OK) return glpgp_cli_fail();
    rc = 0;
    if (glpgp_mesh_write(m, out) != GLPGP_OK)
        rc = glpgp_cli_fail();
    else if (verbosity > 0)
        printf("glpgp: %s: %d vertices, %d triangles -> %s\n", name, m->nv, m->nt, out);
    glpgp_mesh_destroy(&m);
    return rc;
}
