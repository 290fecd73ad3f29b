/* consumer/main.c: the tiny consumer of an installed glpgp: a built-in square
 * of about 600 vertices solved with the reference backend; checks that the
 * solve converged to a regular parametrization (no singularity, median |z|
 * near 1) and prints one line with the version it was built against.
 * Includes the umbrella header alone. */
#include <glpgp/glpgp.h> /* the umbrella header: the whole public API */

#include <stdio.h>

int main(void)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    int ok = glpgp_mesh_generate("square", 600, &m) == GLPGP_OK &&
             glpgp_backend_create_reference(&b) == GLPGP_OK && glpgp_solve(m, b, &o, &r) == GLPGP_OK;
    if (!ok) {
        fprintf(stderr, "consumer: %s\n", glpgp_error_message());
        return 1;
    }
    int bad = 0;
    for (int k = 0; k < 2; k++) {
        if (r->osc[k].plus || r->osc[k].minus) bad = 1;
        if (!(r->osc[k].zabs_median > 0.8 && r->osc[k].zabs_median < 1.2)) bad = 1;
    }
    printf("consumer: glpgp %s, %d vertices, median |z| %.4f %.4f, singularities %d %d, %s\n",
           GLPGP_VERSION, m->nv, r->osc[0].zabs_median, r->osc[1].zabs_median,
           r->osc[0].plus + r->osc[0].minus, r->osc[1].plus + r->osc[1].minus,
           bad ? "WRONG" : "ok");
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
    return bad;
}
