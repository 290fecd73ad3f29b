/* cli/opts.c: the table-driven option parser and help printer of the CLI
 * (opts.h), and the option groups shared by several commands. */
#include "opts.h"

#include "cli.h"

#include "glpgp/io.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void glpgp_opts_init(glpgp_opts *t, const char *cmd, const char *usage, const char *about)
{
    memset(t, 0, sizeof *t);
    t->cmd = cmd;
    t->usage = usage;
    t->about = about;
    t->group = "Options";
}

void glpgp_opts_group(glpgp_opts *t, const char *title) { t->group = title; }

glpgp_opt *glpgp_opts_add(glpgp_opts *t, glpgp_opt o)
{
    if (t->n >= GLPGP_OPTS_MAX) {
        /* a programming error: the tables are static in size */
        fprintf(stderr, "glpgp: internal error: too many options for '%s'\n", t->cmd);
        abort();
    }
    o.group = t->group;
    t->opt[t->n] = o;
    return &t->opt[t->n++];
}

glpgp_opt *glpgp_opt_flag(glpgp_opts *t, const char *name, int *dest, int value, const char *help)
{
    glpgp_opt o = {0};
    o.name = name;
    o.kind = GLPGP_OPT_FLAG;
    o.dest = dest;
    o.ival = value;
    o.help = help;
    o.def = "";
    return glpgp_opts_add(t, o);
}

glpgp_opt *glpgp_opt_int(glpgp_opts *t, const char *name, int *dest, long lo, long hi,
                         const char *meta, const char *help)
{
    glpgp_opt o = {0};
    o.name = name;
    o.kind = GLPGP_OPT_INT;
    o.dest = dest;
    o.lo = (double)lo;
    o.hi = (double)hi;
    o.meta = meta;
    o.help = help;
    return glpgp_opts_add(t, o);
}

glpgp_opt *glpgp_opt_double(glpgp_opts *t, const char *name, double *dest, double lo, int lo_open,
                            double hi, int hi_open, const char *meta, const char *help)
{
    glpgp_opt o = {0};
    o.name = name;
    o.kind = GLPGP_OPT_DOUBLE;
    o.dest = dest;
    o.lo = lo;
    o.hi = hi;
    o.lo_open = lo_open;
    o.hi_open = hi_open;
    o.meta = meta;
    o.help = help;
    return glpgp_opts_add(t, o);
}

glpgp_opt *glpgp_opt_string(glpgp_opts *t, const char *name, const char **dest, const char *meta,
                            const char *help)
{
    glpgp_opt o = {0};
    o.name = name;
    o.kind = GLPGP_OPT_STRING;
    o.dest = dest;
    o.meta = meta;
    o.help = help;
    return glpgp_opts_add(t, o);
}

glpgp_opt *glpgp_opt_choice(glpgp_opts *t, const char *name, int *dest, const char *const *names,
                            const int *values, const char *help)
{
    glpgp_opt o = {0};
    o.name = name;
    o.kind = GLPGP_OPT_CHOICE;
    o.dest = dest;
    o.names = names;
    o.values = values;
    o.help = help;
    return glpgp_opts_add(t, o);
}

static const glpgp_opt_kind k_cli_kind[] = {[GLPGP_OPTK_FLAG] = GLPGP_OPT_FLAG, [GLPGP_OPTK_INT] = GLPGP_OPT_INT,
                                          [GLPGP_OPTK_DOUBLE] = GLPGP_OPT_DOUBLE,
                                          [GLPGP_OPTK_CHOICE] = GLPGP_OPT_CHOICE,
                                          [GLPGP_OPTK_TEXT] = GLPGP_OPT_CUSTOM};

glpgp_opt *glpgp_opts_add_desc(glpgp_opts *t, const glpgp_optdesc *d, void *obj)
{
    glpgp_opt o = {0};
    o.kind = k_cli_kind[d->kind];
    o.dest = d->kind == GLPGP_OPTK_TEXT ? obj : (char *)obj + d->offset;
    o.lo = d->lo;
    o.hi = d->hi;
    o.lo_open = d->lo_open;
    o.hi_open = d->hi_open;
    o.ival = d->ival;
    o.names = d->names;
    o.values = d->values;
    o.meta = d->meta;
    o.help = d->help;
    o.def = d->def;
    if (d->kind == GLPGP_OPTK_FLAG && !o.def) o.def = "";
    o.desc = d;
    o.obj = obj;
    glpgp_opt *p = glpgp_opts_add(t, o);
    snprintf(p->namebuf, sizeof p->namebuf, "--%s", d->name);
    p->name = p->namebuf;
    return p;
}

