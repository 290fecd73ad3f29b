/* test_image_module.c: the image layer loads OpenImageIO and Gmsh on demand
 * (dlopen'd modules glpgp_oiio.so / glpgp_gmsh.so, image/module.c), seen from
 * the process's own memory map (/proc/self/maps):
 *  - at start, and after glpgp_have_oiio / glpgp_have_gmsh (which must not
 *    load anything), no module, OpenImageIO, Gmsh or (unless the sanitizer
 *    runtime brings it) libstdc++ is mapped;
 *  - a child process with GLPGP_MODULE_DIR naming an empty directory gets
 *    GLPGP_ERR_IO from glpgp_image_read and glpgp_mesh_polygons, with one line
 *    naming the module and the directory, and glpgp_have_oiio() == 0;
 *  - glpgp_image_path_writable loads the OpenImageIO module and not Gmsh;
 *    glpgp_gmsh_load then loads the Gmsh module; a round trip through both
 *    (write + read a PNG, mesh a square) works.
 * Without OpenImageIO or Gmsh in the build, their loads must fail with
 * GLPGP_ERR_UNSUPPORTED ("built without"). */
#include "testutil.h"

#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* Whether a mapped file's path contains needle. */
static int mapped(const char *needle)
{
    FILE *f = fopen("/proc/self/maps", "r");
    if (!f) return -1;
    char line[4096];
    int hit = 0;
    while (!hit && fgets(line, sizeof line, f)) hit = strstr(line, needle) != NULL;
    fclose(f);
    return hit;
}

static int heavy_mapped(void)
{
    return mapped("glpgp_oiio") || mapped("glpgp_gmsh") || mapped("libOpenImageIO") ||
           mapped("libgmsh");
}

/* In a child with an empty module directory: the clear "not found" errors. */
static int child_without_modules(const char *empty)
{
    int bad = 0;
    setenv("GLPGP_MODULE_DIR", empty, 1);
    if (glpgp_have_oiio() || glpgp_have_gmsh()) bad |= 1;
    glpgp_image *im = NULL;
    glpgp_status st = glpgp_image_read("x.png", &im);
    const char *msg = glpgp_error_message();
    if (st != GLPGP_ERR_IO || im || !strstr(msg, "glpgp_oiio") || !strstr(msg, empty)) bad |= 2;
    glpgp_error_clear();
    double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    int start[2] = {0, 4}, parent[1] = {-1};
    double area[1] = {1};
    glpgp_polygons p = {1, start, xy, area, parent, 1, 0, 1.0, NULL};
    glpgp_mesh *m = NULL;
    st = glpgp_mesh_polygons(&p, 0.3, 0, &m);
    msg = glpgp_error_message();
    if (st != GLPGP_ERR_IO || m || !strstr(msg, "glpgp_gmsh") || !strstr(msg, empty)) bad |= 4;
    if (heavy_mapped()) bad |= 8;
    return bad;
}

int main(void)
{
    CHECK(mapped("libc") == 1); /* the check itself works */
    CHECK(heavy_mapped() == 0);
    if (!mapped("libasan")) CHECK(!mapped("libstdc++")); /* the ASan runtime brings it */
    int have_oiio = glpgp_have_oiio(), have_gmsh = glpgp_have_gmsh();
    printf("have_oiio %d, have_gmsh %d\n", have_oiio, have_gmsh);
    CHECK(heavy_mapped() == 0);

    if (have_oiio && have_gmsh) {
        char empty[] = "/tmp/glpgp_test_image_module.XXXXXX";
        CHECK(mkdtemp(empty) != NULL);
        pid_t pid = fork();
        if (pid == 0) _exit(child_without_modules(empty));
        int ws = 0;
        CHECK(pid > 0 && waitpid(pid, &ws, 0) == pid);
        if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 0)
            fprintf(stderr, "child without modules: status %d (bits: 1 have, 2 read, 4 mesh, 8 mapped)\n",
                    WIFEXITED(ws) ? WEXITSTATUS(ws) : -1);
        CHECK(WIFEXITED(ws) && WEXITSTATUS(ws) == 0);
        rmdir(empty);
    }

    if (have_oiio) {
        CHECK(glpgp_image_path_writable("x.png"));
        CHECK(mapped("glpgp_oiio") && mapped("libOpenImageIO"));
        CHECK(!mapped("libgmsh") && !mapped("glpgp_gmsh"));
        char path[] = "/tmp/glpgp_test_image_module.XXXXXX";
        CHECK(mkdtemp(path) != NULL);
        char png[600];
        snprintf(png, sizeof png, "%s/a.png", path);
        glpgp_image *im = NULL, *back = NULL;
        CHECK_OK(glpgp_image_create(5, 3, 3, &im));
        if (im) {
            for (int k = 0; k < 5 * 3 * 3; k++) im->px[k] = (float)(k % 7) / 6.0f;
            CHECK_OK(glpgp_image_write(png, im));
            CHECK_OK(glpgp_image_read(png, &back));
            CHECK(back && back->w == 5 && back->h == 3 && back->nc == 3);
            if (back) CHECK_CLOSE(back->px[4], im->px[4], 1.0 / 255, 0);
        }
        glpgp_image_destroy(&im);
        glpgp_image_destroy(&back);
        remove(png);
        rmdir(path);
        /* errors from inside the module reach this thread's record */
        glpgp_error_clear();
        CHECK(glpgp_image_read("/nonexistent/x.png", &back) == GLPGP_ERR_IO);
        CHECK(strstr(glpgp_error_message(), "/nonexistent/x.png") != NULL);
        glpgp_error_clear();
    } else {
        CHECK(glpgp_oiio_load() != GLPGP_OK);
        glpgp_error_clear();
    }

    if (have_gmsh) {
        CHECK_OK(glpgp_gmsh_load());
        CHECK(mapped("glpgp_gmsh") && mapped("libgmsh"));
        double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1};
        int start[2] = {0, 4}, parent[1] = {-1};
        double area[1] = {1};
        glpgp_polygons p = {1, start, xy, area, parent, 1, 0, 1.0, NULL};
        glpgp_mesh *m = NULL;
        CHECK_OK(glpgp_mesh_polygons(&p, 0.25, 0, &m));
        CHECK(m && m->nv > 4 && m->nt > 2);
        if (m) CHECK_CLOSE(m->area, 1.0, 1e-12, 0);
        glpgp_mesh_destroy(&m);
    } else {
        CHECK(glpgp_gmsh_load() == GLPGP_ERR_UNSUPPORTED);
        CHECK(strstr(glpgp_error_message(), "built without") != NULL);
        glpgp_error_clear();
    }
    TEST_DONE();
}
