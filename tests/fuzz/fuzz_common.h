/* tests/fuzz/fuzz_common.h: what every fuzz harness shares. A harness is one
 * file tests/fuzz/fuzz_NAME.c defining LLVMFuzzerTestOneInput; it is built
 * two ways (tests/fuzz/CMakeLists.txt):
 *   - with GLPGP_FUZZ=ON (clang): a libFuzzer binary build-fuzz/tests/fuzz/fuzz_NAME
 *     (run by tests/fuzz/run.sh);
 *   - in every other build: linked with tests/fuzz/replay.c, a ctest
 *     (fuzz_NAME, label unit) that runs the harness once on every file of
 *     tests/fuzz/corpus/NAME/ (seeds) and tests/fuzz/regress/NAME/ (inputs
 *     that once crashed or hung), so the sanitizer build of .ci/run replays
 *     them all.
 * A harness must not print, must release everything it allocated and aborts
 * (FUZZ_ASSERT) when a property of the library is violated. Readers take a
 * path: fuzz_write_file puts the input in a per-process file with the
 * extension the reader dispatches on. */
#ifndef GLPGP_FUZZ_COMMON_H
#define GLPGP_FUZZ_COMMON_H

#include "glpgp/status.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FUZZ_ASSERT(cond)                                                              \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            fprintf(stderr, "%s:%d: property violated: %s (error: %s)\n", __FILE__, __LINE__, \
                    #cond, glpgp_error_message());                                     \
            abort();                                                                   \
        }                                                                              \
    } while (0)

/* The error record after a failure: exactly one line, not empty. */
static inline void fuzz_check_error(glpgp_status st)
{
    if (st == GLPGP_OK) return;
    const char *m = glpgp_error_message();
    FUZZ_ASSERT(m[0] != '\0');
    FUZZ_ASSERT(strchr(m, '\n') == NULL);
    glpgp_error_clear();
}

static char fuzz_paths[8][512];

static void fuzz_cleanup(void)
{
    for (int k = 0; k < 8; k++)
        if (fuzz_paths[k][0]) unlink(fuzz_paths[k]);
}

/* Write data to this process's scratch file number slot (0..7) with the
 * extension ext (".obj"); returns its path. */
static inline const char *fuzz_write_file(int slot, const char *ext, const uint8_t *data, size_t size)
{
    if (!fuzz_paths[slot][0]) {
        const char *dir = getenv("TMPDIR");
        snprintf(fuzz_paths[slot], sizeof fuzz_paths[slot], "%s/glpgp_fuzz_%ld_%d%s",
                 dir && *dir ? dir : "/tmp", (long)getpid(), slot, ext);
        static int registered;
        if (!registered) {
            atexit(fuzz_cleanup);
            registered = 1;
        }
    }
    FILE *f = fopen(fuzz_paths[slot], "wb");
    if (!f) abort();
    if (size && fwrite(data, 1, size, f) != size) abort();
    if (fclose(f) != 0) abort();
    return fuzz_paths[slot];
}

#endif
