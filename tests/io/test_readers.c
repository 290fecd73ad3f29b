/* test_readers.c: the hardened text readers (io/msh_read.c, io/mesh_io.c,
 * io/text_reader.c) on hostile input:
 *  - MSH from pipes (a FIFO named *.msh for glpgp_mesh_read, /dev/fd/N for
 *    glpgp_quads_read_msh), 2.2 and 4.1: same mesh as from a file;
 *  - every malformed class gives GLPGP_ERR_FORMAT or _LIMIT, nothing
 *    returned, and bounded memory (each read runs in a child under a 256 MiB
 *    address-space limit, except in sanitizer builds): node block counts of
 *    2^61 and LONG_MAX, element counts beyond the bytes present, the
 *    163-byte file with tags up to 1e8, huge tags (hash, not arrays),
 *    duplicate tags, repeated sections, non-finite or overflowing
 *    coordinates, unknown nodes, stray $End lines, element blocks that
 *    disagree with the header, lines over the limit, NUL bytes;
 *  - OBJ: non-finite coordinates, a face using a vertex twice, a face index
 *    beyond the vertices (reported on its line), huge indices;
 *  - second- and higher-order elements (their corners), quadrangles (two
 *    triangles each, also non-convex ones), a 6-node triangle a node short;
 *  - OBJ polygon faces (an L from its reflex side, a rectangle with a point
 *    on a side, clockwise in the plane y = 3): ear-clipped; crossing sides:
 *    an error;
 *  - STL, ASCII and binary (one whose header starts with "solid"): welded; a
 *    count beyond the bytes, a facet of 2 vertices, a stray keyword, NaN:
 *    errors with the line, bounded memory;
 *  - a 3D surface: its largest face in a coordinate plane (a box's bottom,
 *    or its side x = 0 when that is larger); none: an error;
 *  - unwelded meshes: a triangle soup and two patches with doubled seam
 *    nodes (OBJ, MSH 4.1) are welded into one piece; the doubled lips of a
 *    crack inside one piece stay apart. */
#include "testutil.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define TU_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TU_ASAN 1
#endif
#endif
#ifndef TU_ASAN
#define TU_ASAN 0
#endif

static void put(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        tu_failures++;
        return;
    }
    fwrite(text, 1, n ? n : strlen(text), f);
    fclose(f);
}

/* Read path in a child (limited address space): 0 = the reader returned
 * want (and nothing), 1 = another status, 2 = crashed or out of memory. */
static int read_in_child(const char *path, int quads, glpgp_status want1, glpgp_status want2, const char *needle)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        if (!TU_ASAN) {
            struct rlimit rl = {256ul << 20, 256ul << 20};
            setrlimit(RLIMIT_AS, &rl);
        }
        glpgp_status st;
        if (quads) {
            glpgp_quadmesh *q = (glpgp_quadmesh *)&q;
            st = glpgp_quads_read_msh(path, &q);
            if (st != GLPGP_OK && q) _exit(3);
        } else {
            glpgp_mesh *m = (glpgp_mesh *)&m;
            st = glpgp_mesh_read(path, &m);
            if (st != GLPGP_OK && m) _exit(3);
        }
        fprintf(stderr, "    %s\n", glpgp_error_message());
        if (st == GLPGP_ERR_NOMEM) _exit(2);
        if ((st == want1 || st == want2) && (!needle || strstr(glpgp_error_message(), needle))) _exit(0);
        _exit(1);
    }
    int status;
    if (pid < 0 || waitpid(pid, &status, 0) != pid) return 2;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 2;
}

static void bad(const char *name, const char *text, const char *needle, int line)
{
    const char *p = tu_tmp_path(name);
    put(p, text, 0);
    for (int quads = 0; quads < 2; quads++) {
        int rc = read_in_child(p, quads, GLPGP_ERR_FORMAT, GLPGP_ERR_LIMIT, needle);
        if (rc) {
            fprintf(stderr, "%s:%d: %s (%s reader): expected a format / limit error%s%s, got %s\n", __FILE__, line,
                    name, quads ? "quad" : "mesh", needle ? " containing " : "", needle ? needle : "",
                    rc == 2 ? "a crash or out of memory" : "another result");
            tu_failures++;
        }
    }
    unlink(p);
}

#define FMT22 "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
#define FMT41 "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
#define NODES22 "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n"
#define ELEMS22 "$Elements\n2\n1 2 0 1 2 3\n2 2 0 1 3 4\n$EndElements\n"

