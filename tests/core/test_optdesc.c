/* test_optdesc.c: option descriptors (glpgp/optdesc.h) and the library's
 * tables: values parsed whole and range-checked with the CLI's reasons,
 * choices, flags and their Python names (--no-repair is repair), defaults as
 * the help shows them, text options (--center, --field, --size-field), and
 * every table entry named, documented and settable from its default. */
#include "testutil.h"

#include <stddef.h>
#include <string.h>

static void check_numbers(void)
{
    const glpgp_optdesc *t = glpgp_solve_option_table();
    glpgp_options o;
    glpgp_options_default(&o);
    char why[256];
    const glpgp_optdesc *size = glpgp_optdesc_find(t, "size");
    CHECK(size && size->kind == GLPGP_OPTK_DOUBLE);
    CHECK(glpgp_optdesc_set(size, &o, "0.25", why, sizeof why) == NULL && o.size == 0.25);
    /* rejected values leave the member unchanged, with the CLI's reason */
    const char *r = glpgp_optdesc_set(size, &o, "0", why, sizeof why);
    CHECK(r && !strcmp(r, "is not a positive number") && o.size == 0.25);
    CHECK(glpgp_optdesc_set(size, &o, "1e400", why, sizeof why) != NULL);
    CHECK(glpgp_optdesc_set(size, &o, "0.3x", why, sizeof why) != NULL);
    CHECK(glpgp_optdesc_set(size, &o, "nan", why, sizeof why) != NULL);
    CHECK(glpgp_optdesc_set(size, &o, "", why, sizeof why) != NULL && o.size == 0.25);
    const glpgp_optdesc *nm = glpgp_optdesc_find(t, "newton_max");
    CHECK(nm && nm == glpgp_optdesc_find(t, "newton-max"));
    r = glpgp_optdesc_set(nm, &o, "0", why, sizeof why);
    CHECK(r && !strcmp(r, "is not an integer >= 1"));
    CHECK(glpgp_optdesc_set(nm, &o, "1.5", why, sizeof why) != NULL);
    CHECK(glpgp_optdesc_set(nm, &o, "99999999999", why, sizeof why) != NULL);
    CHECK(glpgp_optdesc_set(nm, &o, "12", why, sizeof why) == NULL && o.newton_max == 12);
    r = glpgp_optdesc_set(glpgp_optdesc_find(t, "eps_ratio"), &o, "1", why, sizeof why);
    CHECK(r && !strcmp(r, "is not a number in (0, 1)"));
    r = glpgp_optdesc_set(glpgp_optdesc_find(t, "size_chord_area"), &o, "1", why, sizeof why);
    CHECK(r && !strcmp(r, "is not a number in [0, 1)"));
}

static void check_choices_and_text(void)
{
    const glpgp_optdesc *t = glpgp_solve_option_table();
    glpgp_options o;
    glpgp_options_default(&o);
    char why[256], buf[128];
    const glpgp_optdesc *m = glpgp_optdesc_find(t, "method");
    const char *r = glpgp_optdesc_set(m, &o, "foo", why, sizeof why);
    CHECK(r && !strcmp(r, "is not one of gl, pgp") && o.method == GLPGP_METHOD_GL);
    CHECK(glpgp_optdesc_set(m, &o, "pgp", why, sizeof why) == NULL && o.method == GLPGP_METHOD_PGP);
    const glpgp_optdesc *nw = glpgp_optdesc_find(t, "newton");
    CHECK(glpgp_optdesc_set(nw, &o, "paper", why, sizeof why) == NULL && o.hess == GLPGP_HESS_PAPER);
    glpgp_optdesc_value(nw, &o, buf, sizeof buf);
    CHECK(!strcmp(buf, "paper"));
    glpgp_optdesc_choices(glpgp_optdesc_find(t, "oscillators"), "|", buf, sizeof buf);
    CHECK(!strcmp(buf, "auto|concurrent|sequential"));
    const glpgp_optdesc *c = glpgp_optdesc_find(t, "center");
    CHECK(glpgp_optdesc_set(c, &o, "1", why, sizeof why) != NULL && !o.has_center);
    CHECK(glpgp_optdesc_set(c, &o, "1.5,-2", why, sizeof why) == NULL && o.has_center && o.center[0] == 1.5 &&
          o.center[1] == -2.0);
    const glpgp_optdesc *f = glpgp_optdesc_find(t, "field");
    CHECK(glpgp_optdesc_set(f, &o, "cross", why, sizeof why) == NULL && o.field == GLPGP_FIELD_CROSS);
    CHECK(glpgp_optdesc_set(f, &o, "u.txt", why, sizeof why) == NULL && o.field == GLPGP_FIELD_FILE &&
          !strcmp(o.field_file, "u.txt"));
    CHECK(glpgp_optdesc_set(f, &o, "", why, sizeof why) != NULL);
    const glpgp_optdesc *sf = glpgp_optdesc_find(t, "size_field");
    CHECK(glpgp_optdesc_set(sf, &o, "size.png", why, sizeof why) == NULL && o.size_field == GLPGP_SIZE_FUNC);
    CHECK(glpgp_optdesc_set(sf, &o, "none", why, sizeof why) == NULL && o.size_field == GLPGP_SIZE_NONE);
}

