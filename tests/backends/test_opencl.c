/* test_opencl.c: the OpenCL backend against the reference backend, op by op:
 * vectors (write/read, copy, axpby, dot), QUAD assembly of every element kind,
 * NEWTON assembly + DINV of every Hessian variant (matrices read back exactly
 * with glpgp_probe_matrix), gradient, energy, spmv, each fused CG step, and
 * glpgp_cg; on a generated disk (3000 vertices, both launch shapes) and on
 * data/annulus.msh and data/plate_holes.msh (GLPGP_DATA, skipped if missing).
 * Also device-selection errors and GLPGP_KERNEL_DIR (good and broken kernels).
 * Tolerances: |a-b| <= atol + rtol|b|, rtol 1e-12 and atol 1e-14 max|b| for
 * assembly / gradient / spmv / dot (scalars: 1e-12 of their absolute sum);
 * the CG solution within 1e-8 (normwise relative) of the reference.
 * Exit 77 ("skipped: no OpenCL device") when no OpenCL device can be used. */
#include "glpgp/backends.h"
#include "glpgp/backends.h"
#include "element.h"
#include "glpgp/mesh.h"
#include "glpgp/solve.h"
#include "glpgp/system.h"
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Entrywise combined check; prints the worst entry on failure. */
static void cmp(const char *what, const char *mesh, const double *a, const double *b, size_t n, double rtol,
                double afac)
{
    double maxb = 0.0, maxd = 0.0;
    size_t bad = 0, worst = 0;
    for (size_t i = 0; i < n; i++) maxb = fmax(maxb, fabs(b[i]));
    double atol = afac * maxb;
    for (size_t i = 0; i < n; i++) {
        double d = fabs(a[i] - b[i]);
        if (!(d <= atol + rtol * fabs(b[i]))) {
            if (!bad) worst = i;
            bad++;
        }
        if (!(d <= maxd)) maxd = d;
    }
    if (bad) {
        fprintf(stderr, "%s: %s: %zu of %zu entries out of tolerance (max abs diff %.3e, max|ref| %.3e; "
                        "entry %zu: %.17g vs %.17g)\n",
                mesh, what, bad, n, maxd, maxb, worst, a[worst], b[worst]);
        tu_failures++;
    }
}

/* Scalar check with an explicit scale for atol. */
static void cmp1(const char *what, const char *mesh, double a, double b, double scale)
{
    if (!(fabs(a - b) <= 1e-12 * scale + 1e-12 * fabs(b))) {
        fprintf(stderr, "%s: %s: %.17g vs %.17g (scale %.3e)\n", mesh, what, a, b, scale);
        tu_failures++;
    }
}

typedef struct side {
    glpgp_backend *b;
    glpgp_vec *v[6];
} side;