static void malformed_msh(void)
{
    /* the 163-byte file: 3 nodes with tags up to 1e8 (no max-tag-sized array) */
    const char *small = FMT41 "$Nodes\n1 3 1 100000000\n2 1 0 3\n1\n50000000\n100000000\n0 0 0\n1 0 0\n0 1 0\n"
                              "$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 50000000 100000000\n$EndElements\n";
    put(tu_tmp_path("small.msh"), small, 0);
    CHECK(read_in_child(tu_tmp_path("small.msh"), 0, GLPGP_OK, GLPGP_OK, NULL) == 0);
    CHECK(read_in_child(tu_tmp_path("small.msh"), 1, GLPGP_OK, GLPGP_OK, NULL) == 0);
    /* tags near 2^62 work too */
    const char *bigtags = FMT22 "$Nodes\n3\n4611686018427387904 0 0 0\n7 1 0 0\n4611686018427387000 0 1 0\n$EndNodes\n"
                                "$Elements\n1\n1 2 0 4611686018427387904 7 4611686018427387000\n$EndElements\n";
    put(tu_tmp_path("bigtags.msh"), bigtags, 0);
    CHECK(read_in_child(tu_tmp_path("bigtags.msh"), 0, GLPGP_OK, GLPGP_OK, NULL) == 0);
    unlink(tu_tmp_path("small.msh"));
    unlink(tu_tmp_path("bigtags.msh"));

    bad("blocks61.msh", FMT41 "$Nodes\n1 3 1 3\n0 1 0 2305843009213693952\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n",
        "more nodes than", __LINE__);
    bad("nodeslongmax.msh", FMT41 "$Nodes\n1 9223372036854775807 1 3\n0 1 0 9223372036854775807\n1\n$EndNodes\n",
        "declared", __LINE__);
    bad("blockslongmax.msh", FMT41 "$Nodes\n9223372036854775807 3 1 3\n0 1 0 3\n$EndNodes\n", "declared", __LINE__);
    bad("nodes22huge.msh", FMT22 "$Nodes\n2305843009213693952\n1 0 0 0\n$EndNodes\n", "declared", __LINE__);
    bad("elems41huge.msh", FMT41 "$Nodes\n1 3 1 3\n0 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
                                 "$Elements\n1 4611686018427387904 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n",
        "declared", __LINE__);
    bad("elemblock.msh", FMT41 "$Nodes\n1 3 1 3\n0 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
                               "$Elements\n1 1 1 1\n2 1 2 9223372036854775807\n1 1 2 3\n$EndElements\n",
        "more elements than", __LINE__);
    bad("elemcount.msh", FMT41 "$Nodes\n1 3 1 3\n0 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
                               "$Elements\n1 2 1 2\n2 1 2 1\n1 1 2 3\n$EndElements\n",
        "header says", __LINE__);
    bad("overflow.msh", FMT22 "$Nodes\n99999999999999999999\n$EndNodes\n", "number of nodes", __LINE__);
    bad("negative.msh", FMT22 "$Nodes\n-5\n$EndNodes\n", "negative", __LINE__);
    bad("dup.msh", FMT22 "$Nodes\n3\n1 0 0 0\n1 1 0 0\n3 0 1 0\n$EndNodes\n", "duplicate node tag 1", __LINE__);
    bad("nodes2.msh", FMT22 NODES22 NODES22 ELEMS22, "repeated section $Nodes", __LINE__);
    bad("elems2.msh", FMT22 NODES22 ELEMS22 ELEMS22, "repeated section $Elements", __LINE__);
    bad("format2.msh", FMT22 "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n" NODES22 ELEMS22, "repeated", __LINE__);
    bad("nan.msh", FMT22 "$Nodes\n3\n1 0 0 0\n2 nan 0 0\n3 0 1 0\n$EndNodes\n", "finite", __LINE__);
    bad("inf.msh", FMT22 "$Nodes\n3\n1 0 0 0\n2 1e400 0 0\n3 0 1 0\n$EndNodes\n", "finite", __LINE__);
    bad("inf41.msh", FMT41 "$Nodes\n1 3 1 3\n0 1 0 3\n1\n2\n3\n0 0 0\n1 inf 0\n0 1 0\n$EndNodes\n", "finite", __LINE__);
    bad("unknown.msh", FMT22 NODES22 "$Elements\n1\n1 2 0 1 2 9\n$EndElements\n", "unknown node 9", __LINE__);
    bad("before.msh", FMT22 ELEMS22 NODES22, "$Elements before $Nodes", __LINE__);
    bad("stray.msh", FMT22 "$EndNodes\n", "without its section", __LINE__);
    bad("unclosed.msh", FMT22 "$PhysicalNames\n1\n2 1 \"x\"\n", "not closed", __LINE__);
    bad("noend.msh", FMT22 "$Nodes\n1\n1 0 0 0\n$Elements\n", "expected $EndNodes", __LINE__);
    bad("nul.msh", FMT22 "$Nodes\n1\n1 0\x01 0 0\n", NULL, __LINE__);
    {
        char nulmsh[64] = FMT22 "$Nodes\n1\n1 0";
        size_t n = strlen(nulmsh);
        memcpy(nulmsh + n, "\0 0 0\n", 6);
        put(tu_tmp_path("nulbyte.msh"), nulmsh, n + 6);
        CHECK(read_in_child(tu_tmp_path("nulbyte.msh"), 0, GLPGP_ERR_FORMAT, GLPGP_ERR_FORMAT, "NUL") == 0);
        unlink(tu_tmp_path("nulbyte.msh"));
    }
    /* a line over GLPGP_IO_MAX_LINE */
    size_t n = (size_t)GLPGP_IO_MAX_LINE + 100;
    char *longl = malloc(n + 64);
    if (longl) {
        strcpy(longl, FMT22 "$Comments\n");
        size_t k = strlen(longl);
        memset(longl + k, 'x', n);
        strcpy(longl + k + n, "\n$EndComments\n");
        put(tu_tmp_path("longline.msh"), longl, 0);
        CHECK(read_in_child(tu_tmp_path("longline.msh"), 0, GLPGP_ERR_LIMIT, GLPGP_ERR_LIMIT, "longer than") == 0);
        unlink(tu_tmp_path("longline.msh"));
        free(longl);
    }
}