static void check_flags(void)
{
    glpgp_quads_options q;
    glpgp_quads_options_default(&q);
    char py[64], buf[64];
    const glpgp_optdesc *t = glpgp_quads_option_table();
    const glpgp_optdesc *rep = glpgp_optdesc_find(t, "repair");
    CHECK(rep && !strcmp(rep->name, "no-repair"));
    glpgp_optdesc_pyname(rep, py, sizeof py);
    CHECK(!strcmp(py, "repair"));
    glpgp_optdesc_value(rep, &q, buf, sizeof buf);
    CHECK(q.repair == 1 && !strcmp(buf, "true"));
    glpgp_optdesc_set_flag(rep, &q, 0);
    CHECK(q.repair == 0);
    glpgp_optdesc_set_flag(rep, &q, 1);
    CHECK(q.repair == 1);
    CHECK(glpgp_optdesc_set(rep, &q, NULL, buf, sizeof buf) == NULL && q.repair == 0); /* the CLI flag */
    const glpgp_optdesc *kp = glpgp_optdesc_find(t, "keep_polygons");
    glpgp_optdesc_set_flag(kp, &q, 1);
    CHECK(q.keep_polygons == 1);
    const glpgp_optdesc *io = glpgp_optdesc_find(glpgp_solve_option_table(), "input_order");
    glpgp_options o;
    glpgp_options_default(&o);
    glpgp_optdesc_set_flag(io, &o, 1);
    CHECK(io && !io->group && o.vertex_order == GLPGP_ORDER_INPUT);
    glpgp_render_options ro;
    glpgp_render_options_default(&ro);
    const glpgp_optdesc *kind = glpgp_optdesc_find(glpgp_render_option_table(), "kind");
    CHECK(kind && !strcmp(kind->name, "image-kind"));
}

/* every entry: a name, help, a default the help can show, and its own
 * default value accepted back */
static void check_tables(void)
{
    glpgp_options o;
    glpgp_quads_options q;
    glpgp_render_options r;
    glpgp_options_default(&o);
    glpgp_quads_options_default(&q);
    glpgp_render_options_default(&r);
    const glpgp_optdesc *tables[3] = {glpgp_solve_option_table(), glpgp_quads_option_table(),
                                      glpgp_render_option_table()};
    void *objs[3] = {&o, &q, &r};
    int n = 0;
    for (int k = 0; k < 3; k++)
        for (const glpgp_optdesc *d = tables[k]; d->name; d++, n++) {
            char val[128], why[256], def[128];
            CHECK(d->help && *d->help);
            glpgp_optdesc_default(d, objs[k], def, sizeof def);
            if (d->kind == GLPGP_OPTK_TEXT) continue;
            glpgp_optdesc_value(d, objs[k], val, sizeof val);
            if (d->kind == GLPGP_OPTK_FLAG) continue;
            if (d->kind != GLPGP_OPTK_DOUBLE || d->def == NULL) {
                const char *res = glpgp_optdesc_set(d, objs[k], val, why, sizeof why);
                if (res) fprintf(stderr, "%s: its default '%s' %s\n", d->name, val, res);
                CHECK(res == NULL);
            }
        }
    CHECK(n >= 40);
    char def[64];
    glpgp_optdesc_default(glpgp_optdesc_find(glpgp_solve_option_table(), "eps0"), &o, def, sizeof def);
    CHECK(!strcmp(def, "0.5"));
}

int main(void)
{
    check_numbers();
    check_choices_and_text();
    check_flags();
    check_tables();
    TEST_DONE();
}