static int compare_mesh(const char *label, const glpgp_mesh *m)
{
    glpgp_system *sys = NULL;
    side S[2]; /* 0: OpenCL, 1: reference */
    memset(S, 0, sizeof S);
    const int nv = m->nv;
    CHECK_OK(glpgp_system_create(m, &sys));
    if (!sys) return 1;
    const size_t n2 = (size_t)2 * nv, nm = (size_t)4 * sys->nnzb;
    glpgp_cl_options clo = {-1, 0};
    CHECK_OK(glpgp_backend_create_opencl(&clo, &S[0].b));
    CHECK_OK(glpgp_backend_create_reference(&S[1].b));
    if (!S[0].b || !S[1].b) return 1;
    char info[512];
    glpgp_cl_backend_info(S[0].b, info, sizeof info);
    printf("%s: %d vertices, %ld blocks; OpenCL %s\n", label, nv, sys->nnzb, info);
    for (int s = 0; s < 2; s++) {
        CHECK_OK(S[s].b->ops->setup(S[s].b, sys));
        for (int k = 0; k < 6; k++) CHECK_OK(S[s].b->ops->vec_create(S[s].b, n2, &S[s].v[k]));
    }
    double *w = malloc(n2 * sizeof *w), *z = malloc(n2 * sizeof *z), *r = malloc(n2 * sizeof *r);
    double *h[2], *M[2], sc[2][GLPGP_NSLOTS];
    for (int s = 0; s < 2; s++) {
        h[s] = malloc((nm > n2 ? nm : n2) * sizeof(double));
        M[s] = malloc(nm * sizeof(double));
    }
    unsigned char *dir = malloc((size_t)nv);
    /* smooth-ish unit field, random z around |z| = 1, random r */
    for (int i = 0; i < nv; i++) {
        double x = m->xy[2 * i], y = m->xy[2 * i + 1], a = 1.3 * x - 0.7 * y * y + 0.2 * tu_rand();
        w[2 * i] = cos(a);
        w[2 * i + 1] = sin(a);
        double rad = 0.2 + tu_rand(), ph = 2.0 * GLPGP_PI * tu_rand();
        z[2 * i] = rad * cos(ph);
        z[2 * i + 1] = rad * sin(ph);
        r[2 * i] = tu_rand() - 0.5;
        r[2 * i + 1] = tu_rand() - 0.5;
        dir[i] = m->on_boundary[i] && (i % 3 != 0); /* most boundary vertices */
    }
    const double hsize = glpgp_default_size(m, NULL), eps = 0.5 * hsize, inv4e2 = 1.0 / (4.0 * eps * eps);

    /* ---- vectors: write/read, copy, axpby, dot (and determinism) ---- */
    for (int s = 0; s < 2; s++) {
        const glpgp_backend_ops *o = S[s].b->ops;
        CHECK_OK(o->vec_write(S[s].b, S[s].v[0], z));
        CHECK_OK(o->vec_write(S[s].b, S[s].v[1], r));
        CHECK_OK(o->vec_read(S[s].b, S[s].v[0], h[s]));
        CHECK(memcmp(h[s], z, n2 * sizeof(double)) == 0);
        CHECK_OK(o->copy(S[s].b, S[s].v[2], S[s].v[1]));
        CHECK_OK(o->axpby(S[s].b, 0.75, S[s].v[0], -1.5, S[s].v[2])); /* v2 <- 0.75 z - 1.5 r */
        CHECK_OK(o->vec_read(S[s].b, S[s].v[2], h[s]));
        CHECK_OK(o->dot(S[s].b, S[s].v[0], S[s].v[1], GLPGP_S_DOT));
        CHECK_OK(o->dot(S[s].b, S[s].v[2], S[s].v[2], GLPGP_S_DOT2));
        CHECK_OK(o->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS));
    }
    cmp("axpby", label, h[0], h[1], n2, 0.0, 0.0); /* entrywise: identical arithmetic */
    double scale = 0.0, scale2 = 0.0;
    for (size_t i = 0; i < n2; i++) {
        scale += fabs(z[i] * r[i]);
        scale2 += h[1][i] * h[1][i];
    }
    cmp1("dot z.r", label, sc[0][GLPGP_S_DOT], sc[1][GLPGP_S_DOT], scale);
    cmp1("dot v.v", label, sc[0][GLPGP_S_DOT2], sc[1][GLPGP_S_DOT2], scale2);
    {
        double again[GLPGP_NSLOTS];
        CHECK_OK(S[0].b->ops->dot(S[0].b, S[0].v[0], S[0].v[1], GLPGP_S_DOT));
        CHECK_OK(S[0].b->ops->get_scalars(S[0].b, again, GLPGP_NSLOTS));
        CHECK(again[GLPGP_S_DOT] == sc[0][GLPGP_S_DOT]); /* deterministic reduction */
    }

    /* ---- QUAD assembly, every element kind ---- */
    static const int kinds[] = {GLPGP_ELEM_P1, GLPGP_ELEM_TRANSPORT, GLPGP_ELEM_LAPLACE};
    static const char *kname[] = {"QUAD p1", "QUAD transport", "QUAD laplace"};
    for (int s = 0; s < 2; s++) CHECK_OK(S[s].b->ops->set_field(S[s].b, w, dir));
    for (int kk = 0; kk < 3; kk++) {
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->assemble_quadratic(S[s].b, kinds[kk], hsize));
            CHECK_OK(glpgp_probe_matrix(S[s].b, GLPGP_MAT_QUAD, M[s]));
        }
        cmp(kname[kk], label, M[0], M[1], nm, 1e-12, 1e-14);
    }

    /* ---- NEWTON + DINV: every Hessian variant, and no penalty ---- */
    for (int s = 0; s < 2; s++) CHECK_OK(S[s].b->ops->assemble_quadratic(S[s].b, GLPGP_ELEM_P1, hsize));
    static const int hv[] = {GLPGP_HESS_PAPER, GLPGP_HESS_PROJECTED, GLPGP_HESS_EXACT, GLPGP_HESS_MIXED, -1};
    for (int v = 0; v < 5; v++) {
        char what[64];
        double wgt = hv[v] < 0 ? 0.0 : inv4e2;
        int hs = hv[v] < 0 ? GLPGP_HESS_PAPER : hv[v];
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->assemble_newton(S[s].b, S[s].v[0], wgt, hs));
            CHECK_OK(glpgp_probe_matrix(S[s].b, GLPGP_MAT_NEWTON, M[s]));
        }
        snprintf(what, sizeof what, "NEWTON hess %d weight %g", hs, wgt);
        cmp(what, label, M[0], M[1], nm, 1e-12, 1e-14);
        for (int s = 0; s < 2; s++) CHECK_OK(glpgp_probe_matrix(S[s].b, GLPGP_PROBE_DINV, M[s]));
        snprintf(what, sizeof what, "DINV hess %d weight %g", hs, wgt);
        cmp(what, label, M[0], M[1], (size_t)4 * nv, 1e-12, 1e-14);
    }

    /* ---- gradient and energy (with and without penalty), spmv ---- */
    for (int pen = 0; pen < 2; pen++) {
        double wgt = pen ? inv4e2 : 0.0;
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->gradient(S[s].b, S[s].v[0], wgt, S[s].v[3]));
            CHECK_OK(S[s].b->ops->vec_read(S[s].b, S[s].v[3], h[s]));
            CHECK_OK(S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS));
        }
        cmp(pen ? "gradient (penalty)" : "gradient (no penalty)", label, h[0], h[1], n2, 1e-12, 1e-14);
        cmp1("gradient E", label, sc[0][GLPGP_S_E], sc[1][GLPGP_S_E], fabs(sc[1][GLPGP_S_E]));
        cmp1("gradient P", label, sc[0][GLPGP_S_P], sc[1][GLPGP_S_P], fabs(sc[1][GLPGP_S_P]));
        CHECK(pen || sc[0][GLPGP_S_P] == 0.0);
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->energy(S[s].b, S[s].v[0], wgt, S[s].v[4]));
            CHECK_OK(S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS));
        }
        cmp1("energy E", label, sc[0][GLPGP_S_E], sc[1][GLPGP_S_E], fabs(sc[1][GLPGP_S_E]));
        cmp1("energy P", label, sc[0][GLPGP_S_P], sc[1][GLPGP_S_P], fabs(sc[1][GLPGP_S_P]));
    }
    for (int mat = 0; mat < 2; mat++) {
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->spmv(S[s].b, mat, S[s].v[1], S[s].v[3]));
            CHECK_OK(S[s].b->ops->vec_read(S[s].b, S[s].v[3], h[s]));
        }
        cmp(mat ? "spmv NEWTON" : "spmv QUAD", label, h[0], h[1], n2, 1e-12, 1e-14);
    }

    /* ---- fused CG steps, one at a time (NEWTON = projected, SPD) ----
     * v1 = r, v2 = z, v3 = p, v4 = q, v5 = x */
    for (int s = 0; s < 2; s++) {
        const glpgp_backend_ops *o = S[s].b->ops;
        CHECK_OK(o->assemble_newton(S[s].b, S[s].v[0], inv4e2, GLPGP_HESS_PROJECTED));
        CHECK_OK(o->vec_write(S[s].b, S[s].v[1], r));
        CHECK_OK(o->axpby(S[s].b, 0.0, S[s].v[5], 0.0, S[s].v[5]));
    }
    for (int s = 0; s < 2; s++) {
        CHECK_OK(S[s].b->ops->cg_precond(S[s].b, S[s].v[1], S[s].v[2], GLPGP_S_RZ0));
        CHECK_OK(S[s].b->ops->vec_read(S[s].b, S[s].v[2], h[s]));
        CHECK_OK(S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS));
        CHECK_OK(S[s].b->ops->copy(S[s].b, S[s].v[3], S[s].v[2]));
    }
    cmp("cg_precond z", label, h[0], h[1], n2, 1e-12, 1e-14);
    cmp1("cg_precond r.z", label, sc[0][GLPGP_S_RZ0], sc[1][GLPGP_S_RZ0], fabs(sc[1][GLPGP_S_RZ0]));
    cmp1("cg_precond r.r", label, sc[0][GLPGP_S_RR], sc[1][GLPGP_S_RR], fabs(sc[1][GLPGP_S_RR]));
    for (int iter = 0; iter < 3; iter++) {
        int rz = iter % 2 ? GLPGP_S_RZ1 : GLPGP_S_RZ0, rzn = iter % 2 ? GLPGP_S_RZ0 : GLPGP_S_RZ1;
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->cg_spmv_dot(S[s].b, S[s].v[3], S[s].v[4]));
            CHECK_OK(S[s].b->ops->vec_read(S[s].b, S[s].v[4], h[s]));
            CHECK_OK(S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS));
        }
        cmp("cg_spmv_dot q", label, h[0], h[1], n2, 1e-12, 1e-14);
        cmp1("cg_spmv_dot p.q", label, sc[0][GLPGP_S_PQ], sc[1][GLPGP_S_PQ], fabs(sc[1][GLPGP_S_PQ]));
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->cg_update(S[s].b, S[s].v[5], S[s].v[1], S[s].v[3], S[s].v[4], S[s].v[2], rz, rzn));
            CHECK_OK(S[s].b->ops->get_scalars(S[s].b, sc[s], GLPGP_NSLOTS));
        }
        cmp1("cg_update r.z", label, sc[0][rzn], sc[1][rzn], fabs(sc[1][rzn]));
        cmp1("cg_update r.r", label, sc[0][GLPGP_S_RR], sc[1][GLPGP_S_RR], fabs(sc[1][GLPGP_S_RR]));
        for (int k = 1; k <= 5; k += 4) { /* r and x: alpha differs by rounding only */
            for (int s = 0; s < 2; s++) CHECK_OK(S[s].b->ops->vec_read(S[s].b, S[s].v[k], h[s]));
            cmp(k == 1 ? "cg_update r" : "cg_update x", label, h[0], h[1], n2, 1e-10, 1e-10);
        }
        for (int s = 0; s < 2; s++) {
            CHECK_OK(S[s].b->ops->cg_direction(S[s].b, S[s].v[3], S[s].v[2], rzn, rz));
            CHECK_OK(S[s].b->ops->vec_read(S[s].b, S[s].v[3], h[s]));
        }
        cmp("cg_direction p", label, h[0], h[1], n2, 1e-10, 1e-10);
    }

    /* ---- a whole CG solve: NEWTON x = r to 1e-10 ---- */
    int it[2];
    double rel[2];
    for (int s = 0; s < 2; s++) {
        CHECK_OK(S[s].b->ops->vec_write(S[s].b, S[s].v[1], r));
        glpgp_cg_info ci;
        CHECK_OK(glpgp_cg(S[s].b, S[s].v[1], S[s].v[5], 1e-10, 20000, 10, &ci));
        it[s] = ci.iterations;
        rel[s] = ci.relres;
        CHECK_OK(S[s].b->ops->vec_read(S[s].b, S[s].v[5], h[s]));
    }
    double dmax = 0.0, xmax = 0.0;
    for (size_t i = 0; i < n2; i++) {
        dmax = fmax(dmax, fabs(h[0][i] - h[1][i]));
        xmax = fmax(xmax, fabs(h[1][i]));
    }
    printf("%s: CG %d vs %d iterations, rel. residual %.2e vs %.2e, max|dx|/max|x| = %.2e\n", label, it[0], it[1],
           rel[0], rel[1], dmax / xmax);
    CHECK(dmax <= 1e-8 * xmax);
    CHECK(rel[0] <= 1e-10 && abs(it[0] - it[1]) <= 10);

    for (int s = 0; s < 2; s++) {
        for (int k = 0; k < 6; k++) S[s].b->ops->vec_destroy(S[s].b, &S[s].v[k]);
        glpgp_backend_destroy(&S[s].b);
        free(h[s]);
        free(M[s]);
    }
    free(w);
    free(z);
    free(r);
    free(dir);
    glpgp_system_destroy(&sys);
    return 0;
}