/* ---- pipes ------------------------------------------------------------------ */

static const char *const sq22 = FMT22 NODES22 "$Elements\n3\n1 15 2 0 1 1\n2 2 0 1 2 3\n3 3 0 1 3 4 2\n$EndElements\n";

/* Write text into fd from a child process, then exit. */
static pid_t feed(int fd, const char *text)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        size_t n = strlen(text), done = 0;
        while (done < n) {
            ssize_t k = write(fd, text + done, n - done);
            if (k <= 0) _exit(1);
            done += (size_t)k;
        }
        close(fd);
        _exit(0);
    }
    return pid;
}

static void pipes(void)
{
    /* FIFO with a .msh name: the triangle reader dispatches by extension */
    const char *fifo = tu_tmp_path("pipe.msh");
    CHECK(mkfifo(fifo, 0600) == 0);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        int fd = open(fifo, O_WRONLY);
        if (fd < 0) _exit(1);
        const char *text = FMT41 "$Nodes\n2 4 1 4\n0 1 0 2\n1\n2\n0 0 0\n1 0 0\n2 1 0 2\n3\n4\n1 1 0\n0 1 0\n"
                                 "$EndNodes\n$Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n2 1 3 4\n$EndElements\n";
        size_t n = strlen(text);
        if (write(fd, text, n) != (ssize_t)n) _exit(1);
        close(fd);
        _exit(0);
    }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_read(fifo, &m));
    CHECK(m && m->nv == 4 && m->nt == 2 && fabs(m->area - 1.0) < 1e-15);
    glpgp_mesh_destroy(&m);
    int status;
    waitpid(pid, &status, 0);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    unlink(fifo);

    /* /dev/fd/N for the quad reader: 2.2 with a triangle and a quadrangle */
    int fds[2];
    CHECK(pipe(fds) == 0);
    pid = feed(fds[1], sq22);
    close(fds[1]);
    char path[64];
    snprintf(path, sizeof path, "/dev/fd/%d", fds[0]);
    glpgp_quadmesh *q = NULL;
    CHECK_OK(glpgp_quads_read_msh(path, &q));
    CHECK(q && q->nv == 4 && q->nf == 2 && q->face_start[1] == 3 && q->face_start[2] == 7);
    glpgp_quadmesh_destroy(&q);
    close(fds[0]);
    waitpid(pid, &status, 0);

    /* the same from a regular file gives the same faces */
    put(tu_tmp_path("sq22.msh"), sq22, 0);
    CHECK_OK(glpgp_quads_read_msh(tu_tmp_path("sq22.msh"), &q));
    CHECK(q && q->nv == 4 && q->nf == 2);
    glpgp_quadmesh_destroy(&q);
    unlink(tu_tmp_path("sq22.msh"));

    /* a lying count from a pipe (size unknown) still fails cleanly */
    CHECK(pipe(fds) == 0);
    pid = feed(fds[1], FMT22 "$Nodes\n2305843009213693952\n1 0 0 0\n$EndNodes\n");
    close(fds[1]);
    snprintf(path, sizeof path, "/dev/fd/%d", fds[0]);
    CHECK(read_in_child(path, 1, GLPGP_ERR_FORMAT, GLPGP_ERR_LIMIT, NULL) == 0);
    close(fds[0]);
    waitpid(pid, &status, 0);
}

