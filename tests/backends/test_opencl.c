/* test_opencl.c: the OpenCL backend against the reference backend through
 * the cross-check engine (glpgp_crosscheck_create, glpgp/backends.h), which
 * compares every op of the backend table (vectors, axpby with zero
 * coefficients on NaN, dot, QUAD of every element kind, NEWTON + DINV of
 * every Hessian variant and without penalty, gradient and energy with and
 * without penalty, spmv, each fused CG step, a CG solve, a Newton step, and
 * the multigrid ops on the hierarchy of NEWTON: A_l, smoother, restriction,
 * prolongation per level, coarsest matrix and solve, one cycle, a flexible-CG
 * solve; the hierarchy values bit-identical on p1) on random z and r: on a generated disk (3000 vertices, both launch shapes
 * GLPGP_CL_SHAPE=cpu|gpu, the whole GL solve too) and on data/annulus.msh
 * (transport energy) and data/plate_holes.msh (GLPGP_DATA, skipped if
 * missing). Every table row must pass and every stage must be present; the
 * engine must fail when GLPGP_CL_CORRUPT=1 corrupts the OpenCL QUAD. Also
 * device-selection errors and GLPGP_KERNEL_DIR (good and broken kernels, a
 * missing rows.h or amg_rows.h). Exit 77 ("skipped: no OpenCL device") when no OpenCL
 * device can be used; the engine then reports GLPGP_ERR_UNSUPPORTED or
 * GLPGP_ERR_OPENCL. */
