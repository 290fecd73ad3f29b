/* core/util.c: monotonic clock, extension tests, order statistics and the
 * host's memory and processors (glpgp/util.h). */
#include "glpgp/util.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

unsigned long long glpgp_mem_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f) return 0;
    char line[256];
    unsigned long long kb = 0;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1) break;
    fclose(f);
    return kb * 1024ull;
}

int glpgp_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 1 << 20 ? 1 << 20 : (int)n;
}

double glpgp_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void swap_d(double *x, double *y)
{
    const double t = *x;
    *x = *y;
    *y = t;
}

double glpgp_select_double(double *a, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1; /* the answer's index stays in [lo, hi] */
    while (hi > lo) {
        /* pivot: median of a[lo], a[mid], a[hi] (sorted in place, so that
         * a[lo] <= p <= a[hi] bound the scans below) */
        const size_t mid = lo + (hi - lo) / 2;
        if (a[mid] < a[lo]) swap_d(&a[mid], &a[lo]);
        if (a[hi] < a[lo]) swap_d(&a[hi], &a[lo]);
        if (a[hi] < a[mid]) swap_d(&a[hi], &a[mid]);
        if (hi - lo < 3) break; /* three or fewer: sorted now */
        const double p = a[mid];
        /* Hoare partition of a[lo+1 .. hi-1]: i stops at >= p, j at <= p */
        size_t i = lo, j = hi;
        for (;;) {
            do i++; while (a[i] < p);
            do j--; while (a[j] > p);
            if (i >= j) break;
            swap_d(&a[i], &a[j]);
        }
        /* a[lo .. j] <= p <= a[j+1 .. hi] */
        if (k <= j) hi = j;
        else lo = j + 1;
    }
    return a[k];
}

int glpgp_uf_find(int *parent, int i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]]; /* path halving */
        i = parent[i];
    }
    return i;
}

double glpgp_median_double(double *a, size_t n)
{
    const size_t h = n / 2;
    const double upper = glpgp_select_double(a, n, h);
    if (n % 2) return upper;
    /* even: the largest of a[0 .. h), all <= a[h] after the selection */
    double lower = a[0];
    for (size_t i = 1; i < h; i++)
        if (a[i] > lower) lower = a[i];
    return 0.5 * (lower + upper);
}

int glpgp_has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), k = strlen(ext);
    if (n < k) return 0;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)path[n - k + i]) != ext[i]) return 0;
    return 1;
}

int glpgp_is_image_path(const char *path)
{
    static const char *const ext[] = {".png", ".tif", ".tiff", ".exr", ".jpg", ".jpeg", ".bmp",
                                      ".pgm", ".ppm", ".pnm", ".tga", ".gif", ".webp", ".hdr",
                                      NULL};
    if (!path) return 0;
    for (int k = 0; ext[k]; k++)
        if (glpgp_has_ext(path, ext[k])) return 1;
    return 0;
}
