/* cli.c: command-line helpers (see cli.h). */
#include "cli.h"
#include "status.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int glpgp_cli_double(const char *s, double *out)
{
    if (!s || !*s) return 0;
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

int glpgp_cli_long(const char *s, long lo, long hi, long *out)
{
    if (!s || !*s) return 0;
    char *end = NULL;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

int glpgp_has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), k = strlen(ext);
    if (n < k) return 0;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)path[n - k + i]) != ext[i]) return 0;
    return 1;
}

int glpgp_output_dir_ok(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (!slash) {
        strcpy(dir, ".");
    } else if (slash == path) {
        strcpy(dir, "/");
    } else {
        size_t n = (size_t)(slash - path);
        if (n >= sizeof dir) n = sizeof dir - 1;
        memcpy(dir, path, n);
        dir[n] = '\0';
    }
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': directory '%s' does not exist", path, dir);
        return 0;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': directory '%s' is not writable", path, dir);
        return 0;
    }
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': it is a directory", path);
        return 0;
    }
    return 1;
}
