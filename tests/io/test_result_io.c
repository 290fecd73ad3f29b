/* test_result_io.c: results written as legacy .vtk and as .vtu (raw and
 * zlib) read back with glpgp_read_result (same mesh, bit-identical z and
 * field, same Dirichlet sets, h, singularities and |z| statistics); the
 * .vtu of a quad mesh has the expected header; a VTK file without
 * oscillators, a missing file and each malformed-input class of the legacy
 * and XML readers (second POINTS / CELLS, non-finite z, huge or
 * inconsistent counts, repeated arrays, truncated or corrupt binary data,
 * out-of-range indices) give GLPGP_ERR_FORMAT / _LIMIT with nothing
 * returned. */
#include "testutil.h"

#include <string.h>
#include <unistd.h>

static void compare(const glpgp_mesh *m, const glpgp_result *r, const glpgp_mesh *m2, const glpgp_result *r2,
                    int exact_h)
{
    CHECK(m2->nv == m->nv && m2->nt == m->nt);
    if (m2->nv != m->nv || m2->nt != m->nt) return;
    if (exact_h)
        CHECK(r2->size == r->size);
    else
        CHECK_CLOSE(r2->size, r->size, 1e-9, 0);
    CHECK(memcmp(m2->xy, m->xy, sizeof(double) * 2 * (size_t)m->nv) == 0);
    CHECK(memcmp(m2->tri, m->tri, sizeof(int) * 3 * (size_t)m->nt) == 0);
    CHECK(memcmp(r2->field, r->field, sizeof(double) * 2 * (size_t)m->nv) == 0);
    for (int k = 0; k < 2; k++) {
        CHECK(memcmp(r2->osc[k].z, r->osc[k].z, sizeof(double) * 2 * (size_t)m->nv) == 0);
        CHECK(memcmp(r2->osc[k].dirichlet, r->osc[k].dirichlet, (size_t)m->nv) == 0);
        CHECK(memcmp(r2->osc[k].singular, r->osc[k].singular, (size_t)m->nt) == 0);
        CHECK(r2->osc[k].plus == r->osc[k].plus && r2->osc[k].minus == r->osc[k].minus);
        CHECK(r2->osc[k].n_dirichlet == r->osc[k].n_dirichlet);
        CHECK(r2->osc[k].zabs_median == r->osc[k].zabs_median);
    }
}

static void round_trips(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 3000, &m));
    glpgp_backend *b = NULL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    glpgp_options o;
    glpgp_options_default(&o);
    o.size = 0.25;
    o.newton_max = 10;
    glpgp_result *r = NULL;
    CHECK_OK(glpgp_solve(m, b, &o, &r));
    if (!r) return;
    /* make z awkward for a text format: full 17-digit values and a subnormal */
    r->osc[0].z[0] = 0.1 + 0.2;
    r->osc[0].z[1] = 4.9406564584124654e-324;
    CHECK_OK(glpgp_osc_summarize(m, &r->osc[0]));
    r->size = 0.1 + 0.15;

    struct {
        const char *name;
        int level; /* -2: legacy through glpgp_write_result */
    } cases[] = {{"r.vtk", -2}, {"r_raw.vtu", 0}, {"r_z1.vtu", 1}, {"r_z9.vtu", 9}, {"r_def.vtu", -2}};
    long size_raw = 0, size_z = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *p = tu_tmp_path(cases[i].name);
        if (cases[i].level == -2)
            CHECK_OK(glpgp_write_result(m, &o, r, p));
        else
            CHECK_OK(glpgp_write_vtu(m, &o, r, p, cases[i].level));
        FILE *f = fopen(p, "rb");
        long sz = 0;
        if (f) {
            fseek(f, 0, SEEK_END);
            sz = ftell(f);
            fclose(f);
        }
        if (cases[i].level == 0) size_raw = sz;
        if (cases[i].level == 1) size_z = sz;
        glpgp_mesh *m2 = NULL;
        glpgp_result *r2 = NULL;
        CHECK_OK(glpgp_read_result(p, &m2, &r2));
        if (m2 && r2) compare(m, r, m2, r2, strstr(cases[i].name, ".vtu") != NULL);
        printf("%-10s %8ld bytes: read back %s\n", cases[i].name, sz, m2 && r2 ? "ok" : "FAILED");
        glpgp_result_destroy(&r2);
        glpgp_mesh_destroy(&m2);
        unlink(p);
    }
    if (glpgp_io_have_zlib()) CHECK(size_z > 0 && size_z < size_raw);
    CHECK(glpgp_result_path_supported("x.VTU") && glpgp_result_path_supported("x.vtk"));

    /* quad mesh as .vtu: cells, types and the arrays of the legacy writer */
    glpgp_quadmesh *q = NULL;
    double h = r->size;
    CHECK_OK(glpgp_quads_build(m, r, NULL, &q, &h));
    if (q) {
        CHECK_OK(glpgp_quads_write(q, tu_tmp_path("q.vtu")));
        FILE *f = fopen(tu_tmp_path("q.vtu"), "rb");
        char head[4096] = {0};
        size_t n = f ? fread(head, 1, sizeof head - 1, f) : 0;
        if (f) fclose(f);
        head[n < sizeof head ? n : sizeof head - 1] = '\0';
        char want[128];
        snprintf(want, sizeof want, "NumberOfPoints=\"%d\" NumberOfCells=\"%d\"", q->nv, q->nf);
        CHECK(strstr(head, want) != NULL);
        CHECK(strstr(head, "Name=\"scaled_jacobian\"") && strstr(head, "Name=\"valence\"") &&
              strstr(head, "Name=\"corners\"") && strstr(head, "Name=\"types\""));
        CHECK(glpgp_quads_path_supported("q.vtu"));
        unlink(tu_tmp_path("q.vtu"));
        glpgp_quadmesh_destroy(&q);
    }
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    glpgp_backend_destroy(&b);
}