#include "glpgp/backends.h"
#include "glpgp/mesh.h"
#include "glpgp/solve.h"
#include "glpgp/system.h"
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Stages every table must hold (names of glpgp/backends.h's engine). */
static const char *const required_stages[] = {
    "vector write/read", "copy, axpby 0.75 z - 1.5 r", "axpby zero coefficients (NaN)", "dot z.r",
    "dot z.r again (OpenCL, same bits)", "QUAD assembly", "QUAD assembly (laplace)",
    "NEWTON assembly (no penalty)", "NEWTON assembly (paper)", "NEWTON assembly (projected)",
    "NEWTON assembly (exact)", "NEWTON assembly (mixed)", "DINV (no penalty)", "DINV (paper)",
    "DINV (projected)", "DINV (exact)", "DINV (mixed)", "gradient g", "gradient: E = 1/2 x.QUAD x",
    "gradient: P (penalty)", "energy: E", "energy: P", "gradient g (no penalty)",
    "gradient: P = 0 (no penalty)", "energy: P = 0 (no penalty)", "spmv QUAD", "spmv NEWTON",
    "dot x.(NEWTON x)", "CG precond z", "CG precond r.z", "CG precond r.r", "CG spmv_dot q (3 steps)",
    "CG spmv_dot p.q (3 steps)", "CG update r.z (3 steps)", "CG update r.r (3 steps)",
    "CG update r (3 steps)", "CG update x (3 steps)", "CG direction p (3 steps)", "Newton step z + d",
    "multigrid levels (*", "multigrid A_0 x", "multigrid A_1 x", "multigrid smoother level 0",
    "multigrid restriction 0 -> 1", "multigrid prolongation 1 -> 0", "multigrid dots (5)",
    "multigrid axpby (coefficients)", "multigrid kcombine", "multigrid cycle B r", "multigrid coarsest A_*",
    "multigrid coarse solve C r", "FCG+multigrid solve (*"};

/* The row named `name` (or, when name ends in '*', the first starting with the rest). */
static const glpgp_crosscheck_row *find_row(const glpgp_crosscheck *t, const char *name)
{
    size_t n = strlen(name);
    int prefix = n > 0 && name[n - 1] == '*';
    for (int i = 0; i < t->nrows; i++)
        if (prefix ? strncmp(t->rows[i].stage, name, n - 1) == 0 : strcmp(t->rows[i].stage, name) == 0)
            return &t->rows[i];
    return NULL;
}

/* Run the engine on m; every row must pass and every stage be there. */
static void compare_mesh(const char *label, const glpgp_mesh *m, int energy, int solve)
{
    glpgp_crosscheck_options o;
    glpgp_crosscheck_options_default(&o);
    o.mesh = m;
    o.energy = energy;
    o.solve = solve;
    o.seed = 20240601;
    glpgp_crosscheck *t = NULL;
    CHECK_OK(glpgp_crosscheck_create(&o, &t));
    CHECK(t != NULL);
    if (!t) return;
    printf("%s: %d vertices, %ld blocks, %d rows; OpenCL %s\n", label, t->nv, t->nnzb, t->nrows, t->device);
    for (int i = 0; i < t->nrows; i++) {
        const glpgp_crosscheck_row *r = &t->rows[i];
        if (!r->pass)
            fprintf(stderr, "%s: %s FAILED: max abs diff %.3e, max rel diff %.3e, tolerance %s\n", label, r->stage,
                    r->max_abs, r->max_rel, r->tol);
        CHECK(r->pass);
    }
    for (size_t k = 0; k < sizeof required_stages / sizeof required_stages[0]; k++) {
        const glpgp_crosscheck_row *r = find_row(t, required_stages[k]);
        if (!r) fprintf(stderr, "%s: stage '%s' missing from the table\n", label, required_stages[k]);
        CHECK(r != NULL);
    }
    /* the CG solution, normwise: tighter than the engine's 1e-6 (both solve to 1e-10) */
    const glpgp_crosscheck_row *cg = find_row(t, "CG solve (*");
    CHECK(cg != NULL && cg->max_rel <= 1e-8);
    CHECK(!solve || (t->solved && find_row(t, "GL solve z_u*") && find_row(t, "GL singularities v")));
    /* rows whose arithmetic is shared verbatim (kernels/rows.h) are bit-identical;
     * the transport element calls cos/sin, whose last bit the OpenCL library and
     * libm may round differently, so with it only the other QUAD kinds are */
    static const char *const exact_p1[] = {"QUAD assembly", "NEWTON assembly (paper)", "DINV (mixed)",
                                           "gradient g", "spmv NEWTON", "CG precond z", "QUAD assembly (laplace)",
                                           /* the hierarchy (kernels/amg_rows.h) */
                                           "multigrid A_1 x", "multigrid smoother level 0",
                                           "multigrid restriction 0 -> 1", "multigrid prolongation 1 -> 0",
                                           "multigrid coarsest A_*", "multigrid coarse solve C r"};
    static const char *const exact_tr[] = {"QUAD assembly (p1)", "QUAD assembly (laplace)"};
    const int tr = energy == GLPGP_ELEM_TRANSPORT;
    const size_t nexact = tr ? sizeof exact_tr / sizeof exact_tr[0] : sizeof exact_p1 / sizeof exact_p1[0];
    for (size_t k = 0; k < nexact; k++) {
        const char *name = tr ? exact_tr[k] : exact_p1[k];
        const glpgp_crosscheck_row *r = find_row(t, name);
        if (r && r->max_abs != 0.0) fprintf(stderr, "%s: %s differs by %.3e\n", label, name, r->max_abs);
        CHECK(r && r->max_abs == 0.0);
    }
    CHECK(t->pass);
    glpgp_crosscheck_destroy(&t);
    CHECK(t == NULL);
}

/* The engine must be able to fail: a corrupted OpenCL QUAD fails "QUAD
 * assembly"; bad options are refused. */
static void test_engine_fails(const glpgp_mesh *m)
{
    glpgp_crosscheck_options o;
    glpgp_crosscheck *t = NULL;
    glpgp_crosscheck_options_default(&o);
    o.mesh = m;
    o.solve = 0;
    setenv("GLPGP_CL_CORRUPT", "1", 1);
    CHECK_OK(glpgp_crosscheck_create(&o, &t));
    unsetenv("GLPGP_CL_CORRUPT");
    if (t) {
        const glpgp_crosscheck_row *r = find_row(t, "QUAD assembly");
        CHECK(!t->pass && r && !r->pass && r->max_abs >= 0.5);
        glpgp_crosscheck_destroy(&t);
    }
    o.tol_scale = 0.0;
    CHECK(glpgp_crosscheck_create(&o, &t) == GLPGP_ERR_ARG && t == NULL);
    glpgp_error_clear();
    o.tol_scale = 1.0;
    o.mesh = NULL;
    CHECK(glpgp_crosscheck_create(&o, &t) == GLPGP_ERR_ARG && t == NULL);
    glpgp_error_clear();
    glpgp_crosscheck_destroy(&t); /* NULL-safe */
}

/* Write text to dir/name. */
static void write_file(const char *dir, const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static void remove_file(const char *dir, const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    unlink(path);
}

/* Device selection errors and GLPGP_KERNEL_DIR. */
static void test_device_errors(void)
{
    glpgp_backend *b = NULL;
    glpgp_cl_options o = {99, 0, NULL};
    CHECK(glpgp_backend_create_opencl(&o, &b) == GLPGP_ERR_ARG && b == NULL);
    CHECK(strstr(glpgp_error_message(), "no such OpenCL device") != NULL);
    glpgp_error_clear();
    o.device = -1;
    setenv("GLPGP_DEVICE", "abc", 1);
    CHECK(glpgp_backend_create_opencl(&o, &b) == GLPGP_ERR_ARG && b == NULL);
    glpgp_error_clear();
    setenv("GLPGP_DEVICE", "0", 1);
    CHECK_OK(glpgp_backend_create_opencl(&o, &b));
    glpgp_backend_destroy(&b);
    unsetenv("GLPGP_DEVICE");

    /* a broken kernel directory: the build log comes back in the message */
    char dir[] = "/tmp/glpgp_kdir_XXXXXX";
    if (mkdtemp(dir)) {
        write_file(dir, "element.h", "/* empty */\n");
        write_file(dir, "broken.cl",
                   "__kernel void glpgp_finalize(__global double *s) { s[0] = undefined_symbol_xyz; }\n");
        setenv("GLPGP_KERNEL_DIR", dir, 1);
        /* rows.h missing: an I/O error naming it */
        glpgp_status st = glpgp_backend_create_opencl(&o, &b);
        CHECK(st == GLPGP_ERR_IO && b == NULL);
        CHECK(strstr(glpgp_error_message(), "rows.h") != NULL);
        glpgp_error_clear();
        write_file(dir, "rows.h", "/* empty */\n");
        /* amg_rows.h missing: the same */
        st = glpgp_backend_create_opencl(&o, &b);
        CHECK(st == GLPGP_ERR_IO && b == NULL);
        CHECK(strstr(glpgp_error_message(), "amg_rows.h") != NULL);
        glpgp_error_clear();
        write_file(dir, "amg_rows.h", "/* empty */\n");
        /* coupled_rows.h missing: the same */
        st = glpgp_backend_create_opencl(&o, &b);
        CHECK(st == GLPGP_ERR_IO && b == NULL);
        CHECK(strstr(glpgp_error_message(), "coupled_rows.h") != NULL);
        glpgp_error_clear();
        write_file(dir, "coupled_rows.h", "/* empty */\n");
        /* newton_rows.h missing: the same */
        st = glpgp_backend_create_opencl(&o, &b);
        CHECK(st == GLPGP_ERR_IO && b == NULL);
        CHECK(strstr(glpgp_error_message(), "newton_rows.h") != NULL);
        glpgp_error_clear();
        write_file(dir, "newton_rows.h", "/* empty */\n");
        /* amg_dense.h missing: the same */
        st = glpgp_backend_create_opencl(&o, &b);
        CHECK(st == GLPGP_ERR_IO && b == NULL);
        CHECK(strstr(glpgp_error_message(), "amg_dense.h") != NULL);
        glpgp_error_clear();
        write_file(dir, "amg_dense.h", "/* empty */\n");
        st = glpgp_backend_create_opencl(&o, &b);
        CHECK(st == GLPGP_ERR_OPENCL && b == NULL);
        CHECK(strstr(glpgp_error_message(), "build log") != NULL);
        CHECK(strstr(glpgp_error_detail(), "undefined_symbol_xyz") != NULL);
        glpgp_error_clear();
        unsetenv("GLPGP_KERNEL_DIR");
        remove_file(dir, "broken.cl");
        remove_file(dir, "element.h");
        remove_file(dir, "coupled_rows.h");
        remove_file(dir, "rows.h");
        remove_file(dir, "amg_rows.h");
        remove_file(dir, "newton_rows.h");
        remove_file(dir, "amg_dense.h");
        rmdir(dir);
    }
    /* the source kernel directory (next to GLPGP_DATA) builds */
    const char *data = getenv("GLPGP_DATA");
    if (data) {
        char kdir[1024];
        struct stat sb;
        snprintf(kdir, sizeof kdir, "%s/../kernels", data);
        if (stat(kdir, &sb) == 0) {
            setenv("GLPGP_KERNEL_DIR", kdir, 1);
            CHECK_OK(glpgp_backend_create_opencl(&o, &b));
            glpgp_backend_destroy(&b);
            unsetenv("GLPGP_KERNEL_DIR");
        }
    }
}

int main(void)
{
    glpgp_backend *b = NULL;
    glpgp_cl_options o = {-1, 0, NULL};
    if (!glpgp_have_opencl() || glpgp_backend_create_opencl(&o, &b) != GLPGP_OK) {
        /* the engine reports the same: no OpenCL -> UNSUPPORTED / OPENCL, no rows */
        char why[512];
        snprintf(why, sizeof why, "%s", glpgp_have_opencl() ? glpgp_error_message() : "built without OpenCL");
        glpgp_error_clear();
        glpgp_mesh *m = NULL;
        glpgp_crosscheck *t = NULL;
        glpgp_crosscheck_options co;
        glpgp_crosscheck_options_default(&co);
        CHECK_OK(glpgp_mesh_generate("disk", 200, &m));
        co.mesh = m;
        glpgp_status st = glpgp_crosscheck_create(&co, &t);
        CHECK(st == GLPGP_ERR_UNSUPPORTED || st == GLPGP_ERR_OPENCL);
        CHECK(t == NULL || (t->nrows == 0 && !t->pass));
        glpgp_crosscheck_destroy(&t);
        glpgp_mesh_destroy(&m);
        glpgp_error_clear();
        if (tu_failures) TEST_DONE();
        printf("skipped: no OpenCL device (%s)\n", why);
        return 77;
    }
    glpgp_backend_destroy(&b);

    test_device_errors();

    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 3000, &m));
    if (m) {
        compare_mesh("disk:3000", m, GLPGP_ELEM_P1, 1);
        /* the other launch shape on the same device */
        const char *cur = getenv("GLPGP_CL_SHAPE");
        char saved[16] = "";
        if (cur) snprintf(saved, sizeof saved, "%s", cur);
        setenv("GLPGP_CL_SHAPE", cur && !strcmp(cur, "gpu") ? "cpu" : "gpu", 1);
        compare_mesh("disk:3000 (other launch shape)", m, GLPGP_ELEM_P1, 0);
        if (saved[0]) setenv("GLPGP_CL_SHAPE", saved, 1);
        else unsetenv("GLPGP_CL_SHAPE");
        glpgp_mesh_destroy(&m);
    }
    CHECK_OK(glpgp_mesh_generate("disk", 300, &m));
    if (m) test_engine_fails(m);
    glpgp_mesh_destroy(&m);

    const char *data = getenv("GLPGP_DATA");
    static const struct {
        const char *file;
        int energy;
    } files[] = {{"annulus.msh", GLPGP_ELEM_TRANSPORT}, {"plate_holes.msh", GLPGP_ELEM_P1}};
    for (int i = 0; i < 2; i++) {
        char path[1024];
        if (!data) break;
        snprintf(path, sizeof path, "%s/%s", data, files[i].file);
        if (access(path, R_OK) != 0) {
            printf("%s: missing, skipped\n", path);
            continue;
        }
        CHECK_OK(glpgp_mesh_read(path, &m));
        if (m) compare_mesh(files[i].file, m, files[i].energy, 0);
        glpgp_mesh_destroy(&m);
    }
    TEST_DONE();
}
