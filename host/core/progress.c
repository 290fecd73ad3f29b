/* core/progress.c: progress lines of long phases (glpgp/util.h,
 * glpgp_progress_*): at most one INFO line every GLPGP_PROGRESS_S seconds
 * per phase, through the log callback, so that no phase is silent for
 * longer than that (the CLI prints INFO lines unless --quiet). Inner loops
 * of long computations call glpgp_progress_poll(), which prints the
 * innermost phase of the thread when a line is due. */
#include "glpgp/util.h"
#include "glpgp/status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* The phase running on this thread (the innermost), for glpgp_progress_poll. */
static _Thread_local glpgp_progress *g_current;

void glpgp_progress_start(glpgp_progress *p, const char *what)
{
    memset(p, 0, sizeof *p);
    p->what = what;
    p->t0 = p->last = glpgp_now();
    p->outer = g_current;
    g_current = p;
}

void glpgp_progress_set(glpgp_progress *p, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    glpgp_vsnprintf(p->msg, sizeof p->msg, fmt, ap);
    va_end(ap);
}

void glpgp_progress_poll(void)
{
    glpgp_progress *p = g_current;
    if (!p || !glpgp_log_enabled() || !glpgp_progress_due(p)) return;
    glpgp_log(GLPGP_LOG_INFO, "%s: %s (%.1f s)", p->what, p->msg[0] ? p->msg : "working", glpgp_now() - p->t0);
    p->last = glpgp_now();
    p->shown = 1;
}

static void line(glpgp_progress *p, const char *tail, const char *fmt, va_list ap)
{
    char msg[512];
    glpgp_vsnprintf(msg, sizeof msg, fmt, ap);
    glpgp_log(GLPGP_LOG_INFO, "%s: %s%s (%.1f s)", p->what, msg, tail, glpgp_now() - p->t0);
}

int glpgp_progress_due(const glpgp_progress *p) { return glpgp_now() - p->last >= GLPGP_PROGRESS_S; }

void glpgp_progress_tick(glpgp_progress *p, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    glpgp_vsnprintf(p->msg, sizeof p->msg, fmt, ap);
    va_end(ap);
    if (!glpgp_log_enabled() || !glpgp_progress_due(p)) return;
    glpgp_log(GLPGP_LOG_INFO, "%s: %s (%.1f s)", p->what, p->msg, glpgp_now() - p->t0);
    p->last = glpgp_now();
    p->shown = 1;
}

void glpgp_progress_done(glpgp_progress *p, const char *fmt, ...)
{
    if (g_current == p) g_current = p->outer;
    if (!glpgp_log_enabled() || (!p->shown && glpgp_now() - p->t0 < GLPGP_PROGRESS_S)) return;
    va_list ap;
    va_start(ap, fmt);
    line(p, ", done", fmt, ap);
    va_end(ap);
    if (p->outer) p->outer->last = glpgp_now(); /* the enclosing phase was not silent */
}