void glpgp_opts_add_table(glpgp_opts *t, const glpgp_optdesc *table, void *obj)
{
    for (const glpgp_optdesc *d = table; d->name; d++) {
        if (!d->group) continue;
        if (strcmp(t->group, d->group) != 0) glpgp_opts_group(t, d->group);
        glpgp_opts_add_desc(t, d, obj);
    }
}

/* ---- values: parsed and checked by the library (glpgp/optdesc.h) ------------- */

static const glpgp_optkind k_desc_kind[] = {
    [GLPGP_OPT_FLAG] = GLPGP_OPTK_FLAG, [GLPGP_OPT_INT] = GLPGP_OPTK_INT, [GLPGP_OPT_DOUBLE] = GLPGP_OPTK_DOUBLE,
    [GLPGP_OPT_CHOICE] = GLPGP_OPTK_CHOICE};

/* The descriptor of o (FLAG, INT, DOUBLE, CHOICE, or one from a library
 * table) and the struct it sets, in *obj. */
static glpgp_optdesc as_desc(const glpgp_opt *o, void **obj)
{
    if (o->desc) {
        *obj = o->obj;
        return *o->desc;
    }
    glpgp_optdesc d = {.name = o->name, .kind = k_desc_kind[o->kind], .offset = 0, .lo = o->lo, .hi = o->hi,
                       .lo_open = o->lo_open, .hi_open = o->hi_open, .ival = o->ival, .names = o->names,
                       .values = o->values, .def = o->def};
    *obj = o->dest;
    return d;
}

static int has_desc(const glpgp_opt *o) { return o->desc || (o->kind != GLPGP_OPT_STRING && o->kind != GLPGP_OPT_CUSTOM); }

/* The default of o as text (from *dest, before parsing). */
static void capture_default(glpgp_opt *o)
{
    if (o->def) {
        snprintf(o->defbuf, sizeof o->defbuf, "%s", o->def);
        return;
    }
    o->defbuf[0] = '\0';
    if (o->kind == GLPGP_OPT_STRING) {
        const char *s = *(const char **)o->dest;
        if (s) snprintf(o->defbuf, sizeof o->defbuf, "%s", s);
    } else if (has_desc(o)) {
        void *obj;
        glpgp_optdesc d = as_desc(o, &obj);
        glpgp_optdesc_default(&d, obj, o->defbuf, sizeof o->defbuf);
    }
}

/* Store value v into o. Returns -1, or the usage-error exit code. */
static int apply(glpgp_opts *t, glpgp_opt *o, const char *v)
{
    if (o->kind == GLPGP_OPT_STRING) {
        if (!*v) return glpgp_cli_usage_error(t->cmd, "%s: empty value", o->name);
        *(const char **)o->dest = v;
    } else if (!has_desc(o)) {
        const char *why = o->parse(v, o->dest);
        if (why) return glpgp_cli_usage_error(t->cmd, "%s: '%s' %s", o->name, v, why);
    } else {
        char why[320];
        void *obj;
        glpgp_optdesc d = as_desc(o, &obj);
        if (glpgp_optdesc_set(&d, obj, v, why, sizeof why))
            return glpgp_cli_usage_error(t->cmd, "%s: '%s' %s", o->name, v, why);
    }
    if (o->seen) *o->seen = 1;
    return -1;
}

static glpgp_opt *find(glpgp_opts *t, const char *name)
{
    for (int k = 0; k < t->n; k++)
        if (!strcmp(t->opt[k].name, name) || (t->opt[k].alias && !strcmp(t->opt[k].alias, name)))
            return &t->opt[k];
    return NULL;
}

