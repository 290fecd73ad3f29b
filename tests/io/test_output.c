/* test_output.c: tests of the result and statistics writers (io/result_write.c, io/stats.c) on a 3x3-vertex grid mesh with a
 * hand-made result (known z values, windings, level statistics):
 *  - VTK: every array present with the right counts and exact values, theta
 *    in [0, 1) and equal to arg(z)/2pi mod 1;
 *  - OBJ: 9 v, 24 vt, 8 f; texture coordinates unwrapped (no jump > 0.5 inside
 *    a triangle) and congruent to the vertex phases mod 1;
 *  - JSON: syntactically valid (a small recursive-descent checker), required
 *    keys present, NaN written as null, strings escaped; numbers read back
 *    exactly (0.1 + 0.2, 1e-300, the smallest subnormal, DBL_MAX, -0, 1/3)
 *    in the shortest of %.15g/%.16g/%.17g; statistics with a quad report
 *    are one valid object with one "quads" member holding lossless numbers;
 *  - failures: nonexistent directory -> GLPGP_ERR_IO with no temp file left,
 *    destination is a directory -> GLPGP_ERR_IO, unsupported extension ->
 *    GLPGP_ERR_ARG with nothing written, mismatched result -> GLPGP_ERR_ARG;
 *  - atomic writer: abort keeps a pre-existing file intact, commit replaces it. */
#include "testutil.h"

#include <dirent.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define NV 9
#define NT 8
static const double PI = 3.14159265358979323846;

/* Known phases (in periods) and moduli per vertex. Both cross an integer
 * inside the grid, so wrap handling is exercised. */
static double theta_u_of(double x, double y) { return 0.8 + 0.35 * x + 0.05 * y; }
static double theta_v_of(double x, double y) { return 0.1 - 0.3 * y + 0.02 * x; }

static double frac(double t) { return t - floor(t); }