/* Device selection errors and GLPGP_KERNEL_DIR. */
static void test_device_errors(void)
{
    glpgp_backend *b = NULL;
    glpgp_cl_options o = {99, 0};
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
        char path[256];
        snprintf(path, sizeof path, "%s/element.h", dir);
        FILE *f = fopen(path, "w");
        if (f) {
            fputs("/* empty */\n", f);
            fclose(f);
        }
        snprintf(path, sizeof path, "%s/broken.cl", dir);
        f = fopen(path, "w");
        if (f) {
            fputs("__kernel void glpgp_finalize(__global double *s) { s[0] = undefined_symbol_xyz; }\n", f);
            fclose(f);
        }
        setenv("GLPGP_KERNEL_DIR", dir, 1);
        glpgp_status st = glpgp_backend_create_opencl(&o, &b);
        CHECK(st == GLPGP_ERR_OPENCL && b == NULL);
        CHECK(strstr(glpgp_error_message(), "build log") != NULL);
        CHECK(strstr(glpgp_error_detail(), "undefined_symbol_xyz") != NULL);
        glpgp_error_clear();
        unsetenv("GLPGP_KERNEL_DIR");
        unlink(path);
        snprintf(path, sizeof path, "%s/element.h", dir);
        unlink(path);
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
    glpgp_cl_options o = {-1, 0};
    if (!glpgp_have_opencl()) {
        printf("skipped: no OpenCL device (built without OpenCL)\n");
        return 77;
    }
    if (glpgp_backend_create_opencl(&o, &b) != GLPGP_OK) {
        printf("skipped: no OpenCL device (%s)\n", glpgp_error_message());
        return 77;
    }
    glpgp_backend_destroy(&b);

    test_device_errors();

    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 3000, &m));
    if (m) {
        compare_mesh("disk:3000", m);
        /* the other launch shape on the same device */
        const char *cur = getenv("GLPGP_CL_SHAPE");
        setenv("GLPGP_CL_SHAPE", cur && !strcmp(cur, "gpu") ? "cpu" : "gpu", 1);
        compare_mesh("disk:3000 (other launch shape)", m);
        if (cur) setenv("GLPGP_CL_SHAPE", cur, 1);
        else unsetenv("GLPGP_CL_SHAPE");
        glpgp_mesh_destroy(&m);
    }
    const char *data = getenv("GLPGP_DATA");
    static const char *files[] = {"annulus.msh", "plate_holes.msh"};
    for (int i = 0; i < 2; i++) {
        char path[1024];
        if (!data) break;
        snprintf(path, sizeof path, "%s/%s", data, files[i]);
        if (access(path, R_OK) != 0) {
            printf("%s: missing, skipped\n", path);
            continue;
        }
        CHECK_OK(glpgp_mesh_read(path, &m));
        if (m) compare_mesh(files[i], m);
        glpgp_mesh_destroy(&m);
    }
    TEST_DONE();
}