/* ---- OBJ ---------------------------------------------------------------------- */

static void obj_expect(const char *name, const char *text, glpgp_status want, const char *needle, int line)
{
    const char *p = tu_tmp_path(name);
    put(p, text, 0);
    int rc = read_in_child(p, 0, want, want, needle);
    if (rc) {
        fprintf(stderr, "%s:%d: %s: expected status %d containing '%s'\n", __FILE__, line, name, (int)want,
                needle ? needle : "");
        tu_failures++;
    }
    unlink(p);
}

static void malformed_obj(void)
{
    obj_expect("nan.obj", "v 0 0\nv nan 0\nv 0 1\nf 1 2 3\n", GLPGP_ERR_FORMAT, "nan.obj:2:", __LINE__);
    obj_expect("inf.obj", "v 0 0\nv 1e999 0\nv 0 1\nf 1 2 3\n", GLPGP_ERR_FORMAT, "inf.obj:2:", __LINE__);
    obj_expect("twice.obj", "v 0 0\nv 1 0\nv 0 1\nf 1 1 2\n", GLPGP_ERR_FORMAT, "vertex 1 more than once",
               __LINE__);
    obj_expect("twice2.obj", "v 0 0\nv 1 0\nv 0 1\nv 1 1\nf 1 2 4 -3\n", GLPGP_ERR_FORMAT, "more than once",
               __LINE__);
    obj_expect("forward.obj", "v 0 0\nf 1 2 3\nv 1 0\nv 0 1\n", GLPGP_OK, NULL, __LINE__);
    obj_expect("range.obj", "v 0 0\nv 1 0\nv 0 1\nf 1 2 3\nf 1 2 99\n", GLPGP_ERR_FORMAT, "range.obj:5:", __LINE__);
    obj_expect("hugeidx.obj", "v 0 0\nv 1 0\nv 0 1\nf 1 2 9223372036854775807\n", GLPGP_ERR_FORMAT, NULL, __LINE__);
    obj_expect("overidx.obj", "v 0 0\nv 1 0\nv 0 1\nf 1 2 99999999999999999999\n", GLPGP_ERR_FORMAT, NULL, __LINE__);
}

/* Read path (expected to succeed) and check its counts. */
static void read_expect(const char *name, int nv, int nt, int nloops, double area, int line)
{
    glpgp_mesh *m = NULL;
    glpgp_status st = glpgp_mesh_read(tu_tmp_path(name), &m);
    if (st != GLPGP_OK || !m) {
        fprintf(stderr, "line %d: %s: %s\n", line, name, glpgp_error_message());
        tu_failures++;
        return;
    }
    if (m->nv != nv || m->nt != nt || m->nloops != nloops || fabs(m->area - area) > 1e-12) {
        fprintf(stderr, "line %d: %s: nv %d nt %d loops %d area %g, expected %d %d %d %g\n", line, name, m->nv,
                m->nt, m->nloops, m->area, nv, nt, nloops, area);
        tu_failures++;
    }
    glpgp_mesh_destroy(&m);
}

static void welding(void)
{
    /* a 2 x 2 square of 8 triangles, every triangle with its own three
     * vertices: one piece of 9 vertices after welding */
    char soup[4096] = "# triangle soup\n";
    int nf = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            const int q[2][3][2] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};
            for (int k = 0; k < 2; k++) {
                for (int c = 0; c < 3; c++)
                    snprintf(soup + strlen(soup), sizeof soup - strlen(soup), "v %d %d 0\n", i + q[k][c][0],
                             j + q[k][c][1]);
                nf++;
            }
        }
    for (int f = 0; f < nf; f++)
        snprintf(soup + strlen(soup), sizeof soup - strlen(soup), "f %d %d %d\n", 3 * f + 1, 3 * f + 2, 3 * f + 3);
    put(tu_tmp_path("soup.obj"), soup, 0);
    read_expect("soup.obj", 9, 8, 1, 4.0, __LINE__);

    /* two unit squares meshed apart, the seam x = 1 doubled (MSH 4.1, one
     * entity each): one piece, 6 vertices, one loop */
    const char *two = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                      "$Nodes\n2 8 1 8\n"
                      "2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                      "2 2 0 4\n5\n6\n7\n8\n1 0 0\n2 0 0\n2 1 0\n1 1 0\n$EndNodes\n"
                      "$Elements\n2 4 1 4\n2 1 2 2\n1 1 2 3\n2 1 3 4\n2 2 2 2\n3 5 6 7\n4 5 7 8\n"
                      "$EndElements\n";
    put(tu_tmp_path("patches.msh"), two, 0);
    read_expect("patches.msh", 6, 4, 1, 2.0, __LINE__);

    /* a crack: the square [0,2]^2 slit from (1,0) up to (1,1), the slit's
     * foot doubled (vertices 5 and 6) inside one piece: kept apart, one loop
     * running up and down the slit */
    const char *crack = "v 0 0\nv 2 0\nv 2 2\nv 0 2\nv 1 0\nv 1 0\nv 1 1\n"
                        "f 1 5 7\nf 1 7 4\nf 4 7 3\nf 6 2 7\nf 7 2 3\n";
    put(tu_tmp_path("crack.obj"), crack, 0);
    read_expect("crack.obj", 7, 5, 1, 4.0, __LINE__);
}