/* Circular distance between two phases in periods. */
static double cdist(double a, double b)
{
    double d = fabs(frac(a) - frac(b));
    return d > 0.5 ? 1.0 - d : d;
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    if (buf) buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Number of directory entries other than . and .. */
static int dir_count(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

/* ---- VTK parsing ------------------------------------------------------- */

/* Pointer just after the line `line` (exact full line), or NULL. */
static const char *after_line(const char *buf, const char *line)
{
    size_t n = strlen(line);
    const char *p = buf;
    while ((p = strstr(p, line))) {
        int start_ok = p == buf || p[-1] == '\n';
        if (start_ok && p[n] == '\n') return p + n + 1;
        p += n;
    }
    return NULL;
}

/* Read exactly n numbers; then the next token must not be a number. */
static int read_numbers(const char *p, int n, double *out)
{
    if (!p) return 0;
    for (int i = 0; i < n; i++) {
        char *end;
        double v = strtod(p, &end);
        if (end == p) return 0;
        if (out) out[i] = v;
        p = end;
    }
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') p++;
    if (*p == '\0') return 1;
    return !(*p == '-' || *p == '+' || *p == '.' || (*p >= '0' && *p <= '9'));
}

static const char *data_array(const char *buf, const char *header)
{
    char line[128];
    snprintf(line, sizeof line, "%s", header);
    const char *p = after_line(buf, line);
    if (!p) {
        fprintf(stderr, "missing VTK line '%s'\n", header);
        return NULL;
    }
    if (strncmp(header, "SCALARS", 7) == 0) {
        const char *q = after_line(p, "LOOKUP_TABLE default");
        if (q != p + strlen("LOOKUP_TABLE default\n")) return NULL;
        p = q;
    }
    return p;
}

static void test_vtk(const char *dir, const glpgp_mesh *m, const glpgp_result *r)
{
    char path[512];
    snprintf(path, sizeof path, "%s/r.vtk", dir);
    CHECK(glpgp_write_vtk(m, r, path) == GLPGP_OK);
    char *buf = read_all(path);
    CHECK(buf != NULL);
    if (!buf) return;
    CHECK(strncmp(buf, "# vtk DataFile Version", 22) == 0);
    CHECK(strstr(buf, "\nASCII\nDATASET UNSTRUCTURED_GRID\n") != NULL);

    double pts[3 * NV], z[2 * NV], th[NV], v[3 * NT + 3 * NV];
    CHECK(read_numbers(data_array(buf, "POINTS 9 double"), 3 * NV, pts));
    for (int i = 0; i < NV; i++) {
        CHECK(pts[3 * i] == m->xy[2 * i] && pts[3 * i + 1] == m->xy[2 * i + 1]);
        CHECK(pts[3 * i + 2] == 0.0);
    }
    CHECK(read_numbers(data_array(buf, "CELLS 8 32"), 4 * NT, v));
    for (int t = 0; t < NT; t++) {
        CHECK(v[4 * t] == 3);
        for (int k = 0; k < 3; k++) CHECK(v[4 * t + 1 + k] == m->tri[3 * t + k]);
    }
    CHECK(read_numbers(data_array(buf, "CELL_TYPES 8"), NT, v));
    for (int t = 0; t < NT; t++) CHECK(v[t] == 5);
    CHECK(after_line(buf, "POINT_DATA 9") != NULL);
    CHECK(after_line(buf, "CELL_DATA 8") != NULL);

    static const char *const on[2] = {"u", "v"};
    char hdr[128];
    for (int k = 0; k < 2; k++) {
        const double *zk = r->osc[k].z;
        snprintf(hdr, sizeof hdr, "SCALARS z_%s double 2", on[k]);
        CHECK(read_numbers(data_array(buf, hdr), 2 * NV, z));
        for (int i = 0; i < 2 * NV; i++) CHECK(z[i] == zk[i]);

        snprintf(hdr, sizeof hdr, "SCALARS theta_%s double 1", on[k]);
        CHECK(read_numbers(data_array(buf, hdr), NV, th));
        for (int i = 0; i < NV; i++) {
            double x = m->xy[2 * i], y = m->xy[2 * i + 1];
            double want = k == 0 ? theta_u_of(x, y) : theta_v_of(x, y);
            CHECK(th[i] >= 0.0 && th[i] < 1.0);
            CHECK(cdist(th[i], want) < 1e-12);
        }

        snprintf(hdr, sizeof hdr, "SCALARS zabs_%s double 1", on[k]);
        CHECK(read_numbers(data_array(buf, hdr), NV, th));
        for (int i = 0; i < NV; i++) CHECK(fabs(th[i] - hypot(zk[2 * i], zk[2 * i + 1])) < 1e-15);

        snprintf(hdr, sizeof hdr, "SCALARS dirichlet_%s int 1", on[k]);
        CHECK(read_numbers(data_array(buf, hdr), NV, th));
        for (int i = 0; i < NV; i++) CHECK(th[i] == r->osc[k].dirichlet[i]);

        snprintf(hdr, sizeof hdr, "SCALARS singular_%s int 1", on[k]);
        CHECK(read_numbers(data_array(buf, hdr), NT, th));
        for (int t = 0; t < NT; t++) CHECK(th[t] == r->osc[k].singular[t]);
    }
    CHECK(read_numbers(data_array(buf, "VECTORS field_u double"), 3 * NV, v));
    for (int i = 0; i < NV; i++) {
        CHECK(v[3 * i] == r->field[2 * i] && v[3 * i + 1] == r->field[2 * i + 1]);
        CHECK(v[3 * i + 2] == 0.0);
    }
    CHECK(read_numbers(data_array(buf, "VECTORS field_v double"), 3 * NV, v));
    for (int i = 0; i < NV; i++)
        CHECK(v[3 * i] == -r->field[2 * i + 1] && v[3 * i + 1] == r->field[2 * i]);
    free(buf);
    /* only r.vtk in the directory: no temporary left behind */
    CHECK(dir_count(dir) == 1);
    remove(path);
}

/* ---- OBJ --------------------------------------------------------------- */

static void test_obj(const char *dir, const glpgp_mesh *m, const glpgp_result *r)
{
    char path[512];
    snprintf(path, sizeof path, "%s/r.obj", dir);
    CHECK(glpgp_write_result(m, NULL, r, path) == GLPGP_OK);
    FILE *f = fopen(path, "r");
    CHECK(f != NULL);
    if (!f) return;
    double vt[2 * 64];
    int nv = 0, nvt = 0, nf = 0, jumps = 0, wraps = 0;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "v ", 2) == 0) {
            double x, y, zc;
            CHECK(sscanf(line + 2, "%lf %lf %lf", &x, &y, &zc) == 3);
            if (nv < NV) CHECK(x == m->xy[2 * nv] && y == m->xy[2 * nv + 1] && zc == 0.0);
            nv++;
        } else if (strncmp(line, "vt ", 3) == 0) {
            double a, b;
            CHECK(sscanf(line + 3, "%lf %lf", &a, &b) == 2);
            if (nvt < 64) {
                vt[2 * nvt] = a;
                vt[2 * nvt + 1] = b;
            }
            nvt++;
        } else if (strncmp(line, "f ", 2) == 0) {
            int a[3], ta[3];
            CHECK(sscanf(line + 2, "%d/%d %d/%d %d/%d", &a[0], &ta[0], &a[1], &ta[1], &a[2],
                         &ta[2]) == 6);
            CHECK(nf < NT);
            if (nf >= NT) continue;
            for (int k = 0; k < 3; k++) {
                CHECK(a[k] - 1 == m->tri[3 * nf + k]);
                CHECK(ta[k] >= 1 && ta[k] <= nvt);
            }
            const double *t0 = vt + 2 * (ta[0] - 1);
            CHECK(t0[0] >= 0 && t0[0] < 1 && t0[1] >= 0 && t0[1] < 1);
            for (int k = 0; k < 3; k++) {
                const double *tk = vt + 2 * (ta[k] - 1);
                int vi = a[k] - 1;
                double x = m->xy[2 * vi], y = m->xy[2 * vi + 1];
                for (int c = 0; c < 2; c++) {
                    if (fabs(tk[c] - t0[c]) > 0.5) jumps++;
                    if (tk[c] >= 1.0 || tk[c] < 0.0) wraps++;
                    double want = c == 0 ? theta_u_of(x, y) : theta_v_of(x, y);
                    CHECK(cdist(tk[c], want) < 1e-12);
                }
                for (int l = 0; l < 3; l++) {
                    const double *tl = vt + 2 * (ta[l] - 1);
                    CHECK(fabs(tk[0] - tl[0]) <= 0.5 && fabs(tk[1] - tl[1]) <= 0.5);
                }
            }
            nf++;
        }
    }
    fclose(f);
    CHECK(nv == NV);
    CHECK(nvt == 3 * NT);
    CHECK(nf == NT);
    CHECK(jumps == 0);
    CHECK(wraps > 0); /* the test data does cross a period inside some triangle */
    CHECK(dir_count(dir) == 1);
    remove(path);
}

