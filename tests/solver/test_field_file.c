/* test_field_file.c: the guiding-field file of `solve --field FILE`
 * (solver/field.c) on extreme but valid and on malformed input, on a
 * 16-vertex square:
 *  - components around 1e200 (whose squares overflow) and 1e-200 (whose
 *    squares underflow) give the unit vectors of their direction, exactly
 *    as (3, 4) and (1, 0) do (hypot, not sqrt(x^2 + y^2));
 *  - a 600-character line is read whole: its error names line 2, not 3;
 *  - a line beyond the 4096-character limit is reported on its own number;
 *  - a zero vector, nan, too few and too many lines are errors naming the
 *    file; every error is one line. */
#include "testutil.h"

#include <string.h>
#include <unistd.h>

static glpgp_mesh *g_m;
static char g_path[256];

/* Write text, read the field; returns the status (u filled on success). */
static glpgp_status field_of(const char *text, double *u)
{
    FILE *f = fopen(g_path, "w");
    fputs(text, f);
    fclose(f);
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_FILE;
    o.field_file = g_path;
    long cg = 0;
    glpgp_error_clear();
    return glpgp_field_compute(g_m, NULL, &o, u, &cg);
}

static char *lines(const char *first, const char *rest, int nrest)
{
    size_t n = strlen(first) + (size_t)nrest * strlen(rest) + 1;
    char *s = malloc(n);
    strcpy(s, first);
    for (int i = 0; i < nrest; i++) strcat(s, rest);
    return s;
}

static void expect_error(const char *what, const char *text, const char *needle)
{
    double u[32];
    glpgp_status st = field_of(text, u);
    const char *msg = glpgp_error_message();
    printf("%-22s -> %s\n", what, st == GLPGP_OK ? "accepted" : msg);
    CHECK(st != GLPGP_OK);
    CHECK(msg[0] && !strchr(msg, '\n'));
    CHECK(strstr(msg, g_path) != NULL);
    if (needle) CHECK(strstr(msg, needle) != NULL);
    glpgp_error_clear();
}

int main(void)
{
    CHECK_OK(glpgp_mesh_generate("square", 16, &g_m));
    if (!g_m) TEST_DONE();
    CHECK(g_m->nv == 16);
    snprintf(g_path, sizeof g_path, "/tmp/glpgp_field_%ld.txt", (long)getpid());
    double u[32];

    /* huge and tiny components: the direction survives */
    char *t = lines("3e200 4e200\n", "1e-200 0\n", 15);
    CHECK_OK(field_of(t, u));
    printf("(3e200, 4e200) -> (%.17g, %.17g); (1e-200, 0) -> (%g, %g)\n", u[0], u[1], u[2], u[3]);
    CHECK_CLOSE(u[0], 0.6, 1e-15, 0);
    CHECK_CLOSE(u[1], 0.8, 1e-15, 0);
    for (int i = 1; i < 16; i++) {
        CHECK(u[2 * i] == 1.0);
        CHECK(u[2 * i + 1] == 0.0);
    }
    free(t);
    t = lines("-1e308 1e308\n", "0 -1e-300\n", 15);
    CHECK_OK(field_of(t, u));
    CHECK_CLOSE(u[0], -sqrt(0.5), 1e-15, 0);
    CHECK_CLOSE(u[1], sqrt(0.5), 1e-15, 0);
    CHECK(u[2] == 0.0 && u[3] == -1.0);
    free(t);

    /* a 600-character line: read whole, the error names it (line 2) */
    char longline[700];
    memset(longline, 0, sizeof longline);
    strcpy(longline, "1 0 ");
    memset(longline + 4, 'x', 596);
    strcat(longline, "\n");
    char *t2 = calloc(4096, 1);
    snprintf(t2, 4096, "1 0\n%s", longline);
    for (int i = 0; i < 14; i++) strcat(t2, "1 0\n");
    expect_error("600-character line", t2, ":2:");
    /* a valid 600-character line (leading zeros) is accepted */
    memset(t2, 0, 4096);
    snprintf(t2, 4096, "1 0\n0");
    memset(t2 + strlen(t2), '0', 596);
    strcat(t2, "1 1\n");
    for (int i = 0; i < 14; i++) strcat(t2, "1 0\n");
    CHECK(strlen(t2) > 600);
    CHECK_OK(field_of(t2, u));
    CHECK_CLOSE(u[2], sqrt(0.5), 1e-15, 0);
    free(t2);

    /* over the limit: named on its own line number */
    char *huge = malloc(6000);
    memset(huge, 0, 6000);
    strcpy(huge, "1 0\n1 0\n");
    memset(huge + 8, ' ', 5000);
    strcat(huge, "1 0\n");
    for (int i = 0; i < 13; i++) strcat(huge, "1 0\n");
    expect_error("5000-character line", huge, ":3: line longer than");
    free(huge);

    t = lines("0 0\n", "1 0\n", 15);
    expect_error("zero vector", t, ":1: zero vector");
    free(t);
    t = lines("nan 1\n", "1 0\n", 15);
    expect_error("nan", t, ":1:");
    free(t);
    t = lines("1e999 1\n", "1 0\n", 15);
    expect_error("overflowing literal", t, ":1:");
    free(t);
    t = lines("", "1 0\n", 15);
    expect_error("15 lines", t, "15 field lines for 16 vertices");
    free(t);
    t = lines("", "1 0\n", 17);
    expect_error("17 lines", t, "more than 16");
    free(t);

    unlink(g_path);
    glpgp_mesh_destroy(&g_m);
    TEST_DONE();
}
