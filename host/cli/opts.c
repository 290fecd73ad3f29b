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

/* ---- values ------------------------------------------------------------------ */

static int choice_value(const glpgp_opt *o, int k) { return o->values ? o->values[k] : k; }

static void join_names(const char *const *names, const char *sep, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int k = 0; names[k]; k++) {
        int w = snprintf(buf + n, len - n, "%s%s", k ? sep : "", names[k]);
        if (w < 0 || (size_t)w >= len - n) break;
        n += (size_t)w;
    }
}

/* The default of o as text (from *dest, before parsing). */
static void capture_default(glpgp_opt *o)
{
    if (o->def) {
        snprintf(o->defbuf, sizeof o->defbuf, "%s", o->def);
        return;
    }
    o->defbuf[0] = '\0';
    switch (o->kind) {
    case GLPGP_OPT_INT: snprintf(o->defbuf, sizeof o->defbuf, "%d", *(int *)o->dest); break;
    case GLPGP_OPT_DOUBLE: snprintf(o->defbuf, sizeof o->defbuf, "%g", *(double *)o->dest); break;
    case GLPGP_OPT_STRING: {
        const char *s = *(const char **)o->dest;
        if (s) snprintf(o->defbuf, sizeof o->defbuf, "%s", s);
        break;
    }
    case GLPGP_OPT_CHOICE:
        for (int k = 0; o->names[k]; k++)
            if (choice_value(o, k) == *(int *)o->dest) snprintf(o->defbuf, sizeof o->defbuf, "%s", o->names[k]);
        break;
    default: break;
    }
}

/* Text describing the accepted range of a number ("a positive number", ...). */
static void describe_range(const glpgp_opt *o, char *buf, size_t len)
{
    const char *what = o->kind == GLPGP_OPT_INT ? "an integer" : "a number";
    int lo_inf = o->lo == -HUGE_VAL, hi_inf = o->hi == HUGE_VAL;
    if (o->kind == GLPGP_OPT_INT) {
        lo_inf = o->lo <= (double)INT_MIN;
        hi_inf = o->hi >= (double)INT_MAX;
    }
    if (lo_inf && hi_inf)
        snprintf(buf, len, "%s", what);
    else if (hi_inf && o->lo == 0.0 && o->lo_open && o->kind == GLPGP_OPT_DOUBLE)
        snprintf(buf, len, "a positive number");
    else if (hi_inf)
        snprintf(buf, len, "%s %s %g", what, o->lo_open ? ">" : ">=", o->lo);
    else if (lo_inf)
        snprintf(buf, len, "%s %s %g", what, o->hi_open ? "<" : "<=", o->hi);
    else
        snprintf(buf, len, "%s in %c%g, %g%c", what, o->lo_open ? '(' : '[', o->lo, o->hi,
                 o->hi_open ? ')' : ']');
}