/* ---- JSON checker ------------------------------------------------------ */

typedef struct jp {
    const char *p;
    int depth;
} jp;

static void jp_ws(jp *s)
{
    while (*s->p == ' ' || *s->p == '\n' || *s->p == '\t' || *s->p == '\r') s->p++;
}

static int jp_value(jp *s);

static int jp_string(jp *s)
{
    if (*s->p != '"') return 0;
    s->p++;
    while (*s->p && *s->p != '"') {
        unsigned char c = (unsigned char)*s->p;
        if (c < 0x20) return 0;
        if (c == '\\') {
            s->p++;
            if (*s->p == 'u') {
                for (int i = 1; i <= 4; i++)
                    if (!strchr("0123456789abcdefABCDEF", s->p[i]) || !s->p[i]) return 0;
                s->p += 5;
                continue;
            }
            if (!*s->p || !strchr("\"\\/bfnrt", *s->p)) return 0;
        }
        s->p++;
    }
    if (*s->p != '"') return 0;
    s->p++;
    return 1;
}

static int jp_number(jp *s)
{
    const char *p = s->p;
    if (*p == '-') p++;
    if (*p == '0')
        p++;
    else if (*p >= '1' && *p <= '9')
        while (*p >= '0' && *p <= '9') p++;
    else
        return 0;
    if (*p == '.') {
        p++;
        if (!(*p >= '0' && *p <= '9')) return 0;
        while (*p >= '0' && *p <= '9') p++;
    }
    if (*p == 'e' || *p == 'E') {
        p++;
        if (*p == '+' || *p == '-') p++;
        if (!(*p >= '0' && *p <= '9')) return 0;
        while (*p >= '0' && *p <= '9') p++;
    }
    s->p = p;
    return 1;
}