/* Element kinds other than 3-node triangles: second- and higher-order
 * elements give their corners; quadrangles are split in two triangles over
 * a diagonal inside them. */
static void element_kinds(void)
{
    /* MSH 4.1: the unit square as two 6-node triangles (type 9) */
    const char *p2 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                     "$Nodes\n1 9 1 9\n2 1 0 9\n1\n2\n3\n4\n5\n6\n7\n8\n9\n"
                     "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0 0\n1 0.5 0\n0.5 1 0\n0 0.5 0\n0.5 0.5 0\n$EndNodes\n"
                     "$Elements\n1 2 1 2\n2 1 9 2\n1 1 2 3 5 6 9\n2 1 3 4 9 7 8\n$EndElements\n";
    put(tu_tmp_path("p2.msh"), p2, 0);
    read_expect("p2.msh", 4, 2, 1, 1.0, __LINE__);
    /* MSH 2.2: one 9-node quadrangle (type 10) */
    const char *q9 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                     "$Nodes\n9\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0.5 0 0\n6 1 0.5 0\n7 0.5 1 0\n"
                     "8 0 0.5 0\n9 0.5 0.5 0\n$EndNodes\n"
                     "$Elements\n1\n1 10 2 0 1 1 2 3 4 5 6 7 8 9\n$EndElements\n";
    put(tu_tmp_path("q9.msh"), q9, 0);
    read_expect("q9.msh", 4, 2, 1, 1.0, __LINE__);
    /* a non-convex quadrangle (reflex corner 4 at (0.5, 1)): only the
     * diagonal 2-4 lies inside it */
    const char *dart = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                       "$Nodes\n4\n1 0 0 0\n2 2 1 0\n3 0 2 0\n4 0.5 1 0\n$EndNodes\n"
                       "$Elements\n1\n1 3 2 0 1 1 2 3 4\n$EndElements\n";
    put(tu_tmp_path("dart.msh"), dart, 0);
    read_expect("dart.msh", 4, 2, 1, 1.5, __LINE__);
    /* a node short: an error, not a crash */
    const char *short9 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                         "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
                         "$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 1 2\n$EndElements\n";
    put(tu_tmp_path("short9.msh"), short9, 0);
    glpgp_mesh *m = NULL;
    CHECK(glpgp_mesh_read(tu_tmp_path("short9.msh"), &m) == GLPGP_ERR_FORMAT && !m);
    glpgp_error_clear(); /* the next failures record their own messages */
}

/* OBJ polygon faces: ear-clipped in the mesh's plane, whatever corner they
 * start from (a fan from the first corner would fold or flatten them). */
static void polygon_faces(void)
{
    /* an L as one face, listed from the reflex corner's neighbour (2, 1):
     * the fan from it runs outside the L */
    const char *l = "v 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nv 2 0 0\nf 1 2 3 4 5 6\n";
    put(tu_tmp_path("lface.obj"), l, 0);
    read_expect("lface.obj", 6, 4, 1, 3.0, __LINE__);
    /* a rectangle with a point on its bottom side, listed from a corner next
     * to it: the fan's first triangle is flat */
    const char *r = "v 0 0\nv 1 0\nv 2 0\nv 2 1\nv 0 1\nf 1 2 3 4 5\n";
    put(tu_tmp_path("rface.obj"), r, 0);
    read_expect("rface.obj", 5, 3, 1, 2.0, __LINE__);
    /* the L clockwise, in the plane y = 3 */
    const char *lcw = "v 2 3 1\nv 2 3 0\nv 0 3 0\nv 0 3 2\nv 1 3 2\nv 1 3 1\nf 1 2 3 4 5 6\n";
    put(tu_tmp_path("lcw.obj"), lcw, 0);
    read_expect("lcw.obj", 6, 4, 1, 3.0, __LINE__);
    /* a face whose sides cross: an error, nothing returned */
    const char *bow = "v 0 0\nv 2 1\nv 2 0\nv 0 2\nf 1 2 3 4\n";
    put(tu_tmp_path("bow.obj"), bow, 0);
    glpgp_mesh *m = NULL;
    CHECK(glpgp_mesh_read(tu_tmp_path("bow.obj"), &m) != GLPGP_OK && !m);
    glpgp_error_clear();
}

