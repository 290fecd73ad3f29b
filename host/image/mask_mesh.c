/* image/mask_mesh.c: polygon-with-holes -> triangle mesh through the Gmsh
 * module (glpgp_gmsh.so, image/gmsh_shim.c, loaded on first use by
 * image/module.c), and the mask image -> mesh pipeline (glpgp/image.h).
 *
 * Containment of Gmsh. Gmsh 4.8 aborts the whole process on some boundaries
 * (it throws inside an OpenMP region, which ends in std::terminate: exit 134
 * and no message), so the module's mesh_polygons runs in a forked child: the
 * child meshes and writes a header (status, counts, error message) and the
 * vertex and triangle arrays into a pipe, then _exit()s; the parent reads
 * them before a deadline (the caller's timeout, else GLPGP_GMSH_DEFAULT_TIMEOUT:
 * no child runs unbounded), reaps the child (killed at the deadline) and turns
 * its death by a signal, a non-zero exit or a timeout into one GLPGP_ERR_MESH
 * / GLPGP_ERR_LIMIT message. The child has SIGINT/SIGTERM at their defaults
 * (it never runs the CLI's cleanup of the parent's temporaries), its stdout
 * and stderr on /dev/null, and dies with the parent (PR_SET_PDEATHSIG).
 * For the tests, GLPGP_TEST_GMSH_FAULT=abort|segv|exit|garbage|hang in the
 * environment makes the child fail that way instead of meshing, and
 * GLPGP_TEST_GMSH_TIMEOUT=S replaces the default bound
 * (glpgp/internal/debug.h, read before the fork). */
#include "glpgp/internal/debug.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/util.h"
#include "module.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void glpgp_mask_options_default(glpgp_mask_options *o)
{
    glpgp_contour_options_default(&o->contour);
    o->mesh_size = 0;
    o->quad_size = 0;
    o->algorithm = 6;
    o->max_triangles = GLPGP_DEFAULT_MAX_ELEMENTS;
    o->max_pixels = GLPGP_DEFAULT_MAX_PIXELS;
    o->timeout = GLPGP_GMSH_DEFAULT_TIMEOUT;
    o->remesh = 0;
}

double glpgp_mask_default_mesh_size(const glpgp_polygons *p, double quad_size)
{
    double h = quad_size;
    if (!(h > 0)) {
        double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
        for (int i = 0; p && i < p->start[p->n]; i++) {
            double x = p->xy[2 * i], y = p->xy[2 * i + 1];
            if (x < b[0]) b[0] = x;
            if (y < b[1]) b[1] = y;
            if (x > b[2]) b[2] = x;
            if (y > b[3]) b[3] = y;
        }
        h = hypot(b[2] - b[0], b[3] - b[1]) / 20.0;
    }
    return h / 8.0;
}

/* ---- Gmsh in a child process ------------------------------------------------ */

#define CHILD_MAGIC 0x676d7368u /* "gmsh" */

/* Smallest distance between boundary segments handed to Gmsh, as a fraction
 * of the longest side of the bounding box (Gmsh merges points closer than
 * its Geometry.Tolerance, 1e-8 in the scaled coordinates Gmsh gets). */
#define GLPGP_GMSH_MIN_DIST 1e-8

typedef struct child_header {
    uint32_t magic;
    int32_t status;  /* glpgp_status of mesh_polygons */
    int64_t nv, nt;
    int32_t msglen;  /* bytes of the error message that follow (status != OK) */
    int32_t pad;
} child_header;

static int write_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return 0;
        p += w;
        n -= (size_t)w;
    }
    return 1;
}

/* Read exactly n bytes before the monotonic time deadline (<= 0: none).
 * 1: done; 0: end of the stream or error first; -1: deadline passed. */
static int read_all(int fd, void *buf, size_t n, double deadline)
{
    char *p = buf;
    while (n > 0) {
        /* waits of at most a second: a progress line while Gmsh works */
        double left = deadline > 0 ? deadline - now_s() : 1.0;
        if (left <= 0) return -1;
        struct pollfd pfd = {fd, POLLIN, 0};
        int r = poll(&pfd, 1, (int)(fmin(left, 1.0) * 1000.0 + 1.0));
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) return 0;
        if (r == 0) { /* the deadline is checked above */
            glpgp_progress_poll();
            continue;
        }
        ssize_t k = read(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return 0;
        p += k;
        n -= (size_t)k;
    }
    return 1;
}