static int jp_lit(jp *s, const char *lit)
{
    size_t n = strlen(lit);
    if (strncmp(s->p, lit, n)) return 0;
    s->p += n;
    return 1;
}

static int jp_value(jp *s)
{
    if (++s->depth > 64) return 0;
    jp_ws(s);
    int ok;
    if (*s->p == '{') {
        s->p++;
        jp_ws(s);
        ok = 1;
        if (*s->p == '}') {
            s->p++;
        } else {
            for (;;) {
                jp_ws(s);
                if (!jp_string(s)) return 0;
                jp_ws(s);
                if (*s->p != ':') return 0;
                s->p++;
                if (!jp_value(s)) return 0;
                jp_ws(s);
                if (*s->p == ',') {
                    s->p++;
                    continue;
                }
                if (*s->p != '}') return 0;
                s->p++;
                break;
            }
        }
    } else if (*s->p == '[') {
        s->p++;
        jp_ws(s);
        ok = 1;
        if (*s->p == ']') {
            s->p++;
        } else {
            for (;;) {
                if (!jp_value(s)) return 0;
                jp_ws(s);
                if (*s->p == ',') {
                    s->p++;
                    continue;
                }
                if (*s->p != ']') return 0;
                s->p++;
                break;
            }
        }
    } else if (*s->p == '"') {
        ok = jp_string(s);
    } else if (*s->p == 't') {
        ok = jp_lit(s, "true");
    } else if (*s->p == 'f') {
        ok = jp_lit(s, "false");
    } else if (*s->p == 'n') {
        ok = jp_lit(s, "null");
    } else {
        ok = jp_number(s);
    }
    s->depth--;
    return ok;
}

static int json_valid(const char *text)
{
    jp s = {text, 0};
    if (!jp_value(&s)) return 0;
    jp_ws(&s);
    return *s.p == '\0';
}

static void test_json_checker(void)
{
    CHECK(json_valid("{\"a\": [1, -2.5e+3, true, null, \"x\\n\\u00e9\"], \"b\": {}}"));
    CHECK(!json_valid("{\"a\": nan}"));
    CHECK(!json_valid("{\"a\": 1,}"));
    CHECK(!json_valid("{\"a\": 01}"));
    CHECK(!json_valid("{\"a\": \"unterminated}"));
    CHECK(!json_valid("[1 2]"));
    CHECK(!json_valid("{\"a\": inf}"));
}

