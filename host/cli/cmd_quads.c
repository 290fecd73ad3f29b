/* cmd_quads.c: the quad-mesh subcommands of the CLI:
 *   glpgp extract RESULT.vtk --quads OUT.{obj,vtk,msh} [--stats OUT.json] [--size H]
 *                 [--keep-polygons] [--smooth N] [--all-quads]
 *       quad mesh from a result written by `glpgp solve -o RESULT.vtk`;
 *   glpgp quality MESH.msh [--size H] [--domain DOMAIN] [--stats OUT.json]
 *       the same quality report for a quad/triangle mesh made elsewhere (Gmsh),
 *       used by bench/gmsh_compare.sh.
 * Exit codes as in main.c: 0 ok, 1 failure, 2 usage error. */
#include "cli.h"
#include "commands.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"
#include "glpgp/status.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int q_usage(const char *sub, const char *msg, const char *arg)
{
    fprintf(stderr, "glpgp: usage error: %s%s%s%s\nTry 'glpgp %s --help' for the options.\n", msg,
            arg ? " '" : "", arg ? arg : "", arg ? "'" : "", sub);
    return 2;
}

static int q_fail(void) { return glpgp_cli_fail(); }

/* --size value: a finite number > 0 */
static int q_parse_size(const char *v, double *out)
{
    return glpgp_cli_double(v, out) && *out > 0.0;
}

/* "--name=value" or "--name value" */
static const char *q_value(int argc, char **argv, int *i, const char *name)
{
    size_t n = strlen(name);
    if (!strncmp(argv[*i], name, n) && argv[*i][n] == '=') return argv[*i] + n + 1;
    if (!strcmp(argv[*i], name)) return *i + 1 < argc ? argv[++*i] : NULL;
    return NULL;
}

static int q_is(const char *arg, const char *name)
{
    size_t n = strlen(name);
    return !strncmp(arg, name, n) && (arg[n] == '\0' || arg[n] == '=');
}

static void usage_extract(FILE *f)
{
    fprintf(f,
            "Usage: glpgp extract RESULT.vtk --quads OUT.{obj,vtk,msh} [options]\n"
            "\n"
            "Extract the quad mesh whose edges are the integer level lines of theta_u and\n"
            "theta_v from a result written by 'glpgp solve -o RESULT.vtk', and print its\n"
            "quality report.\n"
            "  --quads FILE   quad mesh: .obj (quads as 4-vertex faces, other faces as\n"
            "                 n-gons), .vtk (VTK_QUAD / VTK_POLYGON) or .msh (Gmsh 4.1,\n"
            "                 quadrangles; other faces split into quads + one triangle)\n"
            "  --stats FILE   quality report as JSON {\"quads\": {...}}\n"
            "  --size H       target size h (default: the h recorded in RESULT.vtk)\n"
            "  --keep-polygons  keep the faces left around dislocations as polygons\n"
            "                 (default: join them pairwise or to the boundary through\n"
            "                 strips of quads cut in two: all quads at the same size)\n"
            "  --smooth N     smoothing sweeps around new vertices and faces with a\n"
            "                 scaled Jacobian < 0.5 (default 20; 0: off)\n"
            "  --all-quads    refine every face into quads around its centroid (each\n"
            "                 edge split at its midpoint): the element size is halved\n"
            "                 (report uses h / 2)\n"
            "  --help, -h     this text\n");
}

static void usage_quality(FILE *f)
{
    fprintf(f,
            "Usage: glpgp quality MESH.msh [options]\n"
            "\n"
            "Quality report (valences, scaled Jacobian, edge lengths, boundary distance)\n"
            "of a quad/triangle mesh in Gmsh MSH 4.1 or 2.2 ASCII, e.g. made by Gmsh.\n"
            "  --size H        target size h (> 0; default: mean edge length)\n"
            "  --domain FILE   triangle mesh (.obj/.msh) of the domain: adds the\n"
            "                  Hausdorff distance of the boundaries\n"
            "  --stats FILE    report as JSON {\"quads\": {...}}\n"
            "  --help, -h      this text\n");
}

