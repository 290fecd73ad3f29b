/* glpgp/util.h: small helpers every layer uses: a monotonic clock,
 * case-insensitive file-extension tests, order statistics without sorting,
 * union-find, where the dlopen'd modules are looked for, and numbers read
 * and written whatever the process's locale. Layer: core. */
#ifndef GLPGP_UTIL_H
#define GLPGP_UTIL_H

#include <stdarg.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Limits of every file reader (core/text_reader.c and the readers of the io
 * layer, glpgp/io.h). */
/* Largest count of vertices / nodes, triangles / elements / cells a reader
 * accepts (so that 4 * count still fits an int). */
#define GLPGP_IO_MAX_ITEMS ((1L << 29) - 1)
/* Longest line of a text format (bytes). */
#define GLPGP_IO_MAX_LINE (1L << 20)

/* Seconds of a monotonic clock (for durations only). */
double glpgp_now(void);

/* Progress of a long phase (core/progress.c): INFO log lines "WHAT:
 * MESSAGE (T s)" at most every GLPGP_PROGRESS_S seconds, and a closing
 * "WHAT: MESSAGE, done (T s)" when the phase showed a line or took that
 * long; nothing for short phases. One struct per phase and thread. */
#define GLPGP_PROGRESS_S 2.0
typedef struct glpgp_progress {
    const char *what;  /* the phase, e.g. "refinement" */
    double t0, last;   /* start, last line */
    int shown;         /* a line was printed */
    char msg[160];     /* the state shown by glpgp_progress_poll */
    struct glpgp_progress *outer; /* the enclosing phase of this thread */
} glpgp_progress;
/* Start a phase (it becomes this thread's innermost until glpgp_progress_done). */
void glpgp_progress_start(glpgp_progress *p, const char *what);
/* Set the state a due line will show, without printing. */
void glpgp_progress_set(glpgp_progress *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* From inner loops: a line for this thread's innermost phase when one is
 * due (cheap otherwise: a clock read). */
void glpgp_progress_poll(void);
/* Whether a line is due (GLPGP_PROGRESS_S since the start or the last one):
 * lets callers skip counting work for it. */
int glpgp_progress_due(const glpgp_progress *p);
/* Set the state and print it when a line is due. */
void glpgp_progress_tick(glpgp_progress *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* End the phase: a closing line when it showed one or took long. */
void glpgp_progress_done(glpgp_progress *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Whether path ends with ext (lower-case, with the dot: ".png"), ignoring
 * the case of path. */
int glpgp_has_ext(const char *path, const char *ext);

/* Whether path ends in an image extension glpgp treats as a mask/picture
 * (.png .tif .tiff .exr .jpg .jpeg .bmp .pgm .ppm .pnm .tga .gif .webp .hdr),
 * case-insensitive. Independent of OpenImageIO being built in. */
int glpgp_is_image_path(const char *path);

/* The k-th smallest of a[0 .. n) (0 <= k < n; no NaN), by quickselect in
 * O(n) on average: a is permuted so that a[k] holds it, a[i] <= a[k] for
 * i < k and a[i] >= a[k] for i > k. The value is exactly the sorted array's
 * a[k] (a median of a million |z| in ~10 ms instead of a ~100 ms qsort). */
double glpgp_select_double(double *a, size_t n, size_t k);

/* The median of a[0 .. n) (n >= 1; the mean of the middle two for even n),
 * the same value as from the sorted array; a is permuted. */
double glpgp_median_double(double *a, size_t n);

/* Union-find: the root of i's set in the forest parent[] (parent[r] == r
 * at a root; start with parent[i] = i), halving the path on the way. Union:
 * parent[glpgp_uf_find(p, a)] = glpgp_uf_find(p, b). */
int glpgp_uf_find(int *parent, int i);

/* The host's available memory in bytes (MemAvailable of /proc/meminfo; 0
 * when unknown) and its online processors (at least 1). */
unsigned long long glpgp_mem_available(void);
int glpgp_cpu_count(void);

/* The directories glpgp's modules (glpgp_oiio.so, glpgp_gmsh.so,
 * glpgp_petsc.so) are looked for in, in order: $GLPGP_MODULE_DIR alone when
 * set (from_env = 1); else <directory of the executable>/<its relative
 * install path>, <directory of the shared object holding glpgp>/modules
 * when that is not the executable (the Python extension), the configured
 * install directory, the build tree. */
#define GLPGP_MODULE_MAX_DIRS 5
#define GLPGP_MODULE_PATH_LEN 4096
typedef struct glpgp_module_dirs {
    int n;
    int from_env;
    char dir[GLPGP_MODULE_MAX_DIRS][GLPGP_MODULE_PATH_LEN];
} glpgp_module_dirs;
void glpgp_module_dirs_get(glpgp_module_dirs *d);
/* path <- the first d->dir[i]/file that exists (returns 1), or 0 if none. */
int glpgp_module_find(const glpgp_module_dirs *d, const char *file, char *path, size_t len);
/* The one lock of module loading (image modules, the PETSc module): a loader
 * holds it while it looks a module up, dlopen's it and records the outcome,
 * so two threads asking at once load it once. Not recursive. */
void glpgp_module_lock(void);
void glpgp_module_unlock(void);

/* Locale-independent numbers (core/numlocale.c): every number the library
 * reads or writes (files, option values, messages) uses '.' as the decimal
 * point whatever the process's locale. A scope switches the calling thread
 * alone to the "C" locale (uselocale; the process's locale and other threads
 * are untouched) until its end; begin/end pair in one function on one
 * thread, and nest. The functions below do the same per call. */
typedef struct glpgp_cnum {
    void *prev, *loc; /* the thread's locale before, the "C" one (NULL: unchanged) */
} glpgp_cnum;
void glpgp_cnum_begin(glpgp_cnum *s);
void glpgp_cnum_end(glpgp_cnum *s);
/* strtod, sscanf, snprintf in the "C" locale (errno as strtod leaves it). */
double glpgp_strtod(const char *s, char **end);
int glpgp_sscanf(const char *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(scanf, 2, 3)))
#endif
    ;
int glpgp_snprintf(char *buf, size_t n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
int glpgp_vsnprintf(char *buf, size_t n, const char *fmt, va_list ap);

#ifdef __cplusplus
}
#endif

#endif