static void test_json(const char *dir, const glpgp_mesh *m, const glpgp_result *r)
{
    char path[512];
    snprintf(path, sizeof path, "%s/r.json", dir);
    glpgp_options o;
    glpgp_options_default(&o);
    o.method = GLPGP_METHOD_GL;
    o.field = GLPGP_FIELD_FILE;
    o.field_file = "dir/field \"U\".txt";
    glpgp_stats_extra x = {"in\\put\t.obj", NULL, 0.25, NULL, 0, NULL, "device 0: \"gpu\"\\x", NULL, 0.0, -1.0};
    CHECK(glpgp_write_stats_json(m, &o, r, path, &x) == GLPGP_OK);
    char *buf = read_all(path);
    CHECK(buf != NULL);
    if (!buf) return;
    CHECK(json_valid(buf));
    static const char *const keys[] = {
        "\"version\"", "\"input\": \"in\\\\put\\t.obj\"", "\"vertices\": 9", "\"triangles\": 8",
        "\"size\": 0.5", "\"method\": \"gl\"", "\"energy\"", "\"newton\"",
        "\"backend\": \"ref\\\"x\\\\y\\n\"", "\"device\": \"device 0: \\\"gpu\\\"\\\\x\"", "\"field\": \"file\"",
        "\"field_file\": \"dir/field \\\"U\\\".txt\"", "\"singularities\"", "\"plus\": 1",
        "\"minus\": 2", "\"zabs\"", "\"min\": null", "\"p10\"", "\"median\"",
        "\"newton_iterations\"", "\"total\": 17", "\"cg_iterations\"", "\"total\": 1111",
        "\"eps_schedule\"", "\"restarted\": true", "\"median_zabs\"", "\"grad0\"",
        "\"dirichlet\"", "\"seconds\"", "\"setup\"", "\"field\": 0.125", "\"total\": 2.5",
        "\"read\": 0.25", "\"mesh\"", "\"area\": 1", "\"mean_edge\"", "\"boundary_loops\": 1",
        "\"output\": null", NULL};
    for (int i = 0; keys[i]; i++) {
        if (!strstr(buf, keys[i])) {
            fprintf(stderr, "JSON lacks %s\n", keys[i]);
            tu_failures++;
        }
    }
    CHECK(!strstr(buf, "nan") && !strstr(buf, "inf"));
    free(buf);
    CHECK(dir_count(dir) == 1);
    remove(path);
}

static void test_json_numbers(const char *dir)
{
    const double v[] = {0.1 + 0.2, 1e-300, 4.9406564584124654e-324, 1.7976931348623157e308, -0.0, 1.0 / 3.0,
                        0.1, 123456789012345678.0, -2.5e-8, 3.141592653589793, 1.0, 0.0};
    char buf[32];
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        glpgp_json_format_number(v[i], buf);
        double back = strtod(buf, NULL);
        CHECK(memcmp(&back, &v[i], sizeof back) == 0); /* bit-exact, -0 included */
        CHECK(strlen(buf) < 25);
    }
    CHECK(strcmp(glpgp_json_format_number(0.1, buf), "0.1") == 0);          /* shortest */
    CHECK(strcmp(glpgp_json_format_number(0.1 + 0.2, buf), "0.30000000000000004") == 0);
    CHECK(strcmp(glpgp_json_format_number(1e-300, buf), "1e-300") == 0);
    CHECK(strcmp(glpgp_json_format_number(NAN, buf), "null") == 0);
    CHECK(strcmp(glpgp_json_format_number(-INFINITY, buf), "null") == 0);

    /* a document through the emitter: valid, numbers read back exactly */
    char path[512];
    snprintf(path, sizeof path, "%s/n.json", dir);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    glpgp_json w;
    glpgp_json_init(&w, f);
    glpgp_json_object(&w, NULL);
    glpgp_json_array(&w, "values");
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) glpgp_json_num(&w, NULL, v[i]);
    glpgp_json_num(&w, NULL, NAN);
    glpgp_json_close(&w);
    glpgp_json_str(&w, "s\"k", "a\"b\\c\n\x01\xff");
    glpgp_json_object(&w, "empty");
    glpgp_json_close(&w);
    glpgp_json_int(&w, "big", 9007199254740993LL);
    glpgp_json_finish(&w);
    fclose(f);
    char *text = read_all(path);
    CHECK(text && json_valid(text));
    if (text) {
        const char *p = strchr(text, '[');
        for (size_t i = 0; p && i < sizeof v / sizeof v[0]; i++) {
            char *e;
            double back = strtod(p + 1, &e);
            CHECK(memcmp(&back, &v[i], sizeof back) == 0);
            p = strchr(e, ',');
        }
        CHECK(p && strncmp(p, ",\n    null\n  ]", 14) == 0);
        CHECK(strstr(text, "\"s\\\"k\": \"a\\\"b\\\\c\\n\\u0001\\ufffd\"") != NULL);
        CHECK(strstr(text, "\"empty\": {}") != NULL);
        CHECK(strstr(text, "\"big\": 9007199254740993") != NULL);
    }
    free(text);
    remove(path);
}

