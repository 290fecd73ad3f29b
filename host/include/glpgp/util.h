/* glpgp/util.h: small helpers every layer uses: a monotonic clock and
 * case-insensitive file-extension tests. Layer: core. */
#ifndef GLPGP_UTIL_H
#define GLPGP_UTIL_H

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds of a monotonic clock (for durations only). */
double glpgp_now(void);

/* Whether path ends with ext (lower-case, with the dot: ".png"), ignoring
 * the case of path. */
int glpgp_has_ext(const char *path, const char *ext);

#ifdef __cplusplus
}
#endif

#endif
