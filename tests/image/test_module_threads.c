/* test_module_threads.c: the first loads of the image modules from several
 * threads at once (image/module.c under the modules' one lock,
 * glpgp_module_lock in core/module_dirs.c): every thread gets the same
 * status for OpenImageIO and for Gmsh, the one a later single-threaded call
 * returns; no thread sees a half-recorded failure (an empty message). Under
 * the sanitizer build the loads run with ASan/UBSan. */
#include "testutil.h"

#include <pthread.h>
#include <string.h>

#define NTHREADS 6

typedef struct {
    glpgp_status oiio, gmsh;
    char msg[256];
} outcome;

static pthread_barrier_t g_start;

static void *worker(void *arg)
{
    outcome *o = arg;
    pthread_barrier_wait(&g_start);
    o->gmsh = glpgp_gmsh_load();
    o->oiio = glpgp_oiio_load();
    snprintf(o->msg, sizeof o->msg, "%s", o->gmsh != GLPGP_OK || o->oiio != GLPGP_OK ? glpgp_error_message() : "");
    glpgp_error_clear();
    return NULL;
}

int main(void)
{
    pthread_t th[NTHREADS];
    outcome out[NTHREADS];
    memset(out, 0, sizeof out);
    pthread_barrier_init(&g_start, NULL, NTHREADS);
    for (int i = 0; i < NTHREADS; i++) pthread_create(&th[i], NULL, worker, &out[i]);
    for (int i = 0; i < NTHREADS; i++) pthread_join(th[i], NULL);
    pthread_barrier_destroy(&g_start);
    const glpgp_status gmsh = glpgp_gmsh_load(), oiio = glpgp_oiio_load();
    glpgp_error_clear();
    printf("gmsh %d, oiio %d after the threads\n", (int)gmsh, (int)oiio);
    for (int i = 0; i < NTHREADS; i++) {
        CHECK(out[i].gmsh == gmsh && out[i].oiio == oiio);
        if (out[i].gmsh != GLPGP_OK || out[i].oiio != GLPGP_OK) CHECK(out[i].msg[0] != '\0');
    }
    TEST_DONE();
}