/* The child: mesh, send, _exit. Never returns. */
static void child_main(int wfd, pid_t parent, const glpgp_gmsh_api *api, const glpgp_polygons *p,
                       double hm, int algorithm, const char *fault)
{
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGPIPE, SIG_DFL);
#ifdef __linux__
    prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
    if (getppid() != parent) _exit(3); /* the parent is already gone */
    int dn = open("/dev/null", O_WRONLY);
    if (dn >= 0) {
        dup2(dn, 1);
        dup2(dn, 2);
        if (dn > 2) close(dn);
    }
    glpgp_error_clear();
    /* fault injection for tests/image/test_mask_guard.c: how a child that
     * dies or misbehaves is reported (segv with the default disposition, so
     * that a sanitizer's handler does not turn the crash into an exit) */
    if (*fault) { /* GLPGP_TEST_GMSH_FAULT (glpgp/internal/debug.h) */
        if (!strcmp(fault, "abort")) abort();
        if (!strcmp(fault, "segv")) {
            signal(SIGSEGV, SIG_DFL);
            raise(SIGSEGV);
        }
        if (!strcmp(fault, "hang"))
            for (;;) pause();
        if (!strcmp(fault, "garbage")) (void)!write(wfd, "not a header, not a header, not a header", 40);
        _exit(7); /* "exit" and anything else */
    }
    int nv = 0, nt = 0;
    double *xy = NULL;
    int *tri = NULL;
    glpgp_status st = api->mesh_polygons(p, hm, algorithm, &nv, &xy, &nt, &tri);
    child_header hd;
    memset(&hd, 0, sizeof hd);
    hd.magic = CHILD_MAGIC;
    hd.status = (int32_t)st;
    const char *msg = glpgp_error_message();
    if (st != GLPGP_OK) {
        hd.msglen = (int32_t)strnlen(msg, 1000);
    } else {
        hd.nv = nv;
        hd.nt = nt;
    }
    int ok = write_all(wfd, &hd, sizeof hd);
    if (ok && st != GLPGP_OK) ok = write_all(wfd, msg, (size_t)hd.msglen);
    if (ok && st == GLPGP_OK)
        ok = write_all(wfd, xy, 2 * (size_t)nv * sizeof(double)) &&
             write_all(wfd, tri, 3 * (size_t)nt * sizeof(int));
    _exit(ok ? 0 : 4);
}

/* How the child ended, for a message ("was killed by signal 6 (Aborted)"). */
static void describe_exit(int ws, char *buf, size_t len)
{
    if (WIFSIGNALED(ws))
        snprintf(buf, len, "crashed (signal %d, %s)", WTERMSIG(ws), strsignal(WTERMSIG(ws)));
    else if (WIFEXITED(ws))
        snprintf(buf, len, "failed (its process exited with status %d)", WEXITSTATUS(ws));
    else
        snprintf(buf, len, "failed");
}