int glpgp_cmd_extract(int argc, char **argv)
{
    const char *sub = "extract", *in = NULL, *quads = NULL, *stats = NULL;
    double size = 0.0;
    glpgp_quad_options qo;
    glpgp_quad_options_default(&qo);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage_extract(stdout);
            return 0;
        }
        if (a[0] != '-' || a[1] == '\0') {
            if (in) return q_usage(sub, "unexpected argument", a);
            in = a;
        } else if (!strcmp(a, "--all-quads")) {
            qo.all_quads = 1;
        } else if (!strcmp(a, "--keep-polygons")) {
            qo.keep_polygons = 1;
        } else if (q_is(a, "--smooth")) {
            long lv;
            if (!(v = q_value(argc, argv, &i, "--smooth"))) return q_usage(sub, "--smooth needs a value", NULL);
            if (!glpgp_cli_long(v, 0, 100000, &lv)) return q_usage(sub, "--smooth: not an integer >= 0:", v);
            qo.smooth = (int)lv;
        } else if (q_is(a, "--quads")) {
            if (!(v = q_value(argc, argv, &i, "--quads"))) return q_usage(sub, "--quads needs a value", NULL);
            if (!glpgp_quads_path_supported(v))
                return q_usage(sub, "--quads: must end in .obj, .vtk or .msh:", v);
            quads = v;
        } else if (q_is(a, "--stats")) {
            if (!(v = q_value(argc, argv, &i, "--stats")) || !*v)
                return q_usage(sub, "--stats needs a value", NULL);
            stats = v;
        } else if (q_is(a, "--size")) {
            if (!(v = q_value(argc, argv, &i, "--size"))) return q_usage(sub, "--size needs a value", NULL);
            if (!q_parse_size(v, &size)) return q_usage(sub, "--size: not a positive number:", v);
        } else {
            return q_usage(sub, "unknown option", a);
        }
    }
    if (!in) return q_usage(sub, "missing RESULT.vtk", NULL);
    if (!quads && !stats) return q_usage(sub, "nothing to do: give --quads FILE and/or --stats FILE", NULL);
    if (quads && stats && !strcmp(quads, stats))
        return q_usage(sub, "--quads and --stats name the same file", quads);
    glpgp_error_clear();
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    glpgp_quadmesh *q = NULL;
    int rc = 1;
    if (glpgp_read_result_vtk(in, &m, &r) != GLPGP_OK) {
        rc = q_fail();
        goto done;
    }
    if (size > 0) r->size = size;
    if (!(r->size > 0)) r->size = glpgp_default_size(m, NULL);
    double h = r->size;
    if (glpgp_quads_build(m, r, &qo, &q, &h) != GLPGP_OK) {
        rc = q_fail();
        goto done;
    }
    glpgp_quad_quality qq;
    if (glpgp_quads_quality(q, m, h, &qq) != GLPGP_OK) {
        rc = q_fail();
        goto done;
    }
    qq.singular[0] = r->osc[0].plus + r->osc[0].minus;
    qq.singular[1] = r->osc[1].plus + r->osc[1].minus;
    /* both outputs or neither */
    glpgp_output_set *outs = NULL;
    if (glpgp_output_set_create(&outs) != GLPGP_OK ||
        (quads && glpgp_output_set_quads(outs, q, quads) != GLPGP_OK) ||
        (stats && glpgp_output_set_quads_json(outs, &qq, stats) != GLPGP_OK) ||
        glpgp_output_set_commit(outs) != GLPGP_OK) {
        glpgp_output_set_destroy(&outs);
        rc = q_fail();
        goto done;
    }
    glpgp_output_set_destroy(&outs);
    printf("glpgp: %s: h = %.6g%s, singular triangles u %d, v %d\n", in, h,
           qo.all_quads ? " (--all-quads: half the solve's size)" : "", qq.singular[0], qq.singular[1]);
    glpgp_quads_print(stdout, &qq, "  ");
    if (quads) printf("  wrote          %s\n", quads);
    if (stats) printf("  wrote          %s\n", stats);
    rc = 0;