/* Store value v into o. Returns -1, or the usage-error exit code. */
static int apply(glpgp_opts *t, glpgp_opt *o, const char *v)
{
    char range[96];
    switch (o->kind) {
    case GLPGP_OPT_FLAG: *(int *)o->dest = o->ival; break;
    case GLPGP_OPT_INT: {
        long l;
        long lo = o->lo <= (double)LONG_MIN ? LONG_MIN : (long)o->lo;
        long hi = o->hi >= (double)LONG_MAX ? LONG_MAX : (long)o->hi;
        if (!glpgp_cli_long(v, lo, hi, &l)) {
            describe_range(o, range, sizeof range);
            return glpgp_cli_usage_error(t->cmd, "%s: '%s' is not %s", o->name, v, range);
        }
        *(int *)o->dest = (int)l;
        break;
    }
    case GLPGP_OPT_DOUBLE: {
        double d;
        int ok = glpgp_cli_double(v, &d);
        if (ok) ok = o->lo_open ? d > o->lo : d >= o->lo;
        if (ok) ok = o->hi_open ? d < o->hi : d <= o->hi;
        if (!ok) {
            describe_range(o, range, sizeof range);
            return glpgp_cli_usage_error(t->cmd, "%s: '%s' is not %s", o->name, v, range);
        }
        *(double *)o->dest = d;
        break;
    }
    case GLPGP_OPT_STRING:
        if (!*v) return glpgp_cli_usage_error(t->cmd, "%s: empty value", o->name);
        *(const char **)o->dest = v;
        break;
    case GLPGP_OPT_CHOICE: {
        for (int k = 0; o->names[k]; k++)
            if (!strcmp(v, o->names[k])) {
                *(int *)o->dest = choice_value(o, k);
                if (o->seen) *o->seen = 1;
                return -1;
            }
        char names[256];
        join_names(o->names, ", ", names, sizeof names);
        return glpgp_cli_usage_error(t->cmd, "%s: '%s' is not one of %s", o->name, v, names);
    }
    case GLPGP_OPT_CUSTOM: {
        const char *why = o->parse(v, o->dest);
        if (why) return glpgp_cli_usage_error(t->cmd, "%s: '%s' %s", o->name, v, why);
        break;
    }
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
        if (o->kind == GLPGP_OPT_CHOICE && !o->meta)
            join_names(o->names, "|", meta, sizeof meta);
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

static const char *parse_center(const char *v, void *dest)
{
    glpgp_options *o = dest;
    const char *comma = strchr(v, ',');
    char xs[128];
    size_t n = comma ? (size_t)(comma - v) : 0;
    if (!comma || n >= sizeof xs) return "is not X,Y (two numbers)";
    memcpy(xs, v, n);
    xs[n] = '\0';
    if (!glpgp_cli_double(xs, &o->center[0]) || !glpgp_cli_double(comma + 1, &o->center[1]))
        return "is not X,Y (two numbers)";
    o->has_center = 1;
    return NULL;
}

static const char *parse_field(const char *v, void *dest)
{
    glpgp_options *o = dest;
    if (!*v) return "is empty";
    if (!strcmp(v, "boundary")) {
        o->field = GLPGP_FIELD_BOUNDARY;
    } else if (!strcmp(v, "radial")) {
        o->field = GLPGP_FIELD_RADIAL;
    } else if (!strcmp(v, "cross")) {
        o->field = GLPGP_FIELD_CROSS;
    } else {
        o->field = GLPGP_FIELD_FILE;
        o->field_file = v;
    }
    return NULL;
}

static const char *parse_size_field(const char *v, void *dest)
{
    glpgp_options *o = dest;
    if (!*v) return "is empty";
    if (!strcmp(v, "auto")) {
        o->size_field = GLPGP_SIZE_AUTO;
    } else if (!strcmp(v, "iso")) {
        o->size_field = GLPGP_SIZE_ISO;
    } else if (!strcmp(v, "none")) {
        o->size_field = GLPGP_SIZE_NONE;
    } else if (glpgp_is_image_path(v)) {
        /* a grey-level image: the command reads it once the domain is known
         * (glpgp_cli_size_image sets size_fn) */
        o->size_field = GLPGP_SIZE_FUNC;
        o->size_file = v;
    } else {
        o->size_field = GLPGP_SIZE_FILE;
        o->size_file = v;
    }
    return NULL;
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

static const char *const k_methods[] = {"gl", "pgp", NULL};
static const int k_method_vals[] = {GLPGP_METHOD_GL, GLPGP_METHOD_PGP};
static const char *const k_energies[] = {"p1", "transport", NULL};
static const int k_energy_vals[] = {GLPGP_ELEM_P1, GLPGP_ELEM_TRANSPORT};
static const char *const k_newtons[] = {"mixed", "projected", "paper", NULL};
static const int k_newton_vals[] = {GLPGP_HESS_MIXED, GLPGP_HESS_PROJECTED, GLPGP_HESS_PAPER};
static const char *const k_globals[] = {"trust-region", "line-search", NULL};
static const int k_global_vals[] = {GLPGP_GLOBAL_TRUST_REGION, GLPGP_GLOBAL_LINE_SEARCH};
static const char *const k_preconds[] = {"jacobi", "amg", NULL};
static const int k_precond_vals[] = {GLPGP_PRECOND_JACOBI, GLPGP_PRECOND_AMG};
static const char *const k_couplings[] = {"auto", "off", "on", NULL};
static const int k_coupling_vals[] = {GLPGP_COUPLING_AUTO, GLPGP_COUPLING_OFF, GLPGP_COUPLING_ON};
static const char *const k_cross_sizes[] = {"off", "on", "auto", NULL};
static const int k_cross_size_vals[] = {GLPGP_CROSS_SIZE_OFF, GLPGP_CROSS_SIZE_ON, GLPGP_CROSS_SIZE_AUTO};
static const char *const k_oscs[] = {"auto", "concurrent", "sequential", NULL};
static const int k_osc_vals[] = {GLPGP_OSC_AUTO, GLPGP_OSC_CONCURRENT, GLPGP_OSC_SEQUENTIAL};
static const char *const k_inits[] = {"naive", "one", NULL};
static const int k_init_vals[] = {GLPGP_INIT_NAIVE, GLPGP_INIT_ONE};

void glpgp_opts_add_solver(glpgp_opts *t, glpgp_options *o)
{
    glpgp_opts_group(t, "Parametrization");
    glpgp_opt *p = glpgp_opt_double(t, "--size", &o->size, 0.0, 1, HUGE_VAL, 0, "H",
                                    "target quad size h, the period of the oscillators");
    p->def = "bounding-box diagonal / 20, at least 10 mean edges";
    glpgp_opt_choice(t, "--method", &o->method, k_methods, k_method_vals,
                     "Ginzburg-Landau continuation or naive PGP (one linear solve)");
    glpgp_opt_choice(t, "--energy", &o->energy, k_energies, k_energy_vals,
                     "discretisation of the quadratic energy: P1 finite elements or\n"
                     "the edge-transport (cotan) form of the original PGP");
    glpgp_opt_choice(t, "--newton", &o->hess, k_newtons, k_newton_vals,
                     "penalty Hessian used by Newton: exact where |z|^2 >= 1/2 and\n"
                     "projected in vortex cores (the trust region uses the exact one\n"
                     "everywhere), projected (PSD) everywhere, or the paper's eq. 8");
    glpgp_opt_choice(t, "--globalization", &o->globalization, k_globals, k_global_vals,
                     "Newton step: trust region on the exact Hessian (Steihaug CG,\n"
                     "polar trial points), or the line search of the modified Newton");
    glpgp_opt_choice(t, "--tr-precond", &o->tr_precond, k_preconds, k_precond_vals,
                     "with --precond amg: preconditioner and norm of the trust region's\n"
                     "Steihaug CG: 2x2-block Jacobi, or a symmetric multigrid W-cycle\n"
                     "built on the projected Hessian");
    glpgp_opt c = {0};
    c.name = "--field";
    c.kind = GLPGP_OPT_CUSTOM;
    c.dest = o;
    c.parse = parse_field;
    c.meta = "boundary|radial|cross|FILE";
    c.help = "guiding field U: smooth field aligned with the boundary, radial\n"
             "about --center, from the Ginzburg-Landau cross field (see\n"
             "--cross-eps0), or one \"ux uy\" line per vertex from FILE;\n"
             "a surface: cross (default) or boundary (harmonic, aligned with\n"
             "its boundary and sharp features)";
    c.def = "boundary; surfaces: cross";
    glpgp_opts_add(t, c);
    c.name = "--center";
    c.parse = parse_center;
    c.meta = "X,Y";
    c.help = "centre of the radial field";
    c.def = "area centroid";
    glpgp_opts_add(t, c);
    glpgp_opt_choice(t, "--init", &o->init, k_inits, k_init_vals,
                     "initial guess of the GL continuation: the normalised naive PGP\n"
                     "solution, or z = 1");
    c.name = "--size-field";
    c.parse = parse_size_field;
    c.meta = "auto|iso|none|FILE|IMAGE";
    c.help = "local size h(x) <= h: auto shrinks it where the domain (a wall,\n"
             "strip, web) is thinner than --size-across periods, per\n"
             "oscillator along its direction, and refines the input there;\n"
             "iso: the same for both; none: h everywhere (the input as it\n"
             "is); FILE: one \"h\" or \"h_u h_v\" line per vertex; IMAGE (.png,\n"
             ".tif, .exr, ...): auto, further limited to the grey level times\n"
             "h (black: --size-min h, white: h) over --size-image-box";
    c.def = "auto";
    glpgp_opts_add(t, c);
    glpgp_opt_double(t, "--size-grading", &o->size_grading, 0.0, 1, HUGE_VAL, 0, "G",
                     "local size grows at most G per unit length:\n"
                     "h(x) <= h(y) + G |x - y| along mesh edges");
    glpgp_opt_double(t, "--size-across", &o->size_across, 1.0, 0, HUGE_VAL, 0, "N",
                     "periods (quads) across the thinnest features");
    glpgp_opt_double(t, "--size-min", &o->size_min, 0.0, 1, 1.0, 0, "F",
                     "smallest local size, as a fraction of h (cusps and wedge tips\n"
                     "stop there; black in a --size-field IMAGE)");
    glpgp_opt_double(t, "--size-chord-area", &o->size_chord_area, 0.0, 0, 1.0, 1, "F",
                     "curved boundaries: when the boundary quads' chords would cut\n"
                     "(convex arcs) net of what they add (holes) more than F of the\n"
                     "domain's area (arcs of few chords per turn not netted), the\n"
                     "size near those parts is capped at c x the radius of curvature\n"
                     "(c the largest that brings them within F); 0: off");
    glpgp_opt_double(t, "--size-chord-depth", &o->size_chord_depth, 0.0, 0, 1.0, 1, "F",
                     "curved boundaries: a chord's depth (sagitta) stays below F h\n"
                     "(the size is capped where it would not); 0: off (on a surface: its\n"
                     "curvature the same way)");
    glpgp_opt_double(t, "--feature-angle", &o->feature_angle, 0.0, 0, 180.0, 0, "DEG",
                     "a surface: interior edges whose triangles' normals differ by more\n"
                     "than DEG degrees are sharp features, which the field and the\n"
                     "quads follow like the boundary (180: none)");

    glpgp_opts_group(t, "Continuation and solvers");
    glpgp_opt_double(t, "--eps0", &o->eps0, 0.0, 1, HUGE_VAL, 0, "F", "first eps, as a multiple of h");
    glpgp_opt_double(t, "--cross-eps0", &o->cross_eps0, 0.0, 1, HUGE_VAL, 0, "F",
                     "--field cross: first eps, as a multiple of the bounding-box diagonal");
    glpgp_opt_double(t, "--cross-eps-min", &o->cross_eps_min, 0.0, 1, HUGE_VAL, 0, "F",
                     "--field cross: last eps, as a multiple of the mean edge length");
    glpgp_opt_double(t, "--cross-rtol", &o->cross_rtol, 0.0, 1, 1.0, 1, "F",
                     "--field cross: each eps level stops when |g| <= F |g0|");
    glpgp_opt_choice(t, "--cross-size", &o->cross_size, k_cross_sizes, k_cross_size_vals,
                     "--field cross: local size from the cross field (its conformal\n"
                     "scale, which makes the quads' grid integrable away from the\n"
                     "singularities: fewer dislocations), the smaller of it and\n"
                     "--size-field's; on: fully conformal (largest size h); auto: h at\n"
                     "the --cross-size-quantile of the conformal scale, at least\n"
                     "h / --cross-size-ratio");
    glpgp_opt_double(t, "--cross-size-quantile", &o->cross_size_quantile, 0.0, 1, 1.0, 0, "F",
                     "--cross-size auto: the conformal scale's quantile over the vertices\n"
                     "that gets size h (larger scales are capped at h)");
    glpgp_opt_double(t, "--cross-size-ratio", &o->cross_size_ratio, 1.0, 0, HUGE_VAL, 1, "C",
                     "--cross-size auto: the size stays at least h / C");
    glpgp_opt_choice(t, "--cross-coupling", &o->cross_coupling, k_couplings, k_coupling_vals,
                     "--field cross with singularities: solve u and v coupled across the\n"
                     "cross field's cuts (auto: when it has cuts and the backend can,\n"
                     "on: an error where the backend cannot), or apart (off)");
    glpgp_opt_double(t, "--eps-ratio", &o->eps_ratio, 0.0, 1, 1.0, 1, "F", "eps_{k+1} = F eps_k");
    glpgp_opt_double(t, "--eps-min", &o->eps_min, 0.0, 1, HUGE_VAL, 0, "F",
                     "last eps, as a multiple of the mean edge length");
    glpgp_opt_double(t, "--newton-rtol", &o->newton_rtol, 0.0, 1, 1.0, 1, "F",
                     "the last level stops when |g| <= F |g0|");
    glpgp_opt_int(t, "--newton-max", &o->newton_max, 1, INT_MAX, "N", "Newton iterations per eps level");
    glpgp_opt_double(t, "--cg-rtol", &o->cg_rtol, 0.0, 1, 1.0, 1, "F", "CG stops when |r| <= F |b|");
    glpgp_opt_int(t, "--cg-max", &o->cg_max, 1, INT_MAX, "N", "CG iteration cap");
    glpgp_opt_int(t, "--cg-check", &o->cg_check, 1, INT_MAX, "N",
                  "read the CG residual back every N iterations");
    glpgp_opt_choice(t, "--precond", &o->precond, k_preconds, k_precond_vals,
                     "preconditioner of the linear solves: 2x2-block Jacobi CG, or\n"
                     "aggregation multigrid (K-cycle, flexible CG; falls back to\n"
                     "Jacobi with one warning on a backend without it)");
    glpgp_opt_choice(t, "--oscillators", &o->oscillators, k_oscs, k_osc_vals,
                     "u and v at the same time (v on a second copy of the backend\n"
                     "in a second thread; the same result bit for bit) or one after\n"
                     "the other; auto: concurrent where measured to pay (reference\n"
                     "backend; multigrid on an OpenCL CPU device up to 500k vertices)\n"
                     "with two or more processors and memory for the copy");
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

void glpgp_opts_add_quads(glpgp_opts *t, glpgp_quad_options *q, int *given, int *allow_invalid)
{
    glpgp_opt *o = glpgp_opt_flag(t, "--keep-polygons", &q->keep_polygons, 1,
                                  "keep the faces left around dislocations as polygons\n"
                                  "(default: join them pairwise or to the boundary by strips\n"
                                  "of quads cut in two: all quads, same size)");
    o->seen = given;
    o = glpgp_opt_int(t, "--smooth", &q->smooth, 0, 100000, "N",
                      "smoothing sweeps around the new vertices and the faces with\n"
                      "scaled Jacobian < 0.5 (0: off; a move is kept only if no nearby\n"
                      "corner gets worse)");
    o->seen = given;
    o = glpgp_opt_flag(t, "--all-quads", &q->all_quads, 1,
                       "refine every face into quads (centroid + edge midpoints):\n"
                       "half the element size");
    o->seen = given;
    o = glpgp_opt_flag(t, "--no-repair", &q->repair, 0,
                       "do not re-mesh the regions where the extracted mesh is invalid\n"
                       "(default: remove the bad faces and their neighbours and fill the\n"
                       "hole with quads)");
    o->seen = given;
    o = glpgp_opt_flag(t, "--no-cleanup", &q->cleanup, 0,
                       "keep the irregular vertices the repair and the strips leave\n"
                       "(default: doublet removal, diagonal collapse and edge rotation\n"
                       "where they lower the irregular vertices and keep the quality)");
    o->seen = given;
    o = glpgp_opt_flag(t, "--allow-invalid", allow_invalid, 1,
                       "write an invalid quad mesh anyway, with a warning (default: not\n"
                       "written, exit code 3)");
    o->seen = given;
}

static const char *const k_kinds[] = {"grid", "checker", "zabs", "field", "theta", "cross", NULL};
static const int k_kind_vals[] = {GLPGP_IMAGE_GRID, GLPGP_IMAGE_CHECKER, GLPGP_IMAGE_ZABS,
                                  GLPGP_IMAGE_FIELD, GLPGP_IMAGE_THETA, GLPGP_IMAGE_CROSS};
static const char *const k_backgrounds[] = {"white", "transparent", NULL};

static const char *parse_view(const char *v, void *dest)
{
    glpgp_render_options *r = dest;
    const char *comma = strchr(v, ',');
    char a[128];
    const size_t n = comma ? (size_t)(comma - v) : 0;
    if (!comma || n >= sizeof a) return "is not AZ,EL (two numbers, degrees)";
    memcpy(a, v, n);
    a[n] = '\0';
    double az, el;
    if (!glpgp_cli_double(a, &az) || !glpgp_cli_double(comma + 1, &el)) return "is not AZ,EL (two numbers, degrees)";
    if (!(fabs(el) <= 90.0)) return "has an elevation outside [-90, 90] degrees";
    r->azimuth = az;
    r->elevation = el;
    return NULL;
}

void glpgp_opts_add_picture(glpgp_opts *t, glpgp_render_options *r, int line_width)
{
    glpgp_opt_int(t, "--image-size", &r->size, 16, 32768, "N", "pixels on the long side");
    glpgp_opt_choice(t, "--image-kind", &r->kind, k_kinds, k_kind_vals,
                     "grid (unit grid of theta_u, theta_v: the paper's Fig. 4),\n"
                     "checker, zabs (heat map of min |z_u|, |z_v|), field (arrows of\n"
                     "the guiding field U), theta (red = theta_u, green = theta_v),\n"
                     "cross (the cross field of a --field cross result, singularities\n"
                     "marked: +1/4 red, -1/4 blue)");
    glpgp_opt_choice(t, "--background", &r->transparent, k_backgrounds, NULL, "picture background");
    glpgp_opt c = {0};
    c.name = "--view";
    c.kind = GLPGP_OPT_CUSTOM;
    c.dest = r;
    c.parse = parse_view;
    c.meta = "AZ,EL";
    c.help = "a surface's picture: the camera's azimuth about z (from +x) and\n"
             "elevation above the xy plane, degrees (an orthographic view fitted\n"
             "to the surface, z-buffered and shaded)";
    c.def = "35,25";
    glpgp_opts_add(t, c);
    if (line_width) {
        glpgp_opt *o = glpgp_opt_double(t, "--line-width", &r->line_width, 0.0, 1, 100.0, 0, "W",
                                        "grid line width in pixels");
        o->def = "max(1, 1.5 N / 1024)";
    }
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
                         "stop Gmsh after S seconds (0: no limit)");
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