static glpgp_status mesh_in_child(const glpgp_gmsh_api *api, const glpgp_polygons *p, double hm,
                                  double hm_user, int algorithm, double timeout, int *out_nv, double **out_xy,
                                  int *out_nt, int **out_tri)
{
    *out_nv = *out_nt = 0;
    *out_xy = NULL;
    *out_tri = NULL;
    glpgp_debug dbg; /* read before the fork: the child calls no getenv */
    GLPGP_CHECK(glpgp_debug_read(&dbg));
    if (!(timeout > 0)) timeout = dbg.gmsh_timeout > 0 ? dbg.gmsh_timeout : GLPGP_GMSH_DEFAULT_TIMEOUT;
    int fds[2];
    if (pipe(fds) != 0)
        return GLPGP_FAIL(GLPGP_ERR_MESH, "cannot start the Gmsh process: pipe: %s", strerror(errno));
    fflush(NULL); /* nothing buffered is written twice */
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        int e = errno;
        close(fds[0]);
        close(fds[1]);
        return GLPGP_FAIL(GLPGP_ERR_MESH, "cannot start the Gmsh process: fork: %s", strerror(e));
    }
    if (pid == 0) {
        close(fds[0]);
        child_main(fds[1], parent, api, p, hm, algorithm, dbg.gmsh_fault);
    }
    close(fds[1]);
    const int rfd = fds[0];
    const double deadline = now_s() + timeout; /* always bounded */
    glpgp_status st = GLPGP_OK;
    double *xy = NULL;
    int *tri = NULL;
    child_header hd;
    char msg[1024] = "";
    glpgp_progress pr;
    glpgp_progress_start(&pr, "meshing with Gmsh");
    glpgp_progress_set(&pr, "%d boundary points, mesh size %g", p->start[p->n], hm_user);
    int got = read_all(rfd, &hd, sizeof hd, deadline); /* 1 ok, 0 short, -1 timeout */
    int data_ok = 0, bad_data = 0;
    if (got == 1) {
        if (hd.magic != CHILD_MAGIC || hd.msglen < 0 || hd.msglen >= (int32_t)sizeof msg ||
            hd.nv < 0 || hd.nt < 0 || hd.nv > GLPGP_IO_MAX_ITEMS || hd.nt > GLPGP_IO_MAX_ITEMS) {
            bad_data = 1;
        } else if (hd.status != GLPGP_OK) {
            got = read_all(rfd, msg, (size_t)hd.msglen, deadline);
            msg[got == 1 ? hd.msglen : 0] = '\0';
            data_ok = got == 1;
        } else {
            st = glpgp_malloc(2 * (size_t)hd.nv + 1, sizeof(double), &xy);
            if (st == GLPGP_OK) st = glpgp_malloc(3 * (size_t)hd.nt + 1, sizeof(int), &tri);
            if (st == GLPGP_OK) {
                got = read_all(rfd, xy, 2 * (size_t)hd.nv * sizeof(double), deadline);
                if (got == 1) got = read_all(rfd, tri, 3 * (size_t)hd.nt * sizeof(int), deadline);
                data_ok = got == 1;
            }
        }
    }
    close(rfd);
    glpgp_progress_done(&pr, "%ld vertices, %ld triangles", data_ok ? (long)hd.nv : 0L, data_ok ? (long)hd.nt : 0L);
    if (!data_ok) kill(pid, SIGKILL); /* timeout, garbage, or no memory here */
    int ws = 0;
    pid_t w;
    while ((w = waitpid(pid, &ws, 0)) < 0 && errno == EINTR) {
    }
    if (st != GLPGP_OK) { /* out of memory in the parent (recorded) */
        glpgp_error_push_trace(__FILE__, __LINE__);
    } else if (got == -1) {
        st = GLPGP_FAIL(GLPGP_ERR_LIMIT,
                        "Gmsh did not finish meshing within the time limit of %g s (mesh size %g): "
                        "stopped",
                        timeout, hm_user);
    } else if (!data_ok) {
        char how[96];
        if (bad_data) /* killed by us */
            snprintf(how, sizeof how, "failed (its process sent a malformed reply)");
        else if (w == pid)
            describe_exit(ws, how, sizeof how);
        else
            snprintf(how, sizeof how, "failed (its process sent no reply)");
        st = GLPGP_FAIL(GLPGP_ERR_MESH,
                        "Gmsh %s while meshing %d boundary loop%s (%d points) with mesh size %g; "
                        "Gmsh 4.8 aborts on some boundaries: try another --mesh-size, --simplify, "
                        "--min-area or --threshold",
                        how, p->n, p->n == 1 ? "" : "s", p->start[p->n], hm_user);
    } else if (hd.status != GLPGP_OK) {
        st = GLPGP_FAIL((glpgp_status)hd.status, "%s", msg[0] ? msg : "Gmsh failed");
    } else {
        *out_nv = (int)hd.nv;
        *out_nt = (int)hd.nt;
        *out_xy = xy;
        *out_tri = tri;
        xy = NULL;
        tri = NULL;
    }
    free(xy);
    free(tri);
    return st;
}

/* Gmsh joins three consecutive boundary points of a nearly straight run into
 * one triangle (an ear: its middle point in no other triangle) where the
 * domain is thinner than the points' spacing: at a NACA 0012's sharp trailing
 * edge (points 2e-4 apart, 1e-5 to 1e-4 from the other side) the angle at the
 * middle point was 179.998 degrees, area 1.3e-12, and glpgp_mesh_create
 * refused the mesh as degenerate. An ear whose angle at its middle point
 * exceeds GLPGP_EAR_MAX_DEG is cut off: the boundary takes its chord (moved
 * by the ear's height, at most 0.44% of the chord), the middle point is
 * dropped; repeated while the cut makes new such ears. xy, tri are compacted
 * in place; returns the number of ears cut, *moved the largest height. */