int glpgp_opts_parse_input(glpgp_opts *t, int argc, char **argv, const char **in, const int *verbosity,
                           const char *missing)
{
    int npos = 0;
    int rc = glpgp_opts_parse(t, argc, argv, in, 1, &npos);
    if (rc >= 0) return rc;
    glpgp_cli_set_verbosity(*verbosity); /* as --verbose / --quiet set it */
    if (missing && !*in) return glpgp_cli_usage_error(t->cmd, "missing %s", missing);
    return -1;
}

int glpgp_opts_parse(glpgp_opts *t, int argc, char **argv, const char **pos, int maxpos, int *npos)
{
    *npos = 0;
    for (int k = 0; k < t->n; k++) capture_default(&t->opt[k]);
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (arg[0] != '-' || arg[1] == '\0') {
            if (*npos >= maxpos) return glpgp_cli_usage_error(t->cmd, "unexpected argument '%s'", arg);
            pos[(*npos)++] = arg;
            continue;
        }
        /* "--name=value" or "--name [value]" */
        char name[64];
        const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
        size_t n = eq ? (size_t)(eq - arg) : strlen(arg);
        if (n >= sizeof name) return glpgp_cli_usage_error(t->cmd, "unknown option '%.60s...'", arg);
        memcpy(name, arg, n);
        name[n] = '\0';
        const char *value = eq ? eq + 1 : NULL;
        if (!strcmp(name, "--help") || !strcmp(name, "-h")) {
            if (value) return glpgp_cli_usage_error(t->cmd, "option %s takes no value", name);
            t->help = 1;
            glpgp_opts_usage(t, stdout);
            return 0;
        }
        glpgp_opt *o = find(t, name);
        if (!o) return glpgp_cli_usage_error(t->cmd, "unknown option '%s'", arg);
        if (o->kind == GLPGP_OPT_FLAG) {
            if (value) return glpgp_cli_usage_error(t->cmd, "option %s takes no value", name);
        } else if (!value) {
            if (i + 1 >= argc) return glpgp_cli_usage_error(t->cmd, "option %s needs a value", name);
            value = argv[++i];
        }
        int rc = apply(t, o, value);
        if (rc >= 0) return rc;
    }
    return -1;
}

/* ---- help ---------------------------------------------------------------------- */

#define HELP_COL 24

void glpgp_opts_usage(glpgp_opts *t, FILE *f)
{
    for (int k = 0; k < t->n; k++)
        if (!t->opt[k].defbuf[0]) capture_default(&t->opt[k]);
    fprintf(f, "Usage: %s\n", t->usage);
    if (t->about) fprintf(f, "\n%s", t->about);
    const char *group = NULL;
    for (int k = 0; k < t->n; k++) {
        const glpgp_opt *o = &t->opt[k];
        if (!group || strcmp(group, o->group) != 0) {
            group = o->group;
            fprintf(f, "\n%s:\n", group);
        }
        char left[160], meta[128];
        meta[0] = '\0';
        if (o->kind == GLPGP_OPT_CHOICE && !o->meta) {
            const glpgp_optdesc d = {.kind = GLPGP_OPTK_CHOICE, .names = o->names};
            glpgp_optdesc_choices(&d, "|", meta, sizeof meta);
        }
        else if (o->meta)
            snprintf(meta, sizeof meta, "%s", o->meta);
        snprintf(left, sizeof left, "  %s%s%s%s%s", o->name, o->alias ? ", " : "", o->alias ? o->alias : "",
                 meta[0] ? " " : "", meta);
        int w = (int)strlen(left);
        fputs(left, f);
        if (w >= HELP_COL - 1) {
            fputc('\n', f);
            w = 0;
        }
        /* help lines, the default appended to the last one */
        const char *h = o->help ? o->help : "";
        int first = 1, col = 0;
        for (;;) {
            const char *nl = strchr(h, '\n');
            int len = nl ? (int)(nl - h) : (int)strlen(h);
            fprintf(f, "%*s%.*s", first ? HELP_COL - w : HELP_COL, "", len, h);
            col = HELP_COL + len;
            first = 0;
            if (!nl) break;
            fputc('\n', f);
            h = nl + 1;
        }
        if (o->defbuf[0]) {
            /* the default on the last line, or on its own line when it does not fit */
            int dl = (int)strlen(o->defbuf) + 12;
            if (col + dl > 80)
                fprintf(f, "\n%*s(default: %s)", HELP_COL, "", o->defbuf);
            else
                fprintf(f, " (default: %s)", o->defbuf);
        }
        fputc('\n', f);
    }
    fprintf(f, "\n  --help, -h            this text\n");
    if (t->epilog) fprintf(f, "\n%s", t->epilog);
}

