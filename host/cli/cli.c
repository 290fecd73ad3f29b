/* cli/cli.c: log callback, error and usage printers and number parsing
 * shared by the CLI commands (cli.h). */
#include "cli.h"

#include "glpgp/optdesc.h"
#include "glpgp/quads.h"
#include "glpgp/status.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int g_verbosity = 1;
/* the exit code of a failure already reported on stderr (0: none yet), read
 * by the signal handler (main.c) */
static volatile sig_atomic_t g_reported;

int glpgp_cli_reported(int code)
{
    g_reported = code;
    return code;
}

int glpgp_cli_reported_code(void) { return g_reported; }

static void log_to_stderr(glpgp_log_level level, const char *msg, void *user)
{
    (void)user;
    if ((int)level > g_verbosity) return;
    if (level == GLPGP_LOG_WARNING)
        fprintf(stderr, "glpgp: warning: %s\n", msg);
    else
        fprintf(stderr, "glpgp: %s\n", msg);
}

void glpgp_cli_set_verbosity(int v)
{
    g_verbosity = v;
    glpgp_log_set_callback(log_to_stderr, NULL);
}

int glpgp_cli_verbosity(void) { return g_verbosity; }

int glpgp_cli_fail(void)
{
    const char *msg = glpgp_error_message();
    fprintf(stderr, "glpgp: error: %s\n", *msg ? msg : "unknown failure");
    if (*glpgp_error_detail()) fprintf(stderr, "%s\n", glpgp_error_detail());
    if (g_verbosity >= 2 && *glpgp_error_trace()) fputs(glpgp_error_trace(), stderr);
    glpgp_error_clear();
    return glpgp_cli_reported(GLPGP_EXIT_FAIL);
}

int glpgp_cli_usage_error(const char *sub, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("glpgp: usage error: ", stderr);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    if (sub)
        fprintf(stderr, "\nTry 'glpgp %s --help' for the options.\n", sub);
    else
        fputs("\nTry 'glpgp --help'.\n", stderr);
    return glpgp_cli_reported(GLPGP_EXIT_USAGE);
}

int glpgp_cli_double(const char *s, double *out) { return glpgp_parse_double(s, out); }

int glpgp_cli_long(const char *s, long lo, long hi, long *out) { return glpgp_parse_long(s, lo, hi, out); }

int glpgp_cli_quads_verdict(const struct glpgp_quads_report *qq, unsigned ignore, int allow, char *why, size_t n)
{
    if (qq->repaired_share > GLPGP_QUADS_MOSTLY_REPAIRED)
        glpgp_log(GLPGP_LOG_WARNING, "%.0f%% of the quads come from the repair, not from the parametrization's grid "
                  "(features smaller than the size, or a mesh too coarse for it: try a smaller --size)",
                  100.0 * qq->repaired_share);
    if (!glpgp_quads_invalid_text(qq, ignore, why, n)) return -1;
    if (!allow) return GLPGP_EXIT_INVALID;
    glpgp_log(GLPGP_LOG_WARNING, "the quad mesh is invalid (%s): written anyway (--allow-invalid)", why);
    return -1;
}

int glpgp_cli_invalid(const char *why, const char *what)
{
    fprintf(stderr, "glpgp: error: the quad mesh is invalid (%s)%s%s\n", why, *what ? ": " : "", what);
    return glpgp_cli_reported(GLPGP_EXIT_INVALID);
}
