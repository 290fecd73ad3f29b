/* cli/cmd_opencl.c: the OpenCL commands of the CLI:
 *   glpgp devices      list every OpenCL platform and device (the global device
 *                      index used by --device and GLPGP_DEVICE);
 *   glpgp crosscheck   run the reference and the OpenCL backend on the same mesh
 *                      and compare them stage by stage through the cross-check
 *                      engine of the backends layer (glpgp_crosscheck_create),
 *                      print its table and exit 1 if any stage is out of
 *                      tolerance. */
#include "commands.h"

#include "cli.h"
#include "opts.h"

#include "glpgp/backends.h"
#include "glpgp/solve.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- glpgp devices ------------------------------------------------------- */

int glpgp_cmd_devices(int argc, char **argv)
{
    int verbosity = 1;
    glpgp_opts t;
    glpgp_opts_init(&t, "devices", "glpgp devices",
                    "List the OpenCL platforms and devices: global index (for --device N and the\n"
                    "GLPGP_DEVICE environment variable), name, vendor, version, compute units,\n"
                    "global memory, double precision support and type; \"(default)\" marks the\n"
                    "device used without --device or GLPGP_DEVICE (the first GPU with double\n"
                    "precision, else the first device with it). Exit 1 if no platform.\n");
    glpgp_opts_add_verbosity(&t, &verbosity);
    const char *none = NULL;
    int npos = 0;
    int rc = glpgp_opts_parse(&t, argc, argv, &none, 0, &npos);
    if (rc >= 0) return rc;
    glpgp_device_info *devs = NULL;
    int n = 0;
    if (glpgp_devices_list(&devs, &n) != GLPGP_OK) return glpgp_cli_fail();
    int last_plat = -1;
    if (n == 0) printf("OpenCL platforms found, but no devices\n");
    for (int i = 0; i < n; i++) {
        const glpgp_device_info *d = &devs[i];
        if (d->platform_index != last_plat) {
            last_plat = d->platform_index;
            printf("platform %d: %s | %s | %s\n", last_plat, d->platform, d->platform_vendor,
                   d->platform_version);
        }
        printf("  device %d: %s%s\n", i, d->name, d->is_default ? " (default)" : "");
        printf("      vendor %s | %s | %u compute units | %.2f GiB global memory | fp64 %s | %s\n",
               d->vendor, d->version, d->compute_units,
               (double)d->global_mem / (1024.0 * 1024.0 * 1024.0), d->fp64 ? "yes" : "no", d->type);
    }
    free(devs);
    return 0;
}

/* ---- glpgp crosscheck ---------------------------------------------------- */

/* What the engine compared (the lines it got to), then the table. */
static void cc_print(const char *input, const glpgp_crosscheck *t)
{
    if (t->device[0]) {
        printf("glpgp crosscheck: %s: %d vertices, %d triangles, %ld blocks, h = %.6g, energy %s\n", input, t->nv,
               t->nt, t->nnzb, t->h, t->energy == GLPGP_ELEM_TRANSPORT ? "transport" : "p1");
        printf("OpenCL %s\n\n", t->device);
    }
    if (t->eps > 0.0)
        printf("field: boundary (%ld CG iterations), %d Dirichlet vertices; eps = %.4g\n\n", t->field_cg,
               t->ndirichlet, t->eps);
    if (t->solved)
        printf("GL solve: OpenCL %.2f s, reference %.2f s (CG iterations %ld+%ld vs %ld+%ld)\n\n",
               t->solve_seconds[0], t->solve_seconds[1], t->solve_cg[0][0], t->solve_cg[0][1], t->solve_cg[1][0],
               t->solve_cg[1][1]);
    if (t->nrows == 0) return;
    printf("%-34s | %-12s | %-12s | %-30s | %s\n", "stage", "max abs diff", "max rel diff", "tolerance",
           "result");
    printf("-----------------------------------+--------------+--------------+--------------------------------+-------\n");
    for (int i = 0; i < t->nrows; i++) {
        const glpgp_crosscheck_row *r = &t->rows[i];
        printf("%-34s | %12.3e | %12.3e | %-30s | %s\n", r->stage, r->max_abs, r->max_rel, r->tol,
               r->pass ? "PASS" : "FAIL");
    }
}