#define GLPGP_EAR_MAX_DEG 179.5
static int cut_flat_ears(int *nv, double *xy, int *nt, int *tri, int *count, int *newid, double *moved)
{
    const double cmin = cos(GLPGP_EAR_MAX_DEG * GLPGP_PI / 180.0); /* cos of the angle: below this, cut */
    int cut = 0, changed = 1;
    *moved = 0.0;
    memset(count, 0, sizeof(int) * (size_t)*nv);
    for (int k = 0; k < 3 * *nt; k++) count[tri[k]]++;
    while (changed) {
        changed = 0;
        for (int t = 0; t < *nt; t++) {
            int *v = tri + 3 * t;
            if (v[0] < 0) continue; /* cut before */
            for (int j = 0; j < 3; j++) {
                const int b = v[j], a = v[(j + 2) % 3], c = v[(j + 1) % 3];
                if (count[b] != 1 || count[a] < 2 || count[c] < 2) continue;
                const double ax = xy[2 * a] - xy[2 * b], ay = xy[2 * a + 1] - xy[2 * b + 1];
                const double cx = xy[2 * c] - xy[2 * b], cy = xy[2 * c + 1] - xy[2 * b + 1];
                const double la = hypot(ax, ay), lc = hypot(cx, cy);
                if (!(la > 0 && lc > 0) || !((ax * cx + ay * cy) / (la * lc) < cmin)) continue;
                /* height of b over the chord a-c */
                const double ch = hypot(cx - ax, cy - ay);
                const double hgt = ch > 0 ? fabs(ax * cy - ay * cx) / ch : 0.0;
                if (hgt > *moved) *moved = hgt;
                count[a]--;
                count[b]--;
                count[c]--;
                v[0] = v[1] = v[2] = -1;
                cut++;
                changed = 1;
                break;
            }
        }
    }
    if (!cut) return 0;
    int m = 0;
    for (int i = 0; i < *nv; i++) {
        newid[i] = count[i] > 0 ? m : -1;
        if (count[i] > 0) {
            xy[2 * m] = xy[2 * i];
            xy[2 * m + 1] = xy[2 * i + 1];
            m++;
        }
    }
    int q = 0;
    for (int t = 0; t < *nt; t++) {
        if (tri[3 * t] < 0) continue;
        for (int j = 0; j < 3; j++) tri[3 * q + j] = newid[tri[3 * t + j]];
        q++;
    }
    *nv = m;
    *nt = q;
    return cut;
}