/* ---- malformed inputs ---------------------------------------------------- */

static void put(const char *name, const void *data, size_t n)
{
    FILE *f = fopen(tu_tmp_path(name), "wb");
    if (!f) {
        tu_failures++;
        return;
    }
    fwrite(data, 1, n, f);
    fclose(f);
}

static void expect_bad(const char *name, const char *text, const char *needle, int line)
{
    put(name, text, strlen(text));
    glpgp_mesh *m = (glpgp_mesh *)&m;
    glpgp_result *r = (glpgp_result *)&r;
    glpgp_error_clear();
    glpgp_status st = glpgp_read_result(tu_tmp_path(name), &m, &r);
    if ((st != GLPGP_ERR_FORMAT && st != GLPGP_ERR_LIMIT) || m || r ||
        (needle && !strstr(glpgp_error_message(), needle))) {
        fprintf(stderr, "%s:%d: %s: expected a format error containing '%s', got %d: %s\n", __FILE__, line, name,
                needle ? needle : "", (int)st, glpgp_error_message());
        tu_failures++;
    }
    if (st == GLPGP_OK) {
        glpgp_result_destroy(&r);
        glpgp_mesh_destroy(&m);
    }
    glpgp_error_clear();
    unlink(tu_tmp_path(name));
}

#define HDR "# vtk DataFile Version 3.0\nglpgp result: h 0.5\nASCII\nDATASET UNSTRUCTURED_GRID\n"
#define PTS "POINTS 3 double\n0 0 0\n1 0 0\n0 1 0\n"
#define CELLS "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n"
#define ZU "SCALARS z_u double 2\nLOOKUP_TABLE default\n1 0\n1 0\n1 0\n"
#define ZV "SCALARS z_v double 2\nLOOKUP_TABLE default\n0 1\n0 1\n0 1\n"