int glpgp_cmd_crosscheck(int argc, char **argv)
{
    static const char *const energies[] = {"p1", "transport", NULL};
    static const int energy_vals[] = {GLPGP_ELEM_P1, GLPGP_ELEM_TRANSPORT};
    static const char *const preconds[] = {"jacobi", "amg", NULL};
    static const int precond_vals[] = {GLPGP_PRECOND_JACOBI, GLPGP_PRECOND_AMG};
    glpgp_crosscheck_options co;
    glpgp_crosscheck_options_default(&co);
    const char *input = NULL;
    int no_solve = 0, verbosity = 1;
    glpgp_opts t;
    glpgp_opts_init(&t, "crosscheck", "glpgp crosscheck INPUT [options]",
                    "Compare the OpenCL backend with the reference backend on one mesh (a .obj/.msh\n"
                    "file or shape:NAME[:N]), stage by stage, and print a table; exit 1 if any\n"
                    "stage exceeds its tolerance.\n");
    glpgp_opt *o = glpgp_opt_double(&t, "--size", &co.size, 0.0, 1, HUGE_VAL, 0, "H", "target quad size");
    o->def = "bounding-box diagonal / 20";
    glpgp_opt_choice(&t, "--energy", &co.energy, energies, energy_vals, "discretisation of the quadratic energy");
    o = glpgp_opt_int(&t, "--device", &co.device, 0, INT_MAX, "N", "OpenCL device index as listed by 'glpgp devices'");
    o->def = "$GLPGP_DEVICE, else the first fp64 GPU, else the first fp64 device";
    glpgp_opt_double(&t, "--tol-scale", &co.tol_scale, 0.0, 1, HUGE_VAL, 0, "F", "multiply every tolerance by F");
    glpgp_opt_flag(&t, "--no-solve", &no_solve, 1, "skip the whole GL solve stage");
    glpgp_opt_choice(&t, "--precond", &co.precond, preconds, precond_vals,
                     "preconditioner of the whole GL solve stage (the multigrid ops are\n"
                     "compared stage by stage either way)");
    glpgp_mask_options mo;
    glpgp_mask_options_default(&mo);
    glpgp_opts_add_limits(&t, &mo.max_triangles, &mo.max_pixels);
    glpgp_opts_add_verbosity(&t, &verbosity);
    t.epilog = "Tolerances (|a-b| <= atol + rtol |b|): assembly, gradient, spmv, dot rtol 1e-12;\n"
               "CG, Newton step and GL solve rtol 1e-6 on z (1e-4 for an oscillator whose GL\n"
               "levels stopped at the Newton cap: unconverged vortex drift amplifies rounding).\n"
               "The environment variable GLPGP_CL_CORRUPT=1 corrupts the OpenCL QUAD assembly\n"
               "(the check must fail).\n";
    int rc = glpgp_opts_parse_input(&t, argc, argv, &input, &verbosity, "INPUT (a .obj/.msh file or shape:NAME[:N])");
    if (rc >= 0) return rc;
    co.solve = !no_solve;
    glpgp_mesh *m = NULL;
    if ((rc = glpgp_cli_load_input("crosscheck", input, &mo, &m, NULL)) >= 0) return rc;
    co.mesh = m;
    glpgp_crosscheck *tab = NULL;
    glpgp_status st = glpgp_crosscheck_create(&co, &tab);
    if (tab) cc_print(input, tab);
    const int pass = tab && tab->pass;
    glpgp_crosscheck_destroy(&tab);
    glpgp_mesh_destroy(&m);
    if (st != GLPGP_OK) return glpgp_cli_fail();
    printf("\ncrosscheck: %s\n", pass ? "all stages PASS" : "FAILED");
    return pass ? 0 : 1;
}
