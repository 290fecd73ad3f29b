/* examples/c/solve_quads.c: read a mesh, solve, extract and write the quad mesh. */
#include <glpgp/backends.h>
#include <glpgp/io.h>
#include <glpgp/quads.h>
#include <glpgp/solve.h>
#include <stdio.h>

static glpgp_status run(const char *in, const char *out)
{
    glpgp_mesh *m = NULL; glpgp_backend *b = NULL; glpgp_result *r = NULL;
    glpgp_quadmesh *q = NULL; glpgp_quads_report qq; glpgp_options o; glpgp_status st;
    double h = 0;
    glpgp_options_default(&o);                                  /* the CLI's defaults */
    GLPGP_CHECK_GOTO(st, glpgp_mesh_read(in, &m), done);        /* .obj .msh .stl */
    GLPGP_CHECK_GOTO(st, glpgp_backend_select(GLPGP_BACKEND_AUTO, -1, 0, &b), done);
    GLPGP_CHECK_GOTO(st, glpgp_solve(m, b, &o, &r), done);
    h = r->size;                                                /* the h of the solve */
    GLPGP_CHECK_GOTO(st, glpgp_quads_build(m, r, NULL, &q, &h), done);
    GLPGP_CHECK_GOTO(st, glpgp_quads_quality(q, m, h, &qq), done);
    printf("%d quads, %d irregular, %s\n", qq.quads, qq.irregular, qq.invalid ? "INVALID" : "valid");
    GLPGP_CHECK_GOTO(st, glpgp_quads_write(q, out), done);      /* .obj .vtk .vtu .msh */
done:
    glpgp_quadmesh_destroy(&q); glpgp_result_destroy(&r);
    glpgp_backend_destroy(&b); glpgp_mesh_destroy(&m);
    return st;
}

int main(int argc, char **argv)
{
    if (argc != 3) { fprintf(stderr, "usage: solve_quads IN OUT\n"); return 2; }
    if (run(argv[1], argv[2]) == GLPGP_OK) return 0;
    fprintf(stderr, "solve_quads: %s\n", glpgp_error_message());   /* one line */
    return 1;
}