static void malformed_legacy(void)
{
    /* the valid base reads */
    const char *good = HDR PTS CELLS "POINT_DATA 3\n" ZU ZV;
    put("good.vtk", good, strlen(good));
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    CHECK_OK(glpgp_read_result(tu_tmp_path("good.vtk"), &m, &r));
    CHECK(r && r->size == 0.5 && m && m->nv == 3);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);

    expect_bad("noosc.vtk", HDR PTS CELLS, "without oscillators", __LINE__);
    expect_bad("points2.vtk", HDR PTS CELLS "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n1 1 0\nPOINT_DATA 3\n" ZU ZV,
               "second POINTS", __LINE__);
    expect_bad("cells2.vtk", HDR PTS CELLS "CELLS 2 8\n3 0 1 2\n3 0 2 1\nPOINT_DATA 3\n" ZU ZV, "second CELLS",
               __LINE__);
    expect_bad("nanz.vtk", HDR PTS CELLS "POINT_DATA 3\nSCALARS z_u double 2\nLOOKUP_TABLE default\n1 0\nnan 0\n1 0\n" ZV,
               "not a finite", __LINE__);
    expect_bad("infz.vtk", HDR PTS CELLS "POINT_DATA 3\n" ZU "SCALARS z_v double 2\nLOOKUP_TABLE default\n0 1\n1e999 1\n0 1\n",
               "not a finite", __LINE__);
    expect_bad("hugecells.vtk", HDR PTS "CELLS 4611686018427387904 0\n" "POINT_DATA 3\n" ZU ZV, "declared", __LINE__);
    expect_bad("wrapcells.vtk", HDR PTS "CELLS 4611686018427387905 4\n3 0 1 2\n", NULL, __LINE__);
    expect_bad("hugepoints.vtk", HDR "POINTS 9223372036854775807 double\n0 0 0\n", "declared", __LINE__);
    expect_bad("toolong.vtk", HDR "POINTS 99999999999999999999 double\n", NULL, __LINE__);
    expect_bad("quad.vtk", HDR PTS "CELLS 1 5\n4 0 1 2 0\n", "triangles only", __LINE__);
    expect_bad("index.vtk", HDR PTS "CELLS 1 4\n3 0 1 7\nCELL_TYPES 1\n5\nPOINT_DATA 3\n" ZU ZV, "out of range", __LINE__);
    expect_bad("repeat.vtk", HDR PTS CELLS "POINT_DATA 3\n" ZU ZU ZV, "repeated", __LINE__);
    expect_bad("trunc.vtk", HDR PTS CELLS "POINT_DATA 3\nSCALARS z_u double 2\nLOOKUP_TABLE default\n1 0\n", NULL,
               __LINE__);
    expect_bad("pdmismatch.vtk", HDR PTS CELLS "POINT_DATA 4\n" ZU ZV, "does not match", __LINE__);
    expect_bad("binary.vtk", "# vtk DataFile Version 3.0\nx\nBINARY\n", "only ASCII", __LINE__);
    expect_bad("notvtk.vtk", "hello\n", "not a VTK file", __LINE__);
    expect_bad("types.vtk", HDR PTS "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n9\n", "type", __LINE__);
    expect_bad("nul.vtk", HDR "POINTS 3 double\n0 0 0\n1 0\x01 0\n", NULL, __LINE__);
    unlink(tu_tmp_path("good.vtk"));
}