/* ---- shared groups -------------------------------------------------------------- */

void glpgp_opts_add_verbosity(glpgp_opts *t, int *v)
{
    glpgp_opts_group(t, "Messages");
    glpgp_opt_flag(t, "--quiet", v, 0, "no progress on stderr (warnings and errors only)");
    glpgp_opt_flag(t, "--verbose", v, 2, "debug progress on stderr, and error traces");
}

static const char *parse_box(const char *v, void *dest)
{
    double *box = dest, b[4];
    const char *p = v;
    for (int k = 0; k < 4; k++) {
        const char *comma = strchr(p, ',');
        char num[128];
        size_t n = comma ? (size_t)(comma - p) : strlen(p);
        if ((k < 3) != (comma != NULL) || n >= sizeof num) return "is not X0,Y0,X1,Y1 (four numbers)";
        memcpy(num, p, n);
        num[n] = '\0';
        if (!glpgp_cli_double(num, &b[k])) return "is not X0,Y0,X1,Y1 (four numbers)";
        p = comma ? comma + 1 : p + n;
    }
    if (!(b[2] > b[0]) || !(b[3] > b[1])) return "is an empty box (need X1 > X0 and Y1 > Y0)";
    for (int k = 0; k < 4; k++) box[k] = b[k];
    return NULL;
}

void glpgp_opts_add_size_image(glpgp_opts *t, double box[4])
{
    for (int k = 0; k < 4; k++) box[k] = NAN;
    glpgp_opt c = {0};
    c.name = "--size-image-box";
    c.kind = GLPGP_OPT_CUSTOM;
    c.dest = box;
    c.parse = parse_box;
    c.meta = "X0,Y0,X1,Y1";
    c.help = "area the --size-field IMAGE covers (top row at Y1); for a mask\n"
             "input of W x H pixels: 0,0,W*s,H*s with s = --pixel-size";
    c.def = "the domain's bounding box";
    glpgp_opts_add(t, c);
}

void glpgp_opts_add_solver(glpgp_opts *t, glpgp_options *o)
{
    glpgp_opts_add_table(t, glpgp_solve_option_table(), o);
}

static const char *const k_backends[] = {"auto", "opencl", "reference", "petsc", NULL};
static const int k_backend_vals[] = {GLPGP_BACKEND_AUTO, GLPGP_BACKEND_OPENCL, GLPGP_BACKEND_REFERENCE,
                                     GLPGP_BACKEND_PETSC};

void glpgp_opts_add_backend(glpgp_opts *t, int *kind, int *device)
{
    glpgp_opts_group(t, "Backend");
    glpgp_opt_choice(t, "--backend", kind, k_backends, k_backend_vals,
                     "auto tries OpenCL and falls back to the reference C path with\n"
                     "one warning; petsc runs on MPI ranks (mpirun -n P glpgp solve\n"
                     "... --backend petsc; PETSc options in $PETSC_OPTIONS)");
    glpgp_opt *d = glpgp_opt_int(t, "--device", device, 0, INT_MAX, "N",
                                 "OpenCL device index as listed by 'glpgp devices'; with\n"
                                 "--device, an unusable OpenCL backend is an error");
    d->def = "$GLPGP_DEVICE, else the first fp64 GPU, else the first fp64 device";
}

void glpgp_opts_add_quads(glpgp_opts *t, glpgp_quads_options *q, int *given, int *allow_invalid)
{
    for (const glpgp_optdesc *d = glpgp_quads_option_table(); d->name; d++) glpgp_opts_add_desc(t, d, q)->seen = given;
    glpgp_opt *o = glpgp_opt_flag(t, "--allow-invalid", allow_invalid, 1,
                                  "write an invalid quad mesh anyway, with a warning (default: not\n"
                                  "written, exit code 3)");
    o->seen = given;
}