/* Binary STL bytes: 80-byte header, count, triangles of (normal, 3 x 3
 * float32 vertices, uint16), little-endian. */
static size_t stl_bin(unsigned char *b, const char *hdr, unsigned count, const float (*tri)[9], int ntri)
{
    memset(b, ' ', 80);
    memcpy(b, hdr, strlen(hdr));
    for (int k = 0; k < 4; k++) b[80 + k] = (unsigned char)(count >> (8 * k));
    size_t n = 84;
    for (int t = 0; t < ntri; t++) {
        float rec[12] = {0, 0, 1};
        memcpy(rec + 3, tri[t], sizeof(float) * 9);
        for (int i = 0; i < 12; i++) {
            uint32_t u;
            memcpy(&u, &rec[i], 4);
            for (int k = 0; k < 4; k++) b[n++] = (unsigned char)(u >> (8 * k));
        }
        b[n++] = 0;
        b[n++] = 0;
    }
    return n;
}

/* STL: the unit square's two triangles as ASCII and binary (one binary
 * header starting with "solid"): welded into 4 vertices; a count beyond the
 * bytes, a facet of 2 vertices, a stray keyword: errors, bounded memory. */
static void stl(void)
{
    const char *a = "solid sq\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                    "   vertex 1 1 0\n  endloop\n endfacet\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                    "   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid sq\n";
    put(tu_tmp_path("sq_a.stl"), a, 0);
    read_expect("sq_a.stl", 4, 2, 1, 1.0, __LINE__);
    static const float sq[2][9] = {{0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 0, 1, 1, 0, 0, 1, 0}};
    unsigned char b[84 + 2 * 50];
    size_t n = stl_bin(b, "solid but binary", 2, sq, 2);
    put(tu_tmp_path("sq_b.stl"), (const char *)b, n);
    read_expect("sq_b.stl", 4, 2, 1, 1.0, __LINE__);
    /* a count of 2^31 in a 184-byte file: refused before any allocation */
    n = stl_bin(b, "binary", 0x80000000u, sq, 2);
    put(tu_tmp_path("huge.stl"), (const char *)b, n);
    CHECK(read_in_child(tu_tmp_path("huge.stl"), 0, GLPGP_ERR_FORMAT, GLPGP_ERR_LIMIT, "triangles") == 0);
    obj_expect("two.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
               GLPGP_ERR_FORMAT, "two.stl:6: a facet with 2 vertices", __LINE__);
    obj_expect("kw.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvortex 1 0 0\n", GLPGP_ERR_FORMAT,
               "kw.stl:5: unknown STL keyword 'vortex'", __LINE__);
    obj_expect("nanv.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n", GLPGP_ERR_FORMAT,
               "nanv.stl:4:", __LINE__);
}