glpgp_status glpgp_mesh_polygons_timeout(const glpgp_polygons *p, double hm, int algorithm,
                                         double timeout, glpgp_mesh **out)
{
    if (!p || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_polygons: NULL argument");
    *out = NULL;
    if (!(hm > 0) || !isfinite(hm)) return GLPGP_FAIL(GLPGP_ERR_ARG, "mesh size %g must be positive", hm);
    if (algorithm <= 0) algorithm = 6;
    if (p->n < 1) return GLPGP_FAIL(GLPGP_ERR_MESH, "no boundary loop to mesh");
    /* Gmsh gets the polygons scaled into [0, 1]^2 (x' = (x - x0) / L, L the
     * longest side of the bounding box), so that its absolute geometric
     * tolerance (1e-8: closer points are merged, which breaks the boundary)
     * means the same for every unit; the vertices are scaled back. */
    const int np = p->start[p->n];
    double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < np; i++) {
        b[0] = fmin(b[0], p->xy[2 * i]);
        b[1] = fmin(b[1], p->xy[2 * i + 1]);
        b[2] = fmax(b[2], p->xy[2 * i]);
        b[3] = fmax(b[3], p->xy[2 * i + 1]);
    }
    const double L = fmax(b[2] - b[0], b[3] - b[1]);
    if (!(L > 0) || !isfinite(L))
        return GLPGP_FAIL(GLPGP_ERR_MESH, "the boundary has no extent (or non-finite points)");
    /* crossing or touching boundaries make Gmsh fail or abort: refuse them */
    GLPGP_CHECK(glpgp_polygons_check(p, GLPGP_GMSH_MIN_DIST * L));
    glpgp_polygons q = *p;
    q.xy = NULL;
    q.size = NULL;
    GLPGP_CHECK(glpgp_malloc(2 * (size_t)np + 2, sizeof(double), &q.xy));
    for (int i = 0; i < np; i++) {
        q.xy[2 * i] = (p->xy[2 * i] - b[0]) / L;
        q.xy[2 * i + 1] = (p->xy[2 * i + 1] - b[1]) / L;
    }
    if (p->size) { /* local sizes scale with the points (s' = s / L) */
        glpgp_status sst = glpgp_malloc((size_t)np + 1, sizeof(double), &q.size);
        if (sst != GLPGP_OK) {
            free(q.xy);
            return sst;
        }
        for (int i = 0; i < np; i++) q.size[i] = p->size[i] > 0 ? p->size[i] / L : 0.0;
    }
    const glpgp_gmsh_api *api;
    const char *why;
    glpgp_status st = glpgp_gmsh_module_get(&api, &why);
    if (st != GLPGP_OK) {
        free(q.xy);
        free(q.size);
        return GLPGP_FAIL(st, "cannot mesh the mask: %s", why);
    }
    int nv = 0, nt = 0;
    double *xy = NULL;
    int *tri = NULL;
    st = mesh_in_child(api, &q, hm / L, hm, algorithm, timeout, &nv, &xy, &nt, &tri);
    free(q.xy);
    free(q.size);
    if (st != GLPGP_OK) {
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    for (int i = 0; i < nv; i++) {
        xy[2 * i] = b[0] + xy[2 * i] * L;
        xy[2 * i + 1] = b[1] + xy[2 * i + 1] * L;
    }
    int *work = NULL;
    st = glpgp_malloc(2 * (size_t)nv + 1, sizeof(int), &work);
    if (st == GLPGP_OK) {
        double moved = 0.0;
        const int ears = cut_flat_ears(&nv, xy, &nt, tri, work, work + nv, &moved);
        if (ears > 0)
            glpgp_log(GLPGP_LOG_INFO, "Gmsh joined three consecutive boundary points into %d flat triangle%s "
                      "(angle above %g degrees): cut off, the boundary moved by at most %.3g",
                      ears, ears == 1 ? "" : "s", GLPGP_EAR_MAX_DEG, moved);
        free(work);
        st = glpgp_mesh_create(nv, xy, nt, tri, out);
    }
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    free(xy);
    free(tri);
    return st;
}

glpgp_status glpgp_mesh_polygons(const glpgp_polygons *p, double hm, int algorithm,
                                 glpgp_mesh **out)
{
    GLPGP_CHECK(glpgp_mesh_polygons_timeout(p, hm, algorithm, 0.0, out));
    return GLPGP_OK;
}

/* Put "PATH: " in front of the recorded error message (steps whose messages
 * do not name the image). Returns st. */
static glpgp_status name_the_file(const char *path, glpgp_status st)
{
    char msg[1024];
    snprintf(msg, sizeof msg, "%s", glpgp_error_message());
    glpgp_error_clear();
    return glpgp_error_set(__FILE__, __LINE__, st, "%s: %s", path, msg);
}

glpgp_status glpgp_mask_mesh(const char *path, const glpgp_mask_options *opt, glpgp_mesh **out,
                             glpgp_mask_info *info)
{
    if (!path || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mask_mesh: NULL argument");
    *out = NULL;
    glpgp_mask_options o;
    if (opt)
        o = *opt;
    else
        glpgp_mask_options_default(&o);
    if (o.max_triangles <= 0) o.max_triangles = GLPGP_DEFAULT_MAX_ELEMENTS;
    glpgp_mask_info inf;
    memset(&inf, 0, sizeof inf);
    /* fail before reading the image when Gmsh cannot be had */
    const glpgp_gmsh_api *api;
    const char *why;
    glpgp_status st = glpgp_gmsh_module_get(&api, &why);
    if (st != GLPGP_OK) return GLPGP_FAIL(st, "cannot mesh '%s': %s", path, why);
    double t0 = now_s();
    glpgp_image *im = NULL;
    float *v = NULL;
    glpgp_polygons *p = NULL;
    const int from_mesh = glpgp_has_ext(path, ".obj") || glpgp_has_ext(path, ".msh") || glpgp_has_ext(path, ".stl");
    if (glpgp_is_poly_path(path) || from_mesh) { /* polygons: no image, no contours */
        if (from_mesh) {
            /* a triangle mesh (a CAD export's slivers): its boundary loops */
            glpgp_mesh *in = NULL;
            GLPGP_CHECK(glpgp_mesh_read_ex(path, GLPGP_READ_PLANAR_FACE, &in));
            st = glpgp_polygons_from_mesh(in, &p);
            glpgp_mesh_destroy(&in);
            GLPGP_CHECK(st);
        } else
            GLPGP_CHECK(glpgp_polygons_read(path, &p));
        double t1 = now_s();
        inf.seconds_read = t1 - t0;
        double hm = o.mesh_size > 0 ? o.mesh_size : glpgp_mask_default_mesh_size(p, o.quad_size);
        inf.nouter = p->nouter;
        inf.nholes = p->nholes;
        inf.boundary_points = p->start[p->n];
        inf.polygon_area = p->total_area;
        inf.mesh_size = hm;
        /* the work Gmsh would do, at the finest size it is asked for */
        double hmin = hm;
        if (p->size)
            for (int i = 0; i < p->start[p->n]; i++)
                if (p->size[i] > 0 && p->size[i] < hmin) hmin = p->size[i];
        double est = GLPGP_MASK_TRIANGLES_PER_AREA * p->total_area / (hmin * hmin);
        if (!(est <= (double)o.max_triangles)) {
            st = GLPGP_FAIL(GLPGP_ERR_LIMIT,
                            "%s: mesh size %g would make up to about %.3g triangles (domain area %g): "
                            "more than the limit of %ld (--max-elements); use a larger --mesh-size or --size",
                            path, hmin, est, p->total_area, o.max_triangles);
            goto fin;
        }
        if ((st = glpgp_mesh_polygons_timeout(p, hm, o.algorithm, o.timeout, out)) != GLPGP_OK) {
            name_the_file(path, st);
            goto fin;
        }
        inf.seconds_mesh = now_s() - t1;
        if (info) *info = inf;
        goto fin;
    }
    GLPGP_CHECK(glpgp_image_read_limited(path, o.max_pixels, &im));
    inf.width = im->w;
    inf.height = im->h;
    GLPGP_CHECK_GOTO(st, glpgp_mask_values(im, &v), fin);
    glpgp_image_destroy(&im);
    double t1 = now_s();
    inf.seconds_read = t1 - t0;
    /* raw contours first: the simplification below depends on the mesh size */
    glpgp_contour_options co = o.contour;
    co.tolerance = 0;
    if ((st = glpgp_contours(v, inf.width, inf.height, &co, &p)) != GLPGP_OK) {
        name_the_file(path, st);
        goto fin;
    }
    free(v);
    v = NULL;
    double hm = o.mesh_size > 0 ? o.mesh_size : glpgp_mask_default_mesh_size(p, o.quad_size);
    double area = 0;
    for (int l = 0; l < p->n; l++) area += p->area[l];
    /* the work Gmsh would do: about 3.5 area / hm^2 triangles */
    double est = GLPGP_MASK_TRIANGLES_PER_AREA * area / (hm * hm);
    if (!(est <= (double)o.max_triangles)) {
        st = GLPGP_FAIL(GLPGP_ERR_LIMIT,
                        "%s: mesh size %g would make about %.3g triangles (domain area %g): more "
                        "than the limit of %ld (--max-elements); use a larger --mesh-size or --size",
                        path, hm, est, area, o.max_triangles);
        goto fin;
    }
    /* Douglas-Peucker at max(tolerance, mesh size / 20), keeping the topology */
    double tol = fmax(o.contour.tolerance * o.contour.pixel_size, hm / 20.0);
    if ((st = glpgp_polygons_simplify(p, tol, GLPGP_CONTOUR_MIN_DIST * o.contour.pixel_size)) != GLPGP_OK) {
        name_the_file(path, st);
        goto fin;
    }
    inf.nouter = p->nouter;
    inf.nholes = p->nholes;
    inf.boundary_points = p->start[p->n];
    inf.polygon_area = 0;
    for (int l = 0; l < p->n; l++) inf.polygon_area += p->area[l];
    inf.mesh_size = hm;
    double t2 = now_s();
    inf.seconds_contour = t2 - t1;
    if ((st = glpgp_mesh_polygons_timeout(p, hm, o.algorithm, o.timeout, out)) != GLPGP_OK) {
        name_the_file(path, st);
        goto fin;
    }
    inf.seconds_mesh = now_s() - t2;
    if (info) *info = inf;
fin:
    glpgp_image_destroy(&im);
    free(v);
    glpgp_polygons_destroy(&p);
    return st;
}

int glpgp_is_poly_path(const char *path)
{
    size_t n = path ? strlen(path) : 0;
    if (n < 5) return 0;
    const char *e = path + n - 5;
    return e[0] == '.' && (e[1] | 32) == 'p' && (e[2] | 32) == 'o' && (e[3] | 32) == 'l' && (e[4] | 32) == 'y';
}