void glpgp_opts_add_picture(glpgp_opts *t, glpgp_render_options *r, int line_width)
{
    for (const glpgp_optdesc *d = glpgp_render_option_table(); d->name; d++)
        if (line_width || strcmp(d->name, "line-width") != 0) glpgp_opts_add_desc(t, d, r);
}

static const char *const k_algorithms[] = {"frontal", "delaunay", NULL};
static const int k_algorithm_vals[] = {6, 5};

void glpgp_opts_add_mask(glpgp_opts *t, glpgp_mask_options *m)
{
    glpgp_opt_double(t, "--threshold", &m->contour.threshold, -HUGE_VAL, 0, HUGE_VAL, 0, "T",
                     "inside = mask value >= T (alpha if the image has a varying\n"
                     "alpha channel, else luminance, in [0, 1])");
    glpgp_opt_flag(t, "--invert", &m->contour.invert, 1, "inside = mask value < T");
    glpgp_opt_double(t, "--pixel-size", &m->contour.pixel_size, 0.0, 1, HUGE_VAL, 0, "S",
                     "physical size of a pixel; y points up, the image covers\n"
                     "[0, width S] x [0, height S]");
    glpgp_opt *o = glpgp_opt_double(t, "--mesh-size", &m->mesh_size, 0.0, 1, HUGE_VAL, 0, "M",
                                    "Gmsh target size, physical units (mean edge about 0.7 M)");
    o->def = "h / 8 with h = --size, or the bounding-box diagonal / 20";
    glpgp_opt_double(t, "--min-area", &m->contour.min_area, 0.0, 0, HUGE_VAL, 0, "A",
                     "drop islands and fill holes under A square pixels");
    glpgp_opt_double(t, "--simplify", &m->contour.tolerance, 0.0, 0, HUGE_VAL, 0, "P",
                         "boundary simplification tolerance in pixels (raised to\n"
                         "mesh size / 20)");
    o = glpgp_opt_choice(t, "--algorithm", &m->algorithm, k_algorithms, k_algorithm_vals,
                         "Gmsh 2D algorithm: Frontal-Delaunay, or Delaunay (faster on\n"
                         "huge meshes)");
    o->def = "frontal";
    glpgp_opt_double(t, "--mesh-timeout", &m->timeout, 0.0, 0, HUGE_VAL, 0, "S",
                         "stop Gmsh after S seconds (0: the default, 3600)");
}

static const char *parse_max_elements(const char *v, void *dest)
{
    long n;
    if (!glpgp_cli_long(v, 1, GLPGP_IO_MAX_ITEMS, &n)) return "is not an integer in [1, 536870911]";
    *(long *)dest = n;
    return NULL;
}

static const char *parse_max_pixels(const char *v, void *dest)
{
    long n;
    if (!glpgp_cli_long(v, 1, LONG_MAX, &n)) return "is not a positive integer";
    *(long long *)dest = n;
    return NULL;
}

void glpgp_opts_add_limits(glpgp_opts *t, long *max_elements, long long *max_pixels)
{
    static char def_elements[32], def_pixels[32];
    snprintf(def_elements, sizeof def_elements, "%ld", (long)GLPGP_DEFAULT_MAX_ELEMENTS);
    snprintf(def_pixels, sizeof def_pixels, "%lld", (long long)GLPGP_DEFAULT_MAX_PIXELS);
    glpgp_opts_group(t, "Limits");
    glpgp_opt c = {0};
    c.name = "--max-elements";
    c.kind = GLPGP_OPT_CUSTOM;
    c.dest = max_elements;
    c.parse = parse_max_elements;
    c.meta = "N";
    c.help = "refuse meshes with more triangles (or faces) than N: files,\n"
             "shape:NAME:N (about 2 N), and masks (estimated before Gmsh)";
    c.def = def_elements;
    glpgp_opts_add(t, c);
    if (max_pixels) {
        c.name = "--max-pixels";
        c.dest = max_pixels;
        c.parse = parse_max_pixels;
        c.help = "refuse mask images (width x height, read from the header\n"
                 "before any pixel) and pictures (--image-size^2) with more pixels";
        c.def = def_pixels;
        glpgp_opts_add(t, c);
    }
}