/* A box [0, a] x [0, b] x [0, c] as 12 STL facets (its whole surface). */
static void box_stl(const char *name, double a, double b, double c)
{
    const double X[8][3] = {{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}, {0, 0, c}, {a, 0, c}, {a, b, c}, {0, b, c}};
    const int F[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                          {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    char text[4096] = "solid box\n";
    for (int f = 0; f < 12; f++) {
        snprintf(text + strlen(text), sizeof text - strlen(text), "facet normal 0 0 0\nouter loop\n");
        for (int k = 0; k < 3; k++)
            snprintf(text + strlen(text), sizeof text - strlen(text), "vertex %g %g %g\n", X[F[f][k]][0],
                     X[F[f][k]][1], X[F[f][k]][2]);
        snprintf(text + strlen(text), sizeof text - strlen(text), "endloop\nendfacet\n");
    }
    strcat(text, "endsolid box\n");
    put(tu_tmp_path(name), text, 0);
}

/* A 3D mesh (a CAD part's STL) is a surface now: the closed box of 8
 * vertices, 12 triangles (chi 2, no loop, area 2 (ab + bc + ca)); with
 * GLPGP_READ_PLANAR_FACE its largest face in a coordinate plane (the box
 * 2 x 1 x 0.5 gives its bottom, z = 0, area 2; the box 0.2 x 3 x 2 its side
 * x = 0, area 6), and a tetrahedron with no such face is an error there. */
static void read_expect_flat(const char *name, int nv, int nt, int nloops, double area, int line)
{
    glpgp_mesh *m = NULL;
    glpgp_status st = glpgp_mesh_read_ex(tu_tmp_path(name), GLPGP_READ_PLANAR_FACE, &m);
    if (st != GLPGP_OK || !m || m->xyz || m->nv != nv || m->nt != nt || m->nloops != nloops ||
        fabs(m->area - area) > 1e-12) {
        fprintf(stderr, "line %d: %s: %s\n", line, name, st != GLPGP_OK ? glpgp_error_message() : "wrong mesh");
        tu_failures++;
    }
    glpgp_mesh_destroy(&m);
    glpgp_error_clear();
}

static void three_d(void)
{
    box_stl("flat.stl", 2, 1, 0.5);
    read_expect_flat("flat.stl", 4, 2, 1, 2.0, __LINE__);
    box_stl("tall.stl", 0.2, 3, 2);
    read_expect_flat("tall.stl", 4, 2, 1, 6.0, __LINE__);
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_read(tu_tmp_path("flat.stl"), &m));
    CHECK(m && glpgp_mesh_is_surface(m) && m->nv == 8 && m->nt == 12 && m->nloops == 0 && m->surf->euler == 2);
    CHECK(m && fabs(m->area - 2.0 * (2 * 1 + 1 * 0.5 + 0.5 * 2)) < 1e-12);
    glpgp_mesh_destroy(&m);
    put(tu_tmp_path("tet.obj"), "v 0 0 0\nv 1 0 0.1\nv 0 1 0.2\nv 0.3 0.3 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n", 0);
    CHECK(glpgp_mesh_read_ex(tu_tmp_path("tet.obj"), GLPGP_READ_PLANAR_FACE, &m) == GLPGP_ERR_MESH && !m);
    CHECK(strstr(glpgp_error_message(), "no face of it lies in one") != NULL);
    glpgp_error_clear();
    CHECK_OK(glpgp_mesh_read(tu_tmp_path("tet.obj"), &m));
    CHECK(m && m->nt == 4 && m->surf->euler == 2);
    glpgp_mesh_destroy(&m);
    /* a tilted plane (no coordinate plane): a flat open surface */
    put(tu_tmp_path("tilt.obj"), "v 0 0 0\nv 1 0 1\nv 1 1 1\nv 0 1 0\nf 1 2 3 4\n", 0);
    CHECK_OK(glpgp_mesh_read(tu_tmp_path("tilt.obj"), &m));
    CHECK(m && glpgp_mesh_is_surface(m) && m->nt == 2 && m->nloops == 1 && fabs(m->area - sqrt(2.0)) < 1e-12);
    glpgp_mesh_destroy(&m);
    /* the flipped face of a closed surface: flipped back (the reader's
     * repair), the tetrahedron read as tet.obj is */
    put(tu_tmp_path("flip.obj"), "v 0 0 0\nv 1 0 0.1\nv 0 1 0.2\nv 0.3 0.3 1\nf 1 3 2\nf 1 4 2\nf 2 3 4\nf 3 1 4\n", 0);
    CHECK_OK(glpgp_mesh_read(tu_tmp_path("flip.obj"), &m));
    CHECK(m && m->nt == 4 && m->surf->euler == 2 && m->tri[3] == 0 && m->tri[4] == 1 && m->tri[5] == 3);
    glpgp_mesh_destroy(&m);
}

/* PLY (ASCII, binary little- and big-endian, with extra properties and
 * elements to skip, a quad face) and OFF (comments, a colour after a
 * face, counts on the OFF line): the same tetrahedron-with-a-quad (a
 * square pyramid: 5 vertices, 4 triangles + 1 quad -> 6 triangles). */
static void put_ply_bin(const char *name, int be)
{
    const float X[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 1}};
    const int F[5][4] = {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}};
    char head[512];
    snprintf(head, sizeof head,
             "ply\nformat binary_%s_endian 1.0\ncomment made by test_readers\nelement vertex 5\nproperty float x\n"
             "property float y\nproperty float z\nproperty uchar red\nelement face 5\nproperty list uchar int "
             "vertex_indices\nproperty int flags\nend_header\n",
             be ? "big" : "little");
    FILE *f = fopen(name, "wb");
    if (!f) {
        tu_failures++;
        return;
    }
    fputs(head, f);
#define PUTN(ptr, n)                                                                                   \
    do {                                                                                               \
        unsigned char b_[8];                                                                           \
        memcpy(b_, (ptr), (n));                                                                        \
        for (int k_ = 0; k_ < (n); k_++) fputc(b_[be ? (n) - 1 - k_ : k_], f);                         \
    } while (0)
    for (int v = 0; v < 5; v++) {
        for (int c = 0; c < 3; c++) PUTN(&X[v][c], 4);
        fputc(200, f);
    }
    for (int q = 0; q < 5; q++) {
        const unsigned char n = F[q][3] < 0 ? 3 : 4;
        fputc(n, f);
        for (int c = 0; c < n; c++) PUTN(&F[q][c], 4);
        const int flags = 7;
        PUTN(&flags, 4);
    }
