/* core/util.c: monotonic clock and extension tests (glpgp/util.h). */
#include "glpgp/util.h"

#include <ctype.h>
#include <string.h>
#include <time.h>

double glpgp_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int glpgp_has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), k = strlen(ext);
    if (n < k) return 0;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)path[n - k + i]) != ext[i]) return 0;
    return 1;
}