static void malformed_vtu(void)
{
    /* a small valid .vtu, then damaged copies */
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("square", 200, &m));
    glpgp_result *r = NULL;
    CHECK_OK(glpgp_result_create(m->nv, m->nt, &r));
    if (!r) return;
    for (int i = 0; i < m->nv; i++) r->osc[0].z[2 * i] = r->osc[1].z[2 * i] = 1.0;
    r->size = 0.5;
    for (int level = 0; level <= (glpgp_io_have_zlib() ? 1 : 0); level++) {
        CHECK_OK(glpgp_write_vtu(m, NULL, r, tu_tmp_path("base.vtu"), level));
        FILE *f = fopen(tu_tmp_path("base.vtu"), "rb");
        static char buf[1 << 20];
        size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
        if (f) fclose(f);
        glpgp_mesh *m2 = NULL;
        glpgp_result *r2 = NULL;
        CHECK_OK(glpgp_read_result(tu_tmp_path("base.vtu"), &m2, &r2));
        CHECK(m2 && r2 && r2->size == 0.5);
        glpgp_result_destroy(&r2);
        glpgp_mesh_destroy(&m2);
        static char cp[1 << 20];
        char nm[64];
        struct {
            const char *from, *to, *needle;
        } damage[] = {
            {"NumberOfPoints=\"", "NumberOfPoints=\"9", NULL},
            {"Name=\"z_v\"", "Name=\"z_u\"", "repeated"},
            {"format=\"appended\"", "format=\"binary\"  ", "appended"},
            {"UInt64", "UInt99", "header_type"},
            {"UnstructuredGrid\" version", "PolyData\"         version", "UnstructuredGrid"},
        };
        for (size_t d = 0; d < sizeof damage / sizeof damage[0]; d++) {
            /* same-length or longer patches: rebuild the text */
            size_t kf = strlen(damage[d].from), kt = strlen(damage[d].to);
            char *at = NULL;
            for (size_t i = 0; i + kf <= n; i++)
                if (!memcmp(buf + i, damage[d].from, kf)) {
                    at = buf + i;
                    break;
                }
            CHECK(at != NULL);
            if (!at) continue;
            size_t pre = (size_t)(at - buf);
            memcpy(cp, buf, pre);
            memcpy(cp + pre, damage[d].to, kt);
            memcpy(cp + pre + kt, at + kf, n - pre - kf);
            snprintf(nm, sizeof nm, "dmg%zu_%d.vtu", d, level);
            put(nm, cp, n - kf + kt);
            glpgp_mesh *m3 = NULL;
            glpgp_result *r3 = NULL;
            glpgp_error_clear();
            glpgp_status st = glpgp_read_result(tu_tmp_path(nm), &m3, &r3);
            if ((st != GLPGP_ERR_FORMAT && st != GLPGP_ERR_LIMIT) || m3 || r3 ||
                (damage[d].needle && !strstr(glpgp_error_message(), damage[d].needle))) {
                fprintf(stderr, "%s (level %d): expected a format error, got %d: %s\n", nm, level, (int)st,
                        glpgp_error_message());
                tu_failures++;
            }
            glpgp_error_clear();
            unlink(tu_tmp_path(nm));
        }
        /* truncated data: every cut of the appended section fails cleanly */
        const char *data = strstr(buf, "<AppendedData");
        size_t start = data ? (size_t)(data - buf) : 0;
        int bad = 0;
        for (size_t cut = start; cut < n; cut += (n - start) / 37 + 1) {
            snprintf(nm, sizeof nm, "cut_%d.vtu", level);
            put(nm, buf, cut);
            glpgp_mesh *m3 = NULL;
            glpgp_result *r3 = NULL;
            glpgp_status st = glpgp_read_result(tu_tmp_path(nm), &m3, &r3);
            if (st != GLPGP_ERR_FORMAT || m3 || r3) bad++;
            glpgp_error_clear();
            glpgp_result_destroy(&r3);
            glpgp_mesh_destroy(&m3);
        }
        CHECK(bad == 0);
        /* corrupt the size / compression header of the first array */
        memcpy(cp, buf, n);
        const char *us = strchr(strstr(buf, "<AppendedData"), '_');
        if (us) {
            size_t at = (size_t)(us - buf) + 1;
            memset(cp + at, 0xff, 8); /* byte count or block count = 2^64 - 1 */
            snprintf(nm, sizeof nm, "hdr_%d.vtu", level);
            put(nm, cp, n);
            glpgp_mesh *m3 = NULL;
            glpgp_result *r3 = NULL;
            CHECK(glpgp_read_result(tu_tmp_path(nm), &m3, &r3) == GLPGP_ERR_FORMAT && !m3 && !r3);
            glpgp_error_clear();
        }
        /* a non-finite z value in raw data */
        if (level == 0) {
            memcpy(cp, buf, n);
            const double inf = INFINITY;
            /* first value of z_u: after its 8-byte size */
            const char *zoff = strstr(buf, "Name=\"z_u\"");
            CHECK(zoff != NULL);
            size_t at = (size_t)(strchr(strstr(buf, "<AppendedData"), '_') - buf) + 1;
            long long off = 0;
            if (zoff) sscanf(strstr(zoff, "offset=\"") + 8, "%lld", &off);
            memcpy(cp + at + off + 8, &inf, 8);
            snprintf(nm, sizeof nm, "inf.vtu");
            put(nm, cp, n);
            glpgp_mesh *m3 = NULL;
            glpgp_result *r3 = NULL;
            CHECK(glpgp_read_result(tu_tmp_path(nm), &m3, &r3) == GLPGP_ERR_FORMAT && !m3 && !r3);
            CHECK(strstr(glpgp_error_message(), "not finite") != NULL);
            glpgp_error_clear();
        }
        unlink(tu_tmp_path("base.vtu"));
    }
    unlink(tu_tmp_path("cut_0.vtu"));
    unlink(tu_tmp_path("cut_1.vtu"));
    unlink(tu_tmp_path("hdr_0.vtu"));
    unlink(tu_tmp_path("hdr_1.vtu"));
    unlink(tu_tmp_path("inf.vtu"));
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    if (!tu_tmp_init("rio")) return 1;
    round_trips();
    malformed_legacy();
    malformed_vtu();
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    CHECK(glpgp_read_result_vtk("/nonexistent/x.vtk", &m, &r) == GLPGP_ERR_IO && !m && !r);
    glpgp_error_clear();
    CHECK(glpgp_read_result(tu_tmp_dir, &m, &r) == GLPGP_ERR_IO && !m && !r); /* a directory */
    glpgp_error_clear();
    rmdir(tu_tmp_dir);
    TEST_DONE();
}