done:
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    return rc;
}

int glpgp_cmd_quality(int argc, char **argv)
{
    const char *sub = "quality", *in = NULL, *domain = NULL, *stats = NULL;
    double size = 0.0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage_quality(stdout);
            return 0;
        }
        if (a[0] != '-' || a[1] == '\0') {
            if (in) return q_usage(sub, "unexpected argument", a);
            in = a;
        } else if (q_is(a, "--domain")) {
            if (!(v = q_value(argc, argv, &i, "--domain")) || !*v)
                return q_usage(sub, "--domain needs a value", NULL);
            domain = v;
        } else if (q_is(a, "--stats")) {
            if (!(v = q_value(argc, argv, &i, "--stats")) || !*v)
                return q_usage(sub, "--stats needs a value", NULL);
            stats = v;
        } else if (q_is(a, "--size")) {
            if (!(v = q_value(argc, argv, &i, "--size"))) return q_usage(sub, "--size needs a value", NULL);
            if (!q_parse_size(v, &size)) return q_usage(sub, "--size: not a positive number:", v);
        } else {
            return q_usage(sub, "unknown option", a);
        }
    }
    if (!in) return q_usage(sub, "missing MESH.msh", NULL);
    glpgp_error_clear();
    glpgp_quadmesh *q = NULL;
    glpgp_mesh *dm = NULL;
    int rc = 1;
    if (glpgp_quads_read_msh(in, &q) != GLPGP_OK) {
        rc = q_fail();
        goto done;
    }
    if (domain && glpgp_mesh_read(domain, &dm) != GLPGP_OK) {
        rc = q_fail();
        goto done;
    }
    if (!(size > 0)) { /* mean edge length */
        double s = 0.0;
        int n = 0;
        for (int f = 0; f < q->nf; f++) {
            int b = q->face_start[f], k = q->face_start[f + 1] - b;
            for (int j = 0; j < k; j++) {
                int p = q->face_vert[b + j], r = q->face_vert[b + (j + 1) % k];
                s += hypot(q->xy[2 * p] - q->xy[2 * r], q->xy[2 * p + 1] - q->xy[2 * r + 1]);
                n++;
            }
        }
        size = n ? s / n : 1.0;
    }
    glpgp_quad_quality qq;
    if (glpgp_quads_quality(q, dm, size, &qq) != GLPGP_OK) {
        rc = q_fail();
        goto done;
    }
    if (stats && glpgp_quads_write_json_file(&qq, stats) != GLPGP_OK) {
        rc = q_fail();
        goto done;
    }
    printf("glpgp: %s: h = %.6g\n", in, size);
    glpgp_quads_print(stdout, &qq, "  ");
    if (stats) printf("  wrote          %s\n", stats);
    rc = 0;
done:
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&dm);
    return rc;
}

int glpgp_solve_quads(const glpgp_mesh *m, const glpgp_result *r, const char *quads_path,
                      glpgp_output_set *outs, const glpgp_quad_options *qo, glpgp_quad_quality *qq)
{
    glpgp_quadmesh *q = NULL;
    double h = r->size > 0 ? r->size : glpgp_default_size(m, NULL);
    glpgp_status st = glpgp_quads_build(m, r, qo, &q, &h);
    if (st == GLPGP_OK) st = glpgp_quads_quality(q, m, h, qq);
    if (st == GLPGP_OK) {
        qq->singular[0] = r->osc[0].plus + r->osc[0].minus;
        qq->singular[1] = r->osc[1].plus + r->osc[1].minus;
        st = glpgp_output_set_quads(outs, q, quads_path);
    }
    glpgp_quadmesh_destroy(&q);
    return st == GLPGP_OK ? -1 : q_fail();
}
