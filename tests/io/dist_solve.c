/* dist_solve.c: the distributed solve as a library call
 * (glpgp_solve_distributed, glpgp/distributed.h), run by
 * tests/cli/cli_dist_lib.sh under mpirun -n 2 (and alone: one rank). Rank 0
 * builds a disk, every rank calls the entry points; rank 0 then checks
 *  - the gathered result: one value per input vertex, in the input's order
 *    (the field at each vertex equals the radial field there: unit vector
 *    along the vertex's position), regular (median |z| near 1);
 *  - the .pvtu of DIR/d.pvtu and every rank's piece exist after the commit,
 *    none before it;
 * and a second run with rank 0's mesh missing (NULL) fails on every rank
 * with no rank waiting. Usage: dist_solve DIR (the same on every rank).
 * Exit 77 without PETSc. */
#include "glpgp/backends.h"
#include "glpgp/distributed.h"
#include "glpgp/shapes.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static int g_fail;
#define EXPECT(c)                                                                 \
    do {                                                                          \
        if (!(c)) {                                                               \
            fprintf(stderr, "%s:%d: rank %d: failed: %s\n", __FILE__, __LINE__,   \
                    glpgp_petsc_rank(), #c);                                      \
            g_fail = 1;                                                           \
        }                                                                         \
    } while (0)

static int run(const char *dir, int give_mesh)
{
    const int root = glpgp_petsc_rank() == 0;
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_RADIAL;
    o.precond = GLPGP_PRECOND_JACOBI;
    o.newton_max = 8;
    char pvtu[512];
    snprintf(pvtu, sizeof pvtu, "%s/d%d.pvtu", dir, give_mesh);
    glpgp_dist_options dopt = {1, 1 << 24, pvtu};
    glpgp_dist *d = NULL;
    glpgp_mesh *m = NULL;
    glpgp_output_set *outs = NULL;
    glpgp_result *r = NULL;
    int finished = 0;
    glpgp_status st = glpgp_dist_create(&o, &dopt, &d);
    if (st == GLPGP_OK && glpgp_dist_reads(d) && give_mesh) st = glpgp_mesh_generate("disk", 3000, &m);
    if (st == GLPGP_OK) st = glpgp_output_set_create(&outs);
    if (st == GLPGP_OK) st = glpgp_solve_distributed(d, m, &o, outs, &r, &finished);
    if (st == GLPGP_OK && !finished) {
        char piece[600];
        EXPECT(glpgp_pvtu_piece_path(pvtu, 0, piece, sizeof piece) == GLPGP_OK && access(piece, F_OK) != 0);
        st = glpgp_dist_commit(d, outs);
        EXPECT(st == GLPGP_OK && access(pvtu, F_OK) == 0);
        for (int q = 0; q < glpgp_petsc_size(); q++) {
            EXPECT(glpgp_pvtu_piece_path(pvtu, q, piece, sizeof piece) == GLPGP_OK);
            EXPECT(access(piece, F_OK) == 0);
        }
    }
    if (st == GLPGP_OK && root) {
        EXPECT(r && r->nv == m->nv);
        double worst = 0.0;
        for (int i = 0; r && i < m->nv; i++) { /* radial: u = x / |x| at every vertex off the center */
            const double x = m->xy[2 * i], y = m->xy[2 * i + 1], n = hypot(x, y);
            if (n > 0.2) worst = fmax(worst, hypot(r->field[2 * i] - x / n, r->field[2 * i + 1] - y / n));
        }
        printf("ranks %d: %d vertices gathered, field off the radial by %.2g, median |z| %.3f %.3f\n",
               glpgp_petsc_size(), r ? r->nv : 0, worst, r ? r->osc[0].zabs_median : 0, r ? r->osc[1].zabs_median : 0);
        EXPECT(worst < 1e-6);
        EXPECT(r && r->osc[0].zabs_median > 0.8 && r->osc[1].zabs_median > 0.8);
    }
    if (st != GLPGP_OK && give_mesh) fprintf(stderr, "rank %d: %s\n", glpgp_petsc_rank(), glpgp_error_message());
    glpgp_error_clear();
    glpgp_dist_destroy(&d); /* after a failure: the verdicts this rank owes */
    glpgp_output_set_destroy(&outs);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    return st == GLPGP_OK;
}

int main(int argc, char **argv)
{
    if (argc < 2) return 2;
    if (!glpgp_have_petsc()) {
        printf("SKIPPED: built without PETSc\n");
        return 77;
    }
    if (glpgp_petsc_init() != GLPGP_OK) {
        fprintf(stderr, "%s\n", glpgp_error_message());
        return 1;
    }
    EXPECT(run(argv[1], 1));
    EXPECT(!run(argv[1], 0)); /* rank 0 has no mesh: every rank fails, none waits */
    char p[512];
    snprintf(p, sizeof p, "%s/d0.pvtu", argv[1]);
    EXPECT(access(p, F_OK) != 0);
    const int ok = glpgp_petsc_all_ok(!g_fail);
    glpgp_petsc_finalize();
    return ok ? 0 : 1;
}