/* The statistics with a quad report: one object, "quads" once, lossless. */
static void test_stats_quads(const char *dir, const glpgp_mesh *m, const glpgp_result *r)
{
    char path[512];
    snprintf(path, sizeof path, "%s/sq.json", dir);
    glpgp_quads_report qq;
    memset(&qq, 0, sizeof qq);
    qq.vertices = 36;
    qq.quads = qq.faces = 25;
    qq.others_by_size[0] = 2;
    qq.others_by_size[7] = 1;
    qq.valence_interior[4] = 16;
    qq.valence_boundary[GLPGP_QUADS_MAXVAL] = 3;
    qq.sj_min = 0.1 + 0.2;
    qq.sj_mean = 1.0 / 3.0;
    qq.sj_p01 = NAN;
    qq.h = 1e-300;
    qq.hausdorff = -1;
    qq.singular[0] = qq.singular[1] = -1;
    glpgp_stats_extra x = {"in.obj", "out.vtu", 0.5, &qq, 0, NULL, NULL, NULL, 0.0, -1.0};
    CHECK_OK(glpgp_write_stats_json(m, NULL, r, path, &x));
    char *text = read_all(path);
    CHECK(text && json_valid(text));
    if (!text) return;
    CHECK(strstr(text, "\"device\": null") != NULL); /* no device given */
    const char *q = strstr(text, "\"quads\": {");
    CHECK(q != NULL && strstr(q + 1, "\"quads\": {") == NULL);
    if (q) {
        const char *sj = strstr(q, "\"min\": ");
        CHECK(sj && strtod(sj + 7, NULL) == 0.1 + 0.2);
        sj = strstr(q, "\"mean\": ");
        CHECK(sj && strtod(sj + 8, NULL) == 1.0 / 3.0);
        CHECK(strstr(q, "\"p01\": null") != NULL);
        const char *h = strstr(q, "\"h\": ");
        CHECK(h && strtod(h + 5, NULL) == 1e-300);
        CHECK(strstr(q, "\"3\": 2") && strstr(q, "\">=10\": 1") && strstr(q, "\"4\": 16"));
        CHECK(strstr(q, "\"boundary_distance_over_h\": null") && strstr(q, "\"singular_triangles\": null"));
    }
    /* the quads member is the last one of the top-level object */
    size_t n = strlen(text);
    CHECK(n > 4 && strcmp(text + n - 4, "}\n}\n") == 0);
    free(text);
    CHECK(dir_count(dir) == 1);
    remove(path);
}

/* ---- failure modes and the atomic writer ------------------------------- */