#undef PUTN
    fclose(f);
}

static void pyramid_expect(const char *name, int line)
{
    glpgp_mesh *m = NULL;
    glpgp_status st = glpgp_mesh_read(tu_tmp_path(name), &m);
    if (st != GLPGP_OK || !m || !glpgp_mesh_is_surface(m) || m->nv != 5 || m->nt != 6 || m->nloops != 0 ||
        m->surf->euler != 2 || fabs(m->area - (1.0 + sqrt(5.0))) > 1e-7) {
        fprintf(stderr, "line %d: %s: %s\n", line, name, st != GLPGP_OK ? glpgp_error_message() : "wrong mesh");
        tu_failures++;
    }
    glpgp_mesh_destroy(&m);
    glpgp_error_clear();
}

static void ply_off(void)
{
    put(tu_tmp_path("pyr.ply"),
        "ply\nformat ascii 1.0\ncomment a square pyramid\nelement vertex 5\nproperty double x\nproperty double y\n"
        "property double z\nproperty float nx\nelement face 5\nproperty list uchar int vertex_index\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
        "0 0 0 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n0.5 0.5 1 9\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n0 1\n",
        0);
    pyramid_expect("pyr.ply", __LINE__);
    put_ply_bin(tu_tmp_path("pyr_le.ply"), 0);
    pyramid_expect("pyr_le.ply", __LINE__);
    put_ply_bin(tu_tmp_path("pyr_be.ply"), 1);
    pyramid_expect("pyr_be.ply", __LINE__);
    put(tu_tmp_path("pyr.off"), "OFF 5 5 8\n# a square pyramid\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1 # apex\n"
                      "4 0 3 2 1 255 0 0\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n", 0);
    pyramid_expect("pyr.off", __LINE__);
    put(tu_tmp_path("pyr2.off"), "COFF\n5 5 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n1 1 0 1 1 1 1\n0 1 0 1 1 1 1\n0.5 0.5 1 1 1 1 1\n"
                       "4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n", 0);
    pyramid_expect("pyr2.off", __LINE__);
    /* malformed: one line naming the problem each */
    const char *bad[][2] = {
        {"b1.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 1\n"
                   "property list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n"},
        {"b2.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 1\n0 1 1\n3 0 1 7\n"},
        {"b3.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"},
        {"b4.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 1\n0 1 nan\n3 0 1 2\n"},
        {"b1.off", "OFF\n3 1 0\n0 0 0\n1 0 1\n0 1 1\n3 0 1 3\n"},
        {"b2.off", "OFF BINARY\n"},
        {"b3.off", "OFF\n3 1000000000 0\n0 0 0\n"},
        {"b4.off", "OFF\n3 1 0\n0 0 0\n1 0 1\n0 1 1\n3 0 1 1\n"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        glpgp_mesh *m = NULL;
        put(tu_tmp_path(bad[k][0]), bad[k][1], 0);
        glpgp_error_clear();
        glpgp_status st = glpgp_mesh_read(tu_tmp_path(bad[k][0]), &m);
        printf("%s: %s\n", bad[k][0], glpgp_error_message());
        CHECK(st != GLPGP_OK && m == NULL);
        CHECK(strstr(glpgp_error_message(), bad[k][0]) != NULL && !strchr(glpgp_error_message(), '\n'));
        glpgp_mesh_destroy(&m);
        glpgp_error_clear();
    }
}

int main(void)
{
    if (!tu_tmp_init("test_readers")) return 1;
    signal(SIGPIPE, SIG_IGN);
    malformed_msh();
    pipes();
    malformed_obj();
    welding();
    element_kinds();
    ply_off();
    polygon_faces();
    stl();
    three_d();
    const char *made[] = {"flat.stl", "tall.stl", "tet.obj", "sq_a.stl", "sq_b.stl", "huge.stl", "soup.obj", "patches.msh", "crack.obj", "p2.msh", "q9.msh", "dart.msh", "short9.msh",
                          "lface.obj", "rface.obj", "lcw.obj", "bow.obj", "tilt.obj", "flip.obj", "pyr.ply",
                          "pyr_le.ply", "pyr_be.ply", "pyr.off", "pyr2.off", "b1.ply", "b2.ply", "b3.ply", "b4.ply",
                          "b1.off", "b2.off", "b3.off", "b4.off"};
    for (size_t k = 0; k < sizeof made / sizeof *made; k++) unlink(tu_tmp_path(made[k]));
    rmdir(tu_tmp_dir);
    TEST_DONE();
}