static void test_failures(const char *dir, const glpgp_mesh *m, glpgp_result *r)
{
    char path[512], sub[512];
    snprintf(sub, sizeof sub, "%s/missing", dir);
    snprintf(path, sizeof path, "%s/missing/out.vtk", dir);
    glpgp_error_clear();
    CHECK(glpgp_write_vtk(m, r, path) == GLPGP_ERR_IO);
    CHECK(strstr(glpgp_error_message(), "out.vtk") != NULL);
    glpgp_error_clear();
    snprintf(path, sizeof path, "%s/missing/out.obj", dir);
    CHECK(glpgp_write_result(m, NULL, r, path) == GLPGP_ERR_IO);
    glpgp_error_clear();
    snprintf(path, sizeof path, "%s/missing/out.json", dir);
    CHECK(glpgp_write_stats_json(m, NULL, r, path, NULL) == GLPGP_ERR_IO);
    glpgp_error_clear();
    struct stat sb;
    CHECK(stat(sub, &sb) != 0);
    CHECK(dir_count(dir) == 0);

    /* destination is an existing directory */
    snprintf(sub, sizeof sub, "%s/adir.vtk", dir);
    CHECK(mkdir(sub, 0755) == 0);
    CHECK(glpgp_write_result(m, NULL, r, sub) == GLPGP_ERR_IO);
    glpgp_error_clear();
    CHECK(dir_count(dir) == 1);
    rmdir(sub);

    /* unsupported extension */
    snprintf(path, sizeof path, "%s/out.txt", dir);
    CHECK(glpgp_write_result(m, NULL, r, path) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    snprintf(path, sizeof path, "%s/out", dir);
    CHECK(glpgp_write_result(m, NULL, r, path) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    CHECK(dir_count(dir) == 0);
    CHECK(glpgp_result_path_supported("a.VTK") && glpgp_result_path_supported("b.obj"));
    CHECK(!glpgp_result_path_supported("c.json") && !glpgp_result_path_supported("vtk"));

    /* result that does not match the mesh */
    snprintf(path, sizeof path, "%s/bad.vtk", dir);
    r->nv = NV - 1;
    CHECK(glpgp_write_vtk(m, r, path) == GLPGP_ERR_ARG);
    CHECK(glpgp_write_obj_textured(m, r, path) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    r->nv = NV;
    CHECK(dir_count(dir) == 0);

    /* atomic writer: abort keeps the old content, commit replaces it */
    snprintf(path, sizeof path, "%s/keep.txt", dir);
    glpgp_atomic_file af;
    CHECK(glpgp_atomic_open(&af, path) == GLPGP_OK);
    fputs("old\n", af.f);
    CHECK(glpgp_atomic_commit(&af) == GLPGP_OK);
    CHECK(af.f == NULL && af.tmp == NULL);
    CHECK(glpgp_atomic_open(&af, path) == GLPGP_OK);
    CHECK(dir_count(dir) == 2); /* keep.txt + its temporary */
    fputs("new, half writ", af.f);
    glpgp_atomic_abort(&af);
    glpgp_atomic_abort(&af); /* idempotent */
    char *buf = read_all(path);
    CHECK(buf && strcmp(buf, "old\n") == 0);
    free(buf);
    CHECK(dir_count(dir) == 1);
    CHECK(glpgp_atomic_open(&af, path) == GLPGP_OK);
    fputs("new\n", af.f);
    CHECK(glpgp_atomic_commit(&af) == GLPGP_OK);
    buf = read_all(path);
    CHECK(buf && strcmp(buf, "new\n") == 0);
    free(buf);
    CHECK(dir_count(dir) == 1);
    remove(path);

    /* a result written over an existing file replaces it entirely */
    snprintf(path, sizeof path, "%s/over.vtk", dir);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f) {
        for (int i = 0; i < 100000; i++) fputs("garbage garbage garbage\n", f);
        fclose(f);
    }
    CHECK(glpgp_write_result(m, NULL, r, path) == GLPGP_OK);
    buf = read_all(path);
    CHECK(buf && strncmp(buf, "# vtk", 5) == 0 && !strstr(buf, "garbage"));
    free(buf);
    CHECK(dir_count(dir) == 1);
    remove(path);

    glpgp_error_clear();
    CHECK(glpgp_atomic_open(&af, "") == GLPGP_ERR_ARG);
    glpgp_error_clear();
}

static void test_theta(void)
{
    CHECK(glpgp_theta(1, 0) == 0.0);
    CHECK(fabs(glpgp_theta(0, 1) - 0.25) < 1e-15);
    CHECK(fabs(glpgp_theta(-1, 1e-300) - 0.5) < 1e-15);
    CHECK(fabs(glpgp_theta(0, -1) - 0.75) < 1e-15);
    double t = glpgp_theta(1, -1e-300);
    CHECK(t >= 0 && t < 1);
    CHECK(glpgp_theta(0, 0) == 0.0);
}

int main(void)
{
    double xy[2 * NV];
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            xy[2 * (3 * j + i)] = 0.5 * i;
            xy[2 * (3 * j + i) + 1] = 0.5 * j;
        }
    int tri[3 * NT], nt = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int a = 3 * j + i, b = a + 1, c = a + 4, d = a + 3;
            tri[3 * nt] = a, tri[3 * nt + 1] = b, tri[3 * nt + 2] = c, nt++;
            tri[3 * nt] = a, tri[3 * nt + 1] = c, tri[3 * nt + 2] = d, nt++;
        }
    glpgp_mesh *m = NULL;
    if (glpgp_mesh_create(NV, xy, NT, tri, &m) != GLPGP_OK) {
        fprintf(stderr, "glpgp_mesh_create failed: %s\n", glpgp_error_message());
        return 1;
    }

    double zu[2 * NV], zv[2 * NV], field[2 * NV];
    unsigned char du[NV], dv[NV];
    signed char su[NT] = {0, 1, 0, 0, -1, 0, 0, -1}, sv[NT] = {1, 0, 0, -1, 0, 0, 1, 0};
    for (int i = 0; i < NV; i++) {
        double x = m->xy[2 * i], y = m->xy[2 * i + 1];
        double ru = 0.5 + 0.05 * i, rv = 1.0 - 0.03 * i;
        zu[2 * i] = ru * cos(2 * PI * theta_u_of(x, y));
        zu[2 * i + 1] = ru * sin(2 * PI * theta_u_of(x, y));
        zv[2 * i] = rv * cos(2 * PI * theta_v_of(x, y));
        zv[2 * i + 1] = rv * sin(2 * PI * theta_v_of(x, y));
        field[2 * i] = cos(0.3 * i);
        field[2 * i + 1] = sin(0.3 * i);
        du[i] = (unsigned char)(i % 2);
        dv[i] = (unsigned char)(i % 3 == 0);
    }
    glpgp_result *r = calloc(1, sizeof *r);
    if (!r) return 1;
    r->nv = NV;
    r->nt = NT;
    r->size = 0.5;
    r->field = field;
    r->backend = "ref\"x\\y\n";
    r->seconds_setup = 0.5;
    r->seconds_field = 0.125;
    r->seconds_total = 2.5;
    r->field_cg_iterations = 11;
    glpgp_osc_result *ou = &r->osc[0], *ov = &r->osc[1];
    ou->z = zu;
    ov->z = zv;
    ou->dirichlet = du;
    ov->dirichlet = dv;
    ou->n_dirichlet = 4;
    ov->n_dirichlet = 3;
    ou->singular = su;
    ov->singular = sv;
    ou->plus = 1, ou->minus = 2, ov->plus = 2, ov->minus = 1;
    ou->zabs_min = NAN, ou->zabs_p10 = 0.6, ou->zabs_median = 0.7;
    ov->zabs_min = 0.5, ov->zabs_p10 = 0.8, ov->zabs_median = INFINITY;
    ou->newton_iterations = 10, ov->newton_iterations = 7;
    ou->cg_iterations = 600, ov->cg_iterations = 500;
    ou->seconds = 1.0, ov->seconds = 0.75;
    ou->nlevels = 2;
    static const glpgp_level_stats zero_level;
    glpgp_level_stats l0 = zero_level, l1 = zero_level, l2 = zero_level;
    l0.eps = 0.25, l0.newton = 6, l0.cg = 400, l0.grad0 = 1.0, l0.grad = 1e-7, l0.energy = 3.5;
    l0.median_zabs = 0.9;
    l1.eps = 0.125, l1.newton = 4, l1.cg = 200, l1.grad0 = 0.5, l1.grad = NAN, l1.energy = 3.0;
    l1.median_zabs = 0.95, l1.restarted = 1;
    l2.eps = 0.25, l2.newton = 7, l2.cg = 500, l2.grad0 = 1.0, l2.grad = 1e-8, l2.energy = 2.0;
    l2.median_zabs = 0.97;
    ou->nlevels = 2;
    ou->level[0] = l0;
    ou->level[1] = l1;
    ov->nlevels = 1;
    ov->level[0] = l2;

    char dir[] = "/tmp/glpgp_test_output_XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_theta();
    test_vtk(dir, m, r);
    test_obj(dir, m, r);
    test_json_checker();
    test_json(dir, m, r);
    test_json_numbers(dir);
    test_stats_quads(dir, m, r);
    test_failures(dir, m, r);
    CHECK(dir_count(dir) == 0);
    rmdir(dir);

    free(r);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
